"""The boundary-integral half-space: quadrature rules, the Boussinesq kernel and its closed
forms."""

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import ellipe

from fem_asperity import InputError
from fem_asperity.closed_forms.lj import centre_deflection, traction
from fem_asperity.solids.bem import BoussinesqSurface, radial_grid
from fem_asperity.solids.boussinesq import (
    _NEAR,
    _near_pairs,
    _partition,
    _RangeMax,
    _unit_gauss,
    displacement_matrix,
    galerkin_matrix,
    kernel,
    log_gauss,
)


def _surface(h, r_fine=2.0, r_max=100.0):
    return BoussinesqSurface(radial_grid(h=h, r_fine=r_fine, r_max=r_max))


def _hertz_error(surface):
    """Max |w + (1 − r²/2)| at the nodes r < 0.9 under the Hertz pressure of a = R = δ = 1."""
    r = surface.r_quad
    hertz = 2.0 / np.pi * np.sqrt(np.clip(1.0 - r**2, 0, None))
    w = surface.deflection(np.where(r < 1.0, hertz, 0))
    inside = surface.r_nodes < 0.9
    return np.max(np.abs(-w[inside] - (1.0 - 0.5 * surface.r_nodes[inside] ** 2)))


def test_log_gauss_rule_is_exact_to_degree_2n_minus_1():
    x, w = log_gauss(8)
    assert np.all((0 < x) & (x < 1)) and np.all(w > 0)
    exact = 1.0 / (np.arange(16) + 1.0) ** 2  # ∫₀¹ xᵏ (−ln x) dx
    np.testing.assert_allclose([w @ x**k for k in range(16)], exact, rtol=1e-13)


def test_displacement_matrix_matches_adaptive_quadrature():
    """Random piecewise-linear traction, points inside elements, next to nodes, near and at 0."""
    rng = np.random.default_rng(1)
    nodes = np.concatenate([[0.0], np.cumsum(rng.uniform(0.05, 0.2, 20))])
    p = rng.uniform(-1.0, 1.0, nodes.size)
    r = np.concatenate([rng.uniform(0.0, 1.2 * nodes[-1], 8),
                        [0.0, 1e-4, nodes[3] + 1e-3, nodes[7] - 1e-6]])
    u = displacement_matrix(nodes, r) @ p
    for ri, ui in zip(r, u):
        ref = sum(quad(lambda s, ri=ri: kernel(ri, s) * np.interp(s, nodes, p), lo, hi,
                       points=[ri] if lo < ri < hi else None, epsabs=1e-14, epsrel=1e-13,
                       limit=200)[0]
                  for lo, hi in zip(nodes[:-1], nodes[1:]))
        assert ui == pytest.approx(ref, rel=1e-11, abs=1e-13)


def test_each_mid_range_rule_is_as_accurate_as_eight_points_at_one_length():
    """The element integrals ∫ kernel (1, (s − a)/length) ds of pairs 1 to 9 lengths apart, by
    the `_MID_RULES` (fewer points further out), against 24-point Gauss-Legendre (the kernel is
    analytic there: error ~ρ^(−48)), on elements either side of r, r from 1e-2 to 1e3 lengths:
    within 5.7e-13, the 8-point rule's bound at one length (measured 2.6e-13; one point fewer in
    the first or second tier: 1.2e-12 and 1.5e-12)."""
    x, w = _unit_gauss(24)
    distance, offset = (grid.ravel() for grid in np.meshgrid(np.linspace(1.0, 8.99, 80),
                                                             np.logspace(-2.0, 3.0, 21)))
    a = distance + offset  # elements [a, a + 1], r from 1e-2 to 1e3 lengths either side
    r = np.concatenate([a - distance, a + 1.0 + distance])
    a, distance = np.tile(a, 2), np.tile(distance, 2)
    values = kernel(r[:, None], a[:, None] + x) * w
    i0, i1 = _near_pairs(r, np.arange(r.size), 2 * np.arange(r.size),
                         np.stack([a, a + 1.0], axis=1).ravel(), distance)
    assert np.max(np.abs(i0 / values.sum(axis=1) - 1.0)) <= 5.7e-13
    assert np.max(np.abs(i1 / (values @ x) - 1.0)) <= 5.7e-13


def test_galerkin_matrix_is_the_tested_deflection_tested_against_the_hat_functions():
    """The Galerkin coupling, evaluated by symmetric blocks of element pairs, is Nᵀ diag(W r)
    times the deflection at the quadrature points (checked above against adaptive quadrature)
    to 1e-13 (measured 3e-16), on random elements then a geometric tail: 400 elements, so that
    blocks off the diagonal are used in both orders, and half the pairs lie in blocks far
    enough apart to be interpolated (the premise, checked)."""
    rng = np.random.default_rng(2)
    inner = np.cumsum(rng.uniform(0.01, 0.05, 330))
    nodes = np.concatenate([[0.0], inner, inner[-1] + np.cumsum(0.05 * 1.1 ** np.arange(70))])
    elements = nodes.size - 1
    interpolated = sum((rows.stop - rows.start) * (cols.stop - cols.start)
                       for rows, cols, apart in _partition(nodes[:-1], nodes[1:]) if apart)
    assert interpolated > 0.4 * elements ** 2 / 2
    surface = BoussinesqSurface(nodes)
    weighted = surface.interp.T.multiply(surface.weights).tocsr()
    reference = weighted @ displacement_matrix(nodes, surface.r_quad)
    coupling = galerkin_matrix(nodes)
    assert np.max(np.abs(coupling - reference)) <= 1e-13 * np.max(np.abs(reference))


def test_hertz_pressure_gives_hertz_displacement_to_1e4():
    assert _hertz_error(_surface(0.025)) < 1e-4  # measured 8.1e-5


def test_grid_refinement_converges_at_second_order():
    errors = [_hertz_error(_surface(h)) for h in (0.1, 0.05, 0.025)]
    rates = np.log2(np.array(errors[:-1]) / errors[1:])
    np.testing.assert_allclose(rates, 2.0, atol=0.1)  # measured 1.99, 2.00


def test_uniform_disc():
    """Centre deflection 2pa/E* and the profile (4pa/πE*) E(r²/a²) inside the disc."""
    surface = _surface(0.025)
    w = -surface.deflection((surface.r_quad < 1.0).astype(float))
    assert w[0] == pytest.approx(2.0, rel=1e-4)
    inside = surface.r_nodes < 0.8
    np.testing.assert_allclose(w[inside], 4 / np.pi * ellipe(surface.r_nodes[inside] ** 2),
                               rtol=1e-4)


@pytest.mark.parametrize("x", [1.0, 1.5, 3.0])
def test_rigid_sphere_centre_deflection_is_eq4(x):
    """LJ traction of the undeformed gap x + r²/2: the centre lifts by eq. 4 (μ = 0.01).

    Second order in h; at h = 0.0125 the error is 3.9e-5 (x = 1), 1.3e-5, 6.9e-6."""
    surface = _surface(0.0125, r_fine=4.0)
    mu = 0.01
    w0 = mu**1.5 * surface.deflection(traction(x + 0.5 * surface.r_quad**2))[0]
    assert w0 == pytest.approx(centre_deflection(x, mu=mu), rel=1e-4)


def test_compliance_is_symmetric_positive_definite():
    c = _surface(0.1).compliance
    np.testing.assert_array_equal(c, c.T)
    assert np.linalg.eigvalsh(c).min() > 0


def test_radial_grid():
    nodes = radial_grid(h=0.1, r_fine=1.0, r_max=50.0, growth=0.2)
    steps = np.diff(nodes)
    assert nodes[0] == 0 and nodes[-1] >= 50.0
    np.testing.assert_allclose(steps[:10], 0.1)
    np.testing.assert_allclose(steps[11:-1] / steps[10:-2], 1.2)
    with pytest.raises(InputError):
        radial_grid(h=0.1, r_fine=1.0, r_max=0.5)
    with pytest.raises(InputError):
        BoussinesqSurface([0.0, 1.0, 0.5])


def test_partition_covers_every_element_pair_once():
    """The blocks of `_partition`, each in both orders off the diagonal, cover every pair of
    elements exactly once (`galerkin_matrix` fills an uninitialised array from them), on a grid
    with fine bands between graded runs like an edge grid's; and the longest element of a run,
    which decides separation, is the run's maximum; the blocks called separated are."""
    rng = np.random.default_rng(3)
    steps = np.concatenate([np.full(40, 0.1) * 1.1 ** np.arange(40)[::-1], np.full(150, 0.002),
                            rng.uniform(0.01, 0.2, 60), np.full(120, 0.002),
                            0.002 * 1.1 ** np.arange(60)])
    nodes = np.concatenate([[0.0], np.cumsum(steps)])
    a, b = nodes[:-1], nodes[1:]
    cover = np.zeros((steps.size, steps.size), dtype=int)
    for rows, cols, apart in _partition(a, b):
        cover[rows, cols] += 1
        if rows != cols:
            cover[cols, rows] += 1
        if apart:  # the kernel is analytic there: no near pair inside (`_NEAR`)
            extents = b[rows.stop - 1] - a[rows.start], b[cols.stop - 1] - a[cols.start]
            longest = max(np.max(steps[rows]), np.max(steps[cols]))
            assert a[cols.start] - b[rows.stop - 1] >= max(*extents, _NEAR[1] * longest)
    assert np.all(cover == 1)
    longest = _RangeMax(steps.tolist())
    for start, stop in rng.integers(0, steps.size, size=(200, 2)).tolist():
        start, stop = min(start, stop), max(start, stop) + 1
        assert longest(start, stop) == np.max(steps[start:stop])
