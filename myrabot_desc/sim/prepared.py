"""What the programs derive from the robot alone, built once per loaded Robot.

The Pinocchio model of the arm, the collision geometry (meshes read, bounding volumes,
broadphase), the drive's wheel geometry, the support polygon and the footprint depend on
the robot, not on the run: the counterpart of MuJoCo compiling an MjModel before stepping
it. The first run on a Robot object builds them; later runs on the same object (a
benchmark, a script running several programs) reuse them. Robots are not modified after
loading. The last few robots are kept; ``clear()`` forgets them all.
"""

from __future__ import annotations

from collections import OrderedDict

KEEP = 2
_CACHE: OrderedDict = OrderedDict()      # id(robot) -> (robot, {key: value})


def get(robot, key, build):
    """``build()``, built once for ``robot`` and ``key``."""
    entry = _CACHE.get(id(robot))
    if entry is None or entry[0] is not robot:      # the robot is held, so its id is not reused meanwhile
        entry = _CACHE[id(robot)] = (robot, {})
        while len(_CACHE) > KEEP:
            _CACHE.popitem(last=False)
    _CACHE.move_to_end(id(robot))
    values = entry[1]
    if key not in values:
        values[key] = build()
    return values[key]


def clear() -> None:
    _CACHE.clear()


def drive(robot, wheels: str):
    """``find_drive(robot, wheels)``: a fresh Drive (runs set its limits) on the shared geometry."""
    import dataclasses

    from myrabot_desc.sim.diffdrive import find_drive

    d = get(robot, ("drive", wheels), lambda: find_drive(robot, wheels))
    return dataclasses.replace(d, notes=list(d.notes))


def arm(robot):
    from myrabot_desc.sim.arm import Arm

    return get(robot, "arm", lambda: Arm(robot))


def collider(robot):
    """The arm against the robot's own structure (no scene)."""
    from myrabot_desc.sim.collide import ArmCollider

    return get(robot, "collider", lambda: ArmCollider(arm(robot)))


def support(robot, wheels: str):
    from myrabot_desc.sim.stability import support_polygon

    return get(robot, ("support", wheels), lambda: support_polygon(robot, drive(robot, wheels)))


def footprint(robot) -> list:
    from myrabot_desc.sim.vuelta import footprint as outline

    return list(get(robot, "footprint", lambda: outline(robot)))
