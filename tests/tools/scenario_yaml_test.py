#!/usr/bin/python3
"""scenario.yaml as 'wsntrack run' writes it, read back by the run-directory reader (wsntrack.rundir,
PyYAML) that tools/plot_run.py draws from and by the run loader: for the acoustic scenario of An et
al. 2014 (nested mappings, flow lists, an exponent float) and for oh_quadrants, the values read are the ones the C++ wrote, and the line recorded
for each is the line that holds it.

Usage: scenario_yaml_test.py SOURCE_DIR BIN_DIR WORK_DIR
"""

import subprocess
import sys
import unittest
from pathlib import Path

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
SOURCE, BIN, WORK = Path(sys.argv[1]), Path(sys.argv[2]), Path(sys.argv[3])
sys.path.insert(0, str(SOURCE / "tools"))
from wsntrack_run import load_run  # noqa: E402  (the entry point, which puts the package on sys.path)
from wsntrack import rundir  # noqa: E402

TICKS = 3  # the scenario file is written before the first tick; a short run keeps the test quick


def written_run(scenario):
    """The run directory of a short in-process run of scenarios/SCENARIO.yaml."""
    out = WORK / scenario
    command = [str(BIN / "wsntrack"), "run", str(SOURCE / "scenarios" / f"{scenario}.yaml"), "--in-process",
               "--quiet", "--no-plot", "--ticks", str(TICKS), "--out", str(out), "--overwrite"]
    done = subprocess.run(command, capture_output=True, text=True, timeout=300)
    if done.returncode != 0:
        raise AssertionError(f"{' '.join(command)}: exit {done.returncode}\n{done.stderr}")
    return out


class WrittenScenario:
    """Checks shared by the scenarios; a subclass names the scenario."""

    scenario = None

    @classmethod
    def setUpClass(cls):
        cls.run_dir = written_run(cls.scenario)
        cls.path = cls.run_dir / "scenario.yaml"
        cls.text = cls.path.read_text(encoding="utf-8")
        cls.lines = {}
        cls.data = rundir.parse_yaml(cls.text, cls.path, cls.lines)

    def expect(self, written, keys, value):
        """`written` is in the text at the line recorded for `keys`, and `keys` reads as `value`,
        of its type (3 is not 3.0, "3" is not 3)."""
        line = self.text.splitlines()[self.lines[keys] - 1]
        self.assertIn(written, line, f"{keys} recorded at line {self.lines[keys]}")
        node = self.data
        for key in keys:
            node = node[key]
        self.assertEqual((node, type(node)), (value, type(value)), keys)

    def test_header_comment_and_quoted_name(self):
        self.assertTrue(self.text.startswith("# wsntrack resolved scenario"))
        self.expect(f'name: "{self.scenario}"', ("name",), self.scenario)

    def test_run_section(self):
        self.expect(f"  ticks: {TICKS}", ("run", "ticks"), TICKS)
        self.expect("  seed: 1", ("run", "seed"), 1)

    def test_summary_and_loader_agree(self):
        summary = rundir.read_scenario(self.run_dir)
        self.assertEqual(summary["ticks"], TICKS)
        self.assertEqual(summary["name"], self.scenario)
        self.assertEqual(summary["region"], tuple(float(self.data["region"][k])
                                                  for k in ("x_min", "y_min", "x_max", "y_max")))
        self.assertEqual(load_run(self.run_dir).scenario, self.data)


class AcousticScenario(WrittenScenario, unittest.TestCase):
    scenario = "an2014_scenario1"

    def test_nested_mappings(self):
        self.expect('  kind: "acoustic_doppler"', ("sensor_model", "kind"), "acoustic_doppler")
        self.expect("    sound_speed: 343", ("sensor_model", "acoustic", "sound_speed"), 343)
        self.expect("    detection_step_s: 0.005", ("sensor_model", "acoustic", "detection_step_s"), 0.005)
        self.expect("    preset: none", ("sensor_model", "environmental_noise", "preset"), "none")
        self.expect('  engine: "rulebased"', ("tracker", "engine"), "rulebased")
        # yamlNumber writes 1e-4 as 1.0e-04: PyYAML (YAML 1.1) takes 1e-04 for a string.
        self.expect("    process_noise_min: 1.0e-04", ("tracker", "params", "process_noise_min"), 1e-4)

    def test_flow_lists(self):
        self.expect("- {appear_tick: 1, disappear_tick: 0, x: 150, y: 260, vx: 2, vy: 0.5, sensing_range: 30}",
                    ("targets", "scripted", 1), {"appear_tick": 1, "disappear_tick": 0, "x": 150, "y": 260,
                                                 "vx": 2, "vy": 0.5, "sensing_range": 30})
        self.expect("vy: 0.1", ("targets", "scripted", 2, "vy"), 0.1)
        self.expect("- {x: 625, y: 625}", ("supernodes", 0), {"x": 625, "y": 625})
        self.assertEqual(len(self.data["supernodes"]), 1)
        self.assertEqual(rundir.read_scenario(self.run_dir)["supernodes"], [(625.0, 625.0)])


class OhQuadrants(WrittenScenario, unittest.TestCase):
    scenario = "oh_quadrants"

    def test_values(self):
        self.expect("  noise_sigma: 0.62", ("sensor_model", "noise_sigma"), 0.62)
        self.expect("  pte: 0.3", ("network", "pte"), 0.3)
        # A derived engine parameter carries its derivation as a trailing comment.
        self.expect("    max_gap: 10  # derived: ", ("tracker", "params", "max_gap"), 10)
        self.expect('  association: "mcmcda"', ("aggregator", "association"), "mcmcda")
        self.expect("vx: -1.2, vy: 1}", ("targets", "scripted", 1, "vx"), -1.2)
        self.expect("- {x: 75, y: 75}", ("supernodes", 3), {"x": 75, "y": 75})
        self.assertEqual(rundir.read_scenario(self.run_dir)["supernodes"],
                         [(25.0, 25.0), (75.0, 25.0), (25.0, 75.0), (75.0, 75.0)])


if __name__ == "__main__":
    WORK.mkdir(parents=True, exist_ok=True)
    unittest.main(argv=[sys.argv[0], "-v"])
