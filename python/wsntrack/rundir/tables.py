"""The run directory's CSV and JSON files read by name, every problem reported as FILE[:LINE]: what
was expected. Standard library only: the ONERA table reads runs with it."""

import csv
import json
import math


class InputError(ValueError):
    """A missing or malformed input file; ``str(error)`` is ``FILE[:LINE]: what was expected``."""


class ToolMissing(ImportError):
    """A Python package a tool needs is not installed; the message says what to install."""


def require(path):
    """Raises InputError when the run-directory file `path` is missing."""
    if not path.is_file():
        raise InputError(f"{path}: missing (is {path.parent} a wsntrack run directory?)")


def _number(value, path, line, column, kind=float):
    try:
        number = kind(value)
    except (TypeError, ValueError):
        what = "a whole number" if kind is int else "a number"
        raise InputError(f"{path}:{line}: column '{column}' must be {what}, got '{value}'") from None
    if kind is float and not math.isfinite(number):
        raise InputError(f"{path}:{line}: column '{column}' must be finite, got '{value}'")
    return number


# Column types of read_table besides int, float and str: a whole number, or a finite number, or an
# empty field (None).
OPTIONAL_INT = "optional int"
OPTIONAL_FLOAT = "optional float"


def _convert(value, path, line, column, kind):
    if kind is str:
        return value
    if kind == OPTIONAL_INT:
        return None if value == "" else _number(value, path, line, column, int)
    if kind == OPTIONAL_FLOAT:
        return None if value == "" else _number(value, path, line, column, float)
    return _number(value, path, line, column, kind)


def _header_index(path, header, columns, expected):
    """{name: position} of a CSV header that has every one of `columns`."""
    if header is None:
        raise InputError(f"{path}:1: expected the header {expected}, got an empty file")
    index = {}
    for i, name in enumerate(header):
        if name in index:
            raise InputError(f"{path}:1: column '{name}' appears twice in the header")
        index[name] = i
    missing = [name for name, _ in columns if name not in index]
    if missing:
        raise InputError(f"{path}:1: expected the header {expected}, got '{','.join(header)}' "
                         f"(no column '{missing[0]}')")
    return index


def read_table(path, columns, optional=(), expected=None, check=None, check_header=None):
    """Rows of a CSV file, its columns found by header name so that a file with more columns (from a
    newer wsntrack) still reads. `columns`: (name, type) pairs the header must have; `optional`:
    (name, type, default) triples, read when the header has them, else `default` in every row. A
    type is int, float, str, OPTIONAL_INT or OPTIONAL_FLOAT. Returns (rows, present): every row a tuple in the order
    of `columns` then `optional`, and the set of the optional names the header has. `expected`
    describes the header in the message about a missing column (default: the names of `columns`);
    `check(row)`, when given, returns what is wrong with a converted row, or None, and
    `check_header(present)` what is wrong with the optional columns found."""
    require(path)
    if expected is None:
        expected = "'" + ",".join(name for name, _ in columns) + "'"
    rows = []
    with open(path, newline="", encoding="utf-8", errors="replace") as handle:
        reader = csv.reader(handle)
        try:
            header = next(reader, None)
            index = _header_index(path, header, columns, expected)
            present = {name for name, _, _ in optional if name in index}
            problem = check_header(present) if check_header else None
            if problem:
                raise InputError(f"{path}:1: {problem}")
            # One entry per output field: (index in the row, name, type), or (None, default, None).
            fields = [(index[name], name, kind) for name, kind in columns]
            fields += [(index[name], name, kind) if name in present else (None, default, None)
                       for name, kind, default in optional]
            for row in reader:
                line = reader.line_num
                if not row:
                    continue
                if len(row) != len(header):
                    raise InputError(
                        f"{path}:{line}: expected {len(header)} fields ({','.join(header)}), got {len(row)}")
                rows.append(tuple(name if i is None else _convert(row[i], path, line, name, kind)
                                  for i, name, kind in fields))
                problem = check(rows[-1]) if check else None
                if problem:
                    raise InputError(f"{path}:{line}: {problem}")
        except csv.Error as error:
            raise InputError(f"{path}:{reader.line_num}: malformed CSV ({error})") from None
    return rows, present


def read_csv(path, header, types):
    """Rows of a CSV file with the columns `header` (found by name), converted with `types` (None:
    kept as text)."""
    return read_table(path, [(name, kind or str) for name, kind in zip(header, types)])[0]


def read_header(path):
    """The column names of a CSV file's first line (empty for an empty file)."""
    require(path)
    with open(path, encoding="utf-8", errors="replace") as handle:
        return handle.readline().strip().split(",")


def read_json(path):
    """A JSON file of the run directory (metrics.json, network.json, run.json) as Python values."""
    require(path)
    try:
        return json.loads(path.read_text(encoding="utf-8"))
    except json.JSONDecodeError as error:
        raise InputError(f"{path}:{error.lineno}: malformed JSON ({error.msg})") from None
    except (OSError, UnicodeDecodeError) as error:
        raise InputError(f"{path}: cannot read ({error})") from None
    except (ValueError, RecursionError) as error:
        # An integer of more digits than Python converts (4300), or arrays nested deeper than its
        # parser recurses: found by tests/tools/readers_property_test.py.
        raise InputError(f"{path}: malformed JSON ({error})") from None
