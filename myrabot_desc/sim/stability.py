"""Tip-over margin: the centre of mass against the support polygon, under acceleration.

The ground and the support polygon are model/support.py's (the ones check's P001 and the viewer
use): the robot rests on its lowest collision point and every shape within 5 mm of it holds it
up, such as the casters (the bundled Roomba's rear caster hangs 3 mm up and catches the robot
after a small wobble). Under a base acceleration ``a`` (for a steady turn, centripetal: ``w^2``
times the distance to the turn centre) the resultant of gravity and inertia meets the ground at
``com_xy - (h/g) a_xy``, with ``h`` the height of the centre of mass above the ground. The
margin is that point's distance to the nearest polygon edge, positive inside; a negative margin
tips the robot.
"""

from __future__ import annotations

from myrabot_desc.model.hull2d import convex_hull
from myrabot_desc.model.kinematics import pose_matrix, world_transforms
from myrabot_desc.model.shapes import surface_points
from myrabot_desc.model.support import CONTACT_TOL, Support, ground_support, signed_distances

G = 9.81


def support_polygon(robot, drive, meshes=True) -> tuple[Support, list[str]]:
    """model/support.py's ground support, and notes on how the drive wheels take part in it.
    ``meshes``: how mesh collisions are read (model/support.ground_support)."""

    wheels = {drive.urdf.left.link: drive.urdf.left, drive.urdf.right.link: drive.urdf.right}
    tf = world_transforms(robot)
    wheel_ground = float(min(tf[w.link][2, 3] - w.radius for w in wheels.values()))
    s = ground_support(robot, meshes=meshes, world=tf)
    notes = []
    if s is None:      # no collision shape at all: the wheels (measured from their visuals) alone
        contacts = {n: [(w.xy[0], w.xy[1], wheel_ground)] for n, w in sorted(wheels.items())}
        return (Support(ground_z=wheel_ground, contacts=contacts, polygon=_hull([w.xy for w in wheels.values()]),
                        lowest=None),
                ["only the two drive wheels touch the ground: the body rests on whatever hits the floor when it tips"])
    if s.lowest not in wheels and s.ground_z < wheel_ground - CONTACT_TOL:
        notes.append(f"{s.lowest} reaches {wheel_ground - s.ground_z:.3f} m below the wheels' contact line")
    if len(s.polygon) < 3 or abs(s.area) < 1e-6:
        who = "only the two drive wheels touch" if set(s.links) <= set(wheels) else \
            f"only {', '.join(s.links)} touch"
        notes.append(f"{who} the ground: the body rests on whatever hits the floor when it tips")
    return s, notes


def margin(support: Support, com, accel_xy=(0.0, 0.0)) -> float:
    """Signed distance (m) of the loaded centre-of-pressure point to the polygon edge (+ inside)."""
    import numpy as np

    return float(margins(support, np.array([com], dtype=float), np.array([accel_xy], dtype=float))[0])


def margins(support: Support, coms, accels):
    """``margin`` of many poses at once (numpy rows: centres of mass (n, 3), accelerations (n, 2))."""
    import numpy as np

    h = coms[:, 2] - support.ground_z
    loaded = np.column_stack([coms[:, 0] - h / G * accels[:, 0], coms[:, 1] - h / G * accels[:, 1]])
    return signed_distances(support.polygon, loaded)


def _hull(points):
    """Convex hull in the plane, counter-clockwise (``points``: pairs or an (n, 2) array)."""
    import numpy as np

    return convex_hull(np.asarray(points, dtype=float).reshape(-1, 2).tolist())


def footprint(robot):
    """Convex outline (root frame, xy) of the robot's primitive collision geometry at the zero pose."""
    import numpy as np

    tf = world_transforms(robot)
    pts = []
    for ln, link in robot.links.items():
        for c in link.collisions:
            if c.geometry is None or c.geometry.kind == "mesh":
                continue
            p = np.asarray(surface_points(c.geometry, 72, loc=c.loc))
            M = tf[ln] @ pose_matrix(c.origin)
            pts.append((p @ M[:3, :3].T + M[:3, 3])[:, :2])
    return _hull(np.vstack(pts)) if pts else []
