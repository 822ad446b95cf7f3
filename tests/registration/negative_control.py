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
    fixture = os.path.abspath(fixture)
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
    # The registration must really have happened (a good name among the ctest tests), and the guard
    # must blame exactly the bad names: the glued one, the split one, and not the good one.
    expected = ["case never run by ctest: a name with an unbalanced [ bracket",
                "case never run by ctest: a name; split in two by the semicolon",
                "ctest test matches no case by name: a name with an unbalanced [ bracket;a name after the bracket",
                "ctest test matches no case by name:  split in two by the semicolon"]
    missing = [e for e in expected if e not in guard.stdout]
    wrongly_blamed = "a plain name, registered fine" in guard.stdout
    registered = "wsn_registration_fixture: 5 cases, 4 ctest tests, 1 select exactly their case" in guard.stdout
    if guard.returncode != 1 or missing or wrongly_blamed or not registered:
        print(f"FAIL: the guard exited {guard.returncode} (expected 1); not reported: {missing}; "
              f"good name blamed: {wrongly_blamed}; fixture registered as expected: {registered}")
        return 1
    print("OK: the guard fails on the fixture's bad names, as it must")
    return 0


if __name__ == "__main__":
    sys.exit(main())
