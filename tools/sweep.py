#!/usr/bin/python3
"""Parameter sweeps over wsntrack clusters, as `wsntrack sweep` runs them: one `wsntrack run` per
(grid point, engine, seed), in parallel and resumably, with results.csv, summary.csv (mean, sd,
95 % CI), table.md and plots/; with --scheduler ADDRESS, on a Dask cluster (docs/DASK.md).

  sweep.py SPEC.yaml [--out DIR] [-j N] [--wsntrack PATH]          a sweep spec (sweeps/*.yaml)
  sweep.py --scenario FILE [--set-grid KEY=V1,V2,...] ...          the same sweep given by flags

A thin entry point over the package (wsntrack.sweep). It reads YAML with PyYAML, draws with
matplotlib and takes Student's t from SciPy (Debian's python3-yaml, python3-matplotlib and
python3-scipy, which /usr/bin/python3 has), and Dask's distributed with --scheduler
(python3-distributed); it imports them only when it is used.
"""

import sys
from pathlib import Path

# The package: python/ beside tools/ in the source and build trees; installed, where python-path
# beside this file says (cmake/WsnInstall.cmake).
_HERE = Path(__file__).resolve().parent
_INSTALLED = _HERE / "python-path"
sys.path.insert(0, str(_HERE / _INSTALLED.read_text().strip() if _INSTALLED.is_file() else _HERE.parent / "python"))
from wsntrack.sweep import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
