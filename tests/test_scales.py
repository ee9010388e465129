"""Inputs and scales: E*, the Tabor parameter (eq. 1), its inverse, and input checks."""

import math
import re
import warnings

import numpy as np
import pytest

from fem_asperity import (
    DerjaguinWarning,
    InputError,
    Scales,
    effective_modulus,
    tabor_parameter,
)
from fem_asperity.closed_forms.lj import centre_deflection

# Silicon-like sphere on a compliant film: hand values below use these.
E, NU, DGAMMA, EPS, R = 100e9, 0.25, 0.1, 0.3e-9, 1e-6


def test_effective_modulus_rigid_and_two_bodies():
    assert effective_modulus(E1=E, nu1=NU) == pytest.approx(E / (1 - NU**2), rel=1e-15)
    # two identical bodies: half the single-body plane-strain modulus
    assert effective_modulus(E1=E, nu1=NU, E2=E, nu2=NU) == pytest.approx(E / (2 * (1 - NU**2)))


def test_tabor_parameter_hand_value():
    E_star = 1e9
    expected = (R * DGAMMA**2 / (E_star**2 * EPS**3)) ** (1 / 3)
    assert tabor_parameter(E_star=E_star, dgamma=DGAMMA, eps=EPS, R=R) == pytest.approx(expected)
    # doubling R multiplies mu by 2^(1/3)
    ratio = tabor_parameter(E_star=E_star, dgamma=DGAMMA, eps=EPS, R=2 * R) / expected
    assert ratio == pytest.approx(2 ** (1 / 3))


@pytest.mark.parametrize("mu", [0.01, 0.3, 1.0, 50.0, 500.0])
def test_mu_round_trips_through_the_inverse(mu):
    by_modulus = Scales.for_mu(mu, eps=EPS, R=R, dgamma=DGAMMA)
    by_energy = Scales.for_mu(mu, eps=EPS, R=R, E_star=1e9)
    assert by_modulus.mu == pytest.approx(mu, rel=1e-12)
    assert by_energy.mu == pytest.approx(mu, rel=1e-12)
    assert by_modulus.dgamma == DGAMMA and by_energy.E_star == 1e9


def test_natural_scales():
    s = Scales(E_star=1e9, dgamma=DGAMMA, eps=EPS, R=R)
    assert s.length_z == EPS
    assert s.length_r == pytest.approx(math.sqrt(R * EPS))
    assert s.force == pytest.approx(2 * math.pi * R * DGAMMA)
    assert s.area == pytest.approx(EPS * R)
    # identity of the notes: dgamma / E* = mu^(3/2) sqrt(eps^3 / R)
    assert DGAMMA / 1e9 == pytest.approx(s.mu**1.5 * math.sqrt(EPS**3 / R))


BAD_MODULI = [0.0, -1.0, math.nan, math.inf, "abc"]


@pytest.mark.parametrize("bad", BAD_MODULI)
@pytest.mark.parametrize("name", ["E1", "E2"])
def test_bad_moduli_are_refused(name, bad):
    kwargs = dict(E1=E, nu1=NU, E2=E, nu2=NU)
    kwargs[name] = bad
    with pytest.raises(InputError, match=name):
        effective_modulus(**kwargs)


@pytest.mark.parametrize("bad", [-1.0, 0.5, 0.7, -2.0, math.nan])
@pytest.mark.parametrize("name", ["nu1", "nu2"])
def test_poisson_ratio_outside_open_interval_is_refused(name, bad):
    kwargs = dict(E1=E, nu1=NU, E2=E, nu2=NU)
    kwargs[name] = bad
    with pytest.raises(InputError, match=rf"{name} must be in \(-1, 0.5\)"):
        effective_modulus(**kwargs)


def test_infinite_second_modulus_points_to_the_rigid_option():
    with pytest.raises(InputError, match="leave E2 and nu2 out for a rigid body"):
        effective_modulus(E1=E, nu1=NU, E2=math.inf, nu2=NU)


def test_half_specified_second_body_is_refused():
    with pytest.raises(InputError, match="nu2"):
        effective_modulus(E1=E, nu1=NU, E2=E)
    with pytest.raises(InputError, match="nu2"):
        effective_modulus(E1=E, nu1=NU, nu2=NU)


@pytest.mark.parametrize("name", ["E_star", "dgamma", "eps", "R"])
@pytest.mark.parametrize("bad", [0.0, -3.0, math.nan, math.inf])
def test_bad_physical_inputs_are_refused(name, bad):
    kwargs = dict(E_star=1e9, dgamma=DGAMMA, eps=EPS, R=R)
    kwargs[name] = bad
    with pytest.raises(InputError, match=name):
        tabor_parameter(**kwargs)
    with pytest.raises(InputError, match=name):
        Scales(**kwargs)


def test_derjaguin_ratio_warns_below_300_and_refuses_below_10():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        tabor_parameter(E_star=1e9, dgamma=DGAMMA, eps=EPS, R=301 * EPS)  # no warning
    with pytest.warns(DerjaguinWarning, match="R/eps"):
        tabor_parameter(E_star=1e9, dgamma=DGAMMA, eps=EPS, R=299 * EPS)
    with pytest.raises(InputError, match=r"R/eps must be >= 10"):
        tabor_parameter(E_star=1e9, dgamma=DGAMMA, eps=EPS, R=9.9 * EPS)


def test_inverse_needs_exactly_one_of_modulus_or_energy():
    with pytest.raises(InputError, match="exactly one"):
        Scales.for_mu(1.0, eps=EPS, R=R)
    with pytest.raises(InputError, match="exactly one"):
        Scales.for_mu(1.0, eps=EPS, R=R, E_star=1e9, dgamma=DGAMMA)
    with pytest.raises(InputError, match="mu"):
        Scales.for_mu(-1.0, eps=EPS, R=R, E_star=1e9)


@pytest.mark.parametrize("mu, given, needed", [(1e300, "E_star", "dgamma = inf"),
                                                (1e-300, "dgamma", "E_star = inf"),
                                                (1e6, "E_star", "dgamma = 5.2e+06")])
def test_an_extreme_mu_is_refused_by_the_input_it_would_need(mu, given, needed):
    """Δγ/E* = μ^1.5 √(ε³/R): at E* = 1e9 Pa, ε = 0.3 nm, R = 1 µm, μ = 1e6 needs
    Δγ = 1e9 · 1e9 · √(2.7e-29/1e-6) = 5.2e6 J/m², beyond the supported 1e3."""
    inputs = {"E_star": 1e9, "dgamma": DGAMMA}
    says = re.escape(f"mu = {mu:g} with these inputs needs {needed}")
    with pytest.raises(InputError, match=says):
        Scales.for_mu(mu, eps=0.3e-9, R=1e-6, **{given: inputs[given]})


@pytest.mark.parametrize("bad", [None, True, "1", [1.0, None]])
def test_what_is_no_number_is_refused_even_where_numpy_would_cast_it(bad):
    with pytest.raises(InputError, match="mu must be a real number"):
        Scales.for_mu(bad, eps=EPS, R=R, E_star=1e9)


def test_error_names_offending_array_entry():
    with pytest.raises(InputError, match=r"mu must be in \(0, inf\); got -2.0"):
        centre_deflection(np.ones(3), mu=np.array([1.0, -2.0, 3.0]))
