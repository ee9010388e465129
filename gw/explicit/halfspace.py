"""The elastic half-space seen from a square grid of pixels, by FFT: w = −c G p̄.

Units: displacements w and gaps in ε, tractions p̄ in Δγ/ε (> 0 compressive), lateral lengths in
pixels. The compliance number c = Δγ a / (π E* ε²) (a: the pixel in metres) carries all the
physics; for caps of radius R, with a in √(Rε), c = μ^(3/2) a/π. G is the Boussinesq kernel
1/ρ integrated over a pixel of uniform traction:

- free (a patch on an infinite half-space): G is Love's pixel kernel, evaluated at the pixel
  centres of a grid twice the map's size in each direction, so that its circular convolution is
  the linear one for tractions that vanish outside the map (zero padding);
- periodic: the continuous kernel's transform 2π/|q| (q in 1/pixel) on the map's own grid, the
  mean displacement held at zero (the mean gap is then the control).

The minimisation works in y = (cG)^(−1/2) w, where the elastic energy is ½|y|² (a preconditioned
variable: the Hessian I − S D S of the LJ energy in y has its spectrum near 1 away from contact),
so the half-space needs only S = (cG)^(1/2) in Fourier space.
"""

from dataclasses import dataclass

import numpy as np
import scipy.fft

from fem_asperity.plumbing.checks import positive

#: Threads per FFT: all cores for one solve; a pool of solves sets 1 in each worker
#: (`validation.rough_explicit`), as the sweeps hold BLAS to one thread per curve.
FFT_WORKERS = -1


def love_kernel(offset_x, offset_y):
    """∫∫ dx'dy'/√((x − x')² + (y − y')²) over a unit pixel centred at 0, at the point
    (offset_x, offset_y) in pixels (Love 1929): 4 asinh(1) = 3.5255 at its centre, → 1/ρ far."""
    x, y = np.asarray(offset_x, dtype=float), np.asarray(offset_y, dtype=float)

    def primitive(u, v):  # ∫₀^u∫₀^v du dv/√(u² + v²): odd in u and in v
        u_abs, v_abs = np.abs(u), np.abs(v)
        with np.errstate(divide="ignore", invalid="ignore"):
            rho = np.hypot(u_abs, v_abs)
            both = u_abs * np.log((v_abs + rho) / u_abs) + v_abs * np.log((u_abs + rho) / v_abs)
        return np.sign(u) * np.sign(v) * np.where((u_abs > 0.0) & (v_abs > 0.0), both, 0.0)

    return (primitive(x + 0.5, y + 0.5) - primitive(x - 0.5, y + 0.5)
            - primitive(x + 0.5, y - 0.5) + primitive(x - 0.5, y - 0.5))


def _offsets(n):
    """Signed pixel offsets of a circular grid of n points: 0, 1, …, −1."""
    k = np.arange(n)
    return np.where(k <= n // 2, k, k - n).astype(float)


@dataclass(frozen=True, eq=False)
class PixelHalfSpace:
    """S = (cG)^(1/2) on the map's pixels (`shape`), free or `periodic`, compliance number
    `compliance` (c, dimensionless). `grid` is the shape the unknowns live on: the map's own
    (periodic) or twice it (free)."""

    shape: tuple
    compliance: float
    periodic: bool
    grid: tuple
    root: np.ndarray  # S in Fourier space (rfft2 layout of `grid`)

    @classmethod
    def build(cls, shape, *, compliance, periodic):
        """The half-space under a map of `shape` pixels with compliance number `compliance`."""
        positive("compliance", compliance)
        shape = tuple(int(n) for n in shape)
        if periodic:
            grid = shape
            qx = 2.0 * np.pi * scipy.fft.fftfreq(grid[0])[:, None]
            qy = 2.0 * np.pi * scipy.fft.rfftfreq(grid[1])[None, :]
            q = np.hypot(qx, qy)
            q[0, 0] = np.inf  # the mean displacement is held at zero
            transform = 2.0 * np.pi / q
        else:
            grid = (2 * shape[0], 2 * shape[1])
            kernel = love_kernel(_offsets(grid[0])[:, None], _offsets(grid[1])[None, :])
            transform = scipy.fft.rfft2(kernel).real
            # The circulant of a positive, decreasing kernel is positive definite; a negative
            # mode would be a discretisation defect, not physics.
            if not np.all(transform > 0.0):
                raise ArithmeticError("the padded Boussinesq kernel has a non-positive mode")
        root = np.sqrt(compliance * transform)
        return cls(shape, float(compliance), bool(periodic), grid, root)

    def apply_root(self, v):
        """S v for v on `grid`."""
        return self.inverse(self.forward(v) * self.root)

    def forward(self, v):
        """The Fourier coefficients (rfft2) of a field on `grid`."""
        return scipy.fft.rfft2(v, workers=FFT_WORKERS)

    def inverse(self, coefficients):
        """The field on `grid` of Fourier coefficients (irfft2)."""
        return scipy.fft.irfft2(coefficients, s=self.grid, workers=FFT_WORKERS)

    def from_map(self, field):
        """The Fourier coefficients of a field on the map placed on `grid` (zero outside it):
        `forward` of the zero-padded field, without transforming the padding's zero rows (a
        quarter of the work on a free map). Single precision in, single precision out."""
        if self.periodic:
            return self.forward(field)
        rows = scipy.fft.rfft(field, n=self.grid[1], axis=1, workers=FFT_WORKERS)
        return scipy.fft.fft(rows, n=self.grid[0], axis=0, workers=FFT_WORKERS)

    def to_map(self, coefficients):
        """The map's pixels of the field with these coefficients: `inverse(·)` cut to the map,
        without transforming the rows that would be cut off."""
        if self.periodic:
            return self.inverse(coefficients)
        rows = scipy.fft.ifft(coefficients, axis=0, workers=FFT_WORKERS)[: self.shape[0]]
        field = scipy.fft.irfft(rows, n=self.grid[1], axis=1, workers=FFT_WORKERS)
        return field[:, : self.shape[1]]

    @property
    def parseval(self):
        """Weights w with Σ a b = Σ w Re(â* b̂) for real fields a, b on `grid` (rfft2 keeps
        half the last axis: the columns it drops are the conjugates of those it doubles)."""
        n1 = self.grid[1]
        column = np.full(n1 // 2 + 1, 2.0)
        column[0] = 1.0
        if n1 % 2 == 0:
            column[-1] = 1.0
        return column[None, :] / (self.grid[0] * n1)

    def deflection(self, traction):
        """w = −c G p̄ on the map (ε) for a traction p̄ on the map (Δγ/ε)."""
        return -self.to_map(self.from_map(traction) * self.root**2)
