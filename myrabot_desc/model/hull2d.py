"""The convex hull of points in the plane (support polygons, footprints), in pure Python.

Andrew's monotone chain: a few thousand points take a millisecond or two, where importing
scipy.spatial for its ConvexHull took ~0.4 s of a `sim` run.
"""

from __future__ import annotations


def convex_hull(points, decimals: int = 9) -> list[tuple[float, float]]:
    """Counter-clockwise hull of (x, y) points, from the lowest x (then y); collinear points are
    dropped. Points are rounded to ``decimals`` first, so near-duplicates count once. All
    points on a line give the line's two ends; fewer than three distinct points, those points.
    """
    pts = sorted({(round(float(p[0]), decimals), round(float(p[1]), decimals)) for p in points})
    if len(pts) <= 2:
        return pts

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower: list = []
    upper: list = []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 1e-12:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 1e-12:
            upper.pop()
        upper.append(p)
    return lower[:-1] + upper[:-1]
