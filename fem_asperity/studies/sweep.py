"""Sweeps over μ: many single-asperity curves solved in parallel, each kept in the store as it
finishes, so that a rerun (after a crash, a Ctrl-C or with more μ) solves only what is missing.

Curves run in worker processes on this machine (`jobs`, both cores by default, one BLAS thread
each: `solver.discretised.PATH_BLAS_THREADS`) or on a Dask cluster (`scheduler`, the address of a
running `dask.distributed` scheduler; the optional extra `cluster`). Workers only solve; this
process keeps each result in its own store, so a cluster needs no shared file system. A μ whose
curve fails is reported in its row (status 'failed' and the error) and never costs the others.
A μ that another process is solving into the same store (another sweep, a `stored_curve`) is
waited for and read, not solved twice (`store.lock_entry`). Worker processes end with the sweep's
process, even when it is killed.

Output (`Sweep.write`): events.csv (one row per μ: every event, its error estimate absolute and
relative, the cost and the status), curves.csv (the approach and retraction paths in long format)
and sweep.json (units of every column, the inputs and the solver revision).
"""

import csv
import io
import json
import multiprocessing
import os
import threading
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from concurrent.futures.process import BrokenProcessPool
from dataclasses import asdict, dataclass, replace
from pathlib import Path

import numpy as np

from ..closed_forms.scales import si_unit
from ..curves.curve import Curve
from ..plumbing.checks import in_range
from ..plumbing.cli import format_cell
from ..plumbing.errors import InputError
from ..plumbing.files import staged_folder, writable_folder, write_atomic
from ..plumbing.progress import share
from ..plumbing.version import __version__
from ..solids.fe import Solid
from ..solver.presets import relative_cost
from ..solver.result import PATH_COLUMNS, path_rows
from ..solver.solve import solvable_mu, solve_curve
from .store import (
    COST_KEYS,
    STORE,
    cache_dir,
    check_entry,
    curve_folder,
    keep,
    load_stored,
    lock_entry,
    mu_key,
    solver_revision,
    stored_curve,
    unlock_entry,
)

#: Who writes a sweep's output folder, as its record says (`plumbing.files.staged_folder`).
OWNER = "python -m fem_asperity sweep"
#: Columns of curves.csv with their units (dimensionless, the paper's scales).
CURVE_COLUMNS = {"mu": "-", **PATH_COLUMNS}
#: Units of the events (events.csv names each estimate `<event>_err` and `<event>_rel_err`).
EVENT_UNITS = {"p_max": "2 pi R dgamma", "delta_oc": "eps", "delta_o_star": "eps",
               "a_c": "sqrt(eps R)", "jump_in": "true | false", "x_oc": "eps",
               "delta_jump_in": "eps", "p_jump_before": "2 pi R dgamma",
               "p_jump_after": "2 pi R dgamma", "p_off": "2 pi R dgamma", "delta_off": "eps",
               "delta_jump_out": "eps", "p_jump_out_before": "2 pi R dgamma",
               "p_jump_out_after": "2 pi R dgamma"}
#: Events and estimates that events.csv also gives in SI (physical inputs), their columns
#: (`Scales.si_columns`: <key>_N or <key>_m) and the inputs that precede them.
SI_EVENTS = [key for key in EVENT_UNITS if si_unit(key)] + [
    f"{key}_err" for key in EVENT_UNITS if si_unit(key)]
SI_INPUTS = {"E_star": "Pa", "dgamma": "J/m^2", "eps": "m", "R": "m"}
SI_COLUMNS = list(SI_INPUTS) + [f"{key}_{si_unit(key)}" for key in SI_EVENTS]
SI_UNITS = SI_INPUTS | {f"{key}_{si_unit(key)}": si_unit(key) for key in SI_EVENTS}
#: Units of the cost columns.
COST_UNITS = {**dict.fromkeys(COST_KEYS, "-"), "wall_s": "s (of the solve that stored the curve)"}


@dataclass(frozen=True)
class SweepRow:
    """One μ of a sweep: its `StoredCurve` (None if it failed), status and message."""

    mu: float
    status: str
    message: str
    curve: object = None

    def events_row(self):
        """The events.csv row: μ, status, every event with its error estimate (absolute and
        relative to the event's magnitude), the cost, the message."""
        row = {"mu": self.mu, "status": self.status}
        records = self.curve.events.records() if self.curve else dict.fromkeys(EVENT_UNITS)
        estimate = (self.curve.error_estimate if self.curve else None) or {}
        relative = (self.curve.relative_error_estimate if self.curve else None) or {}
        for key in EVENT_UNITS:
            row[key] = records[key]
            if key != "jump_in":
                row[f"{key}_err"], row[f"{key}_rel_err"] = estimate.get(key), relative.get(key)
        row.update(self.curve.cost if self.curve else dict.fromkeys(COST_KEYS))
        row["message"] = self.message
        return row


@dataclass(frozen=True)
class Sweep:
    """The rows of a sweep (by increasing μ) and how they were obtained: method, accuracy,
    whether with the error estimate and how it was asked for (`estimate_by`), how many curves
    were solved now and how many read from the store, and the wall time; the `solid` of every
    curve. `scales`: the physical inputs (`Scales`) of the μ that came from them; their rows
    gain the inputs and every event in SI."""

    method: str
    accuracy: str
    error_estimate: bool
    rows: tuple
    solved: int
    stored: int
    wall_s: float
    scales: tuple = ()
    solid: Solid = Solid()
    estimate_by: str = "auto"

    @property
    def failed(self):
        """The rows whose curve could not be solved."""
        return [row for row in self.rows if row.curve is None]

    def events_table(self):
        """events.csv as a list of dicts, one per μ; with `scales`, each row continues with the
        physical inputs and every event and estimate in SI (p_max_N, p_max_err_N, a_c_m, ...)."""
        by_mu = {mu_key(s.mu): s for s in self.scales}
        table = []
        for row in self.rows:
            events = row.events_row()
            if self.scales:
                scales, si = by_mu.get(row.mu), {}
                if scales:
                    si = {k: getattr(scales, k) for k in SI_INPUTS} | scales.si_columns(
                        {k: events[k] for k in SI_EVENTS})
                events |= {k: si.get(k) for k in SI_COLUMNS}
            table.append(events)
        return table

    def curves_table(self):
        """curves.csv as a list of dicts: every point of every approach and retraction."""
        table = []
        for row in self.rows:
            if row.curve is None:
                continue
            for name in ("approach", "retraction"):
                table += _long(row.mu, name, getattr(row.curve, name))
        return table

    def to_dataframe(self, table="events"):
        """events.csv ('events') or curves.csv ('curves') as a pandas DataFrame (optional
        extra `tables`)."""
        try:
            import pandas as pd
        except ImportError:
            raise ImportError("to_dataframe needs pandas: pip install pandas") from None
        return pd.DataFrame(self.events_table() if table == "events" else self.curves_table())

    def records(self):
        """The sidecar sweep.json: inputs, counters, units and provenance."""
        return {"method": self.method, "accuracy": self.accuracy,
                "error_estimate": self.error_estimate, "estimate_by": self.estimate_by,
                "solid": asdict(self.solid),
                "mu": [row.mu for row in self.rows],
                "solved": self.solved, "stored": self.stored, "failed": len(self.failed),
                "wall_s": self.wall_s, "solver_revision": solver_revision(),
                "version": __version__,
                "units": {"events": {**EVENT_UNITS, **COST_UNITS,
                                     **(SI_UNITS if self.scales else {})},
                          "curves": CURVE_COLUMNS}}

    def write(self, folder):
        """events.csv, curves.csv and sweep.json into `folder`, all or none. `folder` is new,
        empty or an earlier sweep's (`OWNER`); a folder holding other files is refused."""
        folder = Path(folder)
        with staged_folder(folder, owner=OWNER) as stage:
            write_atomic(stage / "events.csv", _csv(self.events_table()))
            write_atomic(stage / "curves.csv", _csv(self.curves_table(), list(CURVE_COLUMNS)))
            write_atomic(stage / "sweep.json",
                         json.dumps(self.records(), indent=1, allow_nan=False) + "\n")
        return [folder / name for name in ("events.csv", "curves.csv", "sweep.json")]


def _long(mu, name, curve: Curve):
    return [{"mu": mu} | row for row in path_rows(curve, name)]


def _csv(rows, columns=None):
    """CSV text of dict rows (missing values empty); text fields quoted where needed."""
    columns = columns or (list(rows[0]) if rows else ["mu"])
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(columns)
    for row in rows:
        writer.writerow([format_cell(row[c], missing="", words=("true", "false"), digits=10)
                         for c in columns])
    return out.getvalue()


#: Most μ of a `mu_range`: a curve each, seconds to minutes apiece.
MU_RANGE_MAX_N = 10_000


def mu_range(lo, hi, n):
    """`n` Tabor parameters from `lo` to `hi`, evenly spaced in log μ (μ spans decades)."""
    lo, hi = solvable_mu(lo, "lo (--mu-range LO)"), solvable_mu(hi, "hi (--mu-range HI)")
    n = in_range("n (--mu-range N)", n)  # a finite number
    if not (lo < hi and int(n) == n and 2 <= n <= MU_RANGE_MAX_N):
        raise InputError(f"mu range (--mu-range LO HI N) needs lo < hi and n whole in [2, "
                         f"{MU_RANGE_MAX_N}]; got {lo:g}, {hi:g}, {n:g}")
    return [float(m) for m in np.geomspace(lo, hi, int(n))]


def solve_for_sweep(mu, method, accuracy, error_estimate, solid=Solid(), estimate_by="auto"):
    """The worker's job: one curve, without its solved model (it does not travel between
    processes), or the exception that stopped it."""
    try:
        result = solve_curve(mu, method=method, accuracy=accuracy, error_estimate=error_estimate,
                             estimate_by=estimate_by, solid=solid)
    except Exception as exc:  # reported in the μ's row; the sweep goes on
        return exc
    return replace(result, model=None)


class WorkerDied(RuntimeError):
    """The worker process solving a μ ended without a result (killed, out of memory, crashed)."""


#: How often a worker checks that the sweep's process still lives [s]: a worker outlives a
#: killed sweep by at most this (plus the rest of a call that holds the GIL).
PARENT_CHECK_S = 0.5


def _end_with_parent(parent):
    """Worker initializer: end this worker (os._exit) once the sweep's process `parent` (its
    pid) has ended, however it ended.

    A sweep killed by SIGKILL runs no cleanup, and an idle or busy worker would live on for
    ever (and with it multiprocessing's resource tracker, which ends when the last process
    holding its pipe does). An orphan gets a new parent (init or a subreaper), so a thread
    that polls os.getppid() sees it on any POSIX system. Not prctl(PR_SET_PDEATHSIG): Linux
    only, and it fires when the *thread* that started the worker ends, which for
    ProcessPoolExecutor is the caller's thread or its manager thread (it starts replacement
    workers), so it could kill the workers of a sweep that lives on."""

    def watch():
        while os.getppid() == parent:
            time.sleep(PARENT_CHECK_S)
        os._exit(1)

    threading.Thread(target=watch, name="end-with-sweep", daemon=True).start()


def _pool_jobs(jobs, todo, args, job):
    """Run `job(μ, *args)` for each μ of `todo` in `jobs` fresh processes (each ending with this
    one: `_end_with_parent`); yield (μ, result), then return the μ whose results were lost
    because a worker died (the pool breaks)."""
    # Fresh interpreters (spawn): forking a process that runs BLAS and progress threads can
    # deadlock, and Python deprecates it.
    context = multiprocessing.get_context("spawn")
    lost = []
    with ProcessPoolExecutor(max_workers=jobs, mp_context=context, initializer=_end_with_parent,
                             initargs=(os.getpid(),)) as pool:
        futures = {pool.submit(job, mu, *args): mu for mu in todo}
        try:
            for future in as_completed(futures):
                try:
                    result = future.result()
                except BrokenProcessPool:
                    lost.append(futures[future])
                    continue
                yield futures[future], result
        except BaseException:  # Ctrl-C: stop now; what is stored stays stored
            _stop(pool)
            raise
    return lost


def _stop(pool):
    """Cancel what waits in `pool` and end its workers: leaving the pool otherwise waits for
    the curves being solved (a Ctrl-C took up to 83 s to act). The workers only solve; this
    process stores, so nothing is left half-written. (`_processes`: the executor's own
    record of its workers; Python 3.14's terminate_workers does the same.)"""
    pool.shutdown(wait=False, cancel_futures=True)
    for process in list((pool._processes or {}).values()):
        process.terminate()


#: Why a sweep called by a worker as it starts is refused, and what to do.
UNGUARDED = ("sweep() was called again by a worker process as it imported your script: the "
             "workers are fresh interpreters that import the script that started them, so put "
             "the call under `if __name__ == \"__main__\":`")


def _local_jobs(jobs, todo, args, job=solve_for_sweep):
    """Submit the curves to `jobs` worker processes; yield (μ, result or exception). When a
    worker dies, the pool loses every curve still running or waiting: each of those is then run
    alone in a process of its own, so that only the μ that kills its worker is reported
    (`WorkerDied`) and the others are solved."""
    lost = yield from _pool_jobs(jobs, todo, args, job)
    for mu in sorted(lost):
        if (yield from _pool_jobs(1, [mu], args, job)):
            yield mu, WorkerDied(f"the worker process solving mu = {mu:g} died (if its "
                                 f"error above says so: {UNGUARDED})")


def _check_scheduler(scheduler):
    """Refuse (`InputError` naming --scheduler) an address that is no Dask scheduler's
    ('tcp://host:8786': a known scheme and, where it has them, a host and port), and a missing
    dask.distributed; nothing is connected yet."""
    try:
        from distributed.comm import get_address_host_port, parse_address
    except ImportError:
        raise InputError("--scheduler needs dask.distributed: pip install "
                         "'adhesive-contact-verification[cluster]'") from None
    try:
        if parse_address(scheduler)[0] != "inproc":  # an in-process cluster's has no port
            get_address_host_port(scheduler)
    except (TypeError, ValueError) as exc:
        raise InputError(f"--scheduler must be the address of a Dask scheduler, such as "
                         f"tcp://host:8786; got {scheduler!r} ({exc})") from None


def _cluster_jobs(scheduler, todo, args):
    """Submit the curves to the Dask scheduler at `scheduler`; yield (μ, result or exception)."""
    from dask.distributed import Client
    from dask.distributed import as_completed as completed

    with Client(scheduler) as client:
        futures = {client.submit(solve_for_sweep, mu, *args, pure=False): mu for mu in todo}
        for future in completed(list(futures)):
            try:
                result = future.result()
            except Exception as exc:  # e.g. KilledWorker: reported in its row
                result = exc
            yield futures[future], result


#: Most store locks a sweep holds at once (each is an open file, and the soft limit on open
#: files can be as low as 256): more μ than this are solved in rounds.
LOCKS_AT_ONCE = 128


def _free_locks(pending, folders):
    """{μ: its store lock} for the first μ of `pending` (up to LOCKS_AT_ONCE) whose lock no
    other process holds."""
    locks = {}
    try:
        for mu in pending:
            if len(locks) == LOCKS_AT_ONCE:
                break
            if (lock := lock_entry(folders[mu], wait=False)) is not None:
                locks[mu] = lock
    except BaseException:  # e.g. too many open files, Ctrl-C: none of them stays taken
        for lock in locks.values():
            unlock_entry(lock)
        raise
    return locks


def _unclaimed(todo, folders, run):
    """(μ, result or exception) of `run(μs)` for each μ of `todo` that no other process is
    solving into the same store, and (μ, None) for each that another process stored meanwhile.

    Each μ's store lock (`store.lock_entry` of its folder in `folders`) is taken before its
    solve and released when the caller, having kept its result, asks for the next: a μ locked
    elsewhere is left to its holder, waited for when nothing else is left, then read, or solved
    here if the holder stored nothing (it failed or was killed). This waits only while it holds
    no lock, so two sweeps never wait for each other."""
    pending, locks, batch = list(todo), {}, None
    try:
        while pending:
            locks = _free_locks(pending, folders)
            if not locks:  # every one is being solved elsewhere: wait for one, then look again
                unlock_entry(lock_entry(folders[pending[0]]))
                continue
            for mu in list(locks):
                if load_stored(folders[mu]) is not None:  # stored elsewhere while we looked
                    unlock_entry(locks.pop(mu))
                    pending.remove(mu)
                    yield mu, None
            batch = run(list(locks)) if locks else None
            for mu, result in batch or ():
                yield mu, result
                unlock_entry(locks.pop(mu))
                pending.remove(mu)
    finally:  # an error or Ctrl-C: what is stored stays stored, the rest is free again once
        if batch is not None:  # the workers solving it have stopped (`run` is a generator)
            batch.close()
        for lock in locks.values():
            unlock_entry(lock)


def stored_curves(mus, *, method="bem", progress=None, **options):
    """{μ: `StoredCurve`} for each of `mus`, one after the other (`stored_curve` with `method`
    and `options`; a `sweep` solves on several processes instead). progress: callable(fraction
    of the work done), told while a curve is solved, each curve not stored yet (its folder
    absent) weighted by its `relative_cost`."""
    keys = {k: options[k] for k in ("accuracy", "error_estimate", "unstable_branch", "solid",
                                    "cache") if k in options}
    todo = [mu for mu in mus if not curve_folder(mu, method=method, **(
        {"accuracy": "default", "error_estimate": False} | keys)).exists()]
    cost = {mu: relative_cost(mu, method, options.get("solid", Solid())) for mu in todo}
    total, done, parts = sum(cost.values()), 0.0, {}
    for mu in todo:
        parts[mu] = share(progress, done / total, (done + cost[mu]) / total)
        done += cost[mu]
    return {mu: stored_curve(mu, method=method, progress=parts.get(mu), **options) for mu in mus}

def sweep(mus, *, method="fem", accuracy="default", error_estimate=True, estimate_by="auto",
          solid=Solid(), jobs=None, scheduler=None, cache=None, progress=None, scales=()):
    """Solve the curves at every μ of `mus` (those not stored yet) and return the `Sweep`.

    method, accuracy, error_estimate, estimate_by, solid: as `solve_curve`. jobs: worker
    processes on this machine (default: one per core); scheduler: address of a Dask scheduler
    instead ('tcp://host:8786').
    cache: the store's folder (default $ADHESION_CACHE). progress: callable(fraction of the
    work done), called as each curve finishes, each weighted by its `relative_cost`. scales:
    the `Scales` the μ came from (physical inputs), for SI columns in the events.
    """
    if getattr(multiprocessing.current_process(), "_inheriting", False):
        # a worker importing the caller's script, which calls sweep at its top level: without
        # this the worker waited for the store locks its parent holds, and both hung
        raise InputError(UNGUARDED)
    # Every input is checked before the store is touched. μ as the store tells them apart
    # (`mu_key`): μ that share a folder are one μ.
    mus = sorted({check_entry(m, method, accuracy) for m in np.atleast_1d(mus)})
    if not mus:
        raise InputError("a sweep needs at least one mu")
    jobs = in_range("jobs", (os.cpu_count() or 1) if jobs is None else jobs)
    if int(jobs) != jobs or jobs < 1:
        raise InputError(f"jobs must be a whole number >= 1; got {jobs!r}")
    if scheduler is not None:
        _check_scheduler(scheduler)
    start = time.perf_counter()
    folders = {mu: curve_folder(mu, method=method, accuracy=accuracy, solid=solid,
                                error_estimate=error_estimate, estimate_by=estimate_by,
                                cache=cache) for mu in mus}
    stored = {mu: load_stored(folders[mu]) for mu in mus}
    cost = {mu: relative_cost(mu, method, solid) for mu in mus}
    todo = sorted((mu for mu in mus if stored[mu] is None), key=cost.get, reverse=True)
    if todo:  # before solving; a store that holds every μ is only read (it may be read-only)
        writable_folder(cache or cache_dir(), STORE)
    failures, solved, done, finished = {}, 0, 0.0, 0
    total = sum(cost[mu] for mu in todo)
    args = (method, accuracy, error_estimate, solid, estimate_by)

    def run(batch):
        return (_cluster_jobs(scheduler, batch, args) if scheduler is not None
                else _local_jobs(int(jobs), batch, args))

    for mu, result in _unclaimed(todo, folders, run):
        if isinstance(result, BaseException):
            failures[mu] = f"{type(result).__name__}: {result}"
        else:
            if result is not None:  # None: solved and stored by another process meanwhile
                keep(result, folders[mu])
                solved += 1
            stored[mu] = load_stored(folders[mu])
        done, finished = done + cost[mu], finished + 1
        if progress is not None:  # the last exactly 1: sums in another order differ by ulps
            progress(1.0 if finished == len(todo) else done / total)
    rows = []
    for mu in mus:
        if mu in failures:
            rows.append(SweepRow(mu, "failed", failures[mu]))
        else:
            rows.append(SweepRow(mu, stored[mu].status, stored[mu].message, stored[mu]))
    return Sweep(method, accuracy, error_estimate, tuple(rows), solved=solved,
                 stored=len(mus) - solved - len(failures), wall_s=time.perf_counter() - start,
                 scales=tuple(scales), solid=solid, estimate_by=estimate_by)

