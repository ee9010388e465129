"""Benchmark: the cost of a layered curve by each method against a homogeneous one, and of a
layered map serial, on two worker processes and on a local Dask cluster (issue 18).

What is measured:
1. per method (FE, BEM) at `default` accuracy with the error estimate: the wall time and the
   P̄off error estimate of one curve at μ = 1 on the homogeneous substrate and with each layer of
   LAYERS; the events of the two methods side by side (their difference against the sum of their
   estimates);
2. a map of MAP_THICKNESSES × MAP_RATIOS layers at MAP_MUS (BEM draft, with estimates) through
   `fem_asperity.studies.sweep`, each run on an empty store of its own: serial (jobs = 1), two
   worker processes, and a local Dask cluster of two single-threaded worker processes.

    python benchmarks/layered.py            # minutes → benchmarks/results/layered.{md,json}
    python benchmarks/layered.py --quick    # one layer, a 2-point map → layered-quick.*
"""

import argparse
import sys
import tempfile
import time

from provenance import add_output_options, provenance, write_results

from fem_asperity.plumbing.cli import ProgressBar
from fem_asperity.solids.fe import Solid
from fem_asperity.solver.solve import solve_curve
from fem_asperity.studies.sweep import sweep

#: One soft and one stiff layer (t in √(Rε), M = E*_layer/E*_substrate) at μ = 1, against the
#: homogeneous substrate.
MU, LAYERS = 1.0, ((1.0, 0.5), (0.3, 5.0))
#: The map: 3 μ × 2 t × 2 M = 12 curves.
MAP_MUS, MAP_THICKNESSES, MAP_RATIOS = (0.5, 1.0, 2.0), (0.3, 3.0), (0.5, 2.0)
#: --quick: the soft layer only, and a 2-point map.
QUICK_LAYERS, QUICK_MAP = ((1.0, 0.5),), ((1.0,), (1.0,), (0.5, 2.0))
KEYS = ("p_off", "delta_oc", "a_c", "delta_jump_in", "delta_jump_out")


def one_curve(method, solid):
    """The row of one curve: wall time (with the estimate's solve), size, events, estimates."""
    start = time.perf_counter()
    # The FE's own estimate ('finer') for every solid: a homogeneous FE would otherwise be
    # estimated against the BEM, and its cost and estimates would not compare with the layers'.
    result = solve_curve(MU, method=method, accuracy="default", solid=solid, estimate_by="finer",
                         progress=ProgressBar(f"{method} {solid.description()}"))
    record = result.records()
    return {"method": method, "layer": solid.description(), "wall_s": time.perf_counter() - start,
            "surface_nodes": result.surface_nodes, "dofs": result.dofs, "status": result.status,
            **{k: record[k] for k in KEYS},
            **{f"{k}_err": (result.error_estimate or {}).get(k) for k in KEYS}}


def one_map(mus, thicknesses, ratios, scheduler_kind):
    """Wall time of the map on an empty store: 'serial', 'processes' (2) or 'dask' (local
    cluster, 2 single-threaded workers)."""
    with tempfile.TemporaryDirectory() as cache:
        start = time.perf_counter()
        if scheduler_kind == "dask":
            from dask.distributed import LocalCluster

            with LocalCluster(n_workers=2, threads_per_worker=1, processes=True) as cluster:
                start = time.perf_counter()  # the cluster's start-up is not the map's
                _sweeps(mus, thicknesses, ratios, cache, scheduler=cluster.scheduler_address)
                return time.perf_counter() - start
        _sweeps(mus, thicknesses, ratios, cache, jobs=1 if scheduler_kind == "serial" else 2)
        return time.perf_counter() - start


def _sweeps(mus, thicknesses, ratios, cache, **where):
    for t in thicknesses:
        for m in ratios:
            done = sweep(mus, method="bem", accuracy="draft", cache=cache,
                         solid=Solid(layer_thickness=t, layer_modulus_ratio=m), **where)
            if done.failed:
                raise RuntimeError(f"map point t = {t}, M = {m} failed: {done.failed}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_output_options(parser)
    args = parser.parse_args()
    prov = provenance()
    layers = QUICK_LAYERS if args.quick else LAYERS
    mus, thicknesses, ratios = QUICK_MAP if args.quick else (MAP_MUS, MAP_THICKNESSES,
                                                             MAP_RATIOS)
    solids = [Solid()] + [Solid(layer_thickness=t, layer_modulus_ratio=m) for t, m in layers]
    curves = [one_curve(method, solid) for solid in solids for method in ("fem", "bem")]
    maps = []
    for kind in ("serial", "processes", "dask"):
        print(f"map ({kind}) ...", file=sys.stderr, flush=True)
        maps.append({"run": kind, "curves": len(mus) * len(thicknesses) * len(ratios),
                     "wall_s": one_map(mus, thicknesses, ratios, kind)})
    lines = [f"## One curve at μ = {MU:g}, `default`, with its error estimate", "",
             "| method | solid | wall s | surface nodes | DOFs | status | P̄off | ± | δ̄oc | ± |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    lines += [f"| {r['method']} | {r['layer']} | {r['wall_s']:.1f} | {r['surface_nodes']} | "
              f"{r['dofs']} | {r['status']} | {r['p_off']:.7f} | {r['p_off_err']:.1e} | "
              f"{r['delta_oc']:.6f} | {r['delta_oc_err']:.1e} |" for r in curves]
    lines += ["", "Wall time relative to the homogeneous curve of the same method:", ""]
    homogeneous = {r["method"]: r["wall_s"] for r in curves[:2]}
    lines += [f"- {r['method']}, {r['layer']}: {r['wall_s'] / homogeneous[r['method']]:.2f}"
              for r in curves[2:]]
    lines += ["", f"## A map of {maps[0]['curves']} layered curves (BEM draft, with estimates; "
              f"μ = {', '.join(map(str, mus))}, t = {', '.join(map(str, thicknesses))}, "
              f"M = {', '.join(map(str, ratios))}), each run on an empty store", "",
              "| run | wall s | speed-up over serial |", "|---|---|---|"]
    lines += [f"| {m['run']} | {m['wall_s']:.1f} | {maps[0]['wall_s'] / m['wall_s']:.2f} |"
              for m in maps]
    paths = write_results("layered", "Layered media: cost by method, and the map's wall time",
                          prov, lines, {"curves": curves, "maps": maps}, out=args.out,
                          quick=args.quick)
    print("wrote " + ", ".join(map(str, paths)), file=sys.stderr)


if __name__ == "__main__":
    main()
