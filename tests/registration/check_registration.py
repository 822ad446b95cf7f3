#!/usr/bin/python3
"""Guard against Catch2 cases that ctest never runs: for every Catch2 binary, the ctest tests
registered for it must be exactly its cases, each selecting exactly one case.

A name with an unbalanced '[' or a ';' breaks catch_discover_tests silently: CMake's list
splitting glues or splits names, ctest registers a test that matches no case, Catch2 prints
"No tests ran" and exits 0, and ctest reports 100 %. This script makes that a failure.

Usage: check_registration.py --ctest CTEST --build-dir DIR BINARY...
Exit status: 0 when every binary's registration is exact, 1 when any is not, 2 on bad usage.
"""

import argparse
import concurrent.futures
import json
import os
import subprocess
import sys

# ctest prints a test's name in every log line; longer names make the CI log unreadable.
MAX_NAME_LENGTH = 200
NO_TESTS_FLAG = ["--warn", "NoTests"]


def ctest_tests(ctest, build_dir):
    """The tests ctest would run in build_dir, as (name, command, properties)."""
    out = subprocess.run([ctest, "--show-only=json-v1"], cwd=build_dir, check=True, capture_output=True, text=True)
    return [(t["name"], t.get("command", []), {p["name"]: p.get("value") for p in t.get("properties", [])})
            for t in json.loads(out.stdout).get("tests", [])]


def list_cases(binary, spec=None):
    """The case names Catch2 selects with spec (all cases without one)."""
    args = [binary] + ([spec] if spec is not None else []) + ["--list-test-names-only"]
    out = subprocess.run(args, capture_output=True, text=True, timeout=60)
    return [line.strip() for line in out.stdout.splitlines() if line.strip()]


def is_elf(path):
    try:
        with open(path, "rb") as f:
            return f.read(4) == b"\x7fELF"
    except OSError:
        return False


def check(ctest, build_dir, binaries):
    """Returns (problems, summary lines)."""
    problems, summary = [], []
    tests = ctest_tests(ctest, build_dir)
    known = {os.path.realpath(b): b for b in binaries}
    by_binary = {real: [] for real in known}
    build_root = os.path.realpath(build_dir)
    for name, command, properties in tests:
        if len(name) > MAX_NAME_LENGTH:
            problems.append(f"ctest test name of {len(name)} characters (at most {MAX_NAME_LENGTH}): {name[:120]}...")
        if not command:
            problems.append(f"ctest test '{name[:120]}' has no command")
            continue
        exe = os.path.realpath(command[0])
        if exe in by_binary:
            by_binary[exe].append((name, command))
            # A Catch2 case that ctest may skip, invert or not run at all is not a case that ran.
            for hiding in ("DISABLED", "WILL_FAIL", "SKIP_RETURN_CODE", "SKIP_REGULAR_EXPRESSION"):
                if properties.get(hiding) not in (None, False, "OFF", "0"):
                    problems.append(f"ctest test '{name[:120]}' has {hiding}={properties[hiding]}")
        elif exe.startswith(build_root + os.sep) and is_elf(exe):
            problems.append(f"ctest test '{name[:120]}' runs {command[0]}, a binary of this build the guard does not "
                            "know: register Catch2 binaries with wsn_catch_tests() (tests/CMakeLists.txt)")

    for real, binary in known.items():
        cases = list_cases(binary)
        registered = by_binary[real]
        label = os.path.basename(binary)
        if not cases:
            problems.append(f"{label}: --list-test-names-only lists no case")
        names = [name for name, _ in registered]
        for missing in sorted(set(cases) - set(names)):
            problems.append(f"{label}: case never run by ctest: {missing}")
        for extra in sorted(set(names) - set(cases)):
            problems.append(f"{label}: ctest test matches no case by name: {extra[:160]}")
        for name, command in registered:
            if not any(command[i:i + 2] == NO_TESTS_FLAG for i in range(len(command))):
                problems.append(f"{label}: ctest test '{name[:120]}' lacks --warn NoTests")

        # Each registered spec must select exactly its own case, as ctest will run it.
        def selected(entry):
            name, command = entry
            return name, list_cases(binary, command[1] if len(command) > 1 else None)

        exact = 0
        with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 2) as pool:
            for name, picked in pool.map(selected, registered):
                if picked == [name]:
                    exact += 1
                else:
                    problems.append(f"{label}: ctest test '{name[:120]}' selects {len(picked)} cases "
                                    f"({'; '.join(p[:60] for p in picked[:3])})")
        summary.append(f"{label}: {len(cases)} cases, {len(registered)} ctest tests, {exact} select exactly their case")
    return problems, summary


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--ctest", required=True, help="the ctest executable")
    parser.add_argument("--build-dir", required=True, help="the directory ctest runs in")
    parser.add_argument("binaries", nargs="+", help="every Catch2 test binary of the build")
    args = parser.parse_args()
    problems, summary = check(args.ctest, args.build_dir, args.binaries)
    for line in summary:
        print(line)
    for line in problems:
        print("PROBLEM:", line)
    total = sum(int(line.split(": ")[1].split()[0]) for line in summary)
    print(f"{'FAIL' if problems else 'OK'}: {len(args.binaries)} Catch2 binaries, {total} cases, "
          f"{len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
