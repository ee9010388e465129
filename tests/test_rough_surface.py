"""`validation.rough_surface`'s figures and tables: the paper's law beside the solved law over μ."""

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
    """A row per μ and σ with F̄max paper/solved and whether the paper's law holds (within
    10 %), the count above the table."""
    row = {"mu": 1.0, "sigma_nm": 0.5, "f_max_paper": 0.268, "f_max_refit": 0.3,
           "f_max_solved": 0.461, "max_dF": 0.2, "d_at_max_dF": 1.0, "max_dS_rel": 0.1,
           "d_at_max_dS": 1.5, "interpolation_error": 1e-4}
    close = {**row, "mu": 0.1, "f_max_paper": 0.95, "f_max_solved": 1.0}
    table = comparison_table([close, row])
    assert "holds (F̄max within 10% of the solved law's) on 1 of 2 rows" in table
    assert "| 0.950 | holds |" in table and "| 0.581 | fails: -42% |" in table
