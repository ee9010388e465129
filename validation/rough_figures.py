"""Figures of the rough-surface stage: Figs. 9-13 with the ξ collapse, and paper vs solved law."""

import numpy as np
from matplotlib.figure import Figure

from gw.integrate import totals
from gw.laws import PaperLaw
from gw.surface import RoughSurface
from gw.tables import solved_law

#: Line styles of the other laws in Figs. 9-13 (the paper's is solid).
STYLES = {"solved": "--", "corrected": ":", "refit": "-."}


def plot(data, spread, others=None):
    """Figs. 9-13 and the ξ collapse as one 3×3 figure, with the paper's law (solid) and, where
    they have them, the same series with the other laws of `others` ({'solved'|'corrected'|
    'refit': series}, in the line style of STYLES, same colour per μ or σ); returns the
    matplotlib Figure."""
    others = others or {}
    fig = Figure(figsize=(15, 12), layout="tight")
    ax = fig.subplots(3, 3)
    d = data["fig9"]["d"]
    for k, (mu, c) in enumerate(data["fig9"]["curves"].items()):
        ax[0, 0].plot(d, c["F"], color=f"C{k}", label=f"μ = {mu}")
        ax[0, 1].plot(d, c["S"], color=f"C{k}", label=f"μ = {mu}")
        for name, series in others.items():
            if mu in series["fig9"]["curves"]:
                ax[0, 0].plot(d, series["fig9"]["curves"][mu]["F"], STYLES[name],
                              color=f"C{k}")
                ax[0, 1].plot(d, series["fig9"]["curves"][mu]["S"], STYLES[name],
                              color=f"C{k}")
    ax[0, 0].set(xlabel="d / σ", ylabel="F̄", title="Fig. 9a: σ = 2 nm")
    ax[0, 1].set(xlabel="d / σ", ylabel="S̄", title="Fig. 9b: σ = 2 nm", yscale="log",
                 ylim=(1e-4, None))
    inset = ax[0, 2]
    inset.plot(d, data["fig9"]["curves"]["10"]["F"])
    inset.set(xlabel="d / σ", ylabel="F̄", title="Fig. 9a inset: μ = 10")
    panels = [(ax[1, 0], "fig10", "sigma_nm", "σ [nm]", "Fig. 10: μ =", "log"),
              (ax[1, 1], "fig11", "mu", "μ", "Fig. 11: σ [nm] =", "log"),
              (ax[1, 2], "fig12a", "sigma_nm", "σ [nm]", "Fig. 12a: θ =", "linear"),
              (ax[2, 0], "fig12b", "theta", "θ", "Fig. 12b: σ [nm] =", "log"),
              (ax[2, 1], "fig13", "mu", "μ", "Fig. 13: ζ =", "log")]
    for axis, key, x, xlabel, title, scale in panels:
        for k, (label, values) in enumerate(data[key]["f_max"].items()):
            axis.plot(data[key][x], values, color=f"C{k}", label=label)
            for name, series in others.items():
                if key in series:
                    axis.plot(series[key][x], series[key]["f_max"][label], STYLES[name],
                              color=f"C{k}")
        axis.set(xlabel=xlabel, ylabel="F̄max", title=title, xscale=scale)
    xi = np.asarray(spread["zeta"]) / (np.asarray(spread["mu"]) + 1.0)
    sc = ax[2, 2].scatter(xi, spread["f_max"], c=np.log10(spread["mu"]), s=8, cmap="viridis")
    fig.colorbar(sc, ax=ax[2, 2], label="log10 μ")
    ax[2, 2].set(xlabel="ξ = σ/((μ+1)ε)", ylabel="F̄max", xscale="log", title="ξ collapse")
    for axis in ax.flat:
        axis.grid(alpha=0.3)
        if axis.get_legend_handles_labels()[0]:
            axis.legend(fontsize=7)
    shown_as = {"solved": "dashed: the solved law (table of BEM solves, μ ≤ 50)",
                "corrected": "dotted: the corrected law (μ ≤ 50)",
                "refit": "dash-dot: the paper's forms refitted"}
    fig.suptitle(f"Paper's laws on a GW surface (ε = {data['eps_nm']} nm, ω = {data['omega']})"
                 + "".join(f"; {shown_as[name]}" for name in others))
    return fig


def plot_comparison(mus, *, eps_nm, method="bem", accuracy="default", sigma=2.0):
    """F̄ and S̄ vs d̃ with the paper law (dashed) and the solved law (solid) at each μ, on a
    GW surface of ζ = `sigma` / `eps_nm` (both in nm), ω = 1."""
    fig = Figure(figsize=(12, 4.5), layout="tight")
    a, b = fig.subplots(1, 2)
    d = np.linspace(0.0, 8.0, 161)
    surface = RoughSurface(sigma / eps_nm)
    tensile = []  # each curve's largest tension, > 0
    for k, mu in enumerate(mus):
        color = f"C{k}"
        for law, style in ((PaperLaw(mu), "--"), (solved_law(mu, method=method,
                                                             accuracy=accuracy), "-")):
            force, area = totals(law, surface, d)
            tensile.append(-force.min())
            a.plot(d, force, style, color=color, label=f"μ = {mu:g} {law.name}")
            b.plot(d, area, style, color=color)
    # symmetric log: F̄max spans decades over μ, and on a linear axis the weakest lay on zero;
    # linear only within a tenth of the weakest curve's F̄max
    weakest = min(t for t in tensile if t > 0)
    a.set_yscale("symlog", linthresh=0.1 * weakest)
    a.set(xlabel="d / σ", ylabel="F̄ (< 0 tensile; repulsive part clipped; symmetric log)",
          ylim=(-1.5 * max(tensile), max(tensile)),
          title=f"σ = {sigma:g} nm: paper law (--) vs {method}")
    b.set(xlabel="d / σ", ylabel="S̄", yscale="log", ylim=(1e-4, None))
    a.legend(fontsize=7, ncol=2)
    for axis in (a, b):
        axis.grid(alpha=0.3)
    return fig
