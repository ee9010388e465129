"""Command line of validation: `python -m validation all --out DIR` (see --help)."""

import json
import sys
from dataclasses import asdict
from pathlib import Path

from fem_asperity import InputError
from fem_asperity._cli import Parser, dump_json, run
from fem_asperity.laws import PAPER_LAWS

from fem_asperity._io import save_figure, write_atomic
from .closed_forms import closed_form_checks
from .law_figure import law_table, plot_laws
from .report import PENDING, render

PROG = "python -m validation"
FILES = (
    ("paper_laws.json", "the paper-law events over 101 mu in [0.01, 100], with Maugis-Dugdale"),
    ("paper_laws.png", "figure of those laws beside JKR, DMT and Maugis-Dugdale"),
    ("report.md", "closed-form checks with verdicts, and what is not yet judged"),
)


def build_parser():
    parser = Parser(prog=PROG, description=__doc__)
    commands = parser.add_subparsers(dest="command", required=True)
    everything = commands.add_parser("all", help="regenerate the figures and the report")
    everything.add_argument("--out", type=Path, default=Path("out"), help="output folder")
    everything.add_argument("--json", action="store_true", help="print a JSON summary")
    return parser


STEPS = 3


def _step(i, text):
    print(f"[{i}/{STEPS}] {text}", file=sys.stderr, flush=True)


def run_all(out, command):
    """Write every output that exists so far into `out`; return a summary dict."""
    if out.exists() and not out.is_dir():
        raise InputError(f"--out must be a folder; {out} is a file")
    _step(1, "paper laws over mu (closed forms, Maugis-Dugdale)")
    rows = law_table()
    table = {"method": "closed-form laws with the paper's constants (exact evaluation)",
             "constants": asdict(PAPER_LAWS), "rows": rows}
    write_atomic(out / "paper_laws.json", json.dumps(table, indent=1, allow_nan=False))
    _step(2, "figure of the laws")
    save_figure(plot_laws(rows), out / "paper_laws.png")
    _step(3, "closed-form checks and report")
    checks = closed_form_checks()
    write_atomic(out / "report.md", render(checks, FILES, command))
    return {"out": str(out), "files": [name for name, _ in FILES],
            "checks": [c.as_dict() for c in checks],
            "not_yet_available": [{"item": i, "needs": n} for i, n in PENDING]}


def main(argv=None):
    args = build_parser().parse_args(argv)
    command = " ".join([PROG] + (sys.argv[1:] if argv is None else list(argv)))
    summary = run_all(args.out, command)
    if args.json:
        dump_json(summary)
    else:
        verdicts = [c["verdict"] for c in summary["checks"]]
        print(f"wrote {', '.join(summary['files'])} to {args.out}/")
        print(f"closed-form checks: {verdicts.count('holds')} hold, {verdicts.count('fails')} fail, "
              f"{verdicts.count('note')} notes (see report.md)")
        print(f"not yet available: {len(PENDING)} items awaiting the FE model and GW integrator")
    return 0


if __name__ == "__main__":
    sys.exit(run(main, PROG))
