"""A sampled path: the `Curve` arrays and their CSV form.

Units: δ̄o, x̄o in ε; P̄ in 2πRΔγ (negative = tensile); Ā in εR; ā_c in √(εR).
"""

import csv
import io
from dataclasses import dataclass, fields

import numpy as np


@dataclass(frozen=True)
class Curve:
    """Points along a path (the equilibrium curve, or the approach/retraction under δ̄o control).

    `stable`: the point is a local energy minimum at fixed δ̄o. `branch`: segment id, increased at
    every change of stability (equilibrium curve) or at every jump (approach/retraction paths).
    """

    delta: np.ndarray
    x: np.ndarray
    p: np.ndarray
    area: np.ndarray
    a_c: np.ndarray
    stable: np.ndarray
    branch: np.ndarray

    def __len__(self):
        return self.delta.size

    def csv(self):
        """The curve as CSV text with a header row naming each column and its unit
        (`CSV_HEADER`: quantity/unit, the dimensionless units of the paper)."""
        out = io.StringIO()
        writer = csv.writer(out, lineterminator="\n")
        writer.writerow(CSV_HEADER)
        for row in zip(*(getattr(self, f.name) for f in fields(self))):
            writer.writerow([f"{v:.10g}" if isinstance(v, float) else int(v) for v in row])
        return out.getvalue()


#: Header of a curve's CSV: each column as quantity/unit (ε the LJ spacing, R the radius, Δγ the
#: work of adhesion; forces < 0 tensile), then the stability flag and the branch number.
CSV_HEADER = ("delta_o/eps", "x_o/eps", "p/(2 pi R dgamma)", "area/(eps R)", "a_c/sqrt(eps R)",
              "stable", "branch")


def curve_from_columns(delta, x, p, area, a_c, stable, branch):
    """Build a `Curve` from sequences, converting to float/bool/int arrays."""
    floats = [np.asarray(v, dtype=float) for v in (delta, x, p, area, a_c)]
    return Curve(*floats, np.asarray(stable, dtype=bool), np.asarray(branch, dtype=int))
