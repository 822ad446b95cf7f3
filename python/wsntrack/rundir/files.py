"""The run directory's files as rows: tracks (with their readable ids, covariances and classes),
truth, observations, the per-tick metrics and metrics.json's headline, each checked as it is read.
The columns, classes, fates and the track-id layout are those the C++ side writes, read from its
catalogue (wsntrack.catalogue) when first used: COVARIANCE_COLUMNS, COVARIANCE_INDEX,
TRACK_ID_SHIFT, TARGET_CLASSES, TRUTH_CLASSES, OBSERVATION_FATES and PER_TICK_COUNTS are attributes
of this module computed then."""

import re

from .. import catalogue
from .tables import InputError, OPTIONAL_FLOAT, OPTIONAL_INT, read_header, read_json, read_table

_STATE = ("x", "y", "vx", "vy")


def _constants():
    """The facts of the catalogue this module reads, by the names it has always exported."""
    document = catalogue.load()
    # The upper triangle of the symmetric 4 x 4 covariance over (x, y, vx, vy), as tracks.csv
    # orders it, and the (row, column) of each in the matrix.
    covariance = tuple(c for c in document["run_files"]["tracks.csv"] if c.startswith("p_"))
    index = tuple(tuple(_STATE.index(part) for part in re.findall(r"vx|vy|x|y", c[2:])) for c in covariance)
    classes = tuple(document["target_classes"])
    per_tick_whole = ("tick",) + tuple(c["name"] for m in document["metrics"] for c in m["per_tick_columns"]
                                       if c["whole"])
    return {
        "COVARIANCE_COLUMNS": covariance,
        "COVARIANCE_INDEX": index,
        "TRACK_ID_SHIFT": document["track_id"]["owner_shift"],
        # The class names tracks.csv declares (its 'class' column; empty: no class evidence yet) and
        # truth.csv gives its targets ('unknown' too).
        "TARGET_CLASSES": tuple(c for c in classes if c != "unknown"),
        "TRUTH_CLASSES": classes,
        # dead_supernode: due at a supernode that a fault of the scenario killed or paused (docs/FAULTS.md).
        "OBSERVATION_FATES": tuple(document["observation_fates"]),
        # metrics_per_tick.csv's columns that count (whole numbers); every other column is a number.
        "PER_TICK_COUNTS": per_tick_whole,
    }


_CONSTANTS = {}


def __getattr__(name):
    if not _CONSTANTS:
        _CONSTANTS.update(_constants())
    if name in _CONSTANTS:
        return _CONSTANTS[name]
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def _fact(name):
    return __getattr__(name)


def track_label(track):
    """The readable id of a numeric track id, as 'wsntrack watch' shows it and newer tracks.csv
    files write it (common/track_id.hpp, track_id::label): S:N for serial N of supernode S (ids are
    (S + 1) << 48 | N); S:tTsK when the serial is a birth id J << 44 | T << 24 | K (tick T, sensor
    K: the GNN, rule-based and sbmht engines), S:tTsK.J when J, the index of the trees one sensor
    started in one tick (sbmht), is not 0; gN for an id the aggregator minted (below 1 << 48)."""
    layout = catalogue.load()["track_id"]
    shift, tick_shift, index_shift = layout["owner_shift"], layout["birth_tick_shift"], layout["birth_index_shift"]
    owner, serial = track >> shift, track & ((1 << shift) - 1)
    if owner == 0:
        return f"g{track}"
    if serial < layout["birth_serial_floor"]:
        return f"{owner - 1}:{serial}"
    index = serial >> index_shift
    tick = (serial >> tick_shift) & ((1 << (index_shift - tick_shift)) - 1)
    sensor = serial & ((1 << tick_shift) - 1)
    return f"{owner - 1}:t{tick}s{sensor}" + (f".{index}" if index else "")


def _check_track_header(present):
    lacking = [name for name in _fact('COVARIANCE_COLUMNS') if name not in present]
    if lacking and len(lacking) < len(_fact('COVARIANCE_COLUMNS')):
        return f"expected every covariance column {','.join(_fact('COVARIANCE_COLUMNS'))} or none, got no '{lacking[0]}'"
    if ("class" in present) != ("class_probability" in present):
        return "expected both columns 'class' and 'class_probability' or neither, got only " + \
            ("'class'" if "class" in present else "'class_probability'")
    return None


def _check_track_class(row):
    declared, probability = row[-2], row[-1]
    if declared and declared not in _fact('TARGET_CLASSES'):
        return f"column 'class' must be empty or one of {', '.join(_fact('TARGET_CLASSES'))}, got '{declared}'"
    if (probability is None) != (not declared):
        return ("column 'class_probability' must be set exactly when 'class' is, got "
                f"'{'' if probability is None else row[-1]}' with class '{declared}'")
    if probability is not None and not 0.0 <= probability <= 1.0:
        return f"column 'class_probability' must be in [0, 1], got '{probability:g}'"
    return None


def read_tracks(path, supernode=False):
    """tracks.csv (or tracks_supernode.csv with `supernode`, or tracks_settled.csv) as (rows,
    has_label, has_covariance). A row is (tick, [supernode,] track, x, y, vx, vy, label, p_xx, p_xy,
    ..., p_vyvy, stop_probability, class, class_probability), the p_* in COVARIANCE_COLUMNS order,
    stop_probability the probability the track gives its target standing still (None from an
    engine without a stop model), class one of TARGET_CLASSES or "" (no class evidence at the tick)
    and class_probability its probability, or None with no class. Files of older runs have neither
    label nor covariance nor class nor stop columns: the label is then made from the id
    (track_label), the covariance is all zero, which tracks.csv also writes for an unknown
    covariance, the class is "" (None) and the stop probability None."""
    key = ["tick"] + (["supernode"] if supernode else []) + ["track"]
    columns = [(name, int) for name in key] + [(name, float) for name in ("x", "y", "vx", "vy")]
    optional = ([("label", str, "")] + [(name, float, 0.0) for name in _fact('COVARIANCE_COLUMNS')]
                + [("stop_probability", OPTIONAL_FLOAT, None), ("class", str, ""),
                   ("class_probability", OPTIONAL_FLOAT, None)])
    newer = key + ["label", "x", "y", "vx", "vy"] + list(_fact('COVARIANCE_COLUMNS')) + \
        ["class", "class_probability", "stop_probability"]
    expected = f"'{','.join(newer)}' (or the older '{','.join(name for name, _ in columns)}')"
    rows, present = read_table(path, columns, optional, expected, check=_check_track_class,
                               check_header=_check_track_header)
    has_covariance = bool(present & set(_fact('COVARIANCE_COLUMNS')))
    has_label = "label" in present
    if not has_label:
        at = len(key) + 4
        rows = [row[:at] + (track_label(row[len(key) - 1]),) + row[at + 1:] for row in rows]
    return rows, has_label, has_covariance


def read_truth(path, with_class=False):
    """truth.csv as (rows, classes): rows (tick, target, x, y, vx, vy), and {target: its class} from
    the 'class' column (one of TRUTH_CLASSES; an empty cell reads as unknown), empty for a file of
    an older run, which has no such column. A target's class is the one of its last row. With
    `with_class` each row ends with its class too ("unknown" for an older run's)."""
    columns = [("tick", int), ("target", int)] + [(name, float) for name in ("x", "y", "vx", "vy")]

    def check(row):
        if row[6] not in _fact('TRUTH_CLASSES') and row[6] != "":
            return f"column 'class' must be one of {', '.join(_fact('TRUTH_CLASSES'))}, got '{row[6]}'"
        return None

    rows, present = read_table(path, columns, [("class", str, "")], check=check)
    classes = {row[1]: row[6] or "unknown" for row in rows} if "class" in present else {}
    if with_class:
        return [row[:6] + (row[6] or "unknown",) for row in rows], classes
    return [row[:6] for row in rows], classes


def read_observations(path):
    """observations.csv: rows (tick_generated, tick_delivered, sensor, supernode, hops, delay, x, y,
    target, fate, level); tick_delivered and delay are None when the report was not delivered;
    level is the report's power level (None in an older run's file, which has no such column)."""
    columns = [("tick_generated", int), ("tick_delivered", OPTIONAL_INT), ("sensor", int), ("supernode", int),
               ("hops", int), ("delay", OPTIONAL_INT), ("x", float), ("y", float), ("target", int),
               ("fate", str)]

    def check(row):
        if row[9] not in _fact('OBSERVATION_FATES'):
            return f"column 'fate' must be one of {', '.join(_fact('OBSERVATION_FATES'))}, got '{row[9]}'"
        if (row[1] is None) != (row[9] != "delivered"):
            return (f"column 'tick_delivered' must be set exactly when the fate is delivered, got "
                    f"'{'' if row[1] is None else row[1]}' with fate {row[9]}")
        return None

    return read_table(path, columns, [("level", OPTIONAL_INT, None)], check=check)[0]


def read_metrics_per_tick(path):
    """metrics_per_tick.csv as (columns, rows): every column of the file, found by name, as (name,
    int or float) pairs (tick, truth_targets and tracks whole numbers, the others numbers), and the
    rows in that order. tick, truth_targets, tracks and ospa must be there."""
    header = read_header(path)
    for name in _fact('PER_TICK_COUNTS') + ("ospa",):
        if name not in header:
            raise InputError(f"{path}:1: expected a header with the columns tick,truth_targets,tracks,ospa"
                             f"{',gospa,...' if name != 'ospa' else ''}, got '{','.join(header)}' (no column '{name}')")
    columns = [(name, int if name in _fact('PER_TICK_COUNTS') else float) for name in header if name]
    return columns, read_table(path, columns)[0]


def _ospa_of_metrics_json(run_dir, per_tick):
    """{tick: OSPA} from metrics.json's metrics.ospa_per_tick (from metrics.first_tick on)."""
    path = run_dir / "metrics.json"
    if not path.is_file():
        raise InputError(f"{per_tick}: missing, and so is {path}: no OSPA to plot "
                         f"(is {run_dir} a finished wsntrack run?)")
    try:
        metrics = read_json(path).get("metrics", {})
    except AttributeError as error:  # a document that is not an object
        raise InputError(f"{path}: cannot read ({error})") from None
    values = metrics.get("ospa_per_tick") if isinstance(metrics, dict) else None
    if not isinstance(values, list) or not all(isinstance(v, (int, float)) for v in values):
        raise InputError(f"{path}: expected a list of numbers at metrics.ospa_per_tick")
    first = metrics.get("first_tick", 1)
    if isinstance(first, bool) or not isinstance(first, int):
        raise InputError(f"{path}: expected a whole number at metrics.first_tick, got '{first}'")
    return {first + i: float(v) for i, v in enumerate(values)}


def read_per_tick(run_dir, scenario, truth, tracks):
    """Per tick from 1 to T: (ticks, K*, K, OSPA or None, source of OSPA): from metrics_per_tick.csv,
    else counted from the truth and track rows with metrics.json's OSPA."""
    ticks = list(range(1, scenario["ticks"] + 1))
    per_tick = run_dir / "metrics_per_tick.csv"
    k_true = {t: 0 for t in ticks}
    k = {t: 0 for t in ticks}
    if per_tick.is_file():
        columns, rows = read_metrics_per_tick(per_tick)
        at = {name: i for i, (name, _) in enumerate(columns)}
        ospa = {}
        for row in rows:
            tick = row[at["tick"]]
            k_true[tick], k[tick], ospa[tick] = row[at["truth_targets"]], row[at["tracks"]], row[at["ospa"]]
        source = per_tick.name
    else:
        for row in truth:
            k_true[row[0]] = k_true.get(row[0], 0) + 1
        for row in tracks:
            k[row[0]] = k.get(row[0], 0) + 1
        ospa = _ospa_of_metrics_json(run_dir, per_tick)
        source = "metrics.json"
    return ticks, [k_true[t] for t in ticks], [k[t] for t in ticks], [ospa.get(t) for t in ticks], source


def read_metrics_summary(run_dir):
    """eps_K, eps_X and mean OSPA of metrics.json for titles, and under "faults" the scenario's faults
    as (first tick, last tick, what) of their "during" windows (docs/FAULTS.md), to mark them on the
    charts; absent or unreadable values are left out."""
    try:
        document = read_json(run_dir / "metrics.json")
        metrics = document.get("metrics", {})
        summary = {k: metrics.get(k) for k in ("eps_k", "eps_x", "ospa_mean") if isinstance(metrics.get(k), (int, float))}
        listed = document.get("faults")  # a list of faults; anything else ({"faults": 5}) has none to mark
        faults = [(f["during"]["first_tick"], f["during"]["last_tick"], str(f.get("what", f.get("action", "fault"))))
                  for f in (listed if isinstance(listed, list) else [])
                  if isinstance(f, dict) and isinstance(f.get("during"), dict)
                  and all(isinstance(f["during"].get(k), int) for k in ("first_tick", "last_tick"))]
        if faults:
            summary["faults"] = faults
        return summary
    except (InputError, AttributeError):
        return {}

