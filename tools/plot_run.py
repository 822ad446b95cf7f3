#!/usr/bin/python3
"""Plots of one wsntrack run directory: tracks against the truth on the sensor field, the number
of tracks K and of targets K* over time, and OSPA over time; with --animate, the replay animation.
`plot_run.py --help` says everything.

A thin entry point over the package beside it (wsntrack.plots: python/wsntrack/ in the source tree,
build/python/ in a build tree, share/wsntrack/python/ when installed). Needs Debian's
python3-matplotlib and python3-yaml (PyYAML, for the run's scenario.yaml), hence /usr/bin/python3
rather than whatever python3 is first on PATH.
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "python"))
from wsntrack.entry import run  # noqa: E402
from wsntrack.plots.cli import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(run(main, sys.argv[1:]))
