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
from fem_asperity.curves.curve import curve_from_columns
from gw.integrate import D_MAX, RATIO_MAX, WINDOW, separation_range, strength, totals
from gw.laws import CorrectedLaw, PaperLaw, TabulatedLaw
from gw.shared_ground import shared_ground
from gw.surface import MCCOOL_MIN, RoughSurface, height_pdf, omega_mccool, theta, xi

CASES = [(0.1, 0.2, 1.0), (0.3, 0.05, 1.0), (0.49, 1.0, 0.2), (1.0, 6.667, 0.9),
         (10.0, 6.667, 0.5), (46.9, 6.67, 0.3), (0.3, 500.0, 1.0), (2.0, 100.0, 0.99)]


def adaptive(law, surface, d, column, *, above=0.0):
    """F̄ or S̄ by scipy's adaptive quadrature over z̃, split at the breakpoints, ±(WINDOW+3)/ω
    (up to `above`/ω higher: the asperities in contact when d̃ nears 12/ω)."""
    zeta, omega = surface.zeta, surface.omega
    values = getattr(law, column)
    lo, hi = -(WINDOW + 3) / omega, (WINDOW + 3 + above) / omega
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


@pytest.mark.filterwarnings("ignore::scipy.integrate.IntegrationWarning")
@pytest.mark.parametrize("mu, zeta, omega", [
    (1e-20, 1.0, 1.0),  # stiff law: F̄max found 0.7% too large at d̃ = 12.8 (heights cut at 12)
    (1e-25, 1.0, 1.0),  # F̄max beyond the search range: found at its end, d̃ = 13, 21% too large
    (1e-25, 1.0, 0.3),
    (1.0, 1e10, 1.0),  # rough: F̄max found at d̃ = 12.0, the end of the height window
    (1.0, 1e-5, 1.0),  # smooth: F̄max below the search range's lower end (JKR-like plateau)
])
def test_strength_is_an_interior_maximum_of_the_adaptive_quadrature(mu, zeta, omega):
    """F̄max by `strength` against F̄ by adaptive quadrature over the heights up to 15/ω above
    the contact edge z̃c = d̃ − δ̄oc/ζ: the quadrature's F̄ is lowest at the d̃ found, not on
    either side of it, and equals −F̄max."""
    law, surface = PaperLaw(mu), RoughSurface(zeta, omega)
    found = strength(law, surface)
    d = found.d_at_max + np.array([-0.1, 0.0, 0.1]) / omega
    edge = d - min(law.breakpoints) / zeta
    ref = [adaptive(law, surface, di, "force", above=max(e * omega, 0.0)) for di, e in zip(d, edge)]
    assert ref[1] < min(ref[0], ref[2])
    assert found.f_max == pytest.approx(-ref[1], rel=1e-8)


@pytest.mark.parametrize("omega", [0.0, -1.0, 1.5])
def test_omega_is_refused_outside_its_range_and_one_is_in_it(omega):
    """ω in (0, 1]: 1 (GW's default) is taken, and the refusal says so."""
    assert RoughSurface(2.0, 1.0).omega == 1.0
    with pytest.raises(InputError, match=r"omega must be in \(0, 1\]"):
        RoughSurface(2.0, omega)


def test_strength_refuses_a_maximum_it_cannot_bracket():
    """A law whose pull grows without end (F̄ keeps falling with d̃): no maximum to return."""

    class Endless:
        mu, name, breakpoints = 1.0, "endless", (1.0,)

        @staticmethod
        def force(delta):
            return -np.arctan(delta)

        @staticmethod
        def area(delta):
            return np.zeros(np.shape(delta))

    with pytest.raises(InputError, match="not bracketed"):
        strength(Endless(), RoughSurface(1.0, 1.0))


@pytest.mark.parametrize("mu, zeta, match", [
    (1.0, 1e300, "zeta/mu and 1/mu must be < "),  # F̄max was -0.0 (with overflow warnings)
    (1e-300, 1.0, "zeta/mu and 1/mu must be < "),  # repulsion (ζ/μ)^1.5 overflowed: inf - inf
    (1e-60, 1e-20, "zeta/mu and 1/mu must be < "),  # P̄ ∝ μ^(-3/2) at δ̄o = 0: 1e90
    (1.0, 1e-300, "supported [|]d/sigma[|] < "),  # searched at d̃ = 3e300, refused as "d"
])
def test_stiff_or_far_inputs_are_refused_up_front(mu, zeta, match):
    law, surface = PaperLaw(mu), RoughSurface(zeta, 1.0)
    with pytest.raises(InputError, match=match):
        strength(law, surface)
    assert RATIO_MAX == 1e50 and D_MAX == 1e6  # the ranges named in the messages


@pytest.mark.parametrize("mu, zeta", [(1.0, 0.99e50), (1.01e-50, 1.0)])
def test_strength_at_the_ends_of_the_supported_range_is_positive_and_interior(mu, zeta):
    law, surface = PaperLaw(mu), RoughSurface(zeta, 1.0)
    found = strength(law, surface)
    assert np.isfinite(found.f_max) and found.f_max > 0.0
    assert found.d_at_max > separation_range(law, surface)[1]  # beyond the first search range
    near = totals(law, surface, found.d_at_max + np.array([-0.05, 0.05]))[0]
    assert -found.f_max < near.min()
    force = totals(law, surface, np.linspace(-3.0, 40.0, 9))[0]
    assert np.all(np.isfinite(force))


def bradley_law(delta):
    """A `TabulatedLaw` at μ = 0.1 through Bradley's rigid force at `delta`, zero area."""
    force, area = bradley_force(delta), np.zeros_like(delta)
    approach = curve_from_columns(delta, delta, force, area, area, np.ones(delta.size, bool),
                                  np.zeros(delta.size, int))
    return TabulatedLaw(0.1, approach)


def test_tabulated_law_reproduces_its_samples_and_extends():
    delta = 1.0 + 39.0 * np.linspace(1.0, 0.0, 200) ** 2  # dense where P̄ is steep
    force = bradley_force(delta)
    law = bradley_law(delta)
    np.testing.assert_allclose(law.force(delta), force, rtol=1e-12)
    assert law.force(np.array([60.0]))[0] == pytest.approx(bradley_force(60.0))
    deep = law.force(np.array([0.9, 0.5]))
    assert deep[0] > force[-1] - 1e-3 and deep[1] > deep[0]  # Hertz continuation rises
    mid = 0.5 * (delta[1:] + delta[:-1])
    true_error = np.abs(law.force(mid) - bradley_force(mid)).max()
    assert true_error <= law.interpolation_error < 1e-3


@pytest.mark.parametrize("law", [PaperLaw(1.0), PaperLaw(0.3, name="continuous"),
                                 bradley_law(np.linspace(40.0, 1.0, 50))],
                         ids=["paper", "paper-continuous", "tabulated"])
@pytest.mark.parametrize("method", ["force", "area"])
@pytest.mark.parametrize("delta", [np.nan, np.inf, -np.inf, [2.0, np.nan], [[1.0], [-np.inf]]])
def test_laws_refuse_a_non_finite_separation_as_the_closed_forms_do(law, method, delta):
    """PaperLaw(1).force([nan]) returned [nan]; PAPER_LAWS refuses it naming delta_o."""
    with pytest.raises(InputError, match="delta_o must be finite"):
        PAPER_LAWS.force(delta, mu=1.0) if method == "force" else PAPER_LAWS.area(delta, mu=1.0)
    with pytest.raises(InputError, match="delta_o must be finite"):
        getattr(law, method)(delta)


@pytest.mark.parametrize("law", [PaperLaw(1e-3), bradley_law(np.linspace(40.0, 1.0, 50))],
                         ids=["paper", "tabulated"])
@pytest.mark.parametrize("method, deep", [("force", -1e300), ("area", -1.7e308)])
def test_laws_refuse_a_result_beyond_the_float_range(law, method, deep):
    """δ̄o = −1e300 at μ = 1e-3: Hertz's ((δ̄oc − δ̄o)/μ)^(3/2) ≈ 1e454 was inf (with an overflow
    warning), as was π(δ̄o* − δ̄o) at −1.7e308; a finite δ̄o well inside gives a finite value."""
    with pytest.raises(InputError, match="beyond the float range"):
        getattr(law, method)(np.array([1.0, deep]))
    assert np.all(np.isfinite(getattr(law, method)(np.array([1.0, -1e100]))))


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


def test_cli_fmax_never_prints_negative_zero():
    """ζ = 1e300 printed f_max = -0 (exit 0); now refused in one line, naming the range."""
    done = gw_cli("fmax", "--mu", "1", "--zeta", "1e300", "--json")
    assert done.returncode == 2 and "-0.0" not in done.stdout
    assert done.stderr.strip().splitlines() == [
        "python -m gw: error: zeta/mu and 1/mu must be < 1e+50 for the GW integrals (the "
        "asperities' repulsion grows like (zeta/mu)^1.5); got zeta = 1e+300, mu = 1"]
    done = gw_cli("fmax", "--mu", "1e-25", "--zeta", "1", "--json")
    assert done.returncode == 0, done.stderr
    row = json.loads(done.stdout)
    assert row["f_max"] == pytest.approx(0.0066337425, rel=1e-8)
    assert row["d_at_max"] > separation_range(PaperLaw(1e-25), RoughSurface(1.0))[1]


def test_cli_fmax_and_curve_json():
    done = gw_cli("fmax", "--mu", "1", "--zeta", "6.67", "--omega", "0.9", "--json")
    assert done.returncode == 0, done.stderr
    row = json.loads(done.stdout)
    # the warning: the table of solved laws puts the paper's F̄max 64 % off at μ = 1
    assert set(row) == {"mu", "zeta", "omega", "law", "f_max", "d_at_max", "omega_reading",
                        "warning"}
    expected = strength(PaperLaw(1.0), RoughSurface(6.67, 0.9))
    assert row["f_max"] == pytest.approx(expected.f_max, rel=1e-12)
    done = gw_cli("curve", "--mu", "10", "--zeta", "2", "--sigma-r-eta", "0.05", "--d", "0",
                  "4", "--points", "9", "--json")
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout)
    assert len(out["d"]) == len(out["F"]) == len(out["S"]) == 9
    assert out["omega"] == pytest.approx(omega_mccool(0.05))
    # σRη given: GW's F̄ with the ground between summits counted once beside it
    shared = shared_ground(RoughSurface(2.0, out["omega"]), 0.05, np.array(out["d"]))
    assert np.array(out["F_once"]) == pytest.approx(np.array(out["F"]) + shared, abs=1e-12)


@pytest.mark.parametrize("args", [
    ["fmax", "--mu", "1"], ["fmax", "--mu", "-1", "--zeta", "1"],
    ["fmax", "--mu", "1", "--zeta", "1", "--sigma-r-eta", "0.01"],
    ["fmax", "--mu", "1", "--zeta", "1", "--omega", "0.5", "--sigma-r-eta", "0.05"],
    ["fmax", "--mu", "1", "--zeta", "1", "--law", "fitted"], ["fmax", "--sigma", "1e-9"],
    ["curve", "--mu", "1", "--zeta", "1", "--points", "1"],
    ["curve", "--mu", "1", "--zeta", "6", "--d", "1e307", "1e308", "--points", "3"],
    ["curve", "--mu", "1", "--zeta", "1e300", "--points", "3"],  # printed F as "-" (NaN)
    ["fmax", "--sigma", "2e-9", "--eps", "3e-10", "--radius", "1e-6", "--density", "2e13",
     "--estar", "1e9", "--work-of-adhesion", "0.05", "--omega", "0.5"],  # omega is eq. 20's
])
def test_cli_bad_input_is_one_line_exit_2(args):
    done = gw_cli(*args)
    assert done.returncode == 2
    assert len(done.stderr.strip().splitlines()) == 1, done.stderr


def test_physical_inputs_take_the_names_of_fem_asperity_and_the_old_ones(capsys):
    """--E-star/--dgamma/--R (fem_asperity's names) and --estar/--work-of-adhesion/--radius (gw's
    earlier ones) give the same answer."""
    import json

    from gw.__main__ import main

    common = ["fmax", "--sigma", "2e-9", "--eps", "3e-10", "--density", "2e13", "--json"]
    answers = []
    for names in (("--E-star", "--dgamma", "--R"), ("--estar", "--work-of-adhesion", "--radius")):
        pairs = zip(names, ("1e9", "0.05", "1e-6"))
        assert main(common + [item for pair in pairs for item in pair]) == 0
        answers.append(json.loads(capsys.readouterr().out))
    assert answers[0] == answers[1] and answers[0]["f_max"] > 0


def test_curve_in_si_and_the_two_bodies(capsys):
    """`gw curve` with physical inputs: d in m (d̃σ), F/A₀ in Pa (F̄ · 2πRΔγη) and the real
    contact area per nominal area (S̄ · Rηε); E1, ν1 of a body on a rigid one give the same as
    their E* = E1/(1 − ν1²)."""
    import json

    from gw.__main__ import main

    sigma, density, R, dgamma, eps = 2e-9, 2e13, 1e-6, 0.05, 3e-10
    common = ["curve", "--sigma", str(sigma), "--density", str(density), "--eps", str(eps),
              "--R", str(R), "--dgamma", str(dgamma), "--points", "5", "--json"]
    outputs = []
    for modulus in (["--E-star", str(1e9 / (1 - 0.3**2))], ["--E1", "1e9", "--nu1", "0.3"]):
        assert main(common + modulus) == 0
        outputs.append(json.loads(capsys.readouterr().out))
    row = outputs[0]
    assert outputs[1]["F"] == pytest.approx(row["F"], rel=1e-12)
    si, d, F, S = row["si"], *(np.array(row[k]) for k in "dFS")
    assert si["d_m"] == pytest.approx(d * sigma, rel=1e-12)
    assert si["F_Pa"] == pytest.approx(F * 2 * np.pi * R * dgamma * density, rel=1e-12)
    assert si["S_per_A0"] == pytest.approx(S * R * density * eps, rel=1e-12)


def test_fmax_below_omega_one_says_how_far_mccools_reading_is(capsys):
    """Eq. 21 as printed spreads the summits over σ/ω, McCool's σ_s = ωσ over ωσ: at ω = 0.6
    fmax says which it used and gives the other's F̄max, equal to the printed form at ω = 1
    with the summits' own ζ_s = ωζ (heights in σ_s, another route through the integrator)."""
    from gw.__main__ import main

    assert main(["fmax", "--mu", "1", "--zeta", "3", "--omega", "0.6", "--json"]) == 0
    out = capsys.readouterr()
    row = json.loads(out.out)
    reading = row["omega_reading"]
    direct = strength(PaperLaw(1.0), RoughSurface(3 * 0.6, 1.0))
    assert reading["f_max_other"] == pytest.approx(direct.f_max, rel=1e-6)
    assert reading["d_at_max_other"] == pytest.approx(direct.d_at_max * 0.6, rel=1e-4)
    assert reading["relative"] == pytest.approx(direct.f_max / row["f_max"] - 1.0, rel=1e-6)
    assert "McCool" in out.err and "as printed" in out.err
    assert main(["fmax", "--mu", "1", "--zeta", "3", "--json"]) == 0  # ω = 1: one reading
    assert "omega_reading" not in json.loads(capsys.readouterr().out)


def test_compare_puts_the_four_laws_side_by_side_and_warns(capsys, tmp_path, monkeypatch):
    """`fmax --compare`: paper, refit, corrected and solved F̄max with their differences from the
    solved one; the paper's and the corrected's equal their own integrals; the warning appears
    where the difference exceeds --warn-above and not otherwise (at μ = 1, ζ = 3 the paper's
    law is 56% weaker); with σRη, the solved law's F̄max with the ground counted once."""
    import json

    from gw.__main__ import main

    monkeypatch.setenv("ADHESION_CACHE", str(tmp_path))
    base = ["fmax", "--mu", "1", "--zeta", "3", "--accuracy", "draft", "--json"]
    assert main(["fmax", "--mu", "1", "--zeta", "3", "--json"]) == 0  # no --accuracy: refused
    plain = json.loads(capsys.readouterr().out)
    assert main(base + ["--compare"]) == 0
    out = capsys.readouterr()
    compared = json.loads(out.out)
    assert set(compared) >= {"paper", "refit", "corrected", "solved", "warning"}
    assert compared["paper"]["f_max"] == plain["f_max"]
    assert compared["corrected"]["f_max"] == strength(CorrectedLaw(1.0),
                                                      RoughSurface(3.0)).f_max
    assert compared["solved"]["relative_to_solved"] == 0.0
    assert 0 < compared["solved"]["law_interpolation_error_of_max_force"] < 0.01
    off = compared["paper"]["f_max"] / compared["solved"]["f_max"] - 1.0
    assert compared["paper"]["relative_to_solved"] == pytest.approx(off)
    assert abs(off) > 0.1 and "paper's law" in compared["warning"] and "warning" in out.err
    assert main(base + ["--compare", "--warn-above", "1"]) == 0
    assert json.loads(capsys.readouterr().out)["warning"] is None
    assert "shared_ground" not in compared  # no σRη: GW's summits share nothing
    # with σRη: the solved law's F̄max with the ground counted once, below GW's
    assert main(base + ["--compare", "--sigma-r-eta", "0.05"]) == 0
    out = capsys.readouterr()
    shared = json.loads(out.out)
    once = shared["shared_ground"]
    assert once["f_max"] < shared["solved"]["f_max"]
    assert once["relative"] == pytest.approx(once["f_max"] / shared["solved"]["f_max"] - 1)
    assert "note: with the solved law" in out.err


@pytest.mark.parametrize("args", [
    ["fmax", "--mu", "1", "--zeta", "3", "--warn-above", "0.2"],  # without --compare
    ["fmax", "--mu", "1", "--zeta", "3", "--compare", "--law", "refit"],
    ["fmax", "--mu", "1", "--zeta", "3", "--compare", "--warn-above", "-1"],
])
def test_compare_options_are_used_or_refused(args):
    done = gw_cli(*args)
    assert done.returncode == 2
    assert len(done.stderr.strip().splitlines()) == 1, done.stderr


def run_gw(capsys, args):
    """`python -m gw ARGS` in this process: (exit code, stdout, stderr lines)."""
    from fem_asperity.plumbing.cli import run
    from gw.__main__ import PROG, main

    try:
        code = run(main, PROG, args)
    except SystemExit as exc:  # argparse's usage errors
        code = exc.code
    out, err = capsys.readouterr()
    return code, out, err.strip().splitlines()


@pytest.fixture
def no_work(monkeypatch):
    """The refit, the solved curves (minutes) and `curve`'s integrals fail the test if they start:
    bad input must be refused before them (a paper's-law F_max, milliseconds, may come first)."""
    import gw.__main__

    def work(*_args, **_kwargs):
        raise AssertionError("work started before the input was checked")

    for name in ("stored_refit", "solved_law", "totals", "separation_range"):
        monkeypatch.setattr(gw.__main__, name, work)


@pytest.mark.parametrize("args, names", [
    # 1e8 points: a 164 GiB allocation, found only after the integrals ran.
    (["curve", "--mu", "1", "--zeta", "2", "--points", "100000000"], ("--points", "2 to 10000")),
    (["curve", "--mu", "1", "--zeta", "1", "--law", "bem", "--points", "1"], ("--points",)),
    # inf: reported as d = nan with two numpy warnings; nan, 1e307: named "d", not "--d".
    (["curve", "--mu", "1", "--zeta", "2", "--d", "inf", "1"], ("--d", "1e+06")),
    (["curve", "--mu", "1", "--zeta", "2", "--d", "nan", "1"], ("--d",)),
    (["curve", "--mu", "1", "--zeta", "2", "--d", "0", "1e307", "--law", "bem"], ("--d",)),
    # MIN >= MAX: accepted, the table printed from 5 down to 1 (or three times d = 1).
    (["curve", "--mu", "1", "--zeta", "2", "--d", "5", "1"], ("--d", "MIN < MAX")),
    (["curve", "--mu", "1", "--zeta", "2", "--d", "1", "1"], ("--d", "MIN < MAX")),
    # refitted (a minute) before the 1/mu check refused.
    (["fmax", "--mu", "1e-300", "--zeta", "1", "--compare"], ("1/mu", "1e+50")),
    (["fmax", "--mu", "1", "--zeta", "1e300", "--law", "bem"], ("zeta/mu", "1e+50")),
    # below the solvers' range: refused only after the refit.
    (["fmax", "--mu", "1e-5", "--zeta", "1", "--compare"], ("mu of a solved law", "[0.001,")),
    (["fmax", "--mu", "2e4", "--zeta", "1", "--law", "fem"], ("mu of a solved law",)),
    # the paper's F_max cannot be searched: refused only after the refit and the solved curve.
    (["fmax", "--mu", "1", "--zeta", "1e-300", "--compare"], ("d/sigma",)),
    (["fmax", "--mu", "1", "--zeta", "1", "--compare", "--warn-above", "0"], ("--warn-above",)),
    (["fmax", "--mu", "1", "--zeta", "1", "--compare", "--law", "refit"], ("--law",)),
    # accepted and ignored: --accuracy with the paper's law, --warn-above (its default value)
    # without --compare.
    (["fmax", "--mu", "1", "--zeta", "2", "--accuracy", "fine"], ("--accuracy", "refit|fem|bem")),
    (["curve", "--mu", "1", "--zeta", "2", "--accuracy", "draft"], ("--accuracy",)),
    (["fmax", "--mu", "1", "--zeta", "2", "--warn-above", "0.1"], ("--warn-above", "--compare")),
])
def test_cli_refuses_bad_input_in_one_line_before_any_work(capsys, no_work, args, names):
    code, out, err = run_gw(capsys, args)
    assert code == 2 and out == "" and len(err) == 1, err
    assert err[0].startswith("python -m gw: error: ") and all(n in err[0] for n in names), err


def test_cli_curve_takes_the_most_points_and_a_range(capsys):
    """--points POINTS_MAX and --d MIN MAX are served: that many d from MIN to MAX."""
    from gw.__main__ import POINTS_MAX

    code, out, err = run_gw(capsys, ["curve", "--mu", "1", "--zeta", "2", "--d", "-1", "3",
                                     "--points", str(POINTS_MAX), "--json"])
    assert code == 0 and err == [], err
    out = json.loads(out)
    assert len(out["d"]) == POINTS_MAX and out["d"][0] == -1.0 and out["d"][-1] == 3.0
    assert POINTS_MAX == 10_000  # the bound named in the refusal above


def test_a_strength_in_si_is_the_tension_per_nominal_area_and_its_separation():
    """F/A₀ = F̄max·2πRΔγη (eqs. 23, 27) and d = d̃σ, from Scales built of physical inputs; a
    non-positive σ or η is refused."""
    from fem_asperity import Scales

    radius, dgamma, eps, sigma, density = 2e-6, 0.1, 3e-10, 1e-9, 1e12
    scales = Scales.for_mu(1.0, eps=eps, R=radius, dgamma=dgamma)
    found = strength(PaperLaw(1.0), RoughSurface(zeta=sigma / eps))
    si = found.si(scales, sigma=sigma, density=density)
    assert si.pressure_max == pytest.approx(found.f_max * 2 * np.pi * radius * dgamma * density,
                                            rel=1e-12)
    assert si.d_at_max == pytest.approx(found.d_at_max * sigma, rel=1e-12)
    for bad in ({"sigma": 0.0, "density": density}, {"sigma": sigma, "density": -1.0}):
        with pytest.raises(InputError):
            found.si(scales, **bad)
