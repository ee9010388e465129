"""Benchmark: the cost at the ends of the ranges a curve is solved for (issue 43), the evidence
for `solver.solve.MU_RANGE` (the stiffest contact, μ = 50), `WHOLE_CURVE_MU_MAX` (the stiffest
whole curve) and `SPRING_RANGE` (the softest spring, whose curve starts farther out).

    python benchmarks/extremes.py           # minutes → benchmarks/results/extremes.{md,json}
    python benchmarks/extremes.py --quick   # k̄ = 1e-3 only, seconds
"""

import argparse
import sys
import time

from provenance import add_output_options, cell, provenance, write_results

from fem_asperity.plumbing.cli import ProgressBar
from fem_asperity.solver.solve import solve_curve

#: (label, μ, method, accuracy, error estimate, spring k̄ or None): the ends of the solved ranges
#: (methods.md §14). Not pinned by a test; benchmarks/results/extremes.md has the results.
RUNS = (("BEM draft, mu = 50, with estimate", 50.0, "bem", "draft", True, None),
        ("BEM draft, mu = 5, k = 1", 5.0, "bem", "draft", False, 1.0),
        ("BEM draft, mu = 6, k = 1", 6.0, "bem", "draft", False, 1.0),
        ("BEM draft, mu = 1, k = 1e-3", 1.0, "bem", "draft", False, 1e-3),
        ("BEM draft, mu = 1, k = 1e-6", 1.0, "bem", "draft", False, 1e-6),
        ("BEM draft, mu = 1, k = 1e-9", 1.0, "bem", "draft", False, 1e-9),
        ("FE draft, mu = 1, k = 1e-9, with estimate", 1.0, "fem", "draft", True, 1e-9))
QUICK_RUNS = RUNS[3:4]


def one(label, mu, method, accuracy, estimate, spring):
    start = time.perf_counter()
    result = solve_curve(mu, method=method, accuracy=accuracy, error_estimate=estimate,
                         spring_constant=spring, progress=ProgressBar(label))
    wall = time.perf_counter() - start
    estimate = result.error_estimate or {}
    return {"run": label, "wall_s": wall, "status": result.status, "points": result.points,
            "newton_iterations": result.newton_iterations, "p_off": result.events.p_off,
            "p_off_err": estimate.get("p_off"), "delta_o_star": result.events.delta_o_star,
            "delta_o_star_err": estimate.get("delta_o_star")}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_output_options(parser)
    args = parser.parse_args()
    prov = provenance()
    rows = [one(*run) for run in (QUICK_RUNS if args.quick else RUNS)]
    lines = ["One run each, wall time as a user sees it (two cores).", "",
             "| run | wall s | status | points | Newton iterations | P̄off | ± | δ̄o* | ± |",
             "|---|---|---|---|---|---|---|---|---|"]
    lines += [f"| {r['run']} | {r['wall_s']:.1f} | {r['status']} | {r['points']} | "
              f"{r['newton_iterations']} | {r['p_off']:.6f} | {cell(r['p_off_err'], '.1e')} | "
              f"{cell(r['delta_o_star'], '.4f')} | {cell(r['delta_o_star_err'], '.1e')} |"
              for r in rows]
    paths = write_results("extremes", "The cost at the ends of the solved ranges", prov, lines,
                          {"rows": rows}, out=args.out, quick=args.quick)
    print("wrote " + ", ".join(map(str, paths)), file=sys.stderr)


if __name__ == "__main__":
    main()
