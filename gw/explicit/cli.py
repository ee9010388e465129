"""`python -m gw explicit`: a user's topography answered in SI (the command line of `answer`)."""

import csv
import io
import sys

from fem_asperity.closed_forms.physical_arguments import add_physical_arguments, physical_given
from fem_asperity.closed_forms.scales import effective_modulus
from fem_asperity.plumbing.cli import ProgressBar, dump_json, print_table
from fem_asperity.plumbing.files import output_folder, save_figure, staged_folder, write_atomic

from .answer import MODELS, answer
from .relax import keep_freed_memory
from .topography import read_topography
from .whole import STEPS, Adhesion

OWNER = "python -m gw explicit"
HELP = ("your own surface: a height map (.npy in m with --pixel-size, or an instrument file "
        "SurfaceTopography reads) answered by GW, interacting asperities and the whole surface "
        "solved, in N, Pa and m")


def add_parser(commands):
    parser = commands.add_parser("explicit", help=HELP, description=HELP)
    parser.add_argument("--topography", required=True, metavar="FILE",
                        help="height map of the rigid surface, the largest heights touching "
                             "first (a cap is -r^2/2R): .npy in metres, or an instrument file")
    parser.add_argument("--pixel-size", type=float, metavar="M",
                        help="pixel side of a .npy map [m]")
    parser.add_argument("--periodic", action="store_true",
                        help="the map repeats (periodic half-space; default: a free patch)")
    physical = parser.add_argument_group(
        "physical inputs", "--E-star (or --E1 --nu1 [--E2 --nu2]), --dgamma and --eps; --R "
        "overrides the summits' measured mean radius")
    add_physical_arguments(physical)
    parser.add_argument("--model", choices=MODELS, default="whole",
                        help="the most expensive model run (each cheaper one runs too; "
                             "default: whole)")
    parser.add_argument("--accuracy", choices=tuple(STEPS), default="default",
                        help="separation step of the whole surface (and of the cheaper "
                             "models' sampling): draft 0.2, default 0.1, fine 0.05 eps")
    parser.add_argument("--json", action="store_true", help="print JSON instead of a table")
    parser.add_argument("--out", metavar="DIR",
                        help="write result.json, approach.csv, retraction.csv, models.png")


def _adhesion(args, parser):
    if not physical_given(args):
        parser.error("explicit: give --E-star (or --E1 --nu1 [--E2 --nu2]), --dgamma, --eps")
    if (args.E_star is None) == (args.E1 is None):
        parser.error("explicit: give --E-star or --E1 --nu1 [--E2 --nu2], one of the two")
    if args.E1 is not None and args.nu1 is None:
        parser.error("explicit: --E1 needs --nu1")
    missing = [f"--{k}" for k in ("dgamma", "eps") if getattr(args, k) is None]
    if missing:
        parser.error(f"explicit: missing {', '.join(missing)}")
    e_star = args.E_star
    if e_star is None:
        e_star = effective_modulus(E1=args.E1, nu1=args.nu1, E2=args.E2, nu2=args.nu2)
    return Adhesion(e_star, args.dgamma, args.eps)


def main(args, parser):
    adhesion = _adhesion(args, parser)
    topography = read_topography(args.topography, pixel=args.pixel_size,
                                 periodic=args.periodic)
    if args.out is not None:
        output_folder(args.out, "--out", OWNER)  # refused before any solving
    bar = ProgressBar("whole surface", time_left=True) if args.model == "whole" else None
    keep_freed_memory()  # this process is ours: the solve's fields are reused, not refaulted
    found = answer(topography, adhesion, model=args.model, accuracy=args.accuracy,
                   radius=args.R, progress=bar)
    if bar is not None:
        bar.close()
    record = answer_record(found, topography)
    if args.out is not None:
        with staged_folder(args.out, owner=OWNER) as stage:
            write_answer(stage, found, record)
    if args.json:
        dump_json(record)
    else:
        print_table([{"model": name, "F_max [N]": m.force_max, "strength [Pa]": m.pressure_max,
                      "d_at_max [m]": m.d_at_max,
                      "vs whole": found.relative_to_whole.get(name), "seconds": m.seconds}
                     for name, m in found.models.items()],
                    ("model", "F_max [N]", "strength [Pa]", "d_at_max [m]", "vs whole",
                     "seconds"))
        if found.needs:
            print(f"this surface needs: {found.needs} (within 10% of the whole surface)")
        radii = found.statistics["radii"]
        if radii["size"] is not None:  # else its note says why
            print(f"{' and '.join(n for n in ('gw', 'interacting') if n in found.models)} take "
                  f"every summit as a cap of radius {found.radius:.4g} m: each at its own "
                  f"({radii['radii'][0]:.3g}-{radii['radii'][1]:.3g} m) moves the uncoupled "
                  f"summits' F_max by {100 * radii['size']:.3g} % "
                  f"(± {100 * radii['uncertainty']:.2g} %)")
    if found.statistics["radii"]["note"]:
        print(f"note: radii: {found.statistics['radii']['note']}", file=sys.stderr)
    if found.whole is not None and found.whole.status != "ok":
        print(f"warning: {found.whole.message}", file=sys.stderr)
    for note in found.notes:
        print(f"note: {note}", file=sys.stderr)
    return 0


def answer_record(found, topography):
    """The JSON-ready record of `found` (an `Answer`) with the map it answered."""
    return found.records() | {"topography": {"source": topography.source,
                                             "pixels": list(topography.shape),
                                             "pixel": topography.pixel,
                                             "periodic": topography.periodic}}


def write_answer(stage, found, record):
    """result.json (`record`), models.png and, where the whole surface was solved, its
    approach.csv and retraction.csv (SI) into the folder `stage`."""
    import json

    write_atomic(stage / "result.json", json.dumps(record, indent=2, allow_nan=False))
    if found.whole is not None:
        for name, path in (("approach", found.whole.approach),
                           ("retraction", found.whole.retraction)):
            text = io.StringIO()
            writer = csv.writer(text)
            writer.writerow(["d_m", "force_N", "contact_area_m2"])
            writer.writerows(zip(path.d, path.force, path.contact_area))
            write_atomic(stage / f"{name}.csv", text.getvalue())
    save_figure(_figure(found), stage / "models.png")


def _figure(found):
    from matplotlib.figure import Figure

    fig = Figure(figsize=(6, 4))
    ax = fig.add_subplot()
    for name, m in found.models.items():
        ax.plot(m.d * 1e9, m.force * 1e9, label=f"{name} (approach)")
    if found.whole is not None:
        ax.plot(found.whole.retraction.d * 1e9, found.whole.retraction.force * 1e9, "--",
                label="whole (retraction)")
    ax.axhline(0.0, color="0.7", lw=0.5)
    ax.set_xlabel("separation d from the map's datum [nm]")
    ax.set_ylabel("total force F [nN] (< 0 tensile)")
    ax.legend()
    return fig
