"""Tabulated asperity laws from solved single-asperity curves (`fem_asperity.studies.store`)."""

from fem_asperity.studies.store import stored_curve

from .laws import TabulatedLaw


def solved_law(mu, *, method="bem", accuracy="default", cache=None, progress=None):
    """`TabulatedLaw` from the approach path of the curve at `mu` (solved now if not stored)."""
    stored = stored_curve(mu, method=method, accuracy=accuracy, cache=cache, progress=progress)
    return TabulatedLaw(mu, stored.approach, delta_o_star=stored.events.delta_o_star, name=method,
                        source=str(stored.folder))
