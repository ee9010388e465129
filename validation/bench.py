"""Timings of the main operations, for comparing versions: `python -m validation bench [--json]`.

Each operation is timed once after one warm-up call (imports, caches), on the machine it runs on:
compare the numbers of two versions on the same machine only. The operations: one BEM and one FE
curve at μ = 1 `draft` (no estimate), the BEM curve with its estimate, the paper's laws over 101 μ,
and GW F̄max of the paper's law."""

import json
import time

import numpy as np

from fem_asperity.closed_forms.laws import PAPER_LAWS
from fem_asperity.solver.solve import solve_curve


def _operations():
    from gw.integrate import strength
    from gw.laws import PaperLaw
    from gw.surface import RoughSurface

    mus = np.logspace(-2, 2, 101)
    return {
        "bem_curve_mu1_draft": lambda: solve_curve(1.0, method="bem", accuracy="draft",
                                                   error_estimate=False),
        "bem_curve_mu1_draft_with_estimate": lambda: solve_curve(1.0, method="bem",
                                                                 accuracy="draft"),
        "fem_curve_mu1_draft": lambda: solve_curve(1.0, method="fem", accuracy="draft",
                                                   error_estimate=False),
        "paper_laws_101_mu": lambda: PAPER_LAWS.events(mus),
        "gw_f_max_paper_law": lambda: strength(PaperLaw(1.0), RoughSurface(zeta=1.0, omega=1.0)),
    }


def timings():
    """{operation: wall seconds} (the second of two calls)."""
    out = {}
    for name, operation in _operations().items():
        operation()
        start = time.perf_counter()
        operation()
        out[name] = time.perf_counter() - start
    return out


def run(*, as_json=False):
    """Print the timings (a table, or JSON with the provenance); exit code 0."""
    from .report import machine_phrase

    result = timings()
    if as_json:
        from fem_asperity import __version__
        from fem_asperity.plumbing.provenance import git_commit, machine

        from .report import HERE

        print(json.dumps({"version": __version__, "commit": git_commit(HERE),
                          "machine": machine(), "wall_s": result}, indent=1))
    else:
        print(f"on {machine_phrase()}")
        for name, seconds in result.items():
            print(f"{name:40s} {seconds:8.3f} s")
    return 0
