"""What a sweep can tabulate of a run: each metric's table title and where it comes from, a path into
metrics.json (docs/METRICS.md) or a function of the run's files (the report counts and the detection
errors), read through wsntrack.rundir."""

import math

from .. import catalogue
from ..rundir import read_csv, read_json, read_observations

def _catalogue_sources():
    """The metrics.json quantities of the catalogue (`wsntrack components --json`) as name -> (table
    title, path into metrics.json, path of the flag that says whether the run defines it, or None),
    each also of the settled stream (the fixed-lag, smoothed estimate; docs/METRICS.md, "Track
    streams") as settled_NAME; then network.json's numbers (reports, reports_lost, delivery_ratio, ...)."""
    document = catalogue.load()
    sources = {}
    for name, q in catalogue.quantities(document).items():
        sources[name] = (q["title"], tuple(q["path"]), tuple(q["defined"]) or None)
    settled = tuple(document["streams"]["settled"])
    sources.update({
        "settled_" + name: ("settled " + title, settled + where, settled + defined if defined else None)
        for name, (title, where, defined) in list(sources.items())})
    for name, q in catalogue.network_quantities(document).items():
        sources[name] = (q["title"], _network(q["path"]), None)
    return sources


def _network(path):
    def value(data, run_dir):
        document = read_json(run_dir / "network.json")
        for key in path:
            document = document[key]
        return document
    return value


def _received(data, run_dir):
    network = read_json(run_dir / "network.json")
    return network["sent"] - network["lost"] - network["unreachable"]


def _false_reports(data, run_dir):
    return sum(1 for row in read_observations(run_dir / "observations.csv") if row[8] == -1)


def _false_tracks_per_tick(data, run_dir):
    return data["clear_mot"]["false_positives"] / data["ticks"]




def _of_target(target, key):
    def value(data, run_dir):
        for entry in data["track_quality"]["targets"]:
            if entry["id"] == target:
                return entry[key] if entry.get("errors_defined", True) or key == "tlr" else None
        return None
    return value




def _report_detection(data, run_dir):
    """(share of ticks whose number of reports made equals the number of targets, the localisation
    errors of the labelled reports against their target at the tick made, the same errors at the
    ticks whose count is right), from observations.csv and truth.csv; read once per run directory."""
    cached = _DETECTION_CACHE.get(run_dir)
    if cached is None:
        at, surplus = {}, {}  # surplus[t]: reports made at t minus targets at t
        for tick, target, x, y in read_csv(run_dir / "truth.csv", ["tick", "target", "x", "y"],
                                           [int, int, float, float]):
            at[(tick, target)] = (x, y)
            surplus[tick] = surplus.get(tick, 0) - 1
        errors = []  # (tick, distance)
        for tick, target, x, y in read_csv(run_dir / "observations.csv", ["tick_generated", "target", "x", "y"],
                                           [int, int, float, float]):
            surplus[tick] = surplus.get(tick, 0) + 1
            if (tick, target) in at:
                tx, ty = at[(tick, target)]
                errors.append((tick, math.hypot(x - tx, y - ty)))
        ticks = data["ticks"]
        same = sum(1 for t in range(1, ticks + 1) if surplus.get(t, 0) == 0)
        cached = (same / ticks, [e for _, e in errors], [e for t, e in errors if surplus.get(t, 0) == 0])
        _DETECTION_CACHE.clear()  # one run at a time: the metrics of a run are asked together
        _DETECTION_CACHE[run_dir] = cached
    return cached


_DETECTION_CACHE = {}


def _rms(errors):
    return math.sqrt(sum(e * e for e in errors) / len(errors)) if errors else None


def _median(errors):
    return sorted(errors)[len(errors) // 2] if errors else None


# What the sensors detect, before any tracker (ADMAN's "estimated total number" and localisation
# error): the share of ticks with as many reports as targets, and the rms and median distance of a
# labelled report from its target (false alarms left out), over every report and over the ticks
# whose count is right. Meaningful where a model reports each target once a tick (ADMAN, the fused
# reports of Oh eq. 6).
def _file_sources():
    """The quantities a sweep computes from a run's files rather than reads from metrics.json."""
    sources = {
        # Tracks that match no target, per tick (CLEAR-MOT's false positives over the run's ticks), as
        # An et al. 2013 count them.
        "false_per_tick": ("false tracks/tick", _false_tracks_per_tick, None),
        # Counts of the run's reports beside network.json's, as Oh et al. §VII-E gives them ("a total
        # of 1174 observations and 603 observations were false alarms"), from observations.csv.
        "false_reports": ("false reports", _false_reports, None),
        "reports_received": ("reports received", _received, None),
        "count_match": ("count right", lambda data, run_dir: _report_detection(data, run_dir)[0], None),
        "report_error": ("report err rms", lambda data, run_dir: _rms(_report_detection(data, run_dir)[1]), None),
        "report_error_median": ("report err median",
                                lambda data, run_dir: _median(_report_detection(data, run_dir)[1]), None),
        "report_error_count_right": ("report err rms, count right",
                                     lambda data, run_dir: _rms(_report_detection(data, run_dir)[2]), None),
    }
    # One target's <dx> and TLR (track_quality.targets[] in metrics.json), for figures that follow
    # one target (An et al. 2014 Fig. 15): position_error_0 is the target with id 0 (the first scripted).
    for target in range(10):
        sources[f"position_error_{target}"] = (f"<dx> target {target}", _of_target(target, "mean_position_error"),
                                               None)
        sources[f"tlr_{target}"] = (f"TLR target {target}", _of_target(target, "tlr"), None)
    return sources


_SOURCES = {}


def metric_sources():
    """Every metric a sweep can tabulate: name -> (table title, where, defined), `where` a path into
    metrics.json (a tuple of keys) or a function of (metrics.json's data, the run directory), and
    `defined` the path of the flag that says whether the run defines it, or None. The metrics.json
    and network.json ones come from the catalogue; docs/METRICS.md defines each."""
    if not _SOURCES:
        _SOURCES.update(_catalogue_sources())
        _SOURCES.update(_file_sources())
    return _SOURCES


def metric_label(metric):
    """A figure's axis label of a metric: the catalogue's label and unit, for a settled one prefixed
    "settled"; the table title for a quantity computed from the run's files."""
    name = metric[len("settled_"):] if metric.startswith("settled_") else metric
    found = catalogue.quantities().get(name) or catalogue.network_quantities().get(name)
    if found is None:
        return metric_sources()[metric][0]
    return catalogue.axis_label(("settled " if name != metric else "") + found["label"], found["unit"])


def __getattr__(name):
    if name == "METRIC_SOURCES":  # the table as a constant, for readers of older code
        return metric_sources()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def metric_value(metric, data, run_dir):
    """One metric of a run: a path into its metrics.json (`data`), or a function of `data` and the
    run directory (the report counts read its other files)."""
    _, where, defined = metric_sources()[metric]
    if callable(where):
        return where(data, run_dir)
    return None if defined and lookup(data, defined) is False else lookup(data, where)


def lookup(data, path):
    """The value at `path` (a tuple of keys) in nested dicts; KeyError naming the first key that is
    not there, so that a metric the catalogue misplaces never reads as undefined."""
    for i, key in enumerate(path):
        if not isinstance(data, dict) or key not in data:
            raise KeyError(f"metrics.json has no {'.'.join(path[:i + 1])}")
        data = data[key]
    return data


# eps_X gated, not eq. 10 over every pair: a few far pairs of a miscount rule the ungated one (12.06
# against 0.665 gated on a first loss sweep, with intervals of +-5 to +-14 over three seeds).
DEFAULT_METRICS = ("eps_k", "eps_x_gated", "ospa")
