"""Tabulated asperity laws from solved single-asperity curves, computed on demand and stored.

A curve at (μ, method, accuracy) is solved once with `fem_asperity.asperity.solve_curve` and its
files (`approach.csv`, `result.json`, ...) kept under the cache folder: $ADHESION_CACHE, else
~/.cache/adhesion-verification. `result.json` is written last, so a folder without it is
solved again.
"""

import json
import os
from pathlib import Path

import numpy as np

from fem_asperity.asperity import solve_curve
from fem_asperity.curve import curve_from_columns
from fem_asperity.output import write_curves

from .laws import TabulatedLaw


def cache_dir():
    """Folder of stored curves."""
    return Path(os.environ.get("ADHESION_CACHE", Path.home() / ".cache" / "adhesion-verification"))


def solved_law(mu, *, method="bem", accuracy="default", cache=None, progress=None):
    """`TabulatedLaw` from the approach path of the curve at `mu` (solved now if not stored)."""
    folder = Path(cache or cache_dir()) / f"{method}-{accuracy}-mu{mu:.6g}"
    if not (folder / "result.json").exists():
        result = solve_curve(mu, method=method, accuracy=accuracy, error_estimate=False,
                             progress=progress)
        write_curves(result, folder)
    columns = np.loadtxt(folder / "approach.csv", delimiter=",", skiprows=1, ndmin=2)
    approach = curve_from_columns(*columns.T)
    events = json.loads((folder / "result.json").read_text())
    return TabulatedLaw(mu, approach, delta_o_star=events["delta_o_star"], name=method,
                        source=str(folder))
