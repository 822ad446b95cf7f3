#!/usr/bin/env python3
"""Parameter sweeps over wsntrack clusters: one `wsntrack run` per (grid point, engine, seed),
every row in OUT/results.csv and a markdown table of the means over the seeds on stdout.

Standard library only, so that it runs with any python3 on the machine.
"""

import argparse
import csv
import itertools
import json
import os
import re
import shlex
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
    "position_error": ("<dx>", ("track_quality", "mean_position_error"), ("track_quality", "means_defined")),
}
DEFAULT_METRICS = ("eps_k", "eps_x", "ospa")
METRICS = DEFAULT_METRICS  # the tabulated ones, set from --metrics

DESCRIPTION = """\
Runs a grid of wsntrack clusters and tabulates their metrics.

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
    values = {}
    for metric in METRICS:
        _, path, defined = METRIC_SOURCES[metric]
        values[metric] = None if defined and lookup(data, defined) is False else lookup(data, path)
    return values


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
    parser = argparse.ArgumentParser(prog="sweep.py", description=DESCRIPTION, epilog=EPILOG,
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
    parser.add_argument("--jobs", type=int, default=1,
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


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
