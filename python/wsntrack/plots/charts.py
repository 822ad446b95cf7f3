"""The plots of a run's numbers per tick: K and K* (cardinality.FORMAT), OSPA (ospa.FORMAT) and,
for ADMAN sensors, the targets detected (detections.FORMAT)."""

import math

from ..figures import new_figure
from .field import length_unit


def integer_axis(ax):
    """Whole-number ticks on the y axis, for counts."""
    from matplotlib.ticker import MaxNLocator
    ax.yaxis.set_major_locator(MaxNLocator(integer=True))


def _count_axes(ax, scenario, counts, ylabel):
    """The axes of a count per tick: ticks 1..T, integer counts from 0 to a little above the largest."""
    ax.set_xlim(0.5, scenario["ticks"] + 0.5)
    ax.set_ylim(0, max([1] + counts) * 1.05 + 0.5)
    integer_axis(ax)
    ax.set_xlabel("tick", fontsize=11)
    ax.set_ylabel(ylabel, fontsize=11)
    ax.grid(True, color="#dddddd", linewidth=0.6)


# Colours told apart by every reader (Okabe and Ito), one per fault, in the scenario's order.
_FAULT_COLOURS = ("#CC79A7", "#009E73", "#E69F00", "#56B4E9", "#F0E442", "#999999")


def fault_notes(summary, width=140):
    """The lines naming the scenario's faults under a chart ("1: kill of supernode 2 at tick 40; ..."),
    wrapped at `width` characters; none for a run without faults."""
    lines, line = [], ""
    for n, (_, _, what) in enumerate(summary.get("faults") or [], start=1):
        note = f"{n}: {what}"
        if line and len(line) + 2 + len(note) > width:
            lines.append(line + ";")
            line = note
        else:
            line = f"{line}; {note}" if line else note
    return lines + [line] if line else lines


def _chart(mpl, summary):
    """A 10-inch chart with room under its axes for the fault notes."""
    notes = fault_notes(summary)
    bottom = 0.6 + (0.2 + 0.16 * len(notes) if notes else 0.0)
    return new_figure(mpl, 10, 4.4 + bottom - 0.6, left=0.75, right=0.2, bottom=bottom, top=0.85)


def mark_faults(ax, summary):
    """The scenario's faults as shaded spans over the ticks they hold (a kill: its first window), each
    numbered at the top and named under the axes, so that a change in a curve can be read against the
    fault that made it (docs/FAULTS.md)."""
    faults = summary.get("faults") or []
    if not faults:
        return
    top = ax.get_ylim()[1]
    for n, (first, last, _) in enumerate(faults, start=1):
        colour = _FAULT_COLOURS[(n - 1) % len(_FAULT_COLOURS)]
        ax.axvspan(first - 0.5, last + 0.5, color=colour, alpha=0.16, linewidth=0)
        ax.axvline(first - 0.5, color=colour, linewidth=1.2)
        ax.text(first - 0.3, top * 0.97, str(n), color=colour, fontsize=10, fontweight="bold", va="top")
    height = ax.figure.get_size_inches()[1] * ax.get_position().height
    ax.text(0.0, -0.55 / height, "faults (shaded while they hold; a kill: for one tracker window) — " + "\n".join(fault_notes(summary)),
            transform=ax.transAxes, fontsize=8, va="top")


def plot_cardinality(mpl, scenario, ticks, k_true, k, summary, out_path):
    """cardinality.FORMAT: K and K* per tick, |K - K*| shaded (the terms of eps_K, Oh eq. 9)."""
    fig, ax = _chart(mpl, summary)
    ax.fill_between(ticks, k_true, k, step="mid", color="#D55E00", alpha=0.18, linewidth=0,
                    label="|K − K*| (error counted by εK)")
    ax.step(ticks, k_true, where="mid", color="black", linewidth=2.4, label="K*: targets (truth)")
    ax.step(ticks, k, where="mid", color="#0072B2", linewidth=1.6, linestyle="--", label="K: tracks (estimate)")
    _count_axes(ax, scenario, k_true + k, "number of targets / tracks")
    mark_faults(ax, summary)
    title = "Number of targets K* and of tracks K (Oh et al. eq. 9)"
    if "eps_k" in summary:
        title += f": εK = {summary['eps_k']:.3f}"
    # Legend between title and axes: it can then never hide a curve.
    ax.set_title(title, fontsize=12, pad=30)
    ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), ncol=3, fontsize=10, frameon=False)
    fig.savefig(out_path)


def plot_detections(mpl, scenario, detections, out_path):
    """detections.FORMAT: the targets ADMAN's sensors detect per tick, inside r0 and in between,
    against the true number (the ADMAN paper's Fig. 9), with the reports' localisation error."""
    inside, between, true_count, errors = detections
    ticks = list(range(1, scenario["ticks"] + 1))
    total = [a + b for a, b in zip(inside, between)]
    fig, ax = new_figure(mpl, 10, 4.4, left=0.75, right=0.2, bottom=0.6, top=0.85)
    ax.step(ticks, true_count, where="mid", color="black", linewidth=2.4, label="true total number")
    ax.step(ticks, total, where="mid", color="#0072B2", linewidth=1.6, linestyle="--", label="estimated total number")
    ax.step(ticks, inside, where="mid", color="#D55E00", linewidth=1.2, label="inside range (r0)")
    ax.step(ticks, between, where="mid", color="#009E73", linewidth=1.2, linestyle=":", label="in-between area")
    _count_axes(ax, scenario, true_count + total, "number of targets")
    same = sum(1 for a, b in zip(total, true_count) if a == b)
    title = f"Targets detected by ADMAN (its Fig. 9): the count is right at {same} of {len(ticks)} ticks"
    if errors:
        rms = math.sqrt(sum(e * e for e in errors) / len(errors))
        title += f"; localisation error rms {rms:.2f}, median {sorted(errors)[len(errors) // 2]:.2f}"
    ax.set_title(title, fontsize=11, pad=30)
    ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), ncol=4, fontsize=10, frameon=False)
    fig.savefig(out_path)


def plot_ospa(mpl, scenario, ticks, ospa, source, out_path, summary=None):
    """ospa.FORMAT: OSPA per tick with its mean and cut-off c, the scenario's faults marked; `source`
    names the file it came from."""
    fig, ax = _chart(mpl, summary or {})
    xs = [t for t, v in zip(ticks, ospa) if v is not None]
    ys = [v for v in ospa if v is not None]
    c, p = scenario["ospa_c"], scenario["ospa_p"]
    ax.plot(xs, ys, color="#0072B2", linewidth=1.5, marker="o", markersize=3, label="OSPA at the tick")
    if ys:
        mean = sum(ys) / len(ys)
        ax.axhline(mean, color="#D55E00", linestyle=":", linewidth=1.6, label=f"mean {mean:.2f}")
    if math.isfinite(c):
        ax.axhline(c, color="#555555", linestyle="--", linewidth=1.0, label=f"cut-off c = {c:g}")
    top = max([c if math.isfinite(c) else 0.0] + ys + [1.0])
    ax.set_ylim(0, top * 1.12)
    ax.set_xlim(0.5, scenario["ticks"] + 0.5)
    ax.set_xlabel("tick", fontsize=11)
    ax.set_ylabel(f"OSPA ({length_unit(scenario)})", fontsize=11)
    ax.grid(True, color="#dddddd", linewidth=0.6)
    mark_faults(ax, summary or {})
    order = f", p = {p:g}" if math.isfinite(p) else ""
    ax.set_title(f"OSPA distance between tracks and targets (c = {c:g}{order}; from {source})", fontsize=12, pad=30)
    ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), ncol=3, fontsize=10, frameon=False)
    fig.savefig(out_path)
