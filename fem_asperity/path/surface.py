"""The nonlinear surface problem: LJ 9-3 springs between a rigid sphere and the condensed
half-space.

Unknowns: the upward surface displacement w at the surface nodes (in ε) and the sphere position δ̄o
(in ε). Equilibrium g(w, δ) = S w + μ^(3/2) Nᵀ(W p̄(h)) = 0 with S = C⁻¹ the surface stiffness,
N the interpolation to the surface quadrature points, W their weights (r included) and
h = δ + r²/2 − N w the Derjaguin gap (or the exact sphere profile, see `derjaguin_profile`).
"""

from functools import cached_property

import numpy as np
from scipy.sparse import csr_matrix

from ..closed_forms.lj import scaled_potential as potential
from ..closed_forms.lj import scaled_traction as traction
from ..closed_forms.lj import scaled_traction_slope as traction_slope
from ..solids.operator import ElasticSurface
from .paths import disc_area

#: A Newton step never lets a gap fall below this fraction of its current value. Not pinned by a
#: test.
GAP_KEEP = 0.2


def gap_keeping_step(h, dh):
    """Largest fraction ≤ 1 of the gap change dh that keeps every gap h above GAP_KEEP · h."""
    shrinking = dh < 0.0
    if not shrinking.any():
        return 1.0
    return min(1.0, float(np.min((GAP_KEEP - 1.0) * h[shrinking] / dh[shrinking])))


def _spring_pattern(interp):
    """(flat indices, map): the spring matrix Nᵀ diag(s) N of the interpolation N (n_quad ×
    n_nodes) has the entries `map @ s` at the flat positions `indices` of an n_nodes² array."""
    n_quad, n_nodes = interp.shape
    lengths = np.diff(interp.indptr)
    rows = np.repeat(np.arange(n_quad), lengths)
    position = np.arange(interp.nnz) - np.repeat(interp.indptr[:-1], lengths)
    cols = np.zeros((n_quad, lengths.max()), dtype=np.int64)
    values = np.zeros(cols.shape)
    cols[rows, position], values[rows, position] = interp.indices, interp.data
    keys, products, points = [], [], []
    for a in range(cols.shape[1]):
        for b in range(cols.shape[1]):
            keys.append(cols[:, a] * n_nodes + cols[:, b])
            products.append(values[:, a] * values[:, b])
            points.append(np.arange(n_quad))
    keys, products, points = map(np.concatenate, (keys, products, points))
    entries, slot = np.unique(keys, return_inverse=True)
    return entries, csr_matrix((products, (slot, points)), shape=(entries.size, n_quad))


def derjaguin_profile(r, radius_ratio=None):
    """Sphere height above its apex at radius r (in ε; r in √(Rε)).

    None: the Derjaguin parabola r²/2. With `radius_ratio` = R/ε: the exact sphere,
    (R/ε)(1 − √(1 − r²ε/R)), defined for r < √(R/ε); beyond the sphere's equator the gap is
    treated as infinite.
    """
    if radius_ratio is None:
        return 0.5 * r**2
    x = np.clip(r**2 / radius_ratio, 0.0, 1.0)
    return np.where(x < 1.0, radius_ratio * x / (1.0 + np.sqrt(1.0 - x)), np.inf)


#: The gap (ε) that marks the crack tip: the stiffest destabilising gap of the LJ law (methods.md
#: §13); test_tracking.py::test_spring_ratio_limits checks it.
TIP_GAP = 7.5 ** (1.0 / 6.0)


class SurfaceShape:
    """Where a state (w, δ̄o) on the radial nodes `r_nodes` touches: contact radius, crack tip
    and centre gap, from the gaps at the nodes alone (no elastic operator: a state recorded on
    a grid no longer built can still be placed, `grids.EdgeGrids.transplant`)."""

    def __init__(self, r_nodes, *, radius_ratio=None):
        self.r_nodes, self.radius_ratio = r_nodes, radius_ratio
        self.derjaguin = radius_ratio is None
        self.node_profile = derjaguin_profile(r_nodes, radius_ratio)

    def contact(self, w, delta):
        """(Ā, ā_c): the outer radius ā_c of the compressive zone (h < 1) and the disc's area
        π ā_c², as the events' ā_c and the traced folds' areas (`paths.disc_area`). Inside the
        contact h is within ~1e-3 ε of 1 at large μ, where the discretisation's ripples flip its
        sign: summing only the compressive annuli gave 0.91 of the disc near the landing at μ = 20
        and 0.38 at μ = 30 (BEM draft), where ā_c was JKR's to 3e-3; test_contact_area.py holds
        the area to JKR's within 2 % at μ = 20.

        Between nodes w is taken linear and the profile exact (r²/2 for Derjaguin), so the edge is
        the root of a quadratic, not a node position.
        """
        h = delta + self.node_profile - w
        inside = h < 1.0
        if not inside.any():
            return 0.0, 0.0
        if inside[-1]:
            radius = float(self.r_nodes[-1])
        else:
            radius = float(self._crossing(w, delta, int(np.nonzero(inside)[0][-1])))
        return disc_area(radius), radius

    def _crossing(self, w, delta, i):
        """Radius in [r_i, r_i+1] where the gap is 1, with w linear between the two nodes.

        Derjaguin profile: the root of δ + r²/2 − w_lin(r) = 1 (exact parabola); exact sphere:
        linear interpolation of the nodal gaps.
        """
        r0, r1 = self.r_nodes[i], self.r_nodes[i + 1]
        if self.derjaguin:
            slope = (w[i + 1] - w[i]) / (r1 - r0)
            c = delta - w[i] + slope * r0 - 1.0
            roots = slope + np.array([-1.0, 1.0]) * np.sqrt(max(slope**2 - 2.0 * c, 0.0))
            inside = roots[(roots >= r0 - 1e-12) & (roots <= r1 + 1e-12)]
            if inside.size:
                return float(inside[0])
        h0 = delta + self.node_profile[i] - w[i] - 1.0
        h1 = delta + self.node_profile[i + 1] - w[i + 1] - 1.0
        return float(r0 + (r1 - r0) * h0 / (h0 - h1))

    def crack_tip(self, w, delta):
        """Outermost radius (√(Rε)) where the gap rises through TIP_GAP (linear between nodes),
        or 0.0 where the gap exceeds it everywhere (no contact)."""
        gaps = delta + self.node_profile - w
        below = np.nonzero(gaps <= TIP_GAP)[0]
        if below.size == 0:
            return 0.0
        i = below[-1]
        if i + 1 == gaps.size:
            return float(self.r_nodes[-1])
        r0, r1, g0, g1 = self.r_nodes[i], self.r_nodes[i + 1], gaps[i], gaps[i + 1]
        return float(r0 + (r1 - r0) * (TIP_GAP - g0) / (g1 - g0))

    def translated(self, w, delta, shift, new_delta=None, *, onto=None):
        """The state at `new_delta` (default δ) whose node gaps are those of (w, δ) moved
        outward by `shift` (√(Rε)), linearly interpolated; where r − shift falls outside the
        nodes, the end gap is held. A crack tip's front at large μ moves nearly unchanged.
        onto: the `SurfaceShape` whose nodes it is given on (default this one's)."""
        onto = self if onto is None else onto
        gaps = delta + self.node_profile - w
        moved = np.interp(onto.r_nodes - shift, self.r_nodes, gaps)
        # beyond an exact sphere's equator the gap is infinite (inf − inf here): no traction
        # acts there, and the deflection is held (test_bem_curve.py, μ = 5.15 at R/ε = 167)
        with np.errstate(invalid="ignore"):
            translated = (delta if new_delta is None else new_delta) + onto.node_profile - moved
        beyond = ~np.isfinite(translated)
        translated[beyond] = np.interp(onto.r_nodes[beyond], self.r_nodes, w)
        return translated

    def centre_gap(self, w, delta):
        """x̄o = h(0) = δ − w(0), in ε."""
        return float(delta - w[0])


class LJSurface(SurfaceShape):
    """Residual, tangent and derived quantities of the surface problem at one μ, on any
    `ElasticSurface` (FE or boundary integral)."""

    def __init__(self, elastic: ElasticSurface, mu, *, radius_ratio=None):
        super().__init__(elastic.r_nodes, radius_ratio=radius_ratio)
        self.mu = mu
        self.load_factor = mu**1.5
        self.interp = elastic.interp
        self.interp_t = elastic.interp.T.tocsr()
        self.weights = elastic.weights
        self.profile = derjaguin_profile(elastic.r_quad, radius_ratio)
        self.stiffness = elastic.surface_stiffness
        self._stiffness32 = self.stiffness.astype(np.float32)
        self._spring_entries, self._spring_map = _spring_pattern(self.interp)

    def gap(self, w, delta):
        """Gap at the quadrature points, in ε."""
        return delta + self.profile - self.interp @ w

    def residual(self, w, delta):
        """g(w, δ): out-of-balance surface loads (E* = 1 units)."""
        h = self.gap(w, delta)
        return self.stiffness @ w + self.load_factor * (
            self.interp_t @ (self.weights * traction(h)))

    def energy(self, w, delta):
        """E(w; δ) = ½ wᵀS w + μ^(3/2) Σ W φ̄(h), whose gradient in w is the residual g."""
        return 0.5 * w @ (self.stiffness @ w) + self.load_factor * (
            self.weights @ potential(self.gap(w, delta)))

    def sensitivities(self, w, delta):
        """(∂g/∂δ, ∂P̄/∂δ, slope): the load and force sensitivities to δ (∂P̄/∂w =
        −(∂g/∂δ)/μ^(3/2)) and the weighted spring slope W dp̄/dh, which sets the tangent
        (`tangent_matrix`, `tangent_product`)."""
        slope = self.weights * traction_slope(self.gap(w, delta))
        return self.load_factor * (self.interp_t @ slope), float(slope.sum()), slope

    def tangent_matrix(self, slope, precision=np.float32):
        """∂g/∂w for the spring `slope`, symmetric, in single precision (it is only factorised,
        see `continuation.Linearisation`) or `precision` (np.float64)."""
        jac = (self._stiffness32 if precision == np.float32 else self.stiffness).astype(precision)
        jac.reshape(-1)[self._spring_entries] -= self.load_factor * (self._spring_map @ slope)
        return jac

    def tangent_block(self, slope, first, last):
        """The diagonal block [first:last, first:last] of `tangent_matrix(slope)`, entry for
        entry (from the spring entries in its rows: a sparse product of the block's columns
        took three times as long)."""
        n, size = self.r_nodes.size, last - first
        span = slice(*np.searchsorted(self._spring_entries, [first * n, last * n]))
        rows, cols = (index[span] for index in self._spring_rows_cols)
        inside = (cols >= first) & (cols < last)
        block = self._stiffness32[first:last, first:last].copy()
        block.reshape(-1)[(rows[inside] - first) * size + cols[inside] - first] -= (
            self.load_factor * (self._spring_map[span] @ slope)[inside])
        return block

    def tangent_diagonal(self, slope):
        """The diagonal of ∂g/∂w for the spring `slope`, in double precision (the spring
        entries on it, `_spring_pattern`, subtracted from the stiffness's)."""
        on_diagonal, nodes = self._spring_diagonal
        diagonal = self.stiffness.diagonal().copy()
        diagonal[nodes] -= self.load_factor * (self._spring_map[on_diagonal] @ slope)
        return diagonal

    def scaled_tangent_norm(self, slope, scale):
        """‖D ∂g/∂w D‖∞ (a bound of its spectral norm), D = diag(1/`scale`), for the spring
        `slope`: the stiffness's scaled absolute row sums, with the entries the springs change
        replaced."""
        inverse, n = 1.0 / scale, scale.size
        rows, cols = self._spring_rows_cols
        stiffness = self.stiffness.reshape(-1)[self._spring_entries]
        changed = np.abs(stiffness - self.load_factor * (self._spring_map @ slope))
        sums = self._stiffness_abs @ inverse + np.bincount(
            rows, (changed - np.abs(stiffness)) * inverse[cols], minlength=n)
        return float(np.max(inverse * sums))

    @cached_property
    def _stiffness_abs(self):
        """|S| (built when a stability flag first needs it, not with every grid)."""
        return np.abs(self.stiffness)

    @cached_property
    def _spring_rows_cols(self):
        """(row, column) of each spring entry (built on first use, not with every grid)."""
        return np.divmod(self._spring_entries, self.r_nodes.size)

    @cached_property
    def _spring_diagonal(self):
        """(which spring entries lie on the diagonal, their nodes)."""
        rows, cols = self._spring_rows_cols
        on_diagonal = np.flatnonzero(rows == cols)
        return on_diagonal, rows[on_diagonal]

    def tangent_product(self, slope, x):
        """(∂g/∂w) x in double precision for the spring `slope` (from `sensitivities`)."""
        return self.stiffness @ x - self.load_factor * (self.interp_t @ (slope * (self.interp @ x)))

    def force(self, w, delta):
        """P̄ = ∫ p̄ r dr = P/(2πRΔγ); negative = tensile."""
        return float(self.weights @ traction(self.gap(w, delta)))
