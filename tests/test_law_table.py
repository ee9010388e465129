"""The shipped table of solved asperity laws (`gw.law_table`): against direct BEM solves at μ it
was not built from, its own error report, its onset, and `gw fmax --law solved` / the warning of
plain `gw fmax`."""

import json
from pathlib import Path

import numpy as np
import pytest

from fem_asperity.studies.store import stored_curve
from gw.law_table import TABLE_FILE, _unwarp, _warp, shipped_table
from gw.law_table_build import OWNER, held_out_mus, measure, report

DOCS = Path(__file__).parents[1] / "docs"


def test_the_warp_and_its_inverse_agree_beyond_the_landmarks():
    marks = (40.0, 2.6, -2.9, -4.6, -6.1)
    delta = np.concatenate([np.linspace(-80.0, 120.0, 2001), marks])
    np.testing.assert_allclose(_unwarp(_warp(delta, marks), marks), delta, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(_warp(np.array(marks), marks), [1.0, 0.0, -1.0, -2.0, -3.0])


@pytest.mark.slow
@pytest.mark.parametrize("mu", [0.05, 0.6, 1.5, 3.0])
def test_the_table_matches_direct_solves_within_its_stated_error(mu, tmp_path, monkeypatch):
    """At μ that are neither nodes nor held out (0.6 just below the onset, 1.5 above it), the
    table's P̄, jump-in and F̄max on GW surfaces (ζ 0.1-316), and the retraction's P̄ and
    jump-out, against a BEM `default` curve solved now: each within the error the table states
    there."""
    table = shipped_table()
    assert mu not in table.mus and mu not in held_out_mus(list(table.mus))
    monkeypatch.setenv("ADHESION_CACHE", str(tmp_path))
    direct = stored_curve(mu, method="bem", accuracy="default")
    found, stated = measure(table, direct), table.law(mu).error
    assert found["force"] <= stated["force"]
    assert (found["jump"] is None) == (stated["jump"] is None) == (mu < 0.69)
    if found["jump"] is not None:
        assert found["jump"] <= stated["jump"]
    assert max(abs(x) for x in found["f_max"] if x is not None) <= stated["f_max"]
    back, stated_back = found["retraction"], table.law(mu, "retraction").error
    assert back["force"] <= stated_back["force"] and "f_max" not in stated_back
    assert (back["jump"] is None) == (stated_back["jump"] is None) == (mu < 0.69)
    if back["jump"] is not None:
        assert back["jump"] <= stated_back["jump"]


def test_the_shipped_table_says_how_it_was_made_and_its_report_is_current():
    """The record names the command and the solver revision; one held-out μ inside each interval;
    docs/law_table.md is what `report` writes from the shipped table; a few hundred kB."""
    table = shipped_table()
    assert table.record["command"] == OWNER and len(table.record["solver_revision"]) == 10
    assert table.mu_range == (0.01, 50.0)
    held = [e["held_out"] for e in table.errors]
    assert len(held) == len(table.mus) - 1
    assert np.all((table.mus[:-1] < held) & (held < table.mus[1:]))
    assert (DOCS / "law_table.md").read_text() == report(table)
    assert TABLE_FILE.stat().st_size < 2**20


def test_the_stencil_stays_on_its_side_of_the_onset_and_returns_the_nodes():
    table = shipped_table()
    lo, hi = table.record["onset"]["lo"], table.record["onset"]["hi"]
    assert not table.law(lo * 0.999).jumps and table.law(hi * 1.001).jumps
    for k in (0, 17, len(table.mus) - 1):  # at a node the law is the node's own
        node, law = table.node(k), table.law(table.mus[k])
        delta = np.linspace(-5.0, 45.0, 501)
        np.testing.assert_allclose(law.force(delta), node.law.force(delta), rtol=1e-12,
                                   atol=1e-12)


def run_gw(capsys, args):
    from fem_asperity.plumbing.cli import run
    from gw.__main__ import PROG, main

    try:
        code = run(main, PROG, args)
    except SystemExit as exc:
        code = exc.code
    out, err = capsys.readouterr()
    return code, out, err.strip().splitlines()


@pytest.mark.slow
def test_gw_fmax_from_the_table_agrees_with_a_fresh_solve(capsys, tmp_path, monkeypatch):
    """`--law solved` (no solve) against `--law bem` (solved now) at μ = 1.5, ζ = 3: within the
    F̄max error the table's result states, which it carries in the output's units."""
    monkeypatch.setenv("ADHESION_CACHE", str(tmp_path))
    base = ["fmax", "--mu", "1.5", "--zeta", "3", "--json"]
    code, out, _ = run_gw(capsys, base + ["--law", "solved"])
    table = json.loads(out)
    assert code == 0 and set(table["law_error"]) >= {"f_max", "force", "jump", "measured_at_mu"}
    code, out, _ = run_gw(capsys, base + ["--law", "bem"])
    fresh = json.loads(out)
    assert abs(table["f_max"] - fresh["f_max"]) <= table["law_error"]["f_max"]


def test_plain_fmax_warns_where_the_table_puts_the_paper_off(capsys):
    """The paper's law (the default) with no --compare: one warning line where the table puts
    its F̄max more than 10 % off (μ = 1: -64 %), none where it does not (μ = 0.05, ζ = 3)."""
    code, out, err = run_gw(capsys, ["fmax", "--mu", "1", "--zeta", "6.67", "--json"])
    assert code == 0 and "%" in json.loads(out)["warning"]
    assert len(err) == 1 and err[0].startswith("warning: the paper's law puts F_max")
    code, out, err = run_gw(capsys, ["fmax", "--mu", "0.05", "--zeta", "3", "--json"])
    assert code == 0 and "warning" not in json.loads(out) and err == []


@pytest.mark.parametrize("args, names", [
    (["fmax", "--mu", "60", "--zeta", "1", "--law", "solved"], ("table", "50]", "--law bem")),
    (["fmax", "--mu", "0.005", "--zeta", "1", "--law", "solved"], ("table", "0.01")),
    (["curve", "--mu", "1", "--zeta", "1", "--law", "solved", "--accuracy", "fine"],
     ("--accuracy",)),
])
def test_the_table_refuses_what_it_cannot_answer_in_one_line(capsys, args, names):
    code, out, err = run_gw(capsys, args)
    assert code == 2 and out == "" and len(err) == 1, err
    assert all(n in err[0] for n in names), err


def test_law_table_refuses_an_output_it_cannot_write_before_solving(capsys, tmp_path):
    blocker = tmp_path / "a_file"
    blocker.write_text("a user's file\n")
    code, out, err = run_gw(capsys, ["law-table", "--out", str(blocker / "table.npz")])
    assert code == 2 and len(err) == 1 and "--out" in err[0], err
    assert not any("curves of the table" in line for line in err)  # nothing was solved
    assert blocker.read_text() == "a user's file\n"
