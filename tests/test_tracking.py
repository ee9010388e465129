"""Grids that follow the contact edge, against the uniform grid (BEM) and the whole surface
(FE)."""

from dataclasses import replace

import numpy as np
import pytest

from fem_asperity import InputError
from fem_asperity.closed_forms.lj import scaled_traction_slope
from fem_asperity.path.grids import edge_grid, spring_ratio
from fem_asperity.solver.discretised import solve_discretised
from fem_asperity.solver.output import state_fields
from fem_asperity.solver.presets import MU_TRACKING, discretisation
from fem_asperity.solver.solve import solve_curve


def test_spring_ratio_limits():
    """1 at the stiffest destabilising gap 7.5^(1/6) ε, unbounded where the springs stabilise
    (below 3^(1/6) ε), and max(dp̄/dh)/(8 g⁻⁴) for large gaps g."""
    stiffest = 7.5 ** (1.0 / 6.0)
    gaps = np.linspace(0.9, 30.0, 2000)
    assert spring_ratio(stiffest) == pytest.approx(1.0, rel=1e-12)
    assert np.all(spring_ratio(gaps) >= 1.0 - 1e-12)
    assert spring_ratio(1.1) >= 1e11
    peak = scaled_traction_slope(stiffest)
    assert spring_ratio(30.0) == pytest.approx(peak * 30.0**4 / 8.0, rel=1e-6)


def test_edge_grid_spacing():
    h, band, growth = 0.004, 0.03, 0.1
    edge, tip = 3.0, 4.0

    def gap(r):
        return np.where(r < tip, 1.0, 1.0 + 2.0 * (r - tip))

    nodes = edge_grid(edge, tip, gap, h=h, band=band, r_max=100.0, growth=growth, h_inside=0.1)
    sizes = np.diff(nodes)
    assert nodes[0] == 0.0 and nodes[-1] >= 100.0 and np.all(sizes > 0.0)
    left = nodes[:-1]
    near = (np.abs(left - edge) <= band) | (np.abs(left - tip) <= band)
    assert np.all(sizes[near] <= h * (1.0 + 1e-9))
    assert np.all(sizes <= h * spring_ratio(gap(left)) * (1.0 + 1e-9))
    assert np.all(sizes[left < tip] <= 0.1 + 1e-12)
    assert np.all(sizes[1:] / sizes[:-1] <= 1.0 + growth + 1e-9)
    with pytest.raises(InputError, match="edge"):
        edge_grid(tip, edge, gap, h=h, band=band, r_max=100.0, h_inside=0.1)


@pytest.fixture(scope="module")
def mu5():
    """(uniform grid, tracked grids) BEM `default` curves at μ = 5, the tracked grids' edge
    elements as long as the uniform grid's (by default they are half as long)."""
    uniform = discretisation(5.0, method="bem", track_edge=False)
    tracked = replace(discretisation(5.0, method="bem", track_edge=True),
                      h_surface=uniform.h_surface)
    return solve_discretised(5.0, uniform), solve_discretised(5.0, tracked)


@pytest.mark.slow
def test_tracked_grids_give_the_uniform_grids_events(mu5):
    """Measured: P̄max, P̄off, both jumps and the force after the jump-in agree to 1e-6; x̄oc
    to 2.2e-5 (the grid before contact is 0.025 against the uniform grid's 0.0112); δ̄oc, on
    the flat force maximum, to 1.1e-3. ā_c is the radius where the gap passes 1 ε inside an
    adhered zone whose gaps stay within 0.02 ε of 1: landings on grids of other edge elements
    (1, 4, 8 times longer) gave 1.94485, 1.94776 and 1.94715 with P̄max equal to 6e-7; here
    1.1e-3 off."""
    uniform, tracked = (r.events.records() for r in mu5)
    for key in ("p_max", "p_off", "delta_jump_in", "p_jump_after", "delta_jump_out"):
        assert tracked[key] == pytest.approx(uniform[key], rel=1e-5), key
    assert tracked["x_oc"] == pytest.approx(uniform["x_oc"], rel=1e-4)
    assert tracked["delta_oc"] == pytest.approx(uniform["delta_oc"], rel=5e-3)
    assert tracked["a_c"] == pytest.approx(uniform["a_c"], rel=2e-3)


def test_tracked_grids_from_the_bem_threshold_give_the_uniform_grids_events():
    """At MU_TRACKING["bem"] (`draft`, the tracked grids as they are by default): measured
    P̄max and P̄off 2.6e-6 apart, the jumps' δ̄o 4e-7 and 4e-9, ā_c 7.8e-4."""
    mu = MU_TRACKING["bem"]
    uniform, tracked = (solve_discretised(mu, discretisation(mu, "draft", method="bem",
                                                             track_edge=edge)).events.records()
                        for edge in (False, True))
    for key in ("p_max", "p_off", "delta_jump_in", "p_jump_after", "delta_jump_out"):
        assert tracked[key] == pytest.approx(uniform[key], rel=1e-5), key
    assert tracked["a_c"] == pytest.approx(uniform["a_c"], rel=2e-3)
    assert discretisation(mu, "draft", method="bem") == discretisation(
        mu, "draft", method="bem", track_edge=True)


@pytest.mark.slow
def test_tracked_approach_force_follows_the_uniform_one(mu5):
    """P̄(δ̄o) of the approach after the jump-in, interpolated at the tracked samples."""
    uniform, tracked = (r.approach for r in mu5)
    after_u, after_t = uniform.branch == 1, tracked.branch == 1
    order = np.argsort(uniform.delta[after_u])
    du, pu = uniform.delta[after_u][order], uniform.p[after_u][order]
    inside = (tracked.delta >= du[0]) & (tracked.delta <= du[-1]) & after_t
    expected = np.interp(tracked.delta[inside], du, pu)
    assert inside.sum() > 20
    assert np.max(np.abs(tracked.p[inside] - expected)) <= 2e-3


@pytest.mark.slow
def test_tracked_result_says_how_it_was_computed(mu5):
    uniform, tracked = mu5
    assert "grids followed the contact edge" in tracked.message
    assert tracked.surface_nodes < 0.6 * uniform.surface_nodes and tracked.model is None
    with pytest.raises(InputError, match="stable branches"):
        solve_discretised(5.0, discretisation(5.0, method="bem", track_edge=True),
                          unstable_branch=True)


def test_a_whole_curve_on_grids_that_follow_the_edge_is_refused_before_building_them(
        monkeypatch):
    fe = discretisation(5.0, method="fem", track_edge=True)
    monkeypatch.setattr(type(fe), "elastic", lambda *args, **kwargs: pytest.fail("meshed"))
    with pytest.raises(InputError, match="stable branches"):
        solve_discretised(5.0, fe, unstable_branch=True)


@pytest.fixture(scope="module")
def fe_mu5():
    """(whole surface, surface restricted to grids that follow the edge) FE `default` curves at
    μ = 5, on the same mesh."""
    return tuple(solve_discretised(5.0, discretisation(5.0, method="fem", track_edge=track))
                 for track in (False, True))


#: The error estimate of the whole FE surface at μ = 5, `default` (solve_curve, its finer
#: discretisation's difference): the restriction must stay within it.
FE_MU5_ESTIMATE = {"p_max": 2.0e-6, "p_off": 2.0e-6, "p_jump_after": 1.9e-6, "x_oc": 8.8e-6,
                   "delta_jump_in": 1.3e-5, "delta_o_star": 1.3e-5, "delta_jump_out": 7.0e-5,
                   "delta_oc": 1.5e-3, "a_c": 5.1e-4}


@pytest.mark.slow
def test_fe_on_grids_that_follow_the_edge_gives_the_whole_surfaces_events(fe_mu5):
    """Each event of the restricted FE (`solids.fe.RestrictedSurface`) lies within the whole
    surface's error estimate of the whole surface's; measured: P̄ 6e-7, δ̄o at the jumps 4e-7
    and 1.4e-5, x̄oc 2e-7, δ̄oc 1.2e-5, ā_c 4e-6."""
    whole, tracked = (r.events.records() for r in fe_mu5)
    for key, estimate in FE_MU5_ESTIMATE.items():
        assert tracked[key] == pytest.approx(whole[key], abs=estimate), key
    assert "grids followed the contact edge" in fe_mu5[1].message
    assert fe_mu5[1].surface_nodes < 0.6 * fe_mu5[0].surface_nodes


@pytest.mark.slow
def test_fields_of_a_state_on_a_restricted_surface(fe_mu5):
    """The field at P̄off of the restricted FE is the half-space's response to that state's
    pressure: on the surface it is the state's w (on the FE's nodes) to within the restriction's
    error, here 2e-3 of the largest |w| (measured 9e-4; a state read on the wrong nodes is off
    by the order of |w|)."""
    tracked = fe_mu5[1]
    index = int(np.argmin(tracked.equilibrium.p))
    mesh, nodal, _ = state_fields(tracked, index)
    model = tracked.model
    top = np.flatnonzero(mesh.p[1] == mesh.p[1].max())
    w = np.interp(mesh.p[0, top], model.trace.nodes[index], model.trace.states[index])
    assert np.max(np.abs(nodal[top, 1] - w)) <= 2e-3 * np.max(np.abs(w))


@pytest.mark.slow
def test_grids_ahead_of_the_edges_build_fewer_grids_for_the_same_curve(monkeypatch):
    """Grids centred ahead of the moving edges (AHEAD of a band) against centred ones, BEM
    `draft` at μ = 8: fewer grids (the edges cross 1.4 bands per grid instead of 0.75), and
    P̄max, P̄off, ā_c and the jumps differ by no more than the curve's own error estimate.
    ā_c moved by 4.8e-4, more than its estimate from the finer partner alone (1.2e-4: its grids
    are placed alike): the estimate of ā_c adds the curve's `regrid_radius_change` for that,
    and the force estimates its `regrid_change` (P̄off moved by 3.7e-8; at AHEAD = 0.4 and FIT =
    0.5 it moved by 1.3e-8 against 4e-9)."""
    from fem_asperity.path import grids

    ahead = solve_curve(8.0, method="bem", accuracy="draft")
    monkeypatch.setattr(grids, "AHEAD", 0.0)
    centred = solve_discretised(8.0, discretisation(8.0, "draft", method="bem"))
    count = [int(r.message.split(" grids followed")[0].split("; ")[-1]) for r in (ahead, centred)]
    assert count[0] < 0.8 * count[1]
    assert ahead.regrid_change > 0.0 and ahead.regrid_radius_change > 0.0
    for key in ("p_max", "p_off", "a_c", "delta_jump_in", "delta_jump_out"):
        difference = abs(ahead.events.records()[key] - centred.events.records()[key])
        assert difference <= ahead.error_estimate[key], key


def test_grids_tell_which_states_they_resolve():
    """The pre-contact grid resolves states without contact only; a surface built elsewhere
    resolves none."""
    from fem_asperity.path.grids import EdgeGrids

    grids = EdgeGrids(5.0, h=0.01, band=0.07, h_inside=0.1, contact_h=0.05, contact_r=4.0,
                      r_max=100.0)
    start, delta = grids.start, 3.0
    apart = np.zeros(start.r_nodes.size)
    touching = np.where(start.r_nodes < 1.0, delta + start.node_profile - 1.0, 0.0)
    assert start.crack_tip(apart, delta) == 0.0 and start.crack_tip(touching, delta) > 0.9
    assert grids.fits(start, apart, delta) and grids.admits(start, apart, delta)
    assert not grids.fits(start, touching, delta) and not grids.admits(start, touching, delta)
    other = EdgeGrids(5.0, h=0.01, band=0.07, h_inside=0.1, contact_h=0.05, contact_r=4.0,
                      r_max=100.0).start
    assert not grids.fits(other, apart, delta)



def test_a_grid_placed_beyond_its_own_reach_is_refused():
    """A lead `ahead` not below the reach `fit` would build grids that do not fit the states
    they were built for (a landing would move on forever): refused up front."""
    from fem_asperity.path.grids import EdgeGrids

    for fit, ahead in ((0.5, 0.5), (0.5, 0.6), (1.2, 0.4), (0.5, -0.1)):
        with pytest.raises(InputError, match="ahead < fit"):
            EdgeGrids(5.0, h=0.01, band=0.07, h_inside=0.1, contact_h=0.05, contact_r=4.0,
                      r_max=100.0, fit=fit, ahead=ahead)

def test_the_next_grid_is_placed_ahead_the_way_each_edge_moved_since_the_last_was_built():
    """A grid built for the edges (5.0, 8.0) and centred ahead of both (5.04, 8.04); the state
    then at (5.09, 8.01): both edges moved outward, the crack tip by less than the grid's lead,
    so the next grid is centred AHEAD × band beyond each. (Measured from the centre the tip
    seemed to move back, and the grids alternated.)"""
    from fem_asperity.path.grids import AHEAD, EdgeGrids
    from fem_asperity.solids.bem import radial_grid

    band = 0.1
    grids = EdgeGrids(5.0, h=0.01, band=band, h_inside=0.1, contact_h=0.05, contact_r=4.0,
                      r_max=100.0)
    surface = grids._surface(radial_grid(h=0.5, r_fine=10.0, r_max=20.0), (5.04, 8.04),
                             (5.0, 8.0))
    centre = grids._ahead(surface, (5.09, 8.01))
    assert centre == pytest.approx((5.09 + AHEAD * band, 8.01 + AHEAD * band), abs=1e-12)


def test_peeled_jump_landings_on_edge_grids_land_where_the_descent_alone_does(monkeypatch):
    """BEM `draft` at μ = 8: the jump landings on edge grids peel the crack tip along (measured:
    4 peels moving it 1.18 √(Rε) in all) and land where the descent alone lands (the force
    after the jump-out to 1e-9: measured equal to 1e-17). Each from its fold, not from a guess
    (`EdgeGrids.landing_guess`)."""
    from fem_asperity.path import grids
    from fem_asperity.path.landing import Peel

    monkeypatch.setattr(grids.EdgeGrids, "landing_guess", lambda *args, **options: None)
    travel = []

    def peel(surface, w, delta, direction, **options):
        peeled = real_peel(surface, w, delta, direction, **options)
        travel.append(abs(surface.crack_tip(peeled.w, delta) - surface.crack_tip(w, delta)))
        return peeled

    real_peel = grids.peel
    monkeypatch.setattr(grids, "peel", peel)
    peeled = solve_curve(8.0, method="bem", accuracy="draft", error_estimate=False)
    assert sum(travel) > 0.5
    monkeypatch.setattr(grids, "peel", lambda surface, w, *args, **options: Peel(w, 0, False))
    descended = solve_curve(8.0, method="bem", accuracy="draft", error_estimate=False)
    for jump in ("jump_in", "jump_out"):
        a, b = getattr(peeled.events, jump), getattr(descended.events, jump)
        assert a.delta == pytest.approx(b.delta, abs=1e-9)
        assert a.p_after == pytest.approx(b.p_after, abs=1e-9), jump


def test_jumps_land_from_the_guesses_where_the_descent_lands(monkeypatch):
    """BEM `draft` at μ = 8: the jumps landed from `EdgeGrids.landing_guess` (JKR's contact in,
    the undeformed surface out) against the descent from each fold: fewer Newton iterations
    (measured 510 against 1007), and the same landings within what a move to another grid
    changes (the jump-in's land on different grids; measured: P̄ 5.8e-9 and ā_c 1.3e-4 apart,
    the largest move's changes 7.4e-8 and 4.5e-4), and the same jump out (P̄off 1.5e-9 apart,
    its δ̄o 6.9e-8)."""
    from fem_asperity.path import branches
    from fem_asperity.path.grids import EdgeGrids

    kept = []

    def land_from_guess(*args):
        landed = real(*args)
        kept.append(landed[0] is not None)
        return landed

    real = branches._land_from_guess
    monkeypatch.setattr(branches, "_land_from_guess", land_from_guess)
    guessed = solve_curve(8.0, method="bem", accuracy="draft", error_estimate=False)
    assert kept == [True, True]  # both jumps landed from their guesses
    monkeypatch.setattr(EdgeGrids, "landing_guess", lambda *args, **options: None)
    descended = solve_curve(8.0, method="bem", accuracy="draft", error_estimate=False)
    assert guessed.newton_iterations < descended.newton_iterations
    a, b = guessed.events.jump_in, descended.events.jump_in
    assert a.delta == b.delta
    assert a.p_after == pytest.approx(b.p_after, abs=1e-7)
    assert a.a_c_after == pytest.approx(b.a_c_after, abs=5e-4)
    a, b = guessed.events.jump_out, descended.events.jump_out
    assert a.delta == pytest.approx(b.delta, abs=1e-6)
    assert a.a_c_after == b.a_c_after == 0.0
    assert a.p_after == pytest.approx(b.p_after, abs=1e-9)
    assert guessed.events.p_off == pytest.approx(descended.events.p_off, abs=1e-8)


def test_a_branch_moved_to_the_next_grid_is_solved_there_as_the_descent_solves_it(monkeypatch):
    """BEM `draft` at μ = 8: a branch's state moved to a new grid solved again by Newton
    (`EdgeGrids.regrid`) against the same by `land`'s descent alone: fewer Newton iterations,
    and the events agree to 1e-9 (measured: equal to the bit)."""
    from fem_asperity.path import grids

    newton = solve_curve(8.0, method="bem", accuracy="draft", error_estimate=False)
    monkeypatch.setattr(grids, "correct_at_delta", lambda *args, **options: None)  # regrid lands
    descended = solve_curve(8.0, method="bem", accuracy="draft", error_estimate=False)
    assert newton.newton_iterations < descended.newton_iterations
    a, b = newton.events.records(), descended.events.records()
    for key in ("p_max", "a_c", "p_off", "delta_jump_in", "delta_jump_out"):
        assert a[key] == pytest.approx(b[key], abs=1e-9), key


def test_predictor_moves_the_crack_tip_front_along():
    """Two states whose gap profiles are one front translated by 0.05: the prediction one step
    on (fraction 1) is that front translated again, within the window, to interpolation error
    (`continuation._shift_front`)."""
    from fem_asperity.path.continuation import Trace, _shift_front
    from fem_asperity.path.surface import LJSurface
    from fem_asperity.solids.bem import BoussinesqSurface, radial_grid

    surface = LJSurface(BoussinesqSurface(radial_grid(h=0.005, r_fine=2.0, r_max=5.0)), 10.0)
    r, delta = surface.r_nodes, 1.0

    def state(tip):
        gaps = 1.0 + 5.0 / (1.0 + np.exp(-(r - tip) / 0.02))
        return delta + surface.node_profile - gaps

    trace = Trace(delta=[delta, delta], states=[state(1.0), state(1.05)])
    predicted = _shift_front(surface, trace, state(1.05), delta, 1.0, window=0.2)
    expected = surface.crack_tip(state(1.1), delta)
    assert surface.crack_tip(predicted, delta) == pytest.approx(expected, abs=1e-3)
    near = np.abs(r - 1.1) <= 0.2
    # measured 3.1e-4; the last state itself is 2.8 off
    assert np.max(np.abs(predicted - state(1.1))[near]) < 1e-3
