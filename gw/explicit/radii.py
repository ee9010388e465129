"""What one summit radius does to a map's strength of adhesion.

GW and the interacting asperities take every summit of a map as a cap of one radius R (the
mean, `topography.summit_statistics`: R = −1/mean κ, unless the user gives one); a measured
map's summits differ. Here the summits, uncoupled, at their own heights, are summed twice on
the shipped table of solved laws: each with its own radius Rᵢ = −1/κᵢ (force
2πRᵢΔγ P̄(δ̄o; μᵢ), μᵢ = μ (Rᵢ/R)^(1/3), δ̄o = (d − zᵢ)/ε: the law's δ̄o does not scale with R),
and all with R. The relative difference of their F_max is the size of the simplification for
this map, with the heights held as they are. κ is the mean curvature, so Rᵢ is the harmonic
mean of a summit's two principal radii: the anisotropy of elliptic summits (whose Derjaguin
force scales with √(R₁R₂)) is not in the size. With the heights equal and the law rigid
(Bradley's P̄ at every μ), the size is the ratio of the arithmetic to the harmonic mean radius
less one; at μ ~ 1 each summit's law is that solved at its own μᵢ (`tests/test_radii.py`).
"""

from dataclasses import dataclass

import numpy as np

from fem_asperity.plumbing.checks import positive

from ..law_table import shipped_table
from .topography import summits
from .whole import most_tensile


@dataclass(frozen=True)
class RadiusSpread:
    """The summits' own radii against one: `size` (|F_max(own)/F_max(one) − 1|; None where a
    summit's μ, or the one radius's, is outside the table: `note` says so), its `uncertainty`
    (the largest of the table's F̄max errors at the μ used, and each sum's sampling error,
    relative), `f_max_own` and `f_max_one` (N, the largest tensile total on approach,
    positive, each at its own radius and all at the one; None with `size`), the summits' `mu`
    range (lo, hi) and `radii` range (lo, hi, m), and how many `summits`."""

    size: float | None
    uncertainty: float | None
    f_max_own: float | None
    f_max_one: float | None
    mu: tuple
    radii: tuple
    summits: int
    note: str = ""


def own_radii(topography, adhesion, separations, *, radius, mu, table=None):
    """`RadiusSpread` of `topography` (`Topography`, m) with `adhesion` (`Adhesion`): its
    summits each at its own radius against all at `radius` (m; the mean, −1/mean κ, unless the
    user gave one), whose Tabor parameter is `mu`; the totals sampled at `separations` (d, m,
    from the map's datum; `answer`'s grid), on `table` (by default the shipped one)."""
    radius, mu = positive("radius", radius, "m"), positive("mu", mu)
    table = table or shipped_table()
    found = summits(topography)
    radii = -1.0 / found.curvature  # κ < 0 at a pixel above its 8 neighbours
    mus = mu * (radii / radius) ** (1.0 / 3.0)  # μ³ ∝ R at one E*, Δγ, ε
    lo, hi = table.mu_range
    span = dict(mu=(float(mus.min()), float(mus.max())),
                radii=(float(radii.min()), float(radii.max())), summits=int(radii.size))
    outside = int(np.count_nonzero((mus < lo) | (mus > hi)))
    if outside or not lo <= mu <= hi:
        return RadiusSpread(None, None, None, None, **span, note=(
            f"{outside} of {radii.size} summits have mu outside the table of solved laws' "
            f"{lo:g}-{hi:g} at their own radius ({span['mu'][0]:.3g}-{span['mu'][1]:.3g})"
            if outside else f"mu = {mu:.4g} at the radius {radius:.4g} m is outside the table "
            f"of solved laws' {lo:g}-{hi:g}"))
    d = np.asarray(separations, dtype=float) / adhesion.eps
    heights = found.heights / adhesion.eps
    laws = [table.law(m) for m in mus]
    one = table.law(mu)
    unit = 2.0 * np.pi * adhesion.dgamma
    own = unit * sum(r * law.force(d - z) for r, law, z in zip(radii, laws, heights))
    alike = unit * radius * sum(one.force(d - z) for z in heights)
    (f_own, _, sampled_own), (f_one, _, sampled_one) = (most_tensile(d, f) for f in (own, alike))
    uncertainty = max(max(law.f_max_error for law in laws + [one]),
                      sampled_own / f_own, sampled_one / f_one)
    return RadiusSpread(abs(f_own / f_one - 1.0), float(uncertainty), f_own, f_one, **span)
