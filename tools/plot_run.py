#!/usr/bin/python3
"""Plots of one wsntrack run directory: tracks against the truth on the sensor field, the number
of tracks K and of targets K* over time, and OSPA over time; with --animate, the replay animation.
`plot_run.py --help` says everything.

A thin entry point over the package beside it (wsntrack.plots: python/wsntrack/ in the source tree,
build/python/ in a build tree, Debian's python path when installed). Needs Debian's
python3-matplotlib and python3-yaml (PyYAML, for the run's scenario.yaml), hence /usr/bin/python3
rather than whatever python3 is first on PATH.
"""

import sys
from pathlib import Path

# The package: python/ beside tools/ in the source and build trees; installed, where python-path
# beside this file says (cmake/WsnInstall.cmake).
_HERE = Path(__file__).resolve().parent
_INSTALLED = _HERE / "python-path"
sys.path.insert(0, str(_HERE / _INSTALLED.read_text().strip() if _INSTALLED.is_file() else _HERE.parent / "python"))
from wsntrack.entry import run  # noqa: E402
from wsntrack.plots.cli import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(run(main, sys.argv[1:]))
