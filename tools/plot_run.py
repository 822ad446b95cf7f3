#!/usr/bin/python3
"""Plots of one wsntrack run directory: tracks against the truth on the sensor field, the number
of tracks K and of targets K* over time, and OSPA over time.

Needs Debian's python3-matplotlib and python3-yaml (PyYAML, for the run's scenario.yaml), hence
/usr/bin/python3 rather than whatever python3 is first on PATH. Everything else is the standard
library.
"""

import argparse
import csv
import json
import math
import os
import sys
import time
from pathlib import Path

# Imported here rather than when scenario.yaml is read: under 'wsntrack run' (--wait) the import
# then overlaps the run. Without it the script still starts, to report it as a missing tool.
try:
    import yaml
    _YAML_IMPORT_ERROR = None
except ImportError as error:
    yaml = None
    _YAML_IMPORT_ERROR = str(error)

EXIT_BAD_INPUT = 2
EXIT_TOOL_MISSING = 3

DESCRIPTION = """\
Draws the plots of a wsntrack run directory (what 'wsntrack run' does after every run unless
--no-plot is given):

  tracks.FORMAT       the estimated global tracks (tracks.csv) against the true target paths
                      (truth.csv) on the sensor field: sensors, supernodes and their tracking
                      groups (the Voronoi cells of the supernodes: every sensor reports to its
                      nearest supernode), like Oh et al. Fig. 9 (right). One colour per
                      track, unless the tracks carry class evidence (some non-empty 'class'
                      cell in tracks.csv): then, as the ONERA paper draws them, a colour per
                      declared class, tick by tick (the segment between two ticks takes the
                      class of the later one), with a legend entry per class present:
                        wheeled_light  light blue     human   vermillion
                        wheeled_heavy  dark blue      group   orange
                        tracked        green          aerial  purple
                        no class yet (an empty cell): dark grey, dotted
                      Each track's id is then written at its last point (up to 30 tracks), and
                      the targets' labels give their true class (truth.csv's 'class').
                      (--animate keeps one colour per track.)
                      Typed sensors (a 'sensors.layout: list' whose entries set 'type', with
                      sensor_model kind field_sensors, ONERA Table I) are drawn with a marker
                      and colour per type, over their coverage: a faint sector of the sensor's
                      range and field of view centred on its heading (degrees counter-clockwise
                      from +x; a disc for a 360-degree field of view), the entry's 'range' and
                      'fov' else (left out or 0) sensor_model.<type>'s 'range' and 'fov_deg',
                      clipped to the region, beneath the paths and tracks; a legend entry per
                      type present gives its number of sensors, e.g. "camera (10)":
                        radar             wine, diamond      pir       rose, triangle down
                        acoustic_antenna  teal, triangle up  camera    indigo, plus
                        acoustic_beacon   olive, circle      magnetic  dark grey, square
                      A list entry without a type stays a plain grey dot, and any other layout
                      or sensor model draws its sensors as grey dots. (--animate draws every
                      sensor as a grey dot.)
  cardinality.FORMAT  K, the number of tracks, and K*, the number of targets, at every tick
                      (the terms of eps_K, Oh eq. 9)
  ospa.FORMAT         OSPA at every tick, with its cut-off c
  detections.FORMAT   (ADMAN sensors only) the number of targets the sensors detect at every
                      tick, inside r0 and in between, against the true number (the ADMAN
                      paper's Fig. 9), and the reports' localisation error (observations.csv)

With --animate it writes instead an animation of the run, one frame per tick (what 'wsntrack
replay RUN_DIR [OPTION]...' does): the sensor field with the supernodes and their tracking groups,
the reports delivered to the supernodes at the tick (observations.csv; late ones and false alarms
marked), the true targets with fading trails, the global tracks with their ids (S:N) and 2-sigma
position ellipses, and beside them the legend, K and K* and OSPA up to the tick. As
replay.FORMAT in RUN_DIR/plots unless --out names a file or another directory: a GIF (default),
an MP4 (H.264; needs ffmpeg) or an HTML page holding every frame and a player (no network needed).

Lengths are in the scenario's units (sensor separations when the grid spacing is 1), times in
ticks. Reads scenario.yaml, truth.csv, tracks.csv (columns found by name: runs from before the
label, covariance and class columns read too, and draw as they always did), observations.csv
(--animate), metrics_per_tick.csv (else metrics.json's metrics.ospa_per_tick) and sensors.csv when
present (else the sensor grid is computed from scenario.yaml). A 'class' cell that is not a class
name above (truth.csv: or 'unknown'), or a 'class_probability' outside [0, 1] or set without a
class, is malformed input; so is, for typed sensors, a type not listed above, a position or heading
that is not a number, a heading outside [-360, 360], an entry's 'range' outside [0, 1e6] or 'fov'
outside [0, 360], or a type's 'range' outside (0, 1e6] or 'fov_deg' outside (0, 360].

Exit status: 0 on success; 1 when the video encoder (ffmpeg) fails; 2 for a bad command line, a
missing or malformed input file (reported as FILE:LINE: what was expected) or an output that cannot
be written; 3 when a tool is missing: PyYAML or matplotlib (or numpy or Pillow for --animate) for
this python, or ffmpeg on PATH for an MP4.
"""


class InputError(Exception):
    """A missing or malformed input file: reported as one line, exit status 2."""


class ToolMissing(ImportError):
    """A Python package this script needs is not installed: reported as one line, exit status 3."""


# ---------------------------------------------------------------------------------------------
# scenario.yaml, read by PyYAML's safe loader. Its nodes keep their lines, so that a value read
# later can still be reported as FILE:LINE.


def _yaml_error(error, path, text):
    """FILE:LINE: what PyYAML expected, and where the construct it was reading began."""
    if isinstance(error, yaml.MarkedYAMLError) and (error.problem_mark or error.context_mark):
        mark = error.problem_mark or error.context_mark
        what = error.problem or error.context
        if error.problem and error.problem.startswith("but ") and error.context:
            what = f"{error.context}, {error.problem}"  # one sentence that PyYAML splits in two
        elif error.problem and error.context and error.context_mark:
            what += f" ({error.context} at line {error.context_mark.line + 1})"
        return f"{path}:{mark.line + 1}: {what}"
    if isinstance(error, yaml.reader.ReaderError):  # a character YAML does not allow
        line = text.count("\n", 0, error.position) + 1
        return f"{path}:{line}: {error.reason} (character #x{error.character:04x})"
    return f"{path}: malformed YAML ({error})"


def _note_lines(loader, node, keys, where, open_nodes):
    """Records in `where` the line of every key and list item under `node`; an alias of an
    enclosing node (a recursive document) is not followed again."""
    if id(node) in open_nodes:
        return
    open_nodes.add(id(node))
    if isinstance(node, yaml.MappingNode):
        # Later entries overwrite earlier ones, as in the constructed mapping (merged keys come
        # first, and a repeated key wins).
        for key_node, value_node in node.value:
            key = loader.construct_object(key_node, deep=True)
            where[keys + (key,)] = key_node.start_mark.line + 1
            _note_lines(loader, value_node, keys + (key,), where, open_nodes)
    elif isinstance(node, yaml.SequenceNode):
        for index, item in enumerate(node.value):
            where[keys + (index,)] = item.start_mark.line + 1
            _note_lines(loader, item, keys + (index,), where, open_nodes)
    open_nodes.discard(id(node))


def parse_yaml(text, path, where=None):
    """The YAML mapping in `text` (read from `path`), as yaml.safe_load reads it. When `where` is a
    dict it receives the line of every key and list item, keyed by its path (a tuple of keys and
    indices), for messages about values. Raises InputError (FILE:LINE: what was expected) for
    malformed YAML or a document that is not a mapping, and ToolMissing without PyYAML."""
    if yaml is None:
        raise ToolMissing(f"PyYAML is not available to {sys.executable} ({_YAML_IMPORT_ERROR}); "
                          "on Debian: apt-get install python3-yaml")
    loader = None
    try:
        loader = yaml.SafeLoader(text)  # inside the try: it rejects characters YAML does not allow
        node = loader.get_single_node()
        if node is None:
            raise InputError(f"{path}:1: empty file, expected a scenario mapping")
        data = loader.construct_document(node)
        if not isinstance(data, dict):
            raise InputError(f"{path}:{node.start_mark.line + 1}: expected a mapping at the top level")
        if where is not None:
            _note_lines(loader, node, (), where, set())
    except yaml.YAMLError as error:
        raise InputError(_yaml_error(error, path, text)) from None
    finally:
        if loader is not None:
            loader.dispose()
    return data


# ---------------------------------------------------------------------------------------------
# Run-directory inputs


def _require(path):
    if not path.is_file():
        raise InputError(f"{path}: missing (is {path.parent} a wsntrack run directory?)")


def _number(value, path, line, column, kind=float):
    try:
        number = kind(value)
    except (TypeError, ValueError):
        what = "a whole number" if kind is int else "a number"
        raise InputError(f"{path}:{line}: column '{column}' must be {what}, got '{value}'") from None
    if kind is float and not math.isfinite(number):
        raise InputError(f"{path}:{line}: column '{column}' must be finite, got '{value}'")
    return number


# Column types of read_table besides int, float and str: a whole number, or a finite number, or an
# empty field (None).
OPTIONAL_INT = "optional int"
OPTIONAL_FLOAT = "optional float"


def _convert(value, path, line, column, kind):
    if kind is str:
        return value
    if kind == OPTIONAL_INT:
        return None if value == "" else _number(value, path, line, column, int)
    if kind == OPTIONAL_FLOAT:
        return None if value == "" else _number(value, path, line, column, float)
    return _number(value, path, line, column, kind)


def read_table(path, columns, optional=(), expected=None, check=None, check_header=None):
    """Rows of a CSV file, its columns found by header name so that a file with more columns (from a
    newer wsntrack) still reads. `columns`: (name, type) pairs the header must have; `optional`:
    (name, type, default) triples, read when the header has them, else `default` in every row. A
    type is int, float, str, OPTIONAL_INT or OPTIONAL_FLOAT. Returns (rows, present): every row a tuple in the order
    of `columns` then `optional`, and the set of the optional names the header has. `expected`
    describes the header in the message about a missing column (default: the names of `columns`);
    `check(row)`, when given, returns what is wrong with a converted row, or None, and
    `check_header(present)` what is wrong with the optional columns found."""
    _require(path)
    if expected is None:
        expected = "'" + ",".join(name for name, _ in columns) + "'"
    rows = []
    with open(path, newline="", encoding="utf-8", errors="replace") as handle:
        reader = csv.reader(handle)
        try:
            header = next(reader, None)
            if header is None:
                raise InputError(f"{path}:1: expected the header {expected}, got an empty file")
            index = {}
            for i, name in enumerate(header):
                if name in index:
                    raise InputError(f"{path}:1: column '{name}' appears twice in the header")
                index[name] = i
            missing = [name for name, _ in columns if name not in index]
            if missing:
                raise InputError(f"{path}:1: expected the header {expected}, got '{','.join(header)}' "
                                 f"(no column '{missing[0]}')")
            present = {name for name, _, _ in optional if name in index}
            problem = check_header(present) if check_header else None
            if problem:
                raise InputError(f"{path}:1: {problem}")
            # One entry per output field: (index in the row, name, type), or (None, default, None).
            fields = [(index[name], name, kind) for name, kind in columns]
            fields += [(index[name], name, kind) if name in present else (None, default, None)
                       for name, kind, default in optional]
            for row in reader:
                line = reader.line_num
                if not row:
                    continue
                if len(row) != len(header):
                    raise InputError(
                        f"{path}:{line}: expected {len(header)} fields ({','.join(header)}), got {len(row)}")
                rows.append(tuple(name if i is None else _convert(row[i], path, line, name, kind)
                                  for i, name, kind in fields))
                problem = check(rows[-1]) if check else None
                if problem:
                    raise InputError(f"{path}:{line}: {problem}")
        except csv.Error as error:
            raise InputError(f"{path}:{reader.line_num}: malformed CSV ({error})") from None
    return rows, present


def read_csv(path, header, types):
    """Rows of a CSV file with the columns `header` (found by name), converted with `types` (None:
    kept as text)."""
    return read_table(path, [(name, kind or str) for name, kind in zip(header, types)])[0]


# The upper triangle of the symmetric 4 x 4 covariance over (x, y, vx, vy), as tracks.csv orders it,
# and the (row, column) of each in the matrix.
COVARIANCE_COLUMNS = ("p_xx", "p_xy", "p_xvx", "p_xvy", "p_yy", "p_yvx", "p_yvy", "p_vxvx", "p_vxvy", "p_vyvy")
COVARIANCE_INDEX = ((0, 0), (0, 1), (0, 2), (0, 3), (1, 1), (1, 2), (1, 3), (2, 2), (2, 3), (3, 3))
TRACK_ID_SHIFT = 48

# The class names tracks.csv declares (its 'class' column; empty: no class evidence yet) and
# truth.csv gives its targets ('unknown' too), as common/scenario_config.hpp names them.
TARGET_CLASSES = ("wheeled_light", "wheeled_heavy", "tracked", "human", "group", "aerial")
TRUTH_CLASSES = ("unknown",) + TARGET_CLASSES


def track_label(track):
    """The readable id of a numeric track id, as 'wsntrack watch' shows it and newer tracks.csv
    files write it (common/track_id.hpp, track_id::label): S:N for serial N of supernode S (ids are
    (S + 1) << 48 | N); S:tTsK when the serial is a birth id J << 44 | T << 24 | K (tick T, sensor
    K: the GNN, rule-based and sbmht engines), S:tTsK.J when J, the index of the trees one sensor
    started in one tick (sbmht), is not 0; gN for an id the aggregator minted (below 1 << 48)."""
    owner, serial = track >> TRACK_ID_SHIFT, track & ((1 << TRACK_ID_SHIFT) - 1)
    if owner == 0:
        return f"g{track}"
    if serial < 1 << 24:
        return f"{owner - 1}:{serial}"
    index, tick, sensor = serial >> 44, (serial >> 24) & ((1 << 20) - 1), serial & ((1 << 24) - 1)
    return f"{owner - 1}:t{tick}s{sensor}" + (f".{index}" if index else "")


def read_tracks(path, supernode=False):
    """tracks.csv (or tracks_supernode.csv with `supernode`, or tracks_settled.csv) as (rows,
    has_label, has_covariance). A row is (tick, [supernode,] track, x, y, vx, vy, label, p_xx, p_xy,
    ..., p_vyvy, class, class_probability), the p_* in COVARIANCE_COLUMNS order, class one of
    TARGET_CLASSES or "" (no class evidence at the tick) and class_probability its probability, or
    None with no class. Files of older runs have neither label nor covariance nor class columns:
    the label is then made from the id (track_label), the covariance is all zero, which tracks.csv
    also writes for an unknown covariance, and the class is "" (None)."""
    key = ["tick"] + (["supernode"] if supernode else []) + ["track"]
    columns = [(name, int) for name in key] + [(name, float) for name in ("x", "y", "vx", "vy")]
    optional = ([("label", str, "")] + [(name, float, 0.0) for name in COVARIANCE_COLUMNS]
                + [("class", str, ""), ("class_probability", OPTIONAL_FLOAT, None)])
    newer = key + ["label", "x", "y", "vx", "vy"] + list(COVARIANCE_COLUMNS) + ["class", "class_probability"]
    expected = f"'{','.join(newer)}' (or the older '{','.join(name for name, _ in columns)}')"

    def check_header(present):
        lacking = [name for name in COVARIANCE_COLUMNS if name not in present]
        if lacking and len(lacking) < len(COVARIANCE_COLUMNS):
            return f"expected every covariance column {','.join(COVARIANCE_COLUMNS)} or none, got no '{lacking[0]}'"
        if ("class" in present) != ("class_probability" in present):
            return "expected both columns 'class' and 'class_probability' or neither, got only " + \
                ("'class'" if "class" in present else "'class_probability'")
        return None

    def check(row):
        declared, probability = row[-2], row[-1]
        if declared and declared not in TARGET_CLASSES:
            return f"column 'class' must be empty or one of {', '.join(TARGET_CLASSES)}, got '{declared}'"
        if (probability is None) != (not declared):
            return ("column 'class_probability' must be set exactly when 'class' is, got "
                    f"'{'' if probability is None else row[-1]}' with class '{declared}'")
        if probability is not None and not 0.0 <= probability <= 1.0:
            return f"column 'class_probability' must be in [0, 1], got '{probability:g}'"
        return None

    rows, present = read_table(path, columns, optional, expected, check=check, check_header=check_header)
    has_covariance = bool(present & set(COVARIANCE_COLUMNS))
    has_label = "label" in present
    if not has_label:
        at = len(key) + 4
        rows = [row[:at] + (track_label(row[len(key) - 1]),) + row[at + 1:] for row in rows]
    return rows, has_label, has_covariance


def read_truth(path):
    """truth.csv as (rows, classes): rows (tick, target, x, y, vx, vy), and {target: its class} from
    the 'class' column (one of TRUTH_CLASSES; an empty cell reads as unknown), empty for a file of
    an older run, which has no such column. A target's class is the one of its last row."""
    columns = [("tick", int), ("target", int)] + [(name, float) for name in ("x", "y", "vx", "vy")]

    def check(row):
        if row[6] not in TRUTH_CLASSES and row[6] != "":
            return f"column 'class' must be one of {', '.join(TRUTH_CLASSES)}, got '{row[6]}'"
        return None

    rows, present = read_table(path, columns, [("class", str, "")], check=check)
    classes = {row[1]: row[6] or "unknown" for row in rows} if "class" in present else {}
    return [row[:6] for row in rows], classes


OBSERVATION_FATES = ("delivered", "lost", "unreachable", "after_end")


def read_observations(path):
    """observations.csv: rows (tick_generated, tick_delivered, sensor, supernode, hops, delay, x, y,
    target, fate); tick_delivered and delay are None when the report was not delivered."""
    columns = [("tick_generated", int), ("tick_delivered", OPTIONAL_INT), ("sensor", int), ("supernode", int),
               ("hops", int), ("delay", OPTIONAL_INT), ("x", float), ("y", float), ("target", int),
               ("fate", str)]

    def check(row):
        if row[9] not in OBSERVATION_FATES:
            return f"column 'fate' must be one of {', '.join(OBSERVATION_FATES)}, got '{row[9]}'"
        if (row[1] is None) != (row[9] != "delivered"):
            return (f"column 'tick_delivered' must be set exactly when the fate is delivered, got "
                    f"'{'' if row[1] is None else row[1]}' with fate {row[9]}")
        return None

    return read_table(path, columns, check=check)[0]


def read_scenario(run_dir):
    path = run_dir / "scenario.yaml"
    _require(path)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as error:
        raise InputError(f"{path}: cannot read ({error})") from None
    lines = {}
    data = parse_yaml(text, path, lines)

    def at(*keys):
        """FILE:LINE of a value, or of the nearest enclosing key that exists."""
        while keys and keys not in lines:
            keys = keys[:-1]
        return f"{path}:{lines[keys]}" if keys else str(path)

    def get(*keys, kind=float, default=None):
        node = data
        for key in keys:
            node = node.get(key) if isinstance(node, dict) else None
        if node is None:
            if default is not None:
                return default
            raise InputError(f"{at(*keys)}: missing '{'.'.join(keys)}'")
        if kind is str:
            return str(node)
        if isinstance(node, bool) or not isinstance(node, (int, float)) or not math.isfinite(node):
            raise InputError(f"{at(*keys)}: '{'.'.join(keys)}' must be a number, got '{node}'")
        return kind(node)

    region = tuple(get("region", k) for k in ("x_min", "y_min", "x_max", "y_max"))
    if not (region[0] < region[2] and region[1] < region[3]):
        raise InputError(f"{at('region')}: region must have x_min < x_max and y_min < y_max, got {region}")
    layout = get("sensors", "layout", kind=str)
    if layout not in ("grid", "random", "list"):
        raise InputError(f"{at('sensors', 'layout')}: 'sensors.layout' must be grid, random or list, got '{layout}'")
    spacing = get("sensors", "spacing") if layout == "grid" else None
    if spacing is not None and spacing <= 0:
        raise InputError(f"{at('sensors', 'spacing')}: 'sensors.spacing' must be > 0, got {spacing:g}")
    supernodes = []
    for i, node in enumerate(data.get("supernodes") or []):
        if not isinstance(node, dict):
            raise InputError(f"{at('supernodes', i)}: supernodes[{i}] must be a mapping {{x: X, y: Y}}")
        xy = []
        for key in ("x", "y"):
            value = node.get(key)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
                raise InputError(f"{at('supernodes', i, key)}: supernodes[{i}].{key} must be a number, got '{value}'")
            xy.append(float(value))
        supernodes.append(tuple(xy))
    terrain = read_terrain(data.get("terrain"), at)
    sensor_kind = get("sensor_model", "kind", kind=str, default="signal_strength")
    typed_sensors = None
    if layout == "list" and sensor_kind == "field_sensors":
        typed_sensors = read_typed_sensors(data, at)
    return {
        "name": get("name", kind=str, default="?"),
        "region": region,
        "terrain": terrain,
        "layout": layout,
        "spacing": spacing,
        "supernodes": supernodes,
        "ticks": get("run", "ticks", kind=int),
        "seed": get("run", "seed", kind=str, default="?"),
        "engine": get("tracker", "engine", kind=str, default="?"),
        "sensor_kind": sensor_kind,
        "typed_sensors": typed_sensors,
        "ospa_c": get("metrics", "ospa_c", default=math.nan),
        "ospa_p": get("metrics", "ospa_p", default=math.nan),
    }


def read_terrain(section, at):
    """The scenario's roads and masks ({"roads": [[(x, y), ...]], "masks": [(kind, [(x, y), ...])]}),
    empty when it has no terrain section."""
    terrain = {"roads": [], "masks": []}
    if section is None:
        return terrain
    if not isinstance(section, dict):
        raise InputError(f"{at('terrain')}: 'terrain' must be a mapping of roads and masks")

    def points(value, *keys):
        if not isinstance(value, list) or not all(
                isinstance(p, list) and len(p) == 2 and all(
                    isinstance(c, (int, float)) and not isinstance(c, bool) and math.isfinite(c) for c in p)
                for p in value):
            raise InputError(f"{at(*keys)}: '{'.'.join(map(str, keys))}' must be a list of [x, y] points")
        return [(float(x), float(y)) for x, y in value]

    for i, road in enumerate(section.get("roads") or []):
        if not isinstance(road, dict):
            raise InputError(f"{at('terrain', 'roads', i)}: terrain.roads[{i}] must be a mapping {{name, points}}")
        terrain["roads"].append(points(road.get("points"), "terrain", "roads", i, "points"))
    for i, mask in enumerate(section.get("masks") or []):
        if not isinstance(mask, dict):
            raise InputError(f"{at('terrain', 'masks', i)}: terrain.masks[{i}] must be a mapping {{name, kind, polygon}}")
        terrain["masks"].append((str(mask.get("kind")), points(mask.get("polygon"), "terrain", "masks", i, "polygon")))
    return terrain


# The sensor types of sensor_model kind field_sensors (ONERA Table I), in the order of the scenario
# schema, with the coverage of a sensor whose entry and type section give none (node/field_sensors:
# range, fov_deg), and how tracks.png draws them: colour (Paul Tol's muted palette, apart from the
# tracks' class colours where it can be) and marker.
SENSOR_TYPES = {
    "acoustic_antenna": {"range": 200.0, "fov_deg": 360.0, "colour": "#44AA99", "marker": "^"},
    "acoustic_beacon": {"range": 200.0, "fov_deg": 360.0, "colour": "#999933", "marker": "o"},
    "magnetic": {"range": 2.0, "fov_deg": 360.0, "colour": "#555555", "marker": "s"},
    "pir": {"range": 200.0, "fov_deg": 10.0, "colour": "#CC6677", "marker": "v"},
    "radar": {"range": 1000.0, "fov_deg": 90.0, "colour": "#882255", "marker": "D"},
    "camera": {"range": 200.0, "fov_deg": 30.0, "colour": "#332288", "marker": "P"},
}


def _yaml_number(value):
    """A YAML scalar as a finite float, or None when it is not one (booleans are not numbers)."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        return None
    return float(value)


def read_typed_sensors(data, at):
    """The sensors of a `sensors.layout: list` scenario whose sensor model is field_sensors, as
    {"typed": [(type, x, y, heading, range, fov, name)], "plain": [(x, y)]}: heading and fov in
    degrees, the heading counter-clockwise from +x, each range and fov the entry's, else (left out
    or 0) its type's in sensor_model.<type>, else the type's default; "plain" the entries without a
    'type' (drawn as plain sensors). None when no entry has a type: such a list draws as it always
    did. Raises InputError (FILE:LINE: what was expected) for a malformed entry or type section."""
    entries = (data.get("sensors") or {}).get("list")
    if not isinstance(entries, list) or not any(
            isinstance(entry, dict) and entry.get("type") not in (None, "") for entry in entries):
        return None
    model = data.get("sensor_model")
    model = model if isinstance(model, dict) else {}
    coverage = {}  # type: (range, fov), read when a sensor of the type is met

    def type_coverage(kind):
        if kind in coverage:
            return coverage[kind]
        section = model.get(kind)
        if section is None:
            section = {}
        if not isinstance(section, dict):
            raise InputError(f"{at('sensor_model', kind)}: 'sensor_model.{kind}' must be a mapping of the "
                             f"type's settings")
        values = []
        for key, high in (("range", 1e6), ("fov_deg", 360.0)):
            value = section.get(key)
            if value is None:
                values.append(SENSOR_TYPES[kind][key])
                continue
            number = _yaml_number(value)
            if number is None or not 0.0 < number <= high:
                raise InputError(f"{at('sensor_model', kind, key)}: 'sensor_model.{kind}.{key}' must be a number "
                                 f"in (0, {'1e6' if high == 1e6 else f'{high:g}'}], got '{value}'")
            values.append(number)
        coverage[kind] = tuple(values)
        return coverage[kind]

    typed, plain = [], []
    for i, entry in enumerate(entries):
        if not isinstance(entry, dict):
            raise InputError(f"{at('sensors', 'list', i)}: sensors.list[{i}] must be a mapping "
                             "{name, type, x, y, heading, ...}")
        kind = entry.get("type")
        kind = None if kind is None or kind == "" else str(kind)
        if kind is not None and kind not in SENSOR_TYPES:
            raise InputError(f"{at('sensors', 'list', i, 'type')}: sensors.list[{i}].type must be one of "
                             f"{', '.join(SENSOR_TYPES)}, got '{kind}'")
        values = {}
        # key, default, lowest, highest (fov: 0 excluded, but 0 means the type's, like range)
        for key, default, low, high in (("x", None, -math.inf, math.inf), ("y", None, -math.inf, math.inf),
                                        ("heading", 0.0, -360.0, 360.0), ("range", 0.0, 0.0, 1e6),
                                        ("fov", 0.0, 0.0, 360.0)):
            value = entry.get(key)
            if value is None and default is not None:
                values[key] = default
                continue
            number = _yaml_number(value)
            if number is None:
                raise InputError(f"{at('sensors', 'list', i, key)}: sensors.list[{i}].{key} must be a number, "
                                 f"got '{value}'")
            if not low <= number <= high:
                zero = " (0: the type's)" if key in ("range", "fov") else ""
                top = "1e6" if high == 1e6 else f"{high:g}"
                raise InputError(f"{at('sensors', 'list', i, key)}: sensors.list[{i}].{key} must be in "
                                 f"[{low:g}, {top}]{zero}, got {number:g}")
            values[key] = number
            if kind is None and key == "y":
                break  # an untyped sensor is only a position
        if kind is None:
            plain.append((values["x"], values["y"]))
            continue
        default_range, default_fov = type_coverage(kind)
        typed.append((kind, values["x"], values["y"], values["heading"], values["range"] or default_range,
                      values["fov"] or default_fov, str(entry.get("name", ""))))
    return {"typed": typed, "plain": plain} if typed else None


# Masks under everything but the region's tint; roads over the masks, under the target paths.
MASK_COLOURS = {"building": "#8c7b6b", "vegetation": "#7fb77e"}
ROAD_COLOUR = "#8a8a8a"


def draw_terrain(ax, Polygon, scenario):
    """Draws the masks (filled) and the roads (grey lines); returns legend handles for what it drew."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    terrain = scenario.get("terrain") or {"roads": [], "masks": []}
    kinds = []
    for kind, polygon in terrain["masks"]:
        colour = MASK_COLOURS.get(kind, "#aaaaaa")
        ax.add_patch(Polygon(polygon, closed=True, facecolor=colour, edgecolor=colour, alpha=0.55, linewidth=0.8,
                             zorder=1.5))
        if kind not in kinds:
            kinds.append(kind)
    for road in terrain["roads"]:
        ax.plot([p[0] for p in road], [p[1] for p in road], color=ROAD_COLOUR, linewidth=3.0, solid_capstyle="round",
                solid_joinstyle="round", zorder=2.5)
    handles = [Patch(facecolor=MASK_COLOURS.get(kind, "#aaaaaa"), alpha=0.55, label=f"mask: {kind}") for kind in kinds]
    if terrain["roads"]:
        handles.append(Line2D([], [], color=ROAD_COLOUR, linewidth=3.0, label="road"))
    return handles


# Coverage of the typed sensors: faint fills, a thin edge a little stronger, under the masks' edges,
# the tracking-group boundaries, the roads, the target paths and the tracks.
COVERAGE_FILL_ALPHA = 0.10
COVERAGE_EDGE_ALPHA = 0.45
COVERAGE_ZORDER = 1.6


def draw_typed_sensors(ax, scenario):
    """Draws each typed sensor (scenario["typed_sensors"]) as its type's marker, over its coverage:
    a sector of its range and field of view centred on its heading (a disc for a 360-degree field of
    view) in the type's colour, clipped to the region. Returns a legend handle per type present,
    labelled with the type and its number of sensors."""
    from matplotlib.collections import PatchCollection
    from matplotlib.colors import to_rgba
    from matplotlib.lines import Line2D
    from matplotlib.patches import Circle, Patch, Rectangle, Wedge
    x0, y0, x1, y1 = scenario["region"]
    clip = Rectangle((x0, y0), x1 - x0, y1 - y0, transform=ax.transData)
    by_type = {}
    for sensor in scenario["typed_sensors"]["typed"]:
        by_type.setdefault(sensor[0], []).append(sensor)
    handles = []
    for kind, style in SENSOR_TYPES.items():
        sensors = by_type.get(kind)
        if not sensors:
            continue
        colour = style["colour"]
        patches = []
        for _, x, y, heading, reach, fov, _ in sensors:
            if fov >= 360.0:
                patches.append(Circle((x, y), reach))
            else:
                patches.append(Wedge((x, y), reach, heading - fov / 2.0, heading + fov / 2.0))
        coverage = PatchCollection(patches, facecolors=[to_rgba(colour, COVERAGE_FILL_ALPHA)],
                                   edgecolors=[to_rgba(colour, COVERAGE_EDGE_ALPHA)], linewidths=0.6,
                                   zorder=COVERAGE_ZORDER)
        ax.add_collection(coverage)
        coverage.set_clip_path(clip)
        marker = dict(linestyle="none", marker=style["marker"], markersize=6.5, markerfacecolor=colour,
                      markeredgecolor="white", markeredgewidth=0.8)
        ax.plot([s[1] for s in sensors], [s[2] for s in sensors], zorder=5, **marker)
        handles.append((Patch(facecolor=to_rgba(colour, 0.22), edgecolor=to_rgba(colour, COVERAGE_EDGE_ALPHA),
                              linewidth=0.6, label=f"{kind} ({len(sensors)})"),
                        Line2D([], [], **marker)))
    return handles


# Drawing more points than pixels only costs time and file size.
MAX_SENSORS_DRAWN = 40000


def read_sensors(run_dir, scenario):
    """Sensor positions to draw (xs, ys) and n, where 1 in n sensors is drawn."""
    path = run_dir / "sensors.csv"
    if path.is_file():
        rows = read_csv(path, ["sensor", "x", "y"], [int, float, float])
        stride = max(1, math.ceil(len(rows) / MAX_SENSORS_DRAWN))
        shown = rows[::stride]
        return [r[1] for r in shown], [r[2] for r in shown], stride
    if scenario["layout"] != "grid":
        print(f"plot_run.py: {path} missing: the {scenario['layout']} sensor layout is not drawn", file=sys.stderr)
        return [], [], 1
    # Same formula as common/sensor_layout.cpp: sensors at the cell centres.
    x0, y0, x1, y1 = scenario["region"]
    spacing = scenario["spacing"]
    columns = int(math.floor((x1 - x0) / spacing + 1e-9))
    rows = int(math.floor((y1 - y0) / spacing + 1e-9))
    stride = max(1, math.ceil(math.sqrt(columns * rows / MAX_SENSORS_DRAWN)))
    xs, ys = [], []
    for r in range(0, rows, stride):
        for c in range(0, columns, stride):
            xs.append(x0 + (c + 0.5) * spacing)
            ys.append(y0 + (r + 0.5) * spacing)
    return xs, ys, stride * stride


def read_per_tick(run_dir, scenario, truth, tracks):
    """Per tick from 1 to T: (ticks, K*, K, OSPA or None, source of OSPA)."""
    ticks = list(range(1, scenario["ticks"] + 1))
    per_tick = run_dir / "metrics_per_tick.csv"
    if per_tick.is_file():
        header = ["tick", "truth_targets", "tracks", "ospa", "gospa", "gospa_localisation", "gospa_missed",
                  "gospa_false"]
        rows = read_csv(per_tick, header, [int, int, int, float, float, float, float, float])
        k_true = {t: 0 for t in ticks}
        k = {t: 0 for t in ticks}
        ospa = {}
        for row in rows:
            k_true[row[0]], k[row[0]], ospa[row[0]] = row[1], row[2], row[3]
        return ticks, [k_true[t] for t in ticks], [k[t] for t in ticks], [ospa.get(t) for t in ticks], per_tick.name

    k_true = {t: 0 for t in ticks}
    for row in truth:
        k_true[row[0]] = k_true.get(row[0], 0) + 1
    k = {t: 0 for t in ticks}
    for row in tracks:
        k[row[0]] = k.get(row[0], 0) + 1
    path = run_dir / "metrics.json"
    if not path.is_file():
        raise InputError(f"{per_tick}: missing, and so is {path}: no OSPA to plot "
                         f"(is {run_dir} a finished wsntrack run?)")
    try:
        metrics = json.loads(path.read_text(encoding="utf-8")).get("metrics", {})
    except json.JSONDecodeError as error:
        raise InputError(f"{path}:{error.lineno}: malformed JSON ({error.msg})") from None
    except (OSError, UnicodeDecodeError, AttributeError) as error:
        raise InputError(f"{path}: cannot read ({error})") from None
    values = metrics.get("ospa_per_tick") if isinstance(metrics, dict) else None
    if not isinstance(values, list) or not all(isinstance(v, (int, float)) for v in values):
        raise InputError(f"{path}: expected a list of numbers at metrics.ospa_per_tick")
    first = metrics.get("first_tick", 1)
    if isinstance(first, bool) or not isinstance(first, int):
        raise InputError(f"{path}: expected a whole number at metrics.first_tick, got '{first}'")
    ospa = {first + i: float(v) for i, v in enumerate(values)}
    return ticks, [k_true[t] for t in ticks], [k[t] for t in ticks], [ospa.get(t) for t in ticks], path.name


def read_metrics_summary(run_dir):
    """eps_K, eps_X and mean OSPA for the titles; absent values are simply not shown."""
    try:
        data = json.loads((run_dir / "metrics.json").read_text(encoding="utf-8"))
        metrics = data.get("metrics", {})
        return {k: metrics.get(k) for k in ("eps_k", "eps_x", "ospa_mean") if isinstance(metrics.get(k), (int, float))}
    except (OSError, ValueError, AttributeError):
        return {}


# ---------------------------------------------------------------------------------------------
# Geometry


def voronoi_cells(supernodes, region):
    """Cell of each supernode within the region, as a polygon (list of points, maybe empty).
    Ties go to the lower index, as in network_model/topology.cpp."""
    x0, y0, x1, y1 = region
    cells = []
    for i, (sx, sy) in enumerate(supernodes):
        polygon = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
        for j, (tx, ty) in enumerate(supernodes):
            if j == i:
                continue
            if (tx, ty) == (sx, sy):
                if j < i:
                    polygon = []
                continue
            # Keep the points at least as near to supernode i as to j: a . p <= b.
            a = (tx - sx, ty - sy)
            b = (tx * tx + ty * ty - sx * sx - sy * sy) / 2.0
            polygon = _clip(polygon, a, b)
            if not polygon:
                break
        cells.append(polygon)
    return cells



def draw_groups_and_region(ax, Polygon, scenario, bounds):
    """Tints each supernode's tracking group (its Voronoi cell) and outlines the region; returns the
    cells, which the callers also draw the boundaries of."""
    x0, y0, x1, y1 = bounds
    cells = voronoi_cells(scenario["supernodes"], scenario["region"])
    for j, polygon in enumerate(cells):
        if polygon:
            ax.add_patch(Polygon(polygon, closed=True, facecolor=REGION_COLOURS[j % len(REGION_COLOURS)],
                                 edgecolor="none", zorder=0))
    ax.add_patch(Polygon([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], closed=True, fill=False, edgecolor="black",
                         linewidth=0.8, zorder=1))
    return cells

def _clip(polygon, a, b):
    def inside(p):
        return a[0] * p[0] + a[1] * p[1] <= b + 1e-12

    def cut(p, q):
        fp = a[0] * p[0] + a[1] * p[1] - b
        fq = a[0] * q[0] + a[1] * q[1] - b
        s = fp / (fp - fq)
        return (p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1]))

    out = []
    for k, p in enumerate(polygon):
        q = polygon[(k + 1) % len(polygon)]
        if inside(p):
            out.append(p)
            if not inside(q):
                out.append(cut(p, q))
        elif inside(q):
            out.append(cut(p, q))
    return out


def interior_edges(cells, region):
    """Cell edges that are not on the region's border: the tracking-group boundaries."""
    x0, y0, x1, y1 = region
    eps = 1e-9 * max(x1 - x0, y1 - y0)

    def on_border(p, q):
        return ((abs(p[0] - x0) < eps and abs(q[0] - x0) < eps) or (abs(p[0] - x1) < eps and abs(q[0] - x1) < eps)
                or (abs(p[1] - y0) < eps and abs(q[1] - y0) < eps) or (abs(p[1] - y1) < eps and abs(q[1] - y1) < eps))

    seen, edges = set(), []
    for polygon in cells:
        for k, p in enumerate(polygon):
            q = polygon[(k + 1) % len(polygon)]
            key = tuple(sorted((tuple(round(v, 6) for v in p), tuple(round(v, 6) for v in q))))
            if on_border(p, q) or key in seen or key[0] == key[1]:
                continue
            seen.add(key)
            edges.append((p, q))
    return edges


def paths_by_id(rows, id_column):
    """{id: (xs, ys, first tick, last tick)}, a gap of ticks breaking the line (NaN)."""
    paths = {}
    for row in sorted(rows, key=lambda r: (r[id_column], r[0])):
        tick, ident, x, y = row[0], row[id_column], row[id_column + 1], row[id_column + 2]
        if ident not in paths:
            paths[ident] = [[x], [y], tick, tick]
            continue
        path = paths[ident]
        if tick > path[3] + 1:
            path[0].append(math.nan)
            path[1].append(math.nan)
        path[0].append(x)
        path[1].append(y)
        path[3] = tick
    return paths


# ---------------------------------------------------------------------------------------------
# Figures

# Track colours far enough apart to tell neighbouring tracks apart (mostly Okabe-Ito), none of
# them the truth's or the sensors' grey; past the ninth track the colours repeat, dashed, then dotted.
TRACK_COLOURS = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#7B3294", "#8C510A", "#8F8A00"]
TRACK_DASHES = ["solid", (0, (5, 2)), (0, (1.5, 1.5))]
REGION_COLOURS = ["#fff3d6", "#e3f0ff", "#e8f6e8", "#f6e6f2", "#eeeeee", "#fde8e0"]
TRUTH_COLOUR = "#8c8c8c"
# Track colours by declared class (tracks.csv's 'class'), when a run's tracks carry class evidence:
# vehicles in blues and green, people in warm colours, aircraft in purple; a track at a tick
# without class evidence is dark grey and dotted.
CLASS_COLOURS = {"wheeled_light": "#56B4E9", "wheeled_heavy": "#0072B2", "tracked": "#009E73",
                 "human": "#D55E00", "group": "#E69F00", "aerial": "#7B3294"}
NO_CLASS_COLOUR = "#333333"
NO_CLASS_DASHES = (0, (1.5, 1.5))
# Track ids are written beside the tracks (coloured by class, colour no longer tells them apart)
# only when there are this few.
MAX_LABELLED_TRACKS = 30


def new_figure(mpl, width, height, left, right, bottom, top):
    """A figure of width x height inches whose axes leave the given margins (inches). Margins are
    set by hand: bbox_inches="tight" would draw every figure twice, doubling the plotting time."""
    fig = mpl.figure.Figure(figsize=(width, height))
    ax = fig.add_axes([left / width, bottom / height, 1 - (left + right) / width, 1 - (bottom + top) / height])
    return fig, ax


def length_unit(scenario):
    """The axis unit: sensor separations on a unit grid, else the scenario's own unit with Ds."""
    spacing = scenario["spacing"]
    if spacing is None or spacing == 1:
        return "sensor separations"
    return f"scenario units, Ds = {spacing:g}"


# Reports drawn on the tracks map (as Oh et al. 2005 Fig. 11 draws the testbed's observations) only
# when they are this few: beyond, they would hide the tracks. Checked on the file's size first so
# that a large run's observations.csv is never read for it.
MAX_DRAWN_OBSERVATIONS = 1000


def few_observations(path):
    """The (x, y) of every delivered report of observations.csv, or None when there are more than
    MAX_DRAWN_OBSERVATIONS (or the file is absent)."""
    try:
        if path.stat().st_size > 120 * MAX_DRAWN_OBSERVATIONS:
            return None
    except OSError:
        return None
    rows = read_observations(path)
    if len(rows) > MAX_DRAWN_OBSERVATIONS:
        return None
    return [(row[6], row[7]) for row in rows if row[9] == "delivered"]


def class_pieces(rows):
    """The polylines of one track's rows (sorted by tick; row[2:4] is x, y, row[-2] the class
    declared at the tick) in pieces of one class each: [(class, xs, ys)]. The segment between two
    consecutive ticks takes the class of its later tick, so a piece starts at the last point of the
    piece before; a gap of ticks breaks the line. A lone point is a piece of one point."""
    pieces = []
    previous = None
    for row in rows:
        tick, x, y, declared = row[0], row[2], row[3], row[-2]
        joined = previous is not None and tick == previous[0] + 1
        if joined and pieces[-1][0] == declared:
            pieces[-1][1].append(x)
            pieces[-1][2].append(y)
        elif joined:
            pieces.append((declared, [previous[2], x], [previous[3], y]))
        else:
            pieces.append((declared, [x], [y]))
        previous = row
    return pieces


def plot_tracks(mpl, scenario, sensors, truth, tracks, summary, out_path, observations=None, truth_classes=None):
    """tracks.FORMAT. When some track row declares a class, the tracks are coloured by the class
    declared at each tick (CLASS_COLOURS) and labelled with their ids, and the targets' labels
    give their true classes (`truth_classes`); otherwise one colour (then dash) per track."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Polygon, Patch
    from matplotlib.transforms import offset_copy

    x0, y0, x1, y1 = scenario["region"]
    width, height = x1 - x0, y1 - y0
    margin = 0.015 * max(width, height)
    # The axes keep the region's aspect ratio (within reason: a 100 x 1 strip is still readable).
    axes_w = 8.9
    box_aspect = min(1.6, max(0.25, (height + 2 * margin) / (width + 2 * margin)))
    fig, ax = new_figure(mpl, axes_w + 1.1, axes_w * box_aspect + 0.75 + 1.75, left=0.85, right=0.25, bottom=1.75,
                         top=0.75)
    ax.set_xlim(x0 - margin, x1 + margin)
    ax.set_ylim(y0 - margin, y1 + margin)
    ax.set_aspect("equal")

    cells = draw_groups_and_region(ax, Polygon, scenario, (x0, y0, x1, y1))
    terrain_handles = draw_terrain(ax, Polygon, scenario)

    xs, ys, stride = sensors
    sensor_handles = []
    if scenario.get("typed_sensors"):
        # Sensors of a type: its marker over its coverage; only the untyped ones are plain dots.
        sensor_handles = draw_typed_sensors(ax, scenario)
        plain = scenario["typed_sensors"]["plain"]
        xs, ys, stride = [p[0] for p in plain], [p[1] for p in plain], 1
    if xs:
        # A marker line, not scatter: one path drawn many times is ~10x faster than a collection.
        size = math.sqrt(max(0.3, min(4.0, 2500.0 / len(xs))))
        ax.plot(xs, ys, linestyle="none", marker="o", markersize=size, markerfacecolor="#b4b4b4",
                markeredgewidth=0, zorder=1, rasterized=True)

    edges = interior_edges(cells, scenario["region"])
    for p, q in edges:
        ax.plot([p[0], q[0]], [p[1], q[1]], color="#444444", linestyle=(0, (6, 4)), linewidth=1.3, zorder=2)

    by_class = any(row[-2] for row in tracks)
    truth_classes = (truth_classes or {}) if by_class else {}
    show_true_class = any(c != "unknown" for c in truth_classes.values())
    truth_paths = paths_by_id(truth, 1)
    label_targets = len(truth_paths) <= 30
    for ident, (px, py, first, last) in truth_paths.items():
        ax.plot(px, py, color=TRUTH_COLOUR, linewidth=6, alpha=0.45, solid_capstyle="round", zorder=3)
        ax.plot(px[0], py[0], marker="o", markersize=9, markerfacecolor="white", markeredgecolor="black",
                markeredgewidth=1.2, zorder=6)
        if label_targets:
            # Labels point inwards near the right and top edges, where they would leave the figure.
            right = px[0] > x0 + 0.88 * width
            top = py[0] > y0 + 0.95 * height
            true_class = f" {truth_classes.get(ident, 'unknown')}" if show_true_class else ""
            ax.annotate(f"{first}–{last}{true_class}", (px[0], py[0]), xytext=(-7 if right else 7, -7 if top else 5),
                        textcoords="offset points", fontsize=9, color="#222222", zorder=7,
                        ha="right" if right else "left", va="top" if top else "bottom",
                        bbox=dict(boxstyle="round,pad=0.15", facecolor="white", edgecolor="none", alpha=0.75))

    if observations:
        ax.plot([o[0] for o in observations], [o[1] for o in observations], linestyle="none", marker="o",
                markersize=7, markerfacecolor="none", markeredgecolor="#555555", markeredgewidth=0.9, zorder=5)

    track_paths = paths_by_id(tracks, 1)
    order = sorted(track_paths, key=lambda i: (track_paths[i][2], i))
    classes_drawn = []
    if by_class:
        # One line (pieces NaN-separated) and one set of markers per class, each point marked in
        # the class of its tick: a few artists whatever the number of tracks.
        rows_of = {}
        for row in sorted(tracks, key=lambda r: (r[1], r[0])):
            rows_of.setdefault(row[1], []).append(row)
        lines, points = {}, {}
        for ident in order:
            for declared, px, py in class_pieces(rows_of[ident]):
                xs_, ys_ = lines.setdefault(declared, ([], []))
                if len(px) > 1:
                    xs_ += px + [math.nan]
                    ys_ += py + [math.nan]
            for row in rows_of[ident]:
                mx, my = points.setdefault(row[-2], ([], []))
                mx.append(row[2])
                my.append(row[3])
        classes_drawn = [c for c in TARGET_CLASSES + ("",) if c in points]
        for declared in classes_drawn:
            colour = CLASS_COLOURS.get(declared, NO_CLASS_COLOUR)
            if lines.get(declared, ([], []))[0]:
                ax.plot(*lines[declared], color=colour, linestyle="solid" if declared else NO_CLASS_DASHES,
                        linewidth=1.6, zorder=4)
            ax.plot(*points[declared], linestyle="none", marker="o", markersize=2.6, color=colour, zorder=4)
        if len(order) <= MAX_LABELLED_TRACKS:
            # Each track's id at its last point, in the colour of its last class.
            for ident in order:
                last = rows_of[ident][-1]
                ax.annotate(last[6], (last[2], last[3]), xytext=(4, -4), textcoords="offset points", fontsize=8,
                            color=CLASS_COLOURS.get(last[-2], NO_CLASS_COLOUR), ha="left", va="top", zorder=7,
                            bbox=dict(boxstyle="round,pad=0.1", facecolor="white", edgecolor="none", alpha=0.6))
    else:
        for n, ident in enumerate(order):
            px, py, _, _ = track_paths[ident]
            colour = TRACK_COLOURS[n % len(TRACK_COLOURS)]
            dashes = TRACK_DASHES[(n // len(TRACK_COLOURS)) % len(TRACK_DASHES)]
            ax.plot(px, py, color=colour, linestyle=dashes, linewidth=1.6, marker="o", markersize=2.6, zorder=4)

    for j, (sx, sy) in enumerate(scenario["supernodes"]):
        ax.plot(sx, sy, marker="*", markersize=20, markerfacecolor="#ffd21f", markeredgecolor="black",
                markeredgewidth=1.2, zorder=8)
        ax.annotate(f"S{j}", (sx, sy), xytext=(10, -14), textcoords="offset points", fontsize=11, fontweight="bold",
                    zorder=8, bbox=dict(boxstyle="round,pad=0.2", facecolor="white", edgecolor="#444444", alpha=0.85))

    ax.set_xlabel(f"x ({length_unit(scenario)})", fontsize=12)
    ax.set_ylabel(f"y ({length_unit(scenario)})", fontsize=12)
    ax.tick_params(labelsize=10)
    metrics = []
    if "eps_k" in summary:
        metrics.append(f"εK = {summary['eps_k']:.3f}")
    if "eps_x" in summary:
        metrics.append(f"εX = {summary['eps_x']:.3f}")
    if "ospa_mean" in summary:
        metrics.append(f"mean OSPA = {summary['ospa_mean']:.2f}")
    ax.set_title(f"{scenario['name']}, seed {scenario['seed']}, {scenario['ticks']} ticks, engine "
                 f"{scenario['engine']}: {len(track_paths)} tracks, {len(truth_paths)} targets"
                 + ("\n" + ", ".join(metrics) if metrics else ""), fontsize=12)

    handles = [
        Line2D([], [], color=TRUTH_COLOUR, linewidth=6, alpha=0.45, solid_capstyle="round",
               label="true target path"),
        Line2D([], [], linestyle="none", marker="o", markersize=9, markerfacecolor="white", markeredgecolor="black",
               label=("target appears (label: appear–last tick" + (", true class" if show_true_class else "")
                      + ")") if label_targets else "target appears"),
    ]
    if by_class:
        for declared in classes_drawn:
            handles.append(Line2D([], [], color=CLASS_COLOURS.get(declared, NO_CLASS_COLOUR), linewidth=1.6,
                                  linestyle="solid" if declared else NO_CLASS_DASHES, marker="o", markersize=2.6,
                                  label=f"track declared {declared}" if declared else "track, no class yet"))
    else:
        handles.append(Line2D([], [], color=TRACK_COLOURS[0], linewidth=1.6, marker="o", markersize=2.6,
                              label="estimated track (one colour" + (" and dash" if len(order) > len(TRACK_COLOURS)
                                                                     else "") + " per track)"))
    handles += [
        Line2D([], [], linestyle="none", marker="*", markersize=16, markerfacecolor="#ffd21f",
               markeredgecolor="black", label="supernode Sj"),
        Patch(facecolor=REGION_COLOURS[0], edgecolor="#999999", label="tracking group of one supernode"),
    ]
    if observations:
        handles.append(Line2D([], [], linestyle="none", marker="o", markersize=7, markerfacecolor="none",
                              markeredgecolor="#555555", markeredgewidth=0.9, label="delivered report (observation)"))
    if edges:
        handles.append(Line2D([], [], color="#444444", linestyle=(0, (6, 4)), linewidth=1.3,
                              label="tracking-group boundary (nearest supernode)"))
    if xs:
        handles.append(Line2D([], [], linestyle="none", marker="o", markersize=4, markerfacecolor="#b4b4b4",
                              markeredgewidth=0,
                              label="sensor" if stride == 1 else f"sensor (1 in {stride} drawn)"))
    handles += sensor_handles
    handles += terrain_handles
    # Below the map rather than on it, so that no track is hidden; a fixed distance in points
    # clears the tick labels and the x label whatever the map's aspect ratio.
    below = offset_copy(ax.transAxes, fig=fig, y=-44, units="points")
    # A sensor type's handle is a tuple (its coverage, its marker), drawn one over the other.
    labels = [(h[0] if isinstance(h, tuple) else h).get_label() for h in handles]
    legend = ax.legend(handles=handles, labels=labels, loc="upper center", ncol=2, fontsize=10, frameon=False,
                       bbox_to_anchor=(0.5, 0.0), bbox_transform=below, handlelength=3)
    if by_class or sensor_handles:
        # The class and sensor-type entries lengthen the legend: the figure grows at the bottom to
        # hold it, the map keeping its size.
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        renderer = FigureCanvasAgg(fig).get_renderer()  # lays text out without drawing the figure
        lacking = -legend.get_window_extent(renderer).y0 / fig.dpi + 0.15
        if lacking > 0:
            fig_w, fig_h = fig.get_size_inches()
            box = ax.get_position()
            fig.set_size_inches(fig_w, fig_h + lacking)
            ax.set_position([box.x0, (box.y0 * fig_h + lacking) / (fig_h + lacking), box.width,
                             box.height * fig_h / (fig_h + lacking)])
    fig.savefig(out_path)


def _integer_axis(ax):
    from matplotlib.ticker import MaxNLocator
    ax.yaxis.set_major_locator(MaxNLocator(integer=True))


def _count_axes(ax, scenario, counts, ylabel):
    """The axes of a count per tick: ticks 1..T, integer counts from 0 to a little above the largest."""
    ax.set_xlim(0.5, scenario["ticks"] + 0.5)
    ax.set_ylim(0, max([1] + counts) * 1.05 + 0.5)
    _integer_axis(ax)
    ax.set_xlabel("tick", fontsize=11)
    ax.set_ylabel(ylabel, fontsize=11)
    ax.grid(True, color="#dddddd", linewidth=0.6)


def plot_cardinality(mpl, scenario, ticks, k_true, k, summary, out_path):
    fig, ax = new_figure(mpl, 10, 4.4, left=0.75, right=0.2, bottom=0.6, top=0.85)
    ax.fill_between(ticks, k_true, k, step="mid", color="#D55E00", alpha=0.18, linewidth=0,
                    label="|K − K*| (error counted by εK)")
    ax.step(ticks, k_true, where="mid", color="black", linewidth=2.4, label="K*: targets (truth)")
    ax.step(ticks, k, where="mid", color="#0072B2", linewidth=1.6, linestyle="--", label="K: tracks (estimate)")
    _count_axes(ax, scenario, k_true + k, "number of targets / tracks")
    title = "Number of targets K* and of tracks K (Oh et al. eq. 9)"
    if "eps_k" in summary:
        title += f": εK = {summary['eps_k']:.3f}"
    # Legend between title and axes: it can then never hide a curve.
    ax.set_title(title, fontsize=12, pad=30)
    ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), ncol=3, fontsize=10, frameon=False)
    fig.savefig(out_path)


# observations.csv's `level` of an ADMAN report: a target inside r0, or in between.
ADMAN_INSIDE = 3
ADMAN_BETWEEN = 1


def read_detections(run_dir, scenario, truth):
    """Per tick of the run: (inside, between, true count) of the targets the ADMAN sensors detected
    (every report generated, whatever became of it on the network), and the localisation error of
    each labelled report against its target at the tick it was made."""
    path = run_dir / "observations.csv"
    rows, present = read_table(path, [("tick_generated", int), ("x", float), ("y", float), ("target", int)],
                               optional=[("level", int, 0)])
    if "level" not in present:
        raise InputError(f"{path}:1: no column 'level' (a run from before ADMAN); cannot tell inside from in between")
    ticks = scenario["ticks"]
    inside, between, true_count = [0] * ticks, [0] * ticks, [0] * ticks
    at = {}
    for t, target, x, y, _, _ in truth:
        if 1 <= t <= ticks:
            true_count[t - 1] += 1
            at[(t, target)] = (x, y)
    errors = []
    for t, x, y, target, level in rows:
        if not 1 <= t <= ticks:
            continue
        if level == ADMAN_INSIDE:
            inside[t - 1] += 1
        elif level == ADMAN_BETWEEN:
            between[t - 1] += 1
        if (t, target) in at:
            tx, ty = at[(t, target)]
            errors.append(math.hypot(x - tx, y - ty))
    return inside, between, true_count, errors


def plot_detections(mpl, scenario, detections, out_path):
    inside, between, true_count, errors = detections
    ticks = list(range(1, scenario["ticks"] + 1))
    total = [a + b for a, b in zip(inside, between)]
    fig, ax = new_figure(mpl, 10, 4.4, left=0.75, right=0.2, bottom=0.6, top=0.85)
    ax.step(ticks, true_count, where="mid", color="black", linewidth=2.4, label="true total number")
    ax.step(ticks, total, where="mid", color="#0072B2", linewidth=1.6, linestyle="--", label="estimated total number")
    ax.step(ticks, inside, where="mid", color="#D55E00", linewidth=1.2, label="inside range (r0)")
    ax.step(ticks, between, where="mid", color="#009E73", linewidth=1.2, linestyle=":", label="in-between area")
    _count_axes(ax, scenario, true_count + total, "number of targets")
    same = sum(1 for a, b in zip(total, true_count) if a == b)
    title = f"Targets detected by ADMAN (its Fig. 9): the count is right at {same} of {len(ticks)} ticks"
    if errors:
        rms = math.sqrt(sum(e * e for e in errors) / len(errors))
        title += f"; localisation error rms {rms:.2f}, median {sorted(errors)[len(errors) // 2]:.2f}"
    ax.set_title(title, fontsize=11, pad=30)
    ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), ncol=4, fontsize=10, frameon=False)
    fig.savefig(out_path)


def plot_ospa(mpl, scenario, ticks, ospa, source, out_path):
    fig, ax = new_figure(mpl, 10, 4.4, left=0.75, right=0.2, bottom=0.6, top=0.85)
    xs = [t for t, v in zip(ticks, ospa) if v is not None]
    ys = [v for v in ospa if v is not None]
    c, p = scenario["ospa_c"], scenario["ospa_p"]
    ax.plot(xs, ys, color="#0072B2", linewidth=1.5, marker="o", markersize=3, label="OSPA at the tick")
    if ys:
        mean = sum(ys) / len(ys)
        ax.axhline(mean, color="#D55E00", linestyle=":", linewidth=1.6, label=f"mean {mean:.2f}")
    if math.isfinite(c):
        ax.axhline(c, color="#555555", linestyle="--", linewidth=1.0, label=f"cut-off c = {c:g}")
    top = max([c if math.isfinite(c) else 0.0] + ys + [1.0])
    ax.set_ylim(0, top * 1.12)
    ax.set_xlim(0.5, scenario["ticks"] + 0.5)
    ax.set_xlabel("tick", fontsize=11)
    ax.set_ylabel(f"OSPA ({length_unit(scenario)})", fontsize=11)
    ax.grid(True, color="#dddddd", linewidth=0.6)
    order = f", p = {p:g}" if math.isfinite(p) else ""
    ax.set_title(f"OSPA distance between tracks and targets (c = {c:g}{order}; from {source})", fontsize=12, pad=30)
    ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), ncol=3, fontsize=10, frameon=False)
    fig.savefig(out_path)


# ---------------------------------------------------------------------------------------------
# Animation (--animate): one frame per tick, drawn onto one figure whose static parts are drawn once


ANIMATION_FORMATS = ("gif", "mp4", "html")
ANIMATION_SUFFIXES = {".gif": "gif", ".mp4": "mp4", ".html": "html", ".htm": "html"}
ANIMATION_NAME = "replay"
OBSERVATION_COLOUR = "#1a1a1a"
FALSE_ALARM_COLOUR = "#e0115f"
SENSOR_COLOUR = "#c2c2c2"
# 2 sigma: the ellipse of Mahalanobis distance 2 around the position, holding 86 % of a 2-D Gaussian.
ELLIPSE_SIGMAS = 2.0


def ellipse_axes(pxx, pxy, pyy, sigmas=ELLIPSE_SIGMAS):
    """(width, height, angle in degrees) of the `sigmas` ellipse of a 2 x 2 position covariance,
    or None when it is zero or not a covariance (not positive semi-definite)."""
    half_trace = (pxx + pyy) / 2.0
    spread = math.hypot((pxx - pyy) / 2.0, pxy)
    major, minor = half_trace + spread, half_trace - spread
    if not major > 0 or minor < -1e-9 * major:
        return None
    angle = math.degrees(0.5 * math.atan2(2.0 * pxy, pxx - pyy))
    return 2 * sigmas * math.sqrt(major), 2 * sigmas * math.sqrt(max(minor, 0.0)), angle


def animation_target(out, run_dir, chosen_format):
    """(path, format) of the animation: --out names the file when it ends in .gif, .mp4 or .html
    (.htm), else a directory (default RUN_DIR/plots) which gets replay.FORMAT; the format is
    --animate-format, else the file's suffix, else gif."""
    path = Path(out) if out else None
    suffix_format = None
    if path is not None and path.suffix.lower() in ANIMATION_SUFFIXES and not path.is_dir():
        suffix_format = ANIMATION_SUFFIXES[path.suffix.lower()]
        if chosen_format and chosen_format != suffix_format:
            raise InputError(f"--out {out}: the suffix says {suffix_format}, --animate-format says {chosen_format}")
        return path, suffix_format
    if path is not None and path.suffix and not path.is_dir():
        raise InputError(f"--out {out}: an animation is written to a .gif, .mp4 or .html file, or into a "
                         f"directory (which a name ending in '{path.suffix}' is not, unless it exists)")
    chosen_format = chosen_format or "gif"
    directory = path if path is not None else run_dir / "plots"
    return directory / f"{ANIMATION_NAME}.{chosen_format}", chosen_format


def parse_size(text):
    """'WIDTHxHEIGHT' in pixels, rounded down to even numbers (as H.264 needs)."""
    try:
        width, height = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise ValueError(f"--size must be WIDTHxHEIGHT in pixels, e.g. 1280x720, got '{text}'") from None
    if not (320 <= width <= 3840 and 240 <= height <= 2160):
        raise ValueError(f"--size must be within 320x240 .. 3840x2160, got '{text}'")
    return width - width % 2, height - height % 2


class Progress:
    """'frame n/N' on stderr: redrawn in place on a terminal, else a line every tenth of the way."""

    def __init__(self, total, quiet):
        self.total, self.quiet = total, quiet
        self.tty = sys.stderr.isatty()
        self.last_line = -1

    def show(self, done, what):
        if self.quiet:
            return
        if self.tty:
            sys.stderr.write(f"\rplot_run.py: {what} frame {done}/{self.total}")
            if done == self.total:
                sys.stderr.write("\n")
            sys.stderr.flush()
        elif done * 10 // self.total > self.last_line or done == self.total:
            self.last_line = done * 10 // self.total
            print(f"plot_run.py: {what} frame {done}/{self.total}", file=sys.stderr, flush=True)


HTML_PAGE = """<!DOCTYPE html>
<!-- {title}: written by wsntrack's plot_run.py --animate; every frame is embedded, nothing is loaded. -->
<html lang="en"><head><meta charset="utf-8"><title>{title}</title>
<style>
body {{ font-family: sans-serif; margin: 1em; color: #222; }}
#frame {{ max-width: 100%; height: auto; border: 1px solid #ccc; display: block; }}
.bar {{ display: flex; align-items: center; gap: 0.5em; margin: 0.5em 0; max-width: {width}px; }}
.bar button {{ font-size: 1.1em; min-width: 2.4em; }}
#slider {{ flex: 1; }}
#label {{ font-variant-numeric: tabular-nums; min-width: 9em; }}
.hint {{ color: #777; font-size: 0.85em; }}
</style></head><body>
<img id="frame" width="{width}" height="{height}" alt="{title}">
<div class="bar">
<button id="first" title="first tick (Home)">&#x23EE;</button>
<button id="back" title="previous tick (&#x2190;)">&#x25C0;</button>
<button id="play" title="play / pause (space)">&#x25B6;</button>
<button id="next" title="next tick (&#x2192;)">&#x25B6;&#xFE0E;|</button>
<button id="last" title="last tick (End)">&#x23ED;</button>
<input id="slider" type="range" min="0" max="{last_index}" value="0">
<span id="label"></span>
<label>speed <select id="speed"><option value="0.25">&#xBC;&#xD7;</option><option value="0.5">&#xBD;&#xD7;</option>
<option value="1" selected>1&#xD7;</option><option value="2">2&#xD7;</option><option value="4">4&#xD7;</option></select></label>
<label><input id="loop" type="checkbox" checked> loop</label>
</div>
<div class="hint">{fps} frames per second at 1&#xD7;; keys: space, &#x2190; &#x2192;, Home, End</div>
<script>
const ticks = {ticks};
const frames = [
{frames}
];
const img = document.getElementById("frame"), slider = document.getElementById("slider"),
      label = document.getElementById("label"), play = document.getElementById("play");
let index = 0, timer = null;
function show(i) {{
  index = Math.max(0, Math.min(frames.length - 1, i));
  img.src = "data:image/png;base64," + frames[index];
  slider.value = index;
  label.textContent = "tick " + ticks[index] + " (" + (index + 1) + "/" + frames.length + ")";
}}
function stop() {{ clearInterval(timer); timer = null; play.innerHTML = "&#x25B6;"; }}
function start() {{
  if (index >= frames.length - 1) show(0);
  const speed = parseFloat(document.getElementById("speed").value);
  timer = setInterval(() => {{
    if (index < frames.length - 1) show(index + 1);
    else if (document.getElementById("loop").checked) show(0);
    else stop();
  }}, 1000 / ({fps} * speed));
  play.innerHTML = "&#x23F8;";
}}
play.onclick = () => timer ? stop() : start();
document.getElementById("first").onclick = () => {{ stop(); show(0); }};
document.getElementById("last").onclick = () => {{ stop(); show(frames.length - 1); }};
document.getElementById("back").onclick = () => {{ stop(); show(index - 1); }};
document.getElementById("next").onclick = () => {{ stop(); show(index + 1); }};
document.getElementById("speed").onchange = () => {{ if (timer) {{ stop(); start(); }} }};
slider.oninput = () => {{ stop(); show(parseInt(slider.value)); }};
document.addEventListener("keydown", (e) => {{
  if (e.target.tagName === "SELECT") return;
  const keys = {{" ": () => play.onclick(), "ArrowLeft": () => {{ stop(); show(index - 1); }},
                "ArrowRight": () => {{ stop(); show(index + 1); }}, "Home": () => {{ stop(); show(0); }},
                "End": () => {{ stop(); show(frames.length - 1); }}}};
  if (keys[e.key]) {{ keys[e.key](); e.preventDefault(); }}
}});
show(0);
</script>
</body></html>
"""


def _rgb_image(rgba):
    """A Pillow RGB image of an (h, w, 4) RGBA array, without an intermediate copy of the array."""
    from PIL import Image
    height, width = rgba.shape[:2]
    return Image.frombuffer("RGBA", (width, height), rgba, "raw", "RGBA", 0, 1).convert("RGB")


class PaletteSink:
    """Frames reduced to one 256-colour palette shared by all, made from sample frames spread over
    the ticks (animate() draws them first). The frames are flat colours and their anti-aliasing
    shades, so the palette costs nothing visible; sharing it makes the GIF quick (Pillow compares
    frames without converting them back to RGB) and the HTML's PNGs a third of RGB ones."""

    SAMPLES = 8

    palette = None

    def set_samples(self, samples):
        from PIL import Image
        import numpy as np
        probe = np.concatenate([sample[:, :, :3] for sample in samples], axis=0)
        # The octree's 224 most used colours and a ramp of 32 greys: alone, the octree merges light
        # greys (faint curves, sensors) into tinted neighbours, which shows as beige lines.
        octree = Image.fromarray(probe).quantize(224, method=Image.Quantize.FASTOCTREE, dither=Image.Dither.NONE)
        greys = [round(255 * k / 31) for k in range(32)]
        self.palette = Image.new("P", (1, 1))
        self.palette.putpalette(octree.getpalette()[:224 * 3] + [v for g in greys for v in (g, g, g)])

    def quantize(self, rgba):
        # No dithering: it would only speckle the flat areas.
        from PIL import Image
        image = _rgb_image(rgba)
        if self.palette is None:
            return image.quantize(256, method=Image.Quantize.FASTOCTREE, dither=Image.Dither.NONE)
        return image.quantize(palette=self.palette, dither=Image.Dither.NONE)


class HtmlSink(PaletteSink):
    """A self-contained HTML page: the frames as base64 PNG in the page, and a small player."""

    def __init__(self, path, fps, size, title):
        self.path, self.fps, self.size, self.title = path, fps, size, title
        self.frames, self.ticks = [], []

    def add(self, rgba, tick):
        import base64
        import io
        buffer = io.BytesIO()
        self.quantize(rgba).save(buffer, format="png")
        self.frames.append(base64.b64encode(buffer.getvalue()).decode("ascii"))
        self.ticks.append(tick)

    def finish(self):
        import html
        page = HTML_PAGE.format(title=html.escape(self.title), width=self.size[0], height=self.size[1],
                                last_index=len(self.frames) - 1, fps=self.fps, ticks=json.dumps(self.ticks),
                                frames=",\n".join(f'"{frame}"' for frame in self.frames))
        self.path.write_text(page, encoding="utf-8")


class GifSink(PaletteSink):
    """An animated GIF through Pillow, every frame with the shared palette. Pillow keeps every
    frame until the end: about 1 MB a frame at 1280 x 720."""

    def __init__(self, path, fps, hold_s):
        self.path, self.fps, self.hold_s = path, fps, hold_s
        self.frames = []

    def add(self, rgba, tick):
        self.frames.append(self.quantize(rgba))

    def finish(self):
        # GIF frames carry their own duration, so the held last frame is one frame.
        durations = [round(1000 / self.fps)] * len(self.frames)
        durations[-1] += round(1000 * self.hold_s)
        self.frames[0].save(self.path, format="GIF", save_all=True, append_images=self.frames[1:],
                            duration=durations, loop=0, optimize=False, disposal=1)


class Mp4Sink:
    """H.264 in MP4 through ffmpeg, fed raw RGB frames on a pipe (yuv420p, which every player takes)."""

    def __init__(self, path, fps, size, hold_s, ffmpeg):
        import subprocess
        import tempfile
        self.hold_frames = round(hold_s * fps)
        self.last = None
        self.log = tempfile.TemporaryFile()
        self.process = subprocess.Popen(
            [ffmpeg, "-nostdin", "-y", "-loglevel", "error", "-f", "rawvideo", "-pix_fmt", "rgb24",
             "-s", f"{size[0]}x{size[1]}", "-r", str(fps), "-i", "pipe:0", "-c:v", "libx264", "-preset", "medium",
             "-crf", "20", "-pix_fmt", "yuv420p", "-movflags", "+faststart", "-f", "mp4", str(path)],
            stdin=subprocess.PIPE, stdout=self.log, stderr=subprocess.STDOUT)

    def add(self, rgba, tick):
        self.last = rgba[:, :, :3].tobytes()
        self._write(self.last)

    def _write(self, data):
        try:
            self.process.stdin.write(data)
        except BrokenPipeError:
            self.finish()  # ffmpeg has ended: finish() says why

    def finish(self):
        if not self.process.stdin.closed:
            try:
                for _ in range(self.hold_frames if self.last else 0):
                    self.process.stdin.write(self.last)
                self.process.stdin.close()
            except BrokenPipeError:
                pass
        code = self.process.wait()
        if code != 0:
            self.log.seek(0)
            lines = self.log.read().decode("utf-8", "replace").strip().splitlines()
            raise EncoderError(f"ffmpeg exit {code}: {lines[-1] if lines else 'no message'}")


class EncoderError(Exception):
    """The video encoder failed: exit status 1."""


def animate(mpl, scenario, sensors, truth, tracks, observations, per_tick, options):
    """Writes the animation of ticks options.first..options.last to options.path."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.collections import LineCollection, PatchCollection
    from matplotlib.colors import to_rgba
    from matplotlib.lines import Line2D
    from matplotlib.patches import Ellipse, Patch, Polygon
    import numpy as np

    width_px, height_px = options.size
    # Laid out in inches on a figure 7.2 in high, whatever the pixels: text keeps its proportions.
    dpi = height_px / 7.2
    fig = mpl.figure.Figure(figsize=((width_px + 0.25) / dpi, (height_px + 0.25) / dpi), dpi=dpi)
    fig.patch.set_facecolor("white")
    canvas = FigureCanvasAgg(fig)
    fig_w, fig_h = fig.get_size_inches()

    x0, y0, x1, y1 = scenario["region"]
    margin = 0.015 * max(x1 - x0, y1 - y0)
    aspect = (y1 - y0 + 2 * margin) / (x1 - x0 + 2 * margin)
    left, bottom, top, right = 0.62, 0.5, 0.95, 0.3
    # The side panel (legend, K and OSPA so far) takes what the map leaves, at least side_min
    # inches; a frame too narrow for both has the map alone.
    side_min, side_gap = 4.2, 0.75
    map_h = fig_h - bottom - top
    map_w = map_h / aspect
    side = fig_w - left - right >= 8.0
    room = fig_w - left - right - (side_min + side_gap if side else 0.0)
    if map_w > room:
        map_w, map_h = room, room * aspect
    map_bottom = bottom + (fig_h - bottom - top - map_h) / 2
    ax = fig.add_axes([left / fig_w, map_bottom / fig_h, map_w / fig_w, map_h / fig_h])
    ax.set_xlim(x0 - margin, x1 + margin)
    ax.set_ylim(y0 - margin, y1 + margin)
    ax.set_aspect("equal", adjustable="datalim")
    ax.tick_params(labelsize=9)
    ax.set_xlabel(f"x ({length_unit(scenario)})", fontsize=10, labelpad=2)
    ax.set_ylabel(f"y ({length_unit(scenario)})", fontsize=10, labelpad=2)

    # Static: tracking groups, the region, terrain, sensors, boundaries, supernodes.
    cells = draw_groups_and_region(ax, Polygon, scenario, (x0, y0, x1, y1))
    draw_terrain(ax, Polygon, scenario)
    xs, ys, stride = sensors
    if xs:
        pixels_per_sensor = map_w * dpi / math.sqrt(len(xs) * (x1 - x0) / (y1 - y0))
        size = max(0.8, min(3.0, 0.3 * pixels_per_sensor * 72 / dpi))
        ax.plot(xs, ys, linestyle="none", marker="o", markersize=size, markerfacecolor=SENSOR_COLOUR,
                markeredgewidth=0, zorder=1)
    edges = interior_edges(cells, scenario["region"])
    for p, q in edges:
        ax.plot([p[0], q[0]], [p[1], q[1]], color="#555555", linestyle=(0, (6, 4)), linewidth=1.1, zorder=2)
    for j, (sx, sy) in enumerate(scenario["supernodes"]):
        ax.plot(sx, sy, marker="*", markersize=15, markerfacecolor="#ffd21f", markeredgecolor="black",
                markeredgewidth=1.0, zorder=3)
        ax.annotate(f"S{j}", (sx, sy), xytext=(8, -12), textcoords="offset points", fontsize=9, fontweight="bold",
                    color="#333333", zorder=3)

    fig.text(left / fig_w, 1 - 0.3 / fig_h, f"{scenario['name']} · seed {scenario['seed']} · engine "
             f"{scenario['engine']} · {len(scenario['supernodes'])} supernodes", fontsize=10, color="#555555",
             va="baseline")
    # The numbers follow the widest headline, so that they stay put from frame to frame.
    widest = f"tick {scenario['ticks']} / {scenario['ticks']}"
    headline = fig.text(left / fig_w, 1 - 0.72 / fig_h, widest, fontsize=17, fontweight="bold", va="baseline")
    headline_w = headline.get_window_extent(canvas.get_renderer()).width / dpi
    numbers = fig.text((left + headline_w + 0.35) / fig_w, 1 - 0.72 / fig_h, "", fontsize=14, va="baseline")

    # Per-tick indexes.
    ticks = list(range(options.first, options.last + 1))
    truth_at = {}
    for row in truth:
        truth_at.setdefault(row[0], {})[row[1]] = (row[2], row[3])
    track_at = {}
    for row in tracks:
        track_at.setdefault(row[0], {})[row[1]] = row
    first_seen = {}
    for row in tracks:
        first_seen.setdefault(row[1], row[0])
    colour_of = {ident: TRACK_COLOURS[n % len(TRACK_COLOURS)]
                 for n, ident in enumerate(sorted(first_seen, key=lambda i: (first_seen[i], i)))}
    delivered_at = {}
    for row in observations:
        if row[1] is not None:
            delivered_at.setdefault(row[1], []).append(row)
    per_ticks, k_true, k, ospa = per_tick

    # Side panel: legend, K and K* so far, OSPA so far.
    if side:
        side_left = left + map_w + side_gap
        side_w = fig_w - side_left - right
        chart_h, chart_gap = 1.55, 0.5
        legend_bottom = bottom + 2 * chart_h + chart_gap + 0.4
        legend_ax = fig.add_axes([side_left / fig_w, legend_bottom / fig_h, side_w / fig_w,
                                  (fig_h - top - legend_bottom) / fig_h])
        legend_ax.set_axis_off()
        handles = [
            Line2D([], [], linestyle="none", marker="o", markersize=11, markerfacecolor="none",
                   markeredgecolor="#333333", markeredgewidth=1.5, label="true target"),
            Line2D([], [], color=TRUTH_COLOUR, linewidth=5, alpha=0.5, solid_capstyle="round",
                   label=f"its last {options.trail} ticks"),
            Line2D([], [], color=TRACK_COLOURS[0], linewidth=1.8, marker="o", markersize=6,
                   markeredgecolor="white", markeredgewidth=0.8, label="track S:N (trail, estimate)"),
            Patch(facecolor=to_rgba(TRACK_COLOURS[0], 0.15), edgecolor=TRACK_COLOURS[0], linewidth=1.2,
                  label=f"{ELLIPSE_SIGMAS:g}σ position ellipse"),
            Line2D([], [], linestyle="none", marker="o", markersize=4, color=OBSERVATION_COLOUR,
                   label="report delivered in its tick"),
            Line2D([], [], linestyle="none", marker="o", markersize=5.5, markerfacecolor="none",
                   markeredgecolor=OBSERVATION_COLOUR, markeredgewidth=1.0, label="report delivered late"),
            Line2D([], [], linestyle="none", marker="x", markersize=5.5, color=FALSE_ALARM_COLOUR,
                   markeredgewidth=1.4, label="false alarm"),
            Line2D([], [], linestyle="none", marker="*", markersize=13, markerfacecolor="#ffd21f",
                   markeredgecolor="black", label="supernode Sj"),
            Patch(facecolor=REGION_COLOURS[0], edgecolor="#999999", label="its tracking group"),
            Line2D([], [], color="#555555", linestyle=(0, (6, 4)), linewidth=1.1, label="group boundary"),
        ]
        if xs:
            handles.append(Line2D([], [], linestyle="none", marker="o", markersize=3, markerfacecolor=SENSOR_COLOUR,
                                  markeredgewidth=0, label="sensor" if stride == 1 else f"sensor (1 in {stride})"))
        legend_ax.legend(handles=handles, loc="upper left", ncol=2, fontsize=9.5, frameon=False,
                         handlelength=2.2, columnspacing=1.2, labelspacing=0.75, borderaxespad=0)

        k_ax = fig.add_axes([side_left / fig_w, (bottom + chart_h + chart_gap) / fig_h, side_w / fig_w,
                             chart_h / fig_h])
        o_ax = fig.add_axes([side_left / fig_w, bottom / fig_h, side_w / fig_w, chart_h / fig_h], sharex=k_ax)
        for chart in (k_ax, o_ax):
            chart.set_xlim(0.5, scenario["ticks"] + 0.5)
            chart.grid(True, color="#e0e0e0", linewidth=0.6)
            chart.tick_params(labelsize=8.5)
        k_ax.tick_params(labelbottom=False)
        o_ax.set_xlabel("tick", fontsize=9, labelpad=1)
        _integer_axis(k_ax)
        k_ax.set_ylim(0, max([1] + k_true + k) * 1.15 + 0.5)
        k_ax.step(per_ticks, k_true, where="mid", color="black", linewidth=1.0, alpha=0.2)
        k_ax.step(per_ticks, k, where="mid", color="#0072B2", linewidth=1.0, alpha=0.25)
        k_true_line, = k_ax.step([], [], where="mid", color="black", linewidth=2.0, label="K*: targets")
        k_line, = k_ax.step([], [], where="mid", color="#0072B2", linewidth=1.6, linestyle="--", label="K: tracks")
        k_ax.legend(loc="lower left", bbox_to_anchor=(0, 1.0), ncol=2, fontsize=9, frameon=False, borderaxespad=0.2)
        valid = [(t, v) for t, v in zip(per_ticks, ospa) if v is not None]
        c = scenario["ospa_c"]
        o_ax.set_ylim(0, max([c if math.isfinite(c) else 0.0] + [v for _, v in valid] + [1.0]) * 1.12)
        if valid:
            o_ax.plot([t for t, _ in valid], [v for _, v in valid], color="#0072B2", linewidth=1.0, alpha=0.25)
        if math.isfinite(c):
            o_ax.axhline(c, color="#777777", linestyle="--", linewidth=0.9)
        ospa_line, = o_ax.plot([], [], color="#0072B2", linewidth=1.6,
                               label="OSPA" + (f" (cut-off c = {c:g})" if math.isfinite(c) else ""))
        o_ax.legend(loc="lower left", bbox_to_anchor=(0, 1.0), fontsize=9, frameon=False, borderaxespad=0.2)
        cursors = [chart.axvline(ticks[0], color="#D55E00", linewidth=1.2, alpha=0.8) for chart in (k_ax, o_ax)]

    # Dynamic artists, changed in place every frame.
    truth_trail = LineCollection([], linewidths=5, capstyle="round", zorder=4)
    ax.add_collection(truth_trail)
    truth_now, = ax.plot([], [], linestyle="none", marker="o", markersize=11, markerfacecolor="none",
                         markeredgecolor="#333333", markeredgewidth=1.5, zorder=5)
    track_trail = LineCollection([], linewidths=1.8, capstyle="round", zorder=6)
    ax.add_collection(track_trail)
    ellipses = PatchCollection([], zorder=6, linewidths=1.2, match_original=False)
    ax.add_collection(ellipses)
    track_now = ax.scatter([], [], s=36, edgecolors="white", linewidths=0.8, zorder=8)
    on_time, = ax.plot([], [], linestyle="none", marker="o", markersize=3.5, color=OBSERVATION_COLOUR, zorder=9)
    late, = ax.plot([], [], linestyle="none", marker="o", markersize=5, markerfacecolor="none",
                    markeredgecolor=OBSERVATION_COLOUR, markeredgewidth=0.9, zorder=9)
    false_alarms, = ax.plot([], [], linestyle="none", marker="x", markersize=5, color=FALSE_ALARM_COLOUR,
                            markeredgewidth=1.3, zorder=9)
    labels = []
    per_tick_index = {t: i for i, t in enumerate(per_ticks)}
    trail = options.trail
    truth_rgba = to_rgba(TRUTH_COLOUR)

    def fading(rgba, age, strength):
        """The colour of a trail segment `age` ticks old: fading out over the trail's length."""
        return rgba[:3] + (strength * (1.0 - age / (trail + 1)),)

    def trail_segments(positions_at, ident, t, rgba, strength, segments, colours):
        for age in range(trail):
            a, b = positions_at.get(t - age - 1, {}).get(ident), positions_at.get(t - age, {}).get(ident)
            if a is None or b is None:
                break
            segments.append(((a[0], a[1]), (b[0], b[1])))
            colours.append(fading(rgba, age, strength))

    track_xy_at = {tick: {ident: (row[2], row[3]) for ident, row in rows.items()} for tick, rows in track_at.items()}

    def draw(t):
        segments, colours = [], []
        now = truth_at.get(t, {})
        for ident in now:
            trail_segments(truth_at, ident, t, truth_rgba, 0.55, segments, colours)
        truth_trail.set_segments(segments)
        truth_trail.set_color(colours)
        truth_now.set_data([p[0] for p in now.values()], [p[1] for p in now.values()])

        rows = track_at.get(t, {})
        segments, colours, patches, edge, face = [], [], [], [], []
        for ident, row in rows.items():
            rgba = to_rgba(colour_of[ident])
            trail_segments(track_xy_at, ident, t, rgba, 1.0, segments, colours)
            axes = ellipse_axes(row[7], row[8], row[11])
            if axes:
                patches.append(Ellipse((row[2], row[3]), axes[0], axes[1], angle=axes[2]))
                edge.append(rgba)
                face.append(rgba[:3] + (0.15,))
        track_trail.set_segments(segments)
        track_trail.set_color(colours)
        ellipses.set_paths(patches)
        ellipses.set_edgecolor(edge)
        ellipses.set_facecolor(face)
        if rows:
            track_now.set_offsets([(row[2], row[3]) for row in rows.values()])
            track_now.set_facecolor([colour_of[ident] for ident in rows])
        else:
            track_now.set_offsets(np.empty((0, 2)))
        while labels:
            labels.pop().remove()
        for ident, row in rows.items():
            labels.append(ax.annotate(row[6], (row[2], row[3]), xytext=(6, 5), textcoords="offset points",
                                      fontsize=9, fontweight="bold", color=colour_of[ident], zorder=10,
                                      bbox=dict(boxstyle="round,pad=0.12", facecolor="white", edgecolor="none",
                                                alpha=0.75)))

        kinds = ([], [], [])
        for row in delivered_at.get(t, ()):
            kinds[2 if row[8] < 0 else 1 if row[0] < t else 0].append((row[6], row[7]))
        for line, points in zip((on_time, late, false_alarms), kinds):
            line.set_data([p[0] for p in points], [p[1] for p in points])

        headline.set_text(f"tick {t} / {scenario['ticks']}")
        i = per_tick_index.get(t)
        parts = []
        if i is not None:
            parts += [f"K* = {k_true[i]}", f"K = {k[i]}"]
            if ospa[i] is not None:
                parts.append(f"OSPA = {ospa[i]:.2f}")
        delivered = delivered_at.get(t, ())
        details = [f"{len(points)} {what}" for points, what in ((kinds[1], "late"), (kinds[2], "false"))
                   if points]
        parts.append(f"reports {len(delivered)}" + (f" ({', '.join(details)})" if details else ""))
        numbers.set_text("    ".join(parts))
        if numbers.get_window_extent(canvas.get_renderer()).x1 > (fig_w - 0.1) * dpi:
            # A narrow frame: the same without spaces and details.
            numbers.set_text("  ".join(part.replace(" = ", "=").split(" (")[0] for part in parts))
        if side:
            upto = per_tick_index.get(t, -1) + 1
            k_true_line.set_data(per_ticks[:upto], k_true[:upto])
            k_line.set_data(per_ticks[:upto], k[:upto])
            shown = [(tt, v) for tt, v in zip(per_ticks[:upto], ospa[:upto]) if v is not None]
            ospa_line.set_data([tt for tt, _ in shown], [v for _, v in shown])
            for cursor in cursors:
                cursor.set_xdata([t, t])

    # Everything drawn so far but the dynamic artists is the background of every frame: draw it
    # once, then per frame only the artists that change, which is what makes long runs quick.
    dynamic = [truth_trail, truth_now, track_trail, ellipses, track_now, on_time, late, false_alarms, headline,
               numbers]
    if side:
        dynamic += [k_true_line, k_line, ospa_line] + cursors
    for artist in dynamic:
        artist.set_animated(True)
    canvas.draw()
    background = canvas.copy_from_bbox(fig.bbox)
    renderer = canvas.get_renderer()

    def frame(t):
        draw(t)
        canvas.restore_region(background)
        for artist in sorted(dynamic + labels, key=lambda a: a.get_zorder()):
            artist.draw(renderer)
        return np.asarray(canvas.buffer_rgba())

    sink = options.make_sink()
    samples = getattr(sink, "SAMPLES", 0)
    if samples:
        picks = sorted({ticks[(len(ticks) - 1) * k // max(1, samples - 1)] for k in range(samples)})
        sink.set_samples([frame(t).copy() for t in picks])
    progress = Progress(len(ticks), options.quiet)
    for n, t in enumerate(ticks, 1):
        sink.add(frame(t), t)
        progress.show(n, "drew")
    if not options.quiet:
        print(f"plot_run.py: encoding {len(ticks)} frames", file=sys.stderr, flush=True)
    sink.finish()
    return len(ticks)


def load_matplotlib(dpi, warm_up):
    """(matplotlib, None), or (None, the ImportError) when it cannot be imported."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.figure
        from matplotlib.backends.backend_agg import FigureCanvasAgg
    except ImportError as error:
        return None, error
    # No pyplot: its import and figure manager are a third of the start-up and not needed here.
    matplotlib.rcParams.update({"savefig.dpi": dpi, "svg.fonttype": "none", "font.size": 10})
    if warm_up:
        # Loads the fonts and the renderer while there is time to spare.
        fig = matplotlib.figure.Figure(figsize=(1, 1))
        fig.add_subplot().set_title("warm-up")
        FigureCanvasAgg(fig).draw()
    return matplotlib, None


ANIMATION_DEFAULTS = {"fps": 5, "size": "1280x720", "trail": 10, "hold": 1.0}


def main(argv):
    parser = argparse.ArgumentParser(prog="plot_run.py", description=DESCRIPTION,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dir", metavar="RUN_DIR", help="a run directory written by 'wsntrack run'")
    parser.add_argument("--format", choices=("png", "svg"), help="image format of the plots (default png)")
    parser.add_argument("--out", metavar="PATH",
                        help="where the plots go (a directory, default RUN_DIR/plots); with --animate a file "
                             "ending in .gif, .mp4 or .html, or a directory for replay.FORMAT (default "
                             "RUN_DIR/plots/replay.FORMAT)")
    parser.add_argument("--dpi", type=int, help="resolution of PNG files (default 150)")
    parser.add_argument("--wait", action="store_true",
                        help="load matplotlib first, then wait for a line 'go' on stdin before reading RUN_DIR "
                             "(any other line, or the end of stdin: exit 0 without plotting). 'wsntrack run' "
                             "starts the script this way with the cluster, so that loading overlaps the run")
    group = parser.add_argument_group("animation ('wsntrack replay RUN_DIR [OPTION]...' runs plot_run.py "
                                      "--animate RUN_DIR [OPTION]...)")
    group.add_argument("--animate", action="store_true",
                       help="write an animation of the run instead of the plots: one frame per tick")
    group.add_argument("--animate-format", choices=ANIMATION_FORMATS,
                       help="gif (Pillow), mp4 (H.264, needs ffmpeg) or html (one self-contained page with a "
                            "player); default: the suffix of --out, else gif")
    group.add_argument("--fps", type=float, help=f"frames (ticks) per second (default {ANIMATION_DEFAULTS['fps']})")
    group.add_argument("--size", metavar="WxH",
                       help=f"frame size in pixels, rounded down to even numbers (default {ANIMATION_DEFAULTS['size']})")
    group.add_argument("--first", type=int, metavar="TICK", help="first tick drawn (default 1)")
    group.add_argument("--last", type=int, metavar="TICK", help="last tick drawn (default the run's last, T)")
    group.add_argument("--trail", type=int, metavar="TICKS",
                       help=f"length of the fading trails of targets and tracks (default {ANIMATION_DEFAULTS['trail']})")
    group.add_argument("--hold", type=float, metavar="SECONDS",
                       help=f"how long GIF and MP4 show the last frame before they end or loop "
                            f"(default {ANIMATION_DEFAULTS['hold']:g})")
    group.add_argument("--quiet", action="store_true", help="no progress on stderr")
    args = parser.parse_args(argv)
    animation_options = ("animate_format", "fps", "size", "first", "last", "trail", "hold")
    if args.animate:
        for name, instead in (("format", "--animate-format"), ("dpi", "--size"), ("wait", None)):
            if getattr(args, name):
                parser.error(f"--{name} draws the still plots, not --animate"
                             + (f": use {instead}" if instead else ""))
        return animate_main(parser, args)
    for name in animation_options + ("quiet",):
        if getattr(args, name) not in (None, False):
            parser.error(f"--{name.replace('_', '-')} needs --animate")
    args.format = args.format or "png"
    args.dpi = 150 if args.dpi is None else args.dpi
    if not 20 <= args.dpi <= 1200:
        parser.error("--dpi must be in [20, 1200]")
    if args.wait:
        matplotlib, import_error = load_matplotlib(args.dpi, warm_up=True)
        if sys.stdin.readline().strip() != "go":
            return 0
    started = time.monotonic()
    run_dir = Path(args.run_dir)
    out_dir = Path(args.out) if args.out else run_dir / "plots"
    try:
        if not run_dir.is_dir():
            raise InputError(f"{run_dir}: not a directory")
        scenario = read_scenario(run_dir)
        truth, truth_classes = read_truth(run_dir / "truth.csv")
        tracks, _, _ = read_tracks(run_dir / "tracks.csv")
        sensors = read_sensors(run_dir, scenario)
        ticks, k_true, k, ospa, source = read_per_tick(run_dir, scenario, truth, tracks)
        summary = read_metrics_summary(run_dir)
        observations = few_observations(run_dir / "observations.csv")
        detections = read_detections(run_dir, scenario, truth) if scenario["sensor_kind"] == "adman" else None
    except InputError as error:
        print(f"plot_run.py: {error}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except ToolMissing as error:
        print(f"plot_run.py: {error}", file=sys.stderr)
        return EXIT_TOOL_MISSING

    if not args.wait:
        matplotlib, import_error = load_matplotlib(args.dpi, warm_up=False)
    if matplotlib is None:
        print(f"plot_run.py: matplotlib is not available to {sys.executable} ({import_error}); "
              "on Debian: apt-get install python3-matplotlib", file=sys.stderr)
        return EXIT_TOOL_MISSING

    try:
        out_dir.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        print(f"plot_run.py: {out_dir}: cannot create ({error.strerror})", file=sys.stderr)
        return EXIT_BAD_INPUT
    written = []
    plots = [("tracks", lambda path: plot_tracks(matplotlib, scenario, sensors, truth, tracks, summary, path,
                                                 observations, truth_classes)),
             ("cardinality", lambda path: plot_cardinality(matplotlib, scenario, ticks, k_true, k, summary, path)),
             ("ospa", lambda path: plot_ospa(matplotlib, scenario, ticks, ospa, source, path))]
    if detections is not None:
        plots.append(("detections", lambda path: plot_detections(matplotlib, scenario, detections, path)))
    for name, draw in plots:
        path = out_dir / f"{name}.{args.format}"
        try:
            draw(path)
        except OSError as error:
            print(f"plot_run.py: {path}: cannot write ({error.strerror})", file=sys.stderr)
            return EXIT_BAD_INPUT
        written.append(str(path))
    print(f"plot_run.py: wrote {', '.join(written)} in {time.monotonic() - started:.2f} s")
    return 0


class AnimationOptions:
    """What animate() needs besides the run: ticks, trail, frame size, progress and the output."""

    def __init__(self, **fields):
        self.__dict__.update(fields)


def animate_main(parser, args):
    """plot_run.py --animate: checks, reads, draws and writes; returns the exit status."""
    started = time.monotonic()
    for name, value in ANIMATION_DEFAULTS.items():
        if getattr(args, name) is None:
            setattr(args, name, value)
    if not 0.1 <= args.fps <= 60:
        parser.error(f"--fps must be in [0.1, 60], got {args.fps:g}")
    if not 0 <= args.trail <= 1000:
        parser.error(f"--trail must be in [0, 1000], got {args.trail}")
    if not 0 <= args.hold <= 60:
        parser.error(f"--hold must be in [0, 60] seconds, got {args.hold:g}")
    try:
        size = parse_size(args.size)
    except ValueError as error:
        parser.error(str(error))
    run_dir = Path(args.run_dir)
    try:
        path, chosen = animation_target(args.out, run_dir, args.animate_format)
        if not run_dir.is_dir():
            raise InputError(f"{run_dir}: not a directory")
        scenario = read_scenario(run_dir)
        first = 1 if args.first is None else args.first
        last = scenario["ticks"] if args.last is None else args.last
        if not 1 <= first <= last <= scenario["ticks"]:
            raise InputError(f"--first {first} --last {last}: the ticks drawn must satisfy "
                             f"1 <= first <= last <= {scenario['ticks']} (the run's ticks)")
        truth = read_csv(run_dir / "truth.csv", ["tick", "target", "x", "y", "vx", "vy"],
                         [int, int, float, float, float, float])
        tracks, _, _ = read_tracks(run_dir / "tracks.csv")
        observations = read_observations(run_dir / "observations.csv")
        sensors = read_sensors(run_dir, scenario)
        ticks, k_true, k, ospa, _ = read_per_tick(run_dir, scenario, truth, tracks)
    except InputError as error:
        print(f"plot_run.py: {error}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except ToolMissing as error:
        print(f"plot_run.py: {error}", file=sys.stderr)
        return EXIT_TOOL_MISSING

    matplotlib, import_error = load_matplotlib(100, warm_up=False)
    if matplotlib is None:
        print(f"plot_run.py: matplotlib is not available to {sys.executable} ({import_error}); "
              "on Debian: apt-get install python3-matplotlib", file=sys.stderr)
        return EXIT_TOOL_MISSING
    try:
        import importlib
        for module in ("numpy", "PIL.Image"):  # matplotlib needs both too, but not at import
            importlib.import_module(module)
    except ImportError as error:
        print(f"plot_run.py: --animate needs numpy and Pillow, which {sys.executable} lacks ({error}); "
              "on Debian: apt-get install python3-numpy python3-pil", file=sys.stderr)
        return EXIT_TOOL_MISSING
    ffmpeg = None
    if chosen == "mp4":
        import shutil
        ffmpeg = shutil.which("ffmpeg")
        if ffmpeg is None:
            print("plot_run.py: an MP4 needs ffmpeg, which is not on PATH; on Debian: apt-get install ffmpeg "
                  "(or write a GIF or an HTML page: --animate-format gif|html)", file=sys.stderr)
            return EXIT_TOOL_MISSING

    # Written under a temporary name and renamed when complete: a failed or interrupted render
    # never leaves a truncated animation behind under the real name.
    partial = path.with_name(f".{path.name}.{os.getpid()}.partial")

    def make_sink():
        if chosen == "gif":
            return GifSink(partial, args.fps, args.hold)
        if chosen == "mp4":
            return Mp4Sink(partial, args.fps, size, args.hold, ffmpeg)
        return HtmlSink(partial, args.fps, size, f"{scenario['name']}, seed {scenario['seed']}: ticks {first}-{last}")

    options = AnimationOptions(first=first, last=last, trail=args.trail, size=size, quiet=args.quiet,
                               make_sink=make_sink)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        frames = animate(matplotlib, scenario, sensors, truth, tracks, observations,
                         (ticks, k_true, k, ospa), options)
        os.replace(partial, path)
    except OSError as error:
        print(f"plot_run.py: {error.filename or path}: cannot write ({error.strerror})", file=sys.stderr)
        return EXIT_BAD_INPUT
    except EncoderError as error:
        print(f"plot_run.py: {path}: {error}", file=sys.stderr)
        return 1
    finally:
        if partial.exists():
            partial.unlink()
    print(f"plot_run.py: wrote {path} ({frames} frames, ticks {first}-{last}, {size[0]}x{size[1]}, "
          f"{args.fps:g} fps) in {time.monotonic() - started:.1f} s")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except KeyboardInterrupt:
        sys.exit(130)
