"""Height maps and their summit statistics against hand values, brute force and Nayak's theory."""

import sys

import numpy as np
import pytest

from fem_asperity import InputError
from gw.explicit.topography import (
    Topography,
    gaussian_caps,
    read_topography,
    self_affine,
    spectral_summit_statistics,
    summit_statistics,
)
from gw.surface import omega_mccool

R = 1e-6  # cap radius, m


def brute_force_caps(caps, n, pixel, floor, periodic):
    """The caps map as the max over the caps and all their 3×3 periodic images (or none)."""
    x = np.arange(n) * pixel
    side = n * pixel
    shifts = (-side, 0.0, side) if periodic else (0.0,)
    z = np.full((n, n), floor)
    for xi, yi, zi in zip(caps.x, caps.y, caps.z):
        for sx in shifts:
            for sy in shifts:
                r2 = (x[:, None] - xi - sx) ** 2 + (x[None, :] - yi - sy) ** 2
                z = np.maximum(z, zi - r2 / (2.0 * caps.radius))
    return z


def apex_clearance(caps, side):
    """Each apex's distance (m) inside the region where its cap is the highest (< 0: covered).
    Two caps of one radius meet on a straight line (z_i − z_j + d²/2R = 0 at the apex's side
    of it, by d/R per metre): the distance is (z_i − z_j + d²/2R) R/d, the least over j."""
    dx = (caps.x[:, None] - caps.x[None, :] + side / 2) % side - side / 2
    dy = (caps.y[:, None] - caps.y[None, :] + side / 2) % side - side / 2
    d = np.hypot(dx, dy)
    np.fill_diagonal(d, 1.0)
    clearance = (caps.z[:, None] - caps.z[None, :] + d**2 / (2 * caps.radius)) * caps.radius / d
    np.fill_diagonal(clearance, np.inf)
    return clearance.min(axis=1)


# ---------------------------------------------------------------------------------------------
# Topography


def test_topography_properties_and_read_only_copy():
    z = np.zeros((10, 12))
    t = Topography(z, 2e-9, periodic=True, source="hand")
    assert t.shape == (10, 12)
    assert t.size == pytest.approx((20e-9, 24e-9), rel=1e-15)
    assert t.area == pytest.approx(480e-18, rel=1e-15)
    z[0, 0] = 1.0
    assert t.heights[0, 0] == 0.0
    with pytest.raises(ValueError):
        t.heights[0, 0] = 1.0


@pytest.mark.parametrize("heights, pattern", [
    (np.zeros(64), "2-D map"),
    (np.zeros((7, 8)), "at least 8 pixels in each direction"),
    (np.zeros((0, 0)), "empty"),
    (np.zeros((8, 8, 2)), "2-D map"),
    (np.array([["a"] * 8] * 8), "real numbers"),
])
def test_topography_refuses_bad_maps(heights, pattern):
    with pytest.raises(InputError, match=pattern):
        Topography(heights, 1e-9)


def test_topography_names_the_non_finite_pixels():
    z = np.zeros((9, 9))
    z[2, 5], z[7, 1], z[8, 8] = np.nan, np.inf, -np.inf
    with pytest.raises(InputError, match=r"3 of 81 pixels are NaN or inf, the first at pixel "
                                         r"\(2, 5\)"):
        Topography(z, 1e-9)


@pytest.mark.parametrize("pixel", [-1e-9, 0.0, np.nan, np.inf, [1e-9, 1e-9]])
def test_topography_refuses_bad_pixels(pixel):
    with pytest.raises(InputError, match="pixel"):
        Topography(np.zeros((8, 8)), pixel)


# ---------------------------------------------------------------------------------------------
# gaussian_caps


@pytest.mark.parametrize("periodic", [True, False])
def test_caps_map_is_the_max_over_caps_and_images_and_floor(periodic):
    n, pixel, sigma = 48, R / 10, R / 100
    t, caps = gaussian_caps(n=n, pixel=pixel, radius=R, sigma=sigma, density=6 / (n * pixel) ** 2,
                            seed=3, periodic=periodic)
    assert caps.z.size == 6 and caps.radius == R and t.periodic is periodic
    # The documented floor: 20 sigma and s²/(8R) below the lowest summit, s² = area / caps.
    floor = caps.z.min() - 20.0 * sigma - t.area / 6 / (8.0 * R)
    np.testing.assert_allclose(t.heights, brute_force_caps(caps, n, pixel, floor, periodic),
                               rtol=0.0, atol=1e-12 * R)


def test_single_cap_is_one_summit_with_its_radius():
    n, pixel = 64, R / 50
    t, caps = gaussian_caps(n=n, pixel=pixel, radius=R, sigma=R / 100,
                            density=1 / (n * pixel) ** 2, seed=7)
    s = summit_statistics(t)
    assert caps.z.size == 1 and s.count == 1 and s.method == "summits"
    assert s.radius == pytest.approx(R, rel=0.01)  # a paraboloid: the stencil is exact
    assert s.density == pytest.approx(1 / t.area, rel=1e-12)
    # The summit pixel is the nearest to the apex, lower than it by at most pixel²/(4R).
    top = np.unravel_index(np.argmax(t.heights), t.shape)
    assert top == (round(caps.x[0] / pixel) % n, round(caps.y[0] / pixel) % n)
    assert 0.0 <= caps.z[0] - t.heights[top] <= pixel**2 / (4 * R)


def test_sparse_caps_give_back_their_count_heights_and_radius():
    """100 caps at a mean spacing s ≈ 26 pixels, s²/(2R) ≈ 26 sigma. A few cover one another
    (random positions); a cap whose apex lies within a pixel or two of being covered may show
    no summit of its own. A summit's 5-point stencil on its own paraboloid is exact for any
    R/pixel: R is off only where a stencil reaches across to a neighbour."""
    n, pixel, sigma, count = 256, R / 50, R / 200, 100
    t, caps = gaussian_caps(n=n, pixel=pixel, radius=R, sigma=sigma,
                            density=count / (n * pixel) ** 2, seed=0)
    s = summit_statistics(t)
    clearance = apex_clearance(caps, n * pixel)
    shown = clearance > 0
    assert caps.z.size == count
    assert (clearance > 2 * pixel).sum() <= s.count <= shown.sum()
    assert shown.sum() - (clearance > 2 * pixel).sum() <= 5  # seed 0: 92, 95 summits, 97
    assert s.density == pytest.approx(s.count / t.area, rel=1e-12)
    assert s.radius == pytest.approx(R, rel=0.02)
    # The summits' heights are within pixel²/(4R) = 0.5 % sigma of their apexes, so their rms
    # is the visible caps' sample rms but for the few missed...
    assert s.sigma_s == pytest.approx(caps.z[shown].std(), rel=0.03)
    # ...and within 3 standard errors of sigma.
    assert abs(s.sigma_s - sigma) < 3 * sigma / np.sqrt(2 * s.count)


@pytest.mark.parametrize("kwargs, name", [
    ({"n": 7}, "n"), ({"n": 16.0}, "n"), ({"pixel": -1e-8}, "pixel"), ({"radius": 0}, "radius"),
    ({"sigma": -1e-9}, "sigma"), ({"density": np.nan}, "density"),
    ({"density": 1e30}, "density"), ({"seed": -1}, "seed"), ({"seed": 1.5}, "seed"),
    ({"periodic": "yes"}, "periodic"),
])
def test_caps_refuse_bad_inputs(kwargs, name):
    good = {"n": 16, "pixel": 1e-8, "radius": R, "sigma": 1e-9, "density": 1e12}
    with pytest.raises(InputError, match=name):
        gaussian_caps(**(good | kwargs))


# ---------------------------------------------------------------------------------------------
# self_affine


def test_self_affine_rms_cutoffs_and_psd_slope():
    n, pixel, hurst = 256, 1e-8, 0.7
    short, long = 4 * pixel, n * pixel / 4
    t = self_affine(n=n, pixel=pixel, rms_height=2e-7, hurst=hurst, short_cutoff=short,
                    long_cutoff=long, seed=5)
    assert t.periodic and t.shape == (n, n)
    z = t.heights
    assert abs(z.mean()) < 1e-12 * 2e-7
    assert np.sqrt(np.mean(z**2)) == pytest.approx(2e-7, rel=1e-12)
    power = np.abs(np.fft.fft2(z)) ** 2
    q = 2 * np.pi * np.hypot(np.fft.fftfreq(n, pixel)[:, None], np.fft.fftfreq(n, pixel)[None, :])
    q_short, q_long = 2 * np.pi / short, 2 * np.pi / long
    assert power[q > q_short * 1.001].max() < 1e-20 * power.max()
    # log|Z|² of each mode scatters about log C(q) by a constant mean (−γ): the slope is unbiased.
    band = (q > 1.5 * q_long) & (q < q_short / 1.2)
    slope = np.polyfit(np.log(q[band]), np.log(power[band]), 1)[0]
    assert slope == pytest.approx(-2 - 2 * hurst, abs=0.1)


@pytest.mark.parametrize("kwargs, name", [
    ({"hurst": 0.0}, "hurst"), ({"hurst": 1.2}, "hurst"), ({"rms_height": -1.0}, "rms_height"),
    ({"short_cutoff": 1e-8}, "short_cutoff"), ({"short_cutoff": 64e-8}, "short_cutoff"),
    ({"long_cutoff": 3e-8, "short_cutoff": 4e-8}, "long_cutoff"),
    ({"long_cutoff": 65e-8}, "long_cutoff"),
])
def test_self_affine_refuses_bad_inputs(kwargs, name):
    good = {"n": 64, "pixel": 1e-8, "rms_height": 1e-7, "hurst": 0.5}
    with pytest.raises(InputError, match=name):
        self_affine(**(good | kwargs))


# ---------------------------------------------------------------------------------------------
# summit statistics


def test_summits_by_hand_border_and_wrap():
    """Two unit spikes on a flat 8×8 map, one on the border: κ = −2/h², so R = h²/2."""
    z = np.zeros((8, 8))
    z[0, 3] = z[4, 4] = 1.0
    h = 0.5
    free = summit_statistics(Topography(z, h, periodic=False))
    wrapped = summit_statistics(Topography(z, h, periodic=True))
    assert free.count == 1 and wrapped.count == 2
    assert free.density == pytest.approx(1 / (36 * h**2), rel=1e-14)  # the 6×6 inner pixels
    assert wrapped.density == pytest.approx(2 / (64 * h**2), rel=1e-14)
    assert free.radius == wrapped.radius == pytest.approx(h**2 / 2, rel=1e-14)
    assert free.sigma_s == 0.0 and wrapped.sigma_s == 0.0
    assert wrapped.sigma == pytest.approx(np.sqrt(2 / 64 - (2 / 64) ** 2), rel=1e-14)


def test_spectral_statistics_of_two_cosines_by_hand():
    """z = a cos(kx x) + b cos(ky y): profile moments along x and along y, averaged, with the
    forward/second differences' wavenumber 2 sin(k h/2)/h; then Nayak's and McCool's forms."""
    n, h, a, b = 64, 1e-8, 3e-9, 2e-9
    kx, ky = 2 * np.pi / (16 * h), 2 * np.pi / (8 * h)
    x = np.arange(n) * h
    z = a * np.cos(kx * x)[:, None] + b * np.cos(ky * x)[None, :]
    sx, sy = 2 * np.sin(kx * h / 2) / h, 2 * np.sin(ky * h / 2) / h
    m0 = (a**2 + b**2) / 2
    m2 = (a**2 * sx**2 / 2 + b**2 * sy**2 / 2) / 2
    m4 = (a**2 * sx**4 / 2 + b**2 * sy**4 / 2) / 2
    alpha = m0 * m4 / m2**2
    s = spectral_summit_statistics(Topography(z, h, periodic=True))
    assert s.method == "spectral" and s.count is None
    assert s.sigma == pytest.approx(np.sqrt(m0), rel=1e-12)
    assert s.density == pytest.approx(m4 / (6 * np.pi * np.sqrt(3) * m2), rel=1e-12)
    assert s.radius == pytest.approx(0.375 * np.sqrt(np.pi / m4), rel=1e-12)
    assert s.sigma_s == pytest.approx(np.sqrt((1 - 0.8968 / alpha) * m0), rel=1e-12)
    assert s.sigma_r_eta == pytest.approx(s.sigma * s.radius * s.density, rel=1e-14)


def gaussian_acf_map(n, lam, seed):
    """A periodic Gaussian surface with the autocorrelation exp(−r²/(2λ²)) (λ in pixels),
    unit rms: profile moments m2 = 1/λ², m4 = 3/λ⁴, α = 3."""
    q = 2 * np.pi * np.hypot(np.fft.fftfreq(n)[:, None], np.fft.fftfreq(n)[None, :])
    noise = np.random.default_rng(seed).standard_normal((n, n))
    z = np.fft.ifft2(np.fft.fft2(noise) * np.exp(-(q**2) * lam**2 / 4)).real
    return z / z.std()


def test_gaussian_surface_against_nayak_by_counting_and_by_moments():
    """λ = 8 pixels on 512²: about 380 summits. Nayak's density 1/(2π√3 λ²) holds for any α;
    the spectral estimate from the map's moments within 5 % of the analytic ones (the moments
    of one realisation scatter by a few %), the count within 3 standard errors."""
    lam = 8.0
    t = Topography(gaussian_acf_map(512, lam, seed=0), 1.0, periodic=True)
    m0, m2, m4 = 1.0, 1 / lam**2, 3 / lam**4
    eta = m4 / (6 * np.pi * np.sqrt(3) * m2)
    spectral, counted = spectral_summit_statistics(t), summit_statistics(t)
    assert spectral.density == pytest.approx(eta, rel=0.05)
    assert spectral.radius == pytest.approx(0.375 * np.sqrt(np.pi / m4), rel=0.05)
    assert spectral.sigma_s == pytest.approx(np.sqrt((1 - 0.8968 / 3) * m0), rel=0.05)
    assert counted.density == pytest.approx(eta, rel=3 / np.sqrt(counted.count))


def test_spectral_omega_is_the_papers_eq_20():
    """McCool's σ_s with Nayak's R and η is the paper's ω(σRη) (3.717e-4 = 0.8968·0.02036²)."""
    t = self_affine(n=128, pixel=1e-8, rms_height=1e-7, hurst=0.6, short_cutoff=8e-8, seed=2)
    s = spectral_summit_statistics(t)
    assert s.omega == pytest.approx(float(omega_mccool(s.sigma_r_eta)), rel=1e-4)


def test_statistics_refuse_maps_without_summits():
    flat = Topography(np.zeros((8, 8)), 1e-9, periodic=True)
    with pytest.raises(InputError, match="no summit"):
        summit_statistics(flat)
    with pytest.raises(InputError, match="no curvature"):
        spectral_summit_statistics(flat)
    x = np.arange(16.0)
    bowl = Topography(x[:, None] ** 2 + x[None, :] ** 2, 1e-9)  # alpha = 0.2 by hand
    with pytest.raises(InputError, match="alpha"):
        spectral_summit_statistics(bowl)
    with pytest.raises(InputError, match="Topography"):
        summit_statistics(np.zeros((8, 8)))


# ---------------------------------------------------------------------------------------------
# read_topography


def test_read_npy(tmp_path):
    z = np.random.default_rng(0).standard_normal((12, 9)) * 1e-9
    np.save(tmp_path / "map.npy", z)
    t = read_topography(tmp_path / "map.npy", pixel=5e-9, periodic=True)
    np.testing.assert_array_equal(t.heights, z)
    assert t.pixel == 5e-9 and t.periodic and t.source == str(tmp_path / "map.npy")


def test_read_refuses_bad_files(tmp_path, monkeypatch):
    np.save(tmp_path / "line.npy", np.zeros(64))
    np.save(tmp_path / "empty.npy", np.zeros((0, 0)))
    nan = np.zeros((8, 8))
    nan[1, 2] = np.nan
    np.save(tmp_path / "nan.npy", nan)
    np.save(tmp_path / "ok.npy", np.zeros((8, 8)))
    (tmp_path / "junk.npy").write_bytes(b"not an array")
    (tmp_path / "map.sur").write_bytes(b"\x00")
    cases = [
        ("missing.npy", {"pixel": 1e-9}, "no such file"),
        ("ok.npy", {}, "--pixel-size"),
        ("line.npy", {"pixel": 1e-9}, "2-D map"),
        ("empty.npy", {"pixel": 1e-9}, "empty"),
        ("nan.npy", {"pixel": 1e-9}, r"first at pixel \(1, 2\)"),
        ("junk.npy", {"pixel": 1e-9}, "not a readable .npy"),
    ]
    for name, kwargs, pattern in cases:
        with pytest.raises(InputError, match=pattern) as err:
            read_topography(tmp_path / name, **kwargs)
        assert "\n" not in str(err.value) and name in str(err.value)
    with pytest.raises(InputError, match="pixel must be in"):
        read_topography(tmp_path / "ok.npy", pixel=-1e-9)
    monkeypatch.setitem(sys.modules, "SurfaceTopography", None)  # as if not installed
    with pytest.raises(InputError, match="only .npy .*pip install SurfaceTopography"):
        read_topography(tmp_path / "map.sur", pixel=1e-9)
