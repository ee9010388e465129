"""Command line of fem_asperity: `python -m fem_asperity laws|scales ...` (see --help)."""

import sys

from ._cli import Parser, dump_json, print_table, run
from .laws import PAPER_LAWS
from .scales import Scales, effective_modulus

PROG = "python -m fem_asperity"
EVENT_COLUMNS = ("mu", "p_max", "delta_oc", "delta_o_star", "a_c", "jump_in", "x_oc")
LAWS_LEGEND = """\
Paper closed-form laws (Song & Komvopoulos eqs. 2, 6, 7, 10, 12, 13); jump-in for mu >= 0.5.
p_max: max adhesive force / (2 pi R dgamma), < 0 tensile; delta_oc, delta_o_star: separation at
p_max and at first contact / eps; a_c: compressive contact radius at p_max / sqrt(eps R);
x_oc: centre gap at jump-in / eps ('-' where there is no jump-in)."""


def _physical_arguments(parser):
    parser.add_argument("--dgamma", type=float, help="work of adhesion [J/m^2]")
    parser.add_argument("--eps", type=float, help="equilibrium spacing [m]")
    parser.add_argument("--R", type=float, help="reduced radius of curvature [m]")


def build_parser():
    parser = Parser(prog=PROG, description=__doc__)
    commands = parser.add_subparsers(dest="command", required=True)

    laws = commands.add_parser("laws", help="events predicted by the paper's closed-form laws")
    laws.add_argument("--mu", type=float, nargs="+", help="Tabor parameter(s), > 0")
    laws.add_argument("--E-star", dest="E_star", type=float,
                      help="effective modulus [Pa] (with --dgamma, --eps, --R instead of --mu)")
    _physical_arguments(laws)
    laws.add_argument("--json", action="store_true", help="print JSON instead of a table")

    scales = commands.add_parser("scales", help="E*, Tabor parameter and natural scales")
    scales.add_argument("--E1", type=float, required=True, help="modulus of body 1 [Pa]")
    scales.add_argument("--nu1", type=float, required=True, help="Poisson's ratio of body 1")
    scales.add_argument("--E2", type=float, help="modulus of body 2 [Pa] (omit: rigid)")
    scales.add_argument("--nu2", type=float, help="Poisson's ratio of body 2")
    _physical_arguments(scales)
    scales.add_argument("--json", action="store_true", help="print JSON instead of a table")
    return parser


def _laws(args, parser):
    physical = (args.E_star, args.dgamma, args.eps, args.R)
    if (args.mu is not None) == any(v is not None for v in physical):
        parser.error("laws: give either --mu or all of --E-star, --dgamma, --eps, --R")
    if args.mu is None:
        if None in physical:
            parser.error("laws: --E-star, --dgamma, --eps and --R go together")
        mu = Scales(E_star=args.E_star, dgamma=args.dgamma, eps=args.eps, R=args.R).mu
        mus = [mu]
    else:
        mus = args.mu
    rows = PAPER_LAWS.events(mus).records()
    if args.json:
        dump_json(rows[0] if len(rows) == 1 else rows)
    else:
        print(LAWS_LEGEND)
        print_table(rows, EVENT_COLUMNS)


def _scales(args, parser):
    if None in (args.dgamma, args.eps, args.R):
        parser.error("scales: --dgamma, --eps and --R are required")
    E_star = effective_modulus(E1=args.E1, nu1=args.nu1, E2=args.E2, nu2=args.nu2)
    s = Scales(E_star=E_star, dgamma=args.dgamma, eps=args.eps, R=args.R)
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


def main(argv=None):
    parser = build_parser()
    args = parser.parse_args(argv)
    {"laws": _laws, "scales": _scales}[args.command](args, parser)
    return 0


if __name__ == "__main__":
    sys.exit(run(main, PROG))
