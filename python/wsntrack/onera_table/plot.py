"""onera_table.py --plot: per-target RSE and TLR, ours beside the paper's, as grouped bars."""

import os
from pathlib import Path

from .paper import PAPER_A1, PAPER_A2, PAPER_TARGETS

def plot(matplotlib, path, a1, a2, n_a1, n_a2):
    """Draws per-target RSE and TLR, ours (the algorithms given) beside the paper's, as grouped bars
    in two stacked panels, and saves the figure to `path` (its suffix gives the format) through a
    temporary file in the same directory, renamed when complete. Raises OSError when it cannot."""
    n = max(PAPER_TARGETS, len(a1 or []), len(a2 or []))
    # (label, per-target (rse, tlr) rows, colour, paper's style)
    series = []
    if a1 is not None:
        series.append((f"ours A1 (road network, mean of {n_a1} run{'s' if n_a1 != 1 else ''})", a1,
                       "tab:blue", False))
    if a2 is not None:
        series.append((f"ours A2 (no road network, mean of {n_a2} run{'s' if n_a2 != 1 else ''})", a2,
                       "tab:orange", False))
    series.append(("paper A1 (Table II)", PAPER_A1, "tab:blue", True))
    series.append(("paper A2 (Table II)", PAPER_A2, "tab:orange", True))
    width = 0.84 / len(series)

    fig = matplotlib.figure.Figure(figsize=(max(12.0, 0.6 * n), 8.0), constrained_layout=True)
    rse_axes, tlr_axes = fig.subplots(2, 1, sharex=True)
    for axes, k, ylabel in ((rse_axes, 0, "RSE (m)"), (tlr_axes, 1, "TLR")):
        for i, (label, rows, colour, paper) in enumerate(series):
            offset = (i - (len(series) - 1) / 2) * width
            xs, heights = [], []
            for j in range(min(n, len(rows))):
                if rows[j][k] is not None:  # an undefined RSE: no bar
                    xs.append(j + 1 + offset)
                    heights.append(rows[j][k])
            style = ({"color": colour, "alpha": 0.35, "hatch": "///", "edgecolor": colour, "linewidth": 0.6}
                     if paper else {"color": colour, "edgecolor": "black", "linewidth": 0.4})
            axes.bar(xs, heights, width, label=label, zorder=2, **style)
        axes.set_ylabel(ylabel)
        axes.grid(axis="y", color="0.85", zorder=0)
        axes.set_axisbelow(True)
        axes.set_xlim(0.4, n + 0.6)
    tlr_axes.set_ylim(0, 1.05)
    tlr_axes.set_xticks(range(1, n + 1))
    tlr_axes.set_xlabel("target")
    rse_axes.tick_params(labelbottom=True)
    rse_axes.set_title("per-target position RSE (m); a target never associated has no bar", fontsize=10)
    tlr_axes.set_title("per-target TLR (associated ticks / alive ticks)", fontsize=10)
    runs = ", ".join(f"{name} {count} run{'s' if count != 1 else ''}"
                     for name, count in (("A1", n_a1), ("A2", n_a2)) if count)
    fig.suptitle(f"Ours ({runs}; per-target means) vs Pannetier, Dezert and Sella (FUSION 2014), Table II")
    # Above the top panel, so that it hides no bar.
    rse_axes.legend(loc="lower center", bbox_to_anchor=(0.5, 1.1), ncol=len(series), frameon=False,
                    fontsize=9)

    path = Path(path)
    partial = path.with_name(f".{path.name}.{os.getpid()}.partial")
    try:
        fig.savefig(partial, format=path.suffix.lower()[1:])
        os.replace(partial, path)
    finally:
        if partial.exists():
            partial.unlink()
