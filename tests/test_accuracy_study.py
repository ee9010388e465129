"""The speed-accuracy study (`python -m validation accuracy --quick`) and `validation bench`."""

import json

import pytest

from validation.__main__ import main
from validation.accuracy import KEYS, pareto


def test_pareto_front_keeps_the_points_nothing_beats():
    points = [(1.0, 1e-3), (2.0, 1e-4), (3.0, 1e-3), (0.5, 1e-2), (2.5, 1e-5)]
    assert sorted(pareto(points)) == [0, 1, 3, 4]


def test_quick_study_writes_its_files_and_its_estimates_bound_the_errors(tmp_path, capsys):
    """The quick study (μ = 1, both methods, draft and default): every preset's estimate bounds
    the true error of each event the reference resolves (ratio ≥ 1), and the figure, the table
    and the JSON are written."""
    assert main(["accuracy", "--quick", "--out", str(tmp_path), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert set(summary["files"]) == {"accuracy.md", "accuracy.json", "accuracy.png"}
    study = json.loads((tmp_path / "accuracy.json").read_text())
    presets = [r for r in study["rows"] if r["preset"]]
    assert {(r["method"], r["setting"]) for r in presets} == {
        (m, p) for m in ("bem", "fem") for p in ("draft", "default")}
    judged = [(r["method"], r["setting"], k, r["estimate_over_error"][k]) for r in presets
              for k in KEYS if r["estimate_over_error"][k] is not None]
    assert len(judged) >= 20
    assert all(ratio >= 1.0 for *_, ratio in judged), judged
    assert (tmp_path / "accuracy.png").stat().st_size > 10_000


def test_bench_json_names_every_operation_and_the_machine(capsys):
    assert main(["bench", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["machine"]["cpu_count"] >= 1 and data["commit"]
    assert set(data["wall_s"]) >= {"bem_curve_mu1_draft", "fem_curve_mu1_draft",
                                   "gw_f_max_paper_law"}
    assert all(seconds > 0 for seconds in data["wall_s"].values())


def test_exact_sphere_differs_from_derjaguin_like_eps_over_r():
    """The first correction of the sphere's gap to Derjaguin's parabola is O(ε/R): the P̄off
    difference falls with slope −1 in R/ε from 1e2 to 1e5, and is below 1e-4 at R/ε = 1e5."""
    from validation.accuracy import derjaguin

    sphere = derjaguin()
    assert sphere["slope_p_off"] == pytest.approx(-1.0, abs=0.02)
    assert sphere["rows"][-1]["difference"]["p_off"] < 1e-4
