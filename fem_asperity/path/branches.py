"""Approach and retraction along the stable branches only, each jump landed by energy descent.

The approach follows the stable branch from far away until it folds, jumps at the fold's δ̄o to
the stable state found downhill in energy (`landing.land`) and goes on from there, until P̄ ≥
p_end. The retraction walks back along the branches the approach visited and traces only what the
approach did not: from each landing onward in δ̄o, until that branch folds and the solid jumps
off; where it lands on an approach branch it walks back along that. The unstable branches (LU
factorisations and short steps, much of the cost of the whole curve) are never traced;
`whole_curve` reads the same paths off the whole curve instead.
"""

from functools import partial
from typing import NamedTuple

import numpy as np

from ..curves.curve import curve_from_columns
from ..curves.events import Jump
from ..plumbing.errors import ContinuationError
from .continuation import APPROACH, Trace, approach_fraction, follow, start_state
from .grids import Grids
from .paths import GridMoves, PathPoint, Paths, disc_area
from .reading import (
    ADJACENT,
    COLUMNS,
    equilibrium_curve,
    fold_by_parabola,
    path_from_rows,
    point_row,
    refine_force_extrema,
    root_along,
)
from .tip import follow_tip, record_fold_elsewhere, tip_direction

#: Headings in (x̄o, δ̄o, P̄) from a landing: a stable branch always moves in δ̄o.
_DOWN, _UP = np.array([0.0, -1.0, 0.0]), np.array([0.0, 1.0, 0.0])
#: Most jumps one path may make (ripple of a far too coarse mesh, or a landing that loops). Not
#: pinned by a test.
MAX_JUMPS = 200
#: A move to a new grid that changes P̄ by more than this landed past a fold there: a jump
#: (methods.md §13). Not pinned by a test.
REGRID_JUMP = 1e-3
#: Share of the progress bar given to the approach (methods.md §13);
#: test_bem_curve.py::test_progress_rises_to_one_at_the_end_only.
APPROACH_SHARE = 0.6
#: The retraction's progress stops here short of the end: the peel's remaining contact radius
#: measures it, and the separation and the way back to x_start come after.
RETRACTION_SHOWN_MAX = 0.98


class Branch(NamedTuple):
    """A stable branch followed (`follow_branch`): its `trace`, the `fold` it ends in (a
    `PathPoint`, None where `until` was met), the state `beyond` the fold (None where there is
    none), the `surface` of its end and, where a move to a new grid landed elsewhere, the
    (surface, w) it `landed` on (else None)."""

    trace: Trace
    fold: PathPoint | None
    beyond: np.ndarray | None
    surface: object
    landed: tuple | None


class _Piece(NamedTuple):
    """A branch on one grid (`_piece`): its `trace`, `fold` (or None), the first state `beyond`
    the fold and that state's δ̄o."""

    trace: Trace
    fold: PathPoint | None
    beyond: np.ndarray | None
    beyond_delta: float | None


def follow_branch(grids, moves, surface, w, delta, heading, settings, until, on_point):
    """The `Branch` from (w, δ) on `surface`: `_piece`s of the branch, moved to a new grid
    (`grids.regrid`, see `grids`) each time the contact edge leaves the current one's band; on a
    fixed grid, one piece. Where a move lands elsewhere (REGRID_JUMP) the branch ends in a fold
    there and has `landed`. A branch in contact on grids that follow the edge is
    followed in its crack tip's radius first (`tip.follow_tip`), then, where that hands over,
    as any branch. What moving to new grids changed goes into `moves` (a `GridMoves`)."""
    merged = Trace()
    direction = tip_direction(grids, surface, w, delta, heading)
    if direction:
        path = follow_tip(grids, moves, surface, w, delta, direction, settings, until=until,
                          on_point=on_point)
        merged.extend(path.trace)
        if path.fold is not None or (path.last is not None and until(path.trace)):
            return Branch(merged, path.fold, path.beyond, path.surface, None)
        if path.last is not None:  # go on from its last state, which `follow` records again
            surface, w, delta = path.last.surface, path.last.w, path.last.delta
            merged.drop_last()
    while True:
        done = partial(_done_or_off_grid, until, grids, surface)
        traced, fold, beyond, beyond_delta = _piece(surface, w, delta, heading, settings, done,
                                                    on_point, partial(grids.admits, surface))
        if fold is not None and beyond is not None and direction < 0 and traced.delta:
            record_fold_elsewhere(grids, moves, surface, (traced.states[-1], traced.delta[-1]),
                                  (beyond, beyond_delta), settings.tol)
        if fold is not None or until(traced):
            merged.extend(traced)
            return Branch(merged, fold, beyond, surface, None)
        w, delta = traced.states[-1], traced.delta[-1]
        before = point_row(traced, -1, 0)
        traced.drop_last()  # solved again on the next grid
        merged.extend(traced)
        surface, w, its = grids.regrid(surface, w, delta, tol=settings.tol)
        merged.newton_iterations += its
        change = abs(surface.force(w, delta) - before.p)
        if change > REGRID_JUMP:
            return Branch(merged, before, None, surface, (surface, w))
        moves.record_move(change, abs(surface.contact(w, delta)[1] - before.a_c))


def _done_or_off_grid(until, grids, surface, tr):
    """`until(tr)`, or the last point of `tr` is no longer resolved by `surface`."""
    return until(tr) or not grids.fits(surface, tr.states[-1], tr.delta[-1])


def _piece(surface, w, delta, heading, settings, until, on_point, admissible=None):
    """The `_Piece` from (w, δ): its stable Trace with its force extrema refined, the fold (a
    `PathPoint`) at the branch's end, or None if `until` was met.

    The fold is where dδ̄o/ds = 0 between the last stable and the first unstable point
    (`reading.root_along`), or one interval earlier (`reading.ADJACENT`: the last point
    flagged stable may lie just past it, its flag from a reused factorisation); where that
    root is not clean (ripple), the parabola in arc length through the last three points
    (`reading.fold_by_parabola`), or the start if the branch has no more."""
    traced = follow(surface, w, delta, heading, settings, until=until, stop_at_fold=True,
                    on_point=on_point, admissible=admissible)
    fold = beyond = beyond_delta = None
    if not traced.stable[-1]:
        k, exact = len(traced.delta) - 2, None
        beyond = traced.states[-1]  # the first point flagged unstable: the landing starts there
        beyond_delta = traced.delta[-1]
        for j in (k + shift for shift in ADJACENT if shift <= 0 and k + shift >= 0):
            exact = root_along(surface, traced, j, 1)
            if exact is not None:
                break
        if exact is not None:
            w_f, d_f, _ = exact
            radius = surface.contact(w_f, d_f)[1]
            fold = PathPoint(float(d_f), surface.centre_gap(w_f, d_f), surface.force(w_f, d_f),
                             disc_area(radius), radius)
            while len(traced.delta) > j + 2:  # a point flagged stable past the fold
                traced.drop_last()
        elif k >= 1:
            fold = fold_by_parabola(equilibrium_curve(traced), k, k + 1,
                                    descending=heading[1] < 0)
        else:
            fold = PathPoint(traced.delta[0], traced.x[0], traced.p[0],
                             disc_area(traced.a_c[0]), traced.a_c[0])
        traced.drop_last()
    refine_force_extrema(surface, traced)
    return _Piece(traced, fold, beyond, beyond_delta)


def land_jump(grids, surface, fold, beyond, settings, counter, landed=None, *,
              into_contact):
    """Land past `fold` downhill from the unstable state `beyond`, on the grid of the landing
    (`grids.land`), or take the (surface, w) `landed` already: (surface, w, Jump). Where
    `grids.landing_guess` offers a state to land from instead (at large μ: JKR's contact for a
    jump `into_contact`, the undeformed surface for a jump out), the jump lands from there if
    that ends in contact (`into_contact`) or separated (not), lower in energy than `beyond`
    (a check that it lies downhill, not that the descent from the fold ends there: at large μ
    the approach has one stable state in contact at the jump-in's δ̄o, the retraction none at
    the jump-out's)."""
    delta = fold.delta
    if landed is None:
        landed, iterations = _land_from_guess(grids, surface, beyond, delta, settings,
                                              into_contact)
        counter.newton_iterations += iterations
    if landed is None:
        surface, w, iterations = grids.land(surface, beyond, delta, tol=settings.tol)
        counter.newton_iterations += iterations
    else:
        surface, w = landed
    x, p = surface.centre_gap(w, delta), surface.force(w, delta)
    if abs(x - fold.x) <= 1e-9 * (1.0 + abs(x)):
        raise ContinuationError(f"the jump at δ = {delta:.6g} landed back on its own branch")
    return surface, w, Jump(delta=delta, x_before=fold.x, p_before=fold.p, p_after=p,
                   a_c_after=surface.contact(w, delta)[1], x_after=x)


def _land_from_guess(grids, surface, beyond, delta, settings, into_contact):
    """((surface, w) landed at δ̄o from `grids.landing_guess` where it offers one and the
    landing ends in contact (a crack tip) if `into_contact`, separated if not, with an energy
    below that of `beyond` on `surface`; else None), and the Newton iterations spent (those of
    a landing that failed are not known: 0)."""
    try:
        guess = grids.landing_guess(surface, delta, into_contact=into_contact)
        if guess is None:
            return None, 0
        landed, w, iterations = grids.land(*guess, delta, tol=settings.tol)
    except ContinuationError:
        return None, 0
    if ((landed.crack_tip(w, delta) > 0.0) == into_contact
            and landed.energy(w, delta) < surface.energy(beyond, delta)):
        return (landed, w), iterations
    return None, iterations


def _approach_branch(branches, delta, x, jump):
    """(j, c): the approach branch j whose δ̄o range holds `delta` with x̄o there within 1% of the
    jump size of `x`, and its count c of points with larger δ̄o; None if there is none."""
    for j, traced in enumerate(branches):
        d, xs = np.asarray(traced.delta), np.asarray(traced.x)
        if d[-1] <= delta <= d[0] and abs(np.interp(delta, d[::-1], xs[::-1]) - x) <= 0.01 * jump:
            return j, int(np.sum(d > delta))
    return None


def stable_paths(grids: Grids, settings, progress=None):
    """`Paths`: the two paths under δ̄o control (as `whole_curve.walk`), the stable branches
    traced as one `Curve` (approach branches first, `branch` numbering them) and as one Trace
    (states, counters: landings included), and what moving between grids changed.

    grids: the surfaces to run on (`grids.Grids`): one `FixedGrid`, whose surface then holds
    every state of the Trace, or `EdgeGrids` that follow the contact edge from `grids.start`.

    `progress(fraction)`: the approach runs to APPROACH_SHARE (`approach_fraction`), the
    retraction on as its contact radius shrinks; 1 at the end only, never falling.
    Raises ContinuationError where a branch cannot be followed or a jump finds no landing.
    """
    traced, surface, moves = Trace(), grids.start, GridMoves()
    w, delta, traced.newton_iterations = start_state(surface, settings)
    shown = 0.0  # approach_fraction dips where the force falls after a jump-in: never shown

    def report(tr):
        nonlocal shown
        shown = max(shown, APPROACH_SHARE * approach_fraction(tr.x[-1], tr.p[-1], settings))
        progress(shown)

    def reached_end(tr):
        return tr.p[-1] >= settings.p_end

    branches, starts, approach, jumps_in, heading = [], [], [], [], APPROACH
    while True:
        starts.append(surface)
        branch, fold, beyond, surface, landed = follow_branch(
            grids, moves, surface, w, delta, heading, settings, reached_end,
            report if progress else None)
        branches.append(branch)
        approach += [point_row(branch, i, len(jumps_in)) for i in range(len(branch.delta))]
        if fold is None:
            break
        if len(jumps_in) >= MAX_JUMPS:
            raise ContinuationError(f"more than {MAX_JUMPS} jumps on approach")
        approach.append(fold.on(len(jumps_in)))
        surface, w, jump = land_jump(grids, surface, fold, beyond, settings, traced, landed,
                                     into_contact=True)
        jumps_in.append(jump)
        delta, heading = fold.delta, _DOWN
    retraction, jumps_out, extra = _retract(grids, moves, starts, settings, branches, traced,
                                            progress)
    ids = []
    for k, branch in enumerate(branches + extra):
        traced.extend(branch)
        ids += [k] * len(branch.delta)
    equilibrium = curve_from_columns(*(getattr(traced, c) for c in COLUMNS),
                                     np.ones(len(ids), dtype=bool), ids)
    if progress is not None:
        progress(1.0)
    return Paths(path_from_rows(approach), path_from_rows(retraction), jumps_in, jumps_out,
                 equilibrium, traced, moves)


def _retract(grids, moves, starts, settings, branches, counter, progress):
    """(rows, jumps, branches traced): back along approach branch j from its point c − 1, then on
    from its first point (a landing, on the surface starts[j]) by tracing, until a branch reaches
    x_start again."""
    rows, jumps, extra = [], [], []
    j, c = len(branches) - 1, len(branches[-1].delta)
    peel = {"from": None, "shown": 0.0}  # contact radius where the tracing began; shown so far

    def report(tr):
        if progress is None or not tr.a_c:
            return
        if peel["from"] is None:
            peel["from"] = tr.a_c[0]
        if peel["from"] > 0.0:
            peeled = 1.0 - tr.a_c[-1] / peel["from"]
            peel["shown"] = max(peel["shown"], min(RETRACTION_SHOWN_MAX, peeled))
        progress(APPROACH_SHARE + (1.0 - APPROACH_SHARE) * peel["shown"])

    def far(tr):
        return tr.x[-1] >= settings.x_start

    while True:
        rows += [point_row(branches[j], i, len(jumps)) for i in range(c - 1, -1, -1)]
        if j == 0:
            return rows, jumps, extra
        surface, w, delta, skip = starts[j], branches[j].states[0], branches[j].delta[0], 1
        while True:
            branch, fold, beyond, surface, landed = follow_branch(
                grids, moves, surface, w, delta, _UP, settings, far, report)
            extra.append(branch)
            rows += [point_row(branch, i, len(jumps)) for i in range(skip, len(branch.delta))]
            if fold is None:
                return rows, jumps, extra
            if len(jumps) >= MAX_JUMPS:
                raise ContinuationError(f"more than {MAX_JUMPS} jumps on retraction")
            rows.append(fold.on(len(jumps)))
            surface, w, jump = land_jump(grids, surface, fold, beyond, settings, counter, landed,
                                         into_contact=False)
            jumps.append(jump)
            delta, skip = fold.delta, 0
            known = _approach_branch(branches, delta, jump.x_after,
                                     abs(jump.x_after - jump.x_before))
            if known is not None:
                area, radius = surface.contact(w, delta)
                rows.append(PathPoint(delta, jump.x_after, jump.p_after, area, radius,
                                      len(jumps)))
                j, c = known
                break
