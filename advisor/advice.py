"""The cheapest model of a scene that meets its tolerance, with the measured size of every
effect a model leaves out (issue 42; so far a sphere's pull-off force, its jump-in and jump-out,
and the F̄max of a GW surface).

Each effect is the relative change of the quantity asked for that one simplification makes, for
this scene: the pull-off force P̄off, or the separation of a jump (the sphere's δ̄o under a rigid
holder, the cantilever's far end z̄ under a spring):

- a closed form (the pull-off: DMT, JKR, Maugis-Dugdale, Wu's eq. 2; the jump-in: the paper's
  eqs. 12-13 and the corrected law) or the shipped table of solved laws instead of a solve: read
  off the table (`gw.law_table`: the retraction's least force, or the δ̄o of its jump, at the
  scene's μ), its own stated error added; under a spring these answer for a rigid holder;
- Derjaguin's parabola instead of the exact sphere, a homogeneous half-space instead of the
  layer: computed, each as the difference of two BEM `draft` solves that differ in that one
  thing, its uncertainty twice the draft's error estimate;
- a rigid holder instead of the cantilever: none on the pull-off force, exactly (the snap-out
  comes where dP̄/dδ̄o = k̄ > 0, after the least force); on a jump, computed as the two others;
- the BEM `draft` instead of `default`: the draft solve's own error estimate of the quantity;
- the BEM `default` instead of `fine`: likewise, the default solve's own estimate, measured
  where no cheaper model meets the tolerance (the default is then solved with it).

For a rough surface's F̄max (GW), the laws are judged against the table and the ground between
summits counted once in closed form; what GW leaves out beyond those, the summits' elastic
interaction, is read off the measured map the package ships (`gw.explicit.measured_map`) at
the summits' own ζ and σRη (ω times the surface's: the map's caps have ω = 1); outside it, it
is unbounded, or with `--run` on a surface given by σ, R, η measured at the scene as the map
is made. On a height map the interacting asperities on its own summits are a
model too, their error (the far field's) read off the same map; the spread of the map's
summit radii, which the map's caps of one R do not have, is computed for the map
(`gw.explicit.radii`) and counted against every model but the whole surface; `run` answers by
the interacting asperities or by the map solved whole as `gw explicit` does. On a surface given
by σ, R, η, the surface solved whole is its statistics made explicit as the map's surfaces are
(`MadeExplicit`).

A model's error is the sum of the sizes and uncertainties of the effects it leaves out, each
measured alone against its own reference: a first-order estimate, not a bound on effects that
interact. Where an effect cannot be measured (outside the table's μ) the models that need it
are not chosen, and where no cheaper model is known to meet the tolerance the advice is the
BEM `default` solve of the whole scene, by its own estimate, or where even that misses the
safe one, the `fine` solve; it says so.
"""

import time
from dataclasses import dataclass, field, replace

import numpy as np

from fem_asperity.closed_forms.corrected import CORRECTED_LAWS, MU_JUMP
from fem_asperity.closed_forms.laws import PAPER_LAWS, wu_pull_off
from fem_asperity.closed_forms.reference import maugis_dugdale_pull_off
from fem_asperity.plumbing.errors import InputError
from fem_asperity.solids.fe import Solid
from gw.law_table import shipped_table

#: δ̄o samples [ε] on which the table's retraction is searched for its least force: from deep
#: in contact out beyond every jump-out the table holds (47 at μ = 28.7, `gw.law_table`).
PULL_OFF_SEARCH = np.linspace(-5.0, 120.0, 250001)
#: What a sphere scene may ask for: the key of its value in a solved curve's events under a
#: rigid holder, and under a spring (`CurveResult.values`).
PROBE_QUANTITIES = {"pull_off": ("p_off", "p_off"), "jump_in": ("delta_jump_in", "z_jump_in"),
                    "jump_out": ("delta_jump_out", "z_jump_out")}


def _paper_jump_in(mu):
    """The paper's jump-in δ̄o [ε] (eq. 13: contact at δ̄oc), None where it has none."""
    events = PAPER_LAWS.events(mu)
    return float(events.delta_oc) if bool(events.jump_in) else None


def _corrected_jump_in(mu):
    """The corrected law's jump-in δ̄o [ε] (δ̄J, from the onset MU_JUMP on), else None."""
    return CORRECTED_LAWS.at(mu).delta_jump if mu >= MU_JUMP else None


#: The closed forms of each quantity under a rigid holder: name → value(μ) (P̄off [2πRΔγ], a
#: jump's δ̄o [ε]; None where the form has no such jump). No closed form gives the jump-out's.
CLOSED_FORMS = {
    "pull_off": {
        "DMT": lambda mu: -1.0,
        "JKR": lambda mu: -0.75,
        "Maugis-Dugdale": lambda mu: float(maugis_dugdale_pull_off(mu=mu).force),
        "Wu (eq. 2; the paper's and the corrected law's)": lambda mu: float(
            wu_pull_off(mu, PAPER_LAWS.c_off)),
    },
    "jump_in": {"the paper's (eqs. 12-13)": _paper_jump_in,
                "the corrected law's": _corrected_jump_in},
    "jump_out": {},
}


@dataclass(frozen=True)
class Effect:
    """What one simplification does to the quantity asked for, for this scene: its relative
    `size` (None: not bounded here, `note` says why), its uncertainty and how it was obtained."""

    name: str
    size: float | None
    uncertainty: float | None
    how: str
    note: str = ""


@dataclass(frozen=True)
class Model:
    """A way to answer: its value of the quantity asked for (P̄off [2πRΔγ], a jump's δ̄o or z̄
    [ε], or F̄max), the
    effects it leaves out and their summed `error` (relative; None if one is not bounded), and
    its cost in seconds on this machine (measured here where it was run, else None)."""

    name: str
    value: float | None
    leaves_out: tuple[str, ...]
    error: float | None
    cost_s: float | None


@dataclass(frozen=True)
class Advice:
    """The scene, every effect, every model (cheapest first), the one chosen and why, and the
    solves of the whole scene the advice made, by accuracy (`CurveResult`s: the draft the
    effects were measured with, and the default where it was measured as the safe model), and
    on a GW surface the draws of its statistics made explicit where it measured the summits'
    interaction on them (`explicit`, `gw.explicit.measured_map.explicit_draws`)."""

    scene: object
    effects: tuple[Effect, ...]
    models: tuple[Model, ...]
    choice: str
    message: str
    solves: dict = field(default_factory=dict)
    explicit: tuple = ()

    def records(self):
        """A JSON-ready dict: the scene in SI, the effects, the models (the value
        dimensionless and in SI: P̄off in N, a jump's separation in m, F̄max as the tension per
        nominal area in Pa) and the choice."""
        s = self.scene.scales
        to_si, unit = si_unit(self.scene)
        return {
            "scene": {"mu": s.mu, "R_over_eps": s.R / s.eps, "E_star_Pa": s.E_star,
                      "dgamma_J_per_m2": s.dgamma, "eps_m": s.eps, "R_m": s.R,
                      "spring_N_per_m": self.scene.spring_si,
                      "layer": _layer_record(self.scene.solid), "surface": self.scene.surface,
                      "quantity": self.scene.quantity, "tolerance": self.scene.tolerance},
            "effects": [vars(e) for e in self.effects],
            "models": [{**vars(m), "value_si": None if m.value is None else m.value * to_si,
                        "unit": unit} for m in self.models],
            "choice": self.choice, "message": self.message,
        }


def si_unit(scene):
    """(factor to SI, unit) of the quantity `scene` asks for."""
    s, surface = scene.scales, scene.surface
    if surface is not None:
        return s.force * surface["density"], "Pa"
    return (s.force, "N") if scene.quantity == "pull_off" else (s.length_z, "m")


def quantity_key(scene):
    """The key of a sphere scene's quantity in a solved curve (`PROBE_QUANTITIES`)."""
    rigid, spring = PROBE_QUANTITIES[scene.quantity]
    return rigid if scene.spring is None else spring


def value_of(result, key):
    """The value of `key` in the solved curve `result` (its events and spring jumps), None
    where it has none."""
    return result.values().get(key)


def _layer_record(solid):
    if solid.layer_thickness is None:
        return None
    return {"thickness_sqrt_R_eps": solid.layer_thickness,
            "modulus_ratio": solid.layer_modulus_ratio}


def advise(scene, *, solve=None, measure=False, say=None):
    """The `Advice` for `scene` (a `scene.Scene`). solve: the curve solver (`solve_curve`
    by default; tests pass a stand-in). measure: on a GW surface given by σ, R, η outside the
    measured map, measure the summits' interaction at the scene itself (`_measured_here`:
    seconds to minutes) instead of leaving it unbounded; `say(message)` is told first."""
    if scene.surface is not None:
        return _advise_surface(scene, measure, say)
    if solve is None:
        from fem_asperity.solver.solve import solve_curve as solve
    mu, forms = scene.mu, CLOSED_FORMS[scene.quantity]
    effects, models = [], []
    table = _table_value(mu, scene.quantity)
    solved = _solved_effects(scene, solve)
    effects += solved["effects"]
    carried = tuple(e.name for e in solved["effects"] if e.name != DRAFT)
    if table is None:
        note = (f"mu = {mu:.4g} is outside the table of solved laws' "
                f"{shipped_table().mu_range[0]:g}-{shipped_table().mu_range[1]:g}")
        effects.append(Effect(TABLE, None, None, "table lookup", note))
    elif table[0] is None:
        effects.append(Effect(TABLE, None, None, "table lookup",
                              f"the table's law has no {scene.quantity} at mu = {mu:.4g}"))
    else:
        value_table, table_error = table
        effects.append(Effect(TABLE, table_error, None, "the table's stated error of "
                              + TABLE_VALUE[scene.quantity] + ", relative to it",
                              "" if table_error is not None else "the table states none here"))
        for name, law in forms.items():
            value_law = law(mu)
            effects.append(Effect(_closed(name), None, None, "table lookup",
                                  f"the form has no {scene.quantity} at mu = {mu:.4g}")
                           if value_law is None else
                           Effect(_closed(name), abs(value_law / value_table - 1.0),
                                  table_error, "table lookup (against the solved value)"))
    size = {e.name: _with_uncertainty(e) for e in effects}
    for name, law in forms.items():
        models.append(_model(f"{name} closed form", law(mu), (_closed(name), TABLE) + carried,
                             size, 0.0))
    models.append(_model("table of solved laws", table[0] if table else None,
                         (TABLE,) + carried, size, None))
    draft, default, fine = SOLVES
    models.append(_model(draft, solved["value"], (DRAFT,), size, solved["cost_s"]))
    solves = {"draft": solved["result"]}
    if not any(m.error is not None and m.error <= scene.tolerance for m in models):
        # the safe model measured: the default solve with its own estimate
        result, effect, cost = _measured_solve(scene, solve, "default", DEFAULT)
        effects.append(effect)
        solves["default"] = result
        models.append(_model(default, value_of(result, quantity_key(scene)), (DEFAULT,),
                             {DEFAULT: _with_uncertainty(effect)}, cost))
        models.append(Model(fine, None, (), None, None))
        return _chosen(scene, effects, models, "no cheaper model is known to meet the "
                       "tolerance, nor the BEM default solve by its own estimate: the safe "
                       "model, the BEM fine solve of the whole scene (python -m fem_asperity "
                       "curve ... --method bem --accuracy fine)", solves)
    models.append(Model(default, None, (), None, None))
    return _chosen(scene, effects, models, "no cheaper model is known to meet the tolerance: "
                   "the safe model, the BEM default solve of the whole scene (python -m "
                   "fem_asperity curve ... --method bem)", solves)


def _chosen(scene, effects, models, otherwise, solves=None, explicit=()):
    """The `Advice`: the cheapest of `models` whose error meets the scene's tolerance, else the
    last (the safe one), said why in `otherwise`."""
    meets = [m for m in models if m.error is not None and m.error <= scene.tolerance]
    solves = solves or {}
    if not meets:
        return Advice(scene, tuple(effects), tuple(models), models[-1].name, otherwise, solves,
                      explicit)
    best = meets[0]
    return Advice(scene, tuple(effects), tuple(models), best.name,
                  f"{best.name}: the effects it leaves out sum to {best.error:.2g} <= the "
                  f"tolerance {scene.tolerance:g} (each measured alone: a first-order estimate)",
                  solves, explicit)


#: The models that solve the whole scene, by name: the accuracy preset each runs (`run`).
SOLVES = {"BEM draft, the whole scene": "draft", "BEM default, the whole scene": "default",
          "BEM fine, the whole scene": "fine"}
#: A map reading whose caps' summed F̄max is more than this times GW's integral says that its
#: caps stand for a large surface only roughly (`_sample_clause`). Not pinned by a test.
SAMPLE_ROUGHLY = 1.25
#: Effect names.
TABLE, DRAFT = "the table of solved laws instead of a solve", "BEM draft instead of default"
DEFAULT = "BEM default instead of fine"
DERJAGUIN = "Derjaguin's parabola instead of the exact sphere"
HOMOGENEOUS = "a homogeneous half-space instead of the layer"
RIGID = "a rigid holder instead of the cantilever"


def _with_uncertainty(effect):
    """An effect's size with its uncertainty added (None where it is not measured)."""
    if effect.size is None:
        return None
    return effect.size + (effect.uncertainty or 0.0)


def _closed(name):
    return f"{name} closed form instead of a solve"


def _model(name, value, leaves_out, size, cost):
    sizes = [size.get(e) for e in leaves_out]
    error = None if any(s is None for s in sizes) else float(sum(sizes))
    return Model(name, value, leaves_out, error, cost)


#: What the table's error is stated of, per quantity.
TABLE_VALUE = {"pull_off": "the retraction's force", "jump_in": "the jump-in's δ̄o",
               "jump_out": "the jump-out's δ̄o"}


def _table_value(mu, quantity):
    """(value, its relative error) of the shipped table at `mu` under a rigid holder: P̄off,
    the least force of its retraction, or the δ̄o of its jump in or out (value None where its
    law has no such jump); None outside the table."""
    table = shipped_table()
    lo, hi = table.mu_range
    if not lo <= mu <= hi:
        return None
    law = table.law(mu, path="approach" if quantity == "jump_in" else "retraction")
    if quantity == "pull_off":
        p_off = float(np.min(law.force(PULL_OFF_SEARCH)))
        return p_off, law.error["force"] / abs(p_off)
    if not law.jumps:
        return None, None
    delta = float(law.landmarks[1])  # the jump's δ̄o (`gw.law_table.TableLaw`)
    error = law.error.get("jump")
    return delta, None if error is None else error / abs(delta)


def _whole_scene(scene):
    """The solver's options for the whole scene (its solid, sphere and cantilever)."""
    return dict(solid=scene.solid, radius_ratio=scene.scales.R / scene.scales.eps,
                spring_constant=scene.spring)


def _measured_solve(scene, solve, accuracy, name):
    """(result, effect `name`, seconds): the whole scene solved by BEM at `accuracy` with its
    error estimate, the effect that estimate relative to the value. `InputError` where the
    scene has no value of its quantity (a jump it does not make)."""
    key = quantity_key(scene)
    start = time.perf_counter()
    result = solve(scene.mu, method="bem", accuracy=accuracy, error_estimate=True,
                   **_whole_scene(scene))
    cost = time.perf_counter() - start
    value = value_of(result, key)
    if value is None:
        raise InputError(f"want.quantity: the scene makes no {scene.quantity} (its BEM "
                         f"{accuracy} solve, mu = {scene.mu:.4g}: {result.message})")
    estimate = (result.error_estimate or {}).get(key)
    return result, Effect(name, None if estimate is None else estimate / abs(value), None,
                          f"the {accuracy} solve's own error estimate",
                          "" if estimate is not None else f"no estimate: {result.message}"), cost


def _solved_effects(scene, solve):
    """The whole scene at BEM `draft` with its estimate, and one draft solve per simplification
    that applies: {'value', 'cost_s', 'effects', 'result'}. `InputError` where the whole scene
    has no value of its quantity (a jump it does not make)."""
    whole = _whole_scene(scene)
    key = quantity_key(scene)
    full, effect, cost = _measured_solve(scene, solve, "draft", DRAFT)
    value = value_of(full, key)
    twice = None if effect.size is None else 2.0 * effect.size
    effects = [effect]
    variants = [(DERJAGUIN, {"radius_ratio": None}, key)]
    if scene.spring is not None and scene.quantity == "pull_off":
        effects.append(Effect(RIGID, 0.0, None, "exact for the pull-off force: the snap-out "
                              "comes where dP/d(delta_o) = k > 0, after the least force"))
    elif scene.spring is not None:  # the rigid holder's δ̄o of the jump against the z̄
        variants.append((RIGID, {"spring_constant": None}, PROBE_QUANTITIES[scene.quantity][0]))
    if scene.solid.layer_thickness is not None:
        variants.append((HOMOGENEOUS, {"solid": Solid(nu=scene.solid.nu,
                                                      layer_nu=scene.solid.nu)}, key))
    for name, change, other_key in variants:
        other = value_of(solve(scene.mu, method="bem", accuracy="draft", error_estimate=False,
                               **(whole | change)), other_key)
        effects.append(Effect(name, None, None, "computed for this scene: two BEM draft solves",
                              f"without it the scene makes no {scene.quantity}")
                       if other is None else
                       Effect(name, abs(other / value - 1.0), twice,
                              "computed for this scene: two BEM draft solves"))
    return {"value": value, "cost_s": cost, "effects": effects, "result": full}


#: The rough surface's effects on F̄max and its safe model.
PAPER_LAW, CORRECTED_LAW = ("the paper's law instead of the solved law",
                            "the corrected law instead of the solved law")
GROUND = "GW's ground between summits counted more than once"
INTERACTION = "summits that do not feel each other (GW) instead of the surface solved whole"
FAR_FIELD = ("summits that feel each other through the far field only (interacting asperities) "
             "instead of the surface solved whole")
INTERACTING = ("interacting asperities on the map's summits (python -m gw explicit --model "
               "interacting)")
WHOLE = "the surface solved whole (python -m gw explicit on a height map)"
STATISTICS = "the map's summits counted (σ_s, R, η) instead of its spectral moments"
RADII = "every summit a cap of the mean radius instead of its own"


def _advise_surface(scene, measure=False, say=None):
    """F̄max of a GW surface: each law against the table of solved laws, the ground between
    summits counted once in closed form (`gw.shared_ground`); what GW leaves out beyond that
    (the summits' elastic interaction, the ground lifted between them) read off the measured
    map (`_read_off_map`) at the summits' ζ and σRη (ω times the surface's, as GW's integral
    takes them), unbounded outside it unless `measure` (`_measured_here`). On a height map of
    at most MAX_SUMMITS
    summits, the interacting asperities on them too, their error read off the same map (its
    caps were of one R): the spread of the map's summit radii is computed for the map
    (`_radii_effect`) and counted against both."""
    from gw.explicit.answer import MAX_SUMMITS
    from gw.integrate import strength
    from gw.laws import CorrectedLaw, PaperLaw

    from .scene import rough_surface

    s, surface = scene.scales, scene.surface
    sigma_r_eta = surface["sigma"] * s.R * surface["density"]
    rough = rough_surface(surface, s)
    table = shipped_table()
    lo, hi = table.mu_range
    summits = summits_point(scene)
    effects, explicit = [_read_off_map(INTERACTION, *summits)], ()
    if effects[0].size is None and "topography" not in surface:
        if measure:
            effects[0], explicit = _measured_here(effects[0], *summits, say)
        else:
            effects[0] = replace(effects[0], note=f"{effects[0].note}; python -m advisor "
                                 "--run measures it at the scene")
    interacting = "topography" in surface and surface["summits"] <= MAX_SUMMITS
    if interacting:
        effects.append(_read_off_map(FAR_FIELD, *summits))
    cost = {}

    def timed(name, law, **options):  # F̄max, its wall time kept as the model's cost
        start = time.perf_counter()
        found = strength(law, rough, **options).f_max
        cost[name] = time.perf_counter() - start
        return found

    f_paper = timed("paper", PaperLaw(scene.mu))
    f_corrected = timed("corrected", CorrectedLaw(scene.mu))
    if lo <= scene.mu <= hi:
        law = table.law(scene.mu)
        f_table = timed("table", law)
        f_once = timed("once", law, sigma_r_eta=sigma_r_eta)
        effects += [
            Effect(TABLE, law.f_max_error, None, "the table's measured F̄max error"),
            Effect(PAPER_LAW, abs(f_paper / f_table - 1.0), law.f_max_error,
                   "GW integrals with both laws"),
            Effect(CORRECTED_LAW, abs(f_corrected / f_table - 1.0), law.f_max_error,
                   "GW integrals with both laws"),
            Effect(GROUND, abs(f_table / f_once - 1.0), None,
                   f"closed form for summits at random places (sigma R eta = "
                   f"{sigma_r_eta:.3g})")]
    else:
        f_table = f_once = None
        effects += [Effect(name, None, None, "table lookup", f"mu = {scene.mu:.4g} is outside "
                           f"the table of solved laws' {lo:g}-{hi:g}")
                    for name in (TABLE, PAPER_LAW, CORRECTED_LAW, GROUND)]
    measured = ()
    if "spectral" in surface and "none" not in surface["spectral"]:  # (none: `scene._surface`)
        effects.append(_statistics_effect(scene, f_table, table))
        measured = (STATISTICS,)
    if "topography" in surface:
        effects.append(_radii_effect(scene))
        measured += (RADII,)
    size = {e.name: _with_uncertainty(e) for e in effects}
    models = (
        _model("GW, the paper's law", f_paper, (PAPER_LAW, TABLE, GROUND, INTERACTION)
               + measured, size, cost["paper"]),
        _model("GW, the corrected law", f_corrected, (CORRECTED_LAW, TABLE, GROUND,
                                                      INTERACTION) + measured, size,
               cost["corrected"]),
        _model("GW, the table of solved laws", f_table, (TABLE, GROUND, INTERACTION) + measured,
               size, cost.get("table")),
        _model(GW_ONCE, f_once, (TABLE, INTERACTION)
               + measured, size, cost.get("once")))
    if interacting:  # each summit at its own place and height, all of the counted mean R
        models += (_model(INTERACTING, None, (TABLE, FAR_FIELD, RADII), size, None),)
    models += (Model(WHOLE, None, (), None, None),)
    return _chosen(scene, effects, models, "no GW model is known to meet the tolerance (the "
                   "effects each leaves out sum to more, or one is not bounded here): the safe "
                   f"model is {WHOLE}", explicit=explicit)


def summits_point(scene):
    """(μ, ζ, σRη) of a GW scene's summits, where the measured map is read and the statistics
    are made explicit: the map's surfaces are caps of ω = 1, so the point is the summits' (σ_s
    = ωσ), not σ's."""
    from .scene import rough_surface

    s, surface = scene.scales, scene.surface
    rough = rough_surface(surface, s)
    sigma_r_eta = surface["sigma"] * s.R * surface["density"]
    return scene.mu, rough.omega * rough.zeta, rough.omega * sigma_r_eta


def _statistics_effect(scene, f_counted, table):
    """How far GW's strength moves where the map's spectral moments give σ_s, R, η instead of
    its counted summits: the tension F̄max·2πRΔγη [Pa] both ways, GW with the table's law (at
    each R's own μ); unbounded outside the table."""
    from gw.integrate import strength
    from gw.surface import RoughSurface

    s, surface = scene.scales, scene.surface
    spectral = surface["spectral"]
    mu = s.mu * (spectral["radius"] / s.R) ** (1.0 / 3.0)  # μ³ ∝ R
    lo, hi = table.mu_range
    if f_counted is None or not lo <= mu <= hi:
        return Effect(STATISTICS, None, None, "GW with the table's law both ways",
                      f"mu = {scene.mu:.4g} or {mu:.4g} is outside the table of solved laws")
    f_spectral = strength(table.law(mu), RoughSurface(zeta=spectral["sigma"] / s.eps,
                                                      omega=surface["omega"])).f_max
    tension = f_spectral * spectral["radius"] * spectral["density"]
    counted = f_counted * s.R * surface["density"]
    return Effect(STATISTICS, abs(tension / counted - 1.0), None,
                  "computed for this map: GW with the table's law on both statistics "
                  f"({surface['summits']} summits counted at the pixel {surface['pixel']:.3g} m)")


def _radii_effect(scene):
    """How far the map's uncoupled summits' F_max moves where each is a cap of its own radius
    instead of the mean one (`gw.explicit.radii`), on the separations `gw explicit` samples;
    unbounded where a summit's own μ is outside the table."""
    from gw.explicit.answer import separations
    from gw.explicit.radii import own_radii

    topography, adhesion = scene.topography(), _adhesion(scene)
    spread = own_radii(topography, adhesion, separations(topography, adhesion, "default"),
                       radius=scene.scales.R, mu=scene.mu)
    how = (f"computed for this map: its {spread.summits} summits summed on the table's laws, "
           f"each at its own radius ({spread.radii[0]:.3g}-{spread.radii[1]:.3g} m, mu "
           f"{spread.mu[0]:.3g}-{spread.mu[1]:.3g}) and all at the mean (for the interacting "
           "asperities, whose ground counted once sees the summits' shapes, an upper estimate)")
    return Effect(RADII, spread.size, spread.uncertainty, how, spread.note)


#: What each effect read off the measured map is measured as: (the map's model, what it is).
MAP_MODELS = {
    INTERACTION: ("gw_cells", "GW's sum over the summits, the ground counted once (on the map, "
                  "rigid; the closed form's ground for summits at random places stands for "
                  "that map's own: within 1 % on explicit maps of 600 caps)"),
    FAR_FIELD: ("interacting", "the interacting asperities (each summit's law, the others' far "
                "field P/(pi E* r), the ground counted once)"),
}


def _read_off_map(name, mu, zeta, sigma_r_eta):
    """The effect `name` of MAP_MODELS read off the measured map shipped with the package
    (`gw.explicit.measured_map`): the largest error of its model against the surface solved
    whole over the surfaces around the scene; unbounded outside the map."""
    from gw.explicit.measured_map import AXES, measured_error, shipped_map

    model, what = MAP_MODELS[name]
    shipped = shipped_map()
    found = measured_error(model, mu=mu, zeta=zeta, sigma_r_eta=sigma_r_eta, record=shipped)
    if found is not None and found.missing:
        return Effect(name, None, None, "not measured for this scene",
                      "the measured map has no surface at " + "; ".join(
                          ", ".join(f"{k} {v:g}" for k, v in zip(AXES + ("seed",), c))
                          for c in found.missing) + ", around the scene (docs/rough_explicit.md)")
    if found is not None and found.size is None:
        return Effect(name, None, None, "not measured for this scene",
                      f"a surface of the measured map around the scene has no answer of {what} "
                      "(docs/rough_explicit.md)")
    if found is None:
        box = "no map is shipped" if shipped is None else "outside the measured map's " + (
            ", ".join(f"{k} {min(v):g}-{max(v):g}" for k, v in shipped["axes"].items()))
        return Effect(name, None, None, "not measured for this scene",
                      f"mu = {mu:.3g}, the summits' zeta = {zeta:.3g} and sigma R eta = "
                      f"{sigma_r_eta:.3g} are "
                      f"{box} (docs/rough_explicit.md); python -m gw explicit answers for a "
                      "height map")
    around = "; ".join(f"{k} " + " and ".join(f"{v:g}" for v in found.around[k]) for k in AXES)
    return Effect(name, found.size, found.uncertainty,
                  f"read from the measured map shipped with the package: the largest error of "
                  f"{what} against the surface solved whole, over the {found.surfaces} surfaces "
                  f"around the scene's summits (mu {mu:.3g}, zeta {zeta:.3g}, sigma R eta "
                  f"{sigma_r_eta:.3g}: {around})" + _sample_clause(found.sample))


def _sample_clause(sample):
    """What a reading's `sample` (`measured_map.MeasuredError.sample`) says, where its caps do
    not stand for a large surface (their summed F̄max beyond SAMPLE_ROUGHLY of GW's)."""
    if sample is None or sample <= SAMPLE_ROUGHLY:
        return ""
    return (f"; there the map's 16 caps stand for a large surface only roughly: their F_max per "
            f"summit, summed without interaction, is up to {sample:.3g} times GW's integral "
            "(their few highest set it); benchmarks/results/map_sample.md measures whether "
            "the error carries over")


def _measured_here(unbounded, mu, zeta, sigma_r_eta, say=None):
    """(effect, draws): the effect `unbounded` (one of MAP_MODELS, outside the map) measured at
    the scene's own point as the map is made, on the draws of GW's surface made explicit there
    (`gw.explicit.measured_map.explicit_draws`, kept for `run`); where that surface cannot be
    made or the model has no answer on it, the effect as it was, its note saying why."""
    from gw.explicit.measured_map import (
        MAP_SEEDS,
        MAP_SUMMITS,
        explicit_draws,
        measurable,
        measured_from,
    )

    model, what = MAP_MODELS[unbounded.name]
    try:
        side = measurable(mu, zeta, sigma_r_eta)
    except InputError as exc:
        return replace(unbounded, note=f"{unbounded.note}; not measured at the scene either: "
                       f"{exc}"), ()
    if say:
        say(f"measuring {unbounded.name} at the scene itself (mu = {mu:.3g}, the summits' zeta "
            f"= {zeta:.3g} and sigma R eta = {sigma_r_eta:.3g}, outside the measured map): "
            f"{len(MAP_SEEDS)} GW surfaces made explicit, {MAP_SUMMITS} caps on {side} x {side} "
            "pixels each, solved whole (the map's own times: docs/rough_explicit_report.md) ...")
    draws = explicit_draws(mu, zeta, sigma_r_eta)
    found = measured_from(model, draws)
    how = (f"computed for this scene: the largest error of {what} against the surface solved "
           f"whole, on {found.surfaces} GW surfaces made explicit at its mu, zeta, sigma R eta "
           f"({MAP_SUMMITS} caps each, as the measured map's)" + _sample_clause(found.sample))
    if found.size is None:
        return Effect(unbounded.name, None, None, how, f"{what} found no equilibrium before "
                      "the total force turned compressive on one of them"), draws
    return Effect(unbounded.name, found.size, found.uncertainty, how), draws


#: The GW model whose F̄max the surface solved whole on a scene's statistics corrects.
GW_ONCE = "GW, the table, the ground counted once"


@dataclass(frozen=True)
class MadeExplicit:
    """The surface solved whole, for a GW scene given by σ, R, η: GW's integral with the table's
    law and the ground counted once (`gw`, F̄max per summit of the scene's statistics) times
    the ratio of the whole surface's F̄max to that of the sum over the same caps with the ground
    counted once (the interaction, the effect that model leaves out), measured on the `draws`
    of its statistics made explicit (`gw.explicit.compare.Comparison`s of MAP_SEEDS surfaces of
    MAP_SUMMITS caps at the summits' ζ and σRη, `summits_point`, solved whole at the map's
    accuracy), as the measured map measures it. The draws' own F̄max is not the answer: on 16
    caps it rests on the few highest, far above a large surface's where ζ is large (`sample`).
    `error`: relative, the table's stated error (`table_error`) plus the largest whole
    surface's own relative estimate plus the spread of the ratio between the draws (the
    sample's share; with two draws about twice the standard error of their mean, not a bound).
    `coarse`: the whole-surface solver's resolution message for each draw it flags
    (`gw.explicit.whole.resolution`)."""

    draws: tuple
    gw: float
    table_error: float

    @property
    def ratios(self):
        """Each draw's F̄max of the surface solved whole over that of the sum on its caps with
        the ground counted once."""
        return [d.models["whole"].f_max / d.models["gw_cells"].f_max for d in self.draws]

    @property
    def f_max(self):
        return float(self.gw * np.mean(self.ratios))

    @property
    def error(self):
        own = max(d.estimate / d.models["whole"].f_max for d in self.draws)
        ratios = self.ratios
        return float(self.table_error + own + (max(ratios) - min(ratios)) / np.mean(ratios))

    @property
    def sample(self):
        """The draws' F̄max of the sum over their caps against GW's integral on the same
        statistics (both per summit, the table's law): near 1 where 16 caps stand for a large
        surface; far above where the few highest set their strength (large ζ)."""
        return float(np.mean([d.models["gw_sum"].f_max for d in self.draws])
                     / np.mean([d.models["gw_solved"].f_max for d in self.draws]))

    @property
    def coarse(self):
        from gw.explicit.whole import resolution

        found = []
        for draw in self.draws:
            topography = draw.scene.surface()[0]
            check = resolution(topography, draw.scene.adhesion)
            if check.coarse:
                found.append(f"draw {draw.scene.seed}: {check.message(topography.pixel)}")
        return found


def run(advice, *, solve=None, progress=None):
    """The chosen model run: the `CurveResult` of its solve (the draft the advice already has,
    or the BEM `default` solve of the whole scene with its error estimate), the `gw.explicit`
    `Answer` of the interacting asperities or the surface solved whole on a scene's height map
    (`default`, a free patch, as `gw explicit` solves it; `progress(fraction)` as the whole
    surface goes), the `MadeExplicit` surface of a GW scene given by σ, R, η (on the draws the
    advice measured at the summits' point, else solved now; `progress` after each), or None
    for a closed form or the table (their value is the model's). `InputError` where it cannot
    be run (`check_runnable`)."""
    scene = advice.scene
    check_runnable(advice)
    if advice.choice == WHOLE and "topography" not in scene.surface:
        from gw.explicit.measured_map import explicit_draws

        draws = advice.explicit or explicit_draws(*summits_point(scene), progress)
        table = next(e for e in advice.effects if e.name == TABLE)
        return MadeExplicit(draws, _value(advice, GW_ONCE), table.size)
    if advice.choice in SURFACE_MODELS:
        return _on_the_map(scene, SURFACE_MODELS[advice.choice], progress)
    accuracy = SOLVES.get(advice.choice)
    if accuracy is None:
        return None
    if accuracy in advice.solves:
        return advice.solves[accuracy]
    if solve is None:
        from fem_asperity.solver.solve import solve_curve as solve
    return solve(scene.mu, method="bem", accuracy=accuracy, error_estimate=True,
                 **_whole_scene(scene))


def check_runnable(advice):
    """`InputError`, naming the scene's key, where the model chosen cannot be run: on a GW
    surface given by σ, R, η, the interacting asperities (no summits to place) or statistics
    too large to make explicit (`measured_map.measurable`); on a height map, one `gw explicit`
    refuses (too large, too small, too coarse for the cohesive zone)."""
    scene = advice.scene
    if advice.choice not in SURFACE_MODELS:
        return
    if "topography" not in scene.surface:
        from gw.explicit.measured_map import measurable

        try:
            if advice.choice != WHOLE:
                raise InputError("it needs the summits' places")
            if _value(advice, GW_ONCE) is None:
                raise InputError("it corrects GW with the table's law, which has no value here")
            measurable(*summits_point(scene))
        except InputError as exc:
            raise InputError(f"surface.sigma, surface.density: --run: the model chosen, "
                             f"{advice.choice}, cannot be run on the scene's statistics made "
                             f"explicit ({exc}): give [surface] topography, or run python -m gw "
                             f"explicit --topography MAP ...; {_why_not_gw(advice)}") from None
        return
    from gw.explicit.whole import check_map

    try:
        check_map(scene.topography(), _adhesion(scene))
    except InputError as exc:
        raise InputError(f"surface.topography: {exc}") from None


def _value(advice, name):
    """The value of the advice's model `name`."""
    return next(m.value for m in advice.models if m.name == name)


def _why_not_gw(advice):
    """Why no GW model was chosen, in a line: the closest one's summed error against the
    tolerance, with its largest effect, or the effects not bounded."""
    bounded = [m for m in advice.models if m.name.startswith("GW") and m.error is not None]
    if not bounded:
        return "not bounded: " + "; ".join(f"{e.name} ({e.note})" for e in advice.effects
                                           if e.size is None)
    best = min(bounded, key=lambda m: m.error)
    largest = max((e for e in advice.effects if e.name in best.leaves_out),
                  key=_with_uncertainty)
    return (f"the closest GW model, {best.name}, leaves out effects that sum to "
            f"{best.error:.3g} > the tolerance {advice.scene.tolerance:g}, the largest "
            f"{largest.name}: {largest.size:.3g} ({largest.how})")


#: The models run on a scene's height map, by the name `gw.explicit.answer` knows them by.
SURFACE_MODELS = {INTERACTING: "interacting", WHOLE: "whole"}


def _on_the_map(scene, model, progress):
    """`gw.explicit.answer` of the scene's height map up to `model`, each cheaper one too."""
    from gw.explicit.answer import answer

    return answer(scene.topography(), _adhesion(scene), model=model, accuracy="default",
                  progress=progress if model == "whole" else None)


def _adhesion(scene):
    """The scene's `gw.explicit.Adhesion` (E*, Δγ, ε)."""
    from gw.explicit import Adhesion

    s = scene.scales
    return Adhesion(s.E_star, s.dgamma, s.eps)
