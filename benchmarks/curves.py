"""Benchmark: cost and accuracy of one curve per method and accuracy preset (issues 3 and 4).

What is measured: for each μ, method (FE, BEM) and preset, the wall time of one approach +
retraction (`solve_discretised`: no error estimate, so one curve), its size (DOFs, surface nodes,
points, folds), and the relative error of P̄off, δ̄oc, ā_c, x̄oc against a reference: the BEM
with elements REFERENCE_H_FACTOR times the `fine` size and a turn limit of REFERENCE_TURN (above
--reference-mu-max, the BEM `fine` run itself). Then, per μ, the wall-time ratio FE/BEM at equal
accuracy: the cheapest preset of each method whose P̄off error is within each P_OFF_TOLERANCES
and whose curve does not ripple.

    python benchmarks/curves.py                  # full run → benchmarks/results/curves.{md,json}
    python benchmarks/curves.py --quick          # seconds → benchmarks/results/curves-quick.*
    python benchmarks/curves.py [--mu 0.2 1 5] [--methods fem bem] [--presets draft default fine]
                                [--skip fem:5:fine ...] [--reference-mu-max 2] [--out DIR]

The full run is long (the FE `fine` run at μ = 5 is the longest; `--skip fem:5:fine` leaves it
out; see the wall times in results/curves.md). Progress goes to stderr, one bar per curve.
"""

import argparse
import sys
import time
from dataclasses import replace

from provenance import add_output_options, provenance, write_results

from fem_asperity.plumbing.cli import ProgressBar
from fem_asperity.plumbing.errors import ContinuationError
from fem_asperity.solver.discretised import solve_discretised
from fem_asperity.solver.presets import METHODS, PRESETS, discretisation

#: Events compared with the reference: pull-off force, and the most tensile approach force's
#: separation and contact radius, and the separation before the jump-in (the paper's fitted laws).
KEYS = ("p_off", "delta_oc", "a_c", "x_oc")
#: One μ per regime: DMT-like (0.2), the transition (1), JKR-like (5).
MUS = (0.2, 1.0, 5.0)
#: --quick: both methods at the cheapest preset at a μ with both jumps; the reference is the
#: BEM run itself (a smoke check of the whole script, not a measurement).
QUICK_MUS, QUICK_PRESETS = (1.0,), ("draft",)
#: The reference halves the `fine` BEM element and its turn limit (0.05 rad), so its own error
#: is well below that of the runs it judges.
REFERENCE_H_FACTOR, REFERENCE_TURN = 0.5, 0.025
#: Above this μ the reference is the BEM `fine` run: a finer BEM costs hours there.
REFERENCE_MU_MAX = 2.0
#: P̄off accuracies at which FE and BEM are compared: a practical one and a strict one.
P_OFF_TOLERANCES = (1e-3, 1e-4)


def run(mu, method, name, disc):
    """Solve one curve on `disc`; its row (cost, events), or a row of Nones marked `failed`."""
    bar = ProgressBar(f"mu={mu:g} {method} {name}")
    start = time.perf_counter()
    row = {"mu": mu, "method": method, "preset": name, "h_surface": disc.h_surface}
    try:
        result = solve_discretised(mu, disc, progress=bar)
    except ContinuationError as exc:
        if bar.tty:  # end the bar's line
            print(file=sys.stderr)
        print(f"mu={mu:g} {method} {name}: failed: {exc}", file=sys.stderr, flush=True)
        return {**row, "dofs": None, "surface_nodes": None, "points": None, "folds": None,
                "newton_iterations": None, "wall_s": time.perf_counter() - start,
                **{k: None for k in KEYS}, "failed": str(exc)}
    bar.close()
    ev = result.events.records()
    row.update(dofs=result.dofs, surface_nodes=result.surface_nodes, points=result.points,
               folds=result.folds, newton_iterations=result.newton_iterations,
               wall_s=time.perf_counter() - start, **{k: ev[k] for k in KEYS})
    print(f"mu={mu:g} {method} {name}: {row['wall_s']:.1f} s, {row['points']} points, "
          f"{row['folds']} folds", file=sys.stderr, flush=True)
    return row


def reference(mu, block, presets, halve):
    """The reference row at `mu`: if `halve`, a BEM run finer than `fine` (REFERENCE_H_FACTOR,
    REFERENCE_TURN); else the BEM run of the finest of `presets` (from `block` if it is there)."""
    if halve:
        fine = discretisation(mu, "fine", method="bem")
        disc = replace(fine, h_surface=REFERENCE_H_FACTOR * fine.h_surface,
                       trace=replace(fine.trace, turn=REFERENCE_TURN))
        return run(mu, "bem", "reference", disc)
    finest = max(presets, key=list(PRESETS).index)
    row = next((r for r in block if r["method"] == "bem" and r["preset"] == finest), None)
    if row is None:
        row = run(mu, "bem", finest, discretisation(mu, finest, method="bem"))
    return dict(row, preset=f"reference (= bem {finest})")


def with_errors(rows, ref):
    """Each row with `rel_error`: |value / reference − 1| per KEYS (None if either is missing)."""
    return [dict(r, rel_error={k: (abs(r[k] / ref[k] - 1.0)
                                   if r[k] is not None and ref[k] is not None else None)
                               for k in KEYS})
            for r in rows]


def cheapest(rows, method, tol):
    """Wall time of the cheapest preset of `method` with P̄off within `tol` and no ripple (at
    most the two folds of one jump-in and one jump-out: a rippled curve is not a usable result
    however close its P̄off); None if none."""
    ok = [r["wall_s"] for r in rows if r["method"] == method and r["preset"] in PRESETS
          and r["folds"] is not None and r["folds"] <= 2
          and r["rel_error"]["p_off"] is not None and r["rel_error"]["p_off"] <= tol]
    return min(ok) if ok else None


def _number(value, spec):
    return "-" if value is None else format(value, spec)


def markdown(rows, ratios):
    """The two tables: per run, and FE/BEM at equal P̄off accuracy."""
    lines = ["## One curve per method and preset", "",
             "Wall time of one approach + retraction (no error estimate); relative errors "
             "against the reference row of the same μ.", "",
             "| mu | method | preset | h | DOFs | surface nodes | points | folds | wall s | "
             + " | ".join(f"rel. err {k}" for k in KEYS) + " | note |",
             "|" + "---|" * (10 + len(KEYS))]
    for r in rows:
        errs = " | ".join(_number(r["rel_error"][k], ".1e") for k in KEYS)
        lines.append(f"| {r['mu']:g} | {r['method']} | {r['preset']} | {r['h_surface']:.4g} | "
                     f"{_number(r['dofs'], 'd')} | {_number(r['surface_nodes'], 'd')} | "
                     f"{_number(r['points'], 'd')} | {_number(r['folds'], 'd')} | "
                     f"{r['wall_s']:.1f} | {errs} | {'failed' if 'failed' in r else ''} |")
    lines += ["", "## FE/BEM wall time at equal accuracy", "",
              "Cheapest preset of each method whose P̄off is within the tolerance.", "",
              "| mu | P̄off within | FE s | BEM s | FE/BEM |", "|---|---|---|---|---|"]
    for q in ratios:
        cells = " | ".join(_number(q[k], ".1f") for k in ("fem_s", "bem_s", "ratio"))
        lines.append(f"| {q['mu']:g} | {q['p_off_tol']:.0e} | {cells} |")
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mu", type=float, nargs="+", help=f"default {' '.join(map(str, MUS))}")
    parser.add_argument("--methods", nargs="+", default=list(METHODS), choices=list(METHODS))
    parser.add_argument("--presets", nargs="+", choices=list(PRESETS),
                        help=f"default {' '.join(PRESETS)}")
    parser.add_argument("--skip", nargs="*", default=[], metavar="METHOD:MU:PRESET",
                        help="runs to leave out, e.g. fem:5:fine")
    parser.add_argument("--reference-mu-max", type=float, default=REFERENCE_MU_MAX,
                        help="above this μ the reference is the BEM `fine` run")
    add_output_options(parser)
    args = parser.parse_args()
    prov = provenance()
    mus = args.mu or (QUICK_MUS if args.quick else MUS)
    presets = args.presets or (QUICK_PRESETS if args.quick else tuple(PRESETS))
    skip = {tuple(s.split(":")) for s in args.skip}
    rows, ratios = [], []
    for mu in mus:
        block = [run(mu, m, name, discretisation(mu, name, method=m))
                 for m in args.methods for name in presets
                 if (m, f"{mu:g}", name) not in skip]
        ref = reference(mu, block, presets, not args.quick and mu <= args.reference_mu_max)
        block = with_errors(block + [ref], ref)
        rows += block
        for tol in P_OFF_TOLERANCES:
            fem, bem = cheapest(block, "fem", tol), cheapest(block, "bem", tol)
            ratios.append({"mu": mu, "p_off_tol": tol, "fem_s": fem, "bem_s": bem,
                           "ratio": fem / bem if fem and bem else None})
    paths = write_results("curves", "Curve benchmark: cost and accuracy per method and preset",
                          prov, markdown(rows, ratios), {"rows": rows, "ratios": ratios},
                          out=args.out, quick=args.quick)
    print("wrote " + ", ".join(map(str, paths)), file=sys.stderr)


if __name__ == "__main__":
    main()
