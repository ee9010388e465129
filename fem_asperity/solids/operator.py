"""The one interface every elastic solid offers the surface problem (`path.surface.LJSurface`).

The FE half-space (`fe.HalfSpace`) and the boundary integral (`bem.BoussinesqSurface`) implement
it today; the layered kernels will too. Lengths in √(Rε), displacements in ε, E* = 1.
"""

from typing import Protocol, runtime_checkable

import numpy as np
from scipy.linalg import LinAlgError, lapack
from scipy.sparse import csr_matrix


@runtime_checkable
class ElasticSurface(Protocol):
    """Surface operators of an elastic solid under axisymmetric normal pressure.

    r_nodes: radii of the surface unknowns (increasing from 0). r_quad, weights: the surface
    quadrature points and their weights with the factor r included. interp: nodal values → values
    at r_quad (sparse, n_quad × n_nodes). compliance: dense C, the upward nodal displacement per
    unit consistent nodal load, symmetric positive definite; surface_stiffness: its inverse.
    dofs: unknowns of the solid (the surface nodes for a boundary integral, every displacement
    DOF for the FE).
    """

    r_nodes: np.ndarray
    r_quad: np.ndarray
    weights: np.ndarray
    interp: csr_matrix
    compliance: np.ndarray
    surface_stiffness: np.ndarray
    dofs: int

    def nodal_load(self, pressure_at_quad: np.ndarray) -> np.ndarray:
        """Consistent surface load ∫ p φᵢ r dr of a pressure given at the quadrature points."""

    def deflection(self, pressure_at_quad: np.ndarray) -> np.ndarray:
        """Upward surface displacement at the nodes (negative under compression)."""


def spd_inverse(matrix):
    """The inverse of the symmetric positive definite `matrix`, symmetric to the last bit, from
    its Cholesky factor (LAPACK potrf and potri: about n³ flops, less than half of solving
    against the identity). Raises LinAlgError where it is not positive definite."""
    factor, info = lapack.dpotrf(matrix, lower=False, clean=False)
    if info == 0:
        inverse, info = lapack.dpotri(factor, lower=False, overwrite_c=True)
    if info > 0:
        raise LinAlgError(f"the matrix is not positive definite (LAPACK info {info})")
    if info < 0:
        raise ValueError(f"LAPACK rejected argument {-info} of potrf/potri")
    return np.triu(inverse) + np.triu(inverse, 1).T
