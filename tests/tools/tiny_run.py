#!/usr/bin/python3
"""Writes a tiny hand-made wsntrack run directory (no DDS, no cluster) for the tests of
tools/plot_run.py --animate and tools/wsntrack_run.py, whose values the loader test checks exactly.

Usage: tiny_run.py DIR [--old]   (--old: tracks files without label and covariance columns, as
wsntrack wrote them before both were added)
"""

import sys
from pathlib import Path

# A 20 x 10 grid, two supernodes (one boundary at x = 10), 10 ticks; target 0 crosses the
# boundary from tick 1, target 1 appears at tick 4 and moves left.
SCENARIO = """\
# wsntrack resolved scenario (a small hand-made one)
name: "tiny"
region:
  x_min: 0
  y_min: 0
  x_max: 20
  y_max: 10
sensors:
  layout: grid
  spacing: 1
  count: 200
targets:
  scripted:
    - {appear_tick: 1, disappear_tick: 0, x: 1, y: 1, vx: 1, vy: 0.5}
    - {appear_tick: 4, disappear_tick: 0, x: 16.5, y: 8, vx: -1, vy: 0}
dynamics:
  delta: 1
supernodes:
  - {x: 5, y: 5}
  - {x: 15, y: 5}
tracker:
  engine: "gnn"
  params: {}
metrics:
  ospa_c: 5
  ospa_p: 2
run:
  ticks: 10
  seed: 3
"""

TICKS = 10
COVARIANCE = ["p_xx", "p_xy", "p_xvx", "p_xvy", "p_yy", "p_yvx", "p_yvy", "p_vxvx", "p_vxvy", "p_vyvy"]
ID_0_1 = (1 << 48) | 1  # serial 1 of supernode 0: label 0:1
ID_1_1 = (2 << 48) | 1  # serial 1 of supernode 1: label 1:1
ID_G5 = 5  # minted by the aggregator: label g5


def truth_rows():
    for t in range(1, TICKS + 1):
        yield (t, 0, float(t), 1.0 + t / 2, 1.0, 0.5)
        if t >= 4:
            yield (t, 1, 20.5 - t, 8.0, -1.0, 0.0)


def covariance(t, track):
    """A valid covariance that grows with t: p_xx, p_xy, ..., p_vyvy."""
    s = 0.1 * t + (0.5 if track == ID_1_1 else 0.0)
    return (s, 0.3 * s, 0.1, 0.0, 2 * s, 0.0, 0.1, 0.2, 0.0, 0.2)


def track_rows():
    """(tick, supernode, track, label, x, y, vx, vy, covariance...) for the supernodes' and the
    global tracks alike (the aggregator here simply passes them on)."""
    for t in range(2, TICKS + 1):
        yield (t, 0 if t < 10 else 1, ID_0_1, "0:1", t + 0.1, 1.2 + t / 2, 1.0, 0.5) + covariance(t, ID_0_1)
        if t >= 6 and t != 8:
            yield (t, 1, ID_1_1, "1:1", 20.3 - t, 7.8, -1.0, 0.0) + covariance(t, ID_1_1)
        if t == 5:
            yield (t, 1, ID_G5, "g5", 3.0, 9.0, 0.0, 0.0) + (0.0,) * 10  # covariance unknown


def observation_rows():
    """tick_generated,tick_delivered,sensor,supernode,hops,delay,x,y,target,fate."""
    rows = []
    for t in range(1, TICKS + 1):
        x, y = float(t), 1.0 + t / 2
        sensor = int(y) * 20 + int(x)
        supernode = 0 if x < 10 else 1
        if t % 4 == 3:
            rows.append((t, t + 1, sensor, supernode, 2, 1, x + 0.05, y, 0, "delivered"))  # late by one tick
        elif t == 5:
            rows.append((t, "", sensor, supernode, 2, "", x, y, 0, "lost"))
        elif t == 10:
            rows.append((t, "", sensor, supernode, 2, "", x, y, 0, "after_end"))
        else:
            rows.append((t, t, sensor, supernode, 1, 0, x + 0.05, y - 0.05, 0, "delivered"))
        if t >= 4:
            rows.append((t, t, 7 * 20 + int(20.5 - t), 1 if t < 10 else 0, 1, 0, 20.5 - t, 8.1, 1, "delivered"))
    rows.append((2, 2, 45, 0, 1, 0, 5.5, 2.5, -1, "delivered"))  # a false alarm, on time
    rows.append((6, 8, 170, 1, 3, 2, 10.5, 8.5, -1, "delivered"))  # a false alarm, late
    rows.append((7, "", 199, 1, -1, "", 19.5, 9.5, -1, "unreachable"))
    rows.sort(key=lambda r: r[0])
    return rows


def per_tick_rows():
    truth_count = {t: 0 for t in range(1, TICKS + 1)}
    for row in truth_rows():
        truth_count[row[0]] += 1
    track_count = {t: 0 for t in range(1, TICKS + 1)}
    for row in track_rows():
        track_count[row[0]] += 1
    for t in range(1, TICKS + 1):
        ospa = 0.25 * t
        yield (t, truth_count[t], track_count[t], ospa, 2 * ospa, ospa, 0.5 * ospa, 0.5 * ospa)


def write_csv(path, header, rows):
    def text(value):
        return f"{value:.6f}" if isinstance(value, float) else str(value)

    with open(path, "w", encoding="utf-8") as handle:
        handle.write(",".join(header) + "\n")
        for row in rows:
            handle.write(",".join(text(v) for v in row) + "\n")


def write(directory, old=False):
    d = Path(directory)
    d.mkdir(parents=True, exist_ok=True)
    (d / "scenario.yaml").write_text(SCENARIO, encoding="utf-8")
    write_csv(d / "truth.csv", ["tick", "target", "x", "y", "vx", "vy"], truth_rows())
    write_csv(d / "observations.csv",
              ["tick_generated", "tick_delivered", "sensor", "supernode", "hops", "delay", "x", "y", "target", "fate"],
              observation_rows())
    rows = list(track_rows())
    if old:
        write_csv(d / "tracks_supernode.csv", ["tick", "supernode", "track", "x", "y", "vx", "vy"],
                  [r[:3] + r[4:8] for r in rows])
        write_csv(d / "tracks.csv", ["tick", "track", "x", "y", "vx", "vy"], [(r[0],) + r[2:3] + r[4:8] for r in rows])
    else:
        write_csv(d / "tracks_supernode.csv",
                  ["tick", "supernode", "track", "label", "x", "y", "vx", "vy"] + COVARIANCE, rows)
        write_csv(d / "tracks.csv", ["tick", "track", "label", "x", "y", "vx", "vy"] + COVARIANCE,
                  [(r[0],) + r[2:] for r in rows])
    write_csv(d / "metrics_per_tick.csv",
              ["tick", "truth_targets", "tracks", "ospa", "gospa", "gospa_localisation", "gospa_missed", "gospa_false"],
              per_tick_rows())
    (d / "metrics.json").write_text(
        '{\n  "scenario": "tiny",\n  "seed": 3,\n  "eps_k": 0.25,\n  "metrics": {\n    "first_tick": 1,\n'
        '    "eps_k": 0.25,\n    "ospa_mean": 1.375,\n    "ospa_per_tick": [0.25, 0.5, 0.75, 1, 1.25, 1.5, 1.75, 2, '
        '2.25, 2.5]\n  },\n  "timing": {"wall_s": 0.1, "ticks_per_s": 90}\n}\n', encoding="utf-8")
    (d / "network.json").write_text('{\n  "communication_range": 3.0,\n  "pte": 0.1,\n  "pde": 0.2,\n'
                                    '  "sent": 21,\n  "lost": 1\n}\n', encoding="utf-8")
    mark(d, "complete")


def mark(directory, status, reason=None):
    """Writes DIR/run.json as a launcher leaves it: `status` complete, failed (with `reason`) or
    running; None leaves the status out, as a wsntrack from before it did."""
    lines = ['"run_id": "00ff"', '"domain": 7', '"scenario": "tiny"', '"ticks": 10']
    if status is not None:
        lines.append(f'"status": "{status}"')
    if reason is not None:
        lines.append(f'"reason": "{reason}"')
    (Path(directory) / "run.json").write_text("{\n  " + ",\n  ".join(lines) + "\n}\n", encoding="utf-8")


if __name__ == "__main__":
    if len(sys.argv) not in (2, 3) or (len(sys.argv) == 3 and sys.argv[2] != "--old"):
        sys.exit(__doc__)
    write(sys.argv[1], old=len(sys.argv) == 3)
