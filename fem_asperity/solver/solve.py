"""The single-asperity curve: `solve_curve(mu, ...)` → `CurveResult` (curve, events, provenance).

Two methods for the elastic solid behind the same surface problem and path. 'fem': axisymmetric
P2 finite elements of the (layered) half-space (scikit-fem), condensed onto the surface. 'bem':
the Boussinesq integral of the homogeneous half-space on a radial grid (`solids.bem`), no mesh and
no truncation of the solid. Then, for both: LJ 9-3 traction on the surface as a nonlinear boundary
form with its consistent tangent; pseudo-arc-length continuation of the whole equilibrium curve;
exact extrema of P̄; approach and retraction under δ̄o control read off it, jumps included (see
`path.branches`, `path.whole_curve`). The error estimate is twice the change of each event on
a finer discretisation (`for_estimate()` of the `solver.presets` discretisation, `_estimate`);
the FE of a homogeneous half-space is instead checked against the boundary integral
(`_estimate_against_bem`)."""

import threading
import time
from concurrent.futures import ThreadPoolExecutor
from contextlib import contextmanager
from dataclasses import dataclass, replace

import numpy as np
from threadpoolctl import threadpool_limits

from ..closed_forms.lj import bradley_force
from ..curves.events import ESTIMATED, read_events
from ..path.branches import stable_paths
from ..path.load_line import load_line_paths
from ..path.near_events import events_near
from ..path.whole_curve import whole_curve_paths
from ..plumbing.checks import in_range, positive
from ..plumbing.errors import ContinuationError, InputError
from ..solids.fe import Solid
from .presets import ESTIMATE_BY, MU_TRACKING, discretisation, sizing_mu
from .result import PHYSICAL_FOLDS, CurveResult, Model, worst_status

#: BLAS threads while a curve is traced: its dense factorisations ran slower with two on two
#: cores, and the second core serves the error estimate. Not pinned by a test.
PATH_BLAS_THREADS = 1

#: Above the measured jump-in onset's upper end a Derjaguin curve must jump in; one that misses
#: it (or ripples) is refined up to REFINEMENTS times. test_bem_curve.py (fold margin, 0.7).
MU_ONSET_HI, REFINEMENTS = 0.6982, 2

#: Tabor parameters solved for: the rigid limit to the largest μ that finishes at `draft` in
#: minutes (benchmarks/results/extremes.md). test_cli's bad-input test and test_bem_curve.
MU_RANGE = (1e-3, 50.0)
#: Why a μ above MU_RANGE is refused, and what answers there.
TOO_STIFF = ("above it the cohesive zone is too narrow for a solve to finish within minutes; "
             "JKR's closed forms answer there (its pull-off -0.75 is within 0.1 % of the "
             "solved one at mu = 50): python -m fem_asperity laws, "
             "fem_asperity.closed_forms.reference")

#: Springs taken (2πRΔγ/ε): stiffer is displacement control to round-off; softer than any
#: cantilever costs more than a curve (benchmarks/extremes.py). test_cli pins the ends.
SPRING_RANGE = (1e-9, 1e12)
#: Why a softer spring is refused.
SOFT_SPRING = ("the approach starts outside the spring's jump-in, twice (8/(3k))^(1/3) eps "
               "out, and a spring softer than any cantilever would cost more points than a "
               "curve takes")
#: The approach under a spring starts this many times beyond the rigid sphere's jump-in under
#: it. test_load_line.py::test_a_soft_spring_lands_beyond_the_start.
SPRING_FOLD_MARGIN = 2.0
#: Largest μ whose whole curve (unstable branches, or a spring) is traced on one uniform grid
#: (benchmarks/results/extremes.md). test_cli's bad-input test pins it.
WHOLE_CURVE_MU_MAX = 6.0
#: Progress shown until a solve and its error estimate have both ended.
ALMOST_DONE = 0.99
#: The progress bar's share for the curve where its estimate is traced after it (it costs up to
#: as much). test_bem_curve.py::test_progress_rises_to_one_at_the_end_only.
CURVE_SHARE = 0.6
#: The estimated forces: on moving grids their estimate adds `regrid_change` (docs/methods.md
#: §12). test_tracking.py::test_grids_ahead_of_the_edges_build_fewer_grids_for_the_same_curve.
FORCES = ("p_max", "p_jump_after", "p_off")
#: The estimated contact radius adds `regrid_radius_change` likewise (§12).
#: test_tracking.py::test_grids_ahead_of_the_edges_build_fewer_grids_for_the_same_curve.
RADII = ("a_c",)
#: The estimated jump-out adds `regrid_fold_change` likewise (§12).
#: test_tip.py::test_the_jump_outs_fold_found_elsewhere_widens_its_estimate.
FOLDS = ("delta_jump_out",)
#: Each estimated force and its δ̄o: the LJ traction beyond the traction grid is a floor under
#: its estimate (`traction_tail`, §12). test_bem_curve.py::test_the_estimate_of_a_force_sees_*.
FORCE_AT = {"p_max": "delta_oc", "p_jump_after": "delta_jump_in", "p_off": "delta_off"}
#: The FE's estimate against the BEM: DIFFERENCE_FACTOR |FE − BEM| + the BEM's own estimate (§12).
#: test_bem_curve.py::test_the_fes_estimate_against_the_bem_bounds_its_error.
DIFFERENCE_FACTOR = 2.0


def solve_discretised(mu, disc, *, solid=Solid(), radius_ratio=None, unstable_branch=False,
                      spring_constant=None, progress=None):
    """One curve on the given discretisation (`presets.discretisation`; no error estimate, inputs
    unchecked beyond the discretisation's own): for studies that set the resolution themselves.
    spring_constant: load-line control through a spring of that stiffness (2πRΔγ/ε), read off
    the whole curve (`path.load_line`); None: displacement control."""
    return _solve_traced(mu, disc, solid=solid, radius_ratio=radius_ratio,
                         unstable_branch=unstable_branch, spring_constant=spring_constant,
                         progress=progress)[0]


def _solve_traced(mu, disc, *, solid, radius_ratio, unstable_branch, spring_constant, progress):
    """(`solve_discretised`'s result, its trace: the states behind the curve's points)."""
    start = time.perf_counter()
    whole = unstable_branch or spring_constant is not None
    z_jumps = None
    if whole and disc.follows_edge:  # refused before any grid or mesh is built
        raise InputError(f"grids that follow the contact edge (method {disc.method!r}: by "
                         f"default from mu = {MU_TRACKING[disc.method]:g}) trace stable "
                         "branches only: no unstable_branch or spring_constant there")
    with threadpool_limits(PATH_BLAS_THREADS, user_api="blas"):
        grids = disc.grids(mu, solid=solid, radius_ratio=radius_ratio)
        if whole:
            paths = whole_curve_paths(grids.start, disc.trace, progress)
        else:
            paths = stable_paths(grids, disc.trace, progress)
        approach, retraction, jumps_in, jumps_out = (paths.approach, paths.retraction,
                                                     paths.jumps_in, paths.jumps_out)
        curve, traced = paths.equilibrium, paths.traced
        if spring_constant is not None:
            (approach, retraction, jumps_in, jumps_out, *_, z_in, z_out) = load_line_paths(
                grids.start, traced, curve, spring_constant)
            z_jumps = {"z_jump_in": z_in[0] if z_in else None,
                       "z_jump_out": z_out[-1] if z_out else None}
    if unstable_branch and spring_constant is None:  # stability changes along the whole curve
        folds = int(curve.branch.max())
    else:
        folds = len(jumps_in) + len(jumps_out)
    moves = paths.moves if grids.follows_edge else None  # none on one grid or mesh
    message = f"{folds} folds of the equilibrium curve" + grids.summary(moves)
    sized_for = sizing_mu(mu, solid)
    if sized_for != mu:
        message += (f"; elements sized for the layer's Tabor parameter {sized_for:.4g}, the more "
                    f"compliant material")
    status = "ok"
    if folds > PHYSICAL_FOLDS:
        status = "ripples"
        message += (" (more than one jump-in and one jump-out: probably ripple from a surface "
                    "mesh too coarse for this mu; try a finer accuracy)")
    return CurveResult(
        mu=mu,
        accuracy=disc.name,
        solid=solid,
        equilibrium=curve,
        approach=approach,
        retraction=retraction,
        events=read_events(approach, retraction, jumps_in, jumps_out),
        error_estimate=None,
        dofs=grids.dofs,
        surface_nodes=grids.largest_nodes,
        points=len(curve),
        newton_iterations=traced.newton_iterations,
        wall_s=time.perf_counter() - start,
        folds=folds,
        method=disc.method,
        status=status,
        message=message,
        radius_ratio=radius_ratio,
        p_end=disc.trace.p_end,
        unstable_branch=unstable_branch,
        spring_constant=spring_constant,
        z_jumps=z_jumps,
        regrid_change=None if moves is None else moves.force,
        regrid_radius_change=None if moves is None else moves.radius,
        regrid_fold_change=None if moves is None else moves.fold,
        model=None if grids.elastic is None else Model(grids.elastic, grids.start, traced),
    ), traced


def _solve_refining(mu, disc, *, progress=None, **options):
    """`solve_discretised`, then again on discretisations refined (`refined()`) up to
    REFINEMENTS times while the curve ripples, or, for a homogeneous Derjaguin curve above
    MU_ONSET_HI, shows no jump-in; its status is 'ripples' or 'missed_jump' if the last one
    still does. Returns (result, the discretisation it was solved on, its trace)."""
    must_jump = (mu > MU_ONSET_HI and options["solid"].layer_thickness is None
                 and options["radius_ratio"] is None)

    def flaw(result):
        if result.ripples:
            return "ripples"
        return "missed_jump" if must_jump and result.events.jump_in is None else None

    result, traced = _solve_traced(mu, disc, progress=progress, **options)
    first, wall, solved_on = flaw(result), result.wall_s, disc
    if first is None:
        return result, disc, traced
    for level in range(1, REFINEMENTS + 1):
        solved_on = solved_on.refined()
        result, traced = _solve_traced(mu, solved_on, progress=None, **options)
        wall += result.wall_s
        if flaw(result) is None:
            why = ("more folds than a jump-in and a jump-out (ripple)" if first == "ripples"
                   else "no jump-in although mu is above the onset")
            note = (f"; at '{disc.name}' {why}: solved again on a discretisation refined "
                    f"{level} time(s)")
            return replace(result, message=result.message + note, wall_s=wall), solved_on, traced
    if flaw(result) == "ripples":
        note = (f"; still ripples after {REFINEMENTS} refinements: the jump-in is the first fold "
                f"of the approach and the jump-out the last of the retraction; try --tolerance")
    else:
        note = (f"; no jump-in although mu is above the onset, also refined {REFINEMENTS} "
                f"times: try --tolerance or a finer accuracy")
    return replace(result, status=worst_status(result.status, flaw(result)),
                   message=result.message + note, wall_s=wall), solved_on, traced


def _estimate(a, disc, b, partner_disc):
    """Error estimate of the events `a` (records, solved on `disc`) from the partner's `b` (on
    `partner_disc`, surface elements r times as long): |difference| / |r − 1| per ESTIMATED
    key, None where the event is missing in either (`_one_sided` and `_missed` name those
    found by one of the two only).

    Against a finer partner (r = 1/2) that is twice the difference: the error of first-order
    convergence, which bounds faster convergence too (at order p the difference is the
    fraction 1 − 2^(−p) of the error), overstating it by at most 2 in the asymptotic range.
    Against a coarser one (r = 2, `solve_to_tolerance`) it is the difference itself."""
    scale = 1.0 / abs(partner_disc.h_surface / disc.h_surface - 1.0)
    return {k: (scale * abs(a[k] - b[k]) if a[k] is not None and b[k] is not None else None)
            for k in ESTIMATED}


def _one_sided(a, b, other_named="its finer estimate discretisation"):
    """A message naming the estimated events (records `a` of the solve, `b` of the other solve,
    `other_named`) that one of the two has and the other not (a jump one discretisation finds
    and the other misses): their estimate is None."""
    keys = [k for k in ESTIMATED if (a[k] is None) != (b[k] is None)]
    if not keys:
        return ""
    return (f"; {', '.join(keys)} found by only one of the solve and {other_named} (no "
            f"estimate for them): try a finer accuracy")


def solve_curve(mu, *, method="fem", accuracy="default", solid=Solid(), radius_ratio=None,
                p_end=1.0, error_estimate=True, estimate_by="auto", unstable_branch=False,
                spring_constant=None, progress=None):
    """Approach and retraction of a rigid sphere on the half-space at Tabor parameter `mu`.

    method: 'fem' (finite elements) or 'bem' (boundary integral; a layer by `solids.layered`).
    accuracy: 'draft', 'default' or 'fine' (see `presets.PRESETS`).
    solid: `Solid` (homogeneous by default; a layer with thickness in √(Rε)).
    radius_ratio: R/ε for the exact sphere profile instead of Derjaguin's parabola (None).
    p_end: the approach goes on until P̄ reaches this compressive force (2πRΔγ units).
    unstable_branch: also trace the unstable branches between the folds, so that `equilibrium`
        is the whole S-shaped curve (more work: LU factorisations and short steps); by default
        only the stable branches are traced and each jump lands by energy descent
        (`path.branches`).
    error_estimate: also estimate each event's error, as `estimate_by` says. If that fails
        (or a whole second curve ripples) the estimate is None and `status` and `message` say
        why; an event the second solve has none of near the curve's has no estimate and the
        `message` names it. The result is kept.
    estimate_by: one of ESTIMATE_BY.
        'finer': each event solved again on the discretisation of the estimate
        (`for_estimate()`: surface elements and turn limit halved, the bulk graded more gently),
        and per event twice the difference (`_estimate`). The finer discretisation traces the
        curve near each event only (`path.near_events`, after the curve; its surfaces are built
        alongside on the second core); with `unstable_branch` or a `spring_constant` it solves
        the whole curve again alongside.
        'bem' (the FE of a homogeneous half-space only): the boundary integral's curve at the
        same preset, with its own 'finer' estimate, solved alongside on the second core; per
        event DIFFERENCE_FACTOR |FE − BEM| plus the BEM's estimate (`_estimate_against_bem`). It
        costs about as much as the FE's curve instead of 2.5-5.3 times, and estimates the FE's
        whole error (its bulk mesh and truncation included) with an independent method.
        'auto' (default): 'bem' for the FE of a homogeneous half-space, else 'finer'.
    spring_constant: load-line control, as through an AFM cantilever, with a spring of this
        stiffness k̄ = Kε/(2πRΔγ) (> 0): the jumps come where dP̄/dδ̄o reaches k̄, and the
        result's z_jumps hold the spring end's z̄ at them (`path.load_line`); the whole curve is
        traced (on one uniform grid). None (default): displacement control.
    A curve that ripples, or misses a jump it must have, is solved again on refined
    discretisations (up to REFINEMENTS times); one that still does carries that `status`.
    progress: callable(fraction in [0, 1]) for a progress bar.
    Returns a `CurveResult`; raises `ContinuationError` if the path cannot be followed.
    """
    mu = _mu(mu)
    positive("p_end", p_end)
    if radius_ratio is not None:
        in_range("radius_ratio", radius_ratio, 10.0, np.inf, closed_lo=True)
    if spring_constant is not None:
        in_range("spring_constant", spring_constant, *SPRING_RANGE, closed_lo=True,
                 why=SOFT_SPRING)
    _whole_curve_served(mu, unstable_branch or spring_constant is not None)
    by = estimate_kind(estimate_by, method, solid)
    options = dict(solid=solid, radius_ratio=radius_ratio, unstable_branch=unstable_branch,
                   spring_constant=spring_constant)
    disc = _discretisation(mu, accuracy, method=method, p_end=p_end, options=options)
    if not error_estimate:
        return _solve_refining(mu, disc, progress=progress, **options)[0]
    return _with_estimate(mu, disc, options, progress, by)


def estimate_kind(estimate_by, method, solid):
    """The kind of error estimate ('finer' or 'bem') that `estimate_by` (`ESTIMATE_BY`) asks
    for on a curve of `method` and `solid`; `InputError` for 'bem' where there is no FE of a
    homogeneous half-space to check."""
    if estimate_by not in ESTIMATE_BY:
        raise InputError(f"estimate_by must be one of {', '.join(ESTIMATE_BY)}; got "
                         f"{estimate_by!r}")
    checkable = method == "fem" and solid.layer_thickness is None
    if estimate_by == "bem" and not checkable:
        raise InputError("estimate_by='bem' checks the FE of a homogeneous half-space against "
                         "the boundary integral; a BEM curve or a layer's takes 'finer' (or "
                         "'auto')")
    if estimate_by == "auto":
        return "bem" if checkable else "finer"
    return estimate_by


@dataclass(frozen=True)
class _Estimated:
    """A curve (`result`) and its error estimate as one strategy made it: the `estimate` (None
    where it failed), the clause the curve's message gains (`note`) and its `status` with it."""

    result: CurveResult
    estimate: dict | None
    note: str
    status: str

    @classmethod
    def failed(cls, result, exc, what="its finer solve", hint=""):
        """The curve whose estimate's solve (`what`) failed with `exc`; the note ends with
        `hint` (what to try instead)."""
        note = f"; no error estimate: {what} failed ({type(exc).__name__}: {exc}){hint}"
        return cls(result, None, note, worst_status(result.status, "no_estimate"))


def _with_estimate(mu, disc, options, progress, by):
    """The curve on `disc` and its error estimate made as `by` says ('finer' or 'bem', see
    `solve_curve`), in a second thread."""
    start = time.perf_counter()
    if by == "bem":
        estimated = _estimated_by_bem
    elif options["unstable_branch"] or options["spring_constant"] is not None:
        estimated = _estimated_by_whole_solve
    else:
        estimated = _estimated_near_events
    with threadpool_limits(PATH_BLAS_THREADS, user_api="blas"), ThreadPoolExecutor(1) as pool:
        made = estimated(mu, disc, options, progress, pool)
    result, estimate = made.result, made.estimate
    if by == "finer" and estimate is not None and result.regrid_change is not None:
        moved = {**dict.fromkeys(FORCES, result.regrid_change),
                 **dict.fromkeys(RADII, result.regrid_radius_change),
                 **dict.fromkeys(FOLDS, result.regrid_fold_change)}
        estimate = _added(estimate, moved)
    floor = traction_tail(result.events, disc.traction_radius) if estimate is not None else None
    if progress:
        progress(1.0)
    return replace(result, error_estimate=_added(estimate, floor), estimated_by=by,
                   estimate_floor=floor, status=made.status, message=result.message + made.note,
                   wall_s=time.perf_counter() - start)


def traction_tail(events, radius):
    """{force key: the LJ traction's force beyond `radius` (√(Rε)) at the event's δ̄o}, in
    2πRΔγ: Bradley's force at the gap there, δ̄o + radius²/2 (the solid's deflection that far
    out is negligible; the exact sphere's gap grows faster still). The floor of `FORCE_AT`."""
    records = events.records()
    return {key: abs(bradley_force(records[at] + 0.5 * radius**2))
            for key, at in FORCE_AT.items() if records[key] is not None}


def _added(estimate, extra):
    """`estimate` with `extra` added to its entries (None stays None, as does a None entry)."""
    if estimate is None or not extra:
        return estimate
    return {k: (v + extra[k] if k in extra and v is not None else v) for k, v in estimate.items()}


def _estimated_near_events(mu, disc, options, progress, pool):
    """`_Estimated`: the curve, then its events solved again on the
    estimate's discretisation near where the curve has them (`path.near_events`: a fraction of
    a whole finer solve). The finer surfaces are built on the second core meanwhile (the FE's
    condensation)."""
    geometry = dict(solid=options["solid"], radius_ratio=options["radius_ratio"])
    finer_grids = pool.submit(disc.for_estimate().grids, mu, **geometry)
    curve_shown = (lambda f: progress(CURVE_SHARE * f)) if progress else None
    estimate_shown = ((lambda f: progress(CURVE_SHARE + (ALMOST_DONE - CURVE_SHARE) * f))
                      if progress else None)
    result, solved_on, traced = _solve_refining(mu, disc, progress=curve_shown, **options)
    try:
        partner_on = solved_on.for_estimate()
        grids = (finer_grids.result() if solved_on is disc
                 else partner_on.grids(mu, **geometry))
        near = events_near(grids, partner_on.trace, traced, result.equilibrium.branch,
                           result.approach, result.retraction, result.events.jump_in,
                           result.events.jump_out, progress=estimate_shown)
        a = result.events.records()
        note = _missed(near["missed"]) + (
            f"; error estimate from the finer discretisation traced near each event "
            f"({near['windows']} windows, {near['newton_iterations']} Newton iterations)")
        return _Estimated(result, _estimate(a, solved_on, near, partner_on), note,
                          result.status)
    except Exception as exc:  # the estimate never costs the result: whatever stopped it
        return _Estimated.failed(result, exc)


def _missed(missed):
    """A message naming the events (no estimate for them) the finer discretisation has none of
    near the curve's, with why (`path.near_events`: a jump it does not make, a branch it folds
    on, a window it could not follow)."""
    reasons = {}
    for key, reason in missed.items():
        reasons.setdefault(reason, []).append(key)
    return "".join(f"; no error estimate for {', '.join(keys)}: near the curve's, the finer "
                   f"discretisation has none ({reason}); try a finer accuracy"
                   for reason, keys in reasons.items())


@contextmanager
def _alongside(pool, progress, job, *args, **kwargs):
    """`job(*args, progress=..., **kwargs)` run on `pool` while the block traces the curve,
    the bar showing the slower of the two (`_both`). Yields (the curve's progress callback,
    the job's future, the event that stops it); whatever ends the block (its result, an error,
    Ctrl-C), the job ends at its next point (`_stoppable`) instead of being waited for."""
    report_main, report_job = _both(progress)
    stop = threading.Event()
    future = pool.submit(job, *args, progress=_stoppable(report_job, stop), **kwargs)
    try:
        yield report_main, future, stop
    finally:
        stop.set()


def _estimated_by_whole_solve(mu, disc, options, progress, pool):
    """`_Estimated`: the curve and, on the second core alongside, the whole
    curve again on the estimate's discretisation (the whole curve, unstable branches included,
    holds the load-line events, which `path.near_events` does not follow)."""
    # The dense factorisations release the GIL, so the two curves share the two cores (one BLAS
    # thread each).
    with _alongside(pool, progress, solve_discretised, mu, disc.for_estimate(),
                    **options) as (report, finer_job, stop):
        result, solved_on, _ = _solve_refining(mu, disc, progress=report, **options)
        try:
            partner_on = solved_on.for_estimate()
            if solved_on is disc:
                partner = finer_job.result()
            else:  # refined for ripple or a missed jump: its own partner
                stop.set()
                partner = solve_discretised(mu, partner_on, **options)
            if partner.ripples:
                raise ContinuationError(f"it rippled ({partner.folds} folds)")
            a, b = result.events.records(), partner.events.records()
            return _Estimated(result, _estimate(a, solved_on, b, partner_on), _one_sided(a, b),
                              result.status)
        except Exception as exc:  # the estimate never costs the result: whatever stopped it
            return _Estimated.failed(result, exc)


def _estimated_by_bem(mu, disc, options, progress, pool):
    """`_Estimated`: the FE curve and, on the second core alongside, the
    boundary integral's curve at the FE's preset (`disc.name`) with its own 'finer' estimate,
    on grids that follow the edge wherever the FE's do (`_estimate_against_bem`)."""
    bem_disc = _discretisation(mu, disc.name, method="bem", p_end=disc.trace.p_end,
                               options=options, track_edge=disc.follows_edge or None)
    with _alongside(pool, progress, _with_estimate, mu, bem_disc, options,
                    by="finer") as (report, bem_job, _):
        result, _, _ = _solve_refining(mu, disc, progress=report, **options)
        try:
            return _Estimated(result, *_estimate_against_bem(result, bem_job.result()),
                              result.status)
        except Exception as exc:  # the estimate never costs the result: whatever stopped it
            return _Estimated.failed(result, exc, "the boundary integral's curve",
                                     hint="; estimate_by='finer' estimates the FE from its own "
                                          "finer mesh instead")


def _estimate_against_bem(result, partner):
    """(estimate, note) of the events of the FE `result` from the boundary integral's `partner`
    curve: per event DIFFERENCE_FACTOR |FE − BEM| plus the BEM's estimate; None where either
    lacks the event or the BEM's estimate does. A partner that ripples, misses its jump or has
    no estimate gives none (`ContinuationError`)."""
    if partner.status != "ok" or partner.error_estimate is None:
        raise ContinuationError(f"the boundary integral's curve has status {partner.status!r} "
                                f"({partner.message})")
    a, b = result.events.records(), partner.events.records()
    estimate = {k: (DIFFERENCE_FACTOR * abs(a[k] - b[k]) + partner.error_estimate[k]
                    if None not in (a[k], b[k], partner.error_estimate[k]) else None)
                for k in ESTIMATED}
    unestimated = [k for k in ESTIMATED
                   if None not in (a[k], b[k]) and partner.error_estimate[k] is None]
    note = _one_sided(a, b, other_named="the boundary integral's curve")
    if unestimated:
        note += (f"; no error estimate for {', '.join(unestimated)}: the boundary integral's "
                 f"own estimate has none")
    note += (f"; error estimate against the boundary integral (BEM '{partner.accuracy}', "
             f"{partner.points} points, {partner.wall_s:.1f} s alongside): "
             f"{DIFFERENCE_FACTOR:g} |FE - BEM| plus the BEM's own estimate per event")
    return estimate, note


class _Stopped(Exception):
    """Raised inside the estimate's solve once it is no longer wanted."""


def _stoppable(report, stop):
    """A progress callback that passes the fraction to `report` (if any) and ends the solve
    calling it (`_Stopped`) once `stop` is set: a solve reports after every point."""
    def progress(fraction):
        if stop.is_set():
            raise _Stopped("the curve it estimates ended first")
        if report is not None:
            report(fraction)
    return progress


def _both(progress):
    """Two progress callbacks, for the solve and its estimate's solve running alongside, that
    show the lesser of their fractions, below 1 (`solve_curve` shows 1 when both have ended)."""
    if progress is None:
        return None, None
    fractions, lock = [0.0, 0.0], threading.Lock()

    def reporter(i):
        def report(fraction):
            with lock:
                fractions[i] = fraction
                progress(min(min(fractions), ALMOST_DONE))
        return report

    return reporter(0), reporter(1)


def _discretisation(mu, accuracy, *, method, p_end, options, track_edge=None):
    """The preset's discretisation for a curve with `options` (`solve_curve`'s solid,
    radius_ratio, unstable_branch and spring_constant), sized for the most compliant material
    (`sizing_mu`), on one uniform grid where the whole curve is traced (the edge-following
    grids trace stable branches) or a layer's correction would be rebuilt on every
    edge-following grid; else grids that follow the edge as `track_edge` says
    (`presets.discretisation`)."""
    solid, spring_constant = options["solid"], options["spring_constant"]
    uniform = (options["unstable_branch"] or spring_constant is not None
               or solid.layer_thickness is not None)
    disc = discretisation(sizing_mu(mu, solid), accuracy, p_end=p_end, method=method,
                          track_edge=False if uniform else track_edge)
    if spring_constant is None:
        return disc
    # The approach must start outside the spring's jump-in, where the far-field force's slope
    # (8/3)δ̄o⁻³ reaches k̄: SPRING_FOLD_MARGIN times that δ̄o. The jump-out may land far beyond
    # the start (up to 1/k̄ out), on the far-field force (`load_line._far_landing`):
    # test_load_line.py::test_a_soft_spring_lands_beyond_the_start.
    fold = (8.0 / (3.0 * spring_constant)) ** (1.0 / 3.0)
    x_start = max(disc.trace.x_start, SPRING_FOLD_MARGIN * fold)
    return replace(disc, trace=replace(disc.trace, x_start=x_start))


def _mu(mu):
    """μ of a solved curve: one finite number in MU_RANGE."""
    if np.ndim(mu) != 0:
        raise InputError(f"mu must be one number (a curve per call; `studies.sweep` solves "
                         f"many); got an array of shape {np.shape(mu)}")
    return solvable_mu(mu)


def _whole_curve_served(mu, whole):
    """Refuse a `whole` curve (unstable_branch or spring_constant) above WHOLE_CURVE_MU_MAX."""
    if whole and mu > WHOLE_CURVE_MU_MAX:
        raise InputError(f"the unstable branch (--unstable-branch) and a spring "
                         f"(--spring-constant) need mu <= {WHOLE_CURVE_MU_MAX:g}; got mu = "
                         f"{mu:g}: the whole curve is traced on one uniform grid, which "
                         "must resolve the cohesive zone everywhere, and above that it takes "
                         "more than minutes")


def solvable_mu(mu, name="mu"):
    """`mu` (a number or an array) if every entry lies in MU_RANGE, ends included, else an
    `InputError` naming `name` and, above the range, why."""
    mu = in_range(name, mu, MU_RANGE[0], np.inf, closed_lo=True)
    if np.any(np.asarray(mu) > MU_RANGE[1]):
        raise InputError(f"{name} must be at most {MU_RANGE[1]:g} for a solved curve; got "
                         f"{float(np.max(mu)):g}: {TOO_STIFF}")
    return mu


#: Events a tolerance-driven solve converges (relative change between levels).
TOLERANCE_KEYS = ("p_max", "p_off")


def solve_to_tolerance(mu, tolerance, *, method="fem", solid=Solid(), radius_ratio=None,
                       p_end=1.0, max_levels=5, unstable_branch=False, progress=None):
    """Refine from `draft` (halving the surface elements and the turn limit) until P̄max and
    P̄off change by at most `tolerance` (relative) between two levels; the finer one is returned
    with those changes as its error estimate. If `max_levels` do not get there, the last level
    is returned with a message saying so. Arguments otherwise as `solve_curve`."""
    mu = _mu(mu)
    tolerance = in_range("tolerance", tolerance, 0.0, 0.1)
    _whole_curve_served(mu, unstable_branch)
    options = dict(solid=solid, radius_ratio=radius_ratio, unstable_branch=unstable_branch,
                   spring_constant=None)
    disc = _discretisation(mu, "draft", method=method, p_end=p_end, options=options)

    def level(k, d):
        report = (lambda f: progress((k + f) / max_levels)) if progress else None
        return solve_discretised(mu, d, solid=solid, radius_ratio=radius_ratio,
                                 unstable_branch=unstable_branch, progress=report)

    previous, previous_disc, wall = level(0, disc), disc, 0.0
    for k in range(1, max_levels):
        wall += previous.wall_s
        disc = disc.refined()
        result = level(k, disc)
        change = _estimate(result.events.records(), disc, previous.events.records(),
                           previous_disc)
        worst = max(change[key] / abs(getattr(result.events, key)) for key in TOLERANCE_KEYS)
        done = worst <= tolerance
        note = (f"; tolerance {tolerance:g} on P̄max, P̄off " + ("met" if done else "NOT met")
                + f" after {k + 1} levels (relative change {worst:.2g}, h = {disc.h_surface:.4g})")
        status = result.status if done else worst_status(result.status, "tolerance_not_met")
        floor = traction_tail(result.events, disc.traction_radius)
        result = replace(result, accuracy=f"tolerance {tolerance:g}",
                         error_estimate=_added(change, floor), estimated_by="tolerance",
                         estimate_floor=floor, wall_s=wall + result.wall_s, status=status,
                         message=result.message + note)
        if done:
            break
        previous, previous_disc = result, disc
    if progress:
        progress(1.0)
    return result
