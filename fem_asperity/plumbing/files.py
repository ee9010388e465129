"""Atomic file output: write to a temporary file beside the target, then rename over it."""

import contextlib
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


def writable_folder(folder, option):
    """`folder` as a Path if it is, or can be made, a writable folder; else an `InputError` that
    names `option` and the reason, before any work is done."""
    folder = Path(folder)
    if folder.exists() and not folder.is_dir():
        raise InputError(f"{option} must be a folder; {folder} is a file")
    existing = next(p for p in (folder, *folder.parents) if p.exists())
    if not existing.is_dir():
        raise InputError(f"{option}: cannot create {folder}: {existing} is a file")
    if not os.access(existing, os.W_OK | os.X_OK):
        raise InputError(f"{option}: {existing} is not writable")
    return folder


#: Marks the staging folders beside an output folder, so that a later run finds and removes
#: what a killed one left.
STAGE_MARK = ".stage-"


def _replace(source, target):
    """Rename `source` onto `target`; an existing folder `target` is renamed aside first and
    removed after (a rename cannot replace a folder that has files)."""
    if target.is_dir() and not target.is_symlink():
        aside = Path(tempfile.mkdtemp(dir=target.parent, prefix=f".{target.name}{STAGE_MARK}"))
        os.replace(target, aside)
        os.replace(source, target)
        shutil.rmtree(aside, ignore_errors=True)
    else:
        os.replace(source, target)


@contextlib.contextmanager
def staged_folder(folder, *, whole=True):
    """Yield a temporary folder beside `folder` to write a set of outputs into; on success the
    set replaces what was there, on failure (or Ctrl-C) nothing is touched.

    whole=True: `folder` is replaced as a whole, so it never holds a file of an earlier run
    beside the new ones (a folder owned by one result). whole=False: each file or folder of the
    set replaces its namesake and other entries of `folder` stay (a shared output folder).
    Staging folders that a killed run left beside `folder` are removed first."""
    folder = Path(folder)
    folder.parent.mkdir(parents=True, exist_ok=True)
    for leftover in folder.parent.glob(f".{folder.name}{STAGE_MARK}*"):
        shutil.rmtree(leftover, ignore_errors=True)
    stage = Path(tempfile.mkdtemp(dir=folder.parent, prefix=f".{folder.name}{STAGE_MARK}"))
    os.chmod(stage, 0o777 & ~_umask())  # mkdtemp's 0700 would become the output folder's mode
    try:
        yield stage
        if whole or not folder.exists():
            _replace(stage, folder)
        else:
            for item in stage.iterdir():
                _replace(item, folder / item.name)
    finally:
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
