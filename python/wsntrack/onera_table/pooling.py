"""Several runs of one algorithm made one: per target means, the classification and stop_mode blocks
pooled, the targets' true classes and class accuracies, and the share of each target's life the
sensors reported (from truth.csv and observations.csv)."""

import sys
from pathlib import Path

from ..rundir import InputError, read_csv
from .blocks import UNKNOWN_CLASS

def read_reported(arg, targets):
    """Per target, in increasing id order: the share of its alive ticks (truth.csv) with at least one
    delivered report of it (observations.csv). `targets` is the run's number of targets in metrics.json."""
    path = Path(arg)
    if not path.is_dir():
        raise InputError(f"{arg}: not a run directory, so no truth.csv and observations.csv beside it")
    truth = path / "truth.csv"
    alive = {}
    for tick, target in read_csv(truth, ["tick", "target"], [int, int]):
        alive.setdefault(target, set()).add(tick)
    if len(alive) != targets:
        raise InputError(f"{truth}: {len(alive)} targets, but its metrics.json has {targets}")
    reported = {target: set() for target in alive}
    for tick, target, fate in read_csv(path / "observations.csv", ["tick_generated", "target", "fate"],
                                       [int, int, str]):
        if fate == "delivered" and target in reported:
            reported[target].add(tick)
    return [len(reported[t] & alive[t]) / len(alive[t]) for t in sorted(alive)]


def average_reported(runs):
    """Per target the reported share averaged over the runs [(arg, metrics rows)], or None when some
    run's cannot be computed (each such run noted on stderr)."""
    shares = []
    for arg, rows in runs:
        try:
            shares.append(read_reported(arg, len(rows)))
        except InputError as error:
            print(f"onera_table.py: note: {error}; the reported column is shown as '-'", file=sys.stderr)
            shares.append(None)
    if not shares or any(s is None for s in shares):
        return None
    return [sum(s[j] for s in shares) / len(shares) for j in range(len(shares[0]))]


def mean_or_none(values):
    values = [v for v in values if v is not None]
    return sum(values) / len(values) if values else None


def average_runs(runs, label):
    """Per target (rse, tlr, tlr_length) averaged over the runs; every run must have the same targets."""
    counts = {len(rows) for _, rows in runs}
    if len(counts) != 1:
        listing = ", ".join(f"{arg} ({len(rows)})" for arg, rows in runs)
        raise InputError(f"{label} runs disagree on the number of targets: {listing}")
    n = counts.pop()
    out = []
    for j in range(n):
        rse = mean_or_none([rows[j][0] for _, rows in runs])
        tlr = mean_or_none([rows[j][1] for _, rows in runs])
        lengths = [rows[j][2] for _, rows in runs]
        tlr_length = None if any(v is None for v in lengths) else mean_or_none(lengths)
        out.append((rse, tlr, tlr_length))
    return out


def blocks_of(runs, k, block, label):
    """The blocks in place k of one algorithm's runs [(arg, path, rows, classification, stop_mode)],
    named `block` in metrics.json, or None when no run has one. Every run must have it, or none."""
    having = [run[1] for run in runs if run[k] is not None]
    lacking = [run[1] for run in runs if run[k] is None]
    if not having:
        return None
    if lacking:
        raise InputError(f"{lacking[0]}: no {block} block, but {having[0]} (another of the {label} runs) "
                         "has one: the runs of an algorithm must all have it (scored by the same wsntrack) or "
                         "none")
    return [run[k] for run in runs]


def pool_classification(runs, label):
    """The classification blocks of one algorithm's runs [(arg, path, rows, classification, stop_mode)]
    summed: {"runs", "declared" and "correct" (per target position, summed over the runs), "totals" (the
    run totals summed), "confusion" (summed)}, or None when no run has the block. Every run must have
    it, or none."""
    blocks = blocks_of(runs, 3, "classification", label)
    if blocks is None:
        return None
    n = len(runs[0][2])
    declared, correct = [0] * n, [0] * n
    totals = [0, 0, 0]
    confusion = {}
    for c in blocks:
        for j, (_, d, k) in c["targets"].items():
            declared[j] += d
            correct[j] += k
        totals = [a + b for a, b in zip(totals, c["totals"])]
        for truth, row in c["confusion"].items():
            summed = confusion.setdefault(truth, {})
            for name, count in row.items():
                summed[name] = summed.get(name, 0) + count
    return {"runs": len(runs), "declared": declared, "correct": correct, "totals": totals, "confusion": confusion}


def pool_stop_mode(runs, label):
    """The stop_mode blocks of one algorithm's runs [(arg, path, rows, classification, stop_mode)]
    pooled: {"runs", "totals": (ticks_stopped, mean while stopped, ticks_moving, mean while moving,
    ticks_without_stop_model) over the runs, "targets": {position: (ticks_stopped, mean, ticks_moving,
    mean)} over the runs that list the target}, each mean sum(mean * ticks) / sum(ticks) (None when
    the ticks sum to 0), or None when no run has the block. Every run must have it, or none."""
    blocks = blocks_of(runs, 4, "stop_mode", label)
    if blocks is None:
        return None

    def pool(entries):
        out = []
        for m in (0, 1):
            ticks = sum(e[2 * m] for e in entries)
            weighted = sum(e[2 * m + 1] * e[2 * m] for e in entries if e[2 * m])
            out += [ticks, weighted / ticks if ticks else None]
        return tuple(out)

    totals = pool([s["totals"] for s in blocks]) + (sum(s["totals"][4] for s in blocks),)
    positions = sorted({j for s in blocks for j in s["targets"]})
    targets = {j: pool([s["targets"][j] for s in blocks if j in s["targets"]]) for j in positions}
    return {"runs": len(runs), "totals": totals, "targets": targets}


def target_classes(runs):
    """Per target position, its true class in the classification blocks of the runs [(arg, path, rows,
    classification, stop_mode)] (None where no run lists the target: never associated); the same in
    every run."""
    classes = {}  # position: (class, path of the first run giving it)
    for _, path, _, c, _ in runs:
        if c is None:
            continue
        for j, (name, _, _) in sorted(c["targets"].items()):
            if j not in classes:
                classes[j] = (name, path)
            elif classes[j][0] != name:
                raise InputError(f"{path}: classification: target {j + 1} (track_quality.targets[{j}]) has class "
                                 f"'{name}', but '{classes[j][0]}' in {classes[j][1]}: the runs must be of the same "
                                 "scenario")
    n = max((len(rows) for _, _, rows, _, _ in runs), default=0)
    return [classes[j][0] if j in classes else None for j in range(n)]


def class_accuracy(pooled, classes):
    """Per target position, sum(ticks_correct) / sum(ticks_declared) over the runs; None when no tick
    was declared or the true class is unknown (or the target never associated)."""
    return [None if classes[j] in (None, UNKNOWN_CLASS) or pooled["declared"][j] == 0
            else pooled["correct"][j] / pooled["declared"][j] for j in range(len(pooled["declared"]))]
