#!/usr/bin/python3
"""Per-label totals of a ctest run, for the end of the CI log: how many tests of each label passed,
failed or were skipped, and their summed time. Reads ctest's JUnit file (--output-junit) for
results and `ctest --show-only=json-v1` for the labels.

Usage: summary.py BUILD_DIR JUNIT_XML...
"""

import collections
import json
import os
import subprocess
import sys
import xml.etree.ElementTree as ElementTree


def main():
    build_dir, junits = sys.argv[1], [j for j in sys.argv[2:] if os.path.exists(j)]
    if not junits:
        print("no JUnit report (the stage did not run)")
        return 0
    shown = subprocess.run(["ctest", "--show-only=json-v1"], cwd=build_dir, check=True, capture_output=True, text=True)
    labels = {}
    for test in json.loads(shown.stdout).get("tests", []):
        found = [p["value"] for p in test.get("properties", []) if p.get("name") == "LABELS"]
        labels[test["name"]] = found[0] if found else ["(none)"]
    totals = collections.defaultdict(collections.Counter)
    skipped = []
    cases = [c for junit in junits for c in ElementTree.parse(junit).getroot().iter("testcase")]
    for case in cases:
        status = case.get("status", "run")
        if case.find("failure") is not None or case.find("error") is not None or status == "fail":
            outcome = "failed"
        elif case.find("skipped") is not None or status in ("notrun", "disabled"):
            outcome = "skipped"
            skipped.append(case.get("name"))
        else:
            outcome = "passed"
        for label in labels.get(case.get("name"), ["(unregistered)"]):
            totals[label][outcome] += 1
            totals[label]["seconds"] += float(case.get("time", 0) or 0)
    print(f"{'label':<14} {'passed':>7} {'failed':>7} {'skipped':>8} {'test s':>8}")
    for label in sorted(totals):
        t = totals[label]
        print(f"{label:<14} {t['passed']:>7} {t['failed']:>7} {t['skipped']:>8} {t['seconds']:>8.1f}")
    if skipped:
        # The doc tests skip only ./setup.sh lines (CI runs them as its own stages) and blocks marked
        # skip with a reason; the reason is in the test's log.
        print("skipped: " + ", ".join(skipped))
    return 0


if __name__ == "__main__":
    sys.exit(main())
