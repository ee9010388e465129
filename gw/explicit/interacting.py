"""Interacting asperities: GW's summits, each on the solved single-asperity law, coupled through
the elastic far field of the others' forces.

Summit i at height z̄ᵢ (ε) sees the separation

    δ̄ᵢ = d̄ − z̄ᵢ + Σ_{j≠i} Kᵢⱼ P̄ⱼ,    Kᵢⱼ = 2μ^(3/2) G(rᵢⱼ)/ā   (→ 2μ^(3/2)/r̄ᵢⱼ far away),

since a force P on the half-space lowers its surface by P/(πE*r) at a distance r (Boussinesq):
in the asperity units (P̄ in 2πRΔγ, r̄ in √(Rε), δ̄ in ε) that is 2μ^(3/2)P̄/r̄. G is the pixel
kernel of `halfspace` (Love's, ≈ 1/ρ in pixels ā; periodic and zero-mean on a periodic map),
so the model sees the same solid as the whole-surface solver: a free patch sinks as a whole, a
periodic one keeps its mean. Each summit keeps its own state: detached (the approach law,
P̄_a) until δ̄ᵢ falls to the law's jump-in, then attached (the retraction law, P̄_r) until δ̄ᵢ
rises past its jump-out. At each separation the δ̄ are solved by Newton (GMRES on
I − K diag(P̄′)) with the states held, then every summit past its threshold switches and the
solve repeats until no state changes: a switch is that summit's jump, a run of switches a
cascade. Where the coupled branch ends before any summit reaches its own threshold (the
neighbours' pull makes the fold come early), the summit nearest its threshold switches. A
summit switches at most once per separation: where its own jump would take it back past the
other threshold (on a periodic map its own share of the mean deflection moves it by K_ii ΔP̄),
it keeps its new state off its branch, solved there, rather than cycle within the separation.
At the next separation it may switch back: in small periodic cells (|K_ii| large, e.g. one cap
in a cell 8 √(Rε) wide at μ = 1, steps of 0.05 ε) the model then alternates between the two
laws from one separation to the next, a sign that it does not hold there.
With K = 0 this is the GW sum over these summits.
"""

from dataclasses import dataclass

import numpy as np
from scipy.sparse.linalg import LinearOperator, gmres

from fem_asperity.plumbing.checks import positive
from fem_asperity.plumbing.errors import InputError

from .halfspace import PixelHalfSpace

#: Converged where no δ̄ moves by more than this in a Newton step (ε).
TOLERANCE = 1e-10
#: Newton steps per state set, and state sweeps per separation, before giving up.
MAX_NEWTON, MAX_SWEEPS = 50, 200
#: Where the held states have no equilibrium, a summit within this (ε) of its threshold jumps;
#: farther, the model stops (methods.md §14). Not pinned by a test.
FOLD_BAND = 0.1
#: Step of the one-sided difference for P̄′ (ε): the laws are PCHIP in δ̄, smooth on 1e-6.
SLOPE_STEP = 1e-6


@dataclass(frozen=True)
class AsperityLaw:
    """The single-asperity law both ways: `approach` and `retraction` (objects with
    `force(δ̄)` in 2πRΔγ and `area(δ̄)` in εR, e.g. `gw.laws.TabulatedLaw`), and the jump
    thresholds (ε): `jump_in` (None below the onset, μ ≈ 0.697) and `jump_out`."""

    mu: float
    approach: object
    retraction: object
    jump_in: float | None
    jump_out: float | None
    source: str = ""

    @classmethod
    def tabulated(cls, mu):
        """From the shipped table of solved laws (`gw.law_table`, μ 0.01-50): no solve; each
        law carries the table's measured error (`error`)."""
        from ..law_table import shipped_table

        table = shipped_table()
        approach, retraction = table.law(mu), table.law(mu, "retraction")
        return cls(mu, approach, retraction, approach.delta_jump, retraction.delta_jump,
                   approach.source)

    @classmethod
    def at(cls, mu):
        """`tabulated` where the table covers mu, else `solved` (BEM `default`)."""
        from ..law_table import shipped_table

        lo, hi = shipped_table().mu_range
        return cls.tabulated(mu) if lo <= mu <= hi else cls.solved(mu)

    @classmethod
    def solved(cls, mu, *, method="bem", accuracy="default", progress=None):
        """From the stored (or now solved) curve at `mu` (`fem_asperity.studies.store`)."""
        from fem_asperity.studies.store import stored_curve

        from ..laws import TabulatedLaw

        stored = stored_curve(mu, method=method, accuracy=accuracy, progress=progress)
        star = stored.events.delta_o_star
        ev = stored.events
        return cls(mu, TabulatedLaw(mu, stored.approach, delta_o_star=star, name=method),
                   TabulatedLaw(mu, stored.retraction, delta_o_star=star, name=method),
                   ev.jump_in.delta if ev.jump_in else None,
                   ev.jump_out.delta if ev.jump_out else None, str(stored.folder))


@dataclass(frozen=True)
class SummitPath:
    """One direction of travel: `d` (ε, from the map's datum), `force` (Σ P̄ over the
    summits, 2πRΔγ, < 0 tensile), `area` (Σ Ā, εR), `attached` (summits attached), the
    `jumps` (tuples (kind, d̄, summit index)), `sweeps` (state sweeps, the cost), and
    `stopped`: the d̄ where the model found no equilibrium and the path ends (None: it ran
    through every separation)."""

    d: np.ndarray
    force: np.ndarray
    area: np.ndarray
    attached: np.ndarray
    jumps: tuple
    sweeps: int
    stopped: float | None = None


def coupling(rows, columns, *, shape, pixel, mu, periodic):
    """K (n × n): the separation change of summit i per unit P̄ of summit j, for summits at the
    pixels (`rows`, `columns`) of a map of `shape` pixels of `pixel` √(Rε). The diagonal holds
    what a summit does to itself beyond its own law (the law's half-space is free and infinite):
    nothing on a free patch; on a periodic map the regular part of the periodic kernel at its
    own place, lim G_per(ρ) − 1/ρ (< 0: the mean deflection held at zero lowers the ground under
    every loaded summit by its share of the mean). It scales as 1/L, so it is 2(G_L(0) −
    G_2L(0)), the pixel's own part cancelling: −3.925/L on a square map of L pixels against
    the square lattice's Madelung constant −3.9003/L (test_whole_surface.py)."""
    positive("pixel", pixel)
    kernel = _unit_response(shape, periodic)
    grid = kernel.shape
    rows, columns = np.asarray(rows, dtype=int), np.asarray(columns, dtype=int)
    di = (rows[:, None] - rows[None, :]) % grid[0]
    dj = (columns[:, None] - columns[None, :]) % grid[1]
    k = 2.0 * mu**1.5 * kernel[di, dj] / pixel
    own = 0.0
    if periodic:
        own = 2.0 * mu**1.5 * 2.0 * (kernel[0, 0] - _unit_response(
            (2 * shape[0], 2 * shape[1]), periodic)[0, 0]) / pixel
    np.fill_diagonal(k, own)
    return k


def _unit_response(shape, periodic):
    """G at every offset (pixel units): the deflection of a unit Σp̄ on pixel (0, 0)."""
    space = PixelHalfSpace.build(shape, compliance=1.0, periodic=periodic)
    unit = np.zeros(space.grid)
    unit[0, 0] = 1.0
    return space.apply_root(space.apply_root(unit))


class Interacting:
    """Summits at heights `heights` (ε) coupled by `k` (`coupling`; zeros: GW's sum) on
    `law` (`AsperityLaw`)."""

    def __init__(self, heights, k, law):
        """`k`: the coupling (its diagonal the summits' own correction, `coupling`)."""
        self.heights = np.asarray(heights, dtype=float)
        self.k, self.law = np.asarray(k, dtype=float), law
        if self.k.shape != (self.heights.size,) * 2:
            raise InputError(f"the coupling must be {self.heights.size} x {self.heights.size}")

    def _force(self, delta, attached):
        return np.where(attached, self.law.retraction.force(delta),
                        self.law.approach.force(delta))

    def _area(self, delta, attached):
        return np.where(attached, self.law.retraction.area(delta),
                        self.law.approach.area(delta))

    def _residual(self, d, delta, attached):
        return delta - (d - self.heights) - self.k @ self._force(delta, attached)

    def _switching(self, delta, attached):
        """(come in, go out): the summits past their state's threshold at δ̄."""
        jump_in = -np.inf if self.law.jump_in is None else self.law.jump_in
        jump_out = np.inf if self.law.jump_out is None else self.law.jump_out
        return ~attached & (delta <= jump_in), attached & (delta >= jump_out)

    def _solve(self, d, delta, attached, switched):
        """δ̄ with the states held: Newton on δ̄ − (d̄ − z̄) − K P̄(δ̄), each step halved until
        it lowers the largest residual (the laws are steep near a fold) → (δ̄, converged). It
        stops early where a summit passes its threshold: the others' pull took it past its
        fold, so it jumps (its branch ends there and the states must change first). It does
        not converge where the coupled branch has ended before any summit reached its own
        threshold (P̄′ grows without bound at a fold, so K P̄′ reaches 1 first)."""
        n = delta.size
        residual = self._residual(d, delta, attached)
        for _ in range(MAX_NEWTON):
            if any((switch & ~switched).any() for switch in self._switching(delta, attached)):
                return delta, True  # (a summit that switched here may sit off its branch)
            if not self.k.any():
                return delta - residual, True
            # one-sided, away from where the state's branch ends (attached: above, at the
            # jump-out; detached: below, at the jump-in)
            h = np.where(attached, -SLOPE_STEP, SLOPE_STEP)
            slope = (self._force(delta + h, attached) - self._force(delta, attached)) / h

            def product(v, slope=slope):
                return v - self.k @ (slope * v)

            jacobian = LinearOperator((n, n), matvec=product, dtype=float)
            step, _ = gmres(jacobian, -residual, rtol=1e-12, atol=0.0, maxiter=200)
            size, norm = 1.0, np.abs(residual).max()
            while True:
                trial = self._residual(d, delta + size * step, attached)
                if np.abs(trial).max() < norm or size < 1e-6:
                    break
                size *= 0.5
            delta, residual = delta + size * step, trial
            if np.abs(size * step).max() <= TOLERANCE:
                return delta, True
        return delta, False

    def _nearest_fold(self, delta, attached, switched):
        """(come in, go out) with the one summit nearest its threshold switched, if one is
        within FOLD_BAND of it: where the coupled branch ends, the summit nearest its own fold
        goes first. None where none is that near: the far-field model has no equilibrium
        there that a jump explains (contacts too large or too close for it)."""
        jump_in = -np.inf if self.law.jump_in is None else self.law.jump_in
        jump_out = np.inf if self.law.jump_out is None else self.law.jump_out
        margin = np.where(attached, jump_out - delta, delta - jump_in)
        margin[switched] = np.inf  # each summit switches once per separation
        if not margin.min() < FOLD_BAND:
            return None
        first = np.zeros(delta.size, bool)
        first[int(np.argmin(margin))] = True
        return first & ~attached, first & attached

    def follow(self, separations, *, attached=None, delta=None):
        """The path through `separations` (ε, monotone) → (SummitPath, attached, δ̄)."""
        separations = np.asarray(separations, dtype=float)
        attached = np.zeros(self.heights.size, bool) if attached is None else attached.copy()
        delta = separations[0] - self.heights if delta is None else delta
        out = {"d": [], "force": [], "area": [], "attached": []}
        jumps, sweeps, stopped = [], 0, None
        for d in separations:
            switched = np.zeros(self.heights.size, bool)
            for _ in range(MAX_SWEEPS):
                sweeps += 1
                solved, converged = self._solve(d, delta, attached, switched)
                switches = (self._switching(solved, attached) if converged
                            else self._nearest_fold(solved, attached, switched))
                if switches is None:
                    break
                if converged:
                    delta = solved
                come_in, go_out = (s & ~switched for s in switches)
                if not (come_in.any() or go_out.any()):
                    break
                switched |= come_in | go_out
                jumps += [("in", float(d), int(i)) for i in np.flatnonzero(come_in)]
                jumps += [("out", float(d), int(i)) for i in np.flatnonzero(go_out)]
                attached = (attached | come_in) & ~go_out
            else:
                switches = None  # the states cycle: no settled equilibrium either
            if switches is None:
                stopped = float(d)
                break
            out["d"].append(float(d))
            out["force"].append(float(self._force(delta, attached).sum()))
            out["area"].append(float(self._area(delta, attached).sum()))
            out["attached"].append(int(attached.sum()))
        path = SummitPath(*(np.array(out[key]) for key in ("d", "force", "area", "attached")),
                          tuple(jumps), sweeps, stopped)
        return path, attached, delta
