"""Running a spec sweep: its combinations checked with `wsntrack validate`, its runs started -j at a
time (a run that lost its DDS ports to a cluster starting at the same moment started again), each
finished run recorded in its directory so that the same command again reuses it, and SIGINT or
SIGTERM stopping only the runs this sweep started."""

import hashlib
import itertools
import json
import os
import re
import shlex
import signal
import subprocess
import sys
import time
from pathlib import Path

from ..rundir import InputError, incomplete_reason, read_json
from .common import UsageError, duration, engine_sets, plural, scenario_engine, validate
from .metrics import METRIC_SOURCES, metric_value
from .spec import SpecError

RECORD = "sweep_run.json"  # in each run directory, written when the run has finished


def sha256_of(path):
    digest = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def check_with_wsntrack(spec, wsntrack):
    """Exit-2 errors (SpecError) for what would make every run fail: a fixed value, an engine, a
    swept key all of whose values wsntrack rejects; warnings for single swept values it rejects."""
    def check(sets):
        command, error = validate(wsntrack, spec.scenario, sets)
        return error if error is None else (error or f"{shlex.join(command)} failed")

    error = check(spec.fixed)
    if error:
        lines = [line for key, line in spec.fixed_lines.items() if f"--set {key}=" in error]
        command_line = [key for key, _ in spec.fixed if key not in spec.fixed_lines and f"--set {key}=" in error]
        if command_line:
            raise UsageError(f"--set {command_line[0]}: rejected by wsntrack validate: {error}")
        raise SpecError(spec.path, lines[0] if lines else spec.scenario_line, f"rejected by wsntrack validate: {error}")
    if spec.engines is None:
        try:
            spec.engines = [scenario_engine(wsntrack, spec.scenario, spec.fixed)]
        except UsageError as error:
            raise SpecError(spec.path, spec.scenario_line, str(error)) from None
    for engine, line in itertools.zip_longest(spec.engines, spec.engine_lines):
        error = check(engine_sets(engine) + spec.fixed)
        if error:
            raise SpecError(spec.path, line, f"engine {engine}: rejected by wsntrack validate: {error}")
    warnings = []
    base = engine_sets(spec.engines[0]) + spec.fixed
    for key, values, key_line, value_lines in spec.grid:
        errors = [check(base + [(key, value)]) for value in values]
        if all(errors):
            raise SpecError(spec.path, key_line, f"grid: {key}: wsntrack validate rejects every value: {errors[0]}")
        for value, line, error in zip(values, value_lines, errors):
            if error:
                warnings.append(f"{spec.path}:{line}: warning: {key}={value} is rejected by wsntrack validate, so "
                                f"its runs will fail: {error}")
    return warnings


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
        where = METRIC_SOURCES[metric][1]
        try:
            value = metric_value(metric, data, Path(path).parent)
        except (OSError, KeyError, TypeError, InputError) as error:
            raise ValueError(f"{metric}: cannot read it from the run directory ({error!r})") from None
        if value is not None and (isinstance(value, bool) or not isinstance(value, (int, float))):
            what = "the run's files" if callable(where) else ".".join(where)
            raise ValueError(f"{metric}: expected a number at {what}, got {value!r}")
        values[metric] = value
    return values


def reusable(run, scenario_sha, metrics):
    """Whether an earlier invocation completed exactly this run; fills in its results if so."""
    try:
        record = json.loads((run.run_dir / RECORD).read_text(encoding="utf-8"))
        if not isinstance(record, dict) or record.get("command") != run.command or record.get("exit") != 0 or \
                record.get("scenario_sha256") != scenario_sha:
            return False
        if sha256_of(run.run_dir / "metrics.json") != record.get("metrics_sha256"):
            return False
        run.metrics = metrics_of(run.run_dir / "metrics.json", metrics)
    except (OSError, ValueError):
        return False
    run.status, run.exit_code, run.reused = "ok", 0, True
    run.wall_s = record.get("wall_s") if isinstance(record.get("wall_s"), (int, float)) else None
    return True


# A cluster that lost the race for its DDS ports: between the launcher's check that a domain's ports
# are free and the bind, a cluster started at the same moment (this sweep's next run, or anyone's)
# took them. Nothing of the run's own is wrong, so it is started again, at most PORT_CLASH_ATTEMPTS times.
PORT_CLASH = re.compile(r"failed to create unicast sockets|dds_create_domain \d+ failed")
PORT_CLASH_ATTEMPTS = 3


def port_clash(run):
    """Whether a failed run's log, or its roles' logs, show it lost its DDS ports to another cluster."""
    logs = [run.log] + sorted((run.run_dir / "logs").glob("*.log"))
    for path in logs:
        try:
            if path.stat().st_size < (1 << 22) and PORT_CLASH.search(path.read_text(encoding="utf-8", errors="replace")):
                return True
        except OSError:
            pass
    return False


def start_spec_run(run, again=False):
    """Starts a run (`again`: after it lost its DDS ports), its output appended to its log; its
    record is removed until it finishes again."""
    (run.run_dir / RECORD).unlink(missing_ok=True)  # never complete until it finishes again
    run.attempts = run.attempts + 1 if again else 1
    run.log_file = open(run.log, "a" if again else "w", encoding="utf-8")
    if again:
        run.log_file.write(f"sweep: the run lost its DDS ports to another cluster starting at the same time; "
                           f"attempt {run.attempts} of {PORT_CLASH_ATTEMPTS}\n")
    run.log_file.write("$ " + shlex.join(run.command) + "\n")
    run.log_file.flush()
    run.started = time.monotonic()
    run.process = subprocess.Popen(run.command, stdout=run.log_file, stderr=subprocess.STDOUT,
                                   stdin=subprocess.DEVNULL)


def finish_spec_run(run, scenario_sha, metrics):
    """Records how a run that ended went: its status and metrics, and RECORD in its directory
    (written whole, then renamed) for the next invocation to reuse."""
    run.log_file.close()
    run.wall_s = time.monotonic() - run.started
    run.exit_code = run.process.returncode
    run.status = "failed"
    record = {"command": run.command, "scenario_sha256": scenario_sha, "exit": run.exit_code,
              "wall_s": round(run.wall_s, 3), "finished_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())}
    if run.exit_code == 0:
        try:
            record["metrics_sha256"] = sha256_of(run.run_dir / "metrics.json")
            run.metrics = metrics_of(run.run_dir / "metrics.json", metrics)
            run.status = "ok"
        except (OSError, ValueError) as error:
            record["exit"] = None
            with open(run.log, "a", encoding="utf-8") as log:
                log.write(f"sweep: the run exited 0 but is not counted: {error}\n")
    record["status"] = run.status
    if run.run_dir.is_dir():
        temporary = run.run_dir / (RECORD + ".tmp")
        temporary.write_text(json.dumps(record, indent=2) + "\n", encoding="utf-8")
        os.replace(temporary, run.run_dir / RECORD)


def _report_finished(run, done, total, failed, began):
    """The progress line of a run that finished: its outcome, the failures so far and an ETA."""
    if run.status == "ok":
        outcome = f"ok, {run.wall_s:.1f} s"
    else:
        outcome = f"FAILED (exit {run.exit_code}) after {run.wall_s:.1f} s; see {run.log}"
    left = total - done
    elapsed = time.monotonic() - began
    tail = f"ETA {duration(elapsed / done * left)}" if left else f"all done in {duration(elapsed)}"
    print(f"[{done}/{total}] {run.label} ... {outcome} | {failed} failed | {tail}", file=sys.stderr, flush=True)


def _stop_running(running, signum, handlers):
    """Stops only the runs this sweep started, each by its own PID: wsntrack stops its role
    processes on SIGTERM (SIGKILL after 20 s). Further signals wait until they have stopped."""
    for s in handlers:
        signal.signal(s, signal.SIG_IGN)
    print(f"sweep.py: {signal.Signals(signum).name}: stopping {plural(len(running), 'running run')}",
          file=sys.stderr, flush=True)
    for run in running:
        if run.process.poll() is None:
            run.process.terminate()
    deadline = time.monotonic() + 20
    for run in running:
        try:
            run.process.wait(timeout=max(0.1, deadline - time.monotonic()))
        except subprocess.TimeoutExpired:
            run.process.kill()
            run.process.wait()
        run.log_file.close()
        run.status, run.exit_code = "interrupted", run.process.returncode


def run_spec_runs(runs, jobs, scenario_sha, metrics):
    """Runs up to `jobs` clusters at a time. Returns the signal number that stopped it, or None."""
    stop = {"signal": None}

    def on_signal(signum, frame):
        stop["signal"] = signum

    previous = {s: signal.signal(s, on_signal) for s in (signal.SIGINT, signal.SIGTERM)}
    pending = list(runs)
    running = []
    done = failed = 0
    began = time.monotonic()
    try:
        while (pending or running) and not stop["signal"]:
            while pending and len(running) < jobs and not stop["signal"]:
                run = pending.pop(0)
                start_spec_run(run)
                running.append(run)
            still = []
            for run in running:
                if run.process.poll() is None:
                    still.append(run)
                    continue
                if run.process.returncode != 0 and run.attempts < PORT_CLASH_ATTEMPTS and port_clash(run):
                    run.log_file.close()
                    print(f"[{done}/{len(runs)}] {run.label}: lost its DDS ports to another cluster starting at the "
                          "same time; starting it again", file=sys.stderr, flush=True)
                    start_spec_run(run, again=True)
                    still.append(run)
                    continue
                finish_spec_run(run, scenario_sha, metrics)
                done += 1
                failed += run.status != "ok"
                _report_finished(run, done, len(runs), failed, began)
            running = still
            if running:
                time.sleep(0.05)
        if stop["signal"]:
            _stop_running(running, stop["signal"], previous)
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)
    return stop["signal"]
