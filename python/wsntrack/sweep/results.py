"""A finished sweep directory read back for analysis: its description (sweep.json), one row per run
(results.csv) and one per grid point and engine (summary.csv), as numpy record arrays and, when
pandas is installed, DataFrames. The columns are found by name, so a sweep of any grid and metrics
reads; every problem is an InputError with FILE[:LINE]: what was expected.

    from wsntrack.sweep.results import load_sweep
    sweep = load_sweep("runs/fig7")
    sweep.grid                               # {"network.pte": ["0", "0.1", ...]}
    rows = sweep.summary[sweep.summary.engine == "mcmcda"]
    rows["network.pte"], rows.eps_k_mean, rows.eps_k_ci95_low
"""

import math
from pathlib import Path

from ..rundir import InputError, ToolMissing, read_header, read_json, read_table


def _column_type(name, grid_keys):
    """How a column of results.csv or summary.csv reads: grid values and words as text, counts whole,
    everything else a number (empty: NaN)."""
    if name in grid_keys or name in ("engine", "status", "run_dir", "log", "command"):
        return str
    if name in ("seed", "runs", "ok", "failed", "reused") or name.endswith("_n"):
        return "whole"
    return "number"


def _records(path, grid_keys):
    """Every column of a sweep CSV as a numpy record array (columns by name, text as str, whole
    numbers as int with -1 for empty, numbers as float with NaN for empty)."""
    import numpy as np
    header = [name for name in read_header(path) if name]
    rows = read_table(path, [(name, str) for name in header])[0]
    fields, columns = [], []
    for i, name in enumerate(header):
        kind = _column_type(name, grid_keys)
        cells = [row[i] for row in rows]
        try:
            if kind == "whole":
                values, dtype = [int(c) if c else -1 for c in cells], "i8"
            elif kind == "number":
                values, dtype = [float(c) if c else math.nan for c in cells], "f8"
            else:
                values, dtype = cells, f"U{max([1] + [len(c) for c in cells])}"
        except ValueError:
            bad = next(j for j, c in enumerate(cells) if c and not _is_number(c))
            raise InputError(f"{path}:{bad + 2}: column '{name}' must be a number, got '{cells[bad]}'") from None
        fields.append((name, dtype))
        columns.append(values)
    array = np.zeros(len(rows), dtype=fields)
    for (name, _), values in zip(fields, columns):
        array[name] = values
    return np.rec.array(array)


def _is_number(text):
    try:
        float(text)
        return True
    except ValueError:
        return False


class Sweep:
    """One sweep directory, loaded. Attributes:

    path         the sweep directory (a Path)
    description  sweep.json as a dict: scenario, grid, engines, seeds, set, metrics, ...
    grid         {key: [values as written]} of the swept keys, in order
    engines      the engines, seeds the seeds, metrics the metrics tabulated
    results      record array of results.csv: one row per run (engine, grid values, seed, status,
                 exit, each metric, wall_s, run_dir, log, command)
    summary      record array of summary.csv (None for a sweep of an older wsntrack without one): one row
                 per grid point and engine, each metric's _n, _mean, _sd, _ci95_low, _ci95_high
    """

    def __init__(self, path):
        self.path = Path(path)
        if not (self.path / "sweep.json").is_file():
            raise InputError(f"{self.path}: not a sweep directory (no sweep.json)")
        self.description = read_json(self.path / "sweep.json")
        if not isinstance(self.description, dict) or not isinstance(self.description.get("grid"), dict):
            raise InputError(f"{self.path / 'sweep.json'}: expected an object with a 'grid' mapping")
        self.grid = self.description["grid"]
        self.engines = self.description.get("engines")
        self.seeds = self.description.get("seeds")
        self.metrics = self.description.get("metrics")
        self.results = _records(self.path / "results.csv", set(self.grid))
        summary = self.path / "summary.csv"
        self.summary = _records(summary, set(self.grid)) if summary.is_file() else None

    def frame(self, name="summary"):
        """results or summary as a pandas DataFrame; ToolMissing without pandas."""
        if name not in ("results", "summary"):
            raise ValueError(f"frame: expected results or summary, got '{name}'")
        try:
            import pandas
        except ImportError:
            raise ToolMissing("Sweep.frame needs pandas (Debian: apt-get install python3-pandas)") from None
        records = getattr(self, name)
        return None if records is None else pandas.DataFrame({n: records[n] for n in records.dtype.names})

    def __repr__(self):
        return (f"<wsntrack sweep {str(self.path)!r}: grid {', '.join(self.grid)}, "
                f"{len(self.results)} runs, engines {', '.join(self.engines or [])}>")


def load_sweep(path):
    """Loads the sweep directory `path` (see :class:`Sweep`); InputError for a missing or malformed file."""
    return Sweep(path)


def _number_or_none(value):
    return None if value is None or (isinstance(value, float) and math.isnan(value)) else float(value)


def redraw_plots(path, out=None, plot_format="png", x=None):
    """Draws the plots of the finished sweep in `path` again, from its sweep.json and summary.csv
    (nothing is run): into `out` (default DIR/plots, where the earlier plots of that format are
    replaced; in another directory only files of the same names are overwritten), in `plot_format`
    (png, svg or pdf), against the metric `x` when given: one the sweep tabulated (a 1-D grid's;
    `wsntrack sweep --x` measures a new one from the runs). Returns the files written; ValueError for
    a format or x that cannot be drawn."""
    from .plots import PLOT_FORMATS, draw_plots
    from .spec import Spec
    sweep = load_sweep(path)
    if sweep.summary is None:
        raise InputError(f"{sweep.path}: no summary.csv to draw from")
    if plot_format not in PLOT_FORMATS:
        raise ValueError(f"plot_format: expected one of {', '.join(PLOT_FORMATS)}, got '{plot_format}'")
    d = sweep.description
    spec = Spec(Path(d["spec"]) if d.get("spec") else None)
    spec.scenario = Path(d["scenario"])
    spec.grid = [(key, values, None, [None] * len(values)) for key, values in sweep.grid.items()]
    spec.engines, spec.seeds, spec.metrics = list(sweep.engines), list(sweep.seeds), list(sweep.metrics)
    spec.title, spec.notes = d.get("title", ""), d.get("notes", "")
    spec.references = d.get("reference", [])
    spec.fixed = list(d.get("set", {}).items())
    spec.x = x if x is not None else d.get("x")
    if spec.x is not None and spec.x not in spec.metrics:
        raise ValueError(f"x: the sweep did not tabulate '{spec.x}' (it has {', '.join(spec.metrics)}); "
                         f"`wsntrack sweep SPEC --out {sweep.path} --x {spec.x}` reads it from the runs")
    if spec.x is not None and len(spec.grid) != 1:
        raise ValueError(f"x: a measured x axis needs a grid of one key; this sweep has {len(spec.grid)}")
    keys = list(sweep.grid)
    points, cells = [], {}
    for row in sweep.summary:
        point = tuple((key, str(row[key])) for key in keys)
        if list(point) not in points:
            points.append(list(point))
        cells[(point, str(row.engine))] = {
            "runs": int(row.runs), "ok": int(row.ok), "failed": int(row.failed),
            **{m: (int(row[f"{m}_n"]),) + tuple(_number_or_none(row[f"{m}_{s}"]) for s in ("mean", "sd", "ci95_low",
                                                                                                "ci95_high"))
               for m in spec.metrics}}
    fixed_text = " ".join(f"{k}={v}" for k, v in spec.fixed)
    return draw_plots(Path(out) if out else sweep.path / "plots", spec, points, cells, fixed_text, plot_format,
                      own_directory=out is None)
