"""How deep two overlapping primitives (box, sphere, cylinder) go into each other, in closed form and
pure Python: the depth (the shortest move that parts them), the direction of that move and a point
where they meet.

The depth is the distance from the origin to the boundary of the Minkowski difference D = A - B:
the smallest value over unit directions n of its support function h_D(n) = h_A(n) + h_B(-n), exact
here where a GJK/EPA solver (coal) approximates it with polytopes to a tolerance.
- A sphere against a box or a cylinder is the shape swollen by the radius: r minus the signed
  distance from the centre to the shape.
- Two boxes: D is a polytope whose face normals are among the 15 axes of the separating axis test
  (the boxes' faces and the cross products of their edges); the smallest h_D over them is the depth
  (any unit n gives h_D(n) >= depth, so extra axes do no harm).
- A cylinder whose axis is parallel to a box's axis, or to another cylinder's: D is a prism, a
  rounded rectangle or a disc swept along the axis, and the distance to its boundary is the
  smaller of the distance across (2D) and along the axis.
- Other pairs (two cylinders at an angle, a cylinder at an angle to a box) curve in two directions
  at once and have no closed form: ``penetration`` says NotImplemented and the caller asks coal.

An axis counts as parallel when snapping it moves no point of the shape by more than SNAP (the
depth moves by at most that): the Pioneer 3-DX's caster, turned by rpy -3.1415927/2, is 2.7e-8 rad
off, 1e-9 m on its 4 cm wheel; rpy 1.5707 (1e-4 rad) is not parallel and goes to coal.

The point: each shape's deepest feature along the direction (a vertex, an edge, a face, a disc, a
rim line), then the closest points of the two, by alternating projections from the centre of the
smaller feature; the point is halfway between them. A vertex against a face or two crossing edges
give the one contact point; a small face inside a large one its centre; features that overlap in
part (a disc over a box's edge, parallel lines) the middle of the overlap along the way from the
smaller one's centre.
"""

from __future__ import annotations

import math

from myrabot_desc.model.transforms import rotate
from myrabot_desc.records import Struct

SNAP = 1e-8          # m: an axis that snapping moves no point of the shape by more than this is parallel
_ROUNDS = 100        # alternating projections between two features (vertex/face and face/face take one)


class Solid(Struct):
    kind: str            # "box", "sphere" or "cylinder" (axis along local z)
    half: tuple          # half extents: a box's three; (r, r, r) a sphere; (r, r, half length) a cylinder
    R: tuple             # rotation, world from local, as rows
    c: tuple             # centre in the world


class Contact(Struct):
    depth: float         # m, > 0
    point: tuple         # world: halfway between the two shapes' deepest points
    normal: tuple        # unit, from the first shape to the second: moving the second by depth * normal parts them


def penetration(a: Solid, b: Solid):
    """The Contact of two solids that overlap, None when they are apart or only touch, NotImplemented
    for a pair with no closed form here (the caller asks coal)."""
    if not (_finite(a) and _finite(b)):
        return NotImplemented                # no closed form of a pose or size that is not a number
    order = _ORDER.get(a.kind, 9), _ORDER.get(b.kind, 9)
    if order[0] > order[1]:
        got = penetration(b, a)
        if isinstance(got, Contact):
            got = Contact(got.depth, got.point, _neg(got.normal))
        return got
    fn = _PAIRS.get((a.kind, b.kind))
    return NotImplemented if fn is None else fn(a, b)


# -- small vector helpers (3-tuples, rotations as rows) --------------------------------------

def _finite(s: Solid) -> bool:
    return math.isfinite(sum(s.c) + sum(s.half) + sum(map(sum, s.R)))


def _sub(p, q):
    return (p[0] - q[0], p[1] - q[1], p[2] - q[2])


def _neg(p):
    return (-p[0], -p[1], -p[2])


def _dot(p, q):
    return p[0] * q[0] + p[1] * q[1] + p[2] * q[2]


def _norm(p):
    return math.sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2])


def _mid(p, q):
    return ((p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2)


def _axis(R, j):
    """Local axis j in the world: column j of R."""
    return (R[0][j], R[1][j], R[2][j])


def _to_local(s: Solid, x):
    return _to_local_dir(s, _sub(x, s.c))


def _to_local_dir(s: Solid, v):
    R = s.R
    return tuple(R[0][j] * v[0] + R[1][j] * v[1] + R[2][j] * v[2] for j in range(3))


def _to_world(s: Solid, p):
    v, c = rotate(s.R, p), s.c
    return (v[0] + c[0], v[1] + c[1], v[2] + c[2])


def _sign(x: float) -> float:
    return -1.0 if x < 0 else 1.0


# -- a point against a box (any dimension) or a cylinder, in the shape's frame -----------------

def _box_surface(p, h):
    """(q, u, v) of the point p against the box of half extents h centred at 0 (2 or 3 axes): q the
    nearest point of its surface, u the unit outward direction there (towards p when p is out),
    v the distance of p inside (negative: outside). A centre equally near two faces takes the first."""
    q = [min(max(x, -e), e) for x, e in zip(p, h)]
    out = [x - y for x, y in zip(p, q)]
    d = math.sqrt(sum(x * x for x in out))
    if d > 0:
        return tuple(q), tuple(x / d for x in out), -d
    gaps = [e - abs(x) for x, e in zip(p, h)]
    i = gaps.index(min(gaps))
    s = _sign(p[i])
    q = list(p)
    q[i] = s * h[i]
    u = [0.0] * len(p)
    u[i] = s
    return tuple(q), tuple(u), gaps[i]


def _cylinder_surface(p, r, L):
    """_box_surface for the cylinder of radius r, half length L along z."""
    rho = math.hypot(p[0], p[1])
    k = r / rho if rho > r else 1.0
    q = (p[0] * k, p[1] * k, min(max(p[2], -L), L))
    out = _sub(p, q)
    d = _norm(out)
    if d > 0:
        return q, (out[0] / d, out[1] / d, out[2] / d), -d
    side, cap = r - rho, L - abs(p[2])
    if side < cap:
        u = (p[0] / rho, p[1] / rho, 0.0) if rho > 0 else (1.0, 0.0, 0.0)
        return (u[0] * r, u[1] * r, p[2]), u, side
    s = _sign(p[2])
    return (p[0], p[1], s * L), (0.0, 0.0, s), cap


# -- the pairs -------------------------------------------------------------------------------

def _sphere_sphere(a: Solid, b: Solid):
    ra, rb = a.half[0], b.half[0]
    n = _sub(b.c, a.c)
    d = _norm(n)
    depth = ra + rb - d
    if depth <= 0:
        return None
    n = (n[0] / d, n[1] / d, n[2] / d) if d > 0 else (0.0, 0.0, 1.0)     # concentric: any direction parts them
    k = ra - depth / 2
    return Contact(depth, (a.c[0] + n[0] * k, a.c[1] + n[1] * k, a.c[2] + n[2] * k), n)


def _sphere_shape(a: Solid, b: Solid):
    """A sphere against a box or a cylinder: r plus the depth of its centre in the shape."""
    r = a.half[0]
    p = _to_local(b, a.c)
    q, u, v = _box_surface(p, b.half) if b.kind == "box" else _cylinder_surface(p, b.half[0], b.half[2])
    depth = r + v
    if depth <= 0:
        return None
    u = rotate(b.R, u)                  # from the shape towards the sphere's centre
    on_b = _to_world(b, q)
    on_a = (a.c[0] - u[0] * r, a.c[1] - u[1] * r, a.c[2] - u[2] * r)
    return Contact(depth, _mid(on_a, on_b), _neg(u))


def _box_box(a: Solid, b: Solid):
    ua = [_axis(a.R, j) for j in range(3)]
    ub = [_axis(b.R, j) for j in range(3)]
    axes = ua + ub
    for x in ua:
        for y in ub:
            n = (x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0])
            m = _norm(n)
            if m > 1e-9:                     # parallel edges: their faces' axes stand for them
                axes.append((n[0] / m, n[1] / m, n[2] / m))
    d = _sub(a.c, b.c)
    best, best_n = math.inf, None
    for n in axes:
        ext = (sum(abs(_dot(n, x)) * h for x, h in zip(ua, a.half))
               + sum(abs(_dot(n, y)) * h for y, h in zip(ub, b.half)))
        s = _dot(n, d)
        for value, sign in ((ext + s, 1.0), (ext - s, -1.0)):
            if value < best:
                best, best_n = value, (n[0] * sign, n[1] * sign, n[2] * sign)
    if best <= 0:
        return None
    return Contact(best, _contact_point(a, b, best_n), best_n)


def _parallel(axis, to, size) -> bool:
    """``axis`` is parallel to ``to`` (either way) within SNAP for a shape of that size."""
    s = _sign(_dot(axis, to))
    return _norm((axis[0] - s * to[0], axis[1] - s * to[1], axis[2] - s * to[2])) * size <= SNAP


def _box_cylinder(a: Solid, b: Solid):
    """A box and a cylinder parallel to one of its axes: in the box's frame, the disc against the
    rectangle across and the two intervals along."""
    r, L = b.half[0], b.half[2]
    axis = _axis(b.R, 2)
    size = math.hypot(r, L)
    k = next((j for j in range(3) if _parallel(axis, _axis(a.R, j), size)), None)
    if k is None:
        return NotImplemented
    i, j = [x for x in range(3) if x != k]
    h = a.half
    p = _to_local(a, b.c)                    # the cylinder's centre in the box's frame
    q, u, v = _box_surface((p[i], p[j]), (h[i], h[j]))
    across, along = r + v, L + h[k] - abs(p[k])
    if min(across, along) <= 0:
        return None
    n = [0.0, 0.0, 0.0]
    if across <= along:
        n[i], n[j] = u                       # the box's outward direction towards the cylinder's axis
    else:
        n[k] = _sign(p[k])
    n = rotate(a.R, n)
    return Contact(min(across, along), _contact_point(a, b, n), n)


def _cylinder_cylinder(a: Solid, b: Solid):
    """Two parallel cylinders: in a's frame, the two discs across and the two intervals along."""
    ra, La, rb, Lb = a.half[0], a.half[2], b.half[0], b.half[2]
    if not _parallel(_axis(b.R, 2), _axis(a.R, 2), math.hypot(rb, Lb)):
        return NotImplemented
    p = _to_local(a, b.c)
    rho = math.hypot(p[0], p[1])
    across, along = ra + rb - rho, La + Lb - abs(p[2])
    if min(across, along) <= 0:
        return None
    if across <= along:
        n = (p[0] / rho, p[1] / rho, 0.0) if rho > 0 else (1.0, 0.0, 0.0)
    else:
        n = (0.0, 0.0, _sign(p[2]))
    n = rotate(a.R, n)
    return Contact(min(across, along), _contact_point(a, b, n), n)


_ORDER = {"sphere": 0, "box": 1, "cylinder": 2}
_PAIRS = {("sphere", "sphere"): _sphere_sphere, ("sphere", "box"): _sphere_shape,
          ("sphere", "cylinder"): _sphere_shape, ("box", "box"): _box_box,
          ("box", "cylinder"): _box_cylinder, ("cylinder", "cylinder"): _cylinder_cylinder}


# -- the point: the deepest features of the two shapes and their closest points --------------

class _Feature:
    """The points of a box or cylinder that reach furthest along a direction (its support set): per
    local axis fixed at the surface or free across the shape, and the projection onto them."""

    def __init__(self, s: Solid, n):
        self.s = s
        m = _to_local_dir(s, n)
        h = s.half
        if s.kind == "box":
            self.fixed = [_sign(m[j]) * h[j] if abs(m[j]) * h[j] > SNAP else None for j in range(3)]
            free = [h[j] for j in range(3) if self.fixed[j] is None]
            self.rim = None
        else:                                    # a cylinder: the rim point, or the whole disc, at a cap or along
            r, L = h[0], h[2]
            rho = math.hypot(m[0], m[1])
            self.rim = (m[0] / rho * r, m[1] / rho * r) if rho * r > SNAP else None
            self.fixed = [None, None, _sign(m[2]) * L if abs(m[2]) * L > SNAP else None]
            free = ([r, r] if self.rim is None else []) + ([L] if self.fixed[2] is None else [])
        self.size = (len(free), max(free, default=0.0))

    def centre(self):
        f = self.fixed
        if self.rim is not None:
            return _to_world(self.s, (self.rim[0], self.rim[1], f[2] if f[2] is not None else 0.0))
        return _to_world(self.s, tuple(0.0 if x is None else x for x in f))

    def project(self, x):
        s, f = self.s, self.fixed
        p = list(_to_local(s, x))
        h = s.half
        if s.kind == "cylinder":
            if self.rim is not None:
                p[0], p[1] = self.rim
            else:
                rho = math.hypot(p[0], p[1])
                if rho > h[0]:
                    p[0], p[1] = p[0] * h[0] / rho, p[1] * h[0] / rho
            p[2] = f[2] if f[2] is not None else min(max(p[2], -h[2]), h[2])
        else:
            p = [f[j] if f[j] is not None else min(max(p[j], -h[j]), h[j]) for j in range(3)]
        return _to_world(s, p)

    def farthest(self, d):
        """The feature's point furthest along the direction d."""
        s, f = self.s, self.fixed
        m = _to_local_dir(s, d)
        h = s.half
        if s.kind == "cylinder":
            rim = self.rim
            if rim is None:
                rho = math.hypot(m[0], m[1])
                rim = (m[0] / rho * h[0], m[1] / rho * h[0]) if rho > 0 else (0.0, 0.0)
            return _to_world(s, (rim[0], rim[1], f[2] if f[2] is not None else _sign(m[2]) * h[2]))
        return _to_world(s, [f[j] if f[j] is not None else _sign(m[j]) * h[j] if m[j] else 0.0 for j in range(3)])


def _contact_point(a: Solid, b: Solid, n):
    """Halfway between the closest points of a's deepest feature along n and b's along -n: from the
    smaller feature's centre, and where the two meet over a patch (faces, parallel lines) that the
    centre lies off, the middle of the patch along the way the centre had to go."""
    fa, fb = _Feature(a, n), _Feature(b, _neg(n))
    small, other = (fa, fb) if fa.size < fb.size else (fb, fa)
    scale = 1e-12 * (1.0 + max(map(abs, a.c)) + max(map(abs, b.c)) + max(a.half) + max(b.half))
    c = small.centre()
    x, y = _closest(small, other, c, scale)
    d = _sub(x, c)
    if _norm(d) > scale:
        # the centre lies off the other feature: the far side of the patch along d is the small
        # feature's furthest point that way, as far as the other reaches, and alternating from
        # halfway between finds the closest pair there (features that meet at one point only,
        # crossing edges, give that point from any start)
        x, y = _closest(small, other, _mid(x, other.project(small.farthest(d))), scale)
    return _mid(x, y)


def _closest(small: _Feature, other: _Feature, x, scale):
    """A closest pair of points of the two features, by alternating projections from x."""
    x = small.project(x)
    for _ in range(_ROUNDS):
        x2 = small.project(other.project(x))
        moved = _norm(_sub(x2, x))
        x = x2
        if moved <= scale:
            break
    return x, other.project(x)
