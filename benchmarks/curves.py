"""Benchmark: cost and accuracy of one curve per method and accuracy preset (issues 3 and 4).

For each μ and method, solves one approach + retraction per preset (no error estimate, so the wall
time is that of one curve) and reports the relative error of P̄off, δ̄oc, ā_c, x̄oc against a
reference: the boundary-integral solver with elements half the `fine` size and a turn limit of
0.025 rad (above --reference-mu-max, the BEM `fine` run itself). Then, per μ, the wall-time ratio FE/BEM at equal accuracy: the cheapest preset of each
method whose P̄off error is within 1e-3, and within 1e-4.

    python benchmarks/curves.py [--mu 0.2 1 5] [--methods fem bem] [--presets draft default fine]
                                [--skip fem:5:fine ...] [--out out/bench]

Writes curves.json and curves.md under --out; progress on stderr. Long: the FE at μ = 5 takes
minutes per preset (`--skip fem:5:fine` leaves out its ~30-minute `fine` run).
"""

import argparse
import json
import platform
import sys
import time
from dataclasses import replace
from pathlib import Path

from fem_asperity.plumbing.errors import ContinuationError
from fem_asperity.plumbing.files import write_atomic
from fem_asperity.solver.presets import METHODS, PRESETS, discretisation
from fem_asperity.solver.solve import solve_discretised

KEYS = ("p_off", "delta_oc", "a_c", "x_oc")


def run(mu, method, name, disc):
    start = time.perf_counter()
    try:
        result = solve_discretised(mu, disc)
    except ContinuationError as exc:
        print(f"mu={mu:g} {method} {name}: failed: {exc}", file=sys.stderr, flush=True)
        return {"mu": mu, "method": method, "preset": name, "h_surface": disc.h_surface,
                "dofs": None, "surface_nodes": None, "points": None, "folds": None,
                "newton_iterations": None, "wall_s": time.perf_counter() - start,
                **{k: None for k in KEYS}, "failed": str(exc)}
    ev = result.events.records()
    row = {"mu": mu, "method": method, "preset": name, "h_surface": disc.h_surface,
           "dofs": result.dofs, "surface_nodes": result.surface_nodes, "points": result.points,
           "folds": result.folds,
           "newton_iterations": result.newton_iterations,
           "wall_s": time.perf_counter() - start, **{k: ev[k] for k in KEYS}}
    print(f"mu={mu:g} {method} {name:9s} {row['wall_s']:7.1f} s  {row}", file=sys.stderr,
          flush=True)
    return row


def reference(mu, block, halve):
    """BEM with elements half the `fine` size and a turn limit of 0.025 rad if `halve`, else
    the BEM `fine` row of `block` itself (a finer one costs hours above μ ≈ 2)."""
    if not halve:
        fine = next(r for r in block if r["method"] == "bem" and r["preset"] == "fine")
        return dict(fine, preset="reference (= bem fine)")
    fine = discretisation(mu, "fine", method="bem")
    disc = replace(fine, h_surface=fine.h_surface / 2, trace=replace(fine.trace, turn=0.025))
    return run(mu, "bem", "reference", disc)


def cheapest(rows, method, tol):
    """Wall time of the cheapest preset of `method` with P̄off within `tol` (None if none)."""
    ok = [r["wall_s"] for r in rows if r["method"] == method and r["preset"] in PRESETS
          and r["rel_error"]["p_off"] is not None and r["rel_error"]["p_off"] <= tol]
    return min(ok) if ok else None


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mu", type=float, nargs="+", default=[0.2, 1.0, 5.0])
    parser.add_argument("--methods", nargs="+", default=list(METHODS), choices=list(METHODS))
    parser.add_argument("--presets", nargs="+", default=list(PRESETS), choices=list(PRESETS))
    parser.add_argument("--skip", nargs="*", default=[], metavar="METHOD:MU:PRESET",
                        help="runs to leave out, e.g. fem:5:fine")
    parser.add_argument("--reference-mu-max", type=float, default=2.0,
                        help="above this μ the reference is the BEM `fine` run")
    parser.add_argument("--out", default="out/bench")
    args = parser.parse_args()
    skip = {tuple(s.split(":")) for s in args.skip}
    rows, ratios = [], []
    for mu in args.mu:
        block = [run(mu, m, name, discretisation(mu, name, method=m))
                 for m in args.methods for name in args.presets
                 if (m, f"{mu:g}", name) not in skip]
        ref = reference(mu, block, mu <= args.reference_mu_max)
        for row in block + [ref]:
            row["rel_error"] = {k: (abs(row[k] / ref[k] - 1.0)
                                    if row[k] is not None and ref[k] is not None else None)
                                for k in KEYS}
        rows += block + [ref]
        for tol in (1e-3, 1e-4):
            fem, bem = cheapest(block, "fem", tol), cheapest(block, "bem", tol)
            ratios.append({"mu": mu, "p_off_tol": tol, "fem_s": fem, "bem_s": bem,
                           "ratio": fem / bem if fem and bem else None})
    machine = f"{platform.machine()} {platform.processor() or ''} Python {platform.python_version()}"
    out = Path(args.out)
    write_atomic(out / "curves.json",
                 json.dumps({"machine": machine, "rows": rows, "ratios": ratios}, indent=2))
    lines = [f"Curve benchmark ({machine})", "",
             "| mu | method | preset | h | DOFs | surface nodes | points | folds | wall s | "
             + " | ".join(f"rel. err {k}" for k in KEYS) + " |",
             "|" + "---|" * (9 + len(KEYS))]
    for r in rows:
        errs = " | ".join("-" if r["rel_error"][k] is None else f"{r['rel_error'][k]:.1e}"
                          for k in KEYS)
        lines.append(f"| {r['mu']:g} | {r['method']} | {r['preset']} | {r['h_surface']:.4g} | "
                     f"{r['dofs']} | {r['surface_nodes']} | {r['points']} | {r['folds']} | "
                     f"{r['wall_s']:.1f} | {errs} |" + (" failed |" if "failed" in r else ""))
    lines += ["", "| mu | P̄off within | FE s | BEM s | FE/BEM |", "|---|---|---|---|---|"]
    for q in ratios:
        cells = ["-" if q[k] is None else f"{q[k]:.1f}" for k in ("fem_s", "bem_s", "ratio")]
        lines.append(f"| {q['mu']:g} | {q['p_off_tol']:.0e} | " + " | ".join(cells) + " |")
    write_atomic(out / "curves.md", "\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
