"""Input checks at the package boundary: one clear error naming the parameter and its range."""

import warnings

import numpy as np

from .errors import DerjaguinWarning, InputError

#: Below this R/ε the Derjaguin approximation is refused outright.
DERJAGUIN_REFUSE = 10.0
#: Below this R/ε a warning is issued (the paper works with R/ε > 300).
DERJAGUIN_WARN = 300.0


def _scalar_or_array(arr):
    return float(arr) if arr.ndim == 0 else arr


def in_range(name, value, lo=-np.inf, hi=np.inf, *, closed_lo=False, unit="", why=""):
    """Return `value` as float (or float array) if every entry lies in (lo, hi), else raise.

    `closed_lo` admits `lo` itself. The upper end is always open, so +inf and NaN never pass.
    `why`: the reason for the range, appended to the error.
    """
    try:
        kind = np.asarray(value).dtype.kind
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        kind = None
    if kind not in ("i", "u", "f"):  # None, True or "1" are no numbers, though numpy casts them
        raise InputError(f"{name} must be a real number; got {value!r}")
    with np.errstate(invalid="ignore"):
        ok = np.isfinite(arr) & (arr < hi) & ((arr >= lo) if closed_lo else (arr > lo))
    if not ok.all():
        bad = arr[~ok].flat[0] if arr.ndim else float(arr)
        if np.isinf(lo) and np.isinf(hi):
            allowed = "finite"
        else:
            allowed = f"in {'[' if closed_lo else '('}{lo:g}, {hi:g}){' ' + unit if unit else ''}"
        raise InputError(f"{name} must be {allowed}; got {float(bad)!r}"
                         + (f": {why}" if why else ""))
    return _scalar_or_array(arr)


def finite_result(value, what):
    """`value` if every entry is finite, else `InputError` saying that `what` (the quantity and
    the inputs that produced it; a callable giving that text) leaves the float range: no inf or
    NaN leaves the package."""
    if np.all(np.isfinite(value)):
        return value
    what = what() if callable(what) else what
    raise InputError(f"{what} is beyond the float range (about 1.8e308); use less extreme inputs")


def positive(name, value, unit=""):
    """Return `value` if it is finite and > 0 everywhere, else raise `InputError`."""
    return in_range(name, value, 0.0, np.inf, unit=unit)


def poisson(name, value):
    """Poisson's ratio in the open interval (-1, 0.5) (0.5 would lock the FE formulation)."""
    return in_range(name, value, -1.0, 0.5)


def derjaguin(R, eps):
    """Refuse R/ε < 10, warn for R/ε < 300: below that the problem no longer depends on μ alone."""
    ratio = float(np.min(np.asarray(R) / np.asarray(eps)))
    if ratio < DERJAGUIN_REFUSE:
        raise InputError(
            f"R/eps must be >= {DERJAGUIN_REFUSE:g} for the Derjaguin approximation; "
            f"got {ratio:.4g}"
        )
    if ratio < DERJAGUIN_WARN:
        warnings.warn(
            f"R/eps = {ratio:.4g} < {DERJAGUIN_WARN:g}: the Derjaguin approximation (results "
            "depending on the Tabor parameter alone) may be inaccurate",
            DerjaguinWarning,
            stacklevel=3,
        )
