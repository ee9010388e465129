"""`python -m advisor FILE [--json]`: the cheapest model of the scene in FILE that meets its
tolerance, and the measured size of every effect each model leaves out."""

import sys

from fem_asperity.plumbing.cli import Parser, dump_json, print_table, run

from .advice import advise
from .scene import read_scene

PROG = "python -m advisor"


def build_parser():
    parser = Parser(prog=PROG, description=__doc__)
    parser.add_argument("scene", help="the scene file (TOML; advisor/scene.py shows the keys)")
    parser.add_argument("--json", action="store_true", help="print the advice as JSON")
    return parser


def main(argv=None):
    args = build_parser().parse_args(argv)
    scene = read_scene(args.scene)  # every key checked before anything is solved
    print(f"mu = {scene.mu:.4g}, R/eps = {scene.scales.R / scene.scales.eps:.4g}: solving the "
          "scene at BEM draft to measure its effects ...", file=sys.stderr)
    advice = advise(scene)
    record = advice.records()
    if args.json:
        dump_json(record)
        return 0
    print("Effects on the pull-off force (relative):")
    print_table(record["effects"], ("name", "size", "uncertainty", "how"))
    print("\nModels, cheapest first (error: the sum of the effects each leaves out):")
    print_table(record["models"], ("name", "p_off", "p_off_N", "error", "cost_s"))
    print(f"\nchoice: {advice.message}")
    return 0


if __name__ == "__main__":
    sys.exit(run(main, PROG))
