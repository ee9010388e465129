"""The surface compliance of a layer bonded to a substrate, for the boundary integral: the
homogeneous half-space of the layer's material (Boussinesq, exact log treatment in
`boussinesq.py`) plus a smooth correction from the Hankel transform.

Under an axisymmetric normal pressure p (no surface shear), with f̃(k) = ∫₀^∞ f(r) J₀(kr) r dr,
the surface deflection of a layer (thickness t, E*_layer = M in units of the substrate's E*)
perfectly bonded to a substrate is

    w̃(k) = 2 p̃(k) C(kt) / (k M),    so    w(r) = (2/M) ∫₀^∞ C(kt) p̃(k) J₀(kr) dk,

with the compliance factor C of Perriot & Barthel (J. Mater. Res. 19 (2004) 600; the kernel of
Li & Chou, Int. J. Solids Struct. 34 (1997) 4463), `compliance_factor`: C → 1 for kt → ∞ (the
layer's half-space) and C → M for kt → 0 (the substrate). C ≡ 1 splits off the layer's
Boussinesq deflection; the rest, (2/M) ∫ (C − 1) p̃ J₀(kr) dk, has a factor C − 1 that falls like
(kt)² e^{−2kt}, so a Gauss rule in k up to K_MAX_T/t takes it. In the Galerkin form of
`bem.BoussinesqSurface` it adds

    D_ij = (2/M) ∫₀^∞ (C(kt) − 1) φ̃_i(k) φ̃_j(k) dk

to the hat functions' coupling, with the hat transforms φ̃_i exact (`hat_transforms`).
"""

import numpy as np
from scipy.special import itj0y0, j0, j1

#: Upper end of the k integral times t: C − 1 ≈ 4b(kt)² e^{−2kt} is below 3e-13 at kt = 18.
#: test_layered.py::test_correction_converges_in_the_k_rule.
K_MAX_T = 18.0
#: The k rule: panels of K_PANEL_R / r_max (16 radians of J₀(kr)J₀(ks)), K_POINTS Gauss points
#: each (methods.md §13); test_correction_converges_in_the_k_rule.
K_PANEL_R, K_POINTS = 8.0, 22
#: Elements with k·length up to this are integrated by Gauss (the exact antiderivatives
#: cancel there), longer ones exactly. test_hat_transforms_match_brute_force_quadrature.
GAUSS_BELOW, GAUSS_POINTS = 2.0, 6
#: (k value, node) entries per block of the correction's sum: `hat_transforms` holds about eight
#: arrays of that size at once, so a block takes about 130 MB whatever the number of nodes.
K_BLOCK_ENTRIES = 2_000_000


def compliance_factor(kt, modulus_ratio, nu_layer, nu_substrate):
    """C(kt) of a layer bonded to a substrate (Perriot & Barthel 2004), normalised by the layer:
    w̃ = 2p̃C/(kE*_layer); C → 1 for kt → ∞, → `modulus_ratio` = E*_layer/E*_substrate for
    kt → 0, ≡ 1 for one material. With x = kt, Γ = G_layer/G_substrate, κ = 3 − 4ν,
    a = (Γκ_s − κ_l)/(Γκ_s + 1), b = (Γ − 1)/(Γ + κ_l):

        C = [1 + 4bx e^{−2x} − ab e^{−4x}] / [1 − (a + b + 4bx²) e^{−2x} + ab e^{−4x}],

    written with e^{−2x} only (no overflow at any kt) and rearranged so that small kt keeps
    full relative precision (an incompressible layer on a rigid substrate has C ≈ (2/3)(kt)³).
    Checked against a direct solve of the layered elasticity problem in test_layered.py."""
    x = np.minimum(np.asarray(kt, dtype=float), 400.0)  # e^{-800} = 0: C = 1 beyond
    nl, ns = float(nu_layer), float(nu_substrate)
    kl, ks = 3.0 - 4.0 * nl, 3.0 - 4.0 * ns
    g = float(modulus_ratio) * (1.0 - nl) / (1.0 - ns)  # Γ = G_layer / G_substrate
    a, b = (g * ks - kl) / (g * ks + 1.0), (g - 1.0) / (g + kl)
    # exact forms of 1 + a, 1 − a, 1 − b, 1 − ab: no cancellation as a, b → ±1
    one_plus_a = 2.0 * (g * ks - (1.0 - 2.0 * nl)) / (g * ks + 1.0)
    one_minus_a, one_minus_b = (1.0 + kl) / (g * ks + 1.0), (1.0 + kl) / (g + kl)
    one_minus_ab = g * (1.0 + ks) * (1.0 + kl) / ((g * ks + 1.0) * (g + kl))
    e = np.exp(-2.0 * x)
    # q = e^{−2x}(sinh 2x − 2x): a series below x = 0.5, where the closed form cancels
    y2 = 4.0 * x * x
    series = 1.0
    for n in (342, 272, 210, 156, 110, 72, 42, 20):
        series = 1.0 + y2 / n * series
    q = np.where(x < 0.5, e * (2.0 * x) * y2 / 6.0 * series,
                 -0.5 * np.expm1(-4.0 * x) - 2.0 * x * e)
    numerator = one_minus_ab + 2.0 * (a * b * q + 2.0 * b * one_plus_a * x * e)
    em = np.expm1(-2.0 * x)
    denominator = (one_minus_a - a * em) * (one_minus_b - b * em) - 4.0 * b * x * x * e
    return numerator / denominator


def hat_transforms(nodes, k):
    """Φ[q, i] = ∫ φ_i(r) J₀(k_q r) r dr for the piecewise-linear hat functions φ_i on `nodes`
    (the first a half hat) at the wavenumbers `k` (> 0). Per element [a, b] of length L: by
    GAUSS_POINTS-point Gauss where kL ≤ GAUSS_BELOW, else exactly from the antiderivatives
    ∫₀^r ρJ₀(kρ)dρ = rJ₁(kr)/k and ∫₀^r ρ²J₀(kρ)dρ = [u²J₁(u) + uJ₀(u) − ∫₀^u J₀]/k³ (u = kr)."""
    nodes, k = np.asarray(nodes, dtype=float), np.asarray(k, dtype=float)
    x, w = np.polynomial.legendre.leggauss(GAUSS_POINTS)
    x, w = 0.5 * (x + 1.0), 0.5 * w
    u = np.multiply.outer(k, nodes)
    p1 = nodes * j1(u) / k[:, None]
    p2 = (u * u * j1(u) + u * j0(u) - itj0y0(u)[0]) / (k**3)[:, None]
    phi = np.zeros((k.size, nodes.size))
    for e, (a, b) in enumerate(zip(nodes[:-1], nodes[1:])):
        length = b - a
        short = k * length <= GAUSS_BELOW
        rising = np.empty(k.size)  # ∫ (ρ − a)/L ρ J₀(kρ) dρ: the hat of node b
        falling = np.empty(k.size)  # ∫ (b − ρ)/L ρ J₀(kρ) dρ: the hat of node a
        rho = a + length * x
        values = j0(np.multiply.outer(k[short], rho)) * (rho * w * length)
        rising[short], falling[short] = values @ x, values @ (1.0 - x)
        d1 = p1[~short, e + 1] - p1[~short, e]
        d2 = p2[~short, e + 1] - p2[~short, e]
        rising[~short] = (d2 - a * d1) / length
        falling[~short] = (b * d1 - d2) / length
        phi[:, e] += falling
        phi[:, e + 1] += rising
    return phi


def k_rule(thickness, r_max):
    """(k, weights): composite Gauss-Legendre on [0, K_MAX_T/t] with panels of width
    K_PANEL_R/r_max (at most 16 radians of the fastest oscillation), K_POINTS points each."""
    k_max = K_MAX_T / thickness
    panels = max(1, int(np.ceil(k_max * r_max / K_PANEL_R)))
    x, w = np.polynomial.legendre.leggauss(K_POINTS)
    edges = np.linspace(0.0, k_max, panels + 1)
    half = 0.5 * np.diff(edges)
    k = (edges[:-1, None] + half[:, None] * (x + 1.0)).ravel()
    return k, (half[:, None] * w).ravel()


def layer_correction(nodes, solid):
    """D (n × n): the Galerkin coupling of the hat functions on `nodes` that the layer of `solid`
    (`fe.Solid`: thickness t in √(Rε), E*_layer/E*_substrate, Poisson's ratios) adds to its
    layer's half-space, (2/M) ∫ (C(kt) − 1) φ̃_i φ̃_j dk, summed in blocks of k values
    (K_BLOCK_ENTRIES)."""
    t, ratio = solid.layer_thickness, solid.layer_modulus_ratio
    k, weights = k_rule(t, float(np.max(nodes)))
    factor = weights * (compliance_factor(k * t, ratio, solid.layer_nu, solid.nu) - 1.0)
    correction = np.zeros((len(nodes), len(nodes)))
    rows = max(256, K_BLOCK_ENTRIES // len(nodes))
    for start in range(0, k.size, rows):
        block = slice(start, start + rows)
        phi = hat_transforms(nodes, k[block])
        correction += phi.T @ (factor[block, None] * phi)
    return (2.0 / ratio) * correction
