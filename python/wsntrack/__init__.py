"""wsntrack's analysis tools as one package: the run-directory reader and everything built on it.

  wsntrack.rundir       the one reader of a run directory (scenario.yaml, the CSV files, the JSON
                        files), with FILE:LINE messages; standard library only (PyYAML for
                        scenario.yaml)
  wsntrack.loader       a run directory as numpy record arrays (tools/wsntrack_run.py)
  wsntrack.stonesoup    the loaded run as Stone Soup types, when stonesoup is importable
  wsntrack.plots        the plots and the replay animation of a run (tools/plot_run.py)
  wsntrack.sweep        grids of `wsntrack run` and their tables, intervals and plots (tools/sweep.py)
  wsntrack.onera_table  Table II of Pannetier et al. beside our runs (tools/onera_table.py)
  wsntrack.plot         the figures for a script: run_plots, animation, sweep_plots (drawn again)
  wsntrack.catalogue    the facts of the C++ side (`wsntrack components --json`): metrics, columns,
                        classes, labels and units, read instead of restated

docs/PYTHON.md has the details. Installed, the package is in Debian's python path; from the build
tree, PYTHONPATH=build/python. The scripts in tools/ are thin entry points: each puts the package on
sys.path (../python in the source and build trees, where python-path beside it says when installed)
and calls into this package. Importing the package imports nothing else, so that each tool loads only what
it needs (the ONERA table runs on the standard library alone).
"""
