"""Greenwood-Williamson rough surface (Song & Komvopoulos eqs. 20-28) fed by any asperity law.

`RoughSurface` (ζ = σ/ε, ω, or from σ, R, η, ε); laws: `PaperLaw` (the paper's or refitted
constants), `TabulatedLaw` (a solved approach path), `solved_law` (a stored BEM/FE curve);
integrals: `totals` (F̄, S̄ at separations d̃), `strength` (F̄max, a `Strength`; its `.si(...)`
in Pa and m). Units: see the README.
"""

import fem_asperity  # noqa: F401  first: its import quiets a Ctrl-C while the modules load

from .integrate import Strength, StrengthSI, strength, totals
from .laws import PaperLaw, TabulatedLaw
from .surface import RoughSurface, omega_mccool


def __getattr__(name):
    if name == "solved_law":  # loads the solvers (scikit-fem): only when a solved law is asked for
        from .tables import solved_law

        return solved_law
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = ["PaperLaw", "RoughSurface", "Strength", "StrengthSI", "TabulatedLaw", "omega_mccool",
           "solved_law", "strength", "totals"]
