"""One curve on one discretisation: `solve_discretised` (and `solve_traced`, with the states
behind it), refined while it ripples or misses a jump it must have (`solve_refining`), on the
discretisation a curve's options take (`discretisation_for`).

Two methods for the elastic solid behind the same surface problem and path. 'fem': axisymmetric
P2 finite elements of the (layered) half-space (scikit-fem), condensed onto the surface. 'bem':
the Boussinesq integral of the homogeneous half-space on a radial grid (`solids.bem`), no mesh and
no truncation of the solid. Then, for both: LJ 9-3 traction on the surface as a nonlinear boundary
form with its consistent tangent; pseudo-arc-length continuation of the whole equilibrium curve;
exact extrema of P̄; approach and retraction under δ̄o control read off it, jumps included (see
`path.branches`, `path.whole_curve`)."""

import time
from dataclasses import replace

from threadpoolctl import threadpool_limits

from ..curves.events import read_events
from ..path.branches import stable_paths
from ..path.load_line import load_line_paths
from ..path.whole_curve import whole_curve_paths
from ..plumbing.errors import InputError
from ..solids.fe import Solid
from .presets import MU_TRACKING, discretisation, sizing_mu
from .result import PHYSICAL_FOLDS, CurveResult, Model, noted, worst_status

#: BLAS threads while a curve is traced: its dense factorisations ran slower with two on two
#: cores, and the second core serves the error estimate. Not pinned by a test.
PATH_BLAS_THREADS = 1

#: Above the measured jump-in onset's upper end a Derjaguin curve must jump in; one that misses
#: it (or ripples) is refined up to REFINEMENTS times. test_bem_curve.py (fold margin, 0.7).
MU_ONSET_HI, REFINEMENTS = 0.6982, 2

#: The approach under a spring starts this many times beyond the rigid sphere's jump-in under
#: it. test_load_line.py::test_a_soft_spring_lands_beyond_the_start.
SPRING_FOLD_MARGIN = 2.0


def solve_discretised(mu, disc, *, solid=Solid(), radius_ratio=None, unstable_branch=False,
                      spring_constant=None, progress=None):
    """One curve on the given discretisation (`presets.discretisation`; no error estimate, inputs
    unchecked beyond the discretisation's own): for studies that set the resolution themselves.
    spring_constant: load-line control through a spring of that stiffness (2πRΔγ/ε), read off
    the whole curve (`path.load_line`); None: displacement control."""
    return solve_traced(mu, disc, solid=solid, radius_ratio=radius_ratio,
                         unstable_branch=unstable_branch, spring_constant=spring_constant,
                         progress=progress)[0]


def solve_traced(mu, disc, *, solid, radius_ratio, unstable_branch, spring_constant, progress):
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
            spring = load_line_paths(grids.start, traced, curve, spring_constant)
            approach, retraction = spring.approach, spring.retraction
            jumps_in, jumps_out = spring.jumps_in, spring.jumps_out
            z_jumps = {"z_jump_in": spring.z_in[0] if spring.z_in else None,
                       "z_jump_out": spring.z_out[-1] if spring.z_out else None}
    if unstable_branch and spring_constant is None:  # stability changes along the whole curve
        folds = int(curve.branch.max())
    else:
        folds = len(jumps_in) + len(jumps_out)
    moves = paths.moves if grids.follows_edge else None  # none on one grid or mesh
    sized_for = sizing_mu(mu, solid)
    message = noted(f"{folds} folds of the equilibrium curve", grids.summary(moves))
    if sized_for != mu:
        message = noted(message, f"elements sized for the layer's Tabor parameter "
                                 f"{sized_for:.4g}, the more compliant material")
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


def solve_refining(mu, disc, *, progress=None, **options):
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

    result, traced = solve_traced(mu, disc, progress=progress, **options)
    first, wall, solved_on = flaw(result), result.wall_s, disc
    if first is None:
        return result, disc, traced
    for level in range(1, REFINEMENTS + 1):
        solved_on = solved_on.refined()
        result, traced = solve_traced(mu, solved_on, progress=None, **options)
        wall += result.wall_s
        if flaw(result) is None:
            why = ("more folds than a jump-in and a jump-out (ripple)" if first == "ripples"
                   else "no jump-in although mu is above the onset")
            note = (f"at '{disc.name}' {why}: solved again on a discretisation refined "
                    f"{level} time(s)")
            refined = replace(result, message=noted(result.message, note), wall_s=wall)
            return refined, solved_on, traced
    if flaw(result) == "ripples":
        note = (f"still ripples after {REFINEMENTS} refinements: the jump-in is the first fold "
                f"of the approach and the jump-out the last of the retraction; try --tolerance")
    else:
        note = (f"no jump-in although mu is above the onset, also refined {REFINEMENTS} "
                f"times: try --tolerance or a finer accuracy")
    return replace(result, status=worst_status(result.status, flaw(result)),
                   message=noted(result.message, note), wall_s=wall), solved_on, traced


def discretisation_for(mu, accuracy, *, method, p_end, options, track_edge=None):
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
