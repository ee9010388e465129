"""The ground GW counts more than once, for summits at random places: a closed form.

GW sums one single-asperity law per summit, and each law integrates the LJ attraction over a
whole paraboloid. Where summits stand closer than the LJ range lets their tails pass each other,
the ground between them is counted by several laws (`gw.explicit.tails` measures it on a map).
For GW's own surface, summits of one radius R at Poisson places of density η with independent
heights of pdf φ̃ (std s̃ = 1/ω in σ, `surface.height_pdf`), the caps standing above a height u
over a point are Poisson with mean

    Λ(ũ) = 2π σRη s̃ G(ũ/s̃),    G(v) = φ(v) − v Q(v)    (φ, Q: the unit normal's pdf and tail),

so the map's height there has the distribution F(ũ) = exp(−Λ(ũ)). Taken rigid, the map's LJ
force per summit less that of the summits' paraboloids is (an integration by parts joins the two)

    T̄(d̃) = ∫_1^∞ p̄(h) Q(ũ/s̃) [F(ũ) − 1] dh,    ũ = d̃ − h/ζ,

in 2πRΔγ per summit, as GW's F̄ (p̄: the LJ 9-3 traction in Δγ/ε, h the gap in ε). Only the
attraction counts: gaps below 1 ε, where p̄ turns repulsive (contact, each law's own business;
the rigid map cannot press in), are left out of both, as `gw.explicit.tails` does. T̄ > 0 (it
takes attraction away), falls in proportion to σRη as the summits thin out (F − 1 ≈ −Λ), and
keeps F̄ + T̄ within the flat bound F̄ ≤ 1.0264 ζ/(2π σRη) in the rigid limit: the LJ's most
tensile traction over the whole nominal area (`flat_bound`), which GW's sum alone exceeds where
summits are dense against the LJ range.

It is a rigid correction: the summits' own elastic response is in the law, the lift of the ground
between them is not (`gw.explicit.interacting` adds that on an explicit map). Against explicit
surfaces solved whole it is measured in docs/rough_explicit.md.
"""

import numpy as np
from scipy.special import ndtr

from fem_asperity.closed_forms.lj import MAX_TENSION, scaled_potential, scaled_traction
from fem_asperity.plumbing.checks import positive

#: Gaps below this (ε) are left out: the LJ 9-3 traction turns repulsive there (contact), and
#: is zero at it, so T̄ is continuous.
CONTACT_GAP = 1.0
#: Points per unit of log(h/CONTACT_GAP): the densities vary on σ_s (in h: ζ s̃) and the LJ terms
#: on ε; 400 per e-fold keeps T̄ within 1e-5 of a grid twice as fine (test_shared_ground.py).
PER_E_FOLD = 400
#: Heights below −REACH s̃ hold no summit; the gaps are integrated down to where F is e^(−DEPTH),
#: analytically beyond (methods.md §14). Not pinned by a test.
REACH, DEPTH = 13.0, 40.0


def flat_bound(zeta, sigma_r_eta):
    """The most F̄ (> 0, per summit, 2πRΔγ) any surface with LJ 9-3 tractions can pull with:
    the LJ's most tensile traction over the whole nominal area, |p̄|max/(2π ηRε)."""
    return -MAX_TENSION * positive("zeta", zeta) / (
        2.0 * np.pi * positive("sigma_r_eta", sigma_r_eta))


def shared_ground(surface, sigma_r_eta, d):
    """T̄ at the mean separations `d` (d̃, in σ; array): the F̄ (2πRΔγ per summit, > 0 where GW
    counts attraction twice) to add to GW's F̄ for summits at Poisson places of σRη
    `sigma_r_eta` on `surface` (`RoughSurface`)."""
    sigma_r_eta = positive("sigma_r_eta", sigma_r_eta)
    d = np.atleast_1d(np.asarray(d, dtype=float))
    zeta, spread = surface.zeta, 1.0 / surface.omega
    depth = max(REACH * spread, DEPTH / (2.0 * np.pi * sigma_r_eta))
    h, dh = _gaps(zeta, d, depth)  # (d.size, points), from CONTACT_GAP up

    def weight(u):  # Q(ũ/s̃) [F(ũ) − 1] at the height ũ whose gap is h
        return ndtr(-u / spread) * np.expm1(-2.0 * np.pi * sigma_r_eta * spread * _g(u / spread))

    inside = np.sum(scaled_traction(h) * weight(d[:, None] - h / zeta) * dh, axis=1)
    top = h[:, -1]
    beyond = scaled_potential(top) * weight(d - top / zeta)  # ∫_top^∞ p̄ = φ̄(top)
    return inside + beyond


def _g(v):
    """G(v) = ∫_v^∞ Q(t) dt = φ(v) − v Q(v)."""
    return np.exp(-0.5 * v * v) / np.sqrt(2.0 * np.pi) - v * ndtr(-v)


def _gaps(zeta, d, depth):
    """Gaps h ≥ CONTACT_GAP (ε) and their trapezoid weights dh, per d̃: log-spaced from CONTACT_GAP
    to the gap of the ground at −`depth` (σ)."""
    top = np.maximum(zeta * (d + depth), 2.0 * CONTACT_GAP)
    span = np.log(top / CONTACT_GAP)
    count = int(np.ceil(PER_E_FOLD * span.max())) + 1
    t = np.linspace(0.0, 1.0, count)[None, :] * span[:, None]
    h = CONTACT_GAP * np.exp(t)
    weight = np.full(h.shape, 1.0)
    weight[:, [0, -1]] = 0.5
    return h, weight * (span[:, None] / (count - 1)) * h
