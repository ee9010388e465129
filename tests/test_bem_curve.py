"""The boundary-integral curve against the FE (two independent elastic solvers) and the onset."""

from dataclasses import replace

import numpy as np
import pytest

from fem_asperity import InputError
from fem_asperity.curves.events import ESTIMATED
from fem_asperity.solids.fe import Solid
from fem_asperity.solver.discretised import solve_discretised
from fem_asperity.solver.presets import discretisation
from fem_asperity.solver.solve import solve_curve
from fem_asperity.studies.onset import fold_margin


@pytest.mark.parametrize("mu", [0.1, 0.5, 1.0, pytest.param(3.0, marks=pytest.mark.slow)])
def test_bem_agrees_with_fem_within_the_error_estimates(mu):
    """Two independent methods: every event of the FE at `default` lies within the two error
    estimates (the FE's own, from its finer discretisation, and that of the BEM at `fine`) of
    the BEM's. The BEM's is needed for ā_c, which converges slowly and irregularly (it is read
    where the traction changes sign between nodes): at μ = 3 the BEM `fine` is itself 1.1e-3
    off in ā_c, more than the FE's estimate (2.8e-4)."""
    fem = solve_curve(mu, method="fem", accuracy="default", estimate_by="finer")
    bem = solve_curve(mu, method="bem", accuracy="fine")
    a, b = fem.events.records(), bem.events.records()
    assert a["jump_in"] == b["jump_in"]
    for key in ESTIMATED:
        if a[key] is None:
            assert b[key] is None, key
        else:
            assert abs(a[key] - b[key]) <= fem.error_estimate[key] + bem.error_estimate[key], key


def test_the_fes_estimate_against_the_bem_bounds_its_error():
    """The FE of a homogeneous half-space is estimated against the boundary integral by default:
    per event twice |FE − BEM| plus the BEM's own estimate (and for a force the FE's own
    `estimate_floor`), the BEM at the same preset solved alone giving the same numbers. At
    μ = 1, `draft`, each estimate bounds the FE's error against the BEM on elements half as long
    as `fine`'s (measured: estimate over error 2.0-4.2,
    errors 2.2e-5 to 7.4e-3)."""
    fem = solve_curve(1.0, accuracy="draft")
    bem = solve_curve(1.0, method="bem", accuracy="draft")
    reference = solve_discretised(1.0, discretisation(1.0, "fine", method="bem").refined())
    assert fem.estimated_by == "bem" and bem.estimated_by == "finer"
    assert "against the boundary integral" in fem.message and fem.status == "ok"
    a, b, r = (x.events.records() for x in (fem, bem, reference))
    for key in ESTIMATED:
        if a[key] is None:
            assert fem.error_estimate[key] is None, key
            continue
        floor = fem.estimate_floor.get(key, 0.0)  # the FE's own traction tail (forces)
        expected = 2.0 * abs(a[key] - b[key]) + bem.error_estimate[key] + floor
        assert fem.error_estimate[key] == pytest.approx(expected, rel=1e-9), key
        assert abs(a[key] - r[key]) <= fem.error_estimate[key], key


def test_a_whole_fe_curve_is_estimated_against_the_whole_bem_curve():
    """With the unstable branches (and so under a cantilever) both curves are traced whole, on
    uniform grids; the estimate is composed alike."""
    fem = solve_curve(1.0, accuracy="draft", unstable_branch=True)
    bem = solve_curve(1.0, method="bem", accuracy="draft", unstable_branch=True)
    assert fem.estimated_by == "bem" and fem.status == "ok"
    a, b = fem.events.records(), bem.events.records()
    for key in ("p_off", "delta_jump_in", "delta_jump_out"):
        floor = fem.estimate_floor.get(key, 0.0)  # the FE's own traction tail (forces)
        expected = 2.0 * abs(a[key] - b[key]) + bem.error_estimate[key] + floor
        assert fem.error_estimate[key] == pytest.approx(expected, rel=1e-9), key


def test_the_fes_estimate_is_none_if_the_bem_curve_fails(monkeypatch):
    """The boundary integral's curve alongside the FE: if it fails, the FE curve is kept
    without an estimate, and the message says what to try instead. (If the FE stops, the BEM
    curve stops too: `test_an_interrupted_curve_stops_its_estimate_solve_too`.)"""
    import fem_asperity.solver.discretised as discretised

    real = discretised.solve_traced

    def failing_bem(mu, disc, **kwargs):
        if disc.method == "bem":
            raise InputError("need 0 < h <= band (from inside the BEM curve)")
        return real(mu, disc, **kwargs)

    monkeypatch.setattr(discretised, "solve_traced", failing_bem)
    result = solve_curve(1.0, accuracy="draft")
    assert result.error_estimate is None and result.status == "no_estimate"
    assert "InputError" in result.message and result.events.jump_in is not None
    assert "estimate_by='finer'" in result.message  # what to do instead


def test_bem_result_provenance():
    result = solve_curve(1.0, method="bem", accuracy="draft")
    assert result.method == "bem" and result.dofs == result.surface_nodes
    assert result.error_estimate["p_off"] < 1e-4
    assert "2 folds" in result.message and result.folds == 2 and not result.ripples


def test_edge_following_grids_refuse_a_layer_and_methods_are_checked():
    """A layer takes one uniform grid (`solve_curve` chooses it; the edge-following grids would
    rebuild its correction on every grid and refuse it)."""
    edge = discretisation(10.0, "draft", method="bem", track_edge=True)
    with pytest.raises(InputError, match="homogeneous"):
        edge.grids(10.0, solid=Solid(layer_thickness=1.0))
    with pytest.raises(InputError, match="method"):
        solve_curve(1.0, method="spectral")


@pytest.mark.parametrize("method", ["bem", "fem"])
def test_fold_margin_changes_sign_between_069_and_070(method):
    """Both solvers put the jump-in onset between μ = 0.69 and 0.70 (the paper says 0.5)."""
    assert fold_margin(0.5, method=method, accuracy="draft") < -0.2
    assert fold_margin(0.69, method=method, accuracy="draft") < 0.0
    assert fold_margin(0.70, method=method, accuracy="draft") > 0.0


def test_out_files_are_all_or_nothing(tmp_path, monkeypatch):
    """A failure in the last file (the figure) leaves the output folder as an earlier run left
    it; a folder holding anything else is refused before a file is written."""
    from fem_asperity.plumbing.files import RECORD
    from fem_asperity.solver import output

    result = solve_curve(0.3, method="bem", accuracy="draft", error_estimate=False)
    target = tmp_path / "out"
    output.write_all(result, target)
    (target / "approach.csv").write_text("old")
    before = sorted(p.name for p in target.iterdir())

    def broken(*_args):
        raise OSError("disk full")

    monkeypatch.setattr(output, "plot_curve", broken)
    with pytest.raises(OSError):
        output.write_all(result, target)
    assert [p.name for p in tmp_path.iterdir()] == ["out"]
    assert sorted(p.name for p in target.iterdir()) == before  # no staging folder left
    assert (target / "approach.csv").read_text() == "old"
    monkeypatch.undo()
    names = {p.name for p in output.write_all(result, target)}
    assert names == {"approach.csv", "retraction.csv", "equilibrium.csv", "result.json",
                     "curve.png"}
    assert sorted(p.name for p in target.iterdir()) == sorted(names | {RECORD})
    assert (target / "approach.csv").read_text().startswith("delta_o/eps,")
    (tmp_path / "theirs").mkdir()
    (tmp_path / "theirs" / "approach.csv").write_text("a user's")
    with pytest.raises(InputError, match="did not write"):
        output.write_all(result, tmp_path / "theirs")
    assert (tmp_path / "theirs" / "approach.csv").read_text() == "a user's"


def test_tolerance_driven_solve_meets_its_tolerance():
    """Refined until P̄max and P̄off move by ≤ 1e-6; the answer is that close to a much finer
    BEM reference (h = 0.00625, turn 0.025: P̄off = −0.8353323349)."""
    from fem_asperity.solver.solve import solve_to_tolerance

    result = solve_to_tolerance(1.0, 1e-6, method="bem")
    assert "met after" in result.message and result.accuracy == "tolerance 1e-06"
    assert result.error_estimate["p_off"] <= 1e-6 * abs(result.events.p_off)
    assert result.events.p_off == pytest.approx(-0.8353323349, rel=2e-6)


def test_stable_branches_give_the_paths_of_the_whole_curve():
    """The default paths (stable branches only, each jump landed by energy descent) against the
    paths read off the whole traced curve: the force extrema agree to 1e-7; at the folds the
    whole curve's parabola through three samples closes in on the default's exact root of
    dδ̄o/ds as the turn limit shrinks (μ = 2, BEM `draft`)."""
    disc = discretisation(2.0, "draft", method="bem")
    fast = solve_discretised(2.0, disc).events.records()
    whole = solve_discretised(2.0, disc, unstable_branch=True).events.records()
    for key in ("p_max", "delta_oc", "a_c", "p_off"):
        assert fast[key] == pytest.approx(whole[key], rel=1e-7), key
    misses = []
    for turn in (0.2, 0.05):
        fine_steps = replace(disc, trace=replace(disc.trace, turn=turn))
        whole = solve_discretised(2.0, fine_steps, unstable_branch=True).events.records()
        misses.append(abs(whole["x_oc"] - fast["x_oc"]))
    assert misses[1] < 0.25 * misses[0]


@pytest.fixture(scope="module")
def whole_mu2():
    """(surface, trace, stable flags, fold indices, (jump in, jump out)) of the whole curve at
    μ = 2, BEM `draft`, its unstable branch traced."""
    result = solve_discretised(2.0, discretisation(2.0, "draft", method="bem"),
                               unstable_branch=True)
    traced = result.model.trace
    stable = np.asarray(traced.stable)
    folds = np.nonzero(stable[:-1] != stable[1:])[0]
    return (result.model.surface, traced, stable, folds,
            (result.events.jump_in, result.events.jump_out))


def test_energy_descent_lands_where_newton_on_the_traced_branch_does(whole_mu2):
    """Both jumps of the whole curve at μ = 2: `land` from the first unstable point past each
    fold, at the fold's δ̄o, reaches the state that Newton from the traced stable branch found."""
    from fem_asperity.path.landing import land

    surface, traced, stable, folds, jumps = whole_mu2
    for k, jump in zip(folds, jumps):
        beyond = k + 1 if stable[k] else k  # the unstable point next to the fold
        w, _, converged = land(surface, traced.states[beyond], jump.delta)
        assert converged
        assert surface.force(w, jump.delta) == pytest.approx(jump.p_after, rel=1e-8)


def test_a_descent_stops_at_the_first_iterate_its_grid_no_longer_resolves(whole_mu2):
    """At the jump-out of μ = 2 the descent draws the crack tip in (0.87 → 0 √(Rε)): with `resolved`
    asking for a tip beyond half its start (as `grids.EdgeGrids.land` asks it to stay in its
    grid's band) it stops at the first iterate below, not converged and lower in energy, and
    from there lands where the whole descent does."""
    from fem_asperity.path.landing import land

    surface, traced, stable, folds, jumps = whole_mu2
    k, delta = folds[1], jumps[1].delta
    start = traced.states[k + 1 if stable[k] else k]
    bound = 0.5 * surface.crack_tip(start, delta)
    steps = []

    def resolved(w):
        steps.append(surface.crack_tip(w, delta))
        return steps[-1] >= bound

    stopped = land(surface, start, delta, resolved=resolved)
    assert not stopped.converged and stopped.iterations == len(steps) > 1
    assert steps[-1] < bound <= min(steps[:-1])
    assert surface.energy(stopped.w, delta) < surface.energy(start, delta)
    landed = land(surface, stopped.w, delta)
    assert landed.converged
    assert surface.force(landed.w, delta) == pytest.approx(jumps[1].p_after, rel=1e-8)


def test_a_peel_from_the_jump_out_fold_leads_the_descent_to_its_landing(whole_mu2):
    """At the jump-out of μ = 2: `peel` from the first unstable point past the fold, the crack
    tip moved the way it moves there, lowers the energy and takes the tip most of the way in
    (measured 0.87 to 0.075 √(Rε)); `land` from the peeled state reaches the state that Newton
    from the traced stable branch found."""
    from fem_asperity.path.landing import land, peel

    surface, traced, stable, folds, jumps = whole_mu2
    k, delta = folds[1], jumps[1].delta
    beyond, before = (k + 1, k) if stable[k] else (k, k + 1)
    tips = [surface.crack_tip(traced.states[i], traced.delta[i]) for i in (before, beyond)]
    start = traced.states[beyond]
    peeled = peel(surface, start, delta, np.sign(tips[1] - tips[0]),
                  h=np.min(np.diff(surface.r_nodes)), max_step=0.1, tips=(0.0, np.inf),
                  fits=lambda w: True)
    assert surface.energy(peeled.w, delta) < surface.energy(start, delta)
    assert surface.crack_tip(peeled.w, delta) < 0.25 * tips[1]
    landed = land(surface, peeled.w, delta)
    assert landed.converged
    assert surface.force(landed.w, delta) == pytest.approx(jumps[1].p_after, rel=1e-8)


def test_a_pinned_crack_tip_gives_the_minimum_that_holds_it(whole_mu2):
    """`pinned` at the crack tip of a stable traced state returns that state (its point load
    vanishing), and a `peel` towards it from either side stops within a step of it; pinned 0.1 √(Rε)
    further in, the gap there is TIP_GAP and every nearby state that keeps it (moved along
    random directions that leave the pinned gap alone) has a higher energy."""
    from fem_asperity.path.landing import peel, pin_nodes, pinned
    from fem_asperity.path.surface import TIP_GAP

    surface, traced, stable, _, _ = whole_mu2
    i = int(np.nonzero(stable & (np.asarray(traced.a_c) > 1.0))[0][0])
    w, delta = traced.states[i], traced.delta[i]
    tip = surface.crack_tip(w, delta)
    itself = pinned(surface, w, delta, tip)
    assert itself.converged and abs(itself.multiplier) < 1e-8
    assert np.max(np.abs(itself.w - w)) < 1e-7
    held = pinned(surface, w, delta, tip - 0.1)
    assert held.converged and abs(held.multiplier) > 1e-4
    nodes, weights = pin_nodes(surface, tip - 0.1)
    gaps = delta + surface.node_profile[nodes] - held.w[nodes]
    assert weights @ gaps == pytest.approx(TIP_GAP, abs=1e-9)
    energy, rng = surface.energy(held.w, delta), np.random.default_rng(0)
    for _ in range(20):
        v = rng.standard_normal(w.size)
        v[nodes] -= weights * (weights @ v[nodes]) / (weights @ weights)
        for t in (1e-3, -1e-3):
            assert surface.energy(held.w + t * v / np.max(np.abs(v)), delta) > energy
    for shift in (0.25, -0.25):  # from off the minimum, towards it: E rises past it
        peeled = peel(surface, surface.translated(w, delta, shift), delta, -np.sign(shift),
                      h=np.min(np.diff(surface.r_nodes)), max_step=0.1, tips=(0.0, np.inf),
                      fits=lambda state: True)
        assert abs(surface.crack_tip(peeled.w, delta) - tip) <= 0.1


def test_a_refined_curve_gets_its_estimate_from_its_own_finer_solve():
    """At μ = 0.7 the BEM `default` misses the jump and is refined once; its error estimate
    then comes from a solve twice as fine as the refined one, and has the jump-in."""
    result = solve_curve(0.7, method="bem")
    assert result.accuracy == "default/2" and result.status == "ok"
    assert result.error_estimate["delta_jump_in"] is not None
    assert result.error_estimate["p_off"] < 1e-5


def test_a_curve_above_the_onset_that_misses_its_jump_is_refined_until_it_jumps():
    """At mu = 0.7 (onset 0.697) the BEM `default` grid misses the shallow fold; the solve
    notices (mu above the onset, no jump-in) and refines once."""
    from fem_asperity.solver.presets import discretisation

    missed = solve_discretised(0.7, discretisation(0.7, method="bem"))
    assert missed.events.jump_in is None  # the grid alone misses it
    result = solve_curve(0.7, method="bem", error_estimate=False)
    assert result.events.jump_in is not None and result.status == "ok"
    assert result.accuracy == "default/2" and "refined 1 time" in result.message
    below = solve_curve(0.69, method="bem", error_estimate=False)  # no jump to miss below
    assert below.events.jump_in is None and below.accuracy == "default"


def test_a_failing_error_estimate_never_costs_the_result(monkeypatch):
    """Whatever stops the estimate's solve (here an input error from inside it, as the grid of a
    diverged state raised at mu = 9, BEM draft), the curve is kept without an estimate: with
    the estimate traced near the events and with a whole finer solve (the whole curve)."""
    import fem_asperity.solver.discretised as discretised
    import fem_asperity.solver.estimate as estimate

    real = discretised.solve_traced

    def failing(*args, **kwargs):
        raise InputError("need 0 < h <= band (from inside the estimate's solve)")

    def failing_whole(mu, disc, **kwargs):
        if disc.name.endswith("/estimate"):
            failing()
        return real(mu, disc, **kwargs)

    monkeypatch.setattr(estimate, "events_near", failing)
    monkeypatch.setattr(discretised, "solve_traced", failing_whole)
    for whole in (False, True):
        result = solve_curve(1.0, method="bem", accuracy="draft", unstable_branch=whole)
        assert result.error_estimate is None and result.status == "no_estimate"
        assert "InputError" in result.message and result.events.jump_in is not None


@pytest.mark.parametrize("mu, method", [
    (2.5, "bem"), (3.0, "bem"), pytest.param(5.0, "bem", marks=pytest.mark.slow),
    pytest.param(10.0, "bem", marks=pytest.mark.slow),
    pytest.param(5.0, "fem", marks=pytest.mark.slow)])
def test_presets_do_not_ripple(mu, method):
    """`draft`, the coarsest preset, stays below the ripple-free element size RIPPLE_FREE μ⁻²:
    before its elements were capped there it rippled at these μ (BEM: 3, 6, 22 folds; the
    edge-following BEM at μ = 10: 5; the FE at μ = 5: 6, on its whole surface; it now follows
    the edge there)."""
    result = solve_curve(mu, method=method, accuracy="draft", error_estimate=False)
    assert result.folds == 2 and result.status == "ok" and result.accuracy == "draft"


def test_a_rippling_curve_is_refined_and_reports_the_physical_jumps():
    """Elements as long as the old `draft`'s at μ = 3 ripple (6 folds); the jump-out read off
    that curve is still the last fold, the separation (within 1e-3 of the refined curve's; the
    first fold was a ripple), and the solve refines once to a curve without ripple."""
    from fem_asperity.solver.discretised import solve_refining

    mu = 3.0
    disc = replace(discretisation(mu, "draft", method="bem"), h_surface=0.25 * mu**-1.5)
    rippled = solve_discretised(mu, disc)
    assert rippled.ripples and rippled.status == "ripples"
    result, solved_on, _ = solve_refining(mu, disc, solid=Solid(), radius_ratio=None,
                                           unstable_branch=False, spring_constant=None)
    assert result.folds == 2 and result.status == "ok" and "refined 1 time" in result.message
    assert solved_on.h_surface == disc.h_surface / 2
    assert rippled.events.jump_out.delta == pytest.approx(result.events.jump_out.delta, rel=1e-3)
    assert rippled.events.jump_in.delta == pytest.approx(result.events.jump_in.delta, rel=1e-6)


def test_error_estimate_bounds_the_error_without_overstating_it():
    """BEM `default` at μ = 3 against a BEM twice as fine as `fine`: each estimated event's
    error is at most its estimate and at least a tenth of it (where the error is above the
    continuation's tolerance, 1e-8); relative_error_estimate is the same relative to the event."""
    result = solve_curve(3.0, method="bem", accuracy="default")
    reference = solve_discretised(3.0, discretisation(3.0, "fine", method="bem").refined())
    a, b = result.events.records(), reference.events.records()
    for key, estimate in result.error_estimate.items():
        error = abs(a[key] - b[key])
        if error > 1e-8:
            assert error <= estimate <= 10 * error, key
        assert result.relative_error_estimate[key] == pytest.approx(estimate / abs(a[key]))


@pytest.mark.parametrize("mu, estimate", [(3.0, False), (7.0, False), (3.0, True)])
def test_progress_rises_to_one_at_the_end_only(mu, estimate):
    """The progress never falls and reaches 1 only with the last report: on a uniform grid
    (μ = 3), on grids that follow the edge (μ = 7, where it fell with each regrid of the
    retraction and stayed near 0.85 while the peel traced most of its points), and with the
    error estimate's longer solve alongside (the bar showed 1 when the shorter one ended)."""
    seen = []
    solve_curve(mu, method="bem", accuracy="draft", error_estimate=estimate,
                progress=seen.append)
    assert all(b >= a for a, b in zip(seen, seen[1:]))
    assert seen[-1] == 1.0 and max(seen[:-1]) < 1.0
    assert max(seen[:-1]) > 0.9  # the retraction moves the bar on before the end
    if estimate:  # traced after the curve, near each event: the bar moves on meanwhile
        from fem_asperity.solver.estimate import ALMOST_DONE, CURVE_SHARE

        curve_done = len(seen) - seen[::-1].index(CURVE_SHARE)  # the curve's last report
        assert any(CURVE_SHARE < f < ALMOST_DONE for f in seen[curve_done:])


@pytest.mark.parametrize("options, is_estimates", [
    (dict(method="bem", unstable_branch=True), lambda disc: disc.name.endswith("/estimate")),
    (dict(method="fem"), lambda disc: disc.method == "bem"),  # the FE's BEM curve
])
def test_an_interrupted_curve_stops_its_estimate_solve_too(monkeypatch, options, is_estimates):
    """Ctrl-C (or an error) in a curve ends the estimate's longer solve alongside at its next
    point instead of waiting for it: a whole curve's (`unstable_branch`) whole finer solve, an
    FE curve's boundary-integral curve. The estimate's solve ends with `_Stopped`."""
    import fem_asperity.solver.discretised as discretised

    real, ended = discretised.solve_traced, {}

    def interrupted(mu, disc, **kwargs):
        if not is_estimates(disc):
            raise KeyboardInterrupt
        try:
            return real(mu, disc, **kwargs)
        except BaseException as exc:
            ended["estimate"] = type(exc).__name__
            raise

    monkeypatch.setattr(discretised, "solve_traced", interrupted)
    with pytest.raises(KeyboardInterrupt):
        solve_curve(3.0, accuracy="fine", **options)
    assert ended == {"estimate": "_Stopped"}


def test_the_solved_range_includes_both_ends_and_says_why_above():
    from fem_asperity.solver.solve import MU_RANGE, solvable_mu

    assert [solvable_mu(mu) for mu in MU_RANGE] == list(MU_RANGE)
    with pytest.raises(InputError, match="at most 50 for a solved curve; got 50.01: .*JKR"):
        solvable_mu([1.0, 50.01])


def test_the_estimate_of_a_force_sees_the_traction_beyond_the_grid():
    """The BEM's traction grid ends at r = 100 √(Rε); the LJ traction beyond it pulls with
    Bradley's force at the gap there, (4/3)(r²/2 + δ̄o)⁻² ≈ 5.3e-8, which a finer grid of the
    same reach cannot see. Against the same BEM reaching 800 (its P̄off moved by 1.5e-10 from
    400 to 800) the error of P̄off at μ = 1e-3 is that tail, and the estimate covers it."""
    from fem_asperity.solver.discretised import solve_discretised

    result = solve_curve(1e-3, method="bem", accuracy="default")
    far = solve_discretised(1e-3, replace(discretisation(1e-3, "default", method="bem"),
                                          r_max=800.0))
    error = abs(result.events.p_off - far.events.p_off)
    floor = result.estimate_floor["p_off"]
    assert floor == pytest.approx(4.0 / 3.0 * (5000.0 + result.events.delta_off) ** -2, rel=1e-6)
    assert error > result.error_estimate["p_off"] - floor  # what refinement alone would say
    assert error <= result.error_estimate["p_off"]
    assert result.records()["estimate_floor"]["p_off"] == floor


def test_the_exact_sphere_is_followed_at_large_mu_and_tends_to_derjaguin():
    """At μ = 5.15 the path follows the crack tip, moving the gaps outward; beyond an exact
    sphere's equator (r² > R/ε, inside the traction grid up to R/ε = 1e4) the gap is infinite
    and the move made NaNs: Newton failed at the first step for R/ε = 167 and 1000. Now both
    solve, and P̄off tends to Derjaguin's as ε/R (its difference 5.8x smaller at 6x the
    radius)."""
    mu = 5.153785501199396
    p_off = {rr: solve_curve(mu, method="bem", accuracy="draft", error_estimate=False,
                             radius_ratio=rr).events.p_off for rr in (1000.0 / 6.0, 1000.0, None)}
    near, far = (abs(p_off[rr] - p_off[None]) for rr in (1000.0 / 6.0, 1000.0))
    assert near > far > 0.0
    assert near / far == pytest.approx(6.0, rel=0.2)
