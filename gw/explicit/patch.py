"""What a free patch leaves out of an isolated cap: the LJ force beyond its edges."""

import numpy as np

from fem_asperity.closed_forms.lj import scaled_traction

#: Quadrature of `force_beyond` (√(Rε)): radial midpoint step and reach beyond the inscribed
#: circle, and the corners' grid (methods.md §14). Not pinned by a test.
RADIAL_STEP, REACH, STEP = 1e-3, 60.0, 0.01


def force_beyond(d, *, width, mu, force):
    """The LJ force (2πRΔγ, < 0 attractive) between a cap z = −r²/2R centred on a square free
    patch `width` √(Rε) wide and the flat beyond the patch, at separation `d` (ε), the flat
    lifted there by the Boussinesq far field of the patch's total `force` (2πRΔγ): the gap is
    d + r̄²/2 + 2μ^1.5 P̄/r̄ (6 % more tail beyond a patch 8 √(Rε) wide at μ = 1; at μ = 3
    the lift is 2.7 ε at the edge of one 6 wide, where this far-field form falls short). Adding
    it to the patch's force gives the isolated cap's, to compare with the axisymmetric solvers."""
    def traction(r):
        return scaled_traction(d + r**2 / 2 + 2 * mu**1.5 * force / r)

    inner = width / 2  # beyond the square = beyond this circle, less the square's corners
    r = inner + (np.arange(int((REACH - inner) / RADIAL_STEP)) + 0.5) * RADIAL_STEP
    annulus = np.sum(traction(r) * 2 * np.pi * r) * RADIAL_STEP
    x = (np.arange(int(round(width / STEP))) + 0.5) * STEP - width / 2
    rho = np.hypot(x[:, None], x[None, :])
    corners = np.sum(traction(rho[rho > inner])) * STEP * STEP
    return float((annulus - corners) / (2 * np.pi))
