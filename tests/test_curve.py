"""Reading events off sampled curves (`path.curve`)."""

import numpy as np
import pytest

from fem_asperity.path.curve import parabola_vertex


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
