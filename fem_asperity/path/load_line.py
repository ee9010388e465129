"""Load-line control (an AFM's compliant cantilever), read off the whole equilibrium curve.

The sphere hangs on a spring of stiffness k̄ = Kε/(2πRΔγ) whose far end, at z̄ (in ε), is moved:
the spring pulls the sphere with k̄ (z̄ − δ̄o), so in equilibrium P̄ + k̄ (z̄ − δ̄o) = 0, i.e.
z̄ = δ̄o − P̄/k̄; the cantilever's deflection is z̄ − δ̄o = −P̄/k̄. A state of the equilibrium curve
is stable under this control where it is stable at fixed δ̄o and dP̄/dδ̄o < k̄: along the curve,
where dz̄/ds has the sign of dδ̄o/ds. So the jumps happen where the force gradient reaches the
spring's stiffness, earlier than under displacement control (k̄ → ∞), and at any μ. The solid
jumps at fixed z̄ to the next stable state with the same z̄ further along the curve (its δ̄o and
P̄ change in the jump).

Folds of z̄ come from a parabola in arc length through three samples, as accurate as the
curve's sampling (the turn limit), unlike the exact folds of displacement control; a landing is
solved by Newton at the δ̄o interpolated in z̄.
"""

from dataclasses import dataclass, replace

import numpy as np
from scipy.optimize import brentq

from ..closed_forms.lj import rigid_force
from ..curves.events import Jump, parabola_vertex
from ..plumbing.errors import ContinuationError
from .paths import PathPoint
from .reading import COLUMNS, path_from_rows, point_row
from .whole_curve import state_at


def spring_stable(curve, tangents, k):
    """Whether each point of `curve` is stable under a spring of stiffness `k`: stable at fixed
    δ̄o, and dz̄/ds = dδ̄o/ds − (dP̄/ds)/k of the same sign as dδ̄o/ds (`tangents`: unit tangents
    d(x̄o, δ̄o, P̄)/ds of the traced points)."""
    t = np.asarray(tangents)
    d_delta, d_p = t[:, 1], t[:, 2]
    return curve.stable & (d_delta * (d_delta - d_p / k) > 0.0)


def _fold(curve, z, i, j):
    """(z̄, `PathPoint`) at the extremum of z̄ between the stable sample i and the unstable
    sample j: a parabola in arc length (in x̄o, δ̄o, P̄) through the three samples centred on the
    more extreme."""
    descending = z[j] < z[i] if z[j] != z[i] else True
    pair = np.array([i, j])
    extreme = pair[np.argmin(z[pair] if descending else -z[pair])]
    centre = int(np.clip(extreme, 1, len(z) - 2))
    three = slice(centre - 1, centre + 2)
    steps = np.sqrt(np.diff(curve.x[three]) ** 2 + np.diff(curve.delta[three]) ** 2
                    + np.diff(curve.p[three]) ** 2)
    arc = np.concatenate([[0.0], np.cumsum(steps)])
    s_star, z_star = parabola_vertex(arc, z[three])
    row = PathPoint(*(float(np.polyval(np.polyfit(arc, getattr(curve, c)[three], 2), s_star))
                      for c in COLUMNS))
    return float(z_star), row


def _landing(surface, traced, curve, z, stable, order, start, z_jump, k):
    """(position in `order` to go on from, `PathPoint`) of the first segment after `start` whose
    two ends are stable and whose z̄ spans `z_jump`: δ̄o interpolated linearly in z̄ between them,
    then the state there solved by Newton at that δ̄o (far from contact the samples are sparse,
    and P̄ interpolated between them was 7% off after the jump-out at μ = 2). A jump away from
    the surface past the curve's far start lands beyond it (`_far_landing`)."""
    for pos in range(start, len(order) - 1):
        a, b = order[pos], order[pos + 1]
        if not (stable[a] and stable[b]) or (z[a] - z_jump) * (z[b] - z_jump) > 0.0:
            continue
        t = (z_jump - z[a]) / (z[b] - z[a]) if z[b] != z[a] else 0.0
        delta = (1.0 - t) * curve.delta[a] + t * curve.delta[b]
        landed = state_at(surface, traced, a, b, t, delta)
        if landed is not None:
            return pos + 1, landed
    if order[-1] == 0 and z_jump > z[0]:
        return len(order), _far_landing(surface, traced, curve, z_jump, k)
    raise ContinuationError(f"no stable state to land on at z = {z_jump:.6g} under the spring")


def _far_landing(surface, traced, curve, z_jump, k):
    """The state a soft spring's jump-out lands on beyond the curve's far start (δ̄o = δ̄₀ there):
    where the spring balances the LJ pull, P̄ = k̄(δ̄o − z̄), on the far-field force of the rigid
    sphere (`lj.rigid_force`, of the surface's profile; the solid's deflection is smaller there
    than at δ̄₀), the state solved by Newton at that δ̄o from the state at δ̄₀. So no curve is
    traced out to 1/k̄. Its P̄ is the rigid sphere's: the traction grid, ending at a finite
    radius, under-counts the pull that far out (by 0.8 % at δ̄o = 490 on the BEM's r = 100,
    `solver.estimate.traction_tail`). Where that under-count alone put the landing beyond δ̄₀ (the
    balance on the rigid force lies short of it), it lands on the state at δ̄₀."""
    start = float(curve.delta[0])

    def unbalanced(d):
        return d - rigid_force(d, radius_ratio=surface.radius_ratio) / k - z_jump

    if unbalanced(start) >= 0.0:
        return point_row(curve, 0, 0)
    delta = brentq(unbalanced, start, z_jump, xtol=1e-12, rtol=1e-12)
    landed = state_at(surface, traced, 0, 0, 0.0, delta)
    if landed is None:
        raise ContinuationError(f"no state to land on at z = {z_jump:.6g} under the spring "
                                f"(delta = {delta:.6g})")
    return replace(landed, p=rigid_force(delta, radius_ratio=surface.radius_ratio))


def _walk(surface, traced, curve, z, stable, order, k):
    """Follow `order` under z̄ control: (path rows, their z̄, jumps, z̄ of each jump)."""
    rows, zs, jumps, z_jumps, branch, pos = [], [], [], [], 0, 0
    while pos < len(order):
        i = order[pos]
        rows.append(point_row(curve, i, branch))
        zs.append(z[i])
        if pos + 1 < len(order) and not stable[order[pos + 1]]:
            z_jump, before = _fold(curve, z, i, order[pos + 1])
            rows.append(before.on(branch))
            zs.append(z_jump)
            pos, after = _landing(surface, traced, curve, z, stable, order, pos + 1, z_jump,
                                  k)
            branch += 1
            rows.append(after.on(branch))
            zs.append(z_jump)
            jumps.append(Jump(delta=before.delta, x_before=before.x, p_before=before.p,
                              p_after=after.p, a_c_after=after.a_c, x_after=after.x))
            z_jumps.append(z_jump)
        pos += 1
    return rows, np.array(zs), jumps, z_jumps


@dataclass(frozen=True)
class LoadLinePaths:
    """Both paths under a spring's control: `approach` and `retraction` (`Curve`s in the sphere's
    δ̄o, a jump as consecutive points at equal z̄), the `Jump`s in and out, the spring end's z̄
    along each path and at each jump."""

    approach: object
    retraction: object
    jumps_in: list
    jumps_out: list
    z_approach: np.ndarray
    z_retraction: np.ndarray
    z_in: list
    z_out: list


def load_line_paths(surface, traced, curve, k):
    """`LoadLinePaths`: approach and retraction under load-line control with spring stiffness `k`
    (2πRΔγ/ε), read off the whole equilibrium `curve` (ordered from the far start to the deepest
    load) as traced (`traced`: its states and unit tangents) on `surface`."""
    z = curve.delta - curve.p / k
    stable = spring_stable(curve, traced.tangents, k)
    order = np.arange(len(curve))
    approach, z_approach, jumps_in, z_in = _walk(surface, traced, curve, z, stable, order, k)
    retraction, z_retraction, jumps_out, z_out = _walk(surface, traced, curve, z, stable,
                                                       order[::-1], k)
    return LoadLinePaths(path_from_rows(approach), path_from_rows(retraction), jumps_in,
                         jumps_out, z_approach, z_retraction, z_in, z_out)
