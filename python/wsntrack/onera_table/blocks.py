"""One run's metrics.json as the ONERA table reads it: per target RSE, TLR and path-length TLR
(track_quality), and the classification and stop_mode blocks when the run was scored with them;
every problem an InputError naming the file and what was expected."""

import json
import math
from pathlib import Path

from ..rundir import InputError, read_json

def _number(value, where, path):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise InputError(f"{path}: {where}: expected a finite number, got {json.dumps(value)}")
    return float(value)


def _count(value, where, path):
    if isinstance(value, bool) or not isinstance(value, int) or value < 0:
        raise InputError(f"{path}: {where}: expected a count (an integer >= 0), got {json.dumps(value)}")
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
            raise InputError(f"{path}: track_quality.targets[{i}].id: expected an integer (it matches the "
                             f"{block} block's targets), got {json.dumps(target_id)}")
        position[target_id] = i
    return position


def block_targets(block, name, keys, ids, path):
    """The entries of the `targets` list of the block `name`, as (position in track_quality.targets,
    entry, where for messages), each an object with an "id" of one of `ids` (the track_quality
    targets' ids in file order), listed once, and every one of `keys`."""
    if not isinstance(block["targets"], list):
        raise InputError(f"{path}: {name}.targets: expected a list of targets, got {json.dumps(block['targets'])}")
    position = target_positions(ids, name, path)
    seen = set()
    for k, entry in enumerate(block["targets"]):
        where = f"{name}.targets[{k}]"
        if not isinstance(entry, dict):
            raise InputError(f"{path}: {where}: expected an object, got {json.dumps(entry)}")
        for key in ("id",) + tuple(keys):
            if key not in entry:
                raise InputError(f"{path}: {where}: no '{key}' (expected id, {', '.join(keys)})")
        target_id = entry["id"]
        if isinstance(target_id, bool) or not isinstance(target_id, int) or target_id not in position:
            raise InputError(f"{path}: {where}.id: {json.dumps(target_id)} is not the id of a target of "
                             "track_quality.targets")
        if position[target_id] in seen:
            raise InputError(f"{path}: {where}.id: target {target_id} is listed twice")
        seen.add(position[target_id])
        yield position[target_id], entry, where


def read_classification(block, ids, path):
    """One run's classification block: {"targets": {position in track_quality.targets: (true class,
    ticks_declared, ticks_correct)}, "totals": (ticks_associated, ticks_declared, ticks_correct) of the
    run, "confusion": {true class: {declared class or "none": count}}}. `ids` are the track_quality
    targets' ids in file order; a target never associated is not listed and has no position here."""
    if not isinstance(block, dict):
        raise InputError(f"{path}: classification: expected an object, got {json.dumps(block)}")
    fields = ("ticks_associated", "ticks_declared", "ticks_correct")
    for key in fields + ("confusion", "targets"):
        if key not in block:
            raise InputError(f"{path}: classification: no '{key}' (expected {', '.join(fields)}, confusion, targets)")
    totals = tuple(_count(block[key], f"classification.{key}", path) for key in fields)
    confusion = block["confusion"]
    if not isinstance(confusion, dict):
        raise InputError(f"{path}: classification.confusion: expected an object, got {json.dumps(confusion)}")
    for truth, row in confusion.items():
        if not isinstance(row, dict):
            raise InputError(f"{path}: classification.confusion.{truth}: expected an object, got {json.dumps(row)}")
        for declared, count in row.items():
            _count(count, f"classification.confusion.{truth}.{declared}", path)
    targets = {}
    for at, entry, where in block_targets(block, "classification", ("class",) + fields, ids, path):
        if not isinstance(entry["class"], str) or not entry["class"]:
            raise InputError(f"{path}: {where}.class: expected a class name, got {json.dumps(entry['class'])}")
        associated, declared, correct = (_count(entry[key], f"{where}.{key}", path) for key in fields)
        if not correct <= declared <= associated:
            raise InputError(f"{path}: {where}: expected ticks_correct <= ticks_declared <= ticks_associated, "
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
                raise InputError(f"{path}: {where}.{mean_key}: expected a probability (a number in [0, 1]) since "
                                 f"{ticks_key} is {ticks}, got null")
        else:
            mean = _number(mean, f"{where}.{mean_key}", path)
            if not 0.0 <= mean <= 1.0:
                raise InputError(f"{path}: {where}.{mean_key}: expected a probability (a number in [0, 1]), "
                                 f"got {json.dumps(entry[mean_key])}")
        out += [ticks, mean]
    return tuple(out)


def read_stop_mode(block, ids, path):
    """One run's stop_mode block: {"totals": (ticks_stopped, mean while stopped or None, ticks_moving,
    mean while moving or None, ticks_without_stop_model) of the run, "targets": {position in
    track_quality.targets: (ticks_stopped, mean or None, ticks_moving, mean or None)}}. `ids` are the
    track_quality targets' ids in file order; a target never associated is not listed."""
    if not isinstance(block, dict):
        raise InputError(f"{path}: stop_mode: expected an object, got {json.dumps(block)}")
    fields = tuple(key for pair in STOP_FIELDS for key in pair)
    expected = ", ".join(fields + ("ticks_without_stop_model", "targets"))
    for key in fields + ("ticks_without_stop_model", "targets"):
        if key not in block:
            raise InputError(f"{path}: stop_mode: no '{key}' (expected {expected})")
    totals = _stop_means(block, "stop_mode", path) + (
        _count(block["ticks_without_stop_model"], "stop_mode.ticks_without_stop_model", path),)
    targets = {}
    for at, entry, where in block_targets(block, "stop_mode", fields, ids, path):
        targets[at] = _stop_means(entry, where, path)
    for m, (ticks_key, _) in enumerate(STOP_FIELDS):
        summed = sum(t[2 * m] for t in targets.values())
        if summed != totals[2 * m]:
            raise InputError(f"{path}: stop_mode.{ticks_key}: expected the sum of its targets' {ticks_key}, "
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
        raise InputError(f"{arg}: no such run directory (expected a directory written by 'wsntrack run')")
    if not path.exists():
        raise InputError(f"{path}: missing (expected the metrics.json 'wsntrack run' writes at the end of a run; "
                         "did the run finish?)")
    data = read_json(path)
    if not isinstance(data, dict) or not isinstance(data.get("track_quality"), dict):
        raise InputError(f"{path}: no track_quality object (expected metrics.json with the track_quality "
                         "metric's block, docs/METRICS.md)")
    targets = data["track_quality"].get("targets")
    if not isinstance(targets, list):
        raise InputError(f"{path}: track_quality.targets: expected a list of targets, got {json.dumps(targets)}")
    rows, ids = [], []
    for i, entry in enumerate(targets):
        where = f"track_quality.targets[{i}]"
        if not isinstance(entry, dict):
            raise InputError(f"{path}: {where}: expected an object, got {json.dumps(entry)}")
        for key in ("errors_defined", "rse_position", "tlr"):
            if key not in entry:
                raise InputError(f"{path}: {where}: no '{key}' (expected errors_defined, rse_position, tlr)")
        if not isinstance(entry["errors_defined"], bool):
            raise InputError(f"{path}: {where}.errors_defined: expected true or false, "
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
