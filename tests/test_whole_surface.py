"""The whole-surface solver (gw.explicit): its half-space against Boussinesq and Love, one cap
against the axisymmetric boundary integral, two caps against the interacting-asperity model."""

import numpy as np
import pytest

from fem_asperity.plumbing.errors import InputError
from fem_asperity.studies.store import stored_curve
from gw.explicit.halfspace import PixelHalfSpace, love_kernel
from gw.explicit.interacting import AsperityLaw, Interacting, coupling
from gw.explicit.patch import force_beyond
from gw.explicit.topography import Topography
from gw.explicit.whole import Adhesion, resolution, solve_whole

EPS, RADIUS, DGAMMA = 0.3e-9, 100e-9, 0.05  # m, m, J/m²
UNIT = np.sqrt(RADIUS * EPS)  # √(Rε), m
FORCE = 2 * np.pi * RADIUS * DGAMMA  # N


def adhesion_at(mu):
    """E* putting the cap at Tabor parameter mu: μ³ = RΔγ²/(E*²ε³)."""
    return Adhesion(np.sqrt(RADIUS * DGAMMA**2 / (EPS**3 * mu**3)), DGAMMA, EPS)


def cap_map(pixel, width):
    """One cap z = −r²/2R centred on a square free patch `width` √(Rε) wide."""
    n = int(round(width / pixel))
    x = (np.arange(n) - n / 2 + 0.5) * pixel * UNIT
    return Topography(heights=-(x[:, None] ** 2 + x[None, :] ** 2) / (2 * RADIUS),
                      pixel=pixel * UNIT, periodic=False, source="one cap")


def test_love_kernel_is_the_pixel_integral_of_one_over_r():
    assert love_kernel(0.0, 0.0) == pytest.approx(4 * np.arcsinh(1.0), rel=1e-14)
    # far away it is 1/ρ with the pixel's second moment: 1/ρ + (1/24)(...)/ρ³, so 1e-4 at 7
    assert love_kernel(5.0, 5.0) == pytest.approx(1 / np.hypot(5, 5), rel=1e-3)
    # midpoint rule on a 200 × 200 subdivision of the pixel, at an offset of 1.5 pixels
    s = (np.arange(200) + 0.5) / 200 - 0.5
    numeric = np.mean(1 / np.hypot(1.5 - s[:, None], 0.25 - s[None, :]))
    assert love_kernel(1.5, 0.25) == pytest.approx(numeric, rel=1e-5)


def test_periodic_half_space_answers_a_cosine_traction_as_boussinesq_says():
    """p = cos(qx) on a periodic half-space: w = −(2/(E* q)) p, i.e. −c (2π/q) p in pixels."""
    n, c = 64, 0.3
    space = PixelHalfSpace.build((n, n), compliance=c, periodic=True)
    q = 2 * np.pi * 4 / n
    p = np.cos(q * np.arange(n))[:, None] * np.ones((1, n))
    assert np.allclose(space.deflection(p), -c * 2 * np.pi / q * p, atol=1e-12)
    assert abs(space.deflection(np.ones((n, n))).mean()) < 1e-12  # the mean is held at zero


def test_free_half_space_sinks_under_a_far_load_as_one_over_r():
    """One loaded pixel: the deflection 20 pixels away is c/ρ per unit Σp̄ (Boussinesq)."""
    space = PixelHalfSpace.build((48, 48), compliance=1.0, periodic=False)
    load = np.zeros((48, 48))
    load[4, 4] = 1.0
    w = space.deflection(load)
    assert w[4, 24] == pytest.approx(-love_kernel(0, 20), rel=1e-12)
    assert w[4, 24] == pytest.approx(-1 / 20, rel=2e-4)


@pytest.mark.parametrize("mu", [0.1, 1.0])
def test_one_cap_gives_the_axisymmetric_curve(mu):
    """Most tensile force on approach, jump-in and jump-out of a cap on a free patch against
    the boundary-integral curve (an independent solver, axisymmetric), the LJ force of the
    rigid cap beyond the patch added: within the two error estimates."""
    # μ = 0.1 has no jump and a cohesive zone of √(Rε): 0.2 resolves it
    width, pixel = 8.0, 0.1 if mu > 0.5 else 0.2
    reference = stored_curve(mu, method="bem", accuracy="default", error_estimate=True)
    events = reference.events
    adhesion = adhesion_at(mu)
    result = solve_whole(cap_map(pixel, width), adhesion, depth=-0.5 * EPS,
                         jump_resolution=0.005 * EPS)
    assert result.status == "ok", result.message
    f_max = result.force_max / FORCE
    f_max -= force_beyond(result.d_at_max / EPS, width=width, mu=mu, force=-f_max)
    tolerance = (result.error_estimate["force_max"] / FORCE
                 + reference.error_estimate["p_max"])
    assert f_max == pytest.approx(-events.p_max, abs=tolerance)
    assert tolerance < 0.01 * abs(events.p_max)  # and the estimate says something
    jumps = {j.kind: j.d / EPS for j in result.jumps}
    if events.jump_in is None:
        assert not jumps
        return
    coarse = solve_whole(cap_map(2 * pixel, width), adhesion, depth=-0.5 * EPS,
                         jump_resolution=0.005 * EPS, estimate=False)
    coarse_jumps = {j.kind: j.d / EPS for j in coarse.jumps}
    for kind, delta in (("in", events.jump_in.delta), ("out", events.jump_out.delta)):
        estimate = abs(jumps[kind] - coarse_jumps[kind]) + 0.005
        assert jumps[kind] == pytest.approx(delta, abs=estimate)
        assert estimate < 0.01


def test_two_caps_far_apart_are_the_interacting_model():
    """Two caps 12 √(Rε) apart on one free patch at μ = 1: each sinks the other's ground by
    2μ^1.5 P̄/r̄ (0.14 ε), which moves both jumps; the interacting-asperity model (the solved
    law, that far field) puts them within a separation step of the whole surface."""
    mu, pixel, gap = 1.0, 0.2, 12.0
    n1, n2 = int(8 / pixel), int((gap + 8) / pixel)
    x = (np.arange(n1) - n1 / 2 + 0.5) * pixel
    y = (np.arange(n2) + 0.5) * pixel
    centres = (4.0, 4.0 + gap)
    z = np.max([-(x[:, None] ** 2 + (y[None, :] - c) ** 2) / 2 for c in centres], axis=0)
    surface = Topography(heights=z * EPS, pixel=pixel * UNIT, periodic=False, source="two caps")
    whole = solve_whole(surface, adhesion_at(mu), depth=0.0, estimate=False,
                        jump_resolution=0.01 * EPS)
    law = AsperityLaw.solved(mu)
    k = coupling([n1 // 2] * 2, [int(c / pixel) for c in centres], shape=z.shape,
                 pixel=pixel, mu=mu, periodic=False)
    separations = np.arange(4.0, 0.0, -0.005)
    model = Interacting(np.zeros(2), k, law)
    approach, attached, delta = model.follow(separations)
    retraction, _, _ = model.follow(separations[::-1], attached=attached, delta=delta)
    step = 0.01 + 0.005  # the whole surface's jump resolution, the model's grid
    whole_in = [j.d / EPS for j in whole.jumps if j.kind == "in"]
    whole_out = [j.d / EPS for j in whole.jumps if j.kind == "out"]
    model_in = [d for kind, d, _ in approach.jumps if kind == "in"]
    model_out = [d for kind, d, _ in retraction.jumps if kind == "out"]
    assert len(whole_in) == len(model_in) == 2 and len(whole_out) == len(model_out) == 2
    assert np.allclose(whole_in, model_in, atol=step + 1e-9)
    assert np.allclose(whole_out, model_out, atol=step + 1e-9)
    # without the far field both jumps come later by the 0.14 ε it moves them
    alone = Interacting(np.zeros(2), 0 * k, law).follow(separations)[0]
    assert max(d for _, d, _ in alone.jumps) < min(model_in) - 0.04


def test_a_coarse_map_is_refused_naming_the_pixel_needed():
    adhesion = adhesion_at(3.0)  # c = μ^1.5 a/π: a = 0.6 √(Rε) gives 1.0
    check = resolution(cap_map(0.6, 12.0), adhesion)
    assert check.refused and check.needed_pixel < 0.6 * UNIT / 8
    with pytest.raises(InputError, match="use a pixel of at most"):
        solve_whole(cap_map(0.6, 12.0), adhesion)
    with pytest.raises(InputError, match="at least 16 pixels"):
        solve_whole(cap_map(0.2, 2.0), adhesion_at(1.0))


def test_a_periodic_summit_feels_the_lattice_of_its_images():
    """The coupling's diagonal on a periodic map: the regular part of the periodic 1/r kernel
    with the mean held at zero, the square lattice's Madelung constant −3.900265/L (pixels),
    times 2μ^1.5/ā; nothing on a free patch."""
    for n in (58, 116):
        k = coupling([0], [0], shape=(n, n), pixel=1.0, mu=1.0, periodic=True)
        assert k[0, 0] / 2 == pytest.approx(-3.900265 / n, rel=0.01)
    assert coupling([0], [0], shape=(58, 58), pixel=1.0, mu=1.0, periodic=False)[0, 0] == 0


def test_interacting_summits_tend_to_the_gw_sum_as_they_spread():
    """Ten summits at Gaussian heights (σ = 2ε), their places spread by 1, 4 and 16 on a free
    patch at μ = 1: the far field falls as 1/r, and so does the interacting model's departure
    from the sum without interaction (F̄max and the jump-in separations)."""
    law = AsperityLaw.solved(1.0)
    rng = np.random.default_rng(7)
    heights = rng.normal(0.0, 2.0, 10)
    rows, columns = rng.integers(0, 40, 10), rng.integers(0, 40, 10)
    separations = np.arange(8.0, -3.0, -0.05)
    alone = Interacting(heights, np.zeros((10, 10)), law).follow(separations)[0]
    departures = []
    for spread in (1, 4, 16):
        k = coupling(rows * spread, columns * spread, shape=(40 * spread, 40 * spread),
                     pixel=0.5, mu=1.0, periodic=False)
        path = Interacting(heights, k, law).follow(separations)[0]
        departures.append(abs(path.force.min() - alone.force.min()))
    assert departures[0] > 2 * departures[1] > 4 * departures[2]
    assert departures[2] < 0.01 * abs(alone.force.min())


def test_summits_closer_than_their_contacts_have_no_far_field_equilibrium():
    """Two summits at μ = 1 coupled by K = 5 (2μ^1.5/r̄: r̄ = 0.4 √(Rε), closer than their
    contacts): the coupled branch ends where neither summit is near its own jump-in, and the
    path stops there and says where, rather than jump one at a guess."""
    law = AsperityLaw.solved(1.0)
    path = Interacting([0.0, 0.3], 5.0 * (1.0 - np.eye(2)), law).follow(
        np.arange(5.0, -3.0, -0.1))[0]
    assert path.stopped is not None and path.stopped - 0.3 > law.jump_in + 0.5
    assert path.d.min() > path.stopped and not path.jumps


def test_a_soft_solid_starts_far_enough_to_see_its_jump_in():
    """At μ = 3 a cap jumps in from δ̄o = 4.23 (the BEM), beyond the first start (4 ε): the
    start moves out until the relaxed map keeps its distance, so the jump-in is on the path."""
    from gw.explicit.halfspace import PixelHalfSpace
    from gw.explicit.relax import LJMap
    from gw.explicit.whole import START_GAP, _far_start

    n, pixel, mu = 30, 0.2, 3.0
    x = (np.arange(n) - n / 2 + 0.5) * pixel
    space = PixelHalfSpace.build((n, n), compliance=mu**1.5 * pixel / np.pi, periodic=False)
    ljmap = LJMap(-(x[:, None] ** 2 + x[None, :] ** 2) / 2, space)
    assert ljmap.relax(START_GAP, ljmap.rest()).gap.min() < 1.5  # in contact at once
    assert _far_start(ljmap, START_GAP) == 2 * START_GAP


def test_a_jump_across_a_periodic_edge_is_one_jump():
    """One cap centred on the corner of a periodic cell jumps as the same cap centred in the
    cell does: one patch in, one out, at the same separations, centred on the corner. (The
    cell is 12 √(Rε) wide: in one 8 wide the lattice of images shrinks the jump-in at μ = 1 below
    JUMP_CHANGE.)"""
    pixel, n = 0.2, 60
    x = np.arange(n) * pixel
    corner = np.minimum(x, n * pixel - x)  # distance to the corner on the torus, √(Rε)
    middle = np.abs(x - n * pixel / 2)
    jumps = []
    for r in (corner, middle):
        z = -(r[:, None] ** 2 + r[None, :] ** 2) / 2 * EPS
        surface = Topography(heights=z, pixel=pixel * UNIT, periodic=True, source="one cap")
        jumps.append(solve_whole(surface, adhesion_at(1.0), estimate=False,
                                 jump_resolution=0.01 * EPS).jumps)
    assert [j.kind for j in jumps[0]] == [j.kind for j in jumps[1]] == ["in", "out"]
    for on_corner, in_middle in zip(*jumps):
        assert on_corner.d == in_middle.d and on_corner.area == in_middle.area
        assert np.allclose((on_corner.x, on_corner.y), 0.0, atol=1e-6 * UNIT)
        assert np.allclose((in_middle.x, in_middle.y), n / 2 * pixel * UNIT)


def test_the_convergence_tolerance_moves_the_paths_by_far_less_than_the_pixel_does():
    """Caps at Gaussian heights on a free 48² map at μ = 1: relaxed to relax.TOLERANCE and to a
    thousand times less, the force paths agree within 1e-6 of F̄max and the jumps are the same
    (the pixel's own error, |Q(a) − Q(2a)|, is ~1e-3 of F̄max)."""
    from gw.explicit import gaussian_caps, relax

    pixel = 0.2 * UNIT
    surface, _ = gaussian_caps(n=48, pixel=pixel, radius=RADIUS, sigma=2 * EPS,
                               density=6 / (48 * pixel) ** 2, seed=3, periodic=False)
    default = solve_whole(surface, adhesion_at(1.0), accuracy="draft", estimate=False)
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(relax, "TOLERANCE", 1e-3 * relax.TOLERANCE)
        tight = solve_whole(surface, adhesion_at(1.0), accuracy="draft", estimate=False)
    assert [(j.kind, j.d) for j in default.jumps] == [(j.kind, j.d) for j in tight.jumps]
    assert len(default.jumps) >= 4
    for a, b in ((default.approach, tight.approach), (default.retraction, tight.retraction)):
        assert np.array_equal(a.d, b.d)
        assert np.abs(a.force - b.force).max() < 1e-6 * default.force_max
    assert tight.cost["hessian_products"] > default.cost["hessian_products"]
