"""`validation.rough_explicit`: the quick tier's surface solved once, kept, read back; the same
on a Dask cluster."""

import copy

import pytest

from validation import rough_explicit


def test_a_surface_is_solved_once_then_read_from_the_store(tmp_path, monkeypatch):
    monkeypatch.setattr(rough_explicit, "_folder", lambda: tmp_path)
    first = rough_explicit.run_scenes(False, step=lambda text: None)[0][0]
    assert len(list(tmp_path.glob("*.json"))) == 1
    whole = first["models"]["whole"]
    assert whole["f_max"] > 0 and first["estimate"] < 0.05 * whole["f_max"]
    assert set(first["models"]) == set(rough_explicit.NAMES)

    def no_solving(*args, **kwargs):
        raise AssertionError("solved again")

    monkeypatch.setattr("gw.explicit.compare", no_solving)
    assert rough_explicit.run_scenes(False, step=lambda text: None)[0][0] == first

    # an interacting path that stopped once the force had turned compressive keeps its F̄max,
    # and the report says how it stopped (no empty list of μ for the paths in tension)
    stopped = copy.deepcopy(first)
    interacting = stopped["models"]["interacting"]
    interacting["stopped"], interacting["approach"][-1] = interacting["d"][-1] - 0.1, 0.5
    text = rough_explicit.section({"full": False, "accuracy": "draft", "scenes": [stopped],
                                   "wall_s": 1.0})
    assert "stopped in compression" in text and "(μ = )" not in text


@pytest.mark.filterwarnings("ignore::DeprecationWarning", "ignore::ResourceWarning",
                            "ignore::pytest.PytestUnraisableExceptionWarning")
def test_a_dask_cluster_gives_the_serial_surface(tmp_path, monkeypatch):
    distributed = pytest.importorskip("dask.distributed")
    monkeypatch.setattr(rough_explicit, "_folder", lambda: tmp_path / "serial")
    serial = rough_explicit.run_scenes(False, step=lambda text: None)[0][0]
    monkeypatch.setattr(rough_explicit, "_folder", lambda: tmp_path / "cluster")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster:
        clustered = rough_explicit.run_scenes(False, scheduler=cluster.scheduler_address,
                                              step=lambda text: None)[0][0]
    assert list((tmp_path / "cluster").glob("*.json"))
    for name in rough_explicit.NAMES:
        assert clustered["models"][name]["f_max"] == serial["models"][name]["f_max"]


def test_a_self_affine_surface_is_answered_from_its_measured_summits(tmp_path, monkeypatch):
    """The map's self-affine surfaces go through the user's entry (`gw.explicit.answer`): a
    64² map here (the map's are 128²), kept and read back, its errors those of the answer, its
    row in the report."""
    monkeypatch.setattr(rough_explicit, "_folder", lambda: tmp_path)
    monkeypatch.setitem(rough_explicit.AFFINE, "n", 64)
    spec = {"mu": 0.3, "zeta": 1.0, "seed": 1}
    record = rough_explicit.solve_affine(spec)
    assert record["summits"] >= 4 and record["spec"] == spec
    models = record["models"]
    assert set(models) == {"gw", "interacting", "whole"}
    for name in ("gw", "interacting"):
        assert models[name]["error"] == pytest.approx(
            models[name]["f_max"] / models["whole"]["f_max"] - 1.0)
    assert models["whole"]["error"] == 0.0 and record["needs"] in models
    assert rough_explicit.solve_affine(spec) == record  # read back, not solved
    table = rough_explicit.affine_section([record])
    assert "| 0.3 | 1 | 1 |" in table and "Self-affine" in table
    # a model left out (no equilibrium at the first separation) is a dash, not a KeyError
    lone = {**record, "models": {k: v for k, v in models.items() if k != "interacting"}}
    assert "— ✗" in rough_explicit.affine_section([lone])
