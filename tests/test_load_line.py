"""Load-line control (a compliant cantilever): Bradley's closed form, the rigid limit, and the
jumps a spring adds."""

import json
import subprocess
import sys

import pytest
from scipy.optimize import brentq

from fem_asperity import InputError
from fem_asperity.solver.solve import solve_curve


def bradley(d):
    """Bradley's force on a rigid sphere over a rigid flat (eq. 8), 2πRΔγ, and its slope."""
    return (d**-8 - 4 * d**-2) / 3, 8 / 3 * (d**-3 - d**-9)


def test_rigid_bodies_on_a_spring_jump_where_bradleys_slope_is_the_stiffness():
    """μ = 1e-3 (rigid to 1e-4 in the deflection): with k̄ = 0.5 the approach jumps where
    dP̄/dδ̄ = k̄ beyond the LJ equilibrium and the retraction where it is k̄ inside the
    inflection δ̄ = 3^(1/6), each at z̄ = δ̄ − P̄/k̄. z̄ is checked to 1e-4; δ̄ at a fold of z̄ is
    ill-conditioned (z̄ is flat there: an error e in z̄ moves δ̄ by about √(2e/z̄'')), so to 5e-3."""
    k = 0.5
    d_in = brentq(lambda d: bradley(d)[1] - k, 3 ** (1 / 6), 10.0)
    d_out = brentq(lambda d: bradley(d)[1] - k, 1.0, 3 ** (1 / 6))
    row = solve_curve(1e-3, method="bem", spring_constant=k, error_estimate=False).records()
    assert row["jump_in"] and row["z_jump_in"] == pytest.approx(d_in - bradley(d_in)[0] / k,
                                                                rel=1e-4)
    assert row["z_jump_out"] == pytest.approx(d_out - bradley(d_out)[0] / k, rel=1e-4)
    assert row["delta_jump_in"] == pytest.approx(d_in, rel=5e-3)
    assert row["delta_jump_out"] == pytest.approx(d_out, rel=5e-3)
    assert row["p_jump_before"] == pytest.approx(bradley(d_in)[0], rel=5e-3)
    assert row["p_off"] == pytest.approx(-1.0, rel=1e-4)  # the minimum is passed, not jumped


def test_a_stiff_spring_gives_displacement_control():
    """k̄ = 1e8 at μ = 2: the events of displacement control on the whole curve (folds to 4e-5,
    the forces after the jumps to 1e-4; the spring's folds are parabolas through samples, the
    displacement control's exact), and z̄ = δ̄o at the jumps."""
    spring = solve_curve(2.0, method="bem", accuracy="draft", spring_constant=1e8,
                         error_estimate=False).records()
    rigid = solve_curve(2.0, method="bem", accuracy="draft", unstable_branch=True,
                        error_estimate=False).records()
    for key, rel in (("p_max", 1e-9), ("delta_oc", 1e-9), ("p_off", 1e-9),
                     ("delta_jump_in", 1e-5), ("delta_jump_out", 1e-4), ("p_jump_after", 1e-5),
                     ("p_jump_out_after", 1e-3)):
        assert spring[key] == pytest.approx(rigid[key], rel=rel), key
    assert spring["z_jump_in"] == pytest.approx(spring["delta_jump_in"], abs=1e-7)
    assert rigid.get("z_jump_in") is None and spring["inputs"]["control"] == "load line"


def test_a_soft_spring_jumps_below_the_onset_and_earlier():
    """μ = 0.5 has no jump-in under displacement control (onset 0.697); on springs of k̄ = 1 and
    0.3 it jumps in, the softer one farther out (larger z̄), as an AFM cantilever does."""
    assert not solve_curve(0.5, method="bem", accuracy="draft", error_estimate=False).events.jump_in
    stiff, soft = (solve_curve(0.5, method="bem", accuracy="draft", spring_constant=k,
                               error_estimate=False).records() for k in (1.0, 0.3))
    assert stiff["jump_in"] and soft["jump_in"]
    assert soft["z_jump_in"] > stiff["z_jump_in"] and soft["z_jump_out"] > stiff["z_jump_out"]


@pytest.mark.parametrize("k", [1e-5, 1e-9])
def test_a_spring_softer_than_any_cantilever_jumps_where_bradleys_slope_is_its_stiffness(k):
    """Far out the force is a rigid sphere's, −(4/3)δ̄o⁻² (Bradley): a very soft spring jumps in
    where its slope (8/3)δ̄o⁻³ is k̄ (the solid's pull moves that by 0.05 % at k̄ = 1e-5 and
    0.24 % at 1e-9, μ = 1), and after the pull-off flies to z̄ ≈ |P̄off|/k̄, where it lands on
    that force: P̄ = k̄(δ̄o − z̄) = −(4/3)δ̄o⁻². The curve starts twice the jump-in out, not at
    1/k̄ (8e8 at k̄ = 1e-9)."""
    result = solve_curve(1.0, method="bem", accuracy="draft", spring_constant=k,
                         error_estimate=False)
    events, z = result.events, result.z_jumps
    assert events.jump_in.delta == pytest.approx((8.0 / (3.0 * k)) ** (1.0 / 3.0), rel=5e-3)
    out = events.jump_out
    assert z["z_jump_out"] == pytest.approx(out.delta - out.p_before / k, rel=1e-6)
    landed = result.retraction.delta[-1]
    assert -result.retraction.p[-1] == pytest.approx(4.0 / 3.0 * landed**-2, rel=1e-6)
    assert landed - result.retraction.p[-1] / k == pytest.approx(z["z_jump_out"], rel=1e-10)
    assert result.points < 5000


def test_a_soft_spring_lands_beyond_the_start():
    """A soft cantilever (k̄ = 0.002) lets go near Bradley's force, so the sphere flies to
    z̄ ≈ δ̄off + |P̄off|/k̄ ≈ 490, far beyond the start x̄o = 40 (the film-on-silicon AFM
    example failed there): it lands where the spring and the LJ force balance, P̄ = k̄(δ̄o − z̄),
    on the far-field force −(4/3)δ̄o⁻² of a rigid sphere."""
    k = 0.002
    result = solve_curve(0.1, method="bem", accuracy="draft", spring_constant=k,
                         error_estimate=False)
    events, z_out = result.events, result.z_jumps["z_jump_out"]
    assert z_out == pytest.approx(events.delta_off - events.p_off / k, rel=1e-3)
    after = result.retraction  # the landing point follows the jump's take-off point
    landed = next(i for i in range(1, len(after)) if after.delta[i] > 0.5 * z_out)
    # δ̄o of the landing is interpolated in z̄ between two samples, then solved: the balance holds
    # to that interpolation (6e-6 when this was written)
    assert after.p[landed] == pytest.approx(k * (after.delta[landed] - z_out), rel=1e-4)
    assert after.p[landed] == pytest.approx(-4.0 / 3.0 * after.delta[landed] ** -2, rel=1e-2)


@pytest.mark.parametrize("method, mu, k", [("bem", 2.0, 0.5), ("bem", 1.0, 2.0),
                                          ("fem", 1.0, 2.0)])
def test_the_spring_ends_jumps_are_estimated_and_the_estimates_bound_their_error(method, mu, k):
    """Under a spring the spring end's z̄ at each jump carries an error estimate as the events
    do (BEM: twice its change on the finer whole solve; FE: against the BEM), and it bounds
    the `draft` z̄'s distance from the BEM `fine` one, in ε and relative to z̄ (measured in
    these cases: errors 0.53-0.89 of the BEM estimates, 0.42-0.53 of the FE's)."""
    draft = solve_curve(mu, method=method, accuracy="draft", spring_constant=k)
    fine = solve_curve(mu, method="bem", accuracy="fine", spring_constant=k,
                       error_estimate=False)
    for key in ("z_jump_in", "z_jump_out"):
        error = abs(draft.z_jumps[key] - fine.z_jumps[key])
        assert error <= draft.error_estimate[key], key
        relative = draft.relative_error_estimate[key]
        assert relative == pytest.approx(draft.error_estimate[key] / draft.z_jumps[key])


@pytest.mark.parametrize("k", [0.0, -1.0, float("inf")])
def test_a_spring_constant_must_be_positive_and_finite(k):
    with pytest.raises(InputError, match="spring_constant"):
        solve_curve(1.0, method="bem", accuracy="draft", spring_constant=k)


def test_cli_spring_in_newtons_per_metre():
    """--spring-constant in N/m with physical inputs is k̄ = Kε/(2πRΔγ): K = 2πRΔγ/ε · 0.5 gives
    the dimensionless k̄ = 0.5's events; a negative stiffness exits 2 in one line."""
    R, dgamma, eps = 1e-6, 0.05, 3e-10
    physical = ["--E-star", "1e11", "--dgamma", str(dgamma), "--eps", str(eps), "--R", str(R),
                "--profile", "derjaguin", "--method", "bem", "--accuracy", "draft",
                "--no-error-estimate", "--json"]
    K = 0.5 * 2 * 3.141592653589793 * R * dgamma / eps

    def curve(*args):
        return subprocess.run([sys.executable, "-m", "fem_asperity", "curve", *args],
                              capture_output=True, text=True)

    done = curve(*physical, "--spring-constant", str(K))
    assert done.returncode == 0, done.stderr
    row = json.loads(done.stdout)
    assert row["inputs"]["spring_constant"] == pytest.approx(0.5, rel=1e-12)
    same = solve_curve(row["mu"], method="bem", accuracy="draft", spring_constant=0.5,
                       error_estimate=False).records()
    assert row["z_jump_in"] == same["z_jump_in"]
    bad = curve(*physical, "--spring-constant", "-1")
    assert bad.returncode == 2 and len(bad.stderr.strip().splitlines()) == 1


def test_out_writes_the_cantilever_figure(tmp_path):
    from fem_asperity.solver.output import write_all

    result = solve_curve(0.5, method="bem", accuracy="draft", spring_constant=0.5,
                         error_estimate=False)
    names = {p.name for p in write_all(result, tmp_path / "out")}
    assert {"cantilever.png", "curve.png", "result.json"} <= names
    assert (tmp_path / "out" / "cantilever.png").read_bytes()[:4] == b"\x89PNG"


def test_the_cantilever_figure_shows_both_snaps():
    """On a soft lever the snap-out is far out (z̄ well past 10, where the view used to end):
    the figure's axis covers the snap-in and the snap-out."""
    from fem_asperity.solver.output import cantilever_figure

    result = solve_curve(1.0, method="bem", accuracy="draft", spring_constant=0.05,
                         error_estimate=False)
    z_in, z_out = result.z_jumps["z_jump_in"], result.z_jumps["z_jump_out"]
    assert z_out > 10.0
    left, right = cantilever_figure(result).axes[0].get_xlim()
    assert left < z_in < right and left < z_out < right


def test_the_exact_sphere_on_a_soft_spring_lands_on_its_own_far_field():
    """R/ε = 30: the jump-out flies to δ̄o ≈ 800 ≫ R/ε, where the exact sphere pulls far less
    than Derjaguin's parabola; it lands where the spring balances that pull, the traction of
    the sphere's lower half integrated by quadrature (an independent reference)."""
    from scipy.integrate import quad

    k, rho = 1e-3, 30.0
    result = solve_curve(1.0, method="bem", accuracy="draft", spring_constant=k,
                         radius_ratio=rho, error_estimate=False)
    delta, p = result.retraction.delta[-1], result.retraction.p[-1]

    def pull(r):
        h = delta + rho * (1.0 - (1.0 - r * r / rho) ** 0.5)
        return 8.0 / 3.0 * (h**-9 - h**-3) * r

    assert delta > 10 * rho
    assert p == pytest.approx(quad(pull, 0.0, rho**0.5, epsrel=1e-11)[0], rel=1e-6)
    assert p == pytest.approx(k * (delta - result.z_jumps["z_jump_out"]), rel=1e-6)
