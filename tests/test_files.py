"""Output sets are all or nothing and lose nothing: a command replaces only what it wrote into
its folder before (its record says which), refuses a folder holding anything else, a failure
touches nothing, and what a killed run left is cleaned up."""

import json
import os

import pytest

from fem_asperity.plumbing.errors import InputError
from fem_asperity.plumbing.files import (
    OURS_PREFIX,
    RECORD,
    STAGE_PREFIX,
    output_folder,
    staged_folder,
    writable_folder,
)

OWNER = "python -m tool run"


def _tree(folder):
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*"))


def _write(owner, folder, names, whole=True, text="new"):
    with staged_folder(folder, owner=owner, whole=whole) as stage:
        for name in names:
            (stage / name).parent.mkdir(parents=True, exist_ok=True)
            (stage / name).write_text(text)


@pytest.fixture
def earlier_run(tmp_path):
    """A folder the tool wrote (result.json, fields.vtu, sub/old.png) and a user's file that
    was added after."""
    out = tmp_path / "out"
    _write(OWNER, out, ["result.json", "fields.vtu", "sub/old.png"], text="earlier run")
    (out / "mine.txt").write_text("the user's")
    return out


def test_a_new_run_replaces_its_own_earlier_set_and_nothing_else(earlier_run):
    _write(OWNER, earlier_run, ["result.json"])
    assert _tree(earlier_run) == sorted([RECORD, "mine.txt", "result.json"])
    assert (earlier_run / "result.json").read_text() == "new"
    assert (earlier_run / "mine.txt").read_text() == "the user's"
    assert json.loads((earlier_run / RECORD).read_text())["files"] == ["result.json"]
    mask = os.umask(0)
    os.umask(mask)
    assert os.stat(earlier_run).st_mode & 0o777 == 0o777 & ~mask  # not mkdtemp's 0700


def test_a_shared_folder_keeps_the_earlier_set_beside_the_new(earlier_run):
    _write(OWNER, earlier_run, ["sub/new.png", "report.md"], whole=False)
    assert _tree(earlier_run) == sorted([RECORD, "fields.vtu", "mine.txt", "report.md",
                                         "result.json", "sub", "sub/new.png"])
    assert json.loads((earlier_run / RECORD).read_text())["files"] == [
        "fields.vtu", "report.md", "result.json", "sub", "sub/new.png"]


@pytest.mark.parametrize("owner", [OWNER, "python -m other run"])
def test_a_folder_of_someone_elses_files_is_refused_before_and_at_writing(tmp_path, owner):
    project = tmp_path / "project"
    (project / "src").mkdir(parents=True)
    (project / "notes.txt").write_text("keep")
    if owner != OWNER:  # another command's output is someone else's too
        project = tmp_path / "other"
        _write(owner, project, ["report.md"])
    before = _tree(project)
    with pytest.raises(InputError, match="--out: .* holds files that python -m tool run did "
                                         "not write"):
        output_folder(project, "--out", OWNER)
    with pytest.raises(InputError, match="did not write"):
        _write(OWNER, project, ["result.json"])
    assert _tree(project) == before


def test_a_file_the_user_put_where_the_new_set_writes_is_not_replaced(earlier_run):
    (earlier_run / "curve.png").write_text("the user's figure")
    before = _tree(earlier_run)
    with pytest.raises(InputError, match="would replace or remove curve.png, which"):
        _write(OWNER, earlier_run, ["result.json", "curve.png"])
    assert _tree(earlier_run) == before
    assert (earlier_run / "curve.png").read_text() == "the user's figure"
    assert (earlier_run / "result.json").read_text() == "earlier run"


def test_an_empty_or_new_folder_is_taken_and_a_failure_removes_a_new_one(tmp_path):
    (tmp_path / "empty").mkdir()
    _write(OWNER, tmp_path / "empty", ["a.csv"])
    assert _tree(tmp_path / "empty") == sorted([RECORD, "a.csv"])
    with pytest.raises(KeyboardInterrupt), staged_folder(tmp_path / "new", owner=OWNER):
        raise KeyboardInterrupt
    assert sorted(p.name for p in tmp_path.iterdir()) == ["empty"]


@pytest.mark.parametrize("whole", [True, False])
def test_a_failure_touches_nothing_and_leaves_no_staging(earlier_run, whole):
    before = _tree(earlier_run)
    with pytest.raises(KeyboardInterrupt), staged_folder(earlier_run, owner=OWNER,
                                                         whole=whole) as stage:
        (stage / "result.json").write_text("half")
        raise KeyboardInterrupt
    assert _tree(earlier_run) == before
    assert (earlier_run / "result.json").read_text() == "earlier run"


def test_what_a_killed_run_left_is_removed_and_a_running_ones_stays(tmp_path):
    out = tmp_path / "out"
    killed, running = (out / f"{STAGE_PREFIX}{pid}-abc123" for pid in (2**31 - 2, os.getpid()))
    for stage in (killed, running):
        stage.mkdir(parents=True)
        (stage / "half.json").write_text("half")
    (out / f"{RECORD[:-5]}.x1y2.json").write_text("{")  # a record's write cut short
    _write(OWNER, out, ["result.json"])
    assert not killed.exists() and (running / "half.json").exists()
    assert _entries_but_ours(out) == ["result.json"]


def _entries_but_ours(folder):
    return sorted(p.name for p in folder.iterdir() if not p.name.startswith(OURS_PREFIX))


@pytest.mark.parametrize("files", [[".."], ["."], [""], "zz", ["/etc"], ["a/../.."], [RECORD]])
def test_a_record_naming_what_is_not_its_own_is_no_record(tmp_path, files):
    """A record listing '..', '.', '' or an absolute path, or a string instead of a list, is
    not trusted: the folder counts as someone else's and is refused, nothing deleted."""
    out = tmp_path / "out"
    out.mkdir()
    (tmp_path / "precious.txt").write_text("keep")
    (out / "z").write_text("keep")
    (out / RECORD).write_text(json.dumps({"written_by": OWNER, "files": files}))
    with pytest.raises(InputError, match="did not write"):
        _write(OWNER, out, ["result.json"])
    assert (tmp_path / "precious.txt").read_text() == "keep" and (out / "z").exists()


@pytest.mark.parametrize("whole", [True, False])
def test_a_users_file_in_a_subfolder_of_the_output_is_not_deleted(earlier_run, whole):
    """sub/ is the command's, replaced as a whole by a new run: a file the user put into it
    makes the run refuse, naming it, and nothing changes."""
    (earlier_run / "sub" / "notes.txt").write_text("mine")
    before = _tree(earlier_run)
    with pytest.raises(InputError, match="sub/notes.txt, which python -m tool run did not"):
        _write(OWNER, earlier_run, ["sub/new.png", "result.json"], whole=whole)
    assert _tree(earlier_run) == before


def test_a_failed_set_removes_the_folders_it_made_and_no_more(tmp_path):
    with pytest.raises(KeyboardInterrupt), staged_folder(tmp_path / "a" / "b" / "out",
                                                         owner=OWNER):
        raise KeyboardInterrupt
    assert list(tmp_path.iterdir()) == []


def test_a_link_to_nothing_is_refused_up_front(tmp_path):
    (tmp_path / "out").symlink_to(tmp_path / "gone")
    with pytest.raises(InputError, match="--out: .* is a link to nothing"):
        output_folder(tmp_path / "out", "--out", OWNER)


def test_the_current_folder_can_be_the_output(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    _write(OWNER, ".", ["result.json"])
    _write(OWNER, ".", ["result.json", "curve.png"])
    assert _tree(tmp_path) == sorted([RECORD, "curve.png", "result.json"])


@pytest.mark.parametrize("name", ["", "  "])
def test_an_empty_folder_name_is_refused(name):
    with pytest.raises(InputError, match="--out needs a folder name"):
        writable_folder(name, "--out")


def test_writability_is_tried_not_asked(tmp_path):
    """os.access says yes to root for /proc; making a folder there fails for anyone."""
    with pytest.raises(InputError, match="--out: cannot write in /proc"):
        writable_folder("/proc/x", "--out")
    assert writable_folder(tmp_path / "a" / "b", "--out") == tmp_path / "a" / "b"
    assert list(tmp_path.iterdir()) == []  # the try leaves nothing behind
