"""Displacement-control paths read off the traced equilibrium curve: folds, jumps and landings.

On approach (δ̄o decreasing) the solid follows the stable branch it is on until that branch ends at
a fold of δ̄o; past the fold no nearby equilibrium exists and it jumps, at the fold's δ̄o, to the
next stable branch that the curve reaches at the same δ̄o (the landing, solved by Newton at fixed
δ̄o from the interpolated state). Retraction is the same walk backwards along the curve.
"""

import numpy as np

from ..curves.events import Jump
from ..plumbing.errors import ContinuationError
from .continuation import correct, trace
from .paths import PathPoint, Paths
from .reading import (
    equilibrium_curve,
    fold_by_parabola,
    path_from_rows,
    point_row,
    refine_force_extrema,
)


def _landing(surface, trace, curve, order, start, delta):
    """First stable segment after position `start` of `order` that crosses δ̄o = `delta` and on
    which Newton converges; returns (position in order after which to continue, landing values)."""
    for pos in range(start, len(order) - 1):
        a, b = order[pos], order[pos + 1]
        if not (curve.stable[a] and curve.stable[b]):
            continue
        da, db = curve.delta[a] - delta, curve.delta[b] - delta
        if da * db > 0.0:
            continue
        t = da / (da - db) if da != db else 0.0
        landed = state_at(surface, trace, a, b, t, delta)
        if landed is None:  # e.g. a rippled segment: try the next stable crossing
            continue
        return pos + 1, landed
    raise ContinuationError(f"no stable branch to land on at δ = {delta:.6g} (or Newton failed "
                            "on each)")


def state_at(surface, trace, a, b, t, delta):
    """The equilibrium at δ̄o = `delta` by Newton from the state interpolated at fraction `t`
    between trace points a and b, as a `PathPoint`; None if Newton does not converge."""
    guess = (1.0 - t) * trace.states[a] + t * trace.states[b]
    solved = correct(surface, guess, delta, np.array([0.0, 1.0, 0.0]),
                     np.array([0.0, delta, 0.0]), 0.0)
    if solved is None:
        return None
    w, d, _, _ = solved
    area, radius = surface.contact(w, d)
    return PathPoint(d, surface.centre_gap(w, d), surface.force(w, d), area, radius)


def walk(surface, trace, curve, order):
    """Follow `order` (indices along the curve) under δ̄o control; returns (path Curve, jumps)."""
    rows, jumps, branch = [], [], 0
    pos = 0
    while pos < len(order):
        i = order[pos]
        rows.append(point_row(curve, i, branch))
        if pos + 1 < len(order) and not curve.stable[order[pos + 1]]:
            descending = pos > 0 and curve.delta[i] < curve.delta[order[pos - 1]]
            before = fold_by_parabola(curve, i, order[pos + 1], descending)
            delta = before.delta
            rows.append(before.on(branch))
            pos, after = _landing(surface, trace, curve, order, pos + 1, delta)
            branch += 1
            rows.append(after.on(branch))
            jumps.append(Jump(delta=delta, x_before=before.x, p_before=before.p,
                              p_after=after.p, a_c_after=after.a_c, x_after=after.x))
        pos += 1
    return path_from_rows(rows), jumps


def whole_curve_paths(surface, settings, progress=None):
    """`Paths` as `branches.stable_paths`, read off the whole equilibrium curve, unstable branches
    included (on one grid: no moves)."""
    traced = trace(surface, settings, progress=progress)
    refine_force_extrema(surface, traced)
    curve = equilibrium_curve(traced)
    order = np.arange(len(curve))
    approach, jumps_in = walk(surface, traced, curve, order)
    retraction, jumps_out = walk(surface, traced, curve, order[::-1])
    return Paths(approach, retraction, jumps_in, jumps_out, curve, traced)
