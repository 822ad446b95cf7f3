"""tracks.FORMAT: the global tracks against the true target paths on the sensor field, with the
supernodes and their tracking groups (like Oh et al. Fig. 9, right). Layers are drawn bottom up, one
function each; the legend goes below the map."""

import math

from ..figures import new_figure
from .. import rundir
from .field import (CLASS_COLOURS, NO_CLASS_COLOUR, NO_CLASS_DASHES, REGION_COLOURS, TRACK_COLOURS, TRACK_DASHES,
                    TRUTH_COLOUR, draw_groups_and_region, draw_terrain, draw_typed_sensors, length_unit)
from .geometry import class_pieces, interior_edges, paths_by_id

# Track ids are written beside the tracks (coloured by class, colour no longer tells them apart)
# only when there are this few.
MAX_LABELLED_TRACKS = 30
# Targets are labelled with their first and last tick only when there are this few.
MAX_LABELLED_TARGETS = 30
SENSOR_GREY = "#b4b4b4"
BOUNDARY_STYLE = dict(color="#444444", linestyle=(0, (6, 4)), linewidth=1.3)


def _map_figure(mpl, scenario):
    """The figure and the map's axes, which keep the region's aspect ratio (within reason: a 100 x 1
    strip is still readable)."""
    x0, y0, x1, y1 = scenario["region"]
    width, height = x1 - x0, y1 - y0
    margin = 0.015 * max(width, height)
    axes_w = 8.9
    box_aspect = min(1.6, max(0.25, (height + 2 * margin) / (width + 2 * margin)))
    fig, ax = new_figure(mpl, axes_w + 1.1, axes_w * box_aspect + 0.75 + 1.75, left=0.85, right=0.25, bottom=1.75,
                         top=0.75)
    ax.set_xlim(x0 - margin, x1 + margin)
    ax.set_ylim(y0 - margin, y1 + margin)
    ax.set_aspect("equal")
    return fig, ax


def _draw_sensors(ax, scenario, sensors):
    """The sensors: typed ones as their type's marker over its coverage, the others as grey dots.
    Returns ((xs, ys, stride) of the dots, the typed sensors' legend handles)."""
    xs, ys, stride = sensors
    sensor_handles = []
    if scenario.get("typed_sensors"):
        sensor_handles = draw_typed_sensors(ax, scenario)
        plain = scenario["typed_sensors"]["plain"]
        xs, ys, stride = [p[0] for p in plain], [p[1] for p in plain], 1
    if xs:
        # A marker line, not scatter: one path drawn many times is ~10x faster than a collection.
        size = math.sqrt(max(0.3, min(4.0, 2500.0 / len(xs))))
        ax.plot(xs, ys, linestyle="none", marker="o", markersize=size, markerfacecolor=SENSOR_GREY,
                markeredgewidth=0, zorder=1, rasterized=True)
    return (xs, ys, stride), sensor_handles


def _draw_truth(ax, scenario, truth_paths, true_classes):
    """The true paths, each start circled and, when there are few targets, labelled with its first
    and last tick (and its true class, from `true_classes` when given)."""
    x0, y0, x1, y1 = scenario["region"]
    width, height = x1 - x0, y1 - y0
    label_targets = len(truth_paths) <= MAX_LABELLED_TARGETS
    for ident, (px, py, first, last) in truth_paths.items():
        ax.plot(px, py, color=TRUTH_COLOUR, linewidth=6, alpha=0.45, solid_capstyle="round", zorder=3)
        ax.plot(px[0], py[0], marker="o", markersize=9, markerfacecolor="white", markeredgecolor="black",
                markeredgewidth=1.2, zorder=6)
        if label_targets:
            # Labels point inwards near the right and top edges, where they would leave the figure.
            right = px[0] > x0 + 0.88 * width
            top = py[0] > y0 + 0.95 * height
            true_class = f" {true_classes.get(ident, 'unknown')}" if true_classes is not None else ""
            ax.annotate(f"{first}–{last}{true_class}", (px[0], py[0]), xytext=(-7 if right else 7, -7 if top else 5),
                        textcoords="offset points", fontsize=9, color="#222222", zorder=7,
                        ha="right" if right else "left", va="top" if top else "bottom",
                        bbox=dict(boxstyle="round,pad=0.15", facecolor="white", edgecolor="none", alpha=0.75))


def _draw_tracks_by_class(ax, tracks, order):
    """The tracks coloured by the class declared at each tick, and their ids when there are few.
    One line (pieces NaN-separated) and one set of markers per class, each point marked in the class
    of its tick: a few artists whatever the number of tracks. Returns the classes drawn."""
    rows_of = {}
    for row in sorted(tracks, key=lambda r: (r[1], r[0])):
        rows_of.setdefault(row[1], []).append(row)
    lines, points = {}, {}
    for ident in order:
        for declared, px, py in class_pieces(rows_of[ident]):
            xs, ys = lines.setdefault(declared, ([], []))
            if len(px) > 1:
                xs += px + [math.nan]
                ys += py + [math.nan]
        for row in rows_of[ident]:
            mx, my = points.setdefault(row[-2], ([], []))
            mx.append(row[2])
            my.append(row[3])
    classes_drawn = [c for c in rundir.TARGET_CLASSES + ("",) if c in points]
    for declared in classes_drawn:
        colour = CLASS_COLOURS.get(declared, NO_CLASS_COLOUR)
        if lines.get(declared, ([], []))[0]:
            ax.plot(*lines[declared], color=colour, linestyle="solid" if declared else NO_CLASS_DASHES,
                    linewidth=1.6, zorder=4)
        ax.plot(*points[declared], linestyle="none", marker="o", markersize=2.6, color=colour, zorder=4)
    if len(order) <= MAX_LABELLED_TRACKS:
        # Each track's id at its last point, in the colour of its last class.
        for ident in order:
            last = rows_of[ident][-1]
            ax.annotate(last[6], (last[2], last[3]), xytext=(4, -4), textcoords="offset points", fontsize=8,
                        color=CLASS_COLOURS.get(last[-2], NO_CLASS_COLOUR), ha="left", va="top", zorder=7,
                        bbox=dict(boxstyle="round,pad=0.1", facecolor="white", edgecolor="none", alpha=0.6))
    return classes_drawn


def _draw_tracks_by_id(ax, track_paths, order):
    """One colour per track, in the order they appear; past the colours, dashed, then dotted."""
    for n, ident in enumerate(order):
        px, py, _, _ = track_paths[ident]
        colour = TRACK_COLOURS[n % len(TRACK_COLOURS)]
        dashes = TRACK_DASHES[(n // len(TRACK_COLOURS)) % len(TRACK_DASHES)]
        ax.plot(px, py, color=colour, linestyle=dashes, linewidth=1.6, marker="o", markersize=2.6, zorder=4)


def _draw_supernodes(ax, scenario):
    for j, (sx, sy) in enumerate(scenario["supernodes"]):
        ax.plot(sx, sy, marker="*", markersize=20, markerfacecolor="#ffd21f", markeredgecolor="black",
                markeredgewidth=1.2, zorder=8)
        ax.annotate(f"S{j}", (sx, sy), xytext=(10, -14), textcoords="offset points", fontsize=11, fontweight="bold",
                    zorder=8, bbox=dict(boxstyle="round,pad=0.2", facecolor="white", edgecolor="#444444", alpha=0.85))


def _label_axes(ax, scenario, summary, tracks_drawn, targets_drawn):
    """Axis labels, and the title: the run, its numbers of tracks and targets, and its headline metrics."""
    ax.set_xlabel(f"x ({length_unit(scenario)})", fontsize=12)
    ax.set_ylabel(f"y ({length_unit(scenario)})", fontsize=12)
    ax.tick_params(labelsize=10)
    metrics = []
    if "eps_k" in summary:
        metrics.append(f"εK = {summary['eps_k']:.3f}")
    if "eps_x" in summary:
        metrics.append(f"εX = {summary['eps_x']:.3f}")
    if "ospa_mean" in summary:
        metrics.append(f"mean OSPA = {summary['ospa_mean']:.2f}")
    ax.set_title(f"{scenario['name']}, seed {scenario['seed']}, {scenario['ticks']} ticks, engine "
                 f"{scenario['engine']}: {tracks_drawn} tracks, {targets_drawn} targets"
                 + ("\n" + ", ".join(metrics) if metrics else ""), fontsize=12)


def _legend_handles(drawn):
    """A legend entry for every layer drawn; `drawn` says what was: truth labels, classes or track
    count, observations, boundaries, the sensor dots, typed sensors and terrain."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    appears = "target appears"
    if drawn["label_targets"]:
        appears = ("target appears (label: appear–last tick" + (", true class" if drawn["show_true_class"] else "")
                   + ")")
    handles = [
        Line2D([], [], color=TRUTH_COLOUR, linewidth=6, alpha=0.45, solid_capstyle="round",
               label="true target path"),
        Line2D([], [], linestyle="none", marker="o", markersize=9, markerfacecolor="white", markeredgecolor="black",
               label=appears),
    ]
    if drawn["classes"] is not None:
        for declared in drawn["classes"]:
            handles.append(Line2D([], [], color=CLASS_COLOURS.get(declared, NO_CLASS_COLOUR), linewidth=1.6,
                                  linestyle="solid" if declared else NO_CLASS_DASHES, marker="o", markersize=2.6,
                                  label=f"track declared {declared}" if declared else "track, no class yet"))
    else:
        handles.append(Line2D([], [], color=TRACK_COLOURS[0], linewidth=1.6, marker="o", markersize=2.6,
                              label="estimated track (one colour" + (" and dash" if drawn["tracks"] > len(TRACK_COLOURS)
                                                                     else "") + " per track)"))
    handles += [
        Line2D([], [], linestyle="none", marker="*", markersize=16, markerfacecolor="#ffd21f",
               markeredgecolor="black", label="supernode Sj"),
        Patch(facecolor=REGION_COLOURS[0], edgecolor="#999999", label="tracking group of one supernode"),
    ]
    if drawn["observations"]:
        handles.append(Line2D([], [], linestyle="none", marker="o", markersize=7, markerfacecolor="none",
                              markeredgecolor="#555555", markeredgewidth=0.9, label="delivered report (observation)"))
    if drawn["edges"]:
        handles.append(Line2D([], [], **BOUNDARY_STYLE, label="tracking-group boundary (nearest supernode)"))
    xs, _, stride = drawn["sensor_dots"]
    if xs:
        handles.append(Line2D([], [], linestyle="none", marker="o", markersize=4, markerfacecolor=SENSOR_GREY,
                              markeredgewidth=0,
                              label="sensor" if stride == 1 else f"sensor (1 in {stride} drawn)"))
    return handles + drawn["sensor_handles"] + drawn["terrain_handles"]


def _place_legend(fig, ax, handles, grow):
    """The legend below the map rather than on it, so that no track is hidden; a fixed distance in
    points clears the tick labels and the x label whatever the map's aspect ratio. With `grow` (a
    long legend) the figure grows at the bottom to hold it, the map keeping its size."""
    from matplotlib.transforms import offset_copy
    below = offset_copy(ax.transAxes, fig=fig, y=-44, units="points")
    # A sensor type's handle is a tuple (its coverage, its marker), drawn one over the other.
    labels = [(h[0] if isinstance(h, tuple) else h).get_label() for h in handles]
    legend = ax.legend(handles=handles, labels=labels, loc="upper center", ncol=2, fontsize=10, frameon=False,
                       bbox_to_anchor=(0.5, 0.0), bbox_transform=below, handlelength=3)
    if not grow:
        return
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    renderer = FigureCanvasAgg(fig).get_renderer()  # lays text out without drawing the figure
    lacking = -legend.get_window_extent(renderer).y0 / fig.dpi + 0.15
    if lacking > 0:
        fig_w, fig_h = fig.get_size_inches()
        box = ax.get_position()
        fig.set_size_inches(fig_w, fig_h + lacking)
        ax.set_position([box.x0, (box.y0 * fig_h + lacking) / (fig_h + lacking), box.width,
                         box.height * fig_h / (fig_h + lacking)])


def plot_tracks(mpl, scenario, sensors, truth, tracks, summary, out_path, observations=None, truth_classes=None):
    """tracks.FORMAT. When some track row declares a class, the tracks are coloured by the class
    declared at each tick (CLASS_COLOURS) and labelled with their ids, and the targets' labels
    give their true classes (`truth_classes`); otherwise one colour (then dash) per track."""
    from matplotlib.patches import Polygon
    fig, ax = _map_figure(mpl, scenario)
    x0, y0, x1, y1 = scenario["region"]
    cells = draw_groups_and_region(ax, Polygon, scenario, (x0, y0, x1, y1))
    terrain_handles = draw_terrain(ax, Polygon, scenario)
    sensor_dots, sensor_handles = _draw_sensors(ax, scenario, sensors)
    edges = interior_edges(cells, scenario["region"])
    for p, q in edges:
        ax.plot([p[0], q[0]], [p[1], q[1]], **BOUNDARY_STYLE, zorder=2)

    by_class = any(row[-2] for row in tracks)
    truth_classes = (truth_classes or {}) if by_class else {}
    show_true_class = any(c != "unknown" for c in truth_classes.values())
    truth_paths = paths_by_id(truth, 1)
    _draw_truth(ax, scenario, truth_paths, truth_classes if show_true_class else None)
    if observations:
        ax.plot([o[0] for o in observations], [o[1] for o in observations], linestyle="none", marker="o",
                markersize=7, markerfacecolor="none", markeredgecolor="#555555", markeredgewidth=0.9, zorder=5)
    track_paths = paths_by_id(tracks, 1)
    order = sorted(track_paths, key=lambda i: (track_paths[i][2], i))
    classes_drawn = None
    if by_class:
        classes_drawn = _draw_tracks_by_class(ax, tracks, order)
    else:
        _draw_tracks_by_id(ax, track_paths, order)
    _draw_supernodes(ax, scenario)
    _label_axes(ax, scenario, summary, len(track_paths), len(truth_paths))

    handles = _legend_handles({
        "label_targets": len(truth_paths) <= MAX_LABELLED_TARGETS, "show_true_class": show_true_class,
        "classes": classes_drawn, "tracks": len(order), "observations": observations, "edges": edges,
        "sensor_dots": sensor_dots, "sensor_handles": sensor_handles, "terrain_handles": terrain_handles})
    _place_legend(fig, ax, handles, grow=by_class or bool(sensor_handles))
    fig.savefig(out_path)
