"""Accuracy presets: how fine the surface discretisation and the continuation are for a given μ.

The surface element size follows the cohesive zone at the contact edge, whose width shrinks like
μ^(−3/2) √(Rε); the finely meshed strip covers the JKR contact radius at the deepest load. At
large μ the FE's quadratic elements need nodes about 0.7 times as far apart as the boundary-
integral method's linear ones to keep the force curve free of ripple (measured at μ = 5).
"""

from dataclasses import dataclass, replace

import numpy as np

from ..path.continuation import TraceSettings
from ..path.grids import EdgeGrids, FixedGrid
from ..plumbing.checks import positive
from ..plumbing.errors import InputError
from ..solids.bem import BoussinesqSurface, radial_grid
from ..solids.fe import HalfSpace, Solid
from ..solids.mesh import graded_mesh

#: Surface element size relative to the `default` preset, and the continuation's turn limit.
PRESETS = {
    "draft": (2.0, 0.2),
    "default": (1.0, 0.1),
    "fine": (0.5, 0.05),
}
#: Largest turn limit (rad): at 0.4 the BEM at μ = 3 (h = 0.1) stepped off the curve.
MAX_TURN = 0.2
#: FE surface element length of `default`: min(H_MAX, H_COHESIVE · μ^(−3/2)), in √(Rε). The mesh
#: makes its surface edges as long as this allows (⅔ of it at worst, `mesh.graded_mesh`).
#: H_MAX = 1/16: at 1/10 the coarser bulk near the surface shifts the FE separations by 4e-5
#: (μ = 1, jump-in δ̄o against the BEM), more than the error estimate reports (3e-5).
#: H_COHESIVE = 0.2: at 0.25 (edges 0.0214 at μ = 5) the P2 surface ripples (6 folds) and δ̄oc,
#: ā_c are 1.2e-2, 8.7e-3 off; with edges 0.016, 2 folds and 1.3e-3, 9.9e-4.
H_MAX, H_COHESIVE = 0.0625, 0.2
#: BEM element length of `default` at large μ: H_COHESIVE_BEM · μ^(−3/2) (no ripple at μ = 5).
H_COHESIVE_BEM = 0.125
#: Largest boundary-integral element at `default`: linear elements reproduce the centre
#: deflection, and so the initial-contact separation δ̄o*, less well than the FE's quadratic ones
#: (μ = 1: h = 0.05 puts δ̄o* 6e-3 off, h = 0.025 1.4e-3).
H_MAX_BEM = 0.025
#: Truncation radius/depth of the half-space, in √(Rε). The solid outside is restored near the
#: axis (`solids.fe.HalfSpace`) to O((a/L)²): at μ = 3 and 5 the events at L = 1e3 and 1e5 agree
#: to 1e-7, with 25-40% fewer DOFs (μ = 5 `default`: 20.4 s against 24.5 s); at L = 1e2 they
#: move by up to 1e-5. Uncorrected, the separations shifted by ~π μ^(3/2)|P̄|/L. Beyond
#: μ ≈ 10 the size grows as 100 r_fine, keeping (a/L)² ≤ 1e-4.
DOMAIN_SIZE = 1e3
#: Last node of the boundary-integral traction grid, in √(Rε): the LJ tail beyond it carries a
#: force of about (16/3) r⁻⁴ ≈ 5e-8 (the solid itself is not truncated).
TRACTION_RADIUS = 100.0
#: FE bulk grading (element size growth per unit distance from the surface strip). A uniform
#: disc's centre deflection (L = 1e3, h = 0.07) is 4.0e-5 too small at 0.3, 7e-6 at 0.2 and
#: 2.6e-6 at 0.15 (DOFs 15k, 35k, 52k). At 0.3 the error estimate missed the force after the
#: jump-in at μ = 3 (estimate 1.1e-7, error 1.8e-5 against the BEM `fine`: the grading and
#: element-size errors cancelled in the coarser solve); at 0.2 it bounds every event (2.1e-5
#: against 1.3e-5). μ = 5 `default`: 1186 surface nodes against 1142, about 6% slower.
FE_GRADING = 0.2
#: From this μ on the boundary-integral grid follows the contact edge (`path.grids`): fine
#: (h_surface) only on the band from BAND_COHESIVE μ^(−3/2) inside the contact radius to as far
#: outside the crack tip, sized by the LJ spring stiffness elsewhere, at most H_INSIDE inside
#: the contact. μ = 5, with edge elements as long as the uniform grid's: P̄max, P̄off and both
#: jumps agree with the uniform grid's to 1e-6 (test). `default`, one BLAS thread: μ = 5 8.0 s
#: (at most 638 nodes) against 8.3 s (806 nodes, uniform); μ = 10 32 s (763) against 1356 s
#: (3021); μ = 46.9, where a uniform grid would need some 27,000 nodes, see the README.
MU_TRACKING = 6.0
BAND_COHESIVE, H_INSIDE = 8.0, 0.1
#: Growth of boundary-integral elements per element beyond the fine zone.
BEM_GROWTH = 0.1
#: Element length at the edge of grids that follow it, `default`: H_COHESIVE_TRACKING μ^(−3/2),
#: half the uniform grid's. At large μ the crack tip is a front a few elements wide (μ = 46.9:
#: the gap rises from 1.1 to 1.7 ε across one element of H_COHESIVE_BEM μ^(−3/2)), and on such
#: elements it moves in jerks: at μ = 46.9 near the jump-out (δ̄o = 74.03) the continuation
#: needed 191 points and 852 Newton iterations to cross half a band, against 5 and 18 with
#: elements half as long, and at μ = 10 the path showed 6 folds (4 of them ripple) against 2.
H_COHESIVE_TRACKING = 0.0625
#: Methods: finite elements ('fem') or the boundary-integral solver ('bem').
METHODS = ("fem", "bem")
#: The error estimate's coarser solve steepens the bulk (FE) or tail (BEM) grading by this
#: factor: with FE grading 1/3 instead of 0.2 a uniform disc's centre deflection is about 4e-5
#: too small instead of 7e-6, so the estimate also sees the bulk mesh (test_fem_elastic).
COARSE_GRADING = 5.0 / 3.0


class _Resolution:
    """What the three discretisations share: a preset `name`, the surface element length
    `h_surface` (√(Rε)), the continuation's `trace` settings, and coarsening and refinement.
    Each subclass names its grading field in `_GRADING` and its other lengths in `_LENGTHS`."""

    _GRADING = "grading"
    _LENGTHS = ()

    def _scaled(self, name, factor, grading, turn):
        lengths = {k: factor * getattr(self, k) for k in ("h_surface", *self._LENGTHS)}
        return replace(self, name=name, **lengths, **{self._GRADING: grading},
                       trace=replace(self.trace, turn=turn))

    def coarsened(self, factor=2.0):
        """The discretisation of the error estimate: surface elements and the continuation's turn
        limit `factor` times larger, the grading COARSE_GRADING times as steep (at most 1), so
        the estimate also sees the bulk or tail and the sampling of the curve (P̄off moves by
        3e-5 at μ = 1 from turn 0.1 to 0.02). The turn stays ≤ MAX_TURN."""
        grading = min(1.0, getattr(self, self._GRADING) * COARSE_GRADING)
        return self._scaled(f"{self.name}/coarse", factor, grading,
                            min(self.trace.turn * factor, MAX_TURN))

    def refined(self):
        """The next level of a tolerance-driven solve: surface elements and turn limit halved
        (the grading kept: the FE's puts a disc's deflection 7e-6 off)."""
        return self._scaled(f"{self.name}/2", 0.5, getattr(self, self._GRADING),
                            0.5 * self.trace.turn)


@dataclass(frozen=True)
class FEDiscretisation(_Resolution):
    """Finite elements of order `order` (2: quadratic) with surface edges of length h_surface on
    the strip r ≤ r_fine, growing by `grading` per unit distance from it, in a domain of
    `size` × `size` (√(Rε))."""

    name: str
    h_surface: float
    r_fine: float
    size: float = DOMAIN_SIZE
    grading: float = FE_GRADING
    order: int = 2
    trace: TraceSettings = TraceSettings()
    method = "fem"

    def elastic(self, solid=Solid()):
        """The FE half-space of `solid` on this mesh, condensed onto its surface."""
        mesh = graded_mesh(h_surface=self.h_surface, r_fine=self.r_fine, size=self.size,
                           grading=self.grading, layer_thickness=solid.layer_thickness)
        return HalfSpace(mesh, order=self.order, solid=solid)

    def grids(self, mu, *, solid=Solid(), radius_ratio=None):
        """The one surface of a curve at `mu` (`FixedGrid`)."""
        return FixedGrid(self.elastic(solid), mu, radius_ratio=radius_ratio)


@dataclass(frozen=True)
class BEMDiscretisation(_Resolution):
    """Boundary integral on one radial grid: linear elements of length h_surface on [0, r_fine],
    then each (1 + `growth`) times longer than the last, up to the traction radius `r_max`."""

    name: str
    h_surface: float
    r_fine: float
    r_max: float = TRACTION_RADIUS
    growth: float = BEM_GROWTH
    trace: TraceSettings = TraceSettings()
    method = "bem"
    _GRADING = "growth"

    def elastic(self, solid=Solid()):
        """The Boussinesq surface on this grid; refuses a layered `solid`."""
        _homogeneous(solid)
        return BoussinesqSurface(radial_grid(h=self.h_surface, r_fine=self.r_fine,
                                             r_max=self.r_max, growth=self.growth))

    def grids(self, mu, *, solid=Solid(), radius_ratio=None):
        """The one surface of a curve at `mu` (`FixedGrid`)."""
        return FixedGrid(self.elastic(solid), mu, radius_ratio=radius_ratio)


@dataclass(frozen=True)
class EdgeDiscretisation(_Resolution):
    """Boundary-integral grids that follow the contact edge (`path.grids.EdgeGrids`): elements
    of length h_surface within `band` of the contact radius and of the crack tip, at most
    `h_inside` inside the contact, growing by `growth` per element elsewhere up to `r_max`;
    before contact the uniform grid of spacing h_contact on [0, r_contact] (all in √(Rε))."""

    name: str
    h_surface: float
    band: float
    h_contact: float
    r_contact: float = 4.0
    h_inside: float = H_INSIDE
    r_max: float = TRACTION_RADIUS
    growth: float = BEM_GROWTH
    trace: TraceSettings = TraceSettings()
    method = "bem"
    _GRADING = "growth"
    _LENGTHS = ("h_contact",)

    def grids(self, mu, *, solid=Solid(), radius_ratio=None):
        """The grids of a curve at `mu`, built as its edges move; a homogeneous half-space."""
        _homogeneous(solid)
        return EdgeGrids(mu, h=self.h_surface, band=self.band, h_inside=self.h_inside,
                         contact_h=self.h_contact, contact_r=self.r_contact, r_max=self.r_max,
                         growth=self.growth, radius_ratio=radius_ratio)


def _homogeneous(solid):
    if solid.layer_thickness is not None:
        raise InputError("method 'bem' models a homogeneous half-space; use 'fem' for a layer")


def jkr_radius(load, mu):
    """JKR contact radius ā at the force P̄ = `load` (≥ −3/4 ... any compressive value), in √(Rε)."""
    return ((1.5 * np.pi) * mu**1.5 * (load + 1.5 + np.sqrt(3.0 * load + 2.25))) ** (1.0 / 3.0)


def discretisation(mu, accuracy="default", *, p_end=1.0, method="fem", track_edge=None):
    """The discretisation (`FEDiscretisation`, `BEMDiscretisation` or `EdgeDiscretisation`) for
    Tabor parameter `mu`, a preset name (draft, default, fine) and a method ('fem' or 'bem'). track_edge (BEM only): grids that follow the contact edge (True),
    one uniform grid (False), or the first from μ = MU_TRACKING on (None)."""
    mu = positive("mu", mu)
    if track_edge and method != "bem":
        raise InputError(f"track_edge needs method 'bem'; got method {method!r}")
    if accuracy not in PRESETS:
        raise InputError(f"accuracy must be one of {', '.join(PRESETS)}; got {accuracy!r}")
    if method not in METHODS:
        raise InputError(f"method must be one of {', '.join(METHODS)}; got {method!r}")
    factor, turn = PRESETS[accuracy]
    trace = TraceSettings(turn=turn, p_end=p_end)
    if method == "fem":
        r_fine = max(4.0, 1.3 * jkr_radius(p_end, mu))
        return FEDiscretisation(name=accuracy, h_surface=factor * min(H_MAX, H_COHESIVE * mu**-1.5),
                                r_fine=r_fine, size=max(DOMAIN_SIZE, 100.0 * r_fine), trace=trace)
    if track_edge or (track_edge is None and mu >= MU_TRACKING):
        band = BAND_COHESIVE * mu**-1.5
        return EdgeDiscretisation(
            name=accuracy, h_surface=factor * min(H_MAX_BEM, H_COHESIVE_TRACKING * mu**-1.5),
            band=band, h_contact=factor * H_MAX_BEM,
            trace=replace(trace, da=min(trace.da, 0.5 * band), front=band))
    return BEMDiscretisation(name=accuracy,
                             h_surface=factor * min(H_MAX_BEM, H_COHESIVE_BEM * mu**-1.5),
                             r_fine=max(4.0, 1.3 * jkr_radius(p_end, mu)), trace=trace)
