"""The GW integrator against adaptive quadrature, its limits, the surface inputs and the CLI."""

import json
import subprocess
import sys

import numpy as np
import pytest
from scipy.integrate import quad

from fem_asperity import InputError
from fem_asperity.closed_forms.laws import PAPER_LAWS
from fem_asperity.closed_forms.lj import bradley_force
from fem_asperity.path.curve import curve_from_columns
from gw.integrate import WINDOW, strength, totals
from gw.laws import PaperLaw, TabulatedLaw
from gw.surface import MCCOOL_MIN, RoughSurface, height_pdf, omega_mccool, theta, xi

CASES = [(0.1, 0.2, 1.0), (0.3, 0.05, 1.0), (0.49, 1.0, 0.2), (1.0, 6.667, 0.9),
         (10.0, 6.667, 0.5), (46.9, 6.67, 0.3), (0.3, 500.0, 1.0), (2.0, 100.0, 0.99)]


def adaptive(law, surface, d, column):
    """F̄ or S̄ by scipy's adaptive quadrature over z̃, split at the breakpoints, ±(WINDOW+3)/ω."""
    zeta, omega = surface.zeta, surface.omega
    values = getattr(law, column)
    lo, hi = -(WINDOW + 3) / omega, (WINDOW + 3) / omega
    cuts = sorted([lo, hi] + [d - b / zeta for b in law.breakpoints if lo < d - b / zeta < hi])
    return sum(quad(lambda z: values(zeta * (d - z)) * height_pdf(z, omega), a, b,
                    epsabs=0.0, epsrel=1e-13, limit=500)[0] for a, b in zip(cuts[:-1], cuts[1:]))


@pytest.mark.filterwarnings("ignore::scipy.integrate.IntegrationWarning")
@pytest.mark.parametrize("mu, zeta, omega", CASES)
def test_totals_match_adaptive_quadrature_to_1e8(mu, zeta, omega):
    law, surface = PaperLaw(mu), RoughSurface(zeta, omega)
    d = np.array([-1.0, 0.5, 2.0, 4.0, 8.0])
    force, area = totals(law, surface, d)
    for i, di in enumerate(d):
        assert force[i] == pytest.approx(adaptive(law, surface, di, "force"), rel=1e-8)
        assert area[i] == pytest.approx(adaptive(law, surface, di, "area"), rel=1e-8, abs=1e-300)


def test_smooth_surface_limit_is_the_single_asperity():
    """σ → 0 (ζ → 0 at fixed σ-scaled δ̄o = ζ d̃): F̄ → P̄(δ̄o), S̄ → Ā(δ̄o)."""
    zeta, delta = 1e-4, np.array([0.5, 1.2, 3.0])
    law = PaperLaw(0.3)
    force, area = totals(law, RoughSurface(zeta, 1.0), delta / zeta)
    np.testing.assert_allclose(force, law.force(delta), rtol=1e-6)
    np.testing.assert_allclose(area, law.area(delta), rtol=1e-6, atol=1e-9)


def test_strength_finds_the_deepest_minimum():
    law, surface = PaperLaw(1.0), RoughSurface(6.67, 0.9)
    found = strength(law, surface)
    d = np.linspace(found.d_at_max - 0.5, found.d_at_max + 0.5, 2001)
    dense = totals(law, surface, d)[0]
    assert found.f_max >= -dense.min() - 1e-12
    assert found.f_max == pytest.approx(-dense.min(), rel=1e-6)


def test_strength_tends_to_jkr_at_large_mu_and_small_roughness():
    """μ → ∞, ζ ≪ μ: every asperity pulls off at −P̄off → 0.75 (JKR)."""
    found = strength(PaperLaw(1e4), RoughSurface(0.01, 1.0))
    assert found.f_max == pytest.approx(-PAPER_LAWS.p_max(1e4), rel=1e-3)
    assert found.f_max == pytest.approx(0.75, abs=2e-3)


def test_tabulated_law_reproduces_its_samples_and_extends():
    delta = 1.0 + 39.0 * np.linspace(1.0, 0.0, 200) ** 2  # dense where P̄ is steep
    force, area = bradley_force(delta), np.zeros_like(delta)
    approach = curve_from_columns(delta, delta, force, area, area, np.ones(200, bool),
                                  np.zeros(200, int))
    law = TabulatedLaw(0.1, approach)
    np.testing.assert_allclose(law.force(delta), force, rtol=1e-12)
    assert law.force(np.array([60.0]))[0] == pytest.approx(bradley_force(60.0))
    deep = law.force(np.array([0.9, 0.5]))
    assert deep[0] > force[-1] - 1e-3 and deep[1] > deep[0]  # Hertz continuation rises
    mid = 0.5 * (delta[1:] + delta[:-1])
    true_error = np.abs(law.force(mid) - bradley_force(mid)).max()
    assert true_error <= law.interpolation_error < 1e-3


def test_surface_inputs():
    assert omega_mccool(0.05) == pytest.approx(np.sqrt(1 - 3.717e-4 / 0.05**2))
    with pytest.raises(InputError, match="McCool"):
        omega_mccool(MCCOOL_MIN)
    with pytest.raises(InputError):
        RoughSurface(zeta=1.0, omega=1.5)
    s = RoughSurface.from_physical(sigma=2e-9, radius=1e-6, density=2e13, eps=0.3e-9)
    assert s.zeta == pytest.approx(2 / 0.3) and 0 < s.omega < 1
    assert theta(zeta=8.0, mu=2.0) == pytest.approx(8.0)
    assert xi(zeta=3.0, mu=2.0) == pytest.approx(1.0)


def gw_cli(*args):
    return subprocess.run([sys.executable, "-m", "gw", *args], capture_output=True, text=True)


def test_cli_fmax_and_curve_json():
    done = gw_cli("fmax", "--mu", "1", "--zeta", "6.67", "--omega", "0.9", "--json")
    assert done.returncode == 0, done.stderr
    row = json.loads(done.stdout)
    assert set(row) == {"mu", "zeta", "omega", "law", "f_max", "d_at_max"}
    expected = strength(PaperLaw(1.0), RoughSurface(6.67, 0.9))
    assert row["f_max"] == pytest.approx(expected.f_max, rel=1e-12)
    done = gw_cli("curve", "--mu", "10", "--zeta", "2", "--sigma-r-eta", "0.05", "--d", "0",
                  "4", "--points", "9", "--json")
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout)
    assert len(out["d"]) == len(out["F"]) == len(out["S"]) == 9
    assert out["omega"] == pytest.approx(omega_mccool(0.05))


@pytest.mark.parametrize("args", [
    ["fmax", "--mu", "1"], ["fmax", "--mu", "-1", "--zeta", "1"],
    ["fmax", "--mu", "1", "--zeta", "1", "--sigma-r-eta", "0.01"],
    ["fmax", "--mu", "1", "--zeta", "1", "--omega", "0.5", "--sigma-r-eta", "0.05"],
    ["fmax", "--mu", "1", "--zeta", "1", "--law", "fitted"], ["fmax", "--sigma", "1e-9"],
    ["curve", "--mu", "1", "--zeta", "1", "--points", "1"],
    ["curve", "--mu", "1", "--zeta", "6", "--d", "1e307", "1e308", "--points", "3"],
    ["fmax", "--sigma", "2e-9", "--eps", "3e-10", "--radius", "1e-6", "--density", "2e13",
     "--estar", "1e9", "--work-of-adhesion", "0.05", "--omega", "0.5"],  # omega is eq. 20's
])
def test_cli_bad_input_is_one_line_exit_2(args):
    done = gw_cli(*args)
    assert done.returncode == 2
    assert len(done.stderr.strip().splitlines()) == 1, done.stderr
