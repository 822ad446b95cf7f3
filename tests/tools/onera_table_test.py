#!/usr/bin/python3
"""Tests of tools/onera_table.py (Table II of Pannetier et al. 2014 beside our runs) on hand-written
run directories (metrics.json's track_quality block, and for the "reported" column truth.csv and
observations.csv): per-target means over runs against a hand computation, the paper's statistics, the
A1 - A2 deltas and comparisons, undefined RSEs, runs without tlr_length, the reported share and its
notes for missing, inconsistent or malformed CSV files, the errors for missing or malformed
metrics.json, the classification block (per-target class and accuracy pooled over runs, the run
totals and the confusion matrix summed over runs, runs without the block, runs of one algorithm with
and without it, classes that differ between runs, a malformed block), the stop_mode block (the mean
stop probabilities while stopped and while moving pooled over runs by their ticks, per run and per
target, runs without the block, runs of one algorithm with and without it, a malformed block), and
--plot: a PNG or SVG
beside the unchanged table (skipped when /usr/bin/python3 has no matplotlib), a bad extension, a
missing matplotlib (a stand-in package that raises ImportError) and an unwritable file.

Usage: onera_table_test.py SOURCE_DIR WORK_DIR
"""

import json
import os
import shutil
import subprocess
import sys
import unittest
from pathlib import Path

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
SOURCE, WORK = Path(sys.argv[1]).resolve(), Path(sys.argv[2]).resolve()
TOOL = SOURCE / "tools" / "onera_table.py"


def target(i, rse, tlr, tlr_length=None, defined=True):
    entry = {"id": i, "ticks_alive": 10, "ticks_associated": 5, "errors_defined": defined,
             "rse_position": rse if defined else 0.0, "rse_velocity": 0.0, "tlr": tlr}
    if tlr_length is not None:
        entry["tlr_length"] = tlr_length
    return entry


def run_dir(name, targets=None, text=None, files=None):
    """A run directory holding metrics.json with these targets (or this raw text; neither: no file),
    and the other files {name: text} given."""
    path = WORK / name
    path.mkdir(parents=True)
    if text is None and targets is not None:
        text = json.dumps({"eps_k": 0.0, "track_quality": {"gate": 50.0, "targets": targets}})
    if text is not None:
        (path / "metrics.json").write_text(text, encoding="utf-8")
    for file, content in (files or {}).items():
        (path / file).write_text(content, encoding="utf-8")
    return path


def truth_csv(alive):
    """truth.csv for {target id: alive ticks}, tick by tick, the targets of a tick in decreasing id order
    (the table must sort them)."""
    rows = sorted(((tick, i) for i, ticks in alive.items() for tick in ticks), key=lambda r: (r[0], -r[1]))
    return "tick,target,x,y,vx,vy\n" + "".join(f"{tick},{i},1.5,2.5,1.0,0.0\n" for tick, i in rows)


def observations_csv(reports):
    """observations.csv for [(tick_generated, tick_delivered, target, fate)]."""
    return ("tick_generated,tick_delivered,sensor,supernode,hops,delay,x,y,target,fate,level\n"
            + "".join(f"{g},{d},7,0,1,{d - g},1.0,2.0,{t},{fate},0\n" for g, d, t, fate in reports))


PYTHON = "/usr/bin/python3"


def tool(*args, env=None):
    return subprocess.run([PYTHON, "-B", str(TOOL), *map(str, args)], capture_output=True,
                          text=True, timeout=60, env=env)


# The PNG and SVG tests need matplotlib for the python that runs the tool.
HAVE_MATPLOTLIB = subprocess.run([PYTHON, "-c", "import matplotlib"], capture_output=True).returncode == 0
NO_MATPLOTLIB = f"matplotlib is not installed for {PYTHON} (Debian: python3-matplotlib)"


def cells(stdout, first):
    """The cells of the table row whose first cell is `first`."""
    for line in stdout.splitlines():
        parts = [c.strip() for c in line.strip().strip("|").split("|")]
        if parts and parts[0] == first:
            return parts
    raise AssertionError(f"no row {first!r} in:\n{stdout}")


def header(stdout):
    return cells(stdout, "target")


class OneAlgorithm(unittest.TestCase):
    """Only algorithm 2's runs, as today: ours beside the paper's A1 and A2."""

    @classmethod
    def setUpClass(cls):
        # Two seeds, 20 targets. Target 1: RSE 4 and 6, TLR 0.5 and 0.7, TLR_len 0.2 and 0.6 -> 5, 0.6,
        # 0.4. Target 2: RSE undefined in seed 1 -> 8 (seed 2 only), TLR and TLR_len (0 + 0.4) / 2 = 0.2.
        # Target 3: undefined in both -> '-'. Targets 4-20: RSE 10, TLR 1, TLR_len 1.
        s1 = [target(0, 4.0, 0.5, 0.2), target(1, 0.0, 0.0, 0.0, defined=False), target(2, 0, 0.0, 0.0, False)]
        s2 = [target(0, 6.0, 0.7, 0.6), target(1, 8.0, 0.4, 0.4), target(2, 0, 0.0, 0.0, False)]
        rest = [target(i, 10.0, 1.0, 1.0) for i in range(3, 20)]
        cls.seed1 = run_dir("one/s1", s1 + rest)
        cls.seed2 = run_dir("one/s2", s2 + rest)
        cls.result = tool("--a2", cls.seed1, cls.seed2)

    def test_exit_and_columns(self):
        self.assertEqual(self.result.returncode, 0, self.result.stderr)
        self.assertEqual(header(self.result.stdout),
                         ["target", "paper A1 RSE", "paper A1 TLR", "paper A2 RSE", "paper A2 TLR", "paper Δ RSE",
                          "paper Δ TLR", "A2 RSE", "A2 TLR", "A2 TLR_len", "reported"])
        # No truth.csv in these runs: one note per run, and "reported" is '-'.
        self.assertEqual(self.result.stderr.count("onera_table.py: note: "), 2, self.result.stderr)
        for seed in (self.seed1, self.seed2):
            self.assertIn(f"note: {seed / 'truth.csv'}: missing (is {seed} a wsntrack run directory?); the reported "
                          "column is shown as '-'", self.result.stderr)
        self.assertNotIn("reported share", self.result.stdout)

    def test_per_target_means_over_runs(self):
        out = self.result.stdout
        self.assertEqual(cells(out, "1"), ["1", "10.48", "0.99", "19.43", "0.80", "-8.95", "+0.19", "5.00", "0.60", "0.40", "-"])
        self.assertEqual(cells(out, "2")[7:], ["8.00", "0.20", "0.20", "-"])
        self.assertEqual(cells(out, "3")[7:], ["-", "0.00", "0.00", "-"])
        self.assertEqual(cells(out, "20")[7:], ["10.00", "1.00", "1.00", "-"])
        self.assertEqual(cells(out, "14")[5:7], ["-2.28", "+0.00"])  # the paper's equal TLR: no "-0.00"

    def test_summary_rows(self):
        out = self.result.stdout
        # Our RSE over the 19 targets with one: (5 + 8 + 17 * 10) / 19 = 183 / 19 = 9.6316; median 10.
        # TLR over all 20: (0.6 + 0.2 + 0 + 17) / 20 = 0.89; TLR_len (0.4 + 0.2 + 0 + 17) / 20 = 0.88.
        mean = cells(out, "**mean**")
        self.assertEqual(mean[1:5], ["8.773", "0.737", "9.976", "0.707"])
        self.assertEqual(mean[7:], ["9.632", "0.890", "0.880", "-"])
        self.assertEqual(cells(out, "**median**")[1:4], ["7.065", "0.795", "9.175"])
        self.assertEqual(cells(out, "**median**")[7:], ["10.000", "1.000", "1.000", "-"])

    def test_paper_statistics(self):
        out = self.result.stdout
        self.assertIn("- paper: mean RSE 8.77 vs 9.98 m (medians 7.065, 9.175); mean TLR 0.737 vs 0.707", out)
        self.assertIn("- paper: A1's RSE lower on 12/20 targets; A1's TLR higher on 9, equal on 4, lower on 7 "
                      "(targets 4, 7, 11, 12, 13, 15, 20)", out)
        self.assertIn("- ours A2: mean RSE 9.63 m (median 10.000); mean TLR 0.890 (median 1.000); "
                      "mean TLR_len 0.880 (median 1.000)", out)
        self.assertIn("A2 2 runs", out)

    def test_positional_runs_are_algorithm_2(self):
        result = tool(self.seed1, self.seed2)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(result.stdout, self.result.stdout)

    def test_metrics_json_path_is_accepted(self):
        result = tool("--a2", self.seed1 / "metrics.json", self.seed2)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(result.stdout, self.result.stdout)
        self.assertIn(f"note: {self.seed1 / 'metrics.json'}: not a run directory, so no truth.csv", result.stderr)


class TwoAlgorithms(unittest.TestCase):
    """--a1 and --a2: our deltas and comparisons."""

    def test_deltas_and_comparisons(self):
        # 20 targets; A1 = A2 except: target 1 RSE 5 vs 7 (A1 lower), TLR 0.9 vs 0.8 (higher), TLR_len
        # 0.5 vs 0.7 (lower); target 2 RSE 9 vs 7, TLR 0.3 vs 0.6 (lower). Others RSE 7, TLR 0.5 and
        # 0.5 (equal), TLR_len 0.5 (equal).
        a1 = [target(0, 5.0, 0.9, 0.5), target(1, 9.0, 0.3, 0.5)] + [target(i, 7.0, 0.5, 0.5) for i in range(2, 20)]
        a2 = [target(0, 7.0, 0.8, 0.7), target(1, 7.0, 0.6, 0.5)] + [target(i, 7.0, 0.5, 0.5) for i in range(2, 20)]
        result = tool("--a1", run_dir("two/a1", a1), "--a2", run_dir("two/a2", a2))
        self.assertEqual(result.returncode, 0, result.stderr)
        out = result.stdout
        self.assertEqual(header(out)[7:], ["A1 RSE", "A1 TLR", "A1 TLR_len", "A2 RSE", "A2 TLR", "A2 TLR_len",
                                           "reported", "Δ RSE", "Δ TLR", "Δ TLR_len"])
        self.assertEqual(cells(out, "1")[7:], ["5.00", "0.90", "0.50", "7.00", "0.80", "0.70", "-", "-2.00", "+0.10",
                                               "-0.20"])
        self.assertEqual(cells(out, "2")[14:], ["+2.00", "-0.30", "+0.00"])
        self.assertEqual(cells(out, "5")[14:], ["+0.00", "+0.00", "+0.00"])
        self.assertIn("- ours: A1's RSE lower on 1/20 targets; A1's TLR higher on 1, equal on 18, lower on 1 "
                      "(targets 2)", out)
        self.assertIn("- ours, path length: A1's RSE lower on 1/20 targets; A1's TLR_len higher on 0, equal on 19, "
                      "lower on 1 (targets 1)", out)


class Oddities(unittest.TestCase):
    def test_runs_without_tlr_length(self):
        result = tool(run_dir("old/s1", [target(i, 3.0, 0.5) for i in range(20)]))
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(cells(result.stdout, "1")[7:], ["3.00", "0.50", "-", "-"])
        self.assertIn("no tlr_length", result.stderr)

    def test_other_target_count_is_noted(self):
        result = tool(run_dir("short/s1", [target(i, 3.0, 0.5, 0.5) for i in range(3)]))
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("the A2 runs have 3 targets, Table II has 20", result.stderr)
        self.assertEqual(cells(result.stdout, "4")[7:], ["-", "-", "-", "-"])


# Two seeds of 20 targets. Target id 0 (table target 1) is alive at ticks 10-13, the others at 10-11.
# Seed 1: target 0 reported at 10, twice at 11 (counted once) and at 12; its report of tick 13 is lost
# and a false alarm (-1) is delivered at 13: 3/4 = 0.75. Target 1: reported at 11 only: 1/2.
# Seed 2: target 0's reports generated at 11, 12 and 13 are delivered at 12, 14 and 13 (tick_generated
# counts): 3/4 = 0.75. Target 1: one lost report, a false alarm: 0.
# Means: target 1 (0.75 + 0.75) / 2 = 0.75, target 2 (0.5 + 0) / 2 = 0.25, targets 3-20: 1.
ALIVE = {i: [10, 11, 12, 13] if i == 0 else [10, 11] for i in range(20)}
OTHERS = [(t, t, i, "delivered") for i in range(2, 20) for t in (10, 11)]
SEED1_REPORTS = [(10, 10, 0, "delivered"), (11, 11, 0, "delivered"), (11, 12, 0, "delivered"),
                 (12, 12, 0, "delivered"), (13, 13, 0, "lost"), (13, 13, -1, "delivered"),
                 (11, 11, 1, "delivered")] + OTHERS
SEED2_REPORTS = [(11, 12, 0, "delivered"), (12, 14, 0, "delivered"), (13, 13, 0, "delivered"),
                 (10, 10, 1, "dropped"), (11, 11, -1, "delivered")] + OTHERS
# TLR 0.6, 0.2 and 0.9 for the others: mean (0.6 + 0.2 + 18 * 0.9) / 20 = 0.85.
METRICS = [target(0, 5.0, 0.6, 0.6), target(1, 5.0, 0.2, 0.2)] + [target(i, 5.0, 0.9, 0.9) for i in range(2, 20)]


def reported_run(name, reports, metrics=METRICS, alive=ALIVE, **replace):
    files = {"truth.csv": truth_csv(alive), "observations.csv": observations_csv(reports)}
    files.update(replace)
    return run_dir(name, metrics, files={k: v for k, v in files.items() if v is not None})


class Reported(unittest.TestCase):
    """The "reported" column: share of a target's alive ticks with at least one delivered report."""

    @classmethod
    def setUpClass(cls):
        cls.seed1 = reported_run("reported/s1", SEED1_REPORTS)
        cls.seed2 = reported_run("reported/s2", SEED2_REPORTS)
        cls.result = tool("--a2", cls.seed1, cls.seed2)

    def test_shares_averaged_over_runs(self):
        self.assertEqual(self.result.returncode, 0, self.result.stderr)
        self.assertEqual(self.result.stderr, "")
        out = self.result.stdout
        self.assertEqual(header(out)[7:], ["A2 RSE", "A2 TLR", "A2 TLR_len", "reported"])
        self.assertEqual(cells(out, "1")[7:], ["5.00", "0.60", "0.60", "0.75"])
        self.assertEqual(cells(out, "2")[7:], ["5.00", "0.20", "0.20", "0.25"])
        self.assertEqual(cells(out, "3")[10], "1.00")
        self.assertEqual(cells(out, "20")[10], "1.00")

    def test_single_runs(self):
        out = tool("--a2", self.seed1).stdout
        self.assertEqual([cells(out, str(j))[10] for j in (1, 2, 3)], ["0.75", "0.50", "1.00"])
        out = tool("--a2", self.seed2).stdout
        self.assertEqual([cells(out, str(j))[10] for j in (1, 2, 3)], ["0.75", "0.00", "1.00"])

    def test_mean_and_median_rows(self):
        # (0.75 + 0.25 + 18) / 20 = 0.95; median 1.
        self.assertEqual(cells(self.result.stdout, "**mean**")[10], "0.950")
        self.assertEqual(cells(self.result.stdout, "**median**")[10], "1.000")

    def test_statistics_line(self):
        # 0.85 / 0.95 = 0.8947.
        self.assertIn("- reported share: mean 0.950 (median 1.000); TLR / reported: A2 0.895", self.result.stdout)

    def test_a2_files_used_with_both_algorithms(self):
        # The A1 runs have no CSV files: the column comes from the A2 runs' without a note. A1's TLR is
        # 0.5 everywhere: 0.5 / 0.95 = 0.5263.
        a1 = [run_dir(f"reported/a1-{k}", [target(i, 4.0, 0.5, 0.5) for i in range(20)]) for k in (1, 2)]
        result = tool("--a1", *a1, "--a2", self.seed1, self.seed2)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(result.stderr, "")
        self.assertEqual(header(result.stdout)[13:], ["reported", "Δ RSE", "Δ TLR", "Δ TLR_len"])
        self.assertEqual(cells(result.stdout, "1")[13:], ["0.75", "-1.00", "-0.10", "-0.10"])
        self.assertEqual(cells(result.stdout, "2")[13], "0.25")
        self.assertIn("- reported share: mean 0.950 (median 1.000); TLR / reported: A1 0.526, A2 0.895",
                      result.stdout)

    def test_a1_files_without_a2(self):
        result = tool("--a1", self.seed1, self.seed2)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(cells(result.stdout, "1")[7:], ["5.00", "0.60", "0.60", "0.75"])
        self.assertIn("the A1 runs' truth.csv and observations.csv", result.stdout)
        self.assertIn("TLR / reported: A1 0.895", result.stdout)

    def check_dash(self, run, *notes):
        """With `run` beside seed 1 the column is '-' (mean and median too), with these notes; the table
        is still printed."""
        result = tool("--a2", self.seed1, run)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(cells(result.stdout, "1")[7:], ["5.00", "0.60", "0.60", "-"])
        self.assertEqual(cells(result.stdout, "**mean**")[10], "-")
        self.assertEqual(cells(result.stdout, "**median**")[10], "-")
        self.assertNotIn("reported share", result.stdout)
        self.assertEqual(result.stderr.count("onera_table.py: note: "), 1, result.stderr)
        for note in notes:
            self.assertIn(note, result.stderr)

    def test_missing_files(self):
        run = reported_run("reported/no_obs", SEED2_REPORTS, **{"observations.csv": None})
        self.check_dash(run, f"note: {run / 'observations.csv'}: missing (is {run} a wsntrack run directory?); the "
                             "reported column is shown as '-'")
        run = reported_run("reported/no_truth", SEED2_REPORTS, **{"truth.csv": None})
        self.check_dash(run, f"note: {run / 'truth.csv'}: missing")

    def test_target_count_differs(self):
        run = reported_run("reported/19", SEED2_REPORTS, alive={i: [10, 11] for i in range(19)})
        self.check_dash(run, f"{run / 'truth.csv'}: 19 targets, but its metrics.json has 20")

    def test_malformed_csv(self):
        run = reported_run("reported/no_fate", SEED2_REPORTS, **{"observations.csv": observations_csv(
            SEED2_REPORTS).replace(",fate,", ",what,", 1)})
        self.check_dash(run, f"{run / 'observations.csv'}:1: expected the header 'tick_generated,target,fate', got "
                             "'tick_generated,tick_delivered,sensor,supernode,hops,delay,x,y,target,what,level' (no "
                             "column 'fate')")
        run = reported_run("reported/bad_tick", SEED2_REPORTS, **{"truth.csv": truth_csv(ALIVE).replace(
            "\n10,19,", "\nten,19,", 1)})
        self.check_dash(run, f"{run / 'truth.csv'}:2: column 'tick' must be a whole number, got 'ten'")
        run = reported_run("reported/bad_target", SEED2_REPORTS, **{"observations.csv": observations_csv(
            SEED2_REPORTS).replace(",0,delivered,0\n", ",0.5,delivered,0\n", 1)})
        self.check_dash(run, f"{run / 'observations.csv'}:2: column 'target' must be a whole number, got '0.5'")
        run = reported_run("reported/short_row", SEED2_REPORTS, **{"truth.csv": "tick,target,x,y,vx,vy\n10\n"})
        self.check_dash(run, f"{run / 'truth.csv'}:2: expected 6 fields (tick,target,x,y,vx,vy), got 1")

CLASS_COLUMNS = ("wheeled_light", "wheeled_heavy", "tracked", "human", "group", "aerial", "none")


def classification(entries, confusion):
    """A classification block as wsntrack writes it, for targets [(id, class, associated, declared,
    correct)] and confusion {true class: {declared: count}} (the other columns written as zeros)."""
    known = [e for e in entries if e[1] != "unknown"]
    associated, declared, correct = (sum(e[k] for e in known) for k in (2, 3, 4))
    return {"gate": 50.0, "ticks_associated": associated, "ticks_declared": declared, "ticks_correct": correct,
            "declared_share": declared / associated if associated else None,
            "class_accuracy": correct / declared if declared else None,
            "confusion": {truth: {c: row.get(c, 0) for c in CLASS_COLUMNS} for truth, row in confusion.items()},
            "targets": [{"id": i, "class": c, "ticks_associated": a, "ticks_declared": d, "ticks_correct": k,
                         "class_accuracy": k / d if d and c != "unknown" else None} for i, c, a, d, k in entries]}


def class_run(name, block, targets=None):
    """A run directory whose metrics.json has track_quality (20 targets, RSE 5, TLR 0.5 unless given)
    and this classification block after boundary."""
    targets = targets or [target(i, 5.0, 0.5, 0.5) for i in range(20)]
    return run_dir(name, text=json.dumps({"eps_k": 0.0, "track_quality": {"gate": 50.0, "targets": targets},
                                          "boundary": {"band": 5.0}, "classification": block}))


# Two seeds. Table target 1 (id 0, wheeled_light): declared 8 of 10 associated ticks, 6 correct, then 2
# of 5, 2 correct: pooled 8/10 = 0.80 (not the mean of 0.75 and 1). Target 2 (id 1, human): nothing
# declared: '-'. Target 3 (id 2, unknown): 3 declared in each seed, accuracy '-'. Target 4 (id 3,
# tracked): associated in seed 2 only, 1 correct of 4: 0.25. Targets 5-20: never associated, not listed.
# Run totals (known classes): associated 10 + 3 and 5 + 2 + 4 = 24, declared 8 and 2 + 4 = 14, correct
# 6 and 2 + 1 = 9: declared share 14/24 = 0.583, accuracy 9/14 = 0.643.
CLASS_SEED1 = classification(
    [(0, "wheeled_light", 10, 8, 6), (1, "human", 3, 0, 0), (2, "unknown", 5, 3, 0)],
    {"wheeled_light": {"wheeled_light": 6, "human": 2, "none": 2}, "human": {"none": 3},
     "unknown": {"tracked": 3, "none": 2}})
CLASS_SEED2 = classification(
    [(0, "wheeled_light", 5, 2, 2), (1, "human", 2, 0, 0), (2, "unknown", 5, 3, 0), (3, "tracked", 4, 4, 1)],
    {"wheeled_light": {"wheeled_light": 2, "none": 3}, "human": {"none": 2},
     "unknown": {"tracked": 1, "group": 2, "none": 2}, "tracked": {"tracked": 1, "wheeled_heavy": 3}})


class FailingRuns(unittest.TestCase):
    """A case whose tool runs may fail: check_error runs one and expects a clean failure."""

    def check_error(self, args, *expected):
        result = tool(*args)
        self.assertEqual(result.returncode, 1, result.stdout + result.stderr)
        self.assertEqual(result.stdout, "")
        for text in expected:
            self.assertIn(text, result.stderr)


class Classification(FailingRuns):
    """The classification block: class and accuracy columns, the run-level section, older runs."""

    @classmethod
    def setUpClass(cls):
        cls.seed1 = class_run("class/s1", CLASS_SEED1)
        cls.seed2 = class_run("class/s2", CLASS_SEED2)
        cls.result = tool("--a2", cls.seed1, cls.seed2)

    def test_columns(self):
        self.assertEqual(self.result.returncode, 0, self.result.stderr)
        self.assertEqual(header(self.result.stdout),
                         ["target", "class", "paper A1 RSE", "paper A1 TLR", "paper A2 RSE", "paper A2 TLR",
                          "paper Δ RSE", "paper Δ TLR", "A2 RSE", "A2 TLR", "A2 TLR_len", "A2 acc", "reported"])
        self.assertIn("|---:|---|---:|", self.result.stdout)  # the class column left-aligned
        # Only the notes of the missing truth.csv files.
        self.assertEqual(self.result.stderr.count("onera_table.py: note: "), 2, self.result.stderr)

    def test_pooled_accuracy_over_runs(self):
        out = self.result.stdout
        self.assertEqual(cells(out, "1"), ["1", "wheeled_light", "10.48", "0.99", "19.43", "0.80", "-8.95", "+0.19",
                                           "5.00", "0.50", "0.50", "0.80", "-"])
        self.assertEqual(cells(out, "4")[1], "tracked")
        self.assertEqual(cells(out, "4")[11], "0.25")
        # Mean and median over the targets with an accuracy: (0.80 + 0.25) / 2; no mean class.
        self.assertEqual(cells(out, "**mean**")[1], "")
        self.assertEqual(cells(out, "**mean**")[11], "0.525")
        self.assertEqual(cells(out, "**median**")[11], "0.525")

    def test_undefined_accuracy(self):
        out = self.result.stdout
        self.assertEqual(cells(out, "2")[1], "human")
        self.assertEqual(cells(out, "2")[11], "-")  # nothing declared
        self.assertEqual(cells(out, "3")[1], "unknown")
        self.assertEqual(cells(out, "3")[11], "-")  # declared, but no true class to compare with
        self.assertEqual(cells(out, "5")[1], "-")  # never associated: not listed
        self.assertEqual(cells(out, "5")[11], "-")
        self.assertEqual(cells(out, "20")[1], "-")

    def test_single_run(self):
        out = tool("--a2", self.seed1).stdout
        self.assertEqual([cells(out, str(j))[11] for j in (1, 2, 3, 4)], ["0.75", "-", "-", "-"])
        self.assertEqual(cells(out, "4")[1], "-")
        self.assertIn("- A2 (1 run): declared share 0.615 (8/13 associated ticks), accuracy 0.750 "
                      "(6/8 declared ticks)", out)

    def test_run_totals(self):
        self.assertIn("\n- A2 (2 runs): declared share 0.583 (14/24 associated ticks), accuracy 0.643 "
                      "(9/14 declared ticks)\n", self.result.stdout)

    def test_confusion_summed_over_runs(self):
        # Columns: the classes that are a row or counted (aerial is neither), then none; rows in class order.
        out = self.result.stdout
        self.assertEqual(cells(out, "A2 true / declared"),
                         ["A2 true / declared", "wheeled_light", "wheeled_heavy", "tracked", "human", "group", "none"])
        self.assertEqual(cells(out, "wheeled_light"), ["wheeled_light", "8", "0", "0", "2", "0", "5"])
        self.assertEqual(cells(out, "tracked"), ["tracked", "0", "3", "1", "0", "0", "0"])
        self.assertEqual(cells(out, "human"), ["human", "0", "0", "0", "0", "0", "5"])
        self.assertEqual(cells(out, "unknown"), ["unknown", "0", "0", "4", "0", "2", "4"])
        lines = out.splitlines()
        start = lines.index("| A2 true / declared | wheeled_light | wheeled_heavy | tracked | human | group | none |")
        self.assertEqual(lines[start + 1], "|---|---:|---:|---:|---:|---:|---:|")
        self.assertEqual([line.split("|")[1].strip() for line in lines[start + 2:start + 6]],
                         ["wheeled_light", "tracked", "human", "unknown"])
        self.assertEqual(lines[start + 6:], [])  # the end of the output

    def test_both_algorithms(self):
        result = tool("--a1", self.seed1, "--a2", self.seed2)
        self.assertEqual(result.returncode, 0, result.stderr)
        out = result.stdout
        self.assertEqual(header(out)[8:], ["A1 RSE", "A1 TLR", "A1 TLR_len", "A1 acc", "A2 RSE", "A2 TLR",
                                           "A2 TLR_len", "A2 acc", "reported", "Δ RSE", "Δ TLR", "Δ TLR_len"])
        self.assertEqual(cells(out, "1")[11], "0.75")
        self.assertEqual(cells(out, "1")[15], "1.00")
        self.assertEqual(cells(out, "4")[1], "tracked")  # from the A2 run
        self.assertEqual([cells(out, "4")[k] for k in (11, 15)], ["-", "0.25"])
        self.assertIn("- A1 (1 run): declared share 0.615 (8/13 associated ticks)", out)
        self.assertIn("- A2 (1 run): declared share 0.545 (6/11 associated ticks), accuracy 0.500 "
                      "(3/6 declared ticks)", out)
        self.assertEqual(cells(out, "A1 true / declared")[1:], ["wheeled_light", "tracked", "human", "none"])
        self.assertEqual(cells(out, "A2 true / declared")[1:],
                         ["wheeled_light", "wheeled_heavy", "tracked", "human", "group", "none"])

    def test_nothing_associated(self):
        # Only a target of unknown class: the run totals are 0 of 0, shown as '-'.
        run = class_run("class/unknown_only", classification([(5, "unknown", 4, 0, 0)], {"unknown": {"none": 4}}))
        result = tool("--a2", run)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(cells(result.stdout, "6")[1], "unknown")
        self.assertEqual(cells(result.stdout, "6")[11], "-")
        self.assertEqual(cells(result.stdout, "**mean**")[11], "-")
        self.assertIn("- A2 (1 run): declared share - (0/0 associated ticks), accuracy - (0/0 declared ticks)",
                      result.stdout)
        self.assertEqual(cells(result.stdout, "A2 true / declared")[1:], ["none"])

    def test_runs_without_the_block(self):
        # Runs of before the classification metric: no class columns, no section, as before.
        old = [run_dir(f"class/old-{k}", [target(i, 5.0, 0.5, 0.5) for i in range(20)]) for k in (1, 2)]
        result = tool("--a2", *old)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(header(result.stdout)[:2], ["target", "paper A1 RSE"])
        self.assertEqual(header(result.stdout)[7:], ["A2 RSE", "A2 TLR", "A2 TLR_len", "reported"])
        self.assertNotIn("class", result.stdout)
        self.assertNotIn("Classification", result.stdout)
        # With the A1 runs' block: the class and A1 acc columns, and a line saying A2 has none.
        result = tool("--a1", self.seed1, self.seed2, "--a2", *old)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(header(result.stdout)[8:16], ["A1 RSE", "A1 TLR", "A1 TLR_len", "A1 acc", "A2 RSE",
                                                        "A2 TLR", "A2 TLR_len", "reported"])
        self.assertEqual(cells(result.stdout, "1")[1], "wheeled_light")
        self.assertEqual(cells(result.stdout, "1")[11], "0.80")
        self.assertIn("- A1 (2 runs): declared share 0.583", result.stdout)
        self.assertIn("- A2: no classification block in its runs' metrics.json", result.stdout)
        self.assertNotIn("A2 true / declared", result.stdout)

    def test_mixed_runs_fail(self):
        old = run_dir("class/mixed-old", [target(i, 5.0, 0.5, 0.5) for i in range(20)])
        self.check_error(["--a2", self.seed1, old],
                         f"onera_table.py: {old / 'metrics.json'}: no classification block, but "
                         f"{self.seed1 / 'metrics.json'} (another of the --a2 runs) has one")
        self.check_error(["--a1", old, self.seed2, "--a2", self.seed1],
                         f"{old / 'metrics.json'}: no classification block, but {self.seed2 / 'metrics.json'} "
                         "(another of the --a1 runs)")

    def test_class_differs_between_runs(self):
        other = class_run("class/other", classification([(0, "human", 4, 0, 0)], {"human": {"none": 4}}))
        self.check_error(["--a2", self.seed1, other],
                         f"onera_table.py: {other / 'metrics.json'}: classification: target 1 "
                         f"(track_quality.targets[0]) has class 'human', but 'wheeled_light' in "
                         f"{self.seed1 / 'metrics.json'}")
        self.check_error(["--a1", self.seed1, "--a2", other], f"{other / 'metrics.json'}: classification: target 1")

    def test_malformed_block(self):
        run = class_run("class/bad_id", classification([(20, "human", 4, 0, 0)], {"human": {"none": 4}}))
        self.check_error([run], f"{run / 'metrics.json'}: classification.targets[0].id: 20 is not the id of a target "
                                "of track_quality.targets")
        run = class_run("class/bad_counts", classification([(0, "human", 4, 2, 3)], {"human": {"human": 3}}))
        self.check_error([run], f"{run / 'metrics.json'}: classification.targets[0]: expected ticks_correct <= "
                                "ticks_declared <= ticks_associated, got 3, 2, 4")
        block = classification([(0, "human", 4, 0, 0)], {"human": {"none": 4}})
        del block["confusion"]
        run = class_run("class/no_confusion", block)
        self.check_error([run], f"{run / 'metrics.json'}: classification: no 'confusion'")
        block = classification([(0, "human", 4, 0, 0)], {"human": {"none": -1}})
        run = class_run("class/negative", block)
        self.check_error([run], f"{run / 'metrics.json'}: classification.confusion.human.none: expected a count")
        run = class_run("class/not_object", None)
        self.check_error([run], f"{run / 'metrics.json'}: classification: expected an object, got null")

    def test_help(self):
        out = tool("--help").stdout
        self.assertIn("sum of ticks_correct / sum of ticks_declared", out)
        self.assertIn('"Classification" section', out)


def stop_mode(entries, without=0):
    """A stop_mode block as wsntrack writes it, for targets [(id, ticks_stopped, mean while stopped,
    ticks_moving, mean while moving)] (a mean None when its ticks are 0): the run's means weighted by
    the targets' ticks."""
    block = {"gate": 50.0}
    for k, (ticks, mean) in enumerate((("ticks_stopped", "mean_stop_probability_stopped"),
                                       ("ticks_moving", "mean_stop_probability_moving"))):
        count = sum(e[1 + 2 * k] for e in entries)
        block[ticks] = count
        block[mean] = sum(e[1 + 2 * k] * e[2 + 2 * k] for e in entries if e[1 + 2 * k]) / count if count else None
    block["ticks_without_stop_model"] = without
    block["targets"] = [{"id": i, "ticks_stopped": ts, "mean_stop_probability_stopped": ms, "ticks_moving": tm,
                         "mean_stop_probability_moving": mm} for i, ts, ms, tm, mm in entries]
    return block


# Track_quality ids 10-29: id 10 + N - 1 is table target N.
STOP_TARGETS = [target(10 + i, 5.0, 0.5, 0.5) for i in range(20)]


def stop_run(name, block, classification_block=None):
    """A run directory whose metrics.json has track_quality (ids 10-29, RSE 5, TLR 0.5), this stop_mode
    block (None: none) and, when given, this classification block."""
    data = {"eps_k": 0.0, "track_quality": {"gate": 50.0, "targets": STOP_TARGETS}}
    if classification_block is not None:
        data["classification"] = classification_block
    if block is not None:
        data["stop_mode"] = block
    return run_dir(name, text=json.dumps(data))


# Two seeds. Seed 1: table target 2 (id 11) stopped 30 ticks at 0.9 and moving 70 at 0.1; target 5
# (id 14) never stopped, moving 50 at 0.02; target 7 (id 16) stopped 10 at 0.5, moving 40 at 0.05.
# Run: stopped 40 at (27 + 5) / 40 = 0.8, moving 160 at (7 + 1 + 2) / 160 = 0.0625.
# Seed 2: target 2 stopped 10 at 0.5, moving 90 at 0.2; target 5 stopped 20 at 0.7, moving 30 at 0.1;
# target 7 never associated; 5 ticks of tracks without a stop model. Run: stopped 30 at (5 + 14) / 30
# = 0.633, moving 120 at (18 + 3) / 120 = 0.175.
# Pooled: stopped 70 at (32 + 19) / 70 = 0.729 (not the mean of the runs' means, 0.717), moving 280 at
# (10 + 21) / 280 = 0.111 (not 0.119). Per target while stopped: 2 (27 + 5) / 40 = 0.80 (40 ticks),
# 5 14 / 20 = 0.70 (20), 7 0.50 (10).
STOP_SEED1 = stop_mode([(11, 30, 0.9, 70, 0.1), (14, 0, None, 50, 0.02), (16, 10, 0.5, 40, 0.05)])
STOP_SEED2 = stop_mode([(11, 10, 0.5, 90, 0.2), (14, 20, 0.7, 30, 0.1)], without=5)
STOP_HEADING = "Stop mode (metrics.json's stop_mode block): the mean probability a track gives the stop model"


class StopMode(FailingRuns):
    """The stop_mode block: the stop mode section, pooled over runs; older runs; malformed blocks."""

    @classmethod
    def setUpClass(cls):
        cls.seed1 = stop_run("stop/s1", STOP_SEED1)
        cls.seed2 = stop_run("stop/s2", STOP_SEED2)
        cls.old = [stop_run(f"stop/old-{k}", None) for k in (1, 2)]
        cls.result = tool("--a2", cls.seed1, cls.seed2)

    def test_pooled_over_runs(self):
        self.assertEqual(self.result.returncode, 0, self.result.stderr)
        lines = self.result.stdout.splitlines()
        start = next(k for k, line in enumerate(lines) if line.startswith(STOP_HEADING))
        self.assertEqual(lines[start - 1], "")
        self.assertEqual(lines[start + 1:], [
            "",
            "- A2 (2 runs): while stopped 0.729 (70 ticks), while moving 0.111 (280 ticks); 5 associated ticks "
            "of tracks whose engine has no stop model",
            "- per target that stops (target: A2 while stopped (ticks)): 2: 0.80 (40), 5: 0.70 (20), 7: 0.50 (10)"])

    def test_single_run(self):
        result = tool("--a2", self.seed2)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("\n- A2 (1 run): while stopped 0.633 (30 ticks), while moving 0.175 (120 ticks); 5 "
                      "associated ticks of tracks whose engine has no stop model\n", result.stdout)
        self.assertIn("\n- per target that stops (target: A2 while stopped (ticks)): 2: 0.50 (10), 5: 0.70 (20)\n",
                      result.stdout)
        # No tick without a stop model: no such clause.
        result = tool("--a2", self.seed1)
        self.assertIn("\n- A2 (1 run): while stopped 0.800 (40 ticks), while moving 0.062 (160 ticks)\n",
                      result.stdout)

    def test_both_algorithms(self):
        # Target 5 is listed in A1's run but never stopped, target 7 is not listed in A2's: '-' (0).
        result = tool("--a1", self.seed1, "--a2", self.seed2)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("\n- A1 (1 run): while stopped 0.800 (40 ticks), while moving 0.062 (160 ticks)\n"
                      "- A2 (1 run): while stopped 0.633 (30 ticks)", result.stdout)
        self.assertTrue(result.stdout.endswith(
            "\n- per target that stops (target: A1 while stopped (ticks); A2 while stopped (ticks)): 2: 0.90 (30); "
            "0.50 (10), 5: - (0); 0.70 (20), 7: 0.50 (10); - (0)\n"), result.stdout)

    def test_no_target_stops(self):
        run = stop_run("stop/moving_only", stop_mode([(10, 0, None, 8, 0.25)]))
        result = tool("--a2", run)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("\n- A2 (1 run): while stopped - (0 ticks), while moving 0.250 (8 ticks)\n", result.stdout)
        self.assertIn("\n- per target that stops (target: A2 while stopped (ticks)): none\n", result.stdout)
        # An engine without a stop model: no tick has a probability.
        run = stop_run("stop/no_model", stop_mode([(10, 0, None, 0, None)], without=12))
        result = tool("--a2", run)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("\n- A2 (1 run): while stopped - (0 ticks), while moving - (0 ticks); 12 associated ticks of "
                      "tracks whose engine has no stop model\n", result.stdout)

    def test_runs_without_the_block(self):
        # Runs of before the stop_mode metric: no section, and the rest as with the block.
        result = tool("--a2", *self.old)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertNotIn("Stop mode", result.stdout)
        self.assertNotIn("stop", result.stdout)
        self.assertTrue(self.result.stdout.startswith(result.stdout), self.result.stdout)
        self.assertTrue(self.result.stdout[len(result.stdout):].startswith("\n" + STOP_HEADING))
        # With the A1 runs' block: a line saying A2 has none, and only A1 per target.
        result = tool("--a1", self.seed1, self.seed2, "--a2", *self.old)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("\n- A1 (2 runs): while stopped 0.729 (70 ticks)", result.stdout)
        self.assertIn("\n- A2: no stop_mode block in its runs' metrics.json (scored before it existed)\n"
                      "- per target that stops (target: A1 while stopped (ticks)): 2: 0.80 (40), 5: 0.70 (20), "
                      "7: 0.50 (10)\n", result.stdout)

    def test_after_the_classification_section(self):
        run = stop_run("stop/with_class", STOP_SEED1, classification([(10, "human", 4, 0, 0)], {"human": {"none": 4}}))
        result = tool("--a2", run)
        self.assertEqual(result.returncode, 0, result.stderr)
        out = result.stdout
        self.assertIn("Classification (", out)
        self.assertLess(out.index("| human | 0 | 4 |"), out.index(STOP_HEADING))
        self.assertEqual(cells(out, "1")[1], "human")  # the classification block's ids are mapped alike

    def test_mixed_runs_fail(self):
        old = self.old[0]
        self.check_error(["--a2", self.seed1, old],
                         f"onera_table.py: {old / 'metrics.json'}: no stop_mode block, but "
                         f"{self.seed1 / 'metrics.json'} (another of the --a2 runs) has one: the runs of an "
                         "algorithm must all have it")
        self.check_error(["--a1", old, self.seed2, "--a2", self.seed1],
                         f"{old / 'metrics.json'}: no stop_mode block, but {self.seed2 / 'metrics.json'} "
                         "(another of the --a1 runs)")

    def check_bad(self, name, block, expected):
        run = stop_run(f"stop/{name}", block)
        self.check_error([run], f"onera_table.py: {run / 'metrics.json'}: {expected}")

    def test_malformed_block(self):
        self.check_bad("not_object", [], "stop_mode: expected an object, got []")
        block = stop_mode([(10, 3, 0.5, 4, 0.25)])
        del block["ticks_moving"]
        self.check_bad("no_key", block, "stop_mode: no 'ticks_moving' (expected ticks_stopped, "
                                        "mean_stop_probability_stopped, ticks_moving")
        block = stop_mode([(10, 3, 0.5, 4, 0.25)])
        block["ticks_stopped"] = -3
        self.check_bad("negative", block, "stop_mode.ticks_stopped: expected a count (an integer >= 0), got -3")
        block = stop_mode([(10, 3, 0.5, 4, 0.25)])
        block["ticks_without_stop_model"] = 1.5
        self.check_bad("float_count", block, "stop_mode.ticks_without_stop_model: expected a count")
        block = stop_mode([(10, 3, 0.5, 4, 0.25)])
        block["mean_stop_probability_stopped"] = None
        self.check_bad("null_mean", block,
                       "stop_mode.mean_stop_probability_stopped: expected a probability (a number in [0, 1]) "
                       "since ticks_stopped is 3, got null")
        self.check_bad("above_one", stop_mode([(10, 3, 0.5, 4, 1.5)]),
                       "stop_mode.mean_stop_probability_moving: expected a probability (a number in [0, 1]), got 1.5")
        block = stop_mode([(10, 3, 0.5, 4, 0.25)])
        block["targets"][0]["mean_stop_probability_stopped"] = "high"
        self.check_bad("string_mean", block,
                       'stop_mode.targets[0].mean_stop_probability_stopped: expected a finite number, got "high"')
        block = stop_mode([(10, 3, 0.5, 4, 0.25)])
        block["targets"][0]["mean_stop_probability_moving"] = -0.1
        self.check_bad("negative_mean", block, "stop_mode.targets[0].mean_stop_probability_moving: expected a "
                                               "probability (a number in [0, 1]), got -0.1")
        block = stop_mode([(10, 3, 0.5, 4, 0.25)])
        del block["targets"][0]["id"]
        self.check_bad("no_id", block, "stop_mode.targets[0]: no 'id' (expected id, ticks_stopped")
        self.check_bad("bad_id", stop_mode([(3, 3, 0.5, 4, 0.25)]),
                       "stop_mode.targets[0].id: 3 is not the id of a target of track_quality.targets")
        self.check_bad("twice", stop_mode([(10, 3, 0.5, 4, 0.25), (10, 1, 0.5, 0, None)]),
                       "stop_mode.targets[1].id: target 10 is listed twice")
        block = stop_mode([(10, 3, 0.5, 4, 0.25)])
        block["targets"] = {"10": {}}
        self.check_bad("targets_object", block, 'stop_mode.targets: expected a list of targets, got {"10": {}}')
        block = stop_mode([(10, 3, 0.5, 4, 0.25)])
        block["ticks_moving"] = 5
        self.check_bad("sum", block, "stop_mode.ticks_moving: expected the sum of its targets' ticks_moving, 4, got 5")

    def test_help(self):
        out = tool("--help").stdout
        self.assertIn('"Stop mode" section', out)
        self.assertIn("sum(mean * ticks) /", out)


class Plot(unittest.TestCase):
    """--plot FILE: the same table on stdout, and the bar charts in FILE."""

    @classmethod
    def setUpClass(cls):
        # A2: OneAlgorithm's kind of runs (target 3's RSE undefined in both: no bar); A1: 20 plain targets.
        s1 = [target(0, 4.0, 0.5, 0.2), target(1, 0.0, 0.0, 0.0, defined=False), target(2, 0, 0.0, 0.0, False)]
        rest = [target(i, 10.0, 1.0, 1.0) for i in range(3, 20)]
        cls.a2 = [run_dir("plot/a2-s1", s1 + rest), run_dir("plot/a2-s2", s1 + rest)]
        cls.a1 = [run_dir("plot/a1-s1", [target(i, 6.0, 0.8, 0.8) for i in range(20)])]
        cls.args = ["--a1", *cls.a1, "--a2", *cls.a2]
        cls.table = tool(*cls.args)
        assert cls.table.returncode == 0, cls.table.stderr

    def out_dir(self, name):
        path = WORK / "plot" / name
        path.mkdir(parents=True)
        return path

    def check_written(self, out, result):
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(result.stdout, self.table.stdout)  # the table as without --plot
        self.assertIn(f"onera_table.py: wrote the plot to {out}\n", result.stderr)
        self.assertEqual(os.listdir(out.parent), [out.name])  # no temporary file left behind
        data = out.read_bytes()
        self.assertGreater(len(data), 1000)
        return data

    @unittest.skipUnless(HAVE_MATPLOTLIB, NO_MATPLOTLIB)
    def test_png(self):
        out = self.out_dir("png") / "bars.png"
        data = self.check_written(out, tool(*self.args, "--plot", out))
        self.assertEqual(data[:8], b"\x89PNG\r\n\x1a\n")

    @unittest.skipUnless(HAVE_MATPLOTLIB, NO_MATPLOTLIB)
    def test_svg(self):
        out = self.out_dir("svg") / "bars.svg"
        text = self.check_written(out, tool("--plot", out, *self.args)).decode("utf-8")
        self.assertTrue(text.startswith("<?xml") or "<svg" in text, text[:200])
        self.assertIn("<svg", text)

    @unittest.skipUnless(HAVE_MATPLOTLIB, NO_MATPLOTLIB)
    def test_one_algorithm(self):
        out = self.out_dir("a2") / "bars.png"
        result = tool("--a2", *self.a2, "--plot", out)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(out.read_bytes()[:8], b"\x89PNG\r\n\x1a\n")

    @unittest.skipUnless(HAVE_MATPLOTLIB, NO_MATPLOTLIB)
    def test_unwritable(self):
        out = WORK / "plot" / "nowhere" / "bars.png"
        result = tool(*self.args, "--plot", out)
        self.assertEqual(result.returncode, 1, result.stderr)
        self.assertIn(f"onera_table.py: {out}: cannot write the plot", result.stderr)
        self.assertFalse(out.parent.exists())

    def test_bad_extension(self):
        where = self.out_dir("bad")
        for name, named in (("bars.jpg", "unknown extension '.jpg'"), ("bars.png.txt", "unknown extension '.txt'"),
                            ("bars", "no extension")):
            result = tool(*self.args, "--plot", where / name)
            self.assertEqual(result.returncode, 2, result.stderr)
            self.assertEqual(result.stdout, "")
            self.assertIn(f"--plot {where / name}: {named} (expected a file name ending .png or .svg)",
                          result.stderr)
        self.assertEqual(os.listdir(where), [])

    def fake_matplotlib(self):
        """An environment whose PYTHONPATH shadows matplotlib with a package that cannot be imported."""
        fake = WORK / "plot" / "fake"
        if not fake.exists():
            (fake / "matplotlib").mkdir(parents=True)
            (fake / "matplotlib" / "__init__.py").write_text(
                'raise ImportError("stand-in: no matplotlib here")\n', encoding="utf-8")
        return dict(os.environ, PYTHONPATH=str(fake))

    def test_matplotlib_missing(self):
        where = self.out_dir("missing")
        result = tool(*self.args, "--plot", where / "bars.png", env=self.fake_matplotlib())
        self.assertEqual(result.returncode, 1, result.stderr)
        self.assertEqual(result.stdout, "")
        self.assertIn("matplotlib is not available", result.stderr)
        self.assertIn("stand-in: no matplotlib here", result.stderr)
        self.assertIn("apt-get install python3-matplotlib", result.stderr)
        self.assertEqual(os.listdir(where), [])

    def test_table_without_matplotlib(self):
        # Without --plot matplotlib is never imported.
        result = tool(*self.args, env=self.fake_matplotlib())
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(result.stdout, self.table.stdout)

    def test_help(self):
        self.assertIn("--plot FILE", tool("--help").stdout)


class Errors(unittest.TestCase):
    def check(self, args, *expected, status=1):
        result = tool(*args)
        self.assertEqual(result.returncode, status, result.stdout + result.stderr)
        self.assertEqual(result.stdout, "")
        for text in expected:
            self.assertIn(text, result.stderr)

    def test_missing_run_directory(self):
        self.check([WORK / "nowhere"], f"{WORK / 'nowhere'}: no such run directory")

    def test_missing_metrics_json(self):
        path = run_dir("errors/empty")
        self.check([path], f"{path / 'metrics.json'}: missing (expected the metrics.json")

    def test_not_json(self):
        path = run_dir("errors/truncated", text='{"track_quality": {"targets": [')
        self.check([path], f"{path / 'metrics.json'}:1: malformed JSON (")

    def test_no_track_quality(self):
        path = run_dir("errors/no_quality", text='{"eps_k": 0.1}')
        self.check([path], f"{path / 'metrics.json'}: no track_quality object")

    def test_bad_target_fields(self):
        path = run_dir("errors/no_tlr", text='{"track_quality": {"targets": [{"errors_defined": true, "rse_position": 1}]}}')
        self.check([path], f"{path / 'metrics.json'}: track_quality.targets[0]: no 'tlr'")
        path = run_dir("errors/string_rse",
                       text='{"track_quality": {"targets": [{"errors_defined": true, "rse_position": "x", "tlr": 1}]}}')
        self.check([path], f"{path / 'metrics.json'}: track_quality.targets[0].rse_position: expected a finite number")

    def test_runs_disagree(self):
        a = run_dir("errors/three", [target(i, 1.0, 1.0, 1.0) for i in range(3)])
        b = run_dir("errors/four", [target(i, 1.0, 1.0, 1.0) for i in range(4)])
        self.check(["--a2", a, b], "--a2 runs disagree on the number of targets")
        self.check(["--a1", a, "--a2", b], "the A1 runs have 3 targets and the A2 runs 4")

    def test_usage(self):
        self.check([], "no run directories", status=2)
        a = run_dir("errors/usage", [target(0, 1.0, 1.0, 1.0)])
        self.check([a, "--a2", a], "not both", status=2)

    def test_help(self):
        result = tool("--help")
        self.assertEqual(result.returncode, 0)
        self.assertIn("Table II", result.stdout)
        self.assertIn("--a1 RUN_DIR", result.stdout)
        self.assertIn("observations.csv", result.stdout)
        self.assertNotIn("no road model", result.stdout)


if __name__ == "__main__":
    shutil.rmtree(WORK, ignore_errors=True)
    WORK.mkdir(parents=True)
    unittest.main(argv=[sys.argv[0], "-v"])
