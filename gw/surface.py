"""The Greenwood-Williamson rough surface (eqs. 20-21) and the adhesion parameters θ, ζ, ξ.

Dimensionless: heights z̃ = z/σ and the mean separation d̃ = d/σ in σ; ζ = σ/ε links them to the
asperity separation δ̄o = ζ (d̃ − z̃) in ε. With the Derjaguin scaling the totals F̄ and S̄
depend on μ, ζ and ω only.
"""

from dataclasses import dataclass

import numpy as np

from fem_asperity.plumbing.checks import in_range, positive
from fem_asperity.plumbing.errors import InputError

#: McCool's eq. 20 needs σRη above √(3.717e-4) = 0.019280 for a real ω.
MCCOOL_MIN = float(np.sqrt(3.717e-4))


def omega_mccool(sigma_r_eta):
    """ω = σ_s/σ = [1 − 3.717e-4/(σRη)²]^½ (eq. 20); InputError at or below σRη = 0.019280."""
    x = positive("sigma_r_eta", sigma_r_eta)
    if np.any(np.asarray(x) <= MCCOOL_MIN):
        raise InputError(f"sigma_r_eta must be > {MCCOOL_MIN:.6f} (McCool's eq. 20 has no real "
                         f"omega below it; the GW model is outside its range); got {x!r}")
    return np.sqrt(1.0 - 3.717e-4 / np.asarray(x) ** 2)


def height_pdf(z, omega):
    """φ̃(z̃) = ω/√(2π) exp(−ω² z̃²/2) (eq. 21): asperity heights in units of σ."""
    return omega / np.sqrt(2.0 * np.pi) * np.exp(-0.5 * (omega * np.asarray(z)) ** 2)


def theta(*, zeta, mu):
    """Fuller-Tabor adhesion parameter θ = E* σ^(3/2)/(R^½ Δγ) = (ζ/μ)^(3/2) (eq. 3)."""
    return (positive("zeta", zeta) / positive("mu", mu)) ** 1.5


def zeta_from_theta(theta_value, *, mu):
    """ζ = σ/ε for a given θ and μ: μ θ^(2/3)."""
    return positive("mu", mu) * positive("theta", theta_value) ** (2.0 / 3.0)


def xi(*, zeta, mu):
    """Generalised adhesion parameter ξ = σ/((μ + 1) ε) = ζ/(μ + 1)."""
    return positive("zeta", zeta) / (positive("mu", mu) + 1.0)


@dataclass(frozen=True)
class RoughSurface:
    """GW surface in the paper's dimensionless form: ζ = σ/ε and ω = σ_s/σ ∈ (0, 1]."""

    zeta: float
    omega: float = 1.0

    def __post_init__(self):
        positive("zeta", self.zeta)
        omega = in_range("omega", self.omega)  # a finite real number
        if not 0.0 < omega <= 1.0 + 1e-15:  # 1 itself is GW's default
            raise InputError(f"omega must be in (0, 1]; got {omega!r}")

    @classmethod
    def from_physical(cls, *, sigma, radius, density, eps):
        """From σ [m], asperity radius R [m], areal density η [1/m²] and ε [m]."""
        sigma, radius = positive("sigma", sigma, "m"), positive("radius", radius, "m")
        density, eps = positive("density", density, "1/m^2"), positive("eps", eps, "m")
        return cls(zeta=sigma / eps, omega=float(omega_mccool(sigma * radius * density)))
