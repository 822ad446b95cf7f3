"""A sweep spec (sweeps/*.yaml), read strictly: the composed YAML nodes keep their lines, so that an
unknown key or a wrong type fails with SPEC:LINE: what was expected before anything runs."""

import math
import re
from pathlib import Path

from .common import REPO, UsageError, parse_seeds
from .metrics import DEFAULT_METRICS, metric_sources

SPEC_KEYS = ("scenario", "grid", "engines", "seeds", "set", "metrics", "x", "in_process", "title", "notes",
             "reference")
REFERENCE_KEYS = ("metric", "value", "at", "label")
KEY_PATTERN = re.compile(r"[A-Za-z_][A-Za-z0-9_]*(\[\d+\])?(\.[A-Za-z_][A-Za-z0-9_]*(\[\d+\])?)*")
TAG = "tag:yaml.org,2002:"


class SpecError(Exception):
    """A spec that cannot be run: reported as FILE:LINE: what was expected."""

    def __init__(self, path, line, message):
        # A spec built from flags has no file: the message alone (it names the option).
        super().__init__(message if path is None else f"{path}:{line}: {message}" if line else f"{path}: {message}")


def number(text):
    try:
        value = float(text)
    except ValueError:
        return None
    return value if math.isfinite(value) else None


def same_value(a, b):
    """Two grid values as written: equal as text, or as numbers (0.40 and 0.4)."""
    return a == b or (number(a) is not None and number(a) == number(b))


class Spec:
    """A sweep spec, validated; every value of the grid and of set is the scalar's text as written."""

    def __init__(self, path):
        self.path = path
        self.scenario = None  # resolved Path
        self.scenario_line = None
        self.grid = []  # [(key, [values], key line, [value lines])]
        self.engines = None
        self.engine_lines = []
        self.seeds = [1]
        self.fixed = []  # [(key, value)]
        self.fixed_lines = {}  # key -> line (none for a --set of the command line)
        self.metrics = list(DEFAULT_METRICS)
        self.x = None  # a metric measured per run to plot the others against, instead of the swept value
        self.in_process = False
        self.title = ""
        self.notes = ""
        self.references = []  # [{"metric", "value", "at": {key: value}, "label"}]


def load_spec(path):
    """The spec in `path`, validated (Spec); UsageError without PyYAML or for an unreadable file,
    SpecError (SPEC:LINE) for anything the spec gets wrong."""
    try:
        import yaml
    except ImportError:
        raise UsageError(f"{path}: reading a spec needs PyYAML (Debian: apt-get install python3-yaml); run the "
                         "tool with /usr/bin/python3") from None
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as error:
        raise UsageError(f"{path}: cannot read ({error})") from None
    try:
        root = yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.MarkedYAMLError as error:
        mark = error.problem_mark or error.context_mark
        raise SpecError(path, mark.line + 1 if mark else None, f"malformed YAML: {error.problem or error}") from None
    except yaml.YAMLError as error:
        raise SpecError(path, None, f"malformed YAML: {error}") from None
    except RecursionError:  # PyYAML's composer recurses once per level of nesting
        raise SpecError(path, None, "malformed YAML: nested deeper than the reader follows") from None
    return SpecReader(path, yaml).read(root)


class SpecReader:
    """Reads the composed YAML nodes (for their lines) into a Spec; SpecError on anything else."""

    def __init__(self, path, yaml):
        self.path = path
        self.yaml = yaml

    def fail(self, node, message):
        raise SpecError(self.path, node.start_mark.line + 1 if node is not None else 1, message)

    @staticmethod
    def line(node):
        return node.start_mark.line + 1

    def kind(self, node):
        if isinstance(node, self.yaml.MappingNode):
            return "a mapping"
        if isinstance(node, self.yaml.SequenceNode):
            return "a list"
        tag = node.tag[len(TAG):] if node.tag.startswith(TAG) else node.tag
        return {"str": f"the string '{node.value}'", "int": f"the integer {node.value}",
                "float": f"the number {node.value}", "bool": f"the boolean {node.value}",
                "null": "nothing (null)"}.get(tag, f"'{node.value}' ({tag})")

    def tag(self, node):
        return node.tag[len(TAG):] if isinstance(node, self.yaml.ScalarNode) and node.tag.startswith(TAG) else None

    def items(self, node, what, allowed=None):
        if not isinstance(node, self.yaml.MappingNode):
            self.fail(node, f"{what}: expected a mapping, got {self.kind(node)}")
        seen = {}
        result = []
        for key, value in node.value:
            if self.tag(key) != "str":
                self.fail(key, f"{what}: expected a key name, got {self.kind(key)}")
            if key.value in seen:
                self.fail(key, f"{what}: '{key.value}' given twice (first on line {seen[key.value]})")
            if allowed is not None and key.value not in allowed:
                self.fail(key, f"unknown key '{key.value}' in {what}; expected one of: {', '.join(allowed)}")
            seen[key.value] = self.line(key)
            result.append((key, value))
        return result

    def string(self, node, what):
        if self.tag(node) != "str" or not node.value.strip():
            self.fail(node, f"{what}: expected a non-empty string, got {self.kind(node)}")
        return node.value

    def scalar(self, node, what):
        """A --set value: any scalar but null, as written."""
        if self.tag(node) is None or self.tag(node) == "null" or not node.value.strip():
            self.fail(node, f"{what}: expected one value (a number, a word or a string), got {self.kind(node)}")
        return node.value

    def sequence(self, node, what, expected="a list"):
        if not isinstance(node, self.yaml.SequenceNode):
            self.fail(node, f"{what}: expected {expected}, got {self.kind(node)}")
        if not node.value:
            self.fail(node, f"{what}: expected a non-empty list")
        return node.value

    def set_key(self, node, what):
        key = node.value
        if not KEY_PATTERN.fullmatch(key):
            self.fail(node, f"{what}: expected a scenario key such as network.pte or supernodes[0].x, got '{key}'")
        if key == "tracker.engine":
            self.fail(node, f"{what}: tracker.engine: choose the engines with 'engines:', not here")
        if key == "run.seed":
            self.fail(node, f"{what}: run.seed: choose the seeds with 'seeds:', not here")
        return key

    def read(self, root):
        spec = Spec(self.path)
        if root is None:
            raise SpecError(self.path, 1, "expected a mapping with at least 'scenario' and 'grid', got an empty file")
        fields = dict((key.value, (key, value)) for key, value in self.items(root, "the spec", SPEC_KEYS))
        for required in ("scenario", "grid"):
            if required not in fields:
                self.fail(root, f"the spec: '{required}' is missing (required: scenario, grid)")
        key, node = fields["scenario"]
        spec.scenario = self.scenario(node)
        spec.scenario_line = self.line(node)
        self.grid(spec, *fields["grid"])
        if "engines" in fields:
            engines = self.sequence(fields["engines"][1], "engines")
            spec.engines = [self.string(e, "engines") for e in engines]
            spec.engine_lines = [self.line(e) for e in engines]
            for i, engine in enumerate(spec.engines):
                if not re.fullmatch(r"[A-Za-z0-9_.-]+", engine):
                    self.fail(engines[i], f"engines: expected an engine name such as mcmcda, got '{engine}'")
                if engine in spec.engines[:i]:
                    self.fail(engines[i], f"engines: '{engine}' given twice")
        if "seeds" in fields:
            spec.seeds = self.seeds(fields["seeds"][1])
        if "set" in fields:
            for key, value in self.items(fields["set"][1], "set"):
                name = self.set_key(key, "set")
                if any(name == k for k, *_ in spec.grid):
                    self.fail(key, f"set: {name} is swept by the grid; give it in one place")
                spec.fixed.append((name, self.scalar(value, f"set: {name}")))
                spec.fixed_lines[name] = self.line(key)
        if "metrics" in fields:
            nodes = self.sequence(fields["metrics"][1], "metrics")
            spec.metrics = []
            for node in nodes:
                metric = self.string(node, "metrics")
                if metric not in metric_sources():
                    self.fail(node, f"metrics: unknown metric '{metric}'; expected one of: {', '.join(metric_sources())}")
                if metric in spec.metrics:
                    self.fail(node, f"metrics: '{metric}' given twice")
                spec.metrics.append(metric)
        if "x" in fields:
            self.x_axis(spec, fields["x"][1])
        if "in_process" in fields:
            node = fields["in_process"][1]
            if self.tag(node) != "bool":
                self.fail(node, f"in_process: expected true or false, got {self.kind(node)}")
            spec.in_process = node.value.lower() in ("true", "yes", "on", "y")
        for name in ("title", "notes"):
            if name in fields:
                setattr(spec, name, self.string(fields[name][1], name))
        if "reference" in fields:
            for node in self.sequence(fields["reference"][1], "reference"):
                spec.references.append(self.reference(spec, node))
        return spec

    def x_axis(self, spec, node):
        """x: a metric every run measures (delivery_ratio), the plots' x axis instead of the swept
        value; added to the metrics when they lack it."""
        metric = self.string(node, "x")
        if metric not in metric_sources():
            self.fail(node, f"x: unknown metric '{metric}'; expected one of: {', '.join(metric_sources())}")
        if len(spec.grid) != 1:
            self.fail(node, "x: a measured x axis needs a grid of one key (line plots); this grid has "
                      f"{len(spec.grid)}")
        spec.x = metric
        if metric not in spec.metrics:
            spec.metrics.append(metric)

    def scenario(self, node):
        text = self.string(node, "scenario")
        given = Path(text)
        # Beside the spec; else above it, where sweeps/ and scenarios/ sit side by side (the
        # repository, and an installed data directory); else in the repository of this package.
        above = self.path.resolve().parent.parent
        repository = REPO if (REPO / "scenarios").is_dir() else None
        candidates = [given] if given.is_absolute() else \
            [self.path.parent / given, above / given] + ([repository / given] if repository else [])
        for candidate in candidates:
            try:
                if candidate.is_file():
                    return candidate.resolve()
            except OSError as error:  # a name too long for the file system: found by readers_property_test.py
                self.fail(node, f"scenario: no file {text} ({error.strerror})")
        self.fail(node, f"scenario: no file {text} " +
                  ("" if given.is_absolute() else
                   f"beside the spec (in {self.path.parent.resolve()}), above it (in {above})" +
                   (f" or in the repository ({repository})" if repository else "")))

    def grid(self, spec, key_node, node):
        entries = self.items(node, "grid")
        if len(entries) not in (1, 2):
            self.fail(key_node if not entries else node,
                      f"grid: expected 1 or 2 swept keys (a line plot or a heat map), got {len(entries)}")
        for key, values in entries:
            name = self.set_key(key, "grid")
            nodes = self.sequence(values, f"grid: {name}", "a list of values such as [0, 0.2, 0.4]")
            texts = []
            for value in nodes:
                text = self.scalar(value, f"grid: {name}")
                if any(same_value(text, t) for t in texts):
                    self.fail(value, f"grid: {name}: the value {text} is given twice")
                texts.append(text)
            spec.grid.append((name, texts, self.line(key), [self.line(v) for v in nodes]))

    def seeds(self, node):
        tag = self.tag(node)
        if tag == "int":
            return self.seed_list([node])
        if tag == "str":
            try:
                return parse_seeds(node.value)
            except UsageError as error:
                self.fail(node, "seeds: " + str(error).replace("--seeds: ", ""))
        if isinstance(node, self.yaml.SequenceNode):
            return self.seed_list(self.sequence(node, "seeds"))
        self.fail(node, f"seeds: expected seeds like 1-10, 3 or [1, 4, 9], got {self.kind(node)}")

    def seed_list(self, nodes):
        seeds = []
        for node in nodes:
            if self.tag(node) != "int" or not node.value.isdigit() or int(node.value) >= 2**64:
                self.fail(node, f"seeds: expected a seed, an integer in 0 .. 2^64 - 1, got {self.kind(node)}")
            if int(node.value) in seeds:
                self.fail(node, f"seeds: {node.value} given twice")
            seeds.append(int(node.value))
        return seeds

    def reference(self, spec, node):
        fields = dict((key.value, (key, value)) for key, value in self.items(node, "reference", REFERENCE_KEYS))
        if "label" not in fields:
            self.fail(node, "reference: 'label' is missing (what the line stands for, e.g. the paper's statement)")
        if "value" not in fields and "at" not in fields:
            self.fail(node, "reference: expected 'value' (with 'metric'), 'at', or both")
        reference = {"metric": None, "value": None, "at": {}, "label": self.string(fields["label"][1], "reference: label"),
                     "line": self.line(node)}
        if "metric" in fields:
            metric_node = fields["metric"][1]
            reference["metric"] = self.string(metric_node, "reference: metric")
            if reference["metric"] not in spec.metrics:
                self.fail(metric_node, f"reference: metric '{reference['metric']}' is not one of the sweep's metrics "
                          f"({', '.join(spec.metrics)})")
        if "value" in fields:
            value_node = fields["value"][1]
            if self.tag(value_node) not in ("int", "float") or number(value_node.value) is None:
                self.fail(value_node, f"reference: value: expected a number, got {self.kind(value_node)}")
            if reference["metric"] is None:
                self.fail(value_node, "reference: a 'value' needs the 'metric' it is a value of")
            reference["value"] = number(value_node.value)
        if "at" in fields:
            for key, value in self.items(fields["at"][1], "reference: at"):
                swept = [entry for entry in spec.grid if entry[0] == key.value]
                if not swept:
                    self.fail(key, f"reference: at: '{key.value}' is not a key of the grid "
                              f"({', '.join(k for k, *_ in spec.grid)})")
                text = self.scalar(value, f"reference: at: {key.value}")
                if not any(same_value(text, v) for v in swept[0][1]) and \
                        (number(text) is None or any(number(v) is None for v in swept[0][1])):
                    self.fail(value, f"reference: at: {key.value}: {text} is not one of the grid's values "
                              "(and the grid is not numeric)")
                reference["at"][key.value] = text
        return reference


