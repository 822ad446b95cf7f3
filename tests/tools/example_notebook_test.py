#!/usr/bin/python3
"""examples/sweep_and_run.py, run as the README says (the build tree's package on PYTHONPATH), on a
sweep made for it with `wsntrack sweep`: it must write its figure, and the sweep reader it uses must
give back what the sweep wrote.

Usage: example_notebook_test.py SOURCE_DIR WSNTRACK BUILD_PYTHON_DIR WORK_DIR"""

import csv
import os
import shutil
import subprocess
import sys
import unittest
from pathlib import Path

SOURCE, WSNTRACK, BUILD_PYTHON, WORK = (Path(a).resolve() for a in sys.argv[1:5])
SPEC = """scenario: {scenario}
grid:
  network.pte: [0, 0.4]
engines: [mcmcda, gnn]
seeds: 1-2
set:
  run.ticks: 15
metrics: [eps_k, ospa, delivery_ratio]
in_process: true
"""


class Example(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        shutil.rmtree(WORK, ignore_errors=True)
        WORK.mkdir(parents=True)
        spec = WORK / "spec.yaml"
        spec.write_text(SPEC.format(scenario=SOURCE / "scenarios/oh_single_supernode.yaml"), encoding="utf-8")
        cls.sweep = WORK / "sweep"
        subprocess.run([str(WSNTRACK), "sweep", str(spec), "--out", str(cls.sweep), "-j", "2"], check=True,
                       capture_output=True, timeout=300)
        cls.env = dict(os.environ, PYTHONPATH=str(BUILD_PYTHON))
        cls.env.pop("WSNTRACK", None)  # the build tree's catalogue.json, as a user of the one-liner has

    def test_the_example_draws_its_figure(self):
        figure = WORK / "figure.png"
        result = subprocess.run([sys.executable, "-B", str(SOURCE / "examples/sweep_and_run.py"), str(self.sweep),
                                 str(figure)], env=self.env, capture_output=True, text=True, timeout=120, cwd=WORK)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("<wsntrack sweep", result.stdout)
        self.assertIn(f"wrote {figure}", result.stdout)
        self.assertGreater(figure.stat().st_size, 20_000)  # two panels with points and paths, not an empty frame

    def test_the_plots_again_from_python(self):
        code = ("import sys; from wsntrack import plot, rundir; "
                "pdfs = plot.sweep_plots(sys.argv[1], sys.argv[2], 'pdf', x='delivery_ratio'); "
                "print(sorted(p.name for p in pdfs)); "
                "run = rundir.load_run(sys.argv[1] + '/runs/gnn_pte-0.4_seed-1'); print(len(run.truth) > 0); "
                "print([p.name for p in plot.run_plots(run.path, sys.argv[3], 'svg')])")
        result = subprocess.run([sys.executable, "-B", "-c", code, str(self.sweep), str(WORK / "pdf"),
                                 str(WORK / "svg")], env=self.env, capture_output=True, text=True, timeout=120)
        self.assertEqual(result.returncode, 0, result.stderr)
        lines = result.stdout.strip().splitlines()
        self.assertEqual(lines[0], "['eps_k.pdf', 'ospa.pdf']")  # every metric but the x axis's own
        self.assertEqual(lines[1], "True")
        self.assertIn("tracks.svg", lines[2])
        self.assertTrue((WORK / "pdf" / "eps_k.pdf").read_bytes().startswith(b"%PDF"))

    def test_the_sweep_reader_gives_back_the_files(self):
        code = ("import sys; from wsntrack.sweep.results import load_sweep; s = load_sweep(sys.argv[1]); "
                "print(len(s.results), len(s.summary), sorted(set(s.results.engine)), "
                "float(s.summary.delivery_ratio_mean[0]), list(s.grid))")
        result = subprocess.run([sys.executable, "-B", "-c", code, str(self.sweep)], env=self.env,
                                capture_output=True, text=True, timeout=60)
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(self.sweep / "summary.csv", newline="", encoding="utf-8") as f:
            first = next(csv.DictReader(f))
        expected = f"8 4 ['gnn', 'mcmcda'] {float(first['delivery_ratio_mean'])} ['network.pte']"
        self.assertEqual(result.stdout.strip(), expected)


if __name__ == "__main__":
    cases = unittest.defaultTestLoader.loadTestsFromTestCase(Example)
    result = unittest.TextTestRunner(verbosity=2).run(cases)
    sys.exit(0 if result.wasSuccessful() and result.testsRun == 3 else 1)
