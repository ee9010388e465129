"""The paper's eight fit constants refitted from solved curves (BEM or FE) over μ.

Each constant is fitted to the events of stored curves (`store.stored_curve`) in the paper's own
functional form, by least squares:

- c_off (eq. 2, Wu): P̄off(μ) over all μ (bounded scalar minimisation);
- c_a, mu_a (eq. 6b, ā_c = c_a (μ − mu_a)^½): ā_c² linear in μ, where ā_c > 0;
- c_oc (eq. 7, δ̄oc = 1 + c_oc μ) and c_star (eq. 10, δ̄o* = 1 + c_star μ^1.5): through the origin,
  on the curves without jump-in;
- x_0, x_1 (eq. 12, x̄oc = x_0 + x_1 μ^0.4): linear in μ^0.4, on the curves with jump-in;
- mu_jump: the measured onset of jump-in (`onset.stored_onset`).

`Refit` keeps the constants, the RMS and largest residual of each fit and the μ used.
"""

from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np
from scipy.optimize import minimize_scalar

from ..closed_forms.laws import AsperityLaws, wu_pull_off
from ..plumbing.progress import share
from ..plumbing.revision import code_revision
from .onset import stored_onset
from .store import cache_dir, stored_json
from .sweep import stored_curves

#: Tabor parameters of the refit: both regimes, on uniform BEM grids (below
#: MU_TRACKING["bem"]), where a curve is cheap. Not pinned by a test (test_refit.py fits its own μ).
REFIT_MU = (0.05, 0.1, 0.15, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8, 1.0, 1.3, 1.6, 2.0, 2.5, 3.0)


@dataclass(frozen=True)
class Refit:
    """Refitted `laws`, per-constant-group residuals {name: (rms, max)}, and provenance."""

    laws: AsperityLaws
    residuals: dict
    mu: tuple
    method: str
    accuracy: str


def _line(x, y, *, through_origin=False):
    """Least-squares (intercept, slope) of y on x, and the residuals."""
    if through_origin:
        slope = float(x @ y / (x @ x))
        return 0.0, slope, y - slope * x
    slope, intercept = np.polyfit(x, y, 1)
    return float(intercept), float(slope), y - (intercept + slope * x)


def _stats(residual):
    return (float(np.sqrt(np.mean(residual**2))), float(np.max(np.abs(residual))))


def refit(mus=REFIT_MU, *, method="bem", accuracy="default", progress=None):
    """Fit the eight constants to curves at `mus` (solved once, then stored). progress:
    callable(fraction done): the curves solved up to 0.8 (`stored_curves`), then 1 once the
    onset of jump-in is found and the constants fitted."""
    stored = stored_curves(mus, method=method, accuracy=accuracy,
                           progress=share(progress, 0.0, 0.8))
    events = [{"mu": s.mu, **s.events.records()} for s in stored.values()]
    mu = np.array([e["mu"] for e in events])
    col = {k: np.array([np.nan if e[k] is None else e[k] for e in events], float)
           for k in ("p_off", "a_c", "delta_oc", "delta_o_star", "x_oc")}
    jump = np.array([e["jump_in"] for e in events])
    c_off = minimize_scalar(lambda c: np.sum((wu_pull_off(mu, c) - col["p_off"]) ** 2),
                            bounds=(0.1, 10.0), method="bounded", options={"xatol": 1e-10}).x
    touching = col["a_c"] > 0.0
    a0, a1, ra = _line(mu[touching], col["a_c"][touching] ** 2)
    c_a, mu_a = np.sqrt(a1), -a0 / a1
    _, c_oc, roc = _line(mu[~jump], col["delta_oc"][~jump] - 1.0, through_origin=True)
    _, c_star, rst = _line(mu[~jump] ** 1.5, col["delta_o_star"][~jump] - 1.0,
                           through_origin=True)
    x_0, x_1, rx = _line(mu[jump] ** 0.4, col["x_oc"][jump])
    onset = stored_onset(method=method, accuracy=accuracy).mu_onset
    laws = AsperityLaws(c_off=float(c_off), c_a=float(c_a), mu_a=float(mu_a), c_oc=c_oc,
                        c_star=c_star, x_0=x_0, x_1=x_1, mu_jump=float(onset))
    residuals = {"p_off (eq. 2)": _stats(wu_pull_off(mu, c_off) - col["p_off"]),
                 "a_c^2 (eq. 6b)": _stats(ra), "delta_oc (eq. 7)": _stats(roc),
                 "delta_o_star (eq. 10)": _stats(rst), "x_oc (eq. 12)": _stats(rx)}
    if progress:
        progress(1.0)
    return Refit(laws, residuals, tuple(float(m) for m in mu), method, accuracy)


def _refit_from_dict(data):
    residuals = {k: tuple(v) for k, v in data["residuals"].items()}
    return Refit(AsperityLaws(**data["laws"]), residuals, tuple(data["mu"]), data["method"],
                 data["accuracy"])


def stored_refit(*, method="bem", accuracy="default", cache=None, announce=None, progress=None):
    """`Refit` read from the store, or computed (over `REFIT_MU`) and stored. The store key is
    the revision of this module's code and all it imports (the fit forms, the onset search, the
    laws, the solver). announce: callable(str), told when the refit has to be computed (it
    solves and stores the curves it needs first); progress: as `refit`'s, while it is."""
    path = Path(cache or cache_dir()) / f"refit-{method}-{accuracy}-{code_revision(__name__)}.json"

    def compute():
        if announce is not None:
            announce(f"refitting the eight constants from {method} curves at {len(REFIT_MU)} "
                     "mu (stored for next time) ...")
        return refit(method=method, accuracy=accuracy, progress=progress)

    return stored_json(path, _refit_from_dict, compute,
                       lambda found: {**asdict(found), "laws": asdict(found.laws)})
