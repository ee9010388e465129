"""Accuracy presets: how fine the surface discretisation and the continuation are for a given μ.

The surface element size follows the cohesive zone at the contact edge, whose width shrinks like
μ^(−3/2) √(Rε), and stays below the ripple-free limit RIPPLE_FREE μ^(−2), which shrinks faster:
on longer elements the contact edge moves from node to node in jerks and the force curve shows
false folds. The finely meshed strip covers the JKR contact radius at the deepest load.
"""

from dataclasses import dataclass, replace
from functools import partial

import numpy as np

from ..path.continuation import TraceSettings
from ..path.grids import FE_AHEAD, FE_FIT, EdgeGrids, FixedGrid
from ..plumbing.checks import positive
from ..plumbing.errors import InputError
from ..solids.bem import BoussinesqSurface, radial_grid
from ..solids.fe import HalfSpace, Solid
from ..solids.mesh import graded_mesh

#: Surface element size relative to `default` (below the ripple cap) and the turn limit; they
#: converge in turn: test_fem_curve.py::test_pull_off_converges_under_refinement (slow).
PRESETS = {
    "draft": (2.0, 0.2),
    "default": (1.0, 0.1),
    "fine": (0.5, 0.05),
}
#: FE surface element of `default`: min(H_MAX, H_COHESIVE μ^(−3/2)) √(Rε). docs/methods.md §12;
#: test_bem_curve.py::test_bem_agrees_with_fem_within_the_error_estimates.
H_MAX, H_COHESIVE = 0.0625, 0.2
#: BEM element of `default` at large μ: H_COHESIVE_BEM μ^(−3/2) (no ripple at μ = 5). Not pinned.
H_COHESIVE_BEM = 0.125
#: Largest boundary-integral element at `default`: linear elements place δ̄o* less well than
#: quadratic ones (docs/methods.md §12). Not pinned by a test.
H_MAX_BEM = 0.025
#: Truncation radius and depth of the FE half-space (√(Rε); the solid outside is restored).
#: test_fem_elastic.py::test_truncation_size_no_longer_matters.
DOMAIN_SIZE = 1e3
#: Last node of the BEM traction grid (√(Rε)): the LJ tail beyond carries ≈ (16/3) r⁻⁴ ≈ 5e-8.
#: Not pinned by a test (the estimate adds it, `estimate.traction_tail`).
TRACTION_RADIUS = 100.0
#: FE bulk grading (size growth per unit distance from the surface strip). docs/methods.md §12;
#: test_bem_curve.py::test_bem_agrees_with_fem_within_the_error_estimates (μ = 3, slow).
FE_GRADING = 0.2
#: μ from which grids follow the contact edge, per method; their fine band (μ^(−3/2) √(Rε)) and
#: inside spacing. docs/methods.md §12; test_tracking.py::test_tracked_grids_give_*.
MU_TRACKING = {"bem": 4.0, "fem": 5.0}
BAND_COHESIVE, H_INSIDE = 8.0, 0.1
#: Most elements of the ripple-free size in a band: beyond, each Newton matrix grows as n³ while
#: the steps do not (benchmarks/results/large_mu.md). Not pinned by a test.
BAND_ELEMENTS = 128
#: Largest change of ā_c per step on grids that follow the edge, in bands (0.5 gave the same
#: P̄off at more points). Not pinned by a test.
EDGE_STEP = 1.0
#: Growth of boundary-integral elements per element beyond the fine zone. Not pinned by a test.
BEM_GROWTH = 0.1
#: Element at the edge of grids that follow it, × μ^(−3/2) √(Rε): half the uniform grid's, or the
#: crack tip moves in jerks (ripple at μ = 10). Not pinned by a test.
H_COHESIVE_TRACKING = 0.0625
#: Smallest radius (√(Rε)) of the finely resolved surface strip: the sphere's gap there is at least
#: 8 ε, where the LJ tension is 0.5% of its peak. Not pinned by a test.
R_FINE_MIN = 4.0
#: Largest surface element free of ripple folds, × μ^(−2) √(Rε), per grid: benchmarks/results/
#: ripple.md (`python benchmarks/ripple.py`); test_bem_curve.py::test_presets_do_not_ripple.
RIPPLE_FREE = {"fem": 0.45, "bem": 0.28, "edge": 0.33}
#: Presets stay this factor below the ripple-free size (measured at a few μ only). Not pinned.
RIPPLE_MARGIN = 1.25
#: Most surface elements of an FE curve: its dense surface factorisations grow as n³ (tens of
#: minutes here). test_fem_curve.py::test_a_layer_the_fe_cannot_resolve_is_refused_up_front.
FE_MAX_SURFACE_ELEMENTS = 2500
#: Most elements of an FE mesh, checked before assembly (2.2M ran out of memory).
#: test_fem_curve.py::test_a_layer_the_fe_cannot_resolve_is_refused_up_front.
FE_MAX_ELEMENTS = 300_000
#: Most nodes of a uniform boundary-integral grid (dense n² operators, n³ factorisations).
#: test_layered.py::test_extreme_layers_converge_or_stop_with_a_clear_message.
BEM_MAX_NODES = 4000
#: Methods: finite elements ('fem') or the boundary-integral solver ('bem').
METHODS = ("fem", "bem")
#: How a curve's error estimate is made (`solve_curve`'s estimate_by; 'auto': 'bem' for the FE of
#: a homogeneous half-space, else 'finer'). docs/methods.md §12 has their costs.
ESTIMATE_BY = ("auto", "finer", "bem")
#: The estimate's finer solve grades the bulk (FE) or tail (BEM) this much more gently, so it
#: sees the bulk mesh. docs/methods.md §12; test_bem_curve.py::test_bem_agrees_with_fem_*.
ESTIMATE_GRADING = 2.0


class _Resolution:
    """What the discretisations share: a preset `name`, the surface element length
    `h_surface` (√(Rε)), the continuation's `trace` settings, and refinement. Each subclass
    names its grading field in `_GRADING` and its other lengths in `_LENGTHS`; `follows_edge`
    says whether its grids follow the contact edge (`path.grids.EdgeGrids`)."""

    _GRADING = "grading"
    _LENGTHS = ()
    _TRACTION_RADIUS = "r_max"
    follows_edge = False

    @property
    def traction_radius(self):
        """Where the surface carrying the LJ traction ends (√(Rε)): the BEM's `r_max`, the FE
        domain's `size`."""
        return getattr(self, self._TRACTION_RADIUS)

    def _scaled(self, name, factor, grading, turn):
        lengths = {k: factor * getattr(self, k) for k in ("h_surface", *self._LENGTHS)}
        return replace(self, name=name, **lengths, **{self._GRADING: grading},
                       trace=replace(self.trace, turn=turn))

    def grids(self, mu, *, solid=Solid(), radius_ratio=None):
        """The one surface of a curve at `mu` on this discretisation's `elastic()` solid
        (`FixedGrid`); the edge-following discretisation builds its grids instead."""
        return FixedGrid(self.elastic(solid), mu, radius_ratio=radius_ratio)

    def refined(self):
        """The next level of a tolerance-driven solve, or of a curve that rippled or missed its
        jump: surface elements and turn limit halved (the grading kept: the FE's puts a disc's
        deflection 7e-6 off)."""
        return self._scaled(f"{self.name}/2", 0.5, getattr(self, self._GRADING),
                            0.5 * self.trace.turn)

    def for_estimate(self):
        """The discretisation of the error estimate: `refined()`, and the bulk (FE) or tail
        (BEM) graded ESTIMATE_GRADING times more gently, so that the estimate also sees them."""
        return replace(self.refined(), name=f"{self.name}/estimate",
                       **{self._GRADING: getattr(self, self._GRADING) / ESTIMATE_GRADING})


@dataclass(frozen=True)
class FEDiscretisation(_Resolution):
    """Finite elements of order `order` (2: quadratic) with surface edges of length h_surface on
    the strip r ≤ r_fine, growing by `grading` per unit distance from it, in a domain of
    `size` × `size` (√(Rε))."""

    _TRACTION_RADIUS = "size"

    name: str
    h_surface: float
    r_fine: float
    size: float = DOMAIN_SIZE
    grading: float = FE_GRADING
    order: int = 2
    trace: TraceSettings = TraceSettings()
    method = "fem"

    def elastic(self, solid=Solid()):
        """The FE half-space of `solid` on this mesh, condensed onto its surface; refuses a
        surface of more than FE_MAX_SURFACE_ELEMENTS elements (`InputError`)."""
        elements = self.r_fine / self.h_surface
        if elements > FE_MAX_SURFACE_ELEMENTS:
            raise InputError(
                f"the FE surface would need {elements:.0f} elements ({self.h_surface:.3g} over "
                f"r <= {self.r_fine:.3g} sqrt(R eps), sized for the most compliant material's "
                f"Tabor parameter); the FE takes at most {FE_MAX_SURFACE_ELEMENTS}: a smaller mu, "
                f"a stiffer layer, or the BEM")
        mesh = graded_mesh(h_surface=self.h_surface, r_fine=self.r_fine, size=self.size,
                           grading=self.grading, layer_thickness=solid.layer_thickness)
        if mesh.t.shape[1] > FE_MAX_ELEMENTS:
            raise InputError(
                f"the FE mesh has {mesh.t.shape[1]} elements (a layer {solid.layer_thickness} "
                f"sqrt(R eps) thick meshed with surface elements of {self.h_surface:.3g}); the FE "
                f"takes at most {FE_MAX_ELEMENTS}: a thicker or stiffer layer, a smaller mu, or "
                f"a coarser accuracy")
        return HalfSpace(mesh, order=self.order, solid=solid)


@dataclass(frozen=True, kw_only=True)
class FEEdgeDiscretisation(FEDiscretisation):
    """The FE half-space of `FEDiscretisation` with its surface restricted to grids that follow
    the contact edge (`path.grids.EdgeGrids` over `solids.fe.HalfSpace.restricted`): every
    surface node within `band` of the contact radius and of the crack tip, at most `h_inside`
    inside the contact, elements growing by `growth` elsewhere, every node beyond r_fine; before
    contact every node on [0, r_contact] (all in √(Rε)): on the pre-contact grid of the BEM's
    spacing (H_MAX_BEM) x̄o at the jump-in of μ = 5, `default`, was 5.0e-4 off the whole
    surface's, 57 times its error estimate; with every node 2e-7. A homogeneous solid only
    (`_homogeneous`)."""

    band: float
    r_contact: float = R_FINE_MIN
    h_inside: float = H_INSIDE
    growth: float = BEM_GROWTH
    follows_edge = True

    def grids(self, mu, *, solid=Solid(), radius_ratio=None):
        """The grids of a curve at `mu` on this discretisation's half-space (homogeneous)."""
        _homogeneous(solid)
        half_space = self.elastic(solid)
        every_node = float(np.min(np.diff(half_space.r_nodes)))
        return EdgeGrids(mu, h=every_node, band=self.band, h_inside=self.h_inside,
                         contact_h=every_node, contact_r=self.r_contact,
                         r_max=float(half_space.r_nodes[-1]),
                         growth=self.growth, radius_ratio=radius_ratio,
                         elastic_on=partial(half_space.restricted, keep_beyond=self.r_fine),
                         elastic=half_space, fit=FE_FIT, ahead=FE_AHEAD)


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
        """The boundary-integral surface of `solid` (homogeneous or layered) on this grid;
        refuses a grid of more than BEM_MAX_NODES nodes (`InputError`)."""
        nodes = radial_grid(h=self.h_surface, r_fine=self.r_fine, r_max=self.r_max,
                            growth=self.growth)
        if nodes.size > BEM_MAX_NODES:
            raise InputError(
                f"the boundary-integral grid would need {nodes.size} nodes ({self.h_surface:.3g} "
                f"over r <= {self.r_fine:.3g} sqrt(R eps), sized for the most compliant "
                f"material's Tabor parameter); it takes at most {BEM_MAX_NODES}: a smaller mu, "
                f"a stiffer layer, or a coarser accuracy")
        return BoussinesqSurface(nodes, solid=solid)


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
    r_contact: float = R_FINE_MIN
    h_inside: float = H_INSIDE
    r_max: float = TRACTION_RADIUS
    growth: float = BEM_GROWTH
    trace: TraceSettings = TraceSettings()
    method = "bem"
    _GRADING = "growth"
    _LENGTHS = ("h_contact",)
    follows_edge = True

    def grids(self, mu, *, solid=Solid(), radius_ratio=None):
        """The grids of a curve at `mu`, built as its edges move; a homogeneous half-space (a
        layer's correction on every grid would cost more than the grids save)."""
        _homogeneous(solid)
        return EdgeGrids(mu, h=self.h_surface, band=self.band, h_inside=self.h_inside,
                         contact_h=self.h_contact, contact_r=self.r_contact, r_max=self.r_max,
                         growth=self.growth, radius_ratio=radius_ratio)


def _homogeneous(solid):
    """Refuse a layered `solid` for grids that follow the contact edge (`InputError`): on the
    BEM a layer's correction would be rebuilt on every grid; the grids' coarse elements are
    sized (`path.grids.spring_ratio`) against a homogeneous solid's stiffness, which a soft
    layer lowers."""
    if solid.layer_thickness is not None:
        raise InputError("grids that follow the contact edge model a homogeneous "
                         "half-space; a layer takes one uniform grid (track_edge=False)")


def jkr_radius(load, mu):
    """JKR contact radius ā at the force P̄ = `load` (≥ −3/4 ... any compressive value), in √(Rε)."""
    return ((1.5 * np.pi) * mu**1.5 * (load + 1.5 + np.sqrt(3.0 * load + 2.25))) ** (1.0 / 3.0)


#: A curve's cost relative to small μ: flat to COST_KNEE, then ∝ μ^COST_POWER (a sweep weighs
#: its progress and order by it). test_sweep.py::test_the_time_left_weighted_by_cost_*.
COST_KNEE, COST_POWER = 2.0, {"bem": 1.5, "fem": 2.5}


def relative_cost(mu, method, solid=Solid()):
    """Expected wall time of the curve at `mu` (sized for `solid`: `sizing_mu`) relative to one
    at small μ with the same method."""
    return 1.0 + (sizing_mu(mu, solid) / COST_KNEE) ** COST_POWER[method]


def sizing_mu(mu, solid=Solid()):
    """The Tabor parameter a discretisation is sized for: the substrate's `mu`, or, under a
    layer more compliant than the substrate, the layer's, μ · (E*_layer/E*_substrate)^(−2/3) (μ
    grows like E*^(−2/3)): its cohesive zone is the narrower. (For a thin layer that the contact
    hardly feels this is finer than needed.)"""
    if solid.layer_thickness is None or solid.layer_modulus_ratio >= 1.0:
        return mu
    return mu * solid.layer_modulus_ratio ** (-2.0 / 3.0)


def discretisation(mu, accuracy="default", *, p_end=1.0, method="fem", track_edge=None):
    """The discretisation (`FEDiscretisation`, `FEEdgeDiscretisation`, `BEMDiscretisation` or
    `EdgeDiscretisation`) for Tabor parameter `mu` (of the most compliant material:
    `sizing_mu`), a preset name (draft, default, fine) and a method ('fem' or 'bem').
    track_edge: grids that follow the contact edge (True), one uniform grid or the whole FE
    surface (False), or the first from μ = MU_TRACKING[method] on (None)."""
    mu = positive("mu", mu)
    if accuracy not in PRESETS:
        raise InputError(f"accuracy must be one of {', '.join(PRESETS)}; got {accuracy!r}")
    if method not in METHODS:
        raise InputError(f"method must be one of {', '.join(METHODS)}; got {method!r}")
    factor, turn = PRESETS[accuracy]
    trace = TraceSettings(turn=turn, p_end=p_end)
    r_fine = max(R_FINE_MIN, 1.3 * jkr_radius(p_end, mu))
    edge = track_edge or (track_edge is None and mu >= MU_TRACKING[method])
    h_ripple = RIPPLE_FREE["edge" if edge and method == "bem" else method] * mu**-2.0
    band = min(BAND_COHESIVE * mu**-1.5, BAND_ELEMENTS * h_ripple / RIPPLE_MARGIN)
    edge_trace = replace(trace, da=min(trace.da, EDGE_STEP * band), front=band)

    def h(largest, cohesive):
        return min(factor * min(largest, cohesive * mu**-1.5), h_ripple / RIPPLE_MARGIN)

    if method == "fem":
        fe = dict(name=accuracy, h_surface=h(H_MAX, H_COHESIVE), r_fine=r_fine,
                  size=max(DOMAIN_SIZE, 100.0 * r_fine))
        if edge:
            return FEEdgeDiscretisation(**fe, band=band, trace=edge_trace)
        return FEDiscretisation(**fe, trace=trace)
    if edge:
        return EdgeDiscretisation(
            name=accuracy, h_surface=h(H_MAX_BEM, H_COHESIVE_TRACKING), band=band,
            h_contact=factor * H_MAX_BEM, trace=edge_trace)
    return BEMDiscretisation(name=accuracy, h_surface=h(H_MAX_BEM, H_COHESIVE_BEM),
                             r_fine=r_fine, trace=trace)
