"""The single-asperity curve: `solve_curve(mu, ...)` → `CurveResult` (curve, events, error
estimate, provenance), and `solve_to_tolerance`, refined until two levels agree.

The curve is solved on the preset's discretisation (`solver.discretised`) and its events'
error estimated alongside (`solver.estimate`)."""

from dataclasses import replace

import numpy as np

from ..plumbing.checks import in_range, positive
from ..plumbing.errors import InputError
from ..solids.fe import Solid
from .discretised import discretisation_for, solve_discretised, solve_refining
from .estimate import (
    difference_estimate,
    estimate_kind,
    estimate_plus,
    traction_tail,
    with_estimate,
)
from .result import noted, worst_status

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

#: Largest μ whose whole curve (unstable branches, or a spring) is traced on one uniform grid
#: (benchmarks/results/extremes.md). test_cli's bad-input test pins it.
WHOLE_CURVE_MU_MAX = 6.0


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
        and per event twice the difference (`estimate.difference_estimate`). The finer
        discretisation traces the curve near each event only (`path.near_events`, after the
        curve; its surfaces are built alongside on the second core); with `unstable_branch` or a
        `spring_constant` it solves the whole curve again alongside.
        'bem' (the FE of a homogeneous half-space only): the boundary integral's curve at the
        same preset, with its own 'finer' estimate, solved alongside on the second core; per
        event DIFFERENCE_FACTOR |FE − BEM| plus the BEM's estimate
        (`estimate._estimate_against_bem`). It costs about as much as the FE's curve instead of
        2.5-5.3 times, and estimates the FE's whole error (its bulk mesh and truncation
        included) with an independent method.
        'auto' (default): 'bem' for the FE of a homogeneous half-space, else 'finer'.
    spring_constant: load-line control, as through an AFM cantilever, with a spring of this
        stiffness k̄ = Kε/(2πRΔγ) (> 0): the jumps come where dP̄/dδ̄o reaches k̄, and the
        result's z_jumps hold the spring end's z̄ at them (`path.load_line`); the whole curve is
        traced (on one uniform grid). None (default): displacement control.
    A curve that ripples, or misses a jump it must have, is solved again on refined
    discretisations (up to `discretised.REFINEMENTS` times); one that still does carries that
    `status`.
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
    disc = discretisation_for(mu, accuracy, method=method, p_end=p_end, options=options)
    if not error_estimate:
        return solve_refining(mu, disc, progress=progress, **options)[0]
    return with_estimate(mu, disc, options, progress, by)


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
    disc = discretisation_for(mu, "draft", method=method, p_end=p_end, options=options)

    def level(k, d):
        report = (lambda f: progress((k + f) / max_levels)) if progress else None
        return solve_discretised(mu, d, solid=solid, radius_ratio=radius_ratio,
                                 unstable_branch=unstable_branch, progress=report)

    previous, previous_disc, wall = level(0, disc), disc, 0.0
    for k in range(1, max_levels):
        wall += previous.wall_s
        disc = disc.refined()
        result = level(k, disc)
        change = difference_estimate(result.events.records(), disc, previous.events.records(),
                           previous_disc)
        worst = max(change[key] / abs(getattr(result.events, key)) for key in TOLERANCE_KEYS)
        done = worst <= tolerance
        note = (f"tolerance {tolerance:g} on P̄max, P̄off " + ("met" if done else "NOT met")
                + f" after {k + 1} levels (relative change {worst:.2g}, h = {disc.h_surface:.4g})")
        status = result.status if done else worst_status(result.status, "tolerance_not_met")
        floor = traction_tail(result.events, disc.traction_radius)
        result = replace(result, accuracy=f"tolerance {tolerance:g}",
                         error_estimate=estimate_plus(change, floor), estimated_by="tolerance",
                         estimate_floor=floor, wall_s=wall + result.wall_s, status=status,
                         message=noted(result.message, note))
        if done:
            break
        previous, previous_disc = result, disc
    if progress:
        progress(1.0)
    return result
