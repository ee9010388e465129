"""Reference solutions of sphere-on-flat contact (Hertz, JKR, DMT, Maugis-Dugdale), dimensionless.

Units are the paper's: forces in 2πRΔγ (negative = tensile), lengths along z in ε, radii in
√(εR); `mu` is the Tabor parameter. They are independent of the LJ model and serve as checks.
"""

from typing import NamedTuple

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from ..plumbing.checks import in_range, positive
from ..plumbing.errors import InputError
from .lj import MAX_TENSION

#: Maugis' λ per Tabor μ when the Dugdale stress equals the LJ peak tension 16Δγ/(9√3 ε):
#: λ = 2σ₀ (9R / (16πΔγE*²))^(1/3) = 2·1.0264·(3/4)^(2/3)/π^(1/3) μ = 1.1570 μ.
MD_LAMBDA_PER_MU = -2.0 * MAX_TENSION * 0.75 ** (2.0 / 3.0) / np.pi ** (1.0 / 3.0)


class PullOff(NamedTuple):
    """Maximum tensile force `force` (in 2πRΔγ, < 0) and the contact radius `radius` there."""

    force: float
    radius: float


def hertz_force(*, indentation, mu):
    """Hertz force (2/3π)(δ̄/μ)^(3/2) for indentation δ̄ ≥ 0 (in ε); force in 2πRΔγ."""
    d = in_range("indentation", indentation, 0.0, closed_lo=True)
    return 2.0 / (3.0 * np.pi) * (d / positive("mu", mu)) ** 1.5


def hertz_radius(*, indentation):
    """Hertz contact radius ā = √δ̄ (in √(εR)) for indentation δ̄ ≥ 0 (in ε)."""
    return np.sqrt(in_range("indentation", indentation, 0.0, closed_lo=True))


def dmt_force(*, indentation, mu):
    """DMT force: Hertz plus the constant adhesive force −1 (= −2πRΔγ)."""
    return hertz_force(indentation=indentation, mu=mu) - 1.0


def dmt_pull_off():
    """DMT pull-off: force −1 at vanishing contact radius."""
    return PullOff(-1.0, 0.0)


def jkr_force(*, radius, mu):
    """JKR force at contact radius ā (in √(εR)): (2/3π) ā³ μ^(−3/2) − √(2/π) ā^(3/2) μ^(−3/4)."""
    a, mu = in_range("radius", radius, 0.0, closed_lo=True), positive("mu", mu)
    return 2.0 / (3.0 * np.pi) * a**3 * mu**-1.5 - np.sqrt(2.0 / np.pi) * a**1.5 * mu**-0.75


def jkr_approach(*, radius, mu):
    """JKR approach (indentation) at contact radius ā: δ̄ = ā² − √(2πā) μ^(3/4), in ε."""
    a, mu = in_range("radius", radius, 0.0, closed_lo=True), positive("mu", mu)
    return a**2 + _punch_depth(a, mu)


def jkr_radius_at_approach(*, approach, mu):
    """The stable JKR contact radius ā (√(εR)) at approach δ̄ (ε) under displacement control: the
    larger root of `jkr_approach`(ā) = δ̄, at least the radius (π/8)^(1/3) μ^(1/2) where δ̄ is
    least (the fixed-grips pull-off); nan below that least δ̄ (no JKR contact there). One δ̄ at
    a time."""
    if np.ndim(approach):
        raise InputError(f"approach must be one number; got an array of shape "
                         f"{np.shape(approach)}")
    mu, approach = positive("mu", mu), in_range("approach", approach)
    least = (np.pi / 8.0) ** (1.0 / 3.0) * np.sqrt(mu)
    if approach < jkr_approach(radius=least, mu=mu):
        return np.nan
    high = least
    while jkr_approach(radius=high, mu=mu) < approach:
        high *= 2.0
    return brentq(lambda a: jkr_approach(radius=a, mu=mu) - approach, least, high, xtol=1e-14,
                  rtol=4.0 * np.finfo(float).eps)


def jkr_displacement(r, *, radius, mu):
    """Surface displacement into the solid (ε, > 0 pressed in) at radii r (√(εR)) of JKR contact
    of radius ā: the sphere's profile δ̄ − r²/2 inside ā (δ̄ = `jkr_approach`), outside it
    Hertz's for ā plus that of a flat punch of depth −√(2πā) μ^(3/4) (Johnson, Contact
    Mechanics, eqs. 3.42b and 3.36; E* = 1). Far away it tends to Boussinesq's 2μ^(3/2) P̄/r
    for the JKR force P̄."""
    a, mu = positive("radius", radius), positive("mu", mu)
    r = in_range("r", r, 0.0, closed_lo=True)
    hertz, punch = a**2, _punch_depth(a, mu)
    rho = np.maximum(r / a, 1.0)
    outside = (hertz / np.pi * ((2.0 - rho**2) * np.arcsin(1.0 / rho) + np.sqrt(rho**2 - 1.0))
               + 2.0 * punch / np.pi * np.arcsin(1.0 / rho))
    return np.where(r <= a, hertz + punch - 0.5 * r**2, outside)


def jkr_compressive_radius_at(*, radius, mu):
    """Radius (√(εR)) of the compressive zone of JKR contact of radius ā, where Hertz's pressure
    and the flat punch's tension cancel: ā √(1 + d/(2ā²)) for the punch depth d = −√(2πā)
    μ^(3/4); 0 where the tension wins everywhere. At the pull-off radius, eq. A9's ā/√3."""
    a, mu = positive("radius", radius), positive("mu", mu)
    return a * np.sqrt(np.maximum(1.0 + _punch_depth(a, mu) / (2.0 * a**2), 0.0))


def _punch_depth(radius, mu):
    """JKR's flat-punch depth −√(2πā) μ^(3/4) (ε) at contact radius ā, as `jkr_approach`'s."""
    return -np.sqrt(2.0 * np.pi * radius) * mu**0.75


def jkr_pull_off(*, mu):
    """JKR maximum tension −3/4 at contact radius ā = (9π/8)^(1/3) μ^(1/2) (eq. A3)."""
    return PullOff(-0.75, (9.0 * np.pi / 8.0) ** (1.0 / 3.0) * np.sqrt(positive("mu", mu)))


def jkr_compressive_radius(*, mu):
    """Radius of the compressive zone at JKR maximum tension, ā_c = ā/√3 = 0.8794 μ^(1/2)
    (eq. A9)."""
    return jkr_pull_off(mu=mu).radius / np.sqrt(3.0)


def _t_minus_arctan(t):
    """t − arctan t without cancellation for small t."""
    small = t < 1e-2
    ts = np.where(small, t, 0.0)
    series = ts**3 / 3 - ts**5 / 5 + ts**7 / 7 - ts**9 / 9
    return np.where(small, series, t - np.arctan(np.where(small, 1.0, t)))


def _maugis_curve(lam, t):
    """Maugis-Dugdale solution (Johnson & Greenwood 1997 units) along t = √(m² − 1), m = c/a.

    Returns the contact radius Ā = a (4E*/3πΔγR²)^(1/3) and the force P/(πΔγR).
    """
    at, tma = np.arctan(t), _t_minus_arctan(t)
    root = np.sqrt(1.0 + t**2)
    s1 = tma + t**2 * at  # √(m²−1) + (m²−2) arctan √(m²−1)
    s2 = -t * tma + t**2 * root / (1.0 + root)  # √(m²−1) arctan √(m²−1) − m + 1
    a, b = lam * s1 / 2.0, 4.0 * lam**2 * s2 / 3.0
    radius = 2.0 / (b + np.sqrt(b**2 + 4.0 * a))  # positive root of a Ā² + b Ā − 1 = 0
    force = radius**3 - lam * radius**2 * (t + root**2 * at)
    return radius, force


def maugis_dugdale_pull_off(*, mu):
    """Maugis-Dugdale maximum tension (load control) with λ = 1.1570 μ, and ā there.

    The radius is that of the zero-gap zone. Tends to DMT (−1, 0) as μ → 0 and to
    JKR (−3/4, (9π/8)^(1/3) μ^(1/2)) as μ → ∞. Resolved for 1e-6 ≲ μ ≲ 1e8; arrays of μ
    give a `PullOff` of arrays.
    """
    mu = positive("mu", mu)
    if np.ndim(mu):
        each = [maugis_dugdale_pull_off(mu=m) for m in np.ravel(mu)]
        return PullOff(*(np.reshape(v, np.shape(mu)) for v in zip(*each)))
    lam = MD_LAMBDA_PER_MU * mu
    log_t = np.linspace(-8.0, 8.0, 3201)
    i = int(np.argmin(_maugis_curve(lam, 10.0**log_t)[1]))
    if i in (0, log_t.size - 1):
        raise InputError("mu must be in about [1e-6, 1e8] for the Maugis-Dugdale solver; "
                         f"got {mu!r}")
    best = minimize_scalar(
        lambda x: _maugis_curve(lam, 10.0**x)[1],
        bounds=(log_t[i - 1], log_t[i + 1]),
        method="bounded",
        options={"xatol": 1e-12},
    )
    radius, force = _maugis_curve(lam, 10.0**best.x)
    return PullOff(force / 2.0, radius * (3.0 * np.pi / 4.0) ** (1.0 / 3.0) * np.sqrt(mu))
