"""Solved single-asperity curves, computed on demand and stored for reuse.

A curve at (μ, method, accuracy, solid) is solved once with `solver.solve.solve_curve` and its files
(`approach.csv`, ..., `result.json`, `events.json`) are kept under $ADHESION_CACHE, else
~/.cache/adhesion-verification, with `manifest.json` (their checksums) written last: a folder
without it is solved again, one whose files no longer match it is moved aside and solved again.
Folders carry the solver's revision (`solver_revision`): a changed solver solves afresh instead
of serving an older solver's curves. Processes that share a store solve each curve once, the
others waiting for it (`lock_entry`). A store that holds what is asked for is only read, so it
may be read-only; one that cannot serve (a file in its place, a corrupt entry it cannot move
aside) is an `InputError` naming $ADHESION_CACHE and the path.
"""

import contextlib
import hashlib
import io
import json
import os
import warnings
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from ..curves.curve import Curve, curve_from_columns
from ..curves.events import Events, Jump
from ..plumbing.errors import InputError
from ..plumbing.files import nearest_existing, writable_folder, write_atomic
from ..plumbing.revision import solver_revision
from ..solids.fe import Solid
from ..solver.estimate import estimate_kind
from ..solver.presets import METHODS, PRESETS
from ..solver.result import curve_files, relative_estimate
from ..solver.solve import solvable_mu, solve_curve

try:
    import fcntl
except ImportError:  # no flock (Windows): no lock, at worst a curve solved twice
    fcntl = None

#: Cost columns of a stored curve (from its result.json).
COST_KEYS = ("dofs", "surface_nodes", "points", "newton_iterations", "wall_s")
#: How errors name the store: by the setting that chooses its folder.
STORE = "the store ($ADHESION_CACHE)"


@dataclass(frozen=True)
class StoredCurve:
    """A stored curve: its approach and retraction paths and the equilibrium curve traced
    (`Curve`; the whole curve where stored with `unstable_branch`), `Events`, the error estimate
    (None where the curve was stored without one) and how it was made (`estimated_by`), the
    solve's status and message (`CurveResult.status`: 'ok' unless it calls for a finer
    accuracy), its cost (`COST_KEYS`) and its folder."""

    mu: float
    method: str
    accuracy: str
    approach: Curve
    retraction: Curve
    equilibrium: Curve
    events: Events
    error_estimate: dict | None
    status: str
    message: str
    cost: dict
    folder: Path
    estimated_by: str | None = None

    @property
    def relative_error_estimate(self):
        """`error_estimate` relative to each event's magnitude."""
        return relative_estimate(self.error_estimate, self.events.records())


def cache_dir():
    """Folder of stored curves."""
    return Path(os.environ.get("ADHESION_CACHE", Path.home() / ".cache" / "adhesion-verification"))


def _events_from_dict(data):
    jumps = {k: None if data[k] is None else Jump(**data[k]) for k in ("jump_in", "jump_out")}
    return Events(**{**data, **jumps})


def _store_folder(folder):
    """Refuse (`InputError`) the store's `folder` where a file stands in its place or in a
    parent's: reading under it fails as if every entry were corrupt."""
    existing = nearest_existing(Path(folder))
    if not existing.is_dir():
        raise InputError(f"{STORE} must be a folder; {existing} is a file")


def mu_key(mu):
    """μ as the store tells curves apart: to 12 significant digits (μ equal to that many digits
    share a curve)."""
    return float(f"{float(mu):.12g}")


def check_entry(mu, method, accuracy):
    """`mu` as the store keys it (`mu_key`), once μ, method and accuracy are found to be what
    `solve_curve` accepts (else `InputError`): checked before the store creates any file."""
    mu = solvable_mu(mu)
    if method not in METHODS or accuracy not in PRESETS:
        raise InputError(f"method must be one of {', '.join(METHODS)} and accuracy one of "
                         f"{', '.join(PRESETS)}; got {method!r}, {accuracy!r}")
    return mu_key(mu)


def curve_folder(mu, *, method, accuracy, error_estimate, estimate_by="auto",
                 unstable_branch=False, solid=Solid(), cache=None):
    """Where the curve at (`mu`, method, accuracy, solid) of this solver revision is stored;
    curves without the error estimate, with each kind of it (`estimate.estimate_kind` of
    `estimate_by`), and with the whole equilibrium curve (`unstable_branch`), are kept apart
    (each costs more); a solid other than the default adds its Poisson's ratio and layer."""
    kind = estimate_kind(estimate_by, method, solid)  # refused as solve_curve refuses it
    extras = (f"-estimated-{kind}" if error_estimate else "") + ("-whole" if unstable_branch
                                                                 else "")
    if solid.layer_thickness is not None:
        extras += (f"-layer-t{solid.layer_thickness:.12g}-M{solid.layer_modulus_ratio:.12g}"
                   f"-nu{solid.nu:.12g}-{solid.layer_nu:.12g}")
    elif solid != Solid():  # ν enters the FE's truncation
        extras += f"-nu{solid.nu:.12g}"
    name = f"{method}-{accuracy}{extras}-mu{mu_key(mu):.12g}-{solver_revision()}"
    return Path(cache or cache_dir()) / name


#: The files of a stored curve, each recorded in the manifest with its SHA-256.
STORED_FILES = ("approach.csv", "retraction.csv", "equilibrium.csv", "result.json",
                "events.json")
#: Written last: a folder without it is incomplete; a file that no longer matches it is corrupt.
MANIFEST = "manifest.json"


class StoreWarning(UserWarning):
    """A stored entry was unreadable or corrupt: moved aside and solved again."""


def _digest(data):
    return hashlib.sha256(data if isinstance(data, bytes) else data.encode()).hexdigest()


def _move_aside(path, what):
    """Rename the corrupt `path` to the first free `<path>.corrupt-N` and warn in one line."""
    aside = next(path.with_name(f"{path.name}.corrupt-{n}") for n in range(1, 10**6)
                 if not path.with_name(f"{path.name}.corrupt-{n}").exists())
    try:
        os.replace(path, aside)
    except OSError as exc:  # e.g. a read-only store
        raise InputError(f"{STORE}: {path} is corrupt and cannot be moved aside "
                         f"({exc.strerror}); make the store writable, or remove that "
                         "entry") from None
    warnings.warn(f"stored {what} {path.name} was corrupt: moved to {aside.name}, computing it "
                  "again", StoreWarning, stacklevel=3)


def read_stored_json(path, build):
    """`build(data)` of the stored JSON file `path`; None if it is not there, or unreadable (then
    moved aside with a `StoreWarning`, so that the caller computes it again)."""
    path = Path(path)
    _store_folder(path.parent)
    try:
        return build(json.loads(path.read_text()))
    except FileNotFoundError:
        return None
    except (OSError, ValueError, KeyError, TypeError):
        _move_aside(path, "file")
        return None


def stored_json(path, build, compute, dump):
    """`build` of the stored JSON `path`, or `compute()` stored there as `dump(found)`: the store
    of results smaller than a curve (the onset, the refit)."""
    found = read_stored_json(path, build)
    if found is None:
        writable_folder(Path(path).parent, STORE)  # before computing
        found = compute()
        write_atomic(path, json.dumps(dump(found), indent=1) + "\n")
    return found


def keep(result, folder):
    """Store the `CurveResult` in `folder`: its curves, result.json and events.json, then the
    manifest of their checksums."""
    folder = Path(folder)
    files = {**curve_files(result),
             "events.json": json.dumps(asdict(result.events), indent=1) + "\n"}
    for name, text in files.items():
        write_atomic(folder / name, text)
    manifest = {name: _digest(text) for name, text in files.items()}
    write_atomic(folder / MANIFEST, json.dumps(manifest, indent=1) + "\n")


#: What `lock_entry` returns where there is no flock.
NO_LOCK = "no lock"


def lock_entry(folder, wait=True):
    """Take the lock of the store entry `folder` (flock of the file `<folder>.lock`), held while
    its curve is checked and solved, so that two processes asking for one curve solve it once:
    the second waits, then reads it. wait=False: None at once where another process holds it.
    Give the lock to `unlock_entry`, which removes its file.

    The file is removed while it is still locked, and a lock counts only if the locked file is
    still the one at its name, else it is taken again: a process that waited on the file wakes
    holding a removed file, while a newcomer may have locked a new one of that name. (Removing
    it after unlocking could instead remove a file that another process has just locked.)"""
    if fcntl is None:
        return NO_LOCK
    path = folder.with_name(folder.name + ".lock")
    path.parent.mkdir(parents=True, exist_ok=True)
    while True:
        lock = open(path, "a")
        try:
            fcntl.flock(lock, fcntl.LOCK_EX if wait else fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            lock.close()
            return None
        except BaseException:  # e.g. Ctrl-C while waiting
            lock.close()
            raise
        if _still_named(lock, path):
            return lock
        lock.close()


def _still_named(lock, path):
    """Whether the open file `lock` is still the file at `path`."""
    try:
        return os.path.samestat(os.fstat(lock.fileno()), os.stat(path))
    except FileNotFoundError:
        return False


def unlock_entry(lock):
    """Release a lock of `lock_entry`: remove its file, then unlock it (closing it)."""
    if lock is NO_LOCK:
        return
    try:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(lock.name)
    finally:
        lock.close()


@contextlib.contextmanager
def _entry_lock(folder):
    """Hold the lock of the store entry `folder` (`lock_entry`) inside the block."""
    lock = lock_entry(folder)
    try:
        yield
    finally:
        unlock_entry(lock)


def _curve(data):
    return curve_from_columns(*np.loadtxt(io.BytesIO(data), delimiter=",", skiprows=1,
                                          ndmin=2).T)


def _parse(folder, files):
    """The `StoredCurve` of the file contents `files` (name → bytes) of `folder`."""
    result, events = json.loads(files["result.json"]), json.loads(files["events.json"])
    return StoredCurve(result["mu"], result["method"], result["accuracy"],
                       _curve(files["approach.csv"]), _curve(files["retraction.csv"]),
                       _curve(files["equilibrium.csv"]), _events_from_dict(events),
                       result["error_estimate"], result["status"], result["message"],
                       {key: result[key] for key in COST_KEYS}, folder,
                       result["estimated_by"])


def load_stored(folder):
    """The `StoredCurve` kept in `folder` (each file read once), or None if there is none. An
    entry whose files no longer match their manifest (cut, garbled, missing) or do not parse is
    moved aside (`<folder>.corrupt-N`) with a `StoreWarning`, and counts as none."""
    folder = Path(folder)
    _store_folder(folder.parent)
    try:
        recorded = json.loads((folder / MANIFEST).read_text())
    except FileNotFoundError:
        return None
    except (OSError, ValueError):
        recorded = {}
    try:
        files = {name: (folder / name).read_bytes() for name in STORED_FILES}
        if all(_digest(data) == recorded.get(name) for name, data in files.items()):
            return _parse(folder, files)
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        pass
    _move_aside(folder, "curve")
    return None


def stored_curve(mu, *, method="bem", accuracy="default", error_estimate=False,
                 unstable_branch=False, solid=Solid(), cache=None, progress=None):
    """`StoredCurve` at `mu` on `solid`, solved now (and stored) if not stored yet;
    `unstable_branch`: its `equilibrium` is the whole curve, unstable branches included
    (`solve_curve`)."""
    check_entry(mu, method, accuracy)  # before any file is made
    folder = curve_folder(mu, method=method, accuracy=accuracy, error_estimate=error_estimate,
                          unstable_branch=unstable_branch, solid=solid, cache=cache)
    stored = load_stored(folder)
    if stored is not None:
        return stored
    writable_folder(folder.parent, STORE)  # before solving
    with _entry_lock(folder):
        stored = load_stored(folder)  # another process may have solved it while we waited
        if stored is None:
            keep(solve_curve(mu, method=method, accuracy=accuracy, error_estimate=error_estimate,
                             unstable_branch=unstable_branch, solid=solid, progress=progress),
                 folder)
            stored = load_stored(folder)
    return stored
