"""The verification report: a provenance line, the closed-form checks, the single-asperity and
rough-surface sections, and the paper's items not yet judged."""

from datetime import datetime, timezone
from pathlib import Path

import fem_asperity
from fem_asperity.plumbing.provenance import git_commit, machine
from fem_asperity.plumbing.revision import solver_revision

#: Items of the paper not yet judged, with what would judge them.
PENDING = (
    ("eqs. 16-19 beyond the figures: the Hertz-like laws after contact judged by a verdict "
     "(Fig. 7 shows them against Hertz)", "a tolerance on the distance from Hertz"),
)
#: The package's folder: its git checkout, if any, names the commit in the report.
HERE = Path(__file__).resolve().parent


def machine_phrase():
    """Processor, core count and the versions the numbers depend on, in one phrase."""
    m = machine()
    cpu = ", ".join(n for n in (m["cpu"], m["arch"]) if n)
    return (f"{cpu}, {m['cpu_count']} cores, Python {m['python']}, numpy {m['numpy']}, "
            f"scipy {m['scipy']}")


def provenance(command, commit=None):
    """The report's first line: how to regenerate it, and from which code (`commit`: as found
    when the run started; by default now), when and where."""
    now = datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    commit = commit or git_commit(HERE) or "unknown"
    return (f"Regenerate with `{command}`. Package version {fem_asperity.__version__}, "
            f"commit {commit}, solver revision {solver_revision()}, {now}, on "
            f"{machine_phrase()}.")


def counted(n, one, many):
    """'1 item', '2 items': `n` with the noun (or verb) that agrees with it."""
    return f"{n} {one if n == 1 else many}"


def _summary(counts):
    """The summary block: the verdict counts, then the claims that fail, by name."""
    if counts is None:
        return []
    lines, failing = counts
    block = ["## Summary", ""] + [f"- {line}" for line in lines]
    if PENDING:
        block.append(f"- not yet judged: {counted(len(PENDING), 'item', 'items')}")
    if failing:
        block += ["", "The claims that fail:", ""] + [f"- {claim}" for claim in failing]
    return block + [""]


def render(checks, files, command, rough="", single="", layered="", explicit="", wall_s=None,
           counts=None, stages=None, commit=None):
    """The report as Markdown text; `wall_s`: how long the run that wrote it took, `stages`:
    {stage: s} of it; `counts`: (lines, failing claims) for the summary at the top
    (`validation.__main__.verdict_counts`); `commit`: the code the run started from."""
    parts = "" if not stages else " (" + ", ".join(f"{k} {v:.0f} s"
                                                   for k, v in stages.items()) + ")"
    took = [] if wall_s is None else [
        "", f"This run took {wall_s:.0f} s{parts}; curves not in the store were solved, and a "
            "second run reads them."]
    lines = [
        provenance(command, commit),
        *took,
        "",
        "# Verification report: Song & Komvopoulos, adhesive contact of an elastic half-space "
        "with a rigid rough surface",
        "",
        *_summary(counts),
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
    lines += ["", explicit] if explicit else []
    lines += ["", layered] if layered else []
    lines += ["", "## Not yet judged", "", "| item | needs |", "|---|---|"]
    lines += [f"| {item} | {needs} |" for item, needs in PENDING]
    lines += ["", "## Files", ""] + [f"- `{name}`: {what}" for name, what in files]
    return "\n".join(lines) + "\n"
