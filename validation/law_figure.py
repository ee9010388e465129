"""The paper's closed-form asperity events over μ, tabulated and drawn beside JKR, DMT and
Maugis-Dugdale."""

import numpy as np
from matplotlib.figure import Figure

from fem_asperity.closed_forms import reference
from fem_asperity.closed_forms.laws import PAPER_LAWS

#: Tabor parameters of the law table and figure: 0.01 to 100, 25 per decade.
MU_GRID = np.logspace(-2, 2, 101)


def law_table(mu=MU_GRID, laws=PAPER_LAWS):
    """Per-μ records of the law's events plus the Maugis-Dugdale pull-off force and radius."""
    rows = laws.events(mu).records()
    md = reference.maugis_dugdale_pull_off(mu=np.asarray(mu))
    for row, force, radius in zip(rows, md.force, md.radius):
        row["md_p_off"], row["md_a"] = float(force), float(radius)
    return rows


def plot_laws(rows, laws=PAPER_LAWS):
    """A 2x2 figure of P̄max, ā_c, δ̄oc/δ̄o* and x̄oc against μ; returns the matplotlib Figure."""
    col = {k: np.array([np.nan if r[k] is None else r[k] for r in rows], float) for k in rows[0]}
    jkr_a_c = reference.jkr_compressive_radius(mu=col["mu"])
    gap = np.searchsorted(col["mu"], laws.mu_jump)  # NaN row: no line drawn across the regimes
    col = {k: np.insert(v, gap, np.nan) for k, v in col.items()}
    jkr_a_c = np.insert(jkr_a_c, gap, np.nan)
    mu = col["mu"]
    fig = Figure(figsize=(10, 7.5), layout="tight")
    ax = fig.subplots(2, 2, sharex=True)
    (a, b), (c, d) = ax

    a.plot(mu, col["p_max"], label="eq. 2 (Wu, LJ fit)")
    a.plot(mu, col["md_p_off"], "--", label=r"Maugis-Dugdale, $\lambda$ = 1.157 $\mu$")
    a.axhline(-1.0, color="grey", lw=0.8, ls=":", label="DMT / Bradley (-1)")
    a.axhline(-0.75, color="k", lw=0.8, ls=":", label="JKR (-0.75)")
    a.set_ylabel(r"$\bar P_{max} = P_{max}/2\pi R\Delta\gamma$")

    b.plot(mu, col["a_c"], label="eq. 6")
    b.plot(mu, jkr_a_c, "--", label=r"JKR, eq. A9: 0.8794 $\mu^{1/2}$")
    b.set_ylabel(r"$\bar a_c = a_c/\sqrt{\varepsilon R}$")

    c.plot(mu, col["delta_oc"], label=r"$\bar\delta_{oc}$ (eq. 7 | eq. 13)")
    c.plot(mu, col["delta_o_star"], "--", label=r"$\bar\delta_o^*$ (eq. 10 | eq. 13)")
    c.set_ylabel(r"separation $/\varepsilon$")
    c.set_yscale("log")

    d.plot(mu, col["x_oc"], label="eq. 12 (jump-in only)")
    d.axhline(1.0, color="grey", lw=0.8, ls=":", label=r"$\bar x = 1$")
    d.set_ylabel(r"$\bar x_{oc} = x_{oc}/\varepsilon$")

    for axis in ax.flat:
        axis.set_xscale("log")
        axis.axvline(laws.mu_jump, color="r", lw=0.6, alpha=0.5)
        axis.legend(fontsize=8)
        axis.grid(alpha=0.3)
    for axis in (c, d):
        axis.set_xlabel(r"Tabor parameter $\mu$")
    fig.suptitle("Paper's closed-form single-asperity laws (red line: jump-in from mu = 0.5)")
    return fig
