"""The pieces of the surface Newton solver that trade work for speed, each against the plain way."""

import numpy as np
import pytest

from fem_asperity.closed_forms.lj import scaled_traction_slope
from fem_asperity.path.continuation import Linearisation
from fem_asperity.path.elimination import relax_edge
from fem_asperity.path.surface import LJSurface
from fem_asperity.solver.presets import discretisation
from fem_asperity.solver.solve import solve_discretised


@pytest.fixture(scope="module")
def traced():
    """(surface, trace) of the stable paths at μ = 2, BEM `draft`."""
    result = solve_discretised(2.0, discretisation(2.0, "draft", method="bem"))
    return result.model.surface, result.model.trace


@pytest.mark.parametrize("method", ["bem", "fem"])
def test_tangent_from_the_spring_map_is_the_assembled_tangent(method):
    surface = LJSurface(discretisation(2.0, "draft", method=method).elastic(), 2.0)
    rng = np.random.default_rng(0)
    w, delta = 0.1 * rng.random(surface.r_nodes.size), 1.5
    slope = surface.weights * scaled_traction_slope(surface.gap(w, delta))
    spring = (surface.interp_t @ surface.interp.multiply(slope[:, None])).toarray()
    assembled = surface.stiffness - surface.load_factor * spring
    jac = surface.tangent_matrix(slope)
    assert np.max(np.abs(jac - assembled)) <= 1e-6 * np.max(np.abs(assembled))


def _contact_state(traced):
    """A traced stable state in contact, with its δ̄o."""
    surface, trace = traced
    k = next(i for i, a in enumerate(trace.a_c) if a > 1.0 and trace.stable[i])
    return trace.states[k], trace.delta[k]


def test_edge_relaxation_restores_a_disturbed_edge(traced):
    """Nodes at the contact edge of an equilibrium moved by 0.1 ε (the predictor's typical miss)
    are brought back to balance: their residual falls by > 100x."""
    surface = traced[0]
    w, delta = _contact_state(traced)
    h = delta + surface.node_profile - w
    edge = np.nonzero(h < 1.0)[0][-1]
    disturbed = w.copy()
    disturbed[edge - 3:edge + 4] += 0.1
    before = np.linalg.norm(surface.residual(disturbed, delta))
    relaxed = relax_edge(surface, disturbed, delta, limit=0.2)
    assert np.linalg.norm(surface.residual(relaxed, delta)) < 1e-2 * before


def test_edge_relaxation_stays_within_its_limit(traced):
    """Asked to move no node by more than 0.01 ε, it leaves a 0.1 ε disturbance unrelaxed."""
    surface = traced[0]
    w, delta = _contact_state(traced)
    edge = np.nonzero(delta + surface.node_profile - w < 1.0)[0][-1]
    disturbed = w.copy()
    disturbed[edge - 3:edge + 4] += 0.1
    assert relax_edge(surface, disturbed, delta, limit=0.01) is disturbed


def test_edge_relaxation_leaves_a_spread_residual_alone(traced):
    """Far from contact the residual of w = 0 is spread over the whole surface: not an edge."""
    surface = traced[0]
    w = np.zeros(surface.r_nodes.size)
    assert relax_edge(surface, w, 3.0, limit=1.0) is w


def test_moved_linearisation_solves_like_a_fresh_one(traced):
    """A factorisation reused at a state moved by 1e-4 (a Newton increment near convergence),
    refined against that state's matrix, gives the fresh factorisation's Newton step to 1e-3
    (measured 1e-4) and says it converged; moved by 1e-2 everywhere its refinement diverges, and
    it says so."""
    surface = traced[0]
    w, delta = _contact_state(traced)
    row = np.array([-1.0, -1.0, 0.0]) / np.sqrt(2.0)
    converged = []
    for size in (1e-4, 1e-2):
        moved_w = w + size * (1.0 + np.max(np.abs(w))) * np.sin(surface.r_nodes)
        rhs = np.append(surface.residual(moved_w, delta), 0.3)
        fresh = np.append(*Linearisation(surface, moved_w, delta, row).solve(rhs))
        moved = Linearisation(surface, w, delta, row).moved_to(surface, moved_w, delta, row)
        reused = np.append(*moved.solve(rhs))
        converged.append(moved.converged)
        if size == 1e-4:
            assert np.max(np.abs(reused - fresh)) <= 1e-3 * np.max(np.abs(fresh))
    assert converged == [True, False]
