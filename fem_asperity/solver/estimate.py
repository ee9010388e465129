"""A curve's error estimate, each strategy in one place: `with_estimate` solves the curve and
estimates its events alongside, on the second core.

'finer': the events solved again on a finer discretisation (`for_estimate()` of the
`solver.presets` discretisation), near each event only (`path.near_events`), or the whole curve
again where it holds load-line events; twice the change of each event (`difference_estimate`).
'bem': the FE of a homogeneous half-space against the boundary integral's curve
(`_estimate_against_bem`). Every estimate adds the force of the LJ traction beyond the traction
grid (`traction_tail`), and on grids that follow the edge what moving them changed."""

import threading
import time
from concurrent.futures import ThreadPoolExecutor
from contextlib import contextmanager
from dataclasses import dataclass, replace

from threadpoolctl import threadpool_limits

from ..closed_forms.lj import bradley_force
from ..curves.events import ESTIMATED
from ..path.near_events import events_near
from ..plumbing.errors import ContinuationError, InputError
from .discretised import PATH_BLAS_THREADS, discretisation_for, solve_discretised, solve_refining
from .presets import ESTIMATE_BY
from .result import CurveResult, noted, worst_status

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
#: Under a spring, the spring end's z̄ at the jumps (`CurveResult.z_jumps`) is estimated too.
SPRING_JUMPS = ("z_jump_in", "z_jump_out")


def _keys(a, b):
    """The keys estimated of the compared values `a` and `b`: ESTIMATED, and SPRING_JUMPS where
    either is under a spring."""
    return (*ESTIMATED, *(k for k in SPRING_JUMPS if k in a or k in b))


def difference_estimate(a, disc, b, partner_disc):
    """Error estimate of the events `a` (records, solved on `disc`) from the partner's `b` (on
    `partner_disc`, surface elements r times as long): |difference| / |r − 1| per ESTIMATED
    key (and SPRING_JUMPS key under a spring, `CurveResult.values`), None where the event is
    missing in either (`_one_sided` and `_missed` name those found by one of the two only).

    Against a finer partner (r = 1/2) that is twice the difference: the error of first-order
    convergence, which bounds faster convergence too (at order p the difference is the
    fraction 1 − 2^(−p) of the error), overstating it by at most 2 in the asymptotic range.
    Against a coarser one (r = 2, `solve_to_tolerance`) it is the difference itself."""
    scale = 1.0 / abs(partner_disc.h_surface / disc.h_surface - 1.0)
    return {k: (scale * abs(a[k] - b[k]) if a.get(k) is not None and b.get(k) is not None
                else None)
            for k in _keys(a, b)}


def _one_sided(a, b, other_named="its finer estimate discretisation"):
    """The clause naming the estimated events (records `a` of the solve, `b` of the other solve,
    `other_named`) that one of the two has and the other not (a jump one discretisation finds
    and the other misses): their estimate is None. "" where there are none."""
    keys = [k for k in _keys(a, b) if (a.get(k) is None) != (b.get(k) is None)]
    if not keys:
        return ""
    return (f"{', '.join(keys)} found by only one of the solve and {other_named} (no "
            f"estimate for them): try a finer accuracy")


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
    where it failed), the clauses the curve's message gains (`notes`, `result.noted`) and its
    `status` with it."""

    result: CurveResult
    estimate: dict | None
    notes: tuple
    status: str

    @classmethod
    def failed(cls, result, exc, what="its finer solve", hint=""):
        """The curve whose estimate's solve (`what`) failed with `exc`; then the clause `hint`
        (what to try instead)."""
        note = f"no error estimate: {what} failed ({type(exc).__name__}: {exc})"
        return cls(result, None, (note, hint), worst_status(result.status, "no_estimate"))


def with_estimate(mu, disc, options, progress, by):
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
        estimate = estimate_plus(estimate, moved)
    floor = traction_tail(result.events, disc.traction_radius) if estimate is not None else None
    if progress:
        progress(1.0)
    return replace(result, error_estimate=estimate_plus(estimate, floor), estimated_by=by,
                   estimate_floor=floor, status=made.status,
                   message=noted(result.message, *made.notes),
                   wall_s=time.perf_counter() - start)


def traction_tail(events, radius):
    """{force key: the LJ traction's force beyond `radius` (√(Rε)) at the event's δ̄o}, in
    2πRΔγ: Bradley's force at the gap there, δ̄o + radius²/2 (the solid's deflection that far
    out is negligible; the exact sphere's gap grows faster still). The floor of `FORCE_AT`."""
    records = events.records()
    return {key: abs(bradley_force(records[at] + 0.5 * radius**2))
            for key, at in FORCE_AT.items() if records[key] is not None}


def estimate_plus(estimate, extra):
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
    result, solved_on, traced = solve_refining(mu, disc, progress=curve_shown, **options)
    try:
        partner_on = solved_on.for_estimate()
        grids = (finer_grids.result() if solved_on is disc
                 else partner_on.grids(mu, **geometry))
        near = events_near(grids, partner_on.trace, traced, result.equilibrium.branch,
                           result.approach, result.retraction, result.events.jump_in,
                           result.events.jump_out, progress=estimate_shown)
        a = result.events.records()
        notes = (*_missed(near["missed"]),
                 f"error estimate from the finer discretisation traced near each event "
                 f"({near['windows']} windows, {near['newton_iterations']} Newton iterations)")
        return _Estimated(result, difference_estimate(a, solved_on, near, partner_on), notes,
                          result.status)
    except Exception as exc:  # the estimate never costs the result: whatever stopped it
        return _Estimated.failed(result, exc)


def _missed(missed):
    """Clauses naming the events (no estimate for them) the finer discretisation has none of near
    the curve's, with why (`path.near_events`: a jump it does not make, a branch it folds on, a
    window it could not follow)."""
    reasons = {}
    for key, reason in missed.items():
        reasons.setdefault(reason, []).append(key)
    return [f"no error estimate for {', '.join(keys)}: near the curve's, the finer "
            f"discretisation has none ({reason}); try a finer accuracy"
            for reason, keys in reasons.items()]


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
        result, solved_on, _ = solve_refining(mu, disc, progress=report, **options)
        try:
            partner_on = solved_on.for_estimate()
            if solved_on is disc:
                partner = finer_job.result()
            else:  # refined for ripple or a missed jump: its own partner
                stop.set()
                partner = solve_discretised(mu, partner_on, **options)
            if partner.ripples:
                raise ContinuationError(f"it rippled ({partner.folds} folds)")
            a, b = result.values(), partner.values()
            estimate = difference_estimate(a, solved_on, b, partner_on)
            return _Estimated(result, estimate, (_one_sided(a, b),), result.status)
        except Exception as exc:  # the estimate never costs the result: whatever stopped it
            return _Estimated.failed(result, exc)


def _estimated_by_bem(mu, disc, options, progress, pool):
    """`_Estimated`: the FE curve and, on the second core alongside, the
    boundary integral's curve at the FE's preset (`disc.name`) with its own 'finer' estimate,
    on grids that follow the edge wherever the FE's do (`_estimate_against_bem`)."""
    bem_disc = discretisation_for(mu, disc.name, method="bem", p_end=disc.trace.p_end,
                               options=options, track_edge=disc.follows_edge or None)
    with _alongside(pool, progress, with_estimate, mu, bem_disc, options,
                    by="finer") as (report, bem_job, _):
        result, _, _ = solve_refining(mu, disc, progress=report, **options)
        try:
            return _Estimated(result, *_estimate_against_bem(result, bem_job.result()),
                              result.status)
        except Exception as exc:  # the estimate never costs the result: whatever stopped it
            return _Estimated.failed(result, exc, "the boundary integral's curve",
                                     hint="estimate_by='finer' estimates the FE from its own "
                                          "finer mesh instead")


def _estimate_against_bem(result, partner):
    """(estimate, the message's clauses) of the events of the FE `result` from the boundary
    integral's `partner` curve: per event DIFFERENCE_FACTOR |FE − BEM| plus the BEM's estimate;
    None where either lacks the event or the BEM's estimate does. A partner that ripples, misses
    its jump or has no estimate gives none (`ContinuationError`)."""
    if partner.status != "ok" or partner.error_estimate is None:
        raise ContinuationError(f"the boundary integral's curve has status {partner.status!r} "
                                f"({partner.message})")
    a, b = result.values(), partner.values()
    keys = _keys(a, b)
    estimate = {k: (DIFFERENCE_FACTOR * abs(a[k] - b[k]) + partner.error_estimate.get(k)
                    if None not in (a.get(k), b.get(k), partner.error_estimate.get(k)) else None)
                for k in keys}
    unestimated = [k for k in keys
                   if None not in (a.get(k), b.get(k)) and partner.error_estimate.get(k) is None]
    notes = (_one_sided(a, b, other_named="the boundary integral's curve"),
             f"no error estimate for {', '.join(unestimated)}: the boundary integral's own "
             f"estimate has none" if unestimated else "",
             f"error estimate against the boundary integral (BEM '{partner.accuracy}', "
             f"{partner.points} points, {partner.wall_s:.1f} s alongside): "
             f"{DIFFERENCE_FACTOR:g} |FE - BEM| plus the BEM's own estimate per event")
    return estimate, notes


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
