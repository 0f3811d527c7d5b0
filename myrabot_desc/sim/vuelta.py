"""``vuelta``: the seed's "vuelta al ruedo" test program (seed-spec.md §5.1, Appendix A.8).

The node's callbacks are reproduced as written:

* ``home()`` runs at the start of every ``pose_arm`` message and acts once
  (``cont1 == 0``): every joint to 511 at speed 400, torque on;
* each ``start_button`` true **toggles** ``encendido`` (false is ignored);
* while on, every ``pose_arm`` message publishes cmd_vel (0.1 m/s, 0.3 rad/s) and
  runs the swing: ``cont1 == 1`` -> base 718; when the reading is strictly within
  ±110 of the target: after 718 -> 304, after 304 -> ``cont1 = 1`` (so the *next*
  message commands 718 again);
* switching off sends **no zero twist**: the base keeps the last cmd_vel, as the
  Gazebo plugin holds it (a defect of the seed, reproduced and noted).

``pose_arm`` readings go through the bridge's truncating conversion, so a
servo resting at 718 reads 716 (see servo.py). Messages arrive at
``feedback_rate`` (default 100 Hz, the fuerte controller manager's joint-state
rate) on the fixed step grid. Everything between messages is closed form: the
servos move at constant speed and the base on arcs (diffdrive.integrate); messages
at which nothing can change are skipped, not simulated one by one.
"""

from __future__ import annotations

import math
import time

from myrabot_desc.safety import sim_steps
from myrabot_desc.sim import prepared, stability
from myrabot_desc.sim import servo as sv
from myrabot_desc.sim.collide import collision_check, unique_configs
from myrabot_desc.sim.diffdrive import fit_circle, integrate
from myrabot_desc.sim.result import Check, Series, SimResult

V_CMD, W_CMD = 0.1, 0.3
TARGET_A, TARGET_B, TOL = 718, 304, 110
SPEED_UNITS = 400


def run(robot, *, rate=1000.0, duration=25.0, presses=(1.0,), feedback_rate=100.0, wheels="plugin",
        wheel_speed_max=None, wheel_accel_max=None, check_collisions=True, progress=None) -> SimResult:
    import numpy as np

    wall0 = time.perf_counter()
    drive = prepared.drive(robot, wheels)
    drive.wheel_speed_max, drive.wheel_accel_max = wheel_speed_max, wheel_accel_max
    arm = prepared.arm(robot)
    dt = 1.0 / rate
    N = sim_steps(duration, rate)      # bounded: safety.LIMITS max_sim_steps
    every = max(1, int(round(rate / feedback_rate)))
    servos = [sv.Servo(0.0, sv.speed_rad_s(SPEED_UNITS, arm.velocity[i]), arm.lower[i], arm.upper[i])
              for i in range(len(arm.names))]
    press_steps = sorted(int(round(p * rate)) for p in presses)
    tick = None
    if wheels == "plugin" and drive.plugin is not None and drive.plugin.update_rate:
        tick = max(1, int(round(rate / drive.plugin.update_rate)))

    cont = cont1 = encendido = 0
    move = [0] * 5
    segments = []            # (step, v, w) of the base
    last_twist = None
    commands = []            # (t, joint index, units)
    swing_cmds = 0
    pi = 0
    n_msgs = N // every + 1
    report_every = max(1, n_msgs // 50)
    reported = -1

    def publish(t, targets):
        for i, u in enumerate(targets):
            if sv.valid_command(u, SPEED_UNITS, 1):
                goal = sv.units_to_rad(u)
                if servos[i].segments[-1][2] != goal:      # same goal again: the servo carries on
                    servos[i].command(t, goal)
                commands.append((t, i, u))

    # Message by message, but only the messages at which something can happen: a press, the
    # swing's next command, or the base reading entering the ±TOL window (found in one
    # vectorised pass over the messages in between, with the same arithmetic as a step by step loop).
    press_msgs = [-(-ks // every) for ks in press_steps]      # a press is handled at the first message at or after it
    msg_t = (np.arange(n_msgs) * every) * dt                  # as t = k * dt below
    m = 0
    while m < n_msgs:
        k = m * every
        t = k * dt
        while pi < len(press_steps) and press_steps[pi] <= k:     # start_button callbacks first
            if cont == 0:
                encendido, cont = 1, 1
            else:
                encendido, cont = 0, 0
            pi += 1
        p_base = sv.rad_to_units(servos[0].at(t))
        if cont1 == 0:                                             # home()
            move = [sv.UNITS_HOME] * 5
            publish(t, move)
            cont1 = 1
        if encendido == 1:
            if last_twist != (V_CMD, W_CMD):
                ks = k if tick is None else -(-k // tick) * tick   # next plugin update
                segments.append((ks, V_CMD, W_CMD))
                last_twist = (V_CMD, W_CMD)
            if cont1 == 1:
                move[0] = TARGET_A
                cont1 = 2
                publish(t, move)
                swing_cmds += 1
            elif (p_base - TOL) < move[0] < (p_base + TOL):
                if cont1 == 2:
                    move[0] = TARGET_B
                    cont1 = 3
                    publish(t, move)
                    swing_cmds += 1
                else:
                    cont1 = 1
        if progress and m // report_every > reported:
            reported = m // report_every
            progress(0.6 * m / n_msgs)
        # the next message that can change anything
        nxt = min(press_msgs[pi], n_msgs) if pi < len(press_msgs) else n_msgs
        if encendido != 1:
            m = nxt                                    # off: nothing happens until a press
        elif cont1 == 1:
            m += 1                                     # the next message commands TARGET_A
        else:
            m = _first_in_window(servos[0], move[0], m + 1, nxt, msg_t)

    base = integrate(drive, segments, N, dt)
    t = base.t
    arm_q = np.column_stack([s.positions(t) for s in servos])
    if progress:
        progress(0.7)

    res = SimResult(program="vuelta", robot=robot.name, rate=rate, duration=N * dt, t=t, base=base,
                    arm_names=list(arm.names), arm_q=arm_q,
                    wheel_names=(drive.urdf.left.joint, drive.urdf.right.joint))
    res.notes.extend(drive.notes)
    _verdict(res, robot, drive, arm, segments, commands, swing_cmds, dt, check_collisions)
    if progress:
        progress(1.0)
    if len(press_steps) >= 2 and len(press_steps) % 2 == 0:
        res.notes.append("switched off by the last press: the seed sends no zero twist, so the base keeps "
                         "turning (reproduced)")
    res.series = [Series(n, np.degrees(arm_q[:, i]), "deg") for i, n in enumerate(arm.names)]
    base_deg = res.series[0].values
    res.info["base joint range"] = f"{base_deg.min():.1f} … {base_deg.max():.1f} deg"
    res.outline_of = lambda: prepared.footprint(robot)
    res.wall = time.perf_counter() - wall0
    return res


def _first_in_window(servo, target, lo, hi, msg_t):
    """First message in [lo, hi) whose base reading is strictly within ±TOL of ``target`` (else hi).

    Evaluates the same expressions as the per-message check (Servo.at, rad_to_units) on
    a block of message times (``msg_t``) at once; once the servo has arrived the reading stays.
    """
    goal = servo.segments[-1][2]
    while lo < hi:
        q = servo.at_many(msg_t[lo:min(hi, lo + 64)])
        p = sv.rad_to_units_array(q)
        ok = ((p - TOL) < target) & (target < (p + TOL))
        if ok.any():
            return lo + int(ok.argmax())
        if q[-1] == goal:
            return hi
        lo += len(q)
    return hi


def _verdict(res, robot, drive, arm, segments, commands, swing_cmds, dt, check_collisions):
    import numpy as np

    base, t = res.base, res.t
    r_exp, T_exp = V_CMD / W_CMD, 2 * math.pi / W_CMD
    if not segments:
        res.checks.append(Check("start button", False, "never on", "", "a press switches the program on"))
        return
    k0 = segments[0][0]
    settle = 0
    if drive.wheel_accel_max:
        peak = max(abs(r) for r in drive.command_rates(V_CMD, W_CMD))
        settle = int(math.ceil(peak / drive.wheel_accel_max / dt)) + 1
    ks = min(k0 + settle, len(t) - 2)
    ax, ay = base.axle_x[ks:], base.axle_y[ks:]
    span = t[-1] - t[ks]
    if len(ax) >= 3 and span > 0:
        cx, cy, r = fit_circle(ax, ay)
        w_meas = (base.yaw[-1] - base.yaw[ks]) / span
        T_meas = 2 * math.pi / w_meas if w_meas else math.inf
    else:
        r, T_meas = float("nan"), float("nan")
    res.checks.append(Check("circle radius", abs(r - r_exp) <= 0.01 * r_exp, float(r), "m",
                            f"v/w = {r_exp:.4f} m ±1%"))
    res.checks.append(Check("period", abs(T_meas - T_exp) <= 0.01 * T_exp, float(T_meas), "s",
                            f"2π/w = {T_exp:.3f} s ±1%"))
    res.info["turns completed"] = round(float((base.yaw[-1] - base.yaw[ks]) / (2 * math.pi)), 3)
    t_full = t[ks] + T_exp
    if t_full <= t[-1]:
        kf = int(round(t_full / dt))
        res.info["closure after one period"] = f"{math.hypot(base.axle_x[kf] - base.axle_x[ks], base.axle_y[kf] - base.axle_y[ks]) * 1000:.3f} mm"
    base_targets = [u for (_, i, u) in commands if i == 0 and u in (TARGET_A, TARGET_B)]
    reversals = sum(1 for a, b in zip(base_targets, base_targets[1:]) if a != b)
    res.checks.append(Check("arm swings", reversals >= 1, reversals, "",
                            f"base joint {TARGET_A} ↔ {TARGET_B}, ±{TOL}; others at {sv.UNITS_HOME}",
                            f"{swing_cmds} swing commands; "
                            f"{reversals / (res.duration - t[k0]) * T_exp:.1f} swings per turn"))
    res.info["swing commands"] = swing_cmds
    # collisions of the arm with the structure

    poses = unique_configs(t, res.arm_q)     # distinct arm poses, for the tip-over margin too
    q_home = np.array([sv.units_to_rad(sv.UNITS_HOME)] * len(arm.names))
    if check_collisions:
        collision_check(res, arm, t, res.arm_q, q_home, "arm collision",
                        "no contact with the structure while swinging", poses=poses,
                        collider=prepared.collider(robot))
    # tip-over margin under the turn's centripetal acceleration
    sup, sup_notes = prepared.support(robot, drive.wheels)
    mx, my = drive.urdf.axle_mid
    icr = (mx, my + V_CMD / W_CMD)
    coms = arm.coms(poses[1])
    accs = np.column_stack([-W_CMD ** 2 * (coms[:, 0] - icr[0]), -W_CMD ** 2 * (coms[:, 1] - icr[1])])
    mgs = stability.margins(sup, coms, accs)
    w = int(np.argmin(mgs))                    # the first worst pose
    mg, com, a = mgs[w], coms[w], tuple(accs[w])
    res.checks.append(Check("tip-over margin", mg > 0, float(mg), "m",
                            "> 0: centre of mass inside the support polygon",
                            f"COM ({com[0]:.3f}, {com[1]:.3f}, {com[2]:.3f}) m, centripetal "
                            f"{math.hypot(*a):.4f} m/s², support {', '.join(sup.links)}"))
    res.notes.extend(sup_notes)
