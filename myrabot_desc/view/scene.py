"""The robot as triangles: one scene description shared by ``view`` (viser) and ``render`` (MuJoCo).

Every visual and collision element of every link becomes a :class:`Part`: triangles in the
element's own frame, the element's pose in its link frame, and a colour. Colours come from the
same place as the converters' (``convert.appearance``: a resolved ``<gazebo><material>`` wins, as
in Gazebo, else the URDF ``<color>``, else grey). Meshes are read only through ``model.meshes`` (package
roots, size and triangle limits); one that cannot be read is listed in ``problems`` and left out.
Link poses come from ``kinematics.world_transforms``; joint ranges for the sliders from the URDF.
"""

from __future__ import annotations

import math

from myrabot_desc.convert.appearance import Appearance, texture_mean_rgb
from myrabot_desc.convert.common import Notes
from myrabot_desc.convert.gazebo import GazeboProps
from myrabot_desc.errors import InputError
from myrabot_desc.model import meshes
from myrabot_desc.model.kinematics import pose_matrix, world_transforms
from myrabot_desc.records import Struct

DEFAULT_RGBA = (0.7, 0.7, 0.72, 1.0)
COLLISION_RGBA = (1.0, 0.55, 0.1, 0.55)
CYLINDER_SECTIONS = 32


class Part(Struct):
    link: str
    layer: str                 # 'visual' or 'collision'
    index: int                 # position among the link's visuals / collisions
    local: object              # 4x4 numpy: link frame -> element frame
    vertices: object           # (n, 3) float32, element frame, mesh scale applied
    faces: object              # (m, 3) uint32
    rgba: tuple
    kind: str                  # box / cylinder / sphere / mesh
    loc: object = None

    @property
    def key(self) -> str:
        return f"{self.link}/{self.layer}/{self.index}"


class JointRange(Struct):
    name: str
    type: str
    lower: float
    upper: float


class Scene:
    """Parts, joint ranges and problems of one loaded robot."""

    def __init__(self, robot, parts: list[Part], problems: list[str]):
        self.robot = robot
        self.parts = parts
        self.problems = problems
        self.joints = joint_ranges(robot)

    def transforms(self, q: dict | None = None) -> dict:
        """link -> 4x4 world pose (mimic joints follow their leader)."""

        return world_transforms(self.robot, self.pose(q))

    def rest(self) -> dict:
        """The slider joints at the robot's rest pose (``Robot.rest_pose``)."""
        pose = self.robot.rest_pose()
        return {name: pose.get(name, 0.0) for name in self.joints}

    def pose(self, q: dict | None) -> dict:
        """The rest pose with ``q``'s joints (clamped) set."""
        return {**self.rest(), **self.clamp(q)}

    def clamp(self, q: dict | None) -> dict:
        """Joint values limited to the slider ranges; unknown names dropped."""
        out = {}
        for name, v in (q or {}).items():
            r = self.joints.get(name)
            if r is not None:
                out[name] = min(max(float(v), r.lower), r.upper)
        return out

    def world_vertices(self, q: dict | None = None, layer: str = "visual"):
        """(n, 3) numpy: every vertex of one layer in the world frame (for extents and framing)."""
        import numpy as np

        T = self.transforms(q)
        chunks = []
        for p in self.parts:
            if p.layer != layer or p.link not in T:
                continue
            M = T[p.link] @ p.local
            chunks.append(np.asarray(p.vertices, dtype=float) @ M[:3, :3].T + M[:3, 3])
        return np.vstack(chunks) if chunks else np.zeros((0, 3))


def joint_ranges(robot) -> dict[str, JointRange]:
    """Movable, non-mimic joints with a finite range: the URDF limits, continuous (and a revolute
    without limits) +-pi, a prismatic without limits +-1 m. Floating and planar joints are left at zero."""
    out = {}
    for j in robot.joints.values():
        if j.type not in ("revolute", "continuous", "prismatic") or j.mimic is not None:
            continue
        lo, hi = (j.limit.lower, j.limit.upper) if j.limit is not None else (None, None)
        if j.type == "continuous" or lo is None or hi is None or not (math.isfinite(lo) and math.isfinite(hi)) \
                or hi < lo:
            lo, hi = (-math.pi, math.pi) if j.type != "prismatic" else (-1.0, 1.0)
        out[j.name] = JointRange(j.name, j.type, float(lo), float(hi))
    return out


def primitive_mesh(g):
    """(vertices, faces) of a box, cylinder (axis z) or sphere, in the geometry's frame.

    Built with numpy (outward, counter-clockwise faces): a robot of primitives needs no trimesh,
    whose import is most of a `render` of such a robot.
    """
    import numpy as np

    if g.kind == "box":
        h = np.maximum(np.asarray(g.size, dtype=float), 1e-6) / 2
        v = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=float) * h
        f = [[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
             [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]]
    elif g.kind == "cylinder":
        n, r, hz = CYLINDER_SECTIONS, max(g.radius, 1e-6), max(g.length, 1e-6) / 2
        a = np.linspace(0, 2 * math.pi, n, endpoint=False)
        ring = np.column_stack([r * np.cos(a), r * np.sin(a)])
        v = np.vstack([np.column_stack([ring, np.full(n, -hz)]), np.column_stack([ring, np.full(n, hz)]),
                       [[0, 0, -hz], [0, 0, hz]]])
        f = []
        for i in range(n):
            j = (i + 1) % n
            f += [[i, j, n + j], [i, n + j, n + i], [2 * n, j, i], [2 * n + 1, n + i, n + j]]
    elif g.kind == "sphere":
        r, nlat, nlon = max(g.radius, 1e-6), 12, 24
        th = np.linspace(0, math.pi, nlat + 1)[1:-1]
        ph = np.linspace(0, 2 * math.pi, nlon, endpoint=False)
        T, P = np.meshgrid(th, ph, indexing="ij")
        body = np.column_stack([(np.sin(T) * np.cos(P)).ravel(), (np.sin(T) * np.sin(P)).ravel(), np.cos(T).ravel()])
        v = np.vstack([[[0, 0, 1]], body, [[0, 0, -1]]]) * r
        top, bottom = 0, len(v) - 1
        f = []
        for k in range(nlon):
            kk = (k + 1) % nlon
            f.append([top, 1 + k, 1 + kk])
            last = 1 + (nlat - 2) * nlon
            f.append([bottom, last + kk, last + k])
            for i in range(nlat - 2):
                a0, a1 = 1 + i * nlon + k, 1 + i * nlon + kk
                b0, b1 = a0 + nlon, a1 + nlon
                f += [[a0, b0, b1], [a0, b1, a1]]
    else:
        raise ValueError(g.kind)
    return np.asarray(v, dtype=np.float32), np.asarray(f, dtype=np.uint32)


class _Problems:
    """``notes.warn`` for the mesh readers: a warning line in the scene's problems."""

    def __init__(self, problems: list, loc):
        self.problems, self.loc = problems, loc

    def warn(self, message: str, loc=None) -> None:
        where = loc or self.loc
        self.problems.append(f"{where}: warning: {message}" if where else f"warning: {message}")


def build_scene(robot, collision: bool = True) -> Scene:
    """Parts of every visual (and collision, unless ``collision`` is False) element of ``robot``."""
    import numpy as np

    problems: list[str] = []
    notes = Notes()
    props = GazeboProps(robot, Notes())
    look = Appearance(robot, notes)
    cache: dict = {}

    def triangles(g, loc):
        if g.kind != "mesh":
            return primitive_mesh(g)
        if g.path is None:
            problems.append(f"{loc}: warning: mesh {g.filename} cannot be resolved (left out)" if loc
                            else f"warning: mesh {g.filename} cannot be resolved (left out)")
            return None
        key = str(g.path)
        if key not in cache:
            try:
                v, f = meshes.triangles(g.path, _Problems(problems, loc))
                cache[key] = (np.asarray(v, dtype=np.float32), np.asarray(f, dtype=np.uint32))
            except meshes.MeshError as exc:
                problems.append(f"{loc}: warning: mesh {exc} (left out)" if loc else f"warning: mesh {exc}")
                cache[key] = None
        got = cache[key]
        if got is None:
            return None
        v, f = got
        return (v * np.asarray(g.scale, dtype=np.float32)).astype(np.float32), f

    parts: list[Part] = []
    for link in robot.links.values():
        gz_mat = props.get(link.name).get("material")
        for i, vis in enumerate(link.visuals):
            if vis.geometry is None:
                continue
            tri = triangles(vis.geometry, vis.loc or link.loc)
            if tri is None:
                continue
            rgba = DEFAULT_RGBA
            lk = look.look(vis, gz_mat, link.loc)
            if lk is not None:
                rgb = tuple(lk.diffuse[:3])
                mean = texture_mean_rgb(lk.texture) if lk.texture else None
                if mean is not None:
                    rgb = tuple(a * b for a, b in zip(rgb, mean))
                alpha = (lk.diffuse[3] if len(lk.diffuse) > 3 else 1.0) * (1.0 - lk.transparency)
                rgba = tuple(float(c) for c in rgb) + (float(alpha),)
            parts.append(Part(link.name, "visual", i, pose_matrix(vis.origin), tri[0], tri[1], rgba,
                              vis.geometry.kind, vis.loc or link.loc))
        if not collision:
            continue
        for i, col in enumerate(link.collisions):
            if col.geometry is None:
                continue
            tri = triangles(col.geometry, col.loc or link.loc)
            if tri is None:
                continue
            parts.append(Part(link.name, "collision", i, pose_matrix(col.origin), tri[0], tri[1],
                              COLLISION_RGBA, col.geometry.kind, col.loc or link.loc))
    look.finish()
    problems.extend(notes.warnings)
    return Scene(robot, parts, problems)


def parse_joint_values(items, scene: Scene, where: str = "--joint") -> dict[str, float]:
    """``NAME=VALUE`` strings -> {name: radians or metres}; InputError naming the bad one."""

    out = {}
    for it in items:
        name, sep, val = str(it).partition("=")
        name = name.strip()
        if not sep:
            raise InputError(f"{where} {it!r}: expected NAME=VALUE")
        try:
            v = float(val)
        except ValueError:
            raise InputError(f"{where} {it!r}: {val!r} is not a number") from None
        if not math.isfinite(v):
            raise InputError(f"{where} {it!r}: the value must be finite")
        check_joint_name(name, scene, where)
        out[name] = v
    return out


def clamp_notes(q: dict, scene: Scene) -> list[str]:
    """One line for each joint value outside its slider range: what is drawn instead."""
    out = []
    for name, v in q.items():
        r = scene.joints.get(name)
        if r is None or r.lower <= v <= r.upper:
            continue
        unit = "m" if r.type == "prismatic" else "rad"
        at = r.upper if v > r.upper else r.lower
        out.append(f"warning: joint {name} = {v:g} {unit} is outside its limits [{r.lower:g}, {r.upper:g}]; "
                   f"drawn at {at:g}")
    return out


def check_joint_name(name: str, scene: Scene, where: str) -> None:
    if name in scene.joints:
        return
    j = scene.robot.joints.get(name)
    if j is None:
        import difflib

        close = difflib.get_close_matches(name, list(scene.joints), n=1)
        hint = f" (did you mean {close[0]}?)" if close else f"; movable joints: {', '.join(list(scene.joints)[:12])}"
        raise InputError(f"{where}: no movable joint named {name!r}{hint}")
    why = f"mimics {j.mimic.joint}" if j.mimic else f"is {j.type}"
    raise InputError(f"{where}: joint {name!r} {why}, it cannot be set")

