"""Lennard-Jones 9-3 surface law and its closed-form integrals over a rigid sphere (eqs. 4, 8).

Sign convention: traction p > 0 is repulsive (compressive), p < 0 attractive (tensile).
Gaps are in units of ε (h̄ = h/ε); forces in 2πRΔγ; deflections in ε, positive toward the sphere.
"""

import numpy as np

from ..plumbing.checks import finite_result, positive

#: ∫₀^∞(1+t²)⁻⁹dt / ∫₀^∞(1+t²)⁻³dt, the constant of eq. (4).
K_9_3 = 2145.0 / 4096.0
#: Most tensile traction (at h = 3^(1/6) ε) in units of Δγ/ε: −16/(9√3) = −1.0264.
MAX_TENSION = -16.0 / (9.0 * np.sqrt(3.0))


def traction(h, *, dgamma=1.0, eps=1.0):
    """LJ 9-3 traction p(h) = (8Δγ/3ε)[(ε/h)⁹ − (ε/h)³].

    With the defaults (dgamma = eps = 1) `h` is the gap in ε and p comes in Δγ/ε;
    with dgamma in J/m² and eps, h in m, p comes in Pa. Requires h > 0.
    """
    dgamma, eps = positive("dgamma", dgamma), positive("eps", eps)
    return dgamma / eps * scaled_traction(positive("h", h) / eps)


def scaled_traction(h):
    """p̄(h̄) = (8/3)(h̄⁻⁹ − h̄⁻³) in Δγ/ε for a gap h̄ in ε, unchecked (inner loops; h̄ > 0)."""
    s3 = h**-3.0
    return 8.0 / 3.0 * (s3 * s3 * s3 - s3)


def scaled_potential(h):
    """φ̄(h̄) = ∫_h̄^∞ p̄ = (1/3)h̄⁻⁸ − (4/3)h̄⁻² in Δγ (φ̄(1) = −1: the work of adhesion), unchecked."""
    s2 = h**-2.0
    return (s2**4 - 4.0 * s2) / 3.0


def scaled_traction_slope(h):
    """dp̄/dh̄ = (8/3)(−9h̄⁻¹⁰ + 3h̄⁻⁴) in Δγ/ε², unchecked (inner loops; h̄ > 0)."""
    s = 1.0 / h
    s4 = s**4
    return 8.0 * (s4 - 3.0 * s4 * s4 * s * s)


def traction_slope(h, *, dgamma=1.0, eps=1.0):
    """dp/dh = (8Δγ/3ε²)[−9(ε/h)¹⁰ + 3(ε/h)⁴], the tangent stiffness of the LJ springs.

    Units as in `traction`, divided by the unit of h (Δγ/ε² by default, Pa/m in SI).
    """
    dgamma, eps = positive("dgamma", dgamma), positive("eps", eps)
    return dgamma / eps**2 * scaled_traction_slope(positive("h", h) / eps)


def bradley_force(delta):
    """Force on a rigid sphere over a rigid flat at separation δ̄ (eq. 8): (δ̄⁻⁸ − 4δ̄⁻²)/3.

    `delta` in ε (> 0); force in 2πRΔγ, negative = attractive; minimum −1 at δ̄ = 1 (Bradley).
    """
    d = np.asarray(positive("delta", delta))
    with np.errstate(over="ignore"):
        force = (d**-8 - 4.0 * d**-2) / 3.0
    force = finite_result(force, lambda: f"Bradley's force at delta = {np.min(d):g}")
    return float(force) if force.ndim == 0 else force


def rigid_force(delta, *, radius_ratio=None):
    """Force on a rigid sphere over a rigid flat at separation δ̄ (ε, > 0), in 2πRΔγ (< 0
    attractive): Bradley's (`bradley_force`, Derjaguin's parabola) where `radius_ratio` is None,
    else that of the exact sphere's lower half, as `path.surface.derjaguin_profile` gives it,
    ρ = R/ε: ∫₀^ρ p̄(δ̄ + h)(1 − h/ρ) dh (r dr = (1 − h/ρ) dh on it), in closed form. It tends
    to Bradley's as ρ → ∞ and falls off faster beyond δ̄ ~ ρ."""
    if radius_ratio is None:
        return bradley_force(delta)
    d, rho = np.asarray(positive("delta", delta)), positive("radius_ratio", radius_ratio)

    def pulled(s):  # ∫ p̄ ds, and ∫ s p̄ ds
        return -(s**-8.0) / 3.0 + 4.0 / 3.0 * s**-2.0, 8.0 / 3.0 * (-(s**-7.0) / 7.0 + 1.0 / s)

    with np.errstate(over="ignore"):
        (f_near, g_near), (f_far, g_far) = pulled(d), pulled(d + rho)
        force = (f_far - f_near) - (g_far - g_near - d * (f_far - f_near)) / rho
    force = finite_result(force, lambda: f"the sphere's force at delta = {np.min(d):g}")
    return float(force) if force.ndim == 0 else force


def centre_deflection(x, *, mu):
    """Elastic deflection h̄o at r = 0 under the LJ traction of a rigid sphere at gap x̄o (eq. 4).

    h̄o = √2 π μ^(3/2) [x̄o^(−5/2) − (2145/4096) x̄o^(−17/2)], in ε, positive toward the sphere
    (Boussinesq integral over the undeformed surface). `x` in ε (> 0), `mu` > 0.
    """
    x = positive("x", x)
    mu = positive("mu", mu)
    return np.sqrt(2.0) * np.pi * mu**1.5 * (x**-2.5 - K_9_3 * x**-8.5)


def separation_from_gap(x, *, mu):
    """Minimum surface separation δ̄o = x̄o + h̄o(x̄o) (eq. 5), in ε."""
    return positive("x", x) + centre_deflection(x, mu=mu)
