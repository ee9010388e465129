"""`python -m advisor FILE [--json]`: the cheapest model of the scene in FILE that meets its
tolerance, and the measured size of every effect each model leaves out."""

import json
import sys
from pathlib import Path

import numpy as np

from fem_asperity.plumbing.cli import Parser, ProgressBar, dump_json, print_table, run
from fem_asperity.plumbing.files import output_folder, staged_folder, write_atomic
from fem_asperity.solver.output import write_all

from .advice import (
    SURFACE_MODELS,
    WHOLE,
    MadeExplicit,
    advise,
    check_runnable,
    quantity_key,
    si_unit,
    value_of,
)
from .advice import run as run_model
from .scene import read_scene

PROG = "python -m advisor"
#: Who writes an advice's output folder (`plumbing.files.staged_folder`).
OWNER = PROG


def build_parser(prog=PROG):
    parser = Parser(prog=prog, description=__doc__)
    parser.add_argument("scene", help="the scene file (TOML; advisor/scene.py shows the keys)")
    parser.add_argument("--json", action="store_true", help="print the advice as JSON")
    parser.add_argument("--run", action="store_true",
                        help="run the model chosen and write it into --out (SI)")
    parser.add_argument("--out", type=Path,
                        help="with --run: the output folder (advice.json, the scene file, and "
                             "the curve's files where the model is a solve, or the surface's "
                             "where it is run on the scene's height map or its statistics made "
                             "explicit)")
    return parser


def main(argv=None, prog=PROG):
    """The advisor's command line (`prog`: the name its messages give it, e.g. `python -m
    fem_asperity scene`, which hands its command line over)."""
    parser = build_parser(prog)
    args = parser.parse_args(argv)
    if args.run != (args.out is not None):
        parser.error("--run and --out go together: the model chosen is run into --out")
    scene = read_scene(args.scene)  # every key checked before anything is solved
    out = output_folder(args.out, "--out", OWNER) if args.run else None
    if scene.surface is None:
        print(f"mu = {scene.mu:.4g}, R/eps = {scene.scales.R / scene.scales.eps:.4g}: solving "
              "the scene at BEM draft to measure its effects (and at default, with its "
              "estimate, where no cheaper model meets the tolerance) ...", file=sys.stderr)
    advice = advise(scene, measure=args.run, say=lambda m: print(m, file=sys.stderr))
    if args.run:
        check_runnable(advice)  # before anything is run or written
    record = advice.records()
    if args.run:
        _run(advice, record, out, Path(args.scene).name)
    if args.json:
        dump_json(record)
        return 0
    what = {"pull_off": "the pull-off force", "f_max": "the surface's strength F_max",
            "jump_in": "the jump-in's separation", "jump_out": "the jump-out's separation"}
    s = scene.scales
    print(f"mu = {scene.mu:.4g}, R/eps = {s.R / s.eps:.4g}, tolerance {scene.tolerance:.2%}")
    print(f"\nEffects on {what[scene.quantity]} (relative; how: below, by number):")
    effects = record["effects"]
    print_table([{"#": k, **e, "how": e["how"].split(":")[0]} for k, e in enumerate(effects, 1)],
                ("#", "name", "size", "uncertainty", "how"))
    for k, effect in enumerate(effects, 1):
        print(f"  [{k}] {effect['how']}")
        if effect["size"] is None:
            print(f"      not bounded here: {effect['note']}")
    print("\nModels, cheapest first (error: the sum of the effects each leaves out):")
    print_table(record["models"], ("name", "value", "value_si", "unit", "error", "cost_s"))
    print(f"\nchoice: {advice.message}")
    return 0


def _run(advice, record, out, scene_name):
    """The chosen model run and written into `out`, all or nothing: advice.json (the advice, and
    the model's value in SI), the scene file as given, and curve/ (`fem_asperity.write_all`,
    SI) where the model is a solve, or surface/ (as `gw explicit --out` writes it) where it
    is run on the scene's height map (the interacting asperities or the whole surface), or
    surface/whole_curves.csv where the whole surface is the scene's statistics made explicit
    (`MadeExplicit`)."""
    from gw.explicit.answer import Answer
    from gw.explicit.cli import answer_record, write_answer
    from gw.explicit.relax import keep_freed_memory

    print(f"running {advice.choice} ...", file=sys.stderr)
    if advice.choice in SURFACE_MODELS:
        keep_freed_memory()  # this process is ours: the solve's fields are reused
    bar = ProgressBar("whole surface", time_left=True) if advice.choice == WHOLE else None
    result = run_model(advice, progress=bar)
    if bar is not None:
        bar.close()
    if isinstance(result, Answer):
        record["result"] = _surface_result(advice, result)
    elif isinstance(result, MadeExplicit):
        record["result"] = _explicit_result(advice, result)
        for warning in record["result"]["resolution"] + record["result"]["notes"]:
            print(f"warning: {warning}", file=sys.stderr)
    elif result is not None:
        value = value_of(result, quantity_key(advice.scene))
        to_si, unit = si_unit(advice.scene)
        record["result"] = {"model": advice.choice, "value": value,
                            "value_si": None if value is None else value * to_si,
                            "unit": unit, "error_estimate": result.error_estimate,
                            "status": result.status, "message": result.message}
        if value is None:  # written all the same: the solve's files say what it found
            print(f"warning: {advice.choice} makes no {advice.scene.quantity}: "
                  f"{result.message}", file=sys.stderr)
    else:
        chosen = next(m for m in record["models"] if m["name"] == advice.choice)
        record["result"] = {key: chosen[key] for key in ("value", "value_si", "unit", "error")}
        record["result"]["model"] = advice.choice
    with staged_folder(out, owner=OWNER) as stage:
        write_atomic(stage / "advice.json", json.dumps(record, indent=1, allow_nan=False))
        write_atomic(stage / scene_name, advice.scene.source)
        if isinstance(result, Answer):
            (stage / "surface").mkdir()
            write_answer(stage / "surface", result,
                         answer_record(result, advice.scene.topography()))
        elif isinstance(result, MadeExplicit):
            (stage / "surface").mkdir()
            write_atomic(stage / "surface" / "whole_curves.csv",
                         _explicit_curves(advice, result))
        elif result is not None:
            write_all(result, stage / "curve", advice.scene.scales)
    print(f"wrote {out}", file=sys.stderr)


def _surface_result(advice, found):
    """The chosen model's strength on the scene's map as the advice states a model's value:
    F̄max per summit (2πRΔγ, R and η the map's counted summits'), in Pa over the map's area;
    the whole surface's with its error estimate and the cheaper models' F_max against it, the
    interacting asperities' with the error the advice reads off the measured map, or no value
    (a warning) where they found no equilibrium before the total force turned compressive
    (`gw.explicit.compare.settled`: their F_max is then not their own)."""
    from gw.explicit.compare import settled

    to_si, unit = si_unit(advice.scene)
    chosen = found.models.get(SURFACE_MODELS[advice.choice])
    out = {"model": advice.choice, "value": None, "value_si": None, "unit": unit,
           "files": "surface/", "notes": list(found.notes)}
    if chosen is None or not settled(chosen.stopped, chosen.force):
        print(f"warning: {advice.choice} has no answer on this map: "
              + "; ".join(found.notes), file=sys.stderr)
        return out
    out |= {"value": chosen.pressure_max / to_si, "value_si": chosen.pressure_max}
    whole = found.whole
    if whole is None:
        error = next(m for m in advice.models if m.name == advice.choice).error
        return out | {"error": error, "stopped_at_m": chosen.stopped}
    if whole.status != "ok":
        print(f"warning: {whole.message}", file=sys.stderr)
    return out | {"error_estimate": {"value_si": whole.error_estimate["pressure_max"],
                                     "relative": whole.error_estimate["pressure_max"]
                                     / whole.pressure_max},
                  "status": whole.status, "message": whole.message,
                  "relative_to_whole": found.relative_to_whole, "needs": found.needs}


def _explicit_result(advice, made):
    """The surface solved whole on the scene's statistics made explicit (`MadeExplicit`), as the
    advice states a model's value (F̄max per summit, and in Pa), with its relative error, each
    draw, the resolution flags, and a note where the error passes the tolerance."""
    from gw.explicit.measured_map import ACCURACY

    to_si, unit = si_unit(advice.scene)
    ratios, tolerance = made.ratios, advice.scene.tolerance
    spread = (max(ratios) - min(ratios)) / np.mean(ratios)
    notes = ([] if made.error <= tolerance else
             [f"the surface solved whole on {len(made.draws)} draws of the scene's statistics is "
              f"within {made.error:.2g} (the draws' spread {spread:.2g}), beyond the tolerance "
              f"{tolerance:g}: a measured height map ([surface] topography) answers for the "
              "surface itself"])
    if made.sample - 1.0 > tolerance:
        notes.append(f"the draws' {made.draws[0].scene.summits} caps stand for a large surface "
                     f"only roughly: summed on the table's law their F_max per summit is "
                     f"{made.sample:.3g} times GW's integral's (the few highest set it); that "
                     "the interaction measured on them carries over is not measured here")
    return {"model": advice.choice, "value": made.f_max, "value_si": made.f_max * to_si,
            "unit": unit, "error": made.error, "notes": notes, "resolution": made.coarse,
            "sample": made.sample,
            "files": "surface/whole_curves.csv",
            "how": f"GW's integral with the table's law and the ground counted once "
                   f"({made.gw:.4g}) times the ratio of the surface solved whole to the sum over "
                   f"the same caps with the ground counted once, on the scene's "
                   f"statistics made explicit as the measured map's surfaces are: "
                   f"{len(made.draws)} draws of {made.draws[0].scene.summits} caps at the "
                   f"summits' zeta and sigma R eta, solved whole ({ACCURACY}); the error the "
                   "table's, the larger whole surface's own estimate and the spread of the "
                   "ratio between the draws (with two draws about twice the standard error of "
                   "their mean, not a bound)",
            "draws": [{"seed": d.scene.seed, "pixel_sqrt_R_eps": d.scene.pixel,
                       "f_max_whole": d.models["whole"].f_max,
                       "f_max_cells": d.models["gw_cells"].f_max, "ratio": ratio,
                       "estimate_relative": d.estimate / d.models["whole"].f_max,
                       "jumps": list(d.models["whole"].jumps),
                       "seconds": d.models["whole"].seconds}
                      for d, ratio in zip(made.draws, ratios)]}


def _explicit_curves(advice, made):
    """CSV of the whole surfaces' approach and retraction on each draw of `made`: d, from the
    caps' mean height plane (GW's d), in the summits' σ_s and in m, and the force per summit
    on the draw (2πRΔγ; < 0 tensile) and per its area (Pa): the draw's own, 16 caps'."""
    from gw.explicit.compare import visible

    to_si, _ = si_unit(advice.scene)
    lines = ["seed,d_over_sigma_s,d_m,F_approach,F_retraction,F_approach_Pa,F_retraction_Pa"]
    for draw in made.draws:
        whole, sigma_m = draw.models["whole"], draw.scene.zeta * advice.scene.scales.eps
        topography, caps = draw.scene.surface()
        # F̄ is per summit not covered by another cap; the scene's η counts every cap drawn
        shown = visible(caps, topography.size, draw.scene.periodic).sum() / caps.z.size
        retraction = (np.full(whole.d.size, np.nan) if whole.retraction is None
                      else whole.retraction)
        for d, up, down in zip(whole.d, whole.approach, retraction):
            lines.append(f"{draw.scene.seed},{d:.9g},{d * sigma_m:.9g},{up:.9g},{down:.9g},"
                         f"{up * to_si * shown:.9g},{down * to_si * shown:.9g}")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    sys.exit(run(main, PROG))
