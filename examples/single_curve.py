"""One adhesive asperity: approach, jump-in, retraction, jump-out, and the pull-off force.

A rigid sphere approaches an elastic half-space and is then pulled off again, under displacement
control, with Lennard-Jones 9-3 surface forces between them. In the Derjaguin regime (R ≫ ε) the
dimensionless force-separation curve depends on the Tabor parameter μ alone. This script solves
one such curve with the boundary-integral method and answers three questions:

- where does the surface jump into contact on approach, and out of it on retraction?
- what is the pull-off force, and how does it compare with the DMT (−1) and JKR (−3/4) limits
  and with Maugis-Dugdale at the same μ?
- how accurate are those numbers (the solver's own error estimate)?

It saves the curves and a summary with the package's writer and draws the force-separation curve
with matplotlib's object API. EXAMPLES_FAST=1 solves at draft accuracy; EXAMPLES_OUT names the
output folder (default out/examples/single_curve).
"""

# %%
# Settings. μ = 2 lies in the jump-in regime (the measured onset is μ ≈ 0.7, the paper's 0.5), so
# the curve shows both instabilities while the solve stays small (a few hundred nodes). Method
# "bem": the Boussinesq integral of the homogeneous half-space on a radial surface grid, no bulk
# mesh (method "fem" solves the same surface problem with finite elements and also writes stress
# fields). Accuracy "default" sizes the surface elements from the cohesive zone at the contact
# edge; "draft" doubles them and the continuation's turn limit, for a quick look (its error
# estimate, printed below, says how much that costs in accuracy).

import os
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from fem_asperity import Scales, solve_curve, write_all
from fem_asperity.closed_forms.reference import (
    dmt_pull_off,
    jkr_pull_off,
    maugis_dugdale_pull_off,
)

FAST = os.environ.get("EXAMPLES_FAST") == "1"
OUT = Path(os.environ.get("EXAMPLES_OUT", "out/examples/single_curve"))

MU = 2.0
METHOD = "bem"
ACCURACY = "draft" if FAST else "default"

# %%
# Solve. `solve_curve` traces the whole equilibrium curve by pseudo-arc-length continuation and
# reads off the approach and the retraction under δ̄o control, each jump landing where energy
# descent takes it. With `error_estimate=True` (the default) the same curve is also solved with
# surface elements half as long, on the second core, and twice the change of every event is
# reported as its error estimate (`relative_error_estimate`: the same relative to the event).
# `unstable_branch=True` also traces the unstable parts of the S-shaped equilibrium curve between
# the folds (for the plot; it roughly doubles the cost).

result = solve_curve(MU, method=METHOD, accuracy=ACCURACY, unstable_branch=True)
print(f"μ = {result.mu:g}, {result.method}, accuracy '{result.accuracy}': status {result.status}; "
      f"{result.points} points, {result.surface_nodes} surface nodes, {result.wall_s:.2g} s")
print(result.message)

# %%
# The events. Units: separations δ̄o and gaps x̄o in ε, forces P̄ in 2πRΔγ (negative = tensile),
# the compressive contact radius ā_c in √(Rε). `records()` flattens the events into the command
# line's keys; the error estimate holds 2 |event − event on a finer grid| for the key events.

events = result.events.records()
estimate = result.error_estimate or {}
print(f"\n{'event':<18} {'value':>12}  error estimate")
for key, value in events.items():
    if isinstance(value, float):
        err = estimate.get(key)
        print(f"{key:<18} {value:12.6g}  {'' if err is None else f'{err:.1g}'}")
    elif value is not None:
        print(f"{key:<18} {value!s:>12}")

# %%
# Against the closed forms. Under load control DMT (a rigid sphere, μ → 0) pulls off at P̄ = −1
# and JKR (μ → ∞) at −3/4; Maugis-Dugdale interpolates with a Dugdale stress equal to the LJ peak
# tension (λ = 1.157 μ). The LJ pull-off P̄off (the most tensile force along the retraction) must
# lie between DMT and JKR; Maugis-Dugdale's square-well law is only an approximation of the LJ
# law, a few hundredths away at moderate μ.

p_off = result.events.p_off
dmt, jkr = dmt_pull_off().force, jkr_pull_off(mu=MU).force
md = maugis_dugdale_pull_off(mu=MU).force
print(f"\npull-off P̄off = {p_off:.5f}; DMT {dmt:g}, JKR {jkr:g}, Maugis-Dugdale {md:.5f}")

# %%
# Files. `write_all` writes approach.csv, retraction.csv, equilibrium.csv, result.json and
# curve.png all at once or not at all (a staging folder moved into place at the end), so a folder
# holding result.json is complete.

written = write_all(result, OUT)
print("\nwrote " + ", ".join(p.name for p in written) + f" in {OUT}")

# %%
# The force-separation plot, with matplotlib's object API (a `Figure`, no pyplot and no global
# backend: safe inside a notebook or a GUI). The whole equilibrium curve is drawn thin, its
# unstable parts dashed; approach and retraction follow its stable parts and jump where it folds
# (a jump is two points at the same δ̄o). The secondary axes give SI values for one illustrative
# asperity with this μ: R = 1 μm, ε = 0.3 nm, Δγ = 0.1 J/m² (E* is then fixed by μ).

asperity = Scales.for_mu(MU, eps=0.3e-9, R=1e-6, dgamma=0.1)
eq = result.equilibrium
fig = Figure(figsize=(7, 4.5), layout="constrained")
ax = fig.add_subplot()
ax.plot(eq.delta, np.where(eq.stable, eq.p, np.nan), color="0.6", lw=0.8,
        label="equilibrium (stable)")
ax.plot(eq.delta, np.where(eq.stable, np.nan, eq.p), "--", color="0.6", lw=0.8,
        label="equilibrium (unstable)")
ax.plot(result.approach.delta, result.approach.p, color="tab:blue", lw=1.6, label="approach")
ax.plot(result.retraction.delta, result.retraction.p, color="tab:red", lw=1.2, label="retraction")
for level, name, style in ((dmt, "DMT", ":"), (jkr, "JKR", "-."), (md, "Maugis-Dugdale", "--")):
    ax.axhline(level, color="k", ls=style, lw=0.8, label=f"{name} pull-off {level:.3g}")
ax.set_xlim(float(np.min(eq.delta)), min(float(np.max(eq.delta)), 8.0))
ax.set_ylim(-1.1, 1.0)
ax.set_xlabel("separation δ̄o = δo/ε (sphere apex to undeformed surface)")
ax.set_ylabel("force P̄ = P/(2πRΔγ)  (tensile < 0)")
ax.set_title(f"LJ adhesive contact, μ = {MU:g} ({METHOD}, {ACCURACY})")
ax.grid(alpha=0.3)
ax.legend(fontsize=7, loc="upper right")
nm = asperity.length_z * 1e9
ax.secondary_xaxis("top", functions=(lambda d: d * nm, lambda s: s / nm)).set_xlabel(
    "δo [nm] (ε = 0.3 nm)")
nn = asperity.force * 1e9
ax.secondary_yaxis("right", functions=(lambda p: p * nn, lambda f: f / nn)).set_ylabel(
    f"P [nN] (R = 1 μm, Δγ = 0.1 J/m², E* = {asperity.E_star / 1e9:.3g} GPa)")
fig.savefig(OUT / "force_separation.png", dpi=150, bbox_inches="tight")
print(f"wrote {OUT / 'force_separation.png'}")
