"""The pieces of the surface Newton solver that trade work for speed, each against the plain way."""

import numpy as np
import pytest

from fem_asperity.closed_forms.lj import scaled_traction_slope
from fem_asperity.path.continuation import Linearisation
from fem_asperity.path.elimination import relax_edge
from fem_asperity.path.newton import edge_block
from fem_asperity.path.surface import LJSurface
from fem_asperity.solver.discretised import solve_discretised
from fem_asperity.solver.presets import discretisation


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


@pytest.mark.parametrize("block", [(0, 40), (100, 180), (-60, None)])
def test_tangent_block_is_the_tangents_block_entry_for_entry(traced, block):
    """The edge block a moved linearisation refactorises is that block of the whole tangent, to
    the bit, at a state in contact (springs of both signs), at either end and inside."""
    surface = traced[0]
    w, delta = _contact_state(traced)
    _assert_block_is_the_tangents(surface, surface.sensitivities(w, delta)[2], block)


def test_tangent_block_of_a_restricted_fe_surface_is_the_tangents_block():
    """The same on the FE's surface restricted to a graded subset of its nodes (its springs
    from an interpolation through the restriction), with random springs of both signs."""
    half_space = discretisation(2.0, "draft", method="fem").elastic()
    graded = 1.0 + np.cumsum(0.02 * 1.2 ** np.arange(12))
    radii = np.concatenate([np.linspace(0.0, 1.0, 40), graded])
    surface = LJSurface(half_space.restricted(radii, keep_beyond=3.0), 2.0)
    slope = np.random.default_rng(1).standard_normal(surface.weights.size)
    for block in ((0, 20), (15, 45), (-25, None)):
        _assert_block_is_the_tangents(surface, slope, block)


def _assert_block_is_the_tangents(surface, slope, block):
    first, last = slice(*block).indices(surface.r_nodes.size)[:2]
    whole = surface.tangent_matrix(slope)
    assert np.array_equal(surface.tangent_block(slope, first, last),
                          whole[first:last, first:last])


def test_scaled_tangent_norm_is_the_largest_row_sum_of_the_scaled_tangent(traced):
    """`scaled_tangent_norm` is ‖D ∂g/∂w D‖∞ (D = diag(∂g/∂w)^(−1/2), from `tangent_diagonal`)
    at a state in contact, where springs of both signs meet at the edge, though it never forms
    ∂g/∂w."""
    surface = traced[0]
    w, delta = _contact_state(traced)
    slope = surface.sensitivities(w, delta)[2]
    jac = surface.tangent_matrix(slope, np.float64)
    diagonal = surface.tangent_diagonal(slope)
    assert np.allclose(diagonal, jac.diagonal(), rtol=1e-12, atol=0.0)
    scale = np.sqrt(diagonal)
    exact = np.max(np.abs(jac / np.outer(scale, scale)).sum(axis=1))
    assert surface.scaled_tangent_norm(slope, scale) == pytest.approx(exact, rel=1e-12)


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


def test_a_linearisation_moved_to_the_next_point_solves_like_a_fresh_one(traced):
    """At every pair of neighbouring traced points in contact, the linearisation of the first
    moved to the second (its edge block refactorised, as each point's first Newton iterate does)
    gives the fresh Newton step to 1e-3 and says it converged, or declines (None) because the
    crack tip left its edge block, at most a few times along the curve."""
    surface, trace = traced
    row = np.array([-1.0, -1.0, 0.0]) / np.sqrt(2.0)
    moved_pairs = declined = 0
    for k in range(len(trace.delta) - 1):
        if not (trace.stable[k] and trace.stable[k + 1] and trace.a_c[k] > 0.0):
            continue
        w, delta = trace.states[k + 1], trace.delta[k + 1]
        rhs = np.append(surface.residual(w + 1e-3, delta), 0.3)
        moved = Linearisation(surface, trace.states[k], trace.delta[k], row).moved_to(
            surface, w, delta, row)
        if moved is None:
            declined += 1
            continue
        fresh = np.append(*Linearisation(surface, w, delta, row).solve(rhs))
        step = np.append(*moved.solve(rhs))
        assert moved.converged
        assert np.max(np.abs(step - fresh)) <= 1e-3 * np.max(np.abs(fresh))
        moved_pairs += 1
    assert moved_pairs >= 20 and declined <= moved_pairs // 4


def test_a_linearisation_declines_to_move_where_the_tip_left_its_edge_block(traced):
    """Moved from a state in contact to the state before contact (its tip at the centre), the
    linearisation declines: the tip is outside its edge block."""
    surface, trace = traced
    row = np.array([-1.0, -1.0, 0.0]) / np.sqrt(2.0)
    w, delta = _contact_state(traced)
    before = next(k for k, a in enumerate(trace.a_c) if a == 0.0)
    linear = Linearisation(surface, w, delta, row)
    assert edge_block(surface, w, delta)[0] > 0
    assert linear.moved_to(surface, trace.states[before], trace.delta[before], row) is None


def test_each_point_changing_stability_has_its_own_flag():
    """Along the whole curve at μ = 2 (BEM `draft`, unstable branch included), where the flag
    changes between neighbouring points it is that point's own: a fresh factorisation there
    agrees (a flag from the last Newton iterate can be wrong where the softest mode is near
    zero)."""
    result = solve_discretised(2.0, discretisation(2.0, "draft", method="bem"),
                               unstable_branch=True)
    surface, trace = result.model.surface, result.model.trace
    row = np.array([0.0, 1.0, 0.0])
    changes = [k for k in range(1, len(trace.stable)) if trace.stable[k] != trace.stable[k - 1]]
    assert changes
    for k in changes:
        fresh = Linearisation(surface, trace.states[k], trace.delta[k], row)
        assert fresh.stable == trace.stable[k]
