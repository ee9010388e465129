"""Figures of the single-asperity verification: the paper's Figs. 3-7 from the FE sweep (points
with the FE's error estimate as error bars), the BEM as a line, the paper's law dashed and the
refit dotted; and the hysteresis loops (beyond the paper)."""

from dataclasses import replace

import numpy as np
from matplotlib.figure import Figure

from fem_asperity.closed_forms.laws import PAPER_LAWS, AsperityLaws
from fem_asperity.closed_forms.reference import jkr_compressive_radius
from fem_asperity.plumbing.files import save_figure

#: R/ε of Fig. 7's physical axes; the picture's shape does not depend on it (methods.md §14).
#: Not pinned by a test.
RADIUS_RATIO = 1000.0
#: μ of the paper's Fig. 5 (eq. 9 against the FE), Fig. 7 and the hysteresis loops.
FIG5_MU, FIG7_MU, LOOP_MU = (0.091, 0.19, 0.3, 0.425), (0.091, 0.425, 1.0, 1.971), (0.5, 1, 2, 5)


def _refit_laws(refit):
    return AsperityLaws(**{r["constant"]: r["value"] for r in refit.values()})


def _points(ax, rows, key, label, color="k"):
    """FE values with their error estimates as error bars."""
    mu = np.array([r["mu"] for r in rows])
    value = np.array([r[key] for r in rows], dtype=float)
    error = np.array([(r["error_estimate"] or {}).get(key) or 0.0 for r in rows])
    ax.errorbar(mu, value, yerr=error, fmt="o", ms=4, color=color, capsize=2, label=label)


def _line(ax, rows, key, label, style="-", color="tab:blue"):
    ax.plot([r["mu"] for r in rows], [r[key] for r in rows], style, color=color, lw=1,
            label=label)


def fig3(rows, bem, refitted):
    fig = Figure(figsize=(6, 4.5), layout="constrained")
    ax = fig.subplots()
    mu = np.geomspace(min(r["mu"] for r in rows), max(r["mu"] for r in rows), 200)
    _points(ax, rows, "a_c", "FE (error estimate)")
    _line(ax, bem, "a_c", "BEM")
    ax.plot(mu, PAPER_LAWS.a_c(mu), "--", color="tab:red", label="eq. 6 (paper)")
    ax.plot(mu, refitted.a_c(mu), ":", color="tab:green", label="eq. 6 refitted")
    ax.plot(mu, jkr_compressive_radius(mu=mu), "-.", color="grey", label="JKR (eq. A9)")
    ax.set(xscale="log", xlabel=r"Tabor parameter $\mu$",
           ylabel=r"$\bar a_c = a_c/\sqrt{\varepsilon R}$ at $\bar P_{max}$",
           title="Fig. 3: contact radius at maximum adhesion")
    return fig


def fig4(rows, bem, refitted, onset):
    fig = Figure(figsize=(6, 4.5), layout="constrained")
    ax = fig.subplots()
    below = [r for r in rows if r["mu"] < onset]
    bem_below = [r for r in bem if r["mu"] < onset]
    mu = np.linspace(min(r["mu"] for r in below), onset, 200)
    laws = PAPER_LAWS
    for key, color in (("delta_oc", "k"), ("delta_o_star", "tab:purple")):
        _points(ax, below, key, f"FE {key}", color=color)
        _line(ax, bem_below, key, f"BEM {key}", color=color)
    ax.plot(mu, 1 + laws.c_oc * mu, "--", color="k", label="eq. 7 (paper)")
    ax.plot(mu, 1 + refitted.c_oc * mu, ":", color="k", label="eq. 7 refitted")
    ax.plot(mu, 1 + laws.c_star * mu**1.5, "--", color="tab:purple", label="eq. 10 (paper)")
    ax.plot(mu, 1 + refitted.c_star * mu**1.5, ":", color="tab:purple", label="eq. 10 refitted")
    ax.set(xlabel=r"Tabor parameter $\mu$ (no jump-in)",
           ylabel=r"$\bar\delta_{oc}$, $\bar\delta_o^*$ (in $\varepsilon$)",
           title=r"Fig. 4: separation at $\bar P_{max}$ and at first contact")
    return fig


def _curve_of(rows, mu):
    """The stored curve at `mu`, or None if it failed (its panel is then left out)."""
    return next((r["curve"] for r in rows if r["mu"] == mu), None)


def fig5(rows, bem):
    fig = Figure(figsize=(6.5, 4.5), layout="constrained")
    ax = fig.subplots()
    for k, mu in enumerate(FIG5_MU):
        color = f"C{k}"
        fe, be = _curve_of(rows, mu), _curve_of(bem, mu)
        if fe is None:
            continue
        ax.plot(fe.approach.delta, fe.approach.p, "o", ms=2.5, color=color, label=f"FE, μ = {mu:g}")
        if be is not None:
            ax.plot(be.approach.delta, be.approach.p, "-", lw=0.8, color=color)
        fe = fe.approach
        delta = np.linspace(max(0.9, fe.delta.min()), 4.0, 300)
        ax.plot(delta, PAPER_LAWS.force(delta, mu=mu), "--", color=color, lw=1)
    ax.set(xlim=(0.8, 4.0), ylim=(-1.1, 0.5), xlabel=r"$\bar\delta_o = \delta_o/\varepsilon$",
           ylabel=r"$\bar P = P/(2\pi R\Delta\gamma)$",
           title="Fig. 5: approach, FE (points), BEM (lines), eq. 9 (dashed)")
    ax.legend(fontsize=8)
    return fig


def fig6(rows, bem, refitted, onset):
    fig = Figure(figsize=(10, 4.2), layout="constrained")
    left, right = fig.subplots(1, 2)
    above = [r for r in rows if r["jump_in"]]
    bem_above = [r for r in bem if r["jump_in"]]
    mu = np.linspace(onset, max(r["mu"] for r in above), 200)
    # The paper puts P_max at the jump-in (eq. 13 gives both δ_oc and δ_o* there): its δ_oc is
    # compared with the FE's separation at the jump, the FE's δ_o at P_max shown beside it.
    for ax, key, ylabel, law in ((left, "x_oc", r"$\bar x_{oc}$ (gap at jump-in, in $\varepsilon$)",
                                  "x_oc"),
                                 (right, "delta_jump_in",
                                  r"$\bar\delta_{oc}$ (separation at jump-in, in $\varepsilon$)",
                                  "delta_oc")):
        _points(ax, above, key, "FE (error estimate)")
        _line(ax, bem_above, key, "BEM")
        if key == "delta_jump_in":
            ax.plot([r["mu"] for r in above], [r["delta_oc"] for r in above], "s", ms=4,
                    mfc="none", color="k", label=r"FE $\bar\delta_o$ at $\bar P_{max}$")
        paper_values = getattr(AsperityLaws(mu_jump=onset), law)(mu)
        refit_values = getattr(replace(refitted, mu_jump=onset), law)(mu)
        ax.plot(mu, paper_values, "--", color="tab:red", label="paper (eqs. 12, 13)")
        ax.plot(mu, refit_values, ":", color="tab:green", label="refitted")
        ax.axvline(onset, color="grey", lw=0.8, label=f"measured onset {onset:.3f}")
        ax.set(xlabel=r"Tabor parameter $\mu$", ylabel=ylabel)
    left.set_title("Fig. 6: the jump-in")
    left.legend(fontsize=8)
    return fig


def fig7(rows):
    """Hertz-like force and area after contact, in the paper's physical coordinates at
    RADIUS_RATIO (see its comment)."""
    fig = Figure(figsize=(10, 4.2), layout="constrained")
    force, area = fig.subplots(1, 2)
    ratio = 1.0 / RADIUS_RATIO  # ε/R
    largest = 0.0
    for k, mu in enumerate(FIG7_MU):
        row = next((r for r in rows if r["mu"] == mu), None)
        if row is None:
            continue
        path = row["curve"].approach
        pressed = path.delta < row["delta_oc"]
        x = (row["delta_oc"] - path.delta[pressed]) * ratio
        y = 1.5 * np.pi * (mu * ratio) ** 1.5 * (path.p[pressed] - row["p_max"])
        force.plot(x, y, "o", ms=2.5, color=f"C{k}", label=f"FE, μ = {mu:g}")
        touching = path.delta < row["delta_o_star"]
        xa = (row["delta_o_star"] - path.delta[touching]) * ratio
        # The area at first contact: none without a jump-in (eq. 17), the landing's with one
        # (eq. 19).
        a_first = row["a_c_after"] or 0.0
        ya = (path.area[touching] - np.pi * a_first**2) * ratio / np.pi
        area.plot(xa, ya, "o", ms=2.5, color=f"C{k}", label="_nolegend_")  # force's legend
        largest = max(largest, x.max(initial=0.0), xa.max(initial=0.0))
    x = np.linspace(0.0, largest, 100)
    force.plot(x, x**1.5, "k--", label="Hertz")
    area.plot(x, x, "k--", label="Hertz")
    force.set(xlabel=r"$(\delta_{oc} - \delta_o)/R$", ylabel=r"$(P - P_{max})/(4E^*R^2/3)$",
              title=f"Fig. 7: force after contact (R/ε = {RADIUS_RATIO:g})")
    area.set(xlabel=r"$(\delta_o^* - \delta_o)/R$",
             ylabel=r"$(A - \pi a_{c,*}^2)/\pi R^2$ ($a_{c,*}$: at first contact)",
             title="area after contact")
    force.legend(fontsize=8)
    return fig


def loops(rows, energies, bem_energies, whole):
    """The loops at LOOP_MU with the unstable branch between the folds where `whole` (μ → the
    BEM's whole equilibrium curve) has it, and the dissipated energy against μ (FE points, BEM
    line)."""
    fig = Figure(figsize=(15, 7), layout="constrained")
    panels = fig.subplots(2, 3).flat
    for ax, mu in zip([panels[i] for i in (0, 1, 3, 4)], LOOP_MU):
        curve = _curve_of(rows, mu)
        if curve is None:
            continue
        ax.plot(curve.approach.delta, curve.approach.p, "-", color="tab:blue", label="approach")
        ax.plot(curve.retraction.delta, curve.retraction.p, "-", color="tab:red",
                label="retraction")
        if mu in whole:
            branch = whole[mu]
            ax.plot(branch.delta, np.where(branch.stable, np.nan, branch.p), "--", color="grey",
                    lw=1, label="unstable branch (BEM)")
        events = curve.events
        right = max(6.0, 1.2 * (events.jump_out.delta if events.jump_out else 0.0))
        energy = energies[f"{mu:g}"]
        ax.set(xlim=(min(curve.approach.delta.min(), 0.0), right), ylim=(-1.05, 1.05),
               xlabel=r"$\bar\delta_o$", ylabel=r"$\bar P$",
               title=f"μ = {mu:g}: dissipated " + (f"{energy:.3g} (2πRΔγ ε)" if energy > 1e-9
                                                   else "0 (no jumps)"))
    fig.axes[0].legend(fontsize=8)
    energy = panels[2]
    energy.plot([float(m) for m in energies], list(energies.values()), "o", color="k", label="FE")
    energy.plot([float(m) for m in bem_energies], list(bem_energies.values()), "-",
                color="tab:blue", lw=1, label="BEM")
    energy.set(xscale="log", xlabel=r"Tabor parameter $\mu$",
               ylabel=r"dissipated energy / ($2\pi R\Delta\gamma\,\varepsilon$)",
               title="energy of the loop against μ")
    energy.legend(fontsize=8)
    fig.delaxes(panels[5])
    fig.suptitle("Approach and retraction under displacement control (FE)")
    return fig


def save_figures(folder, rows, bem, refit, onset, energies, bem_energies, whole):
    """Write fig3.png ... fig7.png and hysteresis.png into `folder`; their paths."""
    refitted = _refit_laws(refit)
    figures = {"fig3": fig3(rows, bem, refitted), "fig4": fig4(rows, bem, refitted, onset),
               "fig5": fig5(rows, bem), "fig6": fig6(rows, bem, refitted, onset),
               "fig7": fig7(rows), "hysteresis": loops(rows, energies, bem_energies, whole)}
    paths = []
    for name, fig in figures.items():
        for ax in fig.axes:
            ax.grid(alpha=0.3)
            if ax.get_legend() is None and ax.get_legend_handles_labels()[0]:
                ax.legend(fontsize=8)
        paths.append(save_figure(fig, folder / f"{name}.png"))
    return paths
