"""`validation.rough_explicit`: the quick tier's surface solved once, kept, read back; the same
on a Dask cluster."""

import pytest

from validation import rough_explicit


def test_a_surface_is_solved_once_then_read_from_the_store(tmp_path, monkeypatch):
    monkeypatch.setattr(rough_explicit, "_folder", lambda: tmp_path)
    first = rough_explicit.run_scenes(False, step=lambda text: None)[0]
    assert len(list(tmp_path.glob("*.json"))) == 1
    whole = first["models"]["whole"]
    assert whole["f_max"] > 0 and first["estimate"] < 0.05 * whole["f_max"]
    assert set(first["models"]) == set(rough_explicit.NAMES)

    def no_solving(*args, **kwargs):
        raise AssertionError("solved again")

    monkeypatch.setattr("gw.explicit.compare", no_solving)
    assert rough_explicit.run_scenes(False, step=lambda text: None)[0] == first


@pytest.mark.filterwarnings("ignore::DeprecationWarning", "ignore::ResourceWarning",
                            "ignore::pytest.PytestUnraisableExceptionWarning")
def test_a_dask_cluster_gives_the_serial_surface(tmp_path, monkeypatch):
    distributed = pytest.importorskip("dask.distributed")
    monkeypatch.setattr(rough_explicit, "_folder", lambda: tmp_path / "serial")
    serial = rough_explicit.run_scenes(False, step=lambda text: None)[0]
    monkeypatch.setattr(rough_explicit, "_folder", lambda: tmp_path / "cluster")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster:
        clustered = rough_explicit.run_scenes(False, scheduler=cluster.scheduler_address,
                                              step=lambda text: None)[0]
    assert list((tmp_path / "cluster").glob("*.json"))
    for name in rough_explicit.NAMES:
        assert clustered["models"][name]["f_max"] == serial["models"][name]["f_max"]
