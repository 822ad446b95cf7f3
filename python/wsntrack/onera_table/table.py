"""The ONERA table as Markdown lines: per target the paper's and our RSE and TLR with their deltas,
the class and its accuracy, the reported share; then the statistics the paper draws from Table II,
and the classification and stop mode sections."""

import statistics

from .blocks import class_order
from .pooling import class_accuracy
from .paper import PAPER_A1, PAPER_A2, PAPER_TARGETS

def confusion_lines(name, confusion):
    """The summed confusion matrix as a Markdown table: rows the true classes met, columns the declared
    classes that are a row or counted at least once, then "none"."""
    rows = sorted(confusion, key=class_order)
    declared = {d for row in confusion.values() for d in row if d != "none"}
    columns = sorted((d for d in declared
                      if d in confusion or any(row.get(d, 0) for row in confusion.values())), key=class_order)
    columns.append("none")
    lines = [f"| {name} true / declared | " + " | ".join(columns) + " |",
             "|---|" + "|".join("---:" for _ in columns) + "|"]
    for truth in rows:
        lines.append(f"| {truth} | " + " | ".join(str(confusion[truth].get(d, 0)) for d in columns) + " |")
    return lines


def fmt(value, digits):
    return "-" if value is None else f"{value:.{digits}f}"


def fmt_delta(a, b, digits):
    return "-" if a is None or b is None else f"{a - b:+.{digits}f}"


def stats(values):
    """(mean, median) of the defined values, or (None, None)."""
    values = [v for v in values if v is not None]
    if not values:
        return None, None
    return sum(values) / len(values), statistics.median(values)


def compare(a1, a2, k=1):
    """For the targets both define: (number, A1 RSE lower) and (A1 TLR higher, equal, lower target
    numbers), TLR being column k of the rows (1 duration, 2 path length)."""
    rse_pairs = [(a[0], b[0]) for a, b in zip(a1, a2) if a[0] is not None and b[0] is not None]
    rse_lower = sum(1 for x, y in rse_pairs if x < y)
    higher = equal = 0
    lower = []
    for j, (a, b) in enumerate(zip(a1, a2)):
        x, y = round(a[k], 2), round(b[k], 2)  # at the paper's precision
        if x > y:
            higher += 1
        elif x == y:
            equal += 1
        else:
            lower.append(j + 1)
    return len(rse_pairs), rse_lower, higher, equal, lower


def _show(value, digits, delta):
    if value is None:
        return "-"
    if delta and abs(value) < 0.5 * 10 ** -digits:
        value = 0.0  # no "-0.00" from rounding
    return f"{value:+.{digits}f}" if delta else f"{value:.{digits}f}"


def _header(a1, a2, ours, classes, accuracy):
    header = ["target"] + (["class"] if classes is not None else []) + [
              "paper A1 RSE", "paper A1 TLR", "paper A2 RSE", "paper A2 TLR", "paper Δ RSE", "paper Δ TLR"]
    for name, _ in ours:
        header += [f"{name} RSE", f"{name} TLR", f"{name} TLR_len"] + ([f"{name} acc"] if name in accuracy else [])
    header.append("reported")
    if a1 is not None and a2 is not None:
        header += ["Δ RSE", "Δ TLR", "Δ TLR_len"]
    return header


def _columns(a1, a2, n, ours, accuracy, reported):
    """The numeric columns of the table in the header's order, per target: (values, digits, is a delta)."""
    def cell(rows, j, k):
        return rows[j][k] if rows is not None and j < len(rows) else None

    def paper(rows, j, k):
        return rows[j][k] if j < PAPER_TARGETS else None

    columns = [([paper(PAPER_A1, j, 0) for j in range(n)], 2, False),
               ([paper(PAPER_A1, j, 1) for j in range(n)], 2, False),
               ([paper(PAPER_A2, j, 0) for j in range(n)], 2, False),
               ([paper(PAPER_A2, j, 1) for j in range(n)], 2, False)]
    for k in (0, 1):
        columns.append(([None if j >= PAPER_TARGETS else PAPER_A1[j][k] - PAPER_A2[j][k] for j in range(n)], 2, True))
    for name, rows in ours:
        for k in (0, 1, 2):
            columns.append(([cell(rows, j, k) for j in range(n)], 2, False))
        if name in accuracy:
            columns.append(([accuracy[name][j] if j < len(accuracy[name]) else None for j in range(n)], 2, False))
    columns.append(([reported[j] if reported is not None and j < len(reported) else None for j in range(n)], 2, False))
    if a1 is not None and a2 is not None:
        for k in (0, 1, 2):
            columns.append(([None if cell(a1, j, k) is None or cell(a2, j, k) is None
                             else cell(a1, j, k) - cell(a2, j, k) for j in range(n)], 2, True))
    return columns


def _target_lines(header, columns, n, classes):
    """The Markdown table: a row per target, then the mean and median rows."""
    lines = ["| " + " | ".join(header) + " |",
             "|" + "|".join("---" if h == "class" else "---:" for h in header) + "|"]  # text left, numbers right
    for j in range(n):
        text = [str(j + 1)]
        if classes is not None:
            text.append(classes[j] if j < len(classes) and classes[j] is not None else "-")
        lines.append("| " + " | ".join(text + [_show(values[j], d, delta) for values, d, delta in columns]) + " |")
    for label, which in (("mean", 0), ("median", 1)):
        cells = [""] if classes is not None else []  # no mean class
        for values, d, delta in columns:
            cells.append(_show(stats(values)[which], d + 1, delta))
        lines.append("| **" + label + "** | " + " | ".join(cells) + " |")
    return lines


def _legend(n_a1, n_a2, reported_from, classes, accuracy):
    """The paragraph under the table that says what its columns are."""
    runs = ", ".join(f"{name} {count} run{'s' if count != 1 else ''}"
                     for name, count in (("A1", n_a1), ("A2", n_a2)) if count)
    text = (f"Ours: {runs}, each target's values the mean over them. TLR = associated ticks / alive "
            "ticks; TLR_len = associated path length / path length; reported = share of the alive ticks with "
            f"at least one delivered report of the target (the {reported_from} runs' truth.csv and "
            "observations.csv). Means and medians over the targets (RSE over those with a defined RSE).")
    if classes is not None:
        text += (" class = the target's true class (metrics.json's classification block; '-' when no run "
                 "associated the target); " + ", ".join(f"{name} acc" for name in accuracy) +
                 " = ticks its track declared the true class / ticks it declared a class, each summed over "
                 "the runs ('-' when none was declared or the class is unknown; means and medians over the "
                 "targets with one).")
    return text


def _describe(pairs_a1, pairs_a2, who, key=1, what="TLR"):
    count, rse_lower, higher, equal, lower = compare(pairs_a1, pairs_a2, key)
    lower_ids = ", ".join(str(j) for j in lower) or "none"
    return (f"- {who}: A1's RSE lower on {rse_lower}/{count} targets; A1's {what} higher on {higher}, "
            f"equal on {equal}, lower on {len(lower)} (targets {lower_ids})")


def _statistics_lines(a1, a2, n, ours, reported):
    """The statistics the paper's text draws from Table II, the paper's and ours."""
    paper_mean_a1, paper_median_a1 = stats([r[0] for r in PAPER_A1])
    paper_mean_a2, paper_median_a2 = stats([r[0] for r in PAPER_A2])
    lines = [f"- paper: mean RSE {paper_mean_a1:.2f} vs {paper_mean_a2:.2f} m (medians {paper_median_a1:.3f}, "
             f"{paper_median_a2:.3f}); mean TLR {stats([r[1] for r in PAPER_A1])[0]:.3f} vs "
             f"{stats([r[1] for r in PAPER_A2])[0]:.3f}",
             _describe(PAPER_A1, PAPER_A2, "paper")]
    for name, rows in ours:
        mean_rse, median_rse = stats([r[0] for r in rows])
        mean_tlr, median_tlr = stats([r[1] for r in rows])
        mean_len, median_len = stats([r[2] for r in rows])
        lines.append(f"- ours {name}: mean RSE {fmt(mean_rse, 2)} m (median {fmt(median_rse, 3)}); mean TLR "
                     f"{fmt(mean_tlr, 3)} (median {fmt(median_tlr, 3)}); mean TLR_len {fmt(mean_len, 3)} "
                     f"(median {fmt(median_len, 3)})")
    if reported is not None and len(reported) == n and all(v is not None for v in reported):
        mean_rep, median_rep = stats(reported)
        ratios = ", ".join(f"{name} {fmt(stats([r[1] for r in rows])[0] / mean_rep if mean_rep else None, 3)}"
                           for name, rows in ours)
        lines.append(f"- reported share: mean {mean_rep:.3f} (median {median_rep:.3f}); TLR / reported: {ratios}")
    if a1 is not None and a2 is not None:
        lines.append(_describe(a1, a2, "ours"))
        if all(r[2] is not None for r in a1 + a2):
            lines.append(_describe(a1, a2, "ours, path length", key=2, what="TLR_len"))
    return lines


def _classification_lines(ours, pooled):
    """The Classification section: per algorithm its declared share, accuracy and confusion matrix."""
    lines = ["", "Classification (metrics.json's classification block), ticks summed over the runs: declared "
             "share = declared / associated ticks and accuracy = correct / declared ticks, of the targets of "
             "known class; the confusion matrix counts every associated tick by true class (rows) and "
             "declared class (columns; none: no class declared)."]
    for name, _ in ours:
        lines.append("")
        c = pooled.get(name)
        if c is None:
            lines.append(f"- {name}: no classification block in its runs' metrics.json (scored before it existed)")
            continue
        associated, declared, correct = c["totals"]
        runs = f"{c['runs']} run{'s' if c['runs'] != 1 else ''}"
        lines.append(f"- {name} ({runs}): declared share {fmt(declared / associated if associated else None, 3)} "
                     f"({declared}/{associated} associated ticks), accuracy "
                     f"{fmt(correct / declared if declared else None, 3)} ({correct}/{declared} declared ticks)")
        if c["confusion"]:
            lines.append("")
            lines += confusion_lines(name, c["confusion"])
    return lines


def _stop_mode_lines(ours, stop, having):
    """The Stop mode section: per algorithm the mean stop probability while stopped and moving, then
    per target that stops, each algorithm's mean while stopped."""
    lines = ["", "Stop mode (metrics.json's stop_mode block): the mean probability a track gives the stop "
             "model of its IMM, over the ticks its target stands still and the ticks it moves (associated "
             "ticks whose track gives one), summed over the runs ('-' when there is no such tick).", ""]
    for name, _ in ours:
        s = stop.get(name)
        if s is None:
            lines.append(f"- {name}: no stop_mode block in its runs' metrics.json (scored before it existed)")
            continue
        stopped, mean_stopped, moving, mean_moving, without = s["totals"]
        runs = f"{s['runs']} run{'s' if s['runs'] != 1 else ''}"
        line = (f"- {name} ({runs}): while stopped {fmt(mean_stopped, 3)} ({stopped} ticks), while moving "
                f"{fmt(mean_moving, 3)} ({moving} ticks)")
        if without:
            line += f"; {without} associated ticks of tracks whose engine has no stop model"
        lines.append(line)
    stops = sorted({j for name in having for j, t in stop[name]["targets"].items() if t[0] > 0})

    def stopped_cell(name, j):
        t = stop[name]["targets"].get(j)
        return f"{fmt(t[1], 2)} ({t[0]})" if t is not None else "- (0)"

    listing = ", ".join(f"{j + 1}: " + "; ".join(stopped_cell(name, j) for name in having) for j in stops)
    lines.append("- per target that stops (target: " + "; ".join(f"{name} while stopped (ticks)" for name in having)
                 + f"): {listing or 'none'}")
    return lines


def table(a1, a2, n_a1, n_a2, reported=None, reported_from="A2", classes=None, pooled=None, stop=None):
    """The Markdown lines: per-target table, its mean and median rows, then the comparisons.
    `reported` is the per-target reported share (None: '-'), read from the `reported_from` runs.
    `classes` is the per-target true class (None: no class column); `pooled` maps "A1" and "A2" to
    pool_classification's sums of the algorithm's runs, or to None when they have no classification
    block (no accuracy column). Without either, the output is that of runs before classification.
    `stop` maps "A1" and "A2" to pool_stop_mode's pooled means of the algorithm's runs, or to None when
    they have no stop_mode block; without any, there is no stop mode section."""
    n = max(PAPER_TARGETS, len(a1 or []), len(a2 or []))
    ours = [(name, rows) for name, rows in (("A1", a1), ("A2", a2)) if rows is not None]
    pooled = pooled or {}
    accuracy = {name: class_accuracy(pooled[name], classes) for name, _ in ours
                if classes is not None and pooled.get(name) is not None}
    lines = _target_lines(_header(a1, a2, ours, classes, accuracy), _columns(a1, a2, n, ours, accuracy, reported), n,
                          classes)
    lines += ["", _legend(n_a1, n_a2, reported_from, classes, accuracy), ""]
    lines += _statistics_lines(a1, a2, n, ours, reported)
    if any(pooled.get(name) is not None for name, _ in ours):
        lines += _classification_lines(ours, pooled)
    stop = stop or {}
    having = [name for name, _ in ours if stop.get(name) is not None]
    if having:
        lines += _stop_mode_lines(ours, stop, having)
    return lines
