"""Approach and retraction of a rigid map under separation control, with its jumps.

Each separation is relaxed from the state of the one before, carried along the branch by a
secant predictor; a relaxation that lands far from the prediction has left its branch: a jump.
Its pixels are those whose gap moved from the predicted one by more than JUMP_CHANGE, grouped
into connected patches (one per asperity that jumped); the separation where it happened is
located to `jump_resolution` by bisection from the last state before it. Units as in `relax`:
d and gaps in ε, forces as Σ p̄ over the pixels (Δγ a²/ε).
"""

from dataclasses import dataclass

import numpy as np
from scipy import ndimage

from fem_asperity.closed_forms.lj import scaled_traction

#: A pixel within JUMP_RANGE (ε) of the rigid map jumped where its gap leaves the branch's
#: prediction by over JUMP_CHANGE ε (methods.md §14); test_whole_surface.py (periodic edge).
JUMP_CHANGE = 0.5
JUMP_RANGE = 3.0
#: Contact: compressive traction, gap below ε.
CONTACT_GAP = 1.0


@dataclass(frozen=True)
class Jump:
    """One patch of pixels that jumped: `kind` "in" (toward contact) or "out", between the
    separations `d_before` and `d_after` (ε), `centre` (row, column in pixels: the patch's
    centroid; on a periodic map its circular mean, `_torus_centre`), `pixels` (its size) and
    `force_change` (Σp̄ after − before)."""

    kind: str
    d_before: float
    d_after: float
    centre: tuple
    pixels: int
    force_change: float


@dataclass(frozen=True)
class RoughPath:
    """One direction of travel: `d` (ε), `force` (Σp̄, Δγ a²/ε, < 0 tensile), `contact`
    (pixels in compression), `jumps`, with `steps` and `products` (Newton steps and Hessian
    products, the cost) and `converged` (every separation relaxed to `relax.TOLERANCE`)."""

    d: np.ndarray
    force: np.ndarray
    contact: np.ndarray
    jumps: tuple
    steps: int
    products: int
    converged: bool


class _Walker:
    """Carries the state and its predecessor along a path on `ljmap`."""

    def __init__(self, ljmap, y, d):
        self.ljmap, self.y, self.d = ljmap, y, d
        self.y_before, self.d_before = None, None
        self.steps = self.products = 0
        self.converged = True

    def predicted(self, d):
        """The secant prediction of y at `d` (the state itself at the start, or where the
        prediction would put a gap below the floor)."""
        if self.y_before is None or self.d == self.d_before:
            return self.y
        guess = self.y + (self.y - self.y_before) * ((d - self.d) / (self.d - self.d_before))
        return guess if self.ljmap.admissible(guess, d) else self.y

    def relax(self, d):
        """(state, jumped): the state at `d` relaxed from the prediction (not yet accepted),
        and whether it left the branch: a gap within JUMP_RANGE moved from the prediction by
        more than JUMP_CHANGE, or by more than twice the step where there is no secant yet (the
        prediction then moves every gap by it). (Meeting an unstable state on the way is no
        sign: near a fold the prediction itself may be one.)"""
        guess = self.predicted(d)
        state = self.ljmap.relax(d, guess)
        self.steps += state.steps
        self.products += state.products
        change = _departure(self.ljmap.gap(guess, d), state.gap)
        allowed = JUMP_CHANGE
        if self.y_before is None:
            allowed = max(JUMP_CHANGE, 2.0 * abs(d - self.d))
        return state, bool(change > allowed)

    def accept(self, d, state, *, jumped=False):
        """Move to `state` at `d`; after a jump the secant starts afresh."""
        self.converged &= state.converged
        self.y_before, self.d_before = (None, None) if jumped else (self.y, self.d)
        self.y, self.d = state.y, d


def follow(ljmap, separations, y0, *, jump_resolution=None, until=None, progress=None):
    """The path of `ljmap` (`relax.LJMap`) through `separations` (ε, monotone), from the state
    `y0` → (RoughPath, last y). `jump_resolution` (ε): bisect each jump's separation down to
    it (None: the step between separations). `until(forces)`: stop after the first separation
    where it is true of the forces so far. `progress(fraction)`: called after each separation
    with the fraction of `separations` done."""
    separations = np.asarray(separations, dtype=float)
    walker = _Walker(ljmap, y0, separations[0])
    d_out, force, contact, jumps = [], [], [], []
    first = ljmap.relax(separations[0], y0)
    walker.steps, walker.products = first.steps, first.products
    walker.accept(separations[0], first)
    _record(first, separations[0], d_out, force, contact)
    for k, d in enumerate(separations[1:], start=2):
        if until is not None and until(force):
            break
        new, jumped = walker.relax(d)
        while jumped:  # each jump in the step, located and recorded in turn
            new, d_jump = _bisect(walker, d, new, jump_resolution)
            predicted = walker.ljmap.gap(walker.predicted(d_jump), d_jump)
            stayed = walker.ljmap.gap(walker.y, d_jump)  # the state before, moved by the step
            jumps.extend(_patches(predicted, stayed, new, walker.d, d_jump,
                                  periodic=ljmap.halfspace.periodic))
            if d_jump == d:
                break
            walker.accept(d_jump, new, jumped=True)  # the landing is a state of the path too
            _record(new, d_jump, d_out, force, contact)
            new, jumped = walker.relax(d)
        walker.accept(d, new, jumped=jumped)
        _record(new, d, d_out, force, contact)
        if progress is not None:
            progress(k / separations.size)
    path = RoughPath(np.array(d_out), np.array(force), np.array(contact), tuple(jumps),
                     walker.steps, walker.products, walker.converged)
    return path, walker.y


def _record(state, d, d_out, force, contact):
    d_out.append(float(d))
    force.append(float(state.traction.sum()))
    contact.append(int(np.count_nonzero(state.gap < CONTACT_GAP)))


def _bisect(walker, d, jumped, resolution):
    """(state after the jump, d where it happened): halves the step from the last state
    before the jump while it is longer than `resolution`, advancing that state wherever the
    half step stays stable."""
    if resolution is None:
        return jumped, d
    d_jump, landed = d, jumped
    while abs(d_jump - walker.d) > resolution:
        middle = 0.5 * (walker.d + d_jump)
        state, jumped = walker.relax(middle)
        if jumped:
            d_jump, landed = middle, state
        else:
            walker.accept(middle, state)
    return landed, d_jump


def _departure(predicted_gap, gap):
    """Largest |gap − predicted| (ε) over the pixels within JUMP_RANGE."""
    near = np.minimum(predicted_gap, gap) < JUMP_RANGE
    return float(np.abs(gap - predicted_gap)[near].max(initial=0.0))


def _patches(predicted_gap, stayed_gap, landed, d_before, d_after, *, periodic):
    """The jumps in one step: connected patches of pixels whose gap left the prediction by
    more than JUMP_CHANGE (within JUMP_RANGE of the map); on a `periodic` map a patch that
    crosses an edge is one patch, its centre taken on the torus. Its kind and force change are
    measured from `stayed_gap` (the state before the step, moved rigidly to the new
    separation), not from the prediction: near a fold the secant can overshoot the landing, and
    a jump-in would read as a jump-out."""
    change = landed.gap - stayed_gap
    near = np.minimum(predicted_gap, landed.gap) < JUMP_RANGE
    labels, count = ndimage.label((np.abs(landed.gap - predicted_gap) > JUMP_CHANGE) & near)
    if periodic:
        labels, count = _joined_across_edges(labels)
    jumps = []
    for k in range(1, count + 1):
        patch = labels == k
        centre = _torus_centre(patch) if periodic else tuple(
            float(c) for c in ndimage.center_of_mass(patch))
        kind = "in" if change[patch].mean() < 0.0 else "out"
        force_change = float(landed.traction[patch].sum()
                             - scaled_traction(stayed_gap[patch]).sum())
        jumps.append(Jump(kind, float(d_before), float(d_after), centre, int(patch.sum()),
                          force_change))
    return jumps


def _joined_across_edges(labels):
    """(labels, count) with the patches that touch across the map's edges (as neighbours on
    the torus, four-connected as `ndimage.label`) given one label, numbered 1…count."""
    parent = np.arange(labels.max() + 1)

    def root(k):
        while parent[k] != k:
            k = parent[k]
        return k

    for a, b in ((labels[0, :], labels[-1, :]), (labels[:, 0], labels[:, -1])):
        for i, j in zip(a, b):
            if i and j:
                parent[max(root(i), root(j))] = min(root(i), root(j))
    roots = np.array([root(k) for k in range(parent.size)])
    _, renumbered = np.unique(roots, return_inverse=True)  # 0 stays 0: roots[0] = 0
    return renumbered[labels], int(renumbered.max())


def _torus_centre(patch):
    """The centre (row, column, pixels) of a patch on a periodic map: the mean angle of its
    pixels around each axis (the circular mean), so a patch across an edge is centred on it.
    It is the centroid for a patch symmetric about it, near it otherwise (an L of pixels: 19.03
    against 19.05); for a band around the whole map it is arbitrary along the band."""
    centre = []
    for axis, n in enumerate(patch.shape):
        angle = 2.0 * np.pi * np.nonzero(patch)[axis] / n
        mean = np.arctan2(np.sin(angle).mean(), np.cos(angle).mean())
        centre.append(round(float(mean * n / (2.0 * np.pi)), 9) % n)  # −0 → 0, not n
    return tuple(centre)
