#!/usr/bin/python3
"""Property tests (python3-hypothesis) of the Python tools' input readers: the run directory's CSV
and JSON readers (python/wsntrack/rundir, which plot_run.py, the sweep and onera_table.py read runs
with, scenario.yaml's reader among them) and the sweep spec reader (python/wsntrack/sweep/spec.py). Whatever the bytes of the file, a
reader returns its rows or raises the project's own error (rundir.InputError, sweep SpecError or
UsageError: FILE[:LINE]: what was expected) -- never IndexError, KeyError, TypeError, RecursionError
or any other exception, which a tool would print as a traceback.

Usage: readers_property_test.py SOURCE_DIR WORK_DIR [--examples N]

Each property runs N examples (default 200), derandomised, so that a run is deterministic and
bounded: ctest runs a few hundred, CI's fuzz stage (.ci/run) thousands. A failing example is
printed, shrunk, with the exception it raised; it becomes a case of readers_regression_test.py."""

import argparse
import json
import sys
import time
import traceback
from pathlib import Path

try:
    from hypothesis import HealthCheck, given, settings, strategies as st
except ImportError:
    # Never a skip: setup.sh installs python3-hypothesis, and a test that did not run is a failure.
    print("readers_property_test: python3-hypothesis is missing (./setup.sh installs it: apt-get install "
          "python3-hypothesis); run with /usr/bin/python3", file=sys.stderr)
    sys.exit(1)

# Fields that have broken CSV readers elsewhere: empty, signs, non-finite and huge numbers, other
# bases, quotes, separators and line ends inside a field, NUL, non-ASCII digits and letters.
TOKENS = ["", " ", "0", "-1", "1", "2", "7", "1.5", "-0.0", "1e308", "-1e308", "1e999", "nan", "inf", "-inf",
          "0x10", "1_000", "18446744073709551616", "3.4.5", "abc", '"', '""', '"a,b"', ",", "\r", "\n", "\x00",
          "\u0661\u0662", "\u00e9", "delivered", "lost", "human", "unknown", "g1", "0:5", "0.5"]


def token():
    return st.one_of(st.sampled_from(TOKENS), st.integers(-2**70, 2**70).map(str),
                     st.floats(allow_nan=True, allow_infinity=True).map(repr), st.text(max_size=6))


def csv_text(columns):
    """CSV text whose header is mostly the reader's columns (reordered, dropped, doubled, or with
    foreign ones) and whose rows are tokens, with ragged lengths; or any text at all."""
    header = st.lists(st.one_of(st.sampled_from(columns), token()), max_size=len(columns) + 3)
    structured = st.builds(
        lambda names, rows, ending: ending.join([",".join(names)] + [",".join(row) for row in rows]) + ending,
        st.one_of(st.permutations(columns), header),
        st.lists(st.lists(token(), max_size=len(columns) + 2), max_size=6),
        st.sampled_from(["\n", "\r\n", "\r"]))
    return st.one_of(structured, st.text(max_size=200))


def json_value():
    scalars = st.one_of(st.none(), st.booleans(), st.integers(-2**70, 2**70), st.floats(), st.text(max_size=8))
    return st.recursive(scalars, lambda inner: st.one_of(st.lists(inner, max_size=4),
                                                         st.dictionaries(st.sampled_from(JSON_KEYS) | st.text(max_size=5),
                                                                         inner, max_size=4)), max_leaves=20)


# metrics.json's keys the readers look up, so that random documents reach past the first lookup.
JSON_KEYS = ["metrics", "ospa_per_tick", "first_tick", "eps_k", "eps_x", "ospa_mean", "faults", "during",
             "first_tick", "last_tick", "what", "action"]


def json_text():
    """A JSON document: shaped like metrics.json with random values, a random value, one nested
    deeper than any parser recurses, or any text."""
    shaped = st.fixed_dictionaries({}, optional={
        "metrics": st.one_of(json_value(), st.fixed_dictionaries({}, optional={k: json_value() for k in JSON_KEYS})),
        "faults": st.one_of(json_value(), st.lists(st.fixed_dictionaries(
            {}, optional={"during": st.one_of(json_value(), st.fixed_dictionaries(
                {}, optional={"first_tick": json_value(), "last_tick": json_value()})),
                "what": json_value(), "action": json_value()}), max_size=3))})
    deep = st.integers(1, 200_000).map(lambda n: "[" * n + "]" * n)
    return st.one_of(shaped.map(json.dumps), json_value().map(json.dumps), deep, st.text(max_size=100))


def deep_yaml():
    """YAML nested deeper than a recursive reader follows, as a document or under a key."""
    return st.builds(lambda n, prefix: prefix + "[" * n + "]" * n, st.integers(1, 1500),
                     st.sampled_from(["", "grid: ", "region: "]))


def long_scenario_path():
    """A scenario name longer than the file system allows (ENAMETOOLONG, not ENOENT)."""
    return st.integers(1, 2000).map(lambda n: f"scenario: {'x' * n}.yaml\ngrid:\n  network.pte: [0, 0.2]\n")


class Properties:
    """The properties, each a function of hypothesis-drawn text; `expected` are the errors allowed."""

    def __init__(self, source_dir, work_dir):
        sys.path.insert(0, str(source_dir / "python"))
        from wsntrack import rundir
        from wsntrack.sweep import spec
        from wsntrack.sweep.common import UsageError
        self.rundir = rundir
        self.spec = spec
        self.input_errors = (rundir.InputError,)
        self.spec_errors = (spec.SpecError, UsageError)
        self.work = work_dir
        self.work.mkdir(parents=True, exist_ok=True)
        self.sweep_examples = sorted((source_dir / "sweeps").glob("*.yaml"))
        # The small ones: a scenario's size does not change how its lines are read.
        self.shipped_scenarios = [p for p in sorted((source_dir / "scenarios").glob("*.yaml")) if p.stat().st_size < 8000]

    def write(self, name, text):
        path = self.work / name
        path.write_text(text, encoding="utf-8", errors="surrogatepass")
        return path

    def expect(self, errors, read, *args):
        try:
            read(*args)
        except errors:
            pass

    def all(self):
        r = self.rundir
        track_columns = ["tick", "track", "label", "x", "y", "vx", "vy"] + list(r.COVARIANCE_COLUMNS) + \
            ["class", "class_probability"]
        return [
            ("tracks.csv", csv_text(track_columns), lambda t: self.expect(
                self.input_errors, r.read_tracks, self.write("tracks.csv", t))),
            ("tracks_supernode.csv", csv_text(track_columns + ["supernode"]), lambda t: self.expect(
                self.input_errors, r.read_tracks, self.write("tracks_supernode.csv", t), True)),
            ("truth.csv", csv_text(["tick", "target", "x", "y", "vx", "vy", "class"]), lambda t: self.expect(
                self.input_errors, r.read_truth, self.write("truth.csv", t))),
            ("observations.csv", csv_text(["tick_generated", "tick_delivered", "sensor", "supernode", "hops", "delay",
                                           "x", "y", "target", "fate"]), lambda t: self.expect(
                self.input_errors, r.read_observations, self.write("observations.csv", t))),
            ("metrics_per_tick.csv", csv_text(["tick", "truth_targets", "tracks", "ospa", "gospa"]), self.per_tick_csv),
            ("metrics.json (OSPA per tick)", json_text(), self.per_tick_json),
            ("metrics.json (summary)", json_text(), self.summary),
            ("sweep spec", self.spec_text(), self.sweep_spec),
            ("scenario.yaml", self.scenario_text(), self.scenario_yaml),
        ]

    def per_tick_csv(self, text):
        """metrics_per_tick.csv, read alone and as read_per_tick reads it for the charts."""
        path = self.write("metrics_per_tick.csv", text)
        self.expect(self.input_errors, self.rundir.read_metrics_per_tick, path)
        self.expect(self.input_errors, self.rundir.read_per_tick, self.work, {"ticks": 5}, [], [])
        path.unlink()

    def per_tick_json(self, text):
        """metrics.json's ospa_per_tick, which read_per_tick falls back on without metrics_per_tick.csv."""
        (self.work / "metrics_per_tick.csv").unlink(missing_ok=True)
        self.write("metrics.json", text)
        self.expect(self.input_errors, self.rundir.read_per_tick, self.work, {"ticks": 5}, [(1, 0, 0.0, 0.0, 0.0, 0.0)],
                    [])

    def summary(self, text):
        """metrics.json's headline for the charts' titles: never an error, values it cannot read left out."""
        self.write("metrics.json", text)
        self.rundir.read_metrics_summary(self.work)

    def spec_text(self):
        """A shipped spec with lines dropped, doubled or replaced; a spec of random keys and values; any text."""
        shipped = [path.read_text(encoding="utf-8") for path in self.sweep_examples]
        keys = list(self.spec.SPEC_KEYS) + list(self.spec.REFERENCE_KEYS) + ["network.pte", "run.ticks"]
        line = st.one_of(st.sampled_from([l for text in shipped for l in text.splitlines()]), token(),
                         st.builds(lambda k, v: f"{k}: {v}", st.sampled_from(keys), token()),
                         st.builds(lambda k: f"  - {k}", token()), st.just("scenario: " + "x" * 300))
        mutated = st.builds(lambda text, edits: self.edit(text.splitlines(), edits), st.sampled_from(shipped),
                            st.lists(st.tuples(st.integers(0, 40), st.sampled_from("drk"), line), max_size=6))
        return st.one_of(mutated, st.lists(line, max_size=12).map("\n".join), json_value().map(json.dumps),
                         st.text(max_size=200), deep_yaml(), long_scenario_path())

    @staticmethod
    def edit(lines, edits):
        for at, how, line in edits:
            at = at % (len(lines) + 1)
            if how == "d" and at < len(lines):
                del lines[at]
            elif how == "r" and at < len(lines):
                lines[at] = line
            else:
                lines.insert(at, line)
        return "\n".join(lines) + "\n"

    def scenario_text(self):
        """A run's scenario.yaml: a shipped scenario with lines dropped, doubled or replaced, or any text."""
        shipped = [path.read_text(encoding="utf-8") for path in self.shipped_scenarios]
        lines = sorted({l for text in shipped for l in text.splitlines()})
        line = st.one_of(st.sampled_from(lines), token(), st.builds(lambda l, t: l.split(":")[0] + ": " + t,
                                                                    st.sampled_from(lines), token()))
        mutated = st.builds(lambda text, edits: self.edit(text.splitlines(), edits), st.sampled_from(shipped),
                            st.lists(st.tuples(st.integers(0, 200), st.sampled_from("drk"), line), max_size=6))
        return st.one_of(mutated, deep_yaml(), st.text(max_size=200))

    def scenario_yaml(self, text):
        self.write("scenario.yaml", text)
        self.expect(self.input_errors, self.rundir.read_scenario, self.work)

    def sweep_spec(self, text):
        self.expect(self.spec_errors, self.spec.load_spec, self.write("spec.yaml", text))


def counting(check, counted):
    """`check` as a one-argument test for @given, counting the examples it is run on in `counted`."""
    def run(text):
        counted.append(1)
        check(text)
    return run


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("source_dir", type=Path)
    parser.add_argument("work_dir", type=Path)
    parser.add_argument("--examples", type=int, default=200, help="examples per property (default 200)")
    args = parser.parse_args()
    properties = Properties(args.source_dir.resolve(), args.work_dir.resolve())
    # Derandomised and without the example database: the same examples every run, nothing kept
    # between runs, so that CI's verdict depends on the tree alone.
    config = settings(max_examples=args.examples, deadline=None, derandomize=True, database=None,
                      suppress_health_check=list(HealthCheck), print_blob=False)
    failures = 0
    for name, strategy, check in properties.all():
        counted = []
        start = time.monotonic()
        try:
            config(given(strategy)(counting(check, counted)))()
            print(f"OK: {name}: {len(counted)} examples in {time.monotonic() - start:.1f} s")
        except Exception:  # the shrunk example's exception, which hypothesis re-raises: a finding
            failures += 1
            print(f"FAILED: {name}: an unexpected exception (the shrunk example is above it):", file=sys.stderr)
            traceback.print_exc()
    print(f"{failures} of {len(properties.all())} properties failed" if failures else "every property held")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
