"""Where a benchmark table came from, and writing it: the one helper the benchmark scripts share.

Every results file starts with the command that produced it, the git commit (with "+ uncommitted
changes" when tracked files differ from it), the UTC date, and the machine (CPU, cores, memory,
Python, numpy, scipy, scikit-fem, BLAS), so that a number can always be traced to its run.
"""

import argparse
import json
import math
import os
import platform
import shlex
import subprocess
import sys
from datetime import datetime, timezone
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path

from fem_asperity.plumbing.files import write_atomic

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


def _git(*args):
    try:
        done = subprocess.run(["git", *args], cwd=HERE, capture_output=True, text=True,
                              check=True, timeout=30)
    except (OSError, subprocess.SubprocessError):
        return None
    return done.stdout.strip()


def commit() -> str:
    """`git rev-parse --short HEAD`, plus " + uncommitted changes" if tracked files differ."""
    head = _git("rev-parse", "--short", "HEAD")
    if head is None:
        return "unknown (not a git checkout)"
    dirty = _git("status", "--porcelain", "--untracked-files=no")
    return head + (" + uncommitted changes" if dirty else "")


def _proc_field(path, key):
    """The value of the first `key: value` line of a /proc file, or None."""
    try:
        with open(path) as f:
            for line in f:
                name, _, value = line.partition(":")
                if name.strip() == key:
                    return value.strip()
    except OSError:
        pass
    return None


def _memory():
    total = _proc_field("/proc/meminfo", "MemTotal")  # e.g. "24684092 kB"
    if total is None or not total.endswith("kB"):
        return None
    return f"{int(total.split()[0]) / 2**20:.1f} GiB"


def _version(package):
    try:
        return version(package)
    except PackageNotFoundError:
        return None


def _blas():
    """BLAS libraries loaded, as `internal_api version (the wheel that ships it)`: numpy's and
    scipy's wheels each bundle their own."""
    import numpy  # noqa: F401  (threadpoolctl lists only libraries already loaded)
    import scipy.linalg  # noqa: F401
    from threadpoolctl import threadpool_info

    found = set()
    for lib in threadpool_info():
        if lib.get("user_api") == "blas":
            owner = next((p for p in ("numpy", "scipy") if p in lib.get("filepath", "")), None)
            found.add(f"{lib['internal_api']} {lib['version']}" + (f" ({owner})" if owner else ""))
    return ", ".join(sorted(found)) or None


def machine() -> dict:
    """CPU model, cores, memory, OS and the numerical software's versions."""
    return {
        "cpu": _proc_field("/proc/cpuinfo", "model name") or platform.processor() or None,
        "cpu_count": os.cpu_count(),
        "memory": _memory(),
        "os": platform.platform(),
        "python": platform.python_version(),
        "numpy": _version("numpy"),
        "scipy": _version("scipy"),
        "scikit-fem": _version("scikit-fem"),
        "blas": _blas(),
    }


def provenance() -> dict:
    """The command that is running, the commit, the UTC date and the machine. Call it when the
    run starts: the commit is then that of the code the run imported, and the date its start."""
    return {
        "command": shlex.join([Path(sys.executable).name, *sys.argv]),
        "commit": commit(),
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
