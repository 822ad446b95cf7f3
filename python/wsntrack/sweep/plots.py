"""The spec form's plots/: for a 1-D grid each metric against the swept value, one line per engine
with a shaded 95 % band and the spec's reference lines; for a 2-D grid a heat map per metric and
engine, on one colour scale per metric. Axis labels and units come from the catalogue (`wsntrack
components --json`): "transmission failure rate pte [per hop]", "εK (Oh eq. 9)"."""

import math
import sys

from .common import PROG, safe
from .. import catalogue
from .metrics import metric_label, metric_sources
from .spec import number, same_value


PLOT_FORMATS = ("png", "svg", "pdf")


def key_label(key):
    """A figure's label of a swept scenario key: the catalogue's label and unit, else the key."""
    entry = catalogue.scenario_key(key)
    return catalogue.axis_label(entry["label"], entry["unit"]) if entry else key


def save_figure(plt, fig, path):
    """Lays out, writes and closes one figure (its format that of the path's suffix); returns its path."""
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def _axis(values):
    """(positions, categorical) of the grid values on an axis: the numbers, or 0, 1, ... for words."""
    numeric = [number(v) for v in values]
    if all(x is not None for x in numeric):
        return numeric, False
    return list(range(len(values))), True


def _position(values, positions, text):
    """Where a reference's grid value `text` falls on an axis of `values` at `positions`."""
    for v, p in zip(values, positions):
        if same_value(v, text):
            return p
    return number(text)


def _stat(cells, point, engine, metric, index):
    """Item `index` of the summary's (n, mean, sd, low, high) of (point, engine, metric), NaN where undefined."""
    value = cells[(tuple(point), engine)][metric][index]
    return math.nan if value is None else value


def _against_measured(plt, np, ax, spec, points, cells, metric):
    """The lines of a metric against spec.x, the mean of a measured quantity per grid point: per
    engine, the points in the order of x, each with its 95 % band and labelled with its swept value."""
    key, values = spec.grid[0][0], spec.grid[0][1]
    for engine in spec.engines:
        rows = [(_stat(cells, p, engine, spec.x, 1), _stat(cells, p, engine, metric, 1),
                 _stat(cells, p, engine, metric, 3), _stat(cells, p, engine, metric, 4), value)
                for p, value in zip(points, values)]
        rows = sorted((r for r in rows if not math.isnan(r[0])), key=lambda r: r[0])
        xs, mean, low, high = (np.array([r[i] for r in rows]) for i in range(4))
        line, = ax.plot(xs, mean, marker="o", label=engine)
        ax.fill_between(xs, low, high, color=line.get_color(), alpha=0.2, linewidth=0)
        for x, y, *_, value in rows:
            ax.annotate(value, (x, y), textcoords="offset points", xytext=(3, 4), fontsize=6, color=line.get_color())
    for reference in spec.references:
        if reference["metric"] in (None, metric) and reference["value"] is not None:
            ax.axhline(reference["value"], color="0.3", linestyle="--", linewidth=1, label=reference["label"])
    ax.set_xlabel(metric_label(spec.x) + f" (points: {key})")


def _line_plots(plt, np, directory, spec, points, cells, subtitle, plot_format):
    """METRIC.png for a 1-D grid: the mean against the swept value per engine, with its 95 % band;
    against the mean of a measured quantity instead when the spec has an x."""
    key, values = spec.grid[0][0], spec.grid[0][1]
    xs, categorical = _axis(values)
    written = []
    for metric in spec.metrics:
        if metric == spec.x:
            continue
        fig, ax = plt.subplots(figsize=(7.5, 4.8))
        if spec.x:
            _against_measured(plt, np, ax, spec, points, cells, metric)
        for engine in spec.engines if not spec.x else ():
            mean = np.array([_stat(cells, p, engine, metric, 1) for p in points])
            low = np.array([_stat(cells, p, engine, metric, 3) for p in points])
            high = np.array([_stat(cells, p, engine, metric, 4) for p in points])
            line, = ax.plot(xs, mean, marker="o", label=engine)
            ax.fill_between(xs, low, high, color=line.get_color(), alpha=0.2, linewidth=0)
        for reference in spec.references if not spec.x else ():  # _against_measured draws its own
            if reference["metric"] not in (None, metric):
                continue
            label = reference["label"]
            if reference["value"] is not None:
                ax.axhline(reference["value"], color="0.3", linestyle="--", linewidth=1, label=label)
                label = None
            if key in reference["at"]:
                ax.axvline(_position(values, xs, reference["at"][key]), color="0.3", linestyle=":",
                           linewidth=1.2, label=label)
        if categorical and not spec.x:
            ax.set_xticks(xs)
            ax.set_xticklabels(values)
        if not spec.x:
            ax.set_xlabel(key_label(key))
        ax.set_ylabel(metric_label(metric))
        against = spec.x or key
        ax.set_title(f"{spec.title or metric_sources()[metric][0] + ' against ' + against}\n{subtitle}; "
                     "band: 95 % CI of the mean", fontsize=9)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
        written.append(save_figure(plt, fig, directory / f"{safe(metric)}.{plot_format}"))
    return written


def _reference_marks(plt, np, ax, spec, metric, matrix, rows, columns):
    """The spec's references on a heat map: a contour at a value, lines at grid values; returns
    their legend handles."""
    (row_key, row_values), (column_key, column_values) = rows, columns
    handles = []
    for reference in spec.references:
        if reference["metric"] not in (None, metric):
            continue
        drawn = False
        finite_cells = np.isfinite(matrix)
        if reference["value"] is not None and min(matrix.shape) >= 2 and finite_cells.any() and \
                np.nanmin(matrix) < reference["value"] < np.nanmax(matrix):
            ax.contour(np.arange(len(column_values)), np.arange(len(row_values)), np.ma.masked_invalid(matrix),
                       levels=[reference["value"]], colors="red", linestyles="--", linewidths=1.2)
            drawn = True
        if row_key in reference["at"]:
            ax.axhline(_position(row_values, range(len(row_values)), reference["at"][row_key]),
                       color="red", linestyle=":", linewidth=1.2)
            drawn = True
        if column_key in reference["at"]:
            ax.axvline(_position(column_values, range(len(column_values)), reference["at"][column_key]),
                       color="red", linestyle=":", linewidth=1.2)
            drawn = True
        if drawn:
            handles.append(plt.Line2D([], [], color="red", linestyle="--", label=reference["label"]))
    return handles


def _heat_map(plt, np, spec, metric, engine, matrix, scale, cells, subtitle):
    """One heat map: the mean per cell on the metric's colour scale, each cell's mean ± half-width."""
    (row_key, row_values, *_), (column_key, column_values, *_) = spec.grid
    low, high = scale
    fig, ax = plt.subplots(figsize=(max(6.5, 2.5 + 1.0 * len(column_values)),
                                    max(4.5, 2.2 + 0.6 * len(row_values))))
    image = ax.imshow(np.ma.masked_invalid(matrix), origin="lower", aspect="auto", cmap="viridis",
                      vmin=low, vmax=high if high > low else low + 1e-9)
    fig.colorbar(image, ax=ax, label=f"{metric_label(metric)}, mean")
    for i in range(len(row_values)):
        for j in range(len(column_values)):
            point = ((row_key, row_values[i]), (column_key, column_values[j]))
            n, mean, _, ci_low, ci_high = cells[(point, engine)][metric]
            text = "–" if n == 0 else f"{mean:.3g}" + ("" if ci_low is None else f"\n±{(ci_high - ci_low) / 2:.2g}")
            ax.text(j, i, text, ha="center", va="center", fontsize=7,
                    color="white" if n and mean < (low + high) / 2 else "black")
    handles = _reference_marks(plt, np, ax, spec, metric, matrix, (row_key, row_values), (column_key, column_values))
    ax.set_xticks(range(len(column_values)))
    ax.set_xticklabels(column_values)
    ax.set_yticks(range(len(row_values)))
    ax.set_yticklabels(row_values)
    ax.set_xlabel(key_label(column_key))
    ax.set_ylabel(key_label(row_key))
    ax.set_title(f"{spec.title or metric_sources()[metric][0]}: {engine}\n{subtitle}\n"
                 "cells: mean ± half-width of the 95 % CI", fontsize=8)
    if handles:
        ax.legend(handles=handles, fontsize=7, loc="upper left", bbox_to_anchor=(0, -0.18))
    return fig


def _heat_maps(plt, np, directory, spec, points, cells, subtitle, plot_format):
    """METRIC_ENGINE.png for a 2-D grid, one colour scale per metric over its engines."""
    (_, row_values, *_), (_, column_values, *_) = spec.grid
    written = []
    for metric in spec.metrics:
        matrices = {}
        for engine in spec.engines:
            matrix = np.full((len(row_values), len(column_values)), np.nan)
            for point in points:
                i, j = row_values.index(point[0][1]), column_values.index(point[1][1])
                matrix[i, j] = _stat(cells, point, engine, metric, 1)
            matrices[engine] = matrix
        finite = np.concatenate([m[np.isfinite(m)] for m in matrices.values()])
        scale = (finite.min(), finite.max()) if finite.size else (0.0, 1.0)
        for engine, matrix in matrices.items():
            fig = _heat_map(plt, np, spec, metric, engine, matrix, scale, cells, subtitle)
            written.append(save_figure(plt, fig, directory / f"{safe(metric)}_{safe(engine)}.{plot_format}"))
    return written


def draw_plots(directory, spec, points, cells, fixed_text, plot_format="png", own_directory=True):
    """plots/: a line plot per metric (1-D grid) or a heat map per metric and engine (2-D grid), in
    `plot_format` (one of PLOT_FORMATS); returns the files written (none, with a note, without
    matplotlib). In the sweep's `own_directory` the earlier files of that format go first (a metric
    no longer tabulated leaves no stale plot); in a directory of the user's, nothing is deleted."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        import numpy as np
    except ImportError as error:
        print(f"{PROG}: no plots: {error} (Debian: apt-get install python3-matplotlib; run with /usr/bin/python3)",
              file=sys.stderr)
        return []
    directory.mkdir(exist_ok=True)
    for old in directory.glob(f"*.{plot_format}") if own_directory else ():
        old.unlink()
    subtitle = (f"{spec.scenario.name}, {len(spec.seeds)} seed{'s' if len(spec.seeds) != 1 else ''} per point"
                f"{'; ' + fixed_text if fixed_text else ''}")
    if len(spec.grid) not in (1, 2):
        print(f"{PROG}: no plots for a grid of {len(spec.grid)} keys (a line plot needs 1, a heat map 2); "
              "summary.csv has every number", file=sys.stderr)
        return []
    if len(spec.grid) == 1:
        return _line_plots(plt, np, directory, spec, points, cells, subtitle, plot_format)
    return _heat_maps(plt, np, directory, spec, points, cells, subtitle, plot_format)
