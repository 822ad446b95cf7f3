#!/usr/bin/python3
"""Plots of one wsntrack run directory: tracks against the truth on the sensor field, the number
of tracks K and of targets K* over time, and OSPA over time.

Needs Debian's python3-matplotlib, hence /usr/bin/python3 rather than whatever python3 is first
on PATH. Everything else is the standard library; the run's scenario.yaml is read by a small
reader of the subset of YAML that wsntrack writes, so PyYAML is not needed.
"""

import argparse
import csv
import json
import math
import os
import sys
import time
from pathlib import Path

EXIT_BAD_INPUT = 2
EXIT_NO_MATPLOTLIB = 3

DESCRIPTION = """\
Draws the plots of a wsntrack run directory (what 'wsntrack run' does after every run unless
--no-plot is given):

  tracks.FORMAT       the estimated global tracks (tracks.csv) against the true target paths
                      (truth.csv) on the sensor field: sensors, supernodes and their tracking
                      groups (the Voronoi cells of the supernodes: every sensor reports to its
                      nearest supernode), like Oh et al. Fig. 9 (right)
  cardinality.FORMAT  K, the number of tracks, and K*, the number of targets, at every tick
                      (the terms of eps_K, Oh eq. 9)
  ospa.FORMAT         OSPA at every tick, with its cut-off c

Lengths are in the scenario's units (sensor separations when the grid spacing is 1), times in ticks. Reads scenario.yaml, truth.csv, tracks.csv,
metrics_per_tick.csv (else metrics.json's metrics.ospa_per_tick) and sensors.csv when present
(else the sensor grid is computed from scenario.yaml).

Exit status: 0 on success, 2 for a bad command line or a missing or malformed input file
(reported as FILE:LINE: what was expected), 3 when matplotlib is not available to this python.
"""


class InputError(Exception):
    """A missing or malformed input file: reported as one line, exit status 2."""


# ---------------------------------------------------------------------------------------------
# scenario.yaml: wsntrack writes block mappings, block lists of flow mappings, flow mappings and
# plain or double-quoted scalars. Anything outside that subset is reported, not guessed at.


def _strip_comment(line):
    quoted = False
    escaped = False
    for i, c in enumerate(line):
        if escaped:
            escaped = False
        elif c == "\\" and quoted:
            escaped = True
        elif c == '"':
            quoted = not quoted
        elif c == "#" and not quoted and (i == 0 or line[i - 1] in " \t"):
            return line[:i]
    return line


def _split_flow(text, where):
    """Splits the inside of {...} or [...] at top-level commas."""
    items, depth, quoted, escaped, start = [], 0, False, False, 0
    for i, c in enumerate(text):
        if escaped:
            escaped = False
        elif quoted:
            if c == "\\":
                escaped = True
            elif c == '"':
                quoted = False
        elif c == '"':
            quoted = True
        elif c in "[{":
            depth += 1
        elif c in "]}":
            depth -= 1
            if depth < 0:
                raise InputError(f"{where}: unbalanced '{c}'")
        elif c == "," and depth == 0:
            items.append(text[start:i].strip())
            start = i + 1
    if quoted or depth != 0:
        raise InputError(f"{where}: unterminated flow collection or string")
    last = text[start:].strip()
    if last or items:
        items.append(last)
    return items


def _split_key(text, where):
    """'key: value' -> (key, value or ''); the key may be double-quoted."""
    if text.startswith('"'):
        end = 1
        while end < len(text) and (text[end] != '"' or text[end - 1] == "\\"):
            end += 1
        if end >= len(text) or not text[end + 1:].startswith(":"):
            raise InputError(f"{where}: expected '\"key\": value', got '{text}'")
        return _scalar(text[: end + 1], where), text[end + 2:].strip()
    colon = text.find(": ")
    if colon < 0 and text.endswith(":"):
        colon = len(text) - 1
    if colon <= 0:
        raise InputError(f"{where}: expected 'key: value', got '{text}'")
    return text[:colon].strip(), text[colon + 1:].strip()


def _scalar(text, where):
    if text.startswith("{"):
        if not text.endswith("}"):
            raise InputError(f"{where}: unterminated flow mapping '{text}'")
        result = {}
        for item in _split_flow(text[1:-1], where):
            key, value = _split_key(item, where)
            result[key] = _scalar(value, where)
        return result
    if text.startswith("["):
        if not text.endswith("]"):
            raise InputError(f"{where}: unterminated flow list '{text}'")
        return [_scalar(item, where) for item in _split_flow(text[1:-1], where)]
    if text.startswith('"'):
        if len(text) < 2 or not text.endswith('"'):
            raise InputError(f"{where}: unterminated string {text}")
        body = text[1:-1].replace("\\x", "\\u00")
        try:
            return json.loads('"' + body + '"')
        except ValueError:
            raise InputError(f"{where}: malformed string {text}") from None
    if text in ("", "~", "null", "Null", "NULL"):
        return None
    if text in ("true", "True", "TRUE"):
        return True
    if text in ("false", "False", "FALSE"):
        return False
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    lowered = text.lower()
    if lowered in (".inf", "+.inf"):
        return math.inf
    if lowered == "-.inf":
        return -math.inf
    if lowered == ".nan":
        return math.nan
    return text


def parse_yaml_subset(text, path, where=None):
    """The YAML document in `text`; when `where` is a dict it receives the line of every key and
    list item, keyed by its path (a tuple of keys and indices), for messages about values."""
    where = {} if where is None else where
    lines = []
    for number, raw in enumerate(text.splitlines(), 1):
        content = _strip_comment(raw).rstrip()
        if not content.strip() or content.strip() == "---":
            continue
        body = content.lstrip(" ")
        if body.startswith("\t"):
            raise InputError(f"{path}:{number}: tabs are not allowed for indentation")
        lines.append((number, len(content) - len(body), body))
    position = 0

    def note(keys, number, value):
        where[keys] = number
        if isinstance(value, dict):
            for key, item in value.items():
                note(keys + (key,), number, item)
        elif isinstance(value, list):
            for index, item in enumerate(value):
                note(keys + (index,), number, item)

    def block(indent, keys):
        nonlocal position
        number, _, body = lines[position]
        if body == "-" or body.startswith("- "):
            items = []
            while position < len(lines) and lines[position][1] == indent and lines[position][2].startswith("-"):
                number, _, body = lines[position]
                if body != "-" and not body.startswith("- "):
                    raise InputError(f"{path}:{number}: expected '- item', got '{body}'")
                position += 1
                rest = body[1:].strip()
                item_keys = keys + (len(items),)
                where[item_keys] = number
                if rest:
                    items.append(_scalar(rest, f"{path}:{number}"))
                    note(item_keys, number, items[-1])
                elif position < len(lines) and lines[position][1] > indent:
                    items.append(block(lines[position][1], item_keys))
                else:
                    items.append(None)
            return items
        mapping = {}
        while position < len(lines) and lines[position][1] == indent:
            number, _, body = lines[position]
            if body.startswith("- "):
                raise InputError(f"{path}:{number}: expected 'key: value', got a list item")
            key, rest = _split_key(body, f"{path}:{number}")
            if key in mapping:
                raise InputError(f"{path}:{number}: duplicate key '{key}'")
            position += 1
            where[keys + (key,)] = number
            if rest:
                mapping[key] = _scalar(rest, f"{path}:{number}")
                note(keys + (key,), number, mapping[key])
            elif position < len(lines) and lines[position][1] > indent:
                mapping[key] = block(lines[position][1], keys + (key,))
            elif position < len(lines) and lines[position][1] == indent and lines[position][2].startswith("- "):
                mapping[key] = block(indent, keys + (key,))  # a list may sit at its key's own indentation
            else:
                mapping[key] = None
        return mapping

    if not lines:
        raise InputError(f"{path}:1: empty file, expected a scenario mapping")
    result = block(lines[0][1], ())
    if position < len(lines):
        number, _, body = lines[position]
        raise InputError(f"{path}:{number}: unexpected indentation of '{body}'")
    if not isinstance(result, dict):
        raise InputError(f"{path}:{lines[0][0]}: expected a mapping at the top level")
    return result


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


def read_csv(path, header, types):
    """Rows of a CSV file with exactly `header`, converted column by column with `types`."""
    _require(path)
    rows = []
    with open(path, newline="", encoding="utf-8", errors="replace") as handle:
        reader = csv.reader(handle)
        try:
            first = next(reader, None)
            if first is None or first != header:
                got = "an empty file" if first is None else "'" + ",".join(first) + "'"
                raise InputError(f"{path}:1: expected the header '{','.join(header)}', got {got}")
            for row in reader:
                line = reader.line_num
                if not row:
                    continue
                if len(row) != len(header):
                    raise InputError(
                        f"{path}:{line}: expected {len(header)} fields ({','.join(header)}), got {len(row)}")
                rows.append(tuple(_number(v, path, line, c, t) if t else v for v, c, t in zip(row, header, types)))
        except csv.Error as error:
            raise InputError(f"{path}:{reader.line_num}: malformed CSV ({error})") from None
    return rows


def read_scenario(run_dir):
    path = run_dir / "scenario.yaml"
    _require(path)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as error:
        raise InputError(f"{path}: cannot read ({error})") from None
    lines = {}
    data = parse_yaml_subset(text, path, lines)

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
    if layout not in ("grid", "random"):
        raise InputError(f"{at('sensors', 'layout')}: 'sensors.layout' must be grid or random, got '{layout}'")
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
    return {
        "name": get("name", kind=str, default="?"),
        "region": region,
        "layout": layout,
        "spacing": spacing,
        "supernodes": supernodes,
        "ticks": get("run", "ticks", kind=int),
        "seed": get("run", "seed", kind=str, default="?"),
        "engine": get("tracker", "engine", kind=str, default="?"),
        "ospa_c": get("metrics", "ospa_c", default=math.nan),
        "ospa_p": get("metrics", "ospa_p", default=math.nan),
    }


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
        print(f"plot_run.py: {path} missing: the random sensor layout is not drawn", file=sys.stderr)
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


def plot_tracks(mpl, scenario, sensors, truth, tracks, summary, out_path):
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

    cells = voronoi_cells(scenario["supernodes"], scenario["region"])
    for j, polygon in enumerate(cells):
        if polygon:
            ax.add_patch(Polygon(polygon, closed=True, facecolor=REGION_COLOURS[j % len(REGION_COLOURS)],
                                 edgecolor="none", zorder=0))
    ax.add_patch(Polygon([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], closed=True, fill=False, edgecolor="black",
                         linewidth=0.8, zorder=1))

    xs, ys, stride = sensors
    if xs:
        # A marker line, not scatter: one path drawn many times is ~10x faster than a collection.
        size = math.sqrt(max(0.3, min(4.0, 2500.0 / len(xs))))
        ax.plot(xs, ys, linestyle="none", marker="o", markersize=size, markerfacecolor="#b4b4b4",
                markeredgewidth=0, zorder=1, rasterized=True)

    edges = interior_edges(cells, scenario["region"])
    for p, q in edges:
        ax.plot([p[0], q[0]], [p[1], q[1]], color="#444444", linestyle=(0, (6, 4)), linewidth=1.3, zorder=2)

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
            ax.annotate(f"{first}–{last}", (px[0], py[0]), xytext=(-7 if right else 7, -7 if top else 5),
                        textcoords="offset points", fontsize=9, color="#222222", zorder=7,
                        ha="right" if right else "left", va="top" if top else "bottom",
                        bbox=dict(boxstyle="round,pad=0.15", facecolor="white", edgecolor="none", alpha=0.75))

    track_paths = paths_by_id(tracks, 1)
    order = sorted(track_paths, key=lambda i: (track_paths[i][2], i))
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
               label="target appears (label: appear–last tick)" if label_targets else "target appears"),
        Line2D([], [], color=TRACK_COLOURS[0], linewidth=1.6, marker="o", markersize=2.6,
               label="estimated track (one colour" + (" and dash" if len(order) > len(TRACK_COLOURS) else "")
               + " per track)"),
        Line2D([], [], linestyle="none", marker="*", markersize=16, markerfacecolor="#ffd21f",
               markeredgecolor="black", label="supernode Sj"),
        Patch(facecolor=REGION_COLOURS[0], edgecolor="#999999", label="tracking group of one supernode"),
    ]
    if edges:
        handles.append(Line2D([], [], color="#444444", linestyle=(0, (6, 4)), linewidth=1.3,
                              label="tracking-group boundary (nearest supernode)"))
    if xs:
        handles.append(Line2D([], [], linestyle="none", marker="o", markersize=4, markerfacecolor="#b4b4b4",
                              markeredgewidth=0,
                              label="sensor" if stride == 1 else f"sensor (1 in {stride} drawn)"))
    # Below the map rather than on it, so that no track is hidden; a fixed distance in points
    # clears the tick labels and the x label whatever the map's aspect ratio.
    below = offset_copy(ax.transAxes, fig=fig, y=-44, units="points")
    ax.legend(handles=handles, loc="upper center", ncol=2, fontsize=10, frameon=False,
              bbox_to_anchor=(0.5, 0.0), bbox_transform=below, handlelength=3)
    fig.savefig(out_path)


def _integer_axis(ax):
    from matplotlib.ticker import MaxNLocator
    ax.yaxis.set_major_locator(MaxNLocator(integer=True))


def plot_cardinality(mpl, scenario, ticks, k_true, k, summary, out_path):
    fig, ax = new_figure(mpl, 10, 4.4, left=0.75, right=0.2, bottom=0.6, top=0.85)
    ax.fill_between(ticks, k_true, k, step="mid", color="#D55E00", alpha=0.18, linewidth=0,
                    label="|K − K*| (error counted by εK)")
    ax.step(ticks, k_true, where="mid", color="black", linewidth=2.4, label="K*: targets (truth)")
    ax.step(ticks, k, where="mid", color="#0072B2", linewidth=1.6, linestyle="--", label="K: tracks (estimate)")
    ax.set_xlim(0.5, scenario["ticks"] + 0.5)
    ax.set_ylim(0, max([1] + k_true + k) * 1.05 + 0.5)
    _integer_axis(ax)
    ax.set_xlabel("tick", fontsize=11)
    ax.set_ylabel("number of targets / tracks", fontsize=11)
    ax.grid(True, color="#dddddd", linewidth=0.6)
    title = "Number of targets K* and of tracks K (Oh et al. eq. 9)"
    if "eps_k" in summary:
        title += f": εK = {summary['eps_k']:.3f}"
    # Legend between title and axes: it can then never hide a curve.
    ax.set_title(title, fontsize=12, pad=30)
    ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), ncol=3, fontsize=10, frameon=False)
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


def main(argv):
    parser = argparse.ArgumentParser(prog="plot_run.py", description=DESCRIPTION,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dir", metavar="RUN_DIR", help="a run directory written by 'wsntrack run'")
    parser.add_argument("--format", choices=("png", "svg"), default="png", help="image format (default png)")
    parser.add_argument("--out", metavar="DIR", help="where the plots go (default RUN_DIR/plots)")
    parser.add_argument("--dpi", type=int, default=150, help="resolution of PNG files (default 150)")
    parser.add_argument("--wait", action="store_true",
                        help="load matplotlib first, then wait for a line 'go' on stdin before reading RUN_DIR "
                             "(any other line, or the end of stdin: exit 0 without plotting). 'wsntrack run' "
                             "starts the script this way with the cluster, so that loading overlaps the run")
    args = parser.parse_args(argv)
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
        truth = read_csv(run_dir / "truth.csv", ["tick", "target", "x", "y", "vx", "vy"],
                         [int, int, float, float, float, float])
        tracks = read_csv(run_dir / "tracks.csv", ["tick", "track", "x", "y", "vx", "vy"],
                          [int, int, float, float, float, float])
        sensors = read_sensors(run_dir, scenario)
        ticks, k_true, k, ospa, source = read_per_tick(run_dir, scenario, truth, tracks)
        summary = read_metrics_summary(run_dir)
    except InputError as error:
        print(f"plot_run.py: {error}", file=sys.stderr)
        return EXIT_BAD_INPUT

    if not args.wait:
        matplotlib, import_error = load_matplotlib(args.dpi, warm_up=False)
    if matplotlib is None:
        print(f"plot_run.py: matplotlib is not available to {sys.executable} ({import_error}); "
              "on Debian: apt-get install python3-matplotlib", file=sys.stderr)
        return EXIT_NO_MATPLOTLIB

    try:
        out_dir.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        print(f"plot_run.py: {out_dir}: cannot create ({error.strerror})", file=sys.stderr)
        return EXIT_BAD_INPUT
    written = []
    for name, draw in (
            ("tracks", lambda path: plot_tracks(matplotlib, scenario, sensors, truth, tracks, summary, path)),
            ("cardinality", lambda path: plot_cardinality(matplotlib, scenario, ticks, k_true, k, summary, path)),
            ("ospa", lambda path: plot_ospa(matplotlib, scenario, ticks, ospa, source, path))):
        path = out_dir / f"{name}.{args.format}"
        try:
            draw(path)
        except OSError as error:
            print(f"plot_run.py: {path}: cannot write ({error.strerror})", file=sys.stderr)
            return EXIT_BAD_INPUT
        written.append(str(path))
    print(f"plot_run.py: wrote {', '.join(written)} in {time.monotonic() - started:.2f} s")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except KeyboardInterrupt:
        sys.exit(130)
