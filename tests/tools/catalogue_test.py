#!/usr/bin/python3
"""The Python side agrees with wsntrack's catalogue (`wsntrack components --json`) and with the files
wsntrack writes: a real run's files have the catalogue's columns and the package's readers read them;
every metric a sweep offers reads a number (or an undefined null) from that run; the plots have a
style for every sensor type and target class the catalogue lists. Then the negative control: the same
checks against a catalogue with one fact changed fail, naming it.

Usage: catalogue_test.py SOURCE_DIR WSNTRACK WORK_DIR
       catalogue_test.py --check RUN_DIR   (the checks alone, against the catalogue that
                                            WSNTRACK_CATALOGUE or WSNTRACK names; exit 1 on a disagreement)"""

import json
import os
import subprocess
import sys
import unittest
from pathlib import Path

HERE = Path(__file__).resolve()


def check(run_dir):
    """Every disagreement between the package, its catalogue and the run in `run_dir`, as lines."""
    sys.path.insert(0, str(HERE.parents[2] / "python"))
    from wsntrack import catalogue, rundir
    from wsntrack.plots import field
    from wsntrack.sweep.metrics import metric_sources, metric_value

    problems = []
    document = catalogue.load()
    for name, columns in document["run_files"].items():
        path = run_dir / name
        if path.is_file() and rundir.read_header(path) != columns:
            problems.append(f"{name}: the run's header {rundir.read_header(path)} is not the catalogue's {columns}")
    readers = [("truth.csv", rundir.read_truth), ("observations.csv", rundir.read_observations),
               ("tracks.csv", rundir.read_tracks), ("tracks_settled.csv", rundir.read_tracks),
               ("tracks_supernode.csv", lambda p: rundir.read_tracks(p, supernode=True)),
               ("metrics_per_tick.csv", rundir.read_metrics_per_tick)]
    for name, reader in readers:
        try:
            reader(run_dir / name)
        except rundir.InputError as error:
            problems.append(f"{name}: the package's reader refuses the run's file: {error}")
    data = rundir.read_json(run_dir / "metrics.json")
    for metric in metric_sources():
        try:
            value = metric_value(metric, data, run_dir)
        except (KeyError, TypeError) as error:
            problems.append(f"metric {metric}: not where the catalogue says ({error!r})")
            continue
        if value is not None and (isinstance(value, bool) or not isinstance(value, (int, float))):
            problems.append(f"metric {metric}: expected a number, got {value!r}")
    for types in (model["sensor_types"] for model in document["sensor_models"]):
        problems += [f"sensor type {t}: no style in wsntrack.plots.field" for t in types
                     if t not in field.SENSOR_TYPE_STYLES]
    problems += [f"target class {c}: no colour in wsntrack.plots.field" for c in rundir.TARGET_CLASSES
                 if c not in field.CLASS_COLOURS]
    problems += [f"wsntrack.plots.field colours class {c}, which the catalogue does not list" for c in field.CLASS_COLOURS
                 if c not in rundir.TARGET_CLASSES]
    return problems


class Catalogue(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.run_dir = WORK / "run"
        subprocess.run([str(WSNTRACK), "run", str(SOURCE / "scenarios/oh_single_supernode.yaml"), "--ticks", "8",
                        "--in-process", "--out", str(cls.run_dir), "--overwrite"],
                       check=True, capture_output=True, timeout=120)
        cls.catalogue = json.loads(subprocess.run([str(WSNTRACK), "components", "--json"], check=True,
                                                  capture_output=True, text=True).stdout)

    def checked(self, catalogue=None):
        """The --check of this script in a fresh interpreter, with `catalogue` (else wsntrack's)."""
        env = dict(os.environ, WSNTRACK=str(WSNTRACK))
        env.pop("WSNTRACK_CATALOGUE", None)
        if catalogue is not None:
            path = WORK / "changed_catalogue.json"
            path.write_text(json.dumps(catalogue), encoding="utf-8")
            env["WSNTRACK_CATALOGUE"] = str(path)
        return subprocess.run([sys.executable, "-B", str(HERE), "--check", str(self.run_dir)], env=env,
                              capture_output=True, text=True, timeout=120)

    def test_the_package_agrees_with_the_catalogue_and_the_run(self):
        result = self.checked()
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertIn("metrics checked", result.stdout)

    def changed(self, change):
        catalogue = json.loads(json.dumps(self.catalogue))
        change(catalogue)
        return self.checked(catalogue)

    def test_negative_control_a_metric_moved(self):
        def move(c):
            quantity = next(q for m in c["metrics"] for q in m["quantities"] if q["name"] == "mota")
            quantity["path"] = ["clear_mot", "mota_moved"]
        result = self.changed(move)
        self.assertEqual(result.returncode, 1, result.stdout + result.stderr)
        self.assertIn("metric mota: not where the catalogue says", result.stdout)
        self.assertIn("clear_mot.mota_moved", result.stdout)

    def test_negative_control_a_column_renamed(self):
        def rename(c):
            c["run_files"]["tracks.csv"] = [n.replace("p_xvx", "p_x_vx") for n in c["run_files"]["tracks.csv"]]
        result = self.changed(rename)
        self.assertEqual(result.returncode, 1, result.stdout + result.stderr)
        self.assertIn("tracks.csv: the run's header", result.stdout)

    def test_a_bad_catalogue_is_named_with_what_is_wrong(self):
        code = ("import sys; sys.path.insert(0, sys.argv[1]); from wsntrack import catalogue\n"
                "try:\n    catalogue.load()\nexcept catalogue.CatalogueError as error:\n    print(error)")
        for text, expected in (('{"catalogue_version": 1,\n  "metrics": [', ":2: malformed catalogue"),
                               ('{"catalogue_version": 99}', "expected a wsntrack catalogue of version 1, got version 99")):
            path = WORK / "bad_catalogue.json"
            path.write_text(text, encoding="utf-8")
            result = subprocess.run([sys.executable, "-B", "-c", code, str(SOURCE / "python")], capture_output=True,
                                    text=True, timeout=60, env=dict(os.environ, WSNTRACK_CATALOGUE=str(path)))
            self.assertIn(f"{path}{expected}" if expected.startswith(":") else expected, result.stdout, result.stderr)
        # An executable that is not wsntrack: its failure, named.
        result = subprocess.run([sys.executable, "-B", "-c", code.replace("catalogue.load()", "catalogue.load('/bin/false')"),
                                 str(SOURCE / "python")], capture_output=True, text=True, timeout=60)
        self.assertIn("/bin/false components --json failed (exit 1)", result.stdout, result.stderr)

    def test_negative_control_a_class_added(self):
        result = self.changed(lambda c: c["target_classes"].append("submarine"))
        self.assertEqual(result.returncode, 1, result.stdout + result.stderr)
        self.assertIn("target class submarine: no colour", result.stdout)


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--check":
        found = check(Path(sys.argv[2]))
        for line in found:
            print(line)
        from wsntrack.sweep.metrics import metric_sources
        print(f"{len(metric_sources())} metrics checked, {len(found)} disagreements")
        sys.exit(1 if found else 0)
    SOURCE, WSNTRACK, WORK = (Path(a).resolve() for a in sys.argv[1:4])
    WORK.mkdir(parents=True, exist_ok=True)
    cases = unittest.defaultTestLoader.loadTestsFromTestCase(Catalogue)
    result = unittest.TextTestRunner(verbosity=2).run(cases)
    sys.exit(0 if result.wasSuccessful() and result.testsRun == 5 else 1)
