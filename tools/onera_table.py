#!/usr/bin/python3
"""Table II of Pannetier et al. (FUSION 2014) beside our runs: per target RSE and TLR of algorithm 1
(with the road network) and algorithm 2 (without), with the classification and stop-mode scores
when the runs have them, as a Markdown table on stdout (and bar charts with --plot FILE).
`onera_table.py --help` says everything.

A thin entry point over the package beside it (wsntrack.onera_table: python/wsntrack/ in the
source tree, Debian's python path when installed). Standard library only but for --plot, which
needs matplotlib.
"""

import sys
from pathlib import Path

# The package: python/ beside tools/ in the source and build trees; installed, where python-path
# beside this file says (cmake/WsnInstall.cmake).
_HERE = Path(__file__).resolve().parent
_INSTALLED = _HERE / "python-path"
sys.path.insert(0, str(_HERE / _INSTALLED.read_text().strip() if _INSTALLED.is_file() else _HERE.parent / "python"))
from wsntrack.entry import run  # noqa: E402
from wsntrack.onera_table.cli import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(run(main, sys.argv[1:]))
