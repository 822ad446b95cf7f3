#!/usr/bin/python3
"""Tests of tools/wsntrack_run.py (the run-directory loader) on its numpy path: exact values on the
hand-made run of tiny_run.py (new and old tracks.csv formats), errors, and with --real RUN_DIR the
invariants a real run must satisfy.

Usage: loader_test.py SOURCE_DIR WORK_DIR [--real RUN_DIR]
"""

import contextlib
import io
import shutil
import sys
import types
import unittest
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
SOURCE, WORK = Path(sys.argv[1]), Path(sys.argv[2])
REAL = Path(sys.argv[4]) if len(sys.argv) == 5 and sys.argv[3] == "--real" else None
sys.path.insert(0, str(SOURCE / "tools"))
sys.path.insert(0, str(SOURCE / "tests" / "tools"))
import tiny_run  # noqa: E402
import wsntrack_run  # noqa: E402  (the entry point, which puts the package on sys.path)
import wsntrack.catalogue  # noqa: E402
import wsntrack.loader  # noqa: E402
import wsntrack.rundir  # noqa: E402
from wsntrack_run import RunError, ToolMissing, load_run, track_label  # noqa: E402


def fresh(name, old=False):
    """A new copy of the tiny run in WORK/name."""
    path = WORK / name
    shutil.rmtree(path, ignore_errors=True)
    tiny_run.write(path, old=old)
    return path


class TinyRun(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.loaded = load_run(fresh("tiny"))

    def test_scenario_and_geometry(self):
        run = self.loaded
        self.assertEqual(run.ticks, 10)
        self.assertEqual(run.scenario["name"], "tiny")
        self.assertEqual(run.scenario["targets"]["scripted"][1]["x"], 16.5)
        np.testing.assert_array_equal(run.supernodes, [[5, 5], [15, 5]])
        self.assertEqual(run.sensors.shape, (200, 2))
        np.testing.assert_array_equal(run.sensors[0], [0.5, 0.5])
        np.testing.assert_array_equal(run.sensors[21], [1.5, 1.5])  # row by row, as sensor ids go

    def test_truth(self):
        truth = self.loaded.truth
        self.assertEqual(truth.dtype, wsntrack_run.TRUTH_DTYPE)
        self.assertEqual(len(truth), 17)
        at4 = self.loaded.truth_at(4)
        np.testing.assert_array_equal(at4.target, [0, 1])
        self.assertEqual((at4.x[1], at4.y[1], at4.vx[1], at4.vy[1]), (16.5, 8.0, -1.0, 0.0))
        paths = self.loaded.by_id(truth, "target")
        self.assertEqual(sorted(paths), [0, 1])
        np.testing.assert_array_equal(paths[1].tick, np.arange(4, 11))
        self.assertEqual(self.loaded.states(at4).shape, (2, 4))

    def test_tracks_labels_and_covariance(self):
        run = self.loaded
        self.assertTrue(run.has_labels and run.has_covariance)
        tracks = run.tracks
        self.assertEqual(tracks.dtype, wsntrack_run.TRACK_DTYPE)
        self.assertEqual(len(tracks), 14)
        self.assertEqual(set(tracks.label), {"0:1", "1:1", "g5"})
        self.assertEqual(tracks.covariance.shape, (14, 4, 4))
        np.testing.assert_array_equal(tracks.covariance, np.swapaxes(tracks.covariance, 1, 2))
        first = tracks[0]
        self.assertEqual((first.tick, first.track, first.label), (2, tiny_run.ID_0_1, "0:1"))
        # p_xx, p_xy, p_xvx, p_xvy, p_yy, p_yvx, p_yvy, p_vxvx, p_vxvy, p_vyvy = covariance(2, 0:1)
        np.testing.assert_allclose(first.covariance, [[0.2, 0.06, 0.1, 0.0], [0.06, 0.4, 0.0, 0.1],
                                                      [0.1, 0.0, 0.2, 0.0], [0.0, 0.1, 0.0, 0.2]])
        minted = tracks[tracks.label == "g5"]
        self.assertEqual(len(minted), 1)
        self.assertFalse(minted.covariance.any())
        self.assertEqual([r.label for r in run.tracks_at(6)], ["0:1", "1:1"])
        self.assertEqual(sorted(run.by_id(tracks, "label")), ["0:1", "1:1", "g5"])

    def test_supernode_tracks(self):
        tracks = self.loaded.supernode_tracks
        self.assertEqual(tracks.dtype, wsntrack_run.SUPERNODE_TRACK_DTYPE)
        self.assertEqual(len(tracks), 14)
        self.assertEqual([r.label for r in self.loaded.tracks_at(6, supernode=1)], ["1:1"])
        np.testing.assert_array_equal(tracks.covariance, self.loaded.tracks.covariance)

    def test_observations(self):
        obs = self.loaded.observations
        self.assertEqual(obs.dtype, wsntrack_run.OBSERVATION_DTYPE)
        self.assertEqual(len(obs), 20)
        delivered = obs.fate == "delivered"
        self.assertTrue((obs.tick_delivered[~delivered] == -1).all() and (obs.delay[~delivered] == -1).all())
        np.testing.assert_array_equal(obs.delay[delivered], obs.tick_delivered[delivered] - obs.tick_generated[delivered])
        self.assertEqual(sorted(obs.fate[~delivered]), ["after_end", "lost", "unreachable"])
        self.assertEqual(int((obs.target == -1).sum()), 3)
        self.assertEqual(int(obs.hops[obs.fate == "unreachable"][0]), -1)
        at4 = self.loaded.delivered_at(4)
        self.assertEqual(sorted(zip(at4.tick_generated.tolist(), at4.target.tolist())), [(3, 0), (4, 0), (4, 1)])
        late = obs[obs.tick_delivered > obs.tick_generated]
        self.assertEqual(sorted(late.tick_generated.tolist()), [3, 6, 7])

    def test_metrics(self):
        per_tick = self.loaded.metrics_per_tick
        self.assertEqual(per_tick.dtype.names, ("tick", "truth_targets", "tracks", "ospa", "gospa", "gospa_localisation",
                                                "gospa_missed", "gospa_false"))
        np.testing.assert_allclose(per_tick.ospa, 0.25 * np.arange(1, 11))
        np.testing.assert_array_equal(per_tick.truth_targets, [1, 1, 1, 2, 2, 2, 2, 2, 2, 2])
        self.assertEqual(self.loaded.metrics["metrics"]["eps_k"], 0.25)
        self.assertEqual(self.loaded.network["sent"], 21)
        self.assertEqual(self.loaded.info["domain"], 7)

    def test_repr_and_labels(self):
        self.assertIn("tiny, 10 ticks, 2 targets, 3 tracks", repr(self.loaded))
        self.assertEqual(track_label((1 << 48) | 1), "0:1")
        self.assertEqual(track_label((4 << 48) | 12), "3:12")
        self.assertEqual(track_label(7), "g7")
        # A GNN / rule-based birth id: supernode 2, tick 3, sensor 5.
        self.assertEqual(track_label((3 << 48) | (3 << 24) | 5), "2:t3s5")
        self.assertEqual(track_label((3 << 48) | (2 << 44) | (3 << 24) | 5), "2:t3s5.2")

    def test_doctests(self):
        import doctest
        result = doctest.testmod(wsntrack.loader)
        self.assertEqual(result.failed, 0)
        self.assertGreater(result.attempted, 0)


class OldFormat(unittest.TestCase):
    """tracks.csv and tracks_supernode.csv as wsntrack wrote them before label and covariance."""

    def test_old_tracks_read_like_new_ones(self):
        old, new = load_run(fresh("old", old=True)), load_run(fresh("new"))
        self.assertFalse(old.has_labels or old.has_covariance)
        np.testing.assert_array_equal(old.tracks.label, new.tracks.label)  # made from the ids
        np.testing.assert_array_equal(old.supernode_tracks.label, new.supernode_tracks.label)
        for name in ("tick", "track", "x", "y", "vx", "vy"):
            np.testing.assert_array_equal(old.tracks[name], new.tracks[name])
        self.assertFalse(old.tracks.covariance.any())


class Errors(unittest.TestCase):
    def expect(self, directory, pattern):
        with self.assertRaises(RunError) as caught:
            load_run(directory)
        self.assertRegex(str(caught.exception), pattern)

    def test_missing_files(self):
        d = fresh("e-missing")
        (d / "truth.csv").unlink()
        self.expect(d, r"e-missing/truth\.csv: missing")
        self.expect(WORK / "nonexistent", r"nonexistent: not a directory")
        d = fresh("e-noscenario")
        (d / "scenario.yaml").unlink()
        self.expect(d, r"e-noscenario/scenario\.yaml: missing")

    def test_optional_files_absent(self):
        d = fresh("e-optional")
        for name in ("observations.csv", "tracks_supernode.csv", "metrics_per_tick.csv", "metrics.json",
                     "network.json"):
            (d / name).unlink()
        run = load_run(d)
        self.assertIsNone(run.observations)
        self.assertIsNone(run.supernode_tracks)
        self.assertIsNone(run.metrics_per_tick)
        self.assertIsNone(run.metrics)

    def test_incomplete_runs_refused(self):
        # Only run.json's "complete" loads; every other state says why, naming the directory.
        d = fresh("i-failed")
        tiny_run.mark(d, "failed", "aggregator 0 killed by SIGKILL; log i-failed/logs/aggregator-0.log")
        self.expect(d, r"i-failed: incomplete run \(status failed: aggregator 0 killed by SIGKILL; log "
                       r"i-failed/logs/aggregator-0\.log\)$")
        tiny_run.mark(d, "running")
        self.expect(d, r"i-failed: incomplete run \(status running: its launcher has not finished")
        tiny_run.mark(d, None)
        self.expect(d, r"i-failed: incomplete run \(status missing: run\.json has no status")
        (d / "run.json").unlink()
        self.expect(d, r"i-failed: incomplete run \(status missing: no run\.json")
        # Asked for, an incomplete run loads and says why it is incomplete; a complete one says None.
        tiny_run.mark(d, "failed", "timed out after 3 s")
        run = load_run(d, allow_incomplete=True)
        self.assertEqual(run.incomplete, "incomplete run (status failed: timed out after 3 s)")
        self.assertEqual(len(run.truth), 17)
        self.assertIsNone(load_run(fresh("i-complete")).incomplete)

    def edit(self, name, file, line, text):
        d = fresh(name)
        lines = (d / file).read_text().splitlines()
        lines[line - 1] = text
        (d / file).write_text("\n".join(lines) + "\n")
        return d

    def test_malformed(self):
        self.expect(self.edit("e1", "tracks.csv", 3, "3,281474976710657,0:1,abc,1,1,1,0,0,0,0,0,0,0,0,0,0"),
                    r"e1/tracks\.csv:3: column 'x' must be a number, got 'abc'")
        self.expect(self.edit("e2", "observations.csv", 4, "2,2,45,0,1,0,5.5,2.5,-1,vanished"),
                    r"e2/observations\.csv:4: column 'fate' must be one of delivered, lost, unreachable, after_end")
        self.expect(self.edit("e3", "observations.csv", 2, "1,,21,0,1,,1.05,1.45,0,delivered"),
                    r"e3/observations\.csv:2: column 'tick_delivered' must be set exactly when the fate is delivered")
        self.expect(self.edit("e4", "tracks.csv", 1, "tick,track,label,x,y,vx,vy,p_xx"),
                    r"e4/tracks\.csv:1: expected every covariance column .* got no 'p_xy'")
        self.expect(self.edit("e5", "tracks.csv", 1, "tick,id,x,y"),
                    r"e5/tracks\.csv:1: expected the header 'tick,track,label,.*' \(or the older 'tick,track,x,y,vx,vy'\)"
                    r", got 'tick,id,x,y' \(no column 'track'\)")
        self.expect(self.edit("e6", "metrics.json", 2, '  "scenario": '), r"e6/metrics\.json:3: malformed JSON")
        line = tiny_run.SCENARIO.splitlines().index("  ticks: 10") + 1
        self.expect(self.edit("e7", "scenario.yaml", line, "  ticks: many"),
                    rf"e7/scenario\.yaml:{line}: 'run\.ticks' must be a number, got 'many'")
        self.expect(self.edit("e8", "metrics_per_tick.csv", 1, "tick,truth_targets,ospa"),
                    r"e8/metrics_per_tick\.csv:1: expected a header .* \(no column 'tracks'\)")
        self.expect(self.edit("e9", "truth.csv", 3, "2,0,1.0"),
                    r"e9/truth\.csv:3: expected 6 fields \(tick,target,x,y,vx,vy\), got 3")

    def test_malformed_yaml(self):
        # PyYAML meets the unterminated flow mapping at the next line's ':' and names where it began.
        line = tiny_run.SCENARIO.splitlines().index("  x_max: 20") + 1
        self.expect(self.edit("y1", "scenario.yaml", line, "  x_max: {oops"),
                    rf"y1/scenario\.yaml:{line + 1}: expected ',' or '\}}', but got ':' "
                    rf"\(while parsing a flow mapping at line {line}\)")
        line = tiny_run.SCENARIO.splitlines().index("  ticks: 10") + 1
        self.expect(self.edit("y2", "scenario.yaml", line, "\tticks: 10"),
                    rf"y2/scenario\.yaml:{line}: found character '\\t' that cannot start any token")
        # Indented by one: 'ticks: 10 seed' reads as one plain scalar, up to the ':' of the next line.
        self.expect(self.edit("y3", "scenario.yaml", line, " ticks: 10"),
                    rf"y3/scenario\.yaml:{line + 1}: mapping values are not allowed here")
        d = fresh("y4")
        (d / "scenario.yaml").write_text("# nothing but a comment\n")
        self.expect(d, r"y4/scenario\.yaml:1: empty file, expected a scenario mapping")
        (d / "scenario.yaml").write_text("# a list\n- {x: 1}\n")
        self.expect(d, r"y4/scenario\.yaml:2: expected a mapping at the top level")
        (d / "scenario.yaml").write_text(tiny_run.SCENARIO + "---\nname: again\n")
        self.expect(d, r"y4/scenario\.yaml:\d+: expected a single document in the stream, but found another document")

    def test_yaml_lines_of_values(self):
        # A value's FILE:LINE is the line that holds it, inside a flow mapping too.
        lines = tiny_run.SCENARIO.splitlines()
        line = lines.index("  - {x: 15, y: 5}") + 1
        self.expect(self.edit("y5", "scenario.yaml", line, "  - {x: 15, y: north}"),
                    rf"y5/scenario\.yaml:{line}: supernodes\[1\]\.y must be a number, got 'north'")
        line = lines.index("  x_max: 20") + 1
        self.expect(self.edit("y6", "scenario.yaml", line, "  x_max: -5"),
                    rf"y6/scenario\.yaml:{lines.index('region:') + 1}: region must have x_min < x_max")
        # A missing key is reported at the line of the nearest enclosing key.
        self.expect(self.edit("y7", "scenario.yaml", line, "  z_max: 20"),
                    rf"y7/scenario\.yaml:{lines.index('region:') + 1}: missing 'region\.x_max'")
        where = {}
        data = wsntrack_run.parse_yaml(tiny_run.SCENARIO, "s.yaml", where)
        self.assertEqual(data["targets"]["scripted"][1], {"appear_tick": 4, "disappear_tick": 0, "x": 16.5, "y": 8,
                                                          "vx": -1, "vy": 0})
        self.assertEqual(where[("targets", "scripted", 1, "vx")], lines.index("    - {appear_tick: 4, disappear_tick: 0, "
                                                                              "x: 16.5, y: 8, vx: -1, vy: 0}") + 1)
        self.assertEqual(where[("run", "ticks")], lines.index("  ticks: 10") + 1)
        self.assertIs(wsntrack_run.parse_yaml_subset, wsntrack_run.parse_yaml)  # the old name still works

    def test_without_pyyaml(self):
        # A python without PyYAML, simulated by a package of that name that cannot be imported: one
        # line saying what to install and exit status 3, like plot_run.py without matplotlib.
        import subprocess
        fake = WORK / "no-pyyaml" / "yaml"
        fake.mkdir(parents=True, exist_ok=True)
        (fake / "__init__.py").write_text('raise ImportError("simulated: no PyYAML")\n')
        script = SOURCE / "tools" / "wsntrack_run.py"
        done = subprocess.run([sys.executable, "-B", script, str(fresh("no-pyyaml-run"))], capture_output=True, text=True,
                              env={"PATH": "/usr/bin:/bin", "PYTHONPATH": str(fake.parent)})
        self.assertEqual(done.returncode, 3, done.stderr)
        self.assertRegex(done.stderr, r"^wsntrack_run\.py: PyYAML is not available to .*simulated: no PyYAML.*"
                                      r"apt-get install python3-yaml\n$")
        self.assertTrue(issubclass(ToolMissing, ImportError))

    def test_command_line(self):
        import subprocess
        script = SOURCE / "tools" / "wsntrack_run.py"
        ok = subprocess.run([sys.executable, "-B", script, str(fresh("cli"))], capture_output=True, text=True)
        self.assertEqual(ok.returncode, 0, ok.stderr)
        self.assertIn("labels yes, covariance yes", ok.stdout)
        bad = subprocess.run([sys.executable, "-B", script, str(WORK / "nonexistent")], capture_output=True, text=True)
        self.assertEqual(bad.returncode, 2)
        self.assertIn("not a directory", bad.stderr)


class StoneSoupStandIn(unittest.TestCase):
    """The Stone Soup conversions against a stand-in that records the constructor calls Stone Soup
    documents (State(state_vector, timestamp=...), GaussianState(state_vector, covar, ...),
    Track(states, id=..., init_metadata=...), ...): this checks what is passed, not Stone Soup."""

    def setUp(self):
        class Recorded:
            def __init__(self, *args, **kwargs):
                self.args, self.kwargs = args, kwargs

        names = {"stonesoup.types.groundtruth": ["GroundTruthPath", "GroundTruthState"],
                 "stonesoup.types.state": ["GaussianState"], "stonesoup.types.track": ["Track"],
                 "stonesoup.types.detection": ["Clutter", "TrueDetection"]}
        self.saved = {name: sys.modules.get(name) for name in list(names) + ["stonesoup", "stonesoup.types"]}
        sys.modules["stonesoup"] = types.ModuleType("stonesoup")
        sys.modules["stonesoup.types"] = types.ModuleType("stonesoup.types")
        for module, classes in names.items():
            sys.modules[module] = types.ModuleType(module)
            for cls in classes:
                setattr(sys.modules[module], cls, type(cls, (Recorded,), {}))

    def tearDown(self):
        for name, module in self.saved.items():
            if module is None:
                sys.modules.pop(name, None)
            else:
                sys.modules[name] = module

    def test_conversions(self):
        run = load_run(fresh("stonesoup"))
        truths = run.stonesoup_truths()
        self.assertEqual(sorted(truths), [0, 1])
        states = truths[1].args[0]
        self.assertEqual(len(states), 7)
        np.testing.assert_array_equal(states[0].args[0].ravel(), [16.5, -1.0, 8.0, 0.0])  # x, vx, y, vy
        self.assertEqual(states[0].kwargs["timestamp"].isoformat(), "1970-01-01T00:00:04")
        tracks = run.stonesoup_tracks(tick_seconds=2.0)
        self.assertEqual(sorted(tracks), ["0:1", "1:1", "g5"])
        state = tracks["0:1"].args[0][0]
        vector, covariance = state.args
        np.testing.assert_allclose(vector.ravel(), [2.1, 0.5, 2.2, 0.25])  # velocities per second
        np.testing.assert_allclose(covariance, [[0.2, 0.05, 0.06, 0.0], [0.05, 0.05, 0.0, 0.0],
                                                [0.06, 0.0, 0.4, 0.05], [0.0, 0.0, 0.05, 0.05]])
        self.assertEqual(tracks["0:1"].kwargs["id"], "0:1")
        scans = run.stonesoup_detections(truths=truths)
        self.assertEqual(len(scans), 10)
        at4 = scans[3][1]
        self.assertEqual(len(at4), 3)
        late = [d for d in at4 if d.kwargs["metadata"]["tick_generated"] == 3][0]
        self.assertEqual(late.kwargs["timestamp"].isoformat(), "1970-01-01T00:00:03")
        self.assertIs(late.kwargs["groundtruth_path"], truths[0])
        clutter = [d for s in scans for d in s[1] if type(d).__name__ == "Clutter"]
        self.assertEqual(len(clutter), 2)


@unittest.skipUnless(REAL, "no --real RUN_DIR")
class RealRun(unittest.TestCase):
    """Invariants of a run written by 'wsntrack run'."""

    @classmethod
    def setUpClass(cls):
        cls.loaded = load_run(REAL)

    def test_counts_agree_with_metrics_per_tick(self):
        run = self.loaded
        per_tick = run.metrics_per_tick
        np.testing.assert_array_equal(per_tick.tick, np.arange(1, run.ticks + 1))
        truth_counts = np.bincount(run.truth.tick, minlength=run.ticks + 1)[1:]
        track_counts = np.bincount(run.tracks.tick, minlength=run.ticks + 1)[1:]
        np.testing.assert_array_equal(truth_counts, per_tick.truth_targets)
        np.testing.assert_array_equal(track_counts, per_tick.tracks)
        self.assertAlmostEqual(float(per_tick.ospa.mean()), run.metrics["metrics"]["ospa_mean"], places=5)

    def test_observations(self):
        obs = self.loaded.observations
        self.assertGreater(len(obs), 0)
        delivered = obs[obs.fate == "delivered"]
        self.assertTrue((delivered.tick_delivered >= delivered.tick_generated).all())
        self.assertTrue((delivered.tick_delivered <= self.loaded.ticks).all())
        np.testing.assert_array_equal(delivered.delay, delivered.tick_delivered - delivered.tick_generated)
        self.assertTrue((obs.tick_delivered[obs.fate != "delivered"] == -1).all())
        self.assertEqual(self.loaded.network["sent"], len(obs))
        for fate in ("lost", "unreachable", "after_end"):
            self.assertEqual(self.loaded.network[fate], int((obs.fate == fate).sum()), fate)

    def test_tracks(self):
        run = self.loaded
        for tracks in (run.tracks, run.supernode_tracks):
            owner = tracks.track >> np.uint64(48)
            self.assertTrue(((owner == 0) | (owner <= len(run.supernodes))).all())
        self.assertTrue(run.has_labels and run.has_covariance, "tracks.csv lacks the label or covariance columns")
        for tracks in (run.tracks, run.supernode_tracks):
            self.assertEqual(list(tracks.label), [track_label(int(t)) for t in tracks.track])
            covariance = tracks.covariance
            np.testing.assert_array_equal(covariance, np.swapaxes(covariance, 1, 2))
            known = covariance.any(axis=(1, 2))
            self.assertTrue(known.any(), "every covariance is zero")
            self.assertGreaterEqual(float(np.linalg.eigvalsh(covariance[known]).min()), -1e-6)

    def test_every_column_of_the_files(self):
        # Each column of each file (the catalogue's run_files) reaches the record arrays: the truth's
        # classes, the reports' levels, the tracks' stop and class columns, the settled tracks.
        run = self.loaded
        catalogue = wsntrack.catalogue.load()["run_files"]
        for name, records in (("truth.csv", run.truth), ("observations.csv", run.observations),
                              ("tracks.csv", run.tracks), ("tracks_supernode.csv", run.supernode_tracks),
                              ("tracks_settled.csv", run.settled_tracks)):
            fields = set(records.dtype.names) | set(wsntrack.rundir.COVARIANCE_COLUMNS) - {"covariance"}
            self.assertEqual(set(catalogue[name]) - fields, set(), name)
        self.assertEqual(set(run.truth["class"]) - set(wsntrack.rundir.TRUTH_CLASSES), set())
        with open(REAL / "observations.csv", encoding="utf-8") as f:
            levels = [int(line.rsplit(",", 1)[1]) for line in list(f)[1:]]
        np.testing.assert_array_equal(run.observations.level, levels)
        self.assertGreater(len(run.settled_tracks), 0)

    def test_frames(self):
        try:
            import pandas  # noqa: F401
        except ImportError:
            self.skipTest("pandas is not installed (python3-pandas)")
        run = self.loaded
        tracks = run.frame("tracks")
        self.assertEqual(len(tracks), len(run.tracks))
        self.assertIn("p_vyvy", tracks.columns)
        np.testing.assert_array_equal(tracks["p_xy"].to_numpy(), run.tracks.covariance[:, 0, 1])
        self.assertEqual(list(run.frame("truth").columns), list(run.truth.dtype.names))
        with self.assertRaisesRegex(ValueError, "expected one of truth"):
            run.frame("nothing")

    def test_module_example(self):
        # The example of the module's docstring, on this run instead of /tmp/demo.
        doc = wsntrack_run.__doc__
        code = doc[doc.index("    import sys"):doc.index("Arrays are")]
        code = "\n".join(line[4:] for line in code.splitlines()).replace('"/tmp/demo"', repr(str(REAL)))
        code = code.replace('"build/python"', repr(str(SOURCE / "python")))
        with contextlib.redirect_stdout(io.StringIO()):
            exec(compile(code, "wsntrack_run.__doc__", "exec"), {})


if __name__ == "__main__":
    WORK.mkdir(parents=True, exist_ok=True)
    unittest.main(argv=[sys.argv[0], "-v"])
