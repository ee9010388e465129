"""Solved single-asperity curves, computed on demand and stored for reuse.

A curve at (μ, method, accuracy) is solved once with `asperity.solve_curve` (no error estimate)
and its files (`approach.csv`, ..., `result.json`) are kept under $ADHESION_CACHE, else
~/.cache/adhesion-verification. `result.json` is written last, so a folder without it is
solved again. Folders carry the solver's revision (a hash of its source): a changed solver
solves afresh instead of serving an older solver's curves.
"""

import hashlib
import json
import os
from functools import cache
from pathlib import Path

import numpy as np

from .asperity import solve_curve
from .curve import curve_from_columns
from .output import write_curves


def cache_dir():
    """Folder of stored curves."""
    return Path(os.environ.get("ADHESION_CACHE", Path.home() / ".cache" / "adhesion-verification"))


@cache
def solver_revision():
    """First 10 hex digits of the SHA-256 of the solver's source files (fem_asperity/*.py)."""
    digest = hashlib.sha256()
    for path in sorted(Path(__file__).parent.glob("*.py")):
        digest.update(path.read_bytes())
    return digest.hexdigest()[:10]


def stored_curve(mu, *, method="bem", accuracy="default", cache=None, progress=None):
    """(approach `Curve`, events dict of result.json, folder) at `mu`, solved now if not stored."""
    folder = Path(cache or cache_dir()) / f"{method}-{accuracy}-mu{mu:.6g}-{solver_revision()}"
    if not (folder / "result.json").exists():
        result = solve_curve(mu, method=method, accuracy=accuracy, error_estimate=False,
                             progress=progress)
        write_curves(result, folder)
    columns = np.loadtxt(folder / "approach.csv", delimiter=",", skiprows=1, ndmin=2)
    events = json.loads((folder / "result.json").read_text())
    return curve_from_columns(*columns.T), events, folder
