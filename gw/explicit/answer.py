"""A user's own surface answered: its strength of adhesion by GW, by interacting asperities and
solved whole, their differences, and which model the surface needs. SI throughout.

GW and the interacting asperities take the map's summits (`topography.summits`: σ_s, the mean
summit radius R, η, and for the interacting model each summit's place and height) and the solved
single-asperity law at the Tabor parameter of R; the interacting model counts the ground
between the summits once (`tails`, the summits taken as caps of radius R). GW integrates over a
Gaussian of the summits' own rms height σ_s (ζ = σ_s/ε, ω = 1). GW's d is measured from the
summits' mean height; here every d is from the map's datum (z = 0), GW's shifted accordingly.
"""

import time
from dataclasses import dataclass, field, replace

import numpy as np

from fem_asperity.closed_forms.scales import Scales
from fem_asperity.plumbing.errors import InputError

from ..integrate import strength, totals
from ..surface import RoughSurface
from .compare import HOLDS, settled, within
from .interacting import AsperityLaw, Interacting, coupling
from .radii import own_radii
from .tails import SharedTails
from .topography import spectral_summit_statistics, summit_statistics, summits
from .whole import check_map, most_tensile, solve_whole

#: The models, cheapest first; --model names the most expensive one run.
MODELS = ("gw", "interacting", "whole")
#: Most summits the interacting model takes: its coupling is a dense n × n matrix (8 n² bytes,
#: 128 MB at 4000).
MAX_SUMMITS = 4000


@dataclass(frozen=True)
class ModelAnswer:
    """One model's answer: `force_max` (N, the largest tensile total force on approach,
    positive), `d_at_max` (m), `pressure_max` (Pa, over the map's area), `seconds`, the
    curve it came from (`d`, m; `force`, N, < 0 tensile), and `stopped` (m: where the
    interacting model found no equilibrium and its curve ends; None where it did not)."""

    force_max: float
    d_at_max: float
    pressure_max: float
    seconds: float
    d: np.ndarray = field(repr=False)
    force: np.ndarray = field(repr=False)
    stopped: float | None = None


@dataclass(frozen=True)
class Answer:
    """The answer for one map: `models` (name → ModelAnswer), `whole` (the `WholeSurface`, or
    None), `relative_to_whole` (name → F_max/F_max(whole) − 1), `needs` (the cheapest model
    `compare.within` the whole surface, its estimate counted, on a `compare.settled` path;
    None without the whole surface, or where its own estimate is beyond HOLDS), `statistics`
    (the summits counted, the spectral estimate, and `radii`: the summits' own radii against
    their mean, a `radii.RadiusSpread` as a dict), `mu` (at the summit radius), `notes`
    (what was left out and why), `law`: where the asperity law of GW and the interacting
    model came from."""

    models: dict
    whole: object
    relative_to_whole: dict
    needs: str | None
    statistics: dict
    mu: float
    radius: float
    notes: tuple
    law: str = ""

    def records(self):
        """JSON-ready: the whole surface's record (si, error_estimate, paths, jumps) when it was
        solved, every model's F_max in SI, the statistics and the verdict."""
        out = self.whole.records() if self.whole is not None else {}
        if self.whole is None:
            best = self.models[max(self.models, key=MODELS.index)]
            out["si"] = {"force_max": best.force_max, "pressure_max": best.pressure_max,
                         "d_at_max": best.d_at_max}
        out["models"] = {name: {"force_max": m.force_max, "pressure_max": m.pressure_max,
                                "d_at_max": m.d_at_max, "seconds": m.seconds,
                                "relative_to_whole": self.relative_to_whole.get(name),
                                "stopped_at": m.stopped}
                         for name, m in self.models.items()}
        out["needs"] = self.needs
        out["statistics"] = self.statistics
        out["law"] = self.law
        out["mu"], out["summit_radius"] = self.mu, self.radius
        out["notes"] = list(self.notes)
        return out


def answer(topography, adhesion, *, model="whole", accuracy="default", radius=None,
           law=None, progress=None):
    """Every model up to `model` (MODELS) on `topography` (`Topography`, m) with `adhesion`
    (`Adhesion`) → `Answer`. `radius` (m): the summit radius, instead of the measured mean;
    `law`: the `AsperityLaw` at its μ (by default the shipped table's, `AsperityLaw.at`: no
    solve where the table covers μ)."""
    if model not in MODELS:
        raise InputError(f"model must be one of {', '.join(MODELS)}; got {model!r}")
    check_map(topography, adhesion)  # before any statistics or solve
    counted = summit_statistics(topography)
    if counted.count < 2 or not counted.sigma_s > 0:
        raise InputError(f"the map holds {counted.count} summit(s) of one height: GW and the "
                         "interacting asperities need summits of different heights")
    spectral = _spectral(topography)
    radius = counted.radius if radius is None else radius
    if not radius > 0:
        raise InputError(f"the summits' mean curvature gives no positive radius ({radius:g} m)")
    scales = Scales(E_star=adhesion.e_star, dgamma=adhesion.dgamma, eps=adhesion.eps, R=radius)
    law = law or AsperityLaw.at(scales.mu)
    found = summits(topography)
    unit_force = 2 * np.pi * radius * adhesion.dgamma
    area = topography.heights.size * topography.pixel**2
    notes, models = [], {}
    d_grid = separations(topography, adhesion, accuracy)
    spread = own_radii(topography, adhesion, d_grid, radius=radius, mu=scales.mu)

    started = time.perf_counter()
    # GW on the summits' own Gaussian: σ_s = their rms height, ω = 1 (the reading that needs
    # no choice between eq. 21 as printed and McCool's σ_s = ωσ)
    sigma_s = counted.sigma_s
    surface = RoughSurface(zeta=sigma_s / adhesion.eps, omega=1.0)
    count = counted.density * area  # ηA₀: GW's summits on the map
    shift = float(np.mean(found.heights))  # GW's datum (the summits' mean) on the map's
    best = strength(law.approach, surface)
    f = totals(law.approach, surface, (d_grid - shift) / sigma_s)[0] * unit_force * count
    models["gw"] = ModelAnswer(best.f_max * unit_force * count,
                               best.d_at_max * sigma_s + shift,
                               best.f_max * unit_force * count / area,
                               time.perf_counter() - started, d_grid, f)
    if MODELS.index(model) >= 1:
        if found.heights.size > MAX_SUMMITS:
            notes.append(f"interacting: {found.heights.size} summits, more than {MAX_SUMMITS}: "
                         "left out")
        else:
            interacting = _interacting(topography, found, law, scales, d_grid, unit_force,
                                       area, notes)
            if interacting is not None:
                models["interacting"] = interacting
    whole = None
    if model == "whole":
        whole = solve_whole(topography, adhesion, accuracy=accuracy, progress=progress)
        models["whole"] = ModelAnswer(whole.force_max, whole.d_at_max, whole.pressure_max,
                                      whole.cost["seconds"], whole.approach.d,
                                      whole.approach.force)
    relative, needs = {}, None
    if whole is not None:
        reference = whole.force_max
        relative = {name: m.force_max / reference - 1.0 for name, m in models.items()}
        estimate = whole.error_estimate["force_max"]
        if estimate > HOLDS * reference:  # a verdict within HOLDS needs a finer reference
            notes.append(f"needs: not judged: the whole surface's own estimate is "
                         f"{estimate / reference:.0%} of its F_max, beyond the {HOLDS:.0%} "
                         "a verdict needs (refine the map)")
        else:
            needs = next(name for name in MODELS if name in models
                         and within(models[name].force_max, reference, estimate,
                                    settled(models[name].stopped, models[name].force)))
    statistics = {"summits": vars(counted), "spectral": vars(spectral) if spectral else None,
                  "radii": vars(spread)}
    return Answer(models, whole, relative, needs, statistics, scales.mu, radius, tuple(notes),
                  law.source)


def _spectral(topography):
    """The spectral summit statistics, None where McCool's σ_s has no real value."""
    try:
        return spectral_summit_statistics(topography)
    except InputError:
        return None


def separations(topography, adhesion, accuracy):
    """The d (m) the cheap models are sampled at: the whole surface's approach grid."""
    from .whole import START_GAP, STEPS

    eps, z = adhesion.eps, topography.heights
    top = float(z.max()) + START_GAP * eps
    bottom = float(np.percentile(z, 50)) - 2 * eps
    return np.arange(top, bottom, -STEPS[accuracy] * eps)


def _interacting(topography, found, law, scales, d_grid, unit_force, area, notes):
    """The interacting model's `ModelAnswer`; None (and a note) where it has no equilibrium at
    the first separation."""
    started = time.perf_counter()
    pixel = topography.pixel / scales.length_r
    k = coupling(found.rows, found.columns, shape=topography.shape, pixel=pixel, mu=scales.mu,
                 periodic=topography.periodic)
    heights = found.heights / scales.eps
    model = Interacting(heights, k, law)
    path, _, _ = model.follow(d_grid / scales.eps)
    if path.d.size == 0:
        notes.append("interacting: no equilibrium of the far-field model at the first "
                     "separation (contacts too large or too close for it): left out")
        return None
    tails = SharedTails.build(found.rows * pixel, found.columns * pixel, heights,
                              topography.heights / scales.eps, pixel=pixel,
                              periodic=topography.periodic, separations=d_grid / scales.eps)
    path = replace(path, force=path.force + tails.along(path.d))
    if path.stopped is not None:
        notes.append(f"interacting: no equilibrium of the far-field model below d = "
                     f"{path.stopped * scales.eps:.4g} m (contacts too large or too close "
                     "for it); " + ("the total force had turned compressive, its F_max "
                                    "behind it" if settled(path.stopped, path.force) else
                                    "still in tension: its F_max is only that of the path "
                                    "above, no answer"))
    f_max, d_max, _ = most_tensile(path.d, path.force)
    return ModelAnswer(f_max * unit_force, d_max * scales.eps, f_max * unit_force / area,
                       time.perf_counter() - started, path.d * scales.eps,
                       path.force * unit_force,
                       None if path.stopped is None else path.stopped * scales.eps)
