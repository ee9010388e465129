"""What a solved curve is: `CurveResult` (curves, events, error estimate, cost, status) and its
own files (`write_curves`: the CSV curves and result.json, the format the store reads back)."""

import csv
import io
import json
from dataclasses import asdict, dataclass, field
from pathlib import Path

from ..closed_forms.physical_arguments import scale_record
from ..curves.curve import Curve
from ..curves.events import Events
from ..plumbing.files import write_atomic
from ..plumbing.revision import solver_revision
from ..plumbing.version import __version__
from ..solids.fe import Solid
from ..solids.operator import ElasticSurface

#: Values of `CurveResult.status`, from the best to the worst news (`CurveResult` defines each).
STATUSES = ("ok", "no_estimate", "ripples", "missed_jump", "tolerance_not_met")
#: Folds of δ̄o the physics has at most: one jump-in and one jump-out; more are ripple.
PHYSICAL_FOLDS = 2


def relative_estimate(estimate, events):
    """The error estimate per key relative to the event's magnitude (`events`: the
    `Events.records()` dict); None where either is missing or the event is 0."""
    if estimate is None:
        return None
    return {k: (e / abs(events[k]) if e is not None and events.get(k) else None)
            for k, e in estimate.items()}


def worst_status(*statuses):
    """The worst of the given `STATUSES`."""
    return max(statuses, key=STATUSES.index)


def noted(message, *clauses):
    """A curve's `message` with each non-empty one of `clauses` appended after "; " (a message is
    one statement, then a clause per thing that changed or qualifies the result)."""
    return "; ".join((message, *(clause for clause in clauses if clause)))


@dataclass
class Model:
    """The solved model behind a curve (kept for field output): the elastic solid, the LJ
    surface problem of the first state (of every state on one fixed grid; on grids that follow
    the edge each state's nodes are in the trace), the trace."""

    half_space: ElasticSurface
    surface: object
    trace: object


@dataclass(frozen=True)
class CurveResult:
    """One approach + retraction at Tabor parameter `mu`, and how it was obtained.

    equilibrium: the traced equilibrium curve: with `unstable_branch` the whole curve, else the
        stable branches the paths visit, one after the other (`branch` numbers them).
    approach, retraction: the paths under δ̄o control (jumps as consecutive points at equal δ̄o).
    events: `Events` read off the paths. error_estimate: estimated absolute error per event key,
    in the event's units (None where not estimated), under a spring also of z_jumps' keys;
    relative_error_estimate holds the same relative to the event. estimated_by: how the
    estimate was made, 'finer' (the events again on a finer discretisation,
    `estimate.difference_estimate`), 'bem' (the FE against the boundary integral,
    `estimate._estimate_against_bem`), 'tolerance' (the last change between refinement levels,
    `solve.solve_to_tolerance`) or None (no estimate asked for). estimate_floor: the
    part of each force's estimate that no refinement sees, {force key: 2πRΔγ}: the LJ traction
    beyond the traction grid's last node (`estimate.traction_tail`), added to the estimate.
    dofs, surface_nodes, points, newton_iterations, wall_s: cost.
    folds: folds of δ̄o met: changes of stability along the whole curve, or jumps of the paths.
    radius_ratio (R/ε of the exact sphere; None: Derjaguin's parabola), p_end, unstable_branch,
    spring_constant (load-line control; None: displacement control): the inputs of
    `solve_curve` beyond μ, method, accuracy and solid. z_jumps: under load-line control, the
    spring end's z̄ (ε) at the jumps, {'z_jump_in', 'z_jump_out'}; the events' separations stay
    the sphere's δ̄o.
    status: one of `STATUSES` ('ok' unless something calls for a finer accuracy). ok: no more
        folds than one jump-in and one jump-out, the estimate (if asked for) obtained and the
        tolerance (if one was set) met. no_estimate: the error estimate's second solve (finer,
        or the boundary integral's curve) failed or rippled. ripples: more folds than two after
        the refinements, the sign of a surface mesh too coarse for μ. missed_jump: above the
        onset of jump-in, yet no jump-in found on any refinement tried. tolerance_not_met:
        `solve_to_tolerance` ran out of levels.
    message: how it was obtained, and why the status is not 'ok' where it is not.
    regrid_change: on grids that follow the contact edge, the largest |ΔP̄| of a state moved to
        a new grid while on a branch: how much where the grids lie moves the forces (a 'finer'
        error estimate of the forces includes it); None on one grid or mesh.
    regrid_radius_change: the same for ā_c (a 'finer' estimate of ā_c includes it).
    regrid_fold_change: the largest |Δδ̄o| of the jump-out's fold found again on grids placed
        otherwise (a 'finer' estimate of δ̄o at the jump-out includes it; 0 where no fold of a
        retraction in contact was found so, `path.tip.record_fold_elsewhere`).
    model: the `Model` behind the curve, for field output (the FE, or the BEM on one grid; None
        for BEM grids that follow the edge). On grids that follow the edge its surface is the
        first state's only: each state's own nodes are in its trace.
    """

    mu: float
    accuracy: str
    solid: Solid
    equilibrium: Curve
    approach: Curve
    retraction: Curve
    events: Events
    error_estimate: dict | None
    dofs: int
    surface_nodes: int
    points: int
    newton_iterations: int
    wall_s: float
    folds: int = 0
    method: str = "fem"
    status: str = "ok"
    message: str = ""
    radius_ratio: float | None = None
    p_end: float = 1.0
    unstable_branch: bool = False
    spring_constant: float | None = None
    z_jumps: dict | None = None
    regrid_change: float | None = None
    regrid_radius_change: float | None = None
    regrid_fold_change: float | None = None
    estimated_by: str | None = None
    estimate_floor: dict | None = None
    model: Model | None = field(default=None, repr=False, compare=False)

    def values(self):
        """Every estimated value by its key: the events (`Events.records`) and, under a spring,
        the z̄ of its jumps (`z_jumps`)."""
        return self.events.records() | (self.z_jumps or {})

    @property
    def relative_error_estimate(self):
        """`error_estimate` relative to each value's magnitude (`values`, `relative_estimate`)."""
        return relative_estimate(self.error_estimate, self.values())

    @property
    def ripples(self):
        """More folds than one jump-in and one jump-out: the sign of a surface mesh too coarse."""
        return self.folds > PHYSICAL_FOLDS

    def layer_groups(self):
        """The groups that govern a layered contact, None for a homogeneous half-space:
        thickness t/√(Rε), modulus_ratio M = E*_layer/E*_substrate, the Tabor parameters of the
        substrate (μ) and of the layer (μ M^(−2/3), Tabor's μ with the layer's E*), and
        thickness_over_a_c, t over the contact radius at P̄max (None where a_c = 0)."""
        t = self.solid.layer_thickness
        if t is None:
            return None
        ratio, a_c = self.solid.layer_modulus_ratio, self.events.a_c
        return {"thickness": t, "modulus_ratio": ratio, "mu_substrate": self.mu,
                "mu_layer": self.mu * ratio ** (-2.0 / 3.0),
                "thickness_over_a_c": t / a_c if a_c else None}

    def inputs(self):
        """Every input that produced the curve, JSON-ready: the solid (layer included), the
        profile, the control and the paths traced."""
        return {"solid": asdict(self.solid),
                "profile": "derjaguin" if self.radius_ratio is None else "sphere",
                "radius_ratio": self.radius_ratio,
                "control": "displacement" if self.spring_constant is None else "load line",
                "spring_constant": self.spring_constant,
                "p_end": self.p_end, "unstable_branch": self.unstable_branch}

    def to_dataframe(self, scales=None):
        """The approach and retraction as one pandas DataFrame, a row per point (`path_rows`:
        dimensionless columns, and SI ones with `scales`, the `Scales` of physical inputs;
        pandas is the optional extra `tables`)."""
        try:
            import pandas as pd
        except ImportError:
            raise ImportError("to_dataframe needs pandas: pip install pandas") from None
        return pd.DataFrame(self.path_rows(scales))

    def path_rows(self, scales=None):
        """`path_rows` of the approach, then of the retraction."""
        return [row for name in ("approach", "retraction")
                for row in path_rows(getattr(self, name), name, scales, self.spring_constant)]

    def records(self, scales=None):
        """JSON-ready dict: the command line's keys (dimensionless, tensile forces negative),
        then the inputs, the package version and the solver's revision (`plumbing.revision`);
        with `scales` (the `Scales` of physical inputs) an `si` block: the events and their
        estimates in N and m, the scales with E*, Δγ, ε and R, and the spring's K [N/m]."""
        row = self._records()
        if scales is not None:
            row["si"] = {**scales.to_si(row),
                         "error_estimate": scales.to_si(row["error_estimate"] or {}),
                         "scales": scale_record(scales)}
            if self.spring_constant is not None:
                row["si"]["spring_constant"] = self.spring_constant * scales.force / scales.eps
        return row

    def _records(self):
        return {
            "mu": self.mu,
            "method": self.method,
            "accuracy": self.accuracy,
            **self.events.records(),
            **(self.z_jumps or {}),
            "error_estimate": self.error_estimate,
            "relative_error_estimate": self.relative_error_estimate,
            "estimated_by": self.estimated_by,
            "estimate_floor": self.estimate_floor,
            "dofs": self.dofs,
            "surface_nodes": self.surface_nodes,
            "regrid_change": self.regrid_change,
            "regrid_radius_change": self.regrid_radius_change,
            "regrid_fold_change": self.regrid_fold_change,
            "points": self.points,
            "newton_iterations": self.newton_iterations,
            "wall_s": self.wall_s,
            "status": self.status,
            "message": self.message,
            "layer_groups": self.layer_groups(),
            "inputs": self.inputs(),
            "version": __version__,
            "solver_revision": solver_revision(),
        }


#: The columns of `path_rows` with their units: dimensionless (the paper's scales), then SI ones
#: with physical inputs (the last two under load-line control only).
PATH_COLUMNS = {"path": "approach | retraction", "point": "index along the path",
                "delta_o": "eps", "x_o": "eps", "p": "2 pi R dgamma (< 0 tensile)",
                "area": "eps R", "a_c": "sqrt(eps R)", "stable": "1 | 0",
                "branch": "segment between jumps"}
SI_PATH_COLUMNS = {"delta_o_m": "m", "x_o_m": "m", "force_N": "N (< 0 tensile)",
                   "area_m2": "m^2", "a_c_m": "m",
                   "piezo_m": "m (the spring's far end: delta_o - P/K)",
                   "deflection_m": "m (-P/K, > 0 bent toward the surface)"}


def path_rows(curve, name, scales=None, spring_constant=None):
    """The points of path `curve` (called `name`) as dicts with PATH_COLUMNS and, with `scales`
    (the `Scales` of physical inputs), SI_PATH_COLUMNS: separations in m, force in N, area in
    m², contact radius in m and, under load-line control (`spring_constant` k̄), the piezo
    position (δ̄o − P̄/k̄)ε and the cantilever's deflection −P̄ε/k̄."""
    rows = []
    for i in range(len(curve)):
        row = {"path": name, "point": i, "delta_o": float(curve.delta[i]),
               "x_o": float(curve.x[i]), "p": float(curve.p[i]),
               "area": float(curve.area[i]), "a_c": float(curve.a_c[i]),
               "stable": int(curve.stable[i]), "branch": int(curve.branch[i])}
        if scales is not None:
            row |= {"delta_o_m": row["delta_o"] * scales.length_z,
                    "x_o_m": row["x_o"] * scales.length_z, "force_N": row["p"] * scales.force,
                    "area_m2": row["area"] * scales.area, "a_c_m": row["a_c"] * scales.length_r}
            if spring_constant is not None:
                deflection = -row["p"] / spring_constant
                row |= {"piezo_m": (row["delta_o"] + deflection) * scales.length_z,
                        "deflection_m": deflection * scales.length_z}
        rows.append(row)
    return rows


def curve_files(result, scales=None):
    """{file name: text} of a result's own files: approach.csv, retraction.csv,
    equilibrium.csv, then result.json (`result.records(scales)`)."""
    files = {f"{name}.csv": getattr(result, name).csv()
             for name in ("approach", "retraction", "equilibrium")}
    files["result.json"] = json.dumps(result.records(scales), indent=2,
                                      allow_nan=False) + "\n"
    return files


def write_curves(result, folder, scales=None):
    """`curve_files` under `folder`, result.json last (a folder holding it is complete)."""
    folder = Path(folder)
    return [write_atomic(folder / name, text)
            for name, text in curve_files(result, scales).items()]


def csv_text(rows, columns):
    """CSV text of dict rows with a header of `columns` (missing values empty)."""
    out = io.StringIO()
    writer = csv.DictWriter(out, columns, lineterminator="\n", extrasaction="ignore")
    writer.writeheader()
    writer.writerows(rows)
    return out.getvalue()
