"""States with the crack tip held at a radius, δ̄o free: the equilibria `tip.follow_tip` steps
along.

The constraint is linear in (w, δ̄o): the node gaps, interpolated linearly, equal TIP_GAP at the
tip (as `landing.pinned`'s, which holds δ̄o fixed instead). Its bordered Newton matrix
(`newton.BorderedSystem`) also gives the rates d(x̄o, δ̄o, P̄)/d(tip) along the held states.
"""

from typing import NamedTuple

import numpy as np

from .continuation import DELTA_ROW, Linearisation
from .landing import pin_nodes
from .newton import PINNED, SINGLE, BorderedSystem, converged
from .surface import TIP_GAP, gap_keeping_step

#: Bound of dā_c/d(tip) that places a prediction's grid: unbounded where the contact vanishes.
RATE_CAP = 4.0
#: Newton iterations allowed for one held state.
MAX_NEWTON = 10
#: A step's change of (x̄o, δ̄o, P̄) may stray from the rates' prediction by this share of it
#: (`along`): where the tip turns back, another branch has the same tip.
ALONG = 0.5


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


class HeldSystem(BorderedSystem):
    """The Newton matrix [[∂g/∂w, ∂g/∂δ], [−eᵀ, 1]] of a held state (e: the pin's weights on its
    two nodes), factorised; where ∂g/∂w is not positive definite (a prediction, or past the
    fold) with the pin's penalty (`newton.PINNED`), positive definite where the pin holds the
    tip's unstable mode. Keeps ∂g/∂δ (`g_delta`) and ∂P̄/∂δ (`p_delta`) for `rates`."""

    def __init__(self, surface, w, delta, pin):
        self.g_delta, self.p_delta, slope = surface.sensitivities(w, delta)
        super().__init__(surface, slope, self.g_delta, np.append(-pin, 1.0),
                         factorisations=(SINGLE, PINNED), lu=np.float64, stability=False)

    def rates(self, dc_dtip):
        """d(x̄o, δ̄o, P̄)/d(tip) along the held equilibria, from the constraint's own rate
        dc_dtip."""
        dw, dd = self.solve(np.append(np.zeros(self.n), -dc_dtip))
        return np.array([dd - dw[0], dd,
                         -(self.g_delta @ dw) / self._surface.load_factor + self.p_delta * dd])


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
        system = HeldSystem(surface, w, delta, pin)
        dw, dd = system.solve(-np.append(g, c))
        if not (np.isfinite(dd) and np.all(np.isfinite(dw))):
            return None
        if abs(c) <= tol and converged(g, np.append(dw, dd), w, scale, tol):
            return Held(surface, w + dw, delta + dd, tip, system.rates(dc_dtip), iteration)
        alpha = gap_keeping_step(surface.gap(w, delta), dd - surface.interp @ dw)
        w, delta = w + alpha * dw, delta + alpha * dd
    return None


def as_held(surface, w, delta):
    """The equilibrium (w, δ̄o) itself as a `Held` at its own crack tip, its rates from the
    bordered matrix there: a path's first point is then the state it starts from to the bit
    (solved again, a landing moved by Newton's last increment, and the estimate's finer trace
    found no P̄max near it)."""
    tip = surface.crack_tip(w, delta)
    pin, _, dc_dtip = _constraint(surface, w, delta, tip)
    rates = HeldSystem(surface, w, delta, pin).rates(dc_dtip)
    return Held(surface, w, float(delta), tip, rates, 0)


def held_from(grids, state, tip, tol, radius_rate=1.0):
    """`held` at `tip` from the held `state`, its gaps moved along with the tip and δ̄o along its
    rate. Where `state`'s grid does not admit that prediction (its tip would lie on coarse
    elements), on a grid built for it: centred on its tip and on ā_c moved by `radius_rate`
    times the tip's shift (ā_c need not move with the tip: on the retraction it recedes
    faster), the gaps moved onto that grid's nodes."""
    shift = tip - state.tip
    delta = state.delta + state.rates[1] * shift
    surface = state.surface
    w = surface.translated(state.w, state.delta, shift, delta)
    if not grids.admits(surface, w, delta):
        radius = state.contact[1] + radius_rate * shift
        surface = grids.move(surface, w, delta, centre=(radius, tip))[0]
        w = state.surface.translated(state.w, state.delta, shift, delta, onto=surface)
    return held(surface, w, delta, tip, tol=tol)


def contact_radius_rate(first, second):
    """dā_c/d(tip) between the held states `first` and `second` (1 where the tip did not move),
    clamped to [0, RATE_CAP]."""
    shift = second.tip - first.tip
    rate = (second.contact[1] - first.contact[1]) / shift if shift else 1.0
    return float(min(max(rate, 0.0), RATE_CAP))


def along(state, new):
    """Whether the held `new` lies on the branch of the held `state`: the change of (x̄o, δ̄o,
    P̄) between them within ALONG of its prediction from `state`'s rates. Where the tip turns
    back along the branch (d(tip)/ds = 0: the rates grow without bound) Newton from the
    prediction can find a state of another branch with that tip, and the path would go on past
    the jump-out; with this check its steps shrink there and `follow` goes on."""
    predicted = state.rates * (new.tip - state.tip)
    return (np.linalg.norm(new.observed - state.observed - predicted)
            <= ALONG * np.linalg.norm(predicted))


def is_stable(state):
    """Whether the held `state` is stable under δ̄o control, decided as `follow` decides it
    (`continuation.Linearisation.stable`): where it is not although δ̄o still falls as the tip
    advances, another mode than the tip's has set in and `follow` goes on (not seen in the runs
    measured; the check costs a factorisation per point)."""
    return Linearisation(state.surface, state.w, state.delta, DELTA_ROW).stable
