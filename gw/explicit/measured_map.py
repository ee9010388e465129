"""The measured map of where GW holds, shipped with the package so that a scene's GW error is
read, not solved.

The map is `validation rough-explicit --full`'s: GW surfaces made explicit over a grid of
(μ, ζ, σRη), two draws each, solved whole and by every cheaper model (`compare`). It ships as
MAP_FILE (`python -m validation rough-explicit --full --ship` rewrites it): per surface its
grid point, the whole surface's relative error estimate, and each model's F̄max error against
the whole surface (None where the model's path stopped in tension: no answer of its own).
`measured_error` reads off a model's error around a scene inside the map's box.
"""

import itertools
import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fem_asperity.plumbing.errors import InputError
from fem_asperity.plumbing.files import write_atomic

MAP_FILE = Path(__file__).parents[1] / "data" / "rough_map.json"
#: The grid's axes, in the order `measured_error` brackets them.
AXES = ("mu", "zeta", "sigma_r_eta")
#: The map's pixel (√(Rε)) where μ allows: compliance number μ^1.5 a/π = 0.064 at μ = 1, where
#: one cap's F̄max was 8.5e-4 off the boundary integral (test_whole_surface.py).
MAP_PIXEL = 0.2
#: Summits per surface, and two draws of each surface: the spread between them is the
#: sample's share of each model's error.
MAP_SUMMITS, MAP_SEEDS = 16, (0, 1)
#: The separation step and estimate the map's surfaces are solved at.
ACCURACY = "draft"
#: Most pixels along a side of a surface `measure_at` solves: a little above the map's largest
#: (μ = 2, ζ = 12, σRη = 0.02: 883²; its time in docs/rough_explicit_report.md).
MEASURE_MAX_SIDE = 1024
#: A value within this relative distance of a grid value is on it (a scene's μ from E*, R, Δγ
#: and ε in SI carries rounding of ~1e-15; the map's own values are written to ~1e-16).
ON_GRID = 1e-6


@dataclass(frozen=True)
class MeasuredError:
    """A model's F̄max error read off the map around a point: `size` (the largest |error| over
    the `surfaces` solved at the grid points that bracket it; None where the model has no
    answer on one of them, or where one of them, or one of its draws, was not solved:
    `missing`, as (μ, ζ, σRη, seed)), `uncertainty` (the largest over those grid points of
    their whole surfaces' relative estimate plus the spread of the model's error between
    their draws; NaN where none was solved), `around` (each axis's bracketing values), and
    `least`, the smallest |error| over the same surfaces (None with `size`): where even it is
    beyond a bound, every surface around the point is. `sample`: the largest over the same
    surfaces of their caps' F̄max summed without interaction against GW's integral on the same
    statistics (`sample_ratio`): near 1 where the map's caps stand for a large surface, far above
    where their few highest set F̄max (large ζ; benchmarks/results/map_sample.md measures whether
    the errors carry over there)."""

    size: float | None
    uncertainty: float
    surfaces: int
    around: dict
    missing: tuple = ()
    least: float | None = None
    sample: float | None = None


def map_pixel(mu):
    """The pixel (√(Rε)) of the map's surfaces at Tabor parameter `mu`: MAP_PIXEL, or finer
    where the compliance number μ^1.5 a/π would pass the whole-surface solver's warning bound
    (`whole.COMPLIANCE_MAX`, 0.1: 0.111 at μ = 2; its F̄max error there is a few 1e-3, beside
    the map's 10 % verdicts)."""
    from .whole import COMPLIANCE_MAX

    return min(MAP_PIXEL, COMPLIANCE_MAX * np.pi / mu**1.5)


def map_scene(mu, zeta, sigma_r_eta, seed):
    """The map's GW surface made explicit (`compare.Scene`) at (μ, ζ, σRη), draw `seed`."""
    from .compare import Scene

    return Scene(mu=mu, zeta=zeta, sigma_r_eta=sigma_r_eta, summits=MAP_SUMMITS, seed=seed,
                 pixel=map_pixel(mu))


def measurable(mu, zeta, sigma_r_eta):
    """Pixels along a side of the map's surface at (μ, ζ, σRη) (MAP_SUMMITS caps at density
    η = σRη/(σR) on a square √(N/η) = √(N ζ/σRη) √(Rε) wide, at `map_pixel(μ)`); InputError
    where it is outside `compare.Scene`'s ranges or more than MEASURE_MAX_SIDE pixels wide."""
    from .compare import Scene

    Scene(mu=mu, zeta=zeta, sigma_r_eta=sigma_r_eta)  # its ranges
    side = int(np.ceil(np.sqrt(MAP_SUMMITS * zeta / sigma_r_eta) / map_pixel(mu)))
    if side > MEASURE_MAX_SIDE:
        raise InputError(f"its GW surfaces made explicit would be {side} x {side} pixels, more "
                         f"than the {MEASURE_MAX_SIDE} measured here")
    return side


def explicit_draws(mu, zeta, sigma_r_eta, progress=None):
    """The map's draws (MAP_SEEDS) of GW's surface made explicit at (μ, ζ, σRη), each compared
    (`compare.compare`, at ACCURACY) with the table's law (no solve of it): a tuple of
    `compare.Comparison`, the surface solved whole among their models. InputError before
    anything is solved where the point is not `measurable`. `progress(fraction)` after each
    draw."""
    from .compare import compare
    from .interacting import AsperityLaw

    measurable(mu, zeta, sigma_r_eta)
    scenes = [map_scene(mu, zeta, sigma_r_eta, seed) for seed in MAP_SEEDS]
    law, draws = AsperityLaw.tabulated(mu), []
    for k, scene in enumerate(scenes):
        draws.append(compare(scene, accuracy=ACCURACY, law=law))
        if progress:
            progress((k + 1) / len(scenes))
    return tuple(draws)


def measured_from(model, draws):
    """`MeasuredError` of `model` on `draws` (`explicit_draws` of one point), its uncertainty
    as `measured_error`'s."""
    from .compare import settled

    found = []
    for comparison in draws:
        curve = comparison.models[model]
        found.append({"estimate": comparison.estimate / comparison.models["whole"].f_max,
                      "errors": {model: comparison.errors[model]
                                 if settled(curve.stopped, curve.approach) else None}})
    least, size = _range([d["errors"][model] for d in found])
    scene = draws[0].scene
    samples = [sample_ratio(d.errors) for d in draws]
    return MeasuredError(size, _uncertainty(model, found), len(draws),
                         {"mu": [scene.mu], "zeta": [scene.zeta],
                          "sigma_r_eta": [scene.sigma_r_eta]}, (), least,
                         None if None in samples else max(samples))


def measure_at(model, *, mu, zeta, sigma_r_eta, progress=None):
    """`MeasuredError` of `model` solved at (μ, ζ, σRη) itself, as the map is made
    (`explicit_draws`, `measured_from`): for a point the map does not hold. InputError before
    anything is solved where it is not `measurable`."""
    return measured_from(model, explicit_draws(mu, zeta, sigma_r_eta, progress))


def map_record(records, provenance):
    """The compact map (a JSON-ready dict) of `records` (validation.rough_explicit's, one per
    surface) with `provenance` (dict: command, commit, solver revision, date)."""
    from .compare import settled

    surfaces = []
    for r in records:
        whole = r["models"]["whole"]["f_max"]
        errors = {name: (r["errors"][name] if settled(m["stopped"], m["approach"]) else None)
                  for name, m in r["models"].items() if name != "whole"}
        surfaces.append({**{k: r["scene"][k] for k in AXES + ("seed", "pixel", "summits")},
                         "estimate": r["estimate"] / whole, "errors": errors})
    return {"provenance": provenance,
            "axes": {k: sorted({s[k] for s in surfaces}) for k in AXES},
            "surfaces": surfaces}


def save_map(path, record):
    """Write the map `record` to `path` (JSON, atomically)."""
    write_atomic(Path(path), json.dumps(record, indent=1, allow_nan=False) + "\n")


def shipped_map():
    """The map shipped with the package (MAP_FILE), None if it is missing."""
    if not MAP_FILE.exists():
        return None
    return json.loads(MAP_FILE.read_text())


def _bracket(values, x):
    """The grid values around `x` (itself if within ON_GRID of one, else the neighbours below
    and above), None outside [min, max]."""
    values = np.asarray(values, dtype=float)
    logs, target = np.log(values), np.log(x)
    if not logs[0] - ON_GRID <= target <= logs[-1] + ON_GRID:
        return None
    on = np.abs(logs - target) <= ON_GRID
    if on.any():
        return [float(values[on][0])]
    k = int(np.searchsorted(logs, target))  # strictly inside: 1 <= k <= len - 1
    return [float(values[k - 1]), float(values[k])]


def measured_error(model, *, mu, zeta, sigma_r_eta, record=None):
    """`MeasuredError` of `model` (a name of `compare.MODELS` but 'whole') at (μ, ζ, σRη) from
    the map (`record`, by default the shipped one): the largest over the grid points that
    bracket it on every axis (up to eight, each with its draws), a first-order reading (the
    error between grid points is taken as no larger than at them). None outside the map's
    box (or with no map); no size where a grid point around it, or one of the map's draws
    there, was not solved (a map that is not a full product); InputError for a model the map
    does not hold."""
    record = shipped_map() if record is None else record
    if record is None:
        return None
    names = set(record["surfaces"][0]["errors"])
    if model not in names:
        raise InputError(f"model must be one of {', '.join(sorted(names))}; got {model!r}")
    point = {"mu": mu, "zeta": zeta, "sigma_r_eta": sigma_r_eta}
    around = {k: _bracket(record["axes"][k], point[k]) for k in AXES}
    if any(v is None for v in around.values()):
        return None
    near = [s for s in record["surfaces"] if all(s[k] in around[k] for k in AXES)]
    draws = sorted({s["seed"] for s in record["surfaces"]})
    solved = {tuple(s[k] for k in AXES + ("seed",)) for s in near}
    missing = tuple(c for c in itertools.product(*(around[k] for k in AXES), draws)
                    if c not in solved)
    least, size = (None, None) if missing else _range([s["errors"][model] for s in near])
    points = {}  # the draws of each grid point: their spread is the sample's share
    for s in near:
        points.setdefault(tuple(s[k] for k in AXES), []).append(s)
    uncertainty = max((_uncertainty(model, draws) for draws in points.values()), default=np.nan)
    samples = [sample_ratio(s["errors"]) for s in near]
    return MeasuredError(size, uncertainty, len(near), around, missing, least,
                         max(samples) if samples and None not in samples else None)


def sample_ratio(errors):
    """A map surface's F̄max of the sum over its caps (no interaction) against GW's integral on
    its statistics, from its `errors` (each model's against the whole surface); None where
    either has no answer."""
    summed, integral = errors.get("gw_sum"), errors.get("gw_solved")
    if summed is None or integral is None:
        return None
    return (1.0 + summed) / (1.0 + integral)


def _range(errors):
    """(smallest, largest) |error| of `errors`; (None, None) where one has no answer (None)."""
    if any(e is None for e in errors):
        return None, None
    return float(min(abs(e) for e in errors)), float(max(abs(e) for e in errors))


def _uncertainty(model, draws):
    """The uncertainty of `model`'s error read off the `draws` of one point (dicts with
    'estimate' and 'errors'): the largest whole surface's relative estimate, plus the spread
    of the model's errors between the draws (the sample's share; 0 where one has none)."""
    errors = [d["errors"][model] for d in draws if d["errors"][model] is not None]
    spread = max(errors) - min(errors) if errors else 0.0
    return float(max(d["estimate"] for d in draws) + spread)
