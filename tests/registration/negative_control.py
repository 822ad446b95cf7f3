#!/usr/bin/python3
"""Negative control of the registration guard: registers a fixture binary with bad case names
exactly as catch_discover_tests does (Catch2's own CatchAddTests.cmake) and checks that
check_registration.py fails on it, naming the cases ctest would never run.

Usage: negative_control.py CMAKE CTEST CATCH_ADD_TESTS FIXTURE_BINARY WORK_DIR
"""

import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    cmake, ctest, catch_add_tests, fixture, work = sys.argv[1:6]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    tests_file = os.path.join(work, "fixture_tests.cmake")
    subprocess.run([cmake, f"-DTEST_EXECUTABLE={fixture}", "-DTEST_EXTRA_ARGS=--warn;NoTests",
                    f"-DCTEST_FILE={tests_file}", "-DTEST_LIST=fixture_TESTS", f"-DTEST_WORKING_DIR={work}",
                    "-P", catch_add_tests], check=True)
    with open(os.path.join(work, "CTestTestfile.cmake"), "w") as f:
        f.write(f'include("{tests_file}")\n')
    guard = subprocess.run([sys.executable, os.path.join(HERE, "check_registration.py"), "--ctest", ctest,
                            "--build-dir", work, fixture], capture_output=True, text=True)
    print(guard.stdout, end="")
    expected = ["case never run by ctest: a name with an unbalanced [ bracket",
                "case never run by ctest: a name; split in two by the semicolon"]
    missing = [e for e in expected if e not in guard.stdout]
    if guard.returncode != 1 or missing:
        print(f"FAIL: the guard exited {guard.returncode} (expected 1) and did not report: {missing}")
        return 1
    print("OK: the guard fails on the fixture's bad names, as it must")
    return 0


if __name__ == "__main__":
    sys.exit(main())
