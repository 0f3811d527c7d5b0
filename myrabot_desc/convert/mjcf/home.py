"""The ``home`` pose: the robot's rest pose standing on the floor, and what touches there.

Home is ``Robot.rest_pose`` (every joint at 0, or at its nearer limit when 0 is outside its range),
a mimic joint where its equality constraint puts it. The robot stands on the floor (z = 0) at
home: its lowest collision point there (model/support.py) gives how far a free base is lifted in
the keyframe, or how far up a welded root is welded. Body pairs that MuJoCo's collision pass
finds touching at home (it already skips parent-child pairs) get contact exclusions.
"""

from __future__ import annotations

from myrabot_desc.model.kinematics import world_transforms
from myrabot_desc.model.support import lowest


def rest_with_mimics(robot) -> dict[str, float]:
    """``Robot.rest_pose`` with each mimic joint where its equality constraint puts it."""
    rest = robot.rest_pose()
    for j in robot.joints.values():
        if j.mimic is not None and j.mimic.joint in rest:
            rest[j.name] = j.mimic.offset + j.mimic.multiplier * rest[j.mimic.joint]
    return rest


def floor_lift(robot) -> float:
    """How far up the robot must go for its lowest collision point at home to touch z = 0 (0
    without a collision shape)."""
    low = lowest(robot, world_transforms(robot, rest_with_mimics(robot)), meshes=True)
    return -min(z for z, _, _ in low) if low else 0.0


def home_qpos(mujoco, model, robot, lift: float = 0.0):
    """The rest pose as MuJoCo's qpos; a free base ``lift`` m up."""
    qpos = model.qpos0.copy()
    for name, value in rest_with_mimics(robot).items():
        jid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
        if jid >= 0:
            qpos[model.jnt_qposadr[jid]] = value
    if lift:
        for j in range(model.njnt):
            if model.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE:
                qpos[model.jnt_qposadr[j] + 2] += lift
    return qpos


def exclude_touching(mujoco, spec, model, data, report) -> int:
    """Contact exclusions for the body pairs in contact in ``data`` (the model at home)."""
    names = {tuple(sorted((model.body(model.geom_bodyid[c.geom1]).name, model.body(model.geom_bodyid[c.geom2]).name)))
             for c in data.contact[:data.ncon]}
    for b1, b2 in sorted(names):
        spec.add_exclude(bodyname1=b1 or "world", bodyname2=b2 or "world")
    if names:
        report.set("contact", "self-collision", "approximated",
                   f"{len(names)} body pair(s) touching at rest excluded from collision: "
                   + ", ".join(f"{a}-{b}" for a, b in sorted(names)))
    return len(names)
