"""The plane geometry of the plots, without matplotlib: the supernodes' tracking groups (Voronoi
cells clipped to the region) and their boundaries, paths of targets and tracks, a track's path in
pieces of one declared class, and the axes of a covariance ellipse."""

import math


def voronoi_cells(supernodes, region):
    """Cell of each supernode within the region, as a polygon (list of points, maybe empty).
    Ties go to the lower index, as in network_model/topology.cpp."""
    x0, y0, x1, y1 = region
    cells = []
    for i, (sx, sy) in enumerate(supernodes):
        polygon = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
        for j, (tx, ty) in enumerate(supernodes):
            if j == i:
                continue
            if (tx, ty) == (sx, sy):
                if j < i:
                    polygon = []
                continue
            # Keep the points at least as near to supernode i as to j: a . p <= b.
            a = (tx - sx, ty - sy)
            b = (tx * tx + ty * ty - sx * sx - sy * sy) / 2.0
            polygon = _clip(polygon, a, b)
            if not polygon:
                break
        cells.append(polygon)
    return cells


def _clip(polygon, a, b):
    def inside(p):
        return a[0] * p[0] + a[1] * p[1] <= b + 1e-12

    def cut(p, q):
        fp = a[0] * p[0] + a[1] * p[1] - b
        fq = a[0] * q[0] + a[1] * q[1] - b
        s = fp / (fp - fq)
        return (p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1]))

    out = []
    for k, p in enumerate(polygon):
        q = polygon[(k + 1) % len(polygon)]
        if inside(p):
            out.append(p)
            if not inside(q):
                out.append(cut(p, q))
        elif inside(q):
            out.append(cut(p, q))
    return out


def interior_edges(cells, region):
    """Cell edges that are not on the region's border: the tracking-group boundaries."""
    x0, y0, x1, y1 = region
    eps = 1e-9 * max(x1 - x0, y1 - y0)

    def on_border(p, q):
        return ((abs(p[0] - x0) < eps and abs(q[0] - x0) < eps) or (abs(p[0] - x1) < eps and abs(q[0] - x1) < eps)
                or (abs(p[1] - y0) < eps and abs(q[1] - y0) < eps) or (abs(p[1] - y1) < eps and abs(q[1] - y1) < eps))

    seen, edges = set(), []
    for polygon in cells:
        for k, p in enumerate(polygon):
            q = polygon[(k + 1) % len(polygon)]
            key = tuple(sorted((tuple(round(v, 6) for v in p), tuple(round(v, 6) for v in q))))
            if on_border(p, q) or key in seen or key[0] == key[1]:
                continue
            seen.add(key)
            edges.append((p, q))
    return edges


def paths_by_id(rows, id_column):
    """{id: (xs, ys, first tick, last tick)}, a gap of ticks breaking the line (NaN)."""
    paths = {}
    for row in sorted(rows, key=lambda r: (r[id_column], r[0])):
        tick, ident, x, y = row[0], row[id_column], row[id_column + 1], row[id_column + 2]
        if ident not in paths:
            paths[ident] = [[x], [y], tick, tick]
            continue
        path = paths[ident]
        if tick > path[3] + 1:
            path[0].append(math.nan)
            path[1].append(math.nan)
        path[0].append(x)
        path[1].append(y)
        path[3] = tick
    return paths


def class_pieces(rows):
    """The polylines of one track's rows (sorted by tick; row[2:4] is x, y, row[-2] the class
    declared at the tick) in pieces of one class each: [(class, xs, ys)]. The segment between two
    consecutive ticks takes the class of its later tick, so a piece starts at the last point of the
    piece before; a gap of ticks breaks the line. A lone point is a piece of one point."""
    pieces = []
    previous = None
    for row in rows:
        tick, x, y, declared = row[0], row[2], row[3], row[-2]
        joined = previous is not None and tick == previous[0] + 1
        if joined and pieces[-1][0] == declared:
            pieces[-1][1].append(x)
            pieces[-1][2].append(y)
        elif joined:
            pieces.append((declared, [previous[2], x], [previous[3], y]))
        else:
            pieces.append((declared, [x], [y]))
        previous = row
    return pieces


# 2 sigma: the ellipse of Mahalanobis distance 2 around the position, holding 86 % of a 2-D Gaussian.
ELLIPSE_SIGMAS = 2.0


def ellipse_axes(pxx, pxy, pyy, sigmas=ELLIPSE_SIGMAS):
    """(width, height, angle in degrees) of the `sigmas` ellipse of a 2 x 2 position covariance,
    or None when it is zero or not a covariance (not positive semi-definite)."""
    half_trace = (pxx + pyy) / 2.0
    spread = math.hypot((pxx - pyy) / 2.0, pxy)
    major, minor = half_trace + spread, half_trace - spread
    if not major > 0 or minor < -1e-9 * major:
        return None
    angle = math.degrees(0.5 * math.atan2(2.0 * pxy, pxx - pyy))
    return 2 * sigmas * math.sqrt(major), 2 * sigmas * math.sqrt(max(minor, 0.0)), angle
