"""``sim drive --engine mujoco``: the kinematic ``sim drive``'s commanded twist, in MuJoCo, against the
kinematic prediction.

The base stands on the floor with a free joint (our MJCF: velocity actuators on the wheels) and settles
for ``SETTLE`` seconds; then each script segment sets the wheel rates the drive computes for its twist
(the plugin's geometry, or the URDF's: ``--wheels``; a skid-steer base's wheels on one side turn
together). Per segment, after ``RAMP`` seconds of acceleration, the axle midpoint's speed and the yaw
rate are measured as the kinematic program measures them. The kinematic ``sim drive`` of the same
script says what the URDF's wheels make of the command (0.8x for a plugin that believes in bigger
wheels); the MuJoCo ratios must be within ``TOLERANCE`` of those, or the run fails with the cause it
finds in the numbers:

* the wheels do not turn as commanded: the velocity actuator's force limit (the effort limit) or its
  gain, or the command is over the joint's velocity limit;
* the wheels turn but the base does not follow (slip): how much of the weight the wheels carry against
  the casters ("mass on casters"), how hard the other contacts drag ("friction"), a skid-steer base's
  wheels scrubbing sideways in a turn.
"""

from __future__ import annotations

import math
import time

from myrabot_desc.errors import InputError
from myrabot_desc.model import drive as D
from myrabot_desc.model.statics import effort_of
from myrabot_desc.sim import drive as kinematic
from myrabot_desc.sim.diffdrive import find_drive
from myrabot_desc.physics import kinds
from myrabot_desc.physics.engine import Engine, Path
from myrabot_desc.physics.result import Cause, PhysicsResult
from myrabot_desc.sim.result import Check

SETTLE = 0.5             # s on the floor before the first command
RAMP = 0.5               # s of each segment left out of the measurement (the wheels and the base accelerate)
TOLERANCE = 0.10         # relative difference allowed between MuJoCo's ratio and the kinematic one
TRACKING = 0.9           # wheels turning slower than this share of their command: the actuator is the cause
SAMPLE_RATE = 100.0      # Hz


def run(robot, *, script=kinematic.DEFAULT_SCRIPT, wheels="plugin", left=(), right=(), tolerance=TOLERANCE,
        progress=None) -> PhysicsResult:
    import numpy as np

    wall0 = time.perf_counter()
    b = D.base(robot) if not left and not right else None
    if b is not None and b.kind not in ("differential", "skid_steer"):
        # its wheels are no differential pair: its kind's own commands and kinematic model
        return kinds.run(robot, b, script=script, tolerance=tolerance, settle=SETTLE, ramp=RAMP,
                         sample_rate=SAMPLE_RATE, tracking=TRACKING, progress=progress)
    drv = find_drive(robot, wheels, left, right)
    declared = D.main_drive(robot, tuple(left), tuple(right), guess=True)
    predicted = kinematic.run(robot, rate=1000.0, script=script, wheels=wheels, left=left, right=right,
                              tolerance=1.0)
    eng = Engine(robot, "free", robot.rest_pose())
    mj, m, d = eng.mujoco, eng.model, eng.data
    total = SETTLE + sum(s for *_, s in script)
    res = PhysicsResult("drive", robot.name, f"MuJoCo {mj.__version__}", total, float(m.opt.timestep))
    res.notes.extend(drv.notes)
    res.info["command geometry"] = "plugin" if drv.wheels == "plugin" else "URDF"

    # every wheel of each side, with its own radius and forward sign
    per_wheel = {}
    for name in declared.joints:
        w = D.wheel(robot, name)
        if w is None or name not in eng.actuators:
            continue
        per_wheel[name] = (w.origin[1] > 0, w.radius or drv.urdf.radius, w.forward_sign)
    missing = [n for n in declared.joints if n not in eng.actuators]
    if missing:
        res.notes.append(f"wheel joint(s) without a velocity actuator in the MJCF: {', '.join(missing)}")
    u = drv.urdf

    def rates(v, w):
        ql, qr = drv.command_rates(v, w)
        out = {}
        for name, (is_left, radius, sign) in per_wheel.items():
            if drv.wheels == "plugin" and drv.plugin is not None:
                out[name] = ql if is_left else qr            # the plugin sets each named joint's rate
            else:
                vside = (v - w * u.separation / 2) if is_left else (v + w * u.separation / 2)
                out[name] = vside / radius * sign
        return out

    qpos0 = eng.qpos_for(robot.rest_pose())
    eng.exclude_touching(qpos0)
    mj, m, d = eng.mujoco, eng.model, eng.data
    d.qpos[:] = qpos0
    d.qvel[:] = 0.0
    eng.hold(qpos0)
    mj.mj_forward(m, d)
    root = eng.root_body
    mid = np.array([u.axle_mid[0], u.axle_mid[1], 0.0])
    every = max(1, int(round(1.0 / (SAMPLE_RATE * m.opt.timestep))))
    wheel_ids = {n: eng.actuators[n] for n in per_wheel}
    dofs = {n: int(m.jnt_dofadr[eng.joint_ids[n]]) for n in per_wheel}
    wheel_bodies = {eng.body_of_link(robot.joints[n].child) for n in per_wheel}
    path = Path()
    ts, xs, ys, yaws = path.t, path.x, path.y, path.yaw
    wheel_rate_series = {n: [] for n in per_wheel}
    segments = []
    step = 0
    n_settle = eng.steps(SETTLE)
    plan = [(0.0, 0.0, SETTLE, n_settle, None)] + [(v, w, s, eng.steps(s), i) for i, (v, w, s) in enumerate(script)]
    total_steps = sum(p[3] for p in plan)
    for v, w, seconds, n, index in plan:
        cmd = rates(v, w)
        for name, a in wheel_ids.items():
            d.ctrl[a] = cmd.get(name, 0.0)
        seg = {"v": v, "w": w, "start": len(ts), "cmd": cmd, "track": [], "load": [], "drag": []}
        skip = int(round(min(RAMP, seconds / 2) / m.opt.timestep))
        for k in range(n):
            mj.mj_step(m, d)
            step += 1
            if step % every:
                continue
            R = d.xmat[root].reshape(3, 3)
            path.sample(step * m.opt.timestep, R, d.xpos[root] + R @ mid)
            for name in per_wheel:
                wheel_rate_series[name].append(float(d.qvel[dofs[name]]))
            if k >= skip and index is not None:
                seg.setdefault("from", len(ts) - 1)
                seg["track"].append({name: float(d.qvel[dofs[name]]) for name in per_wheel})
                load, drag = eng.floor_loads(wheel_bodies, R[:, 0])
                seg["load"].append(load)
                seg["drag"].append(drag)
        seg["end"] = len(ts) - 1
        if index is not None:
            segments.append(seg)
        if progress:
            progress(step / total_steps)
    res.steps = step
    t = np.asarray(ts)
    res.t = t
    res.series.update(path.series())
    for name, vals in wheel_rate_series.items():
        res.series[f"{name}_rate_rad_s"] = np.asarray(vals)
        res.joints.append(f"{name}_rate_rad_s")

    # per segment: achieved v, w as the kinematic program measures them, and its prediction
    kin_rows = {r["segment"]: r for r in predicted.info.get("segments", [])}
    rows, v_rel, w_rel = [], [], []
    for i, seg in enumerate(segments):
        a, b = seg.get("from"), seg["end"]
        if a is None or b - a < 2:
            continue
        if path.turned_over is not None and b >= path.turned_over:
            rows.append({"segment": i + 1, "v_cmd": seg["v"], "w_cmd": seg["w"], "turned_over": True})
            continue
        T = ts[b] - ts[a]
        dx, dy = np.diff(xs[a:b + 1]), np.diff(ys[a:b + 1])
        heading = np.asarray(yaws[a:b])
        fwd = np.cos(heading) * dx + np.sin(heading) * dy
        v_meas = float(np.sum(np.hypot(dx, dy) * np.sign(fwd))) / T
        w_meas = float(yaws[b] - yaws[a]) / T
        kin = kin_rows.get(i + 1, {})
        row = {"segment": i + 1, "v_cmd": seg["v"], "w_cmd": seg["w"], "v": round(v_meas, 5), "w": round(w_meas, 5)}
        if abs(seg["v"]) > 1e-9 and "v_ratio" in kin:
            row["v_ratio"] = round(v_meas / seg["v"], 4)
            row["v_ratio_kinematic"] = kin["v_ratio"]
            v_rel.append((row["v_ratio"] / kin["v_ratio"] if kin["v_ratio"] else math.inf, i))
        if abs(seg["w"]) > 1e-9 and "w_ratio" in kin:
            row["w_ratio"] = round(w_meas / seg["w"], 4)
            row["w_ratio_kinematic"] = kin["w_ratio"]
            w_rel.append((row["w_ratio"] / kin["w_ratio"] if kin["w_ratio"] else math.inf, i))
        rows.append(row)
    res.info["segments"] = rows

    def worst(rel):
        return max(rel, key=lambda x: abs(x[0] - 1.0)) if rel else (float("nan"), None)

    for label, rel, kind in (("speed vs kinematic", v_rel, "v"), ("turn rate vs kinematic", w_rel, "w")):
        if not rel:
            continue
        value, i = worst(rel)
        ok = abs(value - 1.0) <= tolerance
        causes = [] if ok else _causes(robot, eng, drv, declared, segments[i], kind, per_wheel)
        res.add(Check(label, ok, float(value), "", f"MuJoCo's ratio / the kinematic one = 1 ±{tolerance:.0%}",
                      f"segment {i + 1}: v {segments[i]['v']:g} m/s, w {segments[i]['w']:g} rad/s"), causes)
    upright, tipped = path.upright(segments)
    res.add(upright, [] if tipped is None else _causes(robot, eng, drv, declared, tipped, "w" if tipped["w"] else "v",
                                    per_wheel))
    # what the wheels and the contacts did, for every run
    track = _tracking(segments, per_wheel)
    if track is not None:
        res.info["wheel tracking"] = f"{track:.3f} of the commanded rate (worst segment)"
    share = _mean([s["load"] for s in segments])
    if share is not None:
        res.info["weight on the wheels"] = f"{share:.0%}"
    res.info["kinematic prediction"] = predicted.info.get("predicted ratios", "speed 1, turn 1 (URDF geometry)")
    res.notes.extend(eng.notes)
    res.wall = time.perf_counter() - wall0
    if progress:
        progress(1.0)
    return res


def _mean(groups):
    vals = [x for g in groups for x in g if x is not None]
    return sum(vals) / len(vals) if vals else None


def _tracking(segments, per_wheel) -> float | None:
    """The worst share of its commanded rate a wheel achieved (segment means)."""
    worst = None
    for seg in segments:
        if not seg["track"]:
            continue
        for name in per_wheel:
            want = seg["cmd"].get(name, 0.0)
            if abs(want) < 1e-6:
                continue
            got = sum(t[name] for t in seg["track"]) / len(seg["track"])
            share = got / want
            worst = share if worst is None or abs(share - 1) > abs(worst - 1) else worst
    return worst


def _causes(robot, eng, drv, declared, seg, kind, per_wheel) -> list:
    """Why MuJoCo's motion differs from the kinematic prediction in this segment, in model terms."""
    m = eng.model
    out = []
    # 1. the wheels do not turn as commanded
    for name in per_wheel:
        want = seg["cmd"].get(name, 0.0)
        if abs(want) < 1e-6 or not seg["track"]:
            continue
        got = sum(t[name] for t in seg["track"]) / len(seg["track"])
        if got / want >= TRACKING:
            continue
        j = robot.joints[name]
        a = eng.actuators[name]
        vel = j.limit.velocity if j.limit is not None and j.limit.velocity else None
        effort = effort_of(j)
        if vel is not None and abs(want) > vel:
            out.append(Cause(f"wheel {name} is commanded {abs(want):.3g} rad/s, over its velocity limit {vel:g} rad/s: "
                             f"it turns at {abs(got):.3g}", j.loc))
        elif effort is not None:
            out.append(Cause(f"wheel {name} turns at {got / want:.0%} of its command: its actuator reaches its force "
                             f"limit, the effort {effort:g} N·m, before the kv {float(m.actuator_gainprm[a][0]):.4g} "
                             "gain closes the error (wheel gains)", j.loc))
        else:
            out.append(Cause(f"wheel {name} turns at {got / want:.0%} of its command under the velocity gain kv "
                             f"{float(m.actuator_gainprm[a][0]):.4g} (wheel gains)", j.loc))
        if len(out) >= 2:
            return out
    # 2. they turn, the base does not follow: what holds it
    share = _mean([seg["load"]])
    drag = _mean([seg["drag"]])
    root = robot.links[robot.root].loc if robot.root in robot.links else robot.loc
    if kind == "w" and declared is not None and declared.skid:
        out.append(Cause(f"skid-steer: its {len(declared.left)} + {len(declared.right)} wheels scrub sideways in a "
                         "turn, which the equivalent diff drive of the kinematic prediction does not (friction)",
                         declared.loc or root))
    if share is not None and share < 0.6:
        out.append(Cause(f"mass on casters: the wheels carry {share:.0%} of the weight, the casters and the body "
                         "the rest, "
                         "so the wheels slip", root))
    if drag is not None and abs(drag) > 1e-3:
        out.append(Cause(f"friction: the contacts that are not wheels {'drag' if drag > 0 else 'push'} the base with "
                         f"{abs(drag):.3g} N {'against' if drag > 0 else 'along'} its motion", root))
    if not out:
        out.append(Cause("slip: the wheels turn as commanded but the base does not follow them", root))
    return out
