"""Benchmark: the large-μ runs of issue 19, timed as a user runs them, to compare commits.

What is measured (one at a time on an otherwise idle machine): curves through `solve_curve` (the
median of REPEATS runs where one is short), the BEM `default` curve at μ = 10 alone and with its
error estimate, the BEM `default` curve at μ = 5.7 with its estimate (the uniform grid's worst
ratio of estimate to solve before issue 19), the BEM `draft` curve at μ = 20, `draft` curves
with estimates either side of the BEM's edge-following threshold (issue 44's cost spike at
μ ≈ 5.8), and the FE
`default` curves at μ = 5 (grids that follow the edge) and μ = 1 (the whole surface) alone and
with their estimates; for each, the wall time, points and Newton iterations, and the events, so
that a faster commit can be checked to give the same events within their estimates. Then the
sweep the issue names: 20 log-spaced μ from 0.05 to 10, BEM `default` with estimates, on both
cores, from an empty store.

    python benchmarks/large_mu.py            # minutes → benchmarks/results/large_mu.{md,json}
    python benchmarks/large_mu.py --quick    # μ = 10 draft only → large_mu-quick.*
    python benchmarks/large_mu.py --tag before   # → large_mu-before.* (git-ignored), to compare
    python benchmarks/large_mu.py --large --tag T # μ = 50 draft and μ = 46.9 default only
"""

import argparse
import sys
import tempfile
import time

import numpy as np
from provenance import add_output_options, provenance, write_results

from fem_asperity.plumbing.cli import ProgressBar
from fem_asperity.solver.solve import solve_curve
from fem_asperity.studies.sweep import sweep

#: (label, μ, method, accuracy, with the error estimate). The targets of issue 19 name these.
RUNS = (("BEM default, mu = 10", 10.0, "bem", "default", False),
        ("BEM default, mu = 10, with estimate", 10.0, "bem", "default", True),
        ("BEM default, mu = 5.7", 5.7, "bem", "default", False),
        ("BEM default, mu = 5.7, with estimate", 5.7, "bem", "default", True),
        ("BEM draft, mu = 20", 20.0, "bem", "draft", False),
        # either side of MU_TRACKING["bem"] and the former spike below the old threshold 6
        ("BEM draft, mu = 3.9, with estimate", 3.9, "bem", "draft", True),
        ("BEM draft, mu = 4, with estimate", 4.0, "bem", "draft", True),
        ("BEM draft, mu = 5.8, with estimate", 5.8, "bem", "draft", True),
        ("BEM draft, mu = 7.1, with estimate", 7.1, "bem", "draft", True),
        ("FE default, mu = 5", 5.0, "fem", "default", False),
        ("FE default, mu = 5, with estimate", 5.0, "fem", "default", True),
        ("FE default, mu = 1", 1.0, "fem", "default", False),
        ("FE default, mu = 1, with estimate", 1.0, "fem", "default", True))
QUICK_RUNS = (("BEM draft, mu = 10", 10.0, "bem", "draft", False),)
#: The largest μ of the issue's targets, run on their own (`--large`: tens of minutes each).
LARGE_RUNS = (("BEM draft, mu = 50", 50.0, "bem", "draft", False),
              ("BEM default, mu = 46.9", 46.9, "bem", "default", False))
KEYS = ("p_off", "delta_oc", "a_c", "delta_jump_in", "delta_jump_out")
#: The sweep of the issue: μ, and worker processes (one per core of the 2-core machine).
SWEEP_MUS, SWEEP_JOBS = np.logspace(np.log10(0.05), 1.0, 20), 2
#: A run shorter than SHORT_S (s) is repeated REPEATS times and its median wall time kept: single
#: runs of the FE curve at μ = 1 with its estimate took 1.1-1.7 s on one day (df0f6b4).
SHORT_S, REPEATS = 2.0, 5


def one(label, mu, method, accuracy, estimate):
    walls = []
    while not walls or (walls[0] < SHORT_S and len(walls) < REPEATS):
        start = time.perf_counter()
        result = solve_curve(mu, method=method, accuracy=accuracy, error_estimate=estimate,
                             progress=ProgressBar(label))
        walls.append(time.perf_counter() - start)
    record = result.records()
    return {"run": label, "wall_s": float(np.median(walls)), "runs": len(walls),
            "status": result.status, "points": result.points,
            "newton_iterations": result.newton_iterations,
            "surface_nodes": result.surface_nodes, "message": result.message,
            **{k: record[k] for k in KEYS},
            **{f"{k}_err": (result.error_estimate or {}).get(k) for k in KEYS}}


def timed_sweep():
    """Wall time (s) and statuses of the issue's sweep, from an empty store."""
    with tempfile.TemporaryDirectory() as store:
        start = time.perf_counter()
        result = sweep(SWEEP_MUS, method="bem", accuracy="default", jobs=SWEEP_JOBS,
                       cache=store, progress=ProgressBar("sweep"))
        wall = time.perf_counter() - start
    statuses = sorted({row.status for row in result.rows})
    return wall, statuses


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_output_options(parser)
    parser.add_argument("--tag", help="suffix of the results' name (large_mu-TAG.md), e.g. "
                                      "'before' and 'after' a change")
    parser.add_argument("--large", action="store_true",
                        help="only the largest mu of the targets (50 draft, 46.9 default)")
    args = parser.parse_args()
    prov = provenance()
    runs = QUICK_RUNS if args.quick else LARGE_RUNS if args.large else RUNS
    rows = [one(*run) for run in runs]
    lines = [f"Wall s: one run, or the median of {REPEATS} where one took under {SHORT_S:g} s.",
             "", "| run | wall s | status | points | Newton iterations | largest grid | P̄off | "
             "± | δ̄oc | ± |", "|---|---|---|---|---|---|---|---|---|---|"]
    lines += [f"| {r['run']} | {r['wall_s']:.2f} | {r['status']} | {r['points']} | "
              f"{r['newton_iterations']} | {r['surface_nodes']} | {r['p_off']:.8f} | "
              f"{r['p_off_err'] or float('nan'):.1e} | {r['delta_oc']:.6f} | "
              f"{r['delta_oc_err'] or float('nan'):.1e} |" for r in rows]
    if runs is RUNS:
        wall, statuses = timed_sweep()
        lines += ["", f"Sweep of {SWEEP_MUS.size} mu from {SWEEP_MUS[0]:g} to {SWEEP_MUS[-1]:g}, "
                  f"BEM default with estimates, {SWEEP_JOBS} processes, empty store: "
                  f"{wall:.1f} s wall (statuses: {', '.join(statuses)})."]
        rows.append({"run": "sweep", "wall_s": wall, "statuses": statuses})
    name = "large_mu" + (f"-{args.tag}" if args.tag else "")
    paths = write_results(name, "Large mu: wall time of the issue-19 runs", prov, lines,
                          {"rows": rows}, out=args.out, quick=args.quick)
    print("wrote " + ", ".join(map(str, paths)), file=sys.stderr)


if __name__ == "__main__":
    main()
