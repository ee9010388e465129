"""The verification report: `python -m validation all|<one part> --out DIR`.

all: everything below and the report; single-asperity: the paper's fitted laws (Figs. 3-7)
judged against FE sweeps, the BEM as cross-check; rough-surface: Figs. 9-13, their verdicts, the
paper's law against the solved law; rough-explicit: GW against rough surfaces solved whole and
interacting asperities (all: one small surface; --full: the map over mu, zeta, sigma R eta);
layered: a bonded layer over thickness and modulus. Curves
are solved once and stored ($ADHESION_CACHE). accuracy: the speed-accuracy trade of the solvers'
settings (`validation.accuracy`; not part of all); advisor: the scene advisor's table for the
example scenes (docs/advisor.md; not part of all); bench: timings of the main operations, for
comparing versions."""

import json
import sys
import time
from dataclasses import asdict
from pathlib import Path

from fem_asperity.closed_forms.laws import PAPER_LAWS
from fem_asperity.plumbing.checks import positive
from fem_asperity.plumbing.cli import Parser, ProgressBar, dump_json, run
from fem_asperity.plumbing.files import output_folder, save_figure, staged_folder, write_atomic
from fem_asperity.plumbing.provenance import git_commit
from fem_asperity.solver.presets import PRESETS
from fem_asperity.solver.solve import solvable_mu
from gw.explicit.relax import keep_freed_memory

from .closed_forms import closed_form_checks
from .law_figure import law_table, plot_laws
from .layered import section as layered_section
from .report import HERE, PENDING, counted, provenance, render
from .rough_explicit import section as explicit_section
from .rough_surface import COMPARISON_MU
from .rough_surface import run as run_rough_surface
from .rough_surface import section as rough_section
from .single_asperity import run as run_single_asperity
from .single_asperity import section as single_section

PROG = "python -m validation"
FILES = (
    ("paper_laws.json", "the paper-law events over 101 mu in [0.01, 100], with Maugis-Dugdale"),
    ("paper_laws.png", "figure of those laws beside JKR, DMT and Maugis-Dugdale"),
    ("report.md", "closed-form checks with verdicts, rough-surface claims, and what is not yet "
                  "judged"),
)
SINGLE_FILES = (
    ("single_asperity/report.md", "the paper's single-asperity laws judged against the FE"),
    ("single_asperity/report.json", "verdicts, mu_onset, refit with 95% intervals, FE rows"),
    ("single_asperity/fig3.png ... fig7.png, hysteresis.png", "Figs. 3-7 and the loops"),
    ("single_asperity/fields_after_jump_in.png, .vtu",
     "sigma_zz in the FE solid after the jump-in"),
)
ROUGH_FILES = (
    ("rough_surface.json", "Figs. 9-13 data (paper's laws, GW), xi collapse, omega sensitivity, "
                           "verdicts, paper law vs solved law"),
    ("rough_surface.png", "Figs. 9-13 and the xi collapse"),
    ("law_comparison.png", "F and S from the paper's law and from the BEM curve, sigma = 2 nm"),
    ("rough_surface.md", "the rough-surface section of the report on its own"),
)

EXPLICIT_FILES = (
    ("rough_explicit/report.md", "GW, interacting asperities and the whole surface on GW "
                                 "surfaces made explicit (the map with --full)"),
    ("rough_explicit/rough_explicit.json", "the same as data, with every model's curve"),
    ("rough_explicit/curves.png", "F against d for every model on the first surface"),
)
EXPLICIT_MAP_FILES = (("rough_explicit/map.png", "GW's and the interacting model's F_max error "
                                                "over sigma R eta, per mu and zeta"),
                      ("rough_explicit/rough_map.json", "the compact map the advisor reads "
                                                        "(--ship: into the package too)"))

LAYERED_FILES = (
    ("layered/report.md", "maps over thickness and modulus, limits, coated rough surface, FE "
                          "against the layered BEM"),
    ("layered/layered.json", "the same as data"),
    ("layered/map.png", "pull-off and jump-in over (t, M) for each mu"),
)


def build_parser():
    parser = Parser(prog=PROG, description=__doc__)
    commands = parser.add_subparsers(dest="command", required=True)
    everything = commands.add_parser("all", help="regenerate the figures and the report")
    everything.add_argument("--out", type=Path, default=Path("out"), help="output folder")
    everything.add_argument("--json", action="store_true", help="print a JSON summary")
    single = commands.add_parser("single-asperity",
                                 help="Figs. 3-7: the paper's fitted laws judged against FE sweeps")
    rough = commands.add_parser("rough-surface", help="Figs. 9-13, verdicts, paper vs solved law")
    explicit = commands.add_parser("rough-explicit", help="GW against rough surfaces solved "
                                   "whole and interacting asperities")
    explicit.add_argument("--full", action="store_true",
                          help="the map over mu, zeta and sigma R eta (many whole-surface "
                               "solves; stored, so an interrupted map resumes)")
    explicit.add_argument("--ship", action="store_true",
                          help="with --full: also write the compact map into the package "
                               "(gw/data/rough_map.json, which the advisor reads)")
    layers = commands.add_parser("layered", help="layered media: maps over thickness and modulus, "
                                 "the homogeneous limits, a coated rough surface, FE vs BEM")
    for command in (single, rough, layers, explicit):
        command.add_argument("--out", type=Path, default=Path("out"), help="output folder")
        command.add_argument("--json", action="store_true", help="print a JSON summary")
    layers.add_argument("--accuracy", choices=tuple(PRESETS), default="default",
                        help="accuracy of the layered curves (default)")
    for command in (layers, explicit):
        command.add_argument("--jobs", type=int, help="worker processes (default: one per core)")
        command.add_argument("--scheduler", metavar="ADDRESS",
                             help="run the sweeps on this Dask scheduler (extra 'cluster')")
    for command in (everything, single):
        command.add_argument("--method", choices=("fem", "bem"), default="fem",
                             help="solver judged in the single-asperity sweep (default: fem; "
                                  "the other method is its cross-check)")
        command.add_argument("--jobs", type=int, help="worker processes (default: one per core)")
        command.add_argument("--scheduler", metavar="ADDRESS",
                             help="run the sweeps on this Dask scheduler (extra 'cluster')")
    single.add_argument("--accuracy", choices=tuple(PRESETS), default="default",
                        help="accuracy of the swept curves (default)")
    trade = commands.add_parser("accuracy", help="error against wall time of every preset and "
                                "setting, the Pareto front, orders, estimate/true error")
    trade.add_argument("--out", type=Path, default=Path("out"), help="output folder")
    trade.add_argument("--quick", action="store_true",
                       help="a reduced set (mu = 1, two presets, one setting of each kind)")
    trade.add_argument("--mu", type=float, nargs="+",
                       help="Tabor parameters studied (default: 0.1 1 5 10; --quick: 1)")
    trade.add_argument("--json", action="store_true", help="print a JSON summary")
    table = commands.add_parser("advisor", help="the scene advisor's effects, models, costs "
                                "and choice for each scene file (default: the examples')")
    table.add_argument("--out", type=Path, default=Path("out"), help="output folder")
    table.add_argument("--scenes", type=Path, nargs="+",
                       help="scene files (default: examples/*.toml of the source checkout)")
    table.add_argument("--json", action="store_true", help="print a JSON summary")
    bench = commands.add_parser("bench", help="timings of the main operations")
    bench.add_argument("--json", action="store_true", help="print the timings as JSON")
    for command in (everything, rough):
        command.add_argument("--compare-mu", type=float, nargs="+", default=list(COMPARISON_MU),
                             help="mu of the paper-law vs BEM-law check (default: %(default)s)")
        command.add_argument("--accuracy", choices=tuple(PRESETS), default="default",
                             help="accuracy of the solved curves (default)")
        command.add_argument("--refit-method", choices=("bem", "fem"), default="bem",
                             help="solver of the curves the constants are refitted from (bem: "
                                  "fast; fem: slow the first time, then stored)")
    return parser


def _step(i, text, total):
    print(f"[{i}/{total}] {text}", file=sys.stderr, flush=True)


def _bar(label):
    """The progress bar of a long step inside a stage (on stderr, with the time left)."""
    return ProgressBar(f"  {label}", time_left=True)


def _rough(out, args, first_step, total):
    """Run the rough-surface stage; returns (its full results, the summary's part of them)."""
    steps = iter(range(first_step, first_step + 2))
    rough = run_rough_surface(out, compare_mu=args.compare_mu, accuracy=args.accuracy,
                              refit_method=args.refit_method,
                              step=lambda text: _step(next(steps), text, total), bars=_bar)
    return rough, {"rough_surface": rough["verdicts"],
                   "rough_surface_solved_law": rough["solved"]["verdicts"],
                   "law_comparison": rough["law_comparison"]}


def _single(out, args, first_step, total):
    """Run the single-asperity stage; returns (its summary, the part for the overall one)."""
    steps = iter(range(first_step, first_step + 2))
    single = run_single_asperity(out, method=args.method, accuracy=args.accuracy, jobs=args.jobs,
                                 scheduler=args.scheduler,
                                 step=lambda text: _step(next(steps), text, total), bars=_bar)
    return single, {"single_asperity": single["verdicts"], "mu_onset": single["mu_onset"],
                    "refit": single["refit"]}


def _layered(out, args, first_step, total, command):
    """Run the layered stage; returns (its summary, the part for the overall one)."""
    from .layered import run as run_layered

    steps = iter(range(first_step, first_step + 2))
    layered = run_layered(out, accuracy=args.accuracy, jobs=args.jobs, scheduler=args.scheduler,
                          step=lambda text: _step(next(steps), text, total),
                          header=provenance(command), bars=_bar)
    return layered, {"layered": {k: layered[k] for k in ("not_bracketed", "jump_created",
                                                         "jump_removed", "failed")}}


def _explicit(out, args, first_step, total, command):
    """Run the rough-explicit stage; returns (its summary, the part for the overall one)."""
    from .rough_explicit import run as run_explicit

    steps = iter(range(first_step, first_step + 1))
    explicit = run_explicit(out, full=getattr(args, "full", False), jobs=args.jobs,
                            scheduler=args.scheduler,
                            step=lambda text: _step(next(steps, first_step), text, total),
                            header=provenance(command), command=command)
    holds = {name: sum(r["holds"][name] for r in explicit["scenes"])
             for name in explicit["scenes"][0]["holds"]}
    return explicit, {"rough_explicit": {"surfaces": len(explicit["scenes"]), "holds": holds}}


def run_all(out, command, args):
    """Write every output into `out`; return a summary dict."""
    start, commit = time.perf_counter(), git_commit(HERE)  # the code this run starts from
    stages, lap = {}, start

    def timed(stage):
        nonlocal lap
        now = time.perf_counter()
        stages[stage], lap = now - lap, now

    _step(1, "paper laws over mu (closed forms, Maugis-Dugdale)", 10)
    rows = law_table()
    table = {"method": "closed-form laws with the paper's constants (exact evaluation)",
             "constants": asdict(PAPER_LAWS), "rows": rows}
    write_atomic(out / "paper_laws.json", json.dumps(table, indent=1, allow_nan=False))
    _step(2, "figure of the laws", 10)
    save_figure(plot_laws(rows), out / "paper_laws.png")
    _step(3, "closed-form checks", 10)
    checks = closed_form_checks()
    timed("closed forms")
    single, single_summary = _single(out, args, 4, 10)
    timed("single asperity")
    rough, rough_summary = _rough(out, args, 6, 10)
    timed("rough surface (GW)")
    explicit, explicit_summary = _explicit(out, args, 8, 10, command)
    timed("rough surfaces solved whole")
    layered, layered_summary = _layered(out, args, 9, 10, command)
    timed("layered")
    files = FILES + SINGLE_FILES + ROUGH_FILES + EXPLICIT_FILES + LAYERED_FILES
    wall_s = time.perf_counter() - start
    summary = {"files": [name for name, _ in files],
               "checks": [c.as_dict() for c in checks], **single_summary, **rough_summary,
               **explicit_summary, **layered_summary,
               "not_yet_available": [{"item": i, "needs": n} for i, n in PENDING],
               "wall_s": wall_s, "stage_s": stages}
    write_atomic(out / "report.md", render(checks, files, command, rough_section(rough),
                                           single_section(single), layered_section(layered),
                                           explicit_section(explicit), wall_s=wall_s,
                                           stages=stages, counts=verdict_counts(summary),
                                           commit=commit))
    return summary


def _accuracy(out, args, command):
    """The accuracy study written into `out`; its summary."""
    from . import accuracy

    study = accuracy.run(quick=args.quick, mus=args.mu,
                         step=lambda text: print(text, file=sys.stderr, flush=True))
    header = ["# The speed-accuracy trade", "", provenance(command),
              f"The run took {study['wall_s']:.0f} s. Do not edit by hand."]
    write_atomic(out / "accuracy.md", "\n".join(accuracy.markdown(study, header)) + "\n")
    write_atomic(out / "accuracy.json", json.dumps(study, indent=1, allow_nan=False))
    save_figure(accuracy.figure(study), out / "accuracy.png")
    return {"files": ["accuracy.md", "accuracy.json", "accuracy.png"], "wall_s": study["wall_s"]}


def _advisor(out, scenes, command):
    """The advisor's table for `scenes` written into `out`; its summary."""
    from . import advisor_table

    study = advisor_table.run(scenes, step=advisor_table.progress)
    header = ["# The scene advisor on the example scenes", "", provenance(command),
              f"The run took {study['wall_s']:.0f} s. Do not edit by hand."]
    write_atomic(out / "advisor.md", advisor_table.markdown(study, header) + "\n")
    write_atomic(out / "advisor.json", json.dumps(study, indent=1, allow_nan=False))
    return {"files": ["advisor.md", "advisor.json"], "wall_s": study["wall_s"]}


def _run(args, command, out):
    """The command's outputs written into `out`; its summary."""
    if args.command == "accuracy":
        return _accuracy(out, args, command)
    if args.command == "advisor":
        return _advisor(out, args.scenes, command)
    if args.command == "single-asperity":
        return {"files": [name for name, _ in SINGLE_FILES], **_single(out, args, 1, 2)[1]}
    if args.command == "rough-surface":
        return {"files": [name for name, _ in ROUGH_FILES], **_rough(out, args, 1, 2)[1]}
    if args.command == "rough-explicit":
        files = EXPLICIT_FILES + (EXPLICIT_MAP_FILES if args.full else ())
        return {"files": [name for name, _ in files],
                **_explicit(out, args, 1, 1, command)[1]}
    if args.command == "layered":
        return {"files": [name for name, _ in LAYERED_FILES],
                **_layered(out, args, 1, 2, command)[1]}
    return run_all(out, command, args)


#: The report each command's verdicts are read in (`all`: the combined one).
REPORTS = {"all": "report.md", "single-asperity": "single_asperity/report.md",
           "rough-surface": "rough_surface.md"}


def verdict_counts(summary):
    """One line per kind of claim in `summary` ('closed-form checks: 12 hold, 1 fails, 3
    notes'), then the claims that fail, by name."""
    lines, failing = [], []
    for key, name in (("checks", "closed-form checks"), ("single_asperity", "single-asperity "
                      "claims"), ("rough_surface", "rough-surface claims"),
                      ("rough_surface_solved_law", "rough-surface claims with the solved law")):
        if key in summary:
            verdicts = [v.get("verdict") or ("holds" if v["holds"] else "fails")
                        for v in summary[key]]
            lines.append(f"{name}: {counted(verdicts.count('holds'), 'holds', 'hold')}, "
                         f"{counted(verdicts.count('fails'), 'fails', 'fail')}, "
                         f"{counted(verdicts.count('note'), 'note', 'notes')}")
            failing += [v["claim"] + (" (with the solved law)" if key.endswith("law") else "")
                        for v, verdict in zip(summary[key], verdicts) if verdict == "fails"]
    return lines, failing


def _tell(args, summary):
    """The summary for people."""
    print(f"wrote {', '.join(summary['files'])} to {args.out}/")
    report = REPORTS.get(args.command, "report.md")
    for line in verdict_counts(summary)[0]:
        print(f"{line} (see {report})")
    if args.command == "all" and PENDING:
        print(f"not yet available: {counted(len(PENDING), 'item', 'items')} (see {report})")


def main(argv=None):
    parser = build_parser()
    args = parser.parse_args(argv)
    if getattr(args, "jobs", None) is not None and args.jobs < 1:
        parser.error(f"--jobs must be a whole number >= 1; got {args.jobs}")  # before any work
    if args.command == "bench":
        from .bench import run as run_bench

        return run_bench(as_json=args.json)
    if args.command == "accuracy" and args.mu:
        solvable_mu(args.mu, "--mu")
    if args.command in ("all", "rough-surface"):
        positive("--compare-mu", args.compare_mu)  # before anything is written
    if args.command == "advisor":
        from advisor.scene import read_scene

        from .advisor_table import default_scenes

        args.scenes = args.scenes or default_scenes()
        for path in args.scenes:  # every file checked before anything is written
            read_scene(path)
    if getattr(args, "ship", False) and not args.full:
        parser.error("--ship writes the map: it needs --full")
    output_folder(args.out, "--out", PROG)
    keep_freed_memory()  # this process is ours: large maps' fields are reused, not refaulted
    command = " ".join([PROG] + (sys.argv[1:] if argv is None else list(argv)))
    # All or nothing as a set: written into a staging folder, moved into --out at the end (each
    # file or folder of the set replacing its namesake; what the other commands of validation
    # wrote there stays, and so does what none of them wrote).
    with staged_folder(args.out, owner=PROG, whole=False) as stage:
        summary = {"out": str(args.out), **_run(args, command, stage)}
    if getattr(args, "ship", False):  # once the whole set is in --out
        from gw.explicit.measured_map import MAP_FILE

        write_atomic(MAP_FILE, (args.out / "rough_explicit" / "rough_map.json").read_text())
        print(f"wrote {MAP_FILE}", file=sys.stderr)
    if args.json:
        dump_json(summary)
    else:
        _tell(args, summary)
    return 0


if __name__ == "__main__":
    sys.exit(run(main, PROG))
