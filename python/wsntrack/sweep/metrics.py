"""What a sweep can tabulate of a run: each metric's table title and where it comes from, a path into
metrics.json (docs/METRICS.md) or a function of the run's files (the report counts and the detection
errors), read through wsntrack.rundir."""

import math

from ..rundir import read_csv, read_json, read_observations

# The metrics a sweep can tabulate: name -> (table title, path into metrics.json, path of the flag
# that says whether the run defines it, or None). docs/METRICS.md defines each.
METRIC_SOURCES = {
    "eps_k": ("eps_K", ("eps_k",), ("metrics", "eps_k_defined")),
    "eps_x": ("eps_X", ("eps_x",), ("metrics", "eps_x_defined")),
    "eps_x_gated": ("eps_X gated", ("metrics", "eps_x_gated"), ("metrics", "eps_x_gated_defined")),
    "ospa": ("OSPA", ("ospa",), None),
    "gospa": ("GOSPA", ("gospa", "mean"), None),
    "mota": ("MOTA", ("clear_mot", "mota"), ("clear_mot", "mota_defined")),
    "motp": ("MOTP", ("clear_mot", "motp"), ("clear_mot", "motp_defined")),
    "id_switches": ("ID switches", ("clear_mot", "id_switches"), None),
    "fragmentations": ("fragmentations", ("clear_mot", "fragmentations"), None),
    "boundary_duplicates": ("boundary dup", ("boundary", "boundary", "duplicate_track_ticks"), None),
    "boundary_id_switches": ("boundary IDsw", ("boundary", "boundary", "id_switches"), None),
    "boundary_fragmentations": ("boundary frag", ("boundary", "boundary", "fragmentations"), None),
    "tlr": ("TLR", ("track_quality", "mean_tlr"), ("track_quality", "means_defined")),
    "tlr_length": ("TLR length", ("track_quality", "mean_tlr_length"), ("track_quality", "means_defined")),
    "position_error": ("<dx>", ("track_quality", "mean_position_error"), ("track_quality", "means_defined")),
}
# The same metrics of the settled stream (the fixed-lag, smoothed estimate; docs/METRICS.md, "Track
# streams"): settled_eps_k, settled_ospa, ...
METRIC_SOURCES.update({
    "settled_" + name: ("settled " + title, ("streams", "settled") + where,
                        ("streams", "settled") + defined if defined else None)
    for name, (title, where, defined) in list(METRIC_SOURCES.items())})


def _network(key):
    return lambda data, run_dir: read_json(run_dir / "network.json")[key]


def _received(data, run_dir):
    network = read_json(run_dir / "network.json")
    return network["sent"] - network["lost"] - network["unreachable"]


def _false_reports(data, run_dir):
    return sum(1 for row in read_observations(run_dir / "observations.csv") if row[8] == -1)


def _false_tracks_per_tick(data, run_dir):
    return data["clear_mot"]["false_positives"] / data["ticks"]


# Tracks that match no target, per tick (CLEAR-MOT's false positives over the run's ticks), as An et
# al. 2013 count them.
METRIC_SOURCES["false_per_tick"] = ("false tracks/tick", _false_tracks_per_tick, None)


def _of_target(target, key):
    def value(data, run_dir):
        for entry in data["track_quality"]["targets"]:
            if entry["id"] == target:
                return entry[key] if entry.get("errors_defined", True) or key == "tlr" else None
        return None
    return value


# One target's <dx> and TLR (track_quality.targets[] in metrics.json), for figures that follow one
# target (An et al. 2014 Fig. 15): position_error_0 is the target with id 0 (the first scripted).
for _target in range(10):
    METRIC_SOURCES[f"position_error_{_target}"] = (f"<dx> target {_target}", _of_target(_target, "mean_position_error"), None)
    METRIC_SOURCES[f"tlr_{_target}"] = (f"TLR target {_target}", _of_target(_target, "tlr"), None)

# Counts of the run's reports, as Oh et al. §VII-E gives them ("a total of 1174 observations and 603
# observations were false alarms", packets lost and received delayed): read from the run's
# network.json and observations.csv (README.md, "Run directory") instead of metrics.json.
METRIC_SOURCES.update({
    "reports": ("reports", _network("sent"), None),
    "false_reports": ("false reports", _false_reports, None),
    "reports_lost": ("reports lost", _network("lost"), None),
    "reports_received": ("reports received", _received, None),
    "reports_delayed": ("received delayed", _network("delayed"), None),
})


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
METRIC_SOURCES.update({
    "count_match": ("count right", lambda data, run_dir: _report_detection(data, run_dir)[0], None),
    "report_error": ("report err rms", lambda data, run_dir: _rms(_report_detection(data, run_dir)[1]), None),
    "report_error_median": ("report err median", lambda data, run_dir: _median(_report_detection(data, run_dir)[1]),
                            None),
    "report_error_count_right": ("report err rms, count right",
                                 lambda data, run_dir: _rms(_report_detection(data, run_dir)[2]), None),
})


def metric_value(metric, data, run_dir):
    """One metric of a run: a path into its metrics.json (`data`), or a function of `data` and the
    run directory (the report counts read its other files)."""
    _, where, defined = METRIC_SOURCES[metric]
    if callable(where):
        return where(data, run_dir)
    return None if defined and lookup(data, defined) is False else lookup(data, where)


def lookup(data, path):
    """The value at `path` (a tuple of keys) in nested dicts, or None where the path ends early."""
    for key in path:
        if not isinstance(data, dict):
            return None
        data = data.get(key)
    return data


# eps_X gated, not eq. 10 over every pair: a few far pairs of a miscount rule the ungated one (12.06
# against 0.665 gated on a first loss sweep, with intervals of +-5 to +-14 over three seeds).
DEFAULT_METRICS = ("eps_k", "eps_x_gated", "ospa")
