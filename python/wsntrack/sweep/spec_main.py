"""`wsntrack sweep SPEC.yaml | --scenario FILE ...`: the spec read (or built from the flags) and
checked, the directory compared with the sweep made there before, the runs that are not complete
run, and the results, summary, table and plots written."""

import argparse
import importlib
import itertools
import json
import os
import shlex
import sys
from pathlib import Path

from .common import PROG, UsageError, default_wsntrack, make_runs, plural, run_command, seeds_text, short_names
from .plots import PLOT_FORMATS, draw_plots
from .executors import DaskExecutor, LocalExecutor, require_distributed
from .runner import check_with_wsntrack, reusable, run_spec_runs
from .spec import SpecError, load_spec
from .summary import spec_table, summarise, write_spec_results, write_summary
from .from_flags import apply_options, check_forms, default_out, spec_from_flags
from .task import sha256_of

SPEC_DESCRIPTION = """\
Runs the sweep a spec file describes (sweeps/*.yaml), or one given by flags, in parallel, and
resumes it when run again.

Without a spec file, --scenario FILE and any number of --set-grid KEY=V1,V2,... (the grid is their
product) give the sweep, with --engines, --seeds, --set, --metrics and --in-process for the rest:
the flags build the same spec in memory, and everything below holds for both.

A spec is a YAML mapping:

  scenario: scenarios/oh_single_supernode.yaml   # relative to the spec's directory, else to the repository
  grid:                                          # 1 or 2 swept keys (a line plot, or a heat map)
    network.pte: [0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6]
  engines: [mcmcda, gnn]                         # default: the scenario's own engine
  seeds: 1-10                                    # or 3, or [1, 4, 9]; default 1
  set: {network.pde: 0}                          # fixed values for every run (wsntrack run --set)
  metrics: [eps_k, eps_x_gated, ospa]            # default eps_k, eps_x_gated, ospa
  x: delivery_ratio                              # plot against this metric of each run, not the swept value
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
with absolute paths; -j runs at a time (default: the number of cores), or on a Dask cluster with
--scheduler (below), with progress, failures and an ETA on stderr. A run that lost its DDS ports
to a cluster started at the same moment (Cyclone's "failed to create unicast sockets") is started
again (3 attempts in all). A finished run leaves
DIR/runs/NAME/sweep_run.json: its command, the scenario file's SHA-256 and the SHA-256 of its
metrics.json. Run again with the same DIR, the sweep skips
every run whose record matches the run it would start and whose metrics.json is complete and
unchanged, and runs the others: a sweep stopped with Ctrl-C or SIGTERM (each running wsntrack is
sent SIGTERM by its PID, then SIGKILL after 20 s) resumes where it stopped, a failed run is run
again. When what the runs are changed since DIR was made (the scenario file or its contents,
grid, engines, seeds, set, in_process or the wsntrack executable's path, from the spec or from
--seeds, --set, --engines, --in-process or --wsntrack), the sweep says what differs and stops,
unless --force: then the runs whose command did not change are kept and the others are run. A
changed title, notes, metrics, x or reference only changes the tables and plots.

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

On a Dask cluster (--scheduler ADDRESS, Debian's python3-distributed): each run is a task that a
worker runs as above, started by `dask worker` processes as many at a time as they have threads
(--nthreads); none of -j. ADDRESS is the scheduler's (tcp://HOST:8786), or the file `dask scheduler
--scheduler-file FILE` wrote. The workers write the run directories into DIR themselves: the
wsntrack executable, the scenario, this tool's tree and DIR must be at the same paths on the client
and on every worker (a shared filesystem), which the sweep checks on each worker before anything
runs. The metrics come back to the client, which writes results.csv, summary.csv, table.md and
plots as above, in the order of the runs, not of their completion: summary.csv is the same as on
this machine. A worker that dies has its runs started again on another (its wsntrack is sent
SIGTERM; the run starts again once it has ended); a run that fails is failed, as on this machine.
Resuming works across both: the same DIR skips the finished runs whichever ran them. SIGINT or
SIGTERM stops the runs in progress on the workers too. An unreachable scheduler (within Dask's
connect timeout, distributed.comm.timeouts.connect) or no worker within 60 s: exit status 2.

Exit status: 0 when every run succeeded, 1 when any failed, 2 for a usage or spec error,
128 + the signal number when stopped by SIGINT or SIGTERM.
"""

SPEC_EPILOG = """\
examples:
  wsntrack sweep sweeps/oh_fig7_pte.yaml --out runs/fig7
  wsntrack sweep sweeps/oh_fig7_pte.yaml --out runs/fig7-quick --seeds 1-2 --set run.ticks=20 -j 2
  wsntrack sweep sweeps/oh_fig7_pte.yaml --out runs/fig7-pdf --x delivery_ratio --plot-format pdf
  wsntrack sweep sweeps/oh_fig7_pte.yaml --out /shared/runs/fig7 --scheduler tcp://node01:8786
  wsntrack sweep --scenario scenarios/oh_quadrants.yaml --seeds 1-5 --engines gnn,mcmcda \\
      --set-grid network.pte=0,0.2,0.4 --set-grid network.pde=0,0.3,0.6 --out runs/sweep-loss
"""

# What a run's command depends on: a change of these in the same DIR needs --force.
RUN_FIELDS = ("scenario", "scenario_sha256", "wsntrack", "grid", "engines", "seeds", "set", "in_process")
# What only the tables and plots depend on.
PRESENTATION_FIELDS = ("metrics", "x", "title", "notes", "reference")


def sweep_description(spec, wsntrack, scenario_sha):
    return {
        "form": "spec", "spec": str(spec.path.resolve()) if spec.path else None, "scenario": str(spec.scenario),
        "scenario_sha256": scenario_sha, "wsntrack": str(wsntrack),
        "grid": {k: v for k, v, *_ in spec.grid}, "engines": spec.engines, "seeds": spec.seeds,
        "set": {k: v for k, v in spec.fixed}, "in_process": spec.in_process, "metrics": spec.metrics,
        "title": spec.title, "notes": spec.notes, **({"x": spec.x} if spec.x else {}),
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
    """Lines saying how `fields` of two sweep descriptions (sweep.json) differ, old -> new."""
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
    """The command line of a sweep, by spec file or by flags (one parser: flags build a spec)."""
    parser = argparse.ArgumentParser(
        prog=os.environ.get("WSNTRACK_PROG", "sweep.py"), description=SPEC_DESCRIPTION, epilog=SPEC_EPILOG,
        usage="%(prog)s (SPEC.yaml | --scenario FILE [--set-grid KEY=V1,V2,...]...) [--out DIR] "
              "[-j N | --scheduler ADDRESS] [--force] [--seeds SEEDS] [--engines E1,E2] [--set KEY=VALUE]... "
              "[--metrics M1,M2] [--in-process] [--x METRIC] [--plot-format png|svg|pdf] [--wsntrack PATH]",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("spec", type=Path, nargs="?", help="the sweep spec (YAML), e.g. sweeps/oh_fig7_pte.yaml")
    flags = parser.add_argument_group("a sweep without a spec file (flags build the spec)")
    flags.add_argument("--scenario", type=Path, default=None, help="the scenario every run starts from")
    flags.add_argument("--set-grid", action="append", default=[], metavar="KEY=V1,V2,...",
                       help="a swept key and its values (repeatable: the grid is the product of them)")
    parser.add_argument("--out", type=Path, default=None,
                        help="sweep directory (default: runs/<spec name>; for flags runs/sweep-<scenario>-<hash of the "
                        "grid, engines, seeds and set>, the same for the same flags); the same DIR again resumes "
                        "the sweep")
    parser.add_argument("-j", "--jobs", type=int, default=None,
                        help="runs at a time (default: the number of cores, here %d)" % (os.cpu_count() or 1))
    parser.add_argument("--scheduler", default=None, metavar="ADDRESS",
                        help="run the runs on the Dask cluster whose scheduler is at ADDRESS (tcp://HOST:8786, or a "
                        "--scheduler-file of dask scheduler) instead of on this machine; every path, DIR included, "
                        "must be the same on every worker (a shared filesystem). Needs python3-distributed")
    parser.add_argument("--force", action="store_true",
                        help="go on in a DIR made by a different sweep (keeping the runs whose command is unchanged)")
    parser.add_argument("--seeds", default=None, help="instead of the spec's seeds: 1-5, 1,3,7 or 1-3,10")
    parser.add_argument("--engines", default=None, metavar="E1,E2",
                        help="instead of the spec's engines (default: the scenario's own)")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", dest="fixed",
                        help="a fixed value added to (or replacing one of) the spec's set (repeatable)")
    parser.add_argument("--metrics", default=None, metavar="M1,M2",
                        help="instead of the spec's metrics (default eps_k,eps_x_gated,ospa); every name of "
                        "`wsntrack components --json`'s quantities, settled_NAME, and the report counts")
    parser.add_argument("--in-process", action="store_true", help="wsntrack run --in-process, as the spec's in_process")
    parser.add_argument("--wsntrack", type=Path, default=default_wsntrack(),
                        help="the wsntrack executable (default: the wsntrack that `wsntrack sweep` was started as)")
    parser.add_argument("--x", default=None, metavar="METRIC",
                        help="plot each metric against METRIC, measured per run (the mean per grid point), instead "
                        "of the swept value: e.g. delivery_ratio, the end-to-end share of reports delivered; as "
                        "the spec's x")
    parser.add_argument("--plot-format", choices=PLOT_FORMATS, default="png",
                        help="the plots' file format: png (110 dpi), or svg or pdf (vector, for a paper); "
                        "default png")
    return parser.parse_args(argv)


def _read_spec(args):
    """The spec (read, or built from the flags) with the command line's options applied; UsageError
    or SpecError."""
    check_forms(args)
    if args.jobs is not None and args.jobs < 1:
        raise UsageError("-j/--jobs must be at least 1")
    if args.jobs is not None and args.scheduler:
        raise UsageError("-j and --scheduler: on a cluster the workers' threads (dask worker --nthreads) decide "
                         "how many runs go at once")
    if args.scheduler:
        require_distributed()  # before anything runs, like SciPy below
    if args.spec is not None and not args.spec.is_file():
        raise UsageError(f"{args.spec}: no such spec file")
    spec = spec_from_flags(args) if args.spec is None else load_spec(args.spec)
    try:  # the confidence intervals' Student's t, checked before anything runs
        importlib.import_module("scipy.stats")
    except ImportError:
        raise UsageError("the confidence intervals of a sweep need SciPy (Debian: apt-get install python3-scipy); "
                         "run the tool with /usr/bin/python3") from None
    return apply_options(spec, args)


def _compare_with_earlier(out, description, force):
    """A non-empty DIR must hold a sweep: the same one (its presentation may differ: said on
    stderr), or with --force a different one (said on stderr); else UsageError."""
    try:
        earlier = json.loads((out / "sweep.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        raise UsageError(f"--out: {out} is not empty and holds no sweep (no readable sweep.json); "
                         "choose another") from None
    if earlier.get("form") != "spec":
        changed = ["  it holds a sweep of an older wsntrack's flag form, which did not resume"]
    else:
        changed = differences(earlier, description, RUN_FIELDS)
    if changed and not force:
        raise UsageError(f"--out: {out} holds a different sweep:\n" + "\n".join(changed) +
                         "\nnothing run: choose another --out, or --force to go on here (runs whose command "
                         "did not change are kept, the others are run)")
    if changed:
        print(f"{PROG}: --force: going on in a directory of a different sweep:\n" + "\n".join(changed),
              file=sys.stderr)
    elif earlier.get("form") == "spec":
        presentation = differences(earlier, description, PRESENTATION_FIELDS)
        if presentation:
            print(f"{PROG}: tables and plots follow the changed spec:\n" + "\n".join(presentation),
                  file=sys.stderr)


def _prepare(args):
    """(spec, wsntrack, DIR, the scenario's SHA-256, the sweep's description, warnings): everything
    checked before anything runs; UsageError or SpecError."""
    spec = _read_spec(args)
    wsntrack = args.wsntrack.resolve() if args.wsntrack.exists() else args.wsntrack
    if not os.access(wsntrack, os.X_OK):
        raise UsageError(f"--wsntrack: {args.wsntrack} is not an executable (build first: cmake --build build)")
    warnings = check_with_wsntrack(spec, wsntrack)
    out = args.out or default_out(args, spec)
    if out.exists() and not out.is_dir():
        raise UsageError(f"--out: {out} is not a directory")
    out = out.resolve()
    scenario_sha = sha256_of(spec.scenario)
    description = sweep_description(spec, wsntrack, scenario_sha)
    if out.is_dir() and any(out.iterdir()):
        _compare_with_earlier(out, description, args.force)
    return spec, wsntrack, out, scenario_sha, description, warnings


def _write_outputs(out, spec, points, names, runs, stopped, plot_format):
    """results.csv, summary.csv, table.md (also printed) and, unless stopped, plots/; returns the
    exit status."""
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
        print(f"{PROG}: stopped; {unfinished} of {len(runs)} runs unfinished. Run the same command again to "
              f"resume: finished runs are kept. Results so far: {out / 'results.csv'}", file=sys.stderr)
        return 128 + stopped
    plots = draw_plots(out / "plots", spec, points, cells, fixed_text, plot_format)
    failed = [r for r in runs if r.status == "failed"]
    if failed:
        print(f"{PROG}: {len(failed)} of {len(runs)} runs failed (not counted in summary.csv; run the same "
              "command again to retry them):", file=sys.stderr)
        for run in failed:
            print(f"  {run.label}: {run.reason or f'exit {run.exit_code}'}, log {run.log}", file=sys.stderr)
    print(f"{PROG}: {out / 'results.csv'}, {out / 'summary.csv'}"
          f"{f', {len(plots)} plots in ' + str(out / 'plots') if plots else ''}", file=sys.stderr)
    return 1 if failed else 0


def _executor(args, spec, wsntrack, out):
    """Where the runs go: this machine's cores (-j), or the Dask cluster of --scheduler (connected, and
    its workers checked to see the paths); UsageError."""
    if not args.scheduler:
        return LocalExecutor(args.jobs or os.cpu_count() or 1)
    return DaskExecutor(args.scheduler, [(wsntrack, "x"), (spec.scenario, "r")], out)


def _sweep(argv, spec, wsntrack, out, scenario_sha, description, executor, plot_format="png"):
    """Runs what is not complete from an earlier invocation and writes the outputs; the exit status."""
    names = short_names([k for k, *_ in spec.grid])
    points = [list(p) for p in itertools.product(*[[(k, v) for v in values] for k, values, *_ in spec.grid])]
    runs = make_runs(points, spec.engines, spec.seeds, names, out, spec.metrics)
    for run in runs:
        run.command = run_command(wsntrack, spec.scenario, run, spec.fixed, spec.in_process)
    (out / "runs").mkdir(parents=True, exist_ok=True)
    (out / "logs").mkdir(exist_ok=True)
    description["command"] = shlex.join([sys.argv[0]] + argv)
    (out / "sweep.json").write_text(json.dumps(description, indent=2, ensure_ascii=False) + "\n", encoding="utf-8")

    to_run = [run for run in runs if not reusable(run, scenario_sha, spec.metrics)]
    print(f"{PROG}: {plural(len(runs), 'run')} ({plural(len(points), 'grid point')} x "
          f"{plural(len(spec.engines), 'engine')} x {plural(len(spec.seeds), 'seed')}) into {out}: "
          f"{len(runs) - len(to_run)} complete from an earlier invocation, " +
          (f"{len(to_run)} to run, {executor.where(len(to_run))}" if to_run else "nothing to run"),
          file=sys.stderr, flush=True)
    stopped = run_spec_runs(to_run, executor, scenario_sha, spec.metrics)
    return _write_outputs(out, spec, points, names, runs, stopped, plot_format)


def spec_main(argv):
    """sweep.py SPEC.yaml ...: returns the exit status (0, 1 when a run failed, 2 for a usage or
    spec error, 128 + the signal that stopped it)."""
    args = parse_spec_args(argv)
    try:
        spec, wsntrack, out, scenario_sha, description, warnings = _prepare(args)
        for warning in warnings:
            print(warning, file=sys.stderr)
        executor = _executor(args, spec, wsntrack, out)
    except (UsageError, SpecError) as error:
        print(f"{PROG}: {error}" if isinstance(error, UsageError) else str(error), file=sys.stderr)
        return 2
    try:
        return _sweep(argv, spec, wsntrack, out, scenario_sha, description, executor, args.plot_format)
    finally:
        executor.close()
