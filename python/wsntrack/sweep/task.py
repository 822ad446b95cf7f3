"""One run of a spec sweep, from start to record, wherever it is executed: in a thread of the sweep on
this machine, or on a Dask worker (executors.py). A task is a plain dict (the run's command, its run
directory and log, the scenario's SHA-256, the metrics to read) and so is its result (status, exit,
wall_s, metrics, attempts), so that both cross a Dask cluster as builtins.

The run's log is locked (flock) while its wsntrack lives: wsntrack inherits the locked descriptor as
its stdout, so a wsntrack that outlived the worker that started it keeps the lock, and the run
started again elsewhere waits for it instead of writing into the same directory beside it. wsntrack is
started under `setpriv --pdeathsig TERM`, so that it is told to stop when its starter dies."""

import fcntl
import hashlib
import json
import os
import re
import shlex
import shutil
import socket
import subprocess
import time
from pathlib import Path

from .. import catalogue
from ..rundir import InputError, incomplete_reason, read_json
from .metrics import metric_sources, metric_value

RECORD = "sweep_run.json"  # in each run directory, written when the run has finished

# A cluster that lost the race for its DDS ports: between the launcher's check that a domain's ports
# are free and the bind, a cluster started at the same moment (this sweep's next run, or anyone's)
# took them. Nothing of the run's own is wrong, so it is started again, at most PORT_CLASH_ATTEMPTS times.
PORT_CLASH = re.compile(r"failed to create unicast sockets|dds_create_domain \d+ failed")
PORT_CLASH_ATTEMPTS = 3
STOP_GRACE_S = 20  # wsntrack stops its role processes on SIGTERM; SIGKILL after this long
LOG_LOCK_WAIT_S = 60  # for an earlier attempt's wsntrack to end (it was sent SIGTERM when its starter died)


def sha256_of(path):
    digest = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def metrics_of(path, metrics):
    """The metrics of a complete run's metrics.json; ValueError for a run that is not complete
    (run.json's status: a failed run must never enter the results as numbers) or a malformed file."""
    incomplete = incomplete_reason(Path(path).parent)
    if incomplete:
        raise ValueError(f"{Path(path).parent}: {incomplete}")
    data = read_json(Path(path))
    if not isinstance(data, dict) or not isinstance(data.get("metrics"), dict):
        raise ValueError("no 'metrics' object: not a complete metrics.json")
    values = {}
    for metric in metrics:
        where = metric_sources()[metric][1]
        try:
            value = metric_value(metric, data, Path(path).parent)
        except (OSError, KeyError, TypeError, InputError) as error:
            raise ValueError(f"{metric}: cannot read it from the run directory ({error!r})") from None
        if value is not None and (isinstance(value, bool) or not isinstance(value, (int, float))):
            what = "the run's files" if callable(where) else ".".join(where)
            raise ValueError(f"{metric}: expected a number at {what}, got {value!r}")
        values[metric] = value
    return values


def port_clash(log, run_dir):
    """Whether a failed run's log, or its roles' logs, show it lost its DDS ports to another cluster."""
    for path in [log] + sorted((run_dir / "logs").glob("*.log")):
        try:
            if path.stat().st_size < (1 << 22) and PORT_CLASH.search(path.read_text(encoding="utf-8", errors="replace")):
                return True
        except OSError:
            pass
    return False


def _locked_log(log, stop):
    """The run's log, opened for appending and locked (unless the filesystem has no locks), emptied;
    None when `stop` was set while an earlier attempt's wsntrack still held it. RuntimeError when it
    held it for LOG_LOCK_WAIT_S."""
    log.parent.mkdir(parents=True, exist_ok=True)
    log_file = open(log, "a", encoding="utf-8")
    deadline = time.monotonic() + LOG_LOCK_WAIT_S
    while True:
        try:
            fcntl.flock(log_file, fcntl.LOCK_EX | fcntl.LOCK_NB)
            break
        except BlockingIOError:
            stopping = stop.is_set()
            if stopping or time.monotonic() > deadline:
                log_file.close()
                if stopping:
                    return None
                raise RuntimeError(f"{log}: an earlier attempt's wsntrack still holds it after {LOG_LOCK_WAIT_S} s")
            time.sleep(0.1)
        except OSError:
            break  # no locks here (an NFS mount with nolock): the launcher's own lock still guards the directory
    log_file.truncate(0)
    return log_file


def _start(command, log_file, attempt):
    """Starts wsntrack, its output appended to the locked log (so that it holds the lock too)."""
    if attempt > 1:
        log_file.write(f"sweep: the run lost its DDS ports to another cluster starting at the same time; "
                       f"attempt {attempt} of {PORT_CLASH_ATTEMPTS}\n")
    log_file.write("$ " + shlex.join(command) + "\n")
    log_file.flush()
    setpriv = shutil.which("setpriv")
    prefix = [setpriv, "--pdeathsig", "TERM", "--"] if setpriv else []
    return subprocess.Popen(prefix + command, stdout=log_file, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL)


def _wait(process, stop, poll_s):
    """wsntrack's exit status, or None when `stop` was set first: then it is sent SIGTERM (by its
    PID), and SIGKILL after STOP_GRACE_S."""
    while True:
        try:
            return process.wait(timeout=poll_s)
        except subprocess.TimeoutExpired:
            pass
        if stop.is_set():
            process.terminate()
            try:
                process.wait(timeout=STOP_GRACE_S)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()
            return None


def _finish(task, exit_code, wall_s, attempts, worker):
    """The result of a run that ended, and RECORD in its directory (written whole, then renamed) for
    the next invocation to reuse."""
    run_dir, log = Path(task["run_dir"]), Path(task["log"])
    result = {"status": "failed", "exit": exit_code, "wall_s": wall_s, "metrics": {}, "attempts": attempts}
    record = {"command": task["command"], "scenario_sha256": task["scenario_sha256"], "exit": exit_code,
              "wall_s": round(wall_s, 3), "finished_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
              "host": socket.gethostname(), "dask_worker": worker}
    if exit_code == 0:
        try:
            record["metrics_sha256"] = sha256_of(run_dir / "metrics.json")
            result["metrics"] = metrics_of(run_dir / "metrics.json", task["metrics"])
            result["status"] = "ok"
        except (OSError, ValueError) as error:
            record["exit"] = None
            with open(log, "a", encoding="utf-8") as f:
                f.write(f"sweep: the run exited 0 but is not counted: {error}\n")
    record["status"] = result["status"]
    if run_dir.is_dir():
        temporary = run_dir / (RECORD + ".tmp")
        temporary.write_text(json.dumps(record, indent=2) + "\n", encoding="utf-8")
        os.replace(temporary, run_dir / RECORD)
    return result


def run_task(task, stop, poll_s=0.05, worker=None):
    """Runs one run to its end: started again when it lost its DDS ports (at most PORT_CLASH_ATTEMPTS
    times), stopped when `stop` (anything with is_set()) is set. Returns its result: status ok or
    failed with its metrics, or interrupted, or not run (stopped before it started). `worker`: the
    Dask worker's address, recorded."""
    result = {"status": "not run", "exit": None, "wall_s": None, "metrics": {}, "attempts": 0}
    if stop.is_set():
        return result
    catalogue.use(task["command"][0])  # the metrics' paths of the wsntrack that runs it (on a worker too)
    log_file = _locked_log(Path(task["log"]), stop)
    if log_file is None:
        return result
    try:
        (Path(task["run_dir"]) / RECORD).unlink(missing_ok=True)  # never complete until it finishes again
        for attempt in range(1, PORT_CLASH_ATTEMPTS + 1):
            started = time.monotonic()
            process = _start(task["command"], log_file, attempt)
            exit_code = _wait(process, stop, poll_s)
            if exit_code is None:
                return dict(result, status="interrupted", exit=process.returncode, attempts=attempt)
            if exit_code == 0 or not port_clash(Path(task["log"]), Path(task["run_dir"])):
                break
        return _finish(task, exit_code, time.monotonic() - started, attempt, worker)
    finally:
        log_file.close()
