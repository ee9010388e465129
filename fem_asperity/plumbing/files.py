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


#: Prefix of the staging folders inside an output folder (and of a folder renamed aside while
#: it is replaced), so that a later run finds and removes what a killed one left.
STAGE_PREFIX = ".adhesion-stage-"
#: The record an output folder keeps of the command that wrote it and of the files it wrote:
#: a later run of that command replaces those and nothing else.
RECORD = ".adhesion-output.json"


def writable_folder(folder, option):
    """`folder` as a Path if it is, or can be made, a writable folder; else an `InputError` that
    names `option` and the reason, before any work is done. Writability is tried (a temporary
    folder made and removed), not asked of `os.access`, which says yes to root everywhere."""
    if str(folder).strip() == "":
        raise InputError(f"{option} needs a folder name; got an empty one")
    folder = Path(folder).expanduser()
    if folder.exists() and not folder.is_dir():
        raise InputError(f"{option} must be a folder; {folder} is a file")
    existing = next(p for p in (folder, *folder.absolute().parents) if p.exists())
    if not existing.is_dir():
        raise InputError(f"{option}: cannot create {folder}: {existing} is a file")
    try:
        os.rmdir(tempfile.mkdtemp(dir=existing, prefix=STAGE_PREFIX))
    except OSError as exc:
        raise InputError(f"{option}: cannot write in {existing}: {exc.strerror}") from None
    return folder


def _ours(folder, owner):
    """The entries of `folder` that `owner` wrote there (its record's list), or None where the
    folder holds no record of `owner`."""
    try:
        record = json.loads((folder / RECORD).read_text())
    except (OSError, ValueError):
        return None
    if not isinstance(record, dict) or record.get("written_by") != owner:
        return None
    return {name for name in record.get("files", ()) if isinstance(name, str) and "/" not in name}


def _entries(folder):
    """The names in `folder`, staging leftovers left out."""
    if not folder.is_dir():
        return set()
    return {p.name for p in folder.iterdir() if not p.name.startswith(STAGE_PREFIX)}


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
        aside = Path(tempfile.mkdtemp(dir=folder, prefix=STAGE_PREFIX)) / target.name
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


def _write_record(folder, owner, names):
    write_atomic(folder / RECORD, json.dumps(
        {"written_by": owner, "files": sorted(names),
         "about": "the files the command wrote here; a later run of it replaces only these"},
        indent=1) + "\n")


@contextlib.contextmanager
def staged_folder(folder, *, owner, whole=True):
    """Yield a staging folder to write `owner`'s set of outputs into; on success the set is
    moved into `folder`, on failure (or Ctrl-C) nothing there is touched.

    `folder` must be new, empty or hold `owner`'s earlier output (`output_folder`); entries it
    did not write stay, and a new file that would replace one of them is refused. whole=True:
    the files of `owner`'s earlier set that the new set lacks are removed (a folder owned by
    one result never mixes two runs); whole=False: they stay (commands sharing a folder, each
    writing part). The record lists every file `owner` wrote at each step of the move, so a
    run killed during it leaves nothing unrecognised. Staging folders a killed run left in
    `folder` are removed first."""
    folder = output_folder(folder, "the output folder", owner)
    created = not folder.exists()
    folder.mkdir(parents=True, exist_ok=True)
    for leftover in folder.glob(f"{STAGE_PREFIX}*"):
        shutil.rmtree(leftover, ignore_errors=True)
    stage = Path(tempfile.mkdtemp(dir=folder, prefix=STAGE_PREFIX))
    os.chmod(stage, 0o777 & ~_umask())  # mkdtemp's 0700 would become a folder's mode
    try:
        yield stage
        earlier = _ours(folder, owner) or set()
        new = {p.name for p in stage.iterdir()}
        taken = sorted((new & _entries(folder)) - earlier - {RECORD})
        if taken:
            raise InputError(f"{folder}: {', '.join(taken)} would replace files that {owner} "
                             "did not write; nothing was written")
        _write_record(folder, owner, earlier | new)  # covers both sets while they are moved
        for name in sorted(new):
            _replace(stage / name, folder / name, folder)
        if whole:
            for name in earlier - new:
                _remove(folder / name)
        _write_record(folder, owner, new if whole else (earlier & _entries(folder)) | new)
    except BaseException:
        shutil.rmtree(stage, ignore_errors=True)
        if created and not any(folder.iterdir()):
            folder.rmdir()
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
