"""What a path-following run returns: both paths with their jumps, the states behind them, and
the ledger of what moving between grids changed."""

from dataclasses import dataclass, replace

import numpy as np

from ..curves.curve import Curve


@dataclass(frozen=True)
class PathPoint:
    """A point of a path under δ̄o (or a spring's) control: δ̄o, x̄o, P̄, Ā, ā_c (`reading.COLUMNS`)
    and the path's `branch` (the jumps made before it). A fold of δ̄o, where the path jumps, is
    one too (its branch set where the path takes it, `on`)."""

    delta: float
    x: float
    p: float
    area: float
    a_c: float
    branch: int = 0

    def on(self, branch):
        """This point on the path's `branch`."""
        return replace(self, branch=branch)


def disc_area(radius):
    """Ā of a contact disc of radius ā_c (0 out of contact): a fold's area, where only ā_c is
    read off the curve."""
    return 0.0 if radius <= 0.0 else np.pi * radius**2


@dataclass
class GridMoves:
    """What the placement of grids that follow the contact edge changed along a path, filled as
    it is traced: the largest |ΔP̄| and |Δā_c| of a state moved to a new grid while on a branch
    (`record_move`) and the largest |Δδ̄o| of a fold found again on grids placed otherwise
    (`record_fold`); the error estimate's grid-placement terms."""

    force: float = 0.0
    radius: float = 0.0
    fold: float = 0.0

    def record_move(self, change, radius_change):
        self.force, self.radius = max(self.force, change), max(self.radius, radius_change)

    def record_fold(self, change):
        self.fold = max(self.fold, change)


@dataclass(frozen=True)
class Paths:
    """Both paths under δ̄o control and what they were read from: `approach`, `retraction`
    (`Curve`s), the jumps in and out (`Jump`s), the `equilibrium` curve traced, the `traced`
    states behind it (a `continuation.Trace`) and the `moves` of grids that follow the edge
    (None where the curve was read off the whole curve on one grid)."""

    approach: Curve
    retraction: Curve
    jumps_in: list
    jumps_out: list
    equilibrium: Curve
    traced: object
    moves: GridMoves | None = None
