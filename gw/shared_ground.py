"""The ground GW counts more than once, for summits at random places: a closed form.

GW sums one single-asperity law per summit, and each law integrates the LJ attraction over a
whole paraboloid. Where summits stand closer than the LJ range lets their tails pass each other,
the ground between them is counted by several laws (`gw.explicit.tails` measures it on a map).
For GW's own surface, summits of one radius R at Poisson places of density η with independent
heights of pdf φ̃ (std s̃ = 1/ω in σ, `surface.height_pdf`), the highest cap over a point is
exceedingly simple: the caps above height u there are Poisson with mean

    Λ(ũ) = 2π σRη s̃ G(ũ/s̃),    G(v) = φ(v) − v Q(v)    (φ, Q: the unit normal's pdf and tail),

so the map's height has the distribution F(ũ) = exp(−Λ(ũ)). Taken rigid, the attraction GW
miscounts per summit (F̄, in 2πRΔγ, as GW's) is the map's less the paraboloids':

    T̄(d̃) = (1/(2π ηRε)) ∫ p̄(ζ(d̃ − ũ)) dF(ũ) − ∫ P̄_B(ζ(d̃ − z̃)) φ̃(z̃) dz̃,   ηRε = σRη/ζ,

with p̄ the LJ 9-3 traction (Δγ/ε) and P̄_B its force on a rigid paraboloid, both with gaps below
the LJ's most tensile point held there (as `gw.explicit.tails` does: the rigid map cannot press
in). T̄ → 0 as σRη/ζ → 0 (summits far apart against the LJ range), and F̄ + T̄ never pulls
harder than the LJ's most tensile traction over the whole nominal area does, F̄ ≥ −1.0265 ζ/(2π σRη)
in the rigid limit (`flat_bound`), which GW's sum alone exceeds where summits are dense.

It is a rigid correction: the summits' own elastic response is in the law, the lift of the ground
between them is not (`gw.explicit.interacting` adds that on an explicit map). Against explicit
surfaces solved whole it is measured in docs/rough_explicit.md.
"""

import numpy as np
from scipy.special import ndtr

from fem_asperity.closed_forms.lj import scaled_potential, scaled_traction
from fem_asperity.plumbing.checks import positive

from .surface import height_pdf

#: The gap below which the rigid map's traction is held (ε): the LJ 9-3 traction's most tensile
#: point, as in `gw.explicit.tails`.
PEAK_GAP = 3.0 ** (1.0 / 6.0)
#: |p̄| there (Δγ/ε): (8/3)(3^(-1/2) − 3^(-3/2)) = 1.0265.
PEAK = float(-scaled_traction(PEAK_GAP))
#: Points per unit of log(h/PEAK_GAP) in the gap integrals: the densities vary on σ_s (in h: ζ s̃)
#: and the LJ terms on ε; 400 per e-fold keeps T within 2e-6 of a grid twice as fine
#: (test_shared_ground.py).
PER_E_FOLD = 400
#: Heights below −REACH s̃ carry no summit (the Gaussian's tail beyond 13 is below 1e-37); the
#: map's own lowest ground, far from every cap, reaches deeper: F falls like exp(2π σRη ũ), so the
#: gaps are taken down to where it is e^(−DEPTH).
REACH, DEPTH = 13.0, 40.0


def flat_bound(zeta, sigma_r_eta):
    """The most F̄ (> 0, per summit, 2πRΔγ) any surface with LJ 9-3 tractions can pull with:
    the LJ's most tensile traction over the whole nominal area, PEAK/(2π ηRε)."""
    return PEAK * positive("zeta", zeta) / (2.0 * np.pi * positive("sigma_r_eta", sigma_r_eta))


def shared_ground(surface, sigma_r_eta, d):
    """T̄ at the mean separations `d` (d̃, in σ; array): the F̄ (2πRΔγ per summit, > 0 where GW
    counts attraction twice) to add to GW's F̄ for summits at Poisson places of σRη
    `sigma_r_eta` on `surface` (`RoughSurface`)."""
    sigma_r_eta = positive("sigma_r_eta", sigma_r_eta)
    d = np.atleast_1d(np.asarray(d, dtype=float))
    zeta, spread = surface.zeta, 1.0 / surface.omega
    depth = max(REACH * spread, DEPTH / (2.0 * np.pi * sigma_r_eta))
    h, dh = _gaps(zeta, d, depth)  # (d.size, points), gaps from PEAK_GAP up

    def heights_pdf(u):  # φ̃ of the summits
        return height_pdf(u, surface.omega)

    def map_pdf(u):  # dF/dũ of the highest cap over a point
        return _map_cdf(u, sigma_r_eta, spread) * 2.0 * np.pi * sigma_r_eta * ndtr(-u / spread)

    u = d[:, None] - h / zeta  # the height whose gap is h
    touching = d - PEAK_GAP / zeta  # heights above it are held at the peak
    ground = (-PEAK * (1.0 - _map_cdf(touching, sigma_r_eta, spread))
              + np.sum(scaled_traction(h) * map_pdf(u) * dh, axis=1) / zeta)
    caps = (-PEAK * zeta * spread * _g(touching / spread)
            + float(scaled_potential(PEAK_GAP)) * ndtr(-touching / spread)
            + np.sum(scaled_potential(h) * heights_pdf(u) * dh, axis=1) / zeta)
    return ground * zeta / (2.0 * np.pi * sigma_r_eta) - caps


def _g(v):
    """G(v) = ∫_v^∞ Q(t) dt = φ(v) − v Q(v)."""
    return np.exp(-0.5 * v * v) / np.sqrt(2.0 * np.pi) - v * ndtr(-v)


def _map_cdf(u, sigma_r_eta, spread):
    """F(ũ): the probability that no cap stands above ũ over a point."""
    return np.exp(-2.0 * np.pi * sigma_r_eta * spread * _g(u / spread))


def _gaps(zeta, d, depth):
    """Gaps h ≥ PEAK_GAP (ε) and their trapezoid weights dh, per d̃: log-spaced from PEAK_GAP
    to the gap of the lowest ground that matters, at −`depth` (σ)."""
    top = np.maximum(zeta * (d + depth), 2.0 * PEAK_GAP)
    span = np.log(top / PEAK_GAP)
    count = int(np.ceil(PER_E_FOLD * span.max())) + 1
    t = np.linspace(0.0, 1.0, count)[None, :] * span[:, None]
    h = PEAK_GAP * np.exp(t)
    dt = span[:, None] / (count - 1)
    weight = np.full(h.shape, 1.0)
    weight[:, [0, -1]] = 0.5
    return h, weight * dt * h
