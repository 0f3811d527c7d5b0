"""Tip-over margin: the centre of mass against the support polygon, under acceleration.

The ground is the drive wheels' contact height. The support polygon is the
convex hull of the wheel contact points and of every other collision point that
reaches the ground within 5 mm, such as the casters (the bundled
Roomba's rear caster hangs 3 mm up and catches the robot after a small wobble). Under a base
acceleration ``a`` (for a steady turn, centripetal: ``w^2`` times the distance to
the turn centre) the resultant of gravity and inertia meets the ground at
``com_xy - (h/g) a_xy``, with ``h`` the height of the centre of mass above the
ground. The margin is that point's distance to the nearest polygon edge,
positive inside; a negative margin tips the robot.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

G = 9.81
GROUND_TOL = 0.005     # a caster this close to the floor catches the robot after a wobble of a degree or two


@dataclass
class Support:
    polygon: list[tuple[float, float]]     # convex, counter-clockwise, root frame
    ground_z: float
    links: list[str]
    notes: list[str]

    @property
    def area(self) -> float:
        p = self.polygon
        return 0.5 * sum(p[i][0] * p[(i + 1) % len(p)][1] - p[(i + 1) % len(p)][0] * p[i][1] for i in range(len(p)))


def support_polygon(robot, drive) -> Support:
    import numpy as np

    from myrabot_desc.model.kinematics import pose_matrix, world_transforms
    from myrabot_desc.sim.diffdrive import _geometry_points

    tf = world_transforms(robot)
    wheels = {drive.urdf.left.link: drive.urdf.left, drive.urdf.right.link: drive.urdf.right}
    zc = [tf[w.link][2, 3] - w.radius for w in wheels.values()]
    ground = float(min(zc))
    pts = [w.xy for w in wheels.values()]
    links = list(wheels)
    notes = []
    lowest = (math.inf, None)
    for ln, link in robot.links.items():
        if ln in wheels:
            continue
        for c in link.collisions:
            if c.geometry is None:
                continue
            try:
                p = _geometry_points(robot, c.geometry, c.loc, n=180)
            except Exception:
                continue
            M = tf[ln] @ pose_matrix(c.origin)
            w = p @ M[:3, :3].T + M[:3, 3]
            zmin = float(w[:, 2].min())
            if zmin < lowest[0]:
                lowest = (zmin, ln)
            near = w[w[:, 2] <= ground + GROUND_TOL]
            if len(near):
                pts.extend(near[:, :2].tolist())
                links.append(ln)
    if lowest[1] is not None and lowest[0] < ground - GROUND_TOL:
        notes.append(f"{lowest[1]} reaches {ground - lowest[0]:.3f} m below the wheels' contact line")
    hull = _hull(pts)
    if len(hull) < 3 or abs(_area(hull)) < 1e-6:
        notes.append("only the two drive wheels touch the ground: the body rests on whatever hits the floor "
                     "when it tips")
    return Support(polygon=hull, ground_z=ground, links=sorted(set(links)), notes=notes)


def margin(support: Support, com, accel_xy=(0.0, 0.0)) -> float:
    """Signed distance (m) of the loaded centre-of-pressure point to the polygon edge (+ inside)."""
    import numpy as np

    return float(margins(support, np.array([com], dtype=float), np.array([accel_xy], dtype=float))[0])


def margins(support: Support, coms, accels):
    """``margin`` of many poses at once (numpy rows: centres of mass (n, 3), accelerations (n, 2))."""
    import numpy as np

    poly = support.polygon
    h = coms[:, 2] - support.ground_z
    px = coms[:, 0] - h / G * accels[:, 0]
    py = coms[:, 1] - h / G * accels[:, 1]
    if len(poly) < 3:
        if len(poly) == 2:     # a line: never inside
            (ax, ay), (bx, by) = poly
            L = math.hypot(bx - ax, by - ay) or 1.0
            return -np.abs((bx - ax) * (py - ay) - (by - ay) * (px - ax)) / L
        return np.full(len(coms), -math.inf)
    d = np.full(len(coms), math.inf)
    n = len(poly)
    for i in range(n):
        ax, ay = poly[i]
        bx, by = poly[(i + 1) % n]
        L = math.hypot(bx - ax, by - ay)
        if L < 1e-12:
            continue
        d = np.minimum(d, ((bx - ax) * (py - ay) - (by - ay) * (px - ax)) / L)
    return d


def _area(p) -> float:
    return 0.5 * sum(p[i][0] * p[(i + 1) % len(p)][1] - p[(i + 1) % len(p)][0] * p[i][1] for i in range(len(p)))


def _hull(points):
    """Convex hull in the plane, counter-clockwise (``points``: pairs or an (n, 2) array)."""
    import numpy as np

    from myrabot_desc.model.hull2d import convex_hull

    return convex_hull(np.asarray(points, dtype=float).reshape(-1, 2).tolist())


def footprint(robot):
    """Convex outline (root frame, xy) of the robot's primitive collision geometry at the zero pose."""
    import numpy as np

    from myrabot_desc.model.kinematics import pose_matrix, world_transforms
    from myrabot_desc.sim.diffdrive import _geometry_points

    tf = world_transforms(robot)
    pts = []
    for ln, link in robot.links.items():
        for c in link.collisions:
            if c.geometry is None or c.geometry.kind == "mesh":
                continue
            p = _geometry_points(robot, c.geometry, c.loc, n=72)
            M = tf[ln] @ pose_matrix(c.origin)
            pts.append((p @ M[:3, :3].T + M[:3, 3])[:, :2])
    return _hull(np.vstack(pts)) if pts else []
