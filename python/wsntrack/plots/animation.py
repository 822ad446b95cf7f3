"""The replay animation of a run (plot_run.py --animate, 'wsntrack replay'): one frame per tick on
one figure whose static parts (the field, the legend, the curves of the whole run) are drawn once;
per frame only the artists that change are drawn over that background, which is what makes long
runs quick. The frames go to a sink (wsntrack.plots.sinks)."""

import math
import sys
from types import SimpleNamespace

from ..figures import stamp_if_incomplete
from .charts import integer_axis
from .field import REGION_COLOURS, TRACK_COLOURS, TRUTH_COLOUR, draw_groups_and_region, draw_terrain, length_unit
from .geometry import ELLIPSE_SIGMAS, ellipse_axes, interior_edges
from .sinks import Progress

OBSERVATION_COLOUR = "#1a1a1a"
FALSE_ALARM_COLOUR = "#e0115f"
SENSOR_COLOUR = "#c2c2c2"
BOUNDARY_STYLE = dict(color="#555555", linestyle=(0, (6, 4)), linewidth=1.1)


def _layout(mpl, size):
    """The figure, its canvas and where the map and the side panel go, in inches: laid out on a
    figure 7.2 in high whatever the pixels, so that text keeps its proportions. The side panel
    (legend, K and OSPA so far) takes what the map leaves, at least side_min inches; a frame too
    narrow for both has the map alone."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    width_px, height_px = size
    dpi = height_px / 7.2
    fig = mpl.figure.Figure(figsize=((width_px + 0.25) / dpi, (height_px + 0.25) / dpi), dpi=dpi)
    fig.patch.set_facecolor("white")
    stamp_if_incomplete(fig)
    canvas = FigureCanvasAgg(fig)
    fig_w, fig_h = fig.get_size_inches()
    return SimpleNamespace(fig=fig, canvas=canvas, dpi=dpi, fig_w=fig_w, fig_h=fig_h, left=0.62, bottom=0.5,
                           top=0.95, right=0.3, side_min=4.2, side_gap=0.75)


def _map_axes(layout, scenario):
    """The map's axes, as large as the frame allows at the region's aspect ratio."""
    x0, y0, x1, y1 = scenario["region"]
    margin = 0.015 * max(x1 - x0, y1 - y0)
    aspect = (y1 - y0 + 2 * margin) / (x1 - x0 + 2 * margin)
    fig_w, fig_h = layout.fig_w, layout.fig_h
    map_h = fig_h - layout.bottom - layout.top
    map_w = map_h / aspect
    layout.side = fig_w - layout.left - layout.right >= 8.0
    room = fig_w - layout.left - layout.right - (layout.side_min + layout.side_gap if layout.side else 0.0)
    if map_w > room:
        map_w, map_h = room, room * aspect
    layout.map_w = map_w
    map_bottom = layout.bottom + (fig_h - layout.bottom - layout.top - map_h) / 2
    ax = layout.fig.add_axes([layout.left / fig_w, map_bottom / fig_h, map_w / fig_w, map_h / fig_h])
    ax.set_xlim(x0 - margin, x1 + margin)
    ax.set_ylim(y0 - margin, y1 + margin)
    ax.set_aspect("equal", adjustable="datalim")
    ax.tick_params(labelsize=9)
    ax.set_xlabel(f"x ({length_unit(scenario)})", fontsize=10, labelpad=2)
    ax.set_ylabel(f"y ({length_unit(scenario)})", fontsize=10, labelpad=2)
    return ax


def _draw_field(ax, layout, scenario, sensors):
    """The static map: tracking groups, the region, terrain, sensors, boundaries, supernodes."""
    from matplotlib.patches import Polygon
    x0, y0, x1, y1 = scenario["region"]
    cells = draw_groups_and_region(ax, Polygon, scenario, (x0, y0, x1, y1))
    draw_terrain(ax, Polygon, scenario)
    xs, ys, _ = sensors
    if xs:
        pixels_per_sensor = layout.map_w * layout.dpi / math.sqrt(len(xs) * (x1 - x0) / (y1 - y0))
        size = max(0.8, min(3.0, 0.3 * pixels_per_sensor * 72 / layout.dpi))
        ax.plot(xs, ys, linestyle="none", marker="o", markersize=size, markerfacecolor=SENSOR_COLOUR,
                markeredgewidth=0, zorder=1)
    for p, q in interior_edges(cells, scenario["region"]):
        ax.plot([p[0], q[0]], [p[1], q[1]], **BOUNDARY_STYLE, zorder=2)
    for j, (sx, sy) in enumerate(scenario["supernodes"]):
        ax.plot(sx, sy, marker="*", markersize=15, markerfacecolor="#ffd21f", markeredgecolor="black",
                markeredgewidth=1.0, zorder=3)
        ax.annotate(f"S{j}", (sx, sy), xytext=(8, -12), textcoords="offset points", fontsize=9, fontweight="bold",
                    color="#333333", zorder=3)


def _headline(layout, scenario):
    """The run's description, and the tick and its numbers above the map: (headline, numbers) texts.
    The numbers follow the widest headline, so that they stay put from frame to frame."""
    fig, fig_w, fig_h, left = layout.fig, layout.fig_w, layout.fig_h, layout.left
    fig.text(left / fig_w, 1 - 0.3 / fig_h, f"{scenario['name']} · seed {scenario['seed']} · engine "
             f"{scenario['engine']} · {len(scenario['supernodes'])} supernodes", fontsize=10, color="#555555",
             va="baseline")
    widest = f"tick {scenario['ticks']} / {scenario['ticks']}"
    headline = fig.text(left / fig_w, 1 - 0.72 / fig_h, widest, fontsize=17, fontweight="bold", va="baseline")
    headline_w = headline.get_window_extent(layout.canvas.get_renderer()).width / layout.dpi
    numbers = fig.text((left + headline_w + 0.35) / fig_w, 1 - 0.72 / fig_h, "", fontsize=14, va="baseline")
    return headline, numbers


def _indexes(truth, tracks, observations):
    """Per-tick lookups: the targets' and the tracks' positions, the track rows, each track's
    colour (in the order the tracks appear) and the reports delivered."""
    truth_at = {}
    for row in truth:
        truth_at.setdefault(row[0], {})[row[1]] = (row[2], row[3])
    track_at = {}
    for row in tracks:
        track_at.setdefault(row[0], {})[row[1]] = row
    first_seen = {}
    for row in tracks:
        first_seen.setdefault(row[1], row[0])
    colour_of = {ident: TRACK_COLOURS[n % len(TRACK_COLOURS)]
                 for n, ident in enumerate(sorted(first_seen, key=lambda i: (first_seen[i], i)))}
    delivered_at = {}
    for row in observations:
        if row[1] is not None:
            delivered_at.setdefault(row[1], []).append(row)
    track_xy_at = {tick: {ident: (row[2], row[3]) for ident, row in rows.items()} for tick, rows in track_at.items()}
    return SimpleNamespace(truth_at=truth_at, track_at=track_at, track_xy_at=track_xy_at, colour_of=colour_of,
                           delivered_at=delivered_at)


def _legend_handles(trail, sensors):
    from matplotlib.colors import to_rgba
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    handles = [
        Line2D([], [], linestyle="none", marker="o", markersize=11, markerfacecolor="none",
               markeredgecolor="#333333", markeredgewidth=1.5, label="true target"),
        Line2D([], [], color=TRUTH_COLOUR, linewidth=5, alpha=0.5, solid_capstyle="round",
               label=f"its last {trail} ticks"),
        Line2D([], [], color=TRACK_COLOURS[0], linewidth=1.8, marker="o", markersize=6,
               markeredgecolor="white", markeredgewidth=0.8, label="track S:N (trail, estimate)"),
        Patch(facecolor=to_rgba(TRACK_COLOURS[0], 0.15), edgecolor=TRACK_COLOURS[0], linewidth=1.2,
              label=f"{ELLIPSE_SIGMAS:g}σ position ellipse"),
        Line2D([], [], linestyle="none", marker="o", markersize=4, color=OBSERVATION_COLOUR,
               label="report delivered in its tick"),
        Line2D([], [], linestyle="none", marker="o", markersize=5.5, markerfacecolor="none",
               markeredgecolor=OBSERVATION_COLOUR, markeredgewidth=1.0, label="report delivered late"),
        Line2D([], [], linestyle="none", marker="x", markersize=5.5, color=FALSE_ALARM_COLOUR,
               markeredgewidth=1.4, label="false alarm"),
        Line2D([], [], linestyle="none", marker="*", markersize=13, markerfacecolor="#ffd21f",
               markeredgecolor="black", label="supernode Sj"),
        Patch(facecolor=REGION_COLOURS[0], edgecolor="#999999", label="its tracking group"),
        Line2D([], [], **BOUNDARY_STYLE, label="group boundary"),
    ]
    xs, _, stride = sensors
    if xs:
        handles.append(Line2D([], [], linestyle="none", marker="o", markersize=3, markerfacecolor=SENSOR_COLOUR,
                              markeredgewidth=0, label="sensor" if stride == 1 else f"sensor (1 in {stride})"))
    return handles


class _SidePanel:
    """Beside the map: the legend, and K and K* and OSPA over the whole run (faint), drawn up to the
    tick as the frames go, with a cursor at the tick."""

    def __init__(self, layout, scenario, per_tick, first_tick, trail, sensors):
        fig, fig_w, fig_h, bottom = layout.fig, layout.fig_w, layout.fig_h, layout.bottom
        side_left = layout.left + layout.map_w + layout.side_gap
        side_w = fig_w - side_left - layout.right
        chart_h, chart_gap = 1.55, 0.5
        legend_bottom = bottom + 2 * chart_h + chart_gap + 0.4
        legend_ax = fig.add_axes([side_left / fig_w, legend_bottom / fig_h, side_w / fig_w,
                                  (fig_h - layout.top - legend_bottom) / fig_h])
        legend_ax.set_axis_off()
        legend_ax.legend(handles=_legend_handles(trail, sensors), loc="upper left", ncol=2, fontsize=9.5,
                         frameon=False, handlelength=2.2, columnspacing=1.2, labelspacing=0.75, borderaxespad=0)
        k_ax = fig.add_axes([side_left / fig_w, (bottom + chart_h + chart_gap) / fig_h, side_w / fig_w,
                             chart_h / fig_h])
        o_ax = fig.add_axes([side_left / fig_w, bottom / fig_h, side_w / fig_w, chart_h / fig_h], sharex=k_ax)
        for chart in (k_ax, o_ax):
            chart.set_xlim(0.5, scenario["ticks"] + 0.5)
            chart.grid(True, color="#e0e0e0", linewidth=0.6)
            chart.tick_params(labelsize=8.5)
        k_ax.tick_params(labelbottom=False)
        o_ax.set_xlabel("tick", fontsize=9, labelpad=1)
        self.per_tick = per_tick
        self._cardinality_chart(k_ax)
        self._ospa_chart(o_ax, scenario["ospa_c"])
        self.cursors = [chart.axvline(first_tick, color="#D55E00", linewidth=1.2, alpha=0.8) for chart in (k_ax, o_ax)]
        self.artists = [self.k_true_line, self.k_line, self.ospa_line] + self.cursors

    def _cardinality_chart(self, k_ax):
        per_ticks, k_true, k, _ = self.per_tick
        integer_axis(k_ax)
        k_ax.set_ylim(0, max([1] + k_true + k) * 1.15 + 0.5)
        k_ax.step(per_ticks, k_true, where="mid", color="black", linewidth=1.0, alpha=0.2)
        k_ax.step(per_ticks, k, where="mid", color="#0072B2", linewidth=1.0, alpha=0.25)
        self.k_true_line, = k_ax.step([], [], where="mid", color="black", linewidth=2.0, label="K*: targets")
        self.k_line, = k_ax.step([], [], where="mid", color="#0072B2", linewidth=1.6, linestyle="--", label="K: tracks")
        k_ax.legend(loc="lower left", bbox_to_anchor=(0, 1.0), ncol=2, fontsize=9, frameon=False, borderaxespad=0.2)

    def _ospa_chart(self, o_ax, c):
        per_ticks, _, _, ospa = self.per_tick
        valid = [(t, v) for t, v in zip(per_ticks, ospa) if v is not None]
        o_ax.set_ylim(0, max([c if math.isfinite(c) else 0.0] + [v for _, v in valid] + [1.0]) * 1.12)
        if valid:
            o_ax.plot([t for t, _ in valid], [v for _, v in valid], color="#0072B2", linewidth=1.0, alpha=0.25)
        if math.isfinite(c):
            o_ax.axhline(c, color="#777777", linestyle="--", linewidth=0.9)
        self.ospa_line, = o_ax.plot([], [], color="#0072B2", linewidth=1.6,
                                    label="OSPA" + (f" (cut-off c = {c:g})" if math.isfinite(c) else ""))
        o_ax.legend(loc="lower left", bbox_to_anchor=(0, 1.0), fontsize=9, frameon=False, borderaxespad=0.2)

    def update(self, t, upto):
        """The curves up to the `upto` first ticks of the run, the cursor at tick t."""
        per_ticks, k_true, k, ospa = self.per_tick
        self.k_true_line.set_data(per_ticks[:upto], k_true[:upto])
        self.k_line.set_data(per_ticks[:upto], k[:upto])
        shown = [(tt, v) for tt, v in zip(per_ticks[:upto], ospa[:upto]) if v is not None]
        self.ospa_line.set_data([tt for tt, _ in shown], [v for _, v in shown])
        for cursor in self.cursors:
            cursor.set_xdata([t, t])


class _MapLayers:
    """The artists of the map that change every frame: the targets and their fading trails, the
    tracks with trails, ellipses and ids, and the reports delivered at the tick."""

    def __init__(self, ax, index, trail):
        from matplotlib.collections import LineCollection, PatchCollection
        self.ax, self.index, self.trail = ax, index, trail
        self.truth_trail = LineCollection([], linewidths=5, capstyle="round", zorder=4)
        ax.add_collection(self.truth_trail)
        self.truth_now, = ax.plot([], [], linestyle="none", marker="o", markersize=11, markerfacecolor="none",
                                  markeredgecolor="#333333", markeredgewidth=1.5, zorder=5)
        self.track_trail = LineCollection([], linewidths=1.8, capstyle="round", zorder=6)
        ax.add_collection(self.track_trail)
        self.ellipses = PatchCollection([], zorder=6, linewidths=1.2, match_original=False)
        ax.add_collection(self.ellipses)
        self.track_now = ax.scatter([], [], s=36, edgecolors="white", linewidths=0.8, zorder=8)
        self.on_time, = ax.plot([], [], linestyle="none", marker="o", markersize=3.5, color=OBSERVATION_COLOUR,
                                zorder=9)
        self.late, = ax.plot([], [], linestyle="none", marker="o", markersize=5, markerfacecolor="none",
                             markeredgecolor=OBSERVATION_COLOUR, markeredgewidth=0.9, zorder=9)
        self.false_alarms, = ax.plot([], [], linestyle="none", marker="x", markersize=5, color=FALSE_ALARM_COLOUR,
                                     markeredgewidth=1.3, zorder=9)
        self.labels = []  # the tracks' ids: annotations made afresh every frame
        self.artists = [self.truth_trail, self.truth_now, self.track_trail, self.ellipses, self.track_now,
                        self.on_time, self.late, self.false_alarms]

    def _trail_segments(self, positions_at, ident, t, rgba, strength, segments, colours):
        """The segments of one trail ending at tick t, each fading out over the trail's length."""
        for age in range(self.trail):
            a, b = positions_at.get(t - age - 1, {}).get(ident), positions_at.get(t - age, {}).get(ident)
            if a is None or b is None:
                break
            segments.append(((a[0], a[1]), (b[0], b[1])))
            colours.append(rgba[:3] + (strength * (1.0 - age / (self.trail + 1)),))

    def _draw_truth(self, t):
        from matplotlib.colors import to_rgba
        segments, colours = [], []
        now = self.index.truth_at.get(t, {})
        truth_rgba = to_rgba(TRUTH_COLOUR)
        for ident in now:
            self._trail_segments(self.index.truth_at, ident, t, truth_rgba, 0.55, segments, colours)
        self.truth_trail.set_segments(segments)
        self.truth_trail.set_color(colours)
        self.truth_now.set_data([p[0] for p in now.values()], [p[1] for p in now.values()])

    def _draw_tracks(self, t):
        import numpy as np
        from matplotlib.colors import to_rgba
        from matplotlib.patches import Ellipse
        colour_of = self.index.colour_of
        rows = self.index.track_at.get(t, {})
        segments, colours, patches, edge, face = [], [], [], [], []
        for ident, row in rows.items():
            rgba = to_rgba(colour_of[ident])
            self._trail_segments(self.index.track_xy_at, ident, t, rgba, 1.0, segments, colours)
            axes = ellipse_axes(row[7], row[8], row[11])
            if axes:
                patches.append(Ellipse((row[2], row[3]), axes[0], axes[1], angle=axes[2]))
                edge.append(rgba)
                face.append(rgba[:3] + (0.15,))
        self.track_trail.set_segments(segments)
        self.track_trail.set_color(colours)
        self.ellipses.set_paths(patches)
        self.ellipses.set_edgecolor(edge)
        self.ellipses.set_facecolor(face)
        if rows:
            self.track_now.set_offsets([(row[2], row[3]) for row in rows.values()])
            self.track_now.set_facecolor([colour_of[ident] for ident in rows])
        else:
            self.track_now.set_offsets(np.empty((0, 2)))
        while self.labels:
            self.labels.pop().remove()
        for ident, row in rows.items():
            self.labels.append(self.ax.annotate(
                row[6], (row[2], row[3]), xytext=(6, 5), textcoords="offset points", fontsize=9, fontweight="bold",
                color=colour_of[ident], zorder=10,
                bbox=dict(boxstyle="round,pad=0.12", facecolor="white", edgecolor="none", alpha=0.75)))

    def draw(self, t):
        """Sets every layer to tick t; returns the reports delivered at t: (in time, late, false alarms)."""
        self._draw_truth(t)
        self._draw_tracks(t)
        kinds = ([], [], [])
        for row in self.index.delivered_at.get(t, ()):
            kinds[2 if row[8] < 0 else 1 if row[0] < t else 0].append((row[6], row[7]))
        for line, points in zip((self.on_time, self.late, self.false_alarms), kinds):
            line.set_data([p[0] for p in points], [p[1] for p in points])
        return kinds


def _show_numbers(layout, numbers, parts):
    """The tick's numbers; without spaces and details when the frame is too narrow for them."""
    numbers.set_text("    ".join(parts))
    if numbers.get_window_extent(layout.canvas.get_renderer()).x1 > (layout.fig_w - 0.1) * layout.dpi:
        numbers.set_text("  ".join(part.replace(" = ", "=").split(" (")[0] for part in parts))


def _tick_numbers(t, per_tick, per_tick_index, delivered, kinds):
    """K*, K and OSPA at tick t (when the run has them) and the reports delivered, as text parts."""
    _, k_true, k, ospa = per_tick
    i = per_tick_index.get(t)
    parts = []
    if i is not None:
        parts += [f"K* = {k_true[i]}", f"K = {k[i]}"]
        if ospa[i] is not None:
            parts.append(f"OSPA = {ospa[i]:.2f}")
    details = [f"{len(points)} {what}" for points, what in ((kinds[1], "late"), (kinds[2], "false")) if points]
    parts.append(f"reports {len(delivered)}" + (f" ({', '.join(details)})" if details else ""))
    return parts


def _write_frames(frame, ticks, options):
    """Every frame into the options' sink: first the sample frames a shared palette is made from."""
    sink = options.make_sink()
    samples = getattr(sink, "SAMPLES", 0)
    if samples:
        picks = sorted({ticks[(len(ticks) - 1) * k // max(1, samples - 1)] for k in range(samples)})
        sink.set_samples([frame(t).copy() for t in picks])
    progress = Progress(len(ticks), options.quiet)
    for n, t in enumerate(ticks, 1):
        sink.add(frame(t), t)
        progress.show(n, "drew")
    if not options.quiet:
        print(f"plot_run.py: encoding {len(ticks)} frames", file=sys.stderr, flush=True)
    sink.finish()


def animate(mpl, scenario, sensors, truth, tracks, observations, per_tick, options):
    """Writes the animation of ticks options.first..options.last to options.path; returns the number
    of frames."""
    import numpy as np
    layout = _layout(mpl, options.size)
    ax = _map_axes(layout, scenario)
    _draw_field(ax, layout, scenario, sensors)
    headline, numbers = _headline(layout, scenario)
    ticks = list(range(options.first, options.last + 1))
    index = _indexes(truth, tracks, observations)
    panel = _SidePanel(layout, scenario, per_tick, ticks[0], options.trail, sensors) if layout.side else None
    layers = _MapLayers(ax, index, options.trail)
    per_tick_index = {t: i for i, t in enumerate(per_tick[0])}

    def draw(t):
        kinds = layers.draw(t)
        headline.set_text(f"tick {t} / {scenario['ticks']}")
        _show_numbers(layout, numbers, _tick_numbers(t, per_tick, per_tick_index, index.delivered_at.get(t, ()), kinds))
        if panel is not None:
            panel.update(t, per_tick_index.get(t, -1) + 1)

    # Everything drawn so far but the dynamic artists is the background of every frame: draw it
    # once, then per frame only the artists that change.
    dynamic = layers.artists + [headline, numbers] + (panel.artists if panel is not None else [])
    for artist in dynamic:
        artist.set_animated(True)
    layout.canvas.draw()
    background = layout.canvas.copy_from_bbox(layout.fig.bbox)
    renderer = layout.canvas.get_renderer()

    def frame(t):
        draw(t)
        layout.canvas.restore_region(background)
        for artist in sorted(dynamic + layers.labels, key=lambda a: a.get_zorder()):
            artist.draw(renderer)
        return np.asarray(layout.canvas.buffer_rgba())

    _write_frames(frame, ticks, options)
    return len(ticks)
