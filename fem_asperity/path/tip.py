"""Stable branches in contact at large μ, followed in the crack tip's radius.

At large μ the stable branches in contact move the crack tip over many bands of the grids that
follow the edge: the retraction peels the contact while δ̄o and P̄ hardly move (`tip_direction`:
the retraction only, so far). Arc length in (x̄o, δ̄o, P̄) (`continuation.follow`) then takes
short steps, many of which Newton fails on (BEM `draft`, μ = 20: on the retraction 532 points
and 3084 Newton iterations from the jump-in's landing to the jump-out). Here the tip's radius is
the parameter instead: each state holds its tip at a given radius (the node gaps, interpolated
linearly, equal TIP_GAP there: a linear constraint, as in `landing.pinned`) with δ̄o free, and is
predicted by moving the last state's gaps along with the tip (`translated`: a peeling front
moves nearly unchanged), from which Newton converges in a few iterations (there: 157 points and
516 Newton iterations; P̄off and the jump-out's δ̄o within 4e-8 of the arc length's). δ̄o has
its fold, the jump-out, where dδ̄o/d(tip) = 0, and P̄ its extremum where dP̄/d(tip) = 0; both
are found by Brent's method on those derivatives (an equilibrium and its rates per evaluation).

A state stays on its grid while the grid fits it (`grids.EdgeGrids.fits`); then it is solved
again, its tip held, on the grid of its edges, and the change of P̄ recorded (`record_move`), as
`branches.follow_branch` does.
"""

from typing import NamedTuple

import numpy as np
from scipy.linalg import LinAlgError, cho_solve, lu_factor, lu_solve
from scipy.optimize import brentq

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
#: took at most EASY Newton iterations and halved after a failure, never beyond a band (then the
#: predicted state still lies in the grid's fine zone, `admits`), nor below SMALLEST bands (then
#: the path hands over to `continuation.follow`). Not pinned by a test.
FIRST_STEP, GROWTH, EASY, SMALLEST = 0.25, 1.5, 3, 1.0 / 64.0
#: Steps are shortened where ā_c changes by more than TIP_DA (√(Rε)), down to DA_FLOOR bands, no
#: further: the compressive contact can vanish within such a step while δ̄o and P̄ change
#: smoothly (BEM `draft`, μ = 20: ā_c fell from 1.9 to 0 as the tip receded by 0.17 √(Rε), 1.9
#: bands, near tip 5.5; held to da = 0.5 band, the steps fell below SMALLEST). TIP_DA is the
#: uniform grid's da (`TraceSettings`), not the settings' da, which grids that follow the edge
#: hold to a band (`presets.EDGE_STEP`) for `continuation.follow`: ā_c is no event of a branch
#: followed in its tip, and held to a band (ā_c recedes faster than the tip) the steps were 0.7
#: of a band. BEM `draft`, μ = 50 (one run each, this machine, with `_from`'s grid): 255.1 s →
#: 228.0 s, P̄off 1.2e-9 and the jump-out's δ̄o 6e-7 apart. Not pinned by a test.
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


def _from(grids, state, tip, tol):
    """`held` at `tip` from the held `state`, its gaps moved along with the tip and δ̄o along its
    rate. Where `state`'s grid does not admit that prediction (its tip would lie on coarse
    elements), on the grid of the prediction's edges, the gaps moved onto that grid's nodes."""
    shift = tip - state.tip
    delta = state.delta + state.rates[1] * shift
    surface = state.surface
    w = surface.translated(state.w, state.delta, shift, delta)
    if not grids.admits(surface, w, delta):
        surface = grids.move(surface, w, delta)[0]
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
    (x̄o, δ̄o, P̄), where the branch is followed in the tip: −1, receding, on a retraction (δ̄o
    rising) on grids that follow the edge with a crack tip beyond END bands; else 0. Not the
    approach after a jump-in: there the finer discretisation of the error estimate, followed in
    the tip, found P̄max at an end of its window (BEM `draft`, μ = 8: no estimate of P̄max,
    δ̄oc and ā_c; the path's first state, held at the landing's tip, was not the landing to the
    bit). With that state made the landing, and each move of the approach measured (the state
    moved before the step that leaves its band), every estimate was there, but the curve took
    longer at μ ≤ 10 (BEM `default` μ = 10 with its estimate 6.6 → 7.4 s) and gained at μ = 50
    only (`draft` 228 → 189 s; 132 s with the moves not measured): a grid per step, and a
    Newton solve per move."""
    if not (heading[1] > 0.0 and isinstance(grids, EdgeGrids)
            and surface.crack_tip(w, delta) > END * grids.band):
        return 0
    return -1


def follow_tip(grids, surface, w, delta, direction, settings, *, until, on_point=None):
    """Follow the stable branch from the equilibrium (w, δ̄o) on `surface`, the crack tip moving
    in `direction` (`tip_direction`), until `until(trace)` holds, δ̄o folds (the jump-out), or,
    receding, the tip nears the axis (END bands), or the steps fall below SMALLEST bands (then the
    caller goes on with `continuation.follow` from the last state). Steps are limited as
    `follow`'s: P̄ and ā_c change by at most settings.dp and TIP_DA between points.
    `on_point(trace)` after each point. Returns a `TipPath`."""
    band, tol = grids.band, settings.tol
    state = held(surface, w, delta, surface.crack_tip(w, delta), tol=tol)
    trace = Trace()

    def record(new):
        trace.append(new.surface, new.w, new.delta, True, new.force, new.contact,
                     new.tangent(direction))
        trace.newton_iterations += new.iterations
        if on_point is not None:
            on_point(trace)

    if state is None or not (state.before_fold and _stable(state)):
        return TipPath(trace, None, None, surface, None)
    record(state)
    step, past_extremum = FIRST_STEP * band, False
    while not until(trace):
        target = state.tip + direction * step
        if (direction < 0 and target < END * band) or step < SMALLEST * band:
            break
        new = _from(grids, state, target, tol)
        if new is not None and not _along(state, new):
            new = None
        if new is not None:
            by_force = abs(new.force - state.force) / settings.dp
            ratio = max(by_force, abs(new.contact[1] - state.contact[1]) / TIP_DA
                        if step > DA_FLOOR * band else 0.0)
            if ratio > 1.0:
                step *= 0.8 / ratio
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
        if stable != new.before_fold:  # another mode than the tip's: `follow` goes on
            break
        if not stable:
            return _fold(grids, trace, state, new, direction, tol)
        past_extremum = past_extremum or state.rates[2] * new.rates[2] < 0.0
        _insert_force_extremum(grids, trace, state, new, direction, tol)
        if not grids.fits(new.surface, new.w, new.delta):
            new = _moved(grids, new, tol, record=not past_extremum)
            if new is None:
                break
        state = new
        record(state)
        step = min(step * (GROWTH if state.iterations <= EASY else 1.0), band)
    return TipPath(trace, None, None, state.surface, state)


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


def _moved(grids, state, tol, *, record=True):
    """`state` solved again, its tip held, on the grid of its edges (None where Newton fails
    there). With `record` (a state its grid still resolved, `admits`, before P̄'s extremum, the
    retraction's one estimated force: beyond, next to the fold, grids disagree far more, BEM
    `draft` at μ = 8 by 1.9e-5 against 1.6e-7 before it) the change of P̄ at the state's δ̄o is
    recorded (`record_move`), as `branches.follow_branch` measures it: held at the same tip, P̄
    would also change with δ̄o along the branch.
    Not that of ā_c, recorded to bound the error of ā_c at P̄max, an approach's event: where the
    retraction's compressive contact vanishes ā_c moves by tenths of √(Rε) between grids (μ =
    20: 0.26) while P̄ changes by 1e-6."""
    surface, w = grids.move(state.surface, state.w, state.delta)
    moved = held(surface, w, state.delta, state.tip, tol=tol)
    if moved is not None and record:
        at_delta = correct(surface, moved.w, moved.delta, DELTA_ROW,
                           np.array([0.0, state.delta, 0.0]), 0.0, tol=tol)
        force = moved.force if at_delta is None else surface.force(at_delta[0], state.delta)
        grids.record_move(abs(force - state.force), 0.0)
    return moved


def _root(grids, first, second, rate, tol):
    """The held state between the held states `first` and `second` (solved from the nearest
    state known, `_from`) where the component `rate` of d(x̄o, δ̄o, P̄)/d(tip) vanishes (Brent
    from the two states' own rates, which bracket it), or None where Newton fails inside."""
    known = [first, second]

    def value(tip):
        for end in (first, second):
            if tip == end.tip:
                return end.rates[rate]
        near = min(known[1:], key=lambda s: abs(s.tip - tip))
        solved = _from(grids, near, tip, tol)
        if solved is None:
            raise _NoRoot
        known.append(solved)
        return solved.rates[rate]

    try:
        tip = brentq(value, *sorted((first.tip, second.tip)), xtol=XTOL)
    except _NoRoot:
        return None
    return min(known[2:], key=lambda s: abs(s.tip - tip), default=None)


class _NoRoot(Exception):
    """Newton failed inside a bracket."""


def _insert_force_extremum(grids, trace, state, new, direction, tol):
    """Append the extremum of P̄ between the held `state` and `new` where dP̄/d(tip) changes
    sign there."""
    if state.rates[2] * new.rates[2] >= 0.0:
        return
    extremum = _root(grids, state, new, 2, tol)
    if extremum is not None and extremum.before_fold:
        trace.append(extremum.surface, extremum.w, extremum.delta, True, extremum.force,
                     extremum.contact, extremum.tangent(direction))
        trace.newton_iterations += extremum.iterations


def _fold(grids, trace, last, beyond, direction, tol):
    """The `TipPath` ending at the fold of δ̄o between the last stable state `last` and
    `beyond`, the extremum of P̄ before it included."""
    fold = _root(grids, last, beyond, 1, tol)
    if fold is None:  # the last stable state stands in for it
        fold = last
    _insert_force_extremum(grids, trace, last, fold, direction, tol)
    radius = fold.contact[1]
    values = dict(x=fold.surface.centre_gap(fold.w, fold.delta), p=fold.force, a_c=radius,
                  area=0.0 if radius <= 0.0 else np.pi * radius**2)
    return TipPath(trace, (fold.delta, values), beyond.w, beyond.surface, last)
