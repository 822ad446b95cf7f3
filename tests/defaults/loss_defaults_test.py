#!/usr/bin/python3
"""A first loss sweep with every parameter left to its derived default: no engine may track worse
without loss than with some.

Usage: loss_defaults_test.py BIN_DIR SOURCE_DIR WORK_DIR

Sweeps network.pte over 0 and 0.1 at pde = 0.3 on tests/defaults/new_user_loss.yaml (a 200 x 200
grid, four supernodes, 20 drawn targets), seeds 1-3, with every registered engine that accepts the
scenario (`wsntrack components --names engines`, then `wsntrack validate`), through tools/sweep.py
as a user runs it. Losing a tenth of the reports cannot help a tracker, so an engine whose mean
eps_K at pte = 0 is above its mean at pte = 0.1 by more than the seeds' spread (the larger of the
two standard deviations over the seeds) has a default that misjudges the network: before the
derived miss counts took delays into account, GNN deleted every track whose newest report was only
late and scored 0.75 at pte = 0 against 0.29 at pte = 0.1.
"""

import csv
import shutil
import statistics
import subprocess
import sys
from pathlib import Path

PTES = ("0", "0.1")
SEEDS = "1-3"


def engines_for(wsntrack, scenario):
    names = subprocess.run([wsntrack, "components", "--names", "engines"], check=True, capture_output=True,
                           text=True).stdout.split()
    accepted = [name for name in names
                if subprocess.run([wsntrack, "validate", scenario, "--set", f"tracker.engine={name}"],
                                  capture_output=True).returncode == 0]
    return names, accepted


def main():
    bin_dir, source_dir, work = (Path(a) for a in sys.argv[1:4])
    wsntrack = str(bin_dir / "wsntrack")
    scenario = str(source_dir / "tests/defaults/new_user_loss.yaml")
    names, engines = engines_for(wsntrack, scenario)
    if len(engines) < 2:
        print(f"FAIL: only {engines} of {names} accept {scenario}: nothing to compare")
        return 1
    out = work / "sweep"
    shutil.rmtree(work, ignore_errors=True)  # a stale sweep must not stand in for this one
    command = [str(source_dir / "tools/sweep.py"), "--scenario", scenario, "--seeds", SEEDS,
               "--engines", ",".join(engines), "--set-grid", "network.pte=" + ",".join(PTES),
               "--metrics", "eps_k", "--in-process", "--out", str(out), "-j", "2",
               "--wsntrack", wsntrack]
    print("$", " ".join(command), flush=True)
    subprocess.run(command, check=True)
    values = {}
    with open(out / "results.csv", newline="", encoding="utf-8") as results:
        for row in csv.DictReader(results):
            if row["status"] != "ok":
                print(f"FAIL: run {row} did not finish")
                return 1
            values.setdefault((row["engine"], row["network.pte"]), []).append(float(row["eps_k"]))
    failures = []
    print(f"{'engine':<10} {'pte':>4} {'mean eps_K':>10} {'sd':>7}  seeds")
    for engine in engines:
        summary = {}
        for pte in PTES:
            runs = values.get((engine, pte), [])
            if len(runs) != 3:
                failures.append(f"{engine} at pte {pte}: {len(runs)} runs, expected 3")
                continue
            summary[pte] = (statistics.mean(runs), statistics.stdev(runs))
            print(f"{engine:<10} {pte:>4} {summary[pte][0]:>10.4f} {summary[pte][1]:>7.4f}  "
                  + " ".join(f"{v:.4f}" for v in runs))
        if len(summary) == 2:
            (clean, clean_sd), (lossy, lossy_sd) = summary[PTES[0]], summary[PTES[1]]
            spread = max(clean_sd, lossy_sd)
            if clean - lossy > spread:
                failures.append(f"{engine}: eps_K {clean:.4f} at pte 0 is worse than {lossy:.4f} at pte 0.1 "
                                f"by {clean - lossy:.4f}, beyond the seeds' spread {spread:.4f}")
    for failure in failures:
        print("FAIL:", failure)
    if failures:
        return 1
    print(f"OK: {len(engines)} engines ({', '.join(engines)}), none worse at pte 0 than at pte 0.1")
    return 0


if __name__ == "__main__":
    sys.exit(main())
