#!/usr/bin/python3
"""Loads a wsntrack run directory into numpy arrays for your own analysis, and into Stone Soup
objects when the `stonesoup` package is importable.

A thin entry point over the package (wsntrack.loader: python/wsntrack/ in the source tree,
build/python/wsntrack/ in the build tree, Debian's python path when installed), which it puts on
sys.path when imported; analysis code imports the package itself.

Needs numpy and PyYAML (Debian: python3-numpy and python3-yaml, which /usr/bin/python3 has): the
files are read by wsntrack.rundir, the one run-directory reader, scenario.yaml with PyYAML's safe
loader, so a missing or malformed file is reported as ``FILE:LINE: what was expected`` (a
:class:`RunError`). Without PyYAML, loading a run raises :class:`ToolMissing` (an ImportError)
saying what to install.

Example (from the repository root, after ``build/bin/wsntrack run scenarios/oh_quadrants.yaml
--ticks 20 --out /tmp/demo``)::

    import sys
    sys.path.insert(0, "build/python")   # the build tree's package; nothing once wsntrack is installed
    from wsntrack.loader import load_run

    run = load_run("/tmp/demo")
    run.ticks                            # 20: the run's T
    run.truth[run.truth.tick == 10]      # every target at tick 10: tick, target, x, y, vx, vy
    run.tracks.label                     # readable track ids: '0:1', '2:1', 'g7', ...
    run.tracks.covariance.shape          # (n, 4, 4), over (x, y, vx, vy)
    late = run.observations[run.observations.tick_delivered > run.observations.tick_generated]
    run.metrics_per_tick.ospa.mean()     # the mean OSPA, as metrics.json's metrics.ospa_mean
    run.metrics["metrics"]["eps_k"]      # metrics.json as a dict

Arrays are numpy record arrays: a column reads as ``run.truth.x`` or ``run.truth["x"]``, a row
selection with a boolean mask as above. Lengths are in the scenario's units, velocities per tick,
times in ticks.

When Stone Soup (``pip install stonesoup``) is importable, the run converts to its types; this
part follows Stone Soup's documented constructors but is untested against Stone Soup itself::

    truths = run.stonesoup_truths()           # {target: GroundTruthPath of GroundTruthState}
    tracks = run.stonesoup_tracks()           # {label: Track of GaussianState, with covariance}
    scans = run.stonesoup_detections(truths)  # [(time, {TrueDetection or Clutter})] per tick

Stone Soup states are ordered (x, vx, y, vy), its usual order; a tick is one second unless
``tick_seconds`` says otherwise.
"""

import sys
from pathlib import Path

# The package: python/ beside tools/ in the source and build trees; installed, where python-path
# beside this file says (cmake/WsnInstall.cmake).
_HERE = Path(__file__).resolve().parent
_INSTALLED = _HERE / "python-path"
sys.path.insert(0, str(_HERE / _INSTALLED.read_text().strip() if _INSTALLED.is_file() else _HERE.parent / "python"))
from wsntrack.loader import (OBSERVATION_DTYPE, STONESOUP_ORDER, SUPERNODE_TRACK_DTYPE, TRACK_DTYPE,  # noqa: E402
                             TRUTH_DTYPE, Run, RunError, ToolMissing, covariance_matrix, load_run, main,
                             parse_yaml, parse_yaml_subset, track_label)

__all__ = ["load_run", "Run", "RunError", "ToolMissing", "track_label", "covariance_matrix", "parse_yaml",
           "parse_yaml_subset", "TRUTH_DTYPE", "OBSERVATION_DTYPE", "TRACK_DTYPE", "SUPERNODE_TRACK_DTYPE", "STONESOUP_ORDER"]

if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
