"""Differential drive: a twist (cmd_vel) -> wheel speeds -> base pose, integrated exactly.

Two geometries meet here:

* the URDF's, which moves the robot: separation = distance between the two wheel
  joint origins, radius from the wheel link's collision geometry;
* the diff-drive plugin's (``wheelSeparation``/``wheelDiameter`` and friends), which
  turns the twist into wheel joint rates in Gazebo.

With ``wheels="plugin"`` the plugin's numbers compute the command and the URDF's
the motion, as in Gazebo; a mismatch like the Korean robot's (0.4/0.2 declared,
0.30/0.16 built) shows as a wrong speed (0.16/0.2 = 0.8x) and turn rate
(0.8 x 0.4/0.30 = 1.067x). With ``wheels="urdf"`` the command uses the URDF too.

Integration is exact for constant wheel rates over a step (an arc, not an Euler
step): heading is a cumulative sum and each step's chord is
``v dt sinc(w dt/2)`` along the mid-step heading. Everything is vectorised over the
fixed step grid; commands are piecewise constant (segments), and an optional
wheel acceleration limit ramps each wheel linearly in closed form.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from myrabot_desc.errors import InputError
from myrabot_desc.model import drive as D
from myrabot_desc.model import values as V


@dataclass(frozen=True)
class WheelBase:
    """The wheels as built, what actually moves the robot: each side's first wheel (model/drive.Wheel,
    with the side's mean radius), and the track between the sides."""

    left: D.Wheel
    right: D.Wheel
    track: float | None = None     # model/drive.py's separation (wheel centres along the axle)

    @property
    def separation(self) -> float:
        return self.track if self.track is not None else math.dist(self.left.xy, self.right.xy)

    @property
    def radius(self) -> float:
        return 0.5 * (self.left.radius + self.right.radius)

    @property
    def axle_mid(self) -> tuple[float, float]:
        return (0.5 * (self.left.xy[0] + self.right.xy[0]), 0.5 * (self.left.xy[1] + self.right.xy[1]))


@dataclass
class DiffDrive:
    """A base in the simulator: the wheels as built (``urdf``), the declared drive whose numbers the
    plugin runs with (``plugin``: model/drive.Drive with its defaults filled in, None without a drive
    plugin), whose numbers turn a twist into wheel rates (``wheels``), and the run's limits."""

    urdf: WheelBase
    plugin: D.Drive | None
    wheels: str = "plugin"            # 'plugin' or 'urdf': whose numbers compute the command
    wheel_speed_max: float | None = None      # rad/s
    wheel_accel_max: float | None = None      # rad/s^2
    notes: list[str] = field(default_factory=list)

    def command_rates(self, v: float, w: float) -> tuple[float, float]:
        """Joint rates (rad/s) of the URDF's left and right wheel joints for a twist."""
        u = self.urdf
        if self.wheels == "plugin" and self.plugin is not None:
            p = self.plugin
            vl, vr = v - w * p.separation / 2, v + w * p.separation / 2
            if p.legacy:
                vl, vr = vr, vl
            rates = {p.left[0]: vl / p.radius, p.right[0]: vr / p.radius}
            # The plugin drives joints by name; forward sign is the joint's own business.
            ql, qr = rates.get(u.left.joint, 0.0), rates.get(u.right.joint, 0.0)
            return ql, qr
        vl, vr = v - w * u.separation / 2, v + w * u.separation / 2
        return vl / u.left.radius * u.left.forward_sign, vr / u.right.radius * u.right.forward_sign

    def body_twist(self, ql, qr):
        """Ground truth (v, w) from joint rates through the URDF geometry (numpy ok)."""
        u = self.urdf
        vl = ql * u.left.radius * u.left.forward_sign
        vr = qr * u.right.radius * u.right.forward_sign
        return 0.5 * (vl + vr), (vr - vl) / u.separation


# ------------------------------------------------------------------ reading the model
def find_drive(robot, wheels: str = "plugin", left=(), right=()) -> DiffDrive:
    """The base's drive from the one drive model (model/drive.py): the user's wheel joints, else
    the first declared drive (a plugin of any dialect, ros_control velocity wheels), else
    continuous joints named like wheels, sided by where they sit. A skid-steer base is its equivalent diff drive
    (each side's wheels turn together; the separation is between the sides' centres)."""

    d = D.main_drive(robot, tuple(left), tuple(right), guess=True)
    if d is None:
        raise InputError(f"{robot.name}: cannot tell the drive wheels (no drive plugin, no ros_control velocity "
                         "wheels, no continuous *wheel* joints on both sides of the base): name them with "
                         "--wheels LEFT,RIGHT", robot.loc)
    for name in d.missing(robot):
        raise InputError(f"diff-drive wheel joint {name!r} is not in the model", d.loc or robot.loc)
    if not d.left or not d.right:
        raise InputError(f"{d.label}: no left and right wheel joints given", d.loc or robot.loc)
    for name in d.joints:
        j = robot.joints[name]
        lim = j.limit
        if j.type not in ("continuous", "revolute") or (j.type == "revolute" and lim is not None and lim.lower is not None
                                                        and lim.upper is not None and lim.upper - lim.lower < 2 * math.pi):
            rng = f" with limits [{lim.lower:g}, {lim.upper:g}]" if lim is not None and lim.lower is not None else ""
            raise InputError(f"wheel joint {name} is {j.type}{rng}: a wheel turns freely (a continuous joint)", j.loc)
    lead = {n: robot.joints[n].mimic.joint if robot.joints[n].mimic is not None else n for n in d.joints}
    shared = sorted({lead[n] for n in d.left} & {lead[n] for n in d.right})
    if shared:     # a car-like base: its rear wheels follow one joint, it steers instead
        raise InputError(f"{d.label}: the left and right wheels ({', '.join(d.joints)}) turn together (<mimic> of "
                         f"'{shared[0]}'): not a differential drive, they cannot turn at different speeds",
                         d.loc or robot.loc)
    plugin, plugin_notes = _plugin_drive(d) if d.source == "plugin" else (None, [])
    urdf = urdf_wheels(robot, d)
    notes = []
    if wheels == "plugin" and plugin is None:
        why = (f"{d.label} does not give its wheel separation and diameter" if d.source == "plugin" else
               f"no drive plugin ({d.label}: {', '.join(d.joints)})")
        notes.append(f"{why}: cmd_vel is turned into wheel rates with the URDF's own wheel geometry")
        wheels = "urdf"
    if d.source == "user" and urdf.left.joint != d.left[0]:
        notes.append(f"the left wheel you named, {d.left[0]}, sits on the right (y {urdf.right.origin[1]:+.3f} m; +y is "
                     "left, REP-103): driven as the geometry says; a controller given these names turns the wrong way")
    dr = DiffDrive(urdf=urdf, plugin=plugin, wheels=wheels, notes=notes)
    if plugin is not None:
        mirrored = plugin.left[0] != urdf.left.joint
        notes = list(plugin_notes)
        if mirrored and plugin.legacy:        # an old package written for legacy mode: the two swaps cancel
            notes = [n for n in notes if "legacyMode" not in n]
            notes.append(f"legacyMode swaps the wheels and the plugin's left joint {plugin.left[0]} sits on the "
                         f"right (y {urdf.right.origin[1]:+.3f} m): the two cancel, it turns the right way")
        elif mirrored:
            notes.append(f"the plugin's left joint {plugin.left[0]} sits on the right (y "
                         f"{urdf.right.origin[1]:+.3f} m): it turns the wrong way")
        dr.notes.extend(notes)
    if d.skid:
        dr.notes.append(f"{d.label}: a skid-steer base driven as its equivalent diff drive ({len(d.left)} left and "
                        f"{len(d.right)} right wheels turning together)")
    return dr


def _plugin_drive(d) -> tuple[D.Drive | None, list[str]]:
    """What the plugin believes, its own defaults filling what it does not say (as the plugin does),
    and notes on the defaults it used and its legacy mode."""
    spec = d.spec
    for key, t in d.bad:
        if key in (spec.separation, spec.diameter, spec.radius):
            raise InputError(V.problem(key, t, V.NOT_A_NUMBER) + " (diff-drive plugin)", d.loc)
    full, notes = d.with_defaults()
    if full.separation is None or full.radius is None:
        return None, []
    if full.separation <= 0 or full.radius <= 0:
        raise InputError(f"diff-drive plugin {d.plugin.name}: wheel separation and diameter must be > 0", d.loc)
    if d.legacy:
        notes.append("legacyMode is true (the ROS 1 default): the plugin turns the wrong way"
                     if not d.legacy_explicit else "legacyMode is true: the plugin turns the wrong way")
    return full, notes


def urdf_wheels(robot, d) -> WheelBase:
    """The drive's wheels as built (model/drive.measure); each side's first wheel stands for the side."""

    g = D.measure(robot, d)
    for w in g.wheels:
        j = robot.joints[w.joint]
        if abs(w.axis[1]) < D.LATERAL:
            raise InputError(f"wheel joint {w.joint}: axis {tuple(round(a, 3) for a in w.axis)} is not lateral, "
                             "so it cannot drive the base forward", j.loc)
        if w.radius is None and w.problem is not None:
            raise w.problem
        if w.radius is None:
            link = robot.links[w.link]
            raise InputError(f"wheel link {w.link} has no collision or visual geometry, so its radius is unknown",
                             link.loc)
    lw, rw = (group[0]._replace(radius=sum(x.radius for x in group) / len(group)) for group in (g.left, g.right))
    if lw.origin[1] < rw.origin[1]:     # 'left' is whichever side sits at +y; the plugin still drives by name
        lw, rw = rw, lw
    if not g.separation or g.separation < 1e-6:
        raise InputError(f"{d.label}: the left and right wheels ({lw.joint}, {rw.joint}) are not apart along their "
                         "axle, so they cannot steer the base", d.loc or robot.loc)
    return WheelBase(left=lw, right=rw, track=g.separation)


# ------------------------------------------------------------------ integration
@dataclass
class BaseTrack:
    """Time series on the step grid (N+1 samples, t = k*dt)."""

    t: object
    x: object          # root-frame origin in the world
    y: object
    yaw: object
    wheel_left: object
    wheel_right: object
    v: object          # per step (N): achieved body speed of the axle midpoint
    w: object          # per step (N): achieved yaw rate
    axle_x: object     # axle midpoint path
    axle_y: object


def integrate(drive: DiffDrive, segments, n_steps: int, dt: float, pose0=(0.0, 0.0, 0.0)) -> BaseTrack:
    """Integrate piecewise-constant twists.

    ``segments``: list of (k_start, v, w) with step indices ascending; the twist
    holds until the next segment (as Gazebo plugins hold the last cmd_vel).
    """
    import numpy as np

    N = int(n_steps)
    k = np.arange(N)
    starts = [max(0, min(N, int(s[0]))) for s in segments]
    rates = []
    for (_, v, w) in segments:
        ql, qr = drive.command_rates(v, w)
        m = drive.wheel_speed_max
        if m is not None and m > 0:
            peak = max(abs(ql), abs(qr))
            if peak > m:               # scale both: keeps the curvature of the command
                ql, qr = ql * m / peak, qr * m / peak
        rates.append((ql, qr))
    ql_arr = np.zeros(N)
    qr_arr = np.zeros(N)
    a = drive.wheel_accel_max
    cur_l = cur_r = 0.0
    for i, (ks, (rl, rr)) in enumerate(zip(starts, rates)):
        ke = starts[i + 1] if i + 1 < len(starts) else N
        if ke <= ks:
            continue
        if a is not None and a > 0:
            tau = (k[ks:ke] - ks + 0.5) * dt          # mid-step
            ql_arr[ks:ke] = cur_l + np.clip(rl - cur_l, -a * tau, a * tau)
            qr_arr[ks:ke] = cur_r + np.clip(rr - cur_r, -a * tau, a * tau)
            tend = (ke - ks) * dt
            cur_l = cur_l + float(np.clip(rl - cur_l, -a * tend, a * tend))
            cur_r = cur_r + float(np.clip(rr - cur_r, -a * tend, a * tend))
        else:
            ql_arr[ks:ke], qr_arr[ks:ke] = rl, rr
            cur_l, cur_r = rl, rr
    v, w = drive.body_twist(ql_arr, qr_arr)
    x0, y0, th0 = pose0
    mx, my = drive.urdf.axle_mid
    c0, s0 = math.cos(th0), math.sin(th0)
    ax0, ay0 = x0 + c0 * mx - s0 * my, y0 + s0 * mx + c0 * my
    dth = w * dt
    th = np.concatenate([[th0], th0 + np.cumsum(dth)])
    mid = th[:-1] + dth / 2
    chord = v * dt * np.sinc(dth / (2 * np.pi))
    ax = np.concatenate([[ax0], ax0 + np.cumsum(chord * np.cos(mid))])
    ay = np.concatenate([[ay0], ay0 + np.cumsum(chord * np.sin(mid))])
    c, s = np.cos(th), np.sin(th)
    x = ax - (c * mx - s * my)
    y = ay - (s * mx + c * my)
    wl = np.concatenate([[0.0], np.cumsum(ql_arr * dt)])
    wr = np.concatenate([[0.0], np.cumsum(qr_arr * dt)])
    t = np.arange(N + 1) * dt
    return BaseTrack(t=t, x=x, y=y, yaw=th, wheel_left=wl, wheel_right=wr, v=v, w=w, axle_x=ax, axle_y=ay)


def fit_circle(x, y):
    """Least-squares circle (Kasa): centre (cx, cy) and radius."""
    import numpy as np

    A = np.column_stack([x, y, np.ones_like(x)])
    b = x * x + y * y
    sol, *_ = np.linalg.lstsq(A, b, rcond=None)
    cx, cy = sol[0] / 2, sol[1] / 2
    r = math.sqrt(max(sol[2] + cx * cx + cy * cy, 0.0))
    return float(cx), float(cy), r
