#!/usr/bin/python3
"""Loads a wsntrack run directory into numpy arrays for your own analysis, and into Stone Soup
objects when the `stonesoup` package is importable.

Needs numpy and PyYAML (Debian: python3-numpy and python3-yaml, which /usr/bin/python3 has): the
files are read by tools/plot_run.py's readers, scenario.yaml with PyYAML's safe loader, so a missing
or malformed file is reported as ``FILE:LINE: what was expected`` (a :class:`RunError`). Without
PyYAML, loading a run raises :class:`ToolMissing` (an ImportError) saying what to install.

Example (from the repository root, after ``build/bin/wsntrack run scenarios/oh_quadrants.yaml
--ticks 20 --out /tmp/demo``)::

    import sys
    sys.path.insert(0, "tools")
    from wsntrack_run import load_run

    run = load_run("/tmp/demo")
    run.ticks                            # 20: the run's T
    run.truth[run.truth.tick == 10]      # every target at tick 10: tick, target, x, y, vx, vy
    run.tracks.label                     # readable track ids: '0:1', '2:1', 'g7', ...
    run.tracks.covariance.shape          # (n, 4, 4), over (x, y, vx, vy)
    late = run.observations[run.observations.tick_delivered > run.observations.tick_generated]
    run.metrics_per_tick.ospa.mean()     # the mean OSPA, as metrics.json's metrics.ospa_mean
    run.metrics["metrics"]["eps_k"]      # metrics.json as a dict

Arrays are numpy record arrays: a column reads as ``run.truth.x`` or ``run.truth["x"]``, a row
selection with a boolean mask as above. Lengths are in the scenario's units, velocities per tick,
times in ticks.

When Stone Soup (``pip install stonesoup``) is importable, the run converts to its types; this
part follows Stone Soup's documented constructors but is untested against Stone Soup itself::

    truths = run.stonesoup_truths()           # {target: GroundTruthPath of GroundTruthState}
    tracks = run.stonesoup_tracks()           # {label: Track of GaussianState, with covariance}
    scans = run.stonesoup_detections(truths)  # [(time, {TrueDetection or Clutter})] per tick

Stone Soup states are ordered (x, vx, y, vy), its usual order; a tick is one second unless
``tick_seconds`` says otherwise.
"""

import json
import math
import sys
from pathlib import Path

import numpy as np

try:
    import plot_run as _plot_run
except ImportError:
    # Imported by file path rather than with tools/ on sys.path: plot_run.py is beside this file.
    import importlib.util as _util
    _spec = _util.spec_from_file_location("plot_run", Path(__file__).resolve().with_name("plot_run.py"))
    _plot_run = _util.module_from_spec(_spec)
    _spec.loader.exec_module(_plot_run)

__all__ = ["load_run", "Run", "RunError", "ToolMissing", "track_label", "covariance_matrix", "parse_yaml",
           "TRUTH_DTYPE", "OBSERVATION_DTYPE", "TRACK_DTYPE", "SUPERNODE_TRACK_DTYPE", "STONESOUP_ORDER"]

#: A missing or malformed file of the run directory; ``str(error)`` is ``FILE[:LINE]: what was expected``.
RunError = _plot_run.InputError

#: PyYAML (python3-yaml) is not installed; an ImportError whose message says what to install.
ToolMissing = _plot_run.ToolMissing

#: ``parse_yaml(text, path)``: the mapping of a YAML document as ``yaml.safe_load`` reads it (how
#: scenario.yaml is read); raises :class:`RunError` with FILE:LINE for malformed YAML.
parse_yaml = _plot_run.parse_yaml
#: The name of ``parse_yaml`` from when scenario.yaml was read by a hand-written YAML subset
#: reader; kept so that analysis scripts that import it still run.
parse_yaml_subset = parse_yaml

#: ``track_label(id)``: the readable id of a numeric track id, as common/track_id.hpp writes it:
#: ``S:N`` (ids ``(S + 1) << 48 | N``), ``S:tTsK`` when N is a birth id ``J << 44 | T << 24 | K``
#: (tick T, sensor K) with ``.J`` appended when J is not 0, and ``gN`` for ids below ``1 << 48``,
#: minted by the aggregator.
track_label = _plot_run.track_label

TRUTH_DTYPE = np.dtype([("tick", "i4"), ("target", "i8"), ("x", "f8"), ("y", "f8"), ("vx", "f8"), ("vy", "f8")])

#: ``tick_delivered`` and ``delay`` are -1 for a report that was not delivered (fate ``lost``,
#: ``unreachable`` or ``after_end``); ``hops`` is -1 when no path led to a supernode; ``target``
#: is -1 for a false alarm.
OBSERVATION_DTYPE = np.dtype([
    ("tick_generated", "i4"), ("tick_delivered", "i4"), ("sensor", "i8"), ("supernode", "i4"), ("hops", "i4"),
    ("delay", "i4"), ("x", "f8"), ("y", "f8"), ("target", "i8"), ("fate", "U11")])

_TRACK_FIELDS = [("track", "u8"), ("label", "U24"), ("x", "f8"), ("y", "f8"), ("vx", "f8"), ("vy", "f8"),
                 ("covariance", "f8", (4, 4))]
#: ``covariance`` is the 4 x 4 covariance over (x, y, vx, vy), all zero when unknown (and in runs
#: written before tracks.csv had covariance columns).
TRACK_DTYPE = np.dtype([("tick", "i4")] + _TRACK_FIELDS)
SUPERNODE_TRACK_DTYPE = np.dtype([("tick", "i4"), ("supernode", "i4")] + _TRACK_FIELDS)

#: Stone Soup's usual state order is (x, vx, y, vy), as its ConstantVelocity models and a
#: LinearGaussian measurement model with mapping (0, 2) expect; wsntrack's is (x, y, vx, vy).
#: ``state[STONESOUP_ORDER]`` reorders a wsntrack state, ``P[np.ix_(o, o)]`` a covariance.
STONESOUP_ORDER = [0, 2, 1, 3]


def covariance_matrix(values):
    """The symmetric 4 x 4 matrix over (x, y, vx, vy) of the ten p_* columns of tracks.csv
    (p_xx, p_xy, p_xvx, p_xvy, p_yy, p_yvx, p_yvy, p_vxvx, p_vxvy, p_vyvy): an array of
    shape (..., 10) gives shape (..., 4, 4).

    >>> covariance_matrix([1, 2, 3, 4, 5, 6, 7, 8, 9, 10])[1]
    array([2., 5., 6., 7.])
    """
    values = np.asarray(values, dtype=float)
    matrix = np.zeros(values.shape[:-1] + (4, 4))
    for k, (i, j) in enumerate(_plot_run.COVARIANCE_INDEX):
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
    return np.rec.array(array)


def _json(path, required):
    if not path.is_file():
        if required:
            raise RunError(f"{path}: missing (is {path.parent} a wsntrack run directory?)")
        return None
    try:
        return json.loads(path.read_text(encoding="utf-8"))
    except json.JSONDecodeError as error:
        raise RunError(f"{path}:{error.lineno}: malformed JSON ({error.msg})") from None
    except (OSError, UnicodeDecodeError) as error:
        raise RunError(f"{path}: cannot read ({error})") from None


def _metrics_per_tick(path):
    """Every column of metrics_per_tick.csv, found by name: tick, truth_targets and tracks as whole
    numbers, the others as floats."""
    with open(path, encoding="utf-8", errors="replace") as handle:
        header = handle.readline().strip().split(",")
    whole = ("tick", "truth_targets", "tracks")
    for name in whole + ("ospa",):
        if name not in header:
            raise RunError(f"{path}:1: expected a header with the columns tick,truth_targets,tracks,ospa"
                           f"{',gospa,...' if name != 'ospa' else ''}, got '{','.join(header)}' (no column '{name}')")
    columns = [(name, int if name in whole else float) for name in header if name]
    rows, _ = _plot_run.read_table(path, columns)
    return _records(rows, np.dtype([(name, "i4" if kind is int else "f8") for name, kind in columns]))


class Run:
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
    has_labels, has_covariance   whether tracks.csv has the label / covariance columns (else
                      labels are made from the ids and covariances are zero)
    metrics_per_tick  record array of metrics_per_tick.csv: tick, truth_targets (K*), tracks (K),
                      ospa, gospa, gospa_localisation, gospa_missed, gospa_false
    metrics           metrics.json as a dict (headline eps_k, eps_x, ospa; "metrics": ...)
    network           network.json as a dict (ranges, counts and ratios of the network model)
    info              run.json as a dict (run_id, domain, ticks, processes, ...)
    """

    def __init__(self, path):
        self.path = Path(path)
        if not self.path.is_dir():
            raise RunError(f"{self.path}: not a directory")
        p = self.path
        scenario_path = p / "scenario.yaml"
        if not scenario_path.is_file():
            raise RunError(f"{scenario_path}: missing (is {p} a wsntrack run directory?)")
        try:
            text = scenario_path.read_text(encoding="utf-8")
        except (OSError, UnicodeDecodeError) as error:
            raise RunError(f"{scenario_path}: cannot read ({error})") from None
        self.scenario = parse_yaml(text, scenario_path)
        summary = _plot_run.read_scenario(p)  # checks what the arrays below depend on, with FILE:LINE
        self.ticks = summary["ticks"]
        self.supernodes = np.array(summary["supernodes"], dtype=float).reshape(-1, 2)
        self.sensors = self._sensors(summary)

        self.truth = _records(_plot_run.read_csv(p / "truth.csv", ["tick", "target", "x", "y", "vx", "vy"],
                                                 [int, int, float, float, float, float]), TRUTH_DTYPE)
        rows, self.has_labels, self.has_covariance = _plot_run.read_tracks(p / "tracks.csv")
        self.tracks = _tracks(rows, supernode=False)
        path = p / "tracks_supernode.csv"
        self.supernode_tracks = _tracks(_plot_run.read_tracks(path, supernode=True)[0], True) if path.is_file() \
            else None
        path = p / "observations.csv"
        if path.is_file():
            rows = [(r[0], -1 if r[1] is None else r[1]) + r[2:5] + (-1 if r[5] is None else r[5],) + r[6:]
                    for r in _plot_run.read_observations(path)]
            self.observations = _records(rows, OBSERVATION_DTYPE)
        else:
            self.observations = None
        path = p / "metrics_per_tick.csv"
        self.metrics_per_tick = _metrics_per_tick(path) if path.is_file() else None
        self.metrics = _json(p / "metrics.json", required=False)
        self.network = _json(p / "network.json", required=False)
        self.info = _json(p / "run.json", required=False)

    def __repr__(self):
        return (f"<wsntrack run {str(self.path)!r}: {self.scenario.get('name', '?')}, {self.ticks} ticks, "
                f"{len(np.unique(self.truth.target))} targets, {len(np.unique(self.tracks.track))} tracks>")

    def _sensors(self, summary):
        path = self.path / "sensors.csv"
        if path.is_file():
            rows = _plot_run.read_csv(path, ["sensor", "x", "y"], [int, float, float])
            return np.array([(r[1], r[2]) for r in rows], dtype=float).reshape(-1, 2)
        if summary["layout"] != "grid":
            return None  # a random layout without sensors.csv: the positions are not recorded
        x0, y0, x1, y1 = summary["region"]
        spacing = summary["spacing"]
        # As common/sensor_layout.cpp: sensors at the cell centres, row by row.
        columns = int(math.floor((x1 - x0) / spacing + 1e-9))
        rows = int(math.floor((y1 - y0) / spacing + 1e-9))
        gx, gy = np.meshgrid(x0 + (np.arange(columns) + 0.5) * spacing, y0 + (np.arange(rows) + 0.5) * spacing)
        return np.column_stack([gx.ravel(), gy.ravel()])

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

    # -- Stone Soup -------------------------------------------------------------------------
    # Written against Stone Soup's documented types (stonesoup.types.groundtruth, .track,
    # .state, .detection); untested here, since stonesoup is not installed where this was made.

    def timestamp(self, tick, start=None, tick_seconds=1.0):
        """The datetime of `tick`: `start` (default 1970-01-01 00:00, naive like Stone Soup's
        examples) + tick * tick_seconds."""
        import datetime
        start = datetime.datetime(1970, 1, 1) if start is None else start
        return start + datetime.timedelta(seconds=float(tick) * tick_seconds)

    def _stone_soup_state(self, row, tick_seconds):
        """State vector (x, vx, y, vy) and covariance in Stone Soup's order, velocities per second."""
        scale = np.array([1.0, 1.0, 1.0 / tick_seconds, 1.0 / tick_seconds])
        state = np.array([row.x, row.y, row.vx, row.vy]) * scale
        covariance = row.covariance * np.outer(scale, scale)
        o = STONESOUP_ORDER
        return state[o].reshape(-1, 1), covariance[np.ix_(o, o)]

    def stonesoup_truths(self, start=None, tick_seconds=1.0):
        """``{target: GroundTruthPath}``: one path per target of GroundTruthState (x, vx, y, vy),
        id ``"target <n>"``, metadata {"target", "tick"}. Velocities are per second: per tick
        divided by `tick_seconds` (default 1, so that a tick is a second). Needs stonesoup.
        """
        from stonesoup.types.groundtruth import GroundTruthPath, GroundTruthState
        paths = {}
        for target, rows in self.by_id(self.truth, "target").items():
            states = []
            for row in rows:
                vector = np.array([[row.x], [row.vx / tick_seconds], [row.y], [row.vy / tick_seconds]])
                states.append(GroundTruthState(vector, timestamp=self.timestamp(row.tick, start, tick_seconds),
                                               metadata={"target": int(target), "tick": int(row.tick)}))
            paths[int(target)] = GroundTruthPath(states, id=f"target {target}")
        return paths

    def stonesoup_tracks(self, supernode=None, start=None, tick_seconds=1.0):
        """``{label: Track}`` of GaussianState (x, vx, y, vy) with the covariance reordered to match,
        track id = label (``"0:1"``; ``"S<j> 0:1"`` for supernode j's tracks, with `supernode`).
        Needs stonesoup; a zero covariance (unknown) is passed on as it is."""
        from stonesoup.types.state import GaussianState
        from stonesoup.types.track import Track
        records = self.tracks if supernode is None else self.supernode_tracks[self.supernode_tracks.supernode == supernode]
        tracks = {}
        for label, rows in self.by_id(records, "label").items():
            states = []
            for row in rows:
                vector, covariance = self._stone_soup_state(row, tick_seconds)
                states.append(GaussianState(vector, covariance, timestamp=self.timestamp(row.tick, start, tick_seconds)))
            ident = label if supernode is None else f"S{supernode} {label}"
            tracks[label] = Track(states, id=ident, init_metadata={"label": label, "track": int(rows[0].track)})
        return tracks

    def stonesoup_detections(self, truths=None, measurement_model=None, start=None, tick_seconds=1.0):
        """``[(datetime of tick t, set of detections delivered at t)]`` for t = 1 .. T, the shape a
        Stone Soup DetectionReader's detections_gen() yields. A detection is a TrueDetection (its
        groundtruth_path from `truths`, as stonesoup_truths() returns them, when given) or a Clutter
        for a false alarm; its state vector is the reported (x, y), its timestamp the tick it was
        generated (earlier than t for a late report), its metadata the observations.csv row.
        `measurement_model` (e.g. LinearGaussian(ndim_state=4, mapping=(0, 2), noise_covar=...))
        is attached to every detection. Needs stonesoup."""
        from stonesoup.types.detection import Clutter, TrueDetection
        if self.observations is None:
            raise RunError(f"{self.path / 'observations.csv'}: missing (is {self.path} a finished run?)")
        truths = truths if truths is not None else {}
        delivered = {t: set() for t in range(1, self.ticks + 1)}
        for row in self.observations[self.observations.fate == "delivered"]:
            metadata = {name: row[name].item() for name in OBSERVATION_DTYPE.names}
            vector = np.array([[row.x], [row.y]])
            when = self.timestamp(row.tick_generated, start, tick_seconds)
            if row.target < 0:
                detection = Clutter(vector, timestamp=when, measurement_model=measurement_model, metadata=metadata)
            else:
                detection = TrueDetection(vector, timestamp=when, measurement_model=measurement_model,
                                          metadata=metadata, groundtruth_path=truths.get(int(row.target)))
            delivered.setdefault(int(row.tick_delivered), set()).add(detection)
        return [(self.timestamp(t, start, tick_seconds), delivered[t]) for t in sorted(delivered)]


def load_run(path):
    """Loads the run directory `path` (see :class:`Run` for what it holds). Raises RunError
    (``FILE[:LINE]: what was expected``) for a missing or malformed file, ToolMissing without
    PyYAML; scenario.yaml, truth.csv and tracks.csv must be there, the other files are None when
    absent.

    >>> run = load_run("runs/demo")                                   # doctest: +SKIP
    >>> run.tracks_at(50)[["label", "x", "y"]]                        # doctest: +SKIP
    """
    return Run(path)


if __name__ == "__main__":
    # tools/wsntrack_run.py RUN_DIR: a one-screen summary, or the error and exit status 2 (3 for a
    # missing tool, as plot_run.py).
    if len(sys.argv) != 2 or sys.argv[1].startswith("-"):
        sys.exit("usage: wsntrack_run.py RUN_DIR   (loads a run directory and prints what it holds)")
    try:
        loaded = load_run(sys.argv[1])
    except RunError as error:
        print(f"wsntrack_run.py: {error}", file=sys.stderr)
        sys.exit(2)
    except ToolMissing as error:
        print(f"wsntrack_run.py: {error}", file=sys.stderr)
        sys.exit(3)
    print(loaded)
    for name in ("truth", "observations", "tracks", "supernode_tracks", "metrics_per_tick"):
        value = getattr(loaded, name)
        print(f"  {name:17s} {'absent' if value is None else f'{len(value)} rows'}")
    print(f"  labels {'yes' if loaded.has_labels else 'made from ids'}, covariance "
          f"{'yes' if loaded.has_covariance else 'absent (zero)'}")
