"""GW's ground counted once, in closed form (gw.shared_ground): against explicit surfaces of caps
at random places (the pixel sums of gw.explicit.tails), its sparse limit, the flat bound no
surface can pull beyond, and its quadrature's convergence."""

import numpy as np
import pytest

import gw.shared_ground as shared
from gw.explicit import gaussian_caps
from gw.explicit.tails import SharedTails
from gw.integrate import strength
from gw.law_table import shipped_table
from gw.laws import PaperLaw
from gw.shared_ground import flat_bound, shared_ground
from gw.surface import RoughSurface


@pytest.mark.parametrize("omega", [1.0, 0.7])
def test_the_closed_form_is_the_mean_over_explicit_surfaces(omega):
    """ζ = 0.5, σRη = 0.05, summit heights of rms σ/ω: four periodic maps of 600 caps
    (R = ε = 1 here), each measured pixel by pixel (`SharedTails`): their mean T per summit
    against the Poisson closed form within three standard errors of the mean (0.6-2 % here)
    and 1 % more for what a map of caps is not (one apex per pixel, a floor 20σ down)."""
    zeta, sre, count = 0.5, 0.05, 600
    side = np.sqrt(count / (sre / zeta))  # η = σRη/ζ in 1/R² (σ = ζ, R = 1)
    n = int(side / 0.3)
    d = np.array([0.5, 1.5, 3.0])
    draws = []
    for seed in range(4):
        topography, caps = gaussian_caps(n=n, pixel=side / n, radius=1.0, sigma=zeta / omega,
                                         density=count / side**2, seed=seed, periodic=True)
        tails = SharedTails.build(caps.x, caps.y, caps.z, topography.heights,
                                  pixel=side / n, periodic=True, separations=d * zeta)
        draws.append([tails.force(x * zeta) / caps.z.size for x in d])
    draws = np.array(draws)
    closed = shared_ground(RoughSurface(zeta, omega), sre, d)
    margin = 3 * draws.std(axis=0, ddof=1) / np.sqrt(len(draws)) + 0.01 * closed
    assert np.all(np.abs(draws.mean(axis=0) - closed) < margin)
    assert np.all(closed > 0)  # attraction that GW counts too often


def test_sparse_summits_share_ground_in_proportion_to_their_density():
    """As σRη → 0 the overlap is that of pairs of summits (F − 1 → −Λ ∝ σRη): T per unit σRη
    settles, within 0.5 % from 1e-5 to 1e-6 (0.6 % apart from 1e-4 to 1e-5; 10 % or more from
    1e-2 to 1e-3), and T itself is under 2e-3 (2πRΔγ per summit) at σRη = 1e-4."""
    surface, d = RoughSurface(1.0), np.array([0.0, 1.0, 2.0])
    per_density = [shared_ground(surface, sre, d) / sre for sre in (1e-2, 1e-3, 1e-5, 1e-6)]
    assert np.all(np.abs(shared_ground(surface, 1e-4, d)) < 2e-3)
    assert per_density[2] == pytest.approx(per_density[3], rel=0.005)
    assert np.all(np.abs(per_density[1] / per_density[0] - 1) > 0.1)


def test_gw_counted_once_keeps_within_the_flat_bound():
    """A nearly rigid solved law (μ = 0.01, the shipped table) on dense summits, ζ = 0.2,
    σRη = 0.05: GW's F̄max (0.74) is more than the LJ's most tensile traction over the whole
    nominal area, 16/(9√3) ζ/(2π σRη), can give (0.65); with the ground counted once it is
    within it."""
    law, surface, sre = shipped_table().law(0.01), RoughSurface(0.2), 0.05
    bound = flat_bound(0.2, sre)
    assert bound == pytest.approx(16 / (9 * np.sqrt(3)) * 0.2 / (2 * np.pi * sre), rel=1e-12)
    assert strength(law, surface).f_max > 1.1 * bound
    assert strength(law, surface, sigma_r_eta=sre).f_max < bound


def test_the_gap_quadrature_has_converged(monkeypatch):
    """Twice the points per e-fold of the gap moves T by under 1e-5 (per summit, 2πRΔγ), from
    smooth to rough surfaces and dense summits (6e-6 at ζ = 0.01 in a run here)."""
    d = np.linspace(-1.0, 4.0, 6)
    for zeta, sre in ((0.01, 0.02), (0.2, 0.03), (2.0, 0.05), (300.0, 0.02), (1.0, 10.0)):
        surface = RoughSurface(zeta)
        coarse = shared_ground(surface, sre, d)
        monkeypatch.setattr(shared, "PER_E_FOLD", 2 * shared.PER_E_FOLD)
        fine = shared_ground(surface, sre, d)
        monkeypatch.undo()
        assert np.abs(fine - coarse).max() < 1e-5


def test_fmax_counts_the_ground_once_where_sigma_r_eta_is_given(capsys):
    """gw fmax with --sigma-r-eta: the counted-once F̄max beside GW's, and the note says where
    GW pulls beyond the flat bound."""
    import json

    from gw.__main__ import main

    assert main(["fmax", "--mu", "0.1", "--zeta", "0.2", "--sigma-r-eta", "0.05", "--json"]) == 0
    out = capsys.readouterr()
    row = json.loads(out.out)
    shared_row = row["shared_ground"]
    surface = RoughSurface(0.2, row["omega"])
    direct = strength(PaperLaw(0.1), surface, sigma_r_eta=0.05)
    assert shared_row["f_max"] == pytest.approx(direct.f_max, rel=1e-9)
    assert shared_row["relative"] == pytest.approx(direct.f_max / row["f_max"] - 1, rel=1e-9)
    assert row["f_max"] > shared_row["flat_bound"] > shared_row["f_max"]
    assert "no surface can pull beyond" in out.err
    assert "so does the counted-once" not in out.err
    # μ = 10: JKR contacts larger than each summit's share of the ground, counted once or not
    assert main(["fmax", "--mu", "10", "--zeta", "0.2", "--sigma-r-eta", "0.05", "--law",
                 "solved", "--json"]) == 0
    out = capsys.readouterr()
    assert json.loads(out.out)["shared_ground"]["f_max"] > flat_bound(0.2, 0.05)
    assert "so does the counted-once" in out.err
    assert main(["fmax", "--mu", "0.1", "--zeta", "0.2", "--json"]) == 0  # no σRη: nothing
    assert "shared_ground" not in json.loads(capsys.readouterr().out)
