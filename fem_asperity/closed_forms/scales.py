"""Physical inputs of one adhesive asperity contact, the Tabor parameter and the natural scales.

All physical quantities are SI: moduli in Pa, work of adhesion in J/m², lengths in m, forces in N.
With R/ε large (Derjaguin regime) the dimensionless single-asperity problem depends on μ alone;
the scales here convert between the two worlds: vertical ε, radial √(Rε), force 2πRΔγ, area εR.
"""

from dataclasses import dataclass, field

import numpy as np

from ..plumbing.checks import derjaguin, in_range, poisson, positive
from ..plumbing.errors import InputError

#: Supported ranges of the physical inputs (SI): any solid and LJ system, μ and the scales finite
#: in double precision (methods.md §13); test_cli's bad-input test pins them.
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
        if (E_star is None) == (dgamma is None):
            raise InputError("give exactly one of E_star or dgamma; the other is chosen for mu")
        with np.errstate(over="ignore", divide="ignore"):  # refused below, by what it needs
            ratio = np.float64(mu) ** 1.5 * np.sqrt(eps**3 / R)  # Δγ / E*
            if E_star is None:
                E_star = _within("dgamma", dgamma, ADHESION_RANGE, "J/m^2") / ratio
                needed, value, bounds, unit = "E_star", E_star, MODULUS_RANGE, "Pa"
            else:
                dgamma = _within("E_star", E_star, MODULUS_RANGE, "Pa") * ratio
                needed, value, bounds, unit = "dgamma", dgamma, ADHESION_RANGE, "J/m^2"
        if not bounds[0] <= value < bounds[1]:
            raise InputError(f"mu = {mu:g} with these inputs needs {needed} = {value:.3g} "
                             f"{unit}, outside the supported [{bounds[0]:g}, {bounds[1]:g}) {unit}")
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
        error estimate) in SI by their key's kind (`si_unit`): forces (p_*) in N, separations
        and gaps (delta_*, x_*, and z_*: a cantilever's far end) in m, contact radii (a_*) in m;
        other keys and None values are left out."""
        scale = {"N": self.force, "m_z": self.length_z, "m_r": self.length_r}
        return {key: value * scale[_scale_of(key)] for key, value in values.items()
                if _scale_of(key) and isinstance(value, float)}

    def si_columns(self, values):
        """`to_si` with each key suffixed by its unit (p_max → p_max_N, a_c → a_c_m): columns
        that sit next to the dimensionless ones in a table or CSV."""
        return {f"{key}_{si_unit(key)}": value for key, value in self.to_si(values).items()}

    def at_mu(self, mu):
        """Each physical input that alone puts this contact at Tabor parameter `mu`, the other
        three held: {'E_star': Pa, 'R': m, 'dgamma': J/m², 'eps': m}, from eq. (1),
        μ³ = RΔγ²/(E*²ε³). μ grows with R and Δγ and falls with E* and ε."""
        cube = positive("mu", mu) ** 3
        E, g, eps, R = self.E_star, self.dgamma, self.eps, self.R
        return {"E_star": float(np.sqrt(R * g**2 / (cube * eps**3))),
                "R": float(cube * E**2 * eps**3 / g**2),
                "dgamma": float(np.sqrt(cube * E**2 * eps**3 / R)),
                "eps": float(np.cbrt(R * g**2 / (cube * E**2)))}


def _scale_of(key):
    """Which scale converts the event `key`: 'N' (p_*), 'm_z' (delta_*, x_*, z_*), 'm_r' (a_*),
    or None."""
    return {"p": "N", "delta": "m_z", "x": "m_z", "z": "m_z", "a": "m_r"}.get(key.split("_")[0])


def si_unit(key):
    """SI unit of the event `key` ('N' or 'm'), None for keys without one (mu, jump_in)."""
    kind = _scale_of(key)
    return kind and kind[0]
