"""How strongly does a rough polysilicon MEMS surface stick, in pascals?

Two polysilicon surfaces of a MEMS device (a cantilever resting on its substrate, say) touch at
the summits of their roughness. Song & Komvopoulos model this as a rigid Greenwood-Williamson
(GW) rough surface against an elastic half-space whose asperities each obey the single-asperity
Lennard-Jones laws of the paper (eqs. 2-19). This script

1. turns SI material and surface data into the paper's dimensionless groups: the effective
   modulus E*, the Tabor parameter μ and the natural scales of one asperity; ζ = σ/ε and McCool's
   ω from σRη (eq. 20);
2. computes the strength of adhesion F̄max (the largest tensile total force, eqs. 22-28) with the
   paper's closed-form asperity laws;
3. converts F̄max back to SI: an adhesion pressure in Pa per nominal (apparent) area, and shows
   how quickly it falls as the surface gets rougher;
4. checks the paper's law on this very surface against the asperity law solved by the boundary
   integral (what `python -m gw fmax ... --compare` prints), and says when the closed form
   cannot be trusted.

The same surface on the command line, in SI from end to end:

    python -m gw fmax --E1 160e9 --nu1 0.22 --E2 160e9 --nu2 0.22 --dgamma 0.1 --eps 3e-10 \
                      --R 4e-7 --sigma 2e-9 --density 4e13 --compare

Run it with `python examples/mems_rough_surface.py`; EXAMPLES_FAST=1 uses fewer roughness values,
EXAMPLES_OUT names the output folder (default out/examples/mems_rough_surface).
"""

# %%
# Settings. Every input is a module-level constant in SI units, and all of them are illustrative:
# change them to your device's. The material is polysilicon, E ≈ 160 GPa and ν ≈ 0.22, on both
# sides. The work of adhesion Δγ = 0.1 J/m² is of the order of an oxide-covered (hydrophilic)
# surface in humid air; dry, hydrophobic surfaces adhere less. ε = 0.3 nm is an interatomic
# equilibrium spacing (the value the validation figures assume: the paper states none). The GW
# surface: summit radius R = 400 nm and summit density η = 4e13 m⁻² (40 per μm²), chosen so that
# σRη stays above McCool's limit over the roughness sweep.

import csv
import os
from pathlib import Path

import gw
from fem_asperity import Scales, effective_modulus

FAST = os.environ.get("EXAMPLES_FAST") == "1"
OUT = Path(os.environ.get("EXAMPLES_OUT", "out/examples/mems_rough_surface"))

E_POLY = 160e9  # Young's modulus [Pa]
NU_POLY = 0.22  # Poisson's ratio
DGAMMA = 0.1  # work of adhesion Δγ [J/m²]
EPS = 0.3e-9  # LJ equilibrium spacing ε [m]
RADIUS = 400e-9  # asperity (summit) radius R [m]
DENSITY = 4e13  # summit density η [1/m²]
SIGMA = 2e-9  # rms roughness σ of the headline surface [m]
#: Roughness sweep [m]. The smallest must keep σRη above 0.01928, where McCool's ω stops being real.
SIGMAS = (2e-9, 5e-9) if FAST else (1.5e-9, 2e-9, 3e-9, 5e-9, 10e-9)

# %%
# Step 1: one asperity. Both bodies are polysilicon, so the effective modulus combines two equal
# compliances, E* = [2(1 − ν²)/E]⁻¹. `Scales` holds one asperity's inputs, derives the Tabor
# parameter μ = (RΔγ²/(E*²ε³))^(1/3) (eq. 1) and gives the natural scales: vertical ε, radial
# √(Rε), force 2πRΔγ (Bradley's pull-off of a rigid sphere). It warns if R/ε < 300 (Derjaguin's
# approximation, on which the μ-only scaling rests, would be doubtful); here R/ε ≈ 1300.

E_STAR = effective_modulus(E1=E_POLY, nu1=NU_POLY, E2=E_POLY, nu2=NU_POLY)
scales = Scales(E_star=E_STAR, dgamma=DGAMMA, eps=EPS, R=RADIUS)
MU = scales.mu
print(f"E* = {E_STAR / 1e9:.4g} GPa, R/ε = {RADIUS / EPS:.0f}, Tabor parameter μ = {MU:.4g}")
print(f"asperity scales: ε = {scales.length_z * 1e9:.3g} nm, "
      f"√(Rε) = {scales.length_r * 1e9:.3g} nm, 2πRΔγ = {scales.force * 1e9:.4g} nN")
# μ ≈ 0.28: a stiff, DMT-like asperity. It stays below the measured jump-in onset (μ ≈ 0.7), so
# each asperity approaches continuously (the paper's regime μ < 0.5, eqs. 7, 9-11, 16, 17).

# %%
# Step 2: the rough surface. The paper writes the GW integrals in dimensionless form with two
# groups: ζ = σ/ε (roughness against the range of adhesion) and ω = σ_s/σ (spread of the summit
# heights against the surface heights) from McCool's eq. 20, ω = [1 − 3.717e-4/(σRη)²]^½.
# `RoughSurface.from_physical` computes both (and refuses σRη ≤ 0.01928 with an InputError).
# Caution: the height density of eq. 21 as printed, φ̃(z̃) = ω/√(2π) exp(−ω²z̃²/2), which `gw`
# follows, spreads the summit heights by σ/ω, whereas McCool's σ_s = ωσ would mean ωσ. The two
# agree at ω = 1 (as in the paper's figures); at ω < 1 this surface is taken as rougher than
# McCool's summits, and F̄max comes out smaller.

SIGMA_R_ETA = SIGMA * RADIUS * DENSITY
OMEGA = float(gw.omega_mccool(SIGMA_R_ETA))
surface = gw.RoughSurface.from_physical(sigma=SIGMA, radius=RADIUS, density=DENSITY, eps=EPS)
print(f"σ = {SIGMA * 1e9:g} nm: σRη = {SIGMA_R_ETA:.4g}, ω = {OMEGA:.4f}, "
      f"ζ = σ/ε = {surface.zeta:.4g}, ξ = ζ/(μ + 1) = {surface.zeta / (MU + 1.0):.4g}")

# %%
# Step 3: the strength of adhesion. `PaperLaw(μ)` is the paper's closed-form asperity law (force
# P̄(δ̄o) and area Ā(δ̄o)); `strength` integrates it over the Gaussian summit heights (eqs. 22-28)
# on a grid of mean separations d̃ = d/σ and refines the most tensile point. F̄max is positive:
# the paper defines it with a minus sign, F̄max = −min F̄.

law = gw.PaperLaw(MU)
best = gw.strength(law, surface)
print(f"F̄max = {best.f_max:.4g} at d̃ = {best.d_at_max:.3f} "
      f"(d = {best.d_at_max * SIGMA * 1e9:.3g} nm)")

# %%
# Step 4: back to SI. The paper normalises the total force of N = A₀η summits on the nominal area
# A₀ by N times one asperity's force scale (eqs. 23, 27; gw/integrate.py):
#
#     F̄ = F / (2πR A₀ Δγ η),   so   F / A₀ = F̄ · 2πRΔγ · η.
#
# 2πRΔγ [N] is `scales.force`, η [1/m²] the summits per square metre: their product is a pressure.
# `Strength.si` does this (and d = d̃σ).

PRESSURE = best.si(scales, sigma=SIGMA, density=DENSITY).pressure_max
print(f"F/A₀ = F̄max · 2πRΔγ · η = {best.f_max:.4g} × {scales.force:.4g} N × {DENSITY:.3g} m⁻² "
      f"= {PRESSURE:.4g} Pa ({PRESSURE / 1e3:.3g} kPa)")
# For scale: if every summit pulled with Bradley's 2πRΔγ at once (F̄ = 1), the pressure would be
# 2πRΔγη; roughness leaves only the fraction F̄max of it.
print(f"upper bound 2πRΔγη (every summit at Bradley's pull-off): {scales.force * DENSITY:.4g} Pa")

# %%
# Step 5: the roughness sweep. Each σ changes ζ and, through σRη, ω. The table shows the strength
# of adhesion falling by orders of magnitude as σ grows from a few ε to tens of ε: rougher
# surfaces stick less. At the smallest σ, ω falls fast (σRη nears McCool's limit) and the summit
# spread σ/ω of eq. 21 grows with it, which flattens the start of the table.

rows = []
for sigma in SIGMAS:
    s = gw.RoughSurface.from_physical(sigma=sigma, radius=RADIUS, density=DENSITY, eps=EPS)
    st = gw.strength(law, s)
    si = st.si(scales, sigma=sigma, density=DENSITY)
    rows.append({"sigma_nm": sigma * 1e9, "sigma_r_eta": sigma * RADIUS * DENSITY,
                 "omega": s.omega, "zeta": s.zeta, "mu": MU, "f_max": st.f_max,
                 "d_at_max": st.d_at_max, "d_at_max_nm": si.d_at_max * 1e9,
                 "pressure_pa": si.pressure_max})

print("\n" + " ".join(f"{h:>{w}}" for h, w in (("σ [nm]", 7), ("σRη", 7), ("ω", 6), ("ζ", 7),
                                               ("F̄max", 10), ("d̃ at max", 9), ("F/A₀ [Pa]", 11))))
for r in rows:
    print(f"{r['sigma_nm']:7.3g} {r['sigma_r_eta']:7.4f} {r['omega']:6.3f} {r['zeta']:7.3g} "
          f"{r['f_max']:10.4g} {r['d_at_max']:9.3f} {r['pressure_pa']:11.4g}")

# %%
# Step 6: can the paper's law be trusted here? Its closed forms are fits; `gw.solved_law` is the
# approach curve of one asperity at this μ solved by the boundary integral (stored under
# $ADHESION_CACHE, so a second run reads it), interpolated with a stated error. The same
# integration on the headline surface, with each law, gives the strength both ways; the
# command-line `--compare` warns above a 10 % difference (`gw.__main__.COMPARE_WARNING`).

SOLVED_ACCURACY = "draft" if FAST else "default"
solved = gw.solved_law(MU, method="bem", accuracy=SOLVED_ACCURACY)
best_solved = gw.strength(solved, surface)
OFF = best.f_max / best_solved.f_max - 1.0
print(f"\nsolved BEM law ({SOLVED_ACCURACY}): F̄max = {best_solved.f_max:.4g} "
      f"(F/A₀ = {best_solved.si(scales, sigma=SIGMA, density=DENSITY).pressure_max:.4g} Pa); "
      "the paper's law is "
      f"{OFF:+.1%} off it (interpolation error of the solved law {solved.interpolation_error:.1e})")

# %%
# Output: the sweep as CSV.

OUT.mkdir(parents=True, exist_ok=True)
path = OUT / "mems_rough_surface.csv"
with open(path, "w", newline="") as file:
    writer = csv.DictWriter(file, fieldnames=list(rows[0]), lineterminator="\n")
    writer.writeheader()
    writer.writerows({k: f"{v:.10g}" for k, v in r.items()} for r in rows)
print(f"\nwrote {path}")
