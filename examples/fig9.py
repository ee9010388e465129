"""The paper's Fig. 9 regenerated: total force and contact area of a rough surface against the
mean separation, for Tabor parameters from 0.5 to 46.9.

Song & Komvopoulos' Fig. 9 shows, for a Greenwood-Williamson surface of roughness σ = 2 nm,
(a) the dimensionless total force F̄ = F/(2πRA₀Δγη) and (b) the total contact area
S̄ = S/(RA₀ηε) against the mean separation d̃ = d/σ, at μ = 0.5, 1, 2, 5, 10 and 46.9 (an inset
magnifies F̄ at μ = 10). Its figures are lost from the text; only the captions and the equations
survive. This script recomputes the data with the validation stage's `figure_data` (the paper's
closed-form asperity laws integrated over the Gaussian summit heights, eqs. 20-28) and draws the
two panels.

The paper states neither ε nor R, η: the validation takes ε = 0.3 nm (so ζ = σ/ε = 6.67) and
ω = 1 (σRη ≫ 0.019); F̄ and S̄ depend on μ, ζ and ω only. The figure needs no solver
(closed forms and quadrature only), so EXAMPLES_FAST changes nothing here. EXAMPLES_OUT names
the output folder (default out/examples/fig9).
"""

# %%
# Settings and imports. `figure_data` returns the series of Figs. 9-13 as plain lists; its
# "fig9" entry holds the d̃ grid (0 to 8 in steps of 0.05) and F̄, S̄ per μ. It computes
# Figs. 10-13 too: the validation stage has no Fig.-9-only entry point.

import csv
import os
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from validation.rough_surface import EPS_NM, FIG9_MU, f_max, figure_data

FAST = os.environ.get("EXAMPLES_FAST") == "1"  # nothing to speed up: kept for uniformity
OUT = Path(os.environ.get("EXAMPLES_OUT", "out/examples/fig9"))

# %%
# The data. F̄ < 0 is tensile (the asperities pull the surfaces together); S̄ grows as the
# surfaces approach (d̃ falls).

data = figure_data()
fig9 = data["fig9"]
d = np.asarray(fig9["d"])
curves = {mu: {k: np.asarray(v) for k, v in fig9["curves"][f"{mu:g}"].items()} for mu in FIG9_MU}
print(f"ε = {data['eps_nm']} nm, ω = {data['omega']}, σ = {fig9['sigma_nm']} nm, "
      f"ζ = {fig9['sigma_nm'] / EPS_NM:.4g}")
for mu, c in curves.items():
    k = int(np.argmin(c["F"]))
    print(f"μ = {mu:<5g} most tensile F̄ on the grid {c['F'][k]:+.4g} at d̃ = {d[k]:.2f}; "
          f"S̄(0) = {c['S'][0]:.4g}")

# %%
# The strength of adhesion F̄max = −min F̄ of each curve. The grid's minimum is not enough: at
# μ = 46.9 it sits at the grid's end, d̃ = 0. `f_max` (also from the validation stage) searches
# the whole range of d̃ where F̄ changes. The paper's point about Fig. 9: at μ = 10 the rough
# surface's F̄max stays well below the single-asperity JKR pull-off 0.75 (roughness spreads the
# asperities over separations at which few of them pull at once).
ZETA = fig9["sigma_nm"] / EPS_NM
strengths = {mu: f_max(mu, ZETA, data["omega"]) for mu in FIG9_MU}
print("F̄max: " + ", ".join(f"μ = {mu:g}: {f:.4g}" for mu, f in strengths.items())
      + " (single asperity, JKR: 0.75)")

# %%
# The figure, with matplotlib's object API. Panel (a) F̄ with the inset for μ = 10, panel (b) S̄
# on a logarithmic axis (it spans several decades between first contact and d̃ = 0).

fig = Figure(figsize=(11, 4.5), layout="constrained")
ax_f, ax_s = fig.subplots(1, 2)
for mu, c in curves.items():
    ax_f.plot(d, c["F"], label=f"μ = {mu:g}")
    ax_s.plot(d, c["S"], label=f"μ = {mu:g}")
ax_f.set(xlabel="mean separation d̃ = d/σ", ylabel="total force F̄ = F/(2πRA₀Δγη)",
         title=f"(a) σ = {fig9['sigma_nm']:g} nm, ε = {EPS_NM:g} nm, ω = {data['omega']:g}")
ax_s.set(xlabel="mean separation d̃ = d/σ", ylabel="total contact area S̄ = S/(RA₀ηε)",
         title="(b)", yscale="log", ylim=(1e-4, None))
inset = ax_f.inset_axes([0.45, 0.45, 0.5, 0.45])
inset.plot(d, curves[10.0]["F"], color="C4")
inset.set_title("μ = 10", fontsize=8)
inset.set_xlim(0.0, 5.0)
inset.tick_params(labelsize=7)
for axis in (ax_f, ax_s, inset):
    axis.grid(alpha=0.3)
ax_f.legend(fontsize=8, loc="lower left")
ax_s.legend(fontsize=8)
OUT.mkdir(parents=True, exist_ok=True)
fig.savefig(OUT / "fig9.png", dpi=150, bbox_inches="tight")
print(f"wrote {OUT / 'fig9.png'}")

# %%
# The data behind the figure as CSV: one row per d̃, columns F_mu<μ> and S_mu<μ>.

with open(OUT / "fig9.csv", "w", newline="") as file:
    writer = csv.writer(file, lineterminator="\n")
    writer.writerow(["d"] + [f"{q}_mu{mu:g}" for mu in FIG9_MU for q in ("F", "S")])
    for i, di in enumerate(d):
        writer.writerow([f"{di:.10g}"] + [f"{curves[mu][q][i]:.10g}" for mu in FIG9_MU
                                          for q in ("F", "S")])
print(f"wrote {OUT / 'fig9.csv'}")
