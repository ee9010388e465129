"""The boundary-integral half-space: the surface compliance from the Boussinesq kernel, no mesh.

Same units and interface as `solids.fe.HalfSpace` (r in √(Rε), w in ε, E* = 1, the 2π dropped,
surface integrals weighted by r), so `path.surface.LJSurface` and the continuation run on either.

Galerkin form on a radial grid of linear elements: traction p and deflection w are both
piecewise linear with nodal values; with M = ∫ φᵢ φⱼ r dr and B = ∫ φᵢ(r) u[φⱼ](r) r dr (u the
Boussinesq deflection of a hat traction, `boussinesq.galerkin_matrix`), a load vector
f = ∫ p φᵢ r dr gives p = M⁻¹ f and M w = B p, so the compliance is C = M⁻¹ B M⁻¹, symmetric and
positive definite like the FE's, and the surface stiffness C⁻¹ = M B⁻¹ M. The half-space is
infinite: there is no truncation of the solid, only of the traction beyond the last node.
"""

from functools import cached_property

import numpy as np
from scipy.linalg import cho_solve_banded, cholesky_banded
from scipy.sparse import csr_matrix

from ..plumbing.errors import InputError
from .boussinesq import galerkin_matrix, quadrature
from .layered import layer_correction
from .operator import spd_inverse


def radial_grid(*, h, r_fine, r_max, growth=0.1):
    """Nodes 0, h, 2h, … up to r_fine, then element sizes growing by (1 + growth) up to r_max."""
    if not 0.0 < h <= r_fine < r_max:
        raise InputError(f"need 0 < h <= r_fine < r_max; got {h}, {r_fine}, {r_max}")
    uniform = np.linspace(0.0, r_fine, int(np.ceil(r_fine / h)) + 1)
    tail, size = [r_fine], uniform[1]
    while tail[-1] < r_max:
        size *= 1.0 + growth
        tail.append(tail[-1] + size)
    tail[-1] = max(tail[-1], r_max)
    return np.concatenate([uniform, tail[1:]])


class BoussinesqSurface:
    """Surface operators of the elastic half-space on the radial grid `nodes`: homogeneous, or
    with the bonded layer of `solid` (`fe.Solid`; its layer's half-space plus the correction of
    `layered.layer_correction`).

    The `operator.ElasticSurface` interface: r_nodes, r_quad (Gauss points,
    `boussinesq.quadrature`), weights (Gauss weight × r), interp (nodal values → values at
    r_quad), compliance (dense C, built on first use), surface_stiffness (C⁻¹), dofs (unknowns:
    the surface nodes).
    """

    def __init__(self, nodes, *, solid=None):
        nodes = np.asarray(nodes, dtype=float)
        if nodes[0] != 0.0 or np.any(np.diff(nodes) <= 0.0):
            raise InputError("the radial grid must start at 0 and increase")
        points, weights, x = quadrature(nodes)
        elements, per = points.shape
        self.r_nodes = nodes
        self.r_quad = points.ravel()
        self.weights = weights.ravel() * self.r_quad
        element = np.repeat(np.arange(elements), per)
        rows = np.tile(np.arange(self.r_quad.size), 2)
        cols = np.concatenate([element, element + 1])
        values = np.concatenate([np.tile(1.0 - x, elements), np.tile(x, elements)])
        self.interp = csr_matrix((values, (rows, cols)), shape=(self.r_quad.size, nodes.size))
        weighted = self.interp.T.multiply(self.weights).tocsr()
        self._mass = weighted @ self.interp  # tridiagonal
        coupling = galerkin_matrix(nodes)
        if solid is not None and solid.layer_thickness is not None:
            coupling = (coupling / solid.layer_modulus_ratio
                        + layer_correction(nodes, solid))
        self._coupling = 0.5 * (coupling + coupling.T)
        stiffness = np.asarray(self._mass @ (self._mass @ spd_inverse(self._coupling)).T)
        self.surface_stiffness = 0.5 * (stiffness + stiffness.T)
        self.dofs = nodes.size

    @cached_property
    def compliance(self):
        """C = M⁻¹ B M⁻¹ (banded Cholesky solves with the tridiagonal M)."""
        banded = np.zeros((2, self.r_nodes.size))
        banded[0, 1:], banded[1] = self._mass.diagonal(1), self._mass.diagonal()
        factor = cholesky_banded(banded), False
        half = cho_solve_banded(factor, self._coupling)
        compliance = cho_solve_banded(factor, half.T)
        return 0.5 * (compliance + compliance.T)

    def nodal_load(self, pressure_at_quad):
        """Consistent surface load ∫ p φᵢ r dr of a pressure given at the quadrature points."""
        return self.interp.T @ (self.weights * pressure_at_quad)

    def deflection(self, pressure_at_quad):
        """Upward surface displacement w at the nodes (negative under compression)."""
        return -self.compliance @ self.nodal_load(pressure_at_quad)
