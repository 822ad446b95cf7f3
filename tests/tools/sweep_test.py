#!/usr/bin/python3
"""Tests of tools/sweep.py's spec form (sweep.py SPEC.yaml --out DIR) on tiny sweeps of real
in-process clusters (10 ticks, over DDS on loopback, started only through `wsntrack run`): the rows
and commands of results.csv, summary.csv against a hand computation from results.csv, the plots,
resuming (a second invocation runs nothing, a damaged run is run again, a SIGTERM-stopped sweep
goes on where it stopped), a changed spec refused, bad specs (FILE:LINE, exit 2), a failing run
(exit 1, a failed row, not counted), and that the flag form still works.

Usage: sweep_test.py SOURCE_DIR BIN_DIR WORK_DIR
"""

import csv
import json
import math
import os
import shlex
import shutil
import signal
import statistics
import subprocess
import sys
import time
import unittest
from pathlib import Path

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
SOURCE, BIN, WORK = Path(sys.argv[1]).resolve(), Path(sys.argv[2]).resolve(), Path(sys.argv[3]).resolve()
PYTHON = "/usr/bin/python3"
SWEEP = SOURCE / "tools" / "sweep.py"
WSNTRACK = BIN / "wsntrack"
sys.path.insert(0, str(SOURCE / "python"))
from wsntrack.sweep.metrics import METRIC_SOURCES  # noqa: E402
from wsntrack.sweep.spec import load_spec  # noqa: E402
from wsntrack.sweep.summary import t_quantile  # noqa: E402

# t(0.975, df) from a printed table (e.g. NIST/SEMATECH e-Handbook, 1.3.6.7.2), independent of the
# tool's own computation.
T_975 = {1: 12.706204736, 2: 4.302652730, 4: 2.776445105, 9: 2.262157163, 29: 2.045229642}


def write(path, text):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path


def sweep_command(spec, out, *extra):
    return [PYTHON, str(SWEEP), str(spec), "--out", str(out), "--wsntrack", str(WSNTRACK), *extra]


def fresh(name):
    """An empty output directory WORK/name for one sweep of a test."""
    out = WORK / name
    shutil.rmtree(out, ignore_errors=True)
    return out


def run_sweep(spec, out, *extra, timeout=120, wsntrack=None, env=None):
    command = sweep_command(spec, out, *extra)
    if wsntrack:
        command[command.index("--wsntrack") + 1] = str(wsntrack)
    return subprocess.run(command, capture_output=True, text=True, timeout=timeout, stdin=subprocess.DEVNULL,
                          env=dict(os.environ, **(env or {})))


def rows(path):
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def is_png(path):
    return path.is_file() and path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def processes_naming(path):
    """PIDs of processes whose command line names path: the runs a sweep into path started."""
    found = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                if str(path).encode() in (entry / "cmdline").read_bytes():
                    found.append(int(entry.name))
            except OSError:
                pass
    return [pid for pid in found if pid != os.getpid()]


MAIN_SPEC = """\
# A tiny sweep: 2 pte values x 2 engines x 2 seeds of 10 ticks.
title: tiny sweep
scenario: scenarios/oh_single_supernode.yaml
grid:
  network.pte: [0, 0.3]
engines: [mcmcda, gnn]
seeds: 1-2
set:
  run.ticks: 10
metrics: [eps_k, ospa, mota]
in_process: true
reference:
  - {metric: eps_k, value: 0.18, at: {network.pte: 0.3}, label: "a bound"}
"""


class ReportCounts(unittest.TestCase):
    """The report counts of Oh et al. §VII-E come from each run's network.json and observations.csv."""

    def test_counts_match_the_run_files(self):
        out = fresh("counts")
        spec = write(WORK / "counts.yaml", "scenario: scenarios/oh_quadrants.yaml\ngrid: {network.pte: [0.3]}\n"
                     "engines: [gnn]\nseeds: 1\nset: {run.ticks: 10}\nin_process: true\n"
                     "metrics: [reports, false_reports, reports_lost, reports_received, reports_delayed]\n")
        result = run_sweep(spec, out)
        self.assertEqual(result.returncode, 0, result.stderr)
        [row] = rows(out / "results.csv")
        run_dir = out / row["run_dir"]
        network = json.loads((run_dir / "network.json").read_text())
        with open(run_dir / "observations.csv", newline="") as f:
            observations = list(csv.DictReader(f))
        false_reports = sum(1 for o in observations if o["target"] == "-1")
        self.assertGreater(false_reports, 0)  # oh_quadrants has clutter: the count is not trivially 0
        self.assertEqual(float(row["reports"]), network["sent"])
        self.assertEqual(float(row["reports"]), len(observations))
        self.assertEqual(float(row["false_reports"]), false_reports)
        self.assertEqual(float(row["reports_lost"]), network["lost"])
        self.assertEqual(float(row["reports_received"]), network["sent"] - network["lost"] - network["unreachable"])
        self.assertEqual(float(row["reports_delayed"]), network["delayed"])


class MainSweep(unittest.TestCase):
    """One sweep, then invocations on its directory; the tests run in order (names sort)."""

    @classmethod
    def setUpClass(cls):
        cls.dir = WORK / "main"
        shutil.rmtree(cls.dir, ignore_errors=True)
        cls.spec = write(WORK / "main.yaml", MAIN_SPEC)
        cls.first = run_sweep(cls.spec, cls.dir, "-j", "2")
        cls.results = rows(cls.dir / "results.csv") if (cls.dir / "results.csv").is_file() else []

    def test_1_exit_and_progress(self):
        self.assertEqual(self.first.returncode, 0, self.first.stderr)
        self.assertIn("8 runs (2 grid points x 2 engines x 2 seeds)", self.first.stderr)
        self.assertIn("0 complete from an earlier invocation, 8 to run, 2 at a time", self.first.stderr)
        self.assertIn("[8/8] ", self.first.stderr)
        self.assertIn("| 0 failed | ETA", self.first.stderr)
        self.assertIn("| 0 failed | all done in", self.first.stderr)
        self.assertIn("| pte | mcmcda eps_K |", self.first.stdout)  # the table on stdout
        self.assertEqual(self.first.stdout, (self.dir / "table.md").read_text(encoding="utf-8"))

    def test_2_results_rows_and_commands(self):
        self.assertEqual(len(self.results), 8)
        self.assertEqual(list(self.results[0]), ["engine", "network.pte", "seed", "status", "exit", "eps_k", "ospa",
                                                 "mota", "wall_s", "reused", "run_dir", "log", "command"])
        expected = [(p, e, s) for p in ("0", "0.3") for e in ("mcmcda", "gnn") for s in ("1", "2")]
        self.assertEqual([(r["network.pte"], r["engine"], r["seed"]) for r in self.results], expected)
        for row in self.results:
            self.assertEqual((row["status"], row["exit"], row["reused"]), ("ok", "0", "0"), row)
            run_dir = self.dir / row["run_dir"]
            command = shlex.split(row["command"])
            self.assertEqual(command[:3], [str(WSNTRACK), "run", str(SOURCE / "scenarios/oh_single_supernode.yaml")])
            self.assertEqual(command[3:], ["--seed", row["seed"], "--out", str(run_dir), "--overwrite", "--quiet",
                                           "--no-plot", "--set", f"tracker.engine={row['engine']}", "--set",
                                           "run.ticks=10", "--set", f"network.pte={row['network.pte']}",
                                           "--in-process"])
            # The command is the one wsntrack ran (its run.json), and the one recorded for resuming.
            provenance = json.loads((run_dir / "run.json").read_text())["provenance"]
            self.assertEqual(provenance["command_line"], command)
            self.assertEqual(json.loads((run_dir / "sweep_run.json").read_text())["command"], command)
            self.assertTrue((self.dir / row["log"]).is_file())
            metrics = json.loads((run_dir / "metrics.json").read_text())
            self.assertEqual(metrics["ticks"], 10)
            self.assertEqual(float(row["eps_k"]), metrics["eps_k"])
            self.assertEqual(float(row["ospa"]), metrics["ospa"])
            self.assertEqual(float(row["mota"]), metrics["clear_mot"]["mota"])

    def test_3_summary_by_hand(self):
        summary = rows(self.dir / "summary.csv")
        self.assertEqual([(r["engine"], r["network.pte"]) for r in summary],
                         [("mcmcda", "0"), ("gnn", "0"), ("mcmcda", "0.3"), ("gnn", "0.3")])
        for row in summary:
            mine = [r for r in self.results if r["engine"] == row["engine"] and r["network.pte"] == row["network.pte"]]
            self.assertEqual((row["runs"], row["ok"], row["failed"]), ("2", "2", "0"))
            for metric in ("eps_k", "ospa", "mota"):
                values = [float(r[metric]) for r in mine]
                n = len(values)
                mean = sum(values) / n
                sd = statistics.stdev(values)
                half = T_975[n - 1] * sd / math.sqrt(n)
                self.assertEqual(row[f"{metric}_n"], str(n))
                for name, want in (("mean", mean), ("sd", sd), ("ci95_low", mean - half),
                                   ("ci95_high", mean + half)):
                    self.assertAlmostEqual(float(row[f"{metric}_{name}"]), want, delta=1e-8 * (1 + abs(want)),
                                           msg=f"{row['engine']} pte={row['network.pte']} {metric}_{name}")

    def test_4_plots(self):
        for metric in ("eps_k", "ospa", "mota"):
            self.assertTrue(is_png(self.dir / "plots" / f"{metric}.png"), metric)

    def test_5_resume_runs_nothing(self):
        records = {p: p.stat().st_mtime_ns for p in (self.dir / "runs").glob("*/sweep_run.json")}
        self.assertEqual(len(records), 8)
        summary = (self.dir / "summary.csv").read_text()
        again = run_sweep(self.spec, self.dir)
        self.assertEqual(again.returncode, 0, again.stderr)
        self.assertIn("8 complete from an earlier invocation, nothing to run", again.stderr)
        self.assertNotIn("[1/", again.stderr)
        self.assertEqual({p: p.stat().st_mtime_ns for p in records}, records)
        self.assertEqual((self.dir / "summary.csv").read_text(), summary)
        self.assertEqual({r["reused"] for r in rows(self.dir / "results.csv")}, {"1"})

    def test_6_incomplete_run_is_run_again(self):
        # A metrics.json cut short (as by a crash) is not complete: that run, and only it, runs again.
        victim = self.dir / "runs" / "gnn_pte-0.3_seed-2" / "metrics.json"
        victim.write_text(victim.read_text()[:100])
        again = run_sweep(self.spec, self.dir)
        self.assertEqual(again.returncode, 0, again.stderr)
        self.assertIn("7 complete from an earlier invocation, 1 to run", again.stderr)
        self.assertIn("[1/1] gnn pte=0.3 seed=2 ... ok", again.stderr)
        json.loads(victim.read_text())

    def test_6b_run_marked_failed_is_run_again(self):
        # metrics.json intact, but run.json says the run failed: never reused as a result.
        run_json = self.dir / "runs" / "gnn_pte-0.3_seed-1" / "run.json"
        run_json.write_text(run_json.read_text().replace('"status": "complete"',
                                                         '"status": "failed",\n  "reason": "by hand"'))
        again = run_sweep(self.spec, self.dir)
        self.assertEqual(again.returncode, 0, again.stderr)
        self.assertIn("7 complete from an earlier invocation, 1 to run", again.stderr)
        self.assertIn("[1/1] gnn pte=0.3 seed=1 ... ok", again.stderr)
        self.assertIn('"status": "complete"', run_json.read_text())

    def test_7_changed_spec_is_refused(self):
        records = {p: p.stat().st_mtime_ns for p in (self.dir / "runs").glob("*/sweep_run.json")}
        changed = run_sweep(self.spec, self.dir, "--set", "network.pde=0.1", "--seeds", "1")
        self.assertEqual(changed.returncode, 2, changed.stderr)
        self.assertIn("holds a different sweep", changed.stderr)
        self.assertIn("seeds: 1-2 -> 1", changed.stderr)
        self.assertIn("set: network.pde: (not set) -> 0.1", changed.stderr)
        self.assertIn("--force", changed.stderr)
        self.assertEqual({p: p.stat().st_mtime_ns for p in records}, records)
        # A changed title only changes the tables and plots.
        write(self.spec, MAIN_SPEC.replace("title: tiny sweep", "title: renamed"))
        again = run_sweep(self.spec, self.dir)
        write(self.spec, MAIN_SPEC)
        self.assertEqual(again.returncode, 0, again.stderr)
        self.assertIn('title: tiny sweep -> renamed', again.stderr)
        self.assertIn("nothing to run", again.stderr)
        self.assertTrue((self.dir / "table.md").read_text().startswith("## renamed"))


class BadSpecs(unittest.TestCase):
    def check(self, name, text, line, message):
        out = fresh(f"bad-{name}")
        spec = write(WORK / f"bad_{name}.yaml", text)
        result = run_sweep(spec, out)
        self.assertEqual(result.returncode, 2, result.stderr)
        self.assertIn(f"{spec}:{line}: {message}", result.stderr)
        self.assertFalse(out.exists(), "nothing may be made for a bad spec")

    def test_unknown_key(self):
        self.check("unknown", "scenario: scenarios/oh_single_supernode.yaml\ngrid: {network.pte: [0]}\nengine: [gnn]\n",
                   3, "unknown key 'engine' in the spec; expected one of: scenario, grid, engines")

    def test_wrong_types(self):
        self.check("seeds", "scenario: scenarios/oh_single_supernode.yaml\ngrid: {network.pte: [0]}\n"
                   "seeds: [1, two]\n", 3, "seeds: expected a seed")
        self.check("grid", "scenario: scenarios/oh_single_supernode.yaml\ngrid:\n  network.pte: 0.2\n", 3,
                   "grid: network.pte: expected a list of values")
        self.check("in_process", "scenario: scenarios/oh_single_supernode.yaml\ngrid: {network.pte: [0]}\n"
                   "in_process: 1\n", 3, "in_process: expected true or false, got the integer 1")
        self.check("reference", "scenario: scenarios/oh_single_supernode.yaml\ngrid: {network.pte: [0]}\n"
                   "reference:\n  - metric: eps_k\n    value: low\n    label: x\n", 5,
                   "reference: value: expected a number")

    def test_missing_and_rejected(self):
        self.check("missing", "grid: {network.pte: [0]}\n", 1, "the spec: 'scenario' is missing")
        self.check("scenario", "scenario: no_such.yaml\ngrid: {network.pte: [0]}\n", 1, "scenario: no file no_such.yaml")
        self.check("key", "scenario: scenarios/oh_single_supernode.yaml\ngrid: {network.ptx: [0, 0.1]}\n", 2,
                   "grid: network.ptx: wsntrack validate rejects every value")
        self.check("engine", "scenario: scenarios/oh_single_supernode.yaml\ngrid: {network.pte: [0]}\n"
                   "engines:\n  - gnn\n  - nope\n", 5, "engine nope: rejected by wsntrack validate")
        self.check("yaml", "scenario: scenarios/oh_single_supernode.yaml\ngrid: {network.pte: [0\n", 3,
                   "malformed YAML")


class FailingRun(unittest.TestCase):
    """A 2-D grid with one value wsntrack rejects: its runs fail, the others count, exit 1."""

    def test_failed_rows_and_heat_maps(self):
        out = fresh("failing")
        spec = write(WORK / "failing.yaml", "scenario: scenarios/oh_single_supernode.yaml\n"
                     "grid:\n  network.pte: [0, 1.5]\n  network.pde: [0, 0.2]\nengines: [gnn]\nseeds: 1\n"
                     "set: {run.ticks: 10}\nin_process: true\nmetrics: [eps_k]\n")
        result = run_sweep(spec, out)
        self.assertEqual(result.returncode, 1, result.stderr)
        self.assertIn(f"{spec}:3: warning: network.pte=1.5 is rejected by wsntrack validate", result.stderr)
        self.assertIn("2 of 4 runs failed", result.stderr)
        results = rows(out / "results.csv")
        self.assertEqual([(r["network.pte"], r["network.pde"], r["status"]) for r in results],
                         [("0", "0", "ok"), ("0", "0.2", "ok"), ("1.5", "0", "failed"), ("1.5", "0.2", "failed")])
        for row in results[2:]:
            self.assertNotEqual(row["exit"], "0")
            self.assertEqual(row["eps_k"], "")
            self.assertIn("network.pte=1.5", row["command"])
            self.assertIn("must be in [0, 1]", (out / row["log"]).read_text())
        summary = rows(out / "summary.csv")
        self.assertEqual([(r["runs"], r["ok"], r["failed"], r["eps_k_n"]) for r in summary],
                         [("1", "1", "0", "1"), ("1", "1", "0", "1"), ("1", "0", "1", "0"), ("1", "0", "1", "0")])
        self.assertEqual(summary[0]["eps_k_mean"], results[0]["eps_k"])
        self.assertEqual((summary[0]["eps_k_sd"], summary[0]["eps_k_ci95_low"]), ("", ""))  # n = 1
        self.assertEqual(summary[2]["eps_k_mean"], "")
        self.assertIn("| 1.5 | 0 | – (0/1) |", result.stdout)
        self.assertTrue(is_png(out / "plots" / "eps_k_gnn.png"))
        # Failed runs never look complete: the next invocation runs them again, and only them.
        again = run_sweep(spec, out)
        self.assertEqual(again.returncode, 1, again.stderr)
        self.assertIn("2 complete from an earlier invocation, 2 to run", again.stderr)


class Stopped(unittest.TestCase):
    def test_sigterm_then_resume(self):
        out = fresh("stopped")
        spec = write(WORK / "stopped.yaml", "scenario: scenarios/oh_single_supernode.yaml\n"
                     "grid: {network.pte: [0, 0.1, 0.2, 0.3]}\nengines: [gnn]\nseeds: 1-2\n"
                     "set: {run.ticks: 10}\nin_process: true\n")
        log = open(WORK / "stopped.err", "w+", encoding="utf-8")
        process = subprocess.Popen(sweep_command(spec, out, "-j", "1"), stdout=subprocess.DEVNULL, stderr=log,
                                   stdin=subprocess.DEVNULL)
        deadline = time.monotonic() + 60
        while "[2/8]" not in (WORK / "stopped.err").read_text() and process.poll() is None:
            self.assertLess(time.monotonic(), deadline, "no progress")
            time.sleep(0.02)
        process.send_signal(signal.SIGTERM)  # by its PID, as a user's kill would
        self.assertEqual(process.wait(timeout=60), 128 + signal.SIGTERM)
        log.close()
        stderr = (WORK / "stopped.err").read_text()
        self.assertIn("SIGTERM: stopping", stderr)
        self.assertIn("Run the same command again to resume", stderr)
        self.assertEqual(processes_naming(out / "runs"), [], "a wsntrack run of the sweep outlived it")
        statuses = [r["status"] for r in rows(out / "results.csv")]
        finished = statuses.count("ok")
        self.assertGreaterEqual(finished, 2)
        self.assertLess(finished, 8)
        self.assertEqual(set(statuses) - {"ok", "interrupted", "not run"}, set())
        again = run_sweep(spec, out)
        self.assertEqual(again.returncode, 0, again.stderr)
        self.assertIn(f"{finished} complete from an earlier invocation, {8 - finished} to run", again.stderr)
        self.assertEqual([r["status"] for r in rows(out / "results.csv")], ["ok"] * 8)


class PortClash(unittest.TestCase):
    """A run that lost its DDS ports to a cluster starting at the same moment is started again (at
    most 3 times); simulated by a wrapper whose first `run` calls fail as Cyclone does then."""

    def sweep(self, name, fails):
        out = fresh(f"clash-{name}")
        counter = WORK / f"clash-{name}.count"
        counter.unlink(missing_ok=True)
        wrapper = write(WORK / "clashing.sh", f"""#!/bin/sh
if [ "$1" = run ]; then
  n=$(cat "$CLASH_COUNTER" 2>/dev/null || echo 0); n=$((n + 1)); echo $n >"$CLASH_COUNTER"
  if [ $n -le $CLASH_FAILS ]; then
    echo "1795687427.283072 [34]   wsntrack: rtps_init: failed to create unicast sockets for domain 34"
    echo "wsntrack run: FAILED: launcher: dds_create_domain 34 failed: Error"; exit 1
  fi
fi
exec "{WSNTRACK}" "$@"
""")
        wrapper.chmod(0o755)
        spec = write(WORK / "clash.yaml", "scenario: scenarios/oh_single_supernode.yaml\n"
                     "grid: {network.pte: [0]}\nengines: [gnn]\nset: {run.ticks: 10}\nin_process: true\n")
        result = run_sweep(spec, out, wsntrack=wrapper, env={"CLASH_COUNTER": str(counter), "CLASH_FAILS": str(fails)})
        return result, out, int(counter.read_text())

    def test_started_again(self):
        result, out, calls = self.sweep("once", 1)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("gnn pte=0 seed=1: lost its DDS ports to another cluster", result.stderr)
        self.assertEqual(calls, 2)
        self.assertEqual([r["status"] for r in rows(out / "results.csv")], ["ok"])
        self.assertIn("attempt 2 of 3", (out / "logs" / "gnn_pte-0_seed-1.log").read_text())

    def test_gives_up(self):
        result, out, calls = self.sweep("always", 9)
        self.assertEqual(result.returncode, 1, result.stderr)
        self.assertEqual(calls, 3)
        self.assertEqual([r["status"] for r in rows(out / "results.csv")], ["failed"])


class NotComplete(unittest.TestCase):
    """A run that exits 0 but whose run.json does not say complete is a failed run: its numbers never
    enter results.csv or summary.csv. Simulated by a wrapper that marks the finished run failed."""

    def test_counted_as_failed(self):
        out = fresh("not-complete")
        wrapper = write(WORK / "not_complete.sh", f"""#!/bin/sh
"{WSNTRACK}" "$@" || exit $?
[ "$1" = run ] || exit 0
for a in "$@"; do [ "$prev" = --out ] && dir="$a"; prev="$a"; done
sed -i 's/"status": "complete"/"status": "failed",\\n  "reason": "marked by the test"/' "$dir/run.json"
""")
        wrapper.chmod(0o755)
        spec = write(WORK / "not_complete.yaml", "scenario: scenarios/oh_single_supernode.yaml\n"
                     "grid: {network.pte: [0]}\nengines: [gnn]\nset: {run.ticks: 10}\nin_process: true\n")
        result = run_sweep(spec, out, wsntrack=wrapper)
        self.assertEqual(result.returncode, 1, result.stderr)
        self.assertIn("1 of 1 runs failed", result.stderr)
        results = rows(out / "results.csv")
        self.assertEqual([r["status"] for r in results], ["failed"])
        self.assertEqual(results[0]["eps_k"], "")
        log = (out / "logs" / "gnn_pte-0_seed-1.log").read_text()
        self.assertIn("not counted", log)
        self.assertIn("incomplete run (status failed: marked by the test)", log)


class Pieces(unittest.TestCase):
    def test_t_quantile(self):
        for df, want in T_975.items():
            self.assertAlmostEqual(t_quantile(0.975, df), want, delta=1e-8)

    def test_scenario_beside_the_spec(self):
        spec = write(WORK / "beside" / "spec.yaml", "scenario: mine.yaml\ngrid: {network.pte: [0]}\n")
        shutil.copy(SOURCE / "scenarios" / "oh_single_supernode.yaml", WORK / "beside" / "mine.yaml")
        self.assertEqual(load_spec(spec).scenario, (WORK / "beside" / "mine.yaml").resolve())

    def test_shipped_spec_and_readme(self):
        """The shipped example loads, and README.md's copy of it (without notes) says the same."""
        import yaml
        shipped = SOURCE / "sweeps" / "oh_fig7_pte.yaml"
        spec = load_spec(shipped)
        self.assertEqual(spec.grid[0][:2], ("network.pte", ["0", "0.1", "0.2", "0.3", "0.4", "0.5", "0.6"]))
        self.assertEqual((spec.engines, spec.seeds), (["mcmcda", "gnn"], list(range(1, 11))))
        readme = (SOURCE / "README.md").read_text(encoding="utf-8")
        section = readme[readme.index("## Parameter sweeps"):]
        block = section[section.index("```yaml\n") + 8:]
        block = block[:block.index("```")]
        data = yaml.safe_load(shipped.read_text(encoding="utf-8"))
        data.pop("notes")
        self.assertEqual(yaml.safe_load(block), data)

    def test_every_shipped_spec_loads(self):
        """Each spec under sweeps/ parses, names metrics the tool knows and a scenario that exists."""
        specs = sorted((SOURCE / "sweeps").glob("*.yaml"))
        self.assertGreaterEqual(len(specs), 9)
        for path in specs:
            with self.subTest(spec=path.name):
                spec = load_spec(path)
                self.assertTrue(set(spec.metrics) <= set(METRIC_SOURCES), spec.metrics)
                self.assertTrue(spec.grid)

    def test_flags_build_the_same_sweep_as_a_spec(self):
        # The same sweep by a spec file and by flags: the same results (timing aside), summary and table.
        spec = WORK / "same.yaml"
        spec.write_text(f"scenario: {SOURCE / 'scenarios/oh_single_supernode.yaml'}\ngrid:\n  network.pte: [0, 0.3]\n"
                        "engines: [gnn]\nseeds: 1-2\nset:\n  run.ticks: 10\nin_process: true\n", encoding="utf-8")
        by_spec, by_flags = fresh("same-spec"), fresh("same-flags")
        first = subprocess.run([PYTHON, str(SWEEP), str(spec), "--out", str(by_spec), "--wsntrack", str(WSNTRACK)],
                               capture_output=True, text=True, timeout=120)
        self.assertEqual(first.returncode, 0, first.stderr)
        flags = [PYTHON, str(SWEEP), "--scenario", str(SOURCE / "scenarios/oh_single_supernode.yaml"), "--engines",
                 "gnn", "--seeds", "1-2", "--set-grid", "network.pte=0,0.3", "--set", "run.ticks=10", "--in-process",
                 "--out", str(by_flags), "--wsntrack", str(WSNTRACK)]
        result = subprocess.run(flags, capture_output=True, text=True, timeout=120)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("| pte | gnn eps_K | gnn eps_X gated | gnn OSPA |", result.stdout)
        untimed = [{k: v for k, v in r.items() if k not in ("wall_s", "command")} for r in rows(by_spec / "results.csv")]
        self.assertEqual(len(untimed), 4)
        self.assertEqual(untimed, [{k: v for k, v in r.items() if k not in ("wall_s", "command")}
                                   for r in rows(by_flags / "results.csv")])
        self.assertEqual((by_spec / "summary.csv").read_bytes(), (by_flags / "summary.csv").read_bytes())
        self.assertEqual((by_spec / "table.md").read_bytes(), (by_flags / "table.md").read_bytes())
        self.assertTrue((by_flags / "plots" / "eps_k.png").is_file())
        # And it resumes like one: the same flags again run nothing.
        again = subprocess.run(flags, capture_output=True, text=True, timeout=120)
        self.assertEqual(again.returncode, 0, again.stderr)
        self.assertIn("4 complete from an earlier invocation, nothing to run", again.stderr)

    def test_flags_and_a_spec_file_do_not_mix(self):
        result = subprocess.run([PYTHON, str(SWEEP), str(SOURCE / "sweeps/oh_fig7_pte.yaml"), "--set-grid",
                                 "network.pde=0,0.3", "--wsntrack", str(WSNTRACK)], capture_output=True, text=True,
                                timeout=60)
        self.assertEqual(result.returncode, 2, result.stderr)
        self.assertIn("--set-grid: ", result.stderr)
        self.assertIn("is a spec file, whose scenario and grid are its own", result.stderr)
        result = subprocess.run([PYTHON, str(SWEEP), "--wsntrack", str(WSNTRACK)], capture_output=True, text=True,
                                timeout=60)
        self.assertEqual(result.returncode, 2, result.stderr)
        self.assertIn("expected a spec file (sweeps/*.yaml) or --scenario FILE", result.stderr)


if __name__ == "__main__":
    WORK.mkdir(parents=True, exist_ok=True)
    unittest.main(argv=[sys.argv[0], "-v"])
