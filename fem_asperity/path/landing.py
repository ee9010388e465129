"""Landing after a jump: the stable equilibrium the solid snaps to at fixed δ̄o, found downhill.

Past a fold of δ̄o no equilibrium is near; the solid snaps to a distant stable one. Starting from
a state beyond the energy barrier (a point of the unstable branch next to the fold), Newton on the
energy E(w; δ) (`LJSurface.energy`, whose gradient is the residual) at fixed δ finds it: where the
tangent is indefinite it is shifted by s·diag(S) until a Cholesky factorisation succeeds
(Levenberg), and a backtracking line search keeps every gap above a fraction of itself and never
lets E rise.
So the unstable branch between the folds need not be traced.

Where the contact's crack tip has far to travel (a jump out at large μ peels a contact of
hundreds of grid spacings), the descent crawls: each Newton step moves the tip by about an
element. `peel` then moves the tip along the valley the descent follows, the minima of E with
the tip held at a radius (`pinned`), in steps of many elements while E falls.
"""

from typing import NamedTuple

import numpy as np
from scipy.linalg import LinAlgError

from .continuation import ARMIJO
from .newton import PINNED, BorderedSystem, Cholesky, converged
from .surface import TIP_GAP, gap_keeping_step

#: Levenberg shift of an indefinite tangent (of the elastic diagonal): raised by SHIFT_RAISE from
#: SHIFT_FLOOR until Cholesky succeeds, then scaled per step as a trust region's. Not pinned.
SHIFT_RAISE, SHIFT_FLOOR, SHIFT_AFTER_SHORT, SHIFT_AFTER_FULL = 4.0, 1e-6, 2.0, 0.25
#: Inverse iterations for the most negative curvature, and that step's largest gap change (ε, a
#: fraction of the LJ well's width). Not pinned by a test.
CURVATURE_ITERATIONS, CURVATURE_STEP = 4, 0.5
#: Iterations of a landing beyond one per surface node (a snapping contact edge moves by about
#: one or two nodes per iteration): BASE_ITERATIONS + nodes. Not pinned by a test.
BASE_ITERATIONS = 300
#: Halvings of the energy line search (2^-30 of a step is below rounding of the energy). Not
#: pinned by a test.
MAX_HALVINGS = 30
#: The peel's waypoints: `pinned` to PEEL_TOL in PEEL_NEWTON iterations; failed steps halved down
#: to PEEL_SMALLEST grid spacings (the landing's descent converges at its own tol). Not pinned.
PEEL_TOL, PEEL_NEWTON, PEEL_SMALLEST = 1e-6, 10, 1.0 / 16.0

def _shifted_factor(jac, weight, shift, floor, unshifted_first):
    """(Cholesky factor of jac + s·diag(weight), s) for s = 0 if `unshifted_first` and that
    factorisation succeeds, else s raised SHIFT_RAISE times from max(shift, floor) until it does."""
    diagonal = np.arange(jac.shape[0])
    if unshifted_first:
        try:
            return Cholesky(jac.copy()), 0.0
        except LinAlgError:
            pass
    shift = max(shift, floor)
    while True:
        matrix = jac.copy()
        matrix[diagonal, diagonal] += shift * weight
        try:
            return Cholesky(matrix), shift
        except LinAlgError:
            shift = max(SHIFT_RAISE * shift, floor)


def _negative_curvature(surface, slope, solve, step, g, iterations=CURVATURE_ITERATIONS):
    """A step along the tangent's most negative curvature direction v, downhill (g·v ≤ 0), scaled
    so that no gap changes by more than CURVATURE_STEP (the line search shortens it); zero if the
    curvature found is not negative. v comes from inverse iteration with the shifted factor,
    started from the shifted Newton step. Without it the descent from a point next to a fold,
    where g is tiny, creeps (the energy falling by tiny amounts per iteration)."""
    v = step / np.linalg.norm(step)
    for _ in range(iterations):
        v = solve(v)
        v /= np.linalg.norm(v)
    if v @ surface.tangent_product(slope, v) >= 0.0:
        return np.zeros_like(step)
    if g @ v > 0.0:
        v = -v
    return CURVATURE_STEP * v / np.max(np.abs(surface.interp @ v))


class Landing(NamedTuple):
    """Result of `land`: the state w, the iterations spent, and whether it is a stable
    equilibrium (else the last iterate)."""

    w: np.ndarray
    iterations: int
    converged: bool


def land(surface, w, delta, *, tol=1e-9, max_iterations=None, resolved=None):
    """Stable equilibrium at fixed `delta` reached downhill in energy from the state `w`.

    tol: as `continuation.correct` (residual ≤ tol relative, last increment ≤ √tol relative).
    max_iterations: default BASE_ITERATIONS + the number of surface nodes.
    resolved: callable(w), whether `surface` still resolves the iterate; the descent stops at
        the first iterate of a line-searched step that it does not (None: never).
    Returns a `Landing`: with `converged`, w has a positive definite tangent; without, w is the
    last iterate (lower in energy than the start) after `max_iterations`, or the first that
    `surface` does not resolve.
    """
    if max_iterations is None:
        max_iterations = BASE_ITERATIONS + w.size
    w = w.copy()
    scale = 1.0 + np.max(np.abs(surface.stiffness @ w))
    # The shift is relative to the elastic diagonal: with axisymmetric weights the surface
    # stiffness spans many decades (large at large r), and a shift relative to its mean stalls
    # the descent near a fold.
    weight = np.diag(surface.stiffness).astype(np.float32)
    start = 0.0  # where the raise of the next shift begins
    # The unshifted factorisation is tried only after an unshifted or a full step: after a
    # shortened shifted step it nearly always fails.
    unshifted_first = True
    for iteration in range(1, max_iterations + 1):
        g = surface.residual(w, delta)
        slope = surface.sensitivities(w, delta)[2]
        jac = surface.tangent_matrix(slope)
        factor, shift = _shifted_factor(jac, weight, start, SHIFT_FLOOR, unshifted_first)

        solve = factor.solve
        step = solve(-g)
        step += solve(-g - surface.tangent_product(slope, step) - shift * weight * step)
        if shift > 0.0:
            step += _negative_curvature(surface, slope, solve, step, g)
        if shift == 0.0 and converged(g, step, w, scale, tol):
            return Landing(w + step, iteration, True)
        alpha = gap_keeping_step(surface.gap(w, delta), -(surface.interp @ step))
        energy, descent = surface.energy(w, delta), float(g @ step)
        for _ in range(MAX_HALVINGS):
            w_try = w + alpha * step
            if surface.energy(w_try, delta) <= energy + ARMIJO * alpha * descent:
                break
            if shift == 0.0 and (np.linalg.norm(surface.residual(w_try, delta))
                                 < np.linalg.norm(g)):
                break  # at a minimum E is flat to rounding: Newton's residual decides
            alpha *= 0.5
        w = w_try
        if resolved is not None and not resolved(w):
            return Landing(w, iteration, False)
        unshifted_first = shift == 0.0 or alpha == 1.0
        if shift > 0.0:
            start = shift * (SHIFT_AFTER_SHORT if alpha < 1.0 else SHIFT_AFTER_FULL)
    return Landing(w, max_iterations, False)


class Pinned(NamedTuple):
    """Result of `pinned`: the state w, the Newton iterations, whether it converged, and the
    multiplier λ (the point load, E* = 1 units, that holds the tip)."""

    w: np.ndarray
    iterations: int
    converged: bool
    multiplier: float


def pin_nodes(surface, tip):
    """(the two nodes around the radius `tip`, their linear interpolation weights)."""
    r = surface.r_nodes
    i = int(np.clip(np.searchsorted(r, tip) - 1, 0, r.size - 2))
    t = (tip - r[i]) / (r[i + 1] - r[i])
    return np.array([i, i + 1]), np.array([1.0 - t, t])


def pinned(surface, w, delta, tip, *, tol=PEEL_TOL, max_iterations=PEEL_NEWTON):
    """The minimum of E(w; δ) near `w` with the crack tip held at the radius `tip` (√(Rε)):
    the node gaps, interpolated linearly, equal TIP_GAP there (`SurfaceShape.crack_tip`).

    The constraint eᵀw = c is linear in w. Newton on the bordered system [J e; eᵀ 0], the pin's
    load λ its unknown, solved with the single-precision Cholesky factor of J + ρ e eᵀ
    (`newton.PINNED`): two solves per iteration. Converged when the residual with the pin's
    load, g + λe, is ≤ tol relative and the last increment ≤ √tol relative. Returns a
    `Pinned`; not converged where the penalised tangent is not positive definite (the pin
    leaves an unstable direction) or after `max_iterations`."""
    nodes, weights = pin_nodes(surface, tip)
    held_value = weights @ (delta + surface.node_profile[nodes]) - TIP_GAP  # of eᵀw
    pin = np.zeros_like(w)
    pin[nodes] = weights
    border = np.append(pin, 0.0)
    scale = 1.0 + np.max(np.abs(surface.stiffness @ w))
    w = w.copy()
    for iteration in range(1, max_iterations + 1):
        g = surface.residual(w, delta)
        system = BorderedSystem(surface, surface.sensitivities(w, delta)[2], pin, border,
                                factorisations=(PINNED,), lu=None, refinements=0,
                                stability=False)
        if system.failed:
            return Pinned(w, iteration, False, np.nan)
        step, multiplier = system.solve(np.append(-g, held_value - pin @ w))
        if converged(g + multiplier * pin, step, w, scale, tol):
            return Pinned(w + step, iteration, True, multiplier)
        w = w + gap_keeping_step(delta + surface.node_profile - w, -step) * step
        if not np.all(np.isfinite(w)):
            break
    return Pinned(w, max_iterations, False, np.nan)


class Peel(NamedTuple):
    """Result of `peel`: the state w (lower in energy than the start, or the start), the Newton
    iterations, and whether it stopped because the next state no longer fitted."""

    w: np.ndarray
    iterations: int
    left: bool


def peel(surface, w, delta, direction, *, h, max_step, tips, fits):
    """The state reached from (w, δ) by moving its crack tip in `direction` (±1) along the
    minima of E with the tip held (`pinned`), while E falls.

    h: the grid's spacing at the tip (√(Rε)); max_step: the first and largest step; tips:
    (lowest, highest) tip the surface resolves; fits(w): whether it resolves the state. Each
    step starts from the gaps of the last state moved by the step (`translated`: a peeling
    front moves nearly unchanged; at the μ = 20 fold Newton converged from there in 2
    iterations for steps up to 0.08 √(Rε), and in 4-7 as the neck shrank, where a secant
    predictor in w, blurring the steep front, needed 5 and failed beyond ~15 grid spacings);
    a step that fails to converge is halved, one that converges doubled (up to max_step).
    Stops at the first step that raises E (a minimum of E along the path lies behind: `land`
    finds it), below PEEL_SMALLEST × h, at a tip ≤ 0 (also a start without a crack tip),
    or at the end of `tips` or where the next state does not fit (left=True). The first state
    is the pinned one at the start's own tip, accepted only if E does not rise, so on one
    surface E never rises from `w`."""
    tip = surface.crack_tip(w, delta)
    if tip <= 0.0:
        return Peel(w, 0, False)
    held = pinned(surface, w, delta, tip)
    iterations = held.iterations
    energy = surface.energy(held.w, delta) if held.converged else np.inf
    if energy > surface.energy(w, delta):
        return Peel(w, iterations, False)
    w, step = held.w, max_step
    while step >= PEEL_SMALLEST * h:
        target = min(max(tip + direction * step, tips[0]), tips[1])
        if target <= 0.0:
            break
        if target == tip:
            return Peel(w, iterations, True)
        held = pinned(surface, surface.translated(w, delta, target - tip), delta, target)
        iterations += held.iterations
        if not held.converged:
            step = 0.5 * abs(target - tip)  # the step taken, if `tips` cut it
            continue
        if not fits(held.w):
            return Peel(w, iterations, True)
        next_energy = surface.energy(held.w, delta)
        if next_energy >= energy:
            break
        w, tip, energy = held.w, target, next_energy
        step = min(2.0 * step, max_step)
    return Peel(w, iterations, False)
