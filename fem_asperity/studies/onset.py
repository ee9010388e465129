"""The onset of jump-in under displacement control: the smallest μ whose equilibrium curve folds.

Along the traced equilibrium curve (arc length s in the observables x̄o, δ̄o, P̄, oriented with the
approach) δ̄o decreases everywhere on a curve without folds: dδ̄o/ds < 0. A jump-in needs a fold,
where dδ̄o/ds = 0, and between the two folds of the S-shaped curve dδ̄o/ds > 0. So the fold margin
m(μ) = max_s dδ̄o/ds, read off the exact unit tangents of the continuation (refined by a parabola
through the largest three), is negative below the onset, positive above it and continuous in μ;
its root is the onset. The margin is read at a 5x finer turn limit than the preset's curve
(0.02 rad at `default`): with 0.1 rad the sampled maximum scatters by ~3e-3 between presets,
with 0.02 rad by 2e-5 (μ = 0.69-0.70);
test_bem_curve.py::test_fold_margin_changes_sign_between_069_and_070.
"""

import time
from dataclasses import dataclass, replace
from functools import partial
from pathlib import Path

import numpy as np
from scipy.optimize import brentq
from threadpoolctl import threadpool_limits

from ..curves.events import parabola_vertex
from ..path.continuation import trace
from ..plumbing.errors import InputError
from ..plumbing.revision import code_revision
from ..solver.discretised import PATH_BLAS_THREADS
from ..solver.presets import discretisation
from ..solver.solve import solvable_mu
from .store import cache_dir, stored_json


def fold_margin(mu, *, method="bem", accuracy="default"):
    """max over the equilibrium curve of dδ̄o/ds (unit tangent in x̄o, δ̄o, P̄): > 0 iff folds."""
    disc = discretisation(mu, accuracy, method=method)
    settings = replace(disc.trace, turn=0.2 * disc.trace.turn)
    with threadpool_limits(PATH_BLAS_THREADS, user_api="blas"):
        traced = trace(disc.grids(mu).start, settings)
    slope = np.array(traced.tangents)[:, 1]
    o = np.column_stack([traced.x, traced.delta, traced.p])
    arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(o, axis=0), axis=1))])
    k = int(np.clip(np.argmax(slope), 1, slope.size - 2))
    _, peak = parabola_vertex(arc[k - 1:k + 2], slope[k - 1:k + 2])
    return float(max(peak, slope[k]))


@dataclass(frozen=True)
class Onset:
    """mu_onset with its bracket [lo, hi] (the root of the discretised margin lies inside), how
    it was computed (method, accuracy), the number of curves traced and the wall time."""

    mu_onset: float
    lo: float
    hi: float
    method: str
    accuracy: str
    evaluations: int
    wall_s: float

    def records(self):
        """JSON-ready dict."""
        return dict(self.__dict__)


def jump_in_onset(*, method="bem", accuracy="default", bracket=(0.2, 1.0), xtol=1e-3):
    """Smallest μ with a jump-in under displacement control (root of `fold_margin`).

    bracket: (μ_lo, μ_hi) with no fold at μ_lo and a fold at μ_hi. xtol: half-width of the
    returned bracket. Raises InputError if the bracket does not straddle the onset.
    """
    start = time.perf_counter()
    calls = []

    def margin(mu):
        calls.append(mu)
        return fold_margin(mu, method=method, accuracy=accuracy)

    lo, hi = (solvable_mu(mu, "bracket") for mu in bracket)
    if not lo < hi:
        raise InputError(f"bracket must satisfy lo < hi; got {tuple(bracket)}")
    m_lo, m_hi = margin(lo), margin(hi)
    if m_lo * m_hi > 0.0:
        raise InputError(f"no change of the fold margin in [{lo}, {hi}]: {m_lo:.3g}, {m_hi:.3g}")
    root = brentq(margin, lo, hi, xtol=xtol, rtol=1e-12)
    return Onset(mu_onset=root, lo=root - xtol, hi=root + xtol, method=method, accuracy=accuracy,
                 evaluations=len(calls), wall_s=time.perf_counter() - start)


def stored_onset(*, method="bem", accuracy="default", cache=None):
    """`jump_in_onset` over the default bracket, read from the store or computed and stored
    (keyed by the code of this module and all it imports)."""
    name = f"onset-{method}-{accuracy}-{code_revision(__name__)}.json"
    return stored_json(Path(cache or cache_dir()) / name, lambda data: Onset(**data),
                       partial(jump_in_onset, method=method, accuracy=accuracy), Onset.records)
