"""What one mean summit radius does to a map's strength (gw.explicit.radii), against Bradley's
rigid sphere summed by hand: near the rigid limit the solved law is Bradley's at every μ."""

import numpy as np
import pytest

from fem_asperity.closed_forms.lj import bradley_force
from gw.explicit.radii import own_radii
from gw.explicit.topography import Topography
from gw.explicit.whole import Adhesion

EPS, DGAMMA, PIXEL = 0.3e-9, 0.1, 2e-9


def _caps(radii, heights, n=200):
    """Caps (z = zᵢ − r²/2Rᵢ) 100 pixels apart on a free map of n² pixels."""
    x = (np.arange(n) - n / 2) * PIXEL
    X, Y = np.meshgrid(x, x, indexing="ij")
    centres = np.linspace(-50, 50, len(radii)) * PIXEL
    z = np.max([h - ((X - c) ** 2 + Y**2) / (2 * r)
                for r, h, c in zip(radii, heights, centres)], axis=0)
    return Topography(z, PIXEL)


def _spread(topography, mu, radius, d):
    """own_radii against `radius` where E* gives it Tabor parameter `mu` (μ³ = RΔγ²/(E*²ε³))."""
    adhesion = Adhesion(np.sqrt(radius * DGAMMA**2 / (mu**3 * EPS**3)), DGAMMA, EPS)
    return own_radii(topography, adhesion, d, radius=radius, mu=mu)


def _bradley_f_max(radii, heights, d):
    force = sum(2 * np.pi * DGAMMA * r * bradley_force((d - z) / EPS)
                for r, z in zip(radii, heights))
    return -force.min()


@pytest.mark.parametrize("offset", [0.0, -0.6])
def test_near_the_rigid_limit_the_summits_own_radii_sum_bradleys_forces(offset):
    """Caps of 100 and 300 nm (the mean radius, 1/mean curvature, is their harmonic mean
    150 nm) at μ = 0.02: each sum's F_max is Bradley's summed by hand (the law at μ ≤ 0.025
    within 0.5 % of the rigid one), and with equal heights the size is the ratio of the
    arithmetic to the harmonic mean less one, 1/3."""
    radii, heights = (100e-9, 300e-9), (0.0, offset * EPS)
    d = np.arange(6.0, 0.4, -0.002) * EPS
    spread = _spread(_caps(radii, heights), 0.02, 150e-9, d)
    assert spread.summits == 2
    assert spread.radii == pytest.approx(radii, rel=1e-9)
    assert spread.f_max_own == pytest.approx(_bradley_f_max(radii, heights, d), rel=5e-3)
    assert spread.f_max_one == pytest.approx(_bradley_f_max((150e-9,) * 2, heights, d),
                                              rel=5e-3)
    if offset == 0.0:
        assert spread.size == pytest.approx(1 / 3, rel=5e-3)


def test_summits_of_one_radius_have_no_spread():
    d = np.arange(5.0, -2.0, -0.05) * EPS
    spread = _spread(_caps((200e-9,) * 3, (0.0, -EPS, -2 * EPS)), 1.0, 200e-9, d)
    assert spread.size == pytest.approx(0.0, abs=1e-9)
    assert spread.mu == pytest.approx((1.0, 1.0), rel=1e-6)


def test_at_mu_one_each_summit_takes_the_law_solved_at_its_own_mu():
    """Caps of 100 and 300 nm at μ = 1 for their harmonic mean 150 nm: the summits' μ are
    (100/150)^(1/3) and 2^(1/3) (μ³ ∝ R), and the sum over them at their own radii is that of
    the laws solved (BEM default, not the table) at those μ, within the table's stated F̄max
    error; the one-radius sum likewise with the law solved at μ = 1. Jump-ins and their μ
    dependence are in both."""
    from gw.explicit.interacting import AsperityLaw

    radii, heights = (100e-9, 300e-9), (0.0, -0.7 * EPS)
    d = np.arange(5.0, -1.0, -0.01) * EPS
    spread = _spread(_caps(radii, heights), 1.0, 150e-9, d)
    mus = (1.0 * (2 / 3) ** (1 / 3), 2 ** (1 / 3))
    assert spread.mu == pytest.approx(mus, rel=1e-9)

    def f_max(laws, weights):
        force = sum(2 * np.pi * DGAMMA * r * law.approach.force((d - z) / EPS)
                    for r, law, z in zip(weights, laws, heights))
        return -force.min()

    solved = [AsperityLaw.solved(m) for m in mus]
    tolerance = 2 * spread.uncertainty
    assert spread.f_max_own == pytest.approx(f_max(solved, radii), rel=tolerance)
    one = AsperityLaw.solved(1.0)
    assert spread.f_max_one == pytest.approx(f_max([one, one], (150e-9,) * 2), rel=tolerance)
    assert spread.size > 10 * tolerance  # a spread that matters, resolved


def test_a_summit_whose_own_mu_is_outside_the_table_bounds_nothing():
    """μ ∝ R^(1/3): four caps of 3 µm and one 27 times sharper have the harmonic mean radius
    484 nm; at μ = 0.012 there, the sharp one sits at 0.0073, below the table of solved laws
    (the flat ones at 0.022, inside): no size, and the note counts the one."""
    radii = (3000e-9,) * 4 + (3000e-9 / 27,)
    d = np.arange(5.0, 0.5, -0.05) * EPS
    mean = len(radii) / sum(1 / r for r in radii)
    spread = _spread(_caps(radii, (0.0,) * 5), 0.012, mean, d)
    assert spread.size is None and spread.f_max_own is None
    assert spread.mu == pytest.approx((0.012 / 27 ** (1 / 3) * (3000e-9 / mean) ** (1 / 3),
                                       0.012 * (3000e-9 / mean) ** (1 / 3)), rel=1e-9)
    assert "1 of 5 summits have mu outside the table of solved laws' 0.01-50" in spread.note


def test_a_radius_whose_own_mu_is_outside_the_table_bounds_nothing():
    """A user's radius (gw explicit --R) far above the summits' puts its μ above the table
    though every summit's is inside: no size, the note names it."""
    d = np.arange(5.0, 0.5, -0.05) * EPS
    spread = _spread(_caps((200e-9,) * 2, (0.0, -EPS)), 60.0, 200e-6, d)
    assert spread.size is None
    assert "mu = 60 at the radius 0.0002 m is outside the table" in spread.note


def test_the_spread_is_what_the_map_solved_whole_shows():
    """Caps of 100 and 300 nm, 0.5 ε apart in height, at μ = 0.3 for their harmonic mean, far
    apart on a free map, solved whole (draft): the summits at their own radii sum to the whole
    surface within 1 % (the laws and the FFT half-space agree), and at the one radius they are
    off it by what the spread says (−30 %), within 1 % more its estimate. The interacting
    model, whose ground counted once sees the caps' own shapes rigidly, is off by less than
    the spread (13 %): for it the spread is an upper estimate."""
    from gw.explicit.answer import answer

    radii, mean, mu = (100e-9, 300e-9), 150e-9, 0.3
    adhesion = Adhesion(np.sqrt(mean * DGAMMA**2 / (mu**3 * EPS**3)), DGAMMA, EPS)
    found = answer(_caps(radii, (0.0, -0.5 * EPS)), adhesion, model="whole", accuracy="draft")
    spread, whole = found.statistics["radii"], found.whole
    estimate = whole.error_estimate["force_max"] / whole.force_max
    assert spread["f_max_own"] / whole.force_max - 1 == pytest.approx(0.0, abs=0.01 + estimate)
    assert spread["f_max_one"] / whole.force_max - 1 == pytest.approx(
        -spread["size"] / (1 + spread["size"]), abs=0.01 + estimate)
    assert spread["size"] > 0.3
    assert abs(found.relative_to_whole["interacting"]) < spread["size"]
