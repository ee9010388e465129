"""File output that loses nothing: single files written to a temporary file beside the target
and renamed over it; a command's set of files staged and moved into its output folder only
whole, replacing only what that command wrote there before (its record says which)."""

import contextlib
import json
import os
import shutil
import tempfile
from pathlib import Path

from .errors import InputError


def _umask():
    mask = os.umask(0)
    os.umask(mask)
    return mask


@contextlib.contextmanager
def atomic_path(path):
    """Yield a temporary path beside `path` (same suffix) for a writer that needs a file name;
    on success it is renamed over `path`, on failure removed."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.stem}.", suffix=path.suffix)
    os.close(fd)
    try:
        os.chmod(tmp, 0o666 & ~_umask())
        yield tmp
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


#: Names of the package's own entries in an output folder: its record (and the record's
#: temporary file while it is written) and its staging folders. They are never a user's.
OURS_PREFIX = ".adhesion-"
#: Prefix of staging folders and of folders renamed aside, then the writer's process id: a later
#: run removes a killed one's and leaves a running one's (methods.md §13); test_files.py.
STAGE_PREFIX = OURS_PREFIX + "stage-"
#: An output folder's record of the command that wrote it and every file it wrote: a later run
#: of that command replaces those and nothing else; test_files.py.
RECORD = OURS_PREFIX + "output.json"


def nearest_existing(path):
    """`path` or its nearest ancestor that exists."""
    return next(p for p in (path, *path.absolute().parents) if p.exists())


def writable_folder(folder, option):
    """`folder` as a Path if it is, or can be made, a writable folder; else an `InputError` that
    names `option` and the reason, before any work is done. Writability is tried (a temporary
    folder made and removed), not asked of `os.access`, which says yes to root everywhere."""
    if str(folder).strip() == "":
        raise InputError(f"{option} needs a folder name; got an empty one")
    folder = Path(folder).expanduser()
    if folder.is_symlink() and not folder.exists():
        raise InputError(f"{option}: {folder} is a link to nothing")
    if folder.exists() and not folder.is_dir():
        raise InputError(f"{option} must be a folder; {folder} is a file")
    existing = nearest_existing(folder)
    if not existing.is_dir():
        raise InputError(f"{option}: cannot create {folder}: {existing} is a file")
    try:
        os.rmdir(tempfile.mkdtemp(dir=existing, prefix=STAGE_PREFIX))
    except OSError as exc:
        raise InputError(f"{option}: cannot write in {existing}: {exc.strerror}") from None
    return folder


def _relative(name):
    """Whether `name` (from a record) is a path inside the folder that a command may have
    written: relative, no '.', '..' or empty part, not one of the package's own entries."""
    if not isinstance(name, str) or not name or name.startswith("/"):
        return False
    parts = name.split("/")
    return all(part not in ("", ".", "..") for part in parts) and not parts[0].startswith(
        OURS_PREFIX)


def _ours(folder, owner):
    """The paths in `folder` that `owner` wrote there (its record's list, relative, '/'-
    separated), or None where the folder holds no valid record of `owner`."""
    try:
        record = json.loads((folder / RECORD).read_text())
    except (OSError, ValueError):
        return None
    if not isinstance(record, dict) or record.get("written_by") != owner:
        return None
    files = record.get("files")
    if not isinstance(files, list) or not all(_relative(name) for name in files):
        return None
    return set(files)


def _entries(folder):
    """The names in `folder`, the package's own entries left out."""
    if not folder.is_dir():
        return set()
    return {p.name for p in folder.iterdir() if not p.name.startswith(OURS_PREFIX)}


def _tops(paths):
    """The top-level names of relative '/'-separated `paths`."""
    return {p.split("/")[0] for p in paths}


def _tree(folder):
    """Every path under `folder`, relative and '/'-separated (links not followed)."""
    return {p.relative_to(folder).as_posix() for p in folder.rglob("*")}


def output_folder(folder, option, owner):
    """`folder` as a Path if `owner` (a command, e.g. 'python -m fem_asperity curve') may write
    its output there: a new or empty folder, or one holding its own earlier output (its record);
    else an `InputError` naming `option`, before any work is done. A folder that holds anything
    else is refused: the command never deletes what it did not write."""
    folder = writable_folder(folder, option)
    foreign = sorted(_entries(folder))
    if foreign and _ours(folder, owner) is None:
        shown = ", ".join(foreign[:3]) + (", ..." if len(foreign) > 3 else "")
        raise InputError(f"{option}: {folder} holds files that {owner} did not write "
                         f"({shown}); give a new or empty folder, or one it wrote before")
    return folder


def _replace(source, target, folder):
    """Rename `source` onto `target`; an existing folder `target` is renamed aside (into
    `folder`, under the staging prefix) first and removed after: a rename cannot replace a
    folder that has files."""
    if target.is_dir() and not target.is_symlink():
        aside = _stage(folder) / target.name
        os.replace(target, aside)
        os.replace(source, target)
        shutil.rmtree(aside.parent, ignore_errors=True)
    else:
        os.replace(source, target)


def _remove(path):
    if path.is_dir() and not path.is_symlink():
        shutil.rmtree(path)
    elif path.exists() or path.is_symlink():
        path.unlink()


def _write_record(folder, owner, paths):
    write_atomic(folder / RECORD, json.dumps(
        {"written_by": owner, "files": sorted(paths),
         "about": "the files the command wrote here; a later run of it replaces only these"},
        indent=1) + "\n")


def _stage(folder):
    """A new staging folder in `folder`, named after this process."""
    return Path(tempfile.mkdtemp(dir=folder, prefix=f"{STAGE_PREFIX}{os.getpid()}-"))


def _remove_leftovers(folder):
    """Remove the staging folders in `folder` whose process has ended (killed mid-run)."""
    for stage in folder.glob(f"{STAGE_PREFIX}*"):
        pid = stage.name[len(STAGE_PREFIX):].split("-")[0]
        if pid.isdigit() and not _alive(int(pid)):
            shutil.rmtree(stage, ignore_errors=True)


def _alive(pid):
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # another user's process
        return True
    return True


@contextlib.contextmanager
def _locked(folder):
    """Hold an exclusive lock on `folder` (flock on the folder itself) inside the block, so that
    two runs writing into one folder at once move their sets and records one after the other."""
    try:
        import fcntl
    except ImportError:  # no flock (Windows): runs into one folder at once are not ordered
        yield
        return
    fd = os.open(folder, os.O_RDONLY)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        yield
    finally:
        os.close(fd)


def _check_replaceable(folder, owner, earlier, new, whole):
    """Refuse (`InputError`) a set `new` (relative paths) that would replace or remove anything
    in `folder` that `owner` did not write: a top-level name of the set that it did not write,
    or, inside a subfolder of its earlier set that is replaced or removed as a whole, a path
    that is not in `earlier`."""
    new_top, earlier_top = _tops(new), _tops(earlier)
    taken = sorted((new_top & _entries(folder)) - earlier_top)
    gone = (new_top | (earlier_top if whole else set())) & earlier_top
    taken += sorted(f"{name}/{path}" for name in gone if (folder / name).is_dir()
                    and not (folder / name).is_symlink()
                    for path in _tree(folder / name) if f"{name}/{path}" not in earlier)
    if taken:
        shown = ", ".join(taken[:3]) + (", ..." if len(taken) > 3 else "")
        raise InputError(f"{folder}: the output would replace or remove {shown}, which "
                         f"{owner} did not write; move it away, nothing was written")


@contextlib.contextmanager
def staged_folder(folder, *, owner, whole=True):
    """Yield a staging folder to write `owner`'s set of outputs into; on success the set is
    moved into `folder`, on failure (or Ctrl-C) nothing there is touched.

    `folder` must be new, empty or hold `owner`'s earlier output (`output_folder`); entries it
    did not write stay, and a set that would replace or remove one of them is refused
    (`_check_replaceable`). whole=True: the files of `owner`'s earlier set that the new set
    lacks are removed (a folder owned by one result never mixes two runs); whole=False: they
    stay (commands sharing a folder, each writing part). The record lists every file `owner`
    wrote at each step of the move, so a run killed during it leaves nothing unrecognised; runs
    into one folder at once move one after the other. Staging folders a killed run left in
    `folder` are removed first."""
    folder = output_folder(folder, "the output folder", owner)
    made_from = nearest_existing(folder)  # what a failure removes again, up to here
    folder.mkdir(parents=True, exist_ok=True)
    _remove_leftovers(folder)
    stage = _stage(folder)
    os.chmod(stage, 0o777 & ~_umask())  # mkdtemp's 0700 would become a folder's mode
    try:
        yield stage
        with _locked(folder):
            earlier = _ours(folder, owner) or set()
            new = _tree(stage)
            _check_replaceable(folder, owner, earlier, new, whole)
            _write_record(folder, owner, earlier | new)  # covers both sets while they move
            for name in sorted(p.name for p in stage.iterdir()):
                _replace(stage / name, folder / name, folder)
            if whole:
                for name in _tops(earlier) - _tops(new):
                    _remove(folder / name)
            kept = set() if whole else {p for p in earlier if (folder / p).exists()
                                         or (folder / p).is_symlink()}
            _write_record(folder, owner, new | kept)
    except BaseException:
        shutil.rmtree(stage, ignore_errors=True)
        for made in (folder.absolute(), *folder.absolute().parents):
            if made == made_from.absolute() or any(made.iterdir()):
                break
            made.rmdir()
        raise
    shutil.rmtree(stage, ignore_errors=True)


def write_atomic(path, data):
    """Write `data` (str or bytes) to `path` so that readers see the old file or the whole new
    one."""
    with atomic_path(path) as tmp, open(tmp, "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)
    return Path(path)


def save_figure(fig, path, dpi=150):
    """Save a matplotlib `Figure` atomically as PNG."""
    from io import BytesIO

    buffer = BytesIO()
    fig.savefig(buffer, format="png", dpi=dpi, bbox_inches="tight")
    return write_atomic(path, buffer.getvalue())
