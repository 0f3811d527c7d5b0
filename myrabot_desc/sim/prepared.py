"""What the programs derive from the robot alone, built once per loaded Robot.

The Pinocchio model of the arm, the collision geometry (meshes read, bounding volumes,
broadphase), the drive's wheel geometry, the support polygon and the footprint depend on
the robot, not on the run: the counterpart of MuJoCo compiling an MjModel before stepping
it. The first run on a Robot object builds them and keeps them on the robot
(``Robot.derive``); later runs on the same object (a benchmark, a script running several
programs) reuse them, and they go when the robot goes. Robots are not modified after loading.
"""

from __future__ import annotations

from myrabot_desc.model import meshes
from myrabot_desc.sim.arm import Arm
from myrabot_desc.sim.collide import ArmCollider
from myrabot_desc.sim.diffdrive import find_drive
from myrabot_desc.sim.stability import footprint as outline
from myrabot_desc.sim.stability import support_polygon


def get(robot, key, build):
    """``build()``, built once for ``robot`` and ``key`` (``Robot.derive``, under sim's own keys)."""
    return robot.derive(("sim", key), build)


def clear(robot) -> None:
    """Forget what was built for ``robot`` (benchmarks time the preparation this way)."""
    robot.derived.clear()


def drive(robot, wheels: str):
    """``find_drive(robot, wheels)``: a fresh Drive (runs set its limits) on the shared geometry."""
    import dataclasses

    d = get(robot, ("drive", wheels), lambda: find_drive(robot, wheels))
    return dataclasses.replace(d, notes=list(d.notes))


def arm(robot):
    return get(robot, "arm", lambda: Arm(robot))


def triangles(robot):
    """path -> (vertices, faces) of a mesh file as model/meshes.triangles reads it, each file read
    once for ``robot``: the collider's shapes and the support's lowest points read the same files."""
    def read(path):
        got = get(robot, ("triangles", str(path)), lambda: _triangles_or_error(path))
        if isinstance(got, Exception):
            raise got
        return got
    return read


def _triangles_or_error(path):
    try:
        return meshes.triangles(path)
    except (meshes.MeshError, OSError) as exc:
        return exc


def mesh_vertices(robot):
    """geometry -> its mesh's distinct vertices, scaled (what model/support.ground_support takes for
    a loaded mesh), from ``triangles``; None when the file cannot be read (the shape is left out, as
    the support's own reader leaves it)."""
    read = triangles(robot)

    def of(g):
        import numpy as np

        try:
            v, _f = read(g.path)
        except (meshes.MeshError, OSError):
            return None
        return meshes.unique_rows(np.asarray(v, dtype=float)) * np.asarray(g.scale)
    return of


def collider(robot):
    """The arm against the robot's own structure (no scene)."""

    return get(robot, "collider", lambda: ArmCollider(arm(robot), triangles=triangles(robot)))


def support(robot, wheels: str):
    """(model/support.Support, notes on how the drive wheels take part in it)."""
    return get(robot, ("support", wheels),
               lambda: support_polygon(robot, drive(robot, wheels), meshes=mesh_vertices(robot)))


def footprint(robot) -> list:
    return list(get(robot, "footprint", lambda: outline(robot)))
