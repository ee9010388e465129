"""F̄(d̃) and S̄(d̃) of a GW rough surface for any asperity law (eqs. 22-28), and F̄max.

    F̄(d̃) = ∫ P̄(ζ(d̃ − z̃)) φ̃(z̃) dz̃,    S̄(d̃) = ∫ Ā(ζ(d̃ − z̃)) φ̃(z̃) dz̃,

with F̄ = F/(2πR A₀ Δγ η) (negative = tensile) and S̄ = S/(R A₀ η ε). The integrals are taken in the
asperity separation δ̄o = ζ(d̃ − z̃) over the heights |z̃| ≤ WINDOW/ω, split at the law's
breakpoints (δ̄oc, δ̄o*, a jump). Each piece is cut into 20 equal panels, the two end panels
refined geometrically toward the ends 12 times (the repulsive law grows like (δ̄oc − δ̄o)^(3/2)
from a breakpoint; the LJ terms vary on the scale ε, possibly far below the Gaussian's σ), with 5
Gauss-Legendre points per panel: 220 law evaluations per piece and d̃. Against adaptive
quadrature the relative error is ≤ 9e-10 over μ 0.1-47, ζ 0.05-500, ω 0.2-1. Vectorised over d̃.
"""

from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize_scalar

from fem_asperity.plumbing.checks import in_range

from .surface import height_pdf

#: Heights beyond ±WINDOW/ω are left out: the Gaussian beyond 12 carries < 1e-31 (at 9 the
#: deep-asperity repulsion left out was 1.6e-3 of a tiny F̄ at ζ = 500). Gauss points per panel,
#: equal panels per piece and geometric levels of each end panel: as above. All four pinned by
#: test_gw.py::test_totals_match_adaptive_quadrature_to_1e8.
WINDOW = 12.0
#: Largest |d̃| taken: far beyond any asperity (12/ω) and the LJ range, yet small enough that
#: ζ(d̃ ± 12/ω) stays finite (d̃ = 1e307 gave NaN). test_gw's bad-input test pins it.
D_MAX = 1e6
_GAUSS = np.polynomial.legendre.leggauss(5)
_UNIFORM, _LEVELS = 20, 12


def _template():
    """Nodes and weights on [0, 1]: equal panels, the end ones graded toward 0 and 1."""
    u = 1.0 / _UNIFORM
    graded = u * 2.0 ** -np.arange(_LEVELS, 0, -1)
    edges = np.concatenate([[0.0], graded, np.arange(1, _UNIFORM) * u, 1.0 - graded[::-1], [1.0]])
    x, w = _GAUSS
    left, width = edges[:-1, None], np.diff(edges)[:, None]
    return (left + 0.5 * width * (x + 1.0)).ravel(), (0.5 * width * w).ravel()


_NODES, _WEIGHTS = _template()


def totals(law, surface, d):
    """(F̄, S̄) at the mean separations `d` (d̃, in σ; array or scalar) for `law` on `surface`."""
    d = np.atleast_1d(in_range("d", d, -D_MAX, D_MAX)).astype(float)
    zeta, omega = surface.zeta, surface.omega
    lo, hi = zeta * (d - WINDOW / omega), zeta * (d + WINDOW / omega)  # δ̄o range per d̃
    cuts = [lo] + [np.clip(b, lo, hi) for b in law.breakpoints] + [hi]
    force, area = np.zeros(d.size), np.zeros(d.size)
    for a, b in zip(cuts[:-1], cuts[1:]):
        delta = a[:, None] + (b - a)[:, None] * _NODES
        weight = (b - a)[:, None] * _WEIGHTS * height_pdf(d[:, None] - delta / zeta, omega) / zeta
        force += np.sum(weight * law.force(delta), axis=1)
        area += np.sum(weight * law.area(delta), axis=1)
    return force, area


@dataclass(frozen=True)
class Strength:
    """Strength of adhesion F̄max = −min F̄ (positive) and the d̃ where it occurs."""

    f_max: float
    d_at_max: float


def separation_range(law, surface):
    """(d̃_lo, d̃_hi) where F̄ and S̄ change: from 4 height deviations below the law's lowest
    breakpoint to the height window above its highest."""
    bps = law.breakpoints or (1.0,)
    return (min(bps) / surface.zeta - 4.0 / surface.omega,
            max(bps) / surface.zeta + WINDOW / surface.omega)


def strength(law, surface, *, samples=48):
    """F̄max and its d̃: the lowest of `samples` values of F̄ on a d̃ grid over
    `separation_range`, refined by bounded Brent between its grid neighbours (F̄ can have more
    than one local minimum; the grid picks the deepest)."""
    lo, hi = separation_range(law, surface)
    grid = np.linspace(lo, hi, samples)
    f = totals(law, surface, grid)[0]
    k = int(np.argmin(f))
    a, b = grid[max(k - 1, 0)], grid[min(k + 1, samples - 1)]
    best = minimize_scalar(lambda x: totals(law, surface, x)[0][0], bounds=(a, b),
                           method="bounded", options={"xatol": 1e-10 * max(1.0, abs(hi - lo))})
    d_star, f_star = (best.x, best.fun) if best.fun < f[k] else (grid[k], f[k])
    return Strength(f_max=float(-f_star), d_at_max=float(d_star))
