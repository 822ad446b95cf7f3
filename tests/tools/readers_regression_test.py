#!/usr/bin/python3
"""Inputs that tests/tools/readers_property_test.py found to break the Python tools' readers with an
exception other than their own error, each checked to give that error (or, for the charts' titles,
nothing) now. Standard library and PyYAML only, so that it runs wherever the tools do.

Usage: readers_regression_test.py SOURCE_DIR WORK_DIR"""

import sys
import tempfile
import unittest
from pathlib import Path

SOURCE = Path(sys.argv[1]).resolve() if len(sys.argv) > 1 else Path(__file__).resolve().parents[2]
WORK = Path(sys.argv[2]).resolve() if len(sys.argv) > 2 else Path(tempfile.mkdtemp())
sys.path.insert(0, str(SOURCE / "python"))

from wsntrack import rundir  # noqa: E402
from wsntrack.sweep import spec  # noqa: E402


class Readers(unittest.TestCase):
    def setUp(self):
        self.dir = Path(tempfile.mkdtemp(dir=WORK))

    def write(self, name, text):
        path = self.dir / name
        path.write_text(text, encoding="utf-8")
        return path

    def test_metrics_json_faults_that_are_no_list_mark_no_fault(self):
        # Was TypeError: 'int' object is not iterable, out of plot_run.py's titles.
        self.write("metrics.json", '{"metrics": {"eps_k": 0.25}, "faults": 5}')
        self.assertEqual(rundir.read_metrics_summary(self.dir), {"eps_k": 0.25})

    def test_metrics_json_nested_deeper_than_python_recurses_is_malformed(self):
        # Was RecursionError from json.loads; 100 000 levels is 200 kB, far beyond Python's ~1000.
        path = self.write("metrics.json", "[" * 100_000 + "]" * 100_000)
        with self.assertRaisesRegex(rundir.InputError, "metrics.json: malformed JSON"):
            rundir.read_json(path)
        with self.assertRaisesRegex(rundir.InputError, "malformed JSON"):
            rundir.read_per_tick(self.dir, {"ticks": 3}, [], [])
        self.assertEqual(rundir.read_metrics_summary(self.dir), {})

    def test_metrics_json_integer_beyond_pythons_conversion_limit_is_malformed(self):
        # Was ValueError (Exceeds the limit (4300 digits) for integer string conversion), not InputError.
        path = self.write("metrics.json", '{"metrics": {"first_tick": ' + "7" * 5000 + "}}")
        with self.assertRaisesRegex(rundir.InputError, "malformed JSON"):
            rundir.read_json(path)

    def test_scenario_yaml_nested_deeper_than_pyyaml_recurses_is_malformed(self):
        # Was RecursionError from PyYAML's composer.
        self.write("scenario.yaml", "region: " + "[" * 3000 + "]" * 3000 + "\n")
        with self.assertRaisesRegex(rundir.InputError, r"scenario.yaml: malformed YAML \(nested deeper"):
            rundir.read_scenario(self.dir)

    def test_sweep_spec_nested_deeper_than_pyyaml_recurses_is_a_spec_error(self):
        path = self.write("spec.yaml", "grid: " + "[" * 3000 + "]" * 3000 + "\n")
        with self.assertRaisesRegex(spec.SpecError, "spec.yaml: malformed YAML: nested deeper"):
            spec.load_spec(path)

    def test_sweep_spec_scenario_name_too_long_for_the_file_system_is_a_spec_error(self):
        # Was OSError (File name too long) from Path.is_file, which only ignores a missing file.
        path = self.write("spec.yaml", f"scenario: {'x' * 300}.yaml\ngrid:\n  network.pte: [0, 0.2]\n")
        with self.assertRaisesRegex(spec.SpecError, r"spec.yaml:1: scenario: no file x+\.yaml \(File name too long\)"):
            spec.load_spec(path)


if __name__ == "__main__":
    WORK.mkdir(parents=True, exist_ok=True)
    unittest.main(argv=sys.argv[:1], verbosity=2)
