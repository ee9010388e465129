"""Output sets are all or nothing: a staged set replaces what was there, a failure touches
nothing, and what a killed run left is cleaned up."""

import os

import pytest

from fem_asperity.plumbing.files import STAGE_MARK, staged_folder


def _tree(folder):
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*"))


@pytest.fixture
def earlier_run(tmp_path):
    out = tmp_path / "out"
    (out / "sub").mkdir(parents=True)
    for name in ("result.json", "fields.vtu", "sub/old.png", "mine.txt"):
        (out / name).write_text("earlier run")
    return out


def test_a_whole_folder_is_replaced_so_no_earlier_file_stays(earlier_run):
    with staged_folder(earlier_run) as stage:
        (stage / "result.json").write_text("new")
    assert _tree(earlier_run) == ["result.json"]
    assert (earlier_run / "result.json").read_text() == "new"
    mask = os.umask(0)
    os.umask(mask)
    assert os.stat(earlier_run).st_mode & 0o777 == 0o777 & ~mask  # not mkdtemp's 0700


def test_a_shared_folder_keeps_entries_outside_the_set(earlier_run):
    with staged_folder(earlier_run, whole=False) as stage:
        (stage / "sub").mkdir()
        (stage / "sub" / "new.png").write_text("new")
        (stage / "result.json").write_text("new")
    assert _tree(earlier_run) == ["fields.vtu", "mine.txt", "result.json", "sub", "sub/new.png"]
    assert (earlier_run / "result.json").read_text() == "new"


@pytest.mark.parametrize("whole", [True, False])
def test_a_failure_touches_nothing_and_leaves_no_staging(earlier_run, whole):
    before = _tree(earlier_run)
    with pytest.raises(KeyboardInterrupt), staged_folder(earlier_run, whole=whole) as stage:
        (stage / "result.json").write_text("half")
        raise KeyboardInterrupt
    assert _tree(earlier_run) == before
    assert (earlier_run / "result.json").read_text() == "earlier run"
    assert not list(earlier_run.parent.glob(f".out{STAGE_MARK}*"))


def test_what_a_killed_run_left_is_removed(earlier_run):
    killed = earlier_run.parent / f".out{STAGE_MARK}abc123"
    killed.mkdir()
    (killed / "half.json").write_text("half")
    with staged_folder(earlier_run) as stage:
        (stage / "result.json").write_text("new")
    assert not killed.exists()
