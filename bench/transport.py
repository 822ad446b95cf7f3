#!/usr/bin/python3
"""wsntrack's DDS path and lockstep against their reference points, on the run's own loopback
Cyclone configuration (the scale-out issue, item 4; docs/PERFORMANCE.md):

    bench/transport.py throughput [--sizes 256 1k 4k 16k] [--seconds 10] [--sample report] [--repeats 3]
    bench/transport.py lockstep [--processes 8 16 32 64 70] [--ticks 200] [--in-flight K] [--repeats 3]

throughput: report batches from a node tile's writer to a subscriber in another process
(build/bin/wsn_transport_bench throughput: reliable KEEP_ALL, one freshly encoded ReportBatch per
write, decoded on arrival) beside `ddsperf pub size S` / `ddsperf sub` (reliable, keep-all) at the
same serialized size, both on the Cyclone configuration of a run (ddsperf through CYCLONEDDS_URI);
also "raw", the same path with the subscriber taking without decoding, as ddsperf's does; and with
--sample boundary, a tile's SensorBoundary (flat {sensor, z} readings) in place of the reports. Each
figure is the median over the repeats of the subscriber's median whole-second rate; the ratio is
wsntrack's samples/s over ddsperf's (goal >= 0.5).

lockstep: the cost per tick of a cluster of N processes, `wsntrack run --no-plot` of a field with
no targets (no readings, no tracks: only the lockstep's messages) whose N = tiles + supernodes +
network + aggregator, ticks/s from metrics.json's `timing`; beside a plain publish/subscribe barrier
of N processes (wsn_transport_bench barrier: each writes "done tick t" and waits for all N of t).
The cluster pipelines up to run.max_ticks_in_flight ticks (3); --in-flight 1 holds it to one tick
at a time, as the barrier is. Medians over the repeats; the ratio is the cost per tick of wsntrack
over the barrier's, i.e. barrier ticks/s over wsntrack ticks/s (goal <= 1.5).

Every process is started with a time bound and, if it overruns, stopped by its own pid.
"""

import argparse
import fcntl
import json
import os
import re
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

SOURCE = Path(__file__).resolve().parent.parent
SIZES = {"k": 1024, "m": 1024 * 1024}


def size_bytes(text):
    """'1k' -> 1024, '512' -> 512 (ddsperf's own suffixes, k and M in powers of two)."""
    match = re.fullmatch(r"(\d+)([kKmM]?)", text)
    if not match:
        raise argparse.ArgumentTypeError(f"size {text!r}: a number of bytes, optionally with k or M")
    return int(match.group(1)) * SIZES.get(match.group(2).lower(), 1)


def run_bounded(command, timeout, env=None):
    """Runs `command` to its end within `timeout` s; on overrun stops it by its pid (SIGTERM, then
    SIGKILL) and fails. Returns its stdout."""
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    try:
        out, err = process.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        stop(process)
        sys.exit(f"transport.py: {' '.join(map(str, command))} took over {timeout} s; stopped")
    if process.returncode != 0:
        sys.exit(f"transport.py: {' '.join(map(str, command))} failed (exit {process.returncode}):\n{out[-2000:]}{err[-2000:]}")
    return out


def stop(process, grace=5):
    """Stops one process we started, by its pid: SIGTERM, and SIGKILL if it outlives `grace` s."""
    if process.poll() is not None:
        return
    os.kill(process.pid, signal.SIGTERM)
    try:
        process.wait(timeout=grace)
    except subprocess.TimeoutExpired:
        os.kill(process.pid, signal.SIGKILL)
        process.wait()


class Bench:
    """The benchmark executable and the Cyclone configuration and domain it runs on."""

    def __init__(self, bin_dir):
        self.exe = Path(bin_dir) / "wsn_transport_bench"
        if not self.exe.exists():
            sys.exit(f"transport.py: no {self.exe}; build it (cmake --build build --target wsn_transport_bench) or give --bin")
        self.lock = None

    def config(self, processes, index, run_id):
        return run_bounded([self.exe, "config", "--processes", str(processes), "--index", str(index),
                            "--run-id", str(run_id)], 30)

    def pick_domain(self, processes):
        """A domain whose ports are free for a cluster of `processes` (the benchmark probes them as the
        launcher does), reserved as `wsntrack run` reserves its own, with the lock file launchers
        use, held until the next pick."""
        if self.lock is not None:
            os.close(self.lock)
            self.lock = None
        locks = Path(tempfile.gettempdir()) / "wsntrack-domain-locks"
        if not locks.exists():
            locks.mkdir(exist_ok=True)
            os.chmod(locks, 0o1777)  # as the launcher makes it: any user's runs lock there
        for domain in run_bounded([self.exe, "domains", "--processes", str(processes)], 30).split():
            fd = os.open(locks / f"domain-{domain}.lock", os.O_RDWR | os.O_CREAT, 0o666)
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError:
                os.close(fd)
                continue
            self.lock = fd
            return int(domain)
        sys.exit("transport.py: no Cyclone DDS domain with free loopback ports")


def run_id():
    return (os.getpid() << 20 | int(time.time() * 1000) & 0xFFFFF) or 1


# --- throughput ------------------------------------------------------------------------------------

def wsntrack_throughput(bench, size, seconds, raw, sample, batching):
    """Samples/s, serialized bytes and items per batch of one wsn_transport_bench throughput run;
    `raw`: the subscriber takes without decoding, as ddsperf's does; `batching`: the writer packs
    samples into datagrams until a flush, as ddsperf's does (the roles flush every write)."""
    rid = run_id()
    domain = bench.pick_domain(2)
    out = run_bounded([bench.exe, "throughput", "--bytes", str(size), "--seconds", str(seconds),
                       "--domain", str(domain), "--run-id", str(rid), "--sample", sample] + (["--raw"] if raw else []) + (["--batching"] if batching else []),
                      seconds + 60)
    match = re.search(r"^samples/s (\S+) MB/s (\S+) size (\d+) items (\d+)$", out, re.M)
    if not match:
        sys.exit(f"transport.py: no samples/s line in:\n{out}")
    return float(match.group(1)), int(match.group(3)), int(match.group(4))


def ddsperf_throughput(bench, size, seconds, work):
    """ddsperf pub and sub, each with its own participant index of the same run configuration; the
    median of the subscriber's per-second rates, without the first and last seconds."""
    rid = run_id()
    domain = bench.pick_domain(2)
    envs = []
    for index in (0, 1):
        path = work / f"ddsperf-{index}.xml"
        path.write_text(bench.config(2, index, rid))
        envs.append(dict(os.environ, CYCLONEDDS_URI=f"file://{path}"))
    common = ["ddsperf", "-i", str(domain), "-k", "all", "-Q", "minmatch:1", "-Q", "initwait:30"]
    sub = subprocess.Popen(common + ["-D", str(seconds + 2), "sub"], stdout=subprocess.PIPE,
                           stderr=subprocess.STDOUT, text=True, env=envs[1])
    try:
        run_bounded(common + ["-D", str(seconds), "pub", "size", str(size)], seconds + 60, env=envs[0])
        out, _ = sub.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        stop(sub)
        sys.exit("transport.py: ddsperf sub did not end; stopped")
    finally:
        stop(sub)
    # "[pid] 3.001  size 1024 total 123 lost 0 delta 45 lost 0 rate 45.00 kS/s 368.64 Mb/s ..."
    rates = [float(r) * 1000 for r in re.findall(r"size \d+ total \d+ lost \d+ delta \d+ lost \d+ rate ([0-9.]+) kS/s", out)]
    if len(rates) < 3:
        sys.exit(f"transport.py: ddsperf sub printed under 3 rates:\n{out[-2000:]}")
    return statistics.median(rates[1:-1])


def throughput(args):
    bench = Bench(args.bin)
    if shutil.which("ddsperf") is None:
        sys.exit("transport.py: no ddsperf on PATH (Debian: cyclonedds-tools)")
    rows = []
    work = Path(tempfile.mkdtemp(prefix="wsntrack-transport-"))
    try:
        for size in args.sizes:
            decoded, raw, theirs = [], [], []
            for k in range(args.repeats):
                print(f"size {size}: run {k + 1}/{args.repeats} ...", file=sys.stderr, flush=True)
                rate, bytes_, items = wsntrack_throughput(bench, size, args.seconds, False, args.sample, args.batching)
                decoded.append(rate)
                raw.append(wsntrack_throughput(bench, size, args.seconds, True, args.sample, args.batching)[0])
                theirs.append(ddsperf_throughput(bench, bytes_, args.seconds, work))
            rows.append((size, bytes_, items, *map(statistics.median, (decoded, raw, theirs))))
    finally:
        shutil.rmtree(work, ignore_errors=True)
    writer = "batching writer" if args.batching else "a flush per write"
    print(f"{args.sample} batches, {writer}; medians of {args.repeats} runs of {args.seconds} s each; samples/s (MB/s = samples/s x serialized bytes / 10^6);"
          " ratio: wsntrack decoded / ddsperf")
    print("| size | items | bytes | wsntrack decoded | wsntrack raw | ddsperf | ratio | ratio raw |")
    print("|---|---|---|---|---|---|---|---|")
    for size, bytes_, items, decoded, raw, theirs in rows:
        def cell(rate):
            return f"{rate:.0f} ({rate * bytes_ / 1e6:.1f} MB/s)"
        print(f"| {size} | {items} | {bytes_} | {cell(decoded)} | {cell(raw)} | {cell(theirs)} | {decoded / theirs:.2f} | "
              f"{raw / theirs:.2f} |")
    return 0


# --- lockstep --------------------------------------------------------------------------------------

def cluster_shape(processes):
    """Tiles and supernodes of a cluster of `processes` role processes (network and aggregator
    are the other two): as many tiles as supernodes, the odd one a tile."""
    roles = processes - 2
    return (roles + 1) // 2, roles // 2


def quiet_scenario(tiles, supernodes, ticks):
    """A 40 x 40 field with no targets and noise-free sensors: no readings, no tracks, so a tick
    costs the lockstep's messages and little else. Supernodes on a grid, tiles over 2 Rs cells."""
    side = 1
    while side * side < supernodes:
        side += 1
    step = 40 / side
    spots = [(step * (i % side) + step / 2, step * (i // side) + step / 2) for i in range(supernodes)]
    lines = [f"name: lockstep_{tiles}t_{supernodes}s",
             "region: {x_min: 0, y_min: 0, x_max: 40, y_max: 40}",
             "sensors: {layout: grid, spacing: 1}",
             "sensor_model: {alpha: 2, gamma: 1, eta: 2, sensing_range: 1.5, noise_sigma: 0}",
             "network: {communication_range: 11.6, pte: 0, pde: 0}",
             "tracker: {engine: gnn}",
             "supernodes:"]
    lines += [f"  - {{x: {x:g}, y: {y:g}}}" for x, y in spots]
    lines += [f"run: {{ticks: {ticks}, seed: 1, node_processes: {tiles}}}"]
    return "\n".join(lines) + "\n"


def wsntrack_ticks_per_s(wsntrack, processes, ticks, in_flight, work, timeout):
    tiles, supernodes = cluster_shape(processes)
    scenario = work / f"lockstep-{processes}.yaml"
    scenario.write_text(quiet_scenario(tiles, supernodes, ticks))
    out = work / f"run-{processes}"
    shutil.rmtree(out, ignore_errors=True)
    overrides = ["--set", f"run.max_ticks_in_flight={in_flight}"] if in_flight else []
    run_bounded([wsntrack, "run", scenario, "--no-plot", "--out", out] + overrides, timeout)
    ticks_per_s = json.loads((out / "metrics.json").read_text())["timing"]["ticks_per_s"]
    shutil.rmtree(out)
    return ticks_per_s


def barrier_ticks_per_s(bench, processes, ticks, timeout):
    """N barrier processes on one domain; the median of their ticks/s (they end within a tick)."""
    rid = run_id()
    domain = bench.pick_domain(processes + 1)
    command = [bench.exe, "barrier", "--processes", str(processes), "--ticks", str(ticks), "--domain", str(domain),
               "--run-id", str(rid), "--timeout", str(timeout)]
    started = [subprocess.Popen(command + ["--index", str(i)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
               for i in range(processes)]
    deadline = time.monotonic() + timeout
    rates, failures = [], []
    try:
        for process in started:
            try:
                out, err = process.communicate(timeout=max(1, deadline - time.monotonic()))
            except subprocess.TimeoutExpired:
                failures.append(f"pid {process.pid} took over {timeout} s")
                break
            match = re.search(r"ticks/s ([0-9.]+)$", out, re.M)
            if process.returncode != 0 or not match:
                failures.append(f"pid {process.pid} exit {process.returncode}: {err.strip()[-500:]}")
                break
            rates.append(float(match.group(1)))
    finally:
        for process in started:
            stop(process)
    if failures:
        sys.exit(f"transport.py: barrier of {processes}: " + "; ".join(failures))
    return statistics.median(rates)


def lockstep(args):
    bench = Bench(args.bin)
    wsntrack = Path(args.bin) / "wsntrack"
    if not wsntrack.exists():
        sys.exit(f"transport.py: no {wsntrack}; build it or give --bin")
    rows = []
    work = Path(tempfile.mkdtemp(prefix="wsntrack-lockstep-"))
    try:
        for n in args.processes:
            if n < 4:
                sys.exit("transport.py: a cluster has at least 4 processes (a tile, the network, a supernode, the aggregator)")
            ours, plain = [], []
            for k in range(args.repeats):
                print(f"{n} processes: run {k + 1}/{args.repeats} ...", file=sys.stderr, flush=True)
                ours.append(wsntrack_ticks_per_s(wsntrack, n, args.ticks, args.in_flight, work, args.timeout))
                plain.append(barrier_ticks_per_s(bench, n, args.ticks, args.timeout))
            rows.append((n, *cluster_shape(n), statistics.median(ours), statistics.median(plain)))
    finally:
        shutil.rmtree(work, ignore_errors=True)
    in_flight = args.in_flight or "default"
    print(f"medians of {args.repeats} runs of {args.ticks} ticks, run.max_ticks_in_flight {in_flight}; "
          "ratio = cost per tick of wsntrack / of the barrier")
    print("| processes | tiles | supernodes | wsntrack ticks/s | ms/tick | barrier ticks/s | ms/tick | ratio |")
    print("|---|---|---|---|---|---|---|---|")
    for n, tiles, supernodes, ours, plain in rows:
        print(f"| {n} | {tiles} | {supernodes} | {ours:.1f} | {1000 / ours:.2f} | {plain:.1f} | {1000 / plain:.2f} | "
              f"{plain / ours:.2f} |")
    return 0


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    shared = argparse.ArgumentParser(add_help=False)
    shared.add_argument("--bin", default=str(SOURCE / "build" / "bin"),
                        help="directory of wsn_transport_bench and wsntrack (default: %(default)s)")
    shared.add_argument("--repeats", type=int, default=3, help="runs per row; the table gives medians (default: 3)")
    modes = parser.add_subparsers(dest="mode", required=True)
    tp = modes.add_parser("throughput", parents=[shared], help="report batches against ddsperf")
    tp.add_argument("--sizes", nargs="+", type=size_bytes, default=[256, 1024, 4096, 16384],
                    help="serialized sample sizes (default: 256 1k 4k 16k)")
    tp.add_argument("--sample", choices=["report", "boundary"], default="report",
                    help="report: a tile's ReportBatch; boundary: the flat SensorBoundary, to compare (default: report)")
    tp.add_argument("--batching", action="store_true",
                    help="wsntrack's writer packs samples into datagrams until a flush, as ddsperf's always does; "
                         "without it, every write is sent at once, as the roles' writers do")
    tp.add_argument("--seconds", type=int, default=10, help="publishing time per run, at least 3 (default: 10)")
    ls = modes.add_parser("lockstep", parents=[shared], help="wsntrack's lockstep against a plain barrier")
    ls.add_argument("--processes", nargs="+", type=int, default=[8, 16, 32, 64, 70], help="N (default: 8 16 32 64 70)")
    ls.add_argument("--ticks", type=int, default=200, help="ticks per run (default: 200)")
    ls.add_argument("--in-flight", type=int, default=0,
                    help="wsntrack's run.max_ticks_in_flight; 1: no pipelining, like the barrier (default: the scenario's, 3)")
    ls.add_argument("--timeout", type=int, default=300, help="seconds one run may take before it is stopped (default: 300)")
    args = parser.parse_args(argv)
    if args.repeats < 1:
        sys.exit("transport.py: --repeats must be at least 1")
    if args.mode == "throughput" and args.seconds < 3:
        sys.exit("transport.py: --seconds must be at least 3")
    return throughput(args) if args.mode == "throughput" else lockstep(args)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
