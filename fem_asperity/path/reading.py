"""Reading a traced equilibrium curve: the points where a tangent component vanishes (folds of
δ̄o, extrema of P̄), the curve's arrays, a fold by a parabola, and path rows. Shared by the paths
read off the whole curve (`whole_curve`), the stable branches (`branches`) and the load line.
"""

import numpy as np
from scipy.optimize import brentq

from ..curves.curve import curve_from_columns
from ..curves.events import parabola_vertex
from ..plumbing.errors import ContinuationError
from .continuation import Linearisation, correct
from .paths import PathPoint, disc_area

COLUMNS = ("delta", "x", "p", "area", "a_c")
#: Newton iterations per point of `root_along` (12 were needed at μ = 10 from a linear blend).
#: test_near_events.py::test_the_pull_off_at_large_mu_is_the_extremum_not_a_sample.
ROOT_NEWTON = 40
#: A `root_along` point farther from sample k than this times sample k + 1 is on another part of
#: the curve and ends the search. Not pinned by a test.
BRACKET_REACH = 2.0
#: Intervals searched for an extremum of P̄ about where the stored tangents change sign (their
#: sign can be stale by ~1e-4). docs/methods.md §12; test_near_events.py.
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
    """The `PathPoint` at the extremum of δ̄o between the stable sample i and the unstable sample
    j (a minimum when δ̄o was `descending`), from parabolas in arc length through the three
    samples centred on the more extreme of the two; its area the disc's (`disc_area`)."""
    pair = np.array(sorted((i, j)))
    extreme = pair[np.argmin(curve.delta[pair] if descending else -curve.delta[pair])]
    centre = int(np.clip(extreme, 1, len(curve) - 2))
    three = slice(centre - 1, centre + 2)
    steps = np.hypot(np.diff(curve.x[three]), np.diff(curve.delta[three]))
    arc = np.concatenate([[0.0], np.cumsum(steps)])
    s_star, delta = parabola_vertex(arc, curve.delta[three])
    values = {c: float(np.polyval(np.polyfit(arc, getattr(curve, c)[three], 2), s_star))
              for c in ("x", "p", "a_c")}
    return PathPoint(delta=float(delta), area=disc_area(values["a_c"]), **values)


def point_row(source, i, branch):
    """The `PathPoint` of point i of `source` (a Trace or a Curve) on `branch`."""
    return PathPoint(*(getattr(source, c)[i] for c in COLUMNS), branch)


def path_from_rows(rows):
    """A displacement-control path (`Curve`, all stable) from its `PathPoint`s."""
    columns = {c: [getattr(r, c) for r in rows] for c in (*COLUMNS, "branch")}
    return curve_from_columns(**columns, stable=np.ones(len(rows), dtype=bool))
