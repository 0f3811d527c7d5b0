"""What a robot stands on: its ground contacts, their support polygon, the signed distance of a
point to that polygon, and the centre of mass against it (``stance``). The one computation behind
check's P001/P004, sim's tip-over margin and stance, and the viewer's ground overlay.

The robot rests on its lowest collision point (root frame, at the configuration asked). Every
collision shape reaching within ``CONTACT_TOL`` of that height touches the ground; the support
polygon is the convex hull of those shapes' lowest points. A sphere (a caster) touches in one
point, a horizontal cylinder (a wheel) along its lowest line, a box or mesh at its vertices
within the tolerance.

``CONTACT_TOL`` is 5 mm. The bundled Roomba's rear caster hangs exactly 3 mm above its wheels'
contact line (the seed's geometry), so check's former 3 mm put that caster on a float rounding
edge (it missed it by 1 µm) while sim's 5 mm counted it. A caster that hangs a few millimetres
up is how two-wheel bases keep both drive wheels loaded: the robot rocks onto it after a wobble
of a degree or two (3 mm at 0.13 m is 1.3°) and stands, which is what both questions, "does it
stand?" (P001) and "does it tip over?" (sim), are about. Something 5 mm up at a 0.1 m lever
already means a 3° rock, where a driver notices the robot dip.
"""

import math

from myrabot_desc.model.hull2d import convex_hull
from myrabot_desc.model.kinematics import center_of_mass, world_transforms
from myrabot_desc.model.shapes import lowest_points, surface_points
from myrabot_desc.model.transforms import compose, pose_T
from myrabot_desc.records import Struct

CONTACT_TOL = 0.005      # m: geometry this close to the lowest point holds the robot up (see above)


class Support(Struct):
    ground_z: float                      # height of the lowest collision point (root frame)
    contacts: dict                       # link name -> [(x, y, z)] points within CONTACT_TOL of the ground
    polygon: list                        # convex hull of the contacts' (x, y), counter-clockwise
    lowest: str | None                   # the link whose geometry is lowest
    com: tuple | None = None             # (stance) (x, y, z) centre of mass at the same configuration
    mass: float | None = None            # (stance) total mass
    margin: float | None = None          # (stance) distance of the projected centre of mass to the polygon's edge, + inside

    @property
    def links(self) -> list[str]:
        return sorted(self.contacts)

    @property
    def area(self) -> float:
        p = self.polygon
        n = len(p)
        return 0.5 * sum(p[i][0] * p[(i + 1) % n][1] - p[(i + 1) % n][0] * p[i][1] for i in range(n)) if n > 2 \
            else 0.0


def _mesh_reader(meshes):
    """(mesh geometry, loc) -> scaled vertices (numpy) or None, from ``meshes``: False (skip
    meshes), True (model.shapes.surface_points: the bounded mesh reader's vertices) or a callable
    geometry -> loaded mesh (check's per-run cache). An unreadable mesh is left out (check's M
    rules say why)."""
    if meshes is False or meshes is None:
        return None
    import numpy as np

    if meshes is True:
        def read(g, loc):
            try:
                return np.asarray(surface_points(g, loc=loc), dtype=float)
            except Exception:        # InputError, or a reader's own failure on a malformed file
                return None
        return read

    def read_loaded(g, loc):
        m = meshes(g)
        if m is None or isinstance(m, str):
            return None
        return np.asarray(getattr(m, "vertices", m), dtype=float)
    return read_loaded


def collision_shapes(robot, world, mesh_of=None):
    """(link, collision item, mesh) of every collision shape of a link ``world`` places, in file
    order: the one walk check's P rules, P005 and the support share. ``mesh`` is None for
    primitives; mesh shapes come with ``mesh_of(geometry, loc)``'s answer and are left out without
    ``mesh_of`` or when it gives None or a reason (a str)."""
    for link in robot.links.values():
        if link.name not in world:
            continue
        for it in link.collisions:
            g = it.geometry
            if g is None:
                continue
            mesh = None
            if g.kind == "mesh":
                if mesh_of is None or g.path is None:
                    continue
                mesh = mesh_of(g, it.loc)
                if mesh is None or isinstance(mesh, str):
                    continue
            yield link, it, mesh


def _pose(T):
    """(R as rows, p) of a world pose given as (R, p) (model/kinematics.rest_poses) or as a 4x4 array
    (world_transforms)."""
    if type(T) is tuple:
        return T
    return T[:3, :3].tolist(), T[:3, 3].tolist()


def lowest(robot, world, meshes=True):
    """[(min z, [(x, y, z) points within CONTACT_TOL of it], link name)] of every collision shape
    placed by ``world`` (link -> (R, p) from model.kinematics.rest_poses, or a 4x4 array from
    world_transforms). Primitives in pure Python: without meshes, nothing here imports numpy."""
    read = _mesh_reader(meshes) if meshes else None
    out = []
    for link, it, v in collision_shapes(robot, world, read):
        R, p = compose(_pose(world[link.name]), pose_T(it.origin))
        if v is not None:
            if not len(v):
                continue
            import numpy as np

            w = v @ np.asarray(R, dtype=float).T + np.asarray(p, dtype=float)
            z = float(w[:, 2].min())
            out.append((z, [tuple(q) for q in w[w[:, 2] <= z + CONTACT_TOL].tolist()], link.name))
            continue
        lp = lowest_points(it.geometry, R, p, None, CONTACT_TOL)
        if lp is not None:
            out.append((float(lp[0]), lp[1], link.name))
    return out


def ground_support(robot, q: dict | None = None, meshes=True, world=None, low=None) -> Support | None:
    """The ground contacts and support polygon at configuration ``q`` (joints not named at 0) with
    the robot resting on its lowest collision point; None when no collision shape can be placed.

    ``meshes``: read mesh collisions (True), skip them (False), or a callable geometry -> loaded
    mesh (check passes its per-run cache). ``world``: the link poses when the caller has them;
    ``low``: ``lowest`` of those poses, when the caller has that too."""

    if low is None:
        low = lowest(robot, world if world is not None else world_transforms(robot, q), meshes)
    if not low:
        return None
    zmin, _, lowest_link = min(low, key=lambda t: t[0])
    contacts: dict = {}
    for z, pts, name in low:
        if z <= zmin + CONTACT_TOL:
            contacts.setdefault(name, []).extend(tuple(float(c) for c in p) for p in pts
                                                 if p[2] <= zmin + CONTACT_TOL)
    hull = convex_hull([p[:2] for ps in contacts.values() for p in ps])
    return Support(ground_z=float(zmin), contacts=contacts, polygon=hull, lowest=lowest_link)


def stance(robot, q: dict | None = None, meshes=True, world=None, low=None) -> Support | None:
    """``ground_support`` with the centre of mass (model/kinematics) at the same configuration and
    its margin (``signed_distance`` of its ground projection): what check's P001/P004, sim's
    stance and the viewer's ground overlay show. None without collision geometry or mass."""
    s = ground_support(robot, q, meshes=meshes, world=world, low=low)
    if s is None:
        return None
    mass, com = center_of_mass(robot, q)
    if not mass > 0:
        return None
    return s._replace(com=com, mass=float(mass), margin=signed_distance(s.polygon, com[:2]))


def signed_distances(polygon, xy):
    """Distance of each point (numpy (n, 2)) to the polygon's boundary, positive inside, negative
    outside. A polygon of two points is a line segment (no inside: always <= 0), of one a point,
    of none: -inf."""
    import numpy as np

    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    if not polygon:
        return np.full(len(xy), -math.inf)
    P = np.asarray(polygon, dtype=float)
    px, py = xy[:, 0], xy[:, 1]
    if len(P) == 1:
        return -np.hypot(px - P[0, 0], py - P[0, 1])
    edges = list(zip(P, np.roll(P, -1, axis=0))) if len(P) > 2 else [(P[0], P[1])]
    d = np.full(len(xy), math.inf)
    inside = np.ones(len(xy), dtype=bool)
    for (ax, ay), (bx, by) in edges:
        dx, dy = bx - ax, by - ay
        L = dx * dx + dy * dy
        t = np.zeros(len(xy)) if L == 0 else np.clip(((px - ax) * dx + (py - ay) * dy) / L, 0.0, 1.0)
        d = np.minimum(d, np.hypot(px - ax - t * dx, py - ay - t * dy))
        inside &= dx * (py - ay) - dy * (px - ax) >= 0
    if len(P) < 3:
        return -d
    return np.where(inside, d, -d)


def signed_distance(polygon, p) -> float:
    """``signed_distances`` of one (x, y) point, with the same formulas in pure Python."""
    px, py = float(p[0]), float(p[1])
    if not polygon:
        return -math.inf
    P = [(float(a), float(b)) for a, b in polygon]
    if len(P) == 1:
        return -math.hypot(px - P[0][0], py - P[0][1])
    edges = list(zip(P, P[1:] + P[:1])) if len(P) > 2 else [(P[0], P[1])]
    d, inside = math.inf, True
    for (ax, ay), (bx, by) in edges:
        dx, dy = bx - ax, by - ay
        L = dx * dx + dy * dy
        t = 0.0 if L == 0 else min(max(((px - ax) * dx + (py - ay) * dy) / L, 0.0), 1.0)
        d = min(d, math.hypot(px - ax - t * dx, py - ay - t * dy))
        inside = inside and dx * (py - ay) - dy * (px - ax) >= 0
    if len(P) < 3:
        return -d
    return d if inside else -d
