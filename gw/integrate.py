"""F̄(d̃) and S̄(d̃) of a GW rough surface for any asperity law (eqs. 22-28), and F̄max.

    F̄(d̃) = ∫ P̄(ζ(d̃ − z̃)) φ̃(z̃) dz̃,    S̄(d̃) = ∫ Ā(ζ(d̃ − z̃)) φ̃(z̃) dz̃,

with F̄ = F/(2πR A₀ Δγ η) (negative = tensile) and S̄ = S/(R A₀ η ε). The integrals are taken in the
asperity separation δ̄o = ζ(d̃ − z̃) over the heights −WINDOW/ω ≤ z̃ ≤ `height_top` (WINDOW/ω, or
higher where the asperities in contact come near it: see TAIL), split at 12/ω and the law's
breakpoints (δ̄oc, δ̄o*, a jump). Each piece is cut into 20 equal panels, the two end panels
refined geometrically toward the ends 12 times (the repulsive law grows like (δ̄oc − δ̄o)^(3/2)
from a breakpoint; the LJ terms vary on the scale ε, possibly far below the Gaussian's σ), with 5
Gauss-Legendre points per panel: 220 law evaluations per piece and d̃. Against adaptive
quadrature the relative error is ≤ 9e-10 over μ 0.1-47, ζ 0.05-500, ω 0.2-1. Vectorised over d̃.
"""

from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize_scalar

from fem_asperity.plumbing.checks import in_range, positive
from fem_asperity.plumbing.errors import InputError

from .shared_ground import shared_ground
from .surface import height_pdf

#: Heights outside ±WINDOW/ω are left out, the top as TAIL says (methods.md §14); it and _GAUSS,
#: _UNIFORM, _LEVELS below: test_gw.py::test_totals_match_adaptive_quadrature_to_1e8.
WINDOW = 12.0
#: Above the contact height z̃c the heights go at least to where the Gaussian has fallen by
#: e^(−TAIL), as a stiff law needs (methods.md §14). Not pinned by a test.
TAIL = 40.0
#: Largest |d̃| taken: far beyond any asperity (12/ω) and the LJ range, yet small enough that
#: ζ(d̃ ± 12/ω) stays finite (d̃ = 1e307 gave NaN). test_gw's bad-input test pins it.
D_MAX = 1e6
#: Largest ζ/μ = θ^(2/3) and 1/μ taken, far from overflow and underflow (methods.md §14);
#: test_gw.py::test_stiff_or_far_inputs_are_refused_up_front pins it.
RATIO_MAX = 1e50
#: Most times `strength` extends its d̃ grid past an end (by the width of `separation_range`,
#: at the same spacing) to bring the deepest F̄ inside it.
EXTENSIONS = 8
#: Relative margin by which an end of the grid must lie below its interior to count as lower
#: (F̄ flat to rounding, e.g. JKR's plateau at large μ, small ζ, is not extended).
FLAT = 1e-12
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


def totals(law, surface, d, *, sigma_r_eta=None):
    """(F̄, S̄) at the mean separations `d` (d̃, in σ; array or scalar) for `law` on `surface`.
    With `sigma_r_eta` (σRη), F̄ counts the ground between summits at random places once
    (`shared_ground`: a rigid correction; S̄ is GW's)."""
    d = np.atleast_1d(in_range("d", d, -D_MAX, D_MAX)).astype(float)
    zeta, omega = surface.zeta, surface.omega
    check_stiffness(law, surface)
    contact = d - min(law.breakpoints or (1.0,)) / zeta  # z̃c
    lo, hi = zeta * (d - height_top(contact, omega)), zeta * (d + WINDOW / omega)  # δ̄o range
    cuts = [lo, *(np.clip(b, lo, hi) for b in law.breakpoints), hi]
    window_top = np.clip(zeta * (d - WINDOW / omega), lo, hi)
    if np.any(window_top > lo):  # heights above 12/ω: their own piece, the Gaussian's bulk kept
        cuts = np.sort([window_top, *cuts], axis=0)
    force, area = np.zeros(d.size), np.zeros(d.size)
    for a, b in zip(cuts[:-1], cuts[1:]):
        delta = a[:, None] + (b - a)[:, None] * _NODES
        weight = (b - a)[:, None] * _WEIGHTS * height_pdf(d[:, None] - delta / zeta, omega) / zeta
        force += np.sum(weight * law.force(delta), axis=1)
        area += np.sum(weight * law.area(delta), axis=1)
    if sigma_r_eta is not None:
        force += shared_ground(surface, sigma_r_eta, d)
    return force, area


def height_top(contact, omega):
    """Highest asperity height z̃ integrated when the asperities reach contact at height
    `contact` (z̃c): WINDOW/ω, or higher once z̃c > 8/ω (`TAIL`)."""
    above = np.maximum(omega * np.asarray(contact, dtype=float), 0.0)
    return np.maximum(WINDOW, np.sqrt(above**2 + 2.0 * TAIL)) / omega


def check_stiffness(law, surface):
    """Refuse ζ/μ or 1/μ beyond RATIO_MAX (`law.mu`; `surface.zeta`, ζ = σ/ε): `InputError`."""
    if not max(surface.zeta, 1.0) / law.mu < RATIO_MAX:
        raise InputError(
            f"zeta/mu and 1/mu must be < {RATIO_MAX:g} for the GW integrals (the asperities' "
            f"repulsion grows like (zeta/mu)^1.5); got zeta = {surface.zeta:g}, mu = {law.mu:g}"
        )


@dataclass(frozen=True)
class Strength:
    """Strength of adhesion F̄max = −min F̄ (positive, in 2πRA₀Δγη) and the d̃ where it occurs
    (in σ)."""

    f_max: float
    d_at_max: float

    def si(self, scales, *, sigma, density):
        """This strength in SI for asperities of `scales` (`fem_asperity.Scales`: 2πRΔγ [N]) on a
        surface of rms height `sigma` [m] and summit density `density` [1/m²]: `StrengthSI`,
        the tension per nominal area F̄max·2πRΔγ·η [Pa] and d̃·σ [m]."""
        sigma, density = positive("sigma", sigma, "m"), positive("density", density, "1/m^2")
        return StrengthSI(pressure_max=self.f_max * scales.force * density,
                          d_at_max=self.d_at_max * sigma)


@dataclass(frozen=True)
class StrengthSI:
    """`Strength` in SI: pressure_max, the largest tension per nominal area F_max/A₀ [Pa]
    (positive); d_at_max, the mean separation where it occurs [m]."""

    pressure_max: float
    d_at_max: float


def separation_range(law, surface):
    """(d̃_lo, d̃_hi) where F̄ and S̄ change: from 4 height deviations below the law's lowest
    breakpoint to the height window above its highest."""
    bps = law.breakpoints or (1.0,)
    return (min(bps) / surface.zeta - 4.0 / surface.omega,
            max(bps) / surface.zeta + WINDOW / surface.omega)


def strength(law, surface, *, samples=48, sigma_r_eta=None):
    """F̄max and its d̃: the lowest of `samples` values of F̄ on a d̃ grid over
    `separation_range`, refined by bounded Brent between its grid neighbours (F̄ can have more
    than one local minimum; the grid picks the deepest).

    While the lowest value sits on an end of the grid (a stiff law, small μ or large ζ, can put
    F̄max above the upper end; a smooth surface, ζ ≪ μ, below the lower one) the grid is extended
    past that end by its first width, at the same spacing, up to EXTENSIONS times. `InputError` if
    F̄max is still not bracketed, if the grid would leave |d̃| < D_MAX, or for ζ/μ or 1/μ beyond
    RATIO_MAX; F̄max is > 0 and finite otherwise. `sigma_r_eta`: as `totals`.
    """
    if samples < 3:
        raise InputError(f"samples must be at least 3; got {samples!r}")
    check_stiffness(law, surface)
    lo, hi = separation_range(law, surface)
    _check_grid(lo, hi, law, surface)
    grid = np.linspace(lo, hi, samples)
    f = totals(law, surface, grid, sigma_r_eta=sigma_r_eta)[0]
    step, width = grid[1] - grid[0], hi - lo
    for extension in range(EXTENSIONS + 1):
        k = _deepest(f)
        if 0 < k < grid.size - 1:
            break
        if extension == EXTENSIONS:
            raise InputError(
                f"F_max not bracketed for mu = {law.mu:g}, zeta = {surface.zeta:g}, omega = "
                f"{surface.omega:g}: F still falls at d/sigma = {grid[k]:g}, {EXTENSIONS} x "
                f"{width:g} beyond the search range {lo:g} to {hi:g}"
            )
        new = grid[k] + (1.0 if k else -1.0) * step * np.arange(1, samples)
        _check_grid(new.min(), new.max(), law, surface)
        f_new = totals(law, surface, new, sigma_r_eta=sigma_r_eta)[0]
        if k:
            grid, f = np.concatenate([grid, new]), np.concatenate([f, f_new])
        else:
            grid, f = np.concatenate([new[::-1], grid]), np.concatenate([f_new[::-1], f])
    best = minimize_scalar(lambda x: totals(law, surface, x, sigma_r_eta=sigma_r_eta)[0][0],
                           bounds=(grid[k - 1], grid[k + 1]), method="bounded",
                           options={"xatol": 1e-10 * max(1.0, abs(width))})
    d_star, f_star = (best.x, best.fun) if best.fun < f[k] else (grid[k], f[k])
    if not f_star < 0.0:  # no adhesion left to resolve (or not finite)
        raise InputError(
            f"F_max not resolved for mu = {law.mu:g}, zeta = {surface.zeta:g}, omega = "
            f"{surface.omega:g}: the lowest F found is {f_star!r}"
        )
    return Strength(f_max=float(-f_star), d_at_max=float(d_star) + 0.0)  # never −0.0


def _deepest(f):
    """Index of the lowest F̄; an end only if below every interior value by more than FLAT."""
    k, inner = int(np.argmin(f)), 1 + int(np.argmin(f[1:-1]))
    return k if f[k] < f[inner] - FLAT * abs(f[inner]) else inner


def _check_grid(lo, hi, law, surface):
    """Refuse a d̃ search range that leaves |d̃| < D_MAX (ζ small beside the law's breakpoints,
    or ω small)."""
    if not (-D_MAX < lo and hi < D_MAX):
        raise InputError(
            f"F_max would be searched at d/sigma from {lo:g} to {hi:g} for mu = {law.mu:g}, "
            f"zeta = {surface.zeta:g}, omega = {surface.omega:g}: outside the supported "
            f"|d/sigma| < {D_MAX:g} (breakpoints/zeta and 12/omega must stay below it)"
        )
