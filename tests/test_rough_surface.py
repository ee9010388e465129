"""`validation.rough_surface`'s figures: the paper's law beside the solved law over μ."""

from validation.rough_figures import plot_comparison


def test_the_law_comparison_shows_every_mus_tension():
    """F̄max spans decades over μ: on a linear axis the weakest μ lay flat on zero beside
    μ = 3. The axis is symmetric-log, linear only within a tenth of the weakest curve's
    largest tension, so every curve's tension is drawn on the log part."""
    axis = plot_comparison((0.3, 3.0), eps_nm=0.3, accuracy="draft").axes[0]
    assert axis.get_yscale() == "symlog"
    weakest = min(-line.get_ydata().min() for line in axis.get_lines())
    assert weakest >= 10 * axis.yaxis.get_transform().linthresh
