"""The paper's single-asperity closed-form laws (eqs. 2, 6, 7, 9-19), vectorised over μ and δ̄o.

Units: separations δ̄o, gaps x̄o in ε; forces P̄ in 2πRΔγ (negative = tensile); radii ā in √(εR);
areas Ā in εR. Regimes: μ < mu_jump is continuous approach (eqs. 7, 9, 10, 11, 16, 17);
μ ≥ mu_jump jumps in (eqs. 12-15, 18, 19). The paper leaves μ = 0.5 itself in neither regime;
here it belongs to the jump-in regime, as in its Fig. 9 (μ = 0.5-46.9 with jump-in).
"""

from dataclasses import dataclass, fields

import numpy as np

from ..plumbing.checks import finite_result, in_range, positive
from ..plumbing.errors import InputError
from .lj import bradley_force, separation_from_gap

#: Largest Tabor parameter the closed forms take, far into the JKR limit yet far from where
#: μ^(3/2) in eq. 2 overflows to inf/inf (μ = 1e300 gave NaN). test_cli's bad-input test pins it.
MU_MAX = 1e12


def _mu(mu):
    """μ checked: finite, in (0, MU_MAX)."""
    return in_range("mu", mu, 0.0, MU_MAX)


def wu_pull_off(mu, c_off):
    """Wu's fit of the pull-off force (eq. 2): −(1/8)(7 + (1 − c μ^1.5)/(1 + c μ^1.5)), in 2πRΔγ;
    μ unchecked (for fits that vary c)."""
    k = c_off * mu**1.5
    return -(7.0 + (1.0 - k) / (1.0 + k)) / 8.0


def _out(x):
    """A 0-d result as a Python float or bool, arrays unchanged."""
    return np.asarray(x).item() if np.ndim(x) == 0 else x


@dataclass(frozen=True)
class LawEvents:
    """Events of the approach path that a law predicts, one entry per μ.

    p_max: maximum adhesive force P̄max (< 0); delta_oc: separation δ̄oc at P̄max;
    delta_o_star: separation δ̄o* at first contact; a_c: compressive contact radius ā_c at P̄max;
    jump_in: whether the approach jumps in; x_oc: centre gap x̄oc at jump-in (NaN without one).
    """

    mu: object
    p_max: object
    delta_oc: object
    delta_o_star: object
    a_c: object
    jump_in: object
    x_oc: object

    def records(self):
        """One JSON-ready dict per μ (floats, bools; x_oc None where there is no jump-in, an
        event the law does not give (NaN) None)."""
        columns = np.broadcast_arrays(*(np.atleast_1d(getattr(self, f.name)) for f in fields(self)))
        rows = []
        for values in zip(*columns):
            row = {f.name: None if np.isnan(v) else v.item() for f, v in zip(fields(self), values)}
            row["jump_in"] = bool(row["jump_in"])
            if not row["jump_in"]:
                row["x_oc"] = None
            rows.append(row)
        return rows


@dataclass(frozen=True)
class AsperityLaws:
    """Closed-form single-asperity laws of Song & Komvopoulos with their fit constants.

    The defaults are the paper's; refitted constants are passed in the same way. Constants:
    c_off (eq. 2), c_a and mu_a (eq. 6b: ā_c = c_a (μ − mu_a)^½), c_oc (eq. 7: δ̄oc = 1 + c_oc μ),
    c_star (eq. 10: δ̄o* = 1 + c_star μ^(3/2)), x_0 and x_1 (eq. 12: x̄oc = x_0 + x_1 μ^(2/5)),
    mu_jump (the Tabor parameter from which the approach jumps in).
    """

    c_off: float = 1.98
    c_a: float = 0.83
    mu_a: float = 0.19
    c_oc: float = 0.922
    c_star: float = 2.116
    x_0: float = -0.3
    x_1: float = 2.2
    mu_jump: float = 0.5

    def __post_init__(self):
        for name in ("c_off", "c_a", "mu_a", "c_oc", "c_star"):
            in_range(name, getattr(self, name), 0.0, closed_lo=True)
        in_range("x_0", self.x_0)
        positive("x_1", self.x_1)
        positive("mu_jump", self.mu_jump)
        x_at_jump = self.x_0 + self.x_1 * self.mu_jump**0.4
        if x_at_jump <= 0.0:
            raise InputError(
                "x_0 + x_1 * mu_jump**0.4 (the jump-in gap at mu_jump) must be > 0; "
                f"got {x_at_jump!r}"
            )

    def jump_in(self, mu):
        """True where the approach jumps in (μ ≥ mu_jump)."""
        return _out(_mu(mu) >= self.mu_jump)

    def p_max(self, mu):
        """Maximum adhesive force, Wu's fit (eq. 2) with c = c_off (`wu_pull_off`)."""
        return _out(wu_pull_off(_mu(mu), self.c_off))

    def a_c(self, mu):
        """Compressive contact radius at P̄max (eq. 6): c_a (μ − mu_a)^½, zero below mu_a."""
        mu = _mu(mu)
        return _out(self.c_a * np.sqrt(np.maximum(mu - self.mu_a, 0.0)))

    def _jump_gap(self, mu):
        """x̄oc of eq. (12), evaluated at max(μ, mu_jump) so that it is positive for every μ."""
        return self.x_0 + self.x_1 * np.maximum(mu, self.mu_jump) ** 0.4

    def x_oc(self, mu):
        """Centre gap at jump-in, eq. (12); NaN where there is no jump-in (μ < mu_jump)."""
        mu = np.asarray(_mu(mu))
        return _out(np.where(mu >= self.mu_jump, self._jump_gap(mu), np.nan))

    def _jump_separation(self, mu):
        """δ̄oc = δ̄o* at jump-in, eqs. (12) + (4) + (5) = eq. (13)."""
        return separation_from_gap(self._jump_gap(mu), mu=mu)

    def delta_oc(self, mu):
        """Separation at P̄max: eq. (7) 1 + c_oc μ below mu_jump, eq. (13) from it on."""
        mu = np.asarray(_mu(mu))
        return _out(np.where(mu >= self.mu_jump, self._jump_separation(mu), 1.0 + self.c_oc * mu))

    def delta_o_star(self, mu):
        """Separation at first contact: eq. (10) 1 + c_star μ^1.5 below mu_jump, eq. (13) from it
        on."""
        mu = np.asarray(_mu(mu))
        continuous = 1.0 + self.c_star * mu**1.5
        return _out(np.where(mu >= self.mu_jump, self._jump_separation(mu), continuous))

    def force(self, delta_o, *, mu):
        """Force P̄(δ̄o) on approach (eqs. 9, 14, 16, 18), broadcast over δ̄o and μ.

        Above δ̄oc: eq. (9) (Bradley's law scaled to pass through P̄max) without jump-in, eq. (14)
        (Bradley's law itself) with it; below δ̄oc: P̄max plus Hertz (eqs. 16, 18).
        """
        delta_o, mu = np.broadcast_arrays(in_range("delta_o", delta_o), _mu(mu))
        with np.errstate(over="ignore"):
            force = _force(delta_o, mu, *self._force_constants(mu))
        return _out(finite_result(force, "the force (the Hertz compression (δ̄oc − δ̄o)/μ "
                                         "raised to 3/2)"))

    def area(self, delta_o, *, mu):
        """Contact area Ā(δ̄o) on approach (eqs. 11, 15, 17, 19), broadcast over δ̄o and μ.

        Zero above δ̄o*; below it π(δ̄o* − δ̄o) without jump-in, π(ā_c² + δ̄o* − δ̄o) with it.
        """
        delta_o, mu = np.broadcast_arrays(in_range("delta_o", delta_o), _mu(mu))
        with np.errstate(over="ignore"):
            area = _area(delta_o, *self._area_constants(mu))
        return _out(finite_result(area, "the area π(δ̄o* − δ̄o)"))

    def _force_constants(self, mu):
        """(δ̄oc, P̄max, scale of Bradley's law above δ̄oc) at μ (arrays broadcast)."""
        doc, p_max, jump = self.delta_oc(mu), self.p_max(mu), mu >= self.mu_jump
        return doc, p_max, np.where(jump, 1.0, p_max / bradley_force(np.where(jump, 1.0, doc)))

    def _area_constants(self, mu):
        """(δ̄o*, ā_c² of the jump or 0) at μ."""
        return self.delta_o_star(mu), np.where(mu >= self.mu_jump, self.a_c(mu) ** 2, 0.0)

    def at(self, mu):
        """The laws at one μ as a fast `LawAtMu` (constants evaluated once, δ̄o unchecked)."""
        mu = float(_mu(mu))
        force = tuple(float(c) for c in self._force_constants(mu))
        return LawAtMu(mu, force, tuple(float(c) for c in self._area_constants(mu)))

    def events(self, mu):
        """All approach events at Tabor parameter(s) `mu` as a `LawEvents`."""
        return LawEvents(
            mu=_out(np.asarray(_mu(mu))),
            p_max=self.p_max(mu),
            delta_oc=self.delta_oc(mu),
            delta_o_star=self.delta_o_star(mu),
            a_c=self.a_c(mu),
            jump_in=self.jump_in(mu),
            x_oc=self.x_oc(mu),
        )


def _force(delta_o, mu, doc, p_max, scale):
    """Eqs. 9/14 above δ̄oc, 16/18 below; each branch evaluated on its own domain only (the
    other branch's δ̄o⁻⁸ or negative root never computed)."""
    attractive = delta_o >= doc
    far = np.where(attractive, delta_o, doc)
    near = np.where(attractive, doc, delta_o)
    repulsion = p_max + 2.0 / (3.0 * np.pi) * ((doc - near) / mu) ** 1.5
    return np.where(attractive, scale * bradley_force(far), repulsion)


def _area(delta_o, d_star, jumped):
    """Eqs. 11/17 (jumped = 0) and 15/19 (jumped = ā_c²)."""
    return np.where(delta_o < d_star, np.pi * (jumped + d_star - delta_o), 0.0)


@dataclass(frozen=True)
class LawAtMu:
    """`AsperityLaws` at one μ: force(δ̄o) and area(δ̄o) for arrays of already valid δ̄o."""

    mu: float
    force_constants: tuple
    area_constants: tuple

    def force(self, delta_o):
        return _force(np.asarray(delta_o, dtype=float), self.mu, *self.force_constants)

    def area(self, delta_o):
        return _area(np.asarray(delta_o, dtype=float), *self.area_constants)


#: The laws with the paper's constants.
PAPER_LAWS = AsperityLaws()
