#!/usr/bin/python3
"""City-scale benchmark of the whole cluster: start-up, tick-loop throughput and peak memory of
every process, multi-process on this host, for the scale scenarios (10^4, 10^5, 10^6 sensors by
default), and how they grow from one size to the next.

    bench/scale.py [--bin build/bin] [--repeats 3] [--ticks T] [--set KEY=VALUE]... [SCENARIO...]

Each scenario is run --repeats times with `wsntrack run --no-plot`; the table gives the median
over the repeats of the launcher's own figures: start-up (from the start of the first process
until the aggregator finished tick 1), ticks/s of the tick loop (as metrics.json records it),
the whole command's wall time, and the peak RSS of the largest process of each role. Outputs of
the runs are checked to be byte-identical across repeats (the same scenario and seed). The last
column is each figure's ratio to the row above. Runs go to a temporary directory, removed after.
"""

import argparse
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

SOURCE = Path(__file__).resolve().parent.parent
DEFAULT_SCENARIOS = ["scale_1e4", "scale_1e5", "scale_1e6"]
DETERMINISTIC = ["truth.csv", "observations.csv", "tracks_supernode.csv", "tracks.csv", "network.json"]


def parse_summary(text):
    """The launcher summary's figures: start-up, tick-loop wall time and ticks/s, peak RSS by role."""
    def seconds(label):
        match = re.search(r"^\s+" + re.escape(label) + r"\s+([0-9.]+) s$", text, re.M)
        return float(match.group(1)) if match else None
    ticks_per_s = re.search(r"^\s+ticks/s \(tick loop\)\s+([0-9.]+)$", text, re.M)
    rss = {}
    line = re.search(r"peak RSS per process \(MiB\):(.*)$", text, re.M)
    if line:
        for name, value in re.findall(r"\s*([a-z]+) [0-9-]+(?:@\S+)? ([0-9.]+);", line.group(1)):
            rss[name] = max(rss.get(name, 0.0), float(value))
    return {"startup_s": seconds("start-up (to tick 1)"), "loop_s": seconds("wall time (tick loop)"),
            "ticks_per_s": float(ticks_per_s.group(1)) if ticks_per_s else None, "rss": rss}


def run_once(wsntrack, scenario, out, ticks, sets):
    command = [str(wsntrack), "run", str(scenario), "--out", str(out), "--no-plot"]
    if ticks:
        command += ["--ticks", str(ticks)]
    for text in sets:
        command += ["--set", text]
    started = time.monotonic()
    done = subprocess.run(command, capture_output=True, text=True)
    wall = time.monotonic() - started
    if done.returncode != 0:
        sys.exit(f"scale.py: {' '.join(command)} failed (exit {done.returncode}):\n{done.stdout[-2000:]}{done.stderr[-2000:]}")
    figures = parse_summary(done.stdout)
    figures["wall_s"] = wall
    return figures


def same_outputs(a, b):
    return all((a / name).read_bytes() == (b / name).read_bytes() for name in DETERMINISTIC)


def fmt(value, digits):
    return "n/a" if value is None else f"{value:.{digits}f}"


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    parser.add_argument("scenarios", nargs="*", default=DEFAULT_SCENARIOS,
                        help="scenario names in scenarios/ or paths (default: %(default)s)")
    parser.add_argument("--bin", default=str(SOURCE / "build" / "bin"), help="directory of wsntrack (default: %(default)s)")
    parser.add_argument("--repeats", type=int, default=3, help="runs per scenario; the table gives medians (default: 3)")
    parser.add_argument("--ticks", type=int, default=0, help="override run.ticks (default: the scenario's)")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", dest="sets",
                        help="a scenario value for every run, as `wsntrack run --set` takes it "
                             "(e.g. run.security=off); repeatable")
    args = parser.parse_args(argv)
    wsntrack = Path(args.bin) / "wsntrack"
    if not wsntrack.exists():
        sys.exit(f"scale.py: no {wsntrack}; build first (cmake --build build) or give --bin")
    if args.repeats < 1:
        sys.exit("scale.py: --repeats must be at least 1")

    rows = []
    work = Path(tempfile.mkdtemp(prefix="wsntrack-scale-"))
    try:
        for name in args.scenarios:
            scenario = Path(name) if name.endswith(".yaml") else SOURCE / "scenarios" / f"{name}.yaml"
            if not scenario.exists():
                sys.exit(f"scale.py: no scenario {scenario}")
            runs = []
            for k in range(args.repeats):
                print(f"{scenario.stem}: run {k + 1}/{args.repeats} ...", file=sys.stderr, flush=True)
                out = work / f"{scenario.stem}-{k}"
                runs.append(run_once(wsntrack, scenario, out, args.ticks, args.sets))
                if k > 0 and not same_outputs(work / f"{scenario.stem}-0", out):
                    sys.exit(f"scale.py: {scenario.stem}: run {k + 1}'s outputs differ from run 1's")
                if k > 0:
                    shutil.rmtree(out)
            shutil.rmtree(work / f"{scenario.stem}-0")

            def median(key):
                values = [r[key] for r in runs if r[key] is not None]
                return statistics.median(values) if values else None
            roles = sorted({role for r in runs for role in r["rss"]})
            rows.append({"name": scenario.stem, "startup_s": median("startup_s"), "ticks_per_s": median("ticks_per_s"),
                         "wall_s": median("wall_s"),
                         "rss": {role: statistics.median(r["rss"].get(role, 0.0) for r in runs) for role in roles}})
    finally:
        shutil.rmtree(work, ignore_errors=True)

    roles = sorted({role for row in rows for role in row["rss"]})
    header = ["scenario", "start-up s", "ticks/s", "wall s"] + [f"{role} MiB" for role in roles]
    print(f"medians of {args.repeats} multi-process runs each; (x N): ratio to the row above")
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    previous = None
    for row in rows:
        def cell(value, before, digits):
            text = fmt(value, digits)
            if previous is not None and value and before:
                text += f" (x{value / before:.2f})"
            return text
        cells = [row["name"], cell(row["startup_s"], previous and previous["startup_s"], 2),
                 cell(row["ticks_per_s"], previous and previous["ticks_per_s"], 1),
                 cell(row["wall_s"], previous and previous["wall_s"], 1)]
        cells += [cell(row["rss"].get(role), previous and previous["rss"].get(role), 1) for role in roles]
        print("| " + " | ".join(cells) + " |")
        previous = row
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
