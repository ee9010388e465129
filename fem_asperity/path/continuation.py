"""Pseudo-arc-length continuation of the surface problem: the whole equilibrium curve, both
branches.

The curve is traced in the space of three observables, the centre gap x̄o = δ − w(0), the sphere
position δ̄o and the force P̄: each new point satisfies t·(o − o_k) = Δs, with o = (x̄o, δ̄o, P̄),
o_k the last point and t the last unit tangent in that space. The bordered Jacobian stays regular
at the folds of δ̄o (jump-in, jump-out), so the unstable branch between them is traced like any
other part; including P̄ keeps the steps honest where x̄o and δ̄o hardly move while the contact
neck shrinks (large μ, before jump-out).
"""

from dataclasses import dataclass, field

import numpy as np

from ..plumbing.errors import ContinuationError
from .elimination import relax_edge
from .newton import BorderedSystem, edge_block
from .surface import gap_keeping_step

#: Newton's line search: sufficient decrease of the merit by ARMIJO × the step's fraction, at
#: most MAX_HALVINGS halvings (methods.md §13). Not pinned by a test.
ARMIJO, MAX_HALVINGS = 1e-4, 20
#: An iteration that keeps more than SLOW_PROGRESS of the merit counts as slow (`patience`).
#: Not pinned by a test.
SLOW_PROGRESS = 0.9
#: Step control of `follow` as solve_ivp's: the first step, the safety factor, the floor of the
#: change ratio, the growth and shrink limits (docs/methods.md §3). Not pinned by a test.
FIRST_STEP, SAFETY, MIN_RATIO, MAX_FACTOR, MIN_FACTOR = 0.1, 0.8, 1e-3, 2.0, 0.2
#: A step Newton failed on is halved and caps the next ones at FAILED_CAP of itself, the cap
#: relaxing by CAP_RELAXATION per accepted point. Not pinned by a test.
NEWTON_FAILURE_FACTOR, FAILED_CAP, CAP_RELAXATION = 0.5, 0.7, 1.5
#: The change ratio of a point its grid does not admit: retried shorter. Not pinned by a test.
INADMISSIBLE_RATIO = 2.0
#: Heading in (x̄o, δ̄o, P̄) of an approach from far away (gap and δ̄o decreasing).
APPROACH = np.array([-1.0, -1.0, 0.0])
#: The row of (x̄o, δ̄o, P̄) that holds δ̄o (`correct_at_delta`; any regular border gives the
#: same stability flag, that of ∂g/∂w).
DELTA_ROW = np.array([0.0, 1.0, 0.0])


@dataclass(frozen=True)
class TraceSettings:
    """Step control of the continuation (lengths in ε, forces in 2πRΔγ, radii in √(Rε)).

    dp, da: largest change of P̄ and of ā_c between neighbouring points.
    turn: largest turn of the unit tangent in (x̄o, δ̄o, P̄) between points, in radians (keeps
        points dense at folds and extremes, which are then located by parabolas through three).
    x_start: centre gap of the first point (the force there is ≈ −(4/3) x_start⁻²).
    p_end: the approach ends once the force is this compressive.
    tol: Newton tolerance on the relative residual; the last increment (ε) must be ≤ √tol, so
        with quadratic convergence the state is accurate to about tol.
    max_newton, target_newton: Newton iterations allowed per point, and the count above which
        the next step is shortened.
    patience: a step is abandoned (and retried shorter) after this many Newton iterations in a
        row that cut the residual by less than 10%.
    front: half-width (√(Rε)) of the window about the crack tip in which the predictor moves
        the gap profile along with the tip (`_shift_front`); None: the tangent alone.
    """

    dp: float = 0.05
    da: float = 0.1
    turn: float = 0.1
    ds_max: float = 2.0
    ds_min: float = 1e-7
    x_start: float = 40.0
    p_end: float = 1.0
    tol: float = 1e-9
    max_newton: int = 10
    patience: int = 3
    target_newton: int = 4
    max_points: int = 20000
    front: float | None = None


_POINT_FIELDS = ("delta", "x", "p", "area", "a_c", "stable", "tangents", "states", "nodes")


@dataclass
class Trace:
    """Raw continuation output, one entry per converged point, ordered along the curve: the
    observables, stability, unit tangent, state w and the radial nodes w is given on (those of
    the surface it was solved on)."""

    delta: list = field(default_factory=list)
    x: list = field(default_factory=list)
    p: list = field(default_factory=list)
    area: list = field(default_factory=list)
    a_c: list = field(default_factory=list)
    stable: list = field(default_factory=list)
    tangents: list = field(default_factory=list)
    states: list = field(default_factory=list)
    nodes: list = field(default_factory=list)
    newton_iterations: int = 0
    rejected_steps: int = 0

    def append(self, surface, w, delta, stable, force, contact, tangent):
        """Record the state (w, δ) with its force P̄, contact (Ā, ā_c) and unit tangent
        d(x̄o, δ̄o, P̄)/ds, computed by the caller."""
        self.insert(len(self.delta), surface, w, delta, stable, force, contact, tangent)

    def extend(self, other):
        """Append the points of the Trace `other` and add its counters."""
        for name in _POINT_FIELDS:
            getattr(self, name).extend(getattr(other, name))
        self.newton_iterations += other.newton_iterations
        self.rejected_steps += other.rejected_steps

    def drop_last(self):
        """Remove the last point."""
        for name in _POINT_FIELDS:
            getattr(self, name).pop()

    def insert(self, index, surface, w, delta, stable, force, contact, tangent):
        """As `append`, at position `index` along the curve."""
        area, radius = contact
        values = (delta, surface.centre_gap(w, delta), force, area, radius, stable, tangent,
                  w.copy(), surface.r_nodes)
        for name, value in zip(_POINT_FIELDS, values):
            getattr(self, name).insert(index, value)


def _observables(surface, w, delta):
    return np.array([surface.centre_gap(w, delta), delta, surface.force(w, delta)])


def _observable_gradients(surface, g_delta, p_delta):
    """∂(x̄o, δ̄o, P̄)/∂(w, δ̄o) at a state, (3, n + 1)."""
    n = g_delta.size
    gradients = np.zeros((3, n + 1))
    gradients[0, 0], gradients[0, n] = -1.0, 1.0  # x = δ − w0
    gradients[1, n] = 1.0
    gradients[2, :n], gradients[2, n] = -g_delta / surface.load_factor, p_delta
    return gradients


class Linearisation(BorderedSystem):
    """The arc length's Newton matrix [[∂g/∂w, ∂g/∂δ], [row · ∂o/∂(w, δ)]] at (w, δ), factorised
    on the edge block about the crack tip (`newton.edge_block`), J in single precision, else in
    double, else LU (`newton.BorderedSystem`); `stable` is the state's stability under δ̄o
    control, whatever the row (docs/methods.md, "The bordered Newton system")."""

    def __init__(self, surface, w, delta, row):
        g_delta, p_delta, slope = surface.sensitivities(w, delta)
        self.gradients = _observable_gradients(surface, g_delta, p_delta)
        super().__init__(surface, slope, g_delta, row @ self.gradients,
                         block=edge_block(surface, w, delta))

    def moved_to(self, surface, w, delta, row):
        """`BorderedSystem.relocated` to the state (w, δ) and its `row`: None where it must be
        factorised afresh."""
        g_delta, p_delta, slope = surface.sensitivities(w, delta)
        gradients = _observable_gradients(surface, g_delta, p_delta)
        moved = self.relocated(surface, slope, g_delta, row @ gradients,
                               surface.crack_tip(w, delta))
        if moved is not None:
            moved.gradients = gradients
        return moved

    def tangent(self):
        """Unit tangent (dw/ds, dδ/ds, do/ds), |do/ds| = 1, with row · do/ds > 0."""
        rhs = np.zeros(self.n + 1)
        rhs[-1] = 1.0
        dw, dd = self.solve(rhs)
        observed = self.gradients @ np.append(dw, dd)
        norm = np.linalg.norm(observed)
        return dw / norm, dd / norm, observed / norm


def correct(surface, w, delta, direction, anchor, ds, *, tol=1e-9, max_newton=10, patience=None,
            linear=None):
    """Newton with a gap-preserving, residual-decreasing line search on the bordered system.

    Solves g(w, δ) = 0 with direction·(o(w, δ) − anchor) = ds for the observables
    o = (x̄o, δ̄o, P̄). Each iterate reuses the last `Linearisation` (or `linear`, one of a
    nearby state), moved there (`Linearisation.moved_to`), with refined solves; where the
    refinement does not converge, or the crack tip left its edge block, it factorises afresh
    (chord steps with an old matrix, unrefined, overshoot into the repulsive wall where the
    contact front has moved).
    patience: give up after this many consecutive iterations that cut the residual by < 10%
    (None: only after max_newton); a continuation step is cheaper to retry shorter.
    Returns (w, δ, iterations, the `Linearisation` of the last iteration) or None. That
    linearisation's products lie within the last increment (≤ √tol relative) of the solution;
    if it was moved, its bulk factorisation is an earlier iterate's (or `linear`'s), and its
    stability flag is decided with that factorisation and the exact product at the last iterate
    (`Linearisation.stable`).
    """
    w, delta = w.copy(), float(delta)
    scale, slow = None, 0
    for iteration in range(1, max_newton + 1):
        g = surface.residual(w, delta)
        c = direction @ (_observables(surface, w, delta) - anchor) - ds
        rhs = -np.append(g, c)
        if linear is not None:
            linear = linear.moved_to(surface, w, delta, direction)
        if linear is not None:
            dw, dd = linear.solve(rhs)
        if linear is None or not linear.converged:
            linear = Linearisation(surface, w, delta, direction)
            dw, dd = linear.solve(rhs)
        if not (np.isfinite(dd) and np.all(np.isfinite(dw))):
            return None  # a single-precision factorisation of a singular matrix
        alpha = gap_keeping_step(surface.gap(w, delta), dd - surface.interp @ dw)
        if scale is None:
            scale = 1.0 + np.max(np.abs(surface.stiffness @ w))
        merit = np.linalg.norm(g) / scale + abs(c)
        for _ in range(MAX_HALVINGS):
            w_try, d_try = w + alpha * dw, delta + alpha * dd
            g_try = surface.residual(w_try, d_try)
            c_try = direction @ (_observables(surface, w_try, d_try) - anchor) - ds
            merit_try = np.linalg.norm(g_try) / scale + abs(c_try)
            if merit_try <= (1.0 - ARMIJO * alpha) * merit:
                break
            alpha *= 0.5
        w, delta = w_try, d_try
        increment = alpha * max(np.max(np.abs(dw)), abs(dd))
        converged = (increment <= np.sqrt(tol) * (1.0 + np.max(np.abs(w)))
                     and np.max(np.abs(g_try)) <= tol * scale)
        if converged:
            return w, delta, iteration, linear
        slow = slow + 1 if merit_try > SLOW_PROGRESS * merit else 0
        if patience is not None and slow >= patience:
            return None
    return None


def correct_at_delta(surface, w, delta, *, tol=1e-9):
    """`correct` holding δ̄o at `delta` (from w, which need not be there): (w, δ, iterations,
    linearisation) of the equilibrium at that δ̄o, or None."""
    return correct(surface, w, delta, DELTA_ROW, np.array([0.0, delta, 0.0]), 0.0, tol=tol)


def _predict(surface, trace_so_far, tangent, ds, front=None):
    """Predicted state (w, δ) a step ds along the curve from its last point: the tangent plus the
    curvature that passes through the point before (with the unit tangent at the last point, its
    position σ = t·(o_prev − o_last) along the curve): fewer Newton iterations than the tangent
    alone. With a `front` window, the crack tip's profile is moved along (`_shift_front`)."""
    tr = trace_so_far
    dw, dd, t = tangent
    w, delta = tr.states[-1], tr.delta[-1]
    w_guess, d_guess = w + ds * dw, delta + ds * dd
    if len(tr.delta) > 1:
        back = np.array([tr.x[-2] - tr.x[-1], tr.delta[-2] - delta, tr.p[-2] - tr.p[-1]])
        sigma, curvature = back @ t, ds * ds / (back @ back)
        w_guess += curvature * (tr.states[-2] - w - sigma * dw)
        d_guess += curvature * (tr.delta[-2] - delta - sigma * dd)
        if front is not None:
            w_guess = _shift_front(surface, tr, w_guess, d_guess, ds / np.linalg.norm(back),
                                   front)
    return w_guess, d_guess


def _shift_front(surface, trace_so_far, w_guess, d_guess, fraction, window):
    """w_guess with the last point's gap profile, moved by the crack tip's travel from the point
    before times `fraction`, blended in within `window` of the tip (fading out over a second
    `window`). At large μ the tip is a front a few elements wide, which the tangent's linear
    blend of two positions misplaces. Pinned by
    test_tracking.py::test_predictor_moves_the_crack_tip_front_along."""
    tr, r = trace_so_far, surface.r_nodes
    tips = [surface.crack_tip(tr.states[k], tr.delta[k]) for k in (-2, -1)]
    if min(tips) <= 0.0 or max(tips) >= r[-1]:
        return w_guess
    shift = fraction * (tips[1] - tips[0])
    moved = surface.translated(tr.states[-1], tr.delta[-1], shift, d_guess)
    weight = np.clip(2.0 - np.abs(r - tips[1] - 0.5 * shift) / window, 0.0, 1.0)
    return w_guess + weight * (moved - w_guess)


def start_state(surface, settings):
    """(w, δ, Newton iterations) of the equilibrium at the centre gap x̄o = settings.x_start."""
    x = settings.x_start
    start = correct(surface, np.zeros(surface.r_nodes.size), x, np.array([1.0, 0.0, 0.0]),
                    np.array([x, 0.0, 0.0]), 0.0, tol=settings.tol)
    if start is None:
        raise ContinuationError(f"no equilibrium found at the start x = {x}")
    return start[:3]


def follow(surface, w, delta, heading, settings, *, until, stop_at_fold=False, on_point=None,
           admissible=None):
    """Trace the equilibrium curve from the equilibrium (w, δ), setting off in the direction with
    heading · d(x̄o, δ̄o, P̄)/ds > 0, until `until(trace)` holds at a stable point or, with
    `stop_at_fold`, up to the first unstable point (kept as the trace's last point).

    `on_point(trace)` is called after each accepted point. `admissible(w, δ)`: a converged point
    for which it is False is retried with a shorter step, like one that turned too far (the
    surface resolves it only near where it was built, `grids.EdgeGrids.admits`).
    Raises ContinuationError if the step falls below ds_min, the point budget runs out or the
    path runs off beyond 2 x_start.
    """
    s = settings
    result = Trace()
    row = np.asarray(heading, dtype=float) / np.linalg.norm(heading)
    linear = Linearisation(surface, w, delta, row)
    tangent = linear.tangent()
    result.append(surface, w, delta, linear.stable, surface.force(w, delta),
                  surface.contact(w, delta), tangent[2])
    ds, ds_cap = FIRST_STEP, np.inf
    while not (result.stable[-1] and until(result)):
        if stop_at_fold and not result.stable[-1]:
            break
        if len(result.delta) >= s.max_points:
            raise ContinuationError(f"point budget of {s.max_points} exhausted at δ = {delta:.6g}")
        if result.x[-1] > 2.0 * s.x_start:
            raise ContinuationError(f"the path turned back to separation x = {result.x[-1]:.6g}")
        t = tangent[2]
        anchor = np.array([result.x[-1], delta, result.p[-1]])
        w_guess, d_guess = _predict(surface, result, tangent, ds, s.front)
        step = None  # a prediction through the sphere (a gap ≤ 0) is retried shorter
        if np.min(surface.gap(w_guess, d_guess)) > 0.0:
            w_guess = relax_edge(surface, w_guess, d_guess,
                                 limit=np.max(np.abs(w_guess - result.states[-1])))
            step = correct(surface, w_guess, d_guess, row, anchor, ds * (row @ t),
                           tol=s.tol, max_newton=s.max_newton, patience=s.patience,
                           linear=linear)
        if step is not None:
            # The tangent (and stability) from the last Newton matrix, whose point is within
            # √tol of the new one: one factorisation per point fewer (the events move by < 1e-6).
            w_new, d_new, its, linear = step
            result.newton_iterations += its
            tangent_new = linear.tangent()
            turned = tangent_new[2][1] * t[1] <= 0.0
            if (linear.moved and (turned or not linear.converged)
                    or linear.stable != result.stable[-1]):
                # δ̄o turned (a fold, where stability changes), or the flag says stability
                # changed: the flag must be this point's, not an earlier iterate's (a stale flag
                # before the fold leaves no root of dδ̄o/ds to find, and the parabola misplaces
                # the fold; at μ = 50, BEM `draft`, an iterate 2.5e-3 ε away was unstable, the
                # point stable, and the curve ended in a fold where δ̄o did not turn).
                linear = Linearisation(surface, w_new, d_new, row)
                tangent_new = linear.tangent()
            turn = np.arccos(np.clip(tangent_new[2] @ t, -1.0, 1.0))
            force, contact = surface.force(w_new, d_new), surface.contact(w_new, d_new)
            dp, da = abs(force - result.p[-1]), abs(contact[1] - result.a_c[-1])
            ratio = max(dp / s.dp, da / s.da, turn / s.turn, MIN_RATIO)
            if admissible is not None and not admissible(w_new, d_new):
                ratio = max(ratio, INADMISSIBLE_RATIO)
            if ratio <= 1.0 or ds <= s.ds_min:
                w, delta, row, tangent = w_new, d_new, t, tangent_new
                result.append(surface, w, delta, linear.stable, force, contact, tangent[2])
                if on_point is not None:
                    on_point(result)
                effort = min(1.0, s.target_newton / its)
                ds_cap *= CAP_RELAXATION
                ds = min(ds * min(MAX_FACTOR, SAFETY / ratio) * effort, s.ds_max, ds_cap)
                continue
            ds_next = ds * max(MIN_FACTOR, SAFETY / ratio)
        else:
            ds_next, ds_cap = NEWTON_FAILURE_FACTOR * ds, FAILED_CAP * ds
        result.rejected_steps += 1
        if ds <= s.ds_min:
            raise ContinuationError(f"Newton failed at the smallest step near δ = {delta:.6g}")
        ds = max(ds_next, s.ds_min)
    return result


def trace(surface, settings=TraceSettings(), progress=None):
    """Trace the whole equilibrium curve, unstable branches included, from x̄o = x_start (δ
    decreasing) until P̄ ≥ p_end at a stable point.

    `progress(fraction)` is called after each accepted point. Raises ContinuationError as
    `follow`.
    """
    w, delta, its = start_state(surface, settings)
    report = ((lambda tr: progress(approach_fraction(tr.x[-1], tr.p[-1], settings)))
              if progress else None)
    result = follow(surface, w, delta, APPROACH, settings,
                    until=lambda tr: tr.p[-1] >= settings.p_end, on_point=report)
    result.newton_iterations += its
    return result


def approach_fraction(x, p, settings):
    """Progress of an approach at the centre gap x̄o and force P̄: half for the gap closing from
    x_start to 1 (log scale), half for P̄ rising from −1 to p_end once in contact (where x̄o hardly
    moves; at large μ that is most of the approach)."""
    closing = min(1.0, np.log(settings.x_start / max(x, 1e-3)) / np.log(settings.x_start))
    loading = min(1.0, max(0.0, (p + 1.0) / (settings.p_end + 1.0))) if closing >= 1.0 else 0.0
    return 0.5 * (closing + loading)
