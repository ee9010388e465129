"""Solved single-asperity curves, computed on demand and stored for reuse.

A curve at (μ, method, accuracy) is solved once with `asperity.solve_curve` (no error estimate)
and its files (`approach.csv`, ..., `result.json`) are kept under $ADHESION_CACHE, else
~/.cache/adhesion-verification. `result.json` is written last, so a folder without it is
solved again.
"""

import json
import os
from pathlib import Path

import numpy as np

from .asperity import solve_curve
from .curve import curve_from_columns
from .output import write_curves


def cache_dir():
    """Folder of stored curves."""
    return Path(os.environ.get("ADHESION_CACHE", Path.home() / ".cache" / "adhesion-verification"))


def stored_curve(mu, *, method="bem", accuracy="default", cache=None, progress=None):
    """(approach `Curve`, events dict of result.json, folder) at `mu`, solved now if not stored."""
    folder = Path(cache or cache_dir()) / f"{method}-{accuracy}-mu{mu:.6g}"
    if not (folder / "result.json").exists():
        result = solve_curve(mu, method=method, accuracy=accuracy, error_estimate=False,
                             progress=progress)
        write_curves(result, folder)
    columns = np.loadtxt(folder / "approach.csv", delimiter=",", skiprows=1, ndmin=2)
    events = json.loads((folder / "result.json").read_text())
    return curve_from_columns(*columns.T), events, folder
