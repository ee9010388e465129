"""The bordered Newton system that every path solves: the surface residual g(w, δ̄o) = 0 and one
scalar constraint.

Each path holds one thing: the arc length along the curve (`continuation.correct`, δ̄o the
border's unknown), the crack tip at a radius with δ̄o free (`held_tip.held`), or the tip at a radius
with δ̄o fixed, the pin's load the unknown (`landing.pinned`). Each Newton step solves

    [[J, c], [uᵀ, β]] [dw; z] = [r_w; r_c],   J = ∂g/∂w (symmetric),

the constraint's column c, row u and corner β around the same tangent J. `BorderedSystem`
factorises J (Cholesky, in the order its caller gives: J in single or double precision, or
J + ρ u uᵀ, the pin's penalty), eliminates the border, falls back to LU of the whole matrix
where its caller allows it, and refines each solve against the exact double-precision product
as often as its caller asks. docs/methods.md §3 ("The bordered Newton system") says why.
"""

from copy import copy

import numpy as np
from scipy.linalg import (
    LinAlgError,
    cho_factor,
    cho_solve,
    cholesky,
    lu_factor,
    lu_solve,
    solve_triangular,
)

#: The edge block: this share of the surface nodes, centred on the crack tip, is refactorised
#: when a system moves (`BorderedSystem.relocated`). Not pinned by a test; docs/methods.md §3.
EDGE_SHARE = 0.125
#: A moved system refines each solve up to MOVED_REFINEMENTS times, until a correction is
#: ≤ ACCEPT of the step; test_surface_solver.py::test_moved_linearisation_solves_like_a_fresh_one.
MOVED_REFINEMENTS, ACCEPT = 3, 1e-2
#: The stability flag's inverse iterations and sure-sign bounds on its Rayleigh quotient (of the
#: scaled ‖J‖∞; docs/methods.md §3); test_surface_solver.py::test_stability_below_single_*.
SOFTEST_ITERATIONS, SURE_SIGN, ROUNDING = 3, 6e-7, 1e-14
#: A border eliminated by Cholesky is degenerate (LU instead) below this relative size of its
#: Schur complement: double precision's cancellation. Not pinned by a test.
DEGENERATE_BORDER = 1e-12
#: The pin's penalty ρ u uᵀ, in the largest elastic diagonal entry at the pin: J + ρ u uᵀ positive
#: definite where the pin holds J's one unstable mode; test_tip.py::test_an_indefinite_prediction*.
PIN_PENALTY = 10.0
#: The factorisations of J a caller may try, in its order, before LU of the whole matrix:
#: J in single precision, J in double precision, J + ρ u uᵀ in single precision.
SINGLE, DOUBLE, PINNED = "single", "double", "pinned"


class Cholesky:
    """Cholesky factorisation of a symmetric positive definite matrix (overwritten), solving in
    its precision with the result in double. Raises LinAlgError where it is not positive
    definite."""

    block = None

    def __init__(self, matrix):
        # the transpose is Fortran-ordered, so LAPACK factorises it in place without a copy
        self._factor = cho_factor(matrix.T, check_finite=False, overwrite_a=True)
        self.single = matrix.dtype == np.float32

    def solve(self, rhs):
        """matrix⁻¹ rhs."""
        rhs = rhs.astype(self._factor[0].dtype)
        return cho_solve(self._factor, rhs, check_finite=False).astype(float)


class EdgeBlockCholesky:
    """Cholesky factorisation of a symmetric positive definite matrix J (in J's precision) with
    its nodes ordered bulk first, edge block (`edge_block`) last:

        J = [[L Lᵀ, L M], [Mᵀ Lᵀ, J_ee]],   J_ee − Mᵀ M = S (the edge's Schur complement),

    so that a new edge block J_ee' costs only the Cholesky factorisation of J_ee' − Mᵀ M
    (`with_edge`), the bulk kept. Raises LinAlgError where J is not positive definite."""

    def __init__(self, jac, block):
        first, last = block
        self.block = block
        self._bulk = np.r_[0:first, last:jac.shape[0]]
        bulk, edge = self._bulk, slice(first, last)
        self._l = cholesky(_without_block(jac, first, last), lower=True, overwrite_a=True,
                           check_finite=False)
        self._m = solve_triangular(self._l, jac[bulk, edge], lower=True, check_finite=False)
        self._coupled = self._m.T @ self._m
        self._schur = cho_factor(jac[edge, edge] - self._coupled, check_finite=False)
        self.single = jac.dtype == np.float32

    def with_edge(self, jac_edge):
        """This factorisation with the edge block replaced by `jac_edge`."""
        moved = copy(self)
        moved._schur = cho_factor(jac_edge - self._coupled, check_finite=False)
        return moved

    def solve(self, rhs):
        """J⁻¹ rhs in the factorisation's precision."""
        first, last = self.block
        rhs = rhs.astype(self._l.dtype)
        y = solve_triangular(self._l, rhs[self._bulk], lower=True, check_finite=False)
        z = cho_solve(self._schur, rhs[first:last] - self._m.T @ y, check_finite=False)
        x = np.empty(rhs.size)
        x[first:last] = z
        x[self._bulk] = solve_triangular(self._l, y - self._m @ z, lower=True, trans="T",
                                         check_finite=False)
        return x


def _without_block(jac, first, last):
    """The symmetric `jac` without the rows and columns first:last, Fortran-ordered (for LAPACK
    without a copy), by four slice copies (a gather by index arrays took twice as long)."""
    size = jac.shape[0] - (last - first)
    bulk = np.empty((size, size), dtype=jac.dtype, order="F")
    bulk[:first, :first], bulk[:first, first:] = jac[:first, :first], jac[:first, last:]
    bulk[first:, :first], bulk[first:, first:] = jac[last:, :first], jac[last:, last:]
    return bulk


def cholesky_or_none(matrix, block=None):
    """`EdgeBlockCholesky` of `matrix` with the edge `block`, or `Cholesky` of all of it
    (overwritten), or None where it is not positive definite."""
    try:
        return Cholesky(matrix) if block is None else EdgeBlockCholesky(matrix, block)
    except LinAlgError:
        return None


def edge_block(surface, w, delta):
    """(first, last + 1): the run of EDGE_SHARE of the nodes centred on the crack tip."""
    n = surface.r_nodes.size
    count = max(1, int(EDGE_SHARE * n))
    centre = int(np.searchsorted(surface.r_nodes, surface.crack_tip(w, delta)))
    first = min(max(centre - count // 2, 0), n - count)
    return first, first + count


def pin_penalty(surface, nodes):
    """ρ of the penalty ρ u uᵀ on the pin's `nodes`: PIN_PENALTY × the largest elastic diagonal
    entry there."""
    return PIN_PENALTY * float(np.max(surface.stiffness[nodes, nodes]))


def converged(residual, step, w, scale, tol):
    """Newton's test: the residual ≤ tol × `scale` and the last increment ≤ √tol relative to w
    (with quadratic convergence the state is then accurate to about tol)."""
    return (np.max(np.abs(residual)) <= tol * scale
            and np.max(np.abs(step)) <= np.sqrt(tol) * (1.0 + np.max(np.abs(w))))


class BorderedSystem:
    """[[J, c], [uᵀ, β]] at one state of `surface`, J = ∂g/∂w for the spring `slope`
    (`LJSurface.sensitivities`), the `column` c and the `border` row (u, β), factorised.

    factorisations: tried in order (SINGLE, DOUBLE, PINNED) until one succeeds, on the edge
        `block` (`EdgeBlockCholesky`) or, without one, on all of J; the border is then
        eliminated. PINNED factorises J + ρ u uᵀ (ρ: `pin_penalty` on u's nonzero nodes) and
        adds ρ u times the constraint's row to the first rows, [[J + ρ u uᵀ, c + ρ β u],
        [uᵀ, β]]: the same solutions.
    lu: where none succeeds or the border is degenerate, LU of the whole matrix in this
        precision (np.float32 or np.float64); None: the system then has no solution (`failed`).
    refinements: each solve is refined that many times against the exact double-precision
        product (`converged` says whether the last correction was ≤ ACCEPT of the step).
    stability: whether `stable` is asked for; it says whether J is positive definite (False
        where J itself was not factorised: try DOUBLE to be sure).
    """

    def __init__(self, surface, slope, column, border, *, block=None,
                 factorisations=(SINGLE, DOUBLE), lu=np.float32, refinements=1, stability=True):
        self.n, self.refinements, self.moved, self.converged = column.size, refinements, False, True
        self._stability = stability
        self._set_products(surface, slope, column, border)
        self._penalty, self._cho, self._lu = 0.0, None, None
        for kind in factorisations:
            self._cho = cholesky_or_none(self._matrix(kind), block)
            if self._cho is not None:
                break
        self._stable = (False if self._cho is None or self._penalty
                        else None if self._cho.single else True)
        if self._cho is not None and self._eliminate():
            return
        if self._cho is not None and stability:  # a degenerate border: the flag before LU
            self._stable = self.stable
        self._cho = None
        if lu is not None:
            n = self.n
            matrix = np.empty((n + 1, n + 1), dtype=lu, order="F")  # LU in place
            matrix[:n, :n], matrix[:n, n], matrix[n] = self._tangent(lu), column, border
            self._lu = lu_factor(matrix, check_finite=False, overwrite_a=True)

    @property
    def failed(self):
        """Whether the system was not factorised (no LU allowed)."""
        return self._cho is None and self._lu is None

    def _set_products(self, surface, slope, column, border):
        """Hold the exact (double-precision) bordered product at one state."""
        self._column, self._border = column, border
        self._surface, self._slope = surface, slope

    def _tangent(self, precision=np.float32):
        return self._surface.tangent_matrix(self._slope, precision)

    def _matrix(self, kind):
        """J (SINGLE, DOUBLE) or J + ρ u uᵀ (PINNED) to factorise, ρ set for the elimination."""
        self._penalty = 0.0
        if kind != PINNED:
            return self._tangent(np.float64 if kind == DOUBLE else np.float32)
        u = self._border[:-1]
        nodes = np.flatnonzero(u)
        self._penalty = pin_penalty(self._surface, nodes)
        jac = self._tangent()
        jac[np.ix_(nodes, nodes)] += self._penalty * np.outer(u[nodes], u[nodes])
        return jac

    def _eliminate(self):
        """Set up the block elimination of the border; False if it is degenerate."""
        u, beta = self._border[:-1], self._border[-1]
        column = (self._column if not self._penalty
                  else self._column + (self._penalty * beta) * u)
        self._b = self._cho.solve(column)
        self._denominator = beta - u @ self._b
        size = abs(beta) + abs(u) @ abs(self._b)
        return abs(self._denominator) > DEGENERATE_BORDER * size

    def _solve_factored(self, rhs):
        if self._cho is None:
            # A refinement on a nearly singular factorisation can grow past float32's range: the
            # cast gives inf, which the Newton loops take for the failed step it is (and retry
            # shorter), so the overflow is not worth a warning on the user's terminal.
            with np.errstate(over="ignore"):
                cast = rhs.astype(self._lu[0].dtype)
            return lu_solve(self._lu, cast, check_finite=False).astype(float)
        u = self._border[:-1]
        rhs_w = rhs[:-1] if not self._penalty else rhs[:-1] + (self._penalty * rhs[-1]) * u
        a = self._cho.solve(rhs_w)
        z = (rhs[-1] - u @ a) / self._denominator
        return np.append(a - z * self._b, z)

    def _product(self, x):
        """J x in double precision."""
        return self._surface.tangent_product(self._slope, x)

    def solve(self, rhs):
        """Solution (dw, z) of the bordered system for the right-hand side (n + 1,)."""
        step = self._solve_factored(rhs)
        for _ in range(self.refinements):
            dw, z = step[:-1], step[-1]
            product = np.append(self._product(dw) + z * self._column, self._border @ step)
            correction = self._solve_factored(rhs - product)
            step += correction
            self.converged = np.max(np.abs(correction)) <= ACCEPT * np.max(np.abs(step))
            if self.converged:
                break
        return step[:-1], step[-1]

    @property
    def stable(self):
        """Whether J is positive definite (a stable state), decided on first use: by the
        factorisation that succeeded if it is of J in double precision; else not where a
        diagonal entry is ≤ 0; else by the Rayleigh quotient q of the Jacobi-scaled J that
        inverse iteration finds (`_softest`), if it is clearly negative (then so is the softest
        eigenvalue) or clearly positive (≥ SURE_SIGN of the scaled matrix's ‖·‖∞,
        `LJSurface.scaled_tangent_norm`); else by a double-precision factorisation."""
        if not self._stability:
            raise ValueError("this system was built without a stability flag (stability=False)")
        if self._stable is None:
            diagonal = self._surface.tangent_diagonal(self._slope)
            if np.min(diagonal) <= 0.0:
                self._stable = False
                return self._stable
            scale = np.sqrt(diagonal)
            quotient = self._softest(scale)
            norm = self._surface.scaled_tangent_norm(self._slope, scale)
            if quotient >= SURE_SIGN * norm:
                self._stable = True
            elif quotient <= -ROUNDING * norm:
                self._stable = False
            else:
                double = cholesky_or_none(self._tangent(np.float64), self._cho.block)
                self._stable = double is not None
        return self._stable

    def _softest(self, scale):
        """The Rayleigh quotient of the exact J scaled to D J D, D = diag(1/`scale`), after
        SOFTEST_ITERATIONS inverse iterations with the Cholesky factorisation, from a fixed
        random vector: never below the scaled matrix's softest eigenvalue, near it where the
        factorised matrix is near J."""
        v = np.random.default_rng(0).standard_normal(self.n)
        for _ in range(SOFTEST_ITERATIONS):
            v = scale * self._cho.solve(scale * v)
            v /= np.linalg.norm(v)
        return float((v / scale) @ self._product(v / scale))

    def relocated(self, surface, slope, column, border, tip):
        """This system as the approximate inverse of the bordered matrix at a nearby state (its
        crack tip at `tip`): an edge-block one with its edge refactorised there (the bulk kept),
        an LU one as it is. Solves are refined against that state's exact matrix (up to
        MOVED_REFINEMENTS times, until a correction is ≤ ACCEPT of the step). None where the
        tip left the middle half of the edge block, J has no edge block or was penalised, or the
        refactorised edge is not positive definite: then factorise afresh."""
        moved = copy(self)
        moved._set_products(surface, slope, column, border)
        moved.refinements, moved.moved = MOVED_REFINEMENTS, True
        if self._cho is None:
            return moved
        if self._cho.block is None or self._penalty:
            return None
        moved._stable = None
        first, last = self._cho.block
        quarter = (last - first) // 4
        lowest = first + quarter if first > 0 else 0
        highest = last - quarter if last < self.n else self.n
        if not lowest <= int(np.searchsorted(surface.r_nodes, tip)) <= highest:
            return None
        try:
            moved._cho = self._cho.with_edge(surface.tangent_block(slope, first, last))
        except LinAlgError:
            return None
        return moved if moved._eliminate() else None
