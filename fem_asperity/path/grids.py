"""Grids that follow the contact edge: the surface problem at large μ, on the boundary integral
or on the FE half-space's surface restricted to the grid (`solids.fe.RestrictedSurface`).

The cohesive zone at the contact edge is about μ^(−3/2) √(Rε) wide while the contact grows like
μ^(1/2) √(Rε), so a grid uniformly fine enough for the edge needs n ∝ μ² nodes, beyond dense
algebra at the largest μ. At large μ the edge has two parts: the contact radius ā_c (where the
gap passes 1 ε) and, well outside it, the crack tip (`LJSurface.crack_tip`, where the adhered
zone opens); between them the gap stays within 0.02 ε of 1. Here the grid is uniformly fine (h)
only within a band of each (`edge_grid`); elsewhere its elements grow geometrically, as long as
the LJ springs of each element stay weaker than its elastic stiffness (`spring_ratio`; coarser
elements snap on their own and give the grid spurious equilibria). Before contact (and after a
jump out of it) the grid is the small-μ BEM's (`solids.bem.radial_grid`). On the FE each grid's
radii are replaced by the nearest surface nodes (where the mesh is fine; every node beyond), so
its fine bands hold every node there.

`EdgeGrids.land` finds a stable state downhill in energy on the grid of its edges, moving the
iterate to a new grid (w interpolated linearly) whenever its edges leave the current one's band
(a landing's contact spreads over many grids); the path solver (`branches.stable_paths`) calls
it after every jump. Where a branch's edges leave the band, `EdgeGrids.regrid` solves its state
again on the next grid (Newton, `land` where that fails), and the path solver records how much
the force changed there (a measure of the discretisation error).
"""

import weakref
from functools import partial
from typing import Protocol, runtime_checkable

import numpy as np

from ..closed_forms.lj import scaled_traction_slope
from ..closed_forms.reference import (
    jkr_compressive_radius_at,
    jkr_displacement,
    jkr_radius_at_approach,
)
from ..plumbing.errors import ContinuationError, InputError
from ..solids.bem import BoussinesqSurface, radial_grid
from .continuation import correct_at_delta
from .landing import land, peel
from .paths import GridMoves
from .surface import TIP_GAP, LJSurface, SurfaceShape

#: A landing on moving grids: descent stages of LANDING_STAGE iterations (or a peel), at most
#: MAX_STAGES grids (a jump-out at μ = 50 peels across a few hundred). docs/methods.md §12.
LANDING_STAGE, MAX_STAGES = 100, 2000
#: A grid fits a state while its edges lie within FIT bands of its centre; a new one is centred
#: AHEAD bands beyond moving edges; STILL: an edge that moved less is still. §12; test_tracking.py.
FIT, AHEAD, STILL = 0.75, 0.65, 0.05
#: The FE's FIT and AHEAD (its grids are cheap, so fewer save little). docs/methods.md §12;
#: test_near_events.py::test_events_near_each_event_are_the_whole_finer_solves.
FE_FIT, FE_AHEAD = 0.5, 0.4
_STIFFEST_SLOPE = float(scaled_traction_slope(TIP_GAP))


#: Jumps land from JKR's guess (`EdgeGrids.landing_guess`) from μ = GUESS_MU, its gap GUESS_GAP
#: (ε) off 1 so that its ā_c is JKR's radius. docs/methods.md §12; test_tracking.py.
GUESS_MU, GUESS_GAP = 5.0, 1e-3


def spring_ratio(gap):
    """How much longer than at the stiffest destabilising gap (1.399 ε) an element may be at
    `gap` (in ε) and still be stable on its own: max dp̄/dh / (dp̄/dh at the gap), ≥ 1, growing
    like gap⁴/6, unbounded (1e12) below 3^(1/6) ε where the springs stabilise. An element of
    a grid is unstable on its own where its LJ springs, ∝ μ^(3/2) (dp̄/dh) × its length, outgrow
    its elastic stiffness; on a grid coarse there it snaps on its own (a spurious second
    equilibrium at the same δ̄o, outside the edge)."""
    return _STIFFEST_SLOPE / np.maximum(scaled_traction_slope(gap), 1e-12 * _STIFFEST_SLOPE)


def edge_grid(edge, tip, gap, *, h, band, r_max, growth=0.1, h_inside):
    """Radial nodes from 0 to ≥ r_max (r in √(Rε)): spacing h within `band` of the contact
    radius `edge` (ā_c) and of the crack `tip` (`LJSurface.crack_tip`); elsewhere element sizes
    grow by at most (1 + growth) per element away from those bands, stay below h times the
    `spring_ratio` of gap(r) (a callable: the gap in ε at radius r) and, inside the tip, below
    `h_inside`."""
    if not (0.0 < h <= band and 0.0 <= edge <= tip and tip + band < r_max and h <= h_inside):
        raise InputError(f"need 0 < h <= band, h <= h_inside, 0 <= edge <= tip < r_max - band; "
                         f"got h={h}, band={band}, edge={edge}, tip={tip}, r_max={r_max}, "
                         f"h_inside={h_inside}")

    def size(r):
        distance = max(min(abs(r - edge), abs(r - tip)) - band, 0.0)
        cap = h_inside if r < tip else np.inf
        return min(h + growth * distance, cap, h * float(spring_ratio(gap(r))))

    nodes, last = [0.0], np.inf
    while nodes[-1] < r_max:
        last = min(size(nodes[-1]), (1.0 + growth) * last)
        nodes.append(nodes[-1] + last)
    return np.asarray(nodes)


class EdgeGrids:
    """The surfaces of one curve: the uniform pre-contact grid and grids fine at a contact
    radius and crack tip, each an `LJSurface` on the `ElasticSurface` `elastic_on(nodes)`, built
    on demand: by default the boundary integral on those nodes (`BoussinesqSurface`); for the FE
    its half-space's surface restricted to them (`solids.fe.HalfSpace.restricted`), that
    half-space being `elastic` (kept for field output; None for the boundary integral).

    h, band, h_inside, growth: as `edge_grid`; contact_h, contact_r: spacing and extent of the
    uniform pre-contact grid; r_max: the traction radius; fit, ahead: the reach of a grid and
    the lead of the next, in bands (None: FIT and AHEAD; the FE's are FE_FIT and FE_AHEAD).
    Counters: `regrids` (grids built), `largest_nodes`, `dofs` (the unknowns of the largest
    solid).
    """

    follows_edge = True

    def __init__(self, mu, *, h, band, h_inside, contact_h, contact_r, r_max, growth=0.1,
                 radius_ratio=None, elastic_on=BoussinesqSurface, elastic=None, fit=None,
                 ahead=None):
        fit, ahead = FIT if fit is None else fit, AHEAD if ahead is None else ahead
        if not 0.0 <= ahead < fit <= 1.0:
            raise InputError(f"need 0 <= ahead < fit <= 1 (in bands); got ahead={ahead}, "
                             f"fit={fit}")
        self.mu, self.h, self.band, self.h_inside = mu, h, band, h_inside
        self.fit, self.ahead = fit, ahead
        self.r_max, self.growth, self.radius_ratio = r_max, growth, radius_ratio
        self.elastic_on, self.elastic, self.dofs = elastic_on, elastic, 0
        # surface → (its centre: the (ā_c, tip) of its fine bands, the edges of the state it
        # was built for)
        self._built_for = weakref.WeakKeyDictionary()
        self.start = self._surface(radial_grid(h=contact_h, r_fine=contact_r, r_max=r_max,
                                               growth=growth), (0.0, 0.0), (0.0, 0.0))
        self.regrids, self.largest_nodes = 0, self.start.r_nodes.size

    def _surface(self, nodes, centre, edges):
        elastic = self.elastic_on(nodes)
        self.dofs = max(self.dofs, elastic.dofs)
        surface = LJSurface(elastic, self.mu, radius_ratio=self.radius_ratio)
        self._built_for[surface] = centre, edges
        return surface

    def _edges(self, surface, w, delta):
        """(ā_c, crack tip) of the state (w, δ̄o); (0, 0) without contact or with a tip inside
        the band (a neck about to detach stays on the pre-contact grid: moved to a grid built
        for so small a tip, the neck's gaps can come out negative)."""
        tip = surface.crack_tip(w, delta)
        return (surface.contact(w, delta)[1], tip) if tip > self.band else (0.0, 0.0)

    def fits(self, surface, w, delta):
        """Whether `surface` resolves the state (w, δ̄o) as a grid built for it would: without a
        crack tip (`LJSurface.crack_tip`) the pre-contact grid, else the grid of an ā_c and a tip
        each within `fit` × band of this state's (a surface not built here never fits)."""
        return self._within(surface, w, delta, self.fit * self.band)

    def admits(self, surface, w, delta):
        """Whether `surface` still resolves the state (w, δ̄o), if no longer centred on it:
        its ā_c and tip within a band of those it was built for (inside its fine zones). A step
        beyond is retried shorter (`continuation.follow`): its edge would lie on coarse
        elements, where the curve ripples and shows false folds (from which a landing comes back
        to the same branch)."""
        return self._within(surface, w, delta, self.band)

    def _within(self, surface, w, delta, reach):
        """No contact on the pre-contact grid, or ā_c and tip within `reach` of those the
        surface was built for; False for a surface not built here."""
        built, edges = self._built_for.get(surface, (None,))[0], self._edges(surface, w, delta)
        if built is None or built[1] == 0.0 or edges[1] == 0.0:
            return built is not None and built[1] == edges[1]
        return max(abs(edges[0] - built[0]), abs(edges[1] - built[1])) <= reach

    def _fits_at(self, surface, delta, w):
        """`fits`, its state's w last (for `peel`)."""
        return self.fits(surface, w, delta)

    def _tip_in_band_or_beyond(self, surface, delta, w):
        """Whether the crack tip of the state (w, δ̄o) has not receded below the fine band of
        `surface`'s tip (for `land`): below it the elements grow up to h_inside, and a neck
        narrower than they are is not resolved (BEM `draft`, μ = 50: a jump-out's descent drew
        the tip from 0.61 to 0.059 √(Rε) on elements of 0.1 √(Rε), a node's gap fell to −1.3 ε
        between positive gaps at the quadrature points, and moved to the next grid the landing
        diverged). Always true on the pre-contact grid. Not pinned by a test (that run is in
        `benchmarks/large_mu.py --large`; `landing.land`'s stop is:
        test_bem_curve.py::test_a_descent_stops_at_the_first_iterate_its_grid_no_longer_resolves)."""
        built = self._built_for[surface][0][1]
        return built == 0.0 or surface.crack_tip(w, delta) >= built - self.band

    def _tips(self, surface):
        """(lowest, highest) crack tip that `surface` fits (`fits`): within `fit` × band of the
        tip it was built for and beyond the band (a smaller one counts as no contact); on the
        pre-contact grid, up to the band."""
        tip, reach = self._built_for[surface][0][1], self.fit * self.band
        if tip == 0.0:
            return 0.0, self.band
        return max(tip - reach, self.band) * (1.0 + 1e-12), (tip + reach) * (1.0 - 1e-12)

    def _grid(self, surface, w, delta, edges, centre):
        """Nodes of the grid centred at the (ā_c, tip) `centre` for the state (w, δ̄o) with its
        `edges`; the elements away from the band are sized for the gaps as if the tip had moved
        to `fit` × band either side of the centre (the smaller `spring_ratio` of the two), so the
        grid holds while it fits."""
        gaps = delta + surface.node_profile - w
        r, offset, reach = surface.r_nodes, centre[1] - edges[1], self.fit * self.band
        smaller = np.minimum(np.interp(r - (offset - reach), r, gaps),
                             np.interp(r - (offset + reach), r, gaps))

        def gap(radius):
            return np.interp(radius, r, smaller)

        return edge_grid(*centre, gap, h=self.h, band=self.band, r_max=self.r_max,
                         growth=self.growth, h_inside=self.h_inside)

    def _ahead(self, surface, edges):
        """Where to centre the next grid: each of `edges` moved `ahead` × band further in the
        direction it moved since `surface`'s grid was built (not if it moved less than STILL ×
        band, nor from the pre-contact grid), ā_c kept within [0, tip]. From the edges of the
        state the grid was built for, not from its centre: measured from a centre placed
        ahead, an edge slower than the other seems to move back, and the grids alternate
        (BEM `draft`, μ = 20: 422 grids instead of 64 after the jump-in)."""
        built = self._built_for.get(surface, (None, None))[1]
        if built is None or built[1] == 0.0:
            return edges

        def on(now, then):
            moved = now - then
            return now + (self.ahead * self.band * np.sign(moved)
                          if abs(moved) > STILL * self.band else 0.0)

        tip = on(edges[1], built[1])
        return float(min(max(on(edges[0], built[0]), 0.0), tip)), float(tip)

    def land(self, surface, w, delta, *, tol=1e-9):
        """(surface, w, Newton iterations): the stable state at δ̄o downhill from w
        (`landing.land`), on the grid of its contact edge and crack tip. In stages: LANDING_STAGE
        iterations of descent, or, after a descent stage that did not converge, a `peel` of the
        crack tip the way the descent moved it, on one grid. Whenever the iterate no longer fits
        its grid (a landing's contact spreads beyond it) it moves to the grid of its edges (w
        interpolated linearly); a descent stage ends early where the crack tip recedes below
        its grid's band (`_tip_in_band_or_beyond`). Raises ContinuationError if MAX_STAGES
        stages do not get there."""
        iterations, peeling, stalled = 0, 0.0, False
        for _ in range(MAX_STAGES):
            if not self.fits(surface, w, delta):
                surface, w = self.move(surface, w, delta)
            if peeling:
                tip = surface.crack_tip(w, delta)
                peeled = peel(surface, w, delta, peeling, h=self.h, max_step=0.5 * self.band,
                              tips=self._tips(surface),
                              fits=partial(self._fits_at, surface, delta))
                w, iterations = peeled.w, iterations + peeled.iterations
                # A peel that left its grid goes on on the next, unless neither it nor the one
                # before moved the tip: at the band's end (a tip inside it counts as no
                # contact) the next grid would stop it again.
                moved = surface.crack_tip(w, delta) != tip
                if peeled.left and (moved or not stalled):
                    surface, w = self.move(surface, w, delta)
                else:
                    peeling = 0.0
                stalled = not moved
                continue
            tip = surface.crack_tip(w, delta)
            landed = land(surface, w, delta, tol=tol, max_iterations=LANDING_STAGE,
                          resolved=partial(self._tip_in_band_or_beyond, surface, delta))
            w, iterations = landed.w, iterations + landed.iterations
            if not np.all(np.isfinite(w)):
                raise ContinuationError(f"the landing at δ = {delta:.6g} diverged")
            if landed.converged and self.fits(surface, w, delta):
                return surface, w, iterations
            if not landed.converged and tip > 0.0:
                peeling = float(np.sign(surface.crack_tip(w, delta) - tip))
        raise ContinuationError(f"no stable state on a grid that fits it at δ = {delta:.6g} "
                                f"({MAX_STAGES} stages of landing)")

    def landing_guess(self, surface, delta, *, into_contact):
        """(surface, w): a state near where a jump at large μ (from GUESS_MU on) from a state on
        `surface` lands at δ̄o, to land from instead of the fold (not in equilibrium: `land`
        it), or None. `into_contact` (a jump in, from the pre-contact grid): JKR's contact at δ̄o
        (`reference.jkr_displacement`, the gap just below 1 ε inside its compressive radius and
        just above out to its radius) on the grid of its edges; the contact the jump lands in is
        JKR's but for the cohesive zone, and the descent from the fold crawls (BEM `draft`, μ =
        50: 4251 iterations in 22.8 s from the fold, 118 in 2.0 s from JKR's contact, P̄ 6.8e-9
        apart); None where JKR has no contact wider than the band at δ̄o. Else (a jump out, from
        a grid of the edges): the undeformed surface on the pre-contact grid, where δ̄o leaves it
        without a crack tip; from the fold the descent peels the neck across many grids.
        test_tracking.py::test_jumps_land_from_the_guesses_where_the_descent_lands."""
        if self.mu < GUESS_MU or (surface is self.start) != into_contact:
            return None
        if not into_contact:
            return (self.start, np.zeros(self.start.r_nodes.size)) if delta > TIP_GAP else None
        radius = jkr_radius_at_approach(approach=1.0 - delta, mu=self.mu)
        if not radius > self.band:  # nan: no JKR contact
            return None
        compressive = jkr_compressive_radius_at(radius=radius, mu=self.mu)
        # the start grid's nodes, and the grid's spacing within a band of either radius
        count = np.ceil(self.band / self.h)
        steps = self.h * np.arange(-count, count + 1)
        nodes = np.union1d(self.start.r_nodes, np.r_[compressive + steps, radius + steps])
        shape = SurfaceShape(nodes[nodes >= 0.0], radius_ratio=self.radius_ratio)
        # the gap inside from the surface's own profile (JKR's is Derjaguin's parabola)
        gap = np.where(shape.r_nodes < compressive, 1.0 - GUESS_GAP, 1.0 + GUESS_GAP)
        w = np.where(shape.r_nodes <= radius, delta + shape.node_profile - gap,
                     -jkr_displacement(shape.r_nodes, radius=radius, mu=self.mu))
        return self.move(shape, w, delta)

    def regrid(self, surface, w, delta, *, tol=1e-9):
        """(surface, w, Newton iterations): the equilibrium (w, δ̄o) of a branch, which
        `surface` no longer fits, solved again on the grid of its edges: by Newton at its δ̄o
        (`continuation.correct_at_delta`) from w interpolated there, where that converges to a
        stable state the grid fits (a few iterations), else by `land` (BEM `draft`, μ = 35: all 128
        moves by Newton, 397 iterations where `land`'s descent took about 1500, the same events
        and moves to the bit; test_tracking.py::test_a_branch_moved_to_the_next_grid_is_solved_
        there_as_the_descent_solves_it)."""
        if not self.fits(surface, w, delta):
            surface, w = self.move(surface, w, delta)
        solved = correct_at_delta(surface, w, delta, tol=tol)
        if solved is not None and solved[3].stable and self.fits(surface, solved[0], delta):
            return surface, solved[0], solved[2]
        surface, w, iterations = self.land(surface, w, delta, tol=tol)
        return surface, w, iterations + (0 if solved is None else solved[2])

    def transplant(self, nodes, w, delta):
        """(surface, w): the state (w, δ̄o), given on the radial `nodes` of a grid that may no
        longer exist (or another discretisation's), moved to the grid of its edges here (w
        interpolated linearly; not in equilibrium there: `land` it)."""
        return self.move(SurfaceShape(nodes, radius_ratio=self.radius_ratio), w, delta)

    def summary(self, moves):
        """How many grids followed the edge, their largest size, and from the path's `moves`
        (`paths.GridMoves`) the largest move's |ΔP̄| and |Δā_c| and the largest |Δδ̄o| of a fold
        found again elsewhere: a clause of the curve's message (`result.noted`)."""
        return (f"{self.regrids} grids followed the contact edge (at most "
                f"{self.largest_nodes} nodes), moving a state to a new grid changed P̄ by at "
                f"most {moves.force:.1e} and ā_c by at most {moves.radius:.1e}, and a fold's "
                f"δ̄o by at most {moves.fold:.1e}")

    def move(self, surface, w, delta, *, centre=None):
        """(surface, w) of the state (w, δ̄o) moved to the grid of its edges (the pre-contact
        grid without contact), centred ahead of them as they move (`_ahead`), or on the
        (ā_c, tip) `centre` given (ā_c kept within [0, tip]), w interpolated linearly (not in
        equilibrium there)."""
        edges, new = self._edges(surface, w, delta), self.start
        if edges[1] > 0.0:
            centre = (self._ahead(surface, edges) if centre is None
                      else (float(min(max(centre[0], 0.0), centre[1])), float(centre[1])))
            if centre[1] + self.band >= self.r_max:  # no grid of this traction radius holds it
                raise ContinuationError(f"the crack tip ({edges[1]:.4g} sqrt(R eps)) left the "
                                        f"traction radius {self.r_max:g} at δ = {delta:.6g}; "
                                        "the discretisation is too coarse for this mu")
            new = self._surface(self._grid(surface, w, delta, edges, centre), centre, edges)
        self.regrids += 1
        self.largest_nodes = max(self.largest_nodes, new.r_nodes.size)
        return new, np.interp(new.r_nodes, surface.r_nodes, w)


class FixedGrid:
    """The one surface of a curve on a fixed mesh or grid (FE, uniform BEM): nothing moves.

    elastic: the `ElasticSurface` behind it (kept for field output); start: its `LJSurface`."""

    follows_edge = False

    def __init__(self, elastic, mu, *, radius_ratio=None):
        self.elastic = elastic
        self.start = LJSurface(elastic, mu, radius_ratio=radius_ratio)
        self.dofs, self.largest_nodes = elastic.dofs, elastic.r_nodes.size

    def fits(self, surface, w, delta):
        return True

    def transplant(self, nodes, w, delta):
        """(surface, w): the state given on the radial `nodes` moved to this grid (w interpolated
        linearly; not in equilibrium there: `land` it)."""
        return self.start, np.interp(self.start.r_nodes, nodes, w)

    def admits(self, surface, w, delta):
        return True

    def land(self, surface, w, delta, *, tol=1e-9):
        """(surface, w, Newton iterations) of `landing.land`; ContinuationError if it fails."""
        landed = land(surface, w, delta, tol=tol)
        if not landed.converged:
            raise ContinuationError(f"no stable state found downhill at δ = {delta:.6g}")
        return surface, landed.w, landed.iterations

    def landing_guess(self, surface, delta, *, into_contact):
        """None: on one grid a jump lands downhill from its fold (as a rule at small μ, where
        the descent is short and JKR's contact not the one it lands in)."""
        return None

    def regrid(self, surface, w, delta, *, tol=1e-9):
        """`land` (a state never leaves a fixed grid, so this is not called)."""
        return self.land(surface, w, delta, tol=tol)

    def summary(self, moves):
        """Nothing to add to a curve's message: no state moves."""
        return ""


@runtime_checkable
class Grids(Protocol):
    """The surfaces a path runs on, for `branches.stable_paths`: one (`FixedGrid`) or many
    built as the contact edge moves (`EdgeGrids`).

    start: the `LJSurface` of the first state (far from contact). elastic: the solid behind the
    surfaces, kept for field output (the FE `HalfSpace`, or the one boundary-integral surface
    of a fixed grid); None for boundary-integral grids that follow the edge.
    fits(surface, w, δ̄o): the surface resolves the state as well as one built for it.
    admits(...): it still resolves it (a continuation step beyond is retried shorter).
    land(surface, w, δ̄o, tol=...): (surface, w, iterations) of the stable state downhill, on a
    surface that fits it. regrid(surface, w, δ̄o, tol=...): (surface, w, iterations) of a
    branch's equilibrium that `surface` no longer fits, solved again on one that fits it (by
    Newton where it can: stable, not necessarily downhill).
    landing_guess(surface, δ̄o, into_contact=...): (surface, w) of a state near where a jump
    from a state on `surface` lands, to land from instead, or None (then it lands from the
    fold).
    transplant(nodes, w, δ̄o): (surface, w) of a state given on other radial nodes, moved
    here. summary(moves): a clause for the curve's message, with the path's `paths.GridMoves`.
    follows_edge: whether the grids move with the contact edge. dofs, largest_nodes: the cost
    of the largest solid used.
    """

    start: LJSurface
    elastic: object
    follows_edge: bool
    dofs: int
    largest_nodes: int

    def fits(self, surface: LJSurface, w: np.ndarray, delta: float) -> bool: ...

    def admits(self, surface: LJSurface, w: np.ndarray, delta: float) -> bool: ...

    def land(self, surface: LJSurface, w: np.ndarray, delta: float, *,
             tol: float) -> tuple[LJSurface, np.ndarray, int]: ...

    def regrid(self, surface: LJSurface, w: np.ndarray, delta: float, *,
               tol: float) -> tuple[LJSurface, np.ndarray, int]: ...

    def landing_guess(self, surface: LJSurface, delta: float, *,
                      into_contact: bool) -> tuple[LJSurface, np.ndarray] | None: ...

    def transplant(self, nodes: np.ndarray, w: np.ndarray,
                   delta: float) -> tuple[LJSurface, np.ndarray]: ...

    def summary(self, moves: GridMoves) -> str: ...
