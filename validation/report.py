"""The verification report: a provenance line, the closed-form checks, the single-asperity and
rough-surface sections, and the paper's items not yet judged."""

import os
import platform
import subprocess
from datetime import datetime, timezone
from pathlib import Path

import numpy
import scipy

import fem_asperity

#: Items of the paper not yet judged, with what would judge them.
PENDING = (
    ("eqs. 16-19 beyond the figures: the Hertz-like laws after contact judged by a verdict "
     "(Fig. 7 shows them against Hertz)", "a tolerance on the distance from Hertz"),
)
#: The package's folder: its git checkout, if any, names the commit in the report.
HERE = Path(__file__).resolve().parent


def _git(*args):
    """Output of a git command run in the package's folder; None outside a checkout."""
    try:
        done = subprocess.run(["git", *args], cwd=HERE, capture_output=True, text=True,
                              timeout=10, check=True)
    except (OSError, subprocess.SubprocessError):
        return None
    return done.stdout.strip()


def git_commit():
    """Short hash of HEAD ("unknown" outside a git checkout), marked when tracked files differ."""
    head = _git("rev-parse", "--short", "HEAD")
    if not head:
        return "unknown"
    dirty = _git("status", "--porcelain", "--untracked-files=no")
    return head + (" + uncommitted changes" if dirty else "")


def processor():
    """The processor's model name where Linux tells it, else what `platform` knows."""
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as cpuinfo:
            models = [line.split(":", 1)[1].strip() for line in cpuinfo
                      if line.startswith("model name")]
    except OSError:
        models = []
    name = models[0] if models else platform.processor()
    return ", ".join(dict.fromkeys(n for n in (name, platform.machine()) if n))


def machine():
    """Processor, core count and the versions the numbers depend on, in one phrase."""
    return (f"{processor()}, {os.cpu_count()} cores, Python {platform.python_version()}, "
            f"numpy {numpy.__version__}, scipy {scipy.__version__}")


def provenance(command):
    """The report's first line: how to regenerate it, and from which code, when and where."""
    now = datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    return (f"Regenerate with `{command}`. Package version {fem_asperity.__version__}, "
            f"commit {git_commit()}, {now}, on {machine()}.")


def render(checks, files, command, rough="", single="", wall_s=None):
    """The report as Markdown text; `wall_s`: how long the run that wrote it took."""
    took = [] if wall_s is None else [
        "", f"This run took {wall_s:.0f} s (curves not in the store were solved; a second run "
            "reads them)."]
    lines = [
        provenance(command),
        *took,
        "",
        "# Verification report: Song & Komvopoulos, adhesive contact of an elastic half-space "
        "with a rigid rough surface",
        "",
        "## Closed-form checks (no FE)",
        "",
        "Each row compares a constant or limit of the paper's laws with an independently derived",
        "value. `note` rows have no tolerance in the paper: the numbers are given to judge.",
        "",
        "| claim | source | found | expected | tol | verdict | how |",
        "|---|---|---|---|---|---|---|",
    ]
    for c in checks:
        tol = "-" if c.tol is None else f"{c.tol:g}"
        lines.append(f"| {c.claim} | {c.source} | {c.found:.6g} | {c.expected:.6g} | {tol} "
                     f"| {c.verdict} | {c.how} |")
    lines += ["", single] if single else []
    lines += ["", rough] if rough else []
    lines += ["", "## Not yet judged", "", "| item | needs |", "|---|---|"]
    lines += [f"| {item} | {needs} |" for item, needs in PENDING]
    lines += ["", "## Files", ""] + [f"- `{name}`: {what}" for name, what in files]
    return "\n".join(lines) + "\n"
