"""The store of solved curves: solved once per solver revision, then read back."""

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
