"""Graded triangular mesh of the truncated axisymmetric half-space, built in code.

Lengths are in the radial scale √(Rε) (one length unit for r and z, so the elastic problem stays
isotropic). The domain is [0, size] × [−size, 0]: r along x, depth along −y, the surface at y = 0.
The mesh is fine (surface edges ≤ `h_surface`) along the surface strip 0 ≤ r ≤ `r_fine` and grows
linearly with the distance d from that strip, size ≈ h_surface + grading · d, by conforming
red-green-blue refinement of a coarse tensor grid (`MeshTri.refined`). With a layer, the interface
z = −t is a mesh line and the elements above it form the subdomain 'layer'.
"""

import numpy as np
from skfem import MeshTri

from ..plumbing.checks import in_range, positive

#: Refinement passes allowed; each halves the largest elements, so 60 covers any size/h ratio.
_MAX_PASSES = 60


def _surface_edge(r_fine, h_surface):
    """(edge, cells): the longest surface edge ≤ h_surface that red refinement of `cells`
    ∈ {1, 2, 3} equal coarse cells across the strip reaches exactly (edge = r_fine / (cells · 2^k)
    > ⅔ h)."""
    needed = int(np.ceil(r_fine / h_surface - 1e-9))
    count, cells = min((m * 2 ** int(np.ceil(np.log2(max(needed / m, 1.0)))), m) for m in (1, 2, 3))
    return r_fine / count, cells


def _coarse_grid(r_fine, size, cells, layer_thickness):
    """Tensor grid with `cells` square cells across the strip, then lines at r_fine·2^k (and −t):
    element aspect ratios stay ≤ 3 near r_fine."""
    levels = int(np.ceil(np.log2(size / r_fine)))
    xs = np.concatenate([np.linspace(0.0, r_fine, cells + 1), r_fine * 2.0 ** np.arange(levels),
                         [size]])
    xs = np.unique(xs[xs <= size])
    ys = -xs[::-1]
    if layer_thickness is not None:
        ys = np.unique(np.concatenate([ys, [-layer_thickness]]))
    return MeshTri.init_tensor(xs, ys)


def _element_sizes(mesh):
    corners = mesh.p[:, mesh.t]
    edges = [np.hypot(*(corners[:, i] - corners[:, (i + 1) % 3])) for i in range(3)]
    return np.max(edges, axis=0), corners.mean(axis=1)


def graded_mesh(*, h_surface, r_fine, size, grading=0.3, layer_thickness=None):
    """Return a conforming graded `MeshTri` with boundaries 'top', 'axis', 'far' (bottom + outer).

    h_surface: longest surface edge on the strip r ≤ r_fine, in √(Rε) (edges come out uniform,
        between ⅔ h_surface and h_surface, a few halved by the conforming closure).
    r_fine: radius of the finely meshed surface strip, in √(Rε).
    size: truncation radius and depth L, in √(Rε) (> 4 r_fine).
    grading: growth of the element size per unit distance from the strip, in (0, 1].
    layer_thickness: depth t of a layer interface, in √(Rε), or None for a homogeneous solid;
        elements above it are tagged subdomain 'layer'.
    """
    h_surface = positive("h_surface", h_surface)
    r_fine = in_range("r_fine", r_fine, h_surface, np.inf)
    size = in_range("size", size, 4.0 * r_fine, np.inf)
    grading = in_range("grading", grading, 0.0, 1.0 + 1e-12)
    if layer_thickness is not None:
        layer_thickness = in_range("layer_thickness", layer_thickness, 0.0, size)
    edge, cells = _surface_edge(r_fine, h_surface)
    mesh = _coarse_grid(r_fine, size, cells, layer_thickness)
    for _ in range(_MAX_PASSES):
        diameter, centroid = _element_sizes(mesh)
        distance = np.hypot(np.maximum(centroid[0] - r_fine, 0.0), centroid[1])
        marked = np.nonzero(diameter > np.sqrt(2.0) * edge * (1.0 + 1e-9) + grading * distance)[0]
        if marked.size == 0:
            break
        mesh = mesh.refined(marked)
    tol = 1e-9 * h_surface
    mesh = mesh.with_boundaries(
        {
            "top": lambda x: np.abs(x[1]) < tol,
            "axis": lambda x: np.abs(x[0]) < tol,
            "far": lambda x: (np.abs(x[0] - size) < tol) | (np.abs(x[1] + size) < tol),
        }
    )
    if layer_thickness is not None:
        mesh = mesh.with_subdomains({"layer": lambda x: x[1] > -layer_thickness})
    return mesh
