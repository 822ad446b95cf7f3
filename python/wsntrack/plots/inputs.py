"""What the plots read from a run directory besides the files every tool reads (wsntrack.rundir):
the sensors to draw (a sample of a large field), the few reports drawn on the tracks map, and the
ADMAN sensors' detection counts."""

import math
import sys

from ..rundir import InputError, grid_sensors, grid_shape, read_csv, read_observations, read_table

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
    columns, rows = grid_shape(scenario)
    stride = max(1, math.ceil(math.sqrt(columns * rows / MAX_SENSORS_DRAWN)))
    xs, ys = grid_sensors(scenario, stride)
    return xs, ys, stride * stride


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
