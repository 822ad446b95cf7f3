"""The one reader of a wsntrack run directory (README.md, "Run directory"): `load_run(RUN_DIR)` gives
every file as numpy record arrays and DataFrames (wsntrack.loader); the per-file readers below serve
the plots, the
loader, the sweep and the ONERA table alike: scenario.yaml (PyYAML's safe loader, lines kept),
the CSV files by column name, the JSON files, whether the run is complete (run.json's status); a
missing or malformed file raises InputError with ``FILE[:LINE]: what was expected``. Standard library only, PyYAML aside (ToolMissing without it)."""

from . import files as _files, scenario as _scenario
from .files import (read_metrics_per_tick, read_metrics_summary, read_observations, read_per_tick, read_tracks,
                    read_truth, track_label)
from .status import incomplete_reason, require_complete, run_status
from .scenario import grid_sensors, grid_shape, parse_yaml, read_scenario
from .tables import (OPTIONAL_FLOAT, OPTIONAL_INT, InputError, ToolMissing, read_csv, read_header, read_json,
                     read_table, require)

__all__ = ["COVARIANCE_COLUMNS", "COVARIANCE_INDEX", "OBSERVATION_FATES", "PER_TICK_COUNTS", "TARGET_CLASSES",
           "TRACK_ID_SHIFT", "TRUTH_CLASSES", "read_metrics_per_tick", "read_metrics_summary", "read_observations",
           "read_per_tick", "read_tracks", "read_truth", "track_label", "incomplete_reason", "require_complete",
           "run_status", "SENSOR_TYPES", "grid_sensors", "grid_shape",
           "parse_yaml", "read_scenario", "OPTIONAL_FLOAT", "OPTIONAL_INT", "InputError", "ToolMissing", "read_csv",
           "read_header", "read_json", "read_table", "require"]


def __getattr__(name):
    """The facts read from wsntrack's catalogue (TARGET_CLASSES, SENSOR_TYPES, ...), when first used;
    load_run and Run, the whole run directory as numpy record arrays (wsntrack.loader, which needs
    numpy: imported only then)."""
    if name in ("load_run", "Run"):
        from .. import loader
        return getattr(loader, name)
    return getattr(_scenario if name == "SENSOR_TYPES" else _files, name)
