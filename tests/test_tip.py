"""Stable branches followed in the crack tip's radius (`path.tip`)."""

import numpy as np
import pytest

from fem_asperity.path.continuation import Trace, correct
from fem_asperity.path.held_tip import HeldSystem, _constraint, held
from fem_asperity.path.landing import land
from fem_asperity.path.surface import LJSurface
from fem_asperity.path.tip import _insert_roots
from fem_asperity.solids.bem import BoussinesqSurface, radial_grid
from fem_asperity.solver.discretised import solve_discretised
from fem_asperity.solver.presets import discretisation
from fem_asperity.solver.solve import solve_curve

TOL = 1e-9


@pytest.fixture(scope="module")
def adhered():
    """(surface, w, δ̄o): a stable adhered state at μ = 10 on a uniform boundary-integral grid,
    its crack tip at about 5 √(Rε)."""
    surface = LJSurface(BoussinesqSurface(radial_grid(h=0.01, r_fine=3.0, r_max=20.0)), 10.0)
    delta = 1.0
    touching = np.where(surface.r_nodes < 2.0, delta + surface.node_profile - 1.0, 0.0)
    landed = land(surface, touching, delta, tol=TOL)
    assert landed.converged and surface.crack_tip(landed.w, delta) > 1.0
    return surface, landed.w, delta


def test_a_held_state_is_an_equilibrium_with_its_tip_where_asked(adhered):
    """Held 0.02 √(Rε) inside the state's own tip: the tip is there (to 1e-9), and at its δ̄o
    the state is an equilibrium of displacement control (Newton at that δ̄o is done at once)."""
    surface, w, delta = adhered
    tip = surface.crack_tip(w, delta) - 0.02
    state = held(surface, w, delta, tip, tol=TOL)
    assert state is not None and state.delta > delta  # pulled further to peel
    assert surface.crack_tip(state.w, state.delta) == pytest.approx(tip, abs=1e-9)
    again = correct(surface, state.w, state.delta, np.array([0.0, 1.0, 0.0]),
                    np.array([0.0, state.delta, 0.0]), 0.0, tol=TOL)
    assert again is not None and again[2] == 1
    assert np.max(np.abs(again[0] - state.w)) <= 1e-7 * np.max(np.abs(state.w))


def test_the_rates_are_the_derivatives_of_held_states(adhered):
    """d(x̄o, δ̄o, P̄)/d(tip) from the bordered matrix against central differences of held states
    (step 1e-6 √(Rε)): agreement to 1e-6 relative (measured 1.4e-8; with steps of 1e-4 and 1e-5
    the differences' truncation error, 1.5e-4 and 1.5e-6, the tip on a coarse element)."""
    surface, w, delta = adhered
    tip, step = surface.crack_tip(w, delta) - 0.02, 1e-6
    state = held(surface, w, delta, tip, tol=1e-12)
    ends = [held(surface, state.w, state.delta, tip + s, tol=1e-12) for s in (-step, step)]

    def observed(s):
        return np.array([surface.centre_gap(s.w, s.delta), s.delta, s.force])

    difference = (observed(ends[1]) - observed(ends[0])) / (2.0 * step)
    assert state.rates == pytest.approx(difference, rel=1e-6)
    assert state.before_fold == (state.rates[1] < 0.0)


def test_an_indefinite_prediction_is_solved_through_the_pins_penalty(adhered):
    """A held state's gaps moved 0.05 √(Rε) inward with its tip (the path's prediction) have an
    indefinite ∂g/∂w; the bordered Newton matrix there is solved by the Cholesky factor of
    ∂g/∂w + ρ e eᵀ, and agrees with a double-precision dense solve of the bordered matrix to
    1e-9 relative (measured 1.5e-11: one refinement of a single-precision factor)."""
    surface, w, delta = adhered
    state = held(surface, w, delta, surface.crack_tip(w, delta) - 0.02, tol=TOL)
    tip = state.tip - 0.05
    predicted = surface.translated(state.w, state.delta, -0.05, state.delta)
    slope = surface.sensitivities(predicted, state.delta)[2]
    assert np.min(np.linalg.eigvalsh(surface.tangent_matrix(slope, np.float64))) < 0.0
    pin, c, _ = _constraint(surface, predicted, state.delta, tip)
    system = HeldSystem(surface, predicted, state.delta, pin)
    g_delta = system.g_delta
    assert system._penalty > 0.0 and system._lu is None
    n = pin.size
    dense = np.zeros((n + 1, n + 1))
    dense[:n, :n] = surface.tangent_matrix(slope, np.float64)
    dense[:n, n], dense[n, :n], dense[n, n] = g_delta, -pin, 1.0
    rhs = -np.append(surface.residual(predicted, state.delta), c)
    expected = np.linalg.solve(dense, rhs)
    dw, dd = system.solve(rhs)
    assert np.max(np.abs(np.append(dw, dd) - expected)) <= 1e-9 * np.max(np.abs(expected))


@pytest.mark.slow
class _Admitting:
    """Grids that resolve every state (the fixture's one uniform grid)."""

    def admits(self, surface, w, delta):
        return True


def test_a_crossing_between_two_held_states_is_inserted_as_a_solved_state(adhered):
    """Between two held states 0.01 √(Rε) of peel apart (δ̄o 3.5 and 17.7), the state where the
    centre gap passes the level halfway between theirs (as the path inserts the initial contact,
    x̄o = 1) is solved, not interpolated: one state appended, its x̄o at the level to 1e-9 ε,
    its δ̄o between theirs."""
    surface, w, delta = adhered
    tip = surface.crack_tip(w, delta)
    first = held(surface, w, delta, tip - 0.005, tol=TOL)
    second = held(surface, first.w, first.delta, tip - 0.015, tol=TOL)
    level = 0.5 * (first.observed[0] + second.observed[0])
    assert abs(first.observed[0] - second.observed[0]) > 1e-3
    assert first.before_fold and second.before_fold
    trace = Trace()
    _insert_roots(_Admitting(), trace, first, second, -1, TOL,
                  (lambda state: state.observed[0] - level,))
    assert len(trace.delta) == 1
    assert trace.x[0] == pytest.approx(level, abs=1e-9)
    assert min(first.delta, second.delta) < trace.delta[0] < max(first.delta, second.delta)


def test_the_peel_gives_the_arc_length_paths_events(monkeypatch):
    """BEM `draft` at μ = 8: the retraction followed in the tip against the same branch followed
    in arc length (`continuation.follow`, the peel switched off): P̄off and the jump-out's δ̄o
    differ by less than the curve's error estimate, in fewer Newton iterations."""
    from fem_asperity.path import branches

    peeled = solve_curve(8.0, method="bem", accuracy="draft")
    monkeypatch.setattr(branches, "tip_direction", lambda *args: 0)
    arc = solve_discretised(8.0, discretisation(8.0, "draft", method="bem"))
    assert peeled.newton_iterations < arc.newton_iterations
    a, b = peeled.events.records(), arc.events.records()
    for key in ("p_off", "delta_jump_out"):
        assert abs(a[key] - b[key]) <= peeled.error_estimate[key], key


def test_the_approach_followed_in_the_tip_gives_the_arc_length_paths_curve(monkeypatch):
    """BEM `draft` at μ = 8: the approach after the jump-in followed in the tip (as from μ = 26
    on, `tip.APPROACH_BANDS`, forced here) against the same branch followed in arc length (the
    default at this μ). Its P̄(δ̄o), a cubic spline through its points, passes the arc length's
    points within 1e-6 (measured 6.8e-8; the arc length's own spline through every other point
    misses the rest by 2.5e-7, and a state of another branch would be a P̄ step, 0.05, away);
    every event has an estimate (the path's first point is the landing itself,
    `held_tip.as_held`) and lies within the other curve's."""
    from scipy.interpolate import CubicSpline

    from fem_asperity.path import branches, tip

    arc = solve_curve(8.0, method="bem", accuracy="draft")
    monkeypatch.setattr(tip, "APPROACH_BANDS", 0.0)
    points = []

    def spy(*args, **kwargs):
        path = tip.follow_tip(*args, **kwargs)
        points.append((args[5], len(path.trace.delta)))
        return path

    monkeypatch.setattr(branches, "follow_tip", spy)
    tipped = solve_curve(8.0, method="bem", accuracy="draft")
    assert any(direction == 1 and count > 10 for direction, count in points)

    def contact_branch(result):
        approach = result.approach
        last = approach.branch == approach.branch.max()
        order = np.argsort(approach.delta[last])
        return approach.delta[last][order], approach.p[last][order]

    delta, force = contact_branch(arc)
    spline = CubicSpline(*contact_branch(tipped))
    inside = (delta > spline.x[0]) & (delta < spline.x[-1])
    assert inside.sum() > 20
    assert np.max(np.abs(spline(delta[inside]) - force[inside])) <= 1e-6
    a, b = tipped.events.records(), arc.events.records()
    for key in ("p_max", "delta_oc", "a_c", "p_off", "delta_jump_out"):
        assert tipped.error_estimate.get(key) is not None, key
        assert abs(a[key] - b[key]) <= arc.error_estimate[key], key


def test_the_jump_outs_fold_found_elsewhere_widens_its_estimate():
    """BEM `draft` at μ = 8: the jump-out's fold found again from its bracketing states, each
    on a grid centred the grids' lead further along, moves (`regrid_fold_change` > 0), and the
    estimate of δ̄o at the jump-out includes that move (`solver.estimate.FOLDS`): the finer
    partner places its grids alike and does not see it."""
    result = solve_curve(8.0, method="bem", accuracy="draft")
    assert result.regrid_fold_change > 0.0
    assert result.error_estimate["delta_jump_out"] >= result.regrid_fold_change
    assert f"a fold's δ̄o by at most {result.regrid_fold_change:.1e}" in result.message
