"""``drive``: any wheeled robot the drive model knows, a scripted twist, expected vs achieved motion.

Each script segment holds a twist (v, w) for some seconds. The expected motion
is the commanded twist itself; the achieved motion is what the URDF's wheels do
with the wheel rates the plugin computes (``--wheels plugin``) or that the URDF's
own geometry computes (``--wheels urdf``). Per segment we measure the axle
midpoint's speed (path length over time) and the yaw rate (heading change over
time), after any acceleration ramp, and compare them with the command.
"""

from __future__ import annotations

import math
import time

from myrabot_desc.errors import InputError
from myrabot_desc.model import drive as D
from myrabot_desc.model.kinematics import center_of_mass
from myrabot_desc.model.pin_model import build_model
from myrabot_desc.safety import sim_steps
from myrabot_desc.sim import kinds, stability
from myrabot_desc.sim.diffdrive import find_drive, integrate
from myrabot_desc.sim.result import Series, SimResult, ratio_checks
from myrabot_desc.sim.stability import footprint

DEFAULT_SCRIPT = ((0.2, 0.0, 5.0), (0.0, 0.5, 4.0), (0.2, 0.4, 5.0))


def parse_twist(text: str) -> tuple:
    """'V,W,SECONDS' -> (v, w, seconds); 'VX,VY,W,SECONDS' -> (vx, vy, w, seconds) (a sideways
    speed, for bases that move sideways: mecanum, omni, planar, swerve)."""
    parts = [p for p in text.replace(" ", "").split(",") if p]
    if len(parts) not in (3, 4):
        raise ValueError(f"expected V,W,SECONDS or VX,VY,W,SECONDS (e.g. 0.2,0.4,5), got {text!r}")
    nums = tuple(float(p) for p in parts)
    if not (nums[-1] > 0) or not all(math.isfinite(x) for x in nums):
        raise ValueError(f"twist {text!r}: seconds must be > 0 and numbers finite")
    return nums


def _planar_script(robot, script) -> tuple:
    """The script as (v, w, seconds) for a base that cannot move sideways."""
    out = []
    for seg in script:
        if len(seg) == 4:
            if abs(seg[1]) > 1e-12:
                raise InputError(f"{robot.name}: a sideways speed ({seg[1]:g} m/s) for a base that cannot move "
                                 "sideways (a differential or skid-steer drive)", robot.loc)
            seg = (seg[0], seg[2], seg[3])
        out.append(seg)
    return tuple(out)


def run(robot, *, rate=1000.0, duration=None, script=DEFAULT_SCRIPT, wheels="plugin", left=(), right=(),
        wheel_speed_max=None, wheel_accel_max=None, tolerance=0.02, progress=None) -> SimResult:
    import numpy as np

    if not left and not right:
        b = D.base(robot)
        if b is not None and b.kind not in ("differential", "skid_steer"):
            # mecanum, omni, planar, swerve, Ackermann: the kind's own kinematic model (sim/kinds.py)
            return kinds.run(robot, b, rate=rate, duration=duration, script=script, wheels=wheels,
                             tolerance=tolerance, progress=progress)
    script = _planar_script(robot, script)
    wall0 = time.perf_counter()
    drive = find_drive(robot, wheels, left, right)
    wheels = drive.wheels
    drive.wheel_speed_max, drive.wheel_accel_max = wheel_speed_max, wheel_accel_max
    dt = 1.0 / rate
    total = sum(s for _, _, s in script)
    duration = total if duration is None else float(duration)
    N = sim_steps(duration, rate)      # bounded: safety.LIMITS max_sim_steps
    segments, bounds, k = [], [], 0
    for v, w, s in script:
        n = int(round(s * rate))
        segments.append((k, v, w))
        bounds.append((k, min(k + n, N), v, w))
        k += n
    if k < N:
        segments.append((k, 0.0, 0.0))        # the script ended: stop
    base = integrate(drive, segments, N, dt)
    if progress:
        progress(0.8)
    res = SimResult(program="drive", robot=robot.name, rate=rate, duration=N * dt, t=base.t, base=base,
                    wheel_names=(drive.urdf.left.joint, drive.urdf.right.joint))
    res.notes.extend(drive.notes)
    u = drive.urdf
    geo = {"URDF wheel separation": round(u.separation, 6), "URDF wheel radius": round(u.radius, 6)}
    if drive.plugin is not None:
        p = drive.plugin
        geo["plugin"] = f"{p.name} ({p.library})"
        geo["plugin wheel separation"] = p.separation
        geo["plugin wheel radius"] = p.radius
    geo["command geometry"] = "plugin" if wheels == "plugin" else "URDF"
    res.info.update(geo)

    rows, v_ratios, w_ratios = [], [], []
    expected = _ideal(script, N, dt, drive)
    for i, (ka, kb, v, w) in enumerate(bounds):
        if kb - ka < 2:
            continue
        settle = 0
        if wheel_accel_max:
            peak = max(abs(r) for r in drive.command_rates(v, w))
            settle = min(int(math.ceil(peak / wheel_accel_max / dt)) + 1, (kb - ka) // 2)
        a = ka + settle
        T = (kb - a) * dt
        dx, dy = np.diff(base.axle_x[a:kb + 1]), np.diff(base.axle_y[a:kb + 1])
        fwd = np.cos(base.yaw[a:kb]) * dx + np.sin(base.yaw[a:kb]) * dy
        v_meas = float(np.sum(np.hypot(dx, dy) * np.sign(fwd))) / T
        w_meas = float(base.yaw[kb] - base.yaw[a]) / T
        row = {"segment": i + 1, "v_cmd": v, "w_cmd": w, "v": round(v_meas, 6), "w": round(w_meas, 6)}
        if abs(v) > 1e-9:
            row["v_ratio"] = round(v_meas / v, 6)
            v_ratios.append(v_meas / v)
        if abs(w) > 1e-9:
            row["w_ratio"] = round(w_meas / w, 6)
            w_ratios.append(w_meas / w)
        rows.append(row)

    res.checks.extend(ratio_checks(v_ratios, w_ratios, tolerance))
    ex, ey, eth = expected
    perr = math.hypot(base.axle_x[-1] - ex[-1], base.axle_y[-1] - ey[-1])
    herr = math.degrees(abs(math.remainder(base.yaw[-1] - eth[-1], 2 * math.pi)))
    res.info["segments"] = rows
    res.info["final position error"] = f"{perr:.4f} m"
    res.info["final heading error"] = f"{herr:.2f} deg"
    if drive.plugin is not None and wheels == "plugin":
        p = drive.plugin
        kv = u.radius / p.radius
        kw = kv * p.separation / u.separation * (-1.0 if p.legacy else 1.0)   # legacy mode swaps the turn
        res.info["predicted ratios"] = f"speed {kv:.4f} (URDF r / plugin r), turn {kw:.4f} (× plugin sep / URDF sep)"
    res.info.update(_stance(robot, drive))
    res.moving = [("expected", ex, ey)]
    res.series = [Series("v commanded", _cmd_series(bounds, N, 2), "m/s", group="twist"),
                  Series("v achieved", np.concatenate([base.v, base.v[-1:]]), "m/s", group="twist"),
                  Series("w commanded", _cmd_series(bounds, N, 3), "rad/s", group="twist"),
                  Series("w achieved", np.concatenate([base.w, base.w[-1:]]), "rad/s", group="twist")]

    res.outline_of = lambda: footprint(robot)
    res.wall = time.perf_counter() - wall0
    if progress:
        progress(1.0)
    return res


def _ideal(script, N, dt, drive):
    """The commanded motion of the axle midpoint, integrated exactly (what the user expects)."""
    import numpy as np

    v = np.zeros(N)
    w = np.zeros(N)
    k = 0
    for sv, sw, s in script:
        n = int(round(s / dt))
        v[k:k + n], w[k:k + n] = sv, sw
        k += n
    th = np.concatenate([[0.0], np.cumsum(w * dt)])
    mid = th[:-1] + w * dt / 2
    chord = v * dt * np.sinc(w * dt / (2 * np.pi))
    mx, my = drive.urdf.axle_mid
    x = np.concatenate([[mx], mx + np.cumsum(chord * np.cos(mid))])
    y = np.concatenate([[my], my + np.cumsum(chord * np.sin(mid))])
    return x, y, th


def _cmd_series(bounds, N, col):
    import numpy as np

    out = np.zeros(N + 1)
    for b in bounds:
        out[b[0]:b[1] + 1] = b[col]
    return out


def _stance(robot, drive) -> dict:
    """Static stance: where the centre of mass (model/kinematics, as check and the viewer) sits
    against the support polygon."""
    try:
        _, com = center_of_mass(robot)
        sup, notes = stability.support_polygon(robot, drive)
        mg = stability.margin(sup, com)
        c = [round(float(v), 4) + 0.0 for v in com]     # + 0.0: a -0.00001 is 0.0000, not -0.0000
        out = {"centre of mass": f"({c[0]:.4f}, {c[1]:.4f}, {c[2]:.4f}) m",
               "static tip-over margin": f"{mg:.4f} m" + ("" if mg > 0 else " (tips over at rest)")}
        if len(sup.polygon) == 2:
            (ax, ay), (bx, by) = sup.polygon
            out["axle"] = f"x {0.5 * (ax + bx):.4f} m; COM is {abs(com[0] - 0.5 * (ax + bx)) * 1000:.1f} mm " \
                          f"{'behind' if com[0] < 0.5 * (ax + bx) else 'ahead of'} it"
        for n in notes:
            out.setdefault("stance", n)
        return out
    except Exception as exc:         # stance is informative only
        return {"stance": f"not computed ({type(exc).__name__})"}
