"""What a path-following run returns: both paths with their jumps, the states behind them, and
the ledger of what moving between grids changed."""

from dataclasses import dataclass

from ..curves.curve import Curve


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
