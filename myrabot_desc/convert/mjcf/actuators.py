"""Actuators as MuJoCo Menagerie's models have them, sized against the compiled model at home.

Which joints get one, and of which kind, is the model's answer (model/actuation.py): velocity
actuators for wheels, position actuators for the joints something commands in position, none on a
passive joint or a mimic joint. Position actuators reach the joint's effort limit at 0.05 rad
(5 mm), are bounded for stability by the joint-space inertia, and critically damped. Wheels'
velocity gains are sized against the robot they roll, with an armature when the wheel is light.
A joint whose effort limit cannot hold its subtree at home has that subtree gravity-compensated.
"""

from __future__ import annotations

from myrabot_desc.convert.common import num
from myrabot_desc.model import drive as D

# Position actuators reach the joint's effort limit at this error (rad, or m for prismatic joints),
# and are held to a natural frequency of at most OMEGA_DT / timestep (explicit springs beyond it
# ring or diverge on light links); critically damped.
FULL_EFFORT_AT = {"hinge": 0.05, "slide": 0.005}
OMEGA_DT = 0.5
# Wheels: velocity actuators. implicitfast integrates a velocity servo implicitly, stable at any
# gain, but a force clamped at its range is integrated explicitly: one clamped step on a light
# wheel overshoots by effort*dt/I and the model diverges (ros2_control_demos' DiffBot: 0.3 kg,
# r 1.5 cm wheels, effort 100 N·m, gain 1000: gone to x 69 m, z 72 m). So with an effort limit
# the gain reaches it only at WHEEL_CLAMP_AT times the velocity limit (no command inside
# ctrlrange clamps, from rest), and at least ROLLING_CLAMPED x the rolling gain below, at which a
# clamped step on a loaded wheel does not overshoot.
# Without one, nothing clamps, and the gain is stiff against what the wheel turns: itself and its
# share of the robot rolling on it (m/n r²), plus WHEEL_OVER_DAMPING times its joint damping.
WHEEL_CLAMP_AT = 2.0
WHEEL_OVER_DAMPING = 50.0
ROLLING_CLAMPED = 0.5
# A stiff velocity servo on a light wheel rolling on the floor makes MuJoCo's contacts unstable
# even unclamped (DiffBot, settled, then commanded 0.5 rad/s: thrown 1.3 m up). The wheel joint
# gets an armature (a motor's rotor inertia, which URDF does not describe) so that one step of
# the servo changes its speed by at most 1/WHEEL_SERVO_STEP of the error: kv dt / (I + armature).
WHEEL_SERVO_STEP = 10.0
# A position-controlled joint that needs more than this share of its effort limit to hold what it
# carries at home gets that subtree gravity-compensated (PR2's shoulders rely on a spring
# counterbalance the URDF does not describe).
HOLD_SHARE = 0.8
# A planar base's velocity actuators reach the commanded speed with this time constant: kv = the
# mass (slides) or the yaw inertia (hinge) of the whole robot at home over it (implicitfast keeps a
# velocity servo stable at any gain).
BASE_TAU = 0.05


def _append(report, name: str, detail: str) -> None:
    old = report.get("joint", name)
    report.set("joint", name, old.fate if old else "kept", (old.detail + "; " if old and old.detail else "") + detail)


def gravity_compensate(mujoco, spec, model, data, robot, commands, notes, report) -> None:
    """gravcomp on the bodies moved by a position-controlled joint too weak to hold them at home
    (``data``: the model at home, forward done)."""
    compensated = []
    for name, cmd in commands.items():
        jid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
        j = robot.joints[name]
        effort = j.limit.effort if j.limit is not None and j.limit.effort and j.limit.effort > 0 else None
        if jid < 0 or cmd.kind != "position" or not effort:
            continue
        need = abs(float(data.qfrc_bias[model.jnt_dofadr[jid]]))
        if need <= HOLD_SHARE * effort:
            continue
        root_body = model.jnt_bodyid[jid]
        for b in range(model.nbody):
            a = b
            while a > root_body:
                a = model.body_parentid[a]
            if a == root_body:
                spec.body(model.body(b).name).gravcomp = 1.0
        compensated.append(name)
        _append(report, name, f"holding its subtree at home takes {need:.3g} N*m or N, over 80% of its effort limit "
                f"{num(effort)}: the bodies it moves are gravity-compensated (gravcomp), as a real counterbalance would")
    if compensated:
        notes.warn(f"{len(compensated)} joint(s) cannot hold what they carry at home within their effort limit: "
                   f"the bodies they move are gravity-compensated in MuJoCo: {', '.join(compensated)}")


def add_actuators(mujoco, spec, model, data, robot, commands, report, qpos) -> tuple[list[float], int, int]:
    """Position and velocity actuators (``data``: the model at home, forward done); their home
    controls and how many of each."""
    # the joint-space inertia at home: its diagonal, the last entry of each row of MuJoCo's sparse
    # lower-triangular M (mj_fullM would make a dense nv x nv copy: 3.2 GB at 20,000 joints)
    diag = data.M[model.M_rowadr + model.M_rownnz - 1]
    dt = model.opt.timestep
    n_wheels = sum(1 for c in commands.values() if c.kind == "velocity")
    wheel_share = float(model.body_mass.sum()) / max(n_wheels, 1)     # the mass each wheel rolls
    ctrl: list[float] = []
    n_pos = n_vel = 0
    for name, cmd in commands.items():
        jid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
        if jid < 0:
            continue
        j = robot.joints.get(name)
        if j is None:           # the planar base's slides and yaw hinge (bodies.PLANAR_BASE)
            kv = float(f"{max(float(diag[model.jnt_dofadr[jid]]), 1e-9) / BASE_TAU:.4g}")
            act = spec.add_actuator(name=name, target=name, trntype=mujoco.mjtTrn.mjTRN_JOINT)
            act.set_to_velocity(kv=kv)
            ctrl.append(0.0)
            n_vel += 1
            report.set("joint", name, "translated", f"planar base: velocity actuator (kv {num(kv)}, "
                       f"{BASE_TAU:g} s to the commanded speed)")
            continue
        if cmd.kind is None:
            old = report.get("joint", name)
            report.set("joint", name, old.fate if old else "kept", f"no actuator: {cmd.why}")
            continue
        dof = model.jnt_dofadr[jid]
        inertia = max(float(diag[dof]), 1e-9)
        # a negative limit is SDF's "no limit" (Audibot writes effort and velocity -1): none, like 0
        effort = j.limit.effort if j.limit is not None and j.limit.effort and j.limit.effort > 0 else None
        act = spec.add_actuator(name=name, target=name, trntype=mujoco.mjtTrn.mjTRN_JOINT)
        if effort:
            act.forcelimited = mujoco.mjtLimited.mjLIMITED_TRUE
            act.forcerange = [-effort, effort]
        if cmd.kind == "velocity":
            vel = j.limit.velocity if j.limit is not None and j.limit.velocity and j.limit.velocity > 0 else None
            rolling = _rolling_kv(robot, j, inertia, dt, wheel_share)
            kv = float(f"{max(effort / (WHEEL_CLAMP_AT * vel), ROLLING_CLAMPED * rolling) if effort and vel else rolling:.4g}")
            act.set_to_velocity(kv=kv)
            if vel:
                act.ctrllimited = mujoco.mjtLimited.mjLIMITED_TRUE
                act.ctrlrange = [-vel, vel]
            ctrl.append(0.0)
            n_vel += 1
            detail = f"velocity actuator (kv {num(kv)}{f', force {num(effort)}' if effort else ''})"
            own = float(diag[dof]) - float(model.dof_armature[dof])
            armature = float(f"{kv * dt / WHEEL_SERVO_STEP - own:.3g}")
            if armature > 0:      # a light wheel under a stiff servo: the motor's rotor inertia (see WHEEL_SERVO_STEP)
                spec.joint(name).armature = max(armature, float(model.dof_armature[dof]))
                detail += f", armature {num(armature)} kg·m² (the motor's rotor, which the URDF does not give)"
        else:
            slide = model.jnt_type[jid] == mujoco.mjtJoint.mjJNT_SLIDE
            kp_max = inertia * (OMEGA_DT / dt) ** 2
            kp = min(effort / FULL_EFFORT_AT["slide" if slide else "hinge"], kp_max) if effort else kp_max
            kp = float(f"{kp:.4g}")
            act.set_to_position(kp=kp, dampratio=1.0)
            if model.jnt_limited[jid]:
                act.ctrllimited = mujoco.mjtLimited.mjLIMITED_TRUE
                act.ctrlrange = [float(x) for x in model.jnt_range[jid]]
            ctrl.append(float(qpos[model.jnt_qposadr[jid]]))
            n_pos += 1
            detail = f"position actuator (kp {num(kp)}, critically damped{f', force {num(effort)}' if effort else ''})"
            if j.limit is not None and j.limit.effort == 0:
                detail += "; effort limit 0 read as not given (ROS-Industrial writes 0): no force limit"
        _append(report, name, detail)
    return ctrl, n_pos, n_vel


def _rolling_kv(robot, joint, inertia: float, dt: float, mass_share: float) -> float:
    """A wheel's velocity gain without an effort limit: (its own inertia + its share of the robot's
    mass at its radius) / timestep, plus WHEEL_OVER_DAMPING x its joint damping (see WHEEL_CLAMP_AT)."""

    w = D.wheel(robot, joint.name, read_meshes=True)
    r = w.radius if w is not None and w.radius else 0.0
    damping = joint.dynamics.damping if joint.dynamics is not None else 0.0
    return (inertia + mass_share * r * r) / dt + WHEEL_OVER_DAMPING * damping
