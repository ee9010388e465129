"""GW against the surface it idealises: the same summits as GW's integral (eqs. 22-28), as a
sum over the actual summits, as interacting asperities, and as the whole surface solved.

A "GW made explicit" surface (`explicit_caps`) is caps of one radius R at Gaussian heights
(σ_s = σ, ω = 1) on random positions of density η: everything but the interaction is GW's by
construction, so the models differ by what each leaves out:

- `gw_paper`, `gw_solved`: GW's integral over the Gaussian with the paper's law or the solved
  one (no interaction; the Gaussian, not these summits);
- `gw_once`: GW's integral with the solved law and the ground between summits at random places
  counted once (`gw.shared_ground`, in closed form);
- `gw_sum`: the solved law summed over these summits (their actual heights; no interaction);
- `gw_cells`: the same sum with the ground between the summits counted once (`tails`: each
  summit's law is a whole paraboloid's, whose LJ tail reaches over its neighbours' cells);
- `interacting`: the summits coupled by the elastic far field (`interacting`), the ground
  counted once as in `gw_cells`;
- `whole`: the map solved whole (`whole`): the reference.

All in GW's units: F̄ = F/(2πRΔγ N), N the summits on the map (a cap under another is no
summit and is left out of the sums, `visible`), d̃ = d/σ from the mean height of the Gaussian
the summits were drawn from (the map's datum, z = 0). GW's integral counts every cap drawn as a
summit (ηA₀ caps), so its F̄ is scaled by ηA₀/N: every model's F̄ is its total force over
2πRΔγ N.
"""

import time
from dataclasses import dataclass

import numpy as np

from fem_asperity.plumbing.checks import in_range, positive
from fem_asperity.plumbing.errors import InputError

from ..integrate import strength, totals
from ..laws import PaperLaw
from ..surface import RoughSurface
from .interacting import AsperityLaw, Interacting, coupling
from .tails import SharedTails
from .topography import gaussian_caps
from .whole import Adhesion, most_tensile, solve_whole

#: The physical scale of the explicit surfaces: F̄, d̃ and the jumps depend on μ, ζ, σRη and
#: the pixel in √(Rε) only, so these fix nothing but the SI numbers in the files.
EPS, DGAMMA, RADIUS_OVER_EPS = 0.3e-9, 0.05, 1000.0
#: Models, cheapest first.
MODELS = ("gw_paper", "gw_solved", "gw_once", "gw_sum", "gw_cells", "interacting", "whole")
#: GW "holds" where its F̄max is within this fraction of the whole surface's.
HOLDS = 0.10


@dataclass(frozen=True)
class Scene:
    """A GW surface made explicit: Tabor parameter `mu`, ζ = σ/ε (`zeta`), σRη
    (`sigma_r_eta`), `summits` (how many), `pixel` (in √(Rε)), `seed`, `periodic`."""

    mu: float
    zeta: float
    sigma_r_eta: float
    summits: int = 40
    pixel: float = 0.2
    seed: int = 0
    periodic: bool = True

    def __post_init__(self):
        in_range("mu", self.mu, 0.01, 10.0)
        in_range("zeta", self.zeta, 0.01, 1e3)
        in_range("sigma_r_eta", self.sigma_r_eta, 1e-4, 10.0)
        in_range("summits", self.summits, 1, 10_000)
        positive("pixel", self.pixel)

    @property
    def radius(self):
        return RADIUS_OVER_EPS * EPS

    @property
    def unit(self):
        """√(Rε), m."""
        return np.sqrt(self.radius * EPS)

    @property
    def adhesion(self):
        """E* for μ: μ³ = RΔγ²/(E*²ε³)."""
        return Adhesion(np.sqrt(self.radius * DGAMMA**2 / (EPS**3 * self.mu**3)), DGAMMA, EPS)

    def surface(self):
        """(Topography, Caps): η = σRη/(σR), the map L = √(N/η) wide."""
        sigma = self.zeta * EPS
        density = self.sigma_r_eta / (sigma * self.radius)
        side = np.sqrt(self.summits / density)
        n = int(np.ceil(side / (self.pixel * self.unit)))
        if n > 2048:
            raise InputError(f"the map would need {n} x {n} pixels (sigma_r_eta = "
                             f"{self.sigma_r_eta:g} spreads {self.summits} summits that far): "
                             f"use fewer summits or a larger pixel")
        pixel = side / n
        return gaussian_caps(n=n, pixel=pixel, radius=self.radius, sigma=sigma,
                             density=self.summits / side**2, seed=self.seed,
                             periodic=self.periodic)


@dataclass(frozen=True)
class ModelCurve:
    """One model on one surface: `d` (d̃), `approach` and `retraction` (F̄, < 0 tensile; the
    retraction None where the model has none), `f_max` (F̄max > 0, on approach), `d_at_max`
    (d̃), `f_off` (the most tensile F̄ on retraction, > 0), `jumps` (in, out), `seconds`, and
    `stopped` (d̄, ε: where the interacting model found no equilibrium and its path ends;
    None where it did not; where that is its first separation, its paths are empty and
    F̄max and its d̃ None: no answer at all)."""

    d: np.ndarray
    approach: np.ndarray
    retraction: np.ndarray | None
    f_max: float | None
    d_at_max: float | None
    f_off: float | None
    jumps: tuple
    seconds: float
    stopped: float | None = None


@dataclass(frozen=True)
class Comparison:
    """Every model on one `scene`: `models` (name → ModelCurve), the whole surface's
    `estimate` of F̄max, `errors` (name → F̄max/F̄max(whole) − 1; None for a model with no
    path: no equilibrium at its first separation) and `holds` (name → within HOLDS, counting
    the estimate, on a path that is `settled`)."""

    scene: Scene
    models: dict
    estimate: float
    errors: dict
    holds: dict


def compare(scene, *, accuracy="default", law=None, progress=None):
    """Every model of MODELS on `scene` → `Comparison`. `law`: the `AsperityLaw` at scene.mu
    (solved or read from the store when None)."""
    law = law or AsperityLaw.solved(scene.mu)
    topography, caps = scene.surface()
    shown = visible(caps, topography.size, scene.periodic)
    count, sigma = int(shown.sum()), scene.zeta
    started = time.perf_counter()
    whole = solve_whole(topography, scene.adhesion, accuracy=accuracy, progress=progress)
    d_eps = whole.approach.d / EPS
    per_summit = 2 * np.pi * scene.radius * DGAMMA * count
    models = {"whole": _curve(d_eps / sigma, whole.approach.force / per_summit,
                              whole.retraction.force[::-1] / per_summit,
                              (sum(j.kind == "in" for j in whole.jumps),
                               sum(j.kind == "out" for j in whole.jumps)),
                              time.perf_counter() - started)}
    heights = caps.z[shown] / EPS
    pixel = topography.pixel / scene.unit
    rows = np.round(caps.x[shown] / topography.pixel).astype(int) % topography.shape[0]
    cols = np.round(caps.y[shown] / topography.pixel).astype(int) % topography.shape[1]
    started = time.perf_counter()
    tails = SharedTails.build(caps.x[shown] / scene.unit, caps.y[shown] / scene.unit, heights,
                              topography.heights / EPS, pixel=pixel, periodic=scene.periodic,
                              separations=d_eps)
    tails_seconds = time.perf_counter() - started
    k = coupling(rows, cols, shape=topography.shape, pixel=pixel, mu=scene.mu,
                 periodic=scene.periodic)
    alone = _summits(Interacting(heights, 0.0 * k, law), d_eps)
    models["gw_sum"] = _summit_curve(alone, None, sigma, count)
    models["gw_cells"] = _summit_curve(alone, tails, sigma, count, tails_seconds)
    models["interacting"] = _summit_curve(_summits(Interacting(heights, k, law), d_eps), tails,
                                          sigma, count, tails_seconds)
    surface = RoughSurface(zeta=scene.zeta, omega=1.0)
    drawn = caps.z.size / count  # GW's F̄ is per cap drawn: as a total over N summits
    for name, gw_law, shared in (("gw_paper", PaperLaw(scene.mu), None),
                                 ("gw_solved", law.approach, None),
                                 ("gw_once", law.approach, scene.sigma_r_eta)):
        started = time.perf_counter()
        best = strength(gw_law, surface, sigma_r_eta=shared)
        f = totals(gw_law, surface, d_eps / sigma, sigma_r_eta=shared)[0]
        models[name] = ModelCurve(d_eps / sigma, f * drawn, None, best.f_max * drawn,
                                  best.d_at_max, None,
                                  (0, 0), time.perf_counter() - started)
    reference = models["whole"].f_max
    estimate = whole.error_estimate["force_max"] / per_summit
    errors = {name: None if models[name].f_max is None else models[name].f_max / reference - 1.0
              for name in MODELS}
    holds = {name: within(models[name].f_max, reference, estimate,
                          settled(models[name].stopped, models[name].approach))
             for name in MODELS}
    return Comparison(scene, {name: models[name] for name in MODELS}, estimate, errors, holds)


def within(f_max, reference, estimate, settled=True):
    """Whether a model's `f_max` holds: within HOLDS of the whole surface's `reference`,
    counting its `estimate` (both in f_max's unit), and `settled` (its own; see `settled`)."""
    return settled and abs(f_max - reference) <= HOLDS * reference + estimate


def settled(stopped, force):
    """Whether a path's F_max is its own: it did not stop (`stopped` None), or it stopped
    where its total `force` (< 0 tensile) had turned compressive, its most tensile point
    behind it (past there each contact's force only grows compressive; a summit still to touch
    would have to out-pull them all; the whole surface's own approach ends by the same rule,
    `whole._solve`). A path that stopped in tension has an F_max that is only that of the path
    above, or none where it stopped at its first separation."""
    return stopped is None or bool(len(force) and force[-1] >= 0.0)


def visible(caps, size, periodic):
    """Which caps have their apex on the map (not under another cap): z_i ≥ z_j − r_ij²/2R
    for every j (nearest periodic images if `periodic`; `size` (Lx, Ly), m). A covered cap is
    no summit: the whole surface never sees it, so neither do the sums."""
    dx = caps.x[:, None] - caps.x[None, :]
    dy = caps.y[:, None] - caps.y[None, :]
    if periodic:
        dx -= size[0] * np.round(dx / size[0])
        dy -= size[1] * np.round(dy / size[1])
    above = caps.z[None, :] - (dx**2 + dy**2) / (2 * caps.radius) - caps.z[:, None]
    np.fill_diagonal(above, -np.inf)
    return above.max(axis=1) < 0.0


def _summits(model, separations):
    """(approach, retraction, seconds) of an `Interacting` model through `separations` (ε)
    and back from where its approach ended."""
    started = time.perf_counter()
    up, attached, delta = model.follow(separations)
    down, _, _ = model.follow(up.d[::-1], attached=attached, delta=delta)
    return up, down, time.perf_counter() - started


def _summit_curve(paths, tails, sigma, count, tails_seconds=0.0):
    """The `ModelCurve` of `_summits` paths, with `tails` (`SharedTails`) added to the force
    where given, in GW's units (d̃ = d/σ, F̄ per summit: `count`)."""
    up, down, seconds = paths

    def force(path):
        return path.force + (0.0 if tails is None else tails.along(path.d))

    jumps = (sum(j[0] == "in" for j in up.jumps + down.jumps),
             sum(j[0] == "out" for j in up.jumps + down.jumps))
    if up.d.size == 0:  # no equilibrium at the first separation: no answer at all
        return ModelCurve(up.d, up.force, None, None, None, None, jumps,
                          seconds + tails_seconds, up.stopped)
    return _curve(up.d / sigma, force(up) / count, _padded(force(down)[::-1], up.d.size) / count,
                  jumps, seconds + tails_seconds, up.stopped)


def _padded(values, size):
    """`values` with NaN after them up to `size` (a retraction that stopped early)."""
    return np.concatenate([values, np.full(size - values.size, np.nan)])


def _curve(d, approach, retraction, jumps, seconds, stopped=None):
    f_max, d_max, _ = most_tensile(d, approach)
    f_off = None if np.isnan(retraction).all() else float(-np.nanmin(retraction))
    return ModelCurve(d, approach, retraction, f_max, d_max, f_off, jumps, seconds, stopped)
