"""Is GW itself right? GW surfaces made explicit (`gw.explicit.compare`), solved whole and as
interacting asperities, over (μ, ζ, σRη): where GW holds within 10 % of the whole surface's
F̄max, where the interacting model does, where neither does.

The quick tier (one small surface) runs inside `validation all`; the map (`--full`) is many
whole-surface solves, run on processes or a Dask cluster. Each surface's result is kept under
$ADHESION_CACHE/rough_explicit/<revision>, so an interrupted map resumes where it stopped and a
changed solver starts afresh.
"""

import json
import os
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import asdict
from datetime import datetime, timezone
from pathlib import Path

import numpy as np

from fem_asperity.plumbing.files import save_figure, write_atomic
from fem_asperity.plumbing.provenance import git_commit
from fem_asperity.plumbing.revision import code_revision, solver_revision
from fem_asperity.studies.store import cache_dir, stored_curve
from gw.explicit.compare import settled
from gw.explicit.measured_map import ACCURACY, MAP_SEEDS, MAP_SUMMITS, map_scene

from .report import counted

#: The quick tier: six caps at μ = 1, ζ = 2, σRη = 0.05 (a 58² map; seconds).
QUICK = ({"mu": 1.0, "zeta": 2.0, "sigma_r_eta": 0.05, "summits": 6},)
#: The map: μ below and above the jump-in onset (0.697), ζ smooth to rough (to 12: MEMS
#: surfaces), with the paper's σ = 0.5, 1, 2 nm on ε = 0.3 nm (ζ = 5/3, 10/3, 20/3) on the grid so
#: that its points are read at their own ζ; σRη sparse to crowded; each surface as
#: `gw.explicit.measured_map.map_scene` makes it (methods.md §14). Not pinned by a test.
MAP_MU, MAP_SRE = (0.1, 0.3, 1.0, 2.0), (0.02, 0.05, 0.15)
MAP_ZETA = (0.5, 5 / 3, 2.0, 10 / 3, 6.0, 20 / 3, 12.0)
#: Self-affine surfaces, answered as a user's map is (`gw.explicit.answer`), within the map's
#: resolution bounds at μ = 1, ζ ≤ 2 (methods.md §14). Not pinned by a test.
AFFINE = {"n": 128, "hurst": 0.8, "short": 12, "long": 64}
AFFINE_MU, AFFINE_ZETA, AFFINE_SEEDS = (0.3, 1.0), (1.0, 2.0), (1, 2)


def scenes(full):
    """The `Scene`s of the quick tier or of the map."""
    from gw.explicit import Scene

    if not full:
        return [Scene(**s) for s in QUICK]
    return [map_scene(mu, zeta, sre, seed)
            for mu in MAP_MU for zeta in MAP_ZETA for sre in MAP_SRE for seed in MAP_SEEDS]


def affine_specs(full):
    """The self-affine surfaces of the map (none in the quick tier), as dicts."""
    if not full:
        return []
    return [{"mu": mu, "zeta": zeta, "seed": seed}
            for mu in AFFINE_MU for zeta in AFFINE_ZETA for seed in AFFINE_SEEDS]


def _folder():
    revision = (f"{code_revision('gw.explicit.compare', 'gw.explicit.answer')}-"
                f"{solver_revision()}")
    return cache_dir() / "rough_explicit" / revision


def _key(scene):
    return "_".join(f"{k}={v:g}" if isinstance(v, float) else f"{k}={v}"
                    for k, v in asdict(scene).items())


def solve_scene(scene, accuracy=ACCURACY):
    """One scene compared (`gw.explicit.compare`) as a JSON-ready dict, kept in the store."""
    from gw.explicit import compare

    path = _folder() / f"{_key(scene)}.json"
    if path.exists():
        return json.loads(path.read_text())
    found = compare(scene, accuracy=accuracy)
    record = {"scene": asdict(scene), "accuracy": accuracy, "estimate": found.estimate,
              "errors": found.errors, "holds": found.holds,
              "models": {name: {"f_max": m.f_max, "d_at_max": m.d_at_max, "f_off": m.f_off,
                                "jumps": list(m.jumps), "seconds": m.seconds,
                                "d": m.d.tolist(), "approach": m.approach.tolist(),
                                "retraction": None if m.retraction is None
                                else [v if np.isfinite(v) else None
                                      for v in m.retraction.tolist()],
                                "stopped": m.stopped}
                         for name, m in found.models.items()}}
    write_atomic(path, json.dumps(record, allow_nan=False))
    return record


def _affine_key(spec):
    return "self_affine_" + "_".join(f"{k}={v:g}" for k, v in spec.items())


def solve_affine(spec, accuracy=ACCURACY):
    """One self-affine surface answered by GW, interacting asperities and whole, as a
    JSON-ready dict (F̄max in 2πRΔγ per summit counted), kept in the store."""
    from gw.explicit import Adhesion, self_affine, summit_statistics
    from gw.explicit.answer import answer
    from gw.explicit.compare import DGAMMA, EPS
    from gw.explicit.interacting import AsperityLaw

    path = _folder() / f"{_affine_key(spec)}.json"
    if path.exists():
        return json.loads(path.read_text())
    pixel = 1e-9  # m; F̄, d̃ and the verdicts depend on the map's shape and ζ, μ only
    surface = self_affine(n=AFFINE["n"], pixel=pixel, rms_height=spec["zeta"] * EPS,
                          hurst=AFFINE["hurst"], short_cutoff=AFFINE["short"] * pixel,
                          long_cutoff=AFFINE["long"] * pixel, seed=spec["seed"])
    counted = summit_statistics(surface)
    e_star = np.sqrt(counted.radius * DGAMMA**2 / (EPS**3 * spec["mu"] ** 3))
    found = answer(surface, Adhesion(e_star, DGAMMA, EPS), accuracy=accuracy,
                   law=AsperityLaw.solved(spec["mu"]))
    unit = 2 * np.pi * counted.radius * DGAMMA * counted.count
    whole = found.whole
    record = {"spec": spec, "accuracy": accuracy, "source": surface.source,
              "summits": counted.count, "sigma_r_eta": counted.sigma_s * counted.radius
              * counted.density, "zeta_s": counted.sigma_s / EPS,
              "pixel_sqrt_r_eps": pixel / np.sqrt(counted.radius * EPS),
              "estimate": whole.error_estimate["force_max"] / unit,
              "jumps_in": sum(j.kind == "in" for j in whole.jumps), "needs": found.needs,
              "models": {name: {"f_max": m.force_max / unit, "seconds": m.seconds,
                                "error": found.relative_to_whole[name],
                                "stopped": m.stopped is not None,
                                "settled": settled(m.stopped, m.force)}
                         for name, m in found.models.items()},
              "notes": list(found.notes)}
    write_atomic(path, json.dumps(record, allow_nan=False))
    return record


def run_scenes(full, *, jobs=None, scheduler=None, step=print):
    """(caps, self-affine): every surface's record, solved where not stored: the laws first
    (one per μ, stored), then the surfaces on `jobs` processes or the Dask scheduler at
    `scheduler`."""
    tasks = ([(_key(s), solve_scene, s) for s in scenes(full)]
             + [(_affine_key(a), solve_affine, a) for a in affine_specs(full)])
    for mu in sorted({s.mu for s in scenes(full)} | {a["mu"] for a in affine_specs(full)}):
        stored_curve(mu, method="bem", accuracy="default")
    step(f"rough surfaces: {len(tasks)} surface(s), GW, interacting asperities and the whole "
         "surface")
    records = {}
    if scheduler is not None:
        from dask.distributed import Client

        with Client(scheduler) as client:
            futures = {key: client.submit(solve, task, pure=False)
                       for key, solve, task in tasks}
            records = {key: future.result() for key, future in futures.items()}
    elif (jobs or os.cpu_count() or 1) > 1 and len(tasks) > 1:
        with ProcessPoolExecutor(jobs, initializer=_one_fft_thread) as pool:
            futures = {pool.submit(solve, task): key for key, solve, task in tasks}
            for k, future in enumerate(as_completed(futures), start=1):
                records[futures[future]] = future.result()
                step(f"  {k}/{len(tasks)} surfaces")
    else:
        for k, (key, solve, task) in enumerate(tasks, start=1):
            records[key] = solve(task)
            step(f"  {k}/{len(tasks)} surfaces")
    caps = [records[_key(s)] for s in scenes(full)]
    return caps, [records[_affine_key(a)] for a in affine_specs(full)]


def _one_fft_thread():
    """A map worker's setup: one FFT thread (the pool keeps the cores busy), freed memory
    kept for reuse (`relax.keep_freed_memory`)."""
    from gw.explicit import halfspace
    from gw.explicit.relax import keep_freed_memory

    halfspace.FFT_WORKERS = 1
    keep_freed_memory()


def run(out, *, full=False, jobs=None, scheduler=None, step=print, header="", command=""):
    """Write out/rough_explicit/{report.md, rough_explicit.json, curves.png, and with `full`
    map.png and rough_map.json, the compact map (`gw.explicit.measured_map`)}; return the
    summary. `command`: what produced it, for the map."""
    from gw.explicit.measured_map import map_record, save_map

    folder = out / "rough_explicit"
    start = time.perf_counter()
    records, affine = run_scenes(full, jobs=jobs, scheduler=scheduler, step=step)
    summary = {"full": full, "accuracy": ACCURACY, "scenes": records, "self_affine": affine,
               "wall_s": time.perf_counter() - start}
    save_figure(curves_figure(records[0]), folder / "curves.png")
    if full:
        save_figure(map_figure(records), folder / "map.png")
        compact = map_record(records, {
            "command": command, "commit": git_commit(Path(__file__).parent) or "unknown",
            "solver_revision": solver_revision(), "explicit_revision": _folder().name,
            "accuracy": ACCURACY,
            "date": datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC")})
        save_map(folder / "rough_map.json", compact)
    write_atomic(folder / "rough_explicit.json",
                 json.dumps(summary, indent=1, allow_nan=False))
    write_atomic(folder / "report.md", "\n".join([header, "", section(summary)]) + "\n")
    return summary


NAMES = {"gw_paper": "GW, paper's law", "gw_solved": "GW, solved law",
         "gw_once": "GW, solved law, ground counted once",
         "gw_sum": "sum over these summits", "gw_cells": "the sum, ground counted once",
         "interacting": "interacting asperities",
         "whole": "whole surface"}


def section(summary):
    """Markdown of the comparison (also the section of out/report.md)."""
    lines = ["## Is GW itself right? Rough surfaces solved whole", "",
             "GW surfaces made explicit: caps of one radius R at Gaussian heights (σ_s = σ, "
             "ω = 1) on random positions (`gw.explicit.compare`), each solved whole (FFT "
             "half-space, periodic, LJ 9-3, approach and retraction with every jump; pixel "
             f"{_pixels(summary['scenes'])}, separation step at '{summary['accuracy']}'), as "
             "the sum over these "
             "summits on the solved law (no interaction), as that sum with the ground between "
             "the summits counted once ('cells', `gw.explicit.tails`: each summit's law is a "
             "whole paraboloid's, whose LJ tail reaches over its neighbours' cells), as "
             "interacting asperities (the cells, and the elastic far field of each summit's "
             "force on the others' ground) and by GW's integral (eqs. 22-28) with the "
             "paper's and the solved law, and with the solved law and the ground counted once "
             "for summits at random places ('GW once', `gw.shared_ground`, closed form). "
             "F̄max per summit, in 2πRΔγ; the error of each model "
             "is F̄max/F̄max(whole) − 1; ± is the whole surface's estimate (twice the pixel). "
             "A model holds where it is within 10 % (plus the estimate). Figures: "
             "`rough_explicit/curves.png`"
             + (", `rough_explicit/map.png`." if summary["full"] else "."), "",
             "| μ | ζ | σRη | seed | summits | F̄max whole | ± | GW paper | GW solved | GW once | "
             "sum | cells | interacting | jumps in (whole) | whole s | interacting s |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in summary["scenes"]:
        s, e, m = r["scene"], r["errors"], r["models"]
        lines.append(
            f"| {s['mu']:g} | {s['zeta']:g} | {s['sigma_r_eta']:g} | {s['seed']} | "
            f"{s['summits']} | "
            f"{m['whole']['f_max']:.4f} | {r['estimate']:.1e} | "
            + " | ".join(_cell(e[k], r["holds"][k], _stop(m[k]["stopped"] is not None,
                                                           m[k]["approach"]))
                         for k in ("gw_paper", "gw_solved", "gw_once", "gw_sum",
                                   "gw_cells", "interacting"))
            + f" | {m['whole']['jumps'][0]} | {m['whole']['seconds']:.1f} | "
              f"{m['interacting']['seconds']:.2f} |")
    rows = summary["scenes"]
    counts = {k: sum(r["holds"][k] for r in rows) for k in NAMES if k != "whole"}
    neither = sum(not any(r["holds"][k] for k in ("gw_sum", "gw_cells", "interacting"))
                  for r in rows)
    shared = [r["errors"]["gw_sum"] - r["errors"]["gw_cells"] for r in rows]
    stopped = [r for r in rows if r["models"]["interacting"]["stopped"] is not None
               and r["models"]["interacting"]["approach"]]
    short = [r for r in stopped if not settled(r["models"]["interacting"]["stopped"],
                                               r["models"]["interacting"]["approach"])]
    unanswered = [r for r in rows if not r["models"]["interacting"]["approach"]]
    summits = MAP_SUMMITS if summary["full"] else QUICK[0]["summits"]
    sampling = [r["models"]["gw_solved"]["f_max"] / r["models"]["gw_sum"]["f_max"] - 1.0
                for r in rows]
    lines += ["", "Within 10 % of the whole surface: "
              + ", ".join(f"{NAMES[k]} {c}/{len(rows)}" for k, c in counts.items()) + ".",
              "",
              "The sum over these summits is GW's physics on this very surface (each summit on "
              "the solved law, nothing felt from the others). Each summit's law counts the "
              "LJ attraction of a whole paraboloid, so the ground between the summits is counted "
              "by every law whose tail reaches it: counting it once (rigid, 'cells') lowers "
              f"F̄max by {_span(shared, '.0%')} of the whole surface's, most where the summits "
              "are dense against the LJ range "
              "(summits s √(Rε) apart, s² = ζ/σRη, meet at a gap of about s²/8 ε above the "
              "lower). The interacting model adds the elastic far field to the cells. On "
              f"{neither} of {counted(len(rows), 'surface', 'surfaces')} none of the three "
              "holds. "
              + (f"On {len(stopped)}/{len(rows)} surfaces the interacting model found no "
                 "equilibrium part-way down (contacts too large or too close for a point "
                 "load's far field): "
                 + (f"on {len(short)} of them (μ = "
                    + ", ".join(f"{mu:g}" for mu in sorted({r["scene"]["mu"] for r in short}))
                    + ") still in tension ('stopped in tension' in the table: its F̄max is that "
                    "of the path above, no answer)" if short else "")
                 + ("; " if short and len(short) < len(stopped) else "")
                 + ("on the others once the total force had turned compressive, its F̄max "
                    "behind it ('stopped in compression', the rule the whole surface's own "
                    "approach ends by)" if len(short) < len(stopped) else "")
                 + ". " if stopped else "")
              + (f"On {len(unanswered)}/{len(rows)} (μ = "
                 + ", ".join(f"{mu:g}" for mu in sorted({r["scene"]["mu"] for r in unanswered}))
                 + ") it found none at its first separation: no answer ('—'). "
                 if unanswered else "")
              + "GW's "
              "integral (scaled to the summits on the map: it counts every cap drawn) differs "
              "from the sum over the same summits by the sample and by the caps under others, "
              "mostly low ones, which GW counts as summits: "
              f"with {summits} caps per surface (fewer summits where a cap covers another) the "
              f"integral over their Gaussian lies {_span(sampling, '+.0%')} "
              "off the sum over them, most at large ζ, where F̄max is set by the few highest "
              "summits. So on "
              "these small surfaces the GW-integral columns measure the sample as much as GW; "
              "the sum, cells and interacting columns measure what GW leaves out. ✗: outside 10 % "
              "(plus the estimate). The whole-surface solves took "
              f"{sum(r['models']['whole']['seconds'] for r in rows):.0f} s in all (the column "
              f"'whole s'); this run took {summary['wall_s']:.0f} s (surfaces in the store are "
              "read, not solved)."]
    spread = _draw_spread(rows)
    if spread:
        lines += ["", "Two draws of each surface (seeds): their errors differ by "
                  + "; ".join(f"{NAMES[k]} {_span(v, '.0%')}" for k, v in spread.items())
                  + " of the whole surface's F̄max: the share of the sample in each verdict."]
    if summary.get("self_affine"):
        lines += ["", affine_section(summary["self_affine"])]
    return "\n".join(lines)


def _pixels(records):
    """'0.2 √(Rε)', or each pixel with the μ it was used at where they differ."""
    by_pixel = {}
    for r in records:
        by_pixel.setdefault(r["scene"]["pixel"], set()).add(r["scene"]["mu"])
    if len(by_pixel) == 1:
        return f"{next(iter(by_pixel)):.3g} √(Rε)"
    return "; ".join(f"{a:.3g} √(Rε) at μ = " + ", ".join(f"{mu:g}" for mu in sorted(mus))
                     for a, mus in sorted(by_pixel.items(), reverse=True))


def _span(values, form):
    """'17%' for one value (or all equal as written), else '12% to 31% (median 17%)'."""
    low, high = format(min(values), form), format(max(values), form)
    if low == high:
        return low
    return f"{low} to {high} (median {format(float(np.median(values)), form)})"


def _stop(stopped, force):
    """How a model's path ended: '' (it did not stop), 'in tension' (its F̄max no answer) or
    'in compression' (its F̄max behind it: `gw.explicit.compare.settled`); a model with no
    path at all has no error and its cell is '—' (`_cell`)."""
    if not stopped:
        return ""
    return "in compression" if settled(True, force) else "in tension"


def _cell(error, holds, stop=""):
    """A model's error in the report: ✗ where it does not hold, how its path stopped
    (`_stop`) where it found no equilibrium part-way; '—' where it has no path at all."""
    if error is None:
        return "— ✗"
    return f"{error:+.1%}{f' stopped {stop}' if stop else ''}{'' if holds else ' ✗'}"


def _draw_spread(rows):
    """name → |error(draw a) − error(draw b)| over the surfaces drawn more than once (the
    largest difference between draws of one surface whose F̄max is the model's own: paths
    that did not stop in tension)."""
    groups = {}
    for r in rows:
        s = r["scene"]
        groups.setdefault((s["mu"], s["zeta"], s["sigma_r_eta"], s["summits"]), []).append(r)
    spread = {}
    for k in ("gw_sum", "gw_cells", "interacting"):
        for group in groups.values():
            errors = [r["errors"][k] for r in group
                      if settled(r["models"][k]["stopped"], r["models"][k]["approach"])]
            if len(errors) > 1:
                spread.setdefault(k, []).append(max(errors) - min(errors))
    return spread


def affine_section(records):
    """Markdown of the self-affine surfaces: each model's F̄max against the whole surface's."""
    a = AFFINE
    lines = ["### Self-affine surfaces, answered from their measured summits", "",
             f"Periodic {a['n']}² maps, Hurst {a['hurst']}, wavelengths {a['short']} to "
             f"{a['long']} pixels (`gw.explicit.self_affine`), answered as a user's map is "
             "(`gw.explicit.answer`): GW's integral over the summits' own Gaussian (ζ_s = "
             "σ_s/ε, ω = 1) and the interacting asperities on the summits counted on the map "
             "(8-neighbour maxima as caps of their mean radius R, μ at R, the ground between "
             "them counted once), against the map solved whole. "
             "F̄max in 2πRΔγ per counted summit; error: F̄max/F̄max(whole) − 1; ✗: outside 10 % "
             "(plus the estimate); '—': no equilibrium at the first separation (left out). "
             "'needs': the cheapest model within that.", "",
             "| μ | ζ (rms/ε) | seed | summits | ζ_s | σRη | pixel/√(Rε) | F̄max whole | ± | "
             "GW | interacting | needs | jumps in | whole s |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in records:
        s, m = r["spec"], r["models"]
        margin = 0.10 + r["estimate"] / m["whole"]["f_max"]
        lines.append(
            f"| {s['mu']:g} | {s['zeta']:g} | {s['seed']} | {r['summits']} | "
            f"{r['zeta_s']:.2f} | {r['sigma_r_eta']:.3f} | {r['pixel_sqrt_r_eps']:.2f} | "
            f"{m['whole']['f_max']:.4f} | {r['estimate']:.1e} | "
            + " | ".join(_affine_cell(m.get(k), margin) for k in ("gw", "interacting"))
            + f" | {r['needs']} | {r['jumps_in']} | {m['whole']['seconds']:.1f} |")
    return "\n".join(lines)


def _affine_cell(model, margin):
    """A model's cell in the self-affine table; '—' where it gave no answer (left out)."""
    if model is None:
        return "— ✗"
    stop = "" if not model["stopped"] else (
        "in compression" if model["settled"] else "in tension")
    return _cell(model["error"], abs(model["error"]) <= margin and model["settled"], stop)


def curves_figure(record):
    """F̄(d̃) of every model on one surface."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(6.5, 4.2))
    ax = fig.add_subplot()
    for name, label in NAMES.items():
        m = record["models"][name]
        d = np.asarray(m["d"])
        found = "no equilibrium" if m["f_max"] is None else f"F̄max {m['f_max']:.3f}"
        line, = ax.plot(d, m["approach"], label=f"{label}: {found}")
        if m["retraction"] is not None and name in ("interacting", "whole"):
            ax.plot(d, np.array(m["retraction"], dtype=float), ls="--", color=line.get_color(),
                    lw=0.8)
    s = record["scene"]
    ax.set_title(f"μ = {s['mu']:g}, ζ = {s['zeta']:g}, σRη = {s['sigma_r_eta']:g}, "
                 f"{s['summits']} summits (dashed: retraction)", fontsize=9)
    ax.set_xlabel("mean separation d̃ = d/σ")
    ax.set_ylabel("F̄ = F/(2πRΔγ N)  (< 0 tensile)")
    ax.axhline(0.0, color="0.7", lw=0.5)
    ax.legend(fontsize=7)
    return fig


def _answered(record):
    """Whether the interacting model's F̄max on a map surface is its own (`settled`)."""
    m = record["models"]["interacting"]
    return settled(m["stopped"], m["approach"])


#: The map figure's models, one row each, as (key of a record's errors, label).
FIGURE_MODELS = (("gw_sum", "GW's sum over the summits"),
                 ("gw_cells", "GW, ground counted once"),
                 ("interacting", "interacting asperities"))


def map_figure(records):
    """The F̄max error of GW's sum over the summits, of that sum with the ground counted once and
    of the interacting model (a row each) against σRη, per μ (a column each), one colour per ζ,
    filled marks the first draw and open ones the second (GW's integral differs from the sum by
    the sample: see the report)."""
    from matplotlib import colormaps
    from matplotlib.figure import Figure

    mus = sorted({r["scene"]["mu"] for r in records})
    zetas = sorted({r["scene"]["zeta"] for r in records})
    seeds = sorted({r["scene"]["seed"] for r in records})
    colors = colormaps["viridis"](np.linspace(0.0, 0.9, len(zetas)))
    fig = Figure(figsize=(3.4 * len(mus), 2.6 * len(FIGURE_MODELS) + 0.6), layout="constrained")
    grid = fig.subplots(len(FIGURE_MODELS), len(mus), squeeze=False, sharex=True, sharey="row")
    for (model, label), axes in zip(FIGURE_MODELS, grid):
        for ax, mu in zip(axes, mus):
            for zeta, color in zip(zetas, colors):
                for seed in seeds:
                    rows = sorted((r for r in records if r["scene"]["mu"] == mu
                                   and r["scene"]["zeta"] == zeta
                                   and r["scene"]["seed"] == seed),
                                  key=lambda r: r["scene"]["sigma_r_eta"])
                    x = [r["scene"]["sigma_r_eta"] for r in rows]
                    first = seed == seeds[0]
                    # the interacting model's path stopped in tension: no F̄max of its own (×)
                    own = [model != "interacting" or _answered(r) for r in rows]
                    y = [100 * r["errors"][model] if ok and r["errors"][model] is not None
                         else np.nan for r, ok in zip(rows, own)]
                    ax.plot(x, y, "o-" if first else "o", color=color, ms=4, lw=0.8,
                            mfc=None if first else "none",
                            label=f"ζ = {zeta:.3g}" if first else None)
                    ax.plot(x, [np.nan if ok or r["errors"][model] is None
                                else 100 * r["errors"][model] for r, ok in zip(rows, own)],
                            "x", color=color)
            ax.axhspan(-10, 10, color="0.9")
            ax.set_xscale("log")
            ax.set_xticks(MAP_SRE, [f"{v:g}" for v in MAP_SRE])
            ax.minorticks_off()
            ax.set_title(f"{label}, μ = {mu:g}", fontsize=8)
        axes[0].set_ylabel("F̄max error against\nthe whole surface [%]")
    for ax in grid[-1]:
        ax.set_xlabel("summit density σRη")
    grid[0][0].legend(fontsize=6, ncol=2)
    fig.suptitle("grey: within 10 %; open marks: a second draw; ×: the interacting path "
                 "stopped in tension", fontsize=9)
    return fig
