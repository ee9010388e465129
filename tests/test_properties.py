"""Property-based tests (hypothesis) of the closed forms, the scales and the GW integrals, drawn
over their supported input ranges: finite results, bounds, monotonicity, limits and round trips.

Each property is checked against an expression of its own (a factorisation, a numerical integral,
a scaling law, a normal-distribution identity, a transcription by hand), not by calling the
package's formula again. The examples are derandomised: every run draws the same ones.
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad
from scipy.stats import norm

from fem_asperity import PAPER_LAWS, InputError, Scales, effective_modulus, tabor_parameter
from fem_asperity.closed_forms import reference as ref
from fem_asperity.closed_forms.laws import MU_MAX, wu_pull_off
from fem_asperity.closed_forms.lj import MAX_TENSION, bradley_force, traction
from fem_asperity.closed_forms.scales import ADHESION_RANGE, LENGTH_RANGE, MODULUS_RANGE
from fem_asperity.plumbing.checks import DERJAGUIN_WARN
from gw import PaperLaw, RoughSurface, strength, totals
from gw.integrate import D_MAX, RATIO_MAX, separation_range

PROPERTY = settings(max_examples=50, deadline=None, database=None, derandomize=True)
C_OFF = 1.98  # the paper's constant of eq. 2


def log_uniform(lo, hi):
    """Floats inside (lo, hi) by a relative 2e-9 at least, uniform in log10."""
    return st.floats(math.log10(lo) + 1e-9, math.log10(hi) - 1e-9).map(lambda e: 10.0**e)


def pairs(strategy):
    """Two distinct draws, smaller first."""
    return st.tuples(strategy, strategy).filter(lambda p: p[0] != p[1]).map(sorted)


MU = log_uniform(1e-50, MU_MAX)  # the laws take (0, MU_MAX); the GW integrals μ > 1e-50
OMEGA = st.floats(0.05, 1.0)


def hand_bradley(d):
    """Eq. 8 by hand: (δ⁻⁸ − 4δ⁻²)/3."""
    return (d**-8 - 4.0 * d**-2) / 3.0


def hand_wu(mu):
    """Eq. 2 rewritten: −(1/8)(7 + (1 − k)/(1 + k)) = −1 + k/(4(1 + k)), k = c μ^(3/2)."""
    k = C_OFF * mu**1.5
    return -1.0 + k / (4.0 * (1.0 + k))


# --- the paper's laws ---------------------------------------------------------------------------


@PROPERTY
@given(pairs(log_uniform(1e-300, MU_MAX)))
def test_wu_pull_off_runs_from_dmt_to_jkr_and_rises_with_mu(mus):
    lo, hi = (PAPER_LAWS.p_max(m) for m in mus)
    for mu, p in zip(mus, (lo, hi)):
        k = C_OFF * mu**1.5
        assert -1.0 <= p <= -0.75
        assert p == pytest.approx(hand_wu(mu), rel=1e-14, abs=1e-15)
        assert p + 1.0 <= k / 4.0 + 1e-15  # DMT end, μ → 0: P̄max + 1 ≤ k/4
        assert 4.0 * k * (-0.75 - p) <= 1.0 + 4.0 * k * 1e-15  # JKR end: −3/4 − P̄max ≤ 1/(4k)
    assert lo <= hi


@PROPERTY
@given(log_uniform(1e-300, MU_MAX), st.floats(0.0, 1e3))
def test_wu_pull_off_stays_between_dmt_and_jkr_for_any_refitted_constant(mu, c_off):
    p = wu_pull_off(mu, c_off)
    assert math.isfinite(p) and -1.0 <= p <= -0.75


@PROPERTY
@given(log_uniform(1e-9, MU_MAX), pairs(log_uniform(1e-3, 1e3)))
def test_force_below_delta_oc_is_p_max_plus_hertz(mu, steps):
    """Below δ̄oc the force rises from P̄max as (δ̄oc − δ̄o)^(3/2) (eqs. 16, 18): four times the
    depth, eight times the rise; and it never falls below P̄max."""
    doc, p = PAPER_LAWS.delta_oc(mu), PAPER_LAWS.p_max(mu)
    deep = doc - mu * np.array(steps)
    depth = doc - deep  # exact (Sterbenz) where the step is small beside δ̄oc
    rise = PAPER_LAWS.force(deep, mu=mu) - p
    assert np.all(np.isfinite(rise)) and np.all(rise > 0.0)
    assert rise[1] / rise[0] == pytest.approx((depth[1] / depth[0]) ** 1.5, rel=1e-9)


@PROPERTY
@given(log_uniform(1e-50, MU_MAX), pairs(st.floats(0.0, 1e3)))
def test_force_above_delta_oc_is_bradley_and_never_below_p_max(mu, gaps):
    """Above δ̄oc: Bradley's law, scaled to meet P̄max at δ̄oc without jump-in (eq. 9), as it is
    with one (eq. 14); tensile, weakening with distance, never below P̄max."""
    doc, p = PAPER_LAWS.delta_oc(mu), PAPER_LAWS.p_max(mu)
    # off δ̄oc itself by 1e-12: with a jump-in P̄ jumps there, and δ̄oc of an array of μ can differ
    # from that of the scalar by an ulp (numpy's and Python's powers), flipping P̄(δ̄oc)
    far = doc * (1.0 + 1e-12) + np.array(gaps)
    f = PAPER_LAWS.force(far, mu=mu)
    scale = 1.0 if mu >= 0.5 else p / hand_bradley(doc)
    np.testing.assert_allclose(f, scale * hand_bradley(far), rtol=1e-12)
    assert p - 1e-15 <= f[0] <= f[1] <= 0.0
    if mu < 0.5:  # continuous at δ̄oc
        assert PAPER_LAWS.force(doc, mu=mu) == pytest.approx(p, rel=1e-12)


@PROPERTY
@given(log_uniform(1e-300, MU_MAX), pairs(st.floats(-1e6, 1e6)))
def test_area_is_zero_above_first_contact_and_grows_by_pi_below(mu, deltas):
    """Ā = 0 above δ̄o*, slope −π below (eqs. 11, 15, 17, 19), plus the jump πā_c² with
    ā_c = 0.83 (μ − 0.19)^½ (eq. 6) where the approach jumps in."""
    star = PAPER_LAWS.delta_o_star(mu)
    jump = math.pi * 0.83**2 * (mu - 0.19) if mu >= 0.5 else 0.0
    d = star + np.array(deltas)
    a = PAPER_LAWS.area(d, mu=mu)
    expected = np.where(d < star, jump + math.pi * (star - d), 0.0)
    np.testing.assert_allclose(a, expected, rtol=1e-12, atol=1e-12 * (jump + star))
    assert a[0] >= a[1] >= 0.0


@PROPERTY
@given(log_uniform(1e-300, MU_MAX))
def test_events_separations_follow_eqs_7_10_12_13(mu):
    ev = PAPER_LAWS.events(mu)
    assert ev.jump_in == (mu >= 0.5) and ev.p_max == pytest.approx(hand_wu(mu), abs=1e-15)
    if mu < 0.5:
        assert ev.delta_oc == pytest.approx(1.0 + 0.922 * mu, rel=1e-15)
        assert ev.delta_o_star == pytest.approx(1.0 + 2.116 * mu**1.5, rel=1e-15)
        assert math.isnan(ev.x_oc)
    else:
        x = -0.3 + 2.2 * mu**0.4
        h = math.sqrt(2.0) * math.pi * mu**1.5 * (x**-2.5 - 2145.0 / 4096.0 * x**-8.5)
        assert ev.x_oc == pytest.approx(x, rel=1e-14) and x > 0.0
        assert ev.delta_oc == ev.delta_o_star == pytest.approx(x + h, rel=1e-12)
    assert ev.delta_oc >= 1.0 and ev.delta_o_star >= 1.0


OVERFLOWS = {  # inputs that pass the range checks, results beyond the largest float
    "law-force-tiny-mu": lambda: PAPER_LAWS.force(0.5, mu=1e-300),  # (0.5/μ)^1.5: RuntimeWarning
    "law-force-deep": lambda: PAPER_LAWS.force(-1e300, mu=1e-12),  # RuntimeWarning
    "bradley-tiny-gap": lambda: bradley_force(1e-40),  # δ̄⁻⁸ = 1e320: OverflowError
}


@pytest.mark.parametrize("call", OVERFLOWS.values(), ids=OVERFLOWS.keys())
def test_a_result_beyond_the_float_range_is_refused_not_returned(call):
    """The result guard refuses them with one clear InputError (they overflowed with a
    RuntimeWarning or an OverflowError)."""
    with pytest.raises(InputError, match="beyond the float range"):
        call()


# --- the LJ law and Bradley's rigid sphere ------------------------------------------------------


@PROPERTY
@given(log_uniform(1e-2, 1e4))
def test_bradley_force_has_its_single_minimum_minus_one_at_the_lj_equilibrium(d):
    """P̄ + 1 = (s − 1)²(s² + 2s + 3)/3 with s = δ̄⁻² ≥ 0: the minimum −1 (2πRΔγ) at δ̄ = 1 (ε),
    where the LJ traction vanishes, and nowhere else."""
    s = d**-2
    gap = bradley_force(d) + 1.0
    assert gap == pytest.approx((s - 1.0) ** 2 * (s * s + 2.0 * s + 3.0) / 3.0, rel=1e-9,
                                abs=1e-15)
    assert gap >= 0.0 and bradley_force(1.0) == -1.0 and traction(1.0) == 0.0


@PROPERTY
@given(pairs(log_uniform(1e-2, 1e4)))
def test_bradley_force_falls_to_its_minimum_then_rises(ds):
    f0, f1 = bradley_force(ds[0]), bradley_force(ds[1])
    if ds[1] <= 1.0:
        assert f0 >= f1
    elif ds[0] >= 1.0:
        assert f0 <= f1 <= 0.0


@PROPERTY
@given(log_uniform(0.3, 1e3))
def test_bradley_force_is_the_work_of_the_lj_traction_beyond_it(d):
    """Derjaguin: the rigid sphere's force (2πRΔγ) is ∫_δ̄^∞ p̄ dh̄ of the LJ traction (Δγ/ε),
    and the traction never pulls harder than MAX_TENSION = −16/(9√3)."""
    work = sum(quad(lambda h: traction(h), a, b, epsabs=1e-15, epsrel=1e-11, limit=200)[0]
               for a, b in ((d, 2.0 * d + 2.0), (2.0 * d + 2.0, np.inf)))
    assert bradley_force(d) == pytest.approx(work, rel=1e-9, abs=1e-14)
    assert traction(d) >= MAX_TENSION and MAX_TENSION == pytest.approx(-16 / (9 * math.sqrt(3)))


@PROPERTY
@given(log_uniform(1e-30, 1e300))
def test_bradley_force_is_finite_wherever_it_is_resolved(d):
    assert math.isfinite(bradley_force(d))


# --- the classical references -------------------------------------------------------------------


@PROPERTY
@given(log_uniform(1e-6, 1e8), log_uniform(1e-3, 1e3))
def test_jkr_force_never_below_its_pull_off(mu, fraction):
    """(2/3π)u² − √(2/π)u with u = ā^(3/2) μ^(-3/4) is least, −3/4, at u = (3π/4)√(2/π)."""
    off = ref.jkr_pull_off(mu=mu)
    u = (3.0 * math.pi / 4.0) * math.sqrt(2.0 / math.pi)
    assert off.radius == pytest.approx(u ** (2.0 / 3.0) * math.sqrt(mu), rel=1e-12)
    assert ref.jkr_force(radius=off.radius, mu=mu) == pytest.approx(-0.75, rel=1e-12)
    assert ref.jkr_force(radius=fraction * off.radius, mu=mu) >= -0.75 - 1e-12


@PROPERTY
@given(pairs(log_uniform(1e-5, 1e7)))
def test_maugis_dugdale_pull_off_runs_from_dmt_to_jkr(mus):
    lo, hi = (ref.maugis_dugdale_pull_off(mu=m).force for m in mus)
    assert -1.0 - 1e-9 <= lo <= hi + 1e-9 and hi <= -0.75 + 1e-9


# --- inputs and scales --------------------------------------------------------------------------


@st.composite
def physical(draw):
    """E* [Pa], Δγ [J/m²], ε and R [m] inside their ranges, with R/ε ≥ 300 (no Derjaguin
    warning)."""
    e_star = draw(log_uniform(*MODULUS_RANGE))
    dgamma = draw(log_uniform(*ADHESION_RANGE))
    eps = draw(log_uniform(LENGTH_RANGE[0], LENGTH_RANGE[1] / DERJAGUIN_WARN / 1.001))
    radius = draw(log_uniform(eps * DERJAGUIN_WARN, LENGTH_RANGE[1]))
    return e_star, dgamma, eps, radius


@PROPERTY
@given(physical())
def test_tabor_parameter_is_eq_1_in_logarithms(inputs):
    e_star, dgamma, eps, radius = inputs
    mu = tabor_parameter(E_star=e_star, dgamma=dgamma, eps=eps, R=radius)
    logs = math.log(radius) + 2 * math.log(dgamma) - 2 * math.log(e_star) - 3 * math.log(eps)
    assert math.isfinite(mu) and mu > 0.0
    assert 3.0 * math.log(mu) == pytest.approx(logs, abs=1e-12 * max(1.0, abs(logs)))


@PROPERTY
@given(physical(), log_uniform(0.5, 100.0))
def test_scales_round_trip_physical_dimensionless_physical(inputs, gap):
    """Scales → μ → Scales.for_mu gives back E* and Δγ; the notes' Δγ/E* = μ^(3/2) √(ε³/R);
    the LJ traction at a gap h is the traction scale times the dimensionless one at h/ε."""
    e_star, dgamma, eps, radius = inputs
    s = Scales(E_star=e_star, dgamma=dgamma, eps=eps, R=radius)
    back_e = Scales.for_mu(s.mu, eps=eps, R=radius, dgamma=dgamma)
    back_g = Scales.for_mu(s.mu, eps=eps, R=radius, E_star=e_star)
    assert back_e.E_star == pytest.approx(e_star, rel=1e-12)
    assert back_g.dgamma == pytest.approx(dgamma, rel=1e-12)
    assert back_e.mu == pytest.approx(s.mu, rel=1e-12)
    assert dgamma / e_star == pytest.approx(s.mu**1.5 * math.sqrt(eps**3 / radius), rel=1e-12)
    assert s.length_r**2 == pytest.approx(s.area, rel=1e-14)
    assert s.force == pytest.approx(2.0 * math.pi * radius * dgamma, rel=1e-14)
    h = gap * s.length_z  # a physical gap, through the dimensionless law and back
    assert traction(h, dgamma=dgamma, eps=eps) == pytest.approx(
        s.traction * traction(h / s.length_z), rel=1e-12, abs=1e-12 * s.traction)


@PROPERTY
@given(log_uniform(*MODULUS_RANGE), st.floats(-0.99, 0.49), log_uniform(*MODULUS_RANGE),
       st.floats(-0.99, 0.49))
def test_effective_modulus_is_the_series_of_two_compliances(e1, nu1, e2, nu2):
    one, two = e1 / (1 - nu1**2), e2 / (1 - nu2**2)
    both = effective_modulus(E1=e1, nu1=nu1, E2=e2, nu2=nu2)
    assert both == pytest.approx(effective_modulus(E1=e2, nu1=nu2, E2=e1, nu2=nu1), rel=1e-14)
    assert both == pytest.approx(one * two / (one + two), rel=1e-12)
    assert min(one, two) / 2.0 * (1 - 1e-14) <= both <= min(one, two) * (1 + 1e-14)
    assert effective_modulus(E1=e1, nu1=nu1) == pytest.approx(one, rel=1e-14)


# --- GW rough surface ---------------------------------------------------------------------------


@st.composite
def gw_inputs(draw, mu=MU, zeta_lo=1e-300, headroom=1.0):
    """(μ, ζ, ω) with ζ/μ and 1/μ below RATIO_MAX (ζ/μ below RATIO_MAX/headroom)."""
    m = draw(mu)
    z = draw(log_uniform(zeta_lo, min(RATIO_MAX / headroom * m, 1e300)))
    return m, z, draw(OMEGA)


@PROPERTY
@given(gw_inputs(), st.floats(-20.0, 40.0), st.floats(-D_MAX, D_MAX, exclude_min=True,
                                                      exclude_max=True), st.booleans())
def test_totals_are_finite_and_never_below_the_single_asperity_pull_off(inputs, near, far, pick):
    """F̄ is a Gaussian average of P̄ ≥ P̄max: never below P̄max (2πRΔγη A₀ units); S̄ ≥ 0."""
    mu, zeta, omega = inputs
    law = PaperLaw(mu)
    d = far if pick else min(max(law.breakpoints[0] / zeta + near / omega, -0.99 * D_MAX),
                             0.99 * D_MAX)
    force, area = totals(law, RoughSurface(zeta, omega), d)
    assert np.isfinite(force[0]) and np.isfinite(area[0])
    assert force[0] >= PAPER_LAWS.p_max(mu) * (1.0 + 1e-9) and area[0] >= 0.0


@PROPERTY
@given(gw_inputs(mu=log_uniform(1e-6, 1e8), zeta_lo=1e-3, headroom=20.0),
       st.floats(-10.0, 30.0))
def test_totals_scale_with_omega(inputs, near):
    """φ̃(z̃; ω) = ω φ̃(ω z̃; 1), so F̄ and S̄ at (ζ, ω, d̃) are those at (ζ/ω, 1, ω d̃)."""
    mu, zeta, omega = inputs
    law = PaperLaw(mu)
    d = min(law.breakpoints[0] / zeta + near / omega, 0.99 * D_MAX)
    f, s = totals(law, RoughSurface(zeta, omega), d)
    f1, s1 = totals(law, RoughSurface(zeta / omega, 1.0), omega * d)
    scale = abs(PAPER_LAWS.p_max(mu))
    assert f[0] == pytest.approx(f1[0], rel=1e-9, abs=1e-12 * scale)
    assert s[0] == pytest.approx(s1[0], rel=1e-9, abs=1e-300)


@PROPERTY
@given(log_uniform(0.1, 47.0), log_uniform(0.05, 500.0), st.floats(0.2, 1.0),
       st.floats(-6.0, 6.0))
def test_contact_area_total_is_a_normal_partial_expectation(mu, zeta, omega, u):
    """With Ā = π(ā_j² + δ̄o* − δ̄o) below δ̄o*, S̄ = π[ā_j² Q(u) + (ζ/ω)(φ(u) − u Q(u))] at
    u = ω(d̃ − δ̄o*/ζ) (φ, Q: the standard normal density and tail); over the range where the
    integrator is checked against adaptive quadrature (μ 0.1-47, ζ 0.05-500, ω 0.2-1)."""
    law = PaperLaw(mu)
    star = PAPER_LAWS.delta_o_star(mu)
    jump = 0.83**2 * (mu - 0.19) if mu >= 0.5 else 0.0
    d = star / zeta + u / omega
    expected = math.pi * (jump * norm.sf(u) + zeta / omega * (norm.pdf(u) - u * norm.sf(u)))
    area = totals(law, RoughSurface(zeta, omega), d)[1][0]
    assert area == pytest.approx(expected, rel=1e-8)


@PROPERTY
@given(gw_inputs(zeta_lo=1e-12))
def test_strength_is_positive_finite_interior_and_below_the_pull_off(inputs):
    """0 < F̄max ≤ −P̄max (F̄ ≥ P̄max), and F̄ is no lower on either side of the d̃ found (to the
    integrator's 1e-10: on JKR's plateau, large μ and small ζ, F̄ is flat to that), wherever the
    search range fits in |d̃| < D_MAX; refused up front where it does not."""
    mu, zeta, omega = inputs
    law, surface = PaperLaw(mu), RoughSurface(zeta, omega)
    lo, hi = separation_range(law, surface)
    if not hi < D_MAX:
        with pytest.raises(InputError, match="supported"):
            strength(law, surface)
        return
    found = strength(law, surface)
    assert math.isfinite(found.d_at_max) and 0.0 < found.f_max
    assert found.f_max <= -PAPER_LAWS.p_max(mu) * (1.0 + 1e-9)
    h = 1e-3 * (hi - lo)
    near = totals(law, surface, found.d_at_max + np.array([-h, h]))[0]
    assert np.all(near >= -found.f_max * (1.0 + 1e-10))


@PROPERTY
@given(log_uniform(1e-3, 1e4), pairs(log_uniform(1e-2, 1e3)))
def test_strength_falls_as_the_surface_roughens(mu, zetas):
    """Fuller-Tabor: at a fixed μ (and ω = 1) a rougher surface (larger ζ = σ/ε) adheres less."""
    law = PaperLaw(mu)
    smooth, rough = (strength(law, RoughSurface(z, 1.0)).f_max for z in zetas)
    assert rough <= smooth * (1.0 + 1e-9)


@PROPERTY
@given(log_uniform(0.02, 1e4))  # below 0.0101, δ̄oc/ζ > D_MAX: refused
def test_strength_of_a_smooth_surface_is_the_single_asperity_pull_off(mu):
    """σ ≪ ε μ (θ = (ζ/μ)^1.5 = 1e-6): every asperity pulls off at once, F̄max → −P̄max (eq. 2)."""
    found = strength(PaperLaw(mu), RoughSurface(1e-4 * mu, 1.0))
    assert found.f_max == pytest.approx(-hand_wu(mu), rel=1e-5)
