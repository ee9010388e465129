"""The layered half-space in the boundary integral (`solids.layered`): the compliance factor
against a direct solve of the layered elasticity problem and its limits, the hat transforms
against brute-force quadrature, the k rule's convergence, the surface operator against the FE's, and
curves against the FE and in the limits of a thin and a thick layer."""

import numpy as np
import pytest
from scipy.special import j0

from fem_asperity import InputError
from fem_asperity.solids import layered
from fem_asperity.solids.bem import BoussinesqSurface, radial_grid
from fem_asperity.solids.fe import Solid
from fem_asperity.solids.layered import compliance_factor, hat_transforms
from fem_asperity.solver.presets import discretisation
from fem_asperity.solver.solve import solve_curve


def direct_compliance(kt, ratio, nu_layer, nu_substrate):
    """C(kt) from the layered boundary-value problem itself, one Hankel mode (k = 1, t = kt):
    Papkovich-Neuber potentials 2G u = ∇(φ + zψ) − 4(1−ν)ψ e_z with φ = A(z)J₀(r), ψ = B(z)J₀(r),
    z into the solid; in the layer A, B are combinations of e^{z−t} and e^{−z}, in the substrate
    of e^{−(z−t)} only; σ_zz = −1 and σ_rz = 0 on top, u_r, u_z, σ_zz, σ_rz continuous at z = t.
    Returns the surface u_z over the layer's half-space value 2/E*_layer."""
    t = kt
    g_layer = 1.0
    e_layer = 2.0 * g_layer / (1.0 - nu_layer)
    g_sub = e_layer / ratio * (1.0 - nu_substrate) / 2.0

    def rows(z, g, nu, basis):
        """(u_r, u_z, σ_zz, σ_rz) of each potential of `basis` at depth z: 4 × len(basis)."""
        out = []
        for kind, sign, shift in basis:
            e = np.exp(sign * (z - shift))
            f, df, ddf = e, sign * e, e
            zz = z - (t if shift == t and sign < 0 else 0.0)  # ψ's lever arm: local origin
            A, dA, ddA = (f, df, ddf) if kind == "A" else (0.0, 0.0, 0.0)
            B, dB, ddB = (f, df, ddf) if kind == "B" else (0.0, 0.0, 0.0)
            out.append([-(A + zz * B) / (2 * g), (dA + zz * dB - (3 - 4 * nu) * B) / (2 * g),
                        ddA + zz * ddB - 2 * (1 - nu) * dB, -(dA + zz * dB - (1 - 2 * nu) * B)])
        return np.array(out).T

    layer = [("A", 1.0, t), ("A", -1.0, 0.0), ("B", 1.0, t), ("B", -1.0, 0.0)]
    substrate = [("A", -1.0, t), ("B", -1.0, t)]
    matrix, rhs = np.zeros((6, 6)), np.zeros(6)
    top = rows(0.0, g_layer, nu_layer, layer)
    matrix[0, :4], matrix[1, :4], rhs[0] = top[2], top[3], -1.0
    matrix[2:, :4] = rows(t, g_layer, nu_layer, layer)
    matrix[2:, 4:] = -rows(t, g_sub, nu_substrate, substrate)
    amplitudes = np.linalg.solve(matrix, rhs)
    return top[1] @ amplitudes[:4] / (2.0 / e_layer)


@pytest.mark.parametrize("ratio, nu_layer, nu_substrate", [
    (0.1, 0.3, 0.3), (10.0, 0.3, 0.3), (0.01, 0.49, 0.25), (100.0, 0.2, 0.45), (1.0, 0.5, 0.2)])
def test_compliance_factor_matches_a_direct_solve(ratio, nu_layer, nu_substrate):
    for kt in (1e-3, 0.1, 0.5, 1.0, 3.0, 8.0):
        assert compliance_factor(kt, ratio, nu_layer, nu_substrate) == pytest.approx(
            direct_compliance(kt, ratio, nu_layer, nu_substrate), rel=1e-10)


def test_compliance_factor_limits():
    """One material: C ≡ 1 exactly. kt → 0: the substrate, C → M. kt → ∞: the layer, C → 1,
    with C − 1 ~ e^{−2kt}. A thin layer on a rigid substrate (M = 0) is a Winkler foundation,
    C = kt(1 − 2ν)/(2(1 − ν)²) (confined compression, w = pt/(λ + 2G)); incompressible, the
    linear term vanishes and C = (2/3)(kt)³ (the thin-film limit)."""
    kt = np.array([0.0, 1e-8, 1e-3, 0.7, 5.0, 50.0, 1e300, np.inf])
    assert np.all(compliance_factor(kt, 1.0, 0.3, 0.3) == 1.0)
    for ratio in (0.01, 0.2, 5.0, 100.0):
        assert compliance_factor(0.0, ratio, 0.35, 0.25) == pytest.approx(ratio, rel=1e-14)
        assert compliance_factor(np.inf, ratio, 0.35, 0.25) == pytest.approx(1.0, rel=1e-15)
        assert abs(compliance_factor(20.0, ratio, 0.35, 0.25) - 1.0) < 1e-13
    for nu in (0.0, 0.3, 0.45):
        winkler = 1e-4 * (1 - 2 * nu) / (2 * (1 - nu) ** 2)
        assert compliance_factor(1e-4, 0.0, nu, 0.3) == pytest.approx(winkler, rel=1e-6)
    assert compliance_factor(1e-3, 0.0, 0.5, 0.3) == pytest.approx(2 / 3 * 1e-9, rel=1e-5)


def test_hat_transforms_match_brute_force_quadrature():
    """Exact element integrals and Gauss on short ones, against a brute-force composite Gauss
    rule (20 points per piece of length 1/k at most), at wavenumbers from far below to far
    above the elements' scale."""
    nodes = radial_grid(h=0.05, r_fine=3.0, r_max=100.0, growth=0.1)
    k = np.array([0.01, 0.3, 2.0, 17.0, 35.0])
    phi = hat_transforms(nodes, k)
    x, w = np.polynomial.legendre.leggauss(20)
    for i in (0, 5, 60, len(nodes) - 2):
        hat = np.eye(len(nodes))[i]
        for q, kq in enumerate(k):
            lo, hi = nodes[max(i - 1, 0)], nodes[i + 1]
            cuts = np.unique(np.concatenate([
                np.linspace(lo, nodes[i], int(np.ceil((nodes[i] - lo) * kq)) + 2),
                np.linspace(nodes[i], hi, int(np.ceil((hi - nodes[i]) * kq)) + 2)]))
            a, b = cuts[:-1, None], cuts[1:, None]
            r = 0.5 * (a + b) + 0.5 * (b - a) * x
            ref = np.sum(0.5 * (b - a) * w * np.interp(r, nodes, hat) * j0(kq * r) * r)
            assert phi[q, i] == pytest.approx(ref, rel=1e-9, abs=1e-12 * abs(phi[:, i]).max())


def test_one_material_is_boussinesq_to_round_off():
    """A 'layer' of the substrate's own material adds nothing: the compliance is the
    homogeneous one to the last bit (C − 1 ≡ 0)."""
    nodes = radial_grid(h=0.05, r_fine=3.0, r_max=100.0, growth=0.1)
    homogeneous = BoussinesqSurface(nodes).compliance
    same = BoussinesqSurface(nodes, solid=Solid(nu=0.3, layer_thickness=0.5,
                                                layer_modulus_ratio=1.0, layer_nu=0.3))
    assert np.array_equal(same.compliance, homogeneous)


def test_correction_converges_in_the_k_rule(monkeypatch):
    """The k rule's end (K_MAX_T/t) and panel width (K_PANEL_R/r_max) are converged: extended
    by half and halved, the compliance changes by less than 1e-10 of its largest entry."""
    nodes = radial_grid(h=0.1, r_fine=3.0, r_max=100.0, growth=0.1)
    solid = Solid(nu=0.3, layer_thickness=0.5, layer_modulus_ratio=0.1, layer_nu=0.45)
    base = BoussinesqSurface(nodes, solid=solid).compliance
    monkeypatch.setattr(layered, "K_MAX_T", 1.5 * layered.K_MAX_T)
    monkeypatch.setattr(layered, "K_PANEL_R", 0.5 * layered.K_PANEL_R)
    finer = BoussinesqSurface(nodes, solid=solid).compliance
    assert np.abs(finer - base).max() < 1e-10 * np.abs(base).max()


@pytest.mark.parametrize("thickness, ratio", [(0.5, 0.1), (1.0, 5.0)])
def test_layered_operator_agrees_with_the_fe(thickness, ratio):
    """The same smooth pressure (1 − r²)² on the FE's layered mesh and on the layered boundary
    integral: the deflections agree to 3e-4 of the largest (the FE's discretisation; 2.3e-4 and
    1e-4 when this was written), from the centre to r = 5."""
    solid = Solid(nu=0.3, layer_thickness=thickness, layer_modulus_ratio=ratio, layer_nu=0.4)
    deflections = []
    for method in ("fem", "bem"):
        surface = discretisation(3.0, "default", method=method).elastic(solid)
        w = surface.deflection(np.clip(1.0 - surface.r_quad**2, 0.0, None) ** 2)
        deflections.append(np.interp([0.0, 0.5, 1.0, 2.0, 5.0], surface.r_nodes, w))
    fe, bem = deflections
    assert np.abs(fe - bem).max() < 3e-4 * abs(bem[0])


def _events(result):
    e = result.events
    return np.array([e.p_off, e.delta_oc, e.a_c])


@pytest.mark.parametrize("thickness, ratio, accuracy", [(1.0, 5.0, "default"),
                                                        (0.5, 0.3, "draft")])
def test_layered_curves_of_fe_and_bem_agree_within_their_estimates(thickness, ratio, accuracy):
    """Two independent methods for the layered contact at μ = 1, a stiff and a soft layer:
    P̄off, δ̄oc, ā_c and the jump positions agree within the sum of their error estimates."""
    solid = Solid(nu=0.3, layer_thickness=thickness, layer_modulus_ratio=ratio, layer_nu=0.3)
    fe, bem = (solve_curve(1.0, method=m, accuracy=accuracy, solid=solid)
               for m in ("fem", "bem"))
    assert fe.status == bem.status == "ok"
    for key in ("p_off", "delta_oc", "a_c", "delta_jump_in", "delta_jump_out"):
        allowed = fe.error_estimate[key] + bem.error_estimate[key]
        assert abs(fe.records()[key] - bem.records()[key]) <= allowed, key


def test_a_thick_layer_gives_the_layers_answer():
    """t → ∞: the contact sees the layer's half-space (Tabor parameter μ M^(−2/3)): at t = 500
    P̄off and ā_c are the homogeneous layer's within the error estimate. The separations keep a
    rigid sink of the surface by the substrate's far field, falling like 1/t: five times
    smaller from t = 100 to 500."""
    mu, ratio = 1.0, 0.5
    layer = solve_curve(mu * ratio ** (-2 / 3), method="bem", accuracy="draft")
    thick = {t: solve_curve(mu, method="bem", accuracy="draft",
                            solid=Solid(layer_thickness=t, layer_modulus_ratio=ratio))
             for t in (100.0, 500.0)}
    result = thick[500.0]
    for key in ("p_off", "a_c"):
        allowed = result.error_estimate[key] + layer.error_estimate[key]
        assert abs(result.records()[key] - layer.records()[key]) <= allowed, key
    sink = {t: r.events.delta_oc - layer.events.delta_oc for t, r in thick.items()}
    assert sink[100.0] / sink[500.0] == pytest.approx(5.0, rel=0.02)


@pytest.mark.slow
def test_a_thin_layer_gives_the_substrates_answer():
    """t → 0: the contact sees the substrate (μ itself). P̄off, δ̄oc and ā_c approach the
    substrate's like t: their differences fall by 1.6-2.2 times from t = 0.1 to 0.05 (1.9 when
    this was written; 0.0063 and 0.0033 in P̄off)."""
    mu, ratio = 1.0, 0.5
    substrate = _events(solve_curve(mu, method="bem", accuracy="draft", error_estimate=False))
    gaps = [np.abs(_events(solve_curve(mu, method="bem", accuracy="draft", error_estimate=False,
                                       solid=Solid(layer_thickness=t,
                                                   layer_modulus_ratio=ratio)))
                   - substrate) for t in (0.1, 0.05)]
    assert np.all((1.6 < gaps[0] / gaps[1]) & (gaps[0] / gaps[1] < 2.2))


@pytest.mark.parametrize("method", ["fem", "bem"])
def test_extreme_layers_converge_or_stop_with_a_clear_message(method):
    """At μ = 1: a stiff layer (M = 100) 999 √(Rε) thick is the layer's half-space (a rigid-like
    contact pulling off near Bradley's −1); a soft one (M = 0.01), thick or 0.01 thin, would need
    a grid sized for its Tabor parameter 21.5 (22000 FE surface elements, 35000 BEM nodes) and is
    refused before any work, naming the limit."""
    stiff = solve_curve(1.0, method=method, accuracy="draft", error_estimate=False,
                        solid=Solid(layer_thickness=999.0, layer_modulus_ratio=100.0))
    assert stiff.status == "ok" and stiff.events.p_off == pytest.approx(-0.995, abs=2e-3)
    for thickness in (999.0, 0.01):
        with pytest.raises(InputError, match="at most"):
            solve_curve(1.0, method=method, accuracy="draft", error_estimate=False,
                        solid=Solid(layer_thickness=thickness, layer_modulus_ratio=0.01))


def test_a_thin_stiff_layer_is_the_substrate():
    """A layer 100 times stiffer and 0.01 √(Rε) thin hardly changes the substrate's contact:
    P̄off within 1e-4 (FE; 8e-5 when this was written)."""
    thin = solve_curve(1.0, method="fem", accuracy="draft", error_estimate=False,
                       solid=Solid(layer_thickness=0.01, layer_modulus_ratio=100.0))
    substrate = solve_curve(1.0, method="fem", accuracy="draft", error_estimate=False)
    assert thin.status == "ok"
    assert thin.events.p_off == pytest.approx(substrate.events.p_off, abs=1e-4)


def test_pull_off_bracketing_and_jump_classification():
    """`validation.layered._judged` on hand-made rows: between the limits (within the estimates)
    or not, where in between, and the jump-in created or removed relative to the substrate."""
    from validation.layered import _judged

    def events(p_off, jump, err=1e-6):
        return {"p_off": p_off, "p_off_err": err, "jump_in": jump}

    inside = _judged({"layered": events(-0.85, True), "substrate": events(-0.9, False),
                      "layer": events(-0.8, True)})
    assert inside == {"bracketed": True, "position": pytest.approx(0.5),
                      "jump": "created (as the layer)"}
    outside = _judged({"layered": events(-0.95, False), "substrate": events(-0.9, True),
                       "layer": events(-0.8, True)})
    assert outside["bracketed"] is False and outside["position"] == pytest.approx(-0.5)
    assert outside["jump"] == "removed"
    edge = _judged({"layered": events(-0.9000015, True, 1e-6), "substrate": events(-0.9, True),
                    "layer": events(-0.8, True)})
    assert edge["bracketed"] is True and edge["jump"] == "as substrate"


def test_validation_layered_on_a_one_point_map(tmp_path, monkeypatch, capsys):
    """`python -m validation layered` end to end on a one-point map (μ = 1, t = 1, M = 0.5, draft):
    files written, the FE and the layered BEM agree within their estimates, and both put the
    pull-off of this soft layer outside the two homogeneous limits (more tensile than the
    substrate's, -0.8353, and the layer's, -0.8041: -0.8623 when this was written). Each long
    step shows its progress; a second run solves nothing (the FE check was solved every run)."""
    from validation import layered
    from validation.__main__ import main

    monkeypatch.setenv("ADHESION_CACHE", str(tmp_path / "cache"))
    for name, value in (("MUS", (1.0,)), ("THICKNESSES", (1.0,)), ("RATIOS", (0.5,)),
                        ("FE_CHECKS", ((1.0, 1.0, 0.5),)), ("ROUGH_LAYERS", ((1.0, 0.5),))):
        monkeypatch.setattr(layered, name, value)
    assert main(["layered", "--accuracy", "draft", "--out", str(tmp_path / "out")]) == 0
    folder = tmp_path / "out" / "layered"
    assert sorted(p.name for p in folder.iterdir()) == ["layered.json", "map.png", "report.md"]
    import json

    summary = json.loads((folder / "layered.json").read_text())
    (row,) = summary["rows"]
    assert row["bracketed"] is False and row["layered"]["p_off"] < row["substrate"]["p_off"]
    (check,) = summary["fe_checks"]
    assert all(check["agree"].values())
    assert check["fem"]["events"]["p_off"] < row["substrate"]["p_off"]
    rough = summary["coated_rough_surface"][0]
    assert rough["f_max_coated"] > 0 and "Layered media" in (folder / "report.md").read_text()
    err = capsys.readouterr().err
    for bar in ("homogeneous limits [", "1 layers [", "FE checks ["):
        assert any(bar in line and line.endswith("100%") for line in err.splitlines()), bar
    import fem_asperity.studies.store as store

    def solve_again(*args, **kwargs):
        raise AssertionError("solved again")

    monkeypatch.setattr(store, "solve_curve", solve_again)
    assert main(["layered", "--accuracy", "draft", "--out", str(tmp_path / "again")]) == 0
    again = json.loads((tmp_path / "again" / "layered" / "layered.json").read_text())
    assert again["fe_checks"] == summary["fe_checks"]
    assert "FE checks [" not in capsys.readouterr().err
