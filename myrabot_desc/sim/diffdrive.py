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

# Parameter spellings of the diff-drive plugins we know, per dialect.
SEPARATION_KEYS = ("wheelSeparation", "wheel_separation")
DIAMETER_KEYS = ("wheelDiameter", "wheel_diameter")
RADIUS_KEYS = ("wheel_radius", "wheelRadius")
LEFT_KEYS = ("leftJoint", "left_joint", "left_wheel_joint")
RIGHT_KEYS = ("rightJoint", "right_joint", "right_wheel_joint")
DRIVE_LIBS = ("gazebo_ros_diff_drive", "gazebo_ros_roomba", "gazebo_ros_create", "gazebo_ros_kobuki",
              "diff-drive-system", "diff_drive", "DiffDrive")


@dataclass(frozen=True)
class PluginDrive:
    """What the diff-drive plugin believes about the wheels."""

    name: str
    library: str
    separation: float
    radius: float
    left_joint: str
    right_joint: str
    swapped: bool = False          # ROS 1 gazebo_ros_diff_drive legacyMode (default true) swaps the turn
    update_rate: float | None = None
    loc: object = None
    notes: tuple[str, ...] = ()


@dataclass(frozen=True)
class Wheel:
    joint: str
    link: str
    y: float                       # lateral position in the root frame
    xy: tuple[float, float]
    radius: float
    forward_sign: float            # +1 if a positive joint rate drives the wheel forward


@dataclass(frozen=True)
class UrdfDrive:
    """The wheels as built: what actually moves the robot."""

    left: Wheel
    right: Wheel

    @property
    def separation(self) -> float:
        return math.dist(self.left.xy, self.right.xy)

    @property
    def radius(self) -> float:
        return 0.5 * (self.left.radius + self.right.radius)

    @property
    def axle_mid(self) -> tuple[float, float]:
        return (0.5 * (self.left.xy[0] + self.right.xy[0]), 0.5 * (self.left.xy[1] + self.right.xy[1]))


@dataclass
class Drive:
    urdf: UrdfDrive
    plugin: PluginDrive | None
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
            if p.swapped:
                vl, vr = vr, vl
            rates = {p.left_joint: vl / p.radius, p.right_joint: vr / p.radius}
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
def find_drive(robot, wheels: str = "plugin") -> Drive:
    plugin = find_plugin(robot)
    if plugin is not None:
        left, right = plugin.left_joint, plugin.right_joint
    else:
        left, right = _guess_wheel_joints(robot)
    urdf = urdf_wheels(robot, left, right)
    if wheels == "plugin" and plugin is None:
        raise InputError(f"{robot.name}: no diff-drive plugin found (use --wheels urdf to drive with the "
                         "URDF's own wheel geometry)", robot.loc)
    d = Drive(urdf=urdf, plugin=plugin, wheels=wheels)
    if plugin is not None:
        d.notes.extend(plugin.notes)
        if plugin.left_joint != urdf.left.joint:
            d.notes.append(f"the plugin's left joint {plugin.left_joint} sits on the right (y "
                           f"{urdf.right.y:+.3f} m): it turns the wrong way")
    return d


def _param(params: dict, keys) -> tuple[str | None, str | None]:
    for k in keys:
        if k in params and params[k] not in (None, ""):
            return k, params[k]
    return None, None


def _num(text: str, what: str, loc) -> float:
    try:
        return float(text)
    except (TypeError, ValueError):
        raise InputError(f"diff-drive plugin: {what} is not a number: {text!r}", loc) from None


def find_plugin(robot) -> PluginDrive | None:
    for p in robot.plugins():
        params = p.params or {}
        lib = p.library or ""
        tag = _local(getattr(p.element, "tag", ""))
        is_drive = any(k in lib or k in (p.name or "") or k in tag for k in DRIVE_LIBS)
        sk, sep = _param(params, SEPARATION_KEYS)
        if not is_drive and sep is None:
            continue
        if sep is None:
            continue
        dk, dia = _param(params, DIAMETER_KEYS)
        rk, rad = _param(params, RADIUS_KEYS)
        if dia is None and rad is None:
            continue
        _, left = _param(params, LEFT_KEYS)
        _, right = _param(params, RIGHT_KEYS)
        if not left or not right:
            continue
        radius = _num(rad, rk, p.loc) if rad is not None else _num(dia, dk, p.loc) / 2
        separation = _num(sep, sk, p.loc)
        notes = []
        swapped = False
        if "gazebo_ros_diff_drive" in lib and "wheelSeparation" in params:
            # ROS 1 plugin: legacyMode defaults to true and then swaps the turn direction.
            legacy = (params.get("legacyMode") or "true").strip().lower() in ("1", "true")
            if legacy:
                swapped = True
                notes.append("legacyMode is true (the ROS 1 default): the plugin turns the wrong way")
        rate = None
        _, ur = _param(params, ("updateRate", "update_rate"))
        if ur is not None:
            try:
                rate = float(ur) or None
            except ValueError:
                rate = None
        if separation <= 0 or radius <= 0:
            raise InputError(f"diff-drive plugin {p.name}: wheel separation and diameter must be > 0", p.loc)
        return PluginDrive(name=p.name or tag or lib, library=lib or tag, separation=separation, radius=radius,
                           left_joint=left.strip(), right_joint=right.strip(), swapped=swapped,
                           update_rate=rate, loc=p.loc, notes=tuple(notes))
    return None


def _local(tag) -> str:
    return tag.rsplit("}", 1)[-1] if isinstance(tag, str) else ""


def _guess_wheel_joints(robot) -> tuple[str, str]:
    cands = [j for j in robot.joints.values() if j.type == "continuous" and "wheel" in j.name.lower()]
    left = [j.name for j in cands if "left" in j.name.lower()]
    right = [j.name for j in cands if "right" in j.name.lower()]
    if len(left) != 1 or len(right) != 1:
        raise InputError(f"{robot.name}: cannot tell the two drive wheels (no diff-drive plugin and no "
                         "continuous joints named left*/right*wheel*)", robot.loc)
    return left[0], right[0]


def urdf_wheels(robot, left: str, right: str) -> UrdfDrive:
    import numpy as np

    from myrabot_desc.model.kinematics import world_transforms

    tf = world_transforms(robot)
    out = []
    for name in (left, right):
        j = robot.joints.get(name)
        if j is None:
            raise InputError(f"diff-drive wheel joint {name!r} is not in the model", robot.loc)
        T = tf[j.child]
        axis = T[:3, :3] @ np.asarray(j.axis, dtype=float)
        axis = axis / (np.linalg.norm(axis) or 1.0)
        fwd = float(np.cross(axis, [0.0, 0.0, 1.0])[0])
        if abs(fwd) < 0.9:
            raise InputError(f"wheel joint {name}: axis {tuple(round(a, 3) for a in axis)} is not lateral, "
                             "so it cannot drive the base forward", j.loc)
        r = wheel_radius(robot, j.child, axis, T)
        out.append(Wheel(joint=name, link=j.child, y=float(T[1, 3]), xy=(float(T[0, 3]), float(T[1, 3])),
                         radius=r, forward_sign=math.copysign(1.0, fwd)))
    lw, rw = out
    if lw.y < rw.y:            # 'left' is whichever wheel sits at +y; the plugin still drives by name
        lw, rw = rw, lw
    return UrdfDrive(left=lw, right=rw)


def wheel_radius(robot, link_name: str, axis_world, T_link) -> float:
    """Radius of the wheel from its collision (else visual) geometry, about the joint axis."""
    import numpy as np

    from myrabot_desc.model.kinematics import pose_matrix

    link = robot.links[link_name]
    geoms = [(c.origin, c.geometry, c.loc) for c in link.collisions if c.geometry is not None]
    if not geoms:
        geoms = [(v.origin, v.geometry, v.loc) for v in link.visuals if v.geometry is not None]
    if not geoms:
        raise InputError(f"wheel link {link_name} has no collision or visual geometry, so its radius is unknown",
                         link.loc)
    best = 0.0
    for origin, g, loc in geoms:
        M = T_link @ pose_matrix(origin)
        if g.kind == "sphere":
            best = max(best, g.radius)
            continue
        if g.kind == "cylinder" and abs(float(M[:3, 2] @ axis_world)) > 0.99:
            best = max(best, g.radius)        # a wheel drawn as a cylinder about the joint axis
            continue
        pts = _geometry_points(robot, g, loc)
        world = pts @ M[:3, :3].T + M[:3, 3]
        rel = world - T_link[:3, 3]
        radial = rel - np.outer(rel @ axis_world, axis_world)
        best = max(best, float(np.linalg.norm(radial, axis=1).max()))
    return best


def _geometry_points(robot, g, loc, n: int = 720):
    """Surface points of a primitive or mesh (for extents; cylinders/spheres sampled n around)."""
    import numpy as np

    if g.kind == "box":
        sx, sy, sz = (s / 2 for s in g.size)
        return np.array([[x, y, z] for x in (-sx, sx) for y in (-sy, sy) for z in (-sz, sz)])
    if g.kind == "cylinder":
        a = np.linspace(0, 2 * np.pi, n + 1)[:-1]
        ring = np.stack([g.radius * np.cos(a), g.radius * np.sin(a)], axis=1)
        return np.vstack([np.column_stack([ring, np.full(len(a), z)]) for z in (-g.length / 2, g.length / 2)])
    if g.kind == "sphere":
        a = np.linspace(0, 2 * np.pi, n // 2 + 1)[:-1]
        c, s = np.cos(a), np.sin(a)
        r = g.radius
        return np.vstack([np.column_stack([r * c, r * s, 0 * a]), np.column_stack([r * c, 0 * a, r * s]),
                          np.column_stack([0 * a, r * c, r * s])])
    if g.kind == "mesh":
        from myrabot_desc.model import meshes as meshio

        if g.path is None:
            raise InputError(f"mesh {g.filename} cannot be resolved", loc)
        # size/triangle limits; garbage -> one line
        return meshio.vertices(g.path, loc) * np.asarray(g.scale)
    raise InputError(f"unsupported geometry {g.kind}", loc)


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


def integrate(drive: Drive, segments, n_steps: int, dt: float, pose0=(0.0, 0.0, 0.0)) -> BaseTrack:
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
