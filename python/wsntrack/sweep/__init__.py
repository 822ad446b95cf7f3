"""Parameter sweeps over wsntrack clusters (tools/sweep.py): one `wsntrack run` per (grid point,
engine, seed), every run in results.csv and a markdown table of the means over the seeds.

  spec_main  the spec form, `sweep.py SPEC.yaml`: spec (reading), runner (running, resuming),
             task (one run, wherever it goes), executors (this machine's threads, or a Dask cluster
             with --scheduler; on_worker: what a Dask worker runs), summary (results.csv,
             summary.csv with Student's t intervals, table.md), plots
  flags      the flag form, `sweep.py --scenario FILE ...`: standard library only
  metrics    what a run's metric is read from; common: what both forms share
"""

import os

from .. import catalogue
from .common import REPO
from .flags import main as flag_main
from .spec import spec_form
from .spec_main import spec_main


def _named_wsntrack(argv):
    """The executable of --wsntrack in `argv`, else the repository's build/bin/wsntrack."""
    for i, word in enumerate(argv):
        if word == "--wsntrack" and i + 1 < len(argv):
            return argv[i + 1]
        if word.startswith("--wsntrack="):
            return word[len("--wsntrack="):]
    return str(REPO / "build" / "bin" / "wsntrack")


def main(argv):
    """sweep.py ARGV: the spec form when a spec file is named and --scenario is not, else the flag
    form; returns the exit status. Both read the metrics, labels and columns of the catalogue of the
    wsntrack they run, when it can be run (else the default of wsntrack.catalogue)."""
    wsntrack = _named_wsntrack(argv)
    if os.access(wsntrack, os.X_OK) and not os.path.isdir(wsntrack):
        catalogue.use(os.path.realpath(wsntrack))
    if spec_form(argv):
        return spec_main(argv)
    return flag_main(argv)
