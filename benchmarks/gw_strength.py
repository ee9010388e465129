"""Benchmark: cost of the GW strength of adhesion with the paper's law (issue 5's targets).

One F̄max (μ = 1, ζ = 6.67, ω = 1), best of 20 repeats, and a full Fig. 11 sweep (41 μ in
[0.01, 100] × σ = 0.5, 1, 2 nm at ε = 0.3 nm), best of 3.

    python benchmarks/gw_strength.py
"""

import platform
import time

import numpy as np

from gw.integrate import strength
from gw.laws import PaperLaw
from gw.surface import RoughSurface


def best(fn, repeats):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return min(times)


def main():
    one = best(lambda: strength(PaperLaw(1.0), RoughSurface(6.67)), 20)
    mus = np.logspace(-2, 2, 41)
    sweep = best(lambda: [strength(PaperLaw(mu), RoughSurface(s / 0.3))
                          for s in (0.5, 1.0, 2.0) for mu in mus], 3)
    print(f"GW strength benchmark ({platform.machine()}, Python {platform.python_version()})")
    print(f"one F_max (mu = 1, zeta = 6.67): {one * 1e3:.2f} ms")
    print(f"Fig. 11 sweep (123 F_max): {sweep:.2f} s")


if __name__ == "__main__":
    main()
