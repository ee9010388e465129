"""The attraction GW counts twice (gw.explicit.tails): the binned overlap against its pixel sum,
two caps against the half-plane integral of a paraboloid's tail, and a dense surface of caps
solved whole where the solid is nearly rigid (μ = 0.05), the limit in which counting the ground
once is the whole correction."""

import numpy as np
import pytest
from scipy.integrate import dblquad, quad

from fem_asperity.closed_forms.lj import scaled_potential, scaled_traction
from fem_asperity.plumbing.errors import InputError
from gw.explicit import Scene, compare
from gw.explicit.interacting import AsperityLaw
from gw.explicit.tails import SharedTails
from gw.shared_ground import CONTACT_GAP


def _caps(x, y, z, shape, pixel, periodic, window=False):
    """Each cap's z − r²/2 on the map's pixels (or on the window `SharedTails` takes: the
    map's cell if periodic, nine maps if free), and whether each pixel is on the map."""
    n0, n1 = shape
    span = (np.arange(n0), np.arange(n1)) if periodic or not window else (
        np.arange(-n0, 2 * n0), np.arange(-n1, 2 * n1))
    gx, gy = span[0][:, None] * pixel, span[1][None, :] * pixel
    caps = []
    for xi, yi, zi in zip(x, y, z):
        dx, dy = gx - xi, gy - yi
        if periodic:
            dx = dx - n0 * pixel * np.round(dx / (n0 * pixel))
            dy = dy - n1 * pixel * np.round(dy / (n1 * pixel))
        caps.append(zi - (dx**2 + dy**2) / 2)
    return np.array(caps)


def _attraction(h):
    """The LJ traction where it pulls (gaps above CONTACT_GAP), zero in contact."""
    return np.where(h > CONTACT_GAP, scaled_traction(np.maximum(h, CONTACT_GAP)), 0.0)


def _pixel_sum(x, y, z, counted, shape, pixel, periodic, d):
    """T(d) pixel by pixel (the map: the highest of all the caps; the summits: those
    `counted`), without the part beyond the window."""
    def force(field):
        return _attraction(d - field).sum() * pixel**2 / (2 * np.pi)

    ground = _caps(x, y, z, shape, pixel, periodic).max(axis=0)
    paraboloids = _caps(x[counted], y[counted], z[counted], shape, pixel, periodic, True)
    return force(ground) - sum(force(p) for p in paraboloids)


def _beyond(x, y, z, shape, pixel, periodic, d):
    """The summits' paraboloids' attraction beyond the window, by adaptive quadrature over the
    angle: (1/2π)∫ φ̄(max(d − z + R(θ)²/2, 1)) dθ, R(θ) to the window's edge (the nearest-image
    cell centred on the summit, or nine maps if free)."""
    side = np.array(shape) * pixel
    total = 0.0
    for xi, yi, zi in zip(x, y, z):
        centre = np.array([xi, yi])
        lo, hi = (centre - side / 2, centre + side / 2) if periodic else (
            -side - pixel / 2, 2 * side - pixel / 2)

        def edge(theta, centre=centre, lo=lo, hi=hi):
            u = np.array([np.cos(theta), np.sin(theta)])
            steps = [((hi if c > 0 else lo)[k] - centre[k]) / c for k, c in enumerate(u)
                     if c != 0]
            return min(steps)

        total += quad(lambda t, zi=zi, edge=edge: scaled_potential(
            max(d - zi + edge(t) ** 2 / 2, CONTACT_GAP)), 0, 2 * np.pi, limit=400,
            points=[np.pi / 4 * k for k in range(1, 8)])[0] / (2 * np.pi)
    return total


@pytest.mark.parametrize("periodic", [True, False])
def test_the_binned_overlap_is_the_pixel_sum(periodic):
    """Nine caps on a 40² map, one not taken as a summit (as a cap under another is not): T
    from the bins (and the rays where the periodic cell is too small for a disc) within 1e-4 of
    the pixel sum and the quadrature beyond the window,
    at separations from where the highest apex is 0.5 ε off, in contact already (its pixels
    fill the one bin below the fine ones: in contact at every separation asked), to 0.6 ε
    into it."""
    rng = np.random.default_rng(3)
    shape, pixel = (40, 40), 0.25
    x, y = rng.uniform(0, 10, 9), rng.uniform(0, 10, 9)
    z = rng.normal(0, 0.5, 9)
    counted = np.ones(9, bool)
    counted[4] = False
    ground = _caps(x, y, z, shape, pixel, periodic).max(axis=0)
    separations = np.arange(z.max() + 0.5, z.max() - 0.6, -0.1)
    tails = SharedTails.build(x[counted], y[counted], z[counted], ground, pixel=pixel,
                              periodic=periodic, separations=separations)
    for d in separations:
        exact = (_pixel_sum(x, y, z, counted, shape, pixel, periodic, d)
                 - _beyond(x[counted], y[counted], z[counted], shape, pixel, periodic, d))
        assert tails.force(d) == pytest.approx(exact, rel=1e-4, abs=1e-8)


@pytest.mark.parametrize("periodic, n", [(False, 100), (True, 120)])
def test_each_paraboloid_on_a_disc_of_pixels_is_the_whole_window(periodic, n, monkeypatch):
    """Twelve caps on a map 25-30 √(Rε) wide: each paraboloid counted on the pixels of a disc
    out to DISC_REACH and in closed form beyond it gives the T of the whole window of pixels
    and its rays (the disc made too large to fit) within 1e-4, 2 ε above the highest apex to
    1 ε into it."""
    import gw.explicit.tails as tails_module

    rng = np.random.default_rng(5)
    pixel = 0.25
    x, y = rng.uniform(0, n * pixel, (2, 12))
    z = rng.normal(0, 1.0, 12)
    ground = _caps(x, y, z, (n, n), pixel, periodic).max(axis=0)
    separations = np.arange(z.max() + 2.0, z.max() - 1.0, -0.25)
    assert np.sqrt(2 * (tails_module.DISC_REACH - separations.min() + z.max())) < n * pixel / 2
    disc = SharedTails.build(x, y, z, ground, pixel=pixel, periodic=periodic,
                             separations=separations).along(separations)
    monkeypatch.setattr(tails_module, "DISC_REACH", 1e9)
    window = SharedTails.build(x, y, z, ground, pixel=pixel, periodic=periodic,
                               separations=separations).along(separations)
    assert np.allclose(disc, window, rtol=1e-4, atol=0.0)


def test_one_cap_loses_its_tail_beyond_its_cell():
    """One cap in a periodic cell 4 √(Rε) wide: the map within the cell is its paraboloid, so T
    is the paraboloid's attraction outside the square, φ̄(δ) less the square's (2-D quadrature),
    taken away (T > 0)."""
    side, n = 4.0, 40
    offsets = np.arange(n) * side / n - 2.0
    ground = -(offsets[:, None] ** 2 + offsets[None, :] ** 2) / 2
    for delta in (1.2, 1.5, 3.0):
        tails = SharedTails.build([2.0], [2.0], [0.0], ground, pixel=side / n, periodic=True,
                                  separations=[delta])
        square = dblquad(lambda v, u, delta=delta: _attraction(delta + (u * u + v * v) / 2),
                         -2, 2, -2, 2)[0] / (2 * np.pi)
        outside = scaled_potential(delta) - square
        assert tails.force(delta) == pytest.approx(-outside, rel=1e-4)
        assert tails.force(delta) > 0


def test_two_caps_lose_each_others_half_plane():
    """Two caps of one height s = 2 √(Rε) apart, mid-map on a free 24 √(Rε) patch: each one's
    cell is the half-plane on its side of the bisector, so T is twice the paraboloid's tail
    beyond a line s/2 from its apex, ∫∫ p̄(δ + r²/2) dA/(2π) (quadrature), and a little more for
    the patch's end (under 1 % here)."""
    pixel, n, s = 0.1, 240, 2.0
    x = np.array([12.0, 12.0])
    y = np.array([12.0 - s / 2, 12.0 + s / 2])
    z = np.zeros(2)
    separations = np.array([1.2, 1.5, 2.5])
    ground = _caps(x, y, z, (n, n), pixel, False).max(axis=0)
    tails = SharedTails.build(x, y, z, ground, pixel=pixel, periodic=False,
                              separations=separations)
    for delta in separations:
        def strip(u, delta=delta):  # ∫ dv p̄(δ + (u² + v²)/2) over the line at u
            return 2 * quad(lambda v: scaled_traction(delta + (u * u + v * v) / 2), 0, np.inf)[0]

        half_plane = quad(strip, s / 2, np.inf)[0] / (2 * np.pi)
        assert tails.force(delta) == pytest.approx(-2 * half_plane, rel=0.01)
        assert tails.force(delta) > 0  # an attraction taken away


def test_summits_far_apart_share_nothing():
    """Two caps 28 √(Rε) apart (diagonally) in a periodic cell 40 wide: what each one's tail
    reaches over the other's cell is under 1e-3 of one cap's pull-off, at contact and 3 ε off."""
    x = y = np.array([5.0, 25.0])
    z = np.zeros(2)
    ground = _caps(x, y, z, (200, 200), 0.2, True).max(axis=0)
    tails = SharedTails.build(x, y, z, ground, pixel=0.2, periodic=True,
                              separations=[1.0, 4.0])
    assert abs(tails.force(1.0)) < 1e-3 and abs(tails.force(4.0)) < 1e-3


def test_a_nearly_rigid_dense_surface_is_its_summits_counted_once():
    """Caps at σRη = 0.15, ζ = 0.5 (about 1.8 √(Rε) apart) on a nearly rigid solid, μ = 0.05:
    the sum over the summits' laws counts the ground between them two or three times (F̄max
    91 % above the whole surface's in a run here); with the ground counted once it falls
    within 10 % (plus the whole surface's estimate), and so does the interacting model."""
    scene = Scene(mu=0.05, zeta=0.5, sigma_r_eta=0.15, summits=6)
    found = compare(scene, accuracy="draft", law=AsperityLaw.tabulated(0.05))
    assert found.errors["gw_sum"] > 0.5
    assert found.holds["gw_cells"] and found.holds["interacting"]
    assert abs(found.errors["gw_cells"]) < 0.1


def test_bad_summits_or_maps_are_refused():
    ground = np.zeros((10, 10))
    with pytest.raises(InputError, match="1-D arrays of one length"):
        SharedTails.build([0.0, 1.0], [0.0], [0.0, 0.0], ground, pixel=0.2, periodic=True,
                          separations=[1.0])
    with pytest.raises(InputError, match="pixel"):
        SharedTails.build([0.0], [0.0], [0.0], ground, pixel=0.0, periodic=True,
                          separations=[1.0])
    with pytest.raises(InputError, match="separations"):
        SharedTails.build([0.0], [0.0], [0.0], ground, pixel=0.2, periodic=True,
                          separations=[])
    tails = SharedTails.build([0.0], [0.0], [0.0], ground, pixel=0.2, periodic=True,
                              separations=[1.0, 2.0])
    with pytest.raises(InputError, match="within the separations"):
        tails.force(3.0)  # its bins were laid out for 1 to 2 eps
    ground[3, 3] = np.nan
    with pytest.raises(InputError, match="2-D map of finite numbers"):
        SharedTails.build([0.0], [0.0], [0.0], ground, pixel=0.2, periodic=True,
                          separations=[1.0])
