"""`validation.rough_surface`'s figures and tables: the paper's law beside the solved law over μ."""

import pytest

from validation.rough_figures import plot_comparison
from validation.rough_surface import comparison_table


def test_the_law_comparison_shows_every_mus_tension():
    """F̄max spans decades over μ: on a linear axis the weakest μ lay flat on zero beside
    μ = 3. The axis is symmetric-log, linear only within a tenth of the weakest curve's
    largest tension, so every curve's tension is drawn on the log part."""
    axis = plot_comparison((0.3, 3.0), eps_nm=0.3, accuracy="draft").axes[0]
    assert axis.get_yscale() == "symlog"
    weakest = min(-line.get_ydata().min() for line in axis.get_lines())
    assert weakest >= 10 * axis.yaxis.get_transform().linthresh


def test_the_paper_against_solved_table_gives_the_ratio_and_the_verdict():
    """A row per μ and σ with the four laws' F̄max, paper/solved and whether the paper's law
    holds (within 10 %), corrected/solved, and both counts above the table."""
    row = {"mu": 1.0, "sigma_nm": 0.5, "f_max_paper": 0.268, "f_max_refit": 0.3,
           "f_max_corrected": 0.45, "f_max_solved": 0.461, "max_dF": 0.2, "d_at_max_dF": 1.0,
           "max_dS_rel": 0.1, "d_at_max_dS": 1.5, "interpolation_error": 1e-4}
    close = {**row, "mu": 0.1, "f_max_paper": 0.95, "f_max_corrected": 0.8,
             "f_max_solved": 1.0}
    table = comparison_table([close, row])
    assert ("holds (F̄max within 10% of the solved law's) on 1 of 2 rows; the corrected law "
            "on 1") in table
    assert "| 0.950 | holds | 0.800 |" in table and "| 0.581 | fails: -42% | 0.976 |" in table


def test_gw_itself_at_the_papers_points_is_read_off_the_shipped_map():
    """At μ = 1, σ = 0.6 nm (ζ = 2 at ε = 0.3 nm: a grid point of the map) each σRη's reading
    is the smallest and largest error of the map's two draws there; at μ = 5, beyond the map's
    μ, nothing is read; the map's σRη = 0.02 (McCool's ω = 0.27, not the report's 1) is left
    out. The table marks a point where every surface around is beyond 10 % (✗), where some
    are (?), and where none is."""
    from gw.explicit.measured_map import measured_error
    from validation.rough_surface import _gw_itself_table, _verdict, gw_itself

    found = gw_itself((1.0, 5.0), sigmas=(0.6,))
    assert found["sigma_r_eta"] == [0.05, 0.15]
    inside, outside = found["rows"]
    assert inside["zeta"] == pytest.approx(2.0)
    for model in ("gw_sum", "gw_cells"):
        for value, sre in zip(inside["errors"][model], found["sigma_r_eta"]):
            read = measured_error(model, mu=1.0, zeta=2.0, sigma_r_eta=sre)
            assert read.surfaces == 2 and value == [read.least, read.size]
            assert read.least <= read.size
        assert outside["errors"][model] == [None] * len(found["sigma_r_eta"])
    assert (_verdict(0.11, 0.5), _verdict(0.05, 0.5), _verdict(0.01, 0.1)) == (
        "fails", "open", "holds")
    table = _gw_itself_table(found)
    least, largest = inside["errors"]["gw_sum"][-1]  # the densest: GW's sum 49-56 % above
    assert least > 0.1 and f"{100 * least:.1f}-{100 * largest:.1f} % ✗" in table
    assert "| 5 | 0.6 | 2 | — |" in table


@pytest.mark.slow
def test_figs_9_to_13_draw_the_other_laws_beside_the_papers():
    """The paper's law solid, the corrected law dotted (up to μ = 50, where it is measured), in
    the colour of the same σ; the title says which is which."""
    from gw.laws import CorrectedLaw
    from validation.rough_figures import plot
    from validation.rough_surface import figure_data

    paper, corrected = figure_data(), figure_data(CorrectedLaw, mu_max=50.0)
    spread = {"zeta": [1.0], "mu": [1.0], "f_max": [0.5]}
    figure = plot(paper, spread, {"corrected": corrected})
    fig11 = figure.axes[4]
    assert fig11.get_title() == "Fig. 11: σ [nm] ="
    solid = [line for line in fig11.get_lines() if line.get_linestyle() == "-"]
    dotted = [line for line in fig11.get_lines() if line.get_linestyle() == ":"]
    assert len(solid) == len(dotted) == 3
    assert [line.get_color() for line in solid] == [line.get_color() for line in dotted]
    assert max(dotted[0].get_xdata()) <= 50.0 < max(solid[0].get_xdata())
    assert "dotted: the corrected law" in figure._suptitle.get_text()


def test_the_solved_approach_tends_to_jkrs_landing_not_to_its_pull_off():
    """F̄max of a nearly smooth surface (ζ = 0.01) is the asperity's largest tension on approach.
    Under displacement control a JKR contact lands at δ = 0 with P̄ = −2/3 (its pull-off, −0.75,
    is on retraction); the solved approach heads there as μ grows, so the paper's "F̄max → 0.75
    as μ → ∞" (its law's approach reaches 0.75) fails with the solved law."""
    from fem_asperity.closed_forms.reference import jkr_force, jkr_radius_at_approach
    from gw.law_table import shipped_table
    from validation.rough_surface import f_max

    landing = -jkr_force(radius=jkr_radius_at_approach(approach=0.0, mu=50.0), mu=50.0)
    assert abs(landing - 2.0 / 3.0) < 1e-12
    solved = [f_max(mu, 0.01, law_at=shipped_table().law) for mu in (10.0, 20.0, 50.0)]
    assert 0.75 > solved[0] > solved[1] > solved[2] > landing
    assert abs(f_max(1e4, 0.01) - 0.75) < 2e-3  # the paper's law: its approach reaches 0.75
