"""Stable branches in contact at large μ, followed in the crack tip's radius.

At large μ the stable branches in contact move the crack tip over many bands of the grids that
follow the edge: the retraction peels the contact while δ̄o and P̄ hardly move, and the approach
spreads it (`tip_direction`: the approach only where the band is narrow). Arc length in (x̄o,
δ̄o, P̄) (`continuation.follow`) then takes short steps, many of which Newton fails on (BEM
`draft`, μ = 20: on the retraction 532 points and 3084 Newton iterations from the jump-in's
landing to the jump-out). Here the tip's radius is the parameter instead: each state holds its
tip at a given radius (the node gaps, interpolated linearly, equal TIP_GAP there: a linear
constraint, as in `landing.pinned`) with δ̄o free, and is predicted by moving the last state's
gaps along with the tip (`translated`: a peeling front moves nearly unchanged), from which
Newton converges in a few iterations (there: 157 points and 516 Newton iterations; P̄off and the
jump-out's δ̄o within 4e-8 of the arc length's). δ̄o has its fold, the jump-out, where
dδ̄o/d(tip) = 0, and P̄ its extremum where dP̄/d(tip) = 0; both are found by Brent's method on
those derivatives (an equilibrium and its rates per evaluation).

A prediction its grid does not admit is solved on a grid built for it (`_from`), so a step may
cross several bands. A state its grid no longer fits (`grids.EdgeGrids.fits`) is solved again,
its tip held, on the grid of its edges, and the change of P̄ recorded (`record_move`), as
`branches.follow_branch` does; so is every MEASURED_EVERY-th state, on a grid centred ahead of
it, for the error estimate's grid-placement term.
"""

from typing import NamedTuple

import numpy as np
from scipy.linalg import LinAlgError, cho_solve, lu_factor, lu_solve
from scipy.optimize import brentq

from ..plumbing.errors import ContinuationError
from .continuation import (
    DELTA_ROW,
    Linearisation,
    Trace,
    TraceSettings,
    cholesky_in_place,
    correct,
)
from .grids import EdgeGrids
from .landing import converged, pin_nodes, pin_penalty
from .surface import TIP_GAP, gap_keeping_step

#: The first step of the tip, in bands of the grids; a step is grown by GROWTH after a point that
#: took at most EASY Newton iterations and halved after a failure, never beyond LONGEST bands,
#: nor below SMALLEST bands (then the path hands over to `continuation.follow`). A prediction
#: beyond its grid's band is solved on a grid built for it (`_from`), so the steps are the
#: curve's own (P̄ and ā_c, below) rather than a band's: BEM `draft`, μ = 50, with the approach
#: followed in the tip, LONGEST 8 instead of 1 took the tip's steps from 0.7-0.9 of a band to
#: 4.5-6.8 (ā_c's limit); beyond 8 the P̄ and ā_c limits hold them anyway. Not pinned by a test.
FIRST_STEP, GROWTH, EASY, SMALLEST, LONGEST = 0.25, 1.5, 3, 1.0 / 64.0, 8.0
#: A step whose P̄ or ā_c changed by `ratio` of its limit (below) is retried SAFETY / ratio
#: times as long, and the next after it is at most that (as `continuation.follow`'s): grown by
#: GROWTH regardless, every other step went past ā_c's limit and was retried (BEM `draft`,
#: μ = 50: 584 predictions for 324 points, each on a grid of its own). Not pinned by a test.
SAFETY = 0.8
#: ā_c of a prediction is placed (`_from`) by its rate per tip of the last step, clamped to
#: [0, RATE_CAP]: where the compressive contact vanishes (the retraction) that rate is
#: unbounded, and a grid centred far off would not fit the state (it is then moved,
#: `_moved`). Not pinned by a test.
RATE_CAP = 4.0
#: Steps are shortened where ā_c changes by more than TIP_DA (√(Rε)), down to DA_FLOOR bands, no
#: further: the compressive contact can vanish within such a step while δ̄o and P̄ change
#: smoothly (BEM `draft`, μ = 20: ā_c fell from 1.9 to 0 as the tip receded by 0.17 √(Rε), 1.9
#: bands, near tip 5.5; held to da = 0.5 band, the steps fell below SMALLEST). TIP_DA is the
#: uniform grid's da (`TraceSettings`), not the settings' da, which grids that follow the edge
#: hold to a band (`presets.EDGE_STEP`) for `continuation.follow`: ā_c is no event of a branch
#: followed in its tip, and held to a band (ā_c recedes faster than the tip) the steps were 0.7
#: of a band (faster at the same events, measured in the commit that set it). Not pinned by a
#: test.
TIP_DA, DA_FLOOR = TraceSettings.da, 0.125
#: Newton iterations allowed for one state. Not pinned by a test.
MAX_NEWTON = 10
#: A retraction hands over to `continuation.follow` before the tip comes within END bands of the
#: axis, where a contact about to detach stays on the pre-contact grid (`EdgeGrids._edges`). Not
#: pinned by a test.
END = 3.0
#: A step's change of (x̄o, δ̄o, P̄) may differ from its prediction by the tip's rates by at most
#: ALONG of the prediction (`_along`), or it is retried shorter. Not pinned by a test.
ALONG = 0.5
#: Every MEASURED_EVERY-th state before P̄'s extremum that fits its grid is solved again on a grid
#: centred the grids' lead (`EdgeGrids.ahead`) further along (`_moved`), as a grid built while
#: the edges move is, and the change recorded: the grids are built for each prediction
#: (`_from`), so that the states fit them and few are moved, and those moves alone no longer
#: bound the grids' placement (BEM `draft`, μ = 30: none recorded). Not pinned by a test.
MEASURED_EVERY = 4
#: States a bracket's width apart that `_record_fold_elsewhere` adds, at most, to bracket the
#: fold again on the grids placed otherwise where both of its moved states lie on one side of
#: it. Not pinned by a test.
BRACKETING = 4
#: The approach after a jump-in is followed in the tip where TIP_DA spans at least
#: APPROACH_BANDS bands (`tip_direction`): there a tip's steps can be longer than the arc
#: length's, which its grid's band holds to a band.
APPROACH_BANDS = 2.0
#: Brent's tolerance on the tip's radius of an extremum of P̄ or δ̄o (√(Rε)): the values there are
#: quadratic in its error. Not pinned by a test.
XTOL = 1e-9


class Held(NamedTuple):
    """An equilibrium (w, δ̄o) with its crack tip held at `tip`, on `surface`: its force, contact,
    the derivatives d(x̄o, δ̄o, P̄)/d(tip) and the Newton iterations it took."""

    surface: object
    w: np.ndarray
    delta: float
    tip: float
    rates: np.ndarray
    iterations: int

    @property
    def force(self):
        return self.surface.force(self.w, self.delta)

    @property
    def contact(self):
        return self.surface.contact(self.w, self.delta)

    @property
    def observed(self):
        """(x̄o, δ̄o, P̄)."""
        return np.array([self.surface.centre_gap(self.w, self.delta), self.delta, self.force])

    @property
    def before_fold(self):
        """Whether δ̄o falls as the tip advances, as on a stable branch (the contact spreads as
        the sphere presses, peels as it is pulled)."""
        return self.rates[1] < 0.0

    def tangent(self, direction):
        """Unit tangent in (x̄o, δ̄o, P̄) with the tip moving in `direction` (±1)."""
        return direction * self.rates / np.linalg.norm(self.rates)


class _Bordered:
    """The Newton matrix [[∂g/∂w, ∂g/∂δ], [−eᵀ, 1]] of a held state (e: the pin's weights on its
    two nodes), solved by the single-precision Cholesky factor of ∂g/∂w and elimination of the
    border, refined once against the double-precision product. Where ∂g/∂w is not positive
    definite (a prediction, or past the fold) the pin's penalty ρ e eᵀ (`landing.pin_penalty`)
    is added to it and ρ e times the constraint row subtracted from the first rows,
    [[∂g/∂w + ρ e eᵀ, ∂g/∂δ − ρ e], [−eᵀ, 1]]: the same solutions, positive definite where the
    pin holds the tip's unstable mode (`landing.pinned`); else by double-precision LU."""

    def __init__(self, surface, w, delta, pin):
        self.g_delta, self.p_delta, slope = surface.sensitivities(w, delta)
        self.pin, n = pin, w.size
        self._product = lambda x: surface.tangent_product(slope, x)
        self.load_factor = surface.load_factor
        self._penalty, self._lu = 0.0, None
        self._cho = _cholesky_factor_or_none(surface.tangent_matrix(slope))
        if self._cho is None:
            nodes = np.flatnonzero(pin)
            self._penalty = pin_penalty(surface, nodes)
            jac = surface.tangent_matrix(slope)
            jac[np.ix_(nodes, nodes)] += self._penalty * np.outer(pin[nodes], pin[nodes])
            self._cho = _cholesky_factor_or_none(jac)
        if self._cho is None:
            matrix = np.empty((n + 1, n + 1))
            matrix[:n, :n] = surface.tangent_matrix(slope, np.float64)
            matrix[:n, n], matrix[n, :n], matrix[n, n] = self.g_delta, -pin, 1.0
            self._lu = lu_factor(matrix, overwrite_a=True, check_finite=False)
            return
        self._b = self._solve_j(self.g_delta - self._penalty * pin)

    def _solve_j(self, rhs):
        return cho_solve(self._cho, rhs.astype(np.float32), check_finite=False).astype(float)

    def _solve_factored(self, rhs_w, rhs_c):
        if self._lu is not None:
            step = lu_solve(self._lu, np.append(rhs_w, rhs_c), check_finite=False)
            return step[:-1], step[-1]
        a = self._solve_j(rhs_w - self._penalty * rhs_c * self.pin)
        dd = (rhs_c + self.pin @ a) / (1.0 + self.pin @ self._b)
        return a - dd * self._b, dd

    def solve(self, rhs_w, rhs_c):
        """(dw, dδ) with ∂g/∂w dw + ∂g/∂δ dδ = rhs_w and −eᵀdw + dδ = rhs_c."""
        dw, dd = self._solve_factored(rhs_w, rhs_c)
        if self._lu is None:
            fw, fc = self._solve_factored(rhs_w - self._product(dw) - dd * self.g_delta,
                                          rhs_c + self.pin @ dw - dd)
            dw, dd = dw + fw, dd + fc
        return dw, dd

    def rates(self, dc_dtip):
        """d(x̄o, δ̄o, P̄)/d(tip) along the held equilibria, the constraint's own rate dc_dtip."""
        dw, dd = self.solve(np.zeros_like(self.pin), -dc_dtip)
        return np.array([dd - dw[0], dd, -(self.g_delta @ dw) / self.load_factor
                         + self.p_delta * dd])


def _cholesky_factor_or_none(jac):
    """The single-precision Cholesky factor of `jac` (overwritten), or None where it is not
    positive definite."""
    try:
        return cholesky_in_place(jac)
    except LinAlgError:
        return None


def _constraint(surface, w, delta, tip):
    """(pin weights e over the nodes, c = eᵀ(gaps) − TIP_GAP, dc/d(tip) at fixed w, δ̄o)."""
    nodes, weights = pin_nodes(surface, tip)
    pin = np.zeros_like(w)
    pin[nodes] = weights
    gaps = delta + surface.node_profile[nodes] - w[nodes]
    slope = (gaps[1] - gaps[0]) / (surface.r_nodes[nodes[1]] - surface.r_nodes[nodes[0]])
    return pin, float(weights @ gaps) - TIP_GAP, slope


def held(surface, w, delta, tip, *, tol):
    """The equilibrium with its crack tip at `tip` (√(Rε)) near (w, δ̄o): Newton on (w, δ̄o), the
    gaps kept positive (`gap_keeping_step`), converged as `continuation.correct` (residual ≤ tol
    relative, last increment ≤ √tol relative); a `Held`, or None after MAX_NEWTON iterations."""
    w, delta = w.copy(), float(delta)
    scale = 1.0 + np.max(np.abs(surface.stiffness @ w))
    for iteration in range(1, MAX_NEWTON + 1):
        g = surface.residual(w, delta)
        pin, c, dc_dtip = _constraint(surface, w, delta, tip)
        matrix = _Bordered(surface, w, delta, pin)
        dw, dd = matrix.solve(-g, -c)
        if not (np.isfinite(dd) and np.all(np.isfinite(dw))):
            return None
        if abs(c) <= tol and converged(g, np.append(dw, dd), w, scale, tol):
            return Held(surface, w + dw, delta + dd, tip, matrix.rates(dc_dtip), iteration)
        alpha = gap_keeping_step(surface.gap(w, delta), dd - surface.interp @ dw)
        w, delta = w + alpha * dw, delta + alpha * dd
    return None


def _as_held(surface, w, delta):
    """The equilibrium (w, δ̄o) itself as a `Held` at its own crack tip, its rates from the
    bordered matrix there: a path's first point is then the state it starts from to the bit.
    Solved again with its tip held (`held`), the landing of a jump-in moved by Newton's last
    increment, and the error estimate's finer trace near P̄max, read at the landing, found that
    event at its window's end: no estimate of P̄max, δ̄oc and ā_c (BEM `draft`, μ = 8, the
    approach followed in the tip)."""
    tip = surface.crack_tip(w, delta)
    pin, _, dc_dtip = _constraint(surface, w, delta, tip)
    rates = _Bordered(surface, w, delta, pin).rates(dc_dtip)
    return Held(surface, w, float(delta), tip, rates, 0)


def _from(grids, state, tip, tol, radius_rate=1.0):
    """`held` at `tip` from the held `state`, its gaps moved along with the tip and δ̄o along its
    rate. Where `state`'s grid does not admit that prediction (its tip would lie on coarse
    elements), on a grid built for it: centred on its tip and on ā_c moved by `radius_rate`
    times the tip's shift (ā_c need not move with the tip: on the retraction at μ = 20 it
    recedes about twice as fast), the gaps moved onto that grid's nodes."""
    shift = tip - state.tip
    delta = state.delta + state.rates[1] * shift
    surface = state.surface
    w = surface.translated(state.w, state.delta, shift, delta)
    if not grids.admits(surface, w, delta):
        radius = state.contact[1] + radius_rate * shift
        surface = grids.move(surface, w, delta, centre=(radius, tip))[0]
        w = state.surface.translated(state.w, state.delta, shift, delta, onto=surface)
    return held(surface, w, delta, tip, tol=tol)


class TipPath(NamedTuple):
    """Result of `follow_tip`: the stable states traced (a `Trace`, force extremum included),
    the fold (δ̄o, values there) or None, the first state past it (on `surface`) or None, the
    surface of the last state, and the last stable `Held` (where the path handed over)."""

    trace: Trace
    fold: tuple | None
    beyond: np.ndarray | None
    surface: object
    last: Held


def tip_direction(grids, surface, w, delta, heading):
    """How the crack tip moves along the stable branch from (w, δ̄o) with the `heading` in
    (x̄o, δ̄o, P̄), where the branch is followed in the tip, on grids that follow the edge with a
    crack tip beyond END bands: −1, receding, on a retraction (δ̄o rising); +1, advancing, on an
    approach (δ̄o falling) where TIP_DA spans at least APPROACH_BANDS bands; else 0. Below, a
    grid per step of at most about a band costs more than the arc length's grids, which serve
    about 1.5 bands each (BEM `draft`, μ = 20, 1.2 bands: 177 grids against 121, and longer; at
    μ = 30, 2.7 bands, and μ = 50, 7.4, shorter: `benchmarks/large_mu.py` times them)."""
    if not (isinstance(grids, EdgeGrids) and surface.crack_tip(w, delta) > END * grids.band):
        return 0
    if heading[1] < 0.0:
        return 1 if TIP_DA >= APPROACH_BANDS * grids.band else 0
    return -1


def follow_tip(grids, surface, w, delta, direction, settings, *, until, on_point=None):
    """Follow the stable branch from the equilibrium (w, δ̄o) on `surface`, the crack tip moving
    in `direction` (`tip_direction`), until `until(trace)` holds, δ̄o folds (the jump-out), or,
    receding, the tip nears the axis (END bands), or the steps fall below SMALLEST bands (then the
    caller goes on with `continuation.follow` from the last state). Steps are limited as
    `follow`'s: P̄ and ā_c change by at most settings.dp and TIP_DA between points.
    `on_point(trace)` after each point. Returns a `TipPath`."""
    band, tol = grids.band, settings.tol
    state, trace = _as_held(surface, w, delta), Trace()

    def record(new):
        trace.append(new.surface, new.w, new.delta, True, new.force, new.contact,
                     new.tangent(direction))
        trace.newton_iterations += new.iterations
        if on_point is not None:
            on_point(trace)

    if not (state.before_fold and _stable(state)):
        return TipPath(trace, None, None, surface, None)
    record(state)
    step, past_extremum, radius_rate, longest = FIRST_STEP * band, False, 1.0, LONGEST * band
    while not until(trace):
        target = state.tip + direction * step
        if (direction < 0 and target < END * band) or step < SMALLEST * band:
            break
        new = _from(grids, state, target, tol, radius_rate)
        if new is not None and not _along(state, new):
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
                new = _moved(grids, new, tol, record=False)
        if new is None:
            step *= 0.5
            trace.rejected_steps += 1
            continue
        stable = _stable(new)
        if not (stable and new.before_fold) and step > band:
            # near the fold, steps of at most a band, as before LONGEST: from a longer one
            # Brent's bracket held states of another branch (BEM `draft`, μ = 50: a fold
            # 2.3e-5 below the last stable state's δ̄o), or the step went past the fold and
            # back (stable, δ̄o rising) and `follow` failed there
            step, longest = 0.5 * step, band
            trace.rejected_steps += 1
            continue
        if stable != new.before_fold:  # another mode than the tip's: `follow` goes on
            break
        if not stable:
            return _fold(grids, trace, state, new, direction, tol)
        past_extremum = past_extremum or state.rates[2] * new.rates[2] < 0.0
        _insert_roots(grids, trace, state, new, direction, tol,
                      (_force_rate, _centre_gap_above_contact) if direction > 0
                      else (_force_rate,))
        if not grids.fits(new.surface, new.w, new.delta):
            new = _moved(grids, new, tol, record=not past_extremum, radius=direction > 0)
            if new is None:
                break
        elif not past_extremum and len(trace.delta) % MEASURED_EVERY == 0:
            _moved_ahead(grids, new, direction, tol, radius=direction > 0)
        radius_rate = _radius_rate(state, new)
        state = new
        record(state)
        growth = GROWTH if state.iterations <= EASY else 1.0
        step = min(step * (growth if ratio * growth <= SAFETY else SAFETY / ratio), longest)
    return TipPath(trace, None, None, state.surface, state)


def _radius_rate(first, second):
    """dā_c/d(tip) between the held states `first` and `second` (1 where the tip did not move),
    clamped to [0, RATE_CAP]."""
    shift = second.tip - first.tip
    rate = (second.contact[1] - first.contact[1]) / shift if shift else 1.0
    return float(min(max(rate, 0.0), RATE_CAP))


def _along(state, new):
    """Whether the held `new` lies on the branch of the held `state`: the change of (x̄o, δ̄o,
    P̄) between them within ALONG of its prediction from `state`'s rates. Where the tip turns
    back along the branch (d(tip)/ds = 0: the rates grow without bound) Newton from the
    prediction can find a state of another branch with that tip: BEM `draft` at μ = 50 went on,
    every state stable, past the jump-out that `follow` finds (δ̄o = 81.484) to a fold at
    82.739; with this check its steps shrink there and `follow` goes on (81.484)."""
    predicted = state.rates * (new.tip - state.tip)
    return (np.linalg.norm(new.observed - state.observed - predicted)
            <= ALONG * np.linalg.norm(predicted))


def _stable(state):
    """Whether the held `state` is stable under δ̄o control, decided as `follow` decides it
    (`continuation.Linearisation.stable`): where it is not although δ̄o still falls as the tip
    advances, another mode than the tip's has set in and `follow` goes on (not seen in the runs
    measured; the check costs a factorisation per point)."""
    return Linearisation(state.surface, state.w, state.delta, DELTA_ROW).stable


def _moved(grids, state, tol, *, record=True, radius=False, centre=None):
    """`state` solved again, its tip held, on the grid of its edges (`EdgeGrids.move`, or
    centred on the (ā_c, tip) `centre`; None where Newton fails there). With `record` (a state
    before P̄'s extremum, the retraction's one estimated force: beyond, next to the fold, grids
    disagree far more, BEM `draft` at μ = 8 by 1.9e-5 against 1.6e-7 before it; and the
    approach's states) the change of P̄ at the state's δ̄o is recorded (`record_move`), as
    `branches.follow_branch` measures it: held at the same tip, P̄ would also change with δ̄o
    along the branch.
    With `radius` (the approach, whose ā_c at P̄max is an event) the change of ā_c too; not on
    the retraction: where its compressive contact vanishes ā_c moves by tenths of √(Rε) between
    grids (μ = 20: 0.26) while P̄ changes by 1e-6."""
    surface, w = grids.move(state.surface, state.w, state.delta, centre=centre)
    moved = held(surface, w, state.delta, state.tip, tol=tol)
    if moved is not None and record:
        at_delta = correct(surface, moved.w, moved.delta, DELTA_ROW,
                           np.array([0.0, state.delta, 0.0]), 0.0, tol=tol)
        w_at, d_at = (moved.w, moved.delta) if at_delta is None else (at_delta[0], state.delta)
        force, contact = surface.force(w_at, d_at), surface.contact(w_at, d_at)
        grids.record_move(abs(force - state.force),
                          abs(contact[1] - state.contact[1]) if radius else 0.0)
    return moved


def _moved_ahead(grids, state, direction, tol, **record):
    """`_moved` onto a grid centred the grids' lead (`EdgeGrids.ahead`) further along, in the
    tip's `direction`, than `state`'s edges: a placement the state's own grid does not have."""
    ahead = direction * grids.ahead * grids.band
    return _moved(grids, state, tol, centre=(state.contact[1] + ahead, state.tip + ahead),
                  **record)


def _root(grids, first, second, of, tol):
    """The held state between the held states `first` and `second` (solved from the nearest
    state known, `_from`) where of(state) vanishes (Brent from the two states' own values, which
    bracket it), or None where Newton fails inside."""
    known = [first, second]

    def value(tip):
        for end in (first, second):
            if tip == end.tip:
                return of(end)
        near = min(known[1:], key=lambda s: abs(s.tip - tip))
        solved = _from(grids, near, tip, tol, _radius_rate(first, second))
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
    initial contact too (`_centre_gap_above_contact`; on the retraction, where it is no event,
    x̄o passed 1 eleven times at μ = 50), which `curve._initial_contact` otherwise interpolates
    between points: between the tip's long steps that missed it by 1.1e-3 (BEM `draft`, μ =
    30, against an estimate of 3.1e-4 on the arc length), and the error estimate's finer trace,
    whose crossing is corrected from its first point past it, found none."""
    roots = [_root(grids, state, new, of, tol) for of in values if of(state) * of(new) < 0.0]
    for root in sorted((r for r in roots if r is not None and r.before_fold),
                       key=lambda r: abs(r.tip - state.tip)):
        trace.append(root.surface, root.w, root.delta, True, root.force, root.contact,
                     root.tangent(direction))
        trace.newton_iterations += root.iterations


def _delta_rate(held):
    """dδ̄o/d(tip): the fold of δ̄o where it vanishes."""
    return held.rates[1]


def record_fold_elsewhere(grids, surface, last, beyond, tol):
    """`_record_fold_elsewhere` for a retraction followed in arc length up to its fold
    (`branches.follow_branch`: at BEM μ = 46.9 and 50 the tip path handed over before the
    jump-out), its
    last stable state `last` and the first past it, `beyond`, each (w, δ̄o) on `surface`: the
    fold is found in the tip between them here too, so that both are found alike; nothing is
    recorded where they do not bracket a fold of δ̄o in the tip (the arc length's fold came
    from a parabola, or lies where the tip turns back)."""
    states = [_as_held(surface, w, delta) for w, delta in (last, beyond)]
    if not (min(state.tip for state in states) > END * grids.band
            and _delta_rate(states[0]) < 0.0 < _delta_rate(states[1])):
        return
    try:
        fold = _root(grids, *states, _delta_rate, tol)
    except ContinuationError:  # a diagnostic: it never costs the curve
        return
    if fold is not None:
        _record_fold_elsewhere(grids, fold.delta, *states, -1, tol)


def _record_fold_elsewhere(grids, fold, last, beyond, direction, tol):
    """Find the fold at δ̄o = `fold` again from the held `last` and `beyond`, each solved on a
    grid centred the grids' lead further along (as `follow_tip` measures its states), and record
    how far its δ̄o moved (`record_fold`): the error estimate's finer partner places its grids
    alike, and at BEM `draft`, μ = 8, δ̄o at the jump-out moved by 4.5e-7 between two placements
    of the grids, against its estimate of 4.1e-7 without this term (`solve.FOLDS`). Where the
    two moved states lie on one side of the fold, up to BRACKETING more states a bracket's
    width apart, each on the branch (`_along`). A measurement that fails records nothing."""
    try:
        first, second = [_moved_ahead(grids, state, direction, tol, record=False)
                         for state in (last, beyond)]
        step = beyond.tip - last.tip
        for extension in range(BRACKETING + 1):
            if first is None or second is None:
                return
            if _delta_rate(first) * _delta_rate(second) < 0.0:
                again = _root(grids, first, second, _delta_rate, tol)
                if again is not None:
                    grids.record_fold(abs(again.delta - fold))
                return
            if extension == BRACKETING:
                return
            # both before the fold on these grids: on past `second`; both past it: back
            onward = _delta_rate(second) < 0.0
            end = second if onward else first
            new = _from(grids, end, end.tip + (step if onward else -step), tol,
                        _radius_rate(first, second))
            new = new if new is not None and _along(end, new) else None
            first, second = (second, new) if onward else (new, first)
    except ContinuationError:
        return


def _fold(grids, trace, last, beyond, direction, tol):
    """The `TipPath` ending at the fold of δ̄o between the last stable state `last` and
    `beyond`, the extremum of P̄ before it included."""
    fold = _root(grids, last, beyond, _delta_rate, tol)
    if fold is None:  # the last stable state stands in for it
        fold = last
    elif direction < 0:  # the jump-out, whose estimate adds the move (`solve.FOLDS`)
        _record_fold_elsewhere(grids, fold.delta, last, beyond, direction, tol)
    _insert_roots(grids, trace, last, fold, direction, tol)
    radius = fold.contact[1]
    values = dict(x=fold.surface.centre_gap(fold.w, fold.delta), p=fold.force, a_c=radius,
                  area=0.0 if radius <= 0.0 else np.pi * radius**2)
    return TipPath(trace, (fold.delta, values), beyond.w, beyond.surface, last)
