"""Single asperity: `python -m fem_asperity laws|scales|curve|sweep|onset|scene` (each with
--help).

laws: the paper's closed-form events; scales: E*, the Tabor parameter and the natural scales
from SI inputs; curve: approach and retraction solved by FE or boundary integral; sweep: many
curves over mu in parallel (stored, resumable); onset: the smallest mu with a jump-in; scene: the
scene advisor (`python -m advisor`), a TOML scene in, the cheapest model within its tolerance
out."""

import argparse
import json
import sys
import warnings

from .closed_forms.corrected import CORRECTED_LAWS, MEASURED_MU, MU_JUMP
from .closed_forms.laws import PAPER_LAWS
from .closed_forms.physical_arguments import (
    USAGE,
    add_physical_arguments,
    physical_given,
    physical_scales,
)
from .closed_forms.scales import si_unit
from .plumbing.checks import in_range, positive
from .plumbing.cli import Parser, ProgressBar, dump_json, format_cell, print_table, run
from .plumbing.errors import DerjaguinWarning
from .plumbing.files import output_folder
from .solver.presets import ESTIMATE_BY, METHODS, PRESETS

PROG = "python -m fem_asperity"
EVENT_COLUMNS = ("mu", "p_max", "delta_oc", "delta_o_star", "a_c", "jump_in", "x_oc")
LAWS_LEGEND = """\
Paper closed-form laws (Song & Komvopoulos eqs. 2, 6, 7, 10, 12, 13); jump-in for mu >= 0.5.
p_max: max adhesive force / (2 pi R dgamma), < 0 tensile; delta_oc, delta_o_star: separation at
p_max and at first contact / eps; a_c: compressive contact radius at p_max / sqrt(eps R);
x_oc: centre gap at jump-in / eps ('-' where there is no jump-in).
With physical inputs, the columns ending in _N (newtons) and _m (metres) are the same in SI."""
CORRECTED_LEGEND = """\
Corrected closed-form law (docs/corrected_law.md: the paper's pieces joined as the solved curves
are); jump-in from mu = {onset} (the measured onset).
p_max: max adhesive force / (2 pi R dgamma), < 0 tensile; delta_oc: separation at p_max / eps;
delta_o_star: separation at first contact, the jump / eps; a_c, x_oc: not given by this law.
Against the solved curves at mu {lo:g}-{hi:g}: p_max within 0.5%, delta_oc 6.7%, delta_o_star 7.4%
(the paper's laws: 5.5%, 48%, 6.4%; test_corrected_law.py pins these).
With physical inputs, the columns ending in _N (newtons) and _m (metres) are the same in SI."""


def build_parser():
    parser = Parser(prog=PROG, description=__doc__)
    commands = parser.add_subparsers(dest="command", required=True)

    laws = commands.add_parser("laws", help="events predicted by the paper's closed-form laws "
                               "(or the corrected law)")
    laws.add_argument("--mu", type=float, nargs="+",
                      help=f"Tabor parameter(s), > 0; or the physical inputs ({USAGE})")
    laws.add_argument("--form", choices=("paper", "corrected"), default="paper",
                      help="the paper's laws (eqs. 2-13), or the corrected law: the paper's "
                           "physics in the solved curves' shape (docs/corrected_law.md); "
                           "default: %(default)s")
    add_physical_arguments(laws)
    laws.add_argument("--json", action="store_true",
                      help="print a JSON list (one object per mu) instead of a table")

    scales = commands.add_parser("scales", help="E*, Tabor parameter and natural scales")
    add_physical_arguments(scales)
    scales.add_argument("--json", action="store_true", help="print JSON instead of a table")

    curve = commands.add_parser("curve", help="approach + retraction: events and curves")
    curve.add_argument("--mu", type=float,
                       help="Tabor parameter (substrate E*); or the physical inputs below")
    add_physical_arguments(curve)
    curve.add_argument("--profile", choices=("sphere", "derjaguin"),
                       help="the sphere's exact gap, or Derjaguin's parabola (the paper's; "
                            "results then depend on mu alone). Default with physical inputs: "
                            "sphere; with --mu: derjaguin (no R/eps)")
    curve.add_argument("--method", choices=METHODS, default="fem",
                       help="fem: finite elements; bem: boundary integral (a layer through its "
                            "Hankel-transform kernel), faster (default: %(default)s)")
    curve.add_argument("--accuracy", choices=tuple(PRESETS),
                       help="mesh and step resolution (default: default)")
    curve.add_argument("--tolerance", type=float,
                       help="instead of a preset: refine from draft until P_max and P_off "
                            "change by at most this (relative) between two levels")
    curve.add_argument("--layer-thickness", type=float,
                       help="layer thickness: in m with physical inputs, else t / sqrt(R eps) "
                            "(omit: homogeneous half-space)")
    curve.add_argument("--layer-modulus-ratio", type=float,
                       help="E*_layer / E*_substrate (default: 1); with physical inputs E* (or "
                            "--E1 --nu1) is the substrate's and the sphere rigid")
    curve.add_argument("--layer-E", dest="layer_E", type=float,
                       help="layer's Young's modulus [Pa] (physical inputs; with --layer-nu, "
                            "instead of --layer-modulus-ratio; the sphere must be rigid)")
    curve.add_argument("--nu", type=float,
                       help="substrate Poisson's ratio (default: --nu1, else 0.3)")
    curve.add_argument("--layer-nu", type=float, help="layer Poisson's ratio (default: --nu)")
    curve.add_argument("--spring-constant", type=float,
                       help="load-line control through a spring (an AFM cantilever): its "
                            "stiffness in N/m with physical inputs, else k = K eps/(2 pi R "
                            "dgamma); jumps where dP/d(delta) reaches it (omit: displacement "
                            "control)")
    curve.add_argument("--no-error-estimate", action="store_true",
                       help="skip the error estimate (faster)")
    curve.add_argument("--estimate-by", choices=ESTIMATE_BY,
                       help="how the error estimate is made: 'finer', the events solved again "
                            "on a finer discretisation near each; 'bem', the FE of a "
                            "homogeneous half-space against the boundary integral's curve plus "
                            "that curve's own estimate; 'auto' (default), 'bem' where it "
                            "applies, else 'finer'")
    curve.add_argument("--unstable-branch", action="store_true",
                       help="also trace the unstable branches (the whole S-shaped curve in "
                            "equilibrium.csv and curve.png; slower: LU factorisations and short "
                            "steps on the unstable branches)")
    curve.add_argument("--out",
                       help="folder for curve CSVs, curve.png, result.json, VTU/PNG fields")
    curve.add_argument("--json", action="store_true", help="print JSON instead of a table")

    sweep = commands.add_parser("sweep", help="curves over mu, in parallel, into events.csv "
                                              "and curves.csv (resumable)")
    which = sweep.add_mutually_exclusive_group()
    which.add_argument("--mu", type=float, nargs="+", help="Tabor parameters, > 0")
    which.add_argument("--mu-range", type=float, nargs=3, metavar=("LO", "HI", "N"),
                       help="N values from LO to HI, evenly spaced in log mu")
    physical = sweep.add_argument_group(
        "physical inputs", f"instead of --mu: {USAGE}, each with one or more values (those with "
        "several are swept together; events.csv gains SI columns). The curves use the paper's "
        "Derjaguin profile, whose pull-off error is about 1.6 eps/R")
    add_physical_arguments(physical, several=True)
    sweep.add_argument("--method", choices=METHODS, default="fem",
                       help="solver of each curve (default: %(default)s)")
    sweep.add_argument("--accuracy", choices=tuple(PRESETS), default="default",
                       help="resolution of each curve (default: %(default)s)")
    sweep.add_argument("--no-error-estimate", action="store_true",
                       help="skip each curve's error estimate (faster)")
    sweep.add_argument("--estimate-by", choices=ESTIMATE_BY,
                       help="how each curve's error estimate is made (as for curve)")
    sweep.add_argument("--jobs", type=int, help="worker processes (default: one per core)")
    sweep.add_argument("--scheduler", metavar="ADDRESS",
                       help="run on the Dask cluster of this scheduler (tcp://host:8786) "
                            "instead of local processes (extra 'cluster')")
    sweep.add_argument("--out", required=True, help="folder for events.csv, curves.csv, "
                                                    "sweep.json")
    sweep.add_argument("--json", action="store_true", help="print the events as a JSON list")

    scene = commands.add_parser("scene", add_help=False,
                                help="the scene advisor: a TOML scene in, the cheapest model "
                                     "within its tolerance out (python -m advisor; scene --help)")
    scene.add_argument("advisor_arguments", nargs=argparse.REMAINDER,
                       help="FILE [--json] [--run --out DIR]: as python -m advisor")
    onset = commands.add_parser("onset", help="smallest mu with a jump-in (displacement control)")
    onset.add_argument("--method", choices=METHODS, default="bem",
                       help="solver of each curve (default: %(default)s)")
    onset.add_argument("--accuracy", choices=tuple(PRESETS), default="default",
                       help="resolution of each curve (default: %(default)s)")
    onset.add_argument("--bracket", type=float, nargs=2, default=(0.3, 1.0), metavar=("LO", "HI"),
                       help="mu without and with a jump-in (default: 0.3 1.0)")
    physical = onset.add_argument_group(
        "physical inputs", f"optional ({USAGE}): whether this contact jumps in, and the value of "
        "each input (the others held) at which it starts to")
    add_physical_arguments(physical)
    onset.add_argument("--json", action="store_true", help="print JSON instead of a table")
    return parser


def _laws(args, parser):
    if (args.mu is None) != physical_given(args):
        parser.error(f"laws: give either --mu or the physical inputs ({USAGE})")
    scales = physical_scales(args, parser.error, "laws")
    mus = [scales.mu] if scales else args.mu
    if args.form == "corrected":
        rows = [row | {"form": "corrected"} for row in CORRECTED_LAWS.events(mus).records()]
        lo, hi = MEASURED_MU
        for mu in mus:
            if not lo <= mu <= hi:
                print(f"note: mu = {mu:g} is outside the mu the corrected law was fitted to and "
                      f"measured at ({lo:g}-{hi:g}): its error there is not known",
                      file=sys.stderr)
        legend = CORRECTED_LEGEND.format(onset=MU_JUMP, lo=lo, hi=hi)
    else:
        rows, legend = PAPER_LAWS.events(mus).records(), LAWS_LEGEND
    si = scales.si_columns(rows[0]) if scales else {}  # physical inputs: one mu, one row
    if scales:
        rows[0]["si"] = scales.to_si(rows[0])
    if args.json:
        dump_json(rows)  # a list, one object per mu, whatever their number
    else:
        print(legend)
        print_table([rows[0] | si] if scales else rows, EVENT_COLUMNS + tuple(si))


def _scales(args, parser):
    s = physical_scales(args, parser.error, "scales")
    if s is None:
        parser.error(f"scales: give the physical inputs ({USAGE})")
    row = {"E_star": s.E_star, "mu": s.mu, "R_over_eps": s.R / s.eps, "length_z": s.length_z,
           "length_r": s.length_r, "force": s.force, "area": s.area, "traction": s.traction}
    if args.json:
        dump_json(row)
    else:
        units = {"E_star": "Pa", "mu": "-", "R_over_eps": "-", "length_z": "m (eps)",
                 "length_r": "m (sqrt(R eps))", "force": "N (2 pi R dgamma)",
                 "area": "m^2 (eps R)", "traction": "Pa (dgamma/eps)"}
        print_table([{"quantity": k, "value": v, "unit": units[k]} for k, v in row.items()],
                    ("quantity", "value", "unit"))


def _curve(args, parser):
    from .plumbing.errors import ContinuationError
    from .solver.output import OWNER, write_all
    from .solver.solve import SOFT_SPRING, SPRING_RANGE, solve_curve, solve_to_tolerance

    mu, scales, radius_ratio = _curve_inputs(args, parser)
    if args.out is not None:
        output_folder(args.out, "--out", OWNER)  # before solving
    if args.spring_constant is not None and args.tolerance is not None:
        parser.error("curve: --spring-constant takes a preset (--accuracy), not --tolerance")
    if args.tolerance is not None and (args.estimate_by or args.accuracy
                                       or args.no_error_estimate):
        parser.error("curve: --tolerance refines until the change between its levels (its "
                     "estimate) meets it; --accuracy, --estimate-by and --no-error-estimate "
                     "go with a preset instead")
    _estimate_options(args, parser, "curve")
    solid = _solid(args, parser, scales)
    spring = args.spring_constant
    if spring is not None:  # with physical inputs N/m → 2πRΔγ/ε, the range said in N/m
        per = scales.eps / scales.force if scales is not None else 1.0
        lo, hi = (k / per for k in SPRING_RANGE)
        spring = in_range("--spring-constant", spring, lo, hi, closed_lo=True,
                          unit="N/m" if scales is not None else "", why=SOFT_SPRING) * per
    bar = ProgressBar(f"{args.method.upper()} curve mu={mu:g}")
    try:
        if args.tolerance is not None:
            result = solve_to_tolerance(mu, args.tolerance, method=args.method, solid=solid,
                                        radius_ratio=radius_ratio,
                                        unstable_branch=args.unstable_branch, progress=bar)
        else:
            result = solve_curve(mu, method=args.method, accuracy=args.accuracy or "default",
                                 solid=solid, radius_ratio=radius_ratio,
                                 error_estimate=not args.no_error_estimate,
                                 estimate_by=args.estimate_by,
                                 unstable_branch=args.unstable_branch, spring_constant=spring,
                                 progress=bar)
    except ContinuationError as exc:
        print(f"{PROG}: continuation failed: {exc}", file=sys.stderr)
        return 1
    bar.close()
    if result.status != "ok":
        print(f"warning: {result.message}", file=sys.stderr)
    row = result.records(scales)
    if args.out is not None:  # the same record as on stdout, the paths in SI beside
        write_all(result, args.out, scales=scales)
    if args.json:
        dump_json(row)
    else:
        estimates = ("error_estimate", "relative_error_estimate")
        absolute, relative = (row[key] or {} for key in estimates)
        # below the table, not in it: a message is a sentence, and would widen every column
        provenance = ("layer_groups", "inputs", "version", "solver_revision", "si",
                      "estimate_floor", "message")
        si = row.get("si", {})
        print_table([{"quantity": k, "value": v, "error_estimate": absolute.get(k),
                      "relative": relative.get(k), "SI": _si_text(k, si.get(k))}
                     for k, v in row.items() if k not in estimates + provenance],
                    ("quantity", "value", "error_estimate", "relative")
                    + (("SI",) if si else ()))
        if row["message"]:
            print(f"message: {row['message']}")
        if row["layer_groups"]:
            print("layer: " + ", ".join(f"{k} {format_cell(v)}"
                                        for k, v in row["layer_groups"].items()))
        print(f"version {row['version']}, solver revision {row['solver_revision']}; inputs "
              f"{json.dumps(row['inputs'])}")
    return 0


def _curve_inputs(args, parser):
    """(μ, `Scales` or None, R/ε of the exact sphere or None) of `curve`: --mu, or the physical
    inputs, never both."""
    if (args.mu is None) != physical_given(args):
        parser.error(f"curve: give either --mu or the physical inputs ({USAGE})")
    if args.mu is not None:
        if args.profile == "sphere":
            parser.error("curve: --profile sphere needs R/eps: give the physical inputs "
                         "instead of --mu")
        return args.mu, None, None
    sphere = args.profile != "derjaguin"
    with warnings.catch_warnings():
        if sphere:  # the Derjaguin warning is moot: the exact sphere is solved
            warnings.simplefilter("ignore", DerjaguinWarning)
        scales = physical_scales(args, parser.error, "curve")
    return scales.mu, scales, (scales.R / scales.eps if sphere else None)


def _solid(args, parser, scales):
    """The `Solid` of `curve`: the layer's thickness in √(Rε) (converted from m with physical
    inputs), its modulus ratio (given, or from --layer-E and --layer-nu against the substrate's
    E*) and the Poisson's ratios."""
    from .solids.fe import LAYER_THICKNESS, Solid

    layered = (args.layer_modulus_ratio, args.layer_nu, args.layer_E)
    if args.layer_thickness is None and any(v is not None for v in layered):
        parser.error("curve: --layer-modulus-ratio, --layer-E and --layer-nu need "
                     "--layer-thickness")
    if args.nu is not None and args.nu1 is not None and args.nu != args.nu1:
        parser.error("curve: --nu and --nu1 are the half-space's Poisson's ratio; give one")
    nu = next(v for v in (args.nu, args.nu1, 0.3) if v is not None)
    layer_nu = nu if args.layer_nu is None else args.layer_nu
    thickness, ratio = args.layer_thickness, args.layer_modulus_ratio
    if thickness is not None and args.E2 is not None:
        parser.error("curve: a layer needs a rigid sphere (no --E2 --nu2): E* lumps the "
                     "sphere's compliance into a homogeneous half-space only; with a layer, "
                     "--E-star or --E1 --nu1 is the substrate's")
    if args.layer_E is not None:
        if scales is None or ratio is not None:
            parser.error("curve: --layer-E goes with the physical inputs, instead of "
                         "--layer-modulus-ratio")
        layer_e_star = positive("--layer-E", args.layer_E, unit="Pa") / (1.0 - layer_nu**2)
        ratio = layer_e_star / scales.E_star
    if thickness is not None and scales is not None:  # m → √(Rε), its range said in m
        lo, hi = (bound * scales.length_r for bound in LAYER_THICKNESS)
        unit = f"m ({LAYER_THICKNESS[0]:g}-{LAYER_THICKNESS[1]:g} sqrt(R eps))"
        thickness = in_range("--layer-thickness", thickness, lo, hi, closed_lo=True,
                             unit=unit) / scales.length_r
    return Solid(nu=nu, layer_thickness=thickness,
                 layer_modulus_ratio=1.0 if ratio is None else ratio, layer_nu=layer_nu)


def _estimate_options(args, parser, command):
    """--estimate-by only with the estimate, 'auto' where not given."""
    if args.no_error_estimate and args.estimate_by is not None:
        parser.error(f"{command}: --estimate-by says how the error estimate is made; "
                     "--no-error-estimate skips it")
    args.estimate_by = args.estimate_by or "auto"


def _si_text(key, value):
    """An SI value with its unit for the table ('' where the key has none)."""
    return "" if value is None else f"{value:.6g} {si_unit(key)}"


def _sweep(args, parser):
    from .studies.store import mu_key
    from .studies.sweep import OWNER, mu_range, sweep

    if (args.mu is None and args.mu_range is None) != physical_given(args):
        parser.error(f"sweep: give one of --mu, --mu-range or the physical inputs ({USAGE})")
    scales = physical_scales(args, parser.error, "sweep", several=True)
    _estimate_options(args, parser, "sweep")
    out = output_folder(args.out, "--out", OWNER)  # before solving
    mus = ([s.mu for s in scales] if scales else
           mu_range(*args.mu_range) if args.mu_range else args.mu)
    if scales and len({mu_key(mu) for mu in mus}) < len(mus):
        parser.error("sweep: two sets of physical inputs give the same mu (a sweep solves by "
                     "mu); vary the inputs so that mu changes")
    bar = ProgressBar(f"{args.method.upper()} sweep of {len(mus)} mu", time_left=True)
    result = sweep(mus, method=args.method, accuracy=args.accuracy,
                   error_estimate=not args.no_error_estimate, estimate_by=args.estimate_by,
                   jobs=args.jobs,
                   scheduler=args.scheduler, progress=bar, scales=scales or ())
    bar.close()
    result.write(out)
    print(f"{result.solved} solved, {result.stored} read from the store, {len(result.failed)} "
          f"failed; files in {out}", file=sys.stderr)
    for row in result.rows:
        if row.status != "ok":
            print(f"warning: mu = {row.mu:g}: {row.status}: {row.message}", file=sys.stderr)
    table = result.events_table()
    if args.json:
        dump_json(table)
    else:
        si = ("p_off_N", "delta_oc_m") if scales else ()
        print_table(table, ("mu", "status", "p_max", "p_off", "delta_oc", "a_c", "jump_in",
                            "x_oc", "p_off_err", "wall_s") + si)
    return 1 if result.failed else 0


def _onset(args, parser):
    from .plumbing.errors import ContinuationError
    from .studies.onset import jump_in_onset

    scales = physical_scales(args, parser.error, "onset")
    try:
        row = jump_in_onset(method=args.method, accuracy=args.accuracy,
                            bracket=tuple(args.bracket)).records()
    except ContinuationError as exc:
        print(f"{PROG}: continuation failed: {exc}", file=sys.stderr)
        return 1
    if scales is not None:
        critical = scales.at_mu(row["mu_onset"])
        row["si"] = {"mu": scales.mu, "jumps_in": scales.mu > row["mu_onset"],
                     "E_star_max": critical["E_star"], "R_min": critical["R"],
                     "dgamma_min": critical["dgamma"], "eps_max": critical["eps"]}
    if args.json:
        dump_json(row)
    else:
        units = {"E_star_max": "Pa", "R_min": "m", "dgamma_min": "J/m^2", "eps_max": "m"}
        rows = [{"quantity": k, "value": v, "unit": ""} for k, v in row.items() if k != "si"]
        rows += [{"quantity": k, "value": v, "unit": units.get(k, "")}
                 for k, v in row.get("si", {}).items()]
        print_table(rows, ("quantity", "value", "unit"))
        if scales is not None:
            print("this contact (mu = si.mu) jumps in under displacement control iff mu > "
                  "mu_onset; each *_min/*_max is the input at which it starts to, the others "
                  "held")
    return 0


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv[:1] == ["scene"]:  # before parsing: the advisor's own options, --help among them
        return _scene(argv[1:])
    parser = build_parser()
    args = parser.parse_args(argv)
    return {"laws": _laws, "scales": _scales, "curve": _curve, "sweep": _sweep,
            "onset": _onset}[args.command](args, parser) or 0


def _scene(argv):
    """`scene`: the advisor's own command line. The advisor sits above fem_asperity and gw
    (docs/ARCHITECTURE.md), so only the command line is handed over, here, when asked for."""
    from advisor.__main__ import main as advise

    return advise(argv, prog=f"{PROG} scene")


if __name__ == "__main__":
    sys.exit(run(main, PROG))
