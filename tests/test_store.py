"""The store of solved curves: solved once per solver revision, then read back."""

import os
import re
import shutil
import subprocess
import tempfile
import threading
import time

import pytest

import fem_asperity.studies.store as store
from fem_asperity.plumbing.errors import InputError
from fem_asperity.studies.sweep import sweep

FAST = dict(method="bem", accuracy="draft", error_estimate=False)


@pytest.fixture
def read_only():
    """make(folder): `folder` and all in it read-only for the rest of the test, root included:
    chmod a-w and, as root (whom chmod does not stop), the immutable attribute (chattr +i)."""
    made = []

    def make(folder):
        made.append(folder)
        subprocess.run(["chmod", "-R", "a-w", folder], check=True)
        if os.geteuid() == 0 and (not shutil.which("chattr") or subprocess.run(
                ["chattr", "-R", "+i", folder], capture_output=True).returncode):
            pytest.skip("as root only chattr +i makes a folder read-only, and it failed here")
        try:
            os.rmdir(tempfile.mkdtemp(dir=folder))
        except OSError:
            return
        pytest.skip(f"could not make {folder} read-only")

    yield make
    for folder in made:
        if os.geteuid() == 0 and shutil.which("chattr"):
            subprocess.run(["chattr", "-R", "-i", folder], capture_output=True)
        subprocess.run(["chmod", "-R", "u+w", folder], check=True)


def test_a_changed_solver_solves_afresh(tmp_path, monkeypatch):
    solved = []
    real_solve = store.solve_curve

    def counting_solve(*args, **kwargs):
        solved.append(args)
        return real_solve(*args, **kwargs)

    monkeypatch.setattr(store, "solve_curve", counting_solve)
    first = store.stored_curve(0.2, accuracy="draft", cache=tmp_path)
    again = store.stored_curve(0.2, accuracy="draft", cache=tmp_path)
    assert len(solved) == 1 and again.events == first.events
    assert first.status == "ok" and "folds" in first.message
    monkeypatch.setattr(store, "solver_revision", lambda: "another")
    changed = store.stored_curve(0.2, accuracy="draft", cache=tmp_path)
    assert len(solved) == 2 and changed.folder != first.folder
    assert changed.events.p_off == first.events.p_off


def test_the_onset_is_computed_once_then_read_from_the_store(tmp_path, monkeypatch):
    import fem_asperity.studies.onset as onset

    computed = []

    def fake_onset(*, method, accuracy):
        computed.append((method, accuracy))
        return onset.Onset(0.697, 0.696, 0.698, method, accuracy, evaluations=9, wall_s=1.0)

    monkeypatch.setattr(onset, "jump_in_onset", fake_onset)
    first = onset.stored_onset(method="fem", accuracy="draft", cache=tmp_path)
    again = onset.stored_onset(method="fem", accuracy="draft", cache=tmp_path)
    assert computed == [("fem", "draft")] and again == first


def test_the_whole_curve_is_stored_apart_with_its_unstable_branch(tmp_path):
    stable = store.stored_curve(2.0, accuracy="draft", cache=tmp_path)
    whole = store.stored_curve(2.0, accuracy="draft", unstable_branch=True, cache=tmp_path)
    assert whole.folder != stable.folder
    assert stable.equilibrium.stable.all() and not whole.equilibrium.stable.all()
    assert whole.events.p_off == pytest.approx(stable.events.p_off, rel=1e-6)


def _counting(monkeypatch):
    solved, real_solve = [], store.solve_curve

    def counting_solve(*args, **kwargs):
        solved.append(args)
        return real_solve(*args, **kwargs)

    monkeypatch.setattr(store, "solve_curve", counting_solve)
    return solved


@pytest.mark.parametrize("damage", ["cut a curve at a line boundary", "garble the manifest"])
def test_a_corrupt_entry_is_moved_aside_and_solved_again(tmp_path, monkeypatch, damage):
    solved = _counting(monkeypatch)
    first = store.stored_curve(0.3, accuracy="draft", cache=tmp_path)
    if damage.startswith("cut"):
        lines = (first.folder / "approach.csv").read_text().splitlines(keepends=True)
        (first.folder / "approach.csv").write_text("".join(lines[: len(lines) // 2]))
    else:
        (first.folder / "manifest.json").write_text("{not json")
    with pytest.warns(store.StoreWarning, match="corrupt"):
        again = store.stored_curve(0.3, accuracy="draft", cache=tmp_path)
    assert len(solved) == 2 and again.events == first.events
    assert len(again.approach) == len(first.approach)
    assert (tmp_path / f"{first.folder.name}.corrupt-1").is_dir()


def test_two_callers_of_one_entry_solve_it_once(tmp_path, monkeypatch):
    from concurrent.futures import ThreadPoolExecutor

    solved = _counting(monkeypatch)
    with ThreadPoolExecutor(2) as pool:
        found = list(pool.map(lambda _: store.stored_curve(0.3, accuracy="draft",
                                                           cache=tmp_path), range(2)))
    assert len(solved) == 1 and found[0].events == found[1].events


def test_a_garbled_stored_onset_is_computed_again(tmp_path, monkeypatch):
    import fem_asperity.studies.onset as onset

    computed = []

    def fake_onset(*, method, accuracy):
        computed.append(method)
        return onset.Onset(0.697, 0.696, 0.698, method, accuracy, evaluations=9, wall_s=1.0)

    monkeypatch.setattr(onset, "jump_in_onset", fake_onset)
    onset.stored_onset(method="bem", accuracy="draft", cache=tmp_path)
    (stored,) = tmp_path.glob("onset-*.json")
    stored.write_text('{"mu_onset": 0.69')  # cut
    with pytest.warns(store.StoreWarning, match="corrupt"):
        again = onset.stored_onset(method="bem", accuracy="draft", cache=tmp_path)
    assert len(computed) == 2 and again.mu_onset == 0.697


def test_each_kind_of_estimate_is_stored_apart_and_auto_shares_its_kinds_folder(tmp_path):
    """The FE of a homogeneous half-space: 'auto' is 'bem', 'finer' is kept apart; a BEM curve's
    'auto' is 'finer'; an unknown kind is refused before anything is solved."""
    from fem_asperity import InputError
    from fem_asperity.studies.sweep import sweep

    def folder(method, by):
        return store.curve_folder(1.0, method=method, accuracy="draft", error_estimate=True,
                                  estimate_by=by, cache=tmp_path)

    assert folder("fem", "auto") == folder("fem", "bem") != folder("fem", "finer")
    assert folder("bem", "auto") == folder("bem", "finer")
    assert "-estimated-finer-" in folder("bem", "auto").name
    with pytest.raises(InputError, match="estimate_by"):
        sweep([1.0], estimate_by="richardson", cache=tmp_path)
    with pytest.raises(InputError, match="homogeneous half-space"):
        sweep([1.0], method="bem", estimate_by="bem", cache=tmp_path)
    assert not any(tmp_path.iterdir())


def test_a_refused_curve_leaves_no_file(tmp_path):
    """Every input is checked before the store makes a file (a lock) or a folder."""
    for mu, bad in ((1.0, dict(method="bogus")), (1.0, dict(accuracy="bogus")), (0.0, {}),
                    (1e3, {})):
        with pytest.raises(InputError):
            store.stored_curve(mu, **{**FAST, **bad}, cache=tmp_path / "store")
        with pytest.raises(InputError):
            sweep([mu], **{**FAST, **bad}, cache=tmp_path / "store")
    assert not (tmp_path / "store").exists()


def test_a_lock_is_never_held_twice_and_leaves_no_file(tmp_path):
    """A released lock's file is removed while another process (a thread here: flock keeps two
    opens of one file apart as it keeps two processes) waits on it: the waiter wakes on a
    removed file and must take the lock again, else a newcomer would hold it at once too."""
    folder = tmp_path / "entry"
    first = store.lock_entry(folder)
    waiter_holds, let_go = threading.Event(), threading.Event()

    def waiter():
        lock = store.lock_entry(folder)
        waiter_holds.set()
        let_go.wait(30)
        store.unlock_entry(lock)

    thread = threading.Thread(target=waiter)
    thread.start()
    time.sleep(0.2)  # the waiter now waits on the file that `first` locks
    store.unlock_entry(first)
    try:
        assert waiter_holds.wait(30)
        assert store.lock_entry(folder, wait=False) is None  # a newcomer finds it held
    finally:
        let_go.set()
        thread.join()
    assert not any(tmp_path.iterdir())
    store.unlock_entry(store.lock_entry(folder, wait=False))
    assert not any(tmp_path.iterdir())


def test_a_read_only_store_holding_every_mu_serves_a_sweep(tmp_path, read_only):
    """A sweep that needs to write nothing reads a read-only store; one that must solve is
    refused before it solves, naming the store's setting."""
    cache = tmp_path / "store"
    first = [store.stored_curve(mu, **FAST, cache=cache) for mu in (0.5, 1.0)]
    read_only(cache)
    again = sweep([0.5, 1.0], **FAST, cache=cache, jobs=1)
    assert again.stored == 2 and again.solved == 0
    assert [row.curve.events for row in again.rows] == [curve.events for curve in first]
    with pytest.raises(InputError, match=r"\$ADHESION_CACHE"):
        sweep([0.5, 1.0, 2.0], **FAST, cache=cache, jobs=1)


def test_a_store_that_is_a_file_is_refused_naming_adhesion_cache(tmp_path, monkeypatch):
    import fem_asperity.studies.onset as onset

    monkeypatch.setattr(onset, "jump_in_onset", lambda **_: pytest.fail("computed the onset"))
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    named = rf"\$ADHESION_CACHE.*{re.escape(str(blocker))} is a file"
    for setting in (blocker, blocker / "store"):
        monkeypatch.setenv("ADHESION_CACHE", str(setting))
        with pytest.raises(InputError, match=named):
            store.stored_curve(1.0, **FAST)
        with pytest.raises(InputError, match=named):
            sweep([1.0], **FAST)
        with pytest.raises(InputError, match=named):
            onset.stored_onset(method="bem", accuracy="draft")
    assert blocker.read_text() == "not a folder"


def test_a_corrupt_entry_in_a_read_only_store_is_refused_naming_it(tmp_path, read_only):
    cache = tmp_path / "store"
    folder = store.stored_curve(0.3, **FAST, cache=cache).folder
    (folder / "manifest.json").write_text("{not json")
    read_only(cache)
    named = rf"\$ADHESION_CACHE.*{re.escape(str(folder))} is corrupt"
    with pytest.raises(InputError, match=named):
        store.stored_curve(0.3, **FAST, cache=cache)
    with pytest.raises(InputError, match=named):
        sweep([0.3], **FAST, cache=cache)
