"""The bordered Newton system (`path/newton.py`) on small matrices, against dense solves:
the edge-block Cholesky factorisation, the stability flag, the pin's penalty and the LU
fallback."""

import numpy as np
import pytest
from scipy.linalg import LinAlgError

from fem_asperity.path import newton
from fem_asperity.path.continuation import Linearisation
from fem_asperity.path.newton import PINNED, SINGLE, BorderedSystem, EdgeBlockCholesky


def _spd(n, rng):
    a = rng.random((n, n))
    return (a @ a.T + n * np.eye(n)).astype(np.float32)


@pytest.mark.parametrize("block", [(12, 20), (0, 8), (32, 40)])
def test_edge_block_cholesky_solves_the_matrix_and_its_new_edge(block):
    """The block factorisation solves J x = b to single precision, and with a new edge block
    (`with_edge`) solves the matrix with that block, the block inside or at either end; a
    matrix that is not positive definite in its bulk or its edge raises LinAlgError."""
    rng = np.random.default_rng(1)
    jac, edge = _spd(40, rng), slice(*block)
    rhs = rng.random(40)
    factor = EdgeBlockCholesky(jac, block)
    exact = np.linalg.solve(jac.astype(float), rhs)
    assert np.max(np.abs(factor.solve(rhs) - exact)) <= 1e-5 * np.max(np.abs(exact))
    changed = jac.copy()
    changed[edge, edge] += _spd(8, rng)
    exact = np.linalg.solve(changed.astype(float), rhs)
    moved = factor.with_edge(changed[edge, edge])
    assert np.max(np.abs(moved.solve(rhs) - exact)) <= 1e-5 * np.max(np.abs(exact))
    for bad in ((20, 20), (block[0] + 3,) * 2):  # a negative pivot in the bulk, then the edge
        indefinite = jac.copy()
        indefinite[bad] = -1e3
        with pytest.raises(LinAlgError):
            EdgeBlockCholesky(indefinite, block)


class _SpringlessSurface:
    """The few surface operators `Linearisation` asks for, with a given tangent matrix; its
    single-precision copy shifted by `shift` times the identity (a factorisation that succeeds
    on any machine, as rounding may make it succeed)."""

    def __init__(self, jac, shift=0.0):
        n = jac.shape[0]
        self.jac, self.r_nodes, self.load_factor = jac, np.linspace(0.0, 1.0, n), 1.0
        self.shift, self.stiffness = shift, np.abs(jac)  # the pin's penalty's scale

    def sensitivities(self, w, delta):
        return np.full(w.size, 1e-3), 1.0, None

    def tangent_matrix(self, slope, precision=np.float32):
        if precision == np.float32:
            return (self.jac + self.shift * np.eye(self.jac.shape[0])).astype(precision)
        return self.jac.astype(precision)

    def tangent_product(self, slope, x):
        return self.jac @ x

    def tangent_diagonal(self, slope):
        return self.jac.diagonal().copy()

    def scaled_tangent_norm(self, slope, scale):
        return float(np.max(np.abs(self.jac / np.outer(scale, scale)).sum(axis=1)))

    def crack_tip(self, w, delta):
        return 0.5


def _rotated(spectrum, seed):
    """A symmetric matrix with the given eigenvalues and random eigenvectors."""
    q, _ = np.linalg.qr(np.random.default_rng(seed).standard_normal((spectrum.size,) * 2))
    jac = (q * spectrum) @ q.T
    return 0.5 * (jac + jac.T)


@pytest.mark.parametrize("softest, stable, double", [
    ((1e-10,), True, True), ((-1e-10,), False, False),
    ((-1e-10, 3e-8), False, None), ((-1e-11, 1e-6), False, None), ((1e-3,), True, False)])
def test_stability_below_single_precision_is_decided_in_double(softest, stable, double,
                                                               monkeypatch):
    """Tangents whose softest eigenvalue is ±1e-10 of the stiffest (at μ = 50 the crack tip's
    is 1e-9), also with a second soft mode (where the Rayleigh quotient after inverse iteration
    came out positive for a negative eigenvalue), or 1e-3. Single precision cannot tell the
    sign below ~1e-7 (here its copy is shifted by 1e-6 so that it always factorises, as
    rounding did on this machine, OpenBLAS 0.3.31 with AVX-512, for −1e-10); the flag is
    right. A double-precision factorisation decides the small positive eigenvalue; none is
    needed where inverse iteration finds a clearly negative or clearly positive one (`double`
    None: either, by how the two soft modes mix)."""
    doubles = _count_double_factorisations(monkeypatch)
    spectrum = np.concatenate([softest, np.logspace(-3, 0, 80 - len(softest))])
    surface = _SpringlessSurface(_rotated(spectrum, seed=3), shift=1e-6)
    linear = Linearisation(surface, np.zeros(80), 0.0, np.array([0.0, 1.0, 0.0]))
    assert not any(doubles)  # the shifted single-precision factorisation succeeded
    assert linear.stable is stable
    assert double is None or any(doubles) is double


def _count_double_factorisations(monkeypatch):
    """A list that gains, at each `Linearisation` factorisation attempt, whether it was in
    double precision."""
    doubles = []
    cholesky_or_none = newton.cholesky_or_none

    def counted(jac, block=None):
        doubles.append(jac.dtype == np.float64)
        return cholesky_or_none(jac, block)

    monkeypatch.setattr(newton, "cholesky_or_none", counted)
    return doubles


def test_the_stability_of_a_badly_scaled_tangent_is_judged_on_its_scaled_form(monkeypatch):
    """A tangent S A S with A's eigenvalues in [1e-3, 1] and S's diagonal from 1 to 1e3 (the FE
    surface stiffness grows with r): its softest eigenvalue is below 6e-7 of ‖∂g/∂w‖∞, where
    single precision cannot tell its sign, but A's is not; the flag needs no double-precision
    factorisation (with the unscaled quotient it did)."""
    doubles = _count_double_factorisations(monkeypatch)
    scale = np.logspace(0.0, 3.0, 80)
    jac = _rotated(np.logspace(-3, 0, 80), seed=4) * np.outer(scale, scale)
    norm = np.max(np.abs(jac).sum(axis=1))
    assert np.linalg.eigvalsh(jac)[0] < newton.SURE_SIGN * norm  # the premise
    linear = Linearisation(_SpringlessSurface(jac), np.zeros(80), 0.0, np.array([0.0, 1.0, 0.0]))
    assert linear.stable is True
    assert not any(doubles)


def test_a_tangent_with_a_diagonal_entry_below_zero_is_unstable(monkeypatch):
    """A diagonal entry −1e-9 (no positive definite matrix has one ≤ 0) that single precision's
    copy, shifted by 1e-6, factorises: unstable, without a double-precision factorisation."""
    doubles = _count_double_factorisations(monkeypatch)
    jac = np.diag(np.linspace(1.0, 2.0, 40))
    jac[20, 20] = -1e-9
    linear = Linearisation(_SpringlessSurface(jac, shift=1e-6), np.zeros(40), 0.0,
                           np.array([0.0, 1.0, 0.0]))
    assert linear.stable is False
    assert not any(doubles)


@pytest.mark.filterwarnings("ignore::scipy.linalg.LinAlgWarning")  # the LU is singular here
def test_a_degenerate_border_keeps_the_stability_of_its_cholesky_factorisation():
    """A border that the Cholesky elimination cannot take (∂g/∂δ = −∂g/∂w e₀ with the
    constraint on x̄o = δ − w₀: its Schur complement is zero; a diagonal of powers of 4 keeps
    single precision exact) goes to LU; the flag is still the positive definite tangent's,
    stable, decided before the Cholesky factorisation is dropped."""
    jac = np.diag(4.0 ** np.resize(np.arange(-3, 3), 40))
    surface = _SpringlessSurface(jac)
    surface.sensitivities = lambda w, delta: (-jac[:, 0], 1.0, None)
    linear = Linearisation(surface, np.zeros(40), 0.0, np.array([1.0, 0.0, 0.0]))
    assert linear._cho is None  # the premise: LU
    assert linear.stable is True


def _bordered_dense(jac, column, border):
    n = column.size
    dense = np.zeros((n + 1, n + 1))
    dense[:n, :n], dense[:n, n], dense[n] = jac, column, border
    return dense


def _pin(n, nodes, weights):
    pin = np.zeros(n)
    pin[list(nodes)] = weights
    return pin


def test_the_pins_system_with_its_load_as_unknown_solves_the_bordered_matrix():
    """`landing.pinned`'s system: [[J, e], [eᵀ, 0]] (the pin's load the unknown), factorised
    only as J + ρ e eᵀ, unrefined: the same solution as a dense double-precision solve, to
    single precision (measured 3e-7), for a J with a negative eigenvalue that the pin holds
    (its eigenvector mostly on the pinned nodes), where J alone has no Cholesky factor."""
    rng = np.random.default_rng(5)
    n, e = 30, _pin(30, (14, 15), (0.3, 0.7))
    soft = e / np.linalg.norm(e) + 0.05 * rng.standard_normal(n)
    jac = _rotated(np.linspace(1.0, 3.0, n), seed=6) - 3.5 * np.outer(soft, soft) / (soft @ soft)
    assert np.linalg.eigvalsh(jac)[0] < 0.0  # the premise: indefinite
    surface = _SpringlessSurface(jac)
    border = np.append(e, 0.0)
    system = BorderedSystem(surface, None, e, border, factorisations=(PINNED,), lu=None,
                            refinements=0, stability=False)
    assert not system.failed and system._penalty > 0.0
    rhs = rng.standard_normal(n + 1)
    expected = np.linalg.solve(_bordered_dense(jac, e, border), rhs)
    dw, load = system.solve(rhs)
    assert np.max(np.abs(np.append(dw, load) - expected)) <= 1e-5 * np.max(np.abs(expected))
    with pytest.raises(ValueError, match="stability"):
        assert system.stable is None  # never reached: the flag was not built


def test_a_system_that_may_not_use_lu_fails_where_no_factorisation_succeeds():
    """Two negative eigenvalues the pin cannot both hold: J + ρ e eᵀ has no Cholesky factor
    either, and without LU the system says it failed (`pinned` then stops, not converged)."""
    n, e = 20, _pin(20, (4, 5), (0.5, 0.5))
    jac = _rotated(np.r_[-1.0, -2.0, np.linspace(1.0, 2.0, n - 2)], seed=7)
    system = BorderedSystem(_SpringlessSurface(jac), None, e, np.append(e, 0.0),
                            factorisations=(PINNED,), lu=None, refinements=0, stability=False)
    assert system.failed


@pytest.mark.parametrize("precision, bound", [(np.float64, 1e-12), (np.float32, 1e-9)])
def test_the_lu_fallback_in_either_precision_solves_the_bordered_matrix(precision, bound):
    """Where neither J nor J + ρ u uᵀ factorises (the held tip's row (−e, 1), two negative
    modes), LU of the whole matrix in the precision asked for, refined once against the exact
    product: a dense double-precision solve to `bound` (measured 4e-16 in double, 8e-14 in
    single for this well-conditioned matrix)."""
    rng = np.random.default_rng(8)
    n, e = 20, _pin(20, (9, 10), (0.4, 0.6))
    jac = _rotated(np.r_[-1.0, -2.0, np.linspace(1.0, 2.0, n - 2)], seed=9)
    column, border = rng.standard_normal(n), np.append(-e, 1.0)
    system = BorderedSystem(_SpringlessSurface(jac), None, column, border,
                            factorisations=(SINGLE, PINNED), lu=precision, stability=False)
    assert system._cho is None and system._lu[0].dtype == precision  # the premise: LU
    rhs = rng.standard_normal(n + 1)
    expected = np.linalg.solve(_bordered_dense(jac, column, border), rhs)
    dw, dd = system.solve(rhs)
    assert np.max(np.abs(np.append(dw, dd) - expected)) <= bound * np.max(np.abs(expected))
