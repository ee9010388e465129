"""The single-asperity curve: `solve_curve(mu, ...)` → `CurveResult` (curve, events, provenance).

Two methods for the elastic solid behind the same surface problem and path. 'fem': axisymmetric
P2 finite elements of the (layered) half-space (scikit-fem), condensed onto the surface. 'bem':
the Boussinesq integral of the homogeneous half-space on a radial grid (`solids.bem`), no mesh and
no truncation of the solid. Then, for both: LJ 9-3 traction on the surface as a nonlinear boundary
form with its consistent tangent; pseudo-arc-length continuation of the whole equilibrium curve;
exact extrema of P̄; approach and retraction under δ̄o control read off it, jumps included (see
`path.branches`, `path.whole_curve`). The error estimate is the change of each event on a
coarser discretisation (`coarsened()` of the `solver.presets` discretisation)."""

import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import replace

import numpy as np
from threadpoolctl import threadpool_limits

from ..path.branches import stable_paths
from ..path.curve import read_events
from ..path.grids import FixedGrid
from ..path.whole_curve import whole_curve_paths
from ..plumbing.checks import in_range, positive
from ..plumbing.errors import InputError
from ..solids.fe import Solid
from .presets import discretisation
from .result import PHYSICAL_FOLDS, CurveResult, Model, worst_status

#: BLAS threads while a curve is set up and traced, 1: its dense factorisations (n ≈ 100-3000)
#: ran slower with two threads than with one on a two-core machine, and the second core is better
#: spent on the error estimate's second curve. Not pinned by a test.
PATH_BLAS_THREADS = 1

#: Upper end of the measured onset of jump-in, 0.6972 ± 0.001 (`studies.onset.jump_in_onset`,
#: FE and BEM; test_bem_curve's fold-margin test pins 0.69-0.70): above it a homogeneous
#: Derjaguin curve must jump in. Just above, the fold is shallow and a grid can miss it (BEM
#: `default` at μ = 0.7); such a curve is solved again on grids refined up to
#: MISSED_JUMP_REFINEMENTS times (test_bem_curve).
MU_ONSET_HI, MISSED_JUMP_REFINEMENTS = 0.6982, 2

#: Tabor parameters a curve is solved for: from the rigid limit (μ = 1e-3 solves with both
#: methods; 1e-300 overflowed) to where the edge-following grids end; test_cli's bad-input test
#: pins the lower end.
MU_RANGE = (1e-3, 1e4)

#: Event keys compared between the two meshes of the error estimate.
ESTIMATED = ("p_max", "delta_oc", "a_c", "delta_o_star", "x_oc", "delta_jump_in", "p_jump_after",
             "p_off", "delta_jump_out")


def solve_discretised(mu, disc, *, solid=Solid(), radius_ratio=None, unstable_branch=False,
                      progress=None):
    """One curve on the given discretisation (`presets.discretisation`; no error estimate, inputs
    unchecked beyond the discretisation's own): for studies that set the resolution themselves."""
    start = time.perf_counter()
    with threadpool_limits(PATH_BLAS_THREADS, user_api="blas"):
        grids = disc.grids(mu, solid=solid, radius_ratio=radius_ratio)
        fixed = isinstance(grids, FixedGrid)
        if unstable_branch and not fixed:
            raise InputError("grids that follow the contact edge (BEM at large mu) trace "
                             "stable branches only")
        if unstable_branch:
            solved = whole_curve_paths(grids.start, disc.trace, progress)
        else:
            solved = stable_paths(grids, disc.trace, progress)
        approach, retraction, jumps_in, jumps_out, curve, traced = solved
    folds = int(curve.branch.max()) if unstable_branch else len(jumps_in) + len(jumps_out)
    message = f"{folds} folds of the equilibrium curve" + grids.summary()
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
        model=Model(grids.elastic, grids.start, traced) if fixed else None,
    )


def _solve_with_its_jump(mu, disc, *, progress=None, **options):
    """`solve_discretised`; where a homogeneous Derjaguin curve above MU_ONSET_HI shows no
    jump-in, again on discretisations refined (`refined()`) up to MISSED_JUMP_REFINEMENTS times
    until it does; its status is 'missed_jump' if it never does. Returns (result, missed): missed
    is the solve before the refinement that found the jump (None without one), twice as coarse:
    the error estimate's partner then, as the preset's coarser solve would compare against a
    discretisation that misses the jump too."""
    result = solve_discretised(mu, disc, progress=progress, **options)
    must_jump = (mu > MU_ONSET_HI and options["solid"].layer_thickness is None
                 and options["radius_ratio"] is None)
    if not must_jump or result.events.jump_in is not None:
        return result, None
    wall, finer, missed = result.wall_s, disc, result
    for level in range(1, MISSED_JUMP_REFINEMENTS + 1):
        finer = finer.refined()
        retried = solve_discretised(mu, finer, **options)
        wall += retried.wall_s
        if retried.events.jump_in is not None:
            note = (f"; no jump-in at '{disc.name}' although mu is above the onset: solved "
                    f"again on a discretisation refined {level} time(s)")
            return replace(retried, message=retried.message + note, wall_s=wall), missed
        missed = retried
    note = (f"; no jump-in although mu is above the onset, also refined "
            f"{MISSED_JUMP_REFINEMENTS} times: try --tolerance or a finer accuracy")
    return replace(result, status=worst_status(result.status, "missed_jump"),
                   message=result.message + note, wall_s=wall), None


def _difference(fine, coarse):
    """|fine − coarse| per estimated key; None where either is missing (e.g. no jump on one)."""
    a, b = fine.events.records(), coarse.events.records()
    return {k: (abs(a[k] - b[k]) if a[k] is not None and b[k] is not None else None)
            for k in ESTIMATED}


def solve_curve(mu, *, method="fem", accuracy="default", solid=Solid(), radius_ratio=None,
                p_end=1.0, error_estimate=True, unstable_branch=False, progress=None):
    """Approach and retraction of a rigid sphere on the half-space at Tabor parameter `mu`.

    method: 'fem' (finite elements, layers allowed) or 'bem' (boundary integral, homogeneous).
    accuracy: 'draft', 'default' or 'fine' (see `presets.PRESETS`).
    solid: `Solid` (homogeneous by default; a layer with thickness in √(Rε)).
    radius_ratio: R/ε for the exact sphere profile instead of Derjaguin's parabola (None).
    p_end: the approach goes on until P̄ reaches this compressive force (2πRΔγ units).
    unstable_branch: also trace the unstable branches between the folds, so that `equilibrium`
        is the whole S-shaped curve (more work: LU factorisations and short steps); by default
        only the stable branches are traced and each jump lands by energy descent
        (`path.branches`).
    error_estimate: also solve with twice as large surface elements (and turn limit, and a
        steeper far-field grading) and report the change of every event. That solve runs
        alongside on the second core; if it fails, the estimate is None and `message` says why
        (if the main solve fails, its error is raised once the coarser one has ended).
    progress: callable(fraction in [0, 1]) for a progress bar.
    Returns a `CurveResult`; raises `ContinuationError` if the path cannot be followed.
    """
    mu = in_range("mu", mu, *MU_RANGE, closed_lo=True)
    positive("p_end", p_end)
    if radius_ratio is not None:
        in_range("radius_ratio", radius_ratio, 10.0, np.inf, closed_lo=True)
    disc = discretisation(mu, accuracy, p_end=p_end, method=method)
    options = dict(solid=solid, radius_ratio=radius_ratio, unstable_branch=unstable_branch)
    if not error_estimate:
        return _solve_with_its_jump(mu, disc, progress=progress, **options)[0]
    start = time.perf_counter()
    # The coarser solve runs in a second thread: the dense factorisations release the GIL, so
    # the two curves share the two cores (one BLAS thread each).
    with threadpool_limits(PATH_BLAS_THREADS, user_api="blas"), ThreadPoolExecutor(1) as pool:
        coarse_job = pool.submit(solve_discretised, mu, disc.coarsened(), **options)
        result, missed = _solve_with_its_jump(mu, disc, progress=progress, **options)
        try:
            coarse = coarse_job.result() if missed is None else missed
            estimate, note, status = _difference(result, coarse), "", result.status
            if coarse.ripples:
                note = ("; the coarser solve of the error estimate ripples (more than two folds), "
                        "so the estimate is pessimistic")
        except Exception as exc:  # the estimate never costs the result: whatever stopped it
            estimate, note = None, (f"; no error estimate: the coarser discretisation failed "
                                    f"({type(exc).__name__}: {exc}); try a finer accuracy")
            status = worst_status(result.status, "no_estimate")
    return replace(result, error_estimate=estimate, status=status, message=result.message + note,
                   wall_s=time.perf_counter() - start)


#: Events a tolerance-driven solve converges (relative change between levels).
TOLERANCE_KEYS = ("p_max", "p_off")


def solve_to_tolerance(mu, tolerance, *, method="fem", solid=Solid(), radius_ratio=None,
                       p_end=1.0, max_levels=5, unstable_branch=False, progress=None):
    """Refine from `draft` (halving the surface elements and the turn limit) until P̄max and
    P̄off change by at most `tolerance` (relative) between two levels; the finer one is returned
    with those changes as its error estimate. If `max_levels` do not get there, the last level
    is returned with a message saying so. Arguments otherwise as `solve_curve`."""
    mu = in_range("mu", mu, *MU_RANGE, closed_lo=True)
    tolerance = in_range("tolerance", tolerance, 0.0, 0.1)
    disc = discretisation(mu, "draft", p_end=p_end, method=method)

    def level(k, d):
        report = (lambda f: progress((k + f) / max_levels)) if progress else None
        return solve_discretised(mu, d, solid=solid, radius_ratio=radius_ratio,
                                 unstable_branch=unstable_branch, progress=report)

    previous, wall = level(0, disc), 0.0
    for k in range(1, max_levels):
        wall += previous.wall_s
        disc = disc.refined()
        result = level(k, disc)
        change = _difference(result, previous)
        worst = max(change[key] / abs(getattr(result.events, key)) for key in TOLERANCE_KEYS)
        done = worst <= tolerance
        note = (f"; tolerance {tolerance:g} on P̄max, P̄off " + ("met" if done else "NOT met")
                + f" after {k + 1} levels (relative change {worst:.2g}, h = {disc.h_surface:.4g})")
        status = result.status if done else worst_status(result.status, "tolerance_not_met")
        result = replace(result, accuracy=f"tolerance {tolerance:g}", error_estimate=change,
                         wall_s=wall + result.wall_s, status=status, message=result.message + note)
        if done:
            break
        previous = result
    if progress:
        progress(1.0)
    return result
