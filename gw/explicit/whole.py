"""The whole rough surface solved: a rigid height map on an elastic half-space, LJ 9-3 forces
between them, the separation d as the control, approach and retraction with every jump.

This is the reference the cheaper models (GW, the interacting asperities) are judged by, and
the most expensive of them. Inputs and results in SI: heights and d in m, forces in N; inside,
gaps in ε and lateral lengths in pixels (`halfspace`, `relax`, `path`).

d is the distance from the map's datum (heights z = 0) to the undeformed elastic surface: the
gap is h = d − z − w. With a free patch the solid under it sinks as a whole (the bulk GW leaves
out); with a periodic map the mean deflection is held at zero, so d is the mean gap less the
mean height.

The error estimate is |Q(a) − Q(2a)|: a second solve over the same separations on the map seen
with twice the pixel (2 × 2 blocks averaged). It bounds the error of Q(a) where the errors
shrink at least in proportion to the pixel: against the axisymmetric boundary integral, one cap
at μ = 1 had F_max errors of 8.5e-4 and 3.3e-4 (in 2πRΔγ) at a = 0.2 and 0.1 √(Rε), and the
estimate of the second 5.3e-4 (`tests/test_whole_surface.py`). Where 2a is too coarse for the
cohesive zone (c above COMPLIANCE_MAX) the estimate grows large (0.022 at a = 0.2, μ = 1): it
then says to refine rather than how good the result is.
"""

import time
from dataclasses import dataclass, field

import numpy as np
from threadpoolctl import threadpool_limits

from fem_asperity.curves.events import parabola_vertex
from fem_asperity.plumbing.checks import in_range, positive
from fem_asperity.plumbing.errors import InputError

from .halfspace import PixelHalfSpace
from .path import follow
from .relax import BLAS_THREADS, LJMap

#: Largest compliance number c = Δγ a/(π E* ε²) without a warning (methods.md §14);
#: test_whole_surface.py pins F̄max at c = 0.032, benchmarks/rough_surfaces.py at 0.099.
COMPLIANCE_MAX = 0.1
#: Largest rms height step between neighbouring pixels (ε), a fraction of the LJ range
#: (methods.md §14). Not pinned by a test.
HEIGHT_STEP_MAX = 0.5
#: A map this much coarser than either bound is refused, not warned about.
REFUSE = 8.0
#: Most pixels of a map: its free grid (four times the map) then holds 1.7e7 doubles per field
#: and the solve takes hours (benchmarks/results/rough_surfaces.md times 256² free).
MAX_PIXELS = 2048**2
#: Fewest pixels along a side: the error estimate halves the map, and a contact zone needs a
#: few pixels on the half map.
MIN_PIXELS = 16
#: The approach starts with the highest point this far (ε) from the solid, or farther by steps of
#: it (methods.md §14); test_whole_surface.py (a soft solid's start).
START_GAP = 4.0
#: Times the start is moved out by START_GAP before the map is refused as too soft.
START_TRIES = 25
#: Separation step (ε) by accuracy: a jump's d is known to the step (or to `jump_resolution`).
STEPS = {"draft": 0.2, "default": 0.1, "fine": 0.05}
#: Most separations of one approach: a map whose load is still tensile after so many steps
#: reports status "incomplete" (pass `depth`).
MAX_SEPARATIONS = 5000


@dataclass(frozen=True)
class Adhesion:
    """The two bodies' physics: effective modulus `e_star` (Pa), work of adhesion `dgamma`
    (J/m²) and the LJ equilibrium spacing `eps` (m)."""

    e_star: float
    dgamma: float
    eps: float

    def __post_init__(self):
        positive("e_star", self.e_star, "Pa")
        positive("dgamma", self.dgamma, "J/m^2")
        positive("eps", self.eps, "m")

    def compliance(self, pixel):
        """c = Δγ a/(π E* ε²) for a pixel of `pixel` m."""
        return self.dgamma * pixel / (np.pi * self.e_star * self.eps**2)

    def force_unit(self, pixel):
        """N per unit of Σp̄ over pixels of `pixel` m: Δγ a²/ε."""
        return self.dgamma * pixel**2 / self.eps


@dataclass(frozen=True)
class Resolution:
    """How well a map resolves the cohesive zone: `compliance` (c), `height_step` (rms
    neighbour step, ε), `needed_pixel` (m: the largest pixel meeting both bounds; for the height
    step assuming steps shrink in proportion to the pixel), `coarse` (a bound is exceeded) and
    `refused` (by more than REFUSE)."""

    compliance: float
    height_step: float
    needed_pixel: float
    coarse: bool
    refused: bool

    def message(self, pixel):
        if not self.coarse:
            return ""
        over = ([f"for the cohesive zone: compliance number {self.compliance:.3g}, limit "
                 f"{COMPLIANCE_MAX}"] if self.compliance > COMPLIANCE_MAX else []) + (
            [f"for the heights: rms height step {self.height_step:.3g} eps, limit "
             f"{HEIGHT_STEP_MAX}"] if self.height_step > HEIGHT_STEP_MAX else [])
        return (f"the pixel {pixel:.3g} m is too coarse ({'; '.join(over)}): use a pixel of at "
                f"most {self.needed_pixel:.3g} m")


def resolution(topography, adhesion):
    """The `Resolution` of `topography` (its heights and pixel, m) for `adhesion`."""
    z = topography.heights / adhesion.eps
    steps = np.concatenate([np.diff(z, axis=0).ravel(), np.diff(z, axis=1).ravel()])
    step = float(np.sqrt(np.mean(steps**2)))
    c = adhesion.compliance(topography.pixel)
    worst = max(c / COMPLIANCE_MAX, step / HEIGHT_STEP_MAX)
    return Resolution(c, step, topography.pixel / max(worst, 1.0), worst > 1.0,
                      worst > REFUSE)


def check_map(topography, adhesion):
    """The map's `Resolution`, after refusing (InputError) a map with fewer than MIN_PIXELS
    along a side or a pixel more than REFUSE times too coarse."""
    if topography.heights.size > MAX_PIXELS:
        raise InputError(f"the map has {topography.heights.size} pixels, more than "
                         f"{MAX_PIXELS} (2048^2): crop it or coarsen it")
    if min(topography.heights.shape) < MIN_PIXELS:
        raise InputError(f"the map must have at least {MIN_PIXELS} pixels along each side "
                         f"to hold a contact and its error estimate; got "
                         f"{topography.heights.shape}")
    check = resolution(topography, adhesion)
    if check.refused:
        raise InputError(check.message(topography.pixel) + f" (more than {REFUSE:g} x over)")
    return check


@dataclass(frozen=True)
class SurfacePath:
    """One direction of travel in SI: `d` (m), `force` (N, < 0 tensile), `contact_area` (m²,
    where the traction is compressive)."""

    d: np.ndarray
    force: np.ndarray
    contact_area: np.ndarray


@dataclass(frozen=True)
class SurfaceJump:
    """A patch that jumped: `kind` "in" or "out", `d` (m, after the jump), `x`, `y` (m, its
    centroid from the map's first pixel centre), `area` (m²), `force_change` (N)."""

    kind: str
    d: float
    x: float
    y: float
    area: float
    force_change: float


@dataclass(frozen=True)
class WholeSurface:
    """The whole surface's approach and retraction (`SurfacePath`s) and `jumps`; `force_max`
    (N, the largest tensile total force on approach, positive), `d_at_max` (m),
    `pressure_max` (Pa, force_max over the map's area); `error_estimate` (the same keys, in
    their units) and `estimated_by`; `status` ("ok", "coarse": the pixel exceeds a bound,
    "unconverged", "incomplete": the approach ended still tensile), `message`; `cost`
    (seconds, Newton steps, Hessian products, of the solve and of its estimate); `model`
    (what produced it)."""

    approach: SurfacePath
    retraction: SurfacePath
    jumps: tuple
    force_max: float
    d_at_max: float
    pressure_max: float
    error_estimate: dict
    estimated_by: str
    status: str
    message: str
    cost: dict
    model: dict = field(default_factory=dict)

    def records(self):
        """JSON-ready dict: the SI block, the paths, the jumps, the estimate and provenance."""
        def path(p):
            return {"d": p.d.tolist(), "force": p.force.tolist(),
                    "contact_area": p.contact_area.tolist()}

        return {
            "si": {"force_max": self.force_max, "pressure_max": self.pressure_max,
                   "d_at_max": self.d_at_max},
            "error_estimate": dict(self.error_estimate),
            "estimated_by": self.estimated_by,
            "status": self.status,
            "message": self.message,
            "jumps": {"in": sum(j.kind == "in" for j in self.jumps),
                      "out": sum(j.kind == "out" for j in self.jumps),
                      "each": [vars(j) for j in self.jumps]},
            "approach": path(self.approach),
            "retraction": path(self.retraction),
            "cost": dict(self.cost),
            "model": dict(self.model),
        }


def solve_whole(topography, adhesion, *, accuracy="default", depth=None, jump_resolution=None,
                estimate=True, progress=None):
    """Approach and retraction of `topography` (`topography.Topography`, SI) on an elastic
    half-space with `adhesion` → `WholeSurface`.

    The approach starts with the highest point START_GAP ε from the solid and steps d by
    STEPS[accuracy] ε until the total force turns compressive (or down to `depth`, m, the
    lowest d, if given); the retraction returns over the same separations. `jump_resolution`
    (m): bisect each jump's d to it. `estimate`: solve again with twice the pixel (2 × 2
    blocks averaged) for the error estimate. `progress(fraction)` is called as the solve goes.
    On glibc, `relax.keep_freed_memory()` called once beforehand (the package's commands do)
    makes large maps faster: their fields are reused instead of faulted in afresh.
    """
    if accuracy not in STEPS:
        raise InputError(f"accuracy must be one of {', '.join(STEPS)}; got {accuracy!r}")
    check = check_map(topography, adhesion)
    eps, step = adhesion.eps, STEPS[accuracy]
    top = float(topography.heights.max()) / eps + START_GAP
    lowest = None if depth is None else in_range("depth", depth, -np.inf, top * eps,
                                                  unit="m") / eps  # finite, below the start
    resolution_eps = None if jump_resolution is None else positive(
        "jump_resolution", jump_resolution, "m") / eps
    share = 0.8 if estimate else 1.0
    main = _solve(topography.heights / eps, topography.pixel, topography.periodic, adhesion,
                  top, step, lowest, resolution_eps,
                  (lambda f: progress(share * f)) if progress else None)
    coarse = None
    if estimate:
        coarse = _solve(coarsened(topography.heights) / eps, 2.0 * topography.pixel,
                        topography.periodic, adhesion, top, step, None, resolution_eps,
                        (lambda f: progress(share + (1 - share) * f)) if progress else None,
                        separations=main["separations"])
    if progress:
        progress(1.0)
    return _result(topography, adhesion, check, main, coarse, accuracy, step)


def coarsened(heights):
    """The map seen with twice the pixel: the mean of each 2 × 2 block (an odd last row or
    column dropped: on an odd map the estimate's map is one pixel smaller, and its estimate
    correspondingly larger)."""
    n1, n2 = (n - n % 2 for n in heights.shape)
    return heights[:n1, :n2].reshape(n1 // 2, 2, n2 // 2, 2).mean(axis=(1, 3))


def _solve(heights, pixel, periodic, adhesion, top, step, lowest, resolution_eps, progress,
           separations=None):
    """Both paths on one map (heights in ε) → dict: approach, retraction (RoughPaths), the
    separations of the approach (ε, planned: without the jumps' landings), seconds, pixel.
    Without `separations`, the approach runs from `top` down by `step` until the force turns
    compressive past its most tensile value (or to `lowest`, ε)."""
    started = time.perf_counter()
    space = PixelHalfSpace.build(heights.shape, compliance=adhesion.compliance(pixel),
                                 periodic=periodic)
    ljmap = LJMap(heights, space)
    with threadpool_limits(BLAS_THREADS, user_api="blas"):  # _far_start relaxes too
        until = None
        if separations is None:
            top = _far_start(ljmap, top)
            separations = top - step * np.arange(MAX_SEPARATIONS)
            if lowest is not None:
                separations = separations[separations >= lowest - 1e-9 * step]
            else:
                def until(forces):
                    return forces[-1] > 0.0 and min(forces) < 0.0
        expected = max(top - float(np.mean(heights)), step) / step  # for the progress only

        def approach_progress(fraction):
            progress(0.5 * min(fraction * separations.size / expected, 0.99))

        approach, y = follow(ljmap, separations, ljmap.rest(),
                             jump_resolution=resolution_eps, until=until,
                             progress=approach_progress if progress else None)
        planned = separations[separations >= approach.d.min() - 1e-9 * step]
        retraction, _ = follow(ljmap, planned[::-1], y, jump_resolution=resolution_eps,
                               progress=(lambda f: progress(0.5 + 0.5 * f)) if progress
                               else None)
    return {"approach": approach, "retraction": retraction, "separations": planned,
            "seconds": time.perf_counter() - started, "pixel": pixel,
            "incomplete": until is not None and not until(list(approach.force))}


def _far_start(ljmap, top):
    """The first separation, raised by START_GAP until the map relaxed there stays more than
    half of it away: a soft solid (μ = 3: a cap jumps in at δ̄o = 4.23) would otherwise start
    in contact, its jump-in never seen."""
    for _ in range(START_TRIES):
        relaxed = ljmap.relax(top, ljmap.rest())
        if relaxed.gap.min() > 0.5 * START_GAP:
            return top
        top += START_GAP
    raise InputError(f"the map jumps into contact from {START_GAP * START_TRIES:g} eps away: "
                     "the solid is too soft for this solver (E* too small beside dgamma/eps)")


def _si_path(path, pixel, adhesion):
    unit = adhesion.force_unit(pixel)
    return SurfacePath(path.d * adhesion.eps, path.force * unit, path.contact * pixel**2)


def most_tensile(d, force):
    """(F_max ≥ 0, d at it, sampling error) of forces `force` (< 0 tensile) sampled at the
    separations `d` (monotone): the vertex of the parabola through the lowest sample and its
    two neighbours where it is interior (never above the sample), else the lowest sample; the
    sampling error is |vertex − sample|."""
    d, force = np.asarray(d, dtype=float), np.asarray(force, dtype=float)
    order = np.argsort(d)
    d, force = d[order], force[order]
    i = int(np.argmin(force))
    d_min, f_min = d[i], force[i]
    if 0 < i < force.size - 1:
        d_min, f_min = parabola_vertex(d[i - 1:i + 2], force[i - 1:i + 2])
        if f_min > force[i]:
            d_min, f_min = d[i], force[i]
    return float(-f_min), float(d_min), float(abs(f_min - force[i]))


def _result(topography, adhesion, check, main, coarse, accuracy, step):
    eps, pixel = adhesion.eps, topography.pixel
    unit, area = adhesion.force_unit(pixel), topography.heights.size * pixel**2
    f_max, d_max, sampling = most_tensile(main["approach"].d, main["approach"].force)
    estimate = {"force_max": sampling * unit, "d_at_max": 0.5 * step * eps}
    estimated_by = "sampling of the separations only"
    if coarse is not None:
        f_c, d_c, _ = most_tensile(coarse["approach"].d, coarse["approach"].force)
        estimate["force_max"] += abs(f_max * unit - f_c * adhesion.force_unit(2 * pixel))
        estimate["d_at_max"] += abs(d_max - d_c) * eps
        estimated_by = ("|Q(a) - Q(2a)|, a second solve with twice the pixel (2 x 2 blocks "
                        "averaged), plus the separations' sampling")
    estimate["pressure_max"] = estimate["force_max"] / area
    jumps = tuple(
        SurfaceJump(j.kind, j.d_after * eps, j.centre[0] * pixel, j.centre[1] * pixel,
                    j.pixels * pixel**2, j.force_change * unit)
        for path in (main["approach"], main["retraction"]) for j in path.jumps)
    converged = main["approach"].converged and main["retraction"].converged
    status, message = "ok", ""
    if check.coarse:
        status, message = "coarse", check.message(pixel)
    if main["incomplete"]:
        status, message = "incomplete", (f"the force is still tensile after "
                                         f"{MAX_SEPARATIONS} separations: pass a depth")
    if not converged:
        status, message = "unconverged", "a separation did not relax to the tolerance"
    runs = [main] + ([coarse] if coarse is not None else [])
    cost = {"seconds": sum(r["seconds"] for r in runs),
            "seconds_estimate": coarse["seconds"] if coarse is not None else 0.0,
            "newton_steps": sum(r[k].steps for r in runs for k in ("approach", "retraction")),
            "hessian_products": sum(r[k].products for r in runs
                                    for k in ("approach", "retraction"))}
    model = {"model": "whole surface", "boundary": "periodic" if topography.periodic else "free",
             "pixels": list(topography.heights.shape), "pixel": pixel, "accuracy": accuracy,
             "step": step * eps, "compliance_number": check.compliance,
             "height_step": check.height_step, "source": topography.source}
    return WholeSurface(_si_path(main["approach"], pixel, adhesion),
                        _si_path(main["retraction"], pixel, adhesion), jumps,
                        float(f_max * unit), float(d_max * eps), float(f_max * unit / area),
                        estimate, estimated_by, status, message, cost, model)
