"""What a Dask worker runs for a sweep (executors.DaskExecutor). This module is sent to the workers by
value (cloudpickle), so a worker needs no copy of the package on its path: it imports wsntrack from
the sweep's own tree, which it sees at the same path, as it sees the wsntrack executable, the scenario
and the sweep directory (README.md, "Sweeps over a Dask cluster"). Standard library only here."""

import os
import sys


def missing_paths(paths):
    """Those of `paths` ([(path, "r" or "x")]) this worker cannot read, or execute."""
    return [path for path, mode in paths if not os.access(path, os.X_OK if mode == "x" else os.R_OK)]


def run_there(python_dir, task, stop_name):
    """The sweep's run_task(task) on this worker, stopped when the sweep sets the Dask event
    `stop_name` (polled once a second)."""
    if python_dir not in sys.path:
        sys.path.insert(0, python_dir)
    from distributed import Event, get_worker
    from wsntrack.sweep import task as task_module
    imported = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(task_module.__file__))))
    if os.path.realpath(imported) != os.path.realpath(python_dir):
        raise RuntimeError(f"this worker already runs the wsntrack package of {imported}, not the sweep's "
                           f"{python_dir}: start a fresh worker for this tree")
    return task_module.run_task(task, Event(stop_name), poll_s=1.0, worker=get_worker().address)
