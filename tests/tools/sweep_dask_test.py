#!/usr/bin/python3
"""Tests of tools/sweep.py's spec form on a Dask cluster (--scheduler): a scheduler and two workers
that the test starts on loopback (Debian's python3-distributed: `dask scheduler`, `dask worker
--no-nanny`, so that a worker's PID is the worker), tiny sweeps of in-process clusters over DDS on
loopback. The same sweep on this machine and on the cluster gives the same summary.csv, byte for
byte, with every run done by a worker (its sweep_run.json names it) and both workers used; a sweep
resumes across the two; a worker killed (SIGKILL, by its PID) while a run of the sweep is in flight
on it has that run done by the other worker, and the summary is still the same.

  sweep_dask_test.py SOURCE_DIR BIN_DIR WORK_DIR          the cluster cases
  sweep_dask_test.py SOURCE_DIR BIN_DIR WORK_DIR errors   the error cases: no scheduler there, no
        python3-distributed, -j with --scheduler, a sweep by flags, a worker that cannot see --out

Nothing is skipped: without python3-distributed the test fails. Every process the test starts is
stopped by its PID when it ends."""

import csv
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time
import unittest
from pathlib import Path

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
SOURCE, BIN, WORK = Path(sys.argv[1]).resolve(), Path(sys.argv[2]).resolve(), Path(sys.argv[3]).resolve()
ERRORS = sys.argv[4:] == ["errors"]
PYTHON = "/usr/bin/python3"
SWEEP = SOURCE / "tools" / "sweep.py"
WSNTRACK = BIN / "wsntrack"
# The workers import the package from the source tree (as any worker of a shared tree does).
QUIET_ENV = dict(os.environ, PYTHONDONTWRITEBYTECODE="1")

SPEC = """\
# 2 pte values x 1 engine x 3 seeds of 60 in-process ticks: about half a second a run, so that the
# run in flight on a worker killed as the run starts is still in flight when the worker dies.
title: dask sweep
scenario: scenarios/oh_single_supernode.yaml
grid:
  network.pte: [0, 0.3]
engines: [gnn]
seeds: 1-3
set:
  run.ticks: 60
metrics: [eps_k, ospa, mota]
in_process: true
"""


def fresh(name):
    out = WORK / name
    shutil.rmtree(out, ignore_errors=True)
    return out


def sweep(spec, out, *extra, timeout=90, env=None):
    command = [PYTHON, "-B", str(SWEEP), str(spec), "--out", str(out), "--wsntrack", str(WSNTRACK), *extra]
    return subprocess.run(command, capture_output=True, text=True, timeout=timeout, stdin=subprocess.DEVNULL,
                          env=env)


def rows(path):
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def records(out):
    """{run name: its sweep_run.json}."""
    return {p.parent.name: json.loads(p.read_text()) for p in sorted((out / "runs").glob("*/sweep_run.json"))}


def processes_naming(text):
    """{PID: (parent PID, age in s, command line)} of the live processes whose command line contains
    `text` (a zombie has none)."""
    found = {}
    uptime = float(Path("/proc/uptime").read_text().split()[0])
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit() or int(entry.name) == os.getpid():
            continue
        try:
            stat = (entry / "stat").read_text()
            cmdline = (entry / "cmdline").read_bytes().replace(b"\0", b" ").decode()
        except OSError:
            continue
        if text in cmdline:
            fields = stat[stat.rindex(")") + 2:].split()  # from the state on: man proc, /proc/pid/stat
            started = int(fields[19]) / os.sysconf("SC_CLK_TCK")
            found[int(entry.name)] = (int(fields[1]), uptime - started, cmdline)
    return found


WORKER_START_S = 90


class DaskCluster:
    """A scheduler and workers on 127.0.0.1, started by the test; stop() ends each by its PID.
    `prefix`: a command each worker runs under (unshare, to hide a directory from it)."""

    def __init__(self, name, workers, prefix=()):
        self.dir = fresh(name)
        self.dir.mkdir(parents=True)
        self.file = self.dir / "scheduler.json"
        self.processes = []
        self.workers = {}  # address -> Popen
        dask = shutil.which("dask")
        if not dask:
            raise AssertionError("no `dask` command: install python3-distributed (./setup.sh does)")
        self._start("scheduler", [dask, "scheduler", "--host", "127.0.0.1", "--port", "0", "--no-dashboard",
                                  "--scheduler-file", str(self.file)])
        for i in range(workers):
            self._start(f"worker{i}", list(prefix) + [
                dask, "worker", "--scheduler-file", str(self.file), "--host", "127.0.0.1", "--nthreads", "1",
                "--no-nanny", "--no-dashboard", "--name", f"w{i}", "--local-directory", str(self.dir / f"w{i}")])
        try:
            self._wait_for_workers(workers)
        except BaseException:
            self.stop()  # setUpClass failing means no tearDownClass: nothing may outlive the test
            raise

    def _start(self, name, command):
        log = open(self.dir / f"{name}.log", "w", encoding="utf-8")
        self.processes.append((subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT,
                                                stdin=subprocess.DEVNULL, cwd=self.dir, env=QUIET_ENV), name))
        log.close()

    def _wait_for_workers(self, n):
        """Each worker's address, from its log once it has registered with the scheduler."""
        # Starting a worker imports dask and distributed, about 3 s on an idle machine; a loaded
        # CI host (sanitizer builds beside the suite) has taken over 30.
        deadline = time.monotonic() + WORKER_START_S
        while len(self.workers) < n:
            for process, name in self.processes[1:]:
                text = (self.dir / f"{name}.log").read_text(encoding="utf-8", errors="replace")
                match = re.search(r"Start worker at:\s+(tcp://\S+)", text)
                if match and "Registered to" in text:
                    self.workers[match.group(1)] = process
                if process.poll() is not None:
                    raise AssertionError(f"{name} exited {process.returncode}:\n{text}")
            if time.monotonic() > deadline:
                raise AssertionError(f"{n - len(self.workers)} workers did not register within {WORKER_START_S} s")
            time.sleep(0.1)

    @property
    def address(self):
        return json.loads(self.file.read_text())["address"]

    def stop(self):
        """The workers first (a worker whose scheduler is gone waits for it before it closes), then
        the scheduler: SIGTERM, SIGKILL after 10 s."""
        for group in (self.processes[1:], self.processes[:1]):
            for process, _ in group:
                if process.poll() is None:
                    process.terminate()
            for process, _ in group:
                try:
                    process.wait(timeout=10)
                except subprocess.TimeoutExpired:
                    process.kill()
                    process.wait()


class OnCluster(unittest.TestCase):
    """One cluster of two workers for the cases, in order; the last kills a worker."""

    @classmethod
    def setUpClass(cls):
        cls.spec = WORK / "dask.yaml"
        cls.spec.write_text(SPEC, encoding="utf-8")
        cls.cluster = DaskCluster("cluster", 2)

    @classmethod
    def tearDownClass(cls):
        cls.cluster.stop()

    def ok_sweep(self, out, *extra):
        result = sweep(self.spec, out, *extra)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual({r["status"] for r in rows(out / "results.csv")}, {"ok"})
        return result

    def test_1_same_summary_as_on_this_machine(self):
        local, remote = fresh("local"), fresh("remote")
        self.ok_sweep(local, "-j", "2")
        result = self.ok_sweep(remote, "--scheduler", self.cluster.address)
        self.assertIn(f"6 to run, on the Dask cluster at {self.cluster.address} (2 workers, 2 threads now)",
                      result.stderr)
        self.assertIn("[6/6] ", result.stderr)
        self.assertIn("| 0 failed | all done in", result.stderr)
        self.assertEqual(len(rows(remote / "results.csv")), 6)
        self.assertEqual((remote / "summary.csv").read_bytes(), (local / "summary.csv").read_bytes())
        self.assertEqual((remote / "table.md").read_bytes(), (local / "table.md").read_bytes())
        # Every run was done by a worker of the cluster, and both took part; none locally.
        workers = [r["dask_worker"] for r in records(remote).values()]
        self.assertEqual(len(workers), 6)
        self.assertEqual(set(workers), set(self.cluster.workers))
        self.assertEqual({r["dask_worker"] for r in records(local).values()}, {None})

    def test_2_resumes_across_machine_and_cluster(self):
        local, remote = WORK / "local", WORK / "remote"
        result = self.ok_sweep(local, "--scheduler", self.cluster.file)  # the scheduler file works too
        self.assertIn("6 complete from an earlier invocation, nothing to run", result.stderr)
        (remote / "runs" / "gnn_pte-0.3_seed-2" / "sweep_run.json").unlink()
        result = self.ok_sweep(remote, "--scheduler", self.cluster.address)
        self.assertIn("5 complete from an earlier invocation, 1 to run", result.stderr)
        self.assertIn("[1/1] gnn pte=0.3 seed=2 ... ok", result.stderr)
        self.assertEqual((remote / "summary.csv").read_bytes(), (local / "summary.csv").read_bytes())

    def test_3_worker_killed_mid_sweep(self):
        remote = fresh("remote-kill")
        log = open(WORK / "remote-kill.err", "w+", encoding="utf-8")
        process = subprocess.Popen([PYTHON, "-B", str(SWEEP), str(self.spec), "--out", str(remote), "--wsntrack",
                                    str(WSNTRACK), "--scheduler", self.cluster.address],
                                   stdout=subprocess.DEVNULL, stderr=log, stdin=subprocess.DEVNULL)
        try:
            victim, run_pid, run_name = self.kill_a_busy_worker(remote / "runs")
            self.assertEqual(process.wait(timeout=60), 0, (WORK / "remote-kill.err").read_text())
        finally:
            if process.poll() is None:
                process.kill()
                process.wait()
            log.close()
        self.assertEqual({r["status"] for r in rows(remote / "results.csv")}, {"ok"})
        self.assertEqual((remote / "summary.csv").read_bytes(), (WORK / "local" / "summary.csv").read_bytes())
        # The run that was in flight on the killed worker was done again by the other one.
        self.assertNotEqual(records(remote)[run_name]["dask_worker"], victim)
        self.assertNotIn(run_pid, processes_naming(str(remote)), "the killed worker's wsntrack outlived the sweep")
        self.assertEqual(processes_naming(str(remote)), {}, "a wsntrack of the sweep outlived it")

    def kill_a_busy_worker(self, runs):
        """Kills (SIGKILL, by its PID) the first worker seen running a wsntrack of the sweep into `runs`
        that started less than 0.2 s ago (a run takes longer: it is still in flight);
        returns (the worker's address, that wsntrack's PID, the run's name)."""
        # Starting a worker imports dask and distributed, about 3 s on an idle machine; a loaded
        # CI host (sanitizer builds beside the suite) has taken over 30.
        deadline = time.monotonic() + WORKER_START_S
        while time.monotonic() < deadline:
            for address, worker in self.cluster.workers.items():
                for pid, (parent, age, cmdline) in processes_naming(str(runs)).items():
                    if parent != worker.pid or age > 0.2:
                        continue
                    os.kill(worker.pid, signal.SIGKILL)
                    worker.wait()
                    name = re.search(re.escape(str(runs)) + r"/(\S+)", cmdline).group(1)
                    print(f"killed worker {address} (PID {worker.pid}) while it ran {name} (PID {pid}, "
                          f"started {age:.2f} s before)", file=sys.stderr)
                    return address, pid, name
            time.sleep(0.005)
        raise AssertionError("no run of the sweep was seen starting on a worker within 30 s")


class Errors(unittest.TestCase):
    """Each error is one line naming what to do, exit status 2, before anything runs."""

    @classmethod
    def setUpClass(cls):
        cls.spec = WORK / "errors.yaml"
        cls.spec.write_text(SPEC, encoding="utf-8")

    def fails(self, out, *extra, env=None):
        result = sweep(self.spec, out, *extra, env=env)
        self.assertEqual(result.returncode, 2, result.stderr)
        return result.stderr

    def test_no_scheduler_there(self):
        out = fresh("unreachable")
        short = dict(os.environ, DASK_DISTRIBUTED__COMM__TIMEOUTS__CONNECT="1s")
        stderr = self.fails(out, "--scheduler", "tcp://127.0.0.1:9", env=short)
        self.assertIn("--scheduler tcp://127.0.0.1:9: no Dask scheduler answered at tcp://127.0.0.1:9 within 1 s",
                      stderr)
        self.assertFalse(out.exists())
        self.assertIn("not a scheduler's address", self.fails(out, "--scheduler", "tcp://nowhere"))
        self.assertIn("neither a scheduler's address (tcp://HOST:PORT) nor a file that `dask scheduler "
                      "--scheduler-file` wrote within 1 s", self.fails(out, "--scheduler", str(WORK / "none.json"),
                                                                       env=short))

    def test_no_distributed(self):
        fake = WORK / "no-distributed"
        fake.mkdir(parents=True, exist_ok=True)
        (fake / "distributed.py").write_text("raise ImportError('No module named distributed (simulated)')\n")
        stderr = self.fails(fresh("no-distributed-out"), "--scheduler", "tcp://127.0.0.1:9",
                            env=dict(os.environ, PYTHONPATH=str(fake)))
        self.assertIn("apt-get install python3-distributed", stderr)

    def test_jobs_and_flag_form(self):
        self.assertIn("-j and --scheduler", self.fails(fresh("jobs"), "-j", "2", "--scheduler", "tcp://127.0.0.1:9"))
        # A sweep given by flags is the same spec, and goes to a cluster the same way.
        short = dict(os.environ, DASK_DISTRIBUTED__COMM__TIMEOUTS__CONNECT="1s")
        result = subprocess.run([PYTHON, "-B", str(SWEEP), "--scheduler", "tcp://127.0.0.1:9", "--scenario",
                                 str(SOURCE / "scenarios/oh_single_supernode.yaml"), "--out", str(fresh("flags")),
                                 "--wsntrack", str(WSNTRACK)], capture_output=True, text=True, timeout=60, env=short)
        self.assertEqual(result.returncode, 2, result.stderr)
        self.assertIn("no Dask scheduler answered at tcp://127.0.0.1:9", result.stderr)

    def test_worker_that_cannot_see_the_sweep_directory(self):
        hidden = fresh("hidden")
        hidden.mkdir(parents=True)
        # The worker's own mount namespace has an empty tmpfs over `hidden`.
        prefix = ["unshare", "--mount", "--propagation", "private", "--", "sh", "-c",
                  f'mount -t tmpfs tmpfs "{hidden}" && exec "$0" "$@"']
        if subprocess.run(prefix[:5] + ["true"], capture_output=True).returncode != 0:
            self.fail("unshare --mount is not permitted here: the test needs root in its own mount namespace")
        cluster = DaskCluster("cluster-hidden", 1, prefix)
        try:
            stderr = self.fails(hidden / "out", "--scheduler", cluster.address)
        finally:
            cluster.stop()
        self.assertRegex(stderr, r"worker tcp://127\.0\.0\.1:\d+ cannot see " + re.escape(str(hidden / "out")) +
                         r"/\.sweep-probe-\w+ \(the sweep directory\)")
        self.assertIn("a shared filesystem", stderr)
        self.assertFalse((hidden / "out").exists())


if __name__ == "__main__":
    WORK.mkdir(parents=True, exist_ok=True)
    cases = unittest.defaultTestLoader.loadTestsFromTestCase(Errors if ERRORS else OnCluster)
    result = unittest.TextTestRunner(verbosity=2).run(cases)
    sys.exit(0 if result.wasSuccessful() and result.testsRun else 1)
