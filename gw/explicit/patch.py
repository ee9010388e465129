"""What a free patch leaves out of an isolated cap: the LJ force beyond its edges."""

import numpy as np

from fem_asperity.closed_forms.lj import scaled_traction

#: Quadrature of `force_beyond`: a midpoint grid of 0.01 √(Rε) out to 60 √(Rε) (the tail
#: beyond, (16/3)·60⁻⁴ = 4e-7 of 2πRΔγ, is left out).
STEP, REACH = 0.01, 60.0


def force_beyond(d, *, width, mu, force):
    """The LJ force (2πRΔγ, < 0 attractive) between a cap z = −r²/2R centred on a square free
    patch `width` √(Rε) wide and the flat beyond the patch, at separation `d` (ε), the flat
    lifted there by the Boussinesq far field of the patch's total `force` (2πRΔγ): the gap is
    d + r̄²/2 + 2μ^1.5 P̄/r̄ (at r̄ = 4, μ = 1 the lift moves the tail by about 15 %). Adding it to
    the patch's force gives the isolated cap's, to compare with the axisymmetric solvers."""
    x = (np.arange(int(2 * REACH / STEP)) + 0.5) * STEP - REACH
    r = np.hypot(x[:, None], x[None, :])
    beyond = (np.abs(x)[:, None] > width / 2) | (np.abs(x)[None, :] > width / 2)
    gap = d + r[beyond] ** 2 / 2 + 2 * mu**1.5 * force / r[beyond]
    return float(scaled_traction(gap).sum() * STEP * STEP / (2 * np.pi))
