"""Equilibrium of a rigid height map over the pixel half-space with LJ 9-3 surface forces.

At a separation d (ε) the gap is h = d − z − w (z: the rigid map's heights in ε, the largest
touching first; w: the elastic surface's upward deflection, ε). An equilibrium is a stationary
point of the energy per pixel area, in Δγ,

    E(y) = ½|y|² + Σ φ̄(h),    w = S y,    S = (cG)^(1/2)   (`halfspace.PixelHalfSpace`),

whose gradient y + S p̄ vanishes where w = −cG p̄. `relax` descends to a local minimum (a stable
state) from a given state by Newton-CG with a backtracking line search; where the conjugate
gradients meet a direction of non-positive curvature, that direction is followed downhill with a
line search that expands while the energy falls, so an unstable start leaves the saddle: a warm
start from the previous separation stays on its branch while the branch is stable and falls to
another where it ends, which is a jump.
"""

from dataclasses import dataclass

import numpy as np

from fem_asperity.closed_forms.lj import (
    scaled_potential,
    scaled_traction,
    scaled_traction_slope,
)
from fem_asperity.plumbing.errors import ContinuationError

#: Gaps below this (ε) are refused by the energy (+inf, so the line search halves): the LJ
#: repulsion there, 8/3 h̄⁻⁹ > 5e6 Δγ/ε, is far beyond any load a separation step asks for.
GAP_FLOOR = 0.2
#: Converged where the largest residual of w + cG p̄, i.e. |S ∇E|, is below this (ε): 1e-9 ε
#: of deflection, far below the pixel's own error (the gap varies by ~0.1 ε across a pixel).
TOLERANCE = 1e-9
#: Newton steps allowed per separation before the state is reported unconverged (a jump across
#: a whole asperity takes tens; a step on a stable branch two to four).
MAX_STEPS = 300
#: Relative residual the conjugate gradients stop at (or √|∇E| once that is smaller): 0.5
#: took 1669 Newton steps and 16 s on a 128² rough map where 0.1 took 1197 and 14 s, and 0.01
#: 1050 steps but more products, 16 s (benchmarks/results/rough_surfaces.md has the map).
NEWTON_FORCING = 0.1
#: Conjugate-gradient iterations per Newton step: H = I − SDS is near 1 away from contact, and
#: its largest eigenvalues (~16 c G(0), in contact) are few.
CG_MAX = 400


@dataclass(frozen=True)
class Relaxed:
    """A state at one separation: `y` (the unknowns), `gap` (ε, on the map), `traction`
    (Δγ/ε), `steps` (Newton steps), `products` (Hessian products), `converged`."""

    y: np.ndarray
    gap: np.ndarray
    traction: np.ndarray
    steps: int
    products: int
    converged: bool


class LJMap:
    """The rigid map `heights` (ε) over `halfspace` (a `PixelHalfSpace` of the same shape)."""

    def __init__(self, heights, halfspace):
        self.heights = np.asarray(heights, dtype=float)
        self.halfspace = halfspace
        self.products = 0

    def gap(self, y, d):
        """h = d − z − S y on the map (ε)."""
        return d - self.heights - self.halfspace.on_map(self.halfspace.apply_root(y))

    def admissible(self, y, d):
        """Whether every gap of the state `y` at `d` is above GAP_FLOOR."""
        return bool(self.gap(y, d).min() >= GAP_FLOOR)

    def _energy(self, y, d):
        h = self.gap(y, d)
        if h.min() < GAP_FLOOR:
            return np.inf, np.zeros_like(y)
        gradient = y + self.halfspace.apply_root(self.halfspace.padded(scaled_traction(h)))
        return 0.5 * float(y.ravel() @ y.ravel()) + float(scaled_potential(h).sum()), gradient

    def _hessian_product(self, y, v, d):
        self.products += 1
        space = self.halfspace
        slope = scaled_traction_slope(self.gap(y, d))
        return v - space.apply_root(space.padded(slope * space.on_map(space.apply_root(v))))

    def relax(self, d, y0):
        """The stable state reached from `y0` at separation `d` (ε) → `Relaxed`."""
        products, y = self.products, y0
        energy, gradient = self._energy(y, d)
        if not np.isfinite(energy):
            raise ContinuationError(f"the start state at d = {d:g} eps has a gap below "
                                    f"{GAP_FLOOR} eps")
        converged = False
        step = 0
        while step < MAX_STEPS:
            step += 1
            direction, descent_only = self._newton_direction(y, gradient, d)
            y, energy, gradient = self._line_search(y, energy, gradient, direction, d,
                                                    expand=descent_only)
            if not descent_only and self._residual(gradient) <= TOLERANCE:
                converged = True
                break
        gap = self.gap(y, d)
        return Relaxed(y, gap, scaled_traction(gap), step, self.products - products, converged)

    def _residual(self, gradient):
        """max |S ∇E| (ε): how far w is from −cG p̄."""
        return float(np.abs(self.halfspace.apply_root(gradient)).max())

    def _newton_direction(self, y, gradient, d):
        """(s, unstable): s solves H s = −∇E by conjugate gradients (to a relative residual
        min(NEWTON_FORCING, √|∇E|)); where H shows a direction of non-positive curvature the
        state is not stable, and that direction (downhill), or −∇E if it comes first, is
        returned with unstable = True. The iteration runs on the vectors' Fourier coefficients,
        where S is diagonal: a product H v then takes two FFTs, not four."""
        slope = scaled_traction_slope(self.gap(y, d))
        space = self.halfspace
        root, weights = space.root, space.parseval

        def product(v):  # H v, in Fourier coefficients
            self.products += 1
            half = space.on_map(space.inverse(root * v))
            return v - root * space.forward(space.padded(slope * half))

        def dot(a, b):  # the real fields' Σ a b
            return float(np.sum(weights * (a.real * b.real + a.imag * b.imag)))

        b = space.forward(-gradient)
        norm_b = np.sqrt(dot(b, b))
        target = min(NEWTON_FORCING, np.sqrt(norm_b)) * norm_b
        x, r = np.zeros_like(b), b.copy()
        p, rr = r.copy(), dot(r, r)
        for _ in range(CG_MAX):
            hp = product(p)
            curvature = dot(p, hp)
            if curvature <= 0.0:
                if not x.any():
                    return -gradient, True
                return space.inverse(p if dot(p, b) >= 0.0 else -p), True
            alpha = rr / curvature
            x += alpha * p
            r -= alpha * hp
            rr_new = dot(r, r)
            if np.sqrt(rr_new) <= target:
                break
            p = r + (rr_new / rr) * p
            rr = rr_new
        return space.inverse(x), False

    def _line_search(self, y, energy, gradient, direction, d, *, expand):
        """The step along `direction`: the full step where it lowers the energy (or, within
        rounding of the energy, the gradient), halved until it does; where `expand`
        (unstable), doubled while the energy keeps falling (a jump moves the state far)."""
        slope = float(np.sum(gradient * direction))
        norm_g = float(np.sum(gradient * gradient))
        t = 1.0
        while t > 1e-14:
            e_new, g_new = self._energy(y + t * direction, d)
            rounding = 1e-12 * (abs(energy) + abs(e_new))
            if np.isfinite(e_new) and (e_new <= energy + 1e-4 * t * slope or (
                    abs(e_new - energy) <= rounding and np.sum(g_new * g_new) < norm_g)):
                break
            t *= 0.5
        else:
            raise ContinuationError(f"no descent at d = {d:g} eps: the state cannot be relaxed")
        while expand:
            e_far, g_far = self._energy(y + 2.0 * t * direction, d)
            if not e_far < e_new:
                break
            t, e_new, g_new = 2.0 * t, e_far, g_far
        return y + t * direction, e_new, g_new
