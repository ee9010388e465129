"""Hertz, JKR, DMT and Maugis-Dugdale references: hand values and their limits."""

import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from fem_asperity import InputError
from fem_asperity.closed_forms import reference as ref


def test_hertz_hand_values():
    # P = (4/3) E* R^1/2 d^3/2 in units of 2 pi R dgamma with d in eps: (2/3pi) (d/mu)^1.5
    assert ref.hertz_force(indentation=4.0, mu=1.0) == pytest.approx(16 / (3 * math.pi))
    assert ref.hertz_radius(indentation=4.0) == 2.0  # a^2 = R d
    assert ref.dmt_force(indentation=0.0, mu=3.0) == -1.0


def test_jkr_pull_off_is_the_minimum_of_the_jkr_curve():
    mu = 2.7
    best = minimize_scalar(lambda a: ref.jkr_force(radius=a, mu=mu), bounds=(0.1, 10.0),
                           method="bounded", options={"xatol": 1e-10})
    off = ref.jkr_pull_off(mu=mu)
    assert best.fun == pytest.approx(-0.75, abs=1e-12) and off.force == -0.75
    assert best.x == pytest.approx(off.radius, rel=1e-7)


def test_jkr_compressive_radius_eq_a9():
    assert ref.jkr_compressive_radius(mu=1.0) == pytest.approx(0.8794, abs=5e-5)
    assert ref.jkr_compressive_radius(mu=4.0) == pytest.approx(2 * 0.8794, abs=1e-4)


def test_jkr_approach_vanishes_where_hertz_and_adhesion_balance():
    # delta = a^2 - sqrt(2 pi a) mu^3/4 = 0 at a^3 = 2 pi mu^1.5
    mu = 1.3
    a = (2 * math.pi * mu**1.5) ** (1 / 3)
    assert ref.jkr_approach(radius=a, mu=mu) == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize("mu", [0.5, 50.0, 1e6])
def test_jkr_radius_at_approach_is_the_stable_root_down_to_the_fixed_grips_pull_off(mu):
    # the least approach: where d(approach)/da = 0, found here by minimising it numerically
    least = minimize_scalar(lambda a: ref.jkr_approach(radius=a, mu=mu),
                            bounds=(1e-3 * mu**0.5, 10 * mu**0.5), method="bounded",
                            options={"xatol": 1e-12 * mu**0.5})
    for a in (1.0001 * least.x, 2.0 * least.x, 30.0 * least.x):
        approach = ref.jkr_approach(radius=a, mu=mu)
        assert ref.jkr_radius_at_approach(approach=approach, mu=mu) == pytest.approx(a, rel=1e-9)
    assert math.isnan(ref.jkr_radius_at_approach(approach=least.fun - 1e-6 * abs(least.fun),
                                                 mu=mu))


@pytest.mark.parametrize("mu", [1.0, 50.0])
def test_jkr_displacement_follows_the_sphere_inside_and_boussinesq_far_away(mu):
    a = 2.0 * (np.pi / 8.0) ** (1 / 3) * mu**0.5
    approach = ref.jkr_approach(radius=a, mu=mu)
    inside = np.array([0.0, 0.5 * a, a])
    assert ref.jkr_displacement(inside, radius=a, mu=mu) == pytest.approx(
        approach - inside**2 / 2, rel=1e-13, abs=1e-13 * a**2)
    # continuous across the edge, where Hertz's and the punch's outside fields meet the sphere
    # (the punch's rises like √(r − a): 2e-14 of a off the edge it has moved by ~1e-7 a²)
    edge = ref.jkr_displacement(a * np.array([1 - 1e-14, 1 + 1e-14]), radius=a, mu=mu)
    assert edge[1] == pytest.approx(edge[0], abs=1e-6 * a**2)
    # far away a point load: u = P / (pi E* r) = 2 mu^1.5 P / r in these units
    far = 1e4 * a
    assert ref.jkr_displacement(far, radius=a, mu=mu) == pytest.approx(
        2 * mu**1.5 * ref.jkr_force(radius=a, mu=mu) / far, rel=1e-7)


def test_jkr_forms_refuse_bad_input_with_one_clear_error():
    with pytest.raises(InputError, match="approach"):
        ref.jkr_radius_at_approach(approach=np.nan, mu=1.0)
    with pytest.raises(InputError, match="approach must be one number"):
        ref.jkr_radius_at_approach(approach=[0.0, 1.0], mu=1.0)
    with pytest.raises(InputError, match="mu"):
        ref.jkr_radius_at_approach(approach=0.0, mu=-1.0)
    with pytest.raises(InputError, match="r must"):
        ref.jkr_displacement([1.0, -1.0], radius=1.0, mu=1.0)
    with pytest.raises(InputError, match="radius"):
        ref.jkr_displacement(1.0, radius=0.0, mu=1.0)
    with pytest.raises(InputError, match="radius"):
        ref.jkr_compressive_radius_at(radius=np.inf, mu=1.0)


def test_jkr_compressive_radius_at_the_pull_off_is_eq_a9s_and_vanishes_near_the_least_radius():
    mu = 7.0
    off = ref.jkr_pull_off(mu=mu).radius
    assert ref.jkr_compressive_radius_at(radius=off, mu=mu) == pytest.approx(
        ref.jkr_compressive_radius(mu=mu), rel=1e-12)
    # where the punch's tension outweighs Hertz's pressure everywhere: d/(2a^2) <= -1
    small = (np.pi / 2) ** (1 / 3) * mu**0.5  # a^(3/2) = sqrt(2 pi) mu^(3/4) / 2
    assert ref.jkr_compressive_radius_at(radius=small, mu=mu) == pytest.approx(0.0, abs=1e-6)
    assert ref.jkr_compressive_radius_at(radius=0.9 * small, mu=mu) == 0.0
    both = ref.jkr_compressive_radius_at(radius=np.array([off, 0.9 * small]), mu=mu)
    assert both == pytest.approx([ref.jkr_compressive_radius(mu=mu), 0.0], rel=1e-12)


def test_maugis_lambda_is_1157_mu():
    assert ref.MD_LAMBDA_PER_MU == pytest.approx(1.157, abs=5e-4)


def test_maugis_dugdale_tends_to_dmt_for_small_mu():
    off = ref.maugis_dugdale_pull_off(mu=1e-4)
    assert off.force == pytest.approx(-1.0, abs=1e-5)
    assert off.radius < 1e-4


def test_maugis_dugdale_tends_to_jkr_for_large_mu():
    for mu in (1e3, 1e5):
        off = ref.maugis_dugdale_pull_off(mu=mu)
        jkr = ref.jkr_pull_off(mu=mu)
        assert off.force == pytest.approx(-0.75, abs=1e-6)
        assert off.radius == pytest.approx(jkr.radius, rel=1e-4)


def test_maugis_dugdale_is_monotone_between_the_limits_and_vectorised():
    mu = np.logspace(-2, 2, 9)
    off = ref.maugis_dugdale_pull_off(mu=mu)
    assert off.force.shape == (9,)
    assert np.all(np.diff(off.force) > 0) and np.all((off.force > -1) & (off.force < -0.75))
    assert off.force[4] == pytest.approx(ref.maugis_dugdale_pull_off(mu=mu[4]).force)


@pytest.mark.parametrize("bad", [0.0, -1.0, math.nan, math.inf])
def test_reference_inputs_are_checked(bad):
    with pytest.raises(InputError, match="mu"):
        ref.maugis_dugdale_pull_off(mu=bad)
    with pytest.raises(InputError, match="mu"):
        ref.jkr_pull_off(mu=bad)
    with pytest.raises(InputError, match="indentation"):
        ref.hertz_force(indentation=-1.0, mu=1.0)
