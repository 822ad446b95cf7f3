"""A run's scenario.yaml: read by PyYAML's safe loader with the line of every key kept, so that a
value read later can still be reported as FILE:LINE, and summarised into what the plots and the
loader draw on (region, sensors, supernodes, terrain, typed sensors, ticks, OSPA parameters)."""

import math
import sys

from .tables import InputError, ToolMissing, require
from .. import catalogue

# Imported here rather than when scenario.yaml is read: under 'wsntrack run' (plot_run.py --wait)
# the import then overlaps the run. Without it the tools still start, to report it as a missing tool.
try:
    import yaml
    _YAML_IMPORT_ERROR = None
except ImportError as error:
    yaml = None
    _YAML_IMPORT_ERROR = str(error)


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
    except RecursionError:  # PyYAML's composer recurses once per level of nesting
        raise InputError(f"{path}: malformed YAML (nested deeper than the reader follows)") from None
    finally:
        if loader is not None:
            loader.dispose()
    return data


# ---------------------------------------------------------------------------------------------
# Run-directory inputs


def read_scenario(run_dir):
    """The summary of RUN_DIR/scenario.yaml the tools draw on: name, region, terrain, sensor layout
    and spacing, supernodes, ticks, seed, engine, sensor model kind, typed sensors, OSPA c and p, and
    the whole "document" as yaml.safe_load reads it. Raises InputError (FILE:LINE: what was
    expected) for a missing or malformed file or value, ToolMissing without PyYAML."""
    path = run_dir / "scenario.yaml"
    require(path)
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
        "document": data,
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


def sensor_types():
    """The sensor types of the sensor models (ONERA Table I's of field_sensors), in the catalogue's
    order, each with its defaults (range, fov_deg, ...: the coverage of a sensor whose entry and type
    section give none). wsntrack.plots.field gives each its colour and marker."""
    return {name: defaults for model in catalogue.load()["sensor_models"]
            for name, defaults in model["sensor_types"].items()}


def __getattr__(name):
    if name == "SENSOR_TYPES":  # the table as a constant, as this module has always exported it
        return sensor_types()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


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
    types = sensor_types()
    model = data.get("sensor_model")
    model = model if isinstance(model, dict) else {}
    coverage = {}  # per sensor type: (range, fov), read when a sensor of the type is met

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
                values.append(types[kind][key])
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
        if kind is not None and kind not in types:
            raise InputError(f"{at('sensors', 'list', i, 'type')}: sensors.list[{i}].type must be one of "
                             f"{', '.join(types)}, got '{kind}'")
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


def grid_shape(scenario):
    """(columns, rows) of a grid layout's sensors, as common/sensor_layout.cpp lays them out: one
    sensor at the centre of every whole cell of the region."""
    x0, y0, x1, y1 = scenario["region"]
    spacing = scenario["spacing"]
    return int(math.floor((x1 - x0) / spacing + 1e-9)), int(math.floor((y1 - y0) / spacing + 1e-9))


def grid_sensors(scenario, stride=1):
    """(xs, ys) of a grid layout's sensors row by row, as sensor ids go; with `stride`, only every
    stride-th row and column of them."""
    x0, y0, _, _ = scenario["region"]
    spacing = scenario["spacing"]
    columns, rows = grid_shape(scenario)
    xs, ys = [], []
    for r in range(0, rows, stride):
        for c in range(0, columns, stride):
            xs.append(x0 + (c + 0.5) * spacing)
            ys.append(y0 + (r + 0.5) * spacing)
    return xs, ys
