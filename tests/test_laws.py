"""The paper's closed-form laws: hand values, limits, continuity, regimes, extremes, bad input."""

import json
import math

import numpy as np
import pytest

from fem_asperity import PAPER_LAWS as laws
from fem_asperity import AsperityLaws, InputError


def deflection(x, mu):
    """Eq. (4) transcribed by hand, independent of the package."""
    return math.sqrt(2) * math.pi * mu**1.5 * (x**-2.5 - 2145 / 4096 * x**-8.5)


def test_wu_pull_off_limits_and_a_hand_value():
    assert laws.p_max(1e-9) == pytest.approx(-1.0, abs=1e-12)
    assert laws.p_max(1e9) == pytest.approx(-0.75, abs=1e-12)
    assert laws.p_max(1.0) == pytest.approx(-(7 + (1 - 1.98) / 2.98) / 8, rel=1e-15)


def test_contact_radius_eq6():
    assert laws.a_c(0.1) == 0.0 and laws.a_c(0.19) == 0.0
    assert laws.a_c(1.19) == pytest.approx(0.83)


def test_separations_below_and_above_the_jump_in_threshold():
    assert laws.delta_oc(0.3) == pytest.approx(1 + 0.922 * 0.3)
    assert laws.delta_o_star(0.3) == pytest.approx(1 + 2.116 * 0.3**1.5)
    x = -0.3 + 2.2  # eq. 12 at mu = 1
    assert laws.x_oc(1.0) == pytest.approx(1.9)
    assert laws.delta_oc(1.0) == pytest.approx(x + deflection(x, 1.0), rel=1e-13)
    assert laws.delta_o_star(1.0) == laws.delta_oc(1.0)
    assert math.isnan(laws.x_oc(0.3)) and not laws.jump_in(0.3) and laws.jump_in(0.5)


def test_the_discontinuity_at_mu_half_noted_in_the_errata():
    below = np.nextafter(0.5, 0)
    assert laws.delta_oc(below) == pytest.approx(1.461, abs=5e-4)  # eq. 7
    assert laws.delta_o_star(below) == pytest.approx(1.748, abs=5e-4)  # eq. 10
    assert laws.delta_oc(0.5) == pytest.approx(2.03, abs=5e-3)  # eq. 13


@pytest.mark.parametrize("mu", [0.05, 0.15, 0.3, 0.45])
def test_continuous_regime_force_passes_through_p_max_and_turns_hertzian(mu):
    doc, p_max = laws.delta_oc(mu), laws.p_max(mu)
    assert laws.force(doc, mu=mu) == pytest.approx(p_max, rel=1e-14)
    assert laws.force(doc - 1e-12, mu=mu) == pytest.approx(p_max, rel=1e-9)
    d = 0.7
    assert laws.force(doc - d, mu=mu) - p_max == pytest.approx(2 / (3 * math.pi) * (d / mu) ** 1.5)
    # far field: Bradley's law, scaled (eq. 9), decays as delta^-2
    far = laws.force(100.0, mu=mu)
    assert far == pytest.approx(p_max * (-4 / 3 * 1e-4) / ((doc**-8 - 4 * doc**-2) / 3), rel=1e-6)


@pytest.mark.parametrize("mu", [0.5, 1.0, 10.0, 50.0])
def test_jump_in_regime_force_jumps_from_bradley_to_p_max(mu):
    doc = laws.delta_oc(mu)
    assert laws.force(doc, mu=mu) == pytest.approx((doc**-8 - 4 * doc**-2) / 3, rel=1e-14)
    assert laws.force(np.nextafter(doc, 0), mu=mu) == pytest.approx(laws.p_max(mu), rel=1e-9)
    assert laws.force(2 * doc, mu=mu) == pytest.approx(((2 * doc) ** -8 - 4 * (2 * doc) ** -2) / 3)


def test_area_continuous_regime_eq17():
    mu = 0.3
    star = laws.delta_o_star(mu)
    assert laws.area(star, mu=mu) == 0.0 and laws.area(star + 1, mu=mu) == 0.0
    assert laws.area(star - 0.5, mu=mu) == pytest.approx(math.pi * 0.5)


def test_area_jump_in_regime_eq19_with_its_069():
    mu = 2.0
    star = laws.delta_o_star(mu)
    assert laws.area(star, mu=mu) == 0.0
    just_in = laws.area(np.nextafter(star, 0), mu=mu)
    assert just_in == pytest.approx(math.pi * 0.83**2 * (mu - 0.19), rel=1e-9)
    assert just_in == pytest.approx(math.pi * 0.69 * (mu - 0.19), rel=2e-3)  # eq. 19 as printed


def test_laws_broadcast_over_separation_and_mu():
    delta = np.linspace(-5.0, 20.0, 7)[:, None]
    mu = np.array([0.01, 0.3, 0.5, 5.0])[None, :]
    assert laws.force(delta, mu=mu).shape == (7, 4)
    assert laws.area(delta, mu=mu).shape == (7, 4)


def test_extremes_stay_finite_and_silent():
    """mu from 0.01 to 3000, separations from deep indentation to far away (warnings are errors)."""
    mu = np.logspace(-2, 3.5, 60)[None, :]
    delta = np.concatenate([np.linspace(-100, 0.99, 50), np.logspace(0, 3, 50)])[:, None]
    force, area = laws.force(delta, mu=mu), laws.area(delta, mu=mu)
    assert np.isfinite(force).all() and np.isfinite(area).all() and (area >= 0).all()
    ev = laws.events(mu.ravel())
    assert np.all(ev.delta_oc >= 1.0) and np.all(ev.delta_o_star >= 1.0)
    assert np.all((ev.p_max >= -1) & (ev.p_max <= -0.75))


def test_refitted_constants_are_used():
    refit = AsperityLaws(c_oc=1.0, mu_jump=0.6, x_0=0.0, x_1=2.0)
    assert refit.delta_oc(0.55) == pytest.approx(1.55)
    assert refit.x_oc(1.0) == pytest.approx(2.0)


@pytest.mark.parametrize("kwargs, name", [
    ({"c_off": -1.0}, "c_off"), ({"c_a": math.nan}, "c_a"), ({"mu_jump": 0.0}, "mu_jump"),
    ({"x_1": -2.2}, "x_1"), ({"x_0": -5.0}, "x_0 \\+ x_1"), ({"c_star": math.inf}, "c_star"),
])
def test_bad_constants_are_refused(kwargs, name):
    with pytest.raises(InputError, match=name):
        AsperityLaws(**kwargs)


@pytest.mark.parametrize("bad", [0.0, -0.1, math.nan, math.inf])
def test_bad_mu_and_separation_are_refused(bad):
    with pytest.raises(InputError, match="mu"):
        laws.events(bad)
    with pytest.raises(InputError, match="mu"):
        laws.force(1.0, mu=bad)
    if bad != 0.0 and bad != -0.1:
        with pytest.raises(InputError, match="delta_o"):
            laws.area(bad, mu=1.0)


def test_event_records_are_json_with_null_x_oc_without_jump_in():
    rows = laws.events([0.3, 2.0]).records()
    text = json.dumps(rows, allow_nan=False)
    assert json.loads(text)[0]["x_oc"] is None
    assert rows[1]["x_oc"] == pytest.approx(-0.3 + 2.2 * 2**0.4)
    assert set(rows[0]) == {"mu", "p_max", "delta_oc", "delta_o_star", "a_c", "jump_in", "x_oc"}


@pytest.mark.parametrize("law", ["force", "area"])
def test_a_result_beyond_the_float_range_is_refused_not_returned_as_inf(law):
    """At δ̄o = −1.7e308 the area π(δ̄o* − δ̄o) (and the Hertz force) leave the float range."""
    with pytest.raises(InputError, match="beyond the float range"):
        getattr(laws, law)(-1.7e308, mu=1.0)
