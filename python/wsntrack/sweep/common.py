"""What the pieces of a sweep share: seeds and grids as written on the command line, the names of
runs, the `--set` arguments of `wsntrack run` and `wsntrack validate`, and progress wording."""

import os
import re
import shlex
import subprocess
from pathlib import Path

# The repository, when this package is its python/ (python/wsntrack/sweep/ is three levels down);
# for a build tree's or an installed copy it is not one (no scenarios/ there), and goes unused.
REPO = Path(__file__).resolve().parents[3]


def default_wsntrack():
    """The wsntrack a sweep runs unless --wsntrack names one: $WSNTRACK, else the repository's
    build/bin/wsntrack (this package in a source tree), else the wsntrack on PATH (an installed
    package), else the build path, which the sweep then reports as missing."""
    import shutil
    built = REPO / "build" / "bin" / "wsntrack"
    for candidate in (os.environ.get("WSNTRACK"), built, shutil.which("wsntrack")):
        if candidate and os.access(candidate, os.X_OK) and not os.path.isdir(candidate):
            return Path(candidate)
    return built


# How the sweep's messages name it: the command the user typed (`wsntrack sweep` sets this), else the script.
PROG = os.environ.get("WSNTRACK_PROG", "sweep.py")


class UsageError(Exception):
    """A command line, spec or combination that cannot be run: reported as one line, exit status 2."""


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


def short_names(keys):
    """Column names: the last part of each dotted key (network.pte -> pte) unless two collide."""
    last = [k.split(".")[-1] for k in keys]
    return [s if last.count(s) == 1 else k for s, k in zip(last, keys)]


def safe(text):
    """`text` with every run of characters a file name should not hold replaced by '_'."""
    return re.sub(r"[^A-Za-z0-9._-]+", "_", text)


def run_name(engine, point, seed, names):
    """(file name, label) of the run of `engine` at grid `point` ([(key, value)], its keys shown as
    `names`) with `seed`: 'gnn_pte-0.2_seed-3' and 'gnn pte=0.2 seed=3'."""
    name = "_".join([safe(engine)] + [f"{safe(n)}-{safe(v)}" for n, (_, v) in zip(names, point)]) + f"_seed-{seed}"
    label = " ".join([engine] + [f"{n}={v}" for n, (_, v) in zip(names, point)] + [f"seed={seed}"])
    return name, label


class SweepRun:
    """One wsntrack run of a sweep: what it runs and, once finished, how it went."""

    def __init__(self, engine, point, seed, names, out, metrics):
        self.engine = engine
        self.point = point  # [(key, value)] of the grid point
        self.seed = seed
        self.name, self.label = run_name(engine, point, seed, names)
        self.out = out
        self.command = []
        self.status = "not run"
        self.exit_code = None
        self.metrics = {m: None for m in metrics}
        self.wall_s = None
        self.reused = False  # complete from an earlier invocation (the spec form)
        self.process = None
        self.log_file = None
        self.started = None
        self.attempts = 0
        self.reason = None  # why a run failed without an exit status of wsntrack's (the spec form)

    @property
    def run_dir(self):
        return self.out / "runs" / self.name

    @property
    def log(self):
        return self.out / "logs" / f"{self.name}.log"


def make_runs(points, engines, seeds, names, out, metrics):
    """The runs of a sweep, grid point outermost and seeds innermost, so that each row of the table
    completes as early as it can; names made unique where values differ only in characters a file
    name cannot hold."""
    runs = [SweepRun(e, p, s, names, out, metrics) for p in points for e in engines for s in seeds]
    taken = set()
    for run in runs:
        while run.name in taken:
            run.name += "_"
        taken.add(run.name)
    return runs


def run_command(wsntrack, scenario, run, fixed, in_process):
    """The `wsntrack run` command of one run of a sweep."""
    return ([str(wsntrack), "run", str(scenario), "--seed", str(run.seed), "--out", str(run.run_dir), "--overwrite",
             "--quiet", "--no-plot"] + set_args(engine_sets(run.engine) + fixed + run.point)
            + (["--in-process"] if in_process else []))


def engine_sets(engine):
    return [("tracker.engine", engine)]


def set_args(pairs):
    """`--set KEY=VALUE` arguments of wsntrack for (key, value) pairs."""
    args = []
    for key, value in pairs:
        args += ["--set", f"{key}={value}"]
    return args


def validate(wsntrack, scenario, sets):
    """(the command `wsntrack validate SCENARIO --set ...` for `sets`, what it says is wrong with
    the scenario: None when it is valid)."""
    command = [str(wsntrack), "validate", str(scenario)] + set_args(sets)
    result = subprocess.run(command, capture_output=True, text=True, check=False)
    return command, None if result.returncode == 0 else (result.stderr or result.stdout).strip()


def scenario_engine(wsntrack, scenario, fixed):
    """The engine the scenario (with the fixed --set options) names, from `wsntrack validate`."""
    command = [str(wsntrack), "validate", str(scenario)] + set_args(fixed)
    result = subprocess.run(command, capture_output=True, text=True, check=False)
    match = re.search(r", engine (\S+)\)$", result.stdout.strip())
    if result.returncode != 0 or not match:
        raise UsageError((result.stderr or result.stdout).strip() or f"{shlex.join(command)} failed")
    return match.group(1)


def plural(n, word):
    return f"{n} {word}" + ("" if n == 1 else "s")


def duration(seconds):
    seconds = int(round(seconds))
    if seconds < 60:
        return f"{seconds} s"
    if seconds < 3600:
        return f"{seconds // 60} min {seconds % 60:02d} s"
    return f"{seconds // 3600} h {seconds % 3600 // 60:02d} min"
