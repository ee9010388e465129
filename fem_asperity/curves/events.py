"""The events of one approach and retraction: the `Jump`s and the `Events` read off the two paths.

Units: δ̄o, x̄o in ε; P̄ in 2πRΔγ (negative = tensile); ā_c in √(εR).
"""

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Jump:
    """A jump under displacement control at δ̄o = `delta`: state before (fold) and after
    (landing)."""

    delta: float
    x_before: float
    p_before: float
    p_after: float
    a_c_after: float
    x_after: float


@dataclass(frozen=True)
class Events:
    """Characteristic values of one approach + retraction (None where an event does not occur).

    p_max, delta_oc, a_c: most tensile force on approach, its δ̄o, and ā_c there.
    delta_o_star: δ̄o of initial contact (first compressive traction) on approach.
    jump_in / jump_out: the `Jump` records; p_off, delta_off: most tensile force on retraction.
    """

    p_max: float
    delta_oc: float
    a_c: float
    delta_o_star: float | None
    p_off: float
    delta_off: float
    jump_in: Jump | None
    jump_out: Jump | None

    def records(self):
        """Flat JSON-ready dict in the command line's key names."""
        jin, jout = self.jump_in, self.jump_out
        return {
            "p_max": self.p_max,
            "delta_oc": self.delta_oc,
            "delta_o_star": self.delta_o_star,
            "a_c": self.a_c,
            "jump_in": jin is not None,
            "x_oc": jin.x_before if jin else None,
            "delta_jump_in": jin.delta if jin else None,
            "p_jump_before": jin.p_before if jin else None,
            "p_jump_after": jin.p_after if jin else None,
            "p_off": self.p_off,
            "delta_off": self.delta_off,
            "delta_jump_out": jout.delta if jout else None,
            "p_jump_out_before": jout.p_before if jout else None,
            "p_jump_out_after": jout.p_after if jout else None,
        }


#: The events an error estimate compares (`Events.records` keys): forces, separations, radii;
#: the forces just before a jump, after the jump-out and δ̄off are not estimated.
ESTIMATED = ("p_max", "delta_oc", "a_c", "delta_o_star", "x_oc", "delta_jump_in", "p_jump_after",
             "p_off", "delta_jump_out")


def parabola_vertex(t, y):
    """Abscissa and value of the vertex of the parabola through three points (t, y) (t
    increasing), the abscissa clipped to [t₀, t₂]: where the three are nearly in line the vertex
    lies far off (BEM `draft` at μ = 50 put a jump-out fold at δ̄o = −1.1e6 and stopped), and
    no sample says the curve turns there; test_curve.py."""
    a, b, c = np.polyfit(t - t[1], y, 2)
    s = float(np.clip(-b / (2.0 * a), t[0] - t[1], t[2] - t[1])) if a != 0.0 else 0.0
    return t[1] + s, (a * s + b) * s + c


def _most_tensile(path):
    """(P̄, δ̄o, ā_c) at the minimum of P̄ along `path`: the lowest sample, which is exact where
    the minimum is interior to a stable segment (`reading.refine_force_extrema` inserts it)
    and a jump's landing otherwise. (A parabola through three samples would move δ̄o by ~1e-4 where P̄
    is flat at its minimum.)"""
    i = int(np.argmin(path.p))
    return float(path.p[i]), float(path.delta[i]), float(path.a_c[i])


#: A jump whose centre gap lands within this of ε forms the contact (the traction there < 8 % of
#: its peak). docs/methods.md §12; test_curve.py::test_a_jump_that_lands_at_the_equilibrium_*.
JUMP_CONTACT = 0.01


def contact_index(path):
    """Index of the first point of the approach `path` in contact: x̄o ≤ 1, or a jump's landing
    with x̄o ≤ 1 + JUMP_CONTACT; None if there is none."""
    landings = np.nonzero(np.diff(path.branch) != 0)[0] + 1
    first = [*np.nonzero(path.x <= 1.0)[0][:1],
             *[k for k in landings if path.x[k] <= 1.0 + JUMP_CONTACT][:1]]
    return int(min(first)) if first else None


def _initial_contact(path):
    """δ̄o where the centre gap first reaches 1 on the approach path (x̄o linear in δ̄o between
    samples), or the jump's δ̄o if contact forms by the jump (`contact_index`); None if it never
    forms."""
    k = contact_index(path)
    if k is None:
        return None
    if k == 0:
        return float(path.delta[0])
    if path.branch[k] != path.branch[k - 1]:
        return float(path.delta[k])
    x0, x1 = path.x[k - 1], path.x[k]
    return float(path.delta[k - 1] + (path.delta[k] - path.delta[k - 1]) * (x0 - 1.0) / (x0 - x1))


def read_events(approach, retraction, jumps_in, jumps_out):
    """`Events` from the two displacement-control paths and their jumps: the first jump of the
    approach and the last of the retraction (a curve that ripples folds more often while its
    contact edge moves; the jump into contact comes before those folds and the separation after
    them: test_bem_curve.py::test_a_rippling_curve_is_refined_and_reports_the_physical_jumps)."""
    p_max, delta_oc, a_c = _most_tensile(approach)
    p_off, delta_off, _ = _most_tensile(retraction)
    return Events(
        p_max=p_max,
        delta_oc=delta_oc,
        a_c=a_c,
        delta_o_star=_initial_contact(approach),
        p_off=p_off,
        delta_off=delta_off,
        jump_in=jumps_in[0] if jumps_in else None,
        jump_out=jumps_out[-1] if jumps_out else None,
    )
