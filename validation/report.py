"""The verification report: closed-form checks now, and what awaits the FE and GW stages."""

import platform
from datetime import datetime, timezone

#: Items of the paper not yet judged, with the roadmap stage that will judge them.
PENDING = (
    ("Fig. 3 / eq. 6: a_c at maximum adhesion vs mu", "FE sweep over mu (verification stage)"),
    ("Fig. 4 / eq. 7: delta_oc vs mu (no jump-in)", "FE sweep over mu (verification stage)"),
    ("Fig. 5 / eq. 9: force vs separation, mu = 0.091-0.425", "FE sweep over mu (verification stage)"),
    ("Fig. 6 (caption lost) / eqs. 12-13: jump-in gap and separation", "FE sweep over mu (verification stage)"),
    ("Fig. 7 / eqs. 16-19: Hertz-like force and area after contact", "FE sweep over mu (verification stage)"),
    ("eqs. 15 -> 2: the force lands on P_off at jump-in", "FE sweep over mu (verification stage)"),
    ("refit of the eight constants against the FE itself (here: against the BEM, which agrees "
     "with the FE within its error estimate)", "FE sweep over mu (verification stage)"),
)


def render(checks, files, command, rough=""):
    """The report as Markdown text."""
    now = datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    lines = [
        "# Verification report: Song & Komvopoulos, adhesive rough-surface contact",
        "",
        f"Generated {now} by `{command}` on {platform.node()} "
        f"({platform.machine()}, Python {platform.python_version()}).",
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
    lines += ["", rough] if rough else []
    lines += ["", "## Not yet judged", "", "| item | needs |", "|---|---|"]
    lines += [f"| {item} | {needs} |" for item, needs in PENDING]
    lines += ["", "## Files", ""] + [f"- `{name}`: {what}" for name, what in files]
    return "\n".join(lines) + "\n"
