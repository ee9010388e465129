"""A scene file: what a user keeps beside their data (TOML, every dimensional value with its unit).

    [solid]                      # the half-space (the substrate under a layer)
    E = "3.4 GPa"                # Young's modulus (or E_star, the effective modulus)
    nu = 0.34
    [probe]                      # a sphere (an AFM tip, an asperity)
    radius = "20 nm"
    E = "170 GPa"                # optional, with nu: an elastic sphere (else rigid)
    nu = 0.22
    [adhesion]
    work = "60 mJ/m^2"           # the work of adhesion Δγ
    eps = "0.4 nm"               # the LJ equilibrium spacing ε
    [layer]                      # optional: a bonded layer on the solid (the sphere rigid)
    thickness = "5 nm"
    E = "3.4 GPa"
    nu = 0.34
    [control]                    # optional: a rigid holder (displacement) by default
    spring = "0.5 N/m"           # a cantilever's stiffness
    [want]
    quantity = "pull_off"        # what the user asks for: pull_off, jump_in or jump_out (the
    tolerance = 0.01             # sphere's δ̄o of the jump, the cantilever's z̄ under a spring);
                                 # tolerance: relative

A rough surface (GW: spherical summits of one radius at Gaussian heights) takes the place of the
probe, and its strength F̄max is asked for (no layer or cantilever yet):

    [surface]
    sigma = "2 nm"               # rms roughness σ (McCool's eq. 20; GW's σ as in `gw`)
    radius = "400 nm"            # the summits' radius
    density = "40 /um^2"         # summits per nominal area
    [want]
    quantity = "f_max"

or a measured height map in their place, its GW parameters counted on its summits (as
`python -m gw explicit` counts them: σ_s, R, η; ω = 1), a path relative to the scene file:

    [surface]
    topography = "afm_scan.npy"  # heights in m (.npy), or any SurfaceTopography format
    pixel = "2 nm"               # the pixel of a .npy map

A bad file is refused (`InputError`, one line naming the key) before anything is computed.
"""

import math
import re
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fem_asperity.closed_forms.corrected import MU_JUMP
from fem_asperity.closed_forms.scales import Scales, effective_modulus
from fem_asperity.plumbing.checks import in_range, poisson
from fem_asperity.plumbing.errors import DerjaguinWarning, InputError
from fem_asperity.solids.fe import LAYER_THICKNESS, Solid
from fem_asperity.solver.solve import (
    SOFT_SPRING,
    SPRING_RANGE,
    WHOLE_CURVE_MU_MAX,
    solvable_mu,
)

try:  # Python 3.11+
    import tomllib
except ModuleNotFoundError:  # pragma: no cover (3.10)
    import tomli as tomllib

#: The units a value may carry, per kind, as factors to SI.
UNITS = {
    "pressure": {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9},
    "length": {"m": 1.0, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "nm": 1e-9, "pm": 1e-12,
               "A": 1e-10, "Å": 1e-10},
    "energy per area": {"J/m^2": 1.0, "mJ/m^2": 1e-3, "N/m": 1.0, "mN/m": 1e-3},
    "stiffness": {"N/m": 1.0, "mN/m": 1e-3},
    "per area": {"/m^2": 1.0, "/um^2": 1e12, "/µm^2": 1e12, "/nm^2": 1e18},
}
#: The keys of each section: (kind of value, required). Kinds: a unit kind of UNITS, 'ratio'
#: (a plain number), 'path' (a file), or a tuple of the words allowed.
SECTIONS = {
    "solid": {"E": ("pressure", False), "E_star": ("pressure", False), "nu": ("ratio", False)},
    "probe": {"radius": ("length", True), "E": ("pressure", False), "nu": ("ratio", False)},
    "surface": {"sigma": ("length", False), "radius": ("length", False),
                "density": ("per area", False), "topography": ("path", False),
                "pixel": ("length", False)},
    "adhesion": {"work": ("energy per area", True), "eps": ("length", True)},
    "layer": {"thickness": ("length", True), "E": ("pressure", True), "nu": ("ratio", False)},
    "control": {"spring": ("stiffness", False)},
    "want": {"quantity": (("pull_off", "jump_in", "jump_out", "f_max"), True),
             "tolerance": ("ratio", True)},
}
REQUIRED_SECTIONS = ("solid", "adhesion", "want")
#: What each body may be asked for.
QUANTITIES = {"probe": ("pull_off", "jump_in", "jump_out"), "surface": ("f_max",)}
#: Below the jump-in's onset a sphere on a rigid holder neither jumps in nor out
#: (`closed_forms.corrected.MU_JUMP`; test_advisor.py refuses such a scene).
JUMPS = ("jump_in", "jump_out")
#: The Poisson's ratio where a scene gives none (the package's default, `Solid`).
DEFAULT_NU = 0.3
_VALUE = re.compile(r"^\s*([-+0-9.eE]+)\s*(\S+)\s*$")


@dataclass(frozen=True)
class Scene:
    """A scene in SI and in the package's terms: `scales` (E*, Δγ, ε, R → μ), `solid` (the
    layer in √(Rε) and its E* ratio, or a homogeneous half-space), `spring` (the cantilever's
    k̄ in 2πRΔγ/ε, None: a rigid holder), what is wanted and the relative tolerance; `source`,
    the file's text (copied into any output)."""

    scales: Scales
    solid: Solid
    spring: float | None
    spring_si: float | None
    quantity: str
    tolerance: float
    source: str
    surface: dict | None = None

    @property
    def mu(self):
        return self.scales.mu

    def topography(self):
        """The scene's height map (`gw.explicit.Topography`, a free patch as `gw explicit`
        takes it by default), read again from its file; None where the surface is σ, R, η."""
        if self.surface is None or "topography" not in self.surface:
            return None
        from gw.explicit.topography import read_topography

        return read_topography(self.surface["topography"], pixel=self.surface["pixel"])


def read_scene(path):
    """The `Scene` of the TOML file at `path`."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise InputError(f"scene file {path}: {exc.strerror or exc}") from None
    except UnicodeDecodeError:
        raise InputError(f"scene file {path}: not UTF-8 text (TOML is)") from None
    return parse_scene(text, folder=path.parent)


def parse_scene(text, folder=None):
    """The `Scene` of a scene file's TOML `text`; a file it names is relative to `folder`
    (the scene file's; None: the current folder)."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"scene file: not TOML: {exc}") from None
    values = _checked(data)
    bodies = [b for b in QUANTITIES if b in values]
    if len(bodies) != 1:
        raise InputError("probe, surface: give one of the two (a sphere, or a rough surface)")
    body = bodies[0]
    if values["want"]["quantity"] not in QUANTITIES[body]:
        raise InputError(f"want.quantity: a {body} scene asks for "
                         f"{' or '.join(QUANTITIES[body])}")
    if body == "surface":
        for other in ("layer", "control"):
            if other in values:
                raise InputError(f"{other}: a rough surface scene takes none yet")
        values["surface"] = _surface(values["surface"], folder)
        values["probe"] = {"radius": values["surface"]["radius"]}
    solid, probe, adhesion = values["solid"], values["probe"], values["adhesion"]
    layer, control, want = values.get("layer"), values.get("control", {}), values["want"]
    if ("E" in solid) == ("E_star" in solid):
        raise InputError("solid: give E (with nu) or E_star, one of the two")
    if "E_star" in solid and "nu" in solid:
        raise InputError("solid.nu: E_star already holds the Poisson's ratio; give E with nu")
    if "E_star" in solid and "E" in probe:
        raise InputError("probe.E: E_star is the effective modulus of both bodies; give the "
                         "solid's E and nu with an elastic probe")
    for section in ("solid", "probe", "layer"):
        if "nu" in values.get(section, {}):
            poisson(f"{section}.nu", values[section]["nu"])
    if ("E" in probe) != ("nu" in probe):
        raise InputError("probe: an elastic probe needs both E and nu (omit both: rigid)")
    if layer is not None and "E" in probe:
        raise InputError("probe.E: a layer needs a rigid probe (E* lumps the probe's "
                         "compliance into a homogeneous half-space only)")
    if layer is not None and "E_star" in solid:
        raise InputError("solid.E_star: with a layer give the substrate's E and nu")
    nu = solid.get("nu", DEFAULT_NU)
    E_star = solid.get("E_star") or effective_modulus(E1=solid["E"], nu1=nu, E2=probe.get("E"),
                                                      nu2=probe.get("nu"))
    with warnings.catch_warnings():  # R/ε < 300: the advice measures Derjaguin's effect
        warnings.simplefilter("ignore", DerjaguinWarning)
        try:
            scales = Scales(E_star=E_star, dgamma=adhesion["work"], eps=adhesion["eps"],
                            R=probe["radius"])
        except InputError as exc:
            if "topography" not in values.get("surface", {}):
                raise
            raise InputError(f"surface.topography: the summits' radius {probe['radius']:.3g} m "
                             f"(heights in m?): {exc}") from None
    if body == "surface":
        _check_surface(values["surface"], scales)
    else:
        solvable_mu(scales.mu, "the scene's mu (from solid, probe and adhesion)")
        _check_jumps(want["quantity"], control, layer, scales.mu)
    return Scene(scales=scales, solid=_solid(layer, nu, scales), spring=_spring(control, scales),
                 spring_si=control.get("spring"), quantity=want["quantity"],
                 tolerance=_tolerance(want["tolerance"]), source=text,
                 surface=values.get("surface"))


def _checked(data):
    """{section: {key: value in SI}}, every key known and every value of its kind."""
    unknown = sorted(set(data) - set(SECTIONS))
    if unknown:
        raise InputError(f"{unknown[0]}: unknown section (known: {', '.join(SECTIONS)})")
    missing = [s for s in REQUIRED_SECTIONS if s not in data]
    if missing:
        raise InputError(f"{missing[0]}: missing section")
    out = {}
    for section, entries in data.items():
        if not isinstance(entries, dict):
            raise InputError(f"{section}: must be a [section] of keys")
        known = SECTIONS[section]
        for key in entries:
            if key not in known:
                raise InputError(f"{section}.{key}: unknown key (known: {', '.join(known)})")
        for key, (_, required) in known.items():
            if required and key not in entries:
                raise InputError(f"{section}.{key}: missing")
        out[section] = {key: _value(f"{section}.{key}", value, known[key][0])
                        for key, value in entries.items()}
    return out


def _value(name, value, kind):
    """`value` of `name` in SI: a '<number> <unit>' string of its kind, a plain number for a
    ratio, or one of the allowed words."""
    if isinstance(kind, tuple):
        if value not in kind:
            raise InputError(f"{name}: must be one of {', '.join(kind)}; got {value!r}")
        return value
    if kind == "path":
        if not isinstance(value, str) or not value.strip():
            raise InputError(f"{name}: must be a file name; got {value!r}")
        return value
    if kind == "ratio":
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise InputError(f"{name}: must be a number; got {value!r}")
        try:
            return _finite(name, float(value))
        except OverflowError:
            raise InputError(f"{name}: must be finite; got {value!r}") from None
    units = UNITS[kind]
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        raise InputError(f"{name}: give its unit, e.g. \"{value} {next(iter(units))}\" "
                         f"({kind}: {', '.join(units)})")
    match = _VALUE.match(value) if isinstance(value, str) else None
    if match is None:
        raise InputError(f"{name}: must be a number with its unit, e.g. \"1 "
                         f"{next(iter(units))}\"; got {value!r}")
    number, unit = match.groups()
    if unit not in units:
        raise InputError(f"{name}: {unit!r} is no unit of {kind} ({', '.join(units)})")
    try:
        number = float(number)
    except ValueError:
        raise InputError(f"{name}: {number!r} is not a number") from None
    number = _finite(name, number)
    if number <= 0.0:
        raise InputError(f"{name}: must be > 0; got {value!r}")
    return number * units[unit]


def _finite(name, number):
    if not math.isfinite(number):
        raise InputError(f"{name}: must be finite; got {number!r}")
    return number


def _solid(layer, nu, scales):
    """The `Solid`: homogeneous, or the layer in √(Rε) and its E* against the substrate's."""
    if layer is None:
        return Solid(nu=nu, layer_nu=nu)
    layer_nu = layer.get("nu", nu)
    thickness = layer["thickness"] / scales.length_r
    lo, hi = LAYER_THICKNESS
    if not lo <= thickness <= hi:
        raise InputError(f"layer.thickness: {layer['thickness']:.3g} m is "
                         f"{thickness:.3g} sqrt(R eps); the layered solvers take {lo:g}-{hi:g}")
    ratio = layer["E"] / (1.0 - layer_nu**2) / scales.E_star
    return Solid(nu=nu, layer_thickness=thickness, layer_modulus_ratio=ratio, layer_nu=layer_nu)


def _spring(control, scales):
    """k̄ of the cantilever (N/m → 2πRΔγ/ε), None for a rigid holder."""
    if "spring" not in control:
        return None
    per = scales.eps / scales.force
    lo, hi = (k / per for k in SPRING_RANGE)
    return in_range("control.spring", control["spring"], lo, hi, closed_lo=True, unit="N/m",
                    why=SOFT_SPRING) * per


GW_KEYS = ("sigma", "radius", "density")
#: Summits whose heights spread by less than this share of the map's range are of one height
#: (caps of one height spread by rounding, 1e-40 m): GW needs a spread; test_advisor.py.
SAME_HEIGHT = 1e-9


def _surface(surface, folder):
    """The [surface] section as GW takes it: σ, R, η as given, or counted on the summits of the
    `topography` (σ_s, R, η, ω = 1, as `gw explicit` does), with the spectral moments' σ_s, R, η
    beside (`spectral`) and where the map came from."""
    given = [key for key in GW_KEYS if key in surface]
    if "topography" not in surface:
        missing = [key for key in GW_KEYS if key not in surface]
        if missing:
            raise InputError(f"surface.{missing[0]}: missing (or give a topography)")
        if "pixel" in surface:
            raise InputError("surface.pixel: the pixel of a topography; there is none")
        return surface
    if given:
        raise InputError(f"surface.{given[0]}: give sigma, radius and density or a topography, "
                         "not both")
    from gw.explicit.topography import (
        read_topography,
        spectral_summit_statistics,
        summit_statistics,
    )

    path = (Path(folder or ".") / surface["topography"]).resolve()  # recorded in advice.json
    try:
        topography = read_topography(path, pixel=surface.get("pixel"))
        counted = summit_statistics(topography)
    except InputError as exc:
        raise InputError(f"surface.topography: {exc}") from None
    one_height = counted.sigma_s <= SAME_HEIGHT * float(np.ptp(topography.heights))
    if counted.count < 2 or one_height or not counted.radius > 0:
        raise InputError(f"surface.topography: the map holds {counted.count} summit(s) of one "
                         f"height or of no positive mean radius: GW needs summits of different "
                         "heights (as python -m gw explicit)")
    try:  # optional, as in `gw explicit`: a map dominated by a tilt has none
        found = spectral_summit_statistics(topography)
        spectral = {"sigma": found.sigma_s, "radius": found.radius, "density": found.density}
    except InputError as exc:
        spectral = {"none": str(exc)}
    return {"sigma": counted.sigma_s, "radius": counted.radius, "density": counted.density,
            "omega": 1.0, "topography": str(path), "pixel": topography.pixel,
            "summits": counted.count, "spectral": spectral}


def rough_surface(surface, scales):
    """The `gw.surface.RoughSurface` of a scene's `surface`: ζ = σ/ε, ω given (a topography's)
    or McCool's from σRη (eq. 20)."""
    from gw.surface import RoughSurface

    if "omega" in surface:
        return RoughSurface(zeta=surface["sigma"] / scales.eps, omega=surface["omega"])
    return RoughSurface.from_physical(sigma=surface["sigma"], radius=scales.R,
                                      density=surface["density"], eps=scales.eps)


def _check_jumps(quantity, control, layer, mu):
    """Refuse a jump asked of a homogeneous scene on a rigid holder below the onset (a layer
    softer than the substrate may jump there: its draft solve says), or of a cantilever above
    the largest μ whose whole curve is traced."""
    if quantity not in JUMPS and "spring" not in control:
        return
    if "spring" in control and mu > WHOLE_CURVE_MU_MAX:
        raise InputError(f"control.spring: a cantilever's curve is traced whole, up to mu = "
                         f"{WHOLE_CURVE_MU_MAX:g}; the scene's mu = {mu:.4g}")
    if quantity in JUMPS and "spring" not in control and layer is None and mu < MU_JUMP:
        raise InputError(f"want.quantity: {quantity}: on a rigid holder the sphere jumps only "
                         f"above mu = {MU_JUMP:g} (the scene's mu = {mu:.4g}); give the "
                         "cantilever ([control] spring)")


def _check_surface(surface, scales):
    """The GW surface of `surface` as `gw` takes it (`rough_surface`), refused naming the
    section where it does not."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        try:
            rough_surface(surface, scales)
        except (InputError, ArithmeticError, Warning) as exc:
            raise InputError(f"surface: {exc}") from None


def _tolerance(value):
    if not 0.0 < value < 1.0:
        raise InputError(f"want.tolerance: a relative tolerance in (0, 1), e.g. 0.01; "
                         f"got {value!r}")
    return value
