"""The scene advisor on scene files (by default the examples'): for each, the size of every
effect a cheaper model leaves out, the models with their summed error and their cost on the
machine that ran it, and the choice. `python -m validation advisor --out DIR` writes it;
docs/advisor.md is a copy of its advisor.md."""

import sys
import time
from pathlib import Path

from advisor.advice import advise
from advisor.scene import read_scene
from fem_asperity.plumbing.errors import InputError

#: The scenes shown by default: the examples beside the package (a source checkout).
EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def default_scenes():
    """The example scene files, sorted; InputError where there are none (an installed copy
    without the repository's examples/)."""
    scenes = sorted(EXAMPLES.glob("*.toml"))
    if not scenes:
        raise InputError(f"no scene files in {EXAMPLES}: name them with --scenes")
    return scenes


def run(scenes, step=None):
    """{'scenes': [{'file', 'advice' (`Advice.records()`), 'wall_s'}], 'wall_s'}: each scene
    read (all before any is advised, so a bad file stops the run at once) and advised."""
    read = [(Path(path), read_scene(path)) for path in scenes]
    rows, start = [], time.perf_counter()
    for i, (path, scene) in enumerate(read, 1):
        if step is not None:
            step(f"[{i}/{len(read)}] advising {path.name}")
        begun = time.perf_counter()
        record = advise(scene).records()
        rows.append({"file": path.name, "advice": record,
                     "wall_s": time.perf_counter() - begun})
    return {"scenes": rows, "wall_s": time.perf_counter() - start}


def _cell(value, digits=3, percent=False):
    """A table cell: '—' for None, a relative size in per cent, else `digits` significant."""
    if value is None:
        return "—"
    if isinstance(value, float):
        return f"{100.0 * value:.{digits}g} %" if percent else f"{value:.{digits}g}"
    return str(value)


def markdown(study, header):
    """advisor.md: the `header` lines, then per scene its inputs, effects, models and choice."""
    lines = list(header) + [
        "", "Each effect is the relative change of the quantity asked for that one "
        "simplification makes, for this scene, and how it was obtained; a model's error is the "
        "sum of the effects (and their uncertainties) it leaves out. Costs are wall seconds on "
        "the machine named above (— where the model was not run to advise); "
        "`advisor/advice.py` says how each effect is measured.", ""]
    for row in study["scenes"]:
        advice, scene = row["advice"], row["advice"]["scene"]
        lines += [f"## `{row['file']}`", "",
                  f"μ = {scene['mu']:.4g}, R/ε = {scene['R_over_eps']:.4g}, quantity "
                  f"`{scene['quantity']}`, tolerance {scene['tolerance']:.2%}; advised in "
                  f"{row['wall_s']:.1f} s.", "",
                  "| effect | size | uncertainty | how |", "|---|---|---|---|"]
        for effect in advice["effects"]:
            how = effect["how"] + (f" ({effect['note']})" if effect.get("note") else "")
            lines.append(f"| {effect['name']} | {_cell(effect['size'], percent=True)} | "
                         f"{_cell(effect['uncertainty'], percent=True)} | {how} |")
        lines += ["", "| model | value | value (SI) | error | cost [s] |", "|---|---|---|---|---|"]
        for model in advice["models"]:
            si = ("—" if model["value_si"] is None
                  else f"{model['value_si']:.4g} {model['unit']}")
            lines.append(f"| {model['name']} | {_cell(model['value'], 5)} | {si} | "
                         f"{_cell(model['error'], percent=True)} | "
                         f"{_cell(model['cost_s'], 2)} |")
        lines += ["", f"Choice: {advice['message']}", ""]
    return "\n".join(lines)


def progress(text):
    print(f"  {text}", file=sys.stderr, flush=True)
