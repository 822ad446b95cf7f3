"""The command line's part of a sweep: a sweep given by flags (`wsntrack sweep --scenario FILE
--set-grid KEY=V1,V2 ...`) is built into the same Spec a spec file gives, and the options that
change a spec (--seeds, --set, --engines, --metrics, --in-process, --x) are applied to either. So
there is one form of sweep: one parser, one scheduler, the same outputs."""

import hashlib
import json
from pathlib import Path

from .common import UsageError, parse_seeds, split_key_value
from .metrics import metric_sources
from .spec import KEY_PATTERN, Spec

# The options only a sweep without a spec file has: its scenario and grid.
FLAG_ONLY = (("scenario", "--scenario"), ("set_grid", "--set-grid"))


def parse_grid(texts):
    """['network.pte=0,0.2'] -> [('network.pte', ['0', '0.2'])]; keys in the order given."""
    grid = []
    for text in texts:
        key, values = split_key_value(text, "--set-grid")
        items = [v.strip() for v in values.split(",")]
        if any(v == "" for v in items) or len(set(items)) != len(items):
            raise UsageError(f"--set-grid {text}: expected KEY=V1,V2,... with distinct, non-empty values")
        if not KEY_PATTERN.fullmatch(key):
            raise UsageError(f"--set-grid {key}: expected a scenario key such as network.pte or supernodes[0].x")
        if key in ("tracker.engine", "run.seed"):
            raise UsageError(f"--set-grid {key}: choose {'engines with --engines' if key == 'tracker.engine' else 'seeds with --seeds'}")
        if any(key == k for k, _ in grid):
            raise UsageError(f"--set-grid {key}: given twice; list all its values in one --set-grid")
        grid.append((key, items))
    return grid


def spec_from_flags(args):
    """The Spec of `--scenario FILE [--set-grid KEY=V1,V2,...]...`: any number of swept keys (their
    product), the scenario's engine unless --engines, the default metrics unless --metrics."""
    if not args.scenario.is_file():
        raise UsageError(f"--scenario: {args.scenario} is not a file")
    spec = Spec(None)
    spec.scenario = args.scenario.resolve()
    spec.grid = [(key, values, None, [None] * len(values)) for key, values in parse_grid(args.set_grid)]
    return spec


def default_out(args, spec):
    """Where a sweep goes without --out: runs/<spec name>, or for flags runs/sweep-<scenario>-<hash of
    what its runs are> (scenario, grid, engines, seeds, set, in_process), so that the same flags again
    resume the same sweep and other flags make another."""
    if args.spec is not None:
        return Path("runs") / args.spec.stem
    what = json.dumps([str(spec.scenario), [(k, v) for k, v, *_ in spec.grid], spec.engines, spec.seeds,
                       spec.fixed, spec.in_process])
    return Path("runs") / f"sweep-{spec.scenario.stem}-{hashlib.sha256(what.encode()).hexdigest()[:8]}"


def check_forms(args):
    """UsageError unless the command line names exactly one of a spec file and --scenario, and a spec
    file comes without --scenario and --set-grid."""
    if args.spec is None and args.scenario is None:
        raise UsageError("expected a spec file (sweeps/*.yaml) or --scenario FILE; --help explains both")
    if args.spec is not None:
        for name, option in FLAG_ONLY:
            if getattr(args, name):
                raise UsageError(f"{option}: {args.spec} is a spec file, whose scenario and grid are its own; "
                                 "edit the spec, or give the sweep by flags without a spec file")


def _metric(name, option):
    if name not in metric_sources():
        raise UsageError(f"{option}: unknown metric '{name}'; expected one of: {', '.join(metric_sources())}")
    return name


def apply_options(spec, args):
    """The command line's changes to a spec: --seeds, --set, --engines, --metrics, --in-process, --x."""
    if args.seeds is not None:
        spec.seeds = parse_seeds(args.seeds)
    for text in args.fixed:
        key, value = split_key_value(text, "--set")
        if key in ("tracker.engine", "run.seed"):
            raise UsageError(f"--set {key}: choose {'engines' if key == 'tracker.engine' else 'seeds'} with "
                             f"{'--engines or the spec' if key == 'tracker.engine' else '--seeds or the spec'}")
        if any(key == k for k, *_ in spec.grid):
            raise UsageError(f"--set {key}: the grid sweeps it")
        spec.fixed = [(k, v) for k, v in spec.fixed if k != key] + [(key, value)]
        spec.fixed_lines.pop(key, None)
    if args.engines is not None:
        engines = [e.strip() for e in args.engines.split(",")]
        if any(not e for e in engines) or len(set(engines)) != len(engines):
            raise UsageError(f"--engines: expected distinct names like gnn,mcmcda, got '{args.engines}'")
        spec.engines, spec.engine_lines = engines, []
    if args.metrics is not None:
        metrics = [m.strip() for m in args.metrics.split(",")]
        if not metrics or len(set(metrics)) != len(metrics):
            raise UsageError(f"--metrics: expected distinct names, got '{args.metrics}'")
        spec.metrics = [_metric(m, "--metrics") for m in metrics]
        if spec.x and spec.x not in spec.metrics:
            spec.metrics.append(spec.x)
    if args.in_process:
        spec.in_process = True
    if args.x is not None:
        if len(spec.grid) != 1:
            raise UsageError(f"--x: a measured x axis needs a grid of one key; this sweep has {len(spec.grid)}")
        spec.x = _metric(args.x, "--x")
        if spec.x not in spec.metrics:
            spec.metrics.append(spec.x)
    return spec
