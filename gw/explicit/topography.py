"""Rigid height maps for the explicit rough-surface problem, and their GW summit statistics.

A `Topography` is a map of a rigid surface's heights z (m) on square pixels, the largest heights
touching first: a single spherical cap of radius R is z = −r²/(2R) near its top. heights[i, j]
is the height at x = i·pixel, y = j·pixel, so the map covers nx·pixel × ny·pixel and, if
`periodic`, repeats with that period.

Three sources: `gaussian_caps` (the GW surface made explicit: equal caps at Gaussian heights),
`self_affine` (a Gaussian self-affine surface by Fourier filtering) and `read_topography` (.npy,
or any instrument format SurfaceTopography reads).

Two ways to the GW parameters σ_s, R, η (and ω = σ_s/σ, σRη as `gw.surface` takes them):
`summit_statistics` counts the summits on the pixels and measures their curvature there;
`spectral_summit_statistics` predicts them from the spectral moments m0, m2, m4 (Nayak 1971,
McCool 1986). For a Gaussian surface both see the same discrete map, but the first depends on
the pixel (a finer pixel finds more and sharper summits) and the second rests on asymptotic
formulas for a broad spectrum: they agree for smooth, well-sampled surfaces and part on
self-affine ones.
"""

import numbers
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import scipy.fft

from fem_asperity.plumbing.checks import in_range, positive
from fem_asperity.plumbing.errors import InputError

#: A map needs at least this many pixels in each direction (a summit needs its 3×3
#: neighbourhood, the spectral moments a few wavelengths).
MIN_PIXELS = 8
#: `gaussian_caps` puts its floor this many σ below the lowest summit (plus the margin its
#: docstring gives): no cap is cut within reach of a contact.
FLOOR_SIGMAS = 20.0
#: McCool's constant in σ_s² = (1 − 0.8968/α) m0.
MCCOOL_SUMMIT_HEIGHT = 0.8968
#: Nayak's mean summit curvature (8/3)√(m4/π) for a broad spectrum: R = 0.375 √(π/m4).
NAYAK_RADIUS = 0.375

_PIP = "pip install SurfaceTopography"


def _number(name, value, unit=""):
    """A single real number > 0."""
    if np.ndim(value) != 0:
        raise InputError(f"{name} must be a single number; got an array of shape "
                         f"{np.shape(value)}")
    return positive(name, value, unit)


def _whole(name, value, lo):
    """A whole number ≥ lo (no bools, no floats)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < lo:
        raise InputError(f"{name} must be a whole number >= {lo}; got {value!r}")
    return int(value)


def _flag(name, value):
    if not isinstance(value, (bool, np.bool_)):
        raise InputError(f"{name} must be True or False; got {value!r}")
    return bool(value)


def _height_map(heights):
    """`heights` as a read-only float copy, or InputError: a 2-D map of at least MIN_PIXELS
    pixels in each direction, every height finite."""
    try:
        kind = np.asarray(heights).dtype.kind
    except (TypeError, ValueError):
        kind = None
    if kind not in ("i", "u", "f"):
        raise InputError(f"heights must be an array of real numbers; got {type(heights).__name__}"
                         + (f" of dtype {np.asarray(heights).dtype}" if kind else ""))
    z = np.array(heights, dtype=float)
    if z.size == 0:
        raise InputError(f"heights is empty (shape {z.shape})")
    if z.ndim != 2:
        raise InputError(f"heights must be a 2-D map; got a {z.ndim}-D array of shape {z.shape}")
    if min(z.shape) < MIN_PIXELS:
        raise InputError(f"heights must have at least {MIN_PIXELS} pixels in each direction; "
                         f"got shape {z.shape}")
    bad = ~np.isfinite(z)
    if bad.any():
        i, j = np.argwhere(bad)[0]
        raise InputError(f"heights must be finite; {int(bad.sum())} of {z.size} pixels are NaN "
                         f"or inf, the first at pixel ({i}, {j}): {z[i, j]}")
    z.setflags(write=False)
    return z


@dataclass(frozen=True, eq=False)
class Topography:
    """A rigid surface's height map: `heights` (m, 2-D, at least MIN_PIXELS = 8 pixels in each
    direction, finite; the largest touch first), `pixel` (m, square), `periodic` (whether the
    map repeats) and `source` (how it was made, or which file). `heights` is kept as a read-only
    float copy."""

    heights: np.ndarray
    pixel: float
    periodic: bool = False
    source: str = "array"

    def __post_init__(self):
        object.__setattr__(self, "heights", _height_map(self.heights))
        object.__setattr__(self, "pixel", _number("pixel", self.pixel, "m"))
        object.__setattr__(self, "periodic", _flag("periodic", self.periodic))
        if not isinstance(self.source, str):
            raise InputError(f"source must be a string; got {self.source!r}")

    @property
    def shape(self):
        """(nx, ny) pixels."""
        return self.heights.shape

    @property
    def size(self):
        """(Lx, Ly) in m."""
        return self.shape[0] * self.pixel, self.shape[1] * self.pixel

    @property
    def area(self):
        """Lx·Ly in m²."""
        return self.size[0] * self.size[1]


@dataclass(frozen=True, eq=False)
class Caps:
    """The caps of `gaussian_caps`: apex positions `x`, `y` (m, in [0, L)) and heights `z`
    (m), and their common `radius` (m)."""

    x: np.ndarray
    y: np.ndarray
    z: np.ndarray
    radius: float


def _window(centre, reach, n, pixel, periodic):
    """Pixel indices and their offsets from `centre` (m) along one axis: those within `reach`
    of it, each pixel once (if periodic: wrapped into the map, the offset to the nearest image)."""
    c = int(round(centre / pixel))
    half = int(np.ceil(reach / pixel))
    if not periodic:
        k = np.arange(max(c - half, 0), min(c + half, n - 1) + 1)
        return k, k * pixel - centre
    k = np.arange(max(c - half, c - n // 2), min(c + half, c - n // 2 + n - 1) + 1)
    side = n * pixel
    return k % n, (k * pixel - centre + 0.5 * side) % side - 0.5 * side


def gaussian_caps(*, n, pixel, radius, sigma, density, seed=0, periodic=True):
    """The GW surface made explicit: an n×n map (`pixel`, m) of spherical caps, paraboloids
    z_i − r²/(2R) of one `radius` R (m), with summit heights z_i drawn from a Gaussian of mean 0
    and standard deviation `sigma` (m, ≥ 0), at uniformly random positions with the areal
    `density` η (1/m²): round(η L²) caps, at least 1, at most one per pixel. `seed` (whole
    number) seeds numpy's default generator.

    The map is the highest of the caps (with their periodic images if `periodic`: the nearest
    image of each) and of a flat floor at

        floor = min z_i − 20 σ − s²/(8R),   s = L/√(number of caps) the mean cap spacing,

    so every cap stands at least 20σ above the floor (no contact reaches it) and reaches at
    least s/2 from its apex before the floor cuts it, whatever σ. Between the caps the map is
    the floor. Returns (`Topography`, `Caps`).
    """
    n = _whole("n", n, MIN_PIXELS)
    pixel = _number("pixel", pixel, "m")
    radius = _number("radius", radius, "m")
    if np.ndim(sigma) != 0:
        raise InputError(f"sigma must be a single number; got an array of shape {np.shape(sigma)}")
    sigma = in_range("sigma", sigma, 0.0, np.inf, closed_lo=True, unit="m")
    density = _number("density", density, "1/m^2")
    seed = _whole("seed", seed, 0)
    periodic = _flag("periodic", periodic)
    side = n * pixel
    expected = density * side**2
    if not expected < n * n + 0.5:
        raise InputError(f"density must give at most one cap per pixel ({n * n} on {n}x{n}); "
                         f"got {density!r} 1/m^2, {expected:.4g} caps on {side:g} m x {side:g} m")
    count = max(1, round(expected))
    rng = np.random.default_rng(seed)
    x, y = rng.uniform(0.0, side, count), rng.uniform(0.0, side, count)
    z = rng.normal(0.0, sigma, count) if sigma > 0.0 else np.zeros(count)
    floor = z.min() - FLOOR_SIGMAS * sigma - side**2 / count / (8.0 * radius)
    heights = np.full((n, n), floor)
    for xi, yi, zi in zip(x, y, z):
        reach = np.sqrt(2.0 * radius * (zi - floor))  # beyond it the cap is below the floor
        rows, dx = _window(xi, reach, n, pixel, periodic)
        cols, dy = _window(yi, reach, n, pixel, periodic)
        cap = zi - (dx[:, None] ** 2 + dy[None, :] ** 2) / (2.0 * radius)
        block = np.ix_(rows, cols)
        heights[block] = np.maximum(heights[block], cap)
    source = (f"gaussian_caps(n={n}, pixel={pixel!r}, radius={radius!r}, sigma={sigma!r}, "
              f"density={density!r}, seed={seed}, periodic={periodic})")
    return Topography(heights, pixel, periodic, source), Caps(x, y, z, radius)


def self_affine(*, n, pixel, rms_height, hurst, short_cutoff=None, long_cutoff=None, seed=0):
    """A periodic, isotropic, Gaussian self-affine n×n map (`pixel`, m) by Fourier filtering:
    white noise (numpy's default generator, `seed`) shaped to the power spectrum

        C(q) ∝ q^(−2−2H)          for 2π/long_cutoff ≤ q ≤ 2π/short_cutoff,
        C(q) = C(2π/long_cutoff)  below (the roll-off),   C = 0 above and at q = 0,

    with the Hurst exponent H = `hurst` in (0, 1] and the cutoff wavelengths in m:
    `short_cutoff` in [2 pixel, L) (default 2 pixel, the Nyquist wavelength: the corners of
    the Fourier grid are cut, so the map is isotropic at every scale), `long_cutoff` in
    (short_cutoff, L] (default L: no roll-off). The map is rescaled to `rms_height` (m) about
    its mean 0 exactly.
    """
    n = _whole("n", n, MIN_PIXELS)
    pixel = _number("pixel", pixel, "m")
    rms_height = _number("rms_height", rms_height, "m")
    if np.ndim(hurst) != 0 or not 0.0 < in_range("hurst", hurst) <= 1.0:
        raise InputError(f"hurst must be a single number in (0, 1]; got {hurst!r}")
    hurst = float(hurst)
    seed = _whole("seed", seed, 0)
    side = n * pixel
    short = 2.0 * pixel if short_cutoff is None else _number("short_cutoff", short_cutoff, "m")
    if not 2.0 * pixel <= short < side:
        raise InputError(f"short_cutoff must be in [2 pixel, L) = [{2.0 * pixel:g}, {side:g}) m;"
                         f" got {short!r}")
    long = side if long_cutoff is None else _number("long_cutoff", long_cutoff, "m")
    if not short < long <= side:
        raise InputError(f"long_cutoff must be in (short_cutoff, L] = ({short:g}, {side:g}] m; "
                         f"got {long!r}")
    qx = 2.0 * np.pi * scipy.fft.fftfreq(n, d=pixel)[:, None]
    qy = 2.0 * np.pi * scipy.fft.rfftfreq(n, d=pixel)[None, :]
    q = np.hypot(qx, qy)
    q_short, q_long = 2.0 * np.pi / short, 2.0 * np.pi / long
    # √C, the amplitude filter: zero at q = 0 (mean 0) and above q_short (kept at q_short itself
    # against rounding); the roll-off flat below q_long.
    amplitude = np.where((q > 0.0) & (q <= q_short * (1.0 + 1e-12)),
                         np.maximum(q, q_long) ** (-1.0 - hurst), 0.0)
    noise = np.random.default_rng(seed).standard_normal((n, n))
    z = scipy.fft.irfft2(scipy.fft.rfft2(noise) * amplitude, s=(n, n))
    z -= z.mean()
    z *= rms_height / np.sqrt(np.mean(z**2))
    source = (f"self_affine(n={n}, pixel={pixel!r}, rms_height={rms_height!r}, hurst={hurst!r}, "
              f"short_cutoff={short!r}, long_cutoff={long!r}, seed={seed})")
    return Topography(z, pixel, True, source)


def _length_factor(unit):
    """Metres per `unit` (SurfaceTopography's length units), or InputError."""
    from SurfaceTopography.Support.UnitConversion import get_unit_conversion_factor

    try:
        return float(get_unit_conversion_factor(unit, "m"))
    except ValueError:
        raise InputError(f"the file's length unit {unit!r} is not one SurfaceTopography "
                         "converts to metres") from None


def _read_instrument(path, pixel):
    """(heights in m, pixel in m) of the default channel of an instrument file, through
    SurfaceTopography. A file without a length unit is taken to be in metres, as a .npy is; a
    file without its lateral size needs `pixel`; a file with it must agree with a given one."""
    try:
        import SurfaceTopography
    except ImportError:
        raise InputError(f"{path}: only .npy maps are read without SurfaceTopography, which "
                         f"reads instrument formats ({_PIP})") from None
    try:
        with SurfaceTopography.open_topography(str(path)) as reader:
            channel = reader.default_channel
            if channel.dim != 2:
                raise InputError(f"{path}: its default channel is not a 2-D map (dim "
                                 f"{channel.dim}); a line scan has no summits")
            options = {} if channel.unit is not None else {"unit": "m"}
            if channel.physical_sizes is None:
                if pixel is None:
                    raise InputError(f"{path}: the file does not give its lateral size; give the "
                                     "pixel (--pixel-size, m)")
                per_unit = _length_factor(channel.unit or "m")
                options["physical_sizes"] = tuple(k * pixel / per_unit
                                                  for k in channel.nb_grid_pts)
            topography = reader.topography(**options).to_unit("m")
    except InputError:
        raise
    except SurfaceTopography.IO.CannotDetectFileFormat:
        raise InputError(f"{path}: none of SurfaceTopography's readers recognises its "
                         "format") from None
    except Exception as err:  # the readers raise anything from ValueError to struct.error
        first = (str(err).strip().splitlines() or [""])[0]
        raise InputError(f"{path}: SurfaceTopography cannot read it ({type(err).__name__}"
                         f"{': ' + first if first else ''})") from None
    sizes, counts = topography.physical_sizes, topography.nb_grid_pts
    pixels = (sizes[0] / counts[0], sizes[1] / counts[1])
    if not np.isclose(pixels[0], pixels[1], rtol=1e-6, atol=0.0):
        raise InputError(f"{path}: its pixels are not square ({pixels[0]:g} m x {pixels[1]:g} "
                         "m); resample it first")
    if pixel is not None and not np.isclose(pixel, pixels[0], rtol=1e-6, atol=0.0):
        raise InputError(f"{path}: the file gives the pixel {pixels[0]:g} m, but --pixel-size "
                         f"is {pixel:g} m; leave it out")
    heights = np.ma.filled(np.ma.asarray(topography.heights(), dtype=float), np.nan)
    return heights, float(pixels[0])


def read_topography(path, *, pixel=None, periodic=False):
    """A `Topography` from the file at `path`.

    `.npy`: a 2-D array of heights in m; `pixel` (m, `--pixel-size` on the command line) is
    required. Any other extension is read by SurfaceTopography (`pip install
    SurfaceTopography`; it reads instrument formats and converts to m) if it is installed: the
    file's default channel, its lateral size from the file or else from `pixel`, undefined
    points refused as non-finite heights. `periodic`: whether the map repeats (files do not say
    so reliably). A missing or unreadable file, an empty, 1-D, too small or non-finite map is
    one InputError line naming the file.
    """
    try:
        path = Path(path)
    except TypeError:
        raise InputError(f"path must be a file name; got {path!r}") from None
    if pixel is not None:
        pixel = _number("pixel", pixel, "m")
    periodic = _flag("periodic", periodic)
    if not path.is_file():
        raise InputError(f"{path}: no such file")
    if path.suffix.lower() == ".npy":
        if pixel is None:
            raise InputError(f"{path}: a .npy map holds heights only; give the pixel "
                             "(--pixel-size, m)")
        try:
            heights = np.load(path, allow_pickle=False)
        except (OSError, ValueError, EOFError) as err:
            first = (str(err).strip().splitlines() or [""])[0]
            raise InputError(f"{path}: not a readable .npy array ({first})") from None
    else:
        heights, pixel = _read_instrument(path, pixel)
    try:
        return Topography(heights, pixel, periodic, str(path))
    except InputError as err:
        raise InputError(f"{path}: {err}") from None


@dataclass(frozen=True)
class SummitStatistics:
    """The GW parameters of a map: `sigma` (rms height about the mean, m), `sigma_s` (rms of
    the summit heights about their mean, m), `radius` (mean summit radius of curvature R, m),
    `density` (summits per area η, 1/m²), `omega` = σ_s/σ, `sigma_r_eta` = σRη, `count` (the
    summits counted; None for the spectral estimate) and `method` ("summits" or "spectral")."""

    sigma: float
    sigma_s: float
    radius: float
    density: float
    omega: float
    sigma_r_eta: float
    count: int | None
    method: str


def _checked(topography):
    if not isinstance(topography, Topography):
        raise InputError(f"topography must be a Topography; got {type(topography).__name__}")
    return topography


def _statistics(sigma, sigma_s, radius, density, count, method):
    return SummitStatistics(float(sigma), float(sigma_s), float(radius), float(density),
                            float(sigma_s / sigma), float(sigma * radius * density), count, method)


@dataclass(frozen=True, eq=False)
class Summits:
    """The summits of a map: their pixels (`rows`, `columns`), `heights` (m) and mean
    curvatures `curvature` (κ = (z_xx + z_yy)/2, 1/m, < 0 at a summit), and `inner`, the
    pixels they were sought among."""

    rows: np.ndarray
    columns: np.ndarray
    heights: np.ndarray
    curvature: np.ndarray
    inner: int


def summits(topography):
    """The pixels higher than all 8 neighbours (across the edges if the map is periodic; else
    the border pixels are never summits), with their heights and 5-point mean curvatures →
    `Summits`. InputError where there is none."""
    t = _checked(topography)
    z, h = t.heights, t.pixel
    padded = np.pad(z, 1, mode="wrap") if t.periodic else np.pad(z, 1, constant_values=np.inf)
    nx, ny = z.shape
    summit = np.ones(z.shape, dtype=bool)
    for di in (-1, 0, 1):
        for dj in (-1, 0, 1):
            if di or dj:
                summit &= z > padded[1 + di: 1 + di + nx, 1 + dj: 1 + dj + ny]
    i, j = np.nonzero(summit)
    if i.size == 0:
        raise InputError("topography has no summit (no pixel higher than its 8 neighbours"
                         + ("" if t.periodic else " inside the border") + ")")
    centre = padded[i + 1, j + 1]
    z_xx = (padded[i + 2, j + 1] - 2.0 * centre + padded[i, j + 1]) / h**2
    z_yy = (padded[i + 1, j + 2] - 2.0 * centre + padded[i + 1, j]) / h**2
    inner = nx * ny if t.periodic else (nx - 2) * (ny - 2)
    return Summits(i, j, centre, 0.5 * (z_xx + z_yy), inner)


def summit_statistics(topography):
    """GW parameters by counting the `summits`: η over the pixels they were sought among (the
    (nx−2)(ny−2) inner ones of a map that does not repeat).

    R = −1/mean(κ) with κ = (z_xx + z_yy)/2 the mean curvature at each summit by the 5-point
    finite differences: Nayak's mean summit curvature, inverted after averaging (an average of
    the radii would be dominated by the flattest summits). For a paraboloid the differences are
    exact, for any pixel. For a real or self-affine surface all three of σ_s, R, η depend on
    the pixel: a finer one resolves more, sharper, lower summits (the classical sampling
    dependence of summit statistics, Greenwood 1984); quote them with the pixel.
    """
    t = _checked(topography)
    found = summits(t)
    radius = -1.0 / np.mean(found.curvature)
    return _statistics(np.std(t.heights), np.std(found.heights), radius,
                       found.heights.size / (found.inner * t.pixel**2), found.heights.size,
                       "summits")


def spectral_summit_statistics(topography):
    """GW parameters from the profile's spectral moments (Nayak 1971; McCool 1986):

        η = m4/(6π√3 m2),   R = 0.375 √(π/m4),   σ_s² = (1 − 0.8968/α) m0,   α = m0 m4/m2².

    m0 is the variance of the heights; m2 = ⟨z'²⟩ and m4 = ⟨z''²⟩ are the mean square slope and
    curvature of the profiles along the map's rows and columns, averaged over the two
    directions (for an isotropic surface, the profile moments of any direction), by finite
    differences: the forward difference for the slope, the 3-point second difference for the
    curvature (across the edges if periodic, else inside the map; no tilt is removed). They are
    the moments of the power spectrum with q replaced by 2 sin(q·pixel/2)/pixel: the map's own
    discrete spectrum, the same one the 5-point curvature of `summit_statistics` sees; for
    wavelengths ≫ pixel they are the continuum moments, at the Nyquist wavelength m2 is
    (2/π)² and m4 (2/π)⁴ of them. On a periodic map α ≥ 1 with these moments, so σ_s² > 0; a
    non-periodic map dominated by a tilt can fall below α = 0.8968, which is an InputError.

    Nayak's η holds for any Gaussian isotropic surface; R and σ_s are McCool's broad-spectrum
    (α ≫ 1) forms, the ones behind the paper's eq. 20 (`gw.surface.omega_mccool`:
    3.717e-4 = 0.8968 [0.375/(6√(3π))]²). Sources: P. R. Nayak, "Random process model of
    rough surfaces", J. Lubr. Technol. 93 (1971) 398-407; J. I. McCool, "Comparison of models
    for the contact of rough surfaces", Wear 107 (1986) 37-60.
    """
    t = _checked(topography)
    z = t.heights - t.heights.mean()
    m0 = np.mean(z**2)
    slopes, curvatures = [], []
    for axis in (0, 1):
        if t.periodic:
            ahead, behind = np.roll(z, -1, axis), np.roll(z, 1, axis)
            slopes.append(np.mean((ahead - z) ** 2))
            curvatures.append(np.mean((ahead - 2.0 * z + behind) ** 2))
        else:
            slopes.append(np.mean(np.diff(z, axis=axis) ** 2))
            curvatures.append(np.mean(np.diff(z, n=2, axis=axis) ** 2))
    m2 = np.mean(slopes) / t.pixel**2
    m4 = np.mean(curvatures) / t.pixel**4
    if not m4 > 0.0:
        raise InputError("topography has no curvature (a flat or planar map has no summits)")
    alpha = m0 * m4 / m2**2
    if alpha <= MCCOOL_SUMMIT_HEIGHT:
        raise InputError(f"topography has the bandwidth alpha = m0 m4/m2^2 = {alpha:.4g}, not "
                         f"above {MCCOOL_SUMMIT_HEIGHT} (McCool's sigma_s has no real value): a "
                         "tilt or a single long wave dominates it; level it first")
    return _statistics(np.sqrt(m0), np.sqrt((1.0 - MCCOOL_SUMMIT_HEIGHT / alpha) * m0),
                       NAYAK_RADIUS * np.sqrt(np.pi / m4), m4 / (6.0 * np.pi * np.sqrt(3.0) * m2),
                       None, "spectral")
