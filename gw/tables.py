"""Tabulated asperity laws from solved single-asperity curves (`fem_asperity.store`)."""

from fem_asperity.store import stored_curve

from .laws import TabulatedLaw


def solved_law(mu, *, method="bem", accuracy="default", cache=None, progress=None):
    """`TabulatedLaw` from the approach path of the curve at `mu` (solved now if not stored)."""
    approach, events, folder = stored_curve(mu, method=method, accuracy=accuracy, cache=cache,
                                            progress=progress)
    return TabulatedLaw(mu, approach, delta_o_star=events["delta_o_star"], name=method,
                        source=str(folder))
