"""The sweep engine: parallel (processes, a local Dask cluster) gives the serial events, a killed
sweep resumes without solving again what it stored, a failed μ stays in its row, the files load."""

import csv
import json
import os
import signal
import subprocess
import sys
import time

import pytest

import fem_asperity.studies.sweep as sweep_module
from fem_asperity import solve_curve
from fem_asperity.plumbing.errors import InputError
from fem_asperity.studies.sweep import mu_range, solve_for_sweep, sweep

MUS = (0.3, 1.0, 2.0)
FAST = dict(method="bem", accuracy="draft")


def die_at_one(mu):
    """A worker's job that kills its process at μ = 1 (as an out-of-memory kill would)."""
    if mu == 1.0:
        os._exit(1)
    return 2.0 * mu


@pytest.fixture(scope="module")
def serial():
    """Events of each μ solved on its own, in this process."""
    return {mu: solve_curve(mu, **FAST).events.records() for mu in MUS}


@pytest.fixture(scope="module")
def swept(tmp_path_factory):
    cache = tmp_path_factory.mktemp("store")
    return sweep(MUS, jobs=2, cache=cache, **FAST), cache


def test_two_worker_processes_give_the_serial_events(serial, swept):
    result, _ = swept
    assert [row.mu for row in result.rows] == list(MUS)
    assert result.solved == 3 and result.stored == 0 and not result.failed
    for row in result.rows:
        assert row.curve.events.records() == serial[row.mu]
        assert row.curve.error_estimate is not None and row.status == "ok"
        assert row.curve.estimated_by == "finer"  # a BEM curve's, stored and read back


def test_a_second_sweep_reads_the_store(swept):
    result, cache = swept
    again = sweep((*MUS, 0.5), jobs=2, cache=cache, **FAST)
    assert again.solved == 1 and again.stored == 3


@pytest.mark.filterwarnings("ignore::DeprecationWarning", "ignore::ResourceWarning",
                            "ignore::pytest.PytestUnraisableExceptionWarning")
def test_a_local_dask_cluster_gives_the_serial_events(serial, tmp_path):
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        result = sweep(MUS, scheduler=cluster.scheduler_address, cache=tmp_path, **FAST)
    assert result.solved == 3 and not result.failed
    for row in result.rows:
        assert row.curve.events.records() == serial[row.mu]


@pytest.mark.slow
def test_a_killed_sweep_resumes_without_solving_again_what_it_stored(tmp_path):
    env = {**os.environ, "ADHESION_CACHE": str(tmp_path / "store")}
    # more curves than can finish between the first stored one and the Ctrl-C (with four,
    # each about 0.2 s with its estimate traced near the events, the sweep once ended first)
    mus = ("0.2", "0.25", "0.3", "0.35", "0.4", "0.45", "0.5", "0.55", "0.6", "0.65")
    command = [sys.executable, "-m", "fem_asperity", "sweep", "--mu", *mus,
               "--method", "bem", "--accuracy", "draft", "--jobs", "1", "--out",
               str(tmp_path / "first")]
    # Ctrl-C's default action in the child whatever the runner's (a shell that starts a job in
    # the background passes SIGINT on ignored, and Python then never raises KeyboardInterrupt)
    first = subprocess.Popen(command, env=env, stdout=subprocess.DEVNULL,
                             stderr=subprocess.PIPE, text=True,
                             preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    deadline = time.monotonic() + 120
    while not list((tmp_path / "store").glob("*/manifest.json")) and time.monotonic() < deadline:
        time.sleep(0.05)
    stored_then = len(list((tmp_path / "store").glob("*/manifest.json")))
    first.send_signal(signal.SIGINT)  # Ctrl-C once the first curve is stored
    _, err = first.communicate(timeout=60)
    # interrupted, not finished: one line, no traceback
    assert first.returncode == 130, (first.returncode, stored_then, err)
    assert "Traceback" not in err and err.strip().splitlines()[-1].endswith("interrupted")
    kept = len(list((tmp_path / "store").glob("*/manifest.json")))
    assert 1 <= kept < len(mus)
    again = sweep([float(mu) for mu in mus], cache=tmp_path / "store", jobs=1, **FAST)
    assert again.stored == kept and again.solved == len(mus) - kept and not again.failed


def test_a_failed_mu_is_reported_in_its_row_and_the_others_are_kept(tmp_path, monkeypatch):
    def serial_jobs(jobs, todo, args):
        for mu in todo:
            yield mu, (RuntimeError("no landing") if mu == 1.0 else solve_for_sweep(mu, *args))

    monkeypatch.setattr(sweep_module, "_local_jobs", serial_jobs)
    result = sweep(MUS, cache=tmp_path, **FAST)
    failed = {row.mu: row for row in result.rows if row.status == "failed"}
    assert list(failed) == [1.0] and "no landing" in failed[1.0].message
    assert result.solved == 2 and len(result.failed) == 1
    monkeypatch.undo()  # the real workers: 1.0 is solved now, the finished ones are read
    again = sweep(MUS, cache=tmp_path, jobs=1, **FAST)
    assert again.stored == 2 and again.solved == 1 and not again.failed


def test_a_worker_that_dies_costs_only_its_own_mu():
    """The pool breaks and loses every running curve; each is run again alone, so only the μ
    that kills its worker is reported."""
    found = dict(sweep_module._local_jobs(2, [0.5, 1.0, 2.0], (), job=die_at_one))
    assert found[0.5] == 1.0 and found[2.0] == 4.0
    assert isinstance(found[1.0], sweep_module.WorkerDied)


def test_mu_sharing_a_store_folder_are_one_mu(swept):
    result, cache = swept
    again = sweep([1.0, 1.0 + 1e-15, 1.0 + 1e-13], jobs=1, cache=cache, **FAST)
    assert [row.mu for row in again.rows] == [1.0] and again.solved == 0


def test_the_worker_returns_an_error_instead_of_raising():
    assert isinstance(solve_for_sweep(0.0, "bem", "draft", False), InputError)


def test_files_have_every_event_with_its_estimate_and_the_curves_in_long_format(swept, tmp_path):
    result, _ = swept
    paths = result.write(tmp_path / "out")
    with open(paths[0]) as f:
        events = list(csv.DictReader(f))
    assert [float(row["mu"]) for row in events] == list(MUS)
    for key in ("p_off", "p_max", "delta_oc", "a_c", "x_oc"):
        assert {key, f"{key}_err", f"{key}_rel_err"} <= set(events[0])
    row = events[1]  # μ = 1
    assert float(row["p_off_rel_err"]) == pytest.approx(float(row["p_off_err"])
                                                        / abs(float(row["p_off"])))
    assert {"status", "wall_s", "dofs", "message"} <= set(row)
    with open(paths[1]) as f:
        curves = list(csv.DictReader(f))
    assert set(curves[0]) == {"mu", "path", "point", "delta_o", "x_o", "p", "area", "a_c",
                              "stable"}
    assert {r["path"] for r in curves} == {"approach", "retraction"}
    approach = [r for r in curves if r["mu"] == "1" and r["path"] == "approach"]
    assert len(approach) == len(result.rows[1].curve.approach)
    sidecar = json.loads(paths[2].read_text())
    assert sidecar["units"]["events"]["p_off"] == "2 pi R dgamma"
    assert sidecar["units"]["curves"]["delta_o"] == "eps"


def test_to_dataframe(swept):
    pytest.importorskip("pandas")
    result, _ = swept
    frame = result.to_dataframe()
    assert list(frame["mu"]) == list(MUS) and "p_off_rel_err" in frame
    assert set(result.to_dataframe("curves")["path"]) == {"approach", "retraction"}


def test_mu_range_is_log_spaced_and_checked():
    assert mu_range(0.1, 10, 3) == pytest.approx([0.1, 1.0, 10.0])
    for bad in ((1, 0.1, 3), (0.1, 1, 1), (0, 1, 3), (0.1, 1, 2.5)):
        with pytest.raises(InputError):
            mu_range(*bad)
    with pytest.raises(InputError):
        sweep([], **FAST)
    with pytest.raises(InputError):
        sweep([1.0], method="spectral")


def test_an_unwritable_store_is_refused_before_any_solve(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    with pytest.raises(InputError, match="ADHESION_CACHE"):
        sweep([1.0], cache=blocker / "store", **FAST)
