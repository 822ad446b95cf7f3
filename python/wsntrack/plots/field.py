"""What every picture of the sensor field shares (tracks.png and the replay animation): colours,
the supernodes' tracking groups and the region, terrain, typed sensors with their coverage, and the
axis unit."""

from .geometry import voronoi_cells


# Track colours far enough apart to tell neighbouring tracks apart (mostly Okabe-Ito), none of
# them the truth's or the sensors' grey; past the ninth track the colours repeat, dashed, then dotted.
TRACK_COLOURS = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#7B3294", "#8C510A", "#8F8A00"]
TRACK_DASHES = ["solid", (0, (5, 2)), (0, (1.5, 1.5))]
REGION_COLOURS = ["#fff3d6", "#e3f0ff", "#e8f6e8", "#f6e6f2", "#eeeeee", "#fde8e0"]
TRUTH_COLOUR = "#8c8c8c"
# Track colours by declared class (tracks.csv's 'class'), when a run's tracks carry class evidence:
# vehicles in blues and green, people in warm colours, aircraft in purple; a track at a tick
# without class evidence is dark grey and dotted.
CLASS_COLOURS = {"wheeled_light": "#56B4E9", "wheeled_heavy": "#0072B2", "tracked": "#009E73",
                 "human": "#D55E00", "group": "#E69F00", "aerial": "#7B3294"}
NO_CLASS_COLOUR = "#333333"
NO_CLASS_DASHES = (0, (1.5, 1.5))

# Masks under everything but the region's tint; roads over the masks, under the target paths.
MASK_COLOURS = {"building": "#8c7b6b", "vegetation": "#7fb77e"}
ROAD_COLOUR = "#8a8a8a"

# Coverage of the typed sensors: faint fills, a thin edge a little stronger, under the masks' edges,
# the tracking-group boundaries, the roads, the target paths and the tracks.
COVERAGE_FILL_ALPHA = 0.10
COVERAGE_EDGE_ALPHA = 0.45
COVERAGE_ZORDER = 1.6

# How tracks.png draws each sensor type of wsntrack.rundir.SENSOR_TYPES: colour (Paul Tol's muted
# palette, apart from the tracks' class colours where it can be) and marker.
SENSOR_TYPE_STYLES = {
    "acoustic_antenna": {"colour": "#44AA99", "marker": "^"},
    "acoustic_beacon": {"colour": "#999933", "marker": "o"},
    "magnetic": {"colour": "#555555", "marker": "s"},
    "pir": {"colour": "#CC6677", "marker": "v"},
    "radar": {"colour": "#882255", "marker": "D"},
    "camera": {"colour": "#332288", "marker": "P"},
}


def length_unit(scenario):
    """The axis unit: sensor separations on a unit grid, else the scenario's own unit with Ds."""
    spacing = scenario["spacing"]
    if spacing is None or spacing == 1:
        return "sensor separations"
    return f"scenario units, Ds = {spacing:g}"


def draw_groups_and_region(ax, Polygon, scenario, bounds):
    """Tints each supernode's tracking group (its Voronoi cell) and outlines the region; returns the
    cells, which the callers also draw the boundaries of."""
    x0, y0, x1, y1 = bounds
    cells = voronoi_cells(scenario["supernodes"], scenario["region"])
    for j, polygon in enumerate(cells):
        if polygon:
            ax.add_patch(Polygon(polygon, closed=True, facecolor=REGION_COLOURS[j % len(REGION_COLOURS)],
                                 edgecolor="none", zorder=0))
    ax.add_patch(Polygon([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], closed=True, fill=False, edgecolor="black",
                         linewidth=0.8, zorder=1))
    return cells


def draw_terrain(ax, Polygon, scenario):
    """Draws the masks (filled) and the roads (grey lines); returns legend handles for what it drew."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    terrain = scenario.get("terrain") or {"roads": [], "masks": []}
    kinds = []
    for kind, polygon in terrain["masks"]:
        colour = MASK_COLOURS.get(kind, "#aaaaaa")
        ax.add_patch(Polygon(polygon, closed=True, facecolor=colour, edgecolor=colour, alpha=0.55, linewidth=0.8,
                             zorder=1.5))
        if kind not in kinds:
            kinds.append(kind)
    for road in terrain["roads"]:
        ax.plot([p[0] for p in road], [p[1] for p in road], color=ROAD_COLOUR, linewidth=3.0, solid_capstyle="round",
                solid_joinstyle="round", zorder=2.5)
    handles = [Patch(facecolor=MASK_COLOURS.get(kind, "#aaaaaa"), alpha=0.55, label=f"mask: {kind}") for kind in kinds]
    if terrain["roads"]:
        handles.append(Line2D([], [], color=ROAD_COLOUR, linewidth=3.0, label="road"))
    return handles


def draw_typed_sensors(ax, scenario):
    """Draws each typed sensor (scenario["typed_sensors"]) as its type's marker, over its coverage:
    a sector of its range and field of view centred on its heading (a disc for a 360-degree field of
    view) in the type's colour, clipped to the region. Returns a legend handle per type present,
    labelled with the type and its number of sensors."""
    from matplotlib.collections import PatchCollection
    from matplotlib.colors import to_rgba
    from matplotlib.lines import Line2D
    from matplotlib.patches import Circle, Patch, Rectangle, Wedge
    x0, y0, x1, y1 = scenario["region"]
    clip = Rectangle((x0, y0), x1 - x0, y1 - y0, transform=ax.transData)
    by_type = {}
    for sensor in scenario["typed_sensors"]["typed"]:
        by_type.setdefault(sensor[0], []).append(sensor)
    handles = []
    for kind, style in SENSOR_TYPE_STYLES.items():
        sensors = by_type.get(kind)
        if not sensors:
            continue
        colour = style["colour"]
        patches = []
        for _, x, y, heading, reach, fov, _ in sensors:
            if fov >= 360.0:
                patches.append(Circle((x, y), reach))
            else:
                patches.append(Wedge((x, y), reach, heading - fov / 2.0, heading + fov / 2.0))
        coverage = PatchCollection(patches, facecolors=[to_rgba(colour, COVERAGE_FILL_ALPHA)],
                                   edgecolors=[to_rgba(colour, COVERAGE_EDGE_ALPHA)], linewidths=0.6,
                                   zorder=COVERAGE_ZORDER)
        ax.add_collection(coverage)
        coverage.set_clip_path(clip)
        marker = dict(linestyle="none", marker=style["marker"], markersize=6.5, markerfacecolor=colour,
                      markeredgecolor="white", markeredgewidth=0.8)
        ax.plot([s[1] for s in sensors], [s[2] for s in sensors], zorder=5, **marker)
        handles.append((Patch(facecolor=to_rgba(colour, 0.22), edgecolor=to_rgba(colour, COVERAGE_EDGE_ALPHA),
                              linewidth=0.6, label=f"{kind} ({len(sensors)})"),
                        Line2D([], [], **marker)))
    return handles
