"""Displacement-control paths read off the traced equilibrium curve: folds, jumps and landings.

On approach (δ̄o decreasing) the solid follows the stable branch it is on until that branch ends at
a fold of δ̄o; past the fold no nearby equilibrium exists and it jumps, at the fold's δ̄o, to the
next stable branch that the curve reaches at the same δ̄o (the landing, solved by Newton at fixed
δ̄o from the interpolated state). Retraction is the same walk backwards along the curve.
"""

import numpy as np
from scipy.optimize import brentq

from ..plumbing.errors import ContinuationError
from .continuation import Linearisation, correct, trace
from .curve import Jump, curve_from_columns, parabola_vertex

COLUMNS = ("delta", "x", "p", "area", "a_c")
#: Newton iterations allowed per point of `root_along`, 40: when its guess was the linear
#: blend of the two bracketing states (now the fallback), which blurs a crack front that moved
#: between them, each point at μ = 10 (BEM default, edge-following grids) needed 12, and with
#: the continuation's 10 the pull-off was left a sample, 2.9e-6 off the extremum.
#: test_near_events.py::test_the_pull_off_at_large_mu_is_the_extremum_not_a_sample.
ROOT_NEWTON = 40
#: A point of `root_along` farther from sample k than BRACKET_REACH times sample k + 1 is on
#: another part of the curve (near a fold the constraint plane also holds far-away equilibria)
#: and ends the search. Not pinned by a test.
BRACKET_REACH = 2.0
#: Intervals searched for an extremum of P̄, relative to where the stored tangents change sign:
#: there, then one before and one after (`refine_force_extrema`). At μ = 7 (BEM fine, refined)
#: the stored dP̄/ds at the sample nearest P̄off was −8.4e-5, recomputed +9.9e-5, and P̄off was
#: left a sample 7e-7 off. test_near_events.py.
ADJACENT = (0, -1, 1)


def root_along(surface, trace, k, component, *, xtol=1e-9):
    """The point between trace points k and k + 1 where the `component` (0: x̄o, 1: δ̄o, 2: P̄) of
    the unit tangent vanishes, as (w, δ, Linearisation), or None if there is no clean root.

    The root in the arc length σ ∈ (0, σ₁) along the tangent at k is found by Brent's method,
    each evaluation a converged point (`correct`) and its exact tangent; it needs the component
    to change sign between k and k + 1. Each evaluation starts from the nearest state solved so
    far (k and k + 1 to begin with) moved along its tangent: a linear blend of two states would
    blur a crack front that moved between them (at μ = 10 that took 12 Newton iterations per
    evaluation, this 2-4). Where Newton fails from there (across a fold, at μ = 7 on the grids
    that follow the edge) it starts again from the blend."""
    t0 = trace.tangents[k]
    anchor = np.array([trace.x[k], trace.delta[k], trace.p[k]])
    chord = np.array([trace.x[k + 1], trace.delta[k + 1], trace.p[k + 1]]) - anchor
    end, reach = float(t0 @ chord), float(np.linalg.norm(chord))
    known = {0.0: (trace.states[k], trace.delta[k], None),
             end: (trace.states[k + 1], trace.delta[k + 1], None)}
    states = {}

    def guesses(sigma):
        near = min(known, key=lambda s: abs(s - sigma))
        w, d, rates = known[near]
        if rates is not None:  # (dw/dσ, dδ/dσ) there
            yield w + rates[0] * (sigma - near), d + rates[1] * (sigma - near)
        else:
            yield w, d
        frac = sigma / end  # past a fold the tangent turns: the blend of the two ends
        yield ((1.0 - frac) * trace.states[k] + frac * trace.states[k + 1],
               (1.0 - frac) * trace.delta[k] + frac * trace.delta[k + 1])

    def slope(sigma):
        for w, d in guesses(sigma):
            solved = correct(surface, w, d, t0, anchor, sigma, max_newton=ROOT_NEWTON)
            if solved is not None:
                break
        if solved is None:
            raise ContinuationError(f"no equilibrium near δ = {d:.6g}")
        w, d, _, _ = solved
        away = np.array([surface.centre_gap(w, d), d, surface.force(w, d)]) - anchor
        if np.linalg.norm(away) > BRACKET_REACH * reach:  # another branch: no root here
            raise ContinuationError(f"the search left the bracket (δ = {d:.6g})")
        linear = Linearisation(surface, w, d, t0)
        dw, dd, do = linear.tangent()
        along = float(t0 @ do)  # dσ/ds: the tangent turns less than a step's turn limit
        known[sigma] = (w, d, (dw / along, dd / along) if abs(along) > 0.5 else None)
        states[sigma] = (w, d, linear)
        return do[component]

    try:
        sigma = brentq(slope, 0.0, end, xtol=xtol * max(end, 1.0), rtol=1e-12)
    except (ContinuationError, ValueError):  # no clean root here (e.g. ripple)
        return None
    return states[sigma] if sigma in states and 0.0 < sigma < end else None


def refine_force_extrema(surface, trace, *, xtol=1e-9):
    """Insert into `trace` the exact extrema of P̄ between stable neighbouring samples.

    Where the tangent's P̄ component dP̄/ds changes sign between samples k and k + 1, the root is
    found by `root_along`. Sampled at a turn limit of 0.1 rad, the parabola through three
    samples alone misplaces P̄off by ~3e-5 at μ = 1. A stored tangent may come from a reused
    factorisation, good to about 1e-2 of the step, so where dP̄/ds is that small its sign can be
    wrong and the root lie one interval earlier or later (`ADJACENT`); root_along recomputes the
    tangents and finds which. Where no equilibrium is found inside the bracket (ripple of a too
    coarse surface mesh) the samples are left as they are. Returns the number of points
    inserted.
    """
    inserted = 0
    k = 0
    while k < len(trace.p) - 1:
        t0, t1 = trace.tangents[k], trace.tangents[k + 1]
        if not (trace.stable[k] and trace.stable[k + 1]) or t0[2] * t1[2] >= 0.0:
            k += 1
            continue
        extremum = None
        for j in (k + shift for shift in ADJACENT):
            if 0 <= j < len(trace.p) - 1 and trace.stable[j] and trace.stable[j + 1]:
                extremum = root_along(surface, trace, j, 2, xtol=xtol)
                if extremum is not None:
                    break
        if extremum is not None:
            w, d, linear = extremum
            trace.insert(j + 1, surface, w, d, linear.stable, surface.force(w, d),
                         surface.contact(w, d), linear.tangent()[2])
            inserted += 1
            k = max(k, j) + 2  # past the inserted point and the interval it came from
            continue
        k += 1
    return inserted


def equilibrium_curve(trace):
    """The traced curve as a `Curve`; `branch` counts the changes of stability along it."""
    stable = np.asarray(trace.stable)
    branch = np.concatenate([[0], np.cumsum(stable[1:] != stable[:-1])])
    return curve_from_columns(*(getattr(trace, c) for c in COLUMNS), stable, branch)


def fold_by_parabola(curve, i, j, descending):
    """Values at the extremum of δ̄o between the stable sample i and the unstable sample j (a
    minimum when δ̄o was `descending`), from parabolas in arc length through the three samples
    centred on the more extreme of the two."""
    pair = np.array(sorted((i, j)))
    extreme = pair[np.argmin(curve.delta[pair] if descending else -curve.delta[pair])]
    centre = int(np.clip(extreme, 1, len(curve) - 2))
    three = slice(centre - 1, centre + 2)
    steps = np.hypot(np.diff(curve.x[three]), np.diff(curve.delta[three]))
    arc = np.concatenate([[0.0], np.cumsum(steps)])
    s_star, delta = parabola_vertex(arc, curve.delta[three])
    values = {c: float(np.polyval(np.polyfit(arc, getattr(curve, c)[three], 2), s_star))
              for c in ("x", "p", "a_c")}
    return float(delta), values


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
    between trace points a and b, as a row of COLUMNS; None if Newton does not converge."""
    guess = (1.0 - t) * trace.states[a] + t * trace.states[b]
    solved = correct(surface, guess, delta, np.array([0.0, 1.0, 0.0]),
                     np.array([0.0, delta, 0.0]), 0.0)
    if solved is None:
        return None
    w, d, _, _ = solved
    area, radius = surface.contact(w, d)
    return dict(delta=d, x=surface.centre_gap(w, d), p=surface.force(w, d), area=area,
                a_c=radius)


def walk(surface, trace, curve, order):
    """Follow `order` (indices along the curve) under δ̄o control; returns (path Curve, jumps)."""
    rows, jumps, branch = [], [], 0
    pos = 0
    while pos < len(order):
        i = order[pos]
        rows.append(point_row(curve, i, branch))
        if pos + 1 < len(order) and not curve.stable[order[pos + 1]]:
            descending = pos > 0 and curve.delta[i] < curve.delta[order[pos - 1]]
            delta, before = fold_by_parabola(curve, i, order[pos + 1], descending)
            before["area"] = 0.0 if before["a_c"] <= 0.0 else np.pi * before["a_c"] ** 2
            rows.append(dict(delta=delta, **before, branch=branch))
            pos, after = _landing(surface, trace, curve, order, pos + 1, delta)
            branch += 1
            rows.append(after | {"branch": branch})
            jumps.append(Jump(delta=delta, x_before=before["x"], p_before=before["p"],
                              p_after=after["p"], a_c_after=after["a_c"], x_after=after["x"]))
        pos += 1
    return path_from_rows(rows), jumps


def point_row(source, i, branch):
    """Row of a path: the COLUMNS of point i of `source` (a Trace or a Curve) and `branch`."""
    return {c: getattr(source, c)[i] for c in COLUMNS} | {"branch": branch}


def path_from_rows(rows):
    """A displacement-control path (`Curve`, all stable) from dicts with COLUMNS and 'branch'."""
    columns = {c: [r[c] for r in rows] for c in (*COLUMNS, "branch")}
    return curve_from_columns(**columns, stable=np.ones(len(rows), dtype=bool))


def whole_curve_paths(surface, settings, progress=None):
    """(approach, retraction, jumps in, jumps out, equilibrium, traced) as
    `branches.stable_paths`, read off the whole equilibrium curve, unstable branches included."""
    traced = trace(surface, settings, progress=progress)
    refine_force_extrema(surface, traced)
    curve = equilibrium_curve(traced)
    order = np.arange(len(curve))
    approach, jumps_in = walk(surface, traced, curve, order)
    retraction, jumps_out = walk(surface, traced, curve, order[::-1])
    return approach, retraction, jumps_in, jumps_out, curve, traced
