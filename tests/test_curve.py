"""Reading events off sampled curves (`curves.events`)."""

import numpy as np
import pytest

from fem_asperity.curves.curve import Curve
from fem_asperity.curves.events import JUMP_CONTACT, _initial_contact, parabola_vertex


def test_parabola_vertex_of_a_parabola_is_exact():
    t = np.array([0.0, 0.7, 1.5])
    s, y = parabola_vertex(t, 2.0 * (t - 0.9) ** 2 - 3.0)
    assert s == pytest.approx(0.9, abs=1e-12) and y == pytest.approx(-3.0, abs=1e-12)


def test_parabola_vertex_of_nearly_straight_samples_stays_within_them():
    """Three samples nearly in line (the shape BEM `draft` met at a jump-out at μ = 50): the
    parabola's vertex lies ~1e9 away; the vertex returned is the end sample's."""
    t = np.array([0.0, 1.0, 2.0])
    y = np.array([0.0, -1.0, -2.0 + 1e-9])
    s, value = parabola_vertex(t, y)
    assert s == 2.0 and value == pytest.approx(y[2], abs=1e-12)


def _approach(delta, x, branch):
    n = len(delta)
    return Curve(delta=np.array(delta, float), x=np.array(x, float), p=np.zeros(n),
                 area=np.zeros(n), a_c=np.zeros(n), stable=np.ones(n, bool),
                 branch=np.array(branch))


@pytest.mark.parametrize("x_after, expected", [
    (0.98, 1.5),          # lands inside: the jump forms the contact (μ ≤ 20)
    (1.00059, 1.5),       # lands at the equilibrium spacing (μ = 50): the jump forms it too
    (1.05, -0.5 - 0.5 * 0.04 / 0.05),  # lands short of it: the centre gap crosses 1 later
])
def test_a_jump_that_lands_at_the_equilibrium_spacing_forms_the_contact(x_after, expected):
    """δ̄o* is the jump's δ̄o where the jump lands within JUMP_CONTACT of x̄o = 1, else where x̄o,
    linear between samples, reaches 1 (here from 1.04 at δ̄o = -0.5 to 0.99 at -1: -0.9)."""
    assert JUMP_CONTACT == 0.01
    approach = _approach([3.0, 2.0, 1.5, 1.5, -0.5, -1.0], [3.0, 2.0, 1.5, x_after, 1.04, 0.99],
                         [0, 0, 0, 1, 1, 1])
    found = _initial_contact(approach)
    assert found == pytest.approx(expected, abs=1e-12)


def test_without_a_jump_or_a_touch_there_is_no_initial_contact():
    assert _initial_contact(_approach([3.0, 2.0], [3.0, 2.0], [0, 0])) is None
