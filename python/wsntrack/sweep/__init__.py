"""Parameter sweeps over wsntrack clusters (`wsntrack sweep`, tools/sweep.py): one `wsntrack run`
per (grid point, engine, seed), every run in results.csv, summary.csv with 95 % intervals, a
markdown table and plots.

  spec_main   the command: a spec file (`wsntrack sweep SPEC.yaml`) or flags (`--scenario FILE
              --set-grid ...`, from_flags: built into the same spec), then the runs and outputs
  spec        reading a spec file; runner (running, resuming), task (one run, wherever it goes),
              executors (this machine's threads, or a Dask cluster with --scheduler; on_worker: what
              a Dask worker runs), summary (results.csv, summary.csv with Student's t intervals,
              table.md), plots
  metrics     what a run's metric is read from (the catalogue); common: run names and commands
  results     a finished sweep read back for analysis (load_sweep)
"""

import os

from .. import catalogue
from .common import default_wsntrack
from .spec_main import spec_main


def _named_wsntrack(argv):
    """The executable of --wsntrack in `argv`, else the default (common.default_wsntrack)."""
    for i, word in enumerate(argv):
        if word == "--wsntrack" and i + 1 < len(argv):
            return argv[i + 1]
        if word.startswith("--wsntrack="):
            return word[len("--wsntrack="):]
    return str(default_wsntrack())


def main(argv):
    """`wsntrack sweep` ARGV; returns the exit status. The sweep reads the metrics, labels and columns
    of the catalogue of the wsntrack it runs, when it can be run (else the default of
    wsntrack.catalogue)."""
    wsntrack = _named_wsntrack(argv)
    if os.access(wsntrack, os.X_OK) and not os.path.isdir(wsntrack):
        catalogue.use(os.path.realpath(wsntrack))
    return spec_main(argv)
