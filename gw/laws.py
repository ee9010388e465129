"""Single-asperity laws for the GW integrator: P̄(δ̄o) and Ā(δ̄o) on approach, with breakpoints.

A law is any object with `mu`, `name`, `breakpoints` (the δ̄o, in ε, where force or area has a
kink or a jump: δ̄oc, δ̄o*, the jump-in) and vectorised `force(delta)` (P̄, in 2πRΔγ, < 0 tensile),
`area(delta)` (Ā, in εR) defined for every finite δ̄o in ε (negative = the asperity presses into
the half-space). The laws here refuse a non-finite δ̄o, as `fem_asperity.closed_forms.laws`
does, and a force or area beyond the float range, with `InputError`. Three kinds:

- `PaperLaw`: the paper's closed forms (eqs. 2, 7, 9-19) with its constants or refitted ones;
- `CorrectedLaw`: the corrected closed form (`fem_asperity.closed_forms.corrected`);
- `TabulatedLaw`: the approach path of an FE or boundary-integral curve at the same μ, jump
  included, interpolated piecewise (PCHIP per branch), Bradley's rigid force beyond its first
  point and a Hertz continuation beyond its last.
"""

import numpy as np
from scipy.interpolate import PchipInterpolator

from fem_asperity.closed_forms.corrected import CORRECTED_LAWS
from fem_asperity.closed_forms.laws import PAPER_LAWS
from fem_asperity.closed_forms.lj import bradley_force
from fem_asperity.plumbing.checks import finite_result, in_range, positive


def _delta(delta):
    """δ̄o [ε] as the closed forms take it: finite, else `InputError` naming delta_o."""
    return np.asarray(in_range("delta_o", delta))


def _checked(law, delta, what):
    """`law(δ̄o)` at the checked δ̄o `delta` [ε]; `InputError` saying `what` overflowed where the
    result leaves the float range (the closed forms refuse the force so)."""
    with np.errstate(over="ignore"):
        return finite_result(law(_delta(delta)), what)


#: What leaves the float range at a very deep δ̄o (−δ̄o beyond about 1e206 μ for the force, 5e307
#: for the area).
FORCE = "the force (the Hertz compression (δ̄oc − δ̄o)/μ raised to 3/2)"
AREA = "the area π(δ̄o* − δ̄o)"


class PaperLaw:
    """The closed-form laws of `fem_asperity.closed_forms.laws` at one μ (`constants`: the
    paper's by default, or refitted ones)."""

    def __init__(self, mu, constants=PAPER_LAWS, *, name="paper"):
        self.mu, self.constants, self.name = positive("mu", mu), constants, name
        self._at_mu = constants.at(mu)  # constants evaluated once: the GW integrals call often
        self.breakpoints = tuple(sorted({float(constants.delta_oc(mu)),
                                         float(constants.delta_o_star(mu))}))

    def force(self, delta):
        """P̄(δ̄o) [2πRΔγ] on approach at δ̄o `delta` [ε] (array or scalar)."""
        return _checked(self._at_mu.force, delta, FORCE)

    def area(self, delta):
        """Ā(δ̄o) [εR] on approach at δ̄o `delta` [ε] (array or scalar)."""
        return _checked(self._at_mu.area, delta, AREA)


class CorrectedLaw:
    """The corrected closed form (`fem_asperity.closed_forms.corrected`) at one μ; its F̄max
    error against the solved law is `gw.corrected_law.stated_error(mu)` (relative, the largest
    measured at the μ around mu: docs/corrected_law.md)."""

    def __init__(self, mu, constants=CORRECTED_LAWS, *, name="corrected"):
        self.mu, self.constants, self.name = positive("mu", mu), constants, name
        self._at_mu = constants.at(mu)
        self.delta_jump = self._at_mu.delta_jump
        self.breakpoints = tuple(sorted({self._at_mu.delta_zero, self.delta_jump}))

    def force(self, delta):
        """P̄(δ̄o) [2πRΔγ] on approach at δ̄o `delta` [ε] (array or scalar)."""
        return self._at_mu.force(delta)  # checks δ̄o and the result itself

    def area(self, delta):
        """Ā(δ̄o) [εR] on approach at δ̄o `delta` [ε] (array or scalar)."""
        return self._at_mu.area(delta)


class TabulatedLaw:
    """P̄(δ̄o), Ā(δ̄o) read off an approach path (`fem_asperity.curves.curve.Curve`) at Tabor
    parameter mu.

    Each branch of the path (between jumps) is interpolated by PCHIP in δ̄o; a jump is a
    breakpoint, as is δ̄o* (`delta_o_star`, where the area starts). Above the path's first δ̄o
    the force is Bradley's (rigid: the centre deflection there, √2 π μ^(3/2) δ̄o^(−5/2) by
    eq. 4, is small beside the gap) and the area zero; below its last δ̄o the force continues
    as Hertz, P̄ = P̄₀ + (2/3π)[((δ_H − δ̄o)/μ)^1.5 − ((δ_H − δ̄₀)/μ)^1.5], with δ_H set by the
    slope at the last point, the area with slope −π.
    `interpolation_error`: the largest error, relative to max |P̄|, of PCHIP through every other
    sample at the samples left out: an upper estimate of the error of PCHIP through all of them
    (twice as dense, so ~8x smaller where the curve is resolved).
    """

    def __init__(self, mu, approach, *, delta_o_star=None, name="tabulated", source=""):
        self.mu, self.name, self.source = positive("mu", mu), name, source
        order = np.argsort(approach.delta, kind="stable")
        delta, p, area = (np.asarray(c)[order] for c in (approach.delta, approach.p, approach.area))
        branch = np.asarray(approach.branch)[order]
        self._pieces, jumps, mid_errors = [], [], []
        for b in np.unique(branch):
            keep = branch == b
            d, unique = np.unique(delta[keep], return_index=True)
            if d.size < 2:
                continue
            pb = p[keep][unique]
            pf, pa = PchipInterpolator(d, pb), PchipInterpolator(d, area[keep][unique])
            self._pieces.append((d[0], d[-1], pf, pa))
            if d.size >= 5:  # every other sample left out, then predicted
                half = PchipInterpolator(d[::2], pb[::2])
                mid_errors.append(np.abs(half(d[1:-1:2]) - pb[1:-1:2]))
            jumps.append(d[0])
        self._pieces.sort(key=lambda piece: piece[0])
        bounds = sorted(jumps)[1:] + ([delta_o_star] if delta_o_star is not None else [])
        self.breakpoints = tuple(sorted(float(b) for b in bounds))
        self.interpolation_error = float(np.max(np.concatenate(mid_errors + [[0.0]]))
                                         / np.abs(p).max())
        lo, hi = self._pieces[0], self._pieces[-1]
        self._first, self._last = hi[1], lo[0]
        self._p_last, self._area_last = float(lo[2](lo[0])), float(lo[3](lo[0]))
        slope = float(lo[2](lo[0], 1))  # dP̄/dδ̄o < 0 at the deepest point
        self._hertz_gap = (np.pi * abs(slope) * mu**1.5) ** 2  # δ_H − δ̄₀

    @property
    def solved_range(self):
        """(deepest, farthest) δ̄o [ε] of the path; the continuations lie beyond."""
        return self._last, self._first

    def _piecewise(self, delta, column):
        delta = np.asarray(delta, dtype=float)
        out = np.zeros(delta.shape)
        for lo, hi, pf, pa in self._pieces:
            inside = (delta >= lo) & (delta <= hi)
            out[inside] = (pf if column == "p" else pa)(delta[inside])
        return out, delta

    def force(self, delta):
        """P̄(δ̄o) [2πRΔγ] on approach at δ̄o `delta` [ε] (array or scalar)."""
        return _checked(self._force, delta, FORCE)

    def _force(self, delta):
        out, delta = self._piecewise(delta, "p")
        above, below = delta > self._first, delta < self._last
        out[above] = bradley_force(delta[above])
        depth = self._hertz_gap + self._last - delta[below]
        out[below] = self._p_last + 2.0 / (3.0 * np.pi) * (
            (depth / self.mu) ** 1.5 - (self._hertz_gap / self.mu) ** 1.5)
        return out

    def area(self, delta):
        """Ā(δ̄o) [εR] on approach at δ̄o `delta` [ε] (array or scalar)."""
        return _checked(self._area, delta, AREA)

    def _area(self, delta):
        out, delta = self._piecewise(delta, "area")
        below = delta < self._last
        out[below] = self._area_last + np.pi * (self._last - delta[below])
        return out
