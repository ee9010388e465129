"""The attraction GW counts twice: each summit's law is that of a whole paraboloid, whose LJ
tail reaches over its neighbours' ground.

The single-asperity law integrates the LJ attraction over an infinite paraboloid. On a surface
of many summits the ground beyond a summit's own cell belongs to a neighbour (the map is the
highest of them), whose law counts it again. Taken rigid, what the summits' laws miscount is

    T(d) = Σ_x p̄(d − z(x)) a²/(2π) − Σ_i ∫ p̄(d − z_i + r_i²/2) dA/(2π)

in 2πRΔγ at separation d (ε): the map's LJ force (p̄ in Δγ/ε, z the map in ε, a the pixel in
√(Rε)) less that of every summit's paraboloid (apex z_i, r in √(Rε)). Where the map is a
summit's paraboloid (near its apex) the two cancel pixel by pixel, so T is made of the
paraboloids' tails over their neighbours' cells, which it takes away (T > 0: p̄ < 0 there), and
of the ground no summit's paraboloid describes (caps under another, summits not counted, a
measured map's own shape), which it adds. It depends on the summit spacing against the LJ range:
the gap at a cell's edge is about d − z + s²/8 for summits s √(Rε) apart, s² = ζ/(σRη) =
1/(ηRε). It is taken rigid (the gaps of the undeformed map; the elastic lift of the ground
between summits is the interacting model's far field, not here), and only the attraction counts:
gaps below `CONTACT_GAP` (1 ε, where p̄ turns repulsive: contact, each law's own business) are
left out of both sums, so that contacts that merge add nothing.

The sums are kept as histograms of q (h = d + q; q = −z on the map, r²/2 − z_i on a
paraboloid), binned by `Q_STEP` where a gap can come near contact and logarithmically beyond,
so that T at each d is a sum over the bins. The map's ground is counted on its pixels. Each
paraboloid is counted on the pixels of a disc about its apex, out to where its gap stays above
DISC_REACH at every separation asked, and beyond the disc in closed form: ∫ p̄(h) dA/(2π) over
r > ρ is φ̄(d − z_i + ρ²/2), ρ the disc's equal-area radius. Where the disc would not fit in the
summit's window (the map's cell of nearest images if periodic, three times the map if free),
the paraboloid is counted on the whole window and beyond it by (1/2π)∫ φ̄(d − z_i + R(θ)²/2) dθ
over rays to the window's edge.
"""

from dataclasses import dataclass

import numpy as np

from fem_asperity.closed_forms.lj import scaled_potential, scaled_traction
from fem_asperity.plumbing.checks import positive
from fem_asperity.plumbing.errors import InputError

from ..shared_ground import CONTACT_GAP

#: Rays per summit for its paraboloid's tail beyond the window of pixels: the window's edge is
#: straight, so the tail, (1/2π)∫ φ̄(h(R(θ))) dθ, is smooth in θ (test_tails.py: 1e-4 of it).
ANGLES = 720
#: Bin width of q (ε) where a gap can come within ten ε of the surface; each bin's mean q
#: stands for its pixels (second order in the width: test_tails.py pins it to the pixels').
Q_STEP = 0.005
#: Beyond ten ε of gap, bins grow geometrically by this factor (p̄ ~ h̄⁻³ there).
Q_GROWTH = 1.02
#: Gaps beyond which the fine bins stop (ε): p̄(10) is 3e-3 of the peak.
FINE_REACH = 10.0
#: Gap (ε) beyond which a paraboloid is taken continuous (its disc of pixels ends there): its
#: pixels there differ from the closed form by under 1e-4 of T (test_tails.py: disc vs window).
DISC_REACH = 30.0


@dataclass(frozen=True, eq=False)
class SharedTails:
    """T(d) of summits on a map (`build`): `q` (bin means, ε) and `weight` (pixels per bin
    times a²/(2π): + the map's, − the paraboloids'), the paraboloids' parts beyond their
    pixels as `q_beyond` and `w_beyond` (binned like q: a disc's remainder ρ²/2 − z_i with
    weight −1, or a ray's R(θ)²/2 − z_i with −1/ANGLES; φ̄ at each), and the `separations`
    (d_lo, d_hi, ε) the bins were laid out for."""

    q: np.ndarray
    weight: np.ndarray
    q_beyond: np.ndarray
    w_beyond: np.ndarray
    separations: tuple

    @classmethod
    def build(cls, x, y, z, heights, *, pixel, periodic, separations):
        """Summits at (`x`, `y`) (√(Rε)) with apex heights `z` (ε), each taken as a
        paraboloid z − r²/2 (the caps of its law), on the map `heights` (ε; pixel (i, j)
        centred at (i, j) × `pixel` √(Rε), as `gaussian_caps` and `summits` place them).
        `separations` (ε): the range of d that `force` will be asked at, which sets where the
        bins must be fine."""
        x, y, z = (np.asarray(v, dtype=float) for v in (x, y, z))
        heights = np.asarray(heights, dtype=float)
        if not (x.shape == y.shape == z.shape) or x.ndim != 1 or not x.size:
            raise InputError("x, y and z must be 1-D arrays of one length (>= 1)")
        if not np.all(np.isfinite(np.concatenate([x, y, z]))):
            raise InputError("x, y and z must be finite")
        if heights.ndim != 2 or not np.all(np.isfinite(heights)):
            raise InputError("heights must be a 2-D map of finite numbers")
        pixel = positive("pixel", pixel)
        separations = np.asarray(separations, dtype=float)
        if not separations.size or not np.all(np.isfinite(separations)):
            raise InputError("separations must be finite numbers, at least one")
        n0, n1 = heights.shape
        side = np.array([n0, n1]) * pixel
        if periodic:  # the nearest images: a cell centred on each summit
            rows, cols = np.arange(n0), np.arange(n1)
            lo, hi = np.stack([x, y], 1) - side / 2, np.stack([x, y], 1) + side / 2
        else:  # the map and as much again on each side: no ground there
            rows, cols = np.arange(-n0, 2 * n0), np.arange(-n1, 2 * n1)
            lo = np.broadcast_to(-side - pixel / 2, (x.size, 2))
            hi = np.broadcast_to(2 * side - pixel / 2, (x.size, 2))
        gx, gy = rows * pixel, cols * pixel
        d_lo, d_hi = float(separations.min()), float(separations.max())
        disc = np.sqrt(2.0 * np.maximum(DISC_REACH - d_lo + z, 0.0))  # radius, √(Rε)
        fits = disc < (side.min() / 2.0 if periodic else side.min())
        caps, beyond = [], []  # (q, weight): pixels of the paraboloids, their parts beyond
        for i in np.nonzero(fits)[0]:
            r2 = _disc(x[i], y[i], disc[i], pixel)
            caps.append((r2 / 2.0 - z[i], np.ones(r2.size)))
            beyond.append((np.array([r2.size * pixel**2 / np.pi / 2.0 - z[i]]), np.ones(1)))
        window = np.nonzero(~fits)[0]
        for i in window:
            caps.append((_squared(gx, gy, x[i], y[i], side, periodic).ravel() / 2.0 - z[i],
                         np.ones(gx.size * gy.size)))
        if window.size:
            rays = _rays(np.stack([x[window], y[window]], 1), lo[window], hi[window])
            q_rays = (rays**2 / 2.0 - z[window, None]).ravel()
            beyond.append((q_rays, np.full(q_rays.size, 1.0 / ANGLES)))
        lowest = -max(float(z.max()), float(heights.max())) - 1.0
        highest = max([-float(heights.min())] + [float(q.max(initial=-np.inf))
                                                  for q, _ in caps + beyond])
        edges = _edges(lowest, CONTACT_GAP - d_hi, FINE_REACH - d_lo, highest + 1.0, d_lo)
        ground = _histogram([(-heights.ravel(), np.ones(heights.size))], edges)
        caps, beyond = _histogram(caps, edges), _histogram(beyond, edges)
        area = pixel**2 / (2.0 * np.pi)
        return cls(np.concatenate([ground[0], caps[0]]),
                   np.concatenate([ground[1], -caps[1]]) * area,
                   beyond[0], -beyond[1], (d_lo, d_hi))

    def force(self, d):
        """T at separation `d` (ε, within the `separations` it was built for): F̄ (2πRΔγ,
        < 0 tensile) to add to the summits' laws' sum so that the ground between them is
        counted once."""
        d_lo, d_hi = self.separations
        if not d_lo - 1e-9 <= d <= d_hi + 1e-9:
            raise InputError(f"d must be within the separations the tails were built for, "
                             f"{d_lo:g} to {d_hi:g} eps; got {d!r}")
        gaps = d + self.q
        inside = float(np.dot(self.weight, np.where(gaps > CONTACT_GAP,
                                                    scaled_traction(np.maximum(gaps,
                                                                               CONTACT_GAP)),
                                                    0.0)))
        outside = float(np.dot(self.w_beyond, scaled_potential(
            np.maximum(d + self.q_beyond, CONTACT_GAP))))
        return inside + outside

    def along(self, separations):
        """`force` at each of `separations` (ε), as an array."""
        return np.array([self.force(d) for d in separations])


def _rays(centres, lo, hi):
    """For each centre (n × 2) inside its box [lo, hi] (n × 2): the distance to the box's edge
    along ANGLES rays at equal angles (n × ANGLES)."""
    theta = (np.arange(ANGLES) + 0.5) * 2.0 * np.pi / ANGLES
    direction = np.stack([np.cos(theta), np.sin(theta)], 1)  # (ANGLES, 2)
    with np.errstate(divide="ignore"):
        reach = np.where(direction[None] > 0, (hi[:, None] - centres[:, None]) / direction[None],
                         (lo[:, None] - centres[:, None]) / direction[None])
    return np.min(np.where(direction[None] != 0, reach, np.inf), axis=2)


def _histogram(fields, edges):
    """(weighted mean q, summed weight) of the bins of `edges` that the (q, weight) arrays of
    `fields` fall in."""
    counts, moments = np.zeros(edges.size - 1), np.zeros(edges.size - 1)
    for q, weight in fields:
        index = np.clip(np.searchsorted(edges, q, side="right") - 1, 0, edges.size - 2)
        counts += np.bincount(index, weights=weight, minlength=edges.size - 1)
        moments += np.bincount(index, weights=weight * q, minlength=edges.size - 1)
    used = counts > 0.0
    return moments[used] / counts[used], counts[used]


def _disc(x0, y0, radius, pixel):
    """r² (√(Rε)²) from (x0, y0) at the pixel centres (i, j) × `pixel` within `radius` of it
    (on the plane: a disc inside a periodic cell is its own nearest image)."""
    def span(c):
        return np.arange(np.ceil((c - radius) / pixel), np.floor((c + radius) / pixel) + 1)

    r2 = ((span(x0) * pixel - x0)[:, None] ** 2 + (span(y0) * pixel - y0)[None, :] ** 2)
    return r2[r2 < radius**2]


def _squared(gx, gy, x0, y0, side, periodic):
    """r² (√(Rε)²) from (x0, y0) at the pixel centres (gx, gy); to the nearest image if
    periodic."""
    dx, dy = gx[:, None] - x0, gy[None, :] - y0
    if periodic:
        dx = dx - side[0] * np.round(dx / side[0])
        dy = dy - side[1] * np.round(dy / side[1])
    return dx**2 + dy**2


def _edges(lowest, fine_lo, fine_hi, highest, d_lo):
    """Bin edges of q from `lowest` to `highest` (ε): one bin below `fine_lo` (gaps there are
    below CONTACT_GAP, left out, at every separation), Q_STEP up to `fine_hi`, then growing so
    that the least gap in a bin, q + `d_lo`, grows by Q_GROWTH per bin."""
    fine_lo, fine_hi = max(fine_lo, lowest), max(fine_hi, fine_lo + Q_STEP)
    edges = [np.array([lowest])] if lowest < fine_lo else []
    edges.append(np.arange(fine_lo, fine_hi + Q_STEP, Q_STEP))
    top = edges[-1][-1]
    if highest > top:
        count = int(np.ceil(np.log((highest + d_lo) / (top + d_lo)) / np.log(Q_GROWTH))) + 1
        edges.append((top + d_lo) * Q_GROWTH ** np.arange(1, count + 1) - d_lo)
    return np.concatenate(edges)
