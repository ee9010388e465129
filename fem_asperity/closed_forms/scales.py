"""Physical inputs of one adhesive asperity contact, the Tabor parameter and the natural scales.

All physical quantities are SI: moduli in Pa, work of adhesion in J/m², lengths in m, forces in N.
With R/ε large (Derjaguin regime) the dimensionless single-asperity problem depends on μ alone;
the scales here convert between the two worlds: vertical ε, radial √(Rε), force 2πRΔγ, area εR.
"""

from dataclasses import dataclass, field

import numpy as np

from ..plumbing.checks import derjaguin, in_range, poisson, positive
from ..plumbing.errors import InputError

#: Supported ranges of the physical inputs (SI): wide enough for any solid and any LJ system,
#: narrow enough that μ and the natural scales stay finite in double precision (E = 1e300
#: overflowed, 1e-300 divided by zero). test_cli's bad-input test pins them.
MODULUS_RANGE = (1e-3, 1e15)  # Pa
ADHESION_RANGE = (1e-9, 1e3)  # J/m^2
LENGTH_RANGE = (1e-13, 1e2)  # m, eps and R


def _within(name, value, bounds, unit):
    return in_range(name, value, *bounds, unit=unit)


def effective_modulus(*, E1, nu1, E2=None, nu2=None):
    """Effective modulus E* = [(1−ν1²)/E1 + (1−ν2²)/E2]⁻¹ in Pa.

    Leave `E2` and `nu2` out (None) for a rigid second body, E* = E1/(1−ν1²).
    Poisson's ratios must lie in (−1, 0.5).
    """
    compliance = (1.0 - poisson("nu1", nu1) ** 2) / _within("E1", E1, MODULUS_RANGE, "Pa")
    if E2 is None:
        if nu2 is not None:
            raise InputError("nu2 given without E2: give both for an elastic second body, "
                             "neither for a rigid one")
        return 1.0 / compliance
    if nu2 is None:
        raise InputError("E2 given without nu2: Poisson's ratio nu2 in (-1, 0.5) is required")
    E2 = _within("E2", E2, MODULUS_RANGE, "Pa (leave E2 and nu2 out for a rigid body)")
    return 1.0 / (compliance + (1.0 - poisson("nu2", nu2) ** 2) / E2)


def tabor_parameter(*, E_star, dgamma, eps, R):
    """Tabor parameter μ = (R Δγ² / (E*² ε³))^(1/3), eq. (1); dimensionless.

    E_star in Pa, dgamma (work of adhesion) in J/m², eps (equilibrium spacing) and R in m.
    Warns (`DerjaguinWarning`) for R/ε < 300 and refuses R/ε < 10.
    """
    E_star = _within("E_star", E_star, MODULUS_RANGE, "Pa")
    dgamma = _within("dgamma", dgamma, ADHESION_RANGE, "J/m^2")
    eps, R = _within("eps", eps, LENGTH_RANGE, "m"), _within("R", R, LENGTH_RANGE, "m")
    derjaguin(R, eps)
    return np.cbrt(R * dgamma**2 / (E_star**2 * eps**3))


@dataclass(frozen=True)
class Scales:
    """One asperity contact's physical inputs (SI) and the scales of the dimensionless problem.

    Attributes: E_star [Pa], dgamma [J/m²], eps [m], R [m]; `mu` (Tabor parameter) is derived.
    """

    E_star: float
    dgamma: float
    eps: float
    R: float
    mu: float = field(init=False)

    def __post_init__(self):
        mu = tabor_parameter(E_star=self.E_star, dgamma=self.dgamma, eps=self.eps, R=self.R)
        for name in ("E_star", "dgamma", "eps", "R"):
            object.__setattr__(self, name, float(getattr(self, name)))
        object.__setattr__(self, "mu", float(mu))

    @classmethod
    def for_mu(cls, mu, *, eps, R, E_star=None, dgamma=None):
        """Scales with Tabor parameter `mu`, completing whichever of E_star or dgamma is left out.

        Uses Δγ/E* = μ^(3/2) √(ε³/R); exactly one of E_star, dgamma must be given.
        """
        mu = positive("mu", mu)
        eps, R = _within("eps", eps, LENGTH_RANGE, "m"), _within("R", R, LENGTH_RANGE, "m")
        ratio = mu**1.5 * np.sqrt(eps**3 / R)  # Δγ / E*
        if (E_star is None) == (dgamma is None):
            raise InputError("give exactly one of E_star or dgamma; the other is chosen for mu")
        if E_star is None:
            E_star = _within("dgamma", dgamma, ADHESION_RANGE, "J/m^2") / ratio
        else:
            dgamma = _within("E_star", E_star, MODULUS_RANGE, "Pa") * ratio
        return cls(E_star=E_star, dgamma=dgamma, eps=eps, R=R)

    @property
    def length_z(self):
        """Vertical length scale ε [m] (gaps, separations δo, xo)."""
        return self.eps

    @property
    def length_r(self):
        """Radial length scale √(Rε) [m] (contact radius)."""
        return np.sqrt(self.R * self.eps)

    @property
    def force(self):
        """Force scale 2πRΔγ [N] (Bradley's rigid-sphere pull-off)."""
        return 2.0 * np.pi * self.R * self.dgamma

    @property
    def area(self):
        """Area scale εR [m²]."""
        return self.eps * self.R

    @property
    def traction(self):
        """Traction scale Δγ/ε [Pa]."""
        return self.dgamma / self.eps

    def to_si(self, values):
        """The dimensionless event values `values` (key → value, as `Events.records()` or an
        error estimate) in SI by their key's kind: forces (p_*) in N, separations and gaps
        (delta_*, x_*, and z_*: a cantilever's far end) in m, contact radii (a_*) in m; other
        keys and None values are left out."""
        scale = {"p": self.force, "delta": self.length_z, "x": self.length_z,
                 "z": self.length_z, "a": self.length_r}
        return {key: value * scale[key.split("_")[0]] for key, value in values.items()
                if key.split("_")[0] in scale and isinstance(value, float)}
