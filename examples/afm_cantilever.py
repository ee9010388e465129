"""An AFM tip on a compliant cantilever: where it snaps in and out, in newtons and nanometres.

An AFM does not move the tip; it moves the cantilever's base (the piezo) and reads the
cantilever's deflection. The tip jumps where the force gradient reaches the cantilever's
stiffness K, earlier than under displacement control and even where a rigid holder would show no
jump at all. This script takes a silicon-nitride-like tip on a soft polymer in SI units, solves
the curve twice (rigid holder and cantilever) and answers:

- does the rigid holder see a jump-in at this Tabor parameter? does the cantilever?
- at which piezo positions does the tip snap in and out, and with which forces?
- how do the snap-in and pull-off compare with Bradley's rigid-sphere force, −2πRΔγ?
- what changes when the polymer is a thin film spin-coated on silicon, as AFM samples often are?

EXAMPLES_FAST=1 solves at draft accuracy; EXAMPLES_OUT names the output folder (default
out/examples/afm_cantilever).
"""

# %%
# Inputs, SI. A 20 nm tip (R) on a polymer of E* = 3 GPa with Δγ = 0.05 J/m² and ε = 0.3 nm:
# μ ≈ 0.59, below the onset of jump-in under displacement control (≈ 0.70): a rigid holder
# would see no snap-in, the AFM does. The cantilever, K = 0.5 N/m, is a soft contact-mode lever.
# R/ε ≈ 67 is well below the Derjaguin regime, so the exact sphere profile is solved
# (radius_ratio).

import os
import warnings
from pathlib import Path

from fem_asperity import DerjaguinWarning, Scales, Solid, solve_curve, write_all

FAST = os.environ.get("EXAMPLES_FAST") == "1"
OUT = Path(os.environ.get("EXAMPLES_OUT", "out/examples/afm_cantilever"))

E_STAR, DGAMMA, EPS, R = 3e9, 0.05, 0.3e-9, 20e-9  # Pa, J/m², m, m
K = 0.5  # N/m
ACCURACY = "draft" if FAST else "default"

with warnings.catch_warnings():  # the Derjaguin warning is moot: the exact sphere is solved
    warnings.simplefilter("ignore", DerjaguinWarning)
    scales = Scales(E_star=E_STAR, dgamma=DGAMMA, eps=EPS, R=R)
k_bar = K * EPS / scales.force  # the cantilever's stiffness in 2πRΔγ/ε
print(f"μ = {scales.mu:.4g}, R/ε = {R / EPS:.3g}, k̄ = Kε/(2πRΔγ) = {k_bar:.4g}")

# %%
# Solve under displacement control (a rigid holder) and under load-line control (the
# cantilever). The cantilever's curve is read off the whole equilibrium curve, so both solves
# trace it; each comes with its error estimate.

options = dict(method="bem", accuracy=ACCURACY, radius_ratio=R / EPS)
rigid = solve_curve(scales.mu, unstable_branch=True, **options)
lever = solve_curve(scales.mu, spring_constant=k_bar, **options)
for name, result in (("rigid holder", rigid), ("cantilever", lever)):
    print(f"{name}: status {result.status}; jump-in: {result.events.jump_in is not None}")

# %%
# As the AFM user reads it. The piezo position z = ε z̄ where the tip snaps in and out, the
# deflection −P/K just before each snap, and the pull-off force (the most tensile force on
# retraction). Forces in nN, positions in nm.

row = lever.records()
si = scales.to_si(row)  # the events in N and m
pull_off = si["p_off"]
print(f"snap-in at piezo z = {si['z_jump_in'] * 1e9:.3f} nm, force "
      f"{si['p_jump_before'] * 1e9:.3f} nN (deflection {-si['p_jump_before'] / K * 1e9:.3f} nm)")
print(f"snap-out at piezo z = {si['z_jump_out'] * 1e9:.3f} nm; pull-off force "
      f"{pull_off * 1e9:.3f} nN = {row['p_off']:.4f} × 2πRΔγ (Bradley: −1, JKR: −0.75)")
estimate = lever.relative_error_estimate or {}
print(f"relative error estimate of the pull-off force: {estimate.get('p_off', float('nan')):.2g}")

# %%
# The polymer as a film, FILM nm thick on silicon (E* = 169 GPa/(1 − 0.22²)), under the same
# cantilever, solved here by the finite elements (the boundary integral takes the bonded layer
# too, through its layered kernel: docs/layered.md). μ is now the silicon's, far below the
# polymer's: the elements are sized for the film's own Tabor parameter, the more compliant
# material (the result says so).
# The film is thinner than the tip's contact zone is wide, so the stiff substrate shows
# through: the contact is stiffer than on bulk polymer.

FILM = 2e-9  # m
E_SILICON = 169e9 / (1.0 - 0.22**2)  # Pa
with warnings.catch_warnings():
    warnings.simplefilter("ignore", DerjaguinWarning)
    silicon = Scales(E_star=E_SILICON, dgamma=DGAMMA, eps=EPS, R=R)
coating = Solid(nu=0.22, layer_thickness=FILM / silicon.length_r,
                layer_modulus_ratio=E_STAR / E_SILICON, layer_nu=0.35)
film = solve_curve(silicon.mu, method="fem", accuracy=ACCURACY, radius_ratio=R / EPS,
                   solid=coating, spring_constant=k_bar)
print(f"film on silicon ({coating.description()}, μ_silicon = {silicon.mu:.3g}): status "
      f"{film.status}; {film.message}")
film_si = scales.to_si(film.records())  # the polymer's force scale: same R, Δγ and ε
print(f"pull-off {film_si['p_off'] * 1e9:.3f} nN against {pull_off * 1e9:.3f} nN on bulk "
      f"polymer; snap-in from piezo z = {film_si['z_jump_in'] * 1e9:.3f} nm against "
      f"{si['z_jump_in'] * 1e9:.3f} nm")

# %%
# Files: the curves, result.json (every input, the version, the solver revision), paths_si.csv
# (each point's force in N, the piezo position and the deflection in m) and cantilever.png, the
# deflection against the piezo position as the instrument records it.

written = write_all(lever, OUT, scales)
print("wrote " + ", ".join(p.name for p in written) + f" to {OUT}/")
