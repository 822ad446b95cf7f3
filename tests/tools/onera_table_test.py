#!/usr/bin/python3
"""Tests of tools/onera_table.py (Table II of Pannetier et al. 2014 beside our runs) on hand-written
run directories (only metrics.json's track_quality block): per-target means over runs against a hand
computation, the paper's statistics, the A1 - A2 deltas and comparisons, undefined RSEs, runs without
tlr_length, and the errors for missing or malformed metrics.json.

Usage: onera_table_test.py SOURCE_DIR WORK_DIR
"""

import json
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


def run_dir(name, targets=None, text=None):
    """A run directory holding metrics.json with these targets (or this raw text; neither: no file)."""
    path = WORK / name
    path.mkdir(parents=True)
    if text is None and targets is not None:
        text = json.dumps({"eps_k": 0.0, "track_quality": {"gate": 50.0, "targets": targets}})
    if text is not None:
        (path / "metrics.json").write_text(text, encoding="utf-8")
    return path


def tool(*args):
    return subprocess.run(["/usr/bin/python3", "-B", str(TOOL), *map(str, args)], capture_output=True,
                          text=True, timeout=60)


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
                          "paper Δ TLR", "A2 RSE", "A2 TLR", "A2 TLR_len"])
        self.assertEqual(self.result.stderr, "")

    def test_per_target_means_over_runs(self):
        out = self.result.stdout
        self.assertEqual(cells(out, "1"), ["1", "10.48", "0.99", "19.43", "0.80", "-8.95", "+0.19", "5.00", "0.60", "0.40"])
        self.assertEqual(cells(out, "2")[7:], ["8.00", "0.20", "0.20"])
        self.assertEqual(cells(out, "3")[7:], ["-", "0.00", "0.00"])
        self.assertEqual(cells(out, "20")[7:], ["10.00", "1.00", "1.00"])
        self.assertEqual(cells(out, "14")[5:7], ["-2.28", "+0.00"])  # the paper's equal TLR: no "-0.00"

    def test_summary_rows(self):
        out = self.result.stdout
        # Our RSE over the 19 targets with one: (5 + 8 + 17 * 10) / 19 = 183 / 19 = 9.6316; median 10.
        # TLR over all 20: (0.6 + 0.2 + 0 + 17) / 20 = 0.89; TLR_len (0.4 + 0.2 + 0 + 17) / 20 = 0.88.
        mean = cells(out, "**mean**")
        self.assertEqual(mean[1:5], ["8.773", "0.737", "9.976", "0.707"])
        self.assertEqual(mean[7:], ["9.632", "0.890", "0.880"])
        self.assertEqual(cells(out, "**median**")[1:4], ["7.065", "0.795", "9.175"])
        self.assertEqual(cells(out, "**median**")[7:], ["10.000", "1.000", "1.000"])

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
        self.assertEqual(result.stdout, self.result.stdout)


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
                                           "Δ RSE", "Δ TLR", "Δ TLR_len"])
        self.assertEqual(cells(out, "1")[7:], ["5.00", "0.90", "0.50", "7.00", "0.80", "0.70", "-2.00", "+0.10", "-0.20"])
        self.assertEqual(cells(out, "2")[13:], ["+2.00", "-0.30", "+0.00"])
        self.assertEqual(cells(out, "5")[13:], ["+0.00", "+0.00", "+0.00"])
        self.assertIn("- ours: A1's RSE lower on 1/20 targets; A1's TLR higher on 1, equal on 18, lower on 1 "
                      "(targets 2)", out)
        self.assertIn("- ours, path length: A1's RSE lower on 1/20 targets; A1's TLR_len higher on 0, equal on 19, "
                      "lower on 1 (targets 1)", out)


class Oddities(unittest.TestCase):
    def test_runs_without_tlr_length(self):
        result = tool(run_dir("old/s1", [target(i, 3.0, 0.5) for i in range(20)]))
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(cells(result.stdout, "1")[7:], ["3.00", "0.50", "-"])
        self.assertIn("no tlr_length", result.stderr)

    def test_other_target_count_is_noted(self):
        result = tool(run_dir("short/s1", [target(i, 3.0, 0.5, 0.5) for i in range(3)]))
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("the A2 runs have 3 targets, Table II has 20", result.stderr)
        self.assertEqual(cells(result.stdout, "4")[7:], ["-", "-", "-"])


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
        self.check([path], f"{path / 'metrics.json'}: not JSON (line 1, column")

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


if __name__ == "__main__":
    shutil.rmtree(WORK, ignore_errors=True)
    WORK.mkdir(parents=True)
    unittest.main(argv=[sys.argv[0], "-v"])
