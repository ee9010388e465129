"""The README's three commands are the ones CI runs and the ones that exist."""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def readme_commands():
    block = re.search(r"## Three commands\s+```\n(.*?)```", (ROOT / "README.md").read_text(), re.S)
    return block.group(1).strip().splitlines()


def test_readme_gives_setup_main_and_test_commands():
    setup, main, tests = readme_commands()
    assert setup == 'python -m pip install -e ".[test]"'
    assert main == "python -m validation all --out out/"
    assert tests == "python -m pytest"


def test_ci_runs_the_readme_setup_and_test_commands():
    setup, _, tests = readme_commands()
    ci = (ROOT / ".ci" / "run").read_text().splitlines()
    assert setup in ci and tests in ci
    assert ci.index(setup) < ci.index(tests)


def test_the_committed_reports_come_from_the_current_solver():
    """docs/report.md and docs/layered.md are copies of the main job's output (the README says
    how): each names the solver revision it ran, which must be today's, so a change that moves
    the solver regenerates them."""
    from fem_asperity.plumbing.revision import solver_revision

    for name in ("report.md", "layered.md"):
        found = re.search(r"solver revision (\w+)", (ROOT / "docs" / name).read_text())
        assert found and found.group(1) == solver_revision(), (
            f"docs/{name} was written by another solver revision: regenerate it "
            "(README, 'The report and figures under docs/')")


def test_every_benchmark_script_is_listed_in_the_benchmarks_readme():
    folder = ROOT / "benchmarks"
    listed = (folder / "README.md").read_text()
    scripts = [p.name for p in folder.glob("*.py") if p.name != "provenance.py"]
    assert scripts and all(f"| `{name}` |" in listed for name in scripts), scripts
