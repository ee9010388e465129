"""LJ 9-3 law and the closed forms of eqs. (4) and (8), against quadrature and hand values."""

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import minimize_scalar

from fem_asperity import InputError
from fem_asperity.closed_forms.lj import (
    K_9_3,
    bradley_force,
    centre_deflection,
    rigid_force,
    scaled_potential,
    scaled_traction,
    separation_from_gap,
    traction,
    traction_slope,
)


def test_traction_is_zero_at_eps_and_most_tensile_at_3_to_the_sixth():
    assert traction(1.0) == 0.0
    best = minimize_scalar(traction, bounds=(1.0, 2.0), method="bounded", options={"xatol": 1e-12})
    assert best.x == pytest.approx(3 ** (1 / 6), rel=1e-8)
    assert best.fun == pytest.approx(-1.0264, abs=5e-5)  # -16/(9 sqrt 3) = -1.02640
    assert traction(0.9) > 0 and traction(2.0) < 0  # repulsive inside eps, attractive outside


def test_traction_in_si_units_scales_with_dgamma_over_eps():
    dgamma, eps = 0.05, 0.3e-9
    h = np.array([0.9, 1.0, 1.5, 3.0]) * eps
    assert np.allclose(traction(h, dgamma=dgamma, eps=eps), dgamma / eps * traction(h / eps))


def test_traction_slope_matches_finite_differences():
    h = np.array([0.8, 1.0, 1.12, 2.0, 5.0])
    step = 1e-6
    fd = (traction(h + step) - traction(h - step)) / (2 * step)
    assert np.allclose(traction_slope(h), fd, rtol=1e-7, atol=1e-9)
    # zero slope where the traction is most tensile
    assert traction_slope(3 ** (1 / 6)) == pytest.approx(0.0, abs=1e-12)


def test_bradley_minimum_is_minus_one_at_unit_separation():
    assert bradley_force(1.0) == pytest.approx(-1.0, abs=1e-15)
    best = minimize_scalar(bradley_force, bounds=(0.8, 2.0), method="bounded",
                           options={"xatol": 1e-10})
    assert best.x == pytest.approx(1.0, abs=1e-7)
    assert best.fun == pytest.approx(-1.0, abs=1e-12)


def _lj(h):
    """Independent transcription of the LJ 9-3 traction in units of dgamma/eps."""
    return 8.0 / 3.0 * (h**-9 - h**-3)


@pytest.mark.parametrize("delta", [0.7, 1.0, 1.3, 2.5, 10.0])
def test_eq8_against_quadrature_over_the_sphere(delta):
    # P/(2 pi R dgamma) = int_0^inf p(delta + r^2/2) r dr with r in sqrt(eps R)
    value, _ = quad(lambda r: _lj(delta + r * r / 2) * r, 0, np.inf, epsabs=1e-14, epsrel=1e-13)
    assert bradley_force(delta) == pytest.approx(value, abs=1e-10)


@pytest.mark.parametrize("x", [0.8, 1.0, 1.5, 3.0])
@pytest.mark.parametrize("mu", [0.05, 1.0, 20.0])
def test_eq4_against_boussinesq_quadrature(x, mu):
    # w(0) = -(2/E*) int_0^inf p dr; in eps with r in sqrt(eps R): -2 mu^1.5 int p(x + r^2/2) dr
    value, _ = quad(lambda r: _lj(x + r * r / 2), 0, np.inf, epsabs=1e-14, epsrel=1e-13)
    expected = -2 * mu**1.5 * value
    assert centre_deflection(x, mu=mu) == pytest.approx(expected, abs=1e-10 * max(1, abs(expected)))


def test_eq4_constant_is_the_ratio_of_the_two_integrals():
    i9, _ = quad(lambda t: (1 + t * t) ** -9, 0, np.inf, epsabs=1e-15)
    i3, _ = quad(lambda t: (1 + t * t) ** -3, 0, np.inf, epsabs=1e-15)
    assert K_9_3 == pytest.approx(i9 / i3, rel=1e-12)
    assert i3 == pytest.approx(3 * math.pi / 16, rel=1e-12)


def test_eq10_constant_is_exact_value_of_eq4_at_unit_gap():
    assert math.sqrt(2) * math.pi * (1 - 2145 / 4096) == pytest.approx(2.11623, abs=5e-6)
    mu = 0.37
    assert separation_from_gap(1.0, mu=mu) == pytest.approx(1 + 2.11623 * mu**1.5, rel=1e-6)


@pytest.mark.parametrize("bad", [0.0, -1.0, math.nan, math.inf])
def test_non_positive_gaps_are_refused(bad):
    with pytest.raises(InputError, match="h must be"):
        traction(bad)
    with pytest.raises(InputError, match="delta must be"):
        bradley_force(bad)
    with pytest.raises(InputError, match="x must be"):
        centre_deflection(bad, mu=1.0)


def test_potential_is_the_integral_of_the_traction():
    h = np.linspace(0.8, 5.0, 50)
    step = 1e-6
    slope = (scaled_potential(h + step) - scaled_potential(h - step)) / (2 * step)
    np.testing.assert_allclose(slope, -scaled_traction(h), rtol=1e-7, atol=1e-9)
    assert scaled_potential(1.0) == pytest.approx(-1.0)  # minus the work of adhesion


def _sphere_by_quadrature(delta, rho):
    """∫ p̄(δ̄ + h(r)) r dr over the exact sphere's lower half, h = ρ(1 − √(1 − r²/ρ))."""
    def integrand(r):
        h = rho * (1.0 - np.sqrt(1.0 - r * r / rho))
        return 8.0 / 3.0 * ((delta + h) ** -9 - (delta + h) ** -3) * r

    return quad(integrand, 0.0, np.sqrt(rho), limit=400, epsabs=0.0, epsrel=1e-11)[0]


@pytest.mark.parametrize("delta", [1.0, 2.0, 50.0, 1e4])
@pytest.mark.parametrize("rho", [30.0, 3333.0])
def test_the_exact_spheres_rigid_force_is_its_traction_integrated(delta, rho):
    expected = _sphere_by_quadrature(delta, rho)
    assert rigid_force(delta, radius_ratio=rho) == pytest.approx(expected, rel=1e-5)


def test_the_exact_spheres_rigid_force_tends_to_bradleys():
    assert rigid_force(1.0, radius_ratio=1e8) == pytest.approx(bradley_force(1.0), rel=1e-7)
    assert rigid_force(3.0) == bradley_force(3.0)
