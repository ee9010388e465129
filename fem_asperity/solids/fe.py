"""Axisymmetric linear elasticity of the (optionally layered) half-space, condensed onto its
surface.

Scaled variables: lengths r, z in √(Rε), displacements in ε, the substrate's E* = 1. In these
units the physical problem σ·n = p becomes K u = μ^(3/2) F(p̄) with p̄ = p/(Δγ/ε), so the whole
single-asperity problem depends on μ alone (Derjaguin regime). The 2π of the axisymmetric volume
and surface measures is dropped on both sides; surface integrals carry the weight r, so that the
force ∫ p̄ r dr is P/(2πRΔγ) directly.

The LJ traction acts only on the surface and only normally, so the bulk is condensed once: the
surface compliance C maps normal surface loads to the surface normal displacement w (upward,
toward the sphere), and the nonlinear problem runs on the surface unknowns alone. The solid is
truncated at a finite size; what lies outside is restored by the far field of the load sum
(`HalfSpace._outside_response`).
"""

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy.sparse import coo_matrix, diags
from scipy.sparse.linalg import spilu, splu
from skfem import (
    Basis,
    BilinearForm,
    ElementTriP1,
    ElementTriP2,
    ElementVector,
    FacetBasis,
    asm,
    condense,
)

from ..plumbing.checks import in_range, poisson
from ..plumbing.errors import InputError
from .operator import spd_inverse

ELEMENTS = {1: ElementTriP1, 2: ElementTriP2}
#: SuperLU options for a symmetric positive definite matrix: symmetric ordering, no pivoting.
_SPD = dict(diag_pivot_thresh=0.0, options=dict(SymmetricMode=True))


#: Supported layer/substrate modulus ratios and layer thicknesses in √(Rε), upper ends open
#: (methods.md §13); test_cli's bad-input test pins both.
LAYER_MODULUS_RATIO, LAYER_THICKNESS = (1e-2, 1e2 + 1e-9), (1e-2, 1e3)


@dataclass(frozen=True)
class Solid:
    """Elastic solid: a homogeneous half-space, or a bonded layer on a substrate.

    The substrate has E* = 1 (it defines μ); the layer has E*_layer = `layer_modulus_ratio`.
    `layer_thickness` is t in √(Rε) (None: no layer). Poisson's ratios enter only through the
    truncation of the domain for a homogeneous solid, and fully for a layered one.
    """

    nu: float = 0.3
    layer_thickness: float | None = None
    layer_modulus_ratio: float = 1.0
    layer_nu: float = 0.3

    def __post_init__(self):
        poisson("nu", self.nu)
        poisson("layer_nu", self.layer_nu)
        in_range("layer_modulus_ratio", self.layer_modulus_ratio, *LAYER_MODULUS_RATIO,
                  closed_lo=True)
        if self.layer_thickness is not None:
            in_range("layer_thickness", self.layer_thickness, *LAYER_THICKNESS, closed_lo=True,
                     unit="sqrt(R eps)")
        elif self.layer_modulus_ratio != 1.0 or self.layer_nu != self.nu:
            raise InputError("layer_modulus_ratio and layer_nu need a layer_thickness")

    def description(self):
        """One phrase for titles: the homogeneous half-space, or the layer's thickness and
        modulus ratio."""
        if self.layer_thickness is None:
            return "homogeneous half-space"
        return (f"layer t = {self.layer_thickness:g} √(Rε), E*_layer/E*_substrate = "
                f"{self.layer_modulus_ratio:g}")

    def lame(self, in_layer):
        """Lamé constants (λ, G) per element; `in_layer` is a boolean array over elements."""
        e_star = np.where(in_layer, self.layer_modulus_ratio, 1.0)
        nu = np.where(in_layer, self.layer_nu, self.nu)
        young = e_star * (1.0 - nu**2)
        return young * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), young / (2.0 * (1.0 + nu))


def boussinesq_point_load(r, depth, *, nu):
    """(u_r, u_z) of a half-space (E* = 1) under a normal point force at the origin of unit load
    sum ∫p r dr = 1 (force 2π): u_r outward, u_z downward (into the solid), at radius r and
    depth z ≥ 0 (Johnson, Contact Mechanics, eq. 3.18). On the surface u_z = 2/r."""
    rho = np.hypot(r, depth)
    scale = 1.0 / (1.0 - nu)  # 2π / (4πG) with G = (1 − ν)/2 for E* = 1
    u_r = scale * (r * depth / rho**3 - (1.0 - 2.0 * nu) * r / (rho * (rho + depth)))
    u_z = scale * (2.0 * (1.0 - nu) / rho + depth**2 / rho**3)
    return u_r, u_z


def _strain(u, r):
    """Axisymmetric strains (ε_rr, ε_zz, ε_θθ, γ_rz) of a vector field (u_r, u_z)."""
    grad = u.grad
    return grad[0, 0], grad[1, 1], u[0] / r, grad[0, 1] + grad[1, 0]


#: scikit-fem's threaded kernel loop on one thread: the same matrix to the bit, faster than the
#: plain loop (methods.md §13). Not pinned by a test.
@BilinearForm(nthreads=1)
def axisymmetric_elasticity(u, v, w):
    """∫ σ(u):ε(v) r dr dz with σ = λ tr ε I + 2G ε, hoop strain u_r/r included."""
    r = w.x[0]
    eu, ev = _strain(u, r), _strain(v, r)
    div_u, div_v = eu[0] + eu[1] + eu[2], ev[0] + ev[1] + ev[2]
    normal = eu[0] * ev[0] + eu[1] * ev[1] + eu[2] * ev[2]
    return (w.lam * div_u * div_v + w.shear * (2.0 * normal + eu[3] * ev[3])) * r


def _factor_surface_last(matrix, last, node):
    """(order, LU, S): sparse LU of the SPD `matrix` permuted by `order`, which puts the unknowns
    `last` last and the others in a minimum-degree order of their nodes (`_nodes_in_order`;
    `node`: the node of each unknown), and the Schur complement S = K_ss − K_sb K_bb⁻¹ K_bs on
    `last`: it is the product of the factors' trailing blocks, L_ss U_ss. Cheaper than solving
    C = (K⁻¹)_ss column by column, and the same C to rounding."""
    n, m = matrix.shape[0], last.size
    rest = np.setdiff1d(np.arange(n), last)
    order = np.concatenate([rest[_nodes_in_order(matrix[rest][:, rest], node[rest])], last])
    lu = splu(matrix[order][:, order].tocsc(), permc_spec="NATURAL", **_SPD)
    tail = np.arange(n - m, n)
    if not (np.array_equal(lu.perm_c[tail], tail) and np.array_equal(lu.perm_r[tail], tail)):
        raise RuntimeError("the sparse factorisation moved the surface unknowns")
    schur = lu.L[n - m:, n - m:].toarray() @ lu.U[n - m:, n - m:].toarray()
    return order, lu, schur


def _nodes_in_order(matrix, node):
    """A fill-reducing order of the unknowns of the SPD `matrix`, those of a node together:
    SuperLU's minimum degree on the graph of the nodes (`node`: the node of each unknown), the
    column order of its Laplacian. The unknowns of a node share their couplings, so this orders
    them about as well as minimum degree on the unknowns themselves (μ = 5 `default`: 25.1M
    nonzeros in the factors instead of 26.1M), on a graph a ninth the size. Not pinned by a
    test (the compliance is: test_fem_elastic.py)."""
    nodes, index = np.unique(node, return_inverse=True)
    coupled = matrix.tocoo()
    graph = coo_matrix((np.ones(coupled.nnz), (index[coupled.row], index[coupled.col])),
                       shape=(nodes.size, nodes.size)).tocsr()
    graph.sum_duplicates()
    graph.data[:] = -1.0
    graph.setdiag(0.0)
    graph.eliminate_zeros()
    laplacian = graph + diags(1.0 - np.asarray(graph.sum(axis=1)).ravel())
    # The order is SuperLU's column ordering, done before any factorisation: an incomplete one
    # that drops every fill-in returns the same perm_c in a third of a full LU's time.
    rank = spilu(laplacian.tocsc(), permc_spec="MMD_AT_PLUS_A", drop_tol=np.inf,
                 fill_factor=1, **_SPD).perm_c
    return np.lexsort((np.arange(node.size), rank[index]))


def _node_of_unknown(basis):
    """The node of each unknown of a vector `basis`: its mesh vertex, or for quadratic elements
    the facet whose midpoint it sits at (numbered after the vertices)."""
    node = np.empty(basis.N, dtype=np.int64)
    vertices = basis.nodal_dofs.shape[1]
    node[basis.nodal_dofs] = np.arange(vertices)
    if basis.facet_dofs.size:
        node[basis.facet_dofs] = vertices + np.arange(basis.facet_dofs.shape[1])
    return node


class HalfSpace:
    """Assembled elastic model on a mesh from `graded_mesh`, condensed onto the surface.

    The `operator.ElasticSurface` interface, and for field output mesh, basis,
    displacement_field, stress. Attributes after construction:
      r_nodes: radii of the surface unknowns (sorted), in √(Rε).
      r_quad, weights: surface quadrature points and weights (r included), in √(Rε) and √(Rε)².
      interp: sparse (n_quad × n_nodes) map from surface values w to w at the quadrature points.
      compliance: dense C (n_nodes × n_nodes, built on first use): w = −C·load for the normal
        nodal loads load = interpᵀ(weights·p) with p > 0 pressing into the solid (E* = 1
        units).
      surface_stiffness: C⁻¹.
      dofs: number of displacement unknowns (after the boundary conditions).
    """

    def __init__(self, mesh, *, order=1, solid=Solid(), quad_order=8):
        if order not in ELEMENTS:
            raise InputError(f"order must be 1 or 2; got {order!r}")
        self.mesh, self.solid = mesh, solid
        self.basis = Basis(mesh, ElementVector(ELEMENTS[order]()), intorder=2 * order)
        in_layer = np.zeros(mesh.t.shape[1], dtype=bool)
        if solid.layer_thickness is not None:
            in_layer[mesh.subdomains["layer"]] = True
        self.in_layer = in_layer
        lam, shear = solid.lame(in_layer)
        nqp = self.basis.X.shape[1]
        self._lam = np.repeat(lam[:, None], nqp, axis=1)
        self._shear = np.repeat(shear[:, None], nqp, axis=1)
        self.stiffness = asm(axisymmetric_elasticity, self.basis, lam=self._lam, shear=self._shear)
        fixed = np.union1d(
            self.basis.get_dofs("axis").all("u^1"), self.basis.get_dofs("far").all()
        )
        self.free = self.basis.complement_dofs(fixed)
        self.dofs = self.free.size
        self._surface_operator(quad_order)
        self._surface_position = np.searchsorted(self.free, self.surface_dofs)
        self._order, self._lu, schur = _factor_surface_last(
            condense(self.stiffness, D=fixed, expand=False).tocsc(), self._surface_position,
            _node_of_unknown(self.basis)[self.free])
        self._far_field = self._outside_response()
        # The truncated solid is too stiff by the compliance of what lies outside it: near the
        # axis (r ≪ size) that is a uniform sink k of the whole surface per unit load sum, so
        # C = S⁻¹ + k 11ᵀ (S: the truncated solid's surface stiffness, its Schur complement).
        self._truncated = 0.5 * (schur + schur.T)
        self._outside = -float(self._far_field[self.surface_dofs[0]])
        self.surface_stiffness = _with_outside(self._truncated, self._outside)

    @cached_property
    def compliance(self):
        """C: the upward surface displacement per unit surface nodal load, dense (built on
        first use: the surface problem needs only its inverse, `surface_stiffness`)."""
        return spd_inverse(self._truncated) + self._outside

    def _outside_response(self):
        """Displacement field (all DOFs) per unit load sum ∫p r dr at the axis, of the solid held
        on the far boundary at the half-space's own (Boussinesq) displacement instead of zero.

        Adding load-sum times this field to the truncated solution restores the missing far
        field up to O((r/size)²) near the axis: without it the separations of a solid truncated
        at `size` are off by ~0.5 × 2π ∫p r dr / size (uniform disc, size 1e2 to 1e3)."""
        far = self.basis.get_dofs("far")
        radial, vertical = far.all("u^1"), far.all("u^2")
        u_r, _ = boussinesq_point_load(*self._depth_coordinates(radial), nu=self.solid.nu)
        _, u_down = boussinesq_point_load(*self._depth_coordinates(vertical), nu=self.solid.nu)
        held = np.zeros(self.basis.N)
        held[radial], held[vertical] = u_r, -u_down
        u = self._solve_free(-(self.stiffness @ held)[self.free])
        return u + held

    def _depth_coordinates(self, dofs):
        return self.basis.doflocs[0, dofs], -self.basis.doflocs[1, dofs]

    def _solve_free(self, rhs):
        """All DOFs (zero on the held ones) of K_ff u_f = rhs."""
        u_free = np.empty(self.free.size)
        u_free[self._order] = self._lu.solve(rhs[self._order])
        u = np.zeros(self.basis.N)
        u[self.free] = u_free
        return u

    def _surface_operator(self, quad_order):
        fb = FacetBasis(self.mesh, self.basis.elem, facets="top", intorder=quad_order)
        nf, nq = fb.dx.shape
        rows = np.arange(nf * nq).reshape(nf, nq)
        entries = [
            (rows, np.broadcast_to(fb.element_dofs[j][:, None], (nf, nq)), np.asarray(phi[0])[1])
            for j, phi in enumerate(fb.basis)
        ]
        row, col, val = (np.concatenate([e[k].ravel() for e in entries]) for k in range(3))
        full = coo_matrix((val, (row, col)), shape=(nf * nq, self.basis.N)).tocsc()
        surface = np.intersect1d(self.basis.get_dofs("top").all("u^2"), self.free)
        order = np.argsort(self.basis.doflocs[0, surface])
        self.surface_dofs = surface[order]
        self.r_nodes = self.basis.doflocs[0, self.surface_dofs]
        self.interp = full[:, self.surface_dofs].tocsr()
        self.r_quad = np.asarray(fb.global_coordinates())[0].ravel()
        self.weights = (fb.dx * np.asarray(fb.global_coordinates())[0]).ravel()

    def nodal_load(self, pressure_at_quad):
        """Normal nodal loads interpᵀ(weights·p) for a pressure sampled at `r_quad` (E* = 1
        units)."""
        return self.interp.T @ (self.weights * pressure_at_quad)

    def deflection(self, pressure_at_quad):
        """Surface normal displacement (upward) at `r_nodes` under a pressure p (> 0 into the
        solid)."""
        return -self.compliance @ self.nodal_load(pressure_at_quad)

    def displacement_field(self, nodal_load):
        """Full displacement vector (all DOFs) for normal surface loads (E* = 1 units), the
        far field outside the truncated solid included (`_outside_response`)."""
        rhs = np.zeros(self.free.size)
        rhs[self._surface_position] = -nodal_load
        return self._solve_free(rhs) + np.sum(nodal_load) * self._far_field

    def restricted(self, nodes, *, keep_beyond):
        """This surface with w piecewise linear between the surface nodes nearest to the radii
        `nodes` up to `keep_beyond` (√(Rε)), every node kept beyond it (a `RestrictedSurface`:
        fewer unknowns where the contact edge is not)."""
        return RestrictedSurface(self, nodes, keep_beyond=keep_beyond)

    def stress(self, u):
        """The axisymmetric stress tensor per element (mean over its quadrature points), E* = 1
        units: an (n_elements × 4) array of σ_rr, σ_zz, σ_θθ, σ_rz."""
        field = self.basis.interpolate(u)
        r = np.asarray(self.basis.global_coordinates())[0]
        e_rr, e_zz, e_tt, g_rz = _strain(field, r)
        trace = self._lam * (e_rr + e_zz + e_tt)
        sigma = (trace + 2.0 * self._shear * e_rr, trace + 2.0 * self._shear * e_zz,
                 trace + 2.0 * self._shear * e_tt, self._shear * g_rz)
        return np.column_stack([s.mean(axis=1) for s in sigma])


class RestrictedSurface:
    """The surface of a `HalfSpace` with its normal displacement w restricted to the piecewise
    linear functions on a subset of its surface nodes (a Ritz reduction of the condensed
    energy): the `operator.ElasticSurface` of a grid that is fine only near the contact edge
    (`path.grids.EdgeGrids`).

    The subset: the node nearest to each of the radii `nodes` below `keep_beyond`, every node
    from `keep_beyond` on (where the mesh coarsens, so that the far field, which sets the
    whole surface's sink, stays the FE's: with the requested nodes there δ̄o at the jump-in of
    μ = 5, `default`, moved by 1.1e-5), and the first and the last node. With w = T w̃ at the
    half-space's nodes (T: linear interpolation from the subset) the stiffness is Tᵀ S T (S: the
    half-space's surface stiffness) and the interpolation to the quadrature points N T; the
    quadrature points, their weights and `dofs` are the half-space's. Where the subset holds
    every node this is the half-space itself (test_fem_elastic.py).
    """

    def __init__(self, half_space, nodes, *, keep_beyond):
        r = half_space.r_nodes
        nodes = np.asarray(nodes, dtype=float)
        nodes = nodes[nodes < keep_beyond]
        nearest = np.searchsorted(r, nodes).clip(1, r.size - 1)
        nearest -= (r[nearest] - nodes) > (nodes - r[nearest - 1])
        kept = np.flatnonzero(r >= keep_beyond)
        picked = np.unique(np.concatenate([[0, r.size - 1], nearest, kept]))
        self.half_space, self.r_nodes = half_space, r[picked]
        self.expansion = _linear_interpolation(r, self.r_nodes)
        self.r_quad, self.weights = half_space.r_quad, half_space.weights
        self.interp = (half_space.interp @ self.expansion).tocsr()
        stiffness = self.expansion.T @ (self.expansion.T @ half_space.surface_stiffness).T
        self.surface_stiffness = 0.5 * (stiffness + stiffness.T)
        self.dofs = half_space.dofs

    @cached_property
    def compliance(self):
        """(Tᵀ S T)⁻¹, dense."""
        return spd_inverse(self.surface_stiffness)

    def nodal_load(self, pressure_at_quad):
        """Tᵀ of the half-space's consistent nodal loads (E* = 1 units)."""
        return self.expansion.T @ self.half_space.nodal_load(pressure_at_quad)

    def deflection(self, pressure_at_quad):
        """Upward surface displacement at `r_nodes` of the restricted solid under a pressure p
        (> 0 into the solid)."""
        return -self.compliance @ self.nodal_load(pressure_at_quad)


def _with_outside(stiffness, outside):
    """(S⁻¹ + k 11ᵀ)⁻¹ = S − k s sᵀ/(1 + k 1ᵀs), s = S1 (Sherman-Morrison), for the SPD
    stiffness S of the truncated solid and the compliance k ≥ 0 that the solid outside adds
    uniformly: the surface stiffness without inverting S twice."""
    row_sums = stiffness.sum(axis=1)
    return stiffness - (outside / (1.0 + outside * row_sums.sum())) * np.outer(row_sums,
                                                                               row_sums)


def _linear_interpolation(r, nodes):
    """Sparse T (r.size × nodes.size): values at `nodes` (a subset of the increasing radii r
    that holds both ends) to values at r, linear between neighbouring nodes."""
    right = np.searchsorted(nodes, r, side="right").clip(1, nodes.size - 1)
    t = (r - nodes[right - 1]) / (nodes[right] - nodes[right - 1])
    rows = np.tile(np.arange(r.size), 2)
    cols = np.concatenate([right - 1, right])
    return coo_matrix((np.concatenate([1.0 - t, t]), (rows, cols)),
                      shape=(r.size, nodes.size)).tocsr()
