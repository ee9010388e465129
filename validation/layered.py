"""Layered media (the paper's "future work"): maps over the layer's thickness and modulus, the
homogeneous limits, a coated rough surface, and the FE against the layered boundary integral.

The governing groups of a layer bonded to the substrate (Poisson's ratios ν = NU for both):

- t/√(Rε), the thickness in the radial scale; against the contact radius at P̄max it is
  t/a_c (`CurveResult.layer_groups`): thin (t ≪ a_c) means the substrate governs, thick the layer;
- M = E*_layer/E*_substrate, the modulus ratio;
- the Tabor parameters of the substrate, μ, and of the layer, μ M^(−2/3): the homogeneous limits
  t → 0 and t → ∞.

The maps cover t in THICKNESSES and M in RATIOS at each μ of MUS, solved by the layered boundary
integral (`solids.layered`) through the sweep engine (both cores, or a Dask cluster), each curve
with its error estimate. A pull-off force is bracketed by the two limits where it lies between
the substrate's and the layer's (within the estimates); a layer creates a jump-in where the
substrate's approach does not jump and the layered one does, and removes it the other way round
(noted where the homogeneous layer does the same).
"""

import json
import time
from dataclasses import asdict

import numpy as np

from fem_asperity.plumbing.cli import shown
from fem_asperity.plumbing.files import save_figure, write_atomic
from fem_asperity.plumbing.progress import share
from fem_asperity.solids.fe import Solid
from fem_asperity.studies.store import stored_curve
from fem_asperity.studies.sweep import sweep
from gw import RoughSurface, solved_law, strength

#: The map: Tabor parameters of the substrate, thicknesses (√(Rε)) and modulus ratios, down to
#: 0.3 (methods.md §14). Not pinned by a test.
MUS = (0.5, 1.0, 2.0)
THICKNESSES = (0.3, 1.0, 3.0, 10.0)
RATIOS = (0.3, 0.5, 2.0, 5.0)
#: Poisson's ratio of substrate and layer.
NU = 0.3
#: The coated rough surface: μ of the substrate, the layers, ζ = σ/ε (ω = 1).
ROUGH_MU, ROUGH_LAYERS, ROUGH_ZETA = 1.0, ((1.0, 0.5), (1.0, 2.0)), 3.0
#: Points of the map where the FE checks the layered boundary integral (μ, t, M): a soft and a
#: stiff layer whose pull-off lies outside the two homogeneous limits.
FE_CHECKS = ((1.0, 1.0, 0.5), (1.0, 0.3, 5.0))


def _solid(thickness, ratio):
    return Solid(nu=NU, layer_thickness=thickness, layer_modulus_ratio=ratio, layer_nu=NU)


def _events(row):
    """What the maps need of a sweep row (None where the curve failed)."""
    if row.curve is None:
        return None
    e, err = row.curve.events, row.curve.error_estimate or {}
    return {"p_off": e.p_off, "p_off_err": err.get("p_off"), "a_c": e.a_c,
            "jump_in": e.jump_in is not None,
            "delta_jump_in": e.jump_in.delta if e.jump_in else None, "status": row.status}


def run_map(*, accuracy="default", jobs=None, scheduler=None, step=print, bars=None):
    """The layered curves over the map and the homogeneous limits: (rows, cost). bars: as
    `run`'s."""
    start = time.perf_counter()
    limits = sorted(set(MUS) | {mu * m ** (-2.0 / 3.0) for mu in MUS for m in RATIOS})
    step(f"layered: homogeneous limits at {len(limits)} mu, then {len(THICKNESSES) * len(RATIOS)} "
         f"layers x {len(MUS)} mu (BEM, {accuracy}, with error estimates)")
    with shown(bars, "homogeneous limits") as bar:
        homogeneous = sweep(limits, method="bem", accuracy=accuracy, jobs=jobs,
                            scheduler=scheduler, progress=bar)
    limit = {row.mu: _events(row) for row in homogeneous.rows}

    def at(mu):
        return limit[min(limit, key=lambda m: abs(m - mu))]

    rows, solved = [], homogeneous.solved
    layers = [(t, m) for t in THICKNESSES for m in RATIOS]
    with shown(bars, f"{len(layers)} layers") as bar:
        sweeps = {}
        for k, (t, m) in enumerate(layers):
            sweeps[t, m] = sweep(MUS, method="bem", accuracy=accuracy, solid=_solid(t, m),
                                 jobs=jobs, scheduler=scheduler,
                                 progress=share(bar, k / len(layers), (k + 1) / len(layers)))
    for (t, m), layered in sweeps.items():
        solved += layered.solved
        for row in layered.rows:
            rows.append({"mu": row.mu, "thickness": t, "modulus_ratio": m,
                         "layered": _events(row), "substrate": at(row.mu),
                         "layer": at(row.mu * m ** (-2.0 / 3.0)),
                         "mu_layer": row.mu * m ** (-2.0 / 3.0)})
    for r in rows:
        r.update(_judged(r))
    return rows, {"curves_solved": solved, "wall_s": time.perf_counter() - start}


def _judged(row):
    """Whether the layered pull-off lies between the two limits (within the three estimates),
    and whether the layer creates or removes the substrate's jump-in."""
    lay, sub, top = row["layered"], row["substrate"], row["layer"]
    if lay is None:
        return {"bracketed": None, "position": None, "jump": "failed"}
    if sub is None or top is None:
        return {"bracketed": None, "position": None, "jump": "limit failed"}
    slack = sum(x["p_off_err"] or 0.0 for x in (lay, sub, top))
    lo, hi = sorted((sub["p_off"], top["p_off"]))
    span = top["p_off"] - sub["p_off"]
    position = (lay["p_off"] - sub["p_off"]) / span if span else None
    jump = ("created" if lay["jump_in"] and not sub["jump_in"] else
            "removed" if sub["jump_in"] and not lay["jump_in"] else "as substrate")
    if jump != "as substrate" and lay["jump_in"] == top["jump_in"]:
        jump += " (as the layer)"
    return {"bracketed": lo - slack <= lay["p_off"] <= hi + slack, "position": position,
            "jump": jump}


def coated_rough_surface(accuracy="default"):
    """F̄max of a GW surface (ζ = ROUGH_ZETA, ω = 1) whose asperities are coated (solved laws of
    the layered curves), against all-substrate and all-layer asperities."""
    surface = RoughSurface(zeta=ROUGH_ZETA, omega=1.0)
    found = []
    for t, m in ROUGH_LAYERS:
        laws = {"coated": solved_law(ROUGH_MU, accuracy=accuracy, solid=_solid(t, m)),
                "substrate": solved_law(ROUGH_MU, accuracy=accuracy),
                "layer": solved_law(ROUGH_MU * m ** (-2.0 / 3.0), accuracy=accuracy)}
        found.append({"mu": ROUGH_MU, "thickness": t, "modulus_ratio": m, "zeta": ROUGH_ZETA,
                      **{f"f_max_{k}": strength(law, surface).f_max for k, law in laws.items()},
                      "interpolation_error": max(law.interpolation_error
                                                 for law in laws.values())})
    return found


def fe_checks(accuracy="default", progress=None):
    """The FE and the layered boundary integral at each point of FE_CHECKS (solved once, then
    stored): events, estimates, cost and whether they agree within the sum of the estimates.
    progress: callable(fraction of the curves done), told while one is solved."""
    checks = []
    for i, (mu, t, m) in enumerate(FE_CHECKS):
        found = {}
        for j, method in enumerate(("fem", "bem")):
            k, n = 2 * i + j, 2 * len(FE_CHECKS)
            result = stored_curve(mu, method=method, accuracy=accuracy, solid=_solid(t, m),
                                  error_estimate=True, progress=share(progress, k / n,
                                                                      (k + 1) / n))
            found[method] = {"events": {k: result.events.records()[k] for k in
                                        ("p_off", "delta_oc", "a_c", "delta_jump_in",
                                         "delta_jump_out")},
                             "error_estimate": result.error_estimate,
                             "wall_s": result.cost["wall_s"], "status": result.status}
        fe, bem = found["fem"], found["bem"]
        found["agree"] = {k: None if fe["events"][k] is None or bem["events"][k] is None
                          else abs(fe["events"][k] - bem["events"][k])
                          <= ((fe["error_estimate"] or {}).get(k) or 0.0)
                          + ((bem["error_estimate"] or {}).get(k) or 0.0)
                          for k in fe["events"]}
        checks.append({"mu": mu, "thickness": t, "modulus_ratio": m, **found})
    return checks


def figure(rows):
    """Per μ (columns): the pull-off force P̄off and the jump-in separation over (t, M)."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(4.2 * len(MUS), 7.5), layout="constrained")
    axes = fig.subplots(2, len(MUS), squeeze=False)
    t_edges = _edges(THICKNESSES)
    m_edges = _edges(RATIOS)
    for col, mu in enumerate(MUS):
        grid_p = np.full((len(RATIOS), len(THICKNESSES)), np.nan)
        grid_j = np.full_like(grid_p, np.nan)
        for r in rows:
            if r["mu"] != mu or r["layered"] is None:
                continue
            i, j = RATIOS.index(r["modulus_ratio"]), THICKNESSES.index(r["thickness"])
            grid_p[i, j] = r["layered"]["p_off"]
            grid_j[i, j] = r["layered"]["delta_jump_in"] or np.nan
            if not r["bracketed"]:
                axes[0, col].plot(r["thickness"], r["modulus_ratio"], "kx", ms=10)
        for ax, grid, label in ((axes[0, col], grid_p, "P̄off = P_off/(2πRΔγ)"),
                                (axes[1, col], grid_j, "δ̄o at jump-in (ε); blank: no jump")):
            mesh = ax.pcolormesh(t_edges, m_edges, grid, cmap="viridis")
            fig.colorbar(mesh, ax=ax, label=label)
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel("layer thickness t/√(Rε)")
            ax.set_ylabel("M = E*_layer/E*_substrate")
            ax.set_title(f"μ = {mu:g} (substrate)")
    fig.suptitle("Layered half-space, boundary integral: pull-off (x: not between the "
                 "homogeneous limits) and jump-in")
    return fig


def _edges(values):
    """Cell edges around log-spaced `values` (geometric midpoints, half a step beyond; a factor
    of 2 around a single value)."""
    v = np.log(np.asarray(values, dtype=float))
    half = np.diff(v) / 2.0 if v.size > 1 else np.array([np.log(2.0)])
    return np.exp(np.concatenate([[v[0] - half[0]], v[:-1] + half, [v[-1] + half[-1]]]))


def run(out, *, accuracy="default", jobs=None, scheduler=None, step=print, header="",
        bars=None):
    """Maps, limits, coated rough surface and the FE check; write out/layered/{report.md (after
    `header`, e.g. the provenance line), layered.json, map.png}. bars: callable(label) giving
    the progress bar of each long step (`ProgressBar`), or None. Returns the summary (the
    JSON)."""
    folder = out / "layered"
    rows, cost = run_map(accuracy=accuracy, jobs=jobs, scheduler=scheduler, step=step,
                         bars=bars)
    step("layered: coated rough surface (GW) and the FE against the layered BEM")
    start = time.perf_counter()
    rough = coated_rough_surface(accuracy)
    with shown(bars, "FE checks") as bar:
        checks = fe_checks(accuracy, progress=bar)
    cost["rough_and_fe_wall_s"] = time.perf_counter() - start
    save_figure(figure(rows), folder / "map.png")
    summary = {"accuracy": accuracy, "mu": list(MUS), "thickness": list(THICKNESSES),
               "modulus_ratio": list(RATIOS), "nu": NU, "rows": rows,
               "not_bracketed": [_where(r) for r in rows if r["bracketed"] is False],
               "jump_created": [_where(r) for r in rows if r["jump"].startswith("created")],
               "jump_removed": [_where(r) for r in rows if r["jump"].startswith("removed")],
               "failed": [_where(r) for r in rows if r["layered"] is None],
               "coated_rough_surface": rough, "fe_checks": checks, "cost": cost,
               "solids": [asdict(_solid(t, m)) for t in THICKNESSES for m in RATIOS]}
    write_atomic(folder / "layered.json", json.dumps(summary, indent=1, allow_nan=False) + "\n")
    write_atomic(folder / "report.md", (header + "\n\n" if header else "") + section(summary))
    return summary


def _where(row):
    return {"mu": row["mu"], "thickness": row["thickness"], "modulus_ratio": row["modulus_ratio"]}


def _fmt(value, spec=".4g"):
    return "-" if value is None else format(value, spec)


def section(summary):
    """Markdown of the layered results (also the section of out/report.md)."""
    lines = ["## Layered media (the paper's future work)", "",
             f"A layer bonded to the substrate (ν = {summary['nu']} for both), solved by the "
             f"layered boundary integral at '{summary['accuracy']}' accuracy with error estimates; "
             "t in √(Rε), M = E*_layer/E*_substrate; the homogeneous limits are the substrate "
             "(μ) and the layer (μ M^(−2/3)). Position: where P̄off lies between the substrate "
             "(0) and the layer (1); t/a_c: the thickness over the contact radius at P̄max. "
             "Figure: `layered/map.png`.", "",
             "| μ | t | M | t/a_c | P̄off | ± | substrate | layer | position | "
             "bracketed | jump-in δ̄o | jump |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in summary["rows"]:
        lay, sub, top = r["layered"] or {}, r["substrate"] or {}, r["layer"] or {}
        over = r["thickness"] / lay["a_c"] if lay.get("a_c") else None
        lines.append(f"| {r['mu']:g} | {r['thickness']:g} | {r['modulus_ratio']:g} | "
                     f"{_fmt(over, '.3g')} | "
                     f"{_fmt(lay.get('p_off'), '.6f')} | {_fmt(lay.get('p_off_err'), '.1e')} | "
                     f"{_fmt(sub.get('p_off'), '.6f')} | {_fmt(top.get('p_off'), '.6f')} | "
                     f"{_fmt(r['position'], '.3f')} | {r['bracketed']} | "
                     f"{_fmt(lay.get('delta_jump_in'))} | {r['jump']} |")
    for key, text in (("not_bracketed", "P̄off outside the two homogeneous limits"),
                      ("jump_created", "the layer creates a jump-in (the substrate has none)"),
                      ("jump_removed", "the layer removes the substrate's jump-in"),
                      ("failed", "curves that failed")):
        found = summary[key]
        where = "; ".join(f"μ = {w['mu']:g}, t = {w['thickness']:g}, M = "
                          f"{w['modulus_ratio']:g}" for w in found) or "nowhere"
        lines += ["", f"**{text}**: {where}."]
    lines += ["", "### Coated rough surface (GW, ω = 1)", "",
              "F̄max with every asperity coated (the solved layered law) against all-substrate "
              "and all-layer asperities (solved homogeneous laws).", "",
              "| μ | t | M | ζ | F̄max coated | substrate | layer | interpolation error |",
              "|---|---|---|---|---|---|---|---|"]
    for r in summary["coated_rough_surface"]:
        lines.append(f"| {r['mu']:g} | {r['thickness']:g} | {r['modulus_ratio']:g} | "
                     f"{r['zeta']:g} | {r['f_max_coated']:.4g} | {r['f_max_substrate']:.4g} | "
                     f"{r['f_max_layer']:.4g} | {r['interpolation_error']:.1e} |")
    lines += ["", "### FE against the layered boundary integral", ""]
    for check in summary["fe_checks"]:
        fe, bem = check["fem"], check["bem"]
        lines += [f"μ = {check['mu']:g}, t = {check['thickness']:g}, "
                  f"M = {check['modulus_ratio']:g}: FE {fe['wall_s']:.1f} s, BEM "
                  f"{bem['wall_s']:.1f} s (solve alone, without its estimate's).", "",
                  "| event | FE | ± | BEM | ± | within the sum |", "|---|---|---|---|---|---|"]
        for key, fe_value in fe["events"].items():
            lines.append(f"| {key} | {_fmt(fe_value, '.7g')} | "
                         f"{_fmt((fe['error_estimate'] or {}).get(key), '.1e')} | "
                         f"{_fmt(bem['events'][key], '.7g')} | "
                         f"{_fmt((bem['error_estimate'] or {}).get(key), '.1e')} | "
                         f"{check['agree'][key]} |")
        lines.append("")
    cost = summary["cost"]
    lines += ["", f"The map took {cost['wall_s']:.0f} s ({cost['curves_solved']} curves solved, "
                  "the rest read from the store); the rough surface and the FE check "
                  f"{cost['rough_and_fe_wall_s']:.0f} s.", ""]
    return "\n".join(lines)
