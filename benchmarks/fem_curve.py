"""Benchmark: cost and accuracy of the FE curve per accuracy preset (issue 3's study).

For each μ, solves one approach + retraction per preset (no error estimate, so the wall time is
that of one curve), plus a reference with surface elements half the `fine` size (for μ ≤ --reference-mu-max; above
it `fine` is the reference), and reports the relative change of P̄off, δ̄oc, ā_c, x̄oc against it.

    python benchmarks/fem_curve.py [--mu 0.2 1 5] [--presets draft default fine] [--out out/bench]

Writes fem_curve.json and fem_curve.md under --out; progress on stderr. Long: minutes per μ ≥ 3.
"""

import argparse
import json
import platform
import sys
import time
from dataclasses import replace
from pathlib import Path

from fem_asperity._io import write_atomic
from fem_asperity.accuracy import PRESETS, discretisation
from fem_asperity.asperity import _solve_once
from fem_asperity.elastic import Solid

KEYS = ("p_off", "delta_oc", "a_c", "x_oc")


def run(mu, name, disc):
    start = time.perf_counter()
    result = _solve_once(mu, disc, Solid(), None, None)
    ev = result.events.records()
    row = {"mu": mu, "preset": name, "h_surface": disc.h_surface, "dofs": result.dofs,
           "surface_nodes": result.surface_nodes, "points": result.points,
           "folds": int(result.equilibrium.branch.max()),
           "newton_iterations": result.newton_iterations,
           "wall_s": time.perf_counter() - start, **{k: ev[k] for k in KEYS}}
    print(f"mu={mu:g} {name:9s} {row['wall_s']:7.1f} s  {row}", file=sys.stderr, flush=True)
    return row


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mu", type=float, nargs="+", default=[0.2, 1.0, 5.0])
    parser.add_argument("--out", default="out/bench")
    parser.add_argument("--presets", nargs="+", default=list(PRESETS), choices=list(PRESETS))
    parser.add_argument("--reference-mu-max", type=float, default=2.0,
                        help="above this μ the reference is `fine` itself (halving it is too dear)")
    args = parser.parse_args()
    rows = []
    for mu in args.mu:
        block = [run(mu, name, discretisation(mu, name)) for name in args.presets]
        if mu <= args.reference_mu_max:
            fine = discretisation(mu, "fine")
            block.append(run(mu, "reference", replace(fine, h_surface=fine.h_surface / 2)))
        ref = block[-1]
        for row in block:
            row["rel_change"] = {k: (abs(row[k] / ref[k] - 1.0) if row[k] is not None else None)
                                 for k in KEYS}
        rows += block
    machine = f"{platform.machine()} {platform.processor() or ''} Python {platform.python_version()}"
    out = Path(args.out)
    write_atomic(out / "fem_curve.json", json.dumps({"machine": machine, "rows": rows}, indent=2))
    lines = [f"FE curve benchmark ({machine})", "",
             "| mu | preset | h | DOFs | surface nodes | points | folds | wall s | "
             + " | ".join(f"rel. err {k}" for k in KEYS) + " |",
             "|" + "---|" * (8 + len(KEYS))]
    for r in rows:
        errs = " | ".join("-" if r["rel_change"][k] is None else f"{r['rel_change'][k]:.1e}"
                          for k in KEYS)
        lines.append(f"| {r['mu']:g} | {r['preset']} | {r['h_surface']:.4g} | {r['dofs']} | "
                     f"{r['surface_nodes']} | {r['points']} | {r['folds']} | {r['wall_s']:.1f} | "
                     f"{errs} |")
    write_atomic(out / "fem_curve.md", "\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
