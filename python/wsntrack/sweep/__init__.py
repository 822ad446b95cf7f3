"""Parameter sweeps over wsntrack clusters (tools/sweep.py): one `wsntrack run` per (grid point,
engine, seed), every run in results.csv and a markdown table of the means over the seeds.

  spec_main  the spec form, `sweep.py SPEC.yaml`: spec (reading), runner (running, resuming),
             task (one run, wherever it goes), executors (this machine's threads, or a Dask cluster
             with --scheduler; on_worker: what a Dask worker runs), summary (results.csv,
             summary.csv with Student's t intervals, table.md), plots
  flags      the flag form, `sweep.py --scenario FILE ...`: standard library only
  metrics    what a run's metric is read from; common: what both forms share
"""

from .flags import main as flag_main
from .spec import spec_form
from .spec_main import spec_main


def main(argv):
    """sweep.py ARGV: the spec form when a spec file is named and --scenario is not, else the flag
    form; returns the exit status."""
    if spec_form(argv):
        return spec_main(argv)
    return flag_main(argv)
