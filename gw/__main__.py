"""Greenwood-Williamson rough surface with adhesion: `python -m gw fmax|curve` (each with --help).

fmax: the strength of adhesion F̄max and the separation d̃ where it occurs; curve: the total force
F̄ and contact area S̄ against d̃. Inputs dimensionless (--mu, --zeta, --omega or --sigma-r-eta)
or in SI; the asperity law is the paper's, refitted, or a solved FE/BEM curve (--law)."""

import sys
from functools import partial

import numpy as np

from fem_asperity.closed_forms.scales import Scales
from fem_asperity.plumbing.cli import Parser, ProgressBar, dump_json, print_table, run
from fem_asperity.solver.presets import PRESETS
from fem_asperity.studies.refit import stored_refit

from .integrate import separation_range, strength, totals
from .laws import PaperLaw
from .surface import RoughSurface, omega_mccool
from .tables import solved_law

PROG = "python -m gw"


def _common(parser):
    parser.add_argument("--mu", type=float, help="Tabor parameter of the asperities")
    parser.add_argument("--zeta", type=float, help="sigma / eps")
    parser.add_argument("--omega", type=float, help="sigma_s / sigma (default 1, or eq. 20)")
    parser.add_argument("--sigma-r-eta", type=float, help="sigma R eta: omega from eq. 20")
    parser.add_argument("--sigma", type=float, help="rms roughness [m] (physical inputs)")
    parser.add_argument("--eps", type=float, help="LJ equilibrium spacing [m]")
    # The names of `python -m fem_asperity`; gw's earlier spellings stay as aliases.
    parser.add_argument("--R", "--radius", dest="radius", type=float,
                        help="asperity radius R [m] (alias --radius)")
    parser.add_argument("--density", type=float, help="asperity density eta [1/m^2]")
    parser.add_argument("--E-star", "--estar", dest="estar", type=float,
                        help="effective modulus E* [Pa] (alias --estar)")
    parser.add_argument("--dgamma", "--work-of-adhesion", dest="work_of_adhesion", type=float,
                        help="work of adhesion [J/m^2] (alias --work-of-adhesion)")
    parser.add_argument("--law", choices=("paper", "refit", "fem", "bem"), default="paper",
                        help="paper: the paper's closed forms; refit: the same forms with the "
                             "constants refitted from BEM curves (stored); fem, bem: the approach "
                             "curve of that solver at this mu, solved once and stored "
                             "(default: paper)")
    parser.add_argument("--accuracy", choices=tuple(PRESETS), default="default",
                        help="resolution of a solved law (default: %(default)s)")
    parser.add_argument("--json", action="store_true", help="print JSON instead of a table")


def build_parser():
    parser = Parser(prog=PROG, description=__doc__)
    commands = parser.add_subparsers(dest="command", required=True)
    _common(commands.add_parser("fmax", help="strength of adhesion F_max and its separation"))
    curve = commands.add_parser("curve", help="F and S against the mean separation d / sigma")
    _common(curve)
    curve.add_argument("--d", type=float, nargs=2, metavar=("MIN", "MAX"),
                       help="range of d / sigma (default: around the law's breakpoints)")
    curve.add_argument("--points", type=int, default=101, help="number of d values (101)")
    return parser


def _inputs(args, parser):
    """(mu, RoughSurface) from either dimensionless or physical arguments."""
    physical = (args.sigma, args.eps, args.radius, args.density, args.estar,
                args.work_of_adhesion)
    if any(v is not None for v in physical):
        dimensionless = (args.mu, args.zeta, args.omega, args.sigma_r_eta)
        if None in physical or any(v is not None for v in dimensionless):
            parser.error("physical inputs need all of --sigma --eps --R --density --E-star "
                         "--dgamma, and none of --mu --zeta --omega --sigma-r-eta "
                         "(they follow from the physical inputs: omega from eq. 20)")
        mu = Scales(E_star=args.estar, dgamma=args.work_of_adhesion, eps=args.eps,
                    R=args.radius).mu
        return mu, RoughSurface.from_physical(sigma=args.sigma, radius=args.radius,
                                              density=args.density, eps=args.eps)
    if args.mu is None or args.zeta is None:
        parser.error("give --mu and --zeta (or the physical inputs)")
    if args.omega is not None and args.sigma_r_eta is not None:
        parser.error("give --omega or --sigma-r-eta, not both")
    omega = args.omega if args.sigma_r_eta is None else float(omega_mccool(args.sigma_r_eta))
    return args.mu, RoughSurface(zeta=args.zeta, omega=1.0 if omega is None else omega)


def _law(args, mu):
    if args.law == "paper":
        return PaperLaw(mu)
    if args.law == "refit":
        fit = stored_refit(accuracy=args.accuracy, announce=partial(print, file=sys.stderr))
        return PaperLaw(mu, fit.laws, name="refit")
    bar = ProgressBar(f"{args.law.upper()} curve mu={mu:g} (stored for next time)")
    law = solved_law(mu, method=args.law, accuracy=args.accuracy, progress=bar)
    if bar.shown >= 0:  # solved now, not read from the store
        bar.close()
    return law


def main(argv=None):
    parser = build_parser()
    args = parser.parse_args(argv)
    mu, surface = _inputs(args, parser)
    law = _law(args, mu)
    head = {"mu": mu, "zeta": surface.zeta, "omega": surface.omega, "law": args.law}
    if args.command == "fmax":
        found = strength(law, surface)
        row = head | {"f_max": found.f_max, "d_at_max": found.d_at_max}
        if args.json:
            dump_json(row)
        else:
            print_table([{"quantity": k, "value": v} for k, v in row.items()],
                        ("quantity", "value"))
        return 0
    if args.points < 2:
        parser.error("curve: --points must be at least 2")
    lo, hi = separation_range(law, surface) if args.d is None else args.d
    d = np.linspace(lo, hi, args.points)
    force, area = totals(law, surface, d)
    if args.json:
        dump_json(head | {"d": d.tolist(), "F": force.tolist(), "S": area.tolist()})
    else:
        print_table([{"d": a, "F": b, "S": c} for a, b, c in zip(d, force, area)], ("d", "F", "S"))
    return 0


if __name__ == "__main__":
    sys.exit(run(main, PROG))
