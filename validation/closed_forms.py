"""Checks of the paper's closed-form laws against exact arithmetic and reference solutions.

These need no FE: each compares a printed constant or limit of the laws with a value derived
independently (exact integrals, JKR, DMT, Maugis-Dugdale). The FE verdicts come in later stages.
"""

from dataclasses import dataclass

import numpy as np

from fem_asperity.closed_forms import lj, reference
from fem_asperity.closed_forms.laws import PAPER_LAWS


@dataclass(frozen=True)
class Check:
    """One claim or constant of the paper, what we found and the verdict.

    verdict: 'holds' if |found − expected| ≤ tol, 'fails' otherwise, 'note' where the paper
    states no tolerance and the numbers are reported for the reader to judge.
    """

    claim: str
    source: str
    found: float
    expected: float
    tol: float | None
    how: str

    @property
    def verdict(self):
        if self.tol is None:
            return "note"
        return "holds" if abs(self.found - self.expected) <= self.tol else "fails"

    def as_dict(self):
        return {"claim": self.claim, "source": self.source, "found": self.found,
                "expected": self.expected, "tol": self.tol, "verdict": self.verdict,
                "how": self.how}


def closed_form_checks(laws=PAPER_LAWS):
    """The checks that closed forms alone can settle, as a list of `Check`."""
    exact_c_star = np.sqrt(2.0) * np.pi * (1.0 - lj.K_9_3)
    mu_cross = (laws.c_oc / laws.c_star) ** 2  # 1 + c_oc μ = 1 + c_star μ^1.5
    below, at = np.nextafter(laws.mu_jump, 0.0), laws.mu_jump
    md_mu = np.logspace(-2, 2, 41)
    md_gap = np.max(np.abs(laws.p_max(md_mu) - reference.maugis_dugdale_pull_off(mu=md_mu).force))
    x_one = ((1.0 - laws.x_0) / laws.x_1) ** 2.5
    return [
        Check("eq. 10 constant 2.116 = sqrt(2) pi (1 - 2145/4096)", "eq. 10",
              laws.c_star, exact_c_star, 5e-4,
              "exact value; tol = half a unit of the printed digit"),
        Check("eqs. 7 and 10 cross at mu = 0.19 (a_c > 0 from there on)", "eqs. 6, 7, 10",
              mu_cross, laws.mu_a, 5e-3, "(0.922/2.116)^2; tol = half a unit of the printed digit"),
        Check("eq. 2 tends to DMT (-1) as mu -> 0", "eq. 2",
              laws.p_max(1e-6), reference.dmt_pull_off().force, 1e-6, "eq. 2 at mu = 1e-6"),
        Check("eq. 2 tends to JKR (-0.75) as mu -> infinity", "eq. 2",
              laws.p_max(1e6), reference.jkr_pull_off(mu=1.0).force, 1e-6, "eq. 2 at mu = 1e6"),
        Check("eq. 6b slope 0.83 matches JKR compressive radius 0.8794 mu^1/2 'excellently'",
              "eq. 6b, eq. A9", laws.a_c(1e6) / np.sqrt(1e6),
              reference.jkr_compressive_radius(mu=1.0), None, "a_c / mu^1/2 at mu = 1e6"),
        Check("eq. 2 (Wu's LJ fit) vs Maugis-Dugdale pull-off (lambda = 1.157 mu)", "eq. 2",
              md_gap, 0.0, None, "max abs(difference) over 41 mu in [0.01, 100]"),
        Check("delta_oc continuous at mu = 0.5 (eq. 7 below, eq. 13 at)", "eqs. 7, 13",
              laws.delta_oc(below), laws.delta_oc(at), 1e-3, "both sides of mu_jump"),
        Check("delta_o* continuous at mu = 0.5 (eq. 10 below, eq. 13 at)", "eqs. 10, 13",
              laws.delta_o_star(below), laws.delta_o_star(at), 1e-3, "both sides of mu_jump"),
        Check("eq. 19 constant 0.69 = 0.83^2", "eqs. 6b, 19",
              0.69, laws.c_a**2, 5e-3, "tol = half a unit of the printed digit"),
        Check("eq. 12 gives x_oc >= 1 (gap beyond eps) only above this mu", "eq. 12",
              x_one, laws.mu_jump, None, "((1 + 0.3)/2.2)^2.5; eq. 12 is used for mu >= 0.5 only"),
    ]
