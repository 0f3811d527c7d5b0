"""``drive`` for bases that are not a differential pair (model/drive.base): one kinematic model per kind.

* mecanum / omni: the four corner wheels' rates from the twist (inverse kinematics of a mecanum
  base, rollers at 45°: ω = (vx ∓ vy ∓ (lx + ly) ω_z) / r), computed with the controller's numbers
  when its YAML gives them (``--wheels plugin``) else the URDF's, and the twist those rates make
  with the URDF's geometry (forward kinematics): a controller/URDF mismatch shows as a ratio ≠ 1;
* planar: the plugin sets the body's twist, achieved = commanded;
* swerve: each module points along, and rolls at, the velocity of its steering axis; a module whose
  angle is past its lock turns the other way round (angle ± π, speed reversed), and one that cannot
  reach the angle either way does not move (its share of the twist is lost: least squares);
* Ackermann: a bicycle model about the rear axle's centre: steering δ = atan(L ω / v), clamped
  to the lock, ω achieved = v tan δ / L; it cannot turn on the spot (v = 0) nor tighter than its
  minimum turning radius L / tan(lock).

The twist script is (vx, vy, ω, seconds); the verdict lines are drive's: speed ratio (achieved
velocity along the command over the commanded speed) and turn-rate ratio, each 1 ± tolerance.
"""

from __future__ import annotations

import math
import time

from myrabot_desc.errors import InputError
from myrabot_desc.model import drive as D
from myrabot_desc.safety import sim_steps
from myrabot_desc.sim.diffdrive import BaseTrack
from myrabot_desc.sim.result import Series, SimResult, ratio_checks
from myrabot_desc.sim.stability import footprint

CORNERS = ("front_left", "front_right", "back_left", "back_right")


class Model:
    """A kind's kinematics: ``achieve(vx, vy, w)`` -> (achieved twist, wheel rates by joint, notes)."""

    def __init__(self, robot, base: D.Base, use_controller: bool):
        self.robot, self.base = robot, base
        self.notes: list[str] = []
        self.info: dict = {"drive kind": base.kind, "declared by": base.why}
        self.ref = (0.0, 0.0)           # the point whose motion is compared (root frame)
        self.wheels: tuple[str, str] = ("", "")
        getattr(self, f"_setup_{'mecanum' if base.kind == 'omni' else base.kind}")(use_controller)

    # ------------------------------------------------------------ mecanum / omni
    def _setup_mecanum(self, use_controller):
        b = self.base
        pos = {n: D.joint_position(self.robot, n) for n in b.wheels}
        ws = [n for n in b.wheels if pos[n] is not None]
        if len(ws) < 4 or not (b.wheelbase and b.track and b.radius):
            raise InputError(f"{b.kind} base: four corner wheels with a wheelbase, track and radius are needed "
                             f"(wheels {', '.join(b.wheels) or 'none'})", b.loc or self.robot.loc)
        cx = sum(pos[n][0] for n in ws) / len(ws)
        cy = sum(pos[n][1] for n in ws) / len(ws)
        self.ref = (cx, cy)
        self.corner = {n: ("front" if pos[n][0] > cx else "back") + ("_left" if pos[n][1] > cy else "_right")
                       for n in ws}
        self.urdf = (b.wheelbase / 2, b.track / 2, b.radius)
        cmd = self.urdf
        if use_controller and b.controller is not None:
            cmd = (_or(b.ctrl_wheelbase, b.wheelbase) / 2, _or(b.ctrl_track, b.track) / 2, _or(b.ctrl_radius, b.radius))
            self.info["command geometry"] = f"controller ({b.controller.type})"
        else:
            self.info["command geometry"] = "URDF"
        self.cmd = cmd
        self.info.update({"URDF wheelbase": b.wheelbase, "URDF track": b.track, "URDF wheel radius": b.radius})
        if b.controller is not None:
            self.info.update({"controller wheelbase": b.ctrl_wheelbase, "controller track": b.ctrl_track,
                              "controller wheel radius": b.ctrl_radius})
        first = {c: next((n for n in ws if self.corner[n] == c), None) for c in CORNERS}
        self.wheels = (first["front_left"] or ws[0], first["front_right"] or ws[1])

    @staticmethod
    def _mecanum_rates(geo, vx, vy, w):
        lx, ly, r = geo
        k = lx + ly
        return {"front_left": (vx - vy - k * w) / r, "front_right": (vx + vy + k * w) / r,
                "back_left": (vx + vy - k * w) / r, "back_right": (vx - vy + k * w) / r}

    def _achieve_mecanum(self, vx, vy, w):
        rates = self._mecanum_rates(self.cmd, vx, vy, w)
        lx, ly, r = self.urdf
        fl, fr, bl, br = (rates[c] for c in CORNERS)
        twist = (r / 4 * (fl + fr + bl + br), r / 4 * (-fl + fr + bl - br), r / (4 * (lx + ly)) * (-fl + fr - bl + br))
        return twist, {n: rates[c] for n, c in self.corner.items()}

    # ------------------------------------------------------------ planar
    def _setup_planar(self, use_controller):
        self.info["model"] = "the plugin sets the body's twist (no wheel turns)"

    def _achieve_planar(self, vx, vy, w):
        return (vx, vy, w), {}

    # ------------------------------------------------------------ swerve
    def _setup_swerve(self, use_controller):
        b = self.base
        mods = []
        kids = self.robot.joints_by_parent()
        for s in b.steering:
            j = self.robot.joints[s]
            wheel = next((c.name for c in kids.get(j.child, []) if c.name in b.wheels), None)
            p = D.joint_position(self.robot, s)
            if wheel is None or p is None:
                continue
            w = D.wheel(self.robot, wheel)
            mods.append((s, wheel, p[0], p[1], w.radius if w is not None and w.radius else b.radius))
        if len(mods) < 2 or any(m[4] is None for m in mods):
            raise InputError("swerve base: no steering joint that carries a wheel of known radius",
                             b.loc or self.robot.loc)
        self.mods = mods
        self.ref = (sum(m[2] for m in mods) / len(mods), sum(m[3] for m in mods) / len(mods))
        self.lock = b.steer_limit
        self.wheels = (mods[0][1], mods[1][1])
        self.info.update({"modules": len(mods), "wheelbase": b.wheelbase, "track": b.track, "wheel radius": b.radius,
                          "steering lock": "free" if self.lock is None else f"±{self.lock:.4g} rad"})

    def _module(self, x, y, vx, vy, w):
        """A swerve module at (x, y): (steering angle, wheel speed m/s, whether the lock lets it point)."""
        cx, cy = self.ref
        px, py = x - cx, y - cy
        mvx, mvy = vx - w * py, vy + w * px
        speed = math.hypot(mvx, mvy)
        ang = math.atan2(mvy, mvx) if speed > 1e-12 else 0.0
        if self.lock is not None and abs(ang) > self.lock + 1e-9:
            ang, speed = math.remainder(ang + math.pi, 2 * math.pi), -speed     # the other way round
        return ang, speed, self.lock is None or abs(ang) <= self.lock + 1e-9

    def _achieve_swerve(self, vx, vy, w):
        import numpy as np

        rows, rhs, rates = [], [], {}
        cx, cy = self.ref
        for s, wheel, x, y, r in self.mods:
            px, py = x - cx, y - cy
            ang, speed, reach = self._module(x, y, vx, vy, w)
            rates[wheel] = speed / r if reach else 0.0
            got = (speed * math.cos(ang), speed * math.sin(ang)) if reach else (0.0, 0.0)
            rows += [[1.0, 0.0, -py], [0.0, 1.0, px]]
            rhs += list(got)
        sol, *_ = np.linalg.lstsq(np.array(rows), np.array(rhs), rcond=None)
        return (float(sol[0]), float(sol[1]), float(sol[2])), rates

    # ------------------------------------------------------------ Ackermann (bicycle model)
    def _setup_ackermann(self, use_controller):
        b = self.base
        if not (b.wheelbase and b.radius):
            raise InputError("Ackermann base: no wheelbase or wheel radius to drive it with", b.loc or self.robot.loc)
        steered = {self.robot.joints[n].child for n in b.steering}
        rear = [n for n in b.wheels if self.robot.joints[n].parent not in steered]
        pos = [D.joint_position(self.robot, n) for n in rear]
        pos = [p for p in pos if p is not None]
        self.ref = (sum(p[0] for p in pos) / len(pos), sum(p[1] for p in pos) / len(pos)) if pos else (0.0, 0.0)
        self.L, self.r, self.lock = b.wheelbase, b.radius, b.steer_limit
        self.rear = rear
        self.wheels = (rear[0], rear[-1]) if rear else ("", "")
        self.info.update({"model": "bicycle (rear axle centre)", "wheelbase": self.L, "wheel radius": self.r,
                          "steering lock": "none given" if self.lock is None else f"±{self.lock:.4g} rad"})
        if b.min_turn_radius is not None:
            self.info["minimum turning radius"] = f"{b.min_turn_radius:.4f} m"

    def _achieve_ackermann(self, vx, vy, w):
        if abs(vx) < 1e-12:
            delta = 0.0        # no forward speed: a car cannot turn on the spot
            if abs(w) > 1e-12:
                self._note(f"ω {w:g} rad/s with v 0: an Ackermann base cannot turn on the spot")
        else:
            delta = math.atan(self.L * w / vx)
            if self.lock is not None and abs(delta) > self.lock:
                self._note(f"v {vx:g} m/s, ω {w:g} rad/s asks for a {abs(vx / w):.4g} m radius, tighter than the "
                           f"minimum turning radius {self.base.min_turn_radius:.4g} m: steering held at the lock "
                           f"(±{self.lock:.4g} rad)")
                delta = max(-self.lock, min(self.lock, delta))
        if abs(vy) > 1e-12:
            self._note(f"vy {vy:g} m/s: an Ackermann base cannot move sideways")
        return (vx, 0.0, vx * math.tan(delta) / self.L), {n: vx / self.r for n in self.rear}

    def _steer(self, vx, w):
        """The bicycle's steering angle for (v, ω), held at the lock."""
        if abs(vx) < 1e-12:
            return 0.0
        delta = math.atan(self.L * w / vx)
        return delta if self.lock is None else max(-self.lock, min(self.lock, delta))

    def joint_commands(self, vx, vy, w) -> dict:
        """{joint: ("position" | "velocity", value)} that move a simulated base as this model does:
        steering joints at their angle (rad, about their own axis), each wheel at the rate that rolls
        it along its own path (rad/s, signed to roll the base forward). Mecanum/omni/planar bases are
        moved as a body in MuJoCo: {}."""
        kind = self.base.kind
        out = {}
        if kind == "swerve":
            for s, wheel, x, y, r in self.mods:
                ang, speed, reach = self._module(x, y, vx, vy, w)
                if reach:
                    out[s] = ("position", ang * D.joint_turn_sign(self.robot, s))
                    out[wheel] = ("velocity", speed / r * _forward(self.robot, wheel))
        elif kind == "ackermann":
            delta = self._steer(vx, w)
            weff = vx * math.tan(delta) / self.L
            rx, ry = self.ref
            kids = self.robot.joints_by_parent()
            for s in self.base.steering:
                p = D.joint_position(self.robot, s)
                carries = any(c.name in self.base.wheels for c in kids.get(self.robot.joints[s].child, []))
                if p is None or not carries:
                    out[s] = ("position", delta * D.joint_turn_sign(self.robot, s))    # the bicycle's own joint
                    continue
                ahead, side = p[0] - rx, p[1] - ry
                along = vx - weff * side
                ang = math.atan(weff * ahead / along) if abs(along) > 1e-12 else 0.0
                out[s] = ("position", ang * D.joint_turn_sign(self.robot, s))
            for n in self.base.wheels:
                p = D.joint_position(self.robot, n)
                wh = D.wheel(self.robot, n)
                if p is None or wh is None or not wh.radius:
                    continue
                speed = math.copysign(math.hypot(vx - weff * (p[1] - ry), weff * (p[0] - rx)), vx)
                out[n] = ("velocity", speed / wh.radius * wh.forward_sign)
        return out

    def _note(self, text: str) -> None:
        if text not in self.notes:
            self.notes.append(text)

    def achieve(self, vx, vy, w):
        kind = "mecanum" if self.base.kind == "omni" else self.base.kind
        return getattr(self, f"_achieve_{kind}")(vx, vy, w)


def _forward(robot, joint: str) -> float:
    w = D.wheel(robot, joint)
    return w.forward_sign if w is not None else 1.0


def _or(a, b):
    return a if a is not None else b


def run(robot, base: D.Base, *, rate=1000.0, duration=None, script=(), wheels="plugin", tolerance=0.02,
        progress=None) -> SimResult:
    import numpy as np

    wall0 = time.perf_counter()
    model = Model(robot, base, wheels == "plugin")
    dt = 1.0 / rate
    script = [s if len(s) == 4 else (s[0], 0.0, s[1], s[2]) for s in script]
    total = sum(s[-1] for s in script)
    duration = total if duration is None else float(duration)
    N = sim_steps(duration, rate)
    cmd = np.zeros((N, 3))
    got = np.zeros((N, 3))
    bounds, k = [], 0
    q = {n: np.zeros(N) for n in model.wheels if n}
    for vx, vy, w, s in script:
        n = int(round(s * rate))
        kb = min(k + n, N)
        twist, rates = model.achieve(vx, vy, w)
        cmd[k:kb] = (vx, vy, w)
        got[k:kb] = twist
        for name in q:
            q[name][k:kb] = rates.get(name, 0.0)
        bounds.append((k, kb, vx, vy, w))
        k = kb
    # integrate the reference point: body-frame velocity rotated by the mid-step heading
    dth = got[:, 2] * dt
    th = np.concatenate([[0.0], np.cumsum(dth)])
    mid = th[:-1] + dth / 2
    c, s_ = np.cos(mid), np.sin(mid)
    rx0, ry0 = model.ref
    ax = np.concatenate([[rx0], rx0 + np.cumsum((c * got[:, 0] - s_ * got[:, 1]) * dt)])
    ay = np.concatenate([[ry0], ry0 + np.cumsum((s_ * got[:, 0] + c * got[:, 1]) * dt)])
    cth, sth = np.cos(th), np.sin(th)
    x, y = ax - (cth * rx0 - sth * ry0), ay - (sth * rx0 + cth * ry0)
    names = [n for n in model.wheels]
    wl = np.concatenate([[0.0], np.cumsum(q[names[0]] * dt)]) if names[0] in q else np.zeros(N + 1)
    wr = np.concatenate([[0.0], np.cumsum(q[names[1]] * dt)]) if names[1] in q else np.zeros(N + 1)
    speed = np.hypot(got[:, 0], got[:, 1])
    track = BaseTrack(t=np.arange(N + 1) * dt, x=x, y=y, yaw=th, wheel_left=wl, wheel_right=wr, v=speed,
                      w=got[:, 2], axle_x=ax, axle_y=ay)
    res = SimResult(program="drive", robot=robot.name, rate=rate, duration=N * dt, t=track.t, base=track,
                    wheel_names=tuple(n or "wheel" for n in names))
    res.info.update({k: (round(v, 6) if isinstance(v, float) else v) for k, v in model.info.items()})

    rows, v_ratios, w_ratios = [], [], []
    for i, (ka, kb, vx, vy, w) in enumerate(bounds):
        if kb - ka < 2:
            continue
        T = (kb - ka) * dt
        # achieved motion of the reference point, in the body frame at each step
        dx, dy = np.diff(ax[ka:kb + 1]), np.diff(ay[ka:kb + 1])
        hm = mid[ka:kb]
        bx = float(np.sum(np.cos(hm) * dx + np.sin(hm) * dy)) / T
        by = float(np.sum(-np.sin(hm) * dx + np.cos(hm) * dy)) / T
        w_meas = float(th[kb] - th[ka]) / T
        row = {"segment": i + 1, "vx_cmd": vx, "vy_cmd": vy, "w_cmd": w, "vx": round(bx, 6), "vy": round(by, 6),
               "w": round(w_meas, 6)}
        sp = math.hypot(vx, vy)
        if sp > 1e-9:
            ratio = (bx * vx + by * vy) / (sp * sp)       # achieved velocity along the command / commanded speed
            row["v_ratio"] = round(ratio, 6)
            v_ratios.append(ratio)
        if abs(w) > 1e-9:
            row["w_ratio"] = round(w_meas / w, 6)
            w_ratios.append(w_meas / w)
        rows.append(row)

    res.checks.extend(ratio_checks(v_ratios, w_ratios, tolerance))
    # the commanded motion, integrated the same way (what the user expects)
    dthc = cmd[:, 2] * dt
    thc = np.concatenate([[0.0], np.cumsum(dthc)])
    mc = thc[:-1] + dthc / 2
    ex = np.concatenate([[rx0], rx0 + np.cumsum((np.cos(mc) * cmd[:, 0] - np.sin(mc) * cmd[:, 1]) * dt)])
    ey = np.concatenate([[ry0], ry0 + np.cumsum((np.sin(mc) * cmd[:, 0] + np.cos(mc) * cmd[:, 1]) * dt)])
    res.notes.extend(model.notes)
    res.info["segments"] = rows
    res.info["final position error"] = f"{math.hypot(ax[-1] - ex[-1], ay[-1] - ey[-1]):.4f} m"
    res.info["final heading error"] = f"{math.degrees(abs(math.remainder(th[-1] - thc[-1], 2 * math.pi))):.2f} deg"
    res.moving = [("expected", ex, ey)]
    res.series = [Series("v commanded", np.concatenate([np.hypot(cmd[:, 0], cmd[:, 1]), [0.0]]), "m/s",
                         group="twist"),
                  Series("v achieved", np.concatenate([speed, speed[-1:]]), "m/s", group="twist"),
                  Series("w commanded", np.concatenate([cmd[:, 2], [0.0]]), "rad/s", group="twist"),
                  Series("w achieved", np.concatenate([got[:, 2], got[-1:, 2]]), "rad/s", group="twist")]
    res.outline_of = lambda: footprint(robot)
    res.wall = time.perf_counter() - wall0
    if progress:
        progress(1.0)
    return res
