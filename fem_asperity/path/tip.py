"""Stable branches in contact at large μ, followed in the crack tip's radius.

At large μ the stable branches in contact move the crack tip over many bands of the grids that
follow the edge while δ̄o and P̄ hardly move, and arc length (`continuation.follow`) takes short
steps there, many of which Newton fails on. Here the tip's radius is the parameter instead:
each state holds its tip at a given radius (the node gaps, interpolated linearly, equal TIP_GAP
there) with δ̄o free, predicted by moving the last state's gaps along with the tip
(`translated`). δ̄o has its fold, the jump-out, where dδ̄o/d(tip) = 0, and P̄ its extremum where
dP̄/d(tip) = 0; both are found by Brent's method on those rates. A prediction its grid does not
admit is solved on a grid built for it (`held_from`); states are moved to new grids and measured
there as `branches.follow_branch` does. docs/methods.md §5 has the reasons and measurements.
"""

from typing import NamedTuple

import numpy as np
from scipy.optimize import brentq

from ..plumbing.errors import ContinuationError
from .continuation import DELTA_ROW, Trace, TraceSettings, correct
from .held_tip import Held, along, as_held, contact_radius_rate, held, held_from, is_stable
from .paths import PathPoint, disc_area

#: Tip steps in bands: the first, growth after ≤ EASY Newton iterations, the shortest (then
#: `follow` goes on) and longest (beyond, the P̄ and ā_c limits hold them). docs/methods.md §5.
FIRST_STEP, GROWTH, EASY, SMALLEST, LONGEST = 0.25, 1.5, 3, 1.0 / 64.0, 8.0
#: A step over its P̄ or ā_c limit by `ratio` is retried SAFETY / ratio as long, as `follow`'s.
SAFETY = 0.8
#: ā_c's limit per step (√(Rε), the uniform grid's `da`: ā_c recedes faster than the tip) and
#: the steps (bands) below which it no longer shortens them (the contact can vanish in one).
TIP_DA, DA_FLOOR = TraceSettings.da, 0.125
#: A retraction hands over to `follow` this many bands from the axis (a detaching contact stays
#: on the pre-contact grid, `EdgeGrids._edges`).
END = 3.0
#: Every MEASURED_EVERY-th state before P̄'s extremum is solved again on a grid placed ahead, its
#: change recorded for the estimate (the states' own grids are built for them and seldom move).
MEASURED_EVERY = 4
#: Steps a bracket's width apart that `_record_fold_elsewhere` takes, at most, to bracket the fold.
BRACKETING = 4
#: The approach is followed in the tip where TIP_DA spans this many bands (`tip_direction`).
APPROACH_BANDS = 2.0
#: Brent's tolerance (√(Rε)) on the tip of an extremum of P̄ or δ̄o: the values are quadratic in it.
XTOL = 1e-9


class TipPath(NamedTuple):
    """Result of `follow_tip`: the stable states traced (a `Trace`, force extremum included),
    the fold (a `PathPoint`) or None, the first state past it (on `surface`) or None, the
    surface of the last state, and the last stable `Held` (where the path handed over)."""

    trace: Trace
    fold: PathPoint | None
    beyond: np.ndarray | None
    surface: object
    last: Held


def tip_direction(grids, surface, w, delta, heading):
    """How the crack tip moves along the stable branch from (w, δ̄o) with the `heading` in
    (x̄o, δ̄o, P̄), where the branch is followed in the tip, on grids that follow the edge with a
    crack tip beyond END bands: −1, receding, on a retraction (δ̄o rising); +1, advancing, on an
    approach (δ̄o falling) where TIP_DA spans at least APPROACH_BANDS bands; else 0. Below, a
    grid per step of at most about a band costs more than the arc length's grids, which serve
    about 1.5 bands each (`benchmarks/large_mu.py` times both)."""
    if not (grids.follows_edge and surface.crack_tip(w, delta) > END * grids.band):
        return 0
    if heading[1] < 0.0:
        return 1 if TIP_DA >= APPROACH_BANDS * grids.band else 0
    return -1


def follow_tip(grids, moves, surface, w, delta, direction, settings, *, until, on_point=None):
    """Follow the stable branch from the equilibrium (w, δ̄o) on `surface`, the crack tip moving
    in `direction` (`tip_direction`), until `until(trace)` holds, δ̄o folds (the jump-out), or,
    receding, the tip nears the axis (END bands), or the steps fall below SMALLEST bands (then the
    caller goes on with `continuation.follow` from the last state). Steps are limited as
    `follow`'s: P̄ and ā_c change by at most settings.dp and TIP_DA between points.
    `on_point(trace)` after each point. Returns a `TipPath`."""
    band, tol = grids.band, settings.tol
    state, trace = as_held(surface, w, delta), Trace()

    def record(new):
        trace.append(new.surface, new.w, new.delta, True, new.force, new.contact,
                     new.tangent(direction))
        trace.newton_iterations += new.iterations
        if on_point is not None:
            on_point(trace)

    if not (state.before_fold and is_stable(state)):
        return TipPath(trace, None, None, surface, None)
    record(state)
    step, past_extremum, radius_rate, longest = FIRST_STEP * band, False, 1.0, LONGEST * band
    while not until(trace):
        target = state.tip + direction * step
        if (direction < 0 and target < END * band) or step < SMALLEST * band:
            break
        new = held_from(grids, state, target, tol, radius_rate)
        if new is not None and not along(state, new):
            new = None
        if new is not None:
            by_force = abs(new.force - state.force) / settings.dp
            ratio = max(by_force, abs(new.contact[1] - state.contact[1]) / TIP_DA
                        if step > DA_FLOOR * band else 0.0)
            if ratio > 1.0:
                step *= SAFETY / ratio
                if by_force <= 1.0:
                    step = max(step, DA_FLOOR * band)
                trace.rejected_steps += 1
                continue
            if not grids.admits(new.surface, new.w, new.delta):
                new = _moved(grids, new, tol)
        if new is None:
            step *= 0.5
            trace.rejected_steps += 1
            continue
        stable = is_stable(new)
        if not (stable and new.before_fold) and step > band:
            # near the fold, steps of at most a band: from a longer one Brent's bracket held
            # states of another branch, or the step went past the fold and back
            step, longest = 0.5 * step, band
            trace.rejected_steps += 1
            continue
        if stable != new.before_fold:  # another mode than the tip's: `follow` goes on
            break
        if not stable:
            return _fold(grids, moves, trace, state, new, direction, tol)
        past_extremum = past_extremum or state.rates[2] * new.rates[2] < 0.0
        _insert_roots(grids, trace, state, new, direction, tol,
                      (_force_rate, _centre_gap_above_contact) if direction > 0
                      else (_force_rate,))
        if not grids.fits(new.surface, new.w, new.delta):
            new = _moved(grids, new, tol, moves=None if past_extremum else moves,
                         radius=direction > 0)
            if new is None:
                break
        elif not past_extremum and len(trace.delta) % MEASURED_EVERY == 0:
            _moved_ahead(grids, new, direction, tol, moves=moves, radius=direction > 0)
        radius_rate = contact_radius_rate(state, new)
        state = new
        record(state)
        growth = GROWTH if state.iterations <= EASY else 1.0
        step = min(step * (growth if ratio * growth <= SAFETY else SAFETY / ratio), longest)
    return TipPath(trace, None, None, state.surface, state)


def _moved(grids, state, tol, *, moves=None, radius=False, centre=None):
    """`state` solved again, its tip held, on the grid of its edges (`EdgeGrids.move`, or
    centred on the (ā_c, tip) `centre`; None where Newton fails there). With `moves` (a state
    before P̄'s extremum, the retraction's one estimated force, where grids agree far better
    than next to the fold; and the approach's states) the change of P̄ at the state's δ̄o is
    recorded (`GridMoves.record_move`), as `branches.follow_branch` measures it. With `radius` (the
    approach, whose ā_c at P̄max is an event) the change of ā_c too; not on the retraction,
    where ā_c moves by tenths of √(Rε) between grids as its compressive contact vanishes."""
    surface, w = grids.move(state.surface, state.w, state.delta, centre=centre)
    moved = held(surface, w, state.delta, state.tip, tol=tol)
    if moved is not None and moves is not None:
        at_delta = correct(surface, moved.w, moved.delta, DELTA_ROW,
                           np.array([0.0, state.delta, 0.0]), 0.0, tol=tol)
        w_at, d_at = (moved.w, moved.delta) if at_delta is None else (at_delta[0], state.delta)
        force, contact = surface.force(w_at, d_at), surface.contact(w_at, d_at)
        moves.record_move(abs(force - state.force),
                          abs(contact[1] - state.contact[1]) if radius else 0.0)
    return moved


def _moved_ahead(grids, state, direction, tol, **options):
    """`_moved` onto a grid centred the grids' lead (`EdgeGrids.ahead`) further along, in the
    tip's `direction`, than `state`'s edges: a placement the state's own grid does not have."""
    ahead = direction * grids.ahead * grids.band
    return _moved(grids, state, tol, centre=(state.contact[1] + ahead, state.tip + ahead),
                  **options)


def _root(grids, first, second, of, tol):
    """The held state between the held states `first` and `second` (solved from the nearest
    state known, `held_from`) where of(state) vanishes (Brent from the two states' own values, which
    bracket it), or None where Newton fails inside."""
    known = [first, second]

    def value(tip):
        for end in (first, second):
            if tip == end.tip:
                return of(end)
        near = min(known[1:], key=lambda s: abs(s.tip - tip))
        solved = held_from(grids, near, tip, tol, contact_radius_rate(first, second))
        if solved is None:
            raise _NoRoot
        known.append(solved)
        return of(solved)

    try:
        tip = brentq(value, *sorted((first.tip, second.tip)), xtol=XTOL)
    except _NoRoot:
        return None
    return min(known[2:], key=lambda s: abs(s.tip - tip), default=None)


class _NoRoot(Exception):
    """Newton failed inside a bracket."""


def _force_rate(held):
    """dP̄/d(tip): P̄'s extremum where it vanishes."""
    return held.rates[2]


def _centre_gap_above_contact(held):
    """x̄o − 1 ε: the initial contact (δ̄o*, an event of the approach) where it vanishes."""
    return held.observed[0] - 1.0


def _insert_roots(grids, trace, state, new, direction, tol, values=(_force_rate,)):
    """Append, in order along the path, the held states between the held `state` and `new`
    where each of `values` (functions of a held state) changes sign. On the approach the
    initial contact too (`_centre_gap_above_contact`; no event of the retraction), which
    `curves.events._initial_contact` otherwise interpolates between points, too far apart on
    the tip's long steps."""
    roots = [_root(grids, state, new, of, tol) for of in values if of(state) * of(new) < 0.0]
    for root in sorted((r for r in roots if r is not None and r.before_fold),
                       key=lambda r: abs(r.tip - state.tip)):
        trace.append(root.surface, root.w, root.delta, True, root.force, root.contact,
                     root.tangent(direction))
        trace.newton_iterations += root.iterations


def _delta_rate(held):
    """dδ̄o/d(tip): the fold of δ̄o where it vanishes."""
    return held.rates[1]


def record_fold_elsewhere(grids, moves, surface, last, beyond, tol):
    """`_record_fold_elsewhere` for a retraction followed in arc length up to its fold
    (`branches.follow_branch`, where the tip path handed over before the jump-out), its last
    stable state `last` and the first past it, `beyond`, each (w, δ̄o) on `surface`: the
    fold is found in the tip between them here too, so that both are found alike; nothing is
    recorded where they do not bracket a fold of δ̄o in the tip (the arc length's fold came
    from a parabola, or lies where the tip turns back)."""
    states = [as_held(surface, w, delta) for w, delta in (last, beyond)]
    if not (min(state.tip for state in states) > END * grids.band
            and _delta_rate(states[0]) < 0.0 < _delta_rate(states[1])):
        return
    try:
        fold = _root(grids, *states, _delta_rate, tol)
    except ContinuationError:  # a diagnostic: it never costs the curve
        return
    if fold is not None:
        _record_fold_elsewhere(grids, moves, fold.delta, *states, -1, tol)


def _record_fold_elsewhere(grids, moves, fold, last, beyond, direction, tol):
    """Find the fold at δ̄o = `fold` again from the held `last` and `beyond`, each solved on a
    grid centred the grids' lead further along (as `follow_tip` measures its states), and record
    how far its δ̄o moved in `moves` (`GridMoves.record_fold`): the error estimate's finer
    partner places its grids alike, and misses this term otherwise (`solver.estimate.FOLDS`).
    Where the two moved states lie on one side of the fold, up to BRACKETING more states a bracket's
    width apart, each on the branch (`along`). A measurement that fails records nothing."""
    try:
        first, second = [_moved_ahead(grids, state, direction, tol)
                         for state in (last, beyond)]
        step = beyond.tip - last.tip
        for extension in range(BRACKETING + 1):
            if first is None or second is None:
                return
            if _delta_rate(first) * _delta_rate(second) < 0.0:
                again = _root(grids, first, second, _delta_rate, tol)
                if again is not None:
                    moves.record_fold(abs(again.delta - fold))
                return
            if extension == BRACKETING:
                return
            # both before the fold on these grids: on past `second`; both past it: back
            onward = _delta_rate(second) < 0.0
            end = second if onward else first
            new = held_from(grids, end, end.tip + (step if onward else -step), tol,
                        contact_radius_rate(first, second))
            new = new if new is not None and along(end, new) else None
            first, second = (second, new) if onward else (new, first)
    except ContinuationError:
        return


def _fold(grids, moves, trace, last, beyond, direction, tol):
    """The `TipPath` ending at the fold of δ̄o between the last stable state `last` and
    `beyond`, the extremum of P̄ before it included."""
    fold = _root(grids, last, beyond, _delta_rate, tol)
    if fold is None:  # the last stable state stands in for it
        fold = last
    elif direction < 0:  # the jump-out, whose estimate adds the move (`solver.estimate.FOLDS`)
        _record_fold_elsewhere(grids, moves, fold.delta, last, beyond, direction, tol)
    _insert_roots(grids, trace, last, fold, direction, tol)
    radius = fold.contact[1]
    point = PathPoint(fold.delta, fold.surface.centre_gap(fold.w, fold.delta), fold.force,
                      disc_area(radius), radius)
    return TipPath(trace, point, beyond.w, beyond.surface, last)
