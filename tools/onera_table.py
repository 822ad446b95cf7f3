#!/usr/bin/python3
"""Table II of Pannetier et al. (FUSION 2014) beside our runs: per target RSE and TLR of algorithm 1
(with the road network) and algorithm 2 (without), the share of the target's life in which the
sensors reported it at all and, when the runs were scored with the classification metric, its true
class and class accuracy, as a Markdown table on stdout; then the paper's statistics and, with the
classification metric, the run-level classification scores and confusion matrices and, with the
stop_mode metric, the mean stop probability of the tracks while their targets stand still and move.

  onera_table.py --a1 RUN_DIR... --a2 RUN_DIR...   both algorithms, with the A1 - A2 deltas
  onera_table.py --a2 RUN_DIR...                   algorithm 2 only, beside the paper's A1 and A2
  onera_table.py RUN_DIR...                        the same as --a2 RUN_DIR...
  onera_table.py ... --plot FILE.png|FILE.svg       the table, and bar charts of it in FILE

Standard library only, like tools/sweep.py's flag form, so that it runs with any python3; --plot
alone needs matplotlib (Debian's python3-matplotlib, for /usr/bin/python3), imported only then.
"""

import argparse
import csv
import json
import math
import os
import statistics
import sys
from pathlib import Path

# Table II of Benjamin Pannetier, Jean Dezert and Genevieve Sella, "Multiple target tracking with
# wireless sensor network for ground battlefield surveillance", Proceedings of the 17th International
# Conference on Information Fusion (FUSION 2014), Salamanca, Spain, July 2014 (hal-01070361), §V:
# per target (1-20), (RSE in metres, TLR) of algorithm 1 (with roads) and of algorithm 2 (without).
PAPER_A1 = [(10.48, 0.99), (7.43, 1.0), (5.32, 1.0), (6.20, 0.88), (6.35, 1.0),
            (5.66, 0.68), (22.45, 0.60), (3.43, 1.0), (7.07, 0.86), (12.79, 0.63),
            (6.72, 0.82), (6.58, 0.81), (8.56, 0.51), (1.91, 1.0), (10.39, 0.37),
            (12.77, 0.34), (6.44, 0.78), (9.30, 0.48), (7.06, 0.60), (18.55, 0.38)]
PAPER_A2 = [(19.43, 0.80), (7.70, 1.0), (12.00, 1.0), (6.08, 0.90), (11.74, 0.59),
            (5.20, 0.68), (16.11, 0.85), (7.42, 0.90), (10.28, 0.50), (12.52, 0.45),
            (8.42, 0.85), (7.71, 0.89), (9.87, 0.61), (4.19, 1.0), (9.02, 0.51),
            (12.67, 0.31), (9.33, 0.51), (8.87, 0.46), (7.56, 0.44), (13.40, 0.88)]

DESCRIPTION = __doc__ + """
Each RUN_DIR is a run directory written by 'wsntrack run' (or its metrics.json itself). The tool reads
metrics.json's track_quality block (docs/METRICS.md): per target, in file order (increasing target id),
rse_position, tlr (associated ticks / alive ticks) and tlr_length (associated path length / path
length). Target N of the table is the N-th target of the file, which onera2014_like numbers as the
paper does. Several runs of an algorithm (one per seed, say) are averaged per target: RSE over the
runs in which the target was ever associated (errors_defined), TLR over every run. Every run must
have the same number of targets.

The "reported" column tells how much of a target's life the sensors covered at all: the share of its
alive ticks (the distinct ticks of truth.csv's rows with that target) in which at least one report of
it was delivered (the distinct tick_generated of observations.csv's rows with that target and fate
'delivered'; lost reports and false alarms, target -1, do not count). It is read from the run
directory's truth.csv and observations.csv, those of the A2 runs when given, else of the A1 runs (runs
of the same seeds have the same reports), computed per run and averaged over the runs. Target N is the
N-th target id of truth.csv in increasing order. It explains a low TLR but does not bound it (a track
can coast through unreported ticks). When a run has no truth.csv or observations.csv (or a metrics.json
path was given), a malformed one, or truth.csv's number of targets differs from metrics.json's, a note
on stderr names the file and the column is '-'.

The table lists the paper's A1 and A2 values, ours (RSE, TLR, TLR_len), and the A1 - A2 deltas of
the paper and, with both --a1 and --a2, of ours; between the two, "reported". Below it, the statistics the paper's text draws from
Table II: mean and median RSE and TLR, the number of targets on which A1's RSE is lower, and on which
A1's TLR is higher, equal or lower (compared at the paper's two decimals, as its table gives them);
and, when every target's "reported" is defined, its mean and median and, per algorithm, the mean TLR
divided by the mean reported share. Targets whose RSE is undefined in every run are left out of the
RSE statistics and shown as '-'.

Runs whose metrics.json has the classification block (docs/METRICS.md) add, per target, a "class"
column after "target" and, after each algorithm's TLR_len, an "A1 acc" / "A2 acc" column:
  class     the target's true class (wheeled_light, wheeled_heavy, tracked, human, group, aerial or
            unknown), the class of classification.targets' entry with the id of the N-th entry of
            track_quality.targets; it must be the same in every run of both algorithms. '-' when no run
            lists the target (only targets ever associated are listed).
  A1 acc    class accuracy pooled over the algorithm's runs: sum of ticks_correct / sum of ticks_declared
            (ticks its track declared the true class / ticks it declared a class). '-' when no tick was
            declared or the class is unknown. The mean and median rows are over the targets with one.
Below the statistics, a "Classification" section gives for each algorithm given the run totals summed
over its runs (these count only the targets of known class): declared share = ticks_declared /
ticks_associated and accuracy = ticks_correct / ticks_declared, with the counts ('-' for 0/0), then the
confusion matrix summed over the runs as a Markdown table: rows the true classes met (unknown included),
columns the declared classes that are a row or have a non-zero count, then "none" (associated ticks
whose track declared no class); classes in the order listed above. Runs scored before the classification
metric existed have no block: without it in any run the table is as before and there is no section;
when only one algorithm's runs have it, the other gets no acc column and a line saying its runs have no
block. Some runs of one algorithm with the block and some without is an error.

Runs whose metrics.json has the stop_mode block (docs/METRICS.md, "Stop mode") add, after the
classification section, a "Stop mode" section: for each algorithm given, the mean probability its
tracks give the stop model of their IMM over the associated ticks in which the target stands still
(true velocity exactly 0) and over those in which it moves, pooled over the algorithm's runs as
sum(mean * ticks) / sum(ticks), with the summed tick counts ('-' for no tick), and the associated
ticks of tracks whose engine has no stop model when there are any; then one line with, per target
that stands still in some associated tick of some algorithm's runs (target N being the N-th entry of
track_quality.targets, by the id of stop_mode.targets' entries), each algorithm's mean while stopped
pooled the same way and its ticks. Without the block in any run there is no section; when only one
algorithm's runs have it, the other gets a line saying its runs have no block. Some runs of one
algorithm with the block and some without is an error, as for classification.

With --plot FILE (FILE ending .png or .svg, which chooses the format) the tool also draws the table
in FILE: two panels stacked, per-target RSE (m) above and per-target TLR below, as grouped bars for
targets 1..20 (more if the runs have more): ours A1 and ours A2 (those given), then the paper's A1 and
A2, hatched and lighter. A target with an undefined RSE gets no RSE bar. The title gives the number
of runs per algorithm. The figure is written under a temporary name in FILE's directory and renamed
to FILE when complete, so a failure leaves no partial FILE; a line on stderr says where it was
written. matplotlib is imported (with the Agg backend) only for --plot; when it cannot be, the tool
says so before printing anything and exits with status 1.

Exit status: 0, 1 when a run directory or its metrics.json is missing or malformed (the message
names the file and what was expected; this includes a malformed classification or stop_mode block,
runs of one algorithm with and without either block, and a target whose class differs between runs),
when --plot is given but matplotlib cannot be imported, or when FILE cannot be written; 2 on a usage
error (such as --plot FILE with another extension)."""

PAPER_TARGETS = len(PAPER_A1)


class RunError(Exception):
    """A run directory that cannot be tabulated; the message names the file."""


def _number(value, where, path):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise RunError(f"{path}: {where}: expected a finite number, got {json.dumps(value)}")
    return float(value)


def _count(value, where, path):
    if isinstance(value, bool) or not isinstance(value, int) or value < 0:
        raise RunError(f"{path}: {where}: expected a count (an integer >= 0), got {json.dumps(value)}")
    return value


# The true classes a scenario gives, in the order of TargetClass (common/scenario_config.hpp), the
# order of the confusion matrix's rows and columns; "unknown" (no class given) is never declared.
CLASS_NAMES = ("wheeled_light", "wheeled_heavy", "tracked", "human", "group", "aerial")
UNKNOWN_CLASS = "unknown"


def class_order(name):
    """Sort key: the classes of CLASS_NAMES, then unknown, then any other name alphabetically."""
    order = CLASS_NAMES + (UNKNOWN_CLASS,)
    return (order.index(name), "") if name in order else (len(order), name)


def target_positions(ids, block, path):
    """{target id: its position in track_quality.targets}, for the targets of a block named `block`
    that lists them by id. `ids` are the track_quality targets' ids in file order."""
    position = {}
    for i, target_id in enumerate(ids):
        if isinstance(target_id, bool) or not isinstance(target_id, int):
            raise RunError(f"{path}: track_quality.targets[{i}].id: expected an integer (it matches the "
                           f"{block} block's targets), got {json.dumps(target_id)}")
        position[target_id] = i
    return position


def block_targets(block, name, keys, ids, path):
    """The entries of the `targets` list of the block `name`, as (position in track_quality.targets,
    entry, where for messages), each an object with an "id" of one of `ids` (the track_quality
    targets' ids in file order), listed once, and every one of `keys`."""
    if not isinstance(block["targets"], list):
        raise RunError(f"{path}: {name}.targets: expected a list of targets, got {json.dumps(block['targets'])}")
    position = target_positions(ids, name, path)
    seen = set()
    for k, entry in enumerate(block["targets"]):
        where = f"{name}.targets[{k}]"
        if not isinstance(entry, dict):
            raise RunError(f"{path}: {where}: expected an object, got {json.dumps(entry)}")
        for key in ("id",) + tuple(keys):
            if key not in entry:
                raise RunError(f"{path}: {where}: no '{key}' (expected id, {', '.join(keys)})")
        target_id = entry["id"]
        if isinstance(target_id, bool) or not isinstance(target_id, int) or target_id not in position:
            raise RunError(f"{path}: {where}.id: {json.dumps(target_id)} is not the id of a target of "
                           "track_quality.targets")
        if position[target_id] in seen:
            raise RunError(f"{path}: {where}.id: target {target_id} is listed twice")
        seen.add(position[target_id])
        yield position[target_id], entry, where


def read_classification(block, ids, path):
    """One run's classification block: {"targets": {position in track_quality.targets: (true class,
    ticks_declared, ticks_correct)}, "totals": (ticks_associated, ticks_declared, ticks_correct) of the
    run, "confusion": {true class: {declared class or "none": count}}}. `ids` are the track_quality
    targets' ids in file order; a target never associated is not listed and has no position here."""
    if not isinstance(block, dict):
        raise RunError(f"{path}: classification: expected an object, got {json.dumps(block)}")
    fields = ("ticks_associated", "ticks_declared", "ticks_correct")
    for key in fields + ("confusion", "targets"):
        if key not in block:
            raise RunError(f"{path}: classification: no '{key}' (expected {', '.join(fields)}, confusion, targets)")
    totals = tuple(_count(block[key], f"classification.{key}", path) for key in fields)
    confusion = block["confusion"]
    if not isinstance(confusion, dict):
        raise RunError(f"{path}: classification.confusion: expected an object, got {json.dumps(confusion)}")
    for truth, row in confusion.items():
        if not isinstance(row, dict):
            raise RunError(f"{path}: classification.confusion.{truth}: expected an object, got {json.dumps(row)}")
        for declared, count in row.items():
            _count(count, f"classification.confusion.{truth}.{declared}", path)
    targets = {}
    for at, entry, where in block_targets(block, "classification", ("class",) + fields, ids, path):
        if not isinstance(entry["class"], str) or not entry["class"]:
            raise RunError(f"{path}: {where}.class: expected a class name, got {json.dumps(entry['class'])}")
        associated, declared, correct = (_count(entry[key], f"{where}.{key}", path) for key in fields)
        if not correct <= declared <= associated:
            raise RunError(f"{path}: {where}: expected ticks_correct <= ticks_declared <= ticks_associated, "
                           f"got {correct}, {declared}, {associated}")
        targets[at] = (entry["class"], declared, correct)
    return {"targets": targets, "totals": totals, "confusion": confusion}


# The fields of the stop_mode block's totals and of each of its targets: (tick count, mean stop
# probability over those ticks), target stopped then moving.
STOP_FIELDS = (("ticks_stopped", "mean_stop_probability_stopped"), ("ticks_moving", "mean_stop_probability_moving"))


def _stop_means(entry, where, path):
    """(ticks_stopped, mean while stopped or None, ticks_moving, mean while moving or None) of the
    stop_mode block or of one of its targets: a mean is a probability, null only when its count is 0."""
    out = []
    for ticks_key, mean_key in STOP_FIELDS:
        ticks = _count(entry[ticks_key], f"{where}.{ticks_key}", path)
        mean = entry[mean_key]
        if mean is None:
            if ticks > 0:
                raise RunError(f"{path}: {where}.{mean_key}: expected a probability (a number in [0, 1]) since "
                               f"{ticks_key} is {ticks}, got null")
        else:
            mean = _number(mean, f"{where}.{mean_key}", path)
            if not 0.0 <= mean <= 1.0:
                raise RunError(f"{path}: {where}.{mean_key}: expected a probability (a number in [0, 1]), "
                               f"got {json.dumps(entry[mean_key])}")
        out += [ticks, mean]
    return tuple(out)


def read_stop_mode(block, ids, path):
    """One run's stop_mode block: {"totals": (ticks_stopped, mean while stopped or None, ticks_moving,
    mean while moving or None, ticks_without_stop_model) of the run, "targets": {position in
    track_quality.targets: (ticks_stopped, mean or None, ticks_moving, mean or None)}}. `ids` are the
    track_quality targets' ids in file order; a target never associated is not listed."""
    if not isinstance(block, dict):
        raise RunError(f"{path}: stop_mode: expected an object, got {json.dumps(block)}")
    fields = tuple(key for pair in STOP_FIELDS for key in pair)
    expected = ", ".join(fields + ("ticks_without_stop_model", "targets"))
    for key in fields + ("ticks_without_stop_model", "targets"):
        if key not in block:
            raise RunError(f"{path}: stop_mode: no '{key}' (expected {expected})")
    totals = _stop_means(block, "stop_mode", path) + (
        _count(block["ticks_without_stop_model"], "stop_mode.ticks_without_stop_model", path),)
    targets = {}
    for at, entry, where in block_targets(block, "stop_mode", fields, ids, path):
        targets[at] = _stop_means(entry, where, path)
    for m, (ticks_key, _) in enumerate(STOP_FIELDS):
        summed = sum(t[2 * m] for t in targets.values())
        if summed != totals[2 * m]:
            raise RunError(f"{path}: stop_mode.{ticks_key}: expected the sum of its targets' {ticks_key}, "
                           f"{summed}, got {totals[2 * m]}")
    return {"totals": totals, "targets": targets}


def read_run(arg):
    """(metrics.json's path, the per-target (rse or None, tlr, tlr_length or None) of one run in file
    order, its classification block as read_classification gives it or None when it has none, its
    stop_mode block as read_stop_mode gives it or None when it has none)."""
    path = Path(arg)
    if path.is_dir():
        path = path / "metrics.json"
    elif not path.exists():
        raise RunError(f"{arg}: no such run directory (expected a directory written by 'wsntrack run')")
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise RunError(f"{path}: missing (expected the metrics.json 'wsntrack run' writes at the end of a run; "
                       "did the run finish?)") from None
    except (OSError, UnicodeDecodeError) as error:
        raise RunError(f"{path}: cannot read ({error})") from None
    try:
        data = json.loads(text)
    except json.JSONDecodeError as error:
        raise RunError(f"{path}: not JSON (line {error.lineno}, column {error.colno}: {error.msg})") from None
    if not isinstance(data, dict) or not isinstance(data.get("track_quality"), dict):
        raise RunError(f"{path}: no track_quality object (expected metrics.json with the track_quality "
                       "metric's block, docs/METRICS.md)")
    targets = data["track_quality"].get("targets")
    if not isinstance(targets, list):
        raise RunError(f"{path}: track_quality.targets: expected a list of targets, got {json.dumps(targets)}")
    rows, ids = [], []
    for i, entry in enumerate(targets):
        where = f"track_quality.targets[{i}]"
        if not isinstance(entry, dict):
            raise RunError(f"{path}: {where}: expected an object, got {json.dumps(entry)}")
        for key in ("errors_defined", "rse_position", "tlr"):
            if key not in entry:
                raise RunError(f"{path}: {where}: no '{key}' (expected errors_defined, rse_position, tlr)")
        if not isinstance(entry["errors_defined"], bool):
            raise RunError(f"{path}: {where}.errors_defined: expected true or false, "
                           f"got {json.dumps(entry['errors_defined'])}")
        rse = _number(entry["rse_position"], where + ".rse_position", path)
        tlr = _number(entry["tlr"], where + ".tlr", path)
        # Runs scored before the path-length TLR existed have no tlr_length: shown as '-'.
        tlr_length = _number(entry["tlr_length"], where + ".tlr_length", path) if "tlr_length" in entry else None
        rows.append((rse if entry["errors_defined"] else None, tlr, tlr_length))
        ids.append(entry.get("id"))
    # Runs scored before the classification metric existed have no classification block.
    classification = read_classification(data["classification"], ids, path) if "classification" in data else None
    # Runs scored before the stop_mode metric existed have no stop_mode block.
    stop_mode = read_stop_mode(data["stop_mode"], ids, path) if "stop_mode" in data else None
    return path, rows, classification, stop_mode


class ReportError(Exception):
    """A run whose reported shares cannot be computed; the message names the file."""


def _csv_rows(path, columns, integers):
    """The given columns of each row of a CSV file with a header, the first `integers` of them as int."""
    try:
        handle = path.open(newline="", encoding="utf-8")
    except FileNotFoundError:
        raise ReportError(f"{path}: missing") from None
    except OSError as error:
        raise ReportError(f"{path}: cannot read ({error})") from None
    with handle:
        reader = csv.reader(handle)
        try:
            head = next(reader, None)
            if head is None:
                raise ReportError(f"{path}: empty (expected the header line, with {', '.join(columns)})")
            missing = [c for c in columns if c not in head]
            if missing:
                raise ReportError(f"{path}: line 1: header has no column {', '.join(missing)} "
                                  f"(expected {', '.join(columns)})")
            index = [head.index(c) for c in columns]
            for row in reader:
                if not row:
                    continue  # a blank line
                if max(index) >= len(row):
                    raise ReportError(f"{path}: line {reader.line_num}: {len(row)} fields, expected {len(head)}")
                values = [row[i] for i in index]
                for k in range(integers):
                    try:
                        values[k] = int(values[k])
                    except ValueError:
                        raise ReportError(f"{path}: line {reader.line_num}: {columns[k]}: expected an integer, "
                                          f"got {values[k]!r}") from None
                yield values
        except csv.Error as error:
            raise ReportError(f"{path}: line {reader.line_num}: not CSV ({error})") from None
        except UnicodeDecodeError as error:
            raise ReportError(f"{path}: not UTF-8 after line {reader.line_num} ({error.reason})") from None


def read_reported(arg, targets):
    """Per target, in increasing id order: the share of its alive ticks (truth.csv) with at least one
    delivered report of it (observations.csv). `targets` is the run's number of targets in metrics.json."""
    path = Path(arg)
    if not path.is_dir():
        raise ReportError(f"{arg}: not a run directory, so no truth.csv and observations.csv beside it")
    truth = path / "truth.csv"
    alive = {}
    for tick, target in _csv_rows(truth, ("tick", "target"), 2):
        alive.setdefault(target, set()).add(tick)
    if len(alive) != targets:
        raise ReportError(f"{truth}: {len(alive)} targets, but its metrics.json has {targets}")
    reported = {target: set() for target in alive}
    for tick, target, fate in _csv_rows(path / "observations.csv", ("tick_generated", "target", "fate"), 2):
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
        except ReportError as error:
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
        raise RunError(f"{label} runs disagree on the number of targets: {listing}")
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
        raise RunError(f"{lacking[0]}: no {block} block, but {having[0]} (another of the {label} runs) "
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
                raise RunError(f"{path}: classification: target {j + 1} (track_quality.targets[{j}]) has class "
                               f"'{name}', but '{classes[j][0]}' in {classes[j][1]}: the runs must be of the same "
                               "scenario")
    n = max((len(rows) for _, _, rows, _, _ in runs), default=0)
    return [classes[j][0] if j in classes else None for j in range(n)]


def class_accuracy(pooled, classes):
    """Per target position, sum(ticks_correct) / sum(ticks_declared) over the runs; None when no tick
    was declared or the true class is unknown (or the target never associated)."""
    return [None if classes[j] in (None, UNKNOWN_CLASS) or pooled["declared"][j] == 0
            else pooled["correct"][j] / pooled["declared"][j] for j in range(len(pooled["declared"]))]


def confusion_lines(name, confusion):
    """The summed confusion matrix as a Markdown table: rows the true classes met, columns the declared
    classes that are a row or counted at least once, then "none"."""
    rows = sorted(confusion, key=class_order)
    declared = {d for row in confusion.values() for d in row if d != "none"}
    columns = sorted((d for d in declared
                      if d in confusion or any(row.get(d, 0) for row in confusion.values())), key=class_order)
    columns.append("none")
    lines = [f"| {name} true / declared | " + " | ".join(columns) + " |",
             "|---|" + "|".join("---:" for _ in columns) + "|"]
    for truth in rows:
        lines.append(f"| {truth} | " + " | ".join(str(confusion[truth].get(d, 0)) for d in columns) + " |")
    return lines


def fmt(value, digits):
    return "-" if value is None else f"{value:.{digits}f}"


def fmt_delta(a, b, digits):
    return "-" if a is None or b is None else f"{a - b:+.{digits}f}"


def stats(values):
    """(mean, median) of the defined values, or (None, None)."""
    values = [v for v in values if v is not None]
    if not values:
        return None, None
    return sum(values) / len(values), statistics.median(values)


def compare(a1, a2, k=1):
    """For the targets both define: (number, A1 RSE lower) and (A1 TLR higher, equal, lower target
    numbers), TLR being column k of the rows (1 duration, 2 path length)."""
    rse_pairs = [(a[0], b[0]) for a, b in zip(a1, a2) if a[0] is not None and b[0] is not None]
    rse_lower = sum(1 for x, y in rse_pairs if x < y)
    higher = equal = 0
    lower = []
    for j, (a, b) in enumerate(zip(a1, a2)):
        x, y = round(a[k], 2), round(b[k], 2)  # at the paper's precision
        if x > y:
            higher += 1
        elif x == y:
            equal += 1
        else:
            lower.append(j + 1)
    return len(rse_pairs), rse_lower, higher, equal, lower


def table(a1, a2, n_a1, n_a2, reported=None, reported_from="A2", classes=None, pooled=None, stop=None):
    """The Markdown lines: per-target table, its mean and median rows, then the comparisons.
    `reported` is the per-target reported share (None: '-'), read from the `reported_from` runs.
    `classes` is the per-target true class (None: no class column); `pooled` maps "A1" and "A2" to
    pool_classification's sums of the algorithm's runs, or to None when they have no classification
    block (no accuracy column). Without either, the output is that of runs before classification.
    `stop` maps "A1" and "A2" to pool_stop_mode's pooled means of the algorithm's runs, or to None when
    they have no stop_mode block; without any, there is no stop mode section."""
    n = max(PAPER_TARGETS, len(a1 or []), len(a2 or []))
    ours = [(name, rows) for name, rows in (("A1", a1), ("A2", a2)) if rows is not None]
    pooled = pooled or {}
    accuracy = {name: class_accuracy(pooled[name], classes) for name, _ in ours
                if classes is not None and pooled.get(name) is not None}
    header = ["target"] + (["class"] if classes is not None else []) + [
              "paper A1 RSE", "paper A1 TLR", "paper A2 RSE", "paper A2 TLR", "paper Δ RSE", "paper Δ TLR"]
    for name, _ in ours:
        header += [f"{name} RSE", f"{name} TLR", f"{name} TLR_len"] + ([f"{name} acc"] if name in accuracy else [])
    header.append("reported")
    if a1 is not None and a2 is not None:
        header += ["Δ RSE", "Δ TLR", "Δ TLR_len"]

    def cell(rows, j, k):
        return rows[j][k] if rows is not None and j < len(rows) else None

    def paper(rows, j, k):
        return rows[j][k] if j < PAPER_TARGETS else None

    # The numeric columns, per target: (values, digits, is a delta).
    columns = [([paper(PAPER_A1, j, 0) for j in range(n)], 2, False),
               ([paper(PAPER_A1, j, 1) for j in range(n)], 2, False),
               ([paper(PAPER_A2, j, 0) for j in range(n)], 2, False),
               ([paper(PAPER_A2, j, 1) for j in range(n)], 2, False)]
    for k in (0, 1):
        columns.append(([None if j >= PAPER_TARGETS else PAPER_A1[j][k] - PAPER_A2[j][k] for j in range(n)], 2, True))
    for name, rows in ours:
        for k in (0, 1, 2):
            columns.append(([cell(rows, j, k) for j in range(n)], 2, False))
        if name in accuracy:
            columns.append(([accuracy[name][j] if j < len(accuracy[name]) else None for j in range(n)], 2, False))
    columns.append(([reported[j] if reported is not None and j < len(reported) else None for j in range(n)], 2, False))
    if a1 is not None and a2 is not None:
        for k in (0, 1, 2):
            columns.append(([None if cell(a1, j, k) is None or cell(a2, j, k) is None
                             else cell(a1, j, k) - cell(a2, j, k) for j in range(n)], 2, True))

    def show(value, digits, delta):
        if value is None:
            return "-"
        if delta and abs(value) < 0.5 * 10 ** -digits:
            value = 0.0  # no "-0.00" from rounding
        return f"{value:+.{digits}f}" if delta else f"{value:.{digits}f}"

    lines = ["| " + " | ".join(header) + " |",
             "|" + "|".join("---" if h == "class" else "---:" for h in header) + "|"]  # text left, numbers right
    for j in range(n):
        text = [str(j + 1)]
        if classes is not None:
            text.append(classes[j] if j < len(classes) and classes[j] is not None else "-")
        lines.append("| " + " | ".join(text + [show(values[j], d, delta) for values, d, delta in columns]) + " |")
    for label, which in (("mean", 0), ("median", 1)):
        cells = [""] if classes is not None else []  # no mean class
        for values, d, delta in columns:
            cells.append(show(stats(values)[which], d + 1, delta))
        lines.append("| **" + label + "** | " + " | ".join(cells) + " |")

    lines.append("")
    runs = ", ".join(f"{name} {count} run{'s' if count != 1 else ''}"
                     for name, count in (("A1", n_a1), ("A2", n_a2)) if count)
    lines.append(f"Ours: {runs}, each target's values the mean over them. TLR = associated ticks / alive "
                 "ticks; TLR_len = associated path length / path length; reported = share of the alive ticks with "
                 f"at least one delivered report of the target (the {reported_from} runs' truth.csv and "
                 "observations.csv). Means and medians over the targets (RSE over those with a defined RSE).")
    if classes is not None:
        lines[-1] += (" class = the target's true class (metrics.json's classification block; '-' when no run "
                      "associated the target); " + ", ".join(f"{name} acc" for name in accuracy) +
                      " = ticks its track declared the true class / ticks it declared a class, each summed over "
                      "the runs ('-' when none was declared or the class is unknown; means and medians over the "
                      "targets with one).")
    lines.append("")

    def describe(pairs_a1, pairs_a2, who, key=1, what="TLR"):
        count, rse_lower, higher, equal, lower = compare(pairs_a1, pairs_a2, key)
        lower_ids = ", ".join(str(j) for j in lower) or "none"
        return (f"- {who}: A1's RSE lower on {rse_lower}/{count} targets; A1's {what} higher on {higher}, "
                f"equal on {equal}, lower on {len(lower)} (targets {lower_ids})")

    paper_mean_a1, paper_median_a1 = stats([r[0] for r in PAPER_A1])
    paper_mean_a2, paper_median_a2 = stats([r[0] for r in PAPER_A2])
    lines.append(f"- paper: mean RSE {paper_mean_a1:.2f} vs {paper_mean_a2:.2f} m (medians {paper_median_a1:.3f}, "
                 f"{paper_median_a2:.3f}); mean TLR {stats([r[1] for r in PAPER_A1])[0]:.3f} vs "
                 f"{stats([r[1] for r in PAPER_A2])[0]:.3f}")
    lines.append(describe(PAPER_A1, PAPER_A2, "paper"))
    for name, rows in ours:
        mean_rse, median_rse = stats([r[0] for r in rows])
        mean_tlr, median_tlr = stats([r[1] for r in rows])
        mean_len, median_len = stats([r[2] for r in rows])
        lines.append(f"- ours {name}: mean RSE {fmt(mean_rse, 2)} m (median {fmt(median_rse, 3)}); mean TLR "
                     f"{fmt(mean_tlr, 3)} (median {fmt(median_tlr, 3)}); mean TLR_len {fmt(mean_len, 3)} "
                     f"(median {fmt(median_len, 3)})")
    if reported is not None and len(reported) == n and all(v is not None for v in reported):
        mean_rep, median_rep = stats(reported)
        ratios = ", ".join(f"{name} {fmt(stats([r[1] for r in rows])[0] / mean_rep if mean_rep else None, 3)}"
                           for name, rows in ours)
        lines.append(f"- reported share: mean {mean_rep:.3f} (median {median_rep:.3f}); TLR / reported: {ratios}")
    if a1 is not None and a2 is not None:
        lines.append(describe(a1, a2, "ours"))
        if all(r[2] is not None for r in a1 + a2):
            lines.append(describe(a1, a2, "ours, path length", key=2, what="TLR_len"))
    if any(pooled.get(name) is not None for name, _ in ours):
        lines += ["", "Classification (metrics.json's classification block), ticks summed over the runs: declared "
                  "share = declared / associated ticks and accuracy = correct / declared ticks, of the targets of "
                  "known class; the confusion matrix counts every associated tick by true class (rows) and "
                  "declared class (columns; none: no class declared)."]
        for name, _ in ours:
            lines.append("")
            c = pooled.get(name)
            if c is None:
                lines.append(f"- {name}: no classification block in its runs' metrics.json (scored before it existed)")
                continue
            associated, declared, correct = c["totals"]
            runs = f"{c['runs']} run{'s' if c['runs'] != 1 else ''}"
            lines.append(f"- {name} ({runs}): declared share {fmt(declared / associated if associated else None, 3)} "
                         f"({declared}/{associated} associated ticks), accuracy "
                         f"{fmt(correct / declared if declared else None, 3)} ({correct}/{declared} declared ticks)")
            if c["confusion"]:
                lines.append("")
                lines += confusion_lines(name, c["confusion"])
    stop = stop or {}
    having = [name for name, _ in ours if stop.get(name) is not None]
    if having:
        lines += ["", "Stop mode (metrics.json's stop_mode block): the mean probability a track gives the stop "
                  "model of its IMM, over the ticks its target stands still and the ticks it moves (associated "
                  "ticks whose track gives one), summed over the runs ('-' when there is no such tick).", ""]
        for name, _ in ours:
            s = stop.get(name)
            if s is None:
                lines.append(f"- {name}: no stop_mode block in its runs' metrics.json (scored before it existed)")
                continue
            stopped, mean_stopped, moving, mean_moving, without = s["totals"]
            runs = f"{s['runs']} run{'s' if s['runs'] != 1 else ''}"
            line = (f"- {name} ({runs}): while stopped {fmt(mean_stopped, 3)} ({stopped} ticks), while moving "
                    f"{fmt(mean_moving, 3)} ({moving} ticks)")
            if without:
                line += f"; {without} associated ticks of tracks whose engine has no stop model"
            lines.append(line)
        stops = sorted({j for name in having for j, t in stop[name]["targets"].items() if t[0] > 0})

        def stopped_cell(name, j):
            t = stop[name]["targets"].get(j)
            return f"{fmt(t[1], 2)} ({t[0]})" if t is not None else "- (0)"

        listing = ", ".join(f"{j + 1}: " + "; ".join(stopped_cell(name, j) for name in having) for j in stops)
        lines.append("- per target that stops (target: " + "; ".join(f"{name} while stopped (ticks)" for name in having)
                     + f"): {listing or 'none'}")
    return lines


PLOT_FORMATS = (".png", ".svg")


def load_matplotlib():
    """(matplotlib, None), or (None, the ImportError) when it cannot be imported. Only --plot calls
    it: without --plot the tool needs nothing beyond the standard library."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.figure
        from matplotlib.backends.backend_agg import FigureCanvasAgg  # noqa: F401 (savefig's canvas)
    except ImportError as error:
        return None, error
    # No pyplot: its figure manager is not needed to save a figure.
    matplotlib.rcParams.update({"savefig.dpi": 120, "svg.fonttype": "none", "font.size": 10})
    return matplotlib, None


def plot(matplotlib, path, a1, a2, n_a1, n_a2):
    """Draws per-target RSE and TLR, ours (the algorithms given) beside the paper's, as grouped bars
    in two stacked panels, and saves the figure to `path` (its suffix gives the format) through a
    temporary file in the same directory, renamed when complete. Raises OSError when it cannot."""
    n = max(PAPER_TARGETS, len(a1 or []), len(a2 or []))
    # (label, per-target (rse, tlr) rows, colour, paper's style)
    series = []
    if a1 is not None:
        series.append((f"ours A1 (road network, mean of {n_a1} run{'s' if n_a1 != 1 else ''})", a1,
                       "tab:blue", False))
    if a2 is not None:
        series.append((f"ours A2 (no road network, mean of {n_a2} run{'s' if n_a2 != 1 else ''})", a2,
                       "tab:orange", False))
    series.append(("paper A1 (Table II)", PAPER_A1, "tab:blue", True))
    series.append(("paper A2 (Table II)", PAPER_A2, "tab:orange", True))
    width = 0.84 / len(series)

    fig = matplotlib.figure.Figure(figsize=(max(12.0, 0.6 * n), 8.0), constrained_layout=True)
    rse_axes, tlr_axes = fig.subplots(2, 1, sharex=True)
    for axes, k, ylabel in ((rse_axes, 0, "RSE (m)"), (tlr_axes, 1, "TLR")):
        for i, (label, rows, colour, paper) in enumerate(series):
            offset = (i - (len(series) - 1) / 2) * width
            xs, heights = [], []
            for j in range(min(n, len(rows))):
                if rows[j][k] is not None:  # an undefined RSE: no bar
                    xs.append(j + 1 + offset)
                    heights.append(rows[j][k])
            style = ({"color": colour, "alpha": 0.35, "hatch": "///", "edgecolor": colour, "linewidth": 0.6}
                     if paper else {"color": colour, "edgecolor": "black", "linewidth": 0.4})
            axes.bar(xs, heights, width, label=label, zorder=2, **style)
        axes.set_ylabel(ylabel)
        axes.grid(axis="y", color="0.85", zorder=0)
        axes.set_axisbelow(True)
        axes.set_xlim(0.4, n + 0.6)
    tlr_axes.set_ylim(0, 1.05)
    tlr_axes.set_xticks(range(1, n + 1))
    tlr_axes.set_xlabel("target")
    rse_axes.tick_params(labelbottom=True)
    rse_axes.set_title("per-target position RSE (m); a target never associated has no bar", fontsize=10)
    tlr_axes.set_title("per-target TLR (associated ticks / alive ticks)", fontsize=10)
    runs = ", ".join(f"{name} {count} run{'s' if count != 1 else ''}"
                     for name, count in (("A1", n_a1), ("A2", n_a2)) if count)
    fig.suptitle(f"Ours ({runs}; per-target means) vs Pannetier, Dezert and Sella (FUSION 2014), Table II")
    # Above the top panel, so that it hides no bar.
    rse_axes.legend(loc="lower center", bbox_to_anchor=(0.5, 1.1), ncol=len(series), frameon=False,
                    fontsize=9)

    path = Path(path)
    partial = path.with_name(f".{path.name}.{os.getpid()}.partial")
    try:
        fig.savefig(partial, format=path.suffix.lower()[1:])
        os.replace(partial, path)
    finally:
        if partial.exists():
            partial.unlink()


def main(argv):
    parser = argparse.ArgumentParser(prog="onera_table.py", description=DESCRIPTION,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("runs", nargs="*", metavar="RUN_DIR",
                        help="runs of algorithm 2 (without the road network), as with --a2")
    parser.add_argument("--a1", nargs="+", metavar="RUN_DIR", default=[],
                        help="runs of algorithm 1 (with the road network)")
    parser.add_argument("--a2", nargs="+", metavar="RUN_DIR", default=[],
                        help="runs of algorithm 2 (without the road network)")
    parser.add_argument("--plot", metavar="FILE",
                        help="also draw per-target RSE and TLR, ours beside the paper's, in FILE "
                             "(.png or .svg; needs matplotlib)")
    args = parser.parse_args(argv)
    if args.plot is not None and Path(args.plot).suffix.lower() not in PLOT_FORMATS:
        suffix = Path(args.plot).suffix
        parser.error(f"--plot {args.plot}: " + (f"unknown extension '{suffix}'" if suffix else "no extension")
                     + " (expected a file name ending .png or .svg)")
    if args.runs and args.a2:
        parser.error("give algorithm 2's runs either as RUN_DIR... or after --a2, not both")
    a2_args = args.a2 or args.runs
    if not args.a1 and not a2_args:
        parser.error("no run directories: give RUN_DIR..., --a2 RUN_DIR... and/or --a1 RUN_DIR...")
    try:
        a1_read = [(arg, *read_run(arg)) for arg in args.a1]
        a2_read = [(arg, *read_run(arg)) for arg in a2_args]
        a1_runs = [(arg, rows) for arg, _, rows, _, _ in a1_read]
        a2_runs = [(arg, rows) for arg, _, rows, _, _ in a2_read]
        a1 = average_runs(a1_runs, "--a1") if a1_runs else None
        a2 = average_runs(a2_runs, "--a2") if a2_runs else None
        if a1 is not None and a2 is not None and len(a1) != len(a2):
            raise RunError(f"the A1 runs have {len(a1)} targets and the A2 runs {len(a2)}: they must be "
                           "runs of the same scenario")
        pooled = {"A1": pool_classification(a1_read, "--a1") if a1_read else None,
                  "A2": pool_classification(a2_read, "--a2") if a2_read else None}
        classes = (target_classes(a1_read + a2_read)
                   if any(c is not None for c in pooled.values()) else None)
        stop = {"A1": pool_stop_mode(a1_read, "--a1") if a1_read else None,
                "A2": pool_stop_mode(a2_read, "--a2") if a2_read else None}
    except RunError as error:
        print(f"onera_table.py: {error}", file=sys.stderr)
        return 1
    for name, rows in (("A1", a1), ("A2", a2)):
        if rows is not None and len(rows) != PAPER_TARGETS:
            print(f"onera_table.py: note: the {name} runs have {len(rows)} targets, Table II has {PAPER_TARGETS}; "
                  "rows are matched by position", file=sys.stderr)
        if rows is not None and any(r[2] is None for r in rows):
            print(f"onera_table.py: note: some {name} run has no tlr_length (scored before it existed): "
                  "TLR_len is shown as '-'", file=sys.stderr)
    matplotlib = None
    if args.plot is not None:
        matplotlib, import_error = load_matplotlib()
        if matplotlib is None:
            print(f"onera_table.py: --plot: matplotlib is not available to {sys.executable} ({import_error}); "
                  "on Debian: apt-get install python3-matplotlib (or leave out --plot)", file=sys.stderr)
            return 1
    reported_from = "A2" if a2_runs else "A1"
    reported = average_reported(a2_runs or a1_runs)
    print("\n".join(table(a1, a2, len(a1_runs), len(a2_runs), reported, reported_from, classes, pooled, stop)),
          flush=True)
    if matplotlib is not None:
        try:
            plot(matplotlib, args.plot, a1, a2, len(a1_runs), len(a2_runs))
        except OSError as error:
            print(f"onera_table.py: {args.plot}: cannot write the plot "
                  f"({error.strerror or error})", file=sys.stderr)
            return 1
        print(f"onera_table.py: wrote the plot to {args.plot}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except KeyboardInterrupt:
        sys.exit(130)
