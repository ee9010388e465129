"""Greenwood-Williamson rough surface with adhesion: `python -m gw fmax|curve|explicit` (each
with --help).

fmax: the strength of adhesion F̄max and the separation d̃ where it occurs; curve: the total force
F̄ and contact area S̄ against d̃. Inputs dimensionless (--mu, --zeta, --omega or --sigma-r-eta)
or in SI; the asperity law is the paper's, the shipped table of solved laws, refitted, or a
solved FE/BEM curve (--law). law-table: rebuild that table and measure its error.
explicit: your own topography (a height map) answered by GW, interacting asperities and the
whole surface solved, in SI, with the model the surface needs."""

import argparse
import sys
from functools import partial
from pathlib import Path

import numpy as np

from fem_asperity.closed_forms.physical_arguments import (
    USAGE,
    add_physical_arguments,
    physical_given,
    physical_scales,
)
from fem_asperity.plumbing.checks import in_range
from fem_asperity.plumbing.cli import Parser, ProgressBar, dump_json, print_table, run, shown
from fem_asperity.solver.presets import PRESETS
from fem_asperity.solver.solve import solvable_mu
from fem_asperity.studies.refit import stored_refit

from .corrected_law import ERROR_FILE, stated_error
from .explicit import cli as explicit_command
from .integrate import D_MAX, check_stiffness, separation_range, strength, totals
from .law_table import TABLE_FILE, TableLaw, shipped_table
from .laws import CorrectedLaw, PaperLaw
from .shared_ground import flat_bound, shared_ground
from .surface import RoughSurface, omega_mccool
from .tables import solved_law

PROG = "python -m gw"
#: --compare warns where the paper's law is off the solved law by more than this fraction of F̄max.
COMPARE_WARNING = 0.1
#: Most d values of `curve`: far more than a plot needs, while the memory grows as about 220
#: floats per point and piece (1e8 points asked for 164 GiB). test_gw pins the bound.
POINTS_MAX = 10_000
#: Laws solved at --mu (a curve of that solver), which takes mu in solver.solve.MU_RANGE only.
SOLVED = ("fem", "bem")
LAWS = ("paper", "corrected", "solved", "refit") + SOLVED
#: `--compare`'s name for the solved law's own interpolation error, a fraction of the law's
#: largest |P̄| (not of F̄max: read beside relative_to_solved it looked like an error bar).
LAW_ERROR = "law_interpolation_error_of_max_force"


def _common(parser):
    parser.add_argument("--mu", type=float, help="Tabor parameter of the asperities")
    parser.add_argument("--zeta", type=float, help="sigma / eps")
    parser.add_argument("--omega", type=float, help="sigma_s / sigma (default 1, or eq. 20)")
    parser.add_argument("--sigma-r-eta", type=float, help="sigma R eta: omega from eq. 20")
    physical = parser.add_argument_group(
        "physical inputs", f"instead of --mu --zeta --omega: --sigma, --density and {USAGE} "
        "(aliases --estar, --work-of-adhesion, --radius); the outputs gain SI values")
    physical.add_argument("--sigma", type=float, help="rms roughness [m]")
    physical.add_argument("--density", type=float, help="asperity density eta [1/m^2]")
    add_physical_arguments(physical)
    parser.add_argument("--law", choices=LAWS, default="paper",
                        help="paper: the paper's closed forms; corrected: the corrected closed "
                             "form (docs/corrected_law.md; its measured F_max error goes into "
                             "the output); solved: the table of BEM-solved "
                             "laws shipped with the package (mu 0.01-50, no solve; its measured "
                             "error goes into the output); refit: the paper's forms with the "
                             "constants refitted from BEM curves (stored); fem, bem: the approach "
                             "curve of that solver at this mu, solved once and stored "
                             "(default: paper)")
    parser.add_argument("--accuracy", choices=tuple(PRESETS),
                        help="resolution of the solved curves behind --law refit, fem, bem and "
                             "fmax --compare (default: default)")
    parser.add_argument("--json", action="store_true", help="print JSON instead of a table")


def build_parser():
    parser = Parser(prog=PROG, description=__doc__)
    commands = parser.add_subparsers(dest="command", required=True)
    fmax = commands.add_parser("fmax", help="strength of adhesion F_max and its separation")
    _common(fmax)
    fmax.add_argument("--compare", action="store_true",
                      help="the paper's law, the refitted law, the corrected law and the "
                           "solved law (of --law fem or bem; default bem) side by side, with "
                           "their relative differences and the solved law's interpolation error")
    fmax.add_argument("--warn-above", type=float,
                      help="--compare warns where the paper's F_max is off the solved law's by "
                           f"more than this fraction (default: {COMPARE_WARNING})")
    curve = commands.add_parser("curve", help="F and S against the mean separation d / sigma")
    _common(curve)
    curve.add_argument("--d", type=float, nargs=2, metavar=("MIN", "MAX"),
                       help=f"range of d / sigma, MIN < MAX, both within +-{D_MAX:g} "
                            "(default: around the law's breakpoints)")
    curve.add_argument("--points", type=int, default=101,
                       help=f"number of d values, 2 to {POINTS_MAX} (default: %(default)s)")
    explicit_command.add_parser(commands)
    table = commands.add_parser("law-table", help="rebuild the table of solved laws (--law "
                                "solved) from the sweep engine and measure its error")
    table.add_argument("--out", help="the table file (default: the package's own, "
                                     f"{TABLE_FILE.name})")
    table.add_argument("--jobs", type=int, help="worker processes (default: one per core)")
    table.add_argument("--report", help="also write the measured errors as Markdown to this "
                                        "file (docs/law_table.md is this)")
    table.add_argument("--json", action="store_true", help="print the errors as JSON")
    corrected = commands.add_parser(
        "corrected-law", help="measure the corrected closed form's F_max error against the "
        "table of solved laws (--fit: refit its constants first, minutes)")
    corrected.add_argument("--fit", action="store_true",
                           help="refit the constants to the table and print them with 95%% "
                                "intervals; needs --out (the package's own constants change "
                                "only by editing fem_asperity/closed_forms/corrected.py)")
    corrected.add_argument("--out", help="the error file (default: the package's own, "
                                         f"{ERROR_FILE.name})")
    corrected.add_argument("--report", help="also write the form, constants and errors as "
                                            "Markdown to this file (docs/corrected_law.md)")
    corrected.add_argument("--json", action="store_true", help="print the errors as JSON")
    return parser


def _inputs(args, parser):
    """(mu, RoughSurface, Scales or None) from either dimensionless or physical arguments."""
    if physical_given(args) or args.sigma is not None or args.density is not None:
        dimensionless = (args.mu, args.zeta, args.omega, args.sigma_r_eta)
        if None in (args.sigma, args.density) or any(v is not None for v in dimensionless):
            parser.error(f"physical inputs need --sigma, --density and {USAGE}, and none of "
                         "--mu --zeta --omega --sigma-r-eta (they follow from the physical "
                         "inputs: omega from eq. 20)")
        scales = physical_scales(args, parser.error, args.command)
        surface = RoughSurface.from_physical(sigma=args.sigma, radius=scales.R,
                                             density=args.density, eps=scales.eps)
        return scales.mu, surface, scales
    if args.mu is None or args.zeta is None:
        parser.error("give --mu and --zeta (or the physical inputs)")
    if args.omega is not None and args.sigma_r_eta is not None:
        parser.error("give --omega or --sigma-r-eta, not both")
    omega = args.omega if args.sigma_r_eta is None else float(omega_mccool(args.sigma_r_eta))
    return args.mu, RoughSurface(zeta=args.zeta, omega=1.0 if omega is None else omega), None


def _check(args, parser, mu, surface):
    """Refuse every bad input up front, before a refit or a solved curve (minutes) is computed:
    mu in the closed forms' range, and in solver.solve.MU_RANGE for a solved law; zeta/mu and
    1/mu below RATIO_MAX; each option used by the command and --law given (one usage line
    otherwise); --warn-above > 0; --points in [2, POINTS_MAX]; --d finite, within +-D_MAX,
    MIN < MAX."""
    compare = args.command == "fmax" and args.compare
    check_stiffness(PaperLaw(mu), surface)
    if args.law in SOLVED or compare:
        solvable_mu(mu, "mu of a solved law (--law fem|bem, fmax --compare)")
    if args.law == "solved":
        shipped_table().check_mu(mu)
    if args.accuracy is not None and args.law in ("paper", "corrected", "solved") \
            and not compare:
        parser.error(f"{args.command}: --accuracy applies to --law refit|fem|bem and fmax "
                     "--compare (the paper's and the corrected laws are closed-form and the "
                     "table's resolution is fixed: nothing to resolve)")
    if args.command == "fmax":
        if args.warn_above is not None and not compare:
            parser.error("fmax: --warn-above needs --compare")
        if compare and args.law in ("refit", "corrected"):
            parser.error("fmax --compare: --law chooses the solved law's method (fem or bem)")
        if args.warn_above is not None:
            in_range("--warn-above", args.warn_above, 0.0, np.inf)
        return
    if not 2 <= args.points <= POINTS_MAX:
        parser.error(f"curve: --points must be from 2 to {POINTS_MAX}; got {args.points}")
    if args.d is not None:
        lo, hi = in_range("--d", args.d, -D_MAX, D_MAX)
        if not lo < hi:
            parser.error(f"curve: --d MIN MAX needs MIN < MAX; got {lo:g} {hi:g}")


def _law(args, mu):
    if args.law == "paper":
        return PaperLaw(mu)
    if args.law == "solved":
        return shipped_table().law(mu)
    if args.law == "corrected":
        return CorrectedLaw(mu)
    accuracy = args.accuracy or "default"
    if args.law == "refit":
        with shown(partial(ProgressBar, time_left=True), "refit's curves (stored for next "
                   "time)") as bar:
            fit = stored_refit(accuracy=accuracy, announce=partial(print, file=sys.stderr),
                               progress=bar)
        return PaperLaw(mu, fit.laws, name="refit")
    bar = ProgressBar(f"{args.law.upper()} curve mu={mu:g} (stored for next time)")
    law = solved_law(mu, method=args.law, accuracy=accuracy, progress=bar)
    if bar.shown >= 0:  # solved now, not read from the store
        bar.close()
    return law


def _si(scales, args, d, force, area=None):
    """The GW outputs in SI: d̃ → d [m]; F̄ = F/(2πR A₀ Δγ η) → F/A₀ [Pa] (force per nominal
    area A₀); S̄ = S/(R A₀ η ε) → S/A₀, the real contact area per nominal area."""
    si = {"d_m": d * args.sigma, "F_Pa": force * scales.force * args.density}
    if area is not None:
        si["S_per_A0"] = area * scales.R * args.density * scales.eps
    return si


def _strength_si(found, scales, args):
    """A `Strength` in SI as the JSON holds it: strength [Pa], d_at_max [m]."""
    si = found.si(scales, sigma=args.sigma, density=args.density)
    return {"strength": si.pressure_max, "d_at_max": si.d_at_max}


def _compare(args, mu, surface, scales):
    """`fmax --compare`: F̄max and its d̃ from the paper's law, the refitted law, the corrected
    law and the solved law, their differences relative to the solved one, a warning where the
    paper's is off by more than --warn-above, and where σRη is known the solved law's F̄max
    with the ground between summits counted once (`_shared_ground`)."""
    threshold = COMPARE_WARNING if args.warn_above is None else args.warn_above
    method = args.law if args.law in SOLVED else "bem"
    laws = {"paper": PaperLaw(mu)}
    found = {"paper": strength(laws["paper"], surface)}  # its refusals before the long work
    laws |= {"refit": _law(_with_law(args, "refit"), mu), "corrected": CorrectedLaw(mu),
             "solved": _law(_with_law(args, method), mu)}
    found |= {name: strength(laws[name], surface) for name in ("refit", "corrected", "solved")}
    solved = found["solved"].f_max
    rows = {name: {"f_max": s.f_max, "d_at_max": s.d_at_max,
                   "relative_to_solved": (s.f_max - solved) / solved}
            for name, s in found.items()}
    if scales is not None:  # physical inputs: the strength [Pa] and its d [m] too
        for name, row in rows.items():
            row["si"] = _strength_si(found[name], scales, args)
    # not an error bar on F_max: how well the tabulated law's PCHIP predicts its own samples
    rows["solved"][LAW_ERROR] = laws["solved"].interpolation_error
    rows["solved"]["method"] = method
    off = rows["paper"]["relative_to_solved"]
    warning = (f"the paper's law puts F_max {off:+.1%} off the solved {method.upper()} law (more "
               f"than {threshold:.0%})" if abs(off) > threshold else None)
    out = {"mu": mu, "zeta": surface.zeta, "omega": surface.omega, **rows, "warning": warning}
    shared = _shared_ground(laws["solved"], surface, found["solved"], _sigma_r_eta(args, scales))
    if shared is not None:  # for the solved law, the reference here
        out["shared_ground"] = shared
    if args.json:
        dump_json(out)
    else:
        si = ("strength_Pa", "d_at_max_m") if scales is not None else ()
        print_table([{"law": name, LAW_ERROR: None,
                      **{k: v for k, v in row.items() if k not in ("method", "si")},
                      **({f"{k}_{u}": row["si"][k] for k, u in (("strength", "Pa"),
                                                                 ("d_at_max", "m"))}
                         if si else {})}
                     for name, row in rows.items()],
                    ("law", "f_max", "d_at_max", "relative_to_solved", LAW_ERROR)
                    + si)
    if shared is not None:
        print(f"note: with the solved law, {shared['note']}", file=sys.stderr)
    if warning:
        print(f"warning: {warning}", file=sys.stderr)
    return 0


def _other_reading(law, surface, found):
    """Where ω < 1, how far McCool's reading of the summit heights is from the one used: eq.
    21 as printed, φ̃ = ω/√(2π) exp(−ω²z̃²/2), spreads them over σ/ω; McCool's σ_s = ωσ over
    ωσ, the printed form at ζω² with d̃ scaled by ω² (z̃ = ω²u). None at ω = 1."""
    if surface.omega >= 1.0:
        return None
    other = strength(law, RoughSurface(surface.zeta * surface.omega**2, surface.omega))
    return {"used": "eq. 21 as printed (summit heights of rms sigma/omega)",
            "other": "McCool's reading (rms sigma_s = omega sigma)",
            "f_max_other": other.f_max, "d_at_max_other": other.d_at_max * surface.omega**2,
            "relative": other.f_max / found.f_max - 1.0}


def _fmax(args, law, surface, scales, head):
    """`fmax` without --compare: F̄max, its d̃, the other ω reading, SI values, the table's
    error (--law solved) and, for the paper's law, a warning where the table puts it off."""
    found = strength(law, surface)
    row = head | {"f_max": found.f_max, "d_at_max": found.d_at_max}
    if isinstance(law, TableLaw):
        row["law_error"] = _table_error(law, found.f_max)
    if isinstance(law, CorrectedLaw):
        row["law_error"] = _corrected_error(law, found.f_max)
    reading = _other_reading(law, surface, found)
    if reading is not None:
        row["omega_reading"] = reading
    shared = _shared_ground(law, surface, found, _sigma_r_eta(args, scales))
    if shared is not None:
        row["shared_ground"] = shared
    if scales is not None:  # physical inputs: the same in SI
        row["si"] = _strength_si(found, scales, args)
    warning = _paper_warning(law, surface, found) if args.law == "paper" else None
    if warning is not None:
        row["warning"] = warning
    if args.json:
        dump_json(row)
    else:
        extra = {"strength [Pa]": row["si"]["strength"],
                 "d_at_max [m]": row["si"]["d_at_max"]} if scales is not None else {}
        if "law_error" in row:  # absolute (F̄max's unit) and relative, as the JSON holds them
            extra["f_max_law_error"] = row["law_error"]["f_max"]
            extra["f_max_law_error_relative"] = row["law_error"]["f_max_relative"]
        print_table([{"quantity": k, "value": v} for k, v in (row | extra).items()
                     if k not in ("si", "omega_reading", "law_error", "warning",
                                  "shared_ground")],
                    ("quantity", "value"))
    if reading is not None:
        print(f"note: omega = {surface.omega:.4g} < 1: {reading['used']}; "
              f"{reading['other']} gives f_max {reading['f_max_other']:.4g} "
              f"({reading['relative']:+.0%})", file=sys.stderr)
    if shared is not None:
        print(f"note: {shared['note']}", file=sys.stderr)
    if warning is not None:
        print(f"warning: {warning}", file=sys.stderr)
    return 0


def _sigma_r_eta(args, scales):
    """σRη where the inputs give it (--sigma-r-eta, or --sigma, R and --density), else None."""
    if scales is not None:
        return args.sigma * scales.R * args.density
    return args.sigma_r_eta


def _shared_ground(law, surface, found, sigma_r_eta):
    """Where σRη is known, GW's F̄max with the ground between summits at random places counted
    once (`gw.shared_ground`, rigid), how far it is from GW's, and the flat bound no surface
    with these LJ tractions pulls beyond; None where σRη is not known."""
    if sigma_r_eta is None:
        return None
    once = strength(law, surface, sigma_r_eta=sigma_r_eta)
    bound = flat_bound(surface.zeta, sigma_r_eta)
    relative = once.f_max / found.f_max - 1.0
    note = (f"at sigma R eta = {sigma_r_eta:.3g}, GW counts the ground between summits once "
            "for every summit whose LJ tail reaches it; counted once (summits at random "
            f"places, rigid: gw.shared_ground) f_max is {once.f_max:.4g} ({relative:+.0%})")
    if found.f_max > bound:
        note += (f"; GW's f_max exceeds {bound:.4g}, the LJ's most tensile traction over the "
                 "whole nominal area, which no surface can pull beyond")
    if once.f_max > bound:
        note += ("; so does the counted-once f_max: each summit's law pulls over more ground "
                 "than the summit has (GW's premise, summits apart, does not hold)")
    return {"sigma_r_eta": sigma_r_eta, "f_max": once.f_max, "d_at_max": once.d_at_max,
            "relative": relative, "flat_bound": bound, "note": note}


def _table_error(law, f_max=None):
    """The table's measured error for a `TableLaw` result: P̄ and the jump-in δ̄o always; with
    F̄max, its absolute error (the relative one measured over the table's ζ)."""
    error = law.error
    out = {"measured_at_mu": error["held_out"], "force": error["force"], "jump": error["jump"]}
    if f_max is not None:
        out |= {"f_max": error["f_max"] * f_max, "f_max_relative": error["f_max"]}
    return out


def _corrected_error(law, f_max=None):
    """The corrected law's error as the JSON holds it: F̄max's measured against the table of
    solved laws, relative and (with `f_max`) absolute; None outside the measured μ, with a
    note."""
    relative = stated_error(law.mu)
    if relative is None:
        return {"f_max": None, "f_max_relative": None,
                "note": "outside the mu of the table of solved laws: not measured"}
    out = {"f_max_relative": relative,
           "against": "the table of solved laws, measured at omega = 1, zeta 0.1-316 "
                      "(docs/corrected_law.md)"}
    return out | ({"f_max": relative * f_max} if f_max is not None else {})


def _paper_warning(law, surface, found):
    """A warning where the table of solved laws puts the paper's F̄max off by more than
    COMPARE_WARNING (None within it, or outside the table's μ)."""
    table = shipped_table()
    lo, hi = table.mu_range
    if not lo <= law.mu <= hi:
        return None
    solved = strength(table.law(law.mu), surface).f_max
    off = found.f_max / solved - 1.0
    if abs(off) <= COMPARE_WARNING:
        return None
    return (f"the paper's law puts F_max {off:+.0%} off the solved law (the shipped table of "
            f"BEM solves; --law solved uses it, fmax --compare shows both)")


def _with_law(args, law):
    """`args` with --law replaced."""
    return argparse.Namespace(**{**vars(args), "law": law})


def main(argv=None):
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.command == "explicit":
        return explicit_command.main(args, parser)
    if args.command == "law-table":
        return _law_table(args, parser)
    if args.command == "corrected-law":
        return _corrected_law(args)
    mu, surface, scales = _inputs(args, parser)
    _check(args, parser, mu, surface)
    if args.command == "fmax" and args.compare:
        return _compare(args, mu, surface, scales)
    law = _law(args, mu)
    head = {"mu": mu, "zeta": surface.zeta, "omega": surface.omega, "law": args.law}
    if args.command == "fmax":
        return _fmax(args, law, surface, scales, head)
    if isinstance(law, TableLaw):
        head["law_error"] = _table_error(law)
    if isinstance(law, CorrectedLaw):
        head["law_error"] = _corrected_error(law)
    lo, hi = separation_range(law, surface) if args.d is None else args.d
    d = np.linspace(lo, hi, args.points)
    force, area = totals(law, surface, d)
    columns = {"d": d, "F": force, "S": area}
    sigma_r_eta = _sigma_r_eta(args, scales)
    if sigma_r_eta is not None:  # GW's F̄ with the ground between summits counted once
        columns["F_once"] = force + shared_ground(surface, sigma_r_eta, d)
    if scales is not None:
        columns |= _si(scales, args, d, force, area)
        columns["F_once_Pa"] = _si(scales, args, d, columns["F_once"])["F_Pa"]
    dimensionless = tuple(k for k in ("d", "F", "S", "F_once") if k in columns)
    if args.json:
        si = ({"si": {k: v.tolist() for k, v in columns.items() if k not in dimensionless}}
              if scales else {})
        dump_json(head | {k: columns[k].tolist() for k in dimensionless} | si)
    else:
        print_table([dict(zip(columns, row)) for row in zip(*columns.values())], tuple(columns))
        if "law_error" in head:
            e = head["law_error"]
            print(f"note: the table's law is off the solved one by |dP| <= {e['force']:.1e} "
                  f"(2 pi R dgamma) away from the jump-in, measured at mu = "
                  + ", ".join(f"{m:.4g}" for m in e["measured_at_mu"]), file=sys.stderr)
    return 0


def _law_table(args, parser):
    """`law-table`: rebuild the table (solving what the store lacks) and print its errors."""
    from fem_asperity.plumbing.files import writable_folder, write_atomic

    from .law_table_build import build_table, report

    if args.jobs is not None and args.jobs < 1:
        parser.error(f"law-table: --jobs must be >= 1; got {args.jobs}")
    out = Path(args.out or TABLE_FILE)
    writable_folder(out.parent, "--out")  # before minutes of solves
    if args.report:
        writable_folder(Path(args.report).parent, "--report")
    bar = ProgressBar("curves of the table (stored for next time)")
    table = build_table(out, jobs=args.jobs, progress=bar)
    bar.close()
    rows = [{"held_out_mu": e["held_out"], "force": e["force"], "jump": e["jump"],
             "f_max_relative": max((abs(x) for x in e["f_max"] if x is not None), default=None)}
            for e in table.errors]
    if args.json:
        dump_json({"record": table.record, "errors": list(table.errors)})
    else:
        print_table(rows, ("held_out_mu", "force", "jump", "f_max_relative"))
        print(f"wrote {out}", file=sys.stderr)
    if args.report:
        write_atomic(args.report, report(table))
    return 0


def _corrected_law(args):
    """`corrected-law`: (refit and) measure the corrected law; write the error file, the report."""
    from fem_asperity.closed_forms.corrected import CORRECTED_LAWS
    from fem_asperity.plumbing.errors import InputError
    from fem_asperity.plumbing.files import writable_folder, write_atomic

    from .corrected_law import fit, intervals, measure, record, report, save_errors

    if args.fit and args.out is None:  # the shipped file belongs to corrected.py's constants
        raise InputError("corrected-law --fit: give --out (the package's error file holds the "
                         "errors of the constants in fem_asperity/closed_forms/corrected.py; "
                         "put the fitted ones there, then run without --fit)")
    out = Path(args.out or ERROR_FILE)
    for path, option in ((out, "--out"), (Path(args.report or out), "--report")):
        if path.is_dir():
            raise InputError(f"{option} must be a file; {path} is a folder")
        writable_folder(path.parent, option)  # before minutes of integrals
    constants, found = CORRECTED_LAWS, None
    if args.fit:
        bar = ProgressBar("fit of the corrected law's constants")
        constants = fit(progress=bar)
        bar.close()
    if args.fit or args.report:
        bar = ProgressBar("95% intervals of the constants")
        found = intervals(constants, progress=bar)
        bar.close()
    bar = ProgressBar("F_max errors of the corrected law at the table's mu")
    rows = measure(constants, progress=bar)
    bar.close()
    made = record("python -m gw corrected-law" + (" --fit" if args.fit else ""))
    save_errors(out, rows, constants, made)
    if args.json:
        dump_json({"constants": vars(constants), "intervals": found, "rows": rows,
                   "record": made})
    else:
        print_table([{"mu": r["mu"], "held_out": r["held_out"], "largest": r["largest"]}
                     for r in rows], ("mu", "held_out", "largest"))
        for name, (lo, hi) in (found or {}).items():
            print(f"{name} = {getattr(constants, name)!r}  (95%: {lo:.6g} to {hi:.6g})",
                  file=sys.stderr)
        print(f"wrote {out}", file=sys.stderr)
    if args.report:
        write_atomic(args.report, report(rows, constants, found, made))
    return 0


if __name__ == "__main__":
    sys.exit(run(main, PROG))
