"""Tabulated asperity laws from solved single-asperity curves (`fem_asperity.studies.store`)."""

from fem_asperity.solids.fe import Solid
from fem_asperity.studies.store import stored_curve

from .laws import TabulatedLaw


def solved_law(mu, *, method="bem", accuracy="default", solid=Solid(), cache=None,
               progress=None):
    """`TabulatedLaw` from the approach path of the curve at `mu` on `solid` (homogeneous by
    default; a coated asperity with a layer), solved now if not stored."""
    stored = stored_curve(mu, method=method, accuracy=accuracy, solid=solid, cache=cache,
                          progress=progress)
    return TabulatedLaw(mu, stored.approach, delta_o_star=stored.events.delta_o_star, name=method,
                        source=str(stored.folder))
