"""The flag form of a sweep, `sweep.py --scenario FILE [--set-grid KEY=V1,V2,...] ...`: one run at
a time (or -j), every run again into the same --out, results.csv and a table of the means. Standard
library only, so that it runs with any python3."""

import argparse
import csv
import itertools
import json
import os
import shlex
import subprocess
import sys
import time
from pathlib import Path

from ..rundir import incomplete_reason, read_json
from .common import (REPO, UsageError, make_runs, parse_seeds, plural, run_command, scenario_engine, seeds_text,
                     short_names, split_key_value, engine_sets, validate)
from .metrics import DEFAULT_METRICS, metric_sources, metric_value

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


def read_metrics(run, metrics):
    """The run's tabulated metrics; None for a metric the run leaves undefined. ValueError for a run
    that is not complete (run.json's status): its numbers must never enter the table."""
    incomplete = incomplete_reason(run.run_dir)
    if incomplete:
        raise ValueError(f"{run.run_dir}: {incomplete}")
    data = read_json(run.run_dir / "metrics.json")
    try:
        return {metric: metric_value(metric, data, run.run_dir) for metric in metrics}
    except (KeyError, TypeError) as error:
        raise ValueError(f"cannot read a metric from {run.run_dir} ({error!r})") from None


def first_invalid(wsntrack, scenario, combos):
    """Checks every (engine, grid point) with `wsntrack validate`; returns the first error or None."""
    for sets in combos:
        command, error = validate(wsntrack, scenario, sets)
        if error is not None:
            return f"{error}\n(while checking: {shlex.join(command)})"
    return None


def mean_cell(runs, metric, total):
    values = [r.metrics[metric] for r in runs if r.status == "ok" and r.metrics[metric] is not None]
    if not values:
        return "–"
    text = f"{sum(values) / len(values):.4f}"
    return text if len(values) == total else f"{text} ({len(values)}/{total})"


def markdown_table(args, grid, names, engines, seeds, runs, fixed, metrics):
    """The table printed and saved as table.md: per grid point and engine the means over the seeds."""
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
    header = list(names) + [f"{e} {metric_sources()[m][0]}" for e in engines for m in metrics]
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
            cells += [mean_cell(cell_runs, m, len(seeds)) for m in metrics]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def write_csv(path, grid, runs, metrics):
    """results.csv: one row per run that was started."""
    keys = [k for k, _ in grid]
    with open(path, "w", newline="", encoding="utf-8") as f:
        writer = csv.writer(f)
        writer.writerow(["engine"] + keys + ["seed", "status"] + list(metrics) + ["wall_s", "run_dir", "log"])
        for run in runs:
            if run.status == "not run":
                continue
            metric_values = ["" if run.metrics[m] is None else f"{run.metrics[m]:.6f}" for m in metrics]
            wall = "" if run.wall_s is None else f"{run.wall_s:.3f}"
            writer.writerow([run.engine] + [v for _, v in run.point] + [run.seed, run.status] + metric_values +
                            [wall, run.run_dir, run.log])


def start(run, args, fixed):
    """Starts one run, its output into its log; returns (process, log file)."""
    command = run_command(args.wsntrack, args.scenario, run, fixed, args.in_process)
    log = open(run.log, "w", encoding="utf-8")
    log.write("$ " + shlex.join(command) + "\n")
    log.flush()
    run.started = time.monotonic()
    return subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL), log


def finish(run, process, metrics):
    """Records how a run that ended went: ok with its metrics, or failed."""
    run.wall_s = time.monotonic() - run.started
    run.exit_code = process.returncode
    if run.exit_code != 0:
        run.status = "failed"
        return
    try:
        run.metrics = read_metrics(run, metrics)
        run.status = "ok"
    except (OSError, ValueError) as error:
        run.status = "failed"
        with open(run.log, "a", encoding="utf-8") as log:
            log.write(f"sweep: the run exited 0 but is not counted: {error}\n")


def progress(done, total, run):
    if run.status == "ok":
        outcome = f"{run.wall_s:.1f} s"
    else:
        outcome = f"FAILED (exit {run.exit_code}) after {run.wall_s:.1f} s; see {run.log}"
        if (run.run_dir / "logs").is_dir():
            outcome += f" and {run.run_dir / 'logs'}/"
    print(f"[{done}/{total}] {run.label} ... {outcome}", file=sys.stderr, flush=True)


def run_all(runs, args, fixed, metrics):
    """Runs up to --jobs clusters at a time (each run picks a DDS domain of its own)."""
    pending = list(runs)
    running = []  # (run, process, log file)
    done = 0
    try:
        while pending or running:
            while pending and len(running) < args.jobs:
                run = pending.pop(0)
                process, log = start(run, args, fixed)
                running.append((run, process, log))
            still = []
            for run, process, log in running:
                if process.poll() is None:
                    still.append((run, process, log))
                    continue
                log.close()
                finish(run, process, metrics)
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
    """The flag form's command line."""
    usage = ("%(prog)s SPEC.yaml [--out DIR] [-j N] ...   (the spec form: %(prog)s SPEC.yaml --help)\n"
             "       %(prog)s --scenario SCENARIO [--seeds SEEDS] [--engines ENGINES] [--set-grid KEY=V1,V2,...]\n"
             "                [--set KEY=VALUE] [--out OUT] [-j JOBS] [--wsntrack WSNTRACK] [--metrics METRICS]\n"
             "                [--in-process]")
    parser = argparse.ArgumentParser(prog=os.environ.get("WSNTRACK_PROG", "sweep.py"), description=DESCRIPTION, epilog=EPILOG, usage=usage,
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
                        ", ".join(metric_sources()))
    parser.add_argument("--in-process", action="store_true",
                        help="run each cluster's roles as threads of one process (wsntrack run --in-process); "
                        "the results are the same")
    parser.add_argument("--scheduler", default=None, metavar="ADDRESS",
                        help="not in this form: the spec form (sweep.py SPEC.yaml --scheduler ADDRESS) runs a sweep "
                        "on a Dask cluster")
    return parser.parse_args(argv)


def _checked(args):
    """(metrics, seeds, grid, fixed, engines, out) of the flag form's arguments; UsageError for
    anything that cannot be run."""
    metrics = tuple(m.strip() for m in args.metrics.split(","))
    unknown = [m for m in metrics if m not in metric_sources()]
    if unknown or not metrics or len(set(metrics)) != len(metrics):
        raise UsageError(f"--metrics: expected distinct names from {', '.join(metric_sources())}, got '{args.metrics}'")
    seeds = parse_seeds(args.seeds)
    grid = parse_grid(args.set_grid)
    fixed = [split_key_value(t, "--set") for t in args.fixed]
    if args.jobs < 1:
        raise UsageError("--jobs must be at least 1")
    if args.scheduler:
        raise UsageError("--scheduler: the flag form runs on this machine only; write the sweep as a spec "
                         "(sweep.py SPEC.yaml --help) to run it on a Dask cluster")
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
    return metrics, seeds, grid, fixed, engines, out


def main(argv):
    """sweep.py --scenario FILE ...: returns the exit status (0, 1 when a run failed, 2 for a usage
    or validation error, 130 when interrupted)."""
    args = parse_args(argv)
    try:
        metrics, seeds, grid, fixed, engines, out = _checked(args)
    except UsageError as error:
        print(f"sweep.py: {error}", file=sys.stderr)
        return 2

    names = short_names([k for k, _ in grid])
    points = [list(p) for p in itertools.product(*[[(k, v) for v in values] for k, values in grid])]
    error = first_invalid(args.wsntrack, args.scenario, [engine_sets(e) + fixed + p for p in points for e in engines])
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

    runs = make_runs(points, engines, seeds, names, out, metrics)
    print(f"sweep.py: {plural(len(runs), 'run')} ({plural(len(points), 'grid point')} x "
          f"{plural(len(engines), 'engine')} x {plural(len(seeds), 'seed')}) into {out}", file=sys.stderr)
    interrupted = False
    try:
        run_all(runs, args, fixed, metrics)
    except KeyboardInterrupt:
        interrupted = True
        print("sweep.py: interrupted; writing what finished", file=sys.stderr)

    write_csv(out / "results.csv", grid, runs, metrics)
    table = markdown_table(args, grid, names, engines, seeds, runs, fixed, metrics)
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
