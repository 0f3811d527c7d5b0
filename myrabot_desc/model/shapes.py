"""Solid-body facts of URDF geometry: volume, inertia, extents, lowest points.

Primitives use closed forms (trimesh's Cylinder/Sphere primitives ignore density,
env-notes §5); meshes go through trimesh, imported only when a mesh is loaded.
Cylinders have their axis along local z (URDF convention). numpy is imported inside
functions so that importing the checks stays cheap.
"""

import math

from myrabot_desc.errors import InputError
from myrabot_desc.model import meshes as meshio
from myrabot_desc.model.transforms import matmul3, place, rotate, transpose3
from myrabot_desc.records import Struct


class MassProps(Struct):
    volume: float
    com: tuple           # (x, y, z) in the frame the props are expressed in
    inertia: tuple       # 3x3 as three row tuples, about com, per the given mass
    mass: float


def primitive_volume(g) -> float:
    if g.kind == "box":
        return g.size[0] * g.size[1] * g.size[2]
    if g.kind == "cylinder":
        return math.pi * g.radius ** 2 * g.length
    if g.kind == "sphere":
        return 4.0 / 3.0 * math.pi * g.radius ** 3
    raise ValueError(g.kind)


def primitive_moments(g, mass: float) -> tuple[float, float, float]:
    """The principal moments of a primitive about its centroid, along its own axes (closed forms)."""
    if g.kind == "box":
        x, y, z = g.size
        d = (y * y + z * z, x * x + z * z, x * x + y * y)
        return mass * d[0] / 12.0, mass * d[1] / 12.0, mass * d[2] / 12.0
    if g.kind == "cylinder":
        r, h = g.radius, g.length
        a = mass * (3 * r * r + h * h) / 12.0
        return a, a, mass * r * r / 2.0
    if g.kind == "sphere":
        a = 2.0 / 5.0 * mass * g.radius ** 2
        return a, a, a
    raise ValueError(g.kind)


def primitive_inertia(g, mass: float):
    """3x3 inertia about the centroid in the geometry frame (closed forms), as three row tuples."""
    a, b, c = primitive_moments(g, mass)
    if g.kind == "sphere":
        b = c = a
    return ((a, 0.0, 0.0), (0.0, b, 0.0), (0.0, 0.0, c))


def describe(g) -> str:
    if g.kind == "box":
        return "box {:g}×{:g}×{:g} m".format(*g.size)
    if g.kind == "cylinder":
        return f"cylinder r {g.radius:g} l {g.length:g} m"
    if g.kind == "sphere":
        return f"sphere r {g.radius:g} m"
    sc = "" if tuple(g.scale) == (1.0, 1.0, 1.0) else " scale {:g} {:g} {:g}".format(*g.scale)
    return f"mesh {g.filename.rsplit('/', 1)[-1]}{sc}"


_MESHES: dict = {}          # (path, mtime, scale) -> mesh: robots in one run share mesh files
_MAX_CACHED = 512
_MAX_CACHED_BYTES = 32_000_000   # mesh memory kept across robots (a -j N check has N such caches)
_CACHED = [0]                    # bytes held by _MESHES


def load_mesh(g):
    """The MeshFacts (model/meshes.py: vertices, bounds, volume, inertia, watertightness; trimesh's
    attribute names) of a mesh file with the URDF scale applied; str on failure. Cached per file,
    scale and limits: robots in one run share mesh files, links share them within a robot."""
    try:
        key = (str(g.path), g.path.stat().st_mtime_ns, tuple(g.scale), meshio.limits())
    except OSError as exc:
        return f"cannot read {g.path}: {exc.strerror}"
    if key not in _MESHES:
        m = _load_mesh(g)
        _MESHES[key] = m
        _CACHED[0] += _nbytes(m)
        while len(_MESHES) > _MAX_CACHED or (len(_MESHES) > 1 and _CACHED[0] > _MAX_CACHED_BYTES):
            _CACHED[0] -= _nbytes(_MESHES.pop(next(iter(_MESHES))))
        return m
    return _MESHES[key]


def _nbytes(m) -> int:
    """Memory of a cached mesh: its vertex and face arrays (the facts keep nothing else of size)."""
    if isinstance(m, str) or m is None:
        return 0
    return m.vertices.nbytes + m.faces.nbytes


def _load_mesh(g):
    try:  # size and triangle limits, one-line reasons (meshio.py)
        return meshio.facts(g.path, tuple(g.scale))   # check needs geometry only
    except meshio.MeshError as exc:
        return str(exc)


def shape_props(g, mesh=None):
    """(volume, com (3,), unit inertia (3x3) per kg about com) in the geometry frame, or None.

    Primitives give tuples (pure Python); a mesh gives numpy arrays. For a mesh, ``mesh`` is its
    MeshFacts (``load_mesh``) or a trimesh; only a watertight, outward mesh gives props.
    """
    if g.kind in ("box", "cylinder", "sphere"):
        return primitive_volume(g), (0.0, 0.0, 0.0), primitive_inertia(g, 1.0)
    if mesh is None or isinstance(mesh, str) or not mesh.is_volume or mesh.volume <= 0:
        return None
    import numpy as np

    vol = float(mesh.volume)
    return vol, np.asarray(mesh.center_mass, float), np.asarray(mesh.moment_inertia, float) / vol


def combine(parts, mass: float):
    """Uniform-density solid made of parts [(volume, com, unit_inertia, 4x4 pose)] at total mass.

    Returns MassProps in the link frame (overlaps are counted twice: a fair approximation
    for the rough check this is). numpy's products: the floats check reports (combine_pure
    gives the tensor within a few ulps, without numpy).
    """
    import numpy as np

    vol = sum(p[0] for p in parts)
    if vol <= 0:
        return None
    coms, ms = [], []
    for v, c, _, T in parts:
        coms.append(T[:3, :3] @ np.asarray(c, dtype=float) + T[:3, 3])
        ms.append(mass * v / vol)
    com = sum(m * c for m, c in zip(ms, coms)) / mass if mass > 0 else sum(coms) / len(coms)
    inertia = np.zeros((3, 3))
    for (v, c, Iu, T), m, cw in zip(parts, ms, coms):
        R = T[:3, :3]
        d = cw - com
        inertia += R @ (np.asarray(Iu, dtype=float) * m) @ R.T + m * (d @ d * np.eye(3) - np.outer(d, d))
    return MassProps(vol, tuple(com.tolist()), tuple(map(tuple, inertia.tolist())), mass)


def combine_pure(parts, mass: float):
    """``combine`` in pure Python, the poses given as transforms (R, p) (model/transforms.py). The
    volume is combine's to the bit (the same sum), and so is the centroid of parts whose own centroid
    is their origin (primitives: R @ 0 is a zero, which the sums from 0 make +0); the tensor is
    within a few ulps of combine's (its products round their own way)."""
    vol = sum(p[0] for p in parts)
    if vol <= 0:
        return None
    coms, ms = [], []
    for v, c, _, (R, p) in parts:
        q = rotate(R, c)
        coms.append((q[0] + p[0], q[1] + p[1], q[2] + p[2]))
        ms.append(mass * v / vol)
    if mass > 0:
        com = tuple(sum(m * c[k] for m, c in zip(ms, coms)) / mass for k in range(3))
    else:
        com = tuple(sum(c[k] for c in coms) / len(coms) for k in range(3))
    inertia = [[0.0] * 3 for _ in range(3)]
    for (v, c, Iu, (R, p)), m, cw in zip(parts, ms, coms):
        Rm = matmul3(matmul3(R, [[x * m for x in row] for row in Iu]), transpose3(R))
        d = (cw[0] - com[0], cw[1] - com[1], cw[2] - com[2])
        dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2]
        for a in range(3):
            row = inertia[a]
            for b in range(3):
                row[b] += Rm[a][b] + m * ((dd if a == b else 0.0) - d[a] * d[b])
    return MassProps(vol, com, tuple(map(tuple, inertia)), mass)


def placed_primitive(g, pose, mass: float):
    """``combine([(*shape_props(g), pose_matrix(pose))], mass)`` for one primitive whose pose has no
    rotation, in pure Python, or NotImplemented when that shortcut does not apply.

    The floats are the same: with R the identity (its zeros signed either way) every product
    combine takes is by 1 or by a zero, and a centroid the mass split leaves where it is makes the
    parallel-axis term zero. Anything else (a rotation, a centroid moved by an ulp, non-finite
    numbers) is NotImplemented: the caller takes combine, whose numpy kernels round their own way.
    """
    r, p, y = pose.rpy
    if r != 0 or p != 0 or y != 0 or not mass > 0 or not math.isfinite(mass):
        return NotImplemented
    if g.kind not in ("box", "cylinder", "sphere"):
        return NotImplemented
    v = primitive_volume(g)
    i0, i1, i2 = primitive_moments(g, 1.0)
    vol = 0 + v
    if not math.isfinite(vol) or not (math.isfinite(i0) and math.isfinite(i1) and math.isfinite(i2)):
        return NotImplemented
    if vol <= 0:
        return None
    m = mass * v / vol
    cw = [0.0 + float(c) for c in pose.xyz]                 # R @ (0, 0, 0) is +0: the origin is the centroid
    com = tuple((0 + m * c) / mass for c in cw)
    if cw[0] - com[0] != 0 or cw[1] - com[1] != 0 or cw[2] - com[2] != 0:
        return NotImplemented
    return MassProps(vol, com, ((i0 * m, 0.0, 0.0), (0.0, i1 * m, 0.0), (0.0, 0.0, i2 * m)), mass)


def surface_points(g, n: int = 32, mesh=None, loc=None):
    """Points on the surface of a shape in its own frame: the one sampling check, sim and the drive
    model use for extents, hulls and wheel radii.

    Box: its 8 corners. Cylinder: two rings of ``n`` points (the caps' rims). Sphere: three great
    circles (xy, xz, yz) of ``n // 2`` points each. Primitives come back as a list of (x, y, z)
    tuples (pure Python: convert uses them without numpy); a mesh as the (m, 3) array of its
    vertices, from ``mesh`` (a loaded trimesh or vertex array) or read from ``g.path`` with the
    mesh limits (InputError at ``loc`` when it cannot be read).
    """
    if g.kind == "box":
        sx, sy, sz = (s / 2 for s in g.size)
        return [(x, y, z) for x in (-sx, sx) for y in (-sy, sy) for z in (-sz, sz)]
    if g.kind == "cylinder":
        r, h = g.radius, g.length / 2
        ring = [(r * math.cos(2 * math.pi * k / n), r * math.sin(2 * math.pi * k / n)) for k in range(n)]
        return [(x, y, z) for z in (-h, h) for x, y in ring]
    if g.kind == "sphere":
        m = max(n // 2, 4)
        r = g.radius
        cs = [(r * math.cos(2 * math.pi * k / m), r * math.sin(2 * math.pi * k / m)) for k in range(m)]
        return [(c, s, 0.0) for c, s in cs] + [(c, 0.0, s) for c, s in cs] + [(0.0, c, s) for c, s in cs]
    if g.kind == "mesh":
        if mesh is not None and not isinstance(mesh, str):
            import numpy as np

            return np.asarray(getattr(mesh, "vertices", mesh), float)

        if g.path is None:
            raise InputError(f"mesh {g.filename} cannot be resolved", loc)
        import numpy as np

        return meshio.vertices(g.path, loc) * np.asarray(g.scale)

    raise InputError(f"unsupported geometry {g.kind}", loc)


def lowest_points(g, R, p, mesh=None, tol: float = 1e-3):
    """(min z, [(x, y, z) points within tol of it]) of a shape placed by the world pose (R, p)
    (R a 3x3 as rows), or None. Primitives in pure Python (check's P rules run without numpy), a
    mesh's vertices (``mesh``: loaded) with numpy."""
    if g.kind == "sphere":
        return p[2] - g.radius, [(p[0] - 0.0, p[1] - 0.0, p[2] - g.radius)]
    if g.kind == "box":
        sx, sy, sz = (s / 2 for s in g.size)
        pts = place((R, p), [(x, y, z) for x in (-sx, sx) for y in (-sy, sy) for z in (-sz, sz)])
    elif g.kind == "cylinder":
        axis = (R[0][2], R[1][2], R[2][2])
        down = (0.0 - axis[0] * -axis[2], 0.0 - axis[1] * -axis[2], -1.0 - axis[2] * -axis[2])  # -z, axis part removed
        n = math.sqrt(down[0] * down[0] + down[1] * down[1] + down[2] * down[2])
        if n > 1e-9:                                                  # tilted or horizontal: one rim point per cap
            rim = [tuple(v / n * g.radius for v in down)]
        else:                                                         # upright: sample the bottom circle
            (ux, vx, _), (uy, vy, _), (uz, vz, _) = R
            step = 2 * math.pi / 16
            rad = g.radius
            rim = []
            for t in (k * step for k in range(16)):
                co, si = math.cos(t), math.sin(t)
                rim.append((rad * (co * ux + si * vx), rad * (co * uy + si * vy), rad * (co * uz + si * vz)))
        (ax, ay, az), (px, py, pz), length = axis, p, g.length
        pts = [(px + s * ax * length / 2 + rx, py + s * ay * length / 2 + ry, pz + s * az * length / 2 + rz)
               for s in (-1, 1) for rx, ry, rz in rim]
    elif mesh is not None and not isinstance(mesh, str):
        import numpy as np

        w = np.asarray(mesh.vertices) @ np.asarray(R, dtype=float).T + np.asarray(p, dtype=float)
        pts = [tuple(q) for q in w.tolist()]
    else:
        return None
    zmin = min(q[2] for q in pts)
    return zmin, [q for q in pts if q[2] <= zmin + tol]


def size_of(g, mesh=None) -> float | None:
    """Largest dimension of the shape (m), for relative tolerances."""
    if g.kind == "box":
        return max(g.size)
    if g.kind == "cylinder":
        return max(2 * g.radius, g.length)
    if g.kind == "sphere":
        return 2 * g.radius
    if mesh is not None and not isinstance(mesh, str):
        return float(max(mesh.extents))
    return None
