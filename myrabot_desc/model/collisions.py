"""Self-collision at a configuration: collision shapes of two links that overlap although nothing
lets them, with the depth, the pair and where each shape is written.

Which pairs count. Links joined by fixed joints move as one rigid body (``rigid_bodies``); two
bodies joined by one moving joint are parent and child, whose shapes meet at the joint by design
(MuJoCo, PyBullet and MoveIt skip those pairs too). Every other pair of bodies may not overlap,
unless the model's own exclusions allow it (an SRDF's ``<disable_collisions>``: model/srdf.py).

How they are tested. Boxes, spheres and cylinders are exact: their depth in closed form
(model/penetration.py), in pure Python. Two cylinders at an angle, or a cylinder at an angle to a
box, have none and go to coal (the collision library Pinocchio ships), as do meshes. A mesh is its
convex hull, as MuJoCo and PyBullet collide it; coal gives the penetration depth of the two convex
shapes. A hull overlap that involves a mesh is then confirmed on the triangles themselves (coal's
BVH of the mesh against the other shape): when they do not touch the overlap is ``hull_only``, the
hull of a concave part reaching into another (PR2's shoulder sitting in its concave base: 256 mm of
hull, no triangle). A mesh wholly inside another mesh touches no triangle of it and reads as
hull-only as well; a mesh inside a primitive does not (the primitive is solid). Overlaps of
``TOUCH`` or less are parts resting against each other (CAD assemblies, a tessellated surface,
rounding), not collisions.

coal takes 0.4 s to import: it is imported inside the functions that use it. numpy too: an ordinary
robot at its rest pose without meshes is first screened in pure Python (``Scene._lean_near``, the
same bounding spheres and boxes, and the capsules that hold spheres and cylinders), and the pairs
that come near are settled in closed form (``Scene._pure_overlaps``): such a robot needs neither.
"""

import functools
import math

from myrabot_desc.errors import InputError
from myrabot_desc.model import meshes as meshio
from myrabot_desc.model.kinematics import pose_stack, poses_at, stack_by_identity, world_transforms
from myrabot_desc.model.penetration import Solid, penetration
from myrabot_desc.model.shapes import describe
from myrabot_desc.model.support import _mesh_reader, collision_shapes
from myrabot_desc.model.transforms import compose, pose_T, transpose3
from myrabot_desc.model.tree import maps
from myrabot_desc.records import Struct
from myrabot_desc.safety import limit

TOUCH = 0.001        # m: overlaps this shallow are contact (see the module docstring)
LEAN_MOST = 1000     # collision shapes: up to this many, the pure-Python screen first (numpy's sweep past it)


class TooManyPairs(InputError):
    """More pairs of shapes meet than self-collision tests one by one (links all at one place)."""


def _sphere_pairs(np, items, min_depth: float) -> list:
    """(i, j), i < j, of the shapes whose bounding spheres overlap by more than ``min_depth``, in order,
    refused past ``max_collision_pairs`` (TooManyPairs) before any pair is tested.

    Sweep and prune along x: only spheres whose x extents meet can overlap, so a chain or a spread-out
    tree tests a few neighbours per shape instead of every other shape; candidates are taken a chunk
    at a time (memory linear in the shape count) and judged by the same distance as before."""
    C = np.array([i.centre for i in items], dtype=float).reshape(-1, 3)
    R = np.array([i.radius for i in items], dtype=float)
    return _sphere_pairs_of(np, C, R, min_depth)


def _sphere_pairs_of(np, C, R, min_depth: float) -> list:
    """_sphere_pairs of the shapes whose bounding spheres are centred at the rows of ``C`` (n x 3)
    with radii ``R`` (n): the placed shapes' own arrays, before any of them is an _Item."""
    most = limit("max_collision_pairs")
    n = len(C)
    if n < 2:
        return []
    # widened a hair: |dx| <= distance holds in exact arithmetic, the margin keeps it after rounding
    reach = R + (max(0.0, -min_depth) + 1e-9 * (1.0 + float(np.abs(C).max()) + float(R.max())))
    lo, hi = C[:, 0] - reach, C[:, 0] + reach
    order = np.argsort(lo, kind="stable")
    lo_s, hi_s = lo[order], hi[order]
    stop = np.searchsorted(lo_s, hi_s, side="right")       # sorted places p+1 .. stop-1 meet place p in x
    counts = np.maximum(stop - np.arange(n) - 1, 0)
    found_i: list = []
    found_j: list = []
    total = 0
    # chunks of a few times the limit: shapes piled past it are refused after the first, not after a
    # million candidate distances
    p, chunk = 0, min(1 << 20, max(1 << 16, 4 * most))
    cum = np.concatenate([[0], np.cumsum(counts)])
    while p < n:
        q = max(p + 1, int(np.searchsorted(cum, cum[p] + chunk, side="right")) - 1)
        q = min(q, n)
        k = counts[p:q]
        if k.sum():
            first = np.repeat(np.arange(p, q), k)
            step = np.arange(int(k.sum())) - np.repeat(np.cumsum(k) - k, k)
            a, b = order[first], order[first + 1 + step]
            d = np.linalg.norm(C[a] - C[b], axis=1)
            hit = d < R[a] + R[b] - min_depth
            a, b = a[hit], b[hit]
            total += len(a)
            if total > most:
                raise TooManyPairs(f"self-collision: over {most} pairs of collision shapes meet at this pose (the "
                                   "links are probably all at one place); not tested pair by pair "
                                   "(MYRABOT_DESC_MAX_COLLISION_PAIRS)")
            found_i.append(np.minimum(a, b))
            found_j.append(np.maximum(a, b))
        p = q
    if not total:
        return []
    ii, jj = np.concatenate(found_i), np.concatenate(found_j)
    keep = np.lexsort((jj, ii))
    return list(zip(ii[keep].tolist(), jj[keep].tolist()))


class Overlap(Struct):
    link_a: str                  # the links whose collision shapes overlap (a first in the file)
    link_b: str
    body_a: str                  # their rigid bodies, by the link that heads each
    body_b: str
    depth: float                 # m: penetration depth of the two (convex) shapes
    point: tuple                 # (x, y, z) in the root frame: where they overlap
    loc_a: object                # the <collision> elements (diagnostics.Loc or None)
    loc_b: object
    shape_a: str                 # "box 0.1 0.1 0.2", "mesh link5.stl"
    shape_b: str
    hull_only: bool = False      # the convex hulls overlap, the triangles do not touch
    allowed: object = None       # the exclusion that lets the pair touch (srdf.Disabled), if any

    @property
    def pair(self) -> str:
        return f"{self.link_a}/{self.link_b}"


def rigid_bodies(robot) -> dict[str, str]:
    """link -> the link heading its rigid body (fixed joints merged upward)."""
    out: dict[str, str] = {}
    parent_joint = maps(robot).parent_joint.get      # robot.parent_joint without a call per hop
    links, most = robot.links, len(robot.joints)
    for name in links:
        cur, hops = name, 0
        while hops <= most:
            pj = parent_joint(cur)
            if pj is None or pj.type != "fixed" or pj.parent not in links:
                break
            cur, hops = pj.parent, hops + 1
        out[name] = cur
    return out


def adjacent_bodies(robot, body_of: dict) -> set:
    """frozenset({body, body}) of every two bodies one moving joint joins."""
    return {frozenset((body_of[j.parent], body_of[j.child])) for j in robot.joints.values()
            if j.type != "fixed" and j.parent in body_of and j.child in body_of}


class _Item(Struct):
    link: str
    body: str
    collision: object
    shape: object                # a coal geometry
    T: object                    # 4x4 world pose
    centre: object               # bounding sphere in the world
    radius: float
    mesh: object                 # vertices (mesh shapes) or None
    half: object = None          # half extents of its bounding box (centred on ``centre``, turned as T)


def _coal_shape(coal, np, g, vertices):
    """A coal geometry for a URDF geometry (a mesh: the convex hull of its vertices), or None."""
    if g.kind == "box":
        return coal.Box(*map(float, g.size))
    if g.kind == "sphere":
        return coal.Sphere(float(g.radius))
    if g.kind == "cylinder":
        return coal.Cylinder(float(g.radius), float(g.length))
    key = _mesh_key(g)
    if key is not None and key in _HULLS:
        return _HULLS[key]
    pts = coal.StdVec_Vec3s()
    pts.extend(np.ascontiguousarray(vertices, dtype=float))
    try:
        hull = coal.Convex.convexHull(pts, False, "")
    except Exception:                    # qhull refuses what it cannot hull (a flat mesh): left out
        hull = None
    if key is not None:
        if len(_HULLS) >= 512:
            _HULLS.pop(next(iter(_HULLS)))
        _HULLS[key] = hull
    return hull


_HULLS: dict = {}            # mesh key -> coal hull (or None): robots of one run share mesh files


def _mesh_key(g):
    """(path, mtime, scale) of a mesh geometry, None when its file cannot be stat'ed."""
    try:
        return (str(g.path), g.path.stat().st_mtime_ns, tuple(g.scale))
    except (OSError, AttributeError):
        return None


def _local_box(np, g, vertices):
    """(centre, half extents) of the box holding the shape in its own frame; None for a shape with
    no volume to collide (a zero size, a flat or degenerate mesh)."""
    if g.kind == "box":
        h = np.asarray(g.size, dtype=float) / 2
    elif g.kind == "sphere":
        h = np.full(3, float(g.radius))
    elif g.kind == "cylinder":
        h = np.array([g.radius, g.radius, g.length / 2], dtype=float)
    else:
        v = np.asarray(vertices, dtype=float)
        if len(v) < 4 or not np.isfinite(v).all():
            return None
        lo, hi = v.min(axis=0), v.max(axis=0)
        if (hi - lo).min() <= 1e-9 * max((hi - lo).max(), 1e-300):
            return None                  # flat along an axis: a decal, no volume
        return (lo + hi) / 2, (hi - lo) / 2
    return (np.zeros(3), h) if h.min() > 0 and np.isfinite(h).all() else None


def _boxes_meet(np, A, B, margin: float) -> bool:
    """Do two oriented boxes (centre, rotation, half extents) overlap by more than ``margin``: the
    separating axis test over their 15 axes (face normals and edge cross products)."""
    (ca, Ra, ha), (cb, Rb, hb) = A, B
    axes = np.concatenate([Ra.T, Rb.T, np.cross(Ra.T[:, None, :], Rb.T[None, :, :]).reshape(9, 3)])
    n = np.sqrt((axes * axes).sum(axis=1))
    axes = axes[n > 1e-9] / n[n > 1e-9, None]
    reach = np.abs(axes @ Ra) @ ha + np.abs(axes @ Rb) @ hb
    return bool(np.all(np.abs(axes @ (cb - ca)) <= reach - margin))


def _clearly_apart(np, C, R, H, pairs, margin: float):
    """For each pair (i, j): True when the boxes (centres C, rotations R, half extents H) are apart by
    a clear margin on one of the separating axes _boxes_meet tests, all pairs in a few array calls.
    Only a clear verdict is taken: a pair within rounding of meeting (or not clearly apart) is left
    to _boxes_meet, so the answer is _boxes_meet's to the bit."""
    a = np.array([i for i, _ in pairs], dtype=np.intp)
    b = np.array([j for _, j in pairs], dtype=np.intp)
    At, Bt = np.swapaxes(R[a], 1, 2), np.swapaxes(R[b], 1, 2)               # rows: each box's axes
    axes = np.concatenate([At, Bt, np.cross(At[:, :, None, :], Bt[:, None, :, :]).reshape(-1, 9, 3)], axis=1)
    n = np.sqrt((axes * axes).sum(axis=2))
    use = n > 2e-9                       # kept by _boxes_meet too (its cut is 1e-9)
    axes = axes / np.where(use, n, 1.0)[:, :, None]
    reach = (np.abs(axes @ R[a]) * H[a][:, None, :]).sum(axis=2) + (np.abs(axes @ R[b]) * H[b][:, None, :]).sum(axis=2)
    gap = np.abs((axes * (C[b] - C[a])[:, None, :]).sum(axis=2)) - (reach - margin)
    # rounding differs from _boxes_meet's by a few ulps of these magnitudes; demand far more
    scale = 1.0 + np.abs(C[a]).sum(axis=1) + np.abs(C[b]).sum(axis=1) + H[a].sum(axis=1) + H[b].sum(axis=1) + abs(margin)
    return ((gap > 1e-9 * scale[:, None]) & use).any(axis=1)


def _half_extents(g):
    """_local_box's half extents of a primitive as floats (its centre is its origin), None for no
    volume, False for what the pure screen leaves to numpy (a size that is not three numbers)."""
    try:
        if g.kind == "box":
            if len(g.size) != 3:
                return False
            h = tuple(float(x) / 2 for x in g.size)
        elif g.kind == "sphere":
            r = float(g.radius)
            h = (r, r, r)
        elif g.kind == "cylinder":
            r = float(g.radius)
            h = (r, r, float(g.length / 2))
        else:
            return False
    except (TypeError, ValueError):
        return False
    return h if min(h) > 0 and all(map(math.isfinite, h)) else None


def _lean_sphere_pairs(C, R, min_depth: float, most: int):
    """_sphere_pairs in pure Python, looser by a rounding slack: (i, j), i < j, sorted, a superset
    of its pairs for centres and radii within rounding of its own; None past ``most`` pairs."""
    n = len(C)
    if n < 2:
        return []
    slack = 1e-9 * (1.0 + max(abs(x) for c in C for x in c) + max(R) + abs(min_depth))
    grow = max(0.0, -min_depth) + 2 * slack          # |dx| <= distance: the sweep keeps every pair
    lo = [c[0] - r - grow for c, r in zip(C, R)]
    hi = [c[0] + r + grow for c, r in zip(C, R)]
    order = sorted(range(n), key=lo.__getitem__)
    sqrt = math.sqrt
    out: list = []
    for p, i in enumerate(order):
        (xi, yi, zi), top, reach = C[i], hi[i], R[i] - min_depth + slack
        for k in range(p + 1, n):
            j = order[k]
            if lo[j] > top:
                break
            xj, yj, zj = C[j]
            if sqrt((xi - xj) ** 2 + (yi - yj) ** 2 + (zi - zj) ** 2) < reach + R[j]:
                out.append((i, j) if i < j else (j, i))
                if len(out) > most:
                    return None
    out.sort()
    return out


def _segment_distance(p1, q1, p2, q2) -> float:
    """The distance between the segments p1-q1 and p2-q2 (points: a segment of length zero), by
    the closest points of the two lines clamped to the segments (Ericson, Real-Time Collision
    Detection, 5.1.9)."""
    d1 = (q1[0] - p1[0], q1[1] - p1[1], q1[2] - p1[2])
    d2 = (q2[0] - p2[0], q2[1] - p2[1], q2[2] - p2[2])
    r = (p1[0] - p2[0], p1[1] - p2[1], p1[2] - p2[2])
    a = d1[0] * d1[0] + d1[1] * d1[1] + d1[2] * d1[2]
    e = d2[0] * d2[0] + d2[1] * d2[1] + d2[2] * d2[2]
    f = d2[0] * r[0] + d2[1] * r[1] + d2[2] * r[2]
    if a <= 1e-30 and e <= 1e-30:
        s = t = 0.0
    elif a <= 1e-30:
        s, t = 0.0, min(max(f / e, 0.0), 1.0)
    else:
        c = d1[0] * r[0] + d1[1] * r[1] + d1[2] * r[2]
        if e <= 1e-30:
            s, t = min(max(-c / a, 0.0), 1.0), 0.0
        else:
            b = d1[0] * d2[0] + d1[1] * d2[1] + d1[2] * d2[2]
            den = a * e - b * b
            s = min(max((b * f - c * e) / den, 0.0), 1.0) if den > 1e-30 * a * e else 0.0
            t = (b * s + f) / e
            if t < 0.0:
                s, t = min(max(-c / a, 0.0), 1.0), 0.0
            elif t > 1.0:
                s, t = min(max((b - c) / a, 0.0), 1.0), 1.0
    x = [p1[k] + d1[k] * s - p2[k] - d2[k] * t for k in range(3)]
    return math.sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2])


def _core(g, h):
    """(radius, half length) of a sphere or cylinder with _half_extents ``h``: the segment along
    its z axis that, swollen by the radius, holds it (a capsule); None for other shapes."""
    kind = g.kind
    return (h[0], 0.0) if kind == "sphere" else (h[0], h[2]) if kind == "cylinder" else None


def _capsules_clear(ca, Ra, core_a, cb, Rb, core_b, min_depth: float) -> bool:
    """Two spheres or cylinders that surely overlap by no more than ``min_depth``: the capsules
    that hold them (their core segments swollen by the radii) are apart or overlap by less, with a
    micrometre to spare for the rounding of coal's own depth. A shape inside another overlaps a
    third by no more than the other does; two capsules whose segments are d > 0 apart are parted by
    moving one r_a + r_b - d along the line of their closest points."""
    (ra, la), (rb, lb) = core_a, core_b
    ends = []
    for c, R, half in ((ca, Ra, la), (cb, Rb, lb)):
        u = (R[0][2] * half, R[1][2] * half, R[2][2] * half)          # the shape's z axis in the world
        ends.append(((c[0] - u[0], c[1] - u[1], c[2] - u[2]), (c[0] + u[0], c[1] + u[1], c[2] + u[2])))
    d = _segment_distance(*ends[0], *ends[1])
    return d > 0 and ra + rb - d <= min_depth - 1e-6


def _lean_apart(ca, Ra, ha, cb, Rb, hb, margin: float) -> bool:
    """_clearly_apart for one pair in pure Python (rotations as rows, model/transforms.py): apart by
    a clear margin on a face normal or on an edge cross product that is no near-parallel sliver
    (whose direction rounding turns), so that _boxes_meet, with poses within rounding of these,
    says they do not meet. Not clearly apart: left to _boxes_meet."""
    ua, ub = transpose3(Ra), transpose3(Rb)          # rows: each box's axes in the world
    d = (cb[0] - ca[0], cb[1] - ca[1], cb[2] - ca[2])
    clear = 1e-9 * (1.0 + sum(map(abs, ca)) + sum(map(abs, cb)) + sum(ha) + sum(hb) + abs(margin))

    def gap(u):
        ra = sum(abs(u[0] * a[0] + u[1] * a[1] + u[2] * a[2]) * h for a, h in zip(ua, ha))
        rb = sum(abs(u[0] * b[0] + u[1] * b[1] + u[2] * b[2]) * h for b, h in zip(ub, hb))
        return abs(u[0] * d[0] + u[1] * d[1] + u[2] * d[2]) - (ra + rb - margin)

    for u in ua + ub:
        if gap(u) > clear:
            return True
    for a in ua:
        for b in ub:
            u = (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
            n = math.sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2])
            if n > 1e-3 and gap((u[0] / n, u[1] / n, u[2] / n)) > clear:
                return True
    return False


def _deepest_first(o: Overlap) -> tuple:
    """overlaps()'s order: deepest first (to 0.1 µm: coal's last digits do not reorder), then by links."""
    return (-round(o.depth, 7), o.link_a, o.link_b)


class Scene:
    """The robot's collision shapes, made once (hulls are the costly part), placed at any
    configuration by :meth:`overlaps`."""

    def __init__(self, robot, meshes=True, exclusions=None):
        """``meshes``: read mesh collisions (True), skip them (False), or a callable geometry ->
        loaded mesh (check's per-run cache). ``exclusions``: an object with ``allows(a, b)``
        (model/srdf.Srdf) or None."""
        self.robot = robot
        self.exclusions = exclusions
        self.read = _mesh_reader(meshes)
        self.loaded = meshes if callable(meshes) else None   # check's loaded meshes: their faces too
        self.skipped: list = []          # (link, why) of collision shapes left out
        self._shapes: dict = {}          # id(collision) -> coal shape
        self._local: dict = {}           # id(collision) -> bounding box in its own frame
        self._by_geometry: dict = {}     # (kind, primitive geometry) -> (its bounding box,)
        self._halves: dict = {}          # id(collision) -> _half_extents (_half)
        self._lean_shapes: list = []     # the pure screen's last places

    @functools.cached_property
    def body_of(self) -> dict:
        """link -> the link heading its rigid body: asked only once shapes come near (a scene whose
        pairs are refused as too many, or that no pair reaches, never walks the tree for it)."""
        return rigid_bodies(self.robot)

    @functools.cached_property
    def adjacent(self) -> set:
        return adjacent_bodies(self.robot, self.body_of)

    def _placed(self, world):
        """Every collision shape placed by ``world`` with its bounding box (no coal shape yet)."""
        placed = self._placing(world)
        return self._items(*placed) if placed is not None else []

    def _items(self, found, T, centres, radii):
        """The _Item of each shape _placing placed."""
        body_of = self.body_of
        radii = radii.tolist()
        return [_Item(name, body_of.get(name, name), it, None, T[k], centres[k], radii[k], mesh, box[1])
                for k, (name, it, mesh, box) in enumerate(found)]

    def _placing(self, world):
        """(shapes, their world poses T, centres, radii) of every collision shape placed by ``world``
        with its bounding box, the last three stacked (n x 4 x 4, n x 3, n), or None
        when there is none: the sphere sweep reads the arrays, and _items makes the records only of a
        scene whose pairs it took.

        support.collision_shapes' walk, with the poses, centres and radii as stacked products: the
        same kernels, so the same bits as one product per shape, without a dozen numpy calls per
        shape."""
        import numpy as np

        local, by_geometry = self._local, self._by_geometry
        found, frames, origins = [], [], []
        for link, it, mesh in collision_shapes(self.robot, world, self.read):
            g = it.geometry
            key = id(it)
            if key not in local:
                if mesh is None:     # a primitive's box is its size's: equal sizes share one
                    try:
                        box = by_geometry.get((g.kind, g))
                        if box is None:
                            box = by_geometry[(g.kind, g)] = (_local_box(np, g, mesh),)
                        local[key] = box[0]
                    except TypeError:            # a size given as a list: not hashable
                        local[key] = _local_box(np, g, mesh)
                else:
                    local[key] = _local_box(np, g, mesh)
            box = local[key]
            if box is None:
                continue
            found.append((link.name, it, mesh, box))
            frames.append(world[link.name])
            origins.append(it.origin)
        if not found:
            return None
        T = np.array(frames, dtype=float).reshape(-1, 4, 4) @ pose_stack(origins)
        boxes = [f[3] for f in found]           # (equal primitives share one box)
        c = stack_by_identity([box[0] for box in boxes], (3,))
        h = stack_by_identity([box[1] for box in boxes], (3,))
        centres = (T[:, :3, :3] @ c[:, :, None])[:, :, 0] + T[:, :3, 3]
        radii = np.sqrt((h[:, None, :] @ h[:, :, None])[:, 0, 0])     # np.linalg.norm's dot
        return found, T, centres, radii

    def _near(self, np, items, min_depth: float, within=None, spheres=None) -> list:
        """(i, j) of the placed shapes on different, non-adjacent bodies whose bounding spheres and
        boxes meet by more than ``min_depth``, in order: the pairs overlaps() tests. ``within``: a set of
        pairs holding all of them (_lean_near's), the others need no box test. ``spheres``: the
        pairs whose bounding spheres meet, when the caller has them (_sphere_pairs of ``items``)."""
        adjacent = self.adjacent
        pairs = [(a, b) for a, b in (_sphere_pairs(np, items, min_depth) if spheres is None else spheres)
                 if (within is None or (a, b) in within)
                 and items[a].body != items[b].body and frozenset((items[a].body, items[b].body)) not in adjacent]
        apart = ()
        if len(pairs) > 8:              # a long chain's neighbours: thousands of box tests, one batch
            C = np.array([i.centre for i in items], dtype=float).reshape(-1, 3)
            R = np.array([i.T[:3, :3] for i in items], dtype=float).reshape(-1, 3, 3)
            H = np.array([i.half for i in items], dtype=float).reshape(-1, 3)
            apart = _clearly_apart(np, C, R, H, pairs, min_depth).tolist()
        return [(a, b) for k, (a, b) in enumerate(pairs)
                if not (apart and apart[k])
                and _boxes_meet(np, (items[a].centre, items[a].T[:3, :3], items[a].half),
                                (items[b].centre, items[b].T[:3, :3], items[b].half), min_depth)]

    def _lean_near(self, q, min_depth: float):
        """``_near``'s pairs at ``q`` in pure Python, for a scene without meshes and of at most
        LEAN_MOST shapes: a superset of those that overlap by more than ``min_depth`` (dropped: pairs
        clearly apart, and spheres and cylinders that _capsules_clear), [] when no pair can; None
        when the screen does not apply (the caller takes numpy's path).

        The poses are poses_at's (within rounding of world_transforms'), so every test keeps a
        rounding slack and drops a pair only where numpy's test drops it too: [] here means none
        there. The place where the size decides: past LEAN_MOST shapes numpy's sweep is faster."""
        robot = self.robot
        if self.read is not None or sum(len(link.collisions) for link in robot.links.values()) > LEAN_MOST:
            return None
        poses = poses_at(robot, q or {})[0]
        if poses is None:
            return None
        body_of = self.body_of
        bodies, C, R, H, rot, cores = [], [], [], [], [], []
        self._lean_shapes = shapes = []      # (link, collision, Solid) by place: for _pure_overlaps
        for link, it, _ in collision_shapes(robot, poses, None):
            h = self._half(it)
            if h is None:
                continue
            if h is False:
                return None
            Rw, p = compose(poses[link.name], pose_T(it.origin))
            bodies.append(body_of.get(link.name, link.name))
            C.append(p)
            R.append(math.sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]))
            H.append(h)
            rot.append(Rw)
            cores.append(_core(it.geometry, h))
            shapes.append((link.name, it, Solid(it.geometry.kind, h, Rw, p)))
        pairs = _lean_sphere_pairs(C, R, min_depth, limit("max_collision_pairs"))
        if pairs is None:
            return None                  # numpy's sweep may refuse them (TooManyPairs)
        adjacent = self.adjacent
        return [(a, b) for a, b in pairs
                if bodies[a] != bodies[b] and frozenset((bodies[a], bodies[b])) not in adjacent
                and not _lean_apart(C[a], rot[a], H[a], C[b], rot[b], H[b], min_depth)
                and not (cores[a] and cores[b]
                         and _capsules_clear(C[a], rot[a], cores[a], C[b], rot[b], cores[b], min_depth))]

    def _pure_overlaps(self, pairs, min_depth: float):
        """overlaps()'s result for ``pairs`` of _lean_near's places, every one settled in closed form
        (model/penetration.py); None when some pair has none (two cylinders at an angle): then coal."""
        shapes = self._lean_shapes
        out = []
        for a, b in pairs:
            (la, ia, sa), (lb, ib, sb) = shapes[a], shapes[b]
            got = penetration(sa, sb)
            if got is NotImplemented:
                return None
            if got is not None and got.depth > min_depth:
                out.append(self._overlap(la, lb, ia, ib, got.depth, got.point, False))
        out.sort(key=_deepest_first)
        return out

    def _overlap(self, la, lb, ia, ib, depth, point, hull_only) -> Overlap:
        """The Overlap of collision ``ia`` of link ``la`` and ``ib`` of ``lb``, with the exclusion
        that allows it (the links', else their bodies')."""
        body_a, body_b = self.body_of.get(la, la), self.body_of.get(lb, lb)
        allowed = self.exclusions.allows(la, lb) if self.exclusions is not None else None
        if allowed is None and self.exclusions is not None and (body_a, body_b) != (la, lb):
            allowed = self.exclusions.allows(body_a, body_b)
        return Overlap(la, lb, body_a, body_b, depth, tuple(float(x) for x in point), ia.loc, ib.loc,
                       describe(ia.geometry), describe(ib.geometry), hull_only, allowed)

    def _shape(self, coal, np, item):
        key = id(item.collision)
        if key not in self._shapes:
            s = _coal_shape(coal, np, item.collision.geometry, item.mesh)
            self._shapes[key] = s
            if s is None:
                self.skipped.append((item.link, f"{describe(item.collision.geometry)}: no volume to collide"))
        return self._shapes[key]

    def overlaps(self, q: dict | None = None, world=None, min_depth: float = TOUCH) -> list[Overlap]:
        """Every overlap deeper than ``min_depth`` at configuration ``q`` (joints not named at 0;
        or the link poses ``world``), deepest first; one per pair of shapes. Only shapes whose
        bounding spheres and boxes meet are tested: primitives in closed form, the rest by coal (a
        hull is made the first time a shape is)."""
        screened = self._lean_near(q, min_depth) if world is None else None
        if screened == []:
            return []                    # no pair comes near: neither numpy nor coal is needed
        if screened is not None:
            pure = self._pure_overlaps(screened, min_depth)
            if pure is not None:
                return pure
        import numpy as np

        world = world if world is not None else world_transforms(self.robot, q)
        placed = self._placing(world)
        if placed is None or len(placed[0]) < 2:
            return []
        # the spheres' pairs from the stacked centres and radii (the values _Item holds), refused
        # (TooManyPairs) before a record is made for each shape
        spheres = _sphere_pairs_of(np, placed[2], placed[3], min_depth)
        if not spheres:
            return []
        items = self._items(*placed)
        near = self._near(np, items, min_depth, None if screened is None else set(screened), spheres)
        if not near:
            return []
        coal = req = None
        out = []
        for a, b in near:
            ia, ib = items[a], items[b]
            got = self._solid_contact(ia, ib)
            if got is NotImplemented:
                if coal is None:
                    import coal          # only for a pair no closed form settles: most robots never pay for it

                    req = coal.CollisionRequest()
                    req.enable_contact = True
                    req.num_max_contacts = 1
                got = self._coal_contact(coal, np, req, ia, ib)
            if got is None or got[0] <= min_depth:
                continue
            depth, point, hull_only = got
            out.append(self._overlap(ia.link, ib.link, ia.collision, ib.collision, depth, point, hull_only))
        out.sort(key=_deepest_first)
        return out

    def _solid_contact(self, ia, ib):
        """(depth, point, False) of two placed primitives in closed form, None when they do not
        overlap, NotImplemented when a mesh is one of them or the pair has no closed form."""
        sa, sb = self._solid(ia), self._solid(ib)
        if sa is None or sb is None:
            return NotImplemented
        got = penetration(sa, sb)
        if got is NotImplemented or got is None:
            return got
        return got.depth, got.point, False

    def _solid(self, item):
        """The penetration.Solid of a placed primitive, None for a mesh or a size that is not three numbers."""
        if item.mesh is not None:
            return None
        h = self._half(item.collision)
        if not h:
            return None
        T = item.T.tolist()
        R = tuple(tuple(row[:3]) for row in T[:3])
        return Solid(item.collision.geometry.kind, h, R, (T[0][3], T[1][3], T[2][3]))

    def _half(self, collision):
        """_half_extents of a collision's geometry, made once per collision."""
        key = id(collision)
        h = self._halves.get(key, 0)
        if h == 0:
            h = self._halves[key] = _half_extents(collision.geometry)
        return h

    def _coal_contact(self, coal, np, req, ia, ib):
        """(depth, point, hull_only) of two placed shapes by coal (hull against hull for meshes,
        then their triangles), None when they do not overlap."""
        sa, sb = self._shape(coal, np, ia), self._shape(coal, np, ib)
        if sa is None or sb is None:
            return None
        res = coal.CollisionResult()
        if not coal.collide(sa, _tf(coal, ia.T), sb, _tf(coal, ib.T), req, res):
            return None
        c = res.getContact(0)
        hull_only = False
        if ia.mesh is not None or ib.mesh is not None:
            hull_only = not self._triangles_touch(coal, np, ia._replace(shape=sa), ib._replace(shape=sb))
        return abs(float(c.penetration_depth)), c.pos, hull_only

    def _triangles_touch(self, coal, np, ia, ib) -> bool:
        """Do the shapes themselves touch: a mesh's triangles against the other (a primitive is
        solid; two meshes: triangle against triangle). Only a mesh's triangles that reach into the
        other shape's bounding box are tested. True when a mesh's triangles cannot be read."""
        objs = []
        for it, other in ((ia, ib), (ib, ia)):
            if it.mesh is None:
                objs.append((it.shape, _tf(coal, it.T)))
                continue
            tri = _triangles(it.collision.geometry, self.loaded)
            if tri is None:
                return True
            v, f, lo_t, hi_t = tri
            # the other's bounding box, as an axis-aligned box in this mesh's frame
            R, p = it.T[:3, :3], it.T[:3, 3]
            Ro = other.T[:3, :3]
            c = R.T @ (other.centre - p)
            h = np.abs(R.T @ Ro) @ other.half
            keep = np.all((lo_t <= c + h) & (hi_t >= c - h), axis=1)
            if not keep.any():
                return False
            sub = f[keep]
            used, inverse = np.unique(sub, return_inverse=True)
            bvh = coal.BVHModelOBBRSS()
            bvh.beginModel(len(sub), len(used))
            bvh.addVertices(np.ascontiguousarray(v[used]))
            bvh.addTriangles(np.ascontiguousarray(inverse.reshape(-1, 3), dtype=np.int64))
            bvh.endModel()
            objs.append((bvh, _tf(coal, it.T)))
        if ia.mesh is None:              # coal wants the BVH first
            objs.reverse()
        req = coal.CollisionRequest()
        req.num_max_contacts = 1
        res = coal.CollisionResult()
        return bool(coal.collide(objs[0][0], objs[0][1], objs[1][0], objs[1][1], req, res))


_TRIANGLES: dict = {}        # mesh key -> (vertices, faces, triangle box lows, highs): robots of a run share meshes
_MAX_TRIANGLES = 2_000_000   # triangles kept across robots


def _triangles(g, loaded=None):
    """(vertices, faces, each triangle's box low and high corners) of a mesh file with the URDF
    scale applied, in its own frame; None when unreadable. ``loaded``: geometry -> the mesh check
    has read already (model/meshes.MeshFacts, scale applied), whose triangles serve as they are."""
    import numpy as np

    key = _mesh_key(g)
    if key is None:
        return None
    got = _TRIANGLES.get(key)
    if got is None:
        m = loaded(g) if loaded is not None else None
        if getattr(m, "faces", None) is not None:       # the same triangles; a touch test needs no order
            v, f = np.asarray(m.vertices, dtype=float), np.asarray(m.faces, dtype=np.int64)
        else:
            try:
                v, f = meshio.triangles(g.path, any_order=True)      # a touch test: any face order
            except Exception:        # MeshError, or a reader's own failure: the hull verdict stands
                return None
            v = np.asarray(v, dtype=float) * np.asarray(g.scale, dtype=float)
            f = np.asarray(f, dtype=np.int64)
        corners = v[f]
        got = (v, f, corners.min(axis=1), corners.max(axis=1))
        while _TRIANGLES and sum(len(x[1]) for x in _TRIANGLES.values()) + len(got[1]) > _MAX_TRIANGLES:
            _TRIANGLES.pop(next(iter(_TRIANGLES)))
        _TRIANGLES[key] = got
    return got


def _tf(coal, T):
    return coal.Transform3s(T[:3, :3], T[:3, 3])


def self_collisions(robot, q: dict | None = None, meshes=True, exclusions=None,
                    min_depth: float = TOUCH) -> list[Overlap]:
    """The overlaps of ``robot`` at ``q`` (``Robot.rest_pose`` when None): :class:`Scene` once."""
    return Scene(robot, meshes, exclusions).overlaps(robot.rest_pose() if q is None else q, min_depth=min_depth)
