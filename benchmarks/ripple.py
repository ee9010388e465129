"""Benchmark: where the surface discretisation makes a curve ripple (issue 17).

What is measured: the folds of one approach + retraction (`solve_discretised`, no error
estimate) when the surface elements have length h = c μ⁻² √(Rε), for each grid (FE, uniform
BEM, edge-following BEM), a few μ and a few c around the ripple onset. More than two folds (one
jump-in, one jump-out) is ripple. `solver.presets.RIPPLE_FREE` holds, per grid, the largest c
found free of ripple here; the presets stay below it.

    python benchmarks/ripple.py            # → benchmarks/results/ripple.{md,json}
    python benchmarks/ripple.py --quick    # one cheap case → results/ripple-quick.*
"""

import argparse
import sys
from dataclasses import replace

from provenance import add_output_options, provenance, write_results

from fem_asperity.solver.discretised import solve_discretised
from fem_asperity.solver.presets import RIPPLE_FREE, discretisation

#: (grid, μ, values of c = h μ²): around each grid's onset (the FE above μ = 5 costs minutes
#: per curve, and large μ is the edge-following BEM's).
CASES = (
    ("bem", 2.5, (0.28, 0.31)),
    ("bem", 3.5, (0.28, 0.30, 0.34)),
    ("bem", 5.0, (0.28, 0.31, 0.35)),
    ("edge", 7.0, (0.33,)),
    ("edge", 9.0, (0.33, 0.375)),
    ("edge", 10.0, (0.33, 0.395)),
    ("fem", 3.5, (0.45, 0.65)),
    ("fem", 5.0, (0.45, 0.56)),
)
QUICK_CASES = (("bem", 3.0, (0.28, 0.45)),)


def run(grid, mu, c):
    method = "fem" if grid == "fem" else "bem"
    track = grid == "edge"  # the FE's onset is its whole surface's
    disc = discretisation(mu, "default", method=method, track_edge=track)
    disc = replace(disc, h_surface=c * mu**-2.0)
    result = solve_discretised(mu, disc)
    row = {"grid": grid, "mu": mu, "c": c, "h_surface": disc.h_surface, "folds": result.folds,
           "wall_s": result.wall_s, "ripple_free_c": RIPPLE_FREE[grid]}
    print(f"{grid} mu={mu:g} c={c:g}: {result.folds} folds, {result.wall_s:.1f} s",
          file=sys.stderr, flush=True)
    return row


def markdown(rows):
    lines = ["Folds of one curve with surface elements h = c μ⁻² √(Rε); more than 2 is ripple. "
             "`ripple-free c` is `solver.presets.RIPPLE_FREE` of the grid.", "",
             "| grid | mu | c = h μ² | h | folds | ripple | wall s | ripple-free c |",
             "|---|---|---|---|---|---|---|---|"]
    lines += [f"| {r['grid']} | {r['mu']:g} | {r['c']:g} | {r['h_surface']:.4g} | {r['folds']} | "
              f"{'yes' if r['folds'] > 2 else 'no'} | {r['wall_s']:.1f} | {r['ripple_free_c']:g} |"
              for r in rows]
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_output_options(parser)
    args = parser.parse_args()
    prov = provenance()
    rows = [run(grid, mu, c) for grid, mu, cs in (QUICK_CASES if args.quick else CASES)
            for c in cs]
    paths = write_results("ripple", "Ripple onset of the surface discretisation", prov,
                          markdown(rows), {"rows": rows}, out=args.out, quick=args.quick)
    print("wrote " + ", ".join(map(str, paths)), file=sys.stderr)


if __name__ == "__main__":
    main()
