"""Axisymmetric Boussinesq influence of a piecewise-linear surface traction on a half-space.

With E* = 1 a normal traction p(s) (compressive positive) on the surface of a half-space moves the
surface at radius r down by

    u(r) = (4/π) ∫₀^∞ p(s) s/(r+s) K(m) ds,    m = 4rs/(r+s)²,

with K the complete elliptic integral of the first kind (parameter m). K has a logarithmic
singularity at s = r, K(m) = P(m₁) − Q(m₁) ln m₁ with m₁ = 1 − m = ((s−r)/(s+r))² and
Q(m₁) = K(m₁)/π analytic, and the whole kernel is singular on the circle |s| = r of the complex
s-plane. The integral over each element of the radial grid is therefore done in three ways:

- far from r (distance ≥ the element's length): Gauss-Legendre, 8 points, error ≈ 5.8⁻¹⁶, and
  fewer further out where that is as accurate: 6 from 2.5 lengths, 5 from 4, 4 from 9
  (`_NEAR`, `_MID_RULES`);
- near r: as ∫_r^b − ∫_r^a, each split into pieces that double in length away from r, so that
  every piece is at least its own length away from the singular circle;
- on the piece that starts at r: the log term −2 f Q̃(m₁) ln|s−r| (Q̃ the Taylor polynomial of
  Q, f = (4/π) s/(r+s)) by Gauss quadrature with weight −ln x, which integrates it exactly for
  polynomial factors of degree < 16, and the smooth remainder by Gauss-Legendre.

The rule is checked against adaptive quadrature to 1e-12 in the tests.
"""

from math import gamma

import numpy as np
from scipy.sparse import coo_matrix
from scipy.special import comb, ellipkm1, roots_legendre

#: Points of the Gauss-Legendre and of the logarithmic Gauss rules;
#: test_bem.py::test_displacement_matrix_matches_adaptive_quadrature.
_POINTS = 8
#: Taylor coefficients of Q(m₁) = K(m₁)/π = ½ Σ [(½)ₙ/n!]² m₁ⁿ used to split off the log.
_Q_TAYLOR = np.array([0.5 * (gamma(n + 0.5) / (gamma(0.5) * gamma(n + 1))) ** 2 for n in range(6)])
#: Kernel evaluations per chunk of the dense far-field sum (bounds memory at ~50 MB). Not pinned
#: by a test.
_CHUNK = 2_000_000
#: Elements per block, each way, that `galerkin_matrix` evaluates in full where not well
#: separated: fewer kernel values against more numpy calls. Not pinned by a test.
_LEAF = 32
#: Chebyshev points per variable of a well-separated block: error ~ρ^(−20) ≈ 5e-16 (methods.md §13);
#: test_bem.py::test_galerkin_matrix_is_the_tested_deflection_tested_against_the_hat_functions.
_CHEBYSHEV = 20


def log_gauss(n):
    """Nodes and weights of the n-point Gauss rule for ∫₀¹ f(x) (−ln x) dx (exact for deg < 2n).

    Gautschi's modified Chebyshev algorithm with the monic shifted Legendre polynomials, whose
    modified moments ∫₀¹ P*ₖ(x)(−ln x) dx = (−1)ᵏ/(k(k+1)) (k ≥ 1) are known in closed form,
    then Golub-Welsch.
    """
    k = np.arange(2 * n)
    a = np.full(2 * n, 0.5)
    b = np.concatenate([[0.0], k[1:] ** 2 / (4.0 * (4.0 * k[1:] ** 2 - 1.0))])
    legendre_moments = np.concatenate([[1.0], (-1.0) ** k[1:] / (k[1:] * (k[1:] + 1.0))])
    sigma, sigma_prev = legendre_moments / comb(2 * k, k), np.zeros(2 * n)
    alpha, beta = np.zeros(n), np.zeros(n)
    alpha[0], beta[0] = a[0] + sigma[1] / sigma[0], sigma[0]
    for j in range(1, n):
        nxt = np.zeros(2 * n)
        ell = np.arange(j, 2 * n - j)
        nxt[ell] = (sigma[ell + 1] - (alpha[j - 1] - a[ell]) * sigma[ell]
                    - beta[j - 1] * sigma_prev[ell] + b[ell] * sigma[ell - 1])
        alpha[j] = a[j] + nxt[j + 1] / nxt[j] - sigma[j] / sigma[j - 1]
        beta[j] = nxt[j] / sigma[j - 1]
        sigma_prev, sigma = sigma, nxt
    off = np.sqrt(beta[1:])
    nodes, vectors = np.linalg.eigh(np.diag(alpha) + np.diag(off, 1) + np.diag(off, -1))
    return nodes, beta[0] * vectors[0] ** 2


def _unit_gauss(n):
    x, w = roots_legendre(n)
    return 0.5 * (x + 1.0), 0.5 * w


_GL = _unit_gauss(_POINTS)
_LOG = log_gauss(_POINTS)
#: Far-field Gauss rules by distance in element lengths, each within 5.7e-13 (methods.md §13);
#: test_bem.py::test_displacement_matrix_matches_adaptive_quadrature.
_NEAR, _FAR_RULE = (1.0, 9.0), _unit_gauss(4)
_MID_RULES = ((1.0, _unit_gauss(8)), (2.5, _unit_gauss(6)), (4.0, _unit_gauss(5)))


def kernel(r, s):
    """(4/π) s/(r+s) K(4rs/(r+s)²): surface deflection at r per unit traction at s per unit ds."""
    return (4.0 / np.pi) * s / (r + s) * ellipkm1(((s - r) / (s + r)) ** 2)


def _split_kernel(r, s):
    """(regular, log) with kernel = regular + log · ln|s − r|, both smooth near s = r."""
    m1 = ((s - r) / (s + r)) ** 2
    f = (4.0 / np.pi) * s / (r + s)
    q = np.polynomial.polynomial.polyval(m1, _Q_TAYLOR)
    return f * (ellipkm1(m1) + 2.0 * q * np.log(np.abs(s - r))), -2.0 * f * q


def _from_point(r, c):
    """(∫_r^c kernel(r, s) ds, ∫_r^c kernel(r, s) (s − r) ds) for arrays r > 0 and c (same
    shape)."""
    i0, i1 = np.zeros(r.size), np.zeros(r.size)
    live = c != r
    if live.any():
        i0[live], i1[live] = _from_point_live(r[live], c[live])
    return i0, i1


def _from_point_live(r, c):
    span = np.abs(c - r)
    sign = np.sign(c - r)
    first = np.minimum(span, 0.5 * r)
    x, wx = _GL
    # the piece [r, r + first·sign]: log part by the −ln x rule, the rest by Gauss-Legendre
    s = r[:, None] + (sign * first)[:, None] * x
    regular, log = _split_kernel(r[:, None], s)
    values = (regular + log * np.log(first)[:, None]) * wx
    i0, i1 = values.sum(1), (values * (s - r[:, None])).sum(1)
    t, wt = _LOG
    s = r[:, None] + (sign * first)[:, None] * t
    _, log = _split_kernel(r[:, None], s)
    i0 -= (log * wt).sum(1)
    i1 -= (log * (s - r[:, None]) * wt).sum(1)
    i0, i1 = sign * first * i0, sign * first * i1
    # pieces doubling in length away from r, each at least its length from the circle |s| = r
    lo, live = first.copy(), np.flatnonzero(first < span)
    while live.size:
        hi = np.minimum(2.0 * lo[live], span[live])
        rl, sl = r[live, None], sign[live, None]
        s = rl + sl * (lo[live, None] + (hi - lo[live])[:, None] * x)
        k = kernel(rl, s) * wx * (sl * (hi - lo[live])[:, None])
        i0[live] += k.sum(1)
        i1[live] += (k * (s - rl)).sum(1)
        lo[live] = hi
        live = live[hi < span[live]]
    return i0, i1


def _near_pairs(r, point, element, nodes, ratio):
    """(∫ kernel(r, s) ds, ∫ kernel(r, s) (s − a)/length ds) over the elements [a, b] =
    nodes[element], nodes[element + 1] for arrays of pairs nearer than _NEAR[1] lengths
    (`ratio`: distance in lengths, < 0 inside; `point`: integer ids of the radii r, equal where
    r is): the `_MID_RULES` from _NEAR[0] lengths, the singular split below, as integrals from
    r to each end (`_from_point`), done once for an end that neighbouring elements share."""
    a, b = nodes[element], nodes[element + 1]
    length = b - a
    i0, i1 = np.empty(r.size), np.empty(r.size)
    bounds = [bound for bound, _ in _MID_RULES[1:]] + [np.inf]
    for (start, (x, wx)), stop in zip(_MID_RULES, bounds):
        mid = (ratio >= start) & (ratio < stop)
        k = kernel(r[mid, None], a[mid, None] + length[mid, None] * x) * (wx * length[mid, None])
        i0[mid], i1[mid] = k.sum(1), k @ x
    close = ratio < _NEAR[0]
    r, a, length, element = r[close], a[close], length[close], element[close]
    keys = np.tile(point[close] * nodes.size, 2) + np.concatenate([element, element + 1])
    ends, first, inverse = np.unique(keys, return_index=True, return_inverse=True)
    to_end = (moment[inverse] for moment in _from_point(np.tile(r, 2)[first],
                                                         nodes[ends % nodes.size]))
    (from_a, from_b), (moment_a, moment_b) = (np.split(m, 2) for m in to_end)
    i0[close] = from_b - from_a
    i1[close] = (moment_b - moment_a + (r - a) * i0[close]) / length
    return i0, i1


def _distance_ratio(r, a, b, length):
    """Distance from the radii r (column) to the elements [a, b] in element lengths, < 0 inside."""
    return np.maximum(a - r, r - b) / length


def displacement_matrix(nodes, r):
    """A with u(r) = A @ p: the downward deflection at radii `r` > 0 under the piecewise-linear
    traction with nodal values p on the radial grid `nodes` (increasing, from 0; zero beyond)."""
    r = np.asarray(r, dtype=float)
    a, b = nodes[:-1], nodes[1:]
    length = b - a
    A = np.zeros((r.size, nodes.size))
    rows = max(1, _CHUNK // (_POINTS * a.size))
    for start in range(0, r.size, rows):
        rr = r[start:start + rows]
        ratio = _distance_ratio(rr[:, None], a, b, length)
        ratio[rr == 0.0] = np.inf  # the kernel is 2 at r = 0: any rule is exact
        # Every pair by the far rule, broadcast over contiguous arrays (gathering the pairs of
        # each tier cost more than the kernel); then the nearer pairs again, by their rules.
        x, wx = _FAR_RULE
        with np.errstate(divide="ignore", invalid="ignore"):  # s = r: those pairs are redone
            k = kernel(rr[:, None, None], a[:, None] + length[:, None] * x) * (
                wx * length[:, None])
        i0, i1 = k.sum(-1).ravel(), (k @ x).ravel()
        pairs = np.flatnonzero(ratio < _NEAR[1])
        q, e = np.divmod(pairs, a.size)
        i0[pairs], i1[pairs] = _near_pairs(rr[q], q, e, nodes, ratio.ravel()[pairs])
        i0, i1 = i0.reshape(ratio.shape), i1.reshape(ratio.shape)
        A[start:start + rows, :-1] += i0 - i1
        A[start:start + rows, 1:] += i1
    return A


def quadrature(nodes):
    """(points, weights, x) of the Galerkin form's outer rule on the elements of `nodes`: the far
    rule's Gauss points, (elements, points per element), the weights without the factor r, and
    the points' positions x in [0, 1] on each element."""
    a, length = nodes[:-1, None], np.diff(nodes)[:, None]
    x, wx = _FAR_RULE
    return a + length * x, length * wx, x


def symmetric_kernel(r, s):
    """r · kernel(r, s) = (4/π) rs/(r+s) K(4rs/(r+s)²), symmetric in r and s."""
    total = r + s
    m1 = s - r
    m1 /= total
    m1 *= m1
    product = r * s
    product /= total
    product *= 4.0 / np.pi
    product *= ellipkm1(m1)
    return product


def _chebyshev(lo, hi, targets):
    """(points, L): the _CHEBYSHEV Chebyshev points of the first kind on [lo, hi] and the values
    of their Lagrange polynomials at `targets` (barycentric form), L of shape (targets, points)."""
    angles = (2 * np.arange(_CHEBYSHEV) + 1) * np.pi / (2 * _CHEBYSHEV)
    points = 0.5 * (lo + hi) + 0.5 * (hi - lo) * np.cos(angles)
    offset = targets[:, None] - points
    hits = offset == 0.0
    offset[hits] = 1.0
    terms = (-1.0) ** np.arange(_CHEBYSHEV) * np.sin(angles) / offset
    values = terms / terms.sum(axis=1, keepdims=True)
    on_point = hits.any(axis=1)
    values[on_point] = hits[on_point]
    return points, values


def _partition(a, b):
    """The upper triangle (columns not before rows) of the element pairs of the elements [a, b],
    as (rows, cols, separated) blocks of element slices: `separated` blocks lie at least their
    larger extent and _NEAR[1] of their longest element apart (an analytic kernel there,
    interpolated by `galerkin_matrix`); the others are at most _LEAF elements each way (the
    kernel in full). A block apart from the diagonal is halved on its longer span, not its side
    of more elements: on a graded grid, next to fine elements, that separates blocks sooner (a
    μ = 10 edge grid: 0.7 million kernel values in full blocks instead of 1.7). Depth first, by
    an explicit stack of index ranges (Python numbers: numpy scalars and a generator per level
    took twice as long)."""
    lo, hi = a.tolist(), b.tolist()
    longest = _RangeMax((b - a).tolist())
    blocks, stack = [], [(0, len(lo), 0, len(lo))]
    while stack:
        r0, r1, c0, c1 = stack.pop()
        m, n = r1 - r0, c1 - c0
        if r0 == c0:
            if m <= _LEAF:
                blocks.append((slice(r0, r1), slice(c0, c1), False))
            else:
                mid = (r0 + r1) // 2
                stack += [(mid, r1, mid, r1), (r0, mid, mid, r1), (r0, mid, r0, mid)]
            continue
        row_extent, col_extent = hi[r1 - 1] - lo[r0], hi[c1 - 1] - lo[c0]
        reach = max(row_extent, col_extent,
                    _NEAR[1] * max(longest(r0, r1), longest(c0, c1)))
        if lo[c0] - hi[r1 - 1] >= reach:
            blocks.append((slice(r0, r1), slice(c0, c1), True))
        elif m <= _LEAF and n <= _LEAF:
            blocks.append((slice(r0, r1), slice(c0, c1), False))
        elif (row_extent >= col_extent and m > 1) or n == 1:
            mid = (r0 + r1) // 2
            stack += [(mid, r1, c0, c1), (r0, mid, c0, c1)]
        else:
            mid = (c0 + c1) // 2
            stack += [(r0, r1, mid, c1), (r0, r1, c0, mid)]
    return blocks


class _RangeMax:
    """max(values[start:stop]) in two lookups (a sparse table of the maxima over runs of 2^k)."""

    def __init__(self, values):
        self._levels = [values]
        while 2 ** len(self._levels) <= len(values):
            last, width = self._levels[-1], 2 ** (len(self._levels) - 1)
            self._levels.append([max(x, y) for x, y in zip(last, last[width:])])

    def __call__(self, start, stop):
        level = (stop - start).bit_length() - 1
        values = self._levels[level]
        return max(values[start], values[stop - 2 ** level])


def galerkin_matrix(nodes):
    """B with B_ij = ∫ φᵢ(r) u[φⱼ](r) r dr for the hat functions φ of the radial grid `nodes`:
    the deflection `displacement_matrix` tested against φᵢ by the outer rule `quadrature`, so
    equal to Nᵀ diag(W r) `displacement_matrix(nodes, r_quad)` (N: the hat functions at those
    points), in far fewer kernel evaluations. By the far rule on the source element, whose
    points are the outer rule's, the integrand w_q w_t r_q kernel(r_q, s_t) is symmetric
    (`symmetric_kernel`), so each block of element pairs (`_partition`) is evaluated once for
    both orders: in full next to the diagonal, where the pairs nearer than _NEAR[1] lengths are
    then corrected to their own rules (`_near_pairs`), and through the kernel's values at
    _CHEBYSHEV × _CHEBYSHEV Chebyshev points where the elements lie apart (the kernel is
    analytic there: `_CHEBYSHEV`). The blocks fill an array of element pairs by their end
    nodes (four times B's memory), summed onto the nodes at the end."""
    points, weights, x = quadrature(nodes)
    a, b = nodes[:-1], nodes[1:]
    n_el = a.size
    basis = np.stack([1.0 - x, x], axis=1)  # (point, end node)
    ends = np.empty((n_el, 2, n_el, 2))  # (element, its end node, element, its end node)
    blocks = _partition(a, b)
    for rows, cols, apart in blocks:
        if not apart:
            _store(ends, _full_block(points, weights, basis, rows, cols), rows, cols)
    separated = [(rows, cols) for rows, cols, apart in blocks if apart]
    if separated:
        for (rows, cols), values in zip(separated, _interpolated_blocks(
                a, b, points, weights, basis, separated)):
            _store(ends, values, rows, cols)
    B = np.zeros((nodes.size, nodes.size))
    for i in range(2):
        for j in range(2):
            B[i:i + n_el, j:j + n_el] += ends[:, i, :, j]
    del ends  # before the near pairs' arrays: a peak of about 5 B's, not 7
    _add_near_correction(B, nodes, points, weights, basis)
    return B


def _store(ends, values, rows, cols):
    """Put a block's sums (rows' elements, their end, cols' elements, their end) into `ends`, in
    both orders."""
    ends[rows, :, cols, :] = values
    if rows != cols:
        ends[cols, :, rows, :] = values.transpose(2, 3, 0, 1)


def _full_block(points, weights, basis, rows, cols):
    """The hat functions' sums of the block's kernel values at the outer rule's points; the
    pairs r = s (on a diagonal block) left out: `_add_near_correction` puts them in."""
    m, n, per = rows.stop - rows.start, cols.stop - cols.start, points.shape[1]
    with np.errstate(divide="ignore", invalid="ignore"):  # r = s: a near pair's
        block = symmetric_kernel(points[rows].reshape(-1, 1), points[cols].reshape(1, -1))
    if rows == cols:
        np.fill_diagonal(block, 0.0)
    block *= weights[rows].reshape(-1, 1) * weights[cols].reshape(1, -1)
    summed = np.matmul(basis.T, block.reshape(m, per, n * per))  # (m, 2, n · per)
    return (summed.reshape(-1, per) @ basis).reshape(m, 2, n, 2)


def _interpolated_blocks(a, b, points, weights, basis, blocks):
    """The same sums for the separated `blocks`, through the kernel at Chebyshev points of each
    block's two spans (all blocks' kernel values in one call)."""
    per, factors = points.shape[1], {}

    def factor(span):
        """(Chebyshev points on the span's elements, hat functions' weighted sums of their
        Lagrange polynomials, shape (2 × elements, _CHEBYSHEV))."""
        key = span.start, span.stop
        if key not in factors:
            cheb, values = _chebyshev(a[span.start], b[span.stop - 1], points[span].ravel())
            weighted = values.reshape(-1, per, _CHEBYSHEV) * weights[span, :, None]
            factors[key] = cheb, np.matmul(basis.T, weighted).reshape(-1, _CHEBYSHEV)
        return factors[key]

    spans = [(factor(rows), factor(cols)) for rows, cols in blocks]
    r_cheb = np.array([left[0] for left, _ in spans])
    s_cheb = np.array([right[0] for _, right in spans])
    kernels = symmetric_kernel(r_cheb[:, :, None], s_cheb[:, None, :])
    for ((_, left), (_, right)), (rows, cols), values in zip(spans, blocks, kernels):
        yield (left @ values @ right.T).reshape(rows.stop - rows.start, 2,
                                                cols.stop - cols.start, 2)


def _add_near_correction(B, nodes, points, weights, basis):
    """Add to B what the pairs of a receiving point and a source element nearer than _NEAR[1]
    lengths add by their own rules (`_near_pairs`), less what the far rule of `_full_block` added
    for them (every such pair lies in a full block: a separated one is _NEAR[1] of its longest
    element apart)."""
    a, b = nodes[:-1], nodes[1:]
    length, per = b - a, points.shape[1]
    flat = points.ravel()
    reach = 1.01 * _NEAR[1] * length  # candidates, then the exact test below
    first = np.searchsorted(flat, a - reach)
    count = np.searchsorted(flat, b + reach, side="right") - first
    e = np.repeat(np.arange(a.size), count)
    q = np.arange(e.size) - np.repeat(np.cumsum(count) - count - first, count)
    near = _distance_ratio(flat[q], a[e], b[e], length[e]) < _NEAR[1]
    q, e = q[near], e[near]
    r = flat[q]
    i0, i1 = _near_pairs(r, q, e, nodes, _distance_ratio(r, a[e], b[e], length[e]))
    with np.errstate(divide="ignore", invalid="ignore"):
        summed = symmetric_kernel(r[:, None], points[e]) * weights[e]  # what the block added
    summed[r[:, None] == points[e]] = 0.0
    weight = weights.ravel()[q]
    corrections = (r * (i0 - i1) - summed @ basis[:, 0], r * i1 - summed @ basis[:, 1])
    receiving = q // per
    values, at_row, at_col = [], [], []
    for end, correction in enumerate(corrections):
        for node in (0, 1):
            values.append(weight * basis[q % per, node] * correction)
            at_row.append(receiving + node)
            at_col.append(e + end)
    values, at_row, at_col = map(np.concatenate, (values, at_row, at_col))
    B += coo_matrix((values, (at_row, at_col)), shape=B.shape).toarray()
