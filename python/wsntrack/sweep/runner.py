"""Running a spec sweep: its combinations checked with `wsntrack validate`, each run a task (task.py)
given to an executor (executors.py: -j at a time on this machine, or a Dask cluster), each finished run
recorded in its directory so that the same command again reuses it, progress with an ETA as the runs
come back, and SIGINT or SIGTERM stopping only the runs this sweep started."""

import itertools
import json
import shlex
import signal
import sys
import time

from .common import PROG, UsageError, duration, engine_sets, plural, scenario_engine, validate
from .executors import outcome
from .spec import SpecError
from .task import RECORD, STOP_GRACE_S, metrics_of, sha256_of


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
                where = f"{spec.path}:{line}" if spec.path else f"--set-grid {key}"
                warnings.append(f"{where}: warning: {key}={value} is rejected by wsntrack validate, so "
                                f"its runs will fail: {error}")
    return warnings


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


def spec_task(run, scenario_sha, metrics):
    """The task of a run (task.run_task): plain values, so that it crosses a Dask cluster as it is."""
    return {"name": run.name, "command": run.command, "run_dir": str(run.run_dir), "log": str(run.log),
            "scenario_sha256": scenario_sha, "metrics": list(metrics)}


def _take(run, result):
    """Copies a task's result onto its run."""
    run.status, run.exit_code, run.wall_s = result["status"], result["exit"], result["wall_s"]
    run.attempts = result["attempts"]
    run.reason = result.get("reason")
    if run.status == "ok":
        run.metrics = result["metrics"]


def _report_finished(run, done, total, failed, began):
    """The progress line of a run that finished: its outcome, the failures so far and an ETA."""
    if run.attempts > 1:
        print(f"[{done}/{total}] {run.label}: lost its DDS ports to another cluster starting at the same time; "
              f"started it again ({run.attempts} attempts)", file=sys.stderr, flush=True)
    if run.status == "ok":
        outcome_text = f"ok, {run.wall_s:.1f} s"
    elif run.reason:
        outcome_text = f"FAILED: {run.reason}"
    else:
        outcome_text = f"FAILED (exit {run.exit_code}) after {run.wall_s or 0:.1f} s; see {run.log}"
    left = total - done
    elapsed = time.monotonic() - began
    tail = f"ETA {duration(elapsed / done * left)}" if left else f"all done in {duration(elapsed)}"
    print(f"[{done}/{total}] {run.label} ... {outcome_text} | {failed} failed | {tail}", file=sys.stderr, flush=True)


def _stop_running(futures, executor, signum, handlers):
    """Stops only the runs this sweep started: the executor's stop event makes each running task send
    its wsntrack SIGTERM by its PID (SIGKILL after STOP_GRACE_S) and the others start nothing. Further
    signals are ignored until they have stopped."""
    for s in handlers:
        signal.signal(s, signal.SIG_IGN)
    print(f"{PROG}: {signal.Signals(signum).name}: stopping {plural(len(futures), 'unfinished run')}: those in "
          "progress are sent SIGTERM, the others are not started", file=sys.stderr, flush=True)
    executor.stop()
    deadline = time.monotonic() + STOP_GRACE_S + 10
    while any(not f.done() for f in futures) and time.monotonic() < deadline:
        time.sleep(0.05)
    for future, run in futures.items():
        if future.done():
            _take(run, outcome(future))
        else:
            run.status = "interrupted"  # on a worker that has not answered: the next invocation runs it again


def run_spec_runs(runs, executor, scenario_sha, metrics):
    """Runs every run through `executor`, reporting each as it comes back. Returns the signal number
    that stopped it, or None."""
    stop = {"signal": None}

    def on_signal(signum, frame):
        stop["signal"] = signum

    previous = {s: signal.signal(s, on_signal) for s in (signal.SIGINT, signal.SIGTERM)}
    began = time.monotonic()
    done = failed = 0
    try:
        futures = {executor.submit(spec_task(run, scenario_sha, metrics)): run for run in runs}
        while futures and not stop["signal"]:
            finished = [future for future in futures if future.done()]
            for future in finished:
                run = futures.pop(future)
                _take(run, outcome(future))
                done += 1
                failed += run.status != "ok"
                _report_finished(run, done, len(runs), failed, began)
            if not finished:
                time.sleep(0.05)
        if stop["signal"]:
            _stop_running(futures, executor, stop["signal"], previous)
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)
    return stop["signal"]
