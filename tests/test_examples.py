"""The examples run top to bottom at fast settings, and what they write agrees with independent
references: hand formulas, the DMT and JKR limits, Wu's pull-off fit (eq. 2), and the rigid-sphere
(Bradley) force integrated over the Gaussian heights with scipy's adaptive quadrature."""

import csv
import json
import runpy
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import quad

from fem_asperity import PAPER_LAWS

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
PNG = b"\x89PNG\r\n\x1a\n"


def run_example(name, out, monkeypatch):
    """Run examples/<name>.py as a script with EXAMPLES_FAST=1, output into `out`; its globals."""
    monkeypatch.setenv("EXAMPLES_FAST", "1")
    monkeypatch.setenv("EXAMPLES_OUT", str(out))
    return runpy.run_path(str(EXAMPLES / f"{name}.py"), run_name="__main__")


def read_csv(path):
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        return reader.fieldnames, list(reader)


def assert_png(path):
    assert path.read_bytes()[:8] == PNG, path


def test_mems_rough_surface(tmp_path, monkeypatch):
    out = tmp_path / "not made yet"  # the example makes its folder
    ns = run_example("mems_rough_surface", out, monkeypatch)
    E, nu, dgamma, eps = ns["E_POLY"], ns["NU_POLY"], ns["DGAMMA"], ns["EPS"]
    R, eta = ns["RADIUS"], ns["DENSITY"]
    # Two equal bodies: E* = [2(1 − ν²)/E]⁻¹; Tabor's μ = (RΔγ²/(E*²ε³))^(1/3).
    e_star = E / (2.0 * (1.0 - nu**2))
    mu = (R * dgamma**2 / (e_star**2 * eps**3)) ** (1.0 / 3.0)
    assert ns["E_STAR"] == pytest.approx(e_star, rel=1e-12)
    assert ns["MU"] == pytest.approx(mu, rel=1e-12)
    columns, rows = read_csv(out / "mems_rough_surface.csv")
    expected = {"sigma_nm", "omega", "zeta", "mu", "f_max", "d_at_max_nm", "pressure_pa"}
    assert expected <= set(columns)
    assert len(rows) >= 2
    pressures = []
    for row in rows:
        sigma = float(row["sigma_nm"]) * 1e-9
        omega = np.sqrt(1.0 - 3.717e-4 / (sigma * R * eta) ** 2)  # McCool, eq. 20
        assert float(row["omega"]) == pytest.approx(omega, rel=1e-9)
        assert float(row["zeta"]) == pytest.approx(sigma / eps, rel=1e-9)
        # The tensile force per nominal area, straight from the GW sum in SI: N = A₀η summits,
        # each pulling 2πRΔγ·P̄((d − z)/ε), heights distributed as eq. 21 with z̃ = z/σ.
        d = float(row["d_at_max_nm"]) * 1e-9
        kink = d - float(PAPER_LAWS.delta_oc(mu)) * eps  # z where P̄ turns from LJ to Hertz

        def per_area(z_tilde, d=d, sigma=sigma, omega=omega):
            p_bar = PAPER_LAWS.force((d - sigma * z_tilde) / eps, mu=mu)
            pdf = omega / np.sqrt(2.0 * np.pi) * np.exp(-0.5 * (omega * z_tilde) ** 2)
            return eta * 2.0 * np.pi * R * dgamma * p_bar * pdf

        window = 12.0 / omega
        force = quad(per_area, -window, window, points=[kink / sigma], limit=400,
                     epsabs=0.0, epsrel=1e-10)[0]
        pressure = float(row["pressure_pa"])
        assert pressure == pytest.approx(-force, rel=1e-6)
        # No summit pulls harder than Bradley's 2πRΔγ.
        assert 0.0 < pressure < 2.0 * np.pi * R * dgamma * eta
        pressures.append(pressure)
    # From σ = 2 nm on (ω near 1), rougher surfaces stick less.
    order = np.argsort([float(r["sigma_nm"]) for r in rows])
    kept = [pressures[i] for i in order if float(rows[i]["sigma_nm"]) >= 2.0]
    assert np.all(np.diff(kept) < 0.0)
    # Step 6: the solved BEM law on the headline surface. Below the jump-in (μ ≈ 0.28) every
    # summit pulls at most Bradley's force, so F̄max ≤ 1, and the paper's law is off it by more
    # than the 10 % that `gw fmax --compare` warns at (19 % measured when this was written).
    assert 0.0 < ns["best_solved"].f_max < 1.0
    assert ns["OFF"] == pytest.approx(ns["best"].f_max / ns["best_solved"].f_max - 1.0)
    assert abs(ns["OFF"]) > 0.1 > ns["solved"].interpolation_error


def test_single_curve(tmp_path, monkeypatch):
    ns = run_example("single_curve", tmp_path, monkeypatch)
    for name in ("approach.csv", "retraction.csv", "equilibrium.csv", "result.json"):
        assert (tmp_path / name).stat().st_size > 0
    for name in ("curve.png", "force_separation.png"):
        assert_png(tmp_path / name)
    result = json.loads((tmp_path / "result.json").read_text())
    mu = ns["MU"]
    assert result["mu"] == mu and result["method"] == "bem" and result["accuracy"] == "draft"
    # The pull-off lies between the DMT (−1) and JKR (−3/4) limits, within 2% of Wu's fit (eq. 2).
    assert -1.0 < result["p_off"] < -0.75
    assert result["p_off"] == pytest.approx(PAPER_LAWS.p_max(mu), rel=0.02)
    # μ = 2 is above the onset of jump-in: the approach jumps in and the retraction jumps out.
    assert result["jump_in"] and result["delta_jump_out"] > result["delta_jump_in"]
    columns, rows = read_csv(tmp_path / "retraction.csv")
    assert columns[:3] == ["delta_o/eps", "x_o/eps", "p/(2 pi R dgamma)"]
    assert min(float(r["p/(2 pi R dgamma)"]) for r in rows) == pytest.approx(result["p_off"],
                                                                abs=1e-9)


def test_mu_sweep(tmp_path, monkeypatch):
    monkeypatch.setenv("ADHESION_CACHE", str(tmp_path / "cache"))
    out = tmp_path / "out"
    run_example("mu_sweep", out, monkeypatch)
    assert {"events.csv", "curves.csv", "sweep.json"} <= {p.name for p in (out / "sweep").iterdir()}
    columns, rows = read_csv(out / "mu_sweep.csv")
    assert {"mu", "p_off", "p_off_err", "jump_in", "paper_p_max", "paper_jump_in",
            "dmt_pull_off", "jkr_pull_off", "md_pull_off"} <= set(columns)
    mu = np.array([float(r["mu"]) for r in rows])
    p_off = np.array([float(r["p_off"]) for r in rows])
    assert mu.size >= 3 and np.all(np.diff(mu) > 0.0)
    # Between DMT and JKR, moving toward JKR as μ grows, within 2% of Wu's fit at each μ.
    assert np.all((p_off > -1.0) & (p_off < -0.75))
    assert np.all(np.diff(p_off) > 0.0)
    np.testing.assert_allclose(p_off, PAPER_LAWS.p_max(mu), rtol=0.02)
    # Jump-in only above the onset (μ ≈ 0.7): none at μ ≤ 0.5, one at μ = 2.
    jumps = {float(r["mu"]): r["jump_in"] in ("True", "true") for r in rows}
    assert not any(j for m, j in jumps.items() if m <= 0.5)
    assert jumps[2.0]


def test_fig9(tmp_path, monkeypatch):
    out = tmp_path / "not made yet"  # the example makes its folder
    ns = run_example("fig9", out, monkeypatch)
    assert_png(out / "fig9.png")
    columns, rows = read_csv(out / "fig9.csv")
    mus = (0.5, 1.0, 2.0, 5.0, 10.0, 46.9)
    assert columns == ["d"] + [f"{q}_mu{m:g}" for m in mus for q in ("F", "S")]
    d = np.array([float(r["d"]) for r in rows])
    assert d[0] == 0.0 and d[-1] == pytest.approx(8.0)
    zeta = 2.0 / 0.3  # σ = 2 nm, ε = 0.3 nm
    for m in mus:
        force = np.array([float(r[f"F_mu{m:g}"]) for r in rows])
        area = np.array([float(r[f"S_mu{m:g}"]) for r in rows])
        # No asperity pulls harder than a rigid sphere (Bradley: P̄ ≥ −1); the area grows as
        # the surfaces approach.
        assert np.all(force >= -1.0)
        assert np.all(np.diff(area) <= 0.0)
    # Far apart (d̃ ≥ 7) every asperity sits beyond its jump-in separation (δ̄oc/ζ < 0.6 σ for
    # μ ≤ 2), where the law is Bradley's rigid-sphere force (eq. 8): F̄ = ∫ P̄_B(ζ(d̃ − z̃)) φ̃ dz̃.
    for m in (0.5, 1.0, 2.0):
        top = float(PAPER_LAWS.delta_oc(m)) / zeta
        for i in np.nonzero(d >= 7.0)[0]:
            def bradley(z, di=d[i]):
                delta = zeta * (di - z)
                pdf = np.exp(-0.5 * z**2) / np.sqrt(2.0 * np.pi)
                return (delta**-8 - 4.0 * delta**-2) / 3.0 * pdf

            expected = quad(bradley, -12.0, d[i] - top, epsabs=0.0, epsrel=1e-11, limit=200)[0]
            assert float(rows[i][f"F_mu{m:g}"]) == pytest.approx(expected, rel=1e-6)
    # The paper's reading of Fig. 9: at μ = 10 the rough surface's strength of adhesion stays
    # well below the single-asperity JKR pull-off 0.75.
    assert 0.0 < ns["strengths"][10.0] < 0.75


def test_afm_cantilever(tmp_path, monkeypatch):
    """Below the onset (μ ≈ 0.59) the rigid holder shows no jump-in and the cantilever does; the
    pull-off in newtons is p̄_off · 2πRΔγ; the cantilever figure is written; the polymer as a
    film on silicon."""
    ns = run_example("afm_cantilever", tmp_path, monkeypatch)
    assert 0.5 < ns["scales"].mu < 0.69
    assert ns["rigid"].events.jump_in is None and ns["lever"].events.jump_in is not None
    R, dgamma = ns["R"], ns["DGAMMA"]
    assert ns["pull_off"] == pytest.approx(ns["row"]["p_off"] * 2 * np.pi * R * dgamma)
    assert ns["k_bar"] == pytest.approx(ns["K"] * ns["EPS"] / (2 * np.pi * R * dgamma))
    saved = json.loads((tmp_path / "result.json").read_text())
    assert saved["inputs"]["control"] == "load line"
    assert saved["z_jump_in"] == ns["row"]["z_jump_in"]
    assert saved["si"]["scales"]["R"] == R  # the record on disk is in SI too
    header = (tmp_path / "paths_si.csv").read_text().splitlines()[0].split(",")
    assert {"force_N", "piezo_m", "deflection_m"} <= set(header)
    assert_png(tmp_path / "cantilever.png")
    # The film on silicon: meshed for the film's own μ, and a thin film on a stiff substrate
    # pulls off between the bulk polymer and Bradley's rigid limit, −1 (silicon alone: μ = 0.04)
    film = ns["film"]
    assert film.status == "ok" and film.events.jump_in is not None
    assert "sized for the layer's Tabor parameter" in film.message
    assert -1.0 < film.events.p_off < ns["row"]["p_off"]
