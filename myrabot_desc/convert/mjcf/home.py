"""The ``home`` pose: the robot's rest pose standing on the floor, and what touches there.

Home is ``Robot.rest_pose`` (every joint at 0, or at its nearer limit when 0 is outside its range),
a mimic joint where its equality constraint puts it. The robot stands on the floor (z = 0) at
home: the lowest point of MuJoCo's collision geoms there (exact for primitives and mesh vertices)
gives how far a free base is lifted in the keyframe, or how far up a welded robot is welded.
Body pairs that MuJoCo's collision pass finds touching at home (it already skips parent-child
pairs) get contact exclusions.
"""

from __future__ import annotations


def rest_with_mimics(robot) -> dict[str, float]:
    """``Robot.rest_pose`` with each mimic joint where its equality constraint puts it."""
    rest = robot.rest_pose()
    for j in robot.joints.values():
        if j.mimic is not None and j.mimic.joint in rest:
            rest[j.name] = j.mimic.offset + j.mimic.multiplier * rest[j.mimic.joint]
    return rest


def floor_lift(mujoco, model, data, moving_only: bool) -> float:
    """How far up the robot must go for its lowest collision point in ``data`` (forward done) to
    touch z = 0; 0 without a collision geom. ``moving_only``: leave out the world body's geoms."""
    import numpy as np

    low = np.inf
    for g in range(model.ngeom):
        if not (model.geom_contype[g] or model.geom_conaffinity[g]) or (moving_only and model.geom_bodyid[g] == 0):
            continue
        t = model.geom_type[g]
        R = data.geom_xmat[g].reshape(3, 3)
        z = data.geom_xpos[g][2]
        sz = model.geom_size[g]
        if t == mujoco.mjtGeom.mjGEOM_MESH:
            a, n = model.mesh_vertadr[model.geom_dataid[g]], model.mesh_vertnum[model.geom_dataid[g]]
            low = min(low, float(z + (model.mesh_vert[a:a + n] @ R[2]).min()))
        elif t == mujoco.mjtGeom.mjGEOM_SPHERE:
            low = min(low, z - sz[0])
        elif t == mujoco.mjtGeom.mjGEOM_CYLINDER:
            low = min(low, z - abs(R[2, 2]) * sz[1] - sz[0] * np.sqrt(max(0.0, 1 - R[2, 2] ** 2)))
        elif t == mujoco.mjtGeom.mjGEOM_BOX:
            low = min(low, z - float(np.abs(R[2]) @ sz))
    return -float(low) if np.isfinite(low) else 0.0


def home_qpos(mujoco, model, robot):
    """The rest pose as MuJoCo's qpos."""
    qpos = model.qpos0.copy()
    for name, value in rest_with_mimics(robot).items():
        jid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
        if jid >= 0:
            qpos[model.jnt_qposadr[jid]] = value
    return qpos


def raise_free_joints(mujoco, model, qpos, lift: float) -> None:
    """Every free joint of ``qpos`` ``lift`` m up."""
    for j in range(model.njnt):
        if model.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE:
            qpos[model.jnt_qposadr[j] + 2] += lift


def raise_welded(spec, lift: float) -> None:
    """What hangs from the world body ``lift`` m up: the frames the welded roots were fused into,
    and the bodies joined to the world by a joint of their own."""
    for el in list(spec.worldbody.frames) + list(spec.worldbody.bodies):
        if el.frame is None:       # the world body's own children, not those of its frames
            el.pos = [float(el.pos[0]), float(el.pos[1]), float(el.pos[2]) + lift]


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
