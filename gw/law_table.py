"""The solved asperity law at any μ of the shipped table, in milliseconds: no solve.

The table holds the approach and retraction paths (P̄, Ā against δ̄o, the jumps included) of
BEM `default` curves at log-spaced μ (the nodes, 12 per decade, and a few at the jump-in
onset), and the errors of the table measured at μ between the nodes that were not used to
build it (`python -m gw law-table` rebuilds it from the sweep engine; `build_table`).

Between the nodes, P̄ and Ā are interpolated at equal *warped* separation ξ, a piecewise-linear
map of δ̄o through landmarks every path has, mapped to ξ = 1, 0, −1, −2, −3: FAR (where the paths
start, or farther where a jump-out lies beyond it; beyond it ξ − 1 = δ̄o − FAR, so Bradley's
tail stays in place), the path's jump (the
jump-in on approach, the jump-out on retraction; below the onset, where P̄ is steepest: where
the fold appears), and the δ̄o where P̄ crosses LEVELS in contact (so that the Hertz core scales
with the contact; deeper, the last segment's scale goes on). At a μ, each node's law
(`TabulatedLaw`, with its Bradley and Hertz continuations) is read at the δ̄o of equal ξ and
the values are combined with the Lagrange weights of STENCIL nodes in log μ, all on one side of
the onset, as are the landmarks, which map ξ back to δ̄o. The jump stays a jump at ξ = 0.

Units: δ̄o in ε; P̄ in 2πRΔγ (< 0 tensile); Ā in εR; F̄ in 2πRA₀Δγη.
"""

import functools
import io
import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fem_asperity.curves.curve import Curve
from fem_asperity.plumbing.checks import finite_result, in_range
from fem_asperity.plumbing.errors import InputError
from fem_asperity.plumbing.files import write_atomic

from .laws import AREA, FORCE, TabulatedLaw

#: δ̄o where every solved approach starts (solver.solve's far end): the far landmark.
FAR = 40.0
#: Where the jump-out lies beyond FAR (μ ≳ 22), the far landmark is this factor beyond it
#: (methods.md §14). Not pinned by a test; docs/law_table.md has the error.
FAR_BEYOND_JUMP = 1.25
#: P̄ of the landmarks in contact; every solved path reaches P̄ = 1 (solve_curve's p_end).
LEVELS = (0.0, 0.5, 1.0)
_XI = 1.0 - np.arange(2 + len(LEVELS), dtype=float)
#: Nodes combined in log μ: cubic. Linear weights were off by up to 15 % in F̄max at 6 nodes per
#: decade, cubic by 0.5 % (held-out μ, BEM default): test_law_table.py checks the shipped errors.
STENCIL = 4
#: ζ at which the table's F̄max error is measured: the paper's range (validation/rough_surface).
ZETAS = tuple(np.round(np.logspace(-1.0, 2.5, 8), 6))
#: The shipped table.
TABLE_FILE = Path(__file__).with_name("data") / "solved_law.npz"
_FIELDS = ("delta", "p", "area", "branch")


def _warp(delta, marks):
    """ξ of δ̄o (array) through the landmarks `marks` (decreasing), linear beyond both ends."""
    m = np.asarray(marks)
    out = -np.interp(-delta, -m, -_XI)
    far, deep = delta > m[0], delta < m[-1]
    out[far] = _XI[0] + (delta[far] - m[0])
    out[deep] = _XI[-1] + (delta[deep] - m[-1]) / (m[-2] - m[-1])
    return out


def _unwarp(xi, marks):
    """δ̄o of ξ (array): the inverse of `_warp`."""
    m = np.asarray(marks)
    out = -np.interp(-xi, -_XI, -m)
    far, deep = xi > _XI[0], xi < _XI[-1]
    out[far] = m[0] + (xi[far] - _XI[0])
    out[deep] = m[-1] + (xi[deep] - _XI[-1]) * (m[-2] - m[-1])
    return out


def _crossing(force, level, lo, hi):
    """The deepest δ̄o in [lo, hi] where `force` rises through `level` going deeper."""
    d = np.linspace(lo, hi, 4001)
    above = force(d) >= level
    if not above[0] or above.all():
        raise InputError(f"a tabulated approach does not cross P̄ = {level:g} in contact")
    i = int(np.argmin(above))
    return float(np.interp(level, force(d[[i, i - 1]]), d[[i, i - 1]]))


@dataclass(frozen=True)
class Node:
    """A solved approach or retraction at one μ: its law, landmarks (δ̄o at ξ = 1, 0, −1, ...,
    ξ = 0 at its jump), whether it jumps, and δ̄o* (initial contact on approach) [ε]."""

    mu: float
    law: TabulatedLaw
    landmarks: tuple
    jumps: bool
    delta_o_star: float

    @classmethod
    def from_path(cls, mu, path, jump, delta_o_star):
        """From a solved approach or retraction (`Curve`), its jump's δ̄o (None: none) and δ̄o*
        (of the approach)."""
        law = TabulatedLaw(mu, path, delta_o_star=delta_o_star, name="node")
        deep, _ = law.solved_range
        if jump is None:  # where the fold will appear: the steepest point on the loading side
            d = np.linspace(deep, FAR, 40001)
            p = law.force(d)
            loading = d > d[np.argmin(p)]
            slope = np.gradient(p, d)
            mark = float(d[loading][np.argmax(slope[loading])])
        else:
            mark = float(jump)
        marks = [max(FAR, FAR_BEYOND_JUMP * mark), mark]
        for level in LEVELS:
            marks.append(_crossing(law.force, level, deep, marks[-1] - 1e-9))
        return cls(float(mu), law, tuple(marks), jump is not None, float(delta_o_star))


def _around(measured):
    """The largest of each error in the held-out measurements `measured` (`TableLaw.error`)."""
    jumps = [m["jump"] for m in measured if m["jump"] is not None]
    out = {"held_out": [m["held_out"] for m in measured],
           "force": max(m["force"] for m in measured), "jump": max(jumps) if jumps else None}
    if all("f_max" in m for m in measured):  # the approach's: F̄max on GW surfaces
        out["f_max"] = max(abs(x) for m in measured for x in m["f_max"] if x is not None)
    return out


def _lagrange(x, xs):
    """Lagrange weights at x of the points xs."""
    xs = np.asarray(xs)
    return np.array([np.prod([(x - xk) / (xj - xk) for k, xk in enumerate(xs) if k != j])
                     for j, xj in enumerate(xs)])


class TableLaw:
    """The table's law at `mu` (the `gw.laws` interface: mu, name, breakpoints, force, area).

    `error`: the table's error, the largest measured at the held-out μ of this μ's interval and
    of the intervals on either side (`held_out`: those μ; `force`: |ΔP̄| [2πRΔγ] over the solved
    δ̄o outside the jump's shift; `jump`: |Δδ̄o| of the jump-in [ε], None without one; `f_max`:
    relative F̄max error over the ζ of `ZETAS`). One held-out μ per interval missed the error
    at other μ of the interval by up to 10x near the onset; three did not (test_law_table.py).
    `interpolation_error`: `error['force']`, as a fraction of max |P̄| (as TabulatedLaw's)."""

    def __init__(self, mu, nodes, weights, error, source):
        self.mu, self.name, self.source, self.error = mu, "solved", source, error
        self._nodes, self._w = nodes, weights
        self.landmarks = sum(w * np.asarray(n.landmarks) for w, n in zip(weights, nodes))
        star = sum(w * _warp(np.array([n.delta_o_star]), n.landmarks)[0]
                   for w, n in zip(weights, nodes))
        marks = {float(_unwarp(np.array([star]), self.landmarks)[0])}
        self.jumps = any(n.jumps for n in nodes)  # at landmarks[1]
        if self.jumps:
            marks.add(float(self.landmarks[1]))
        self.breakpoints = tuple(sorted(marks))
        self.interpolation_error = error.get("force", np.nan)

    def _blend(self, delta, what):
        d = np.asarray(in_range("delta_o", delta), dtype=float)
        xi = _warp(np.atleast_1d(d).ravel(), self.landmarks)
        # the nodes' unchecked evaluations: δ̄o was checked above, and the per-call checks cost
        # more than the interpolation on the GW integrals' small arrays
        with np.errstate(over="ignore", invalid="ignore"):  # refused by finite_result
            out = sum(w * getattr(n.law, f"_{what}")(_unwarp(xi, n.landmarks))
                      for w, n in zip(self._w, self._nodes))
        return out.reshape(d.shape)

    def force(self, delta):
        """P̄(δ̄o) [2πRΔγ] on approach at δ̄o `delta` [ε]."""
        return finite_result(self._blend(delta, "force"), FORCE)

    def area(self, delta):
        """Ā(δ̄o) [εR] on approach at δ̄o `delta` [ε]."""
        return finite_result(self._blend(delta, "area"), AREA)

    @property
    def delta_jump(self):
        """δ̄o of the path's jump [ε] (the jump-in on approach, the jump-out on retraction;
        None below the onset)."""
        return float(self.landmarks[1]) if self.jumps else None

    @property
    def f_max_error(self):
        """The table's relative F̄max error (`error['f_max']`): the largest measured."""
        return self.error["f_max"]


@dataclass(frozen=True)
class Entry:
    """A node as stored: μ, its solved approach and retraction (`Curve`), the δ̄o of their jumps
    (None: none) and δ̄o*."""

    mu: float
    approach: Curve
    jump_in: float | None
    retraction: Curve
    jump_out: float | None
    delta_o_star: float


class LawTable:
    """The nodes (`Entry`, increasing μ; each path made a `Node` when first combined), the
    errors measured at the held-out μ (one dict per interval between nodes, as
    `TableLaw.error`, the retraction's under 'retraction'; the held-out μ lies in the interval)
    and the record of how the table was made (solver revision, method, accuracy, command,
    date)."""

    def __init__(self, entries, errors, record):
        self.entries, self.errors, self.record = tuple(entries), tuple(errors), dict(record)
        self.mus = np.array([e.mu for e in self.entries])
        jumps = np.array([e.jump_in is not None for e in self.entries])
        if jumps.any() and not jumps[np.argmax(jumps):].all():
            raise InputError("a table node below the jump-in onset jumps in, or one above "
                             "does not")
        self._first_jump = int(np.argmax(jumps)) if jumps.any() else len(self.entries)
        self._nodes = {}

    @property
    def mu_range(self):
        return float(self.mus[0]), float(self.mus[-1])

    def node(self, k, path="approach"):
        """The `Node` of entry k's `path` ('approach' or 'retraction')."""
        if (k, path) not in self._nodes:
            e = self.entries[k]
            jump = e.jump_in if path == "approach" else e.jump_out
            self._nodes[k, path] = Node.from_path(e.mu, getattr(e, path), jump, e.delta_o_star)
        return self._nodes[k, path]

    def _stencil(self, mu):
        """(indices of the nodes combined at mu, index of its interval). The nodes are those on
        mu's side of the onset: below the first node that jumps in, those that do not."""
        n, split = len(self.entries), self._first_jump
        i = int(np.clip(np.searchsorted(self.mus, mu, side="right") - 1, 0, n - 2))
        lo, hi = (0, n) if split in (0, n) else (0, split) if mu < self.mus[split] else (split, n)
        first = int(np.clip(i - (STENCIL - 1) // 2, lo, max(hi - STENCIL, lo)))
        return np.arange(first, min(first + STENCIL, hi)), i

    def check_mu(self, mu):
        """mu as a float if within `mu_range` (ends included), else `InputError`."""
        lo, hi = self.mu_range
        try:
            return float(in_range("mu", mu, lo, np.nextafter(hi, np.inf), closed_lo=True))
        except InputError:
            raise InputError(f"mu of the table of solved laws (--law solved) must be in "
                             f"[{lo:g}, {hi:g}]; got {mu!r}: outside, --law bem solves the "
                             "law at that mu") from None

    def law(self, mu, path="approach"):
        """`TableLaw` of `path` ('approach', the GW integrals' law, or 'retraction') at mu
        (within `mu_range`; `InputError` outside)."""
        mu = self.check_mu(mu)
        nodes, i = self._stencil(mu)
        weights = _lagrange(np.log(mu), np.log(self.mus[nodes]))
        around = self.errors[max(i - 1, 0):i + 2]
        if path == "retraction":
            around = [e["retraction"] | {"held_out": e["held_out"]} for e in around]
        return TableLaw(mu, [self.node(k, path) for k in nodes], weights,
                        _around(around) if around else {},
                        f"table of solved laws ({path}), nodes mu = "
                        + ", ".join(f"{m:.4g}" for m in self.mus[nodes]))


# --- the file -----------------------------------------------------------------------------------

def save_table(path, entries, errors, record):
    """Write the `Entry`s (increasing μ), the measured `errors` and the `record` to `path` (.npz,
    written whole or not at all)."""
    arrays = {"mu": np.array([e.mu for e in entries]),
              "delta_o_star": np.array([e.delta_o_star for e in entries]),
              "meta": np.array(json.dumps({"errors": list(errors), "record": record}))}
    for name, jump in (("approach", "jump_in"), ("retraction", "jump_out")):
        arrays[jump] = np.array([np.nan if getattr(e, jump) is None else getattr(e, jump)
                                 for e in entries])
        arrays[f"{name}_start"] = np.cumsum([0] + [len(getattr(e, name)) for e in entries])
        for f in _FIELDS:
            arrays[f"{name}_{f}"] = np.concatenate([getattr(getattr(e, name), f)
                                                    for e in entries])
    buffer = io.BytesIO()
    np.savez_compressed(buffer, **arrays)
    write_atomic(path, buffer.getvalue())


@functools.cache
def shipped_table():
    """The table shipped with the package (read once per process)."""
    return load_table(TABLE_FILE)


def load_table(path=TABLE_FILE):
    """The `LawTable` at `path` (the shipped one by default)."""
    try:
        data = np.load(path, allow_pickle=False)
    except FileNotFoundError:
        raise InputError(f"no table of solved laws at {path}: `python -m gw law-table` "
                         "writes it") from None
    meta = json.loads(str(data["meta"]))

    def stored(path, k):
        lo, hi = data[f"{path}_start"][k:k + 2]
        n = hi - lo
        return Curve(data[f"{path}_delta"][lo:hi], np.zeros(n), data[f"{path}_p"][lo:hi],
                     data[f"{path}_area"][lo:hi], np.zeros(n), np.ones(n, bool),
                     data[f"{path}_branch"][lo:hi].astype(int))

    def jump(name, k):
        value = float(data[name][k])
        return None if np.isnan(value) else value

    entries = [Entry(float(mu), stored("approach", k), jump("jump_in", k),
                     stored("retraction", k), jump("jump_out", k),
                     float(data["delta_o_star"][k])) for k, mu in enumerate(data["mu"])]
    return LawTable(entries, meta["errors"], meta["record"])
