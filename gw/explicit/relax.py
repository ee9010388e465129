"""Equilibrium of a rigid height map over the pixel half-space with LJ 9-3 surface forces.

At a separation d (ε) the gap is h = d − z − w (z: the rigid map's heights in ε, the largest
touching first; w: the elastic surface's upward deflection, ε). An equilibrium is a stationary
point of the energy per pixel area, in Δγ,

    E(y) = ½|y|² + Σ φ̄(h),    w = S y,    S = (cG)^(1/2)   (`halfspace.PixelHalfSpace`),

whose gradient y + S p̄ vanishes where w = −cG p̄. States and gradients are kept as Fourier
coefficients, where S is diagonal. `relax` descends to a local minimum (a stable
state) from a given state by Newton-CG with a backtracking line search; where the conjugate
gradients meet a direction of non-positive curvature, that direction is followed downhill with a
line search that expands while the energy falls, so an unstable start leaves the saddle: a warm
start from the previous separation stays on its branch while the branch is stable and falls to
another where it ends, which is a jump.
"""

import ctypes
import functools
import platform
from dataclasses import dataclass

import numpy as np
from scipy.linalg import blas

from fem_asperity.closed_forms.lj import (
    scaled_potential,
    scaled_traction,
    scaled_traction_slope,
)
from fem_asperity.plumbing.errors import ContinuationError

#: Gaps below this (ε) are refused by the energy (+inf, so the line search halves): the LJ
#: repulsion there, 8/3 h̄⁻⁹ > 5e6 Δγ/ε, is far beyond any load a separation step asks for.
GAP_FLOOR = 0.2
#: Converged where the largest residual |S ∇E| is below this, in ε of deflection (methods.md §14);
#: test_whole_surface.py pins the paths' agreement with a thousand times less.
TOLERANCE = 1e-6
#: Newton steps allowed per separation before the state is reported unconverged (a jump across
#: a whole asperity takes tens; a step on a stable branch two to four).
MAX_STEPS = 300
#: Relative residual the conjugate gradients stop at (or √|∇E| once that is smaller): the
#: cheapest measured (methods.md §14). Not pinned by a test.
NEWTON_FORCING = 0.1
#: BLAS threads while a map is solved (`whole`): one is as fast for the CG's dot products and
#: updates (methods.md §14). Not pinned by a test.
BLAS_THREADS = 1
#: `keep_freed_memory` takes blocks below MMAP_BELOW bytes from the heap and keeps its top up to
#: KEEP_FREED bytes: freed fields are not faulted in again (methods.md §14). Not pinned by a test.
MMAP_BELOW = 32 * 2**20
KEEP_FREED = 256 * 2**20
#: Conjugate-gradient iterations per Newton step: H = I − SDS is near 1 away from contact, and
#: its largest eigenvalues (~16 c G(0), in contact) are few.
CG_MAX = 400


@functools.cache
def keep_freed_memory():
    """Where the C library is glibc, keep freed memory for reuse (MMAP_BELOW, KEEP_FREED,
    through mallopt): for the rest of the process, every allocation of it, so a library call
    never does this on its own; elsewhere nothing → whether it was set."""
    if platform.libc_ver()[0] != "glibc":
        return False
    try:
        mallopt = ctypes.CDLL(None).mallopt
    except (OSError, AttributeError):
        return False
    m_trim_threshold, m_mmap_threshold = -1, -3  # glibc's malloc.h
    return bool(mallopt(m_mmap_threshold, MMAP_BELOW)) and bool(
        mallopt(m_trim_threshold, KEEP_FREED))


@dataclass(frozen=True)
class Relaxed:
    """A state at one separation: `y` (the unknowns, as the Fourier coefficients of y on the
    half-space's grid), `gap` (ε, on the map), `traction` (Δγ/ε), `steps` (Newton steps),
    `products` (Hessian products), `converged`."""

    y: np.ndarray
    gap: np.ndarray
    traction: np.ndarray
    steps: int
    products: int
    converged: bool


@dataclass(frozen=True)
class _Point:
    """A state evaluated at one separation: `y` (coefficients), `gap`, `energy` (Δγ per pixel
    area), `gradient` (the coefficients of ∇E)."""

    y: np.ndarray
    gap: np.ndarray
    energy: float
    gradient: np.ndarray


class LJMap:
    """The rigid map `heights` (ε) over `halfspace` (a `PixelHalfSpace` of the same shape).
    States are kept as Fourier coefficients: S is diagonal there, so an evaluation of the
    energy and its gradient takes two FFTs (the gap's and the traction's) and a Newton step's
    right-hand side none."""

    def __init__(self, heights, halfspace):
        self.heights = np.asarray(heights, dtype=float)
        self.halfspace = halfspace
        self.products = 0
        self._weights = halfspace.parseval
        # The conjugate gradients run on u = √w ŷ (w: `parseval`), where Σ a b of the fields is
        # the plain complex dot product (BLAS, no temporaries); S is folded into the scaling.
        scale = np.sqrt(self._weights)
        self._scale = scale
        self._root_in = (halfspace.root / scale).astype(np.float32)
        self._root_out = (halfspace.root * scale).astype(np.float32)

    def rest(self):
        """The undeformed state (w = 0)."""
        return np.zeros_like(self.halfspace.root, dtype=complex)

    def gap(self, y, d):
        """h = d − z − S y on the map (ε)."""
        return d - self.heights - self.halfspace.to_map(self.halfspace.root * y)

    def admissible(self, y, d):
        """Whether every gap of the state `y` at `d` is above GAP_FLOOR."""
        return bool(self.gap(y, d).min() >= GAP_FLOOR)

    def _dot(self, a, b):
        """Σ a b of the real fields with coefficients a, b."""
        return float(np.vdot(self._weights * a, b).real)

    def _evaluate(self, y, d):
        """The `_Point` of `y` at `d` (energy +inf where a gap is below the floor)."""
        h = self.gap(y, d)
        if h.min() < GAP_FLOOR:
            return _Point(y, h, np.inf, None)
        space = self.halfspace
        energy = 0.5 * self._dot(y, y) + float(scaled_potential(h).sum())
        return _Point(y, h, energy, y + space.root * space.from_map(scaled_traction(h)))

    def relax(self, d, y0):
        """The stable state reached from `y0` (coefficients) at separation `d` (ε) →
        `Relaxed`."""
        products = self.products
        point = self._evaluate(y0, d)
        if not np.isfinite(point.energy):
            raise ContinuationError(f"the start state at d = {d:g} eps has a gap below "
                                    f"{GAP_FLOOR} eps")
        converged = False
        step = 0
        while step < MAX_STEPS:
            step += 1
            direction, descent_only = self._newton_direction(point)
            point = self._line_search(point, direction, d, expand=descent_only)
            if not descent_only and self._residual(point.gradient) <= TOLERANCE:
                converged = True
                break
        return Relaxed(point.y, point.gap, scaled_traction(point.gap), step,
                       self.products - products, converged)

    def _residual(self, gradient):
        """max |S ∇E| (ε): how far w is from −cG p̄."""
        return float(np.abs(self.halfspace.inverse(self.halfspace.root * gradient)).max())

    def _newton_direction(self, point):
        """(s, unstable): s solves H s = −∇E by conjugate gradients (to a relative residual
        min(NEWTON_FORCING, √|∇E|)); where H shows a direction of non-positive curvature the
        state is not stable, and that direction (downhill), or −∇E if it comes first, is
        returned with unstable = True. The conjugate gradients run in single precision (a
        product H v takes two FFTs; the vectors' updates are BLAS calls in place, half the
        memory traffic of double's): the direction only needs the relative residual above,
        far coarser than single precision's 1e-7, and a Hessian off by ~1e-7 does not move the
        converged state, which the double-precision gradient decides."""
        space = self.halfspace
        shape = point.gradient.shape
        root_in, root_out = self._root_in, self._root_out
        slope = scaled_traction_slope(point.gap).astype(np.float32)

        def product(u):  # H v for u = √w v, flat
            self.products += 1
            half = space.to_map(u.reshape(shape) * root_in)
            half *= slope
            out = space.from_map(half)
            out *= root_out
            return np.subtract(u, out.ravel(), out=out.ravel())

        def dot(a, b):
            return float(blas.cdotc(a, b).real)

        b = (-point.gradient * self._scale).astype(np.complex64).ravel()
        norm_b = np.sqrt(dot(b, b))
        target = min(NEWTON_FORCING, np.sqrt(norm_b)) * norm_b
        x, r = np.zeros_like(b), b.copy()
        p, rr = r.copy(), dot(r, r)
        for _ in range(CG_MAX):
            hp = product(p)
            curvature = dot(p, hp)
            if curvature <= 0.0:
                if not x.any():
                    return -point.gradient, True
                return (p if dot(p, b) >= 0.0 else -p).reshape(shape) / self._scale, True
            alpha = rr / curvature
            x = blas.caxpy(p, x, a=alpha)  # in place for contiguous complex64, as here
            r = blas.caxpy(hp, r, a=-alpha)
            rr_new = dot(r, r)
            if np.sqrt(rr_new) <= target:
                break
            p *= np.float32(rr_new / rr)
            p += r
            rr = rr_new
        return x.reshape(shape) / self._scale, False

    def _line_search(self, point, direction, d, *, expand):
        """The point along `direction`: the full step where it lowers the energy (or, within
        rounding of the energy, the gradient), halved until it does; where `expand`
        (unstable), doubled while the energy keeps falling (a jump moves the state far)."""
        slope = self._dot(point.gradient, direction)
        norm_g = self._dot(point.gradient, point.gradient)
        t = 1.0
        while t > 1e-14:
            new = self._evaluate(point.y + t * direction, d)
            rounding = 1e-12 * (abs(point.energy) + abs(new.energy))
            if np.isfinite(new.energy) and (
                    new.energy <= point.energy + 1e-4 * t * slope
                    or (abs(new.energy - point.energy) <= rounding
                        and self._dot(new.gradient, new.gradient) < norm_g)):
                break
            t *= 0.5
        else:
            raise ContinuationError(f"no descent at d = {d:g} eps: the state cannot be relaxed")
        while expand:
            far = self._evaluate(point.y + 2.0 * t * direction, d)
            if not far.energy < new.energy:
                break
            t, new = 2.0 * t, far
        return new
