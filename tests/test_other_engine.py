"""The other engine (ContactMechanics + Adhesion, `gw.explicit.other_engine`) far from contact.

One paraboloidal cap z = −r²/2R, free boundary, Tabor μ = 0.1 (so the elastic deflection is a
fraction of a percent of ε): at d = 3ε and 5ε the force must be attractive and match

- the rigid cap's force on the same pixels (the 9-3 pressure at the undeflected gaps, summed),
  slightly exceeded, as the surface deflects toward the cap;
- Bradley's rigid-sphere force 2πRΔγ·(1/3)(δ⁻⁸ − 4δ⁻²), δ = d/ε, once the part of it that comes
  from outside the 64×64 patch (6.4 √(Rε) wide: 10-20 % of the total at these separations) is
  added back, integrated here for the rigid cap over the plane outside the square.

Runs only where ContactMechanics and Adhesion are installed (`pip install ContactMechanics
Adhesion`), e.g. `/work/cm-venv/bin/python -m pytest tests/test_other_engine.py`.
"""

import warnings

import numpy as np
import pytest
from scipy import integrate

from gw.explicit.other_engine import other_engine_forces

with warnings.catch_warnings():
    warnings.filterwarnings("ignore", message="Could not import mpi4py")  # NuMPI without MPI
    pytest.importorskip("ContactMechanics")
    pytest.importorskip("Adhesion")

EPS = 1e-9  # m
RADIUS = 100 * EPS
E_STAR = 1e9  # Pa
MU = 0.1
DGAMMA = MU**1.5 * E_STAR * np.sqrt(EPS**3 / RADIUS)  # μ = (RΔγ²/E*²ε³)^(1/3)
N = 64
PIXEL = 0.1 * np.sqrt(RADIUS * EPS)


def pressure(h):
    """The 9-3 law (Pa) at gaps h (m)."""
    return 8 * DGAMMA / (3 * EPS) * ((EPS / h) ** 9 - (EPS / h) ** 3)


def bradley(d):
    delta = d / EPS
    return 2 * np.pi * RADIUS * DGAMMA / 3 * (delta**-8 - 4 * delta**-2)


def rigid_square(d, half):
    """The rigid cap's force from the square |x|, |y| < half (continuous, not pixels)."""

    def integrand(y, x):
        return pressure(d + (x * x + y * y) / (2 * RADIUS))

    value, _ = integrate.dblquad(integrand, 0, half, 0, half, epsabs=0, epsrel=1e-10)
    return 4 * value


def test_far_field_matches_bradley():
    x = (np.arange(N) - (N - 1) / 2) * PIXEL
    heights = -(x[:, None] ** 2 + x[None, :] ** 2) / (2 * RADIUS)
    separations = np.array([5.0, 3.0]) * EPS
    out = other_engine_forces(
        heights,
        pixel=PIXEL,
        e_star=E_STAR,
        dgamma=DGAMMA,
        eps=EPS,
        separations=separations,
        periodic=False,
    )
    assert out["converged"] == [True, True]
    assert out["engine"].startswith("ContactMechanics ")
    np.testing.assert_array_equal(out["d"], separations)
    for d, force in zip(separations, out["force"]):
        assert force < 0
        on_pixels = pressure(d - heights).sum() * PIXEL**2
        assert 0.9995 < force / on_pixels < 1.02
        outside = bradley(d) - rigid_square(d, N * PIXEL / 2)
        assert force + outside == pytest.approx(bradley(d), rel=0.01)


@pytest.mark.parametrize("periodic", [False, True])
def test_the_whole_surface_solver_agrees_with_the_other_engine_on_a_rough_patch(periodic):
    """Six caps at Gaussian heights (σ = 2ε) on a 48 × 48 map, μ = 1: both engines along the
    whole approach and retraction, jumps and all, warm-started the same way. The two share the
    pixel kernel, so they agree to the solvers' tolerances (2e-7 of 2πRΔγ measured on 64²),
    far inside the pixel's own error (1e-3)."""
    from gw.explicit import Adhesion, gaussian_caps, solve_whole

    radius, mu = 300 * EPS, 1.0
    dgamma = 0.05
    e_star = np.sqrt(radius * dgamma**2 / (EPS**3 * mu**3))
    unit = np.sqrt(radius * EPS)
    surface, _ = gaussian_caps(n=48, pixel=0.2 * unit, radius=radius, sigma=2 * EPS,
                               density=6 / (48 * 0.2 * unit) ** 2, seed=3, periodic=periodic)
    ours = solve_whole(surface, Adhesion(e_star, dgamma, EPS), accuracy="draft",
                       estimate=False)
    assert ours.jumps  # the path crosses jumps, so the warm starts matter
    d = np.concatenate([ours.approach.d, ours.retraction.d])
    force = np.concatenate([ours.approach.force, ours.retraction.force])
    other = other_engine_forces(surface.heights, pixel=surface.pixel, e_star=e_star,
                                dgamma=dgamma, eps=EPS, separations=d, periodic=periodic,
                                gtol=1e-8)
    scale = 2 * np.pi * radius * dgamma
    assert np.abs(force - other["force"]).max() < 1e-5 * scale
