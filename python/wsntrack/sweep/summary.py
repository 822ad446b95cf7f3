"""The spec form's outputs besides the plots: results.csv (one row per run), summary.csv (per grid
point and engine: runs, and each metric's n, mean, sd and 95 % confidence interval of the mean) and
the markdown table."""

import csv
import math
import shlex

from .common import seeds_text
from .metrics import metric_sources


def t_quantile(p, df):
    """The p quantile of Student's t with df degrees of freedom (SciPy's, python3-scipy)."""
    from scipy.stats import t
    return float(t.ppf(p, df))


def describe_stats(values):
    """(n, mean, sd, ci_low, ci_high) of a sample; None where undefined (mean: n = 0; others: n < 2)."""
    n = len(values)
    if n == 0:
        return 0, None, None, None, None
    mean = sum(values) / n
    if n < 2:
        return n, mean, None, None, None
    sd = math.sqrt(sum((v - mean) ** 2 for v in values) / (n - 1))
    half = t_quantile(0.975, n - 1) * sd / math.sqrt(n)
    return n, mean, sd, mean - half, mean + half


def cell_text(value):
    """A CSV cell: empty for None, a float in full (repr), anything else as text."""
    return "" if value is None else repr(float(value)) if isinstance(value, float) else str(value)


def write_spec_results(path, spec, runs):
    """results.csv: one row per run, finished or not, with its command."""
    keys = [k for k, *_ in spec.grid]
    with open(path, "w", newline="", encoding="utf-8") as f:
        writer = csv.writer(f)
        writer.writerow(["engine"] + keys + ["seed", "status", "exit"] + spec.metrics +
                        ["wall_s", "reused", "run_dir", "log", "command"])
        for run in runs:
            wall = "" if run.wall_s is None else f"{run.wall_s:.3f}"
            writer.writerow([run.engine] + [v for _, v in run.point] +
                            [run.seed, run.status, cell_text(run.exit_code)] +
                            [cell_text(run.metrics.get(m)) if run.status == "ok" else "" for m in spec.metrics] +
                            [wall, int(run.reused), run.run_dir.relative_to(run.out), run.log.relative_to(run.out),
                             shlex.join(run.command)])


def summarise(spec, points, runs):
    """{(point, engine): {"runs", "ok", "failed", metric: (n, mean, sd, low, high)}}."""
    cells = {}
    for point in points:
        for engine in spec.engines:
            mine = [r for r in runs if r.engine == engine and r.point == point]
            cell = {"runs": len(mine), "ok": sum(r.status == "ok" for r in mine),
                    "failed": sum(r.status == "failed" for r in mine)}
            for metric in spec.metrics:
                cell[metric] = describe_stats([r.metrics[metric] for r in mine
                                               if r.status == "ok" and r.metrics.get(metric) is not None])
            cells[(tuple(point), engine)] = cell
    return cells


def write_summary(path, spec, points, cells):
    """summary.csv: one row per grid point and engine, each metric's n, mean, sd and interval."""
    keys = [k for k, *_ in spec.grid]
    with open(path, "w", newline="", encoding="utf-8") as f:
        writer = csv.writer(f)
        header = ["engine"] + keys + ["runs", "ok", "failed"]
        for metric in spec.metrics:
            header += [f"{metric}_n", f"{metric}_mean", f"{metric}_sd", f"{metric}_ci95_low", f"{metric}_ci95_high"]
        writer.writerow(header)
        for point in points:
            for engine in spec.engines:
                cell = cells[(tuple(point), engine)]
                row = [engine] + [v for _, v in point] + [cell["runs"], cell["ok"], cell["failed"]]
                for metric in spec.metrics:
                    row += [cell_text(x) for x in cell[metric]]
                writer.writerow(row)


def spec_table(spec, points, names, cells, fixed_text):
    """table.md: the means ± the half-width of their 95 % interval, per grid point and engine."""
    lines = [f"## {spec.title or 'Sweep of ' + spec.scenario.name}", ""]
    if spec.notes:
        lines += [spec.notes.strip(), ""]
    lines += [f"Scenario {spec.scenario.name}; {'seed' if len(spec.seeds) == 1 else 'seeds'} {seeds_text(spec.seeds)} "
              f"({len(spec.seeds)} per cell){'; fixed: ' + fixed_text if fixed_text else ''}.", "",
              "Each cell is the mean over the seeds ± the half-width of its 95 % confidence interval (Student's t); "
              "(k/n): only k of the n runs were counted (a run failed, or the metric is undefined for it); –: none.", ""]
    header = list(names) + [f"{e} {metric_sources()[m][0]}" for e in spec.engines for m in spec.metrics]
    lines.append("| " + " | ".join(header) + " |")
    lines.append("|" + "|".join(["---"] * len(names) + ["---:"] * (len(header) - len(names))) + "|")
    for point in points:
        row = [v for _, v in point]
        for engine in spec.engines:
            cell = cells[(tuple(point), engine)]
            for metric in spec.metrics:
                n, mean, _, low, high = cell[metric]
                text = "–" if n == 0 else f"{mean:.4f}" + ("" if low is None else f" ± {(high - low) / 2:.4f}")
                if n != cell["runs"]:
                    text += f" ({n}/{cell['runs']})"
                row.append(text)
        lines.append("| " + " | ".join(row) + " |")
    return "\n".join(lines) + "\n"


