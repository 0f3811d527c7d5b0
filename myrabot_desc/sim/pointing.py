"""``escoja`` and ``seguir``: the arm points at a can (seed-spec.md §5.2–5.4).

The seed does not ship either program (they live in ``brazo_fer``); what it says
is the behaviour: escoja "points at the object we indicate and, after a short
period, returns to its initial position"; seguir "follows the indicated
object" while ``mover_objetos`` moves it in 0.005 m steps, at most one step
per 0.1 s (its ``retardo``). We reproduce that behaviour with our own pointing
IK (arm.py defines "point at") and the lab's servo units: every command goes
through the truncating conversions of servo.py, so the achieved pointing error
includes the 1° command resolution the lab's code has.

The robot stands still at the layout's robot pose. Scene collisions (table,
cans) and self collisions (arm vs structure) are checked along the motion.
"""

from __future__ import annotations

import math
import time

from myrabot_desc.safety import sim_steps
from myrabot_desc.sim import prepared
from myrabot_desc.sim import scene as sc
from myrabot_desc.sim import servo as sv
from myrabot_desc.sim.collide import collision_check
from myrabot_desc.sim.diffdrive import BaseTrack
from myrabot_desc.sim.result import Check, Series, SimResult

# mover_objetos key codes (Appendix A.9): arrows arrive as ESC [ A/B/C/D, the code reads the last byte
KEYS = {"C": (0.005, 0, 0), "D": (-0.005, 0, 0), "A": (0, 0, 0.005), "B": (0, 0, -0.005),
        "w": (0, 0.005, 0), "s": (0, -0.005, 0), "a": None, "d": None, "e": None, "q": None}
DEFAULT_KEYS = "D*16 w*30 C*16 s*60 w*30"
RETARDO = 0.1


def parse_keys(text: str) -> list[str]:
    """'D*16 w*30' -> ['D'] * 16 + ['w'] * 30; keys as mover_objetos reads them (C D A B w s a d e q)."""
    out = []
    for tok in text.replace(",", " ").split():
        key, _, n = tok.partition("*")
        if key not in KEYS:
            raise ValueError(f"unknown key {key!r} (mover_objetos keys: C D A B = → ← ↑ ↓, w s, a d e q)")
        try:
            count = int(n) if n else 1
        except ValueError:
            raise ValueError(f"bad repeat count in {tok!r}") from None
        if count < 0 or count > 100000:
            raise ValueError(f"repeat count out of range in {tok!r}")
        out.extend([key] * count)
    return out


def _setup(robot, layout, speed_units):
    import numpy as np

    arm = prepared.arm(robot)
    servos = [sv.Servo(0.0, sv.speed_rad_s(speed_units, arm.velocity[i]), arm.lower[i], arm.upper[i])
              for i in range(len(arm.names))]
    q_home = np.array([sv.units_to_rad(sv.UNITS_HOME)] * len(arm.names))
    return arm, servos, q_home


def _command(servos, t, units):
    for s, u in zip(servos, units):
        goal = sv.units_to_rad(u)
        if s.segments[-1][2] != goal:
            s.command(t, goal)


def _to_units(q, mode="nearest"):
    return [sv.units_for_angle(float(x), mode) for x in q]


def _base_track(robot, N, dt):
    """The base stands still: a constant track on the grid."""
    import numpy as np

    z = np.zeros(N + 1)
    return BaseTrack(t=np.arange(N + 1) * dt, x=z, y=z, yaw=z, wheel_left=z, wheel_right=z, v=z[:-1], w=z[:-1],
                     axle_x=z, axle_y=z)


def _collisions(res, arm, scene, q_home, label):
    collision_check(res, arm, res.t, res.arm_q, q_home, "collision", label, scene)


def run_escoja(robot, layout_objects, *, which="1", rate=1000.0, duration=None, select_at=0.5, hold=2.0,
               speed_units=400, standoff=0.05, tolerance=5.0, units_mode="nearest", progress=None) -> SimResult:
    import numpy as np

    wall0 = time.perf_counter()
    target_obj = sc.select(layout_objects, which)
    arm, servos, q_home = _setup(robot, layout_objects, speed_units)
    target = target_obj.centre()
    dt = 1.0 / rate
    home_u = [sv.UNITS_HOME] * len(arm.names)
    _command(servos, 0.0, home_u)                                   # home at start
    t_sel = max(select_at, 0.0)
    q_ideal = arm.ik_point(target, target_obj.radius() + standoff, q_home)
    units = _to_units(q_ideal, units_mode)
    units[4] = sv.UNITS_HOME                                        # the gripper stays
    other = "lab" if units_mode == "nearest" else "nearest"
    units_other = _to_units(q_ideal, other)
    units_other[4] = sv.UNITS_HOME
    _command(servos, t_sel, units)
    t_arrive = max(s.arrival() for s in servos)
    t_back = t_arrive + hold
    _command(servos, t_back, home_u)
    t_home = max(s.arrival() for s in servos)
    if duration is None:
        duration = math.ceil((t_home + 0.5) * 10) / 10
    N = sim_steps(duration, rate)      # bounded: safety.LIMITS max_sim_steps
    base = _base_track(robot, N, dt)
    t = base.t
    arm_q = np.column_stack([s.positions(t) for s in servos])
    if progress:
        progress(0.5)
    res = SimResult(program="escoja", robot=robot.name, rate=rate, duration=N * dt, t=t, base=base,
                    arm_names=list(arm.names), arm_q=arm_q)
    q_cmd = np.array([sv.units_to_rad(u) for u in units])
    err_ideal = arm.pointing_error(q_ideal, target)
    err = arm.pointing_error(q_cmd, target)
    err_other = arm.pointing_error(np.array([sv.units_to_rad(u) for u in units_other]), target)
    held = t_back <= t[-1]
    res.checks.append(Check("pointing error", held and err <= tolerance, float(err), "deg",
                            f"≤ {tolerance:g}° while holding, object {which} = {target_obj.model}",
                            f"units {units[:4]} (base, arti1, arti2, arti3, {units_mode} conversion); "
                            f"IK {err_ideal:.3f}° before conversion; the {other} conversion would give "
                            f"{err_other:.3f}°; target ({target[0]:.3f}, {target[1]:.3f}, {target[2]:.3f}) m"))
    res.info[f"pointing error, {other} conversion"] = round(err_other, 4)
    back = t_home <= t[-1]
    res.checks.append(Check("returns home", back, f"at {t_home:.2f} s" if back else "not within the run", "",
                            f"held {hold:g} s, then all joints back to {sv.UNITS_HOME}"))
    # pointing error over time (100 Hz is plenty for the plot)
    ks = np.arange(0, N + 1, max(1, int(round(rate / 100))))
    errs = np.array([arm.pointing_error(arm_q[k], target) for k in ks])
    if progress:
        progress(0.7)
    _collisions(res, arm, layout_objects, q_home, "no contact with the robot, the table or the cans")
    tip = arm.wrist(q_cmd)[2]
    res.info["object"] = f"{which} = {target_obj.model}"
    res.info["pointing reached"] = f"{t_arrive:.3f} s (selected at {t_sel:g} s)"
    res.info["tip to object centre"] = f"{float(np.linalg.norm(tip - target)):.3f} m"
    res.info["joint angles"] = {n: round(math.degrees(q), 2) for n, q in zip(arm.names[:4], q_cmd[:4])}
    res.series = [Series(n, np.degrees(arm_q[:, i]), "deg") for i, n in enumerate(arm.names)]
    res.series.append(Series("pointing error", errs, "deg (error)", t=t[ks]))
    res.scene = list(layout_objects)

    res.outline_of = lambda: prepared.footprint(robot)
    res.wall = time.perf_counter() - wall0
    if progress:
        progress(1.0)
    return res


def run_seguir(robot, layout_objects, *, which="1", keys=DEFAULT_KEYS, rate=1000.0, duration=None, select_at=0.5,
               move_at=2.0, track_rate=10.0, speed_units=400, standoff=0.05, tolerance=5.0,
               units_mode="nearest", progress=None) -> SimResult:
    import numpy as np

    wall0 = time.perf_counter()
    obj = sc.select(layout_objects, which)
    others = [o for o in layout_objects if o is not obj]
    arm, servos, q_home = _setup(robot, layout_objects, speed_units)
    dt = 1.0 / rate
    seq = parse_keys(keys)
    # the can's positions: one mover_objetos step per retardo, from move_at
    offsets = [(0.0, 0.0, 0.0)]
    for k in seq:
        d = KEYS[k] or (0, 0, 0)             # tilt keys change the orientation only
        x, y, z = offsets[-1]
        offsets.append((x + d[0], y + d[1], z + d[2]))
    t_end_path = move_at + len(seq) * RETARDO
    if duration is None:
        duration = math.ceil((t_end_path + 1.5) * 10) / 10
    N = sim_steps(duration, rate)      # bounded: safety.LIMITS max_sim_steps
    c0 = obj.centre()

    def centre_at(t):
        i = 0 if t < move_at else min(len(offsets) - 1, int(math.floor((t - move_at) / RETARDO + 1e-9)) + 1)
        return c0 + np.asarray(offsets[i])

    home_u = [sv.UNITS_HOME] * len(arm.names)
    _command(servos, 0.0, home_u)
    r_obj = obj.radius()
    every = max(1, int(round(rate / track_rate)))
    q_prev = None
    n_updates = 0
    k_sel = int(round(select_at * rate))
    k_start = -(-k_sel // every) * every
    for k in range(k_start, N + 1, every):
        t = k * dt
        q_goal = arm.ik_point(centre_at(t), r_obj + standoff, q_home, q_init=q_prev)
        q_prev = q_goal
        u = _to_units(q_goal, units_mode)
        u[4] = sv.UNITS_HOME
        _command(servos, t, u)
        n_updates += 1
        if progress and n_updates % 10 == 0:
            progress(0.6 * k / N)
    base = _base_track(robot, N, dt)
    t = base.t
    arm_q = np.column_stack([s.positions(t) for s in servos])
    res = SimResult(program="seguir", robot=robot.name, rate=rate, duration=N * dt, t=t, base=base,
                    arm_names=list(arm.names), arm_q=arm_q)
    ks = np.arange(0, N + 1, max(1, int(round(rate / 100))))
    centres = np.array([centre_at(t[k]) for k in ks])
    errs = np.array([arm.pointing_error(arm_q[k], c) for k, c in zip(ks, centres)])
    if progress:
        progress(0.8)
    after = t[ks] >= select_at
    acquired = np.nonzero(after & (errs <= tolerance))[0]
    window = t[ks] >= move_at                       # tracking: from the first step of the can to the end
    if len(acquired) and window.any():
        ka = acquired[0]
        tail = errs[window]
        emax = float(tail.max())
        t_max = float(t[ks][window][int(tail.argmax())])
        moving = window & (t[ks] <= t_end_path)
        rms = float(np.sqrt(np.mean(errs[moving] ** 2))) if moving.any() else float("nan")
        res.checks.append(Check("tracking error", emax <= tolerance, emax, "deg",
                                f"max while the can moves and after ≤ {tolerance:g}°",
                                f"acquired at {t[ks][ka]:.2f} s; worst at {t_max:.2f} s; RMS while the can "
                                f"moves {rms:.3f}°"))
        res.info["tracking RMS while moving"] = round(rms, 4)
        res.info["tracking max"] = round(emax, 4)
        res.info["acquired at"] = f"{t[ks][ka]:.2f} s"
    else:
        res.checks.append(Check("tracking error", False, float(errs[after].min()) if after.any() else float("nan"),
                                "deg", f"the arm never points within {tolerance:g}°"))
    _collisions(res, arm, others, q_home, "no contact with the robot or the table")
    path = np.array(offsets) + c0
    res.info["object"] = f"{which} = {obj.model}"
    res.info["path"] = f"{len(seq)} steps of 0.005 m every {RETARDO:g} s from {move_at:g} s; " \
                       f"{float(np.sum(np.linalg.norm(np.diff(path, axis=0), axis=1))):.3f} m"
    res.info["IK updates"] = f"{n_updates} at {track_rate:g} Hz"
    res.series = [Series(n, np.degrees(arm_q[:, i]), "deg") for i, n in enumerate(arm.names)]
    res.series.append(Series("tracking error", errs, "deg (error)", t=t[ks]))
    res.scene = list(others) + [obj]
    res.moving = [(obj.model, path[:, 0], path[:, 1])]

    res.outline_of = lambda: prepared.footprint(robot)
    res.wall = time.perf_counter() - wall0
    if progress:
        progress(1.0)
    return res
