"""A curve's events solved again on another discretisation, traced only near each event.

The error estimate compares each event of a curve with the same event on a finer discretisation
(`solver.solve`). That finer solve need not trace the whole curve again: each event belongs to
the stable branch it lies on (an extremum of P̄, the centre gap passing 1 ε, a fold of δ̄o and
its landing), and that branch is reached from the curve's own state a few points before the
event, moved onto the finer discretisation (`Grids.transplant`) and corrected there in the
plane normal to the curve's tangent (`continuation.correct`, regular at folds too). From there
the branch is traced on the finer discretisation until as far past the event (`WINDOW` points
of the curve), the event read off as the whole solve reads it, and a jump landed again from
the finer fold. The long stretches between events (the approach into deep contact, the peel)
are not traced again.

What this cannot see: a jump the finer discretisation makes and the curve does not (a shallow
fold near the onset of jump-in); the whole finer solve
(`solver.discretised.solve_discretised`) finds those.
"""

import threading
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from ..curves.events import ESTIMATED, JUMP_CONTACT, Jump, contact_index
from ..plumbing.errors import ContinuationError
from .branches import follow_branch
from .continuation import Linearisation, correct
from .paths import GridMoves

#: Points of the curve traced again before and after each event (methods.md §13);
#: test_near_events.py.
WINDOW = 3
#: Times a window's start moves WINDOW points back where it is not stable on the finer
#: discretisation (methods.md §13). Not pinned by a test.
BACK_OFF = 3
#: Newton iterations for a state moved from another grid, four times a continuation step's
#: (methods.md §13). Not pinned by a test.
MOVED_NEWTON = 40


#: The constraint direction that makes `correct` solve for a given centre gap x̄o.
_GAP = np.array([1.0, 0.0, 0.0])


class NotNear(ContinuationError):
    """An event of the curve has no counterpart near it on the finer discretisation."""


def events_near(grids, settings, traced, branch, approach, retraction, jump_in, jump_out,
                progress=None):
    """The events of a curve solved on `grids` (the finer discretisation's `grids.Grids`, with
    its trace `settings`) near where the curve has them: a dict of the `curves.events.ESTIMATED`
    events, None where the
    curve has no such event or the finer discretisation none near it, plus 'missed' (event →
    why the finer discretisation has none near it) and the counters 'newton_iterations' and
    'windows'.

    traced: the curve's stable branches as one `continuation.Trace` (states, tangents and the
    nodes of each state); branch: their ids per point (`Curve.branch` of the equilibrium);
    approach, retraction: its displacement-control paths (`Curve`), jump_in, jump_out: its
    first and last jumps (`curves.events.Jump` or None). progress: callable(fraction of the events
    found), called as each is.
    """
    near = _Near(grids, settings, traced, np.asarray(branch))
    found, missed = dict.fromkeys(ESTIMATED), {}
    stages, done = 3 + bool(jump_in) + bool(jump_out), []  # the jumps, the extremes, δ̄o*

    def attempt(keys, compute, values=lambda result: result):
        """compute(): the `keys`' values (as `values` reads them); on a ContinuationError (none
        near, or a window that could not be followed) they stay None, the reason in missed."""
        try:
            result = compute()
        except ContinuationError as exc:
            missed.update(dict.fromkeys(keys, str(exc)))
            result = None
        else:
            found.update(zip(keys, values(result)))
        done.append(keys)
        if progress is not None:
            progress(len(done) / stages)
        return result

    # The two folds' windows are independent: the jump-out's is traced on a second thread while
    # the jump-in's is traced here (the curve they estimate has been traced by then, so its
    # thread waits; the dense factorisations release the GIL). Each thread reads the trace and
    # builds its own states; what both write is locked (the counters) or keyed apart (the
    # window cache; the grids' regrid counters, which events_near's callers do not read). The same
    # events as one after the other: test_near_events.py.
    with ThreadPoolExecutor(1) as side:
        out = jump_out and side.submit(near.jump, retraction, jump_out, land=False)
        try:
            fine_in = jump_in and attempt(
                ("x_oc", "delta_jump_in", "p_jump_after"),
                lambda: near.jump(approach, jump_in, land=True),
                lambda fine: (fine[0].x_before, fine[0].delta, fine[0].p_after))
            fine_out = jump_out and attempt(("delta_jump_out",), out.result,
                                            lambda fine: (fine[0].delta,))
        except BaseException:  # an error or Ctrl-C here: the other window ends at its next step
            near.stop.set()
            raise
    jumps = ((jump_in, fine_in), (jump_out, fine_out))
    attempt(("p_max", "delta_oc", "a_c"), lambda: near.most_tensile(approach, *jumps))
    attempt(("p_off",), lambda: near.most_tensile(retraction, *jumps)[:1])
    attempt(("delta_o_star",), lambda: (near.initial_contact(approach, jump_in, fine_in),))
    return found | {"missed": missed, "newton_iterations": near.newton_iterations,
                    "windows": near.windows}


class _Near:
    """The curve's trace and the finer grids, and the windows traced on them."""

    def __init__(self, grids, settings, traced, branch):
        self.grids, self.settings, self.traced, self.branch = grids, settings, traced, branch
        self.newton_iterations, self.windows, self._windows = 0, 0, {}
        self._counting = threading.Lock()  # windows are traced on two threads at once
        self.stop = threading.Event()  # set, a window being traced ends at its next step

    def _count(self, iterations, windows=0):
        """Add to the counters (from either thread)."""
        with self._counting:
            self.newton_iterations += iterations
            self.windows += windows

    def index(self, delta, p):
        """Index in the trace of the point with exactly this δ̄o and P̄ (a path's rows are
        copies of trace points), or None (a fold or a landing row)."""
        at = np.flatnonzero((np.asarray(self.traced.delta) == delta)
                            & (np.asarray(self.traced.p) == p))
        return int(at[0]) if at.size else None

    def _span(self, k):
        """(first, last) index of the branch of trace point k."""
        same = np.flatnonzero(self.branch == self.branch[k])
        return int(same[0]), int(same[-1])

    def _start(self, k):
        """(surface, w, δ̄o, heading) on the finer grids: trace point k moved there and corrected
        in the plane through it normal to its tangent; None if that is no stable state."""
        t = self.traced
        heading = np.asarray(t.tangents[k], dtype=float)
        anchor = np.array([t.x[k], t.delta[k], t.p[k]])
        surface, w = self.grids.transplant(t.nodes[k], t.states[k], t.delta[k])
        for _ in range(2):  # once more if the corrected state left the grid it was moved to
            solved = correct(surface, w, t.delta[k], heading, anchor, 0.0, tol=self.settings.tol,
                             max_newton=MOVED_NEWTON)
            if solved is None:
                return None
            w, delta, iterations, _ = solved
            self._count(iterations)
            if self.grids.fits(surface, w, delta):
                break
            surface, w = self.grids.transplant(surface.r_nodes, w, delta)
        # factorised afresh: the last iteration's may be an earlier iterate's, even the
        # transplanted state's, which need not be stable
        stable = Linearisation(surface, w, delta, heading).stable
        return (surface, w, delta, heading) if stable else None

    def window(self, k, before, after_delta, *, until=None):
        """The finer trace (`branches.follow_branch`) of the branch of trace point k, from
        `before` points back until δ̄o passes `after_delta` (or `until(trace)` holds) or the
        branch folds: (Trace, fold or None). Starts further back (BACK_OFF
        times) where the start is not stable on the finer discretisation. A window asked for
        twice (P̄max and P̄off at one point of a curve without jumps) is traced once."""
        key = (k, before, after_delta)
        if until is None and key in self._windows:
            return self._windows[key]
        first, _ = self._span(k)
        for attempt in range(BACK_OFF + 1):
            begin = max(first, k - before * (attempt + 1))
            start = self._start(begin)
            if start is not None or begin == first:
                break
        if start is None:
            raise NotNear(f"no stable state near δ = {self.traced.delta[k]:.6g} on the finer "
                          f"discretisation")
        surface, w, delta, heading = start
        sign = np.sign(heading[1])

        def done(tr):
            if self.stop.is_set():
                raise NotNear("stopped: the other window's thread ended with an error")
            return sign * (tr.delta[-1] - after_delta) >= 0.0 or (until is not None
                                                                 and until(tr))

        # the moves between the finer grids are not read: the estimate is the events' change
        followed = follow_branch(self.grids, GridMoves(), surface, w, delta, heading,
                                 self.settings, done, None)
        branch, fold = followed.trace, followed.fold
        self._count(branch.newton_iterations, windows=1)
        if until is None:
            self._windows[key] = branch, fold
        return branch, fold

    def _before(self, path, jump):
        """Trace index of the last stable point before `jump`'s fold on `path`."""
        rows = np.flatnonzero((path.delta == jump.delta) & (path.p == jump.p_before))
        if rows.size == 0 or rows[0] == 0:
            raise NotNear(f"the fold at δ = {jump.delta:.6g} is not on the path")
        k = self.index(path.delta[rows[0] - 1], path.p[rows[0] - 1])
        if k is None:
            raise NotNear(f"no traced point before the fold at δ = {jump.delta:.6g}")
        return k

    def jump(self, path, jump, *, land):
        """(Jump, fold values) of `jump` (a fold on `path`) on the finer discretisation: its
        branch traced from WINDOW points before the fold to as far past it. With `land` (a
        jump in) and the curve's own landing a traced point, landed (p_after, a_c_after,
        x_after) from that state moved to the finer fold's δ̄o (the same basin, without the
        descent's spreading contact over many grids); else those are the curve's."""
        k = self._before(path, jump)
        first, _ = self._span(k)
        beyond_fold = jump.delta + (jump.delta - self.traced.delta[max(first, k - WINDOW)])
        fold = self.window(k, WINDOW, beyond_fold)[1]
        if fold is None:
            raise NotNear(f"the finer discretisation does not fold near δ = {jump.delta:.6g}")
        delta, before = fold.delta, fold
        after = dict(p_after=jump.p_after, a_c_after=jump.a_c_after, x_after=jump.x_after)
        landing = self.index(jump.delta, jump.p_after) if land else None
        if landing is not None:
            t = self.traced
            surface, w = self.grids.transplant(t.nodes[landing], t.states[landing], delta)
            surface, w, iterations = self.grids.land(surface, w, delta, tol=self.settings.tol)
            self._count(iterations)
            after = dict(p_after=surface.force(w, delta), a_c_after=surface.contact(w, delta)[1],
                         x_after=surface.centre_gap(w, delta))
        return Jump(delta=delta, x_before=before.x, p_before=before.p, **after), before

    def most_tensile(self, path, *jumps):
        """(P̄, δ̄o, ā_c) at the most tensile point of `path` on the finer discretisation: the
        landing or fold of one of `jumps` ((curve's Jump, its finer (Jump, fold values))) if the
        curve has it there, else the least P̄ of its branch traced WINDOW points either side."""
        i = int(np.argmin(path.p))
        d, p = path.delta[i], path.p[i]
        for coarse, fine in jumps:
            if coarse is not None and d == coarse.delta and p in (coarse.p_after,
                                                                  coarse.p_before):
                if fine is None:
                    raise NotNear("its jump has no counterpart on the finer discretisation")
                jump, fold = fine
                if p == coarse.p_after:
                    return jump.p_after, jump.delta, jump.a_c_after
                return fold.p, jump.delta, fold.a_c
        k = self.index(d, p)
        if k is None:
            raise NotNear(f"the most tensile point at δ = {d:.6g} is not a traced point")
        _, last = self._span(k)
        branch, fold = self.window(k, WINDOW, self.traced.delta[min(last, k + WINDOW)])
        j = int(np.argmin(branch.p))
        if fold is not None or j in (0, len(branch.p) - 1):
            raise NotNear(f"the finer branch's most tensile point near δ = {d:.6g} is not "
                          f"inside its window ({'it folds there' if fold else 'at an end'})")
        return float(branch.p[j]), float(branch.delta[j]), float(branch.a_c[j])

    def initial_contact(self, approach, jump_in, fine_in):
        """δ̄o where the centre gap first reaches 1 ε on the approach, on the finer
        discretisation: the jump's if contact forms by the jump
        (`curves.events.contact_index`: it lands with x̄o ≤ 1 + JUMP_CONTACT), else the state
        with x̄o = 1 exactly (`continuation.correct` with x̄o as the constraint) on its branch,
        from the first point with x̄o ≤ 1 of the branch traced from WINDOW points before; None if
        contact never forms. (The curve's own is interpolated between samples,
        `curves.events._initial_contact`: the estimate includes that error.)"""
        i = contact_index(approach)
        if i is None:
            return None
        if i > 0 and approach.branch[i] != approach.branch[i - 1]:
            if jump_in is None or approach.delta[i] != jump_in.delta or fine_in is None:
                raise NotNear("contact forms by a jump the finer discretisation does not make")
            fine, fold = fine_in
            if not (fold.x > 1.0 and fine.x_after <= 1.0 + JUMP_CONTACT):
                raise NotNear("on the finer discretisation contact does not form by the jump")
            return fine.delta
        k = self.index(approach.delta[i], approach.p[i])
        if k is None or i == 0:
            raise NotNear("initial contact is not between two traced points")
        first, last = self._span(k)
        far = self.traced.delta[last]  # the gap may fall more slowly on the finer one
        before = WINDOW
        while True:  # back until the finer gap starts above 1 (where x̄o falls slowly)
            branch, fold = self.window(k, before, far, until=lambda tr: tr.x[-1] <= 1.0)
            inside = np.flatnonzero(np.asarray(branch.x) <= 1.0)
            if inside.size == 0:
                raise NotNear("the finer branch does not reach a centre gap of 1" +
                              (" before it folds" if fold else ""))
            if inside[0] > 0 or k - before <= first:
                break
            before *= 4
        if inside[0] == 0:
            raise NotNear("the finer branch starts at a centre gap below 1")
        j = int(inside[0])
        surface, w = self.grids.transplant(branch.nodes[j], branch.states[j], branch.delta[j])
        solved = correct(surface, w, branch.delta[j], _GAP, np.zeros(3), 1.0,
                         tol=self.settings.tol, max_newton=MOVED_NEWTON)
        if solved is None:
            raise NotNear("no state with a centre gap of 1 near the finer window's crossing")
        self._count(solved[2])
        return float(solved[1])
