"""Benchmark: does the measured map's verdict on 16 caps carry over to a larger surface?

The map (`python -m validation rough-explicit --full`) solves GW surfaces of 16 caps. Where ζ is
large their F̄max per summit rests on the few highest caps, far above GW's integral over the same
statistics (the `sample` column: the sum over the caps on the table's law against the integral),
while a large surface's is not. Here the same points are solved with 16 and with 256 caps, two
draws each, and each model's error against the whole surface compared.

    python benchmarks/map_sample.py           # tens of minutes → results/map_sample.{md,json}
    python benchmarks/map_sample.py --quick   # one point, 16 and 32 caps, seconds
"""

import argparse
import sys
import time

from provenance import add_output_options, provenance, write_results

from fem_asperity.plumbing.cli import ProgressBar
from gw.explicit.compare import Scene, compare
from gw.explicit.interacting import AsperityLaw
from gw.explicit.measured_map import ACCURACY, MAP_SEEDS, map_pixel

#: (μ, ζ, σRη): the paper's ζ = 10/3 and 20/3 on the map's grid, below and above the jump-in
#: onset, where 16 caps' F̄max is 3-34 times GW's integral (results/map_sample.md).
POINTS = ((0.3, 10 / 3, 0.05), (1.0, 10 / 3, 0.05), (0.3, 20 / 3, 0.05), (1.0, 20 / 3, 0.05))
#: Caps per surface: the map's, and 16 times as many.
CAPS = (16, 256)
QUICK_POINTS, QUICK_CAPS = POINTS[:1], (16, 32)
#: The models whose error against the whole surface is compared.
MODELS = ("gw_solved", "gw_once", "gw_sum", "gw_cells", "interacting")


def one(mu, zeta, sigma_r_eta, caps, seed, law):
    """One surface compared, as a row."""
    start = time.perf_counter()
    found = compare(Scene(mu=mu, zeta=zeta, sigma_r_eta=sigma_r_eta, summits=caps,
                          pixel=map_pixel(mu), seed=seed), accuracy=ACCURACY, law=law)
    models = found.models
    return {"mu": mu, "zeta": zeta, "sigma_r_eta": sigma_r_eta, "caps": caps, "seed": seed,
            "f_max_whole": models["whole"].f_max,
            "estimate_relative": found.estimate / models["whole"].f_max,
            "sample": models["gw_sum"].f_max / models["gw_solved"].f_max,
            "errors": {name: found.errors[name] for name in MODELS},
            "wall_s": time.perf_counter() - start}


def _percent(value):
    return "-" if value is None else f"{100 * value:+.1f}%"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_output_options(parser)
    args = parser.parse_args()
    prov = provenance()
    points, counts = (QUICK_POINTS, QUICK_CAPS) if args.quick else (POINTS, CAPS)
    runs = [(p, n, seed) for p in points for n in counts for seed in MAP_SEEDS]
    bar = ProgressBar("surfaces", time_left=True)
    laws, rows = {}, []
    for k, ((mu, zeta, sre), n, seed) in enumerate(runs):
        law = laws.setdefault(mu, AsperityLaw.tabulated(mu))
        rows.append(one(mu, zeta, sre, n, seed, law))
        bar((k + 1) / len(runs))
    bar.close()
    lines = ["Each surface as the map makes it (`gw.explicit.measured_map.map_scene`: caps of one "
             f"R at Gaussian heights, pixel `map_pixel(μ)`, `{ACCURACY}`), the table's law; "
             "errors: F̄max/F̄max(whole) − 1; sample: the sum over the caps without interaction "
             "against GW's integral on the same statistics (1: the caps stand for a large "
             "surface). One run each, wall time on the machine above.", "",
             "| μ | ζ | σRη | caps | seed | sample | F̄max whole | ± rel | "
             + " | ".join(MODELS) + " | wall s |",
             "|---|---|---|---|---|---|---|---|" + "---|" * len(MODELS) + "---|"]
    lines += [f"| {r['mu']:g} | {r['zeta']:.3g} | {r['sigma_r_eta']:g} | {r['caps']} | "
              f"{r['seed']} | {r['sample']:.2f} | {r['f_max_whole']:.4g} | "
              f"{r['estimate_relative']:.1e} | "
              + " | ".join(_percent(r["errors"][m]) for m in MODELS) + f" | {r['wall_s']:.0f} |"
              for r in rows]
    paths = write_results("map_sample", "The measured map's 16 caps against a larger surface",
                          prov, lines, {"rows": rows}, out=args.out, quick=args.quick)
    print("wrote " + ", ".join(map(str, paths)), file=sys.stderr)


if __name__ == "__main__":
    main()
