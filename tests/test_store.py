"""The store of solved curves: solved once per solver revision, then read back."""

import pytest

import fem_asperity.studies.store as store


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
