"""FE approach/retraction curves against independent references (draft meshes)."""

import numpy as np
import pytest

from fem_asperity import InputError
from fem_asperity.closed_forms.lj import bradley_force, centre_deflection
from fem_asperity.solids.fe import Solid
from fem_asperity.solver.solve import solve_curve


def wu_pull_off(mu):
    """Wu's fit (eq. 2) with the paper's constant 1.98, written out here independently of `laws`."""
    c = 1.98 * mu**1.5
    return -(7.0 + (1.0 - c) / (1.0 + c)) / 8.0


_CACHE = {}


def curve(mu, **kwargs):
    key = (mu, tuple(sorted(kwargs.items())))
    if key not in _CACHE:
        _CACHE[key] = solve_curve(mu, accuracy=kwargs.pop("accuracy", "draft"),
                                  error_estimate=False, **kwargs)
    return _CACHE[key]


def test_rigid_limit_follows_bradley_and_eq4():
    eq = curve(0.01).equilibrium
    far = eq.delta > 0.9
    # eq. 8 neglects the deflection h̄o ≤ 4.4e-3 (eq. 4 at μ = 0.01): allow 5e-3 in P̄.
    np.testing.assert_allclose(eq.p[far], bradley_force(eq.delta[far]), atol=5e-3)
    gap = eq.x > 1.0
    deflection = eq.delta[gap] - eq.x[gap]
    np.testing.assert_allclose(deflection, centre_deflection(eq.x[gap], mu=0.01), rtol=5e-3)


@pytest.mark.parametrize("mu", [0.1, 1.0, 3.0])
def test_pull_off_matches_wu(mu):
    assert curve(mu).events.p_off == pytest.approx(wu_pull_off(mu), rel=0.02)


@pytest.mark.slow
def test_pull_off_converges_under_refinement():
    values = [curve(1.0, accuracy=a).events.p_off for a in ("draft", "default", "fine")]
    assert abs(values[2] - values[1]) < abs(values[1] - values[0])
    assert abs(values[2] - values[1]) < 1e-4 * abs(values[2])


def test_no_jump_at_small_mu_and_paths_coincide():
    result = curve(0.2)
    assert result.events.jump_in is None and result.events.jump_out is None
    assert result.equilibrium.stable.all()
    a, r = result.approach, result.retraction
    np.testing.assert_allclose(np.interp(a.delta, r.delta, r.p), a.p, atol=1e-12)
    assert result.events.p_off == pytest.approx(result.events.p_max, rel=1e-12)


@pytest.mark.slow
def test_jump_in_and_hysteresis_at_mu_2():
    result = curve(2.0)
    ev = result.events
    assert ev.jump_in is not None and ev.jump_out is not None
    assert ev.jump_out.delta > ev.jump_in.delta  # hysteresis loop
    assert ev.jump_in.p_after < ev.jump_in.p_before  # snaps into stronger attraction
    assert ev.jump_out.p_after > ev.jump_out.p_before  # snaps off to weak attraction
    assert ev.jump_in.x_before > 1.0 and ev.jump_in.x_after < ev.jump_in.x_before
    assert result.equilibrium.stable.all()  # only the stable branches were traced
    assert (~curve(2.0, unstable_branch=True).equilibrium.stable).any()  # the whole S-curve
    # between the two jumps approach and retraction are on different branches
    mid = 0.5 * (ev.jump_in.delta + ev.jump_out.delta)
    a, r = result.approach, result.retraction
    on_approach = np.interp(mid, a.delta[a.branch == 0][::-1], a.p[a.branch == 0][::-1])
    on_retraction = np.interp(mid, r.delta[r.branch == 0], r.p[r.branch == 0])
    assert on_retraction < on_approach - 0.05


def test_events_are_consistent():
    ev = curve(1.0).events
    assert ev.p_max <= ev.jump_in.p_after <= ev.jump_in.p_before < 0.0
    assert ev.delta_o_star <= ev.jump_in.delta
    assert 0.0 < ev.a_c


def test_derjaguin_profile_matches_exact_sphere_at_large_radius():
    derjaguin = curve(1.0).events
    sphere = curve(1.0, radius_ratio=1e6).events
    assert sphere.p_off == pytest.approx(derjaguin.p_off, rel=1e-4)
    small = curve(1.0, radius_ratio=20.0).events
    assert abs(small.p_off - derjaguin.p_off) > 1e-3


def test_homogeneous_layer_reproduces_half_space():
    plain = curve(1.0).events
    layered = curve(1.0, solid=Solid(layer_thickness=0.8)).events
    assert layered.p_off == pytest.approx(plain.p_off, rel=2e-3)
    assert layered.jump_in.delta == pytest.approx(plain.jump_in.delta, rel=2e-3)


def test_error_estimate_and_provenance():
    result = solve_curve(0.2, accuracy="draft")
    rec = result.records()
    assert rec["method"] == "fem" and rec["accuracy"] == "draft"
    assert rec["error_estimate"]["p_off"] is not None and rec["error_estimate"]["x_oc"] is None
    assert rec["dofs"] > 1000 and rec["newton_iterations"] > rec["points"] > 10
    assert rec["wall_s"] > 0.0


def test_bad_input():
    with pytest.raises(InputError, match="mu"):
        solve_curve(0.0)
    with pytest.raises(InputError, match="accuracy"):
        solve_curve(1.0, accuracy="best")
    with pytest.raises(InputError, match="radius_ratio"):
        solve_curve(1.0, radius_ratio=2.0)
    with pytest.raises(InputError, match="estimate_by"):
        solve_curve(1.0, estimate_by="richardson")
    for other in (dict(method="bem"), dict(solid=Solid(layer_thickness=0.5))):
        with pytest.raises(InputError, match="homogeneous half-space"):
            solve_curve(1.0, estimate_by="bem", **other)


def test_a_saved_result_records_every_input_the_version_and_the_revision():
    """result.json tells a layered curve from a homogeneous one, and names the code."""
    import json

    import fem_asperity
    from fem_asperity.plumbing.revision import solver_revision
    from fem_asperity.solver.result import curve_files

    solid = Solid(layer_thickness=0.5, layer_modulus_ratio=0.5)
    result = solve_curve(0.3, accuracy="draft", solid=solid, error_estimate=False)
    saved = json.loads(curve_files(result)["result.json"])
    assert saved["inputs"]["solid"] == {"nu": 0.3, "layer_thickness": 0.5,
                                        "layer_modulus_ratio": 0.5, "layer_nu": 0.3}
    assert saved["inputs"]["profile"] == "derjaguin" and saved["inputs"]["radius_ratio"] is None
    assert saved["inputs"]["control"] == "displacement" and saved["inputs"]["p_end"] == 1.0
    assert saved["version"] == fem_asperity.__version__
    assert saved["solver_revision"] == solver_revision() and len(saved["solver_revision"]) == 10


@pytest.mark.slow
def test_a_layer_the_fe_cannot_resolve_is_refused_up_front():
    """A film 100 times softer than the substrate at μ = 1 has the Tabor parameter 21.5: its
    cohesive zone needs 22000 FE surface elements; one 0.01 √(Rε) thin and 10 times softer
    needs 2.2M elements (the process was killed for memory). Each refused before the solve,
    naming why; a thin stiff layer (ratio 100) solves without ripple."""
    with pytest.raises(InputError, match="most compliant material"):
        solve_curve(1.0, accuracy="draft", solid=Solid(layer_thickness=0.5,
                                                       layer_modulus_ratio=0.01))
    with pytest.raises(InputError, match="FE mesh has"):
        solve_curve(1.0, accuracy="draft", solid=Solid(layer_thickness=0.01,
                                                       layer_modulus_ratio=0.1))
    stiff = solve_curve(1.0, accuracy="draft", error_estimate=False,
                        solid=Solid(layer_thickness=0.01, layer_modulus_ratio=100.0))
    assert stiff.status == "ok" and stiff.folds == 2


@pytest.mark.slow
def test_a_soft_film_is_meshed_for_its_own_tabor_parameter():
    """A film 10 times softer than the substrate, 0.5 √(Rε) thick, at μ = 1: meshed for the
    substrate's μ its `default` curve showed 7 folds (ripple); meshed for the film's
    Tabor parameter, 1 · 0.1^(−2/3) = 4.64, it has the physical two, and says why."""
    solid = Solid(layer_thickness=0.5, layer_modulus_ratio=0.1)
    result = solve_curve(1.0, solid=solid, error_estimate=False)
    assert result.status == "ok" and result.folds == 2
    assert "layer's Tabor parameter 4.642" in result.message
