"""Where a benchmark table came from, and writing it: the one helper the benchmark scripts share.

Every results file starts with the command that produced it, the git commit (with "+ uncommitted
changes" when tracked files differ from it), the UTC date, and the machine (CPU, cores, memory,
Python, numpy, scipy, scikit-fem, BLAS), so that a number can always be traced to its run.
"""

import argparse
import json
import math
import shlex
import sys
from datetime import datetime, timezone
from pathlib import Path

from fem_asperity.plumbing.files import write_atomic
from fem_asperity.plumbing.provenance import git_commit, machine

#: The benchmarks' own folder; results go to its `results/` unless --out says otherwise.
HERE = Path(__file__).resolve().parent
RESULTS = HERE / "results"
#: Suffix of a --quick run's files (git-ignored in results/), so a smoke run never overwrites
#: the real tables.
QUICK_SUFFIX = "-quick"


def add_output_options(parser: argparse.ArgumentParser) -> None:
    """The options every benchmark has: --quick (a smoke run of seconds) and --out (folder)."""
    parser.add_argument("--quick", action="store_true",
                        help=f"a tiny subset in seconds, written as <name>{QUICK_SUFFIX}.md/.json")
    parser.add_argument("--out", type=Path, default=RESULTS,
                        help="folder of the results files (default: benchmarks/results)")


def provenance() -> dict:
    """The command that is running, the commit, the UTC date and the machine. Call it when the
    run starts: the commit is then that of the code the run imported, and the date its start."""
    return {
        "command": shlex.join([Path(sys.executable).name, *sys.argv]),
        "commit": git_commit(HERE) or "unknown (not a git checkout)",
        "date": datetime.now(timezone.utc).isoformat(timespec="seconds"),
        "machine": machine(),
    }


def _markdown_header(title, prov):
    m = prov["machine"]
    return [
        f"# {title}",
        "",
        "Written by the benchmark script; do not edit by hand (run the command again).",
        "",
        f"- command: `{prov['command']}`",
        f"- commit: {prov['commit']}",
        f"- date: {prov['date']}",
        f"- machine: {m['cpu']}, {m['cpu_count']} CPUs, {m['memory']} memory, {m['os']}",
        f"- software: Python {m['python']}, numpy {m['numpy']}, scipy {m['scipy']}, "
        f"scikit-fem {m['scikit-fem']}, BLAS {m['blas']}",
        "",
    ]


def _finite(obj):
    """`obj` with non-finite floats as None: strict JSON, and a long run is not lost to a NaN."""
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    if isinstance(obj, dict):
        return {k: _finite(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_finite(v) for v in obj]
    return obj


def write_results(name, title, prov, markdown, data, *, out=RESULTS, quick=False):
    """Write `<out>/<name>.md` (the provenance `prov`, then the `markdown` lines) and
    `<name>.json` ({"provenance": prov, **data}), each atomically; `quick` appends QUICK_SUFFIX
    to the name. Both texts are built before either is written. Returns the two paths."""
    stem = name + (QUICK_SUFFIX if quick else "")
    text = "\n".join(_markdown_header(title, prov) + list(markdown)) + "\n"
    payload = json.dumps(_finite({"provenance": prov, **data}), indent=2, allow_nan=False) + "\n"
    out = Path(out)
    return write_atomic(out / f"{stem}.md", text), write_atomic(out / f"{stem}.json", payload)


def cell(value, spec):
    """A table cell: `value` formatted with `spec`, or "-" where there is none."""
    return "-" if value is None else format(value, spec)
