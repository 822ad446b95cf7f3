#!/usr/bin/python3
"""Parameter sweeps over wsntrack clusters: one `wsntrack run` per (grid point, engine, seed),
every row in OUT/results.csv and a markdown table of the means over the seeds on stdout.

Two forms:
  sweep.py SPEC.yaml [--out DIR] [-j N]   a sweep spec (sweeps/*.yaml): runs in parallel, resumes,
                                          writes summary.csv (mean, sd, 95 % CI) and plots/
  sweep.py --scenario FILE [--set-grid KEY=V1,V2,...] ...   the flag form

The flag form needs the standard library only, so that it runs with any python3 on the machine. The
spec form reads YAML with PyYAML and draws with matplotlib (Debian's python3-yaml and
python3-matplotlib, which /usr/bin/python3 has); it imports them only when it is used.
"""

import argparse
import csv
import hashlib
import itertools
import json
import math
import os
import re
import shlex
import signal
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
# The metrics a sweep can tabulate: name -> (table title, path into metrics.json, path of the flag
# that says whether the run defines it, or None). docs/METRICS.md defines each.
METRIC_SOURCES = {
    "eps_k": ("eps_K", ("eps_k",), ("metrics", "eps_k_defined")),
    "eps_x": ("eps_X", ("eps_x",), ("metrics", "eps_x_defined")),
    "eps_x_gated": ("eps_X gated", ("metrics", "eps_x_gated"), ("metrics", "eps_x_gated_defined")),
    "ospa": ("OSPA", ("ospa",), None),
    "gospa": ("GOSPA", ("gospa", "mean"), None),
    "mota": ("MOTA", ("clear_mot", "mota"), ("clear_mot", "mota_defined")),
    "motp": ("MOTP", ("clear_mot", "motp"), ("clear_mot", "motp_defined")),
    "id_switches": ("ID switches", ("clear_mot", "id_switches"), None),
    "fragmentations": ("fragmentations", ("clear_mot", "fragmentations"), None),
    "boundary_duplicates": ("boundary dup", ("boundary", "boundary", "duplicate_track_ticks"), None),
    "boundary_id_switches": ("boundary IDsw", ("boundary", "boundary", "id_switches"), None),
    "boundary_fragmentations": ("boundary frag", ("boundary", "boundary", "fragmentations"), None),
    "tlr": ("TLR", ("track_quality", "mean_tlr"), ("track_quality", "means_defined")),
    "tlr_length": ("TLR length", ("track_quality", "mean_tlr_length"), ("track_quality", "means_defined")),
    "position_error": ("<dx>", ("track_quality", "mean_position_error"), ("track_quality", "means_defined")),
}
# The same metrics of the settled stream (the fixed-lag, smoothed estimate; docs/METRICS.md, "Track
# streams"): settled_eps_k, settled_ospa, ...
METRIC_SOURCES.update({
    "settled_" + name: ("settled " + title, ("streams", "settled") + where,
                        ("streams", "settled") + defined if defined else None)
    for name, (title, where, defined) in list(METRIC_SOURCES.items())})


def _network(key):
    return lambda data, run_dir: json.loads((run_dir / "network.json").read_text(encoding="utf-8"))[key]


def _received(data, run_dir):
    network = json.loads((run_dir / "network.json").read_text(encoding="utf-8"))
    return network["sent"] - network["lost"] - network["unreachable"]


def _false_reports(data, run_dir):
    with open(run_dir / "observations.csv", encoding="utf-8", newline="") as f:
        return sum(1 for row in csv.DictReader(f) if row["target"] == "-1")


def _false_tracks_per_tick(data, run_dir):
    return data["clear_mot"]["false_positives"] / data["ticks"]


# Tracks that match no target, per tick (CLEAR-MOT's false positives over the run's ticks), as An et
# al. 2013 count them.
METRIC_SOURCES["false_per_tick"] = ("false tracks/tick", _false_tracks_per_tick, None)

def _of_target(target, key):
    def value(data, run_dir):
        for entry in data["track_quality"]["targets"]:
            if entry["id"] == target:
                return entry[key] if entry.get("errors_defined", True) or key == "tlr" else None
        return None
    return value


# One target's <dx> and TLR (track_quality.targets[] in metrics.json), for figures that follow one
# target (An et al. 2014 Fig. 15): position_error_0 is the target with id 0 (the first scripted).
for _target in range(10):
    METRIC_SOURCES[f"position_error_{_target}"] = (f"<dx> target {_target}", _of_target(_target, "mean_position_error"), None)
    METRIC_SOURCES[f"tlr_{_target}"] = (f"TLR target {_target}", _of_target(_target, "tlr"), None)

# Counts of the run's reports, as Oh et al. §VII-E gives them ("a total of 1174 observations and 603
# observations were false alarms", packets lost and received delayed): read from the run's
# network.json and observations.csv (README.md, "Run directory") instead of metrics.json.
METRIC_SOURCES.update({
    "reports": ("reports", _network("sent"), None),
    "false_reports": ("false reports", _false_reports, None),
    "reports_lost": ("reports lost", _network("lost"), None),
    "reports_received": ("reports received", _received, None),
    "reports_delayed": ("received delayed", _network("delayed"), None),
})


def _report_detection(data, run_dir):
    """(share of ticks whose number of reports made equals the number of targets, the localisation
    errors of the labelled reports against their target at the tick made, the same errors at the
    ticks whose count is right), from observations.csv and truth.csv; read once per run directory."""
    cached = _DETECTION_CACHE.get(run_dir)
    if cached is None:
        at, surplus = {}, {}  # surplus[t]: reports made at t minus targets at t
        with open(run_dir / "truth.csv", encoding="utf-8", newline="") as f:
            for row in csv.DictReader(f):
                tick = int(row["tick"])
                at[(tick, row["target"])] = (float(row["x"]), float(row["y"]))
                surplus[tick] = surplus.get(tick, 0) - 1
        errors = []  # (tick, distance)
        with open(run_dir / "observations.csv", encoding="utf-8", newline="") as f:
            for row in csv.DictReader(f):
                tick = int(row["tick_generated"])
                surplus[tick] = surplus.get(tick, 0) + 1
                if (tick, row["target"]) in at:
                    x, y = at[(tick, row["target"])]
                    errors.append((tick, math.hypot(float(row["x"]) - x, float(row["y"]) - y)))
        ticks = data["ticks"]
        same = sum(1 for t in range(1, ticks + 1) if surplus.get(t, 0) == 0)
        cached = (same / ticks, [e for _, e in errors], [e for t, e in errors if surplus.get(t, 0) == 0])
        _DETECTION_CACHE.clear()  # one run at a time: the metrics of a run are asked together
        _DETECTION_CACHE[run_dir] = cached
    return cached


_DETECTION_CACHE = {}


def _rms(errors):
    return math.sqrt(sum(e * e for e in errors) / len(errors)) if errors else None


def _median(errors):
    return sorted(errors)[len(errors) // 2] if errors else None


# What the sensors detect, before any tracker (ADMAN's "estimated total number" and localisation
# error): the share of ticks with as many reports as targets, and the rms and median distance of a
# labelled report from its target (false alarms left out), over every report and over the ticks
# whose count is right. Meaningful where a model reports each target once a tick (ADMAN, the fused
# reports of Oh eq. 6).
METRIC_SOURCES.update({
    "count_match": ("count right", lambda data, run_dir: _report_detection(data, run_dir)[0], None),
    "report_error": ("report err rms", lambda data, run_dir: _rms(_report_detection(data, run_dir)[1]), None),
    "report_error_median": ("report err median", lambda data, run_dir: _median(_report_detection(data, run_dir)[1]),
                            None),
    "report_error_count_right": ("report err rms, count right",
                                 lambda data, run_dir: _rms(_report_detection(data, run_dir)[2]), None),
})


def metric_value(metric, data, run_dir):
    """One metric of a run: a path into its metrics.json (`data`), or a function of `data` and the
    run directory (the report counts read its other files)."""
    _, where, defined = METRIC_SOURCES[metric]
    if callable(where):
        return where(data, run_dir)
    return None if defined and lookup(data, defined) is False else lookup(data, where)
DEFAULT_METRICS = ("eps_k", "eps_x", "ospa")
METRICS = DEFAULT_METRICS  # the tabulated ones, set from --metrics

DESCRIPTION = """\
Runs a grid of wsntrack clusters and tabulates their metrics.

This is the flag form. The spec form, `sweep.py SPEC.yaml [--out DIR] [-j N]`, reads the sweep
from a YAML file (sweeps/*.yaml), runs in parallel, resumes a stopped sweep and writes summary.csv
(mean, sd and 95 % confidence interval) and plots/: `sweep.py SPEC.yaml --help` describes it.

For every grid point (the cartesian product of the --set-grid values), every engine and every
seed it runs

  wsntrack run SCENARIO --seed S --out OUT/runs/NAME --overwrite --quiet --no-plot
               --set tracker.engine=E [--set KEY=VALUE for the fixed --set options]
               [--set KEY=V for each --set-grid key] [--in-process]

reads the run's metrics.json (by default eps_k: Oh eq. 9, eps_x: eq. 10, ospa: mean OSPA; more
with --metrics), shows progress on stderr, and writes:

  OUT/results.csv   one row per run: engine, the grid keys, seed, status, the metrics,
                    wall_s (the whole run as this tool timed it), run_dir, log
  OUT/table.md      the table printed on stdout: one row per grid point and, for each engine,
                    the means over the seeds of each metric
  OUT/sweep.json    the sweep's parameters (and the command line that started it)
  OUT/runs/NAME/    each run directory (see README.md, "Run directory")
  OUT/logs/NAME.log each run's wsntrack output

KEY is a dotted path into the scenario YAML as for `wsntrack run --set` (scenarios/README.md);
engines and seeds are chosen with --engines and --seeds, not with tracker.engine or run.seed.
Every combination is checked with `wsntrack validate` before the first run starts, so a bad
--set or an unknown engine fails at once. A run that fails is reported with its log and the
sweep goes on; a mean leaves out runs that failed and metrics that are undefined for a run
(eps_K with no true targets, eps_X with no matched track), and says so with (k/n).

Exit status: 0 when every run succeeded, 1 when any failed, 2 for a usage or validation error.
"""

EPILOG = """\
examples:
  tools/sweep.py --scenario scenarios/oh_quadrants.yaml --seeds 1-5 --engines gnn \\
      --set-grid network.pte=0,0.2,0.4 --set-grid network.pde=0,0.3,0.6 --out runs/sweep-loss
  tools/sweep.py --scenario scenarios/oh_quadrants.yaml --seeds 1-5 --set-grid aggregator.association=gated,mcmcda \\
      --metrics eps_k,ospa,boundary_duplicates,boundary_id_switches,boundary_fragmentations --out runs/sweep-assoc
  tools/sweep.py --scenario scenarios/oh_single_supernode.yaml --seeds 1-3 --engines gnn \\
      --set-grid network.pte=0,0.1,0.2,0.3 --set tracker.params.gate_chi2=12 --jobs 2
  tools/sweep.py sweeps/oh_fig7_pte.yaml --out runs/fig7        (the spec form)

'wsntrack engines' lists the engines and their parameters; scenarios/README.md every key.
"""


class UsageError(Exception):
    pass


def parse_seeds(text):
    """'1-5' -> [1..5]; '1,3,7' and '1-3,10' work too. Order kept, duplicates dropped."""
    seeds = []
    seen = set()
    for part in text.split(","):
        part = part.strip()
        match = re.fullmatch(r"(\d+)(?:-(\d+))?", part)
        if not match:
            raise UsageError(f"--seeds: expected seeds like 1-5 or 1,3,7, got '{text}'")
        first = int(match.group(1))
        last = int(match.group(2)) if match.group(2) is not None else first
        if last < first:
            raise UsageError(f"--seeds: range '{part}' runs backwards")
        if last - first >= 100000:
            raise UsageError(f"--seeds: range '{part}' is too long")
        for seed in range(first, last + 1):
            if seed >= 2**64:
                raise UsageError(f"--seeds: {seed} exceeds 2^64 - 1")
            if seed not in seen:
                seen.add(seed)
                seeds.append(seed)
    return seeds


def seeds_text(seeds):
    """[1, 2, 3, 5] -> '1-3, 5'."""
    parts = []
    for seed in seeds:
        if parts and parts[-1][1] == seed - 1:
            parts[-1][1] = seed
        else:
            parts.append([seed, seed])
    return ", ".join(str(a) if a == b else f"{a}-{b}" for a, b in parts)


def split_key_value(text, option):
    key, equals, value = text.partition("=")
    if not equals or not key:
        raise UsageError(f"{option} {text}: expected KEY=VALUE")
    return key, value


def parse_grid(texts):
    """['network.pte=0,0.2'] -> [('network.pte', ['0', '0.2'])]; keys in the order given."""
    grid = []
    for text in texts:
        key, values = split_key_value(text, "--set-grid")
        items = [v.strip() for v in values.split(",")]
        if any(v == "" for v in items) or len(set(items)) != len(items):
            raise UsageError(f"--set-grid {text}: expected KEY=V1,V2,... with distinct, non-empty values")
        if any(key == k for k, _ in grid):
            raise UsageError(f"--set-grid {key}: given twice; list all its values in one --set-grid")
        grid.append((key, items))
    return grid


def short_names(keys):
    """Column names: the last part of each dotted key (network.pte -> pte) unless two collide."""
    last = [k.split(".")[-1] for k in keys]
    return [s if last.count(s) == 1 else k for s, k in zip(last, keys)]


def safe(text):
    return re.sub(r"[^A-Za-z0-9._-]+", "_", text)


class Run:
    """One wsntrack run of the sweep."""

    def __init__(self, engine, point, seed, names, out):
        self.engine = engine
        self.point = point  # [(key, value)] of the grid point
        self.seed = seed
        label = "_".join([safe(engine)] + [f"{safe(n)}-{safe(v)}" for n, (_, v) in zip(names, point)])
        self.name = f"{label}_seed-{seed}"
        self.label = " ".join([engine] + [f"{n}={v}" for n, (_, v) in zip(names, point)] + [f"seed={seed}"])
        self.run_dir = out / "runs" / self.name
        self.log = out / "logs" / f"{self.name}.log"
        self.status = "not run"
        self.exit_code = None
        self.metrics = {m: None for m in METRICS}
        self.started = None
        self.wall_s = None


def engine_sets(engine):
    return [("tracker.engine", engine)]


def set_args(pairs):
    args = []
    for key, value in pairs:
        args += ["--set", f"{key}={value}"]
    return args


def lookup(data, path):
    for key in path:
        if not isinstance(data, dict):
            return None
        data = data.get(key)
    return data


def read_metrics(run):
    """The run's tabulated metrics; None for a metric the run leaves undefined."""
    with open(run.run_dir / "metrics.json", encoding="utf-8") as f:
        data = json.load(f)
    try:
        return {metric: metric_value(metric, data, run.run_dir) for metric in METRICS}
    except (KeyError, TypeError, json.JSONDecodeError) as error:
        raise ValueError(f"cannot read a metric from {run.run_dir} ({error!r})") from None


def scenario_engine(wsntrack, scenario, fixed):
    """The engine the scenario (with the fixed --set options) names, from `wsntrack validate`."""
    command = [str(wsntrack), "validate", str(scenario)] + set_args(fixed)
    result = subprocess.run(command, capture_output=True, text=True, check=False)
    match = re.search(r", engine (\S+)\)$", result.stdout.strip())
    if result.returncode != 0 or not match:
        raise UsageError((result.stderr or result.stdout).strip() or f"{shlex.join(command)} failed")
    return match.group(1)


def validate(wsntrack, scenario, combos):
    """Checks every (engine, grid point) with `wsntrack validate`; returns the first error or None."""
    for sets in combos:
        command = [str(wsntrack), "validate", str(scenario)] + set_args(sets)
        result = subprocess.run(command, capture_output=True, text=True, check=False)
        if result.returncode != 0:
            message = (result.stderr or result.stdout).strip()
            return f"{message}\n(while checking: {shlex.join(command)})"
    return None


def mean_cell(runs, metric, total):
    values = [r.metrics[metric] for r in runs if r.status == "ok" and r.metrics[metric] is not None]
    if not values:
        return "–"
    text = f"{sum(values) / len(values):.4f}"
    return text if len(values) == total else f"{text} ({len(values)}/{total})"


def markdown_table(args, grid, names, engines, seeds, runs, fixed):
    lines = [
        f"## Sweep of {args.scenario}: {'seed' if len(seeds) == 1 else 'seeds'} {seeds_text(seeds)} "
        f"({len(seeds)} per cell)",
        "",
    ]
    if fixed:
        lines += ["Fixed: " + " ".join(f"`--set {k}={v}`" for k, v in fixed), ""]
    lines += [
        "Each cell is the mean over the seeds; (k/n): only k of the n runs were counted (a run failed, "
        "or the metric is undefined for it); –: none.",
        "",
    ]
    header = list(names) + [f"{e} {METRIC_SOURCES[m][0]}" for e in engines for m in METRICS]
    lines.append("| " + " | ".join(header) + " |")
    lines.append("|" + "|".join(["---"] * len(names) + ["---:"] * (len(header) - len(names))) + "|")
    by_cell = {}
    for run in runs:
        by_cell.setdefault((tuple(run.point), run.engine), []).append(run)
    points = list(itertools.product(*[[(k, v) for v in values] for k, values in grid]))
    for point in points:
        cells = [v for _, v in point]
        for engine in engines:
            cell_runs = by_cell.get((tuple(point), engine), [])
            cells += [mean_cell(cell_runs, m, len(seeds)) for m in METRICS]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def write_csv(path, grid, runs):
    keys = [k for k, _ in grid]
    with open(path, "w", newline="", encoding="utf-8") as f:
        writer = csv.writer(f)
        writer.writerow(["engine"] + keys + ["seed", "status"] + list(METRICS) + ["wall_s", "run_dir", "log"])
        for run in runs:
            if run.status == "not run":
                continue
            metric_values = ["" if run.metrics[m] is None else f"{run.metrics[m]:.6f}" for m in METRICS]
            wall = "" if run.wall_s is None else f"{run.wall_s:.3f}"
            writer.writerow([run.engine] + [v for _, v in run.point] + [run.seed, run.status] + metric_values +
                            [wall, run.run_dir, run.log])


def start(run, wsntrack, scenario, fixed, in_process):
    command = [str(wsntrack), "run", str(scenario), "--seed", str(run.seed), "--out", str(run.run_dir), "--overwrite",
               "--quiet", "--no-plot"] + set_args(engine_sets(run.engine) + fixed + run.point)
    if in_process:
        command.append("--in-process")
    log = open(run.log, "w", encoding="utf-8")
    log.write("$ " + shlex.join(command) + "\n")
    log.flush()
    run.started = time.monotonic()
    return subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL), log


def finish(run, process):
    run.wall_s = time.monotonic() - run.started
    run.exit_code = process.returncode
    if run.exit_code != 0:
        run.status = "failed"
        return
    try:
        run.metrics = read_metrics(run)
        run.status = "ok"
    except (OSError, ValueError) as error:
        run.status = "failed"
        with open(run.log, "a", encoding="utf-8") as log:
            log.write(f"sweep: cannot read {run.run_dir / 'metrics.json'}: {error}\n")


def plural(n, word):
    return f"{n} {word}" + ("" if n == 1 else "s")


def progress(done, total, run):
    if run.status == "ok":
        outcome = f"{run.wall_s:.1f} s"
    else:
        outcome = f"FAILED (exit {run.exit_code}) after {run.wall_s:.1f} s; see {run.log}"
        if (run.run_dir / "logs").is_dir():
            outcome += f" and {run.run_dir / 'logs'}/"
    print(f"[{done}/{total}] {run.label} ... {outcome}", file=sys.stderr, flush=True)


def run_all(runs, args, fixed):
    """Runs up to --jobs clusters at a time (each run picks a DDS domain of its own)."""
    pending = list(runs)
    running = []  # (run, process, log file)
    done = 0
    try:
        while pending or running:
            while pending and len(running) < args.jobs:
                run = pending.pop(0)
                process, log = start(run, args.wsntrack, args.scenario, fixed, args.in_process)
                running.append((run, process, log))
            still = []
            for run, process, log in running:
                if process.poll() is None:
                    still.append((run, process, log))
                    continue
                log.close()
                finish(run, process)
                done += 1
                progress(done, len(runs), run)
            running = still
            if running:
                time.sleep(0.05)
    except KeyboardInterrupt:
        # wsntrack stops its role processes on SIGTERM; only the runs this tool started are stopped.
        for run, process, log in running:
            process.terminate()
        for run, process, log in running:
            process.wait()
            log.close()
            run.status = "interrupted"
            run.exit_code = process.returncode
        raise


def parse_args(argv):
    usage = ("%(prog)s SPEC.yaml [--out DIR] [-j N] ...   (the spec form: %(prog)s SPEC.yaml --help)\n"
             "       %(prog)s --scenario SCENARIO [--seeds SEEDS] [--engines ENGINES] [--set-grid KEY=V1,V2,...]\n"
             "                [--set KEY=VALUE] [--out OUT] [-j JOBS] [--wsntrack WSNTRACK] [--metrics METRICS]\n"
             "                [--in-process]")
    parser = argparse.ArgumentParser(prog="sweep.py", description=DESCRIPTION, epilog=EPILOG, usage=usage,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scenario", required=True, type=Path, help="scenario file (YAML)")
    parser.add_argument("--seeds", default="1", help="seeds: 1-5, 1,3,7 or 1-3,10 (default: 1)")
    parser.add_argument("--engines", default=None,
                        help="comma-separated tracker engines, one column group each (default: the scenario's "
                        "own engine); 'wsntrack engines' lists them")
    parser.add_argument("--set-grid", action="append", default=[], metavar="KEY=V1,V2,...",
                        help="a swept scenario key and its values (repeatable; the grid is the product, the first "
                        "key varying slowest). KEY as for wsntrack --set; values may not contain commas")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", dest="fixed",
                        help="a scenario value for every run, passed to wsntrack run --set (repeatable), e.g. "
                        "run.ticks=20 or tracker.params.gate_chi2=12")
    parser.add_argument("--out", type=Path, default=None,
                        help="sweep directory (default: runs/sweep-<scenario>-<UTC time>); an existing one must "
                        "be empty or hold an earlier sweep")
    parser.add_argument("-j", "--jobs", type=int, default=1,
                        help="clusters run at the same time (default 1; each cluster is several processes)")
    parser.add_argument("--wsntrack", type=Path, default=REPO / "build" / "bin" / "wsntrack",
                        help="the wsntrack executable (default: build/bin/wsntrack of this repository)")
    parser.add_argument("--metrics", default=",".join(DEFAULT_METRICS),
                        help="comma-separated metrics to tabulate (default: %(default)s); one of: " +
                        ", ".join(METRIC_SOURCES))
    parser.add_argument("--in-process", action="store_true",
                        help="run each cluster's roles as threads of one process (wsntrack run --in-process); "
                        "the results are the same")
    return parser.parse_args(argv)


def main(argv):
    if spec_form(argv):
        return spec_main(argv)
    args = parse_args(argv)
    global METRICS
    try:
        METRICS = tuple(m.strip() for m in args.metrics.split(","))
        unknown = [m for m in METRICS if m not in METRIC_SOURCES]
        if unknown or not METRICS or len(set(METRICS)) != len(METRICS):
            raise UsageError(f"--metrics: expected distinct names from {', '.join(METRIC_SOURCES)}, got '{args.metrics}'")
        seeds = parse_seeds(args.seeds)
        grid = parse_grid(args.set_grid)
        fixed = [split_key_value(t, "--set") for t in args.fixed]
        if args.jobs < 1:
            raise UsageError("--jobs must be at least 1")
        if not os.access(args.wsntrack, os.X_OK):
            raise UsageError(f"--wsntrack: {args.wsntrack} is not an executable (build first: cmake --build build)")
        if not args.scenario.is_file():
            raise UsageError(f"--scenario: {args.scenario} is not a file")
        # The engine is a column group of the table, never a grid key or a fixed --set.
        if any(k == "tracker.engine" for k, _ in grid + fixed):
            raise UsageError("tracker.engine: choose engines with --engines, not --set or --set-grid")
        if any(k == "run.seed" for k, _ in grid + fixed):
            raise UsageError("run.seed: choose seeds with --seeds (wsntrack's --seed would override it)")
        clash = {k for k, _ in grid} & {k for k, _ in fixed}
        if clash:
            raise UsageError(f"{', '.join(sorted(clash))}: both swept (--set-grid) and fixed (--set); give it once")
        if args.engines is None:
            engines = [scenario_engine(args.wsntrack, args.scenario, fixed)]
        else:
            engines = [e.strip() for e in args.engines.split(",")]
            if any(not e for e in engines) or len(set(engines)) != len(engines):
                raise UsageError(f"--engines: expected distinct names like gnn,mcmcda, got '{args.engines}'")
        out = args.out or Path("runs") / f"sweep-{args.scenario.stem}-{time.strftime('%Y%m%d-%H%M%S', time.gmtime())}"
        if out.exists() and (not out.is_dir() or (any(out.iterdir()) and not (out / "sweep.json").exists())):
            raise UsageError(f"--out: {out} exists and is not an earlier sweep (no sweep.json); choose another")
    except UsageError as error:
        print(f"sweep.py: {error}", file=sys.stderr)
        return 2

    names = short_names([k for k, _ in grid])
    points = [list(p) for p in itertools.product(*[[(k, v) for v in values] for k, values in grid])]
    error = validate(args.wsntrack, args.scenario,
                     [engine_sets(e) + fixed + p for p in points for e in engines])
    if error:
        print(f"sweep.py: not a valid combination, nothing run:\n{error}", file=sys.stderr)
        return 2

    (out / "runs").mkdir(parents=True, exist_ok=True)
    (out / "logs").mkdir(exist_ok=True)
    with open(out / "sweep.json", "w", encoding="utf-8") as f:
        json.dump({"command": shlex.join([sys.argv[0]] + argv), "scenario": str(args.scenario), "seeds": seeds,
                   "engines": engines, "grid": {k: v for k, v in grid}, "set": {k: v for k, v in fixed},
                   "in_process": args.in_process}, f, indent=2)
        f.write("\n")

    # Grid point outermost, seeds innermost: each row of the table completes as early as it can.
    runs = [Run(e, p, s, names, out) for p in points for e in engines for s in seeds]
    taken = set()
    for run in runs:  # values that differ only in characters a file name cannot hold
        while run.name in taken:
            run.name += "_"
            run.run_dir = out / "runs" / run.name
            run.log = out / "logs" / f"{run.name}.log"
        taken.add(run.name)
    print(f"sweep.py: {plural(len(runs), 'run')} ({plural(len(points), 'grid point')} x "
          f"{plural(len(engines), 'engine')} x {plural(len(seeds), 'seed')}) into {out}", file=sys.stderr)
    interrupted = False
    try:
        run_all(runs, args, fixed)
    except KeyboardInterrupt:
        interrupted = True
        print("sweep.py: interrupted; writing what finished", file=sys.stderr)

    write_csv(out / "results.csv", grid, runs)
    table = markdown_table(args, grid, names, engines, seeds, runs, fixed)
    (out / "table.md").write_text(table, encoding="utf-8")
    sys.stdout.write(table)
    failed = [r for r in runs if r.status == "failed"]
    if failed:
        print(f"sweep.py: {len(failed)} of {len(runs)} runs failed:", file=sys.stderr)
        for run in failed:
            print(f"  {run.label}: exit {run.exit_code}, log {run.log}", file=sys.stderr)
    print(f"sweep.py: results in {out / 'results.csv'}", file=sys.stderr)
    if interrupted:
        return 130
    return 1 if failed else 0


# ---------------------------------------------------------------------------------------------
# The spec form: sweep.py SPEC.yaml [--out DIR] [-j N]

SPEC_DESCRIPTION = """\
Runs the sweep a spec file describes (sweeps/*.yaml), in parallel, and resumes it when run again.

A spec is a YAML mapping:

  scenario: scenarios/oh_single_supernode.yaml   # relative to the spec's directory, else to the repository
  grid:                                          # 1 or 2 swept keys (a line plot, or a heat map)
    network.pte: [0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6]
  engines: [mcmcda, gnn]                         # default: the scenario's own engine
  seeds: 1-10                                    # or 3, or [1, 4, 9]; default 1
  set: {network.pde: 0}                          # fixed values for every run (wsntrack run --set)
  metrics: [eps_k, eps_x, ospa]                  # default eps_k, eps_x, ospa
  in_process: true                               # wsntrack run --in-process (default false)
  title: "Oh et al. Fig. 7"                      # plots and table.md
  notes: "..."                                   # table.md and sweep.json
  reference:                                     # lines on the plots: the paper's statements
    - {metric: eps_k, value: 0.18, at: {network.pte: 0.4}, label: "performs well for pte <= .4"}

Keys are `wsntrack run --set` keys (scenarios/README.md); engines and seeds are chosen with
`engines` and `seeds`, never with tracker.engine or run.seed. A reference draws a horizontal line
at `value` on the plots of `metric` (a contour on a heat map) and a line at the grid value of `at`;
it needs a `label` and at least one of them. An unknown key or a wrong type fails with
`SPEC:LINE: what was expected` and exit status 2, before anything runs; so does a fixed value,
engine or swept key that `wsntrack validate` rejects. A swept value it rejects only makes the runs
of that value fail (a warning says so first).

Each run is `wsntrack run SCENARIO --seed S --out DIR/runs/NAME --overwrite --quiet --no-plot
--set tracker.engine=E [--set KEY=VALUE of set] [--set KEY=V of the grid point] [--in-process]`,
with absolute paths; -j runs at a time (default: the number of cores), with progress, failures and
an ETA on stderr. A run that lost its DDS ports to a cluster started at the same moment (Cyclone's
"failed to create unicast sockets") is started again, up to 3 times. A finished run leaves
DIR/runs/NAME/sweep_run.json: its command, the scenario file's SHA-256 and the SHA-256 of its
metrics.json. Run again with the same DIR, the sweep skips
every run whose record matches the run it would start and whose metrics.json is complete and
unchanged, and runs the others: a sweep stopped with Ctrl-C or SIGTERM (each running wsntrack is
sent SIGTERM by its PID, then SIGKILL after 20 s) resumes where it stopped, a failed run is run
again. When the spec (or --seeds, --set, --wsntrack, or the scenario file's contents) changed
since DIR was made, the sweep says what differs and stops, unless --force: then the runs whose
command did not change are kept and the others are run. A changed title, notes, metrics or
reference only changes the tables and plots.

Outputs in DIR:
  results.csv   one row per run: engine, the grid keys, seed, status (ok, failed, interrupted,
                not run), exit (wsntrack's status), the metrics, wall_s, reused (1: complete from
                an earlier invocation), run_dir and log (relative to DIR), command
  summary.csv   one row per grid point and engine: runs, ok, failed, and for each metric M:
                M_n (successful runs that define M), M_mean, M_sd (sample sd), M_ci95_low and
                M_ci95_high (mean -+ t(0.975, n-1) sd / sqrt(n), Student's t; empty when n < 2)
  table.md      the means with the half-width of their 95 % interval, also printed on stdout
  plots/        1-D grid: METRIC.png, the metric against the swept value, one line per engine
                with a shaded 95 % band, and the reference lines; 2-D grid: METRIC_ENGINE.png,
                a heat map of the mean (one colour scale per metric)
  sweep.json    the sweep as run (what the next invocation compares with)
  runs/NAME/    each run directory; logs/NAME.log each run's wsntrack output

--seeds and --set change the spec's seeds and fixed values for this invocation (e.g. a quick
look with --seeds 1 --set run.ticks=20); they count as a change of the sweep in the same DIR.

Exit status: 0 when every run succeeded, 1 when any failed, 2 for a usage or spec error,
128 + the signal number when stopped by SIGINT or SIGTERM.
"""

SPEC_EPILOG = """\
examples:
  tools/sweep.py sweeps/oh_fig7_pte.yaml --out runs/fig7
  tools/sweep.py sweeps/oh_fig7_pte.yaml --out runs/fig7-quick --seeds 1-2 --set run.ticks=20 -j 2
"""

SPEC_KEYS = ("scenario", "grid", "engines", "seeds", "set", "metrics", "in_process", "title", "notes", "reference")
REFERENCE_KEYS = ("metric", "value", "at", "label")
# What a run's command depends on: a change of these in the same DIR needs --force.
RUN_FIELDS = ("scenario", "scenario_sha256", "wsntrack", "grid", "engines", "seeds", "set", "in_process")
# What only the tables and plots depend on.
PRESENTATION_FIELDS = ("metrics", "title", "notes", "reference")
RECORD = "sweep_run.json"  # in each run directory, written when the run has finished
KEY_PATTERN = re.compile(r"[A-Za-z_][A-Za-z0-9_]*(\[\d+\])?(\.[A-Za-z_][A-Za-z0-9_]*(\[\d+\])?)*")
TAG = "tag:yaml.org,2002:"


class SpecError(Exception):
    """A spec that cannot be run: reported as FILE:LINE: what was expected."""

    def __init__(self, path, line, message):
        super().__init__(f"{path}:{line}: {message}" if line else f"{path}: {message}")


def spec_form(argv):
    """The spec form: no --scenario, and a spec file named (first, or any *.yaml / *.yml word)."""
    if any(a == "--scenario" or a.startswith("--scenario=") for a in argv):
        return False
    return bool(argv) and (not argv[0].startswith("-") or any(a.endswith((".yaml", ".yml")) for a in argv))


# Student's t quantile, computed, not tabulated: the CDF through the regularised incomplete beta
# function (continued fraction, Numerical Recipes' betacf) and bisection, so that any number of seeds
# gets its t(0.975, n-1), to about 1e-10 relative: 12.7062 for n = 2, 2.2622 for n = 10 (no scipy).

def _beta_continued_fraction(a, b, x):
    tiny = 1e-300
    c, d = 1.0, 1.0 - (a + b) * x / (a + 1.0)
    d = 1.0 / (d if abs(d) > tiny else tiny)
    h = d
    for m in range(1, 1000):
        for numerator in (m * (b - m) * x / ((a + 2 * m - 1) * (a + 2 * m)),
                          -(a + m) * (a + b + m) * x / ((a + 2 * m) * (a + 2 * m + 1))):
            d = 1.0 + numerator * d
            d = 1.0 / (d if abs(d) > tiny else tiny)
            c = 1.0 + numerator / c
            c = c if abs(c) > tiny else tiny
            h *= d * c
        if abs(d * c - 1.0) < 1e-15:
            break
    return h


def _incomplete_beta(a, b, x):
    """I_x(a, b), the regularised incomplete beta function."""
    if x <= 0.0:
        return 0.0
    if x >= 1.0:
        return 1.0
    front = math.exp(math.lgamma(a + b) - math.lgamma(a) - math.lgamma(b) + a * math.log(x) + b * math.log1p(-x))
    if x < (a + 1.0) / (a + b + 2.0):
        return front * _beta_continued_fraction(a, b, x) / a
    return 1.0 - front * _beta_continued_fraction(b, a, 1.0 - x) / b


def t_cdf(t, df):
    tail = 0.5 * _incomplete_beta(df / 2.0, 0.5, df / (df + t * t))
    return 1.0 - tail if t > 0 else tail


def t_quantile(p, df):
    """The p quantile of Student's t with df degrees of freedom (p > 0.5)."""
    low, high = 0.0, 1.0
    while t_cdf(high, df) < p:
        low, high = high, high * 2.0
    while high - low > 1e-12 * max(1.0, high):
        middle = (low + high) / 2.0
        low, high = (middle, high) if t_cdf(middle, df) < p else (low, middle)
    return (low + high) / 2.0


def describe_stats(values):
    """(n, mean, sd, ci_low, ci_high) of a sample; None where undefined (mean: n = 0; others: n < 2)."""
    n = len(values)
    if n == 0:
        return 0, None, None, None, None
    mean = sum(values) / n
    if n < 2:
        return n, mean, None, None, None
    sd = math.sqrt(sum((v - mean) ** 2 for v in values) / (n - 1))
    half = t_quantile(0.975, n - 1) * sd / math.sqrt(n)
    return n, mean, sd, mean - half, mean + half


def number(text):
    try:
        value = float(text)
    except ValueError:
        return None
    return value if math.isfinite(value) else None


def same_value(a, b):
    """Two grid values as written: equal as text, or as numbers (0.40 and 0.4)."""
    return a == b or (number(a) is not None and number(a) == number(b))


class Spec:
    """A sweep spec, validated; every value of the grid and of set is the scalar's text as written."""

    def __init__(self, path):
        self.path = path
        self.scenario = None  # resolved Path
        self.scenario_line = None
        self.grid = []  # [(key, [values], key line, [value lines])]
        self.engines = None
        self.engine_lines = []
        self.seeds = [1]
        self.fixed = []  # [(key, value)]
        self.fixed_lines = {}  # key -> line (none for a --set of the command line)
        self.metrics = list(DEFAULT_METRICS)
        self.in_process = False
        self.title = ""
        self.notes = ""
        self.references = []  # [{"metric", "value", "at": {key: value}, "label"}]


def load_spec(path):
    try:
        import yaml
    except ImportError:
        raise UsageError(f"{path}: reading a spec needs PyYAML (Debian: apt-get install python3-yaml); run the "
                         "tool with /usr/bin/python3") from None
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as error:
        raise UsageError(f"{path}: cannot read ({error})") from None
    try:
        root = yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.MarkedYAMLError as error:
        mark = error.problem_mark or error.context_mark
        raise SpecError(path, mark.line + 1 if mark else None, f"malformed YAML: {error.problem or error}") from None
    except yaml.YAMLError as error:
        raise SpecError(path, None, f"malformed YAML: {error}") from None
    return SpecReader(path, yaml).read(root)


class SpecReader:
    """Reads the composed YAML nodes (for their lines) into a Spec; SpecError on anything else."""

    def __init__(self, path, yaml):
        self.path = path
        self.yaml = yaml

    def fail(self, node, message):
        raise SpecError(self.path, node.start_mark.line + 1 if node is not None else 1, message)

    @staticmethod
    def line(node):
        return node.start_mark.line + 1

    def kind(self, node):
        if isinstance(node, self.yaml.MappingNode):
            return "a mapping"
        if isinstance(node, self.yaml.SequenceNode):
            return "a list"
        tag = node.tag[len(TAG):] if node.tag.startswith(TAG) else node.tag
        return {"str": f"the string '{node.value}'", "int": f"the integer {node.value}",
                "float": f"the number {node.value}", "bool": f"the boolean {node.value}",
                "null": "nothing (null)"}.get(tag, f"'{node.value}' ({tag})")

    def tag(self, node):
        return node.tag[len(TAG):] if isinstance(node, self.yaml.ScalarNode) and node.tag.startswith(TAG) else None

    def items(self, node, what, allowed=None):
        if not isinstance(node, self.yaml.MappingNode):
            self.fail(node, f"{what}: expected a mapping, got {self.kind(node)}")
        seen = {}
        result = []
        for key, value in node.value:
            if self.tag(key) != "str":
                self.fail(key, f"{what}: expected a key name, got {self.kind(key)}")
            if key.value in seen:
                self.fail(key, f"{what}: '{key.value}' given twice (first on line {seen[key.value]})")
            if allowed is not None and key.value not in allowed:
                self.fail(key, f"unknown key '{key.value}' in {what}; expected one of: {', '.join(allowed)}")
            seen[key.value] = self.line(key)
            result.append((key, value))
        return result

    def string(self, node, what):
        if self.tag(node) != "str" or not node.value.strip():
            self.fail(node, f"{what}: expected a non-empty string, got {self.kind(node)}")
        return node.value

    def scalar(self, node, what):
        """A --set value: any scalar but null, as written."""
        if self.tag(node) is None or self.tag(node) == "null" or not node.value.strip():
            self.fail(node, f"{what}: expected one value (a number, a word or a string), got {self.kind(node)}")
        return node.value

    def sequence(self, node, what, expected="a list"):
        if not isinstance(node, self.yaml.SequenceNode):
            self.fail(node, f"{what}: expected {expected}, got {self.kind(node)}")
        if not node.value:
            self.fail(node, f"{what}: expected a non-empty list")
        return node.value

    def set_key(self, node, what):
        key = node.value
        if not KEY_PATTERN.fullmatch(key):
            self.fail(node, f"{what}: expected a scenario key such as network.pte or supernodes[0].x, got '{key}'")
        if key == "tracker.engine":
            self.fail(node, f"{what}: tracker.engine: choose the engines with 'engines:', not here")
        if key == "run.seed":
            self.fail(node, f"{what}: run.seed: choose the seeds with 'seeds:', not here")
        return key

    def read(self, root):
        spec = Spec(self.path)
        if root is None:
            raise SpecError(self.path, 1, "expected a mapping with at least 'scenario' and 'grid', got an empty file")
        fields = dict((key.value, (key, value)) for key, value in self.items(root, "the spec", SPEC_KEYS))
        for required in ("scenario", "grid"):
            if required not in fields:
                self.fail(root, f"the spec: '{required}' is missing (required: scenario, grid)")
        key, node = fields["scenario"]
        spec.scenario = self.scenario(node)
        spec.scenario_line = self.line(node)
        self.grid(spec, *fields["grid"])
        if "engines" in fields:
            engines = self.sequence(fields["engines"][1], "engines")
            spec.engines = [self.string(e, "engines") for e in engines]
            spec.engine_lines = [self.line(e) for e in engines]
            for i, engine in enumerate(spec.engines):
                if not re.fullmatch(r"[A-Za-z0-9_.-]+", engine):
                    self.fail(engines[i], f"engines: expected an engine name such as mcmcda, got '{engine}'")
                if engine in spec.engines[:i]:
                    self.fail(engines[i], f"engines: '{engine}' given twice")
        if "seeds" in fields:
            spec.seeds = self.seeds(fields["seeds"][1])
        if "set" in fields:
            for key, value in self.items(fields["set"][1], "set"):
                name = self.set_key(key, "set")
                if any(name == k for k, *_ in spec.grid):
                    self.fail(key, f"set: {name} is swept by the grid; give it in one place")
                spec.fixed.append((name, self.scalar(value, f"set: {name}")))
                spec.fixed_lines[name] = self.line(key)
        if "metrics" in fields:
            nodes = self.sequence(fields["metrics"][1], "metrics")
            spec.metrics = []
            for node in nodes:
                metric = self.string(node, "metrics")
                if metric not in METRIC_SOURCES:
                    self.fail(node, f"metrics: unknown metric '{metric}'; expected one of: {', '.join(METRIC_SOURCES)}")
                if metric in spec.metrics:
                    self.fail(node, f"metrics: '{metric}' given twice")
                spec.metrics.append(metric)
        if "in_process" in fields:
            node = fields["in_process"][1]
            if self.tag(node) != "bool":
                self.fail(node, f"in_process: expected true or false, got {self.kind(node)}")
            spec.in_process = node.value.lower() in ("true", "yes", "on", "y")
        for name in ("title", "notes"):
            if name in fields:
                setattr(spec, name, self.string(fields[name][1], name))
        if "reference" in fields:
            for node in self.sequence(fields["reference"][1], "reference"):
                spec.references.append(self.reference(spec, node))
        return spec

    def scenario(self, node):
        text = self.string(node, "scenario")
        given = Path(text)
        candidates = [given] if given.is_absolute() else [self.path.parent / given, REPO / given]
        for candidate in candidates:
            if candidate.is_file():
                return candidate.resolve()
        self.fail(node, f"scenario: no file {text} " +
                  ("" if given.is_absolute() else
                   f"beside the spec (in {self.path.parent.resolve()}) or in the repository ({REPO})"))

    def grid(self, spec, key_node, node):
        entries = self.items(node, "grid")
        if len(entries) not in (1, 2):
            self.fail(key_node if not entries else node,
                      f"grid: expected 1 or 2 swept keys (a line plot or a heat map), got {len(entries)}")
        for key, values in entries:
            name = self.set_key(key, "grid")
            nodes = self.sequence(values, f"grid: {name}", "a list of values such as [0, 0.2, 0.4]")
            texts = []
            for value in nodes:
                text = self.scalar(value, f"grid: {name}")
                if any(same_value(text, t) for t in texts):
                    self.fail(value, f"grid: {name}: the value {text} is given twice")
                texts.append(text)
            spec.grid.append((name, texts, self.line(key), [self.line(v) for v in nodes]))

    def seeds(self, node):
        tag = self.tag(node)
        if tag == "int":
            return self.seed_list([node])
        if tag == "str":
            try:
                return parse_seeds(node.value)
            except UsageError as error:
                self.fail(node, "seeds: " + str(error).replace("--seeds: ", ""))
        if isinstance(node, self.yaml.SequenceNode):
            return self.seed_list(self.sequence(node, "seeds"))
        self.fail(node, f"seeds: expected seeds like 1-10, 3 or [1, 4, 9], got {self.kind(node)}")

    def seed_list(self, nodes):
        seeds = []
        for node in nodes:
            if self.tag(node) != "int" or not node.value.isdigit() or int(node.value) >= 2**64:
                self.fail(node, f"seeds: expected a seed, an integer in 0 .. 2^64 - 1, got {self.kind(node)}")
            if int(node.value) in seeds:
                self.fail(node, f"seeds: {node.value} given twice")
            seeds.append(int(node.value))
        return seeds

    def reference(self, spec, node):
        fields = dict((key.value, (key, value)) for key, value in self.items(node, "reference", REFERENCE_KEYS))
        if "label" not in fields:
            self.fail(node, "reference: 'label' is missing (what the line stands for, e.g. the paper's statement)")
        if "value" not in fields and "at" not in fields:
            self.fail(node, "reference: expected 'value' (with 'metric'), 'at', or both")
        reference = {"metric": None, "value": None, "at": {}, "label": self.string(fields["label"][1], "reference: label"),
                     "line": self.line(node)}
        if "metric" in fields:
            metric_node = fields["metric"][1]
            reference["metric"] = self.string(metric_node, "reference: metric")
            if reference["metric"] not in spec.metrics:
                self.fail(metric_node, f"reference: metric '{reference['metric']}' is not one of the sweep's metrics "
                          f"({', '.join(spec.metrics)})")
        if "value" in fields:
            value_node = fields["value"][1]
            if self.tag(value_node) not in ("int", "float") or number(value_node.value) is None:
                self.fail(value_node, f"reference: value: expected a number, got {self.kind(value_node)}")
            if reference["metric"] is None:
                self.fail(value_node, "reference: a 'value' needs the 'metric' it is a value of")
            reference["value"] = number(value_node.value)
        if "at" in fields:
            for key, value in self.items(fields["at"][1], "reference: at"):
                swept = [entry for entry in spec.grid if entry[0] == key.value]
                if not swept:
                    self.fail(key, f"reference: at: '{key.value}' is not a key of the grid "
                              f"({', '.join(k for k, *_ in spec.grid)})")
                text = self.scalar(value, f"reference: at: {key.value}")
                if not any(same_value(text, v) for v in swept[0][1]) and \
                        (number(text) is None or any(number(v) is None for v in swept[0][1])):
                    self.fail(value, f"reference: at: {key.value}: {text} is not one of the grid's values "
                              "(and the grid is not numeric)")
                reference["at"][key.value] = text
        return reference


def sha256_of(path):
    digest = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def check_with_wsntrack(spec, wsntrack):
    """Exit-2 errors (SpecError) for what would make every run fail: a fixed value, an engine, a
    swept key all of whose values wsntrack rejects; warnings for single swept values it rejects."""
    def check(sets):
        command = [str(wsntrack), "validate", str(spec.scenario)] + set_args(sets)
        result = subprocess.run(command, capture_output=True, text=True, check=False)
        return None if result.returncode == 0 else ((result.stderr or result.stdout).strip() or
                                                    f"{shlex.join(command)} failed")

    error = check(spec.fixed)
    if error:
        lines = [line for key, line in spec.fixed_lines.items() if f"--set {key}=" in error]
        command_line = [key for key, _ in spec.fixed if key not in spec.fixed_lines and f"--set {key}=" in error]
        if command_line:
            raise UsageError(f"--set {command_line[0]}: rejected by wsntrack validate: {error}")
        raise SpecError(spec.path, lines[0] if lines else spec.scenario_line, f"rejected by wsntrack validate: {error}")
    if spec.engines is None:
        try:
            spec.engines = [scenario_engine(wsntrack, spec.scenario, spec.fixed)]
        except UsageError as error:
            raise SpecError(spec.path, spec.scenario_line, str(error)) from None
    for engine, line in itertools.zip_longest(spec.engines, spec.engine_lines):
        error = check(engine_sets(engine) + spec.fixed)
        if error:
            raise SpecError(spec.path, line, f"engine {engine}: rejected by wsntrack validate: {error}")
    warnings = []
    base = engine_sets(spec.engines[0]) + spec.fixed
    for key, values, key_line, value_lines in spec.grid:
        errors = [check(base + [(key, value)]) for value in values]
        if all(errors):
            raise SpecError(spec.path, key_line, f"grid: {key}: wsntrack validate rejects every value: {errors[0]}")
        for value, line, error in zip(values, value_lines, errors):
            if error:
                warnings.append(f"{spec.path}:{line}: warning: {key}={value} is rejected by wsntrack validate, so "
                                f"its runs will fail: {error}")
    return warnings


class SpecRun:
    """One wsntrack run of a spec sweep."""

    def __init__(self, engine, point, seed, names, out):
        self.engine = engine
        self.point = point  # [(key, value)]
        self.seed = seed
        self.name = "_".join([safe(engine)] + [f"{safe(n)}-{safe(v)}" for n, (_, v) in zip(names, point)]) + \
            f"_seed-{seed}"
        self.label = " ".join([engine] + [f"{n}={v}" for n, (_, v) in zip(names, point)] + [f"seed={seed}"])
        self.out = out
        self.command = []
        self.status = "not run"
        self.exit_code = None
        self.metrics = {}
        self.wall_s = None
        self.reused = False
        self.process = None
        self.log_file = None
        self.started = None
        self.attempts = 0

    @property
    def run_dir(self):
        return self.out / "runs" / self.name

    @property
    def log(self):
        return self.out / "logs" / f"{self.name}.log"


def metrics_of(path, metrics):
    """The metrics of a complete metrics.json; ValueError for an incomplete or malformed one."""
    with open(path, encoding="utf-8") as f:
        data = json.load(f)
    if not isinstance(data, dict) or not isinstance(data.get("metrics"), dict):
        raise ValueError("no 'metrics' object: not a complete metrics.json")
    values = {}
    for metric in metrics:
        where = METRIC_SOURCES[metric][1]
        try:
            value = metric_value(metric, data, Path(path).parent)
        except (OSError, KeyError, TypeError, json.JSONDecodeError) as error:
            raise ValueError(f"{metric}: cannot read it from the run directory ({error!r})") from None
        if value is not None and (isinstance(value, bool) or not isinstance(value, (int, float))):
            what = "the run's files" if callable(where) else ".".join(where)
            raise ValueError(f"{metric}: expected a number at {what}, got {value!r}")
        values[metric] = value
    return values


def reusable(run, scenario_sha, metrics):
    """Whether an earlier invocation completed exactly this run; fills in its results if so."""
    try:
        record = json.loads((run.run_dir / RECORD).read_text(encoding="utf-8"))
        if not isinstance(record, dict) or record.get("command") != run.command or record.get("exit") != 0 or \
                record.get("scenario_sha256") != scenario_sha:
            return False
        if sha256_of(run.run_dir / "metrics.json") != record.get("metrics_sha256"):
            return False
        run.metrics = metrics_of(run.run_dir / "metrics.json", metrics)
    except (OSError, ValueError):
        return False
    run.status, run.exit_code, run.reused = "ok", 0, True
    run.wall_s = record.get("wall_s") if isinstance(record.get("wall_s"), (int, float)) else None
    return True


# A cluster that lost the race for its DDS ports: between the launcher's check that a domain's ports
# are free and the bind, a cluster started at the same moment (this sweep's next run, or anyone's)
# took them. Nothing of the run's own is wrong, so it is started again, at most PORT_CLASH_ATTEMPTS times.
PORT_CLASH = re.compile(r"failed to create unicast sockets|dds_create_domain \d+ failed")
PORT_CLASH_ATTEMPTS = 3


def port_clash(run):
    """Whether a failed run's log, or its roles' logs, show it lost its DDS ports to another cluster."""
    logs = [run.log] + sorted((run.run_dir / "logs").glob("*.log"))
    for path in logs:
        try:
            if path.stat().st_size < (1 << 22) and PORT_CLASH.search(path.read_text(encoding="utf-8", errors="replace")):
                return True
        except OSError:
            pass
    return False


def start_spec_run(run, again=False):
    (run.run_dir / RECORD).unlink(missing_ok=True)  # never complete until it finishes again
    run.attempts = run.attempts + 1 if again else 1
    run.log_file = open(run.log, "a" if again else "w", encoding="utf-8")
    if again:
        run.log_file.write(f"sweep: the run lost its DDS ports to another cluster starting at the same time; "
                           f"attempt {run.attempts} of {PORT_CLASH_ATTEMPTS}\n")
    run.log_file.write("$ " + shlex.join(run.command) + "\n")
    run.log_file.flush()
    run.started = time.monotonic()
    run.process = subprocess.Popen(run.command, stdout=run.log_file, stderr=subprocess.STDOUT,
                                   stdin=subprocess.DEVNULL)


def finish_spec_run(run, scenario_sha, metrics):
    run.log_file.close()
    run.wall_s = time.monotonic() - run.started
    run.exit_code = run.process.returncode
    run.status = "failed"
    record = {"command": run.command, "scenario_sha256": scenario_sha, "exit": run.exit_code,
              "wall_s": round(run.wall_s, 3), "finished_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())}
    if run.exit_code == 0:
        try:
            record["metrics_sha256"] = sha256_of(run.run_dir / "metrics.json")
            run.metrics = metrics_of(run.run_dir / "metrics.json", metrics)
            run.status = "ok"
        except (OSError, ValueError) as error:
            record["exit"] = None
            with open(run.log, "a", encoding="utf-8") as log:
                log.write(f"sweep: cannot read {run.run_dir / 'metrics.json'}: {error}\n")
    record["status"] = run.status
    if run.run_dir.is_dir():
        temporary = run.run_dir / (RECORD + ".tmp")
        temporary.write_text(json.dumps(record, indent=2) + "\n", encoding="utf-8")
        os.replace(temporary, run.run_dir / RECORD)


def duration(seconds):
    seconds = int(round(seconds))
    if seconds < 60:
        return f"{seconds} s"
    if seconds < 3600:
        return f"{seconds // 60} min {seconds % 60:02d} s"
    return f"{seconds // 3600} h {seconds % 3600 // 60:02d} min"


def run_spec_runs(runs, jobs, scenario_sha, metrics):
    """Runs up to `jobs` clusters at a time. Returns the signal number that stopped it, or None."""
    stop = {"signal": None}

    def on_signal(signum, frame):
        stop["signal"] = signum

    previous = {s: signal.signal(s, on_signal) for s in (signal.SIGINT, signal.SIGTERM)}
    pending = list(runs)
    running = []
    done = failed = 0
    began = time.monotonic()
    try:
        while (pending or running) and not stop["signal"]:
            while pending and len(running) < jobs and not stop["signal"]:
                run = pending.pop(0)
                start_spec_run(run)
                running.append(run)
            still = []
            for run in running:
                if run.process.poll() is None:
                    still.append(run)
                    continue
                if run.process.returncode != 0 and run.attempts < PORT_CLASH_ATTEMPTS and port_clash(run):
                    run.log_file.close()
                    print(f"[{done}/{len(runs)}] {run.label}: lost its DDS ports to another cluster starting at the "
                          "same time; starting it again", file=sys.stderr, flush=True)
                    start_spec_run(run, again=True)
                    still.append(run)
                    continue
                finish_spec_run(run, scenario_sha, metrics)
                done += 1
                failed += run.status != "ok"
                if run.status == "ok":
                    outcome = f"ok, {run.wall_s:.1f} s"
                else:
                    outcome = f"FAILED (exit {run.exit_code}) after {run.wall_s:.1f} s; see {run.log}"
                left = len(runs) - done
                elapsed = time.monotonic() - began
                tail = f"ETA {duration(elapsed / done * left)}" if left else f"all done in {duration(elapsed)}"
                print(f"[{done}/{len(runs)}] {run.label} ... {outcome} | {failed} failed | {tail}",
                      file=sys.stderr, flush=True)
            running = still
            if running:
                time.sleep(0.05)
        if stop["signal"]:
            # Stop only the runs this sweep started, each by its own PID: wsntrack stops its role
            # processes on SIGTERM. Further signals wait until they have stopped.
            for s in previous:
                signal.signal(s, signal.SIG_IGN)
            print(f"sweep.py: {signal.Signals(stop['signal']).name}: stopping {plural(len(running), 'running run')}",
                  file=sys.stderr, flush=True)
            for run in running:
                if run.process.poll() is None:
                    run.process.terminate()
            deadline = time.monotonic() + 20
            for run in running:
                try:
                    run.process.wait(timeout=max(0.1, deadline - time.monotonic()))
                except subprocess.TimeoutExpired:
                    run.process.kill()
                    run.process.wait()
                run.log_file.close()
                run.status, run.exit_code = "interrupted", run.process.returncode
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)
    return stop["signal"]


def cell_text(value):
    return "" if value is None else repr(float(value)) if isinstance(value, float) else str(value)


def write_spec_results(path, spec, runs):
    keys = [k for k, *_ in spec.grid]
    with open(path, "w", newline="", encoding="utf-8") as f:
        writer = csv.writer(f)
        writer.writerow(["engine"] + keys + ["seed", "status", "exit"] + spec.metrics +
                        ["wall_s", "reused", "run_dir", "log", "command"])
        for run in runs:
            wall = "" if run.wall_s is None else f"{run.wall_s:.3f}"
            writer.writerow([run.engine] + [v for _, v in run.point] +
                            [run.seed, run.status, cell_text(run.exit_code)] +
                            [cell_text(run.metrics.get(m)) if run.status == "ok" else "" for m in spec.metrics] +
                            [wall, int(run.reused), run.run_dir.relative_to(run.out), run.log.relative_to(run.out),
                             shlex.join(run.command)])


def summarise(spec, points, runs):
    """{(point, engine): {"runs", "ok", "failed", metric: (n, mean, sd, low, high)}}."""
    cells = {}
    for point in points:
        for engine in spec.engines:
            mine = [r for r in runs if r.engine == engine and r.point == point]
            cell = {"runs": len(mine), "ok": sum(r.status == "ok" for r in mine),
                    "failed": sum(r.status == "failed" for r in mine)}
            for metric in spec.metrics:
                cell[metric] = describe_stats([r.metrics[metric] for r in mine
                                               if r.status == "ok" and r.metrics.get(metric) is not None])
            cells[(tuple(point), engine)] = cell
    return cells


def write_summary(path, spec, points, cells):
    keys = [k for k, *_ in spec.grid]
    with open(path, "w", newline="", encoding="utf-8") as f:
        writer = csv.writer(f)
        header = ["engine"] + keys + ["runs", "ok", "failed"]
        for metric in spec.metrics:
            header += [f"{metric}_n", f"{metric}_mean", f"{metric}_sd", f"{metric}_ci95_low", f"{metric}_ci95_high"]
        writer.writerow(header)
        for point in points:
            for engine in spec.engines:
                cell = cells[(tuple(point), engine)]
                row = [engine] + [v for _, v in point] + [cell["runs"], cell["ok"], cell["failed"]]
                for metric in spec.metrics:
                    row += [cell_text(x) for x in cell[metric]]
                writer.writerow(row)


def spec_table(spec, points, names, cells, fixed_text):
    lines = [f"## {spec.title or 'Sweep of ' + spec.scenario.name}", ""]
    if spec.notes:
        lines += [spec.notes.strip(), ""]
    lines += [f"Scenario {spec.scenario.name}; {'seed' if len(spec.seeds) == 1 else 'seeds'} {seeds_text(spec.seeds)} "
              f"({len(spec.seeds)} per cell){'; fixed: ' + fixed_text if fixed_text else ''}.", "",
              "Each cell is the mean over the seeds ± the half-width of its 95 % confidence interval (Student's t); "
              "(k/n): only k of the n runs were counted (a run failed, or the metric is undefined for it); –: none.", ""]
    header = list(names) + [f"{e} {METRIC_SOURCES[m][0]}" for e in spec.engines for m in spec.metrics]
    lines.append("| " + " | ".join(header) + " |")
    lines.append("|" + "|".join(["---"] * len(names) + ["---:"] * (len(header) - len(names))) + "|")
    for point in points:
        row = [v for _, v in point]
        for engine in spec.engines:
            cell = cells[(tuple(point), engine)]
            for metric in spec.metrics:
                n, mean, _, low, high = cell[metric]
                text = "–" if n == 0 else f"{mean:.4f}" + ("" if low is None else f" ± {(high - low) / 2:.4f}")
                if n != cell["runs"]:
                    text += f" ({n}/{cell['runs']})"
                row.append(text)
        lines.append("| " + " | ".join(row) + " |")
    return "\n".join(lines) + "\n"


def save_figure(plt, fig, path):
    """Lays out, writes and closes one figure; returns its path."""
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def draw_plots(directory, spec, points, cells, fixed_text):
    """plots/: a line plot per metric (1-D grid) or a heat map per metric and engine (2-D grid)."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        import numpy as np
    except ImportError as error:
        print(f"sweep.py: no plots: {error} (Debian: apt-get install python3-matplotlib; run with /usr/bin/python3)",
              file=sys.stderr)
        return []
    directory.mkdir(exist_ok=True)
    for old in list(directory.glob("*.png")):
        old.unlink()
    subtitle = (f"{spec.scenario.name}, {len(spec.seeds)} seed{'s' if len(spec.seeds) != 1 else ''} per point"
                f"{'; ' + fixed_text if fixed_text else ''}")
    written = []

    def axis(values):
        numeric = [number(v) for v in values]
        if all(x is not None for x in numeric):
            return numeric, False
        return list(range(len(values))), True

    def position(values, positions, text):
        for v, p in zip(values, positions):
            if same_value(v, text):
                return p
        return number(text)

    def stat(point, engine, metric, index):
        value = cells[(tuple(point), engine)][metric][index]
        return np.nan if value is None else value

    if len(spec.grid) == 1:
        key, values = spec.grid[0][0], spec.grid[0][1]
        xs, categorical = axis(values)
        for metric in spec.metrics:
            fig, ax = plt.subplots(figsize=(7.5, 4.8))
            for engine in spec.engines:
                mean = np.array([stat(p, engine, metric, 1) for p in points])
                low = np.array([stat(p, engine, metric, 3) for p in points])
                high = np.array([stat(p, engine, metric, 4) for p in points])
                line, = ax.plot(xs, mean, marker="o", label=engine)
                ax.fill_between(xs, low, high, color=line.get_color(), alpha=0.2, linewidth=0)
            for reference in spec.references:
                if reference["metric"] not in (None, metric):
                    continue
                label = reference["label"]
                if reference["value"] is not None:
                    ax.axhline(reference["value"], color="0.3", linestyle="--", linewidth=1, label=label)
                    label = None
                if key in reference["at"]:
                    ax.axvline(position(values, xs, reference["at"][key]), color="0.3", linestyle=":",
                               linewidth=1.2, label=label)
            if categorical:
                ax.set_xticks(xs)
                ax.set_xticklabels(values)
            ax.set_xlabel(key)
            ax.set_ylabel(f"{METRIC_SOURCES[metric][0]} ({metric})")
            ax.set_title(f"{spec.title or METRIC_SOURCES[metric][0] + ' against ' + key}\n{subtitle}; "
                         "band: 95 % CI of the mean", fontsize=9)
            ax.grid(True, alpha=0.3)
            ax.legend(fontsize=8)
            written.append(save_figure(plt, fig, directory / f"{safe(metric)}.png"))
        return written

    (row_key, row_values, *_), (column_key, column_values, *_) = spec.grid
    for metric in spec.metrics:
        matrices = {}
        for engine in spec.engines:
            matrix = np.full((len(row_values), len(column_values)), np.nan)
            for point in points:
                i, j = row_values.index(point[0][1]), column_values.index(point[1][1])
                matrix[i, j] = stat(point, engine, metric, 1)
            matrices[engine] = matrix
        finite = np.concatenate([m[np.isfinite(m)] for m in matrices.values()])
        low, high = (finite.min(), finite.max()) if finite.size else (0.0, 1.0)
        for engine, matrix in matrices.items():
            fig, ax = plt.subplots(figsize=(max(6.5, 2.5 + 1.0 * len(column_values)),
                                            max(4.5, 2.2 + 0.6 * len(row_values))))
            image = ax.imshow(np.ma.masked_invalid(matrix), origin="lower", aspect="auto", cmap="viridis",
                              vmin=low, vmax=high if high > low else low + 1e-9)
            fig.colorbar(image, ax=ax, label=f"{METRIC_SOURCES[metric][0]} (mean)")
            for i in range(len(row_values)):
                for j in range(len(column_values)):
                    point = ((row_key, row_values[i]), (column_key, column_values[j]))
                    n, mean, _, ci_low, ci_high = cells[(point, engine)][metric]
                    text = "–" if n == 0 else f"{mean:.3g}" + ("" if ci_low is None else
                                                                f"\n±{(ci_high - ci_low) / 2:.2g}")
                    ax.text(j, i, text, ha="center", va="center", fontsize=7,
                            color="white" if n and mean < (low + high) / 2 else "black")
            handles = []
            for reference in spec.references:
                if reference["metric"] not in (None, metric):
                    continue
                drawn = False
                finite_cells = np.isfinite(matrix)
                if reference["value"] is not None and min(matrix.shape) >= 2 and finite_cells.any() and \
                        np.nanmin(matrix) < reference["value"] < np.nanmax(matrix):
                    ax.contour(np.arange(len(column_values)), np.arange(len(row_values)), np.ma.masked_invalid(matrix),
                               levels=[reference["value"]], colors="red", linestyles="--", linewidths=1.2)
                    drawn = True
                if row_key in reference["at"]:
                    ax.axhline(position(row_values, range(len(row_values)), reference["at"][row_key]),
                               color="red", linestyle=":", linewidth=1.2)
                    drawn = True
                if column_key in reference["at"]:
                    ax.axvline(position(column_values, range(len(column_values)), reference["at"][column_key]),
                               color="red", linestyle=":", linewidth=1.2)
                    drawn = True
                if drawn:
                    handles.append(plt.Line2D([], [], color="red", linestyle="--", label=reference["label"]))
            ax.set_xticks(range(len(column_values)))
            ax.set_xticklabels(column_values)
            ax.set_yticks(range(len(row_values)))
            ax.set_yticklabels(row_values)
            ax.set_xlabel(column_key)
            ax.set_ylabel(row_key)
            ax.set_title(f"{spec.title or METRIC_SOURCES[metric][0]}: {engine}\n{subtitle}\n"
                         "cells: mean ± half-width of the 95 % CI", fontsize=8)
            if handles:
                ax.legend(handles=handles, fontsize=7, loc="upper left", bbox_to_anchor=(0, -0.18))
            written.append(save_figure(plt, fig, directory / f"{safe(metric)}_{safe(engine)}.png"))
    return written


def sweep_description(spec, wsntrack, scenario_sha):
    return {
        "form": "spec", "spec": str(spec.path.resolve()), "scenario": str(spec.scenario),
        "scenario_sha256": scenario_sha, "wsntrack": str(wsntrack),
        "grid": {k: v for k, v, *_ in spec.grid}, "engines": spec.engines, "seeds": spec.seeds,
        "set": {k: v for k, v in spec.fixed}, "in_process": spec.in_process, "metrics": spec.metrics,
        "title": spec.title, "notes": spec.notes,
        "reference": [{k: v for k, v in r.items() if k != "line"} for r in spec.references],
    }


def shown(value):
    """A value of sweep.json as a difference shows it: (not set), a word, [a, b] or JSON."""
    if value is None:
        return "(not set)"
    if isinstance(value, list) and all(isinstance(v, (str, int, float)) for v in value):
        return "[" + ", ".join(str(v) for v in value) + "]"
    return value if isinstance(value, str) else json.dumps(value, ensure_ascii=False)


def differences(old, new, fields):
    lines = []
    for field in fields:
        if old.get(field) != new.get(field):
            if field == "scenario_sha256":
                lines.append("  the scenario file's contents changed")
            elif field == "seeds":
                lines.append(f"  seeds: {seeds_text(old.get('seeds') or [])} -> {seeds_text(new['seeds'])}")
            elif isinstance(new.get(field), dict) and isinstance(old.get(field), dict):
                for key in list(old[field]) + [k for k in new[field] if k not in old[field]]:
                    if old[field].get(key) != new[field].get(key):
                        lines.append(f"  {field}: {key}: {shown(old[field].get(key))} -> {shown(new[field].get(key))}")
            else:
                lines.append(f"  {field}: {shown(old.get(field))} -> {shown(new.get(field))}")
    return lines


def parse_spec_args(argv):
    parser = argparse.ArgumentParser(
        prog="sweep.py", description=SPEC_DESCRIPTION, epilog=SPEC_EPILOG,
        usage="%(prog)s SPEC.yaml [--out DIR] [-j N] [--force] [--seeds SEEDS] [--set KEY=VALUE]... [--wsntrack PATH]",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("spec", type=Path, help="the sweep spec (YAML), e.g. sweeps/oh_fig7_pte.yaml")
    parser.add_argument("--out", type=Path, default=None,
                        help="sweep directory (default: runs/<spec name>); the same DIR again resumes the sweep")
    parser.add_argument("-j", "--jobs", type=int, default=None,
                        help="runs at a time (default: the number of cores, here %d)" % (os.cpu_count() or 1))
    parser.add_argument("--force", action="store_true",
                        help="go on in a DIR made by a different sweep (keeping the runs whose command is unchanged)")
    parser.add_argument("--seeds", default=None, help="instead of the spec's seeds: 1-5, 1,3,7 or 1-3,10")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", dest="fixed",
                        help="a fixed value added to (or replacing one of) the spec's set (repeatable)")
    parser.add_argument("--wsntrack", type=Path, default=REPO / "build" / "bin" / "wsntrack",
                        help="the wsntrack executable (default: build/bin/wsntrack of this repository)")
    return parser.parse_args(argv)


def spec_main(argv):
    args = parse_spec_args(argv)
    warnings = []
    try:
        if args.jobs is not None and args.jobs < 1:
            raise UsageError("-j/--jobs must be at least 1")
        if not args.spec.is_file():
            raise UsageError(f"{args.spec}: no such spec file")
        spec = load_spec(args.spec)
        if args.seeds is not None:
            spec.seeds = parse_seeds(args.seeds)
        for text in args.fixed:
            key, value = split_key_value(text, "--set")
            if key in ("tracker.engine", "run.seed"):
                raise UsageError(f"--set {key}: choose {'engines' if key == 'tracker.engine' else 'seeds'} in the "
                                 f"spec{'' if key == 'tracker.engine' else ' or with --seeds'}")
            if any(key == k for k, *_ in spec.grid):
                raise UsageError(f"--set {key}: the spec's grid sweeps it")
            spec.fixed = [(k, v) for k, v in spec.fixed if k != key] + [(key, value)]
            spec.fixed_lines.pop(key, None)
        wsntrack = args.wsntrack.resolve() if args.wsntrack.exists() else args.wsntrack
        if not os.access(wsntrack, os.X_OK):
            raise UsageError(f"--wsntrack: {args.wsntrack} is not an executable (build first: cmake --build build)")
        warnings = check_with_wsntrack(spec, wsntrack)
        out = args.out or Path("runs") / args.spec.stem
        if out.exists() and not out.is_dir():
            raise UsageError(f"--out: {out} is not a directory")
        out = out.resolve()
        scenario_sha = sha256_of(spec.scenario)
        description = sweep_description(spec, wsntrack, scenario_sha)
        if out.is_dir() and any(out.iterdir()):
            try:
                earlier = json.loads((out / "sweep.json").read_text(encoding="utf-8"))
            except (OSError, ValueError):
                raise UsageError(f"--out: {out} is not empty and holds no sweep (no readable sweep.json); "
                                 "choose another") from None
            if earlier.get("form") != "spec":
                changed = ["  it holds a sweep of the flag form (sweep.py --scenario ...)"]
            else:
                changed = differences(earlier, description, RUN_FIELDS)
            if changed and not args.force:
                raise UsageError(f"--out: {out} holds a different sweep:\n" + "\n".join(changed) +
                                 "\nnothing run: choose another --out, or --force to go on here (runs whose command "
                                 "did not change are kept, the others are run)")
            if changed:
                print("sweep.py: --force: going on in a directory of a different sweep:\n" + "\n".join(changed),
                      file=sys.stderr)
            elif earlier.get("form") == "spec":
                presentation = differences(earlier, description, PRESENTATION_FIELDS)
                if presentation:
                    print("sweep.py: tables and plots follow the changed spec:\n" + "\n".join(presentation),
                          file=sys.stderr)
    except (UsageError, SpecError) as error:
        print(f"sweep.py: {error}" if isinstance(error, UsageError) else str(error), file=sys.stderr)
        return 2
    for warning in warnings:
        print(warning, file=sys.stderr)

    jobs = args.jobs or os.cpu_count() or 1
    names = short_names([k for k, *_ in spec.grid])
    points = [list(p) for p in itertools.product(*[[(k, v) for v in values] for k, values, *_ in spec.grid])]
    runs = [SpecRun(e, p, s, names, out) for p in points for e in spec.engines for s in spec.seeds]
    taken = set()
    for run in runs:  # values that differ only in characters a file name cannot hold
        while run.name in taken:
            run.name += "_"
        taken.add(run.name)
        run.command = [str(wsntrack), "run", str(spec.scenario), "--seed", str(run.seed), "--out", str(run.run_dir),
                       "--overwrite", "--quiet", "--no-plot"] + \
            set_args(engine_sets(run.engine) + spec.fixed + run.point) + (["--in-process"] if spec.in_process else [])
    (out / "runs").mkdir(parents=True, exist_ok=True)
    (out / "logs").mkdir(exist_ok=True)
    description["command"] = shlex.join([sys.argv[0]] + argv)
    (out / "sweep.json").write_text(json.dumps(description, indent=2, ensure_ascii=False) + "\n", encoding="utf-8")

    to_run = [run for run in runs if not reusable(run, scenario_sha, spec.metrics)]
    print(f"sweep.py: {plural(len(runs), 'run')} ({plural(len(points), 'grid point')} x "
          f"{plural(len(spec.engines), 'engine')} x {plural(len(spec.seeds), 'seed')}) into {out}: "
          f"{len(runs) - len(to_run)} complete from an earlier invocation, " +
          (f"{len(to_run)} to run, {min(jobs, len(to_run))} at a time" if to_run else "nothing to run"),
          file=sys.stderr, flush=True)
    stopped = run_spec_runs(to_run, jobs, scenario_sha, spec.metrics)

    fixed_text = " ".join(f"{k}={v}" for k, v in spec.fixed)
    write_spec_results(out / "results.csv", spec, runs)
    cells = summarise(spec, points, runs)
    write_summary(out / "summary.csv", spec, points, cells)
    table = spec_table(spec, points, names, cells, fixed_text)
    (out / "table.md").write_text(table, encoding="utf-8")
    sys.stdout.write(table)
    sys.stdout.flush()
    if stopped:
        unfinished = sum(r.status in ("interrupted", "not run") for r in runs)
        print(f"sweep.py: stopped; {unfinished} of {len(runs)} runs unfinished. Run the same command again to "
              f"resume: finished runs are kept. Results so far: {out / 'results.csv'}", file=sys.stderr)
        return 128 + stopped
    plots = draw_plots(out / "plots", spec, points, cells, fixed_text)
    failed = [r for r in runs if r.status == "failed"]
    if failed:
        print(f"sweep.py: {len(failed)} of {len(runs)} runs failed (not counted in summary.csv; run the same "
              "command again to retry them):", file=sys.stderr)
        for run in failed:
            print(f"  {run.label}: exit {run.exit_code}, log {run.log}", file=sys.stderr)
    print(f"sweep.py: {out / 'results.csv'}, {out / 'summary.csv'}"
          f"{f', {len(plots)} plots in ' + str(out / 'plots') if plots else ''}", file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
