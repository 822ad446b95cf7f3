"""What wsntrack knows, read from wsntrack itself: the catalogue `wsntrack components --json` prints
(every scenario key, sensor model, engine, association and metric with units, labels and defaults;
the metrics.json and network.json quantities a sweep tabulates; the columns of each output file;
the measurement kinds, target classes, observation fates and the track-id layout). The Python side
reads these facts here instead of restating them. Standard library only.

Where it comes from, the first that exists:
  1. the wsntrack executable given to load() (a sweep passes the one it runs);
  2. the file named by the environment variable WSNTRACK_CATALOGUE;
  3. catalogue.json beside this module (the build tree's and an installed package's copy);
  4. the executable named by WSNTRACK, the source tree's build/bin/wsntrack, `wsntrack` on PATH.
"""

import json
import os
import shutil
import subprocess
from pathlib import Path

from .rundir.tables import ToolMissing

VERSION = 1  # the catalogue_version this package reads
FILE_VARIABLE = "WSNTRACK_CATALOGUE"
_HERE = Path(__file__).resolve().parent
_loaded = {}  # source -> catalogue
_chosen = []  # the source use() made the default, if any


class CatalogueError(ToolMissing):
    """No catalogue could be found or read; the message says what to do."""


def _from_executable(executable):
    try:
        result = subprocess.run([str(executable), "components", "--json"], capture_output=True, text=True,
                                timeout=60, check=False)
    except OSError as error:
        raise CatalogueError(f"{executable}: cannot run it for the catalogue ({error.strerror})") from None
    if result.returncode != 0:
        raise CatalogueError(f"{executable} components --json failed (exit {result.returncode}): "
                             f"{result.stderr.strip() or 'no message'}; is it a wsntrack that has `components --json`?")
    return _parsed(result.stdout, f"{executable} components --json")


def _parsed(text, where):
    try:
        catalogue = json.loads(text)
    except json.JSONDecodeError as error:
        raise CatalogueError(f"{where}:{error.lineno}: malformed catalogue ({error.msg})") from None
    if not isinstance(catalogue, dict) or catalogue.get("catalogue_version") != VERSION:
        found = catalogue.get("catalogue_version") if isinstance(catalogue, dict) else None
        raise CatalogueError(f"{where}: expected a wsntrack catalogue of version {VERSION}, got version {found!r}")
    return catalogue


def use(wsntrack):
    """Makes load() without an argument read the catalogue of wsntrack `wsntrack` in this process
    (a sweep: the catalogue of the executable it runs)."""
    _chosen[:] = [("executable", str(wsntrack))]


def _default_source():
    if _chosen:
        return _chosen[0]
    if os.environ.get(FILE_VARIABLE):
        return ("file", os.environ[FILE_VARIABLE])
    if (_HERE / "catalogue.json").is_file():
        return ("file", str(_HERE / "catalogue.json"))
    for candidate in (os.environ.get("WSNTRACK"), _HERE.parent.parent / "build" / "bin" / "wsntrack",
                      shutil.which("wsntrack")):
        if candidate and os.access(candidate, os.X_OK) and not os.path.isdir(candidate):
            return ("executable", str(candidate))
    raise CatalogueError(f"no wsntrack catalogue: build wsntrack (./setup.sh build), or set WSNTRACK to the "
                         f"wsntrack executable or {FILE_VARIABLE} to the output of `wsntrack components --json`")


def load(wsntrack=None):
    """The catalogue as a dict (of wsntrack `wsntrack` when given), read once per source."""
    source = ("executable", str(wsntrack)) if wsntrack else _default_source()
    if source not in _loaded:
        kind, where = source
        if kind == "executable":
            _loaded[source] = _from_executable(where)
        else:
            try:
                text = Path(where).read_text(encoding="utf-8")
            except OSError as error:
                raise CatalogueError(f"{where}: cannot read the catalogue ({error.strerror})") from None
            _loaded[source] = _parsed(text, where)
    return _loaded[source]


def quantities(catalogue=None):
    """{name: quantity} of every number of metrics.json a sweep can tabulate, in the catalogue's
    order: name, title (a table column), label and unit (a figure's axis), path and defined (keys
    from the top of a stream's block in metrics.json), meaning."""
    catalogue = catalogue or load()
    return {q["name"]: q for metric in catalogue["metrics"] for q in metric["quantities"]}


def network_quantities(catalogue=None):
    """{name: quantity} of network.json's numbers (path: keys into network.json)."""
    catalogue = catalogue or load()
    return {q["name"]: q for q in catalogue["network_quantities"]}


def scenario_key(key, catalogue=None):
    """The catalogue's entry of a scenario key ("network.pte"): label, unit, default, range, meaning;
    for an engine or association parameter (tracker.params.NAME, aggregator.params.NAME) the first
    component's entry of that name; None for a key it does not list."""
    catalogue = catalogue or load()
    for entry in catalogue["scenario_keys"]:
        if entry["key"] == key:
            return entry
    for model in catalogue["sensor_models"]:
        for entry in model["keys"]:
            if entry["key"] == key:
                return entry
    for prefix, kind in (("tracker.params.", "engines"), ("aggregator.params.", "associations")):
        if key.startswith(prefix):
            for component in catalogue[kind]:
                for param in component["params"]:
                    if param["name"] == key[len(prefix):]:
                        return {"key": key, "label": param["name"], "unit": param["unit"],
                                "default": param["default"], "meaning": param["meaning"]}
    return None


def axis_label(label, unit):
    """A figure's axis label: the label, with its unit in brackets when it has one."""
    return f"{label} [{unit}]" if unit else label
