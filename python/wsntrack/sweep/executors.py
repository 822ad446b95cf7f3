"""Where a spec sweep's runs go: LocalExecutor, -j at a time on this machine, or DaskExecutor, on a Dask
distributed cluster (`--scheduler`, Debian's python3-distributed). Both take the same tasks (task.py),
each run one task, and hand back futures with done() and result(); both have a stop event the tasks
watch. The runner (runner.py) is one loop over either.

On a cluster every path is the same on the client and on every worker: the wsntrack executable, the
scenario, this package's tree and the sweep directory, into which the workers write the run
directories (a shared filesystem). The client checks that each worker sees them before anything runs.
A worker that dies has its runs started again on another (Dask reschedules them); a task that raises
is retried TASK_RETRIES times; a run that fails is a failed run, as on this machine."""

import concurrent.futures
import json
import threading
import time
import uuid
from pathlib import Path

from . import on_worker
from .common import UsageError, plural
from .task import run_task

PYTHON_DIR = Path(__file__).resolve().parents[2]  # the directory that holds the wsntrack package
TASK_RETRIES = 2  # a task that raised (its worker could not write the log, say) runs again elsewhere
WORKER_WAIT_S = 60  # for the first worker to join the scheduler


def outcome(future):
    """A finished future's result; a task that raised, or that the cluster dropped (its scheduler gone:
    the sweep never cancels a task itself), is a failed run with the reason."""
    try:
        return future.result()
    except concurrent.futures.CancelledError:
        reason = "the Dask cluster dropped it (its scheduler is gone?)"
    except Exception as error:  # whatever the task or the cluster raised: the run is reported failed with it
        reason = f"{type(error).__name__}: {error}"
    return {"status": "failed", "exit": None, "wall_s": None, "metrics": {}, "attempts": 0, "reason": reason}


class LocalExecutor:
    """-j runs at a time on this machine, each in a thread that starts its wsntrack and waits for it."""

    def __init__(self, jobs):
        self.jobs = jobs
        self.stop_event = threading.Event()
        self._pool = concurrent.futures.ThreadPoolExecutor(max_workers=jobs, thread_name_prefix="sweep-run")

    def where(self, runs):
        return f"{min(self.jobs, runs)} at a time"

    def submit(self, task):
        return self._pool.submit(run_task, task, self.stop_event)

    def stop(self):
        self.stop_event.set()

    def close(self):
        self._pool.shutdown(wait=True, cancel_futures=True)


def require_distributed():
    """Dask's distributed and cloudpickle, or UsageError naming the Debian package."""
    try:
        import cloudpickle
        import distributed
    except ImportError as error:
        raise UsageError(f"--scheduler needs Dask's distributed ({error}; Debian: apt-get install "
                         "python3-distributed), and the tool run with /usr/bin/python3") from None
    return distributed, cloudpickle


def _scheduler_address(scheduler, timeout):
    """The address `scheduler` names: itself (tcp://HOST:PORT, or HOST:PORT), or the one in the file
    `dask scheduler --scheduler-file` writes, waited for up to `timeout` s (the scheduler may still be
    starting, as in a batch job); UsageError."""
    from distributed.comm.addressing import get_address_host_port
    try:
        get_address_host_port(scheduler)
        return scheduler
    except ValueError as error:
        if "://" in scheduler:
            raise UsageError(f"--scheduler {scheduler}: not a scheduler's address ({error})") from None
    deadline = time.monotonic() + timeout
    while True:
        try:
            return json.loads(Path(scheduler).read_text(encoding="utf-8"))["address"]
        except (OSError, ValueError, KeyError, TypeError):
            if time.monotonic() > deadline:
                raise UsageError(f"--scheduler {scheduler}: neither a scheduler's address (tcp://HOST:PORT) nor a "
                                 f"file that `dask scheduler --scheduler-file` wrote within {timeout:g} s") from None
            time.sleep(0.1)


def _connect(distributed, scheduler):
    """A client of the scheduler `scheduler` names (an address, or the file `dask scheduler
    --scheduler-file` writes), or UsageError naming it."""
    from dask import config
    from dask.utils import parse_timedelta
    timeout = parse_timedelta(config.get("distributed.comm.timeouts.connect"), "s")
    address = _scheduler_address(scheduler, timeout)
    try:
        return distributed.Client(address, timeout=timeout, set_as_default=False)
    except (OSError, TimeoutError) as error:
        raise UsageError(f"--scheduler {scheduler}: no Dask scheduler answered at {address} within {timeout:g} s "
                         f"({type(error).__name__}: {error}); start one with `dask scheduler`, or wait longer "
                         "with DASK_DISTRIBUTED__COMM__TIMEOUTS__CONNECT=60s") from None


class DaskExecutor:
    """Each run a task on the Dask cluster whose scheduler is at `scheduler`; `paths`: [(path, "r" or
    "x")] every worker must see, besides this package and `out` (the sweep directory)."""

    def __init__(self, scheduler, paths, out):
        distributed, cloudpickle = require_distributed()
        self.client = _connect(distributed, scheduler)
        try:
            self.address = self.client.scheduler.address
            try:
                self.client.wait_for_workers(1, timeout=WORKER_WAIT_S)
            except TimeoutError:
                raise UsageError(f"--scheduler {scheduler}: no worker joined the scheduler at {self.address} "
                                 f"within {WORKER_WAIT_S} s; start workers with `dask worker {self.address}`") from None
            cloudpickle.register_pickle_by_value(on_worker)  # the workers need not have the package on their path
            self._check_workers(paths, out)
            self.stop_name = f"wsntrack-sweep-stop-{uuid.uuid4().hex}"
            self.stop_event = distributed.Event(self.stop_name, client=self.client)
            self.stopped = False
        except BaseException:
            self.client.close()
            raise

    def _check_workers(self, paths, out):
        """UsageError unless every worker sees every path, this package and a file just written in `out`."""
        created = not out.exists()
        out.mkdir(parents=True, exist_ok=True)
        probe = out / f".sweep-probe-{uuid.uuid4().hex}"
        probe.write_text("written by the sweep's client; every worker must see it\n", encoding="utf-8")
        try:
            wanted = [(str(p), mode) for p, mode in paths] + [(str(PYTHON_DIR / "wsntrack" / "sweep" / "task.py"), "r"),
                                                             (str(probe), "r")]
            seen = self.client.run(on_worker.missing_paths, wanted)
        finally:
            probe.unlink()
        missing = {w: m for w, m in seen.items() if m}
        if missing:
            if created:
                out.rmdir()
            worker, paths_missing = sorted(missing.items())[0]
            raise UsageError(f"--scheduler: worker {worker} cannot see {paths_missing[0]}"
                             f"{' (the sweep directory)' if paths_missing[0] == str(probe) else ''} ({len(missing)} of "
                             f"{plural(len(seen), 'worker')} cannot see a path): the executable, the scenario, the "
                             "tools' tree and --out must be at the same paths on every worker (a shared filesystem)")

    def where(self, runs):
        workers = self.client.scheduler_info()["workers"]
        threads = sum(w["nthreads"] for w in workers.values())
        return (f"on the Dask cluster at {self.address} ({plural(len(workers), 'worker')}, "
                f"{plural(threads, 'thread')} now)")

    def submit(self, task):
        return self.client.submit(on_worker.run_there, str(PYTHON_DIR), task, self.stop_name, pure=False,
                                  retries=TASK_RETRIES, key=f"{task['name']}-{uuid.uuid4().hex[:12]}")

    def stop(self):
        self.stopped = True
        self.stop_event.set()

    def close(self):
        """Disconnects; a stop event that was never set is dropped from the scheduler (a set one stays
        for the tasks that may still poll it)."""
        if not self.stopped and self.client.status == "running":
            try:
                self.stop_event.clear()
            except (OSError, TimeoutError):
                pass  # the scheduler went away: nothing there to drop
        self.client.close(timeout=10)
