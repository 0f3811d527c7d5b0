"""Demo scenes: the table and cans of ``layouts/*.yaml`` placed around the robot.

A layout names each object's model file (relative to the package root) and its
world pose (x, y, z, yaw). Objects are loaded with ``load_robot`` like any model;
their collision geometry, placed at the pose and expressed in the robot's root
frame, serves the collision checks, the plot, and the pointing target (the
centre of the object's collision bounding box: a can's mid-height point).

Selectable objects (``--object N``, like the seed's ``selected_object`` topic)
are the objects spawned above the floor (z > 0), numbered 1, 2, … in spawn order;
for escoja.yaml, 1 = lata_cocacola (the robot's right), 2 = lata_amstel (its left).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from myrabot_desc.diagnostics import Loc
from myrabot_desc.errors import InputError
from myrabot_desc.expand.packages import data_root
from myrabot_desc.expand.yaml_load import load_path
from myrabot_desc.model.kinematics import pose_matrix, world_transforms
from myrabot_desc.model.loader import load_robot
from myrabot_desc.model.shapes import surface_points
from myrabot_desc.safety import check_path, display, limit
from myrabot_desc.sim.collide import coal_shape
from myrabot_desc.sim.stability import _hull


@dataclass
class SceneObject:
    model: str
    file: Path
    pose: tuple[float, float, float, float]      # x, y, z, yaw in the world
    shapes: list                                 # (link, geometry, 4x4 in the robot root frame)
    selectable: bool

    def coal_shapes(self):
        for i, (ln, g, M) in enumerate(self.shapes):
            s = coal_shape(g)
            if s is not None:
                yield f"{self.model}/{ln}_{i}", s, M

    def points(self):
        import numpy as np

        out = []
        for ln, g, M in self.shapes:
            p = np.asarray(surface_points(g, 720))
            out.append(p @ M[:3, :3].T + M[:3, 3])
        return np.vstack(out) if out else np.zeros((0, 3))

    def centre(self):
        p = self.points()
        return (p.min(axis=0) + p.max(axis=0)) / 2

    def radius(self) -> float:
        p = self.points()
        ext = p.max(axis=0) - p.min(axis=0)
        return float(max(ext[0], ext[1]) / 2)

    def moved(self, dx: float, dy: float, dz: float) -> "SceneObject":
        import numpy as np

        T = np.eye(4)
        T[:3, 3] = (dx, dy, dz)
        x, y, z, yaw = self.pose
        return SceneObject(self.model, self.file, (x + dx, y + dy, z + dz, yaw),
                           [(ln, g, T @ M) for ln, g, M in self.shapes], self.selectable)

    def outline(self):
        """Top-view shapes for the plot: ('circle', ((x, y), r)) or ('poly', [(x, y), ...])."""

        out = []
        for ln, g, M in self.shapes:
            if g.kind == "cylinder" and abs(M[2, 2]) > 0.99:
                out.append(("circle", ((float(M[0, 3]), float(M[1, 3])), g.radius)))
            else:
                import numpy as np

                p = np.asarray(surface_points(g, 720)) @ M[:3, :3].T + M[:3, 3]
                out.append(("poly", _hull(p[:, :2])))
        # big things first so that small ones stay visible
        out.sort(key=lambda o: -(o[1][1] if o[0] == "circle" else 1.0))
        return out

    def colour(self):
        name = self.model.lower()
        if "cola" in name:
            return (200, 30, 30), (90, 0, 0)
        if "amstel" in name or "cerveza" in name:
            return (230, 190, 40), (120, 90, 0)
        return (222, 184, 135), (110, 80, 40)


def load_layout(path: Path, robot_pose=None) -> list[SceneObject]:
    import numpy as np

    path = Path(path)
    doc = load_path(path, limit("max_input_bytes"))     # our loader: no code from tags, no FIFO
    if not isinstance(doc, dict) or not isinstance(doc.get("objects"), list):
        raise InputError(f"{path}: error: a layout needs an 'objects' list (see layouts/escoja.yaml)")
    root = _package_root(path) or data_root()
    rp = (doc.get("robot") or {}).get("pose") or {}
    T_rw = np.linalg.inv(_pose_T(_pose(rp, path)))          # world -> robot root frame
    out = []
    for i, entry in enumerate(doc["objects"]):
        if not isinstance(entry, dict) or "file" not in entry:
            raise InputError(f"{path}: error: object {i + 1} needs 'model', 'file' and 'pose'")
        f = root / str(entry["file"])
        try:    # inside the layout's package (or the bundled one), a regular file
            check_path(f, [root, path.resolve().parent], what="file")
        except InputError as exc:
            raise InputError(f"object {entry.get('model', i + 1)}: {exc.message}", Loc(display(path)),
                             code=exc.code) from None
        pose = _pose(entry.get("pose") or {}, path)
        obj_robot = load_robot(str(f))
        tf = world_transforms(obj_robot)
        T = T_rw @ _pose_T(pose)
        shapes = []
        for ln, link in obj_robot.links.items():
            for c in link.collisions:
                if c.geometry is None or c.geometry.kind == "mesh" or ln not in tf:
                    continue
                shapes.append((ln, c.geometry, T @ tf[ln] @ pose_matrix(c.origin)))
        out.append(SceneObject(str(entry.get("model", obj_robot.name)), f, pose, shapes, selectable=pose[2] > 0))
    return out


def select(objects: list[SceneObject], which: str) -> SceneObject:
    sel = [o for o in objects if o.selectable]
    if which.isdigit():
        n = int(which)
        if not 1 <= n <= len(sel):
            names = ", ".join(f"{i + 1} = {o.model}" for i, o in enumerate(sel))
            raise InputError(f"--object {n}: the layout has {len(sel)} selectable objects ({names})")
        return sel[n - 1]
    for o in objects:
        if o.model == which:
            return o
    raise InputError(f"--object {which}: no such object in the layout "
                     f"({', '.join(o.model for o in objects)})")


def _pose(p: dict, path) -> tuple[float, float, float, float]:
    try:
        return tuple(float(p.get(k, 0.0)) for k in ("x", "y", "z", "yaw"))
    except (TypeError, ValueError):
        raise InputError(f"{path}: error: pose values must be numbers: {p}") from None


def _pose_T(pose):
    import numpy as np

    x, y, z, yaw = pose
    T = np.eye(4)
    c, s = math.cos(yaw), math.sin(yaw)
    T[:3, :3] = [[c, -s, 0], [s, c, 0], [0, 0, 1]]
    T[:3, 3] = (x, y, z)
    return T


def _package_root(path: Path) -> Path | None:
    for d in [path.resolve().parent, *path.resolve().parents]:
        if (d / "package.xml").is_file():
            return d
    return None
