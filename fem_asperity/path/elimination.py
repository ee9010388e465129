"""Nonlinear elimination of the contact edge: a local Newton on the few nodes where a predicted
state is out of balance, before the global Newton starts.

Along the curve the neck at the contact edge travels outward; a predictor extrapolated node by
node misplaces it by ~0.1 ε at a few tens of nodes, and the global Newton then spends several
dense factorisations closing that error slowly. Solving the equilibrium of those nodes alone
first (the others held) costs a few small dense solves and saves global iterations, the events
unchanged; test_surface_solver.py::test_edge_relaxation_* pin what it does and refuses to do.
"""

import numpy as np
from scipy.linalg import LinAlgError, cho_factor, cho_solve

from ..closed_forms.lj import scaled_traction as traction
from ..closed_forms.lj import scaled_traction_slope as traction_slope
from .surface import gap_keeping_step

#: Nodes whose residual exceeds this fraction of the largest one are relaxed (with two
#: neighbours each side). Not pinned by a test.
FRACTION = 0.05
#: A residual spread over more nodes than this is not an edge's: left to the global Newton;
#: test_surface_solver.py::test_edge_relaxation_leaves_a_spread_residual_alone.
MAX_NODES = 64


def relax_edge(surface, w, delta, *, limit, iterations=8, tol=1e-6):
    """w with the out-of-balance nodes brought to local equilibrium at fixed δ (the others held).

    Local Newton with the exact tangent of those nodes and a gap-keeping step, stopped once a
    step moves no node by more than `tol` ε. Returns `w` itself, unrelaxed, if the local tangent
    is not positive definite (the edge would snap: a fold, left to the continuation), if a node
    would move by more than `limit` ε (the predictor's own largest move: further would risk
    stepping onto another branch) or if the local residual did not fall.
    """
    g = surface.residual(w, delta)
    big = np.nonzero(np.abs(g) > FRACTION * np.max(np.abs(g)))[0]
    if big.size > MAX_NODES:
        return w
    nodes = np.unique(np.clip(big[:, None] + np.arange(-2, 3), 0, w.size - 1))
    local = surface.interp[:, nodes].tocsc()
    points = np.unique(local.nonzero()[0])
    local = local[points].tocsr()
    local_t = local.T.tocsr()
    weights = surface.weights[points]
    stiffness = surface.stiffness[np.ix_(nodes, nodes)]
    gap0 = surface.gap(w, delta)[points]
    elastic = g[nodes] - surface.load_factor * (local_t @ (weights * traction(gap0)))
    change = np.zeros(nodes.size)

    def local_residual(gap):
        return elastic + stiffness @ change + surface.load_factor * (
            local_t @ (weights * traction(gap)))

    start = np.linalg.norm(g[nodes])
    for _ in range(iterations):
        gap = gap0 - local @ change
        slope = weights * traction_slope(gap)
        jac = stiffness - surface.load_factor * (local_t @ local.multiply(slope[:, None])).toarray()
        try:
            step = cho_solve(cho_factor(jac), -local_residual(gap))
        except LinAlgError:
            return w
        alpha = gap_keeping_step(gap, -(local @ step))
        change += alpha * step
        if alpha * np.max(np.abs(step)) < tol:
            break
    if (np.max(np.abs(change)) > limit
            or not np.linalg.norm(local_residual(gap0 - local @ change)) < start):
        return w
    relaxed = w.copy()
    relaxed[nodes] += change
    return relaxed
