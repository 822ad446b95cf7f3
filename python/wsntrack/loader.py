"""A wsntrack run directory loaded into numpy record arrays for your own analysis (what
tools/wsntrack_run.py exports; its docstring has the example). The files are read by
wsntrack.rundir, so a missing or malformed file is a RunError with ``FILE:LINE: what was expected``,
and a python without PyYAML raises ToolMissing. Stone Soup conversions: wsntrack.stonesoup."""

import sys
from pathlib import Path

import numpy as np

from . import rundir
from .stonesoup import STONESOUP_ORDER, StoneSoupConversions

__all__ = ["load_run", "Run", "RunError", "ToolMissing", "track_label", "covariance_matrix", "parse_yaml",
           "TRUTH_DTYPE", "OBSERVATION_DTYPE", "TRACK_DTYPE", "SUPERNODE_TRACK_DTYPE", "STONESOUP_ORDER"]

#: A missing or malformed file of the run directory; ``str(error)`` is ``FILE[:LINE]: what was expected``.
RunError = rundir.InputError

#: PyYAML (python3-yaml) is not installed; an ImportError whose message says what to install.
ToolMissing = rundir.ToolMissing

#: ``parse_yaml(text, path)``: the mapping of a YAML document as ``yaml.safe_load`` reads it (how
#: scenario.yaml is read); raises :class:`RunError` with FILE:LINE for malformed YAML.
parse_yaml = rundir.parse_yaml
#: The name of ``parse_yaml`` from when scenario.yaml was read by a hand-written YAML subset
#: reader; kept so that analysis scripts that import it still run.
parse_yaml_subset = parse_yaml

#: ``track_label(id)``: the readable id of a numeric track id, as common/track_id.hpp writes it:
#: ``S:N`` (ids ``(S + 1) << 48 | N``), ``S:tTsK`` when N is a birth id ``J << 44 | T << 24 | K``
#: (tick T, sensor K) with ``.J`` appended when J is not 0, and ``gN`` for ids below ``1 << 48``,
#: minted by the aggregator.
track_label = rundir.track_label

#: ``class`` is the target's class (``unknown`` in an older run's file, which has no such column).
TRUTH_DTYPE = np.dtype([("tick", "i4"), ("target", "i8"), ("x", "f8"), ("y", "f8"), ("vx", "f8"), ("vy", "f8"),
                        ("class", "U16")])

#: ``tick_delivered`` and ``delay`` are -1 for a report that was not delivered (fate ``lost``,
#: ``unreachable``, ``after_end`` or ``dead_supernode``); ``hops`` is -1 when no path led to a supernode; ``target``
#: is -1 for a false alarm; ``level`` is the report's power level (-1 in an older run's file).
OBSERVATION_DTYPE = np.dtype([
    ("tick_generated", "i4"), ("tick_delivered", "i4"), ("sensor", "i8"), ("supernode", "i4"), ("hops", "i4"),
    ("delay", "i4"), ("x", "f8"), ("y", "f8"), ("target", "i8"), ("fate", "U14"), ("level", "i4")])

_TRACK_FIELDS = [("track", "u8"), ("label", "U24"), ("x", "f8"), ("y", "f8"), ("vx", "f8"), ("vy", "f8"),
                 ("covariance", "f8", (4, 4)), ("stop_probability", "f8"), ("class", "U16"),
                 ("class_probability", "f8")]
#: ``covariance`` is the 4 x 4 covariance over (x, y, vx, vy), all zero when unknown (and in runs
#: written before tracks.csv had covariance columns); ``stop_probability`` the probability the
#: track gives its target standing still (NaN from an engine without a stop model); ``class`` the
#: class it declares ("" without class evidence) and ``class_probability`` its probability (NaN
#: without a class).
TRACK_DTYPE = np.dtype([("tick", "i4")] + _TRACK_FIELDS)
SUPERNODE_TRACK_DTYPE = np.dtype([("tick", "i4"), ("supernode", "i4")] + _TRACK_FIELDS)


def covariance_matrix(values):
    """The symmetric 4 x 4 matrix over (x, y, vx, vy) of the ten p_* columns of tracks.csv
    (p_xx, p_xy, p_xvx, p_xvy, p_yy, p_yvx, p_yvy, p_vxvx, p_vxvy, p_vyvy): an array of
    shape (..., 10) gives shape (..., 4, 4).

    >>> covariance_matrix([1, 2, 3, 4, 5, 6, 7, 8, 9, 10])[1]
    array([2., 5., 6., 7.])
    """
    values = np.asarray(values, dtype=float)
    matrix = np.zeros(values.shape[:-1] + (4, 4))
    for k, (i, j) in enumerate(rundir.COVARIANCE_INDEX):
        matrix[..., i, j] = matrix[..., j, i] = values[..., k]
    return matrix


def _records(rows, dtype):
    return np.rec.array(np.array(rows, dtype=dtype) if rows else np.zeros(0, dtype=dtype))


def _tracks(rows, supernode):
    """Record array of read_tracks rows: (tick, [supernode,] track, x, y, vx, vy, label, p...)."""
    key = 3 if supernode else 2
    dtype = SUPERNODE_TRACK_DTYPE if supernode else TRACK_DTYPE
    array = np.zeros(len(rows), dtype=dtype)
    if rows:
        columns = list(zip(*rows))
        array["tick"] = columns[0]
        if supernode:
            array["supernode"] = columns[1]
        array["track"] = np.array(columns[key - 1], dtype=np.uint64)
        for offset, name in enumerate(("x", "y", "vx", "vy")):
            array[name] = columns[key + offset]
        array["label"] = columns[key + 4]
        array["covariance"] = covariance_matrix(np.array(columns[key + 5:key + 15], dtype=float).T)
        array["stop_probability"] = [np.nan if v is None else v for v in columns[key + 15]]
        array["class"] = columns[key + 16]
        array["class_probability"] = [np.nan if v is None else v for v in columns[key + 17]]
    return np.rec.array(array)


def _optional_json(path):
    return rundir.read_json(path) if path.is_file() else None


def _metrics_per_tick(path):
    """Every column of metrics_per_tick.csv as a record array: tick, truth_targets and tracks whole
    numbers, the others floats."""
    columns, rows = rundir.read_metrics_per_tick(path)
    return _records(rows, np.dtype([(name, "i4" if kind is int else "f8") for name, kind in columns]))


def _observations(path):
    """observations.csv as a record array, -1 for the tick_delivered and delay of an undelivered report."""
    rows = [(r[0], -1 if r[1] is None else r[1]) + r[2:5] + (-1 if r[5] is None else r[5],) + r[6:10] +
            (-1 if r[10] is None else r[10],) for r in rundir.read_observations(path)]
    return _records(rows, OBSERVATION_DTYPE)


class Run(StoneSoupConversions):
    """One run directory, loaded. Attributes (None when the file is absent, as in an unfinished
    run or one written by an older wsntrack):

    path              the run directory (a Path)
    scenario          scenario.yaml as a dict: the run's scenario with every default filled in
    ticks             T, the number of ticks (ticks are numbered 1 .. T)
    supernodes        (m, 2) array: the supernodes' x, y; index j is supernode j
    sensors           (n, 2) array: every sensor's x, y, row n = sensor n (sensors.csv, or the grid
                      of scenario.yaml; None for a random layout without sensors.csv)
    truth             record array TRUTH_DTYPE, truth.csv: per tick, every target's state
    observations      record array OBSERVATION_DTYPE, observations.csv (None when absent): one
                      row per report with its generation and delivery ticks and fate
    tracks            record array TRACK_DTYPE, tracks.csv: the aggregator's global tracks per
                      tick, with label and 4 x 4 covariance
    supernode_tracks  record array SUPERNODE_TRACK_DTYPE, tracks_supernode.csv: every
                      supernode's confirmed tracks per tick
    settled_tracks    record array TRACK_DTYPE, tracks_settled.csv: the settled (fixed-lag,
                      smoothed) estimate of each tick once it left the supernodes' windows
    has_labels, has_covariance   whether tracks.csv has the label / covariance columns (else
                      labels are made from the ids and covariances are zero)
    metrics_per_tick  record array of metrics_per_tick.csv: tick, truth_targets (K*), tracks (K),
                      ospa, gospa, gospa_localisation, gospa_missed, gospa_false
    metrics           metrics.json as a dict (headline eps_k, eps_x, ospa; "metrics": ...)
    network           network.json as a dict (ranges, counts and ratios of the network model)
    info              run.json as a dict (run_id, domain, ticks, processes, status, ...)
    incomplete        None for a complete run; else why not ("incomplete run (status failed: ...)"),
                      loaded only with allow_incomplete=True
    """

    def __init__(self, path, allow_incomplete=False):
        self.path = Path(path)
        if not self.path.is_dir():
            raise RunError(f"{self.path}: not a directory")
        #: None for a complete run, else why it is not (only with allow_incomplete)
        self.incomplete = rundir.incomplete_reason(self.path)
        if self.incomplete and not allow_incomplete:
            raise RunError(f"{self.path}: {self.incomplete}")
        p = self.path
        summary = rundir.read_scenario(p)  # checks what the arrays below depend on, with FILE:LINE
        self.scenario = summary["document"]
        self.ticks = summary["ticks"]
        self.supernodes = np.array(summary["supernodes"], dtype=float).reshape(-1, 2)
        self.sensors = self._sensors(summary)

        self.truth = _records(rundir.read_truth(p / "truth.csv", with_class=True)[0], TRUTH_DTYPE)
        rows, self.has_labels, self.has_covariance = rundir.read_tracks(p / "tracks.csv")
        self.tracks = _tracks(rows, supernode=False)
        path = p / "tracks_supernode.csv"
        self.supernode_tracks = _tracks(rundir.read_tracks(path, supernode=True)[0], True) if path.is_file() \
            else None
        path = p / "tracks_settled.csv"
        self.settled_tracks = _tracks(rundir.read_tracks(path)[0], False) if path.is_file() else None
        path = p / "observations.csv"
        self.observations = _observations(path) if path.is_file() else None
        path = p / "metrics_per_tick.csv"
        self.metrics_per_tick = _metrics_per_tick(path) if path.is_file() else None
        self.metrics = _optional_json(p / "metrics.json")
        self.network = _optional_json(p / "network.json")
        self.info = _optional_json(p / "run.json")

    FRAMES = ("truth", "observations", "tracks", "supernode_tracks", "settled_tracks", "metrics_per_tick")

    def frame(self, name):
        """One of FRAMES as a pandas DataFrame (None when the file is absent): the record array's
        columns, the 4 x 4 covariance as its ten p_* columns of tracks.csv. ToolMissing without
        pandas (Debian: apt-get install python3-pandas)."""
        if name not in self.FRAMES:
            raise ValueError(f"frame: expected one of {', '.join(self.FRAMES)}, got '{name}'")
        try:
            import pandas
        except ImportError:
            raise ToolMissing("Run.frame needs pandas (Debian: apt-get install python3-pandas)") from None
        records = getattr(self, name)
        if records is None:
            return None
        columns = {}
        for field in records.dtype.names:
            if field == "covariance":
                for column, (i, j) in zip(rundir.COVARIANCE_COLUMNS, rundir.COVARIANCE_INDEX):
                    columns[column] = records.covariance[:, i, j]
            else:
                columns[field] = records[field]
        return pandas.DataFrame(columns)

    def __repr__(self):
        return (f"<wsntrack run {str(self.path)!r}: {self.scenario.get('name', '?')}, {self.ticks} ticks, "
                f"{len(np.unique(self.truth.target))} targets, {len(np.unique(self.tracks.track))} tracks>")

    def _sensors(self, summary):
        path = self.path / "sensors.csv"
        if path.is_file():
            rows = rundir.read_csv(path, ["sensor", "x", "y"], [int, float, float])
            return np.array([(r[1], r[2]) for r in rows], dtype=float).reshape(-1, 2)
        if summary["layout"] != "grid":
            return None  # a random layout without sensors.csv: the positions are not recorded
        return np.column_stack(rundir.grid_sensors(summary)).astype(float).reshape(-1, 2)

    # -- selections -------------------------------------------------------------------------

    def truth_at(self, tick):
        """The targets' states at `tick` (record array TRUTH_DTYPE)."""
        return self.truth[self.truth.tick == tick]

    def tracks_at(self, tick, supernode=None):
        """The global tracks at `tick`; with `supernode` (an index), that supernode's tracks."""
        if supernode is None:
            return self.tracks[self.tracks.tick == tick]
        return self.supernode_tracks[(self.supernode_tracks.tick == tick)
                                     & (self.supernode_tracks.supernode == supernode)]

    def delivered_at(self, tick):
        """The reports a supernode received at `tick`: generated then or earlier (late ones have
        tick_generated < tick), false alarms included (target == -1)."""
        return self.observations[self.observations.tick_delivered == tick]

    @staticmethod
    def by_id(records, field):
        """``{id: rows}`` of a record array grouped by `field` (e.g. ``"target"``, ``"label"``),
        rows in tick order.

        >>> paths = Run.by_id(run.truth, "target")          # doctest: +SKIP
        >>> paths[0].x, paths[0].y                          # doctest: +SKIP
        """
        order = np.lexsort((records.tick, records[field]))
        records = records[order]
        keys, starts = np.unique(records[field], return_index=True)
        bounds = list(starts[1:]) + [len(records)]
        return {key.item(): records[start:end] for key, start, end in zip(keys, starts, bounds)}

    def states(self, records):
        """(n, 4) array of the (x, y, vx, vy) of a truth or tracks record array."""
        return np.column_stack([records.x, records.y, records.vx, records.vy])


def load_run(path, allow_incomplete=False):
    """Loads the run directory `path` (see :class:`Run` for what it holds). Raises RunError
    (``FILE[:LINE]: what was expected``) for a missing or malformed file, ToolMissing without
    PyYAML; scenario.yaml, truth.csv and tracks.csv must be there, the other files are None when
    absent. A run that is not complete (run.json's status is not "complete": failed, interrupted,
    still running, or no status at all) raises RunError "RUN_DIR: incomplete run (status failed:
    REASON)" unless `allow_incomplete`; then `run.incomplete` says why.

    >>> run = load_run("runs/demo")                                   # doctest: +SKIP
    >>> run.tracks_at(50)[["label", "x", "y"]]                        # doctest: +SKIP
    """
    return Run(path, allow_incomplete)


def main(argv):
    """wsntrack_run.py RUN_DIR: a one-screen summary, or the error and exit status 2 (3 for a
    missing tool, as plot_run.py). Returns the exit status."""
    if len(argv) != 1 or argv[0].startswith("-"):
        print("usage: wsntrack_run.py RUN_DIR   (loads a run directory and prints what it holds)", file=sys.stderr)
        return 1
    try:
        loaded = load_run(argv[0])
    except RunError as error:
        print(f"wsntrack_run.py: {error}", file=sys.stderr)
        return 2
    except ToolMissing as error:
        print(f"wsntrack_run.py: {error}", file=sys.stderr)
        return 3
    print(loaded)
    for name in ("truth", "observations", "tracks", "supernode_tracks", "metrics_per_tick"):
        value = getattr(loaded, name)
        print(f"  {name:17s} {'absent' if value is None else f'{len(value)} rows'}")
    print(f"  labels {'yes' if loaded.has_labels else 'made from ids'}, covariance "
          f"{'yes' if loaded.has_covariance else 'absent (zero)'}")
    return 0
