"""Rough surfaces made explicit: a height map (generated, or a user's measured topography)
solved whole, as interacting asperities, and as GW's sum, side by side.

`Topography` (heights in m, `read_topography`, `gaussian_caps`, `self_affine`), its summit
statistics both ways (`summit_statistics`, `spectral_summit_statistics`); `solve_whole` (the
whole surface: FFT half-space, LJ 9-3 forces, approach and retraction with every jump) with
`Adhesion` (E*, Δγ, ε); `Interacting` (summits on the solved law, coupled by the elastic far
field; `AsperityLaw`, `coupling`); `compare` (every model on a GW surface made explicit,
`Scene`). Units: SI at the boundary; inside, the modules say theirs.
"""

from .compare import MODELS, Comparison, Scene, compare
from .interacting import AsperityLaw, Interacting, coupling
from .topography import (
    Topography,
    gaussian_caps,
    read_topography,
    self_affine,
    spectral_summit_statistics,
    summit_statistics,
)
from .whole import Adhesion, WholeSurface, resolution, solve_whole

__all__ = ["MODELS", "Adhesion", "AsperityLaw", "Comparison", "Interacting", "Scene",
           "Topography", "WholeSurface", "compare", "coupling", "gaussian_caps",
           "read_topography", "resolution", "self_affine", "solve_whole",
           "spectral_summit_statistics", "summit_statistics"]
