"""``sim drive --engine mujoco`` for bases that are not a differential pair: mecanum, omni, planar,
swerve and Ackermann (model/drive.base), in our MJCF on a floor, against their kinematic model
(sim/kinds.py).

* mecanum, omni, planar: ``convert --to mjcf`` moves the body with world slides and a yaw hinge
  (its rollers are not modelled); each step the slides get the twist the kinematic model says the
  wheels (or the plugin) make of the command, turned by the base's yaw. What MuJoCo adds: the body
  keeps to the floor and follows at the actuators' gains, against whatever else touches the floor
  (casters, a low body).
* swerve, Ackermann: a free base rolling on its wheels; each steering joint gets the angle and each
  wheel the rate the kinematic model gives (every steered wheel along its own path: the Ackermann
  law about the rear axle's centre, a swerve module along its axis's velocity).

Per segment, after the ramp, the reference point's body-frame velocity and the yaw rate are measured
as the kinematic program measures them; the ratios (achieved along the command / commanded speed, and
turn rate) must be within the tolerance of the kinematic ones. A failure names what did not follow:
a steering joint short of its angle, a wheel short of its rate (the actuator's force limit or gain),
or the base slipping while its joints do as told.
"""

from __future__ import annotations

import math
import time

from myrabot_desc.convert.mjcf.bodies import PLANAR_BASE
from myrabot_desc.model import drive as D
from myrabot_desc.physics.engine import Engine, Path
from myrabot_desc.physics.result import Cause, PhysicsResult
from myrabot_desc.sim import kinds as kinematic
from myrabot_desc.sim.result import Check

STEER_TOL = 0.05         # rad: a steering joint further than this from its command did not follow
FLOOR_TOL = 0.005        # m: the lowest collision point may leave the floor by this much


def run(robot, base: D.Base, *, script, tolerance, settle, ramp, sample_rate, tracking,
        progress=None) -> PhysicsResult:
    import numpy as np

    wall0 = time.perf_counter()
    script = [s if len(s) == 4 else (s[0], 0.0, s[1], s[2]) for s in script]
    model = kinematic.Model(robot, base, True)
    predicted = kinematic.run(robot, base, rate=1000.0, script=script, tolerance=1.0)
    eng = Engine(robot, "planar" if base.kind in D.BODY_MOVED else "free", robot.rest_pose())
    mj = eng.mujoco
    planar = all(n in eng.actuators for n in PLANAR_BASE)
    qpos0 = eng.qpos_for(robot.rest_pose())
    eng.exclude_touching(qpos0)
    m, d = eng.model, eng.data
    d.qpos[:] = qpos0
    d.qvel[:] = 0.0
    eng.hold(qpos0)
    mj.mj_forward(m, d)
    total = settle + sum(s[-1] for s in script)
    res = PhysicsResult("drive", robot.name, f"MuJoCo {mj.__version__}", total, float(m.opt.timestep))
    res.info["drive kind"] = base.kind
    res.info["declared by"] = base.why
    res.info["moved by"] = ("the planar base's velocity actuators (base_x, base_y, base_yaw): a body twist, "
                            "rollers not modelled" if planar else "its steering (position) and wheel (velocity) "
                            "actuators, rolling on the floor")
    root = eng.body_of_link(robot.root)
    ref = np.array([model.ref[0], model.ref[1], 0.0])
    yaw_adr = int(m.jnt_qposadr[m.joint("base_yaw").id]) if planar else None
    slides = [eng.actuators[n] for n in PLANAR_BASE] if planar else []
    joint_adr = {n: (int(m.jnt_qposadr[j]), int(m.jnt_dofadr[j])) for n, j in eng.joint_ids.items()}
    floor0 = None
    wheel_bodies = {eng.body_of_link(robot.joints[n].child) for n in base.wheels if n in robot.joints}
    every = max(1, int(round(1.0 / (sample_rate * m.opt.timestep))))
    path = Path()
    ts = path.t
    segments, step = [], 0
    plan = [((0.0, 0.0, 0.0), settle, None)] + [((vx, vy, w), s, i) for i, (vx, vy, w, s) in enumerate(script)]
    counts = [eng.steps(s) for _, s, _ in plan]
    total_steps = sum(counts)
    for (cmd, seconds, index), n in zip(plan, counts):
        body_twist = model.achieve(*cmd)[0] if index is not None else (0.0, 0.0, 0.0)
        joints = {k: v for k, v in model.joint_commands(*cmd).items() if k in eng.actuators} \
            if index is not None else {}
        for name, (_, value) in joints.items():
            d.ctrl[eng.actuators[name]] = value
        # the planar base's slides move the root origin: the reference point's twist carried to it
        tx, ty, tw = body_twist
        ox, oy = tx + tw * ref[1], ty - tw * ref[0]
        seg = {"cmd": cmd, "joints": joints, "steer": [], "wheel": [], "load": [], "drag": [], "rub": set(), "floor": set()}
        skip = int(round(min(ramp, seconds / 2) / m.opt.timestep))
        for k in range(n):
            if planar:
                th = d.qpos[yaw_adr]
                c, s_ = math.cos(th), math.sin(th)
                d.ctrl[slides] = (c * ox - s_ * oy, s_ * ox + c * oy, tw)
            mj.mj_step(m, d)
            step += 1
            if step % every:
                continue
            R = d.xmat[root].reshape(3, 3)
            path.sample(step * m.opt.timestep, R, d.xpos[root] + R @ ref)
            if k >= skip and index is not None:
                seg.setdefault("from", len(ts) - 1)
                for name, (mode, want) in joints.items():
                    qa, va = joint_adr.get(name, (None, None))
                    if qa is None:
                        continue
                    if mode == "position":
                        seg["steer"].append((name, want, float(d.qpos[qa])))
                    else:
                        seg["wheel"].append((name, want, float(d.qvel[va])))
                load, drag = eng.floor_loads(wheel_bodies, R[:, 0])
                seg["load"].append(load)
                seg["drag"].append(drag)
                if not planar:
                    seg["rub"] |= eng.rubbing(wheel_bodies)
                    seg["floor"] |= eng.on_floor(wheel_bodies)
        if index is None:
            mj.mj_kinematics(m, d)
            floor0 = eng.lowest_point()
        else:
            seg["end"] = len(ts) - 1
            segments.append(seg)
        if progress:
            progress(step / total_steps)
    res.steps = step
    res.t = np.asarray(ts)
    res.series.update(path.series())

    kin_rows = {r["segment"]: r for r in predicted.info.get("segments", [])}
    rows, v_rel, w_rel = [], [], []
    for i, seg in enumerate(segments):
        a, b = seg.get("from"), seg["end"]
        if a is None or b - a < 2:
            continue
        vx, vy, w = seg["cmd"]
        if path.turned_over is not None and b >= path.turned_over:
            rows.append({"segment": i + 1, "vx_cmd": vx, "vy_cmd": vy, "w_cmd": w, "turned_over": True})
            continue
        bx, by, w_meas = path.body_twist(a, b)
        kin = kin_rows.get(i + 1, {})
        row = {"segment": i + 1, "vx_cmd": vx, "vy_cmd": vy, "w_cmd": w,
               "vx": round(bx, 5), "vy": round(by, 5), "w": round(w_meas, 5)}
        sp = math.hypot(vx, vy)
        if sp > 1e-9 and "v_ratio" in kin:
            row["v_ratio"] = round((bx * vx + by * vy) / (sp * sp), 4)
            row["v_ratio_kinematic"] = kin["v_ratio"]
            v_rel.append((_relative(row["v_ratio"], kin["v_ratio"]), i))
        if abs(w) > 1e-9 and "w_ratio" in kin:
            row["w_ratio"] = round(w_meas / w, 4)
            row["w_ratio_kinematic"] = kin["w_ratio"]
            w_rel.append((_relative(row["w_ratio"], kin["w_ratio"]), i))
        rows.append(row)
    res.info["segments"] = rows

    for label, rel in (("speed vs kinematic", v_rel), ("turn rate vs kinematic", w_rel)):
        if not rel:
            continue
        value, i = max(rel, key=lambda x: abs(x[0] - 1.0))
        ok = abs(value - 1.0) <= tolerance
        seg = segments[i]
        vx, vy, w = seg["cmd"]
        res.add(Check(label, ok, float(value), "", f"MuJoCo's ratio / the kinematic one = 1 ±{tolerance:.0%}",
                      f"segment {i + 1}: vx {vx:g}, vy {vy:g} m/s, w {w:g} rad/s"),
                [] if ok else _causes(robot, eng, base, seg, tracking))
    upright, tipped = path.upright(segments)
    res.add(upright, [] if tipped is None else _causes(robot, eng, base, tipped, tracking))
    mj.mj_kinematics(m, d)
    low = eng.lowest_point()
    if floor0 is not None and math.isfinite(low) and math.isfinite(floor0):
        res.add(Check("stays on the floor", abs(low - floor0) <= FLOOR_TOL, round(low - floor0, 4), "m",
                      f"the lowest collision point within {FLOOR_TOL * 1000:g} mm of where it settled",
                      "" if abs(low - floor0) <= FLOOR_TOL else
                      ("it sank into the floor" if low < floor0 else "it left the floor (tipped or hopped)")))
    res.info["kinematic prediction"] = ", ".join(
        f"{k} {v}" for k, v in (("speed", _worst(predicted, "v_ratio")), ("turn", _worst(predicted, "w_ratio")))
        if v is not None) or "no ratio"
    res.notes.extend(model.notes)
    res.notes.extend(eng.notes)
    res.wall = time.perf_counter() - wall0
    if progress:
        progress(1.0)
    return res


def _relative(mujoco_ratio: float, kinematic_ratio: float) -> float:
    """MuJoCo's ratio over the kinematic one; where the kinematic model says the base does not move
    that way (a car asked to turn on the spot), 1 + the difference."""
    if abs(kinematic_ratio) < 1e-6:
        return 1.0 + mujoco_ratio - kinematic_ratio
    return mujoco_ratio / kinematic_ratio


def _worst(result, key: str):
    vals = [r[key] for r in result.info.get("segments", []) if key in r]
    return round(max(vals, key=lambda v: abs(v - 1.0)), 4) if vals else None


def _causes(robot, eng, base, seg, tracking) -> list:
    """What did not follow its command in this segment, in model terms: a joint short of its command
    (and what it rubs on), else what holds the base back on the floor."""
    out = []
    by_joint: dict = {}
    for kind, samples in (("steer", seg["steer"]), ("wheel", seg["wheel"])):
        for name, want, got in samples:
            by_joint.setdefault((kind, name), (want, []))[1].append(got)
    rubs: dict = {}
    for body, other in sorted(seg["rub"]):
        rubs.setdefault(eng.body_name[body], []).append(other)
    for (kind, name), (want, got) in by_joint.items():
        mean = sum(got) / len(got)
        j = robot.joints[name]
        if kind == "steer" and abs(mean - want) > STEER_TOL:
            out.append(Cause(f"steering joint {name} reaches {mean:.3g} rad of its {want:.3g} rad command (its "
                             "actuator's force limit or gain, or the joint's limits)", j.loc))
        elif kind == "wheel" and abs(want) > 1e-6 and mean / want < tracking:
            touch = rubs.get(eng.body_name[eng.body_of_link(j.child)])
            why = (f"turning, its collision meets {', '.join(touch)}'s, which holds it" if touch else
                   "its actuator's force limit, the effort, or its gain")
            out.append(Cause(f"wheel {name} turns at {mean / want:.0%} of its {want:.3g} rad/s command: {why}", j.loc))
    out = out[:3]
    root = robot.links[robot.root].loc if robot.root in robot.links else robot.loc
    loads = [x for x in seg["load"] if x is not None]
    drags = [x for x in seg["drag"] if x is not None]
    drag = sum(drags) / len(drags) if drags else 0.0
    if abs(drag) > 1e-3 and base.kind not in D.BODY_MOVED:
        who = ", ".join(sorted(seg["floor"])[:4]) or "other contacts"
        out.append(Cause(f"friction: {who} touch the floor without a joint that rolls them and drag the base "
                         f"with {drag:.3g} N", root))
    if loads and sum(loads) / len(loads) < 0.6 and base.kind not in D.BODY_MOVED:
        out.append(Cause(f"the rolling wheels carry {sum(loads) / len(loads):.0%} of the weight, the rest rests on "
                         "other contacts, so the wheels slip", root))
    if not out:
        out.append(Cause("slip: the steering and the wheels do as commanded but the base does not follow them"
                         if base.kind not in D.BODY_MOVED else
                         "the body does not follow the planar base's actuators (their gains against its mass, or "
                         "something on the floor holds it)", base.loc or root))
    return out
