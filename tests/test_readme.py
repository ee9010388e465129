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
