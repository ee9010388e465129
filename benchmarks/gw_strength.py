"""Benchmark: cost of the GW strength of adhesion with the paper's law, the corrected closed form
and the shipped table of solved laws (issues 5 and 40).

What is measured: the wall time of `gw.integrate.strength` (F̄max of a Greenwood-Williamson
surface) for one F̄max at μ = 1, ζ = 6.67, ω = 1 with `PaperLaw`, `CorrectedLaw` and the
table's law (each law built at that μ included), the last also with the ground between summits
counted once (`sigma_r_eta`, `gw.shared_ground`), for a full Fig. 11 sweep (41 μ log-spaced in
[0.01, 100] × σ = 0.5, 1, 2 nm at ε = 0.3 nm) with the paper's law, and the whole command
`python -m gw fmax` with --law paper (which also reads the table, for its warning), corrected
and solved, as a user runs it;
the best and the median of repeated runs (the best is the cost without interference from other
jobs).

    python benchmarks/gw_strength.py             # → benchmarks/results/gw_strength.{md,json}
    python benchmarks/gw_strength.py --quick     # → benchmarks/results/gw_strength-quick.*
    python benchmarks/gw_strength.py --out DIR

Progress goes to stderr.
"""

import argparse
import statistics
import subprocess
import sys
import time

import numpy as np
from provenance import add_output_options, provenance, write_results

from fem_asperity.plumbing.cli import ProgressBar
from gw.integrate import strength
from gw.law_table import shipped_table
from gw.laws import CorrectedLaw, PaperLaw
from gw.surface import RoughSurface
from validation.rough_surface import EPS_NM, f_max

#: The single F̄max: the paper's example surface (σ = 2 nm at ε = 0.3 nm, so ζ = 6.67) at μ = 1.
ONE_MU, ONE_ZETA = 1.0, 6.67
#: σRη for the ground counted once (`gw.shared_ground`): a common GW density.
ONE_SIGMA_R_ETA = 0.05
#: Fig. 11 as the validation draws it (`validation.rough_surface`: ε = EPS_NM): μ from 0.01 to
#: 100, 41 points (10 per decade), for σ = 0.5, 1, 2 nm.
SWEEP_MU_RANGE, SWEEP_POINTS = (0.01, 100.0), 41
SWEEP_SIGMA_NM = (0.5, 1.0, 2.0)
#: Repeats (one F̄max, sweep, command): enough for a stable best time; a single F̄max takes
#: milliseconds, a command about a second (mostly imports).
REPEATS = (20, 3, 5)
#: --quick: a few repeats and 5 μ per σ (a smoke check, not a measurement).
QUICK_REPEATS, QUICK_SWEEP_POINTS = (3, 1, 1), 5


def timed(fn, repeats, bar):
    """Best and median wall time of `repeats` calls of `fn` (s), reporting to `bar`."""
    times = []
    for k in range(repeats):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
        bar((k + 1) / repeats)
    bar.close()
    return min(times), statistics.median(times)


def sweep(points):
    """The Fig. 11 F̄max: `points` μ per σ."""
    mus = np.logspace(*np.log10(SWEEP_MU_RANGE), points)
    return [f_max(mu, s / EPS_NM) for s in SWEEP_SIGMA_NM for mu in mus]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_output_options(parser)
    args = parser.parse_args()
    prov = provenance()
    repeats_one, repeats_sweep, repeats_command = QUICK_REPEATS if args.quick else REPEATS
    points = QUICK_SWEEP_POINTS if args.quick else SWEEP_POINTS
    one = f"mu = {ONE_MU:g}, zeta = {ONE_ZETA:g}, omega = 1"
    table = shipped_table()  # read once per process, as a command does
    cases = [
        (f"one F_max, paper's law ({one})", 1, repeats_one,
         lambda: strength(PaperLaw(ONE_MU), RoughSurface(ONE_ZETA))),
        (f"one F_max, corrected law ({one}, the law built too)", 1, repeats_one,
         lambda: strength(CorrectedLaw(ONE_MU), RoughSurface(ONE_ZETA))),
        (f"one F_max, table of solved laws ({one}, the law built too)", 1, repeats_one,
         lambda: strength(table.law(ONE_MU), RoughSurface(ONE_ZETA))),
        (f"one F_max, table of solved laws, ground counted once ({one}, sigma R eta = "
         f"{ONE_SIGMA_R_ETA:g})", 1, repeats_one,
         lambda: strength(table.law(ONE_MU), RoughSurface(ONE_ZETA),
                          sigma_r_eta=ONE_SIGMA_R_ETA)),
        (f"Fig. 11 sweep, paper's law ({points} mu x {len(SWEEP_SIGMA_NM)} sigma)",
         points * len(SWEEP_SIGMA_NM), repeats_sweep, lambda: sweep(points)),
    ]
    for law in ("paper", "corrected", "solved"):
        command = [sys.executable, "-m", "gw", "fmax", "--mu", f"{ONE_MU:g}", "--zeta",
                   f"{ONE_ZETA:g}", "--law", law]
        cases.append((f"command `python -m gw fmax ... --law {law}` ({one})", 1,
                      repeats_command,
                      lambda c=command: subprocess.run(c, check=True, capture_output=True)))
    rows = []
    for case, evaluations, repeats, fn in cases:
        best, median = timed(fn, repeats, ProgressBar(case))
        rows.append({"case": case, "evaluations": evaluations, "repeats": repeats,
                     "best_s": best, "median_s": median})
    lines = ["| case | F_max evaluations | repeats | best s | median s | best ms per F_max |",
             "|---|---|---|---|---|---|"]
    lines += [f"| {r['case']} | {r['evaluations']} | {r['repeats']} | {r['best_s']:.4g} | "
              f"{r['median_s']:.4g} | {1e3 * r['best_s'] / r['evaluations']:.3g} |" for r in rows]
    paths = write_results("gw_strength", "GW strength benchmark: cost of F̄max (paper's law, "
                          "corrected law, table of solved laws, ground counted once)",
                          prov, lines, {"rows": rows}, out=args.out, quick=args.quick)
    print("wrote " + ", ".join(map(str, paths)), file=sys.stderr)


if __name__ == "__main__":
    main()
