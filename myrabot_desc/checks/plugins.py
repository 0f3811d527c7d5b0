"""G: Gazebo extensions and plugins (diff drives against the URDF, parameters, dialect, materials, topics)."""

from __future__ import annotations

import math

from myrabot_desc.checks.examples import ELECTRIC_IMU, MODERN_IMU, ackermann_example, controllers_yaml, \
    mecanum_example, ros2_control_example
from myrabot_desc.checks.examples import drive_example as _drive
from myrabot_desc.checks.rule import Finding, Fix, FixInfo, InsertInto, RemoveElement, RenameTag, SetValue, rule
from myrabot_desc.checks.urdf_syntax import suggest
from myrabot_desc.materials.stock import is_stock
from myrabot_desc.model import drive as D
from myrabot_desc.model.drive import GZ, ROS1, ROS2
from myrabot_desc.model.plugins import published_topics, publishes_ranges

# Parameters every old-style plugin is known to carry but that a given plugin ignores: a hint for G007.
IGNORED_HINT = {
    "torque": "ROS 1 gazebo_ros_diff_drive reads wheelTorque",
    "alwaysOn": "a Gazebo 0.x controller flag; Gazebo classic plugins do not read it",
    "command_topic": "ROS 2 gazebo_ros_diff_drive subscribes cmd_vel; remap it with <ros><remapping>cmd_vel:=...",
    "odometry_topic": "ROS 2 gazebo_ros_diff_drive publishes odom; remap it with <ros><remapping>odom:=...",
    "odom_publisher_frequency": "gz-sim DiffDrive reads odom_publish_frequency (a typo in the migration guide)",
}


def drives(ctx):
    """[(plugin, Drive)] for every recognised drive plugin (model/drive.py)."""
    return [(d.plugin, d) for d in D.plugin_drives(ctx.robot)]


@rule("G001", "drive-wheel-separation", "error",
      bad=_drive(sep="0.4"),
      message="wheelSeparation 0.4 m, but the wheel joints left_wheel_joint and right_wheel_joint are 0.3 m apart "
              "(y 0.15 and -0.15): the robot turns at 1.33× the commanded rate (before any diameter error)",
      good=_drive(),
      fix=FixInfo("sometimes", "safe", "the plugin's separation parameter becomes the distance between the wheel "
                  "joints, when the plugin writes the parameter (a default is not inserted). Safe: the simulator "
                  "moves the wheels where the URDF puts them; the plugin's number only has to agree. The other "
                  "direction (moving the wheels to the plugin's number) is never done: it changes the robot."))
def wheel_separation(ctx):
    """A diff-drive plugin's wheel separation must match the distance between the wheels in the URDF.

    The plugin turns a twist (v, ω) into wheel speeds with its own separation s:
    ω_L,R = (v ∓ ω·s/2)/r. If s is not the real track, the robot turns at the wrong
    rate and odometry drifts (seed B: 0.4 vs 0.30 m turns 1.33× too fast). Fix: the
    distance given (between the wheel centres along the axle).
    """
    for p, d in drives(ctx):
        spec = d.spec
        sep = d.separation
        g = D.measure(ctx.robot, d)
        if sep is None or not g.left or not g.right:
            continue
        lw, rw = g.left[0], g.right[0]
        real = g.separation
        if real < 1e-9:  # both wheels at one point (broken origins/axis): nothing to compare
            continue
        if abs(sep - real) > max(0.002, 0.02 * real):
            if len(g.left) == 1 and len(g.right) == 1:
                where = (f"the wheel joints {lw.joint} and {rw.joint} are {real:.3g} m apart "
                         f"(y {lw.centre[1]:.3g} and {rw.centre[1]:.3g})")
            else:
                where = _sides(g, real)
            yield Finding(f"{spec.separation} {sep:.3g} m, but {where}: the robot turns at "
                          f"{sep / real:.3g}× the commanded rate (before any diameter error)", p.loc,
                          {"plugin": p.name, "param": spec.separation, "value": sep, "urdf": real,
                           "fix": round(real, 6)},
                          fix=_param_fix(p, spec.separation, round(real, 6)))


def _sides(g, real: float) -> str:
    """G001's words for several wheels a side: the separation is between the means of each side's
    wheel centres along the axle (model/drive.separation), so every wheel is named with its own
    coordinate, and a wheel off the others of its side is pointed out."""
    ax = g.left[0].axis
    mean = lambda ws: sum(sum(w.centre[k] * ax[k] for k in range(3)) for w in ws) / len(ws)  # noqa: E731
    sign = 1.0 if mean(g.left) >= mean(g.right) else -1.0     # left positive, as y is
    coord = {w.joint: sign * sum(w.centre[k] * ax[k] for k in range(3)) for w in g.left + g.right}
    label = "y" if abs(ax[1]) > 0.99 else "along the axle"

    def side(ws):
        return ", ".join(f"{w.joint} {coord[w.joint]:.3g}" for w in ws)

    text = (f"the left and right wheel centres are {real:.3g} m apart (the mean of each side, {label}: "
            f"{side(g.left)}; {side(g.right)})")
    # the wheel off the pattern: farthest from the median distance to the centre line of all wheels
    dist = sorted(abs(v) for v in coord.values())
    n = len(dist)
    median = dist[n // 2] if n % 2 else (dist[n // 2 - 1] + dist[n // 2]) / 2
    w = max(g.left + g.right, key=lambda w: abs(abs(coord[w.joint]) - median))
    off = abs(coord[w.joint]) - median
    if abs(off) > 0.002:
        text += (f"; wheel {w.link} (joint {w.joint}) is {abs(off) * 1000:.0f} mm "
                 f"{'closer to' if off < 0 else 'farther from'} the centre line than the others")
    return text


@rule("G002", "drive-wheel-size", "error",
      bad=_drive(dia="0.2"),
      message="wheelDiameter 0.2 m, but wheel left_wheel (joint left_wheel_joint) has a collision diameter of "
              "0.16 m: the robot drives at 0.8× the commanded speed",
      good=_drive(),
      fix=FixInfo("sometimes", "safe", "the plugin's wheel diameter (or radius) parameter becomes the wheel's "
                  "collision size, when the plugin writes it. Safe for the reason G001 gives."))
def wheel_size(ctx):
    """A diff-drive plugin's wheel diameter (or radius) must match the wheel's collision geometry.

    The plugin converts speeds with its own radius; a wrong value scales every linear
    speed and the odometry (seed B: diameter 0.2 on 0.16 m wheels drives at 0.8× the
    command). Fix: the value given from the wheel's collision cylinder.
    """
    for p, d in drives(ctx):
        spec = d.spec
        key = spec.diameter or spec.radius
        val, _ = D.number(p, key)
        if val is None:
            continue
        g = D.measure(ctx.robot, d)
        for w in g.left[:1] + g.right[:1]:
            if w.radius is None:
                continue
            real = 2 * w.radius if spec.diameter else w.radius
            if abs(val - real) > max(0.001, 0.02 * real):
                word = "diameter" if spec.diameter else "radius"
                yield Finding(f"{key} {val:.3g} m, but wheel {w.link} (joint {w.joint}) has a collision {word} of "
                              f"{real:.3g} m: the robot drives at "
                              f"{f'{real / val:.3g}×' if val else 'an infinite multiple of'} the commanded speed",
                              p.loc,
                              {"plugin": p.name, "param": key, "value": val, "urdf": real, "fix": round(real, 6)},
                              fix=_param_fix(p, key, round(real, 6)))
                break


@rule("G003", "drive-joints-exist", "error",
      bad=_drive(left="left_wheel_jiont"),
      message="gazebo_ros_diff_drive (ROS 1): leftJoint 'left_wheel_jiont' is not a joint of this robot; "
              "did you mean left_wheel_joint?",
      good=_drive())
def drive_joints_exist(ctx):
    """The joints a drive plugin names must exist in the URDF.

    The plugin looks its joints up by name at load; a missing one makes it fail to load
    (Gazebo logs an error and the robot never moves). Fix: the exact joint name.
    """

    r = ctx.robot
    for p, d in drives(ctx):
        spec = d.spec
        for key in (*spec.left, *spec.right, *spec.fixed_ok):
            for name in p.values(key):
                if name not in r.joints:
                    guess = suggest(name, r.joints)
                    yield Finding(f"{spec.label}: {key} '{name}' is not a joint of this robot"
                                  + (f"; did you mean {guess}?" if guess else ""), p.loc,
                                  {"plugin": p.name, "param": key, "joint": name, "suggestion": guess})
        if not d.left or not d.right:
            yield Finding(f"{spec.label}: no {spec.left[0]}/{spec.right[0]} given", p.loc, {"plugin": p.name})


@rule("G004", "drive-joints-continuous", "error",
      bad=_drive(jtype="fixed"),
      message="gazebo_ros_diff_drive (ROS 1): leftJoint left_wheel_joint is fixed: fixed joints are merged away "
              "in URDF→SDF conversion, so the plugin cannot find it",
      good=_drive())
def drive_joints_continuous(ctx):
    """Wheel joints of a drive plugin must be continuous (revolute stops at its limits; fixed is gone).

    A fixed wheel joint is merged away by the URDF→SDF conversion so the plugin cannot
    find it; a revolute one stops turning at its limit (warning). Joints named as
    casters by the Create/Roomba plugin are reported as a warning when fixed: the plugin
    publishes zeros for them. Wheels that ros_control or ros2_control commands in velocity are
    judged the same way (model/drive.ros_wheel_joints), with the distance a revolute wheel
    rolls before its stop; a range of a million radians or more is taken as unlimited. Fix:
    `type="continuous"`.
    """
    r = ctx.robot
    yield from _ros_wheel_types(r)
    for p, d in drives(ctx):
        spec = d.spec
        for key in (*spec.left, *spec.right, *spec.fixed_ok):
            for name in p.values(key):
                j = r.joints.get(name)
                if j is None or j.type == "continuous":
                    continue
                caster = key in spec.fixed_ok
                if j.type == "fixed":
                    sev = "warning" if caster else "error"
                    why = "fixed joints are merged away in URDF→SDF conversion, so the plugin cannot find it"
                elif j.type == "revolute":
                    sev, why = "warning", "a revolute wheel stops at its limits"
                else:
                    sev, why = "error", f"a {j.type} joint cannot roll a wheel"
                who = f"joint {name}" if key == name else f"{key} {name}"   # not "front_castor_joint front_castor_joint"
                yield Finding(f"{spec.label}: {who} is {j.type}: {why}", p.loc,
                              {"plugin": p.name, "joint": name, "type": j.type}, severity=sev)


UNLIMITED = 1e6         # rad: a revolute range this wide never stops a wheel (MPO-700 writes ±1e16)


def _ros_wheel_types(r):
    """G004 for the wheels ros_control/ros2_control commands in velocity."""
    names, source = D.ros_wheel_joints(r)
    label = f"{source} velocity wheels"
    for name in names:
        j = r.joints[name]
        if j.type == "continuous":
            continue
        if j.type == "revolute":
            lim = j.limit
            # urdfdom reads a missing lower or upper as 0: such a wheel cannot turn that way at all
            lo, hi = (lim.lower or 0.0, lim.upper or 0.0) if lim is not None else (0.0, 0.0)
            if min(-lo, hi) >= UNLIMITED:
                continue
            w = D.wheel(r, name)
            rad = w.radius if w is not None else None
            reach = min(abs(lo), abs(hi))
            roll = f", {reach * rad:.3g} m of travel" if rad else ""
            yield Finding(f"{label}: joint {name} is revolute ({lo:.3g} to {hi:.3g} rad): a revolute wheel stops at "
                          f"its limits, after {reach / (2 * math.pi):.2g} turn from the zero pose{roll}", j.loc,
                          {"joint": name, "type": j.type, "lower": lo, "upper": hi, "radius": rad,
                           "travel": reach * rad if rad else None, "source": source}, severity="warning")
        else:
            why = ("fixed joints are merged away in URDF→SDF conversion, so the controller cannot find it"
                   if j.type == "fixed" else f"a {j.type} joint cannot roll a wheel")
            yield Finding(f"{label}: joint {name} is {j.type}: {why}", j.loc,
                          {"joint": name, "type": j.type, "source": source}, severity="error")


@rule("G005", "drive-axis-across-travel", "error",
      bad=_drive(axis="0 0 1"),
      message="gazebo_ros_diff_drive (ROS 1): left wheel joint left_wheel_joint turns about (0 0 1) in base_link: "
              "not across the direction of travel (y)",
      good=_drive())
def drive_axis(ctx):
    """Drive wheels must turn about an axis across the direction of travel (the base's y).

    The base drives along its x axis (REP-103); a wheel whose axis is along x or z rolls
    sideways or spins like a turntable. A left wheel on the right (negative y) side
    swaps the turning direction (warning); for ros_control/ros2_control wheels, whose
    sides the controller's configuration gives (outside the URDF), a wheel joint named
    "left" on the right side (or "right" on the left) is reported the same way
    (ros2_control_demos' DiffBot); when every such wheel sits on one side (a wheel mirrored to
    the wrong side) there is no drive at all, an error. Fix: `<axis xyz="0 1 0"/>` (in the wheel
    joint's frame) and the left wheel at +y.
    """
    import re

    names, source = D.ros_wheel_joints(ctx.robot)
    label = f"{source} velocity wheels"
    T = D.link_transforms(ctx.robot)
    ws = [w for w in (D.wheel(ctx.robot, n, T, read_meshes=False) for n in names) if w is not None]
    for w in ws:
        words = set(re.split(r"[^a-z]+", w.joint.lower()))
        y = w.origin[1]
        named = "left" if "left" in words and "right" not in words else \
            "right" if "right" in words and "left" not in words else None
        if (named == "left" and y < -1e-3) or (named == "right" and y > 1e-3):
            yield Finding(f"{label}: wheel joint {w.joint} is named {named} but sits at y {y:.3g} (the "
                          f"{'right' if y < 0 else 'left'} side; +y is left, REP-103): a controller given it as "
                          f"the {named} wheel turns the robot the wrong way", ctx.robot.joints[w.joint].loc,
                          {"joint": w.joint, "y": float(y), "named": named}, severity="warning")
    lateral = [w for w in ws if abs(w.axis[1]) >= D.LATERAL and abs(w.origin[1]) >= 1e-4]
    sides = {w.origin[1] > 0 for w in lateral}
    if len(lateral) >= 2 and len(sides) == 1 and not any(d.source == source for d in D.find(ctx.robot)):
        side = "left" if sides == {True} else "right"
        where = ", ".join(f"{w.joint} {w.origin[1]:.3g}" for w in lateral)
        yield Finding(f"{label}: every wheel sits on the {side} side (y: {where}; +y is left, REP-103): with no "
                      "wheel on the other side nothing drives this base (a wheel moved or mirrored to the wrong "
                      "side)", ctx.robot.joints[lateral[0].joint].loc,
                      {"joints": [w.joint for w in lateral], "y": [float(w.origin[1]) for w in lateral],
                       "side": side})
    r = ctx.robot
    for p, d in drives(ctx):
        spec = d.spec
        g = D.measure(ctx.robot, d)
        for side, w in (("left", g.left[0] if g.left else None), ("right", g.right[0] if g.right else None)):
            if w is None:
                continue
            j = r.joints[w.joint]
            a = w.axis
            if abs(a[1]) < D.LATERAL:
                yield Finding(f"{spec.label}: {side} wheel joint {j.name} turns about ({a[0]:.2g} {a[1]:.2g} {a[2]:.2g}) "
                              f"in {r.root}: not across the direction of travel (y)", j.loc,
                              {"joint": j.name, "axis_world": list(a)})
            y = w.origin[1]
            if d.legacy:
                continue       # legacy mode swaps the wheels itself: G013 says which way it turns
            if (side == "left" and y < -1e-3) or (side == "right" and y > 1e-3):
                yield Finding(f"{spec.label}: the {side} wheel joint {j.name} is at y {y:.3g} (the {'right' if y < 0 else 'left'} "
                              "side): left and right are swapped, the robot turns the wrong way", p.loc,
                              {"joint": j.name, "y": float(y)}, severity="warning")


@rule("G013", "drive-legacy-mode", "warning",
      bad=_drive().replace("<legacyMode>false</legacyMode>\n    ", ""),
      message="gazebo_ros_diff_drive (ROS 1): no <legacyMode> given: it defaults to true, so the plugin drives "
              "left_wheel_joint (y 0.15) with the right wheel's speed and right_wheel_joint (y -0.15) with the left "
              "one's: the robot turns the wrong way (a commanded 0.5 rad/s turns at -0.5 rad/s, turn ratio -1; the "
              "wheels run at v ± 0.075 m/s the other way round)",
      good=_drive(),
      fix=FixInfo("always", "safe", "`<legacyMode>` becomes false (inserted when absent). Safe: the robot then "
                  "turns the way its URDF and REP-103 say; a package that named its wheels the other way round "
                  "for legacy mode is not reported, so not changed."))
def drive_legacy_mode(ctx):
    """A ROS 1 gazebo_ros_diff_drive in legacy mode turns the wrong way.

    Without `<legacyMode>false</legacyMode>` the ROS 1 plugin (Indigo to Melodic) defaults
    to legacy mode, in which it commands the left joint with the right wheel's speed and
    the right joint with the left one's: with the left wheel at +y (REP-103) every turn
    goes the other way (turn ratio −1; Noetic's plugin no longer reads the flag). An old
    package that named its wheels the other way round for legacy mode turns right and is
    not reported. Fix: `<legacyMode>false</legacyMode>`.
    """
    for p, d in drives(ctx):
        if not d.legacy:
            continue
        g = D.measure(ctx.robot, d)
        if not g.left or not g.right:
            continue
        lw, rw = g.left[0], g.right[0]
        if not (lw.origin[1] > 1e-3 and rw.origin[1] < -1e-3):
            continue           # an old package with the wheels named the other way round: legacy mode fixes it
        why = "legacyMode is true" if d.legacy_explicit else "no <legacyMode> given: it defaults to true"
        sep = d.separation if d.separation is not None else g.separation
        w = 0.5
        yield Finding(f"{d.label}: {why}, so the plugin drives {lw.joint} (y {lw.origin[1]:.3g}) with the right "
                      f"wheel's speed and {rw.joint} (y {rw.origin[1]:.3g}) with the left one's: the robot turns the "
                      f"wrong way (a commanded {w:g} rad/s turns at {-w:g} rad/s, turn ratio -1; the wheels run at "
                      f"v ± {w * sep / 2:.3g} m/s the other way round)",
                      p.loc, {"plugin": p.name, "param": "legacyMode", "explicit": d.legacy_explicit,
                              "turn_ratio": -1.0, "fix": "false"},
                      fix=_param_fix(p, "legacyMode", "false", insert=not d.legacy_explicit))


@rule("G014", "drive-summary", "info",
      bad=_drive(),
      message="drive (gazebo_ros_diff_drive (ROS 1)): left left_wheel_joint, right right_wheel_joint; "
              "separation 0.3 m, wheel radius 0.08 m on the URDF",
      good=None)
def drive_summary(ctx):
    """The drive the model declares, as convert and sim see it (information).

    One line per drive (model/drive.py: a plugin of any dialect, or ros_control /
    ros2_control velocity wheels): its wheel joints, and the wheel separation and radius
    measured on the URDF (the numbers `convert` writes into the gz DiffDrive system and
    `sim drive` moves the robot with).
    """
    r = ctx.robot
    for d in D.find(r):
        g = D.measure(ctx.robot, d)
        if not g.left or not g.right:
            continue
        nums = []
        if g.separation is not None:
            nums.append(f"separation {g.separation:.4g} m")
        if g.radius is not None:
            nums.append(f"wheel radius {g.radius:.4g} m")
        loc = d.loc or r.joints[g.left[0].joint].loc
        yield Finding(f"drive ({d.label}): left {', '.join(d.left)}, right {', '.join(d.right)}"
                      + (f"; {', '.join(nums)} on the URDF" if nums else ""), loc,
                      {"source": d.source, "drive": d.label, "left": list(d.left), "right": list(d.right),
                       "separation": g.separation, "radius": g.radius,
                       "plugin_separation": d.separation, "plugin_radius": d.radius, "legacy": d.legacy})


_PLANAR = """<gazebo>
  <plugin name="object_controller" filename="libgazebo_ros_planar_move.so">
    <commandTopic>cmd_vel</commandTopic>
  </plugin>
</gazebo>"""


def _m(v) -> str:
    return f"{v:.4g} m"


@rule("G015", "drive-kind", "info",
      bad=_PLANAR,
      message="planar base (plugin libgazebo_ros_planar_move.so): the plugin moves the body as commanded "
              "(an omni twist); no wheels turn",
      good=None)
def drive_kind(ctx):
    """The kind of base the model declares when it is more than a left/right wheel drive (information).

    model/drive.base(): mecanum or omni wheels, a planar body-velocity plugin, Ackermann or swerve
    steering, or a drive whose ros2_control controller YAML (named by a plugin's `<parameters>`)
    gives its numbers. One line: the kind and what says so, the joints that drive and steer it,
    its wheelbase, track, wheel radius and steering lock on the URDF (the minimum turning radius
    of an Ackermann base), and the controller's own numbers after its multipliers. `convert` and
    `sim drive` move the robot as this kind.
    """
    r = ctx.robot
    b = D.base(r)
    if b is None or (b.kind in ("differential", "skid_steer") and b.controller is None):
        return                 # G014 says it all
    label = b.kind.replace("_", "-")
    parts = []
    if b.kind == "planar" and not b.steering:
        parts.append("the plugin moves the body as commanded (an omni twist); no wheels turn")
    else:
        parts.append("wheels " + ", ".join(b.wheels))
        if b.steering:
            parts.append("steering " + ", ".join(b.steering))
    nums = [f"{k} {_m(v)}" for k, v in (("wheelbase", b.wheelbase), ("track", b.track), ("wheel radius", b.radius))
            if v is not None and b.kind != "planar"]
    if b.steer_limit is not None:
        nums.append(f"steering lock ±{b.steer_limit:.3g} rad")
    if b.min_turn_radius is not None:
        nums.append(f"minimum turning radius {_m(b.min_turn_radius)}")
    if nums:
        parts.append(", ".join(nums) + " on the URDF")
    ctrl = [f"{k} {_m(v)}" for k, v in (("wheelbase", b.ctrl_wheelbase), ("track", b.ctrl_track),
                                         ("wheel radius", b.ctrl_radius)) if v is not None]
    if ctrl:
        parts.append(f"the controller's {', '.join(ctrl)}")
    yield Finding(f"{label} base ({b.why}): " + "; ".join(parts), b.loc,
                  {"kind": b.kind, "why": b.why, "wheels": list(b.wheels), "steering": list(b.steering),
                   "wheelbase": b.wheelbase, "track": b.track, "radius": b.radius, "steer_limit": b.steer_limit,
                   "min_turn_radius": b.min_turn_radius, "controller": b.controller and b.controller.type,
                   "controller_wheelbase": b.ctrl_wheelbase, "controller_track": b.ctrl_track,
                   "controller_radius": b.ctrl_radius})


_WORDS = {"track": "track", "wheelbase": "wheelbase", "radius": "wheel radius", "kingpin": "steering axes' spread",
          "half_sum": "half wheelbase + half track"}


def _close(what: str, value: float, urdf: float) -> bool:
    if what == "radius":
        return abs(value - urdf) <= max(0.001, 0.02 * urdf)
    return abs(value - urdf) <= max(0.002, 0.02 * urdf)


def _effect(b, what: str, value: float, urdf: float) -> str:
    """What driving with ``value`` where the URDF measures ``urdf`` does to the robot, in numbers
    (each number alone, the others as the URDF has them)."""
    sideways = " and sideways" if b.holonomic else ""
    if what == "radius":
        return f"the robot drives{sideways} at {urdf / value:.3g}× the commanded speed"
    if what == "half_sum" or (b.kind == "ackermann" and what == "wheelbase") or \
            (b.kind in ("differential", "skid_steer") and what == "track"):
        # ω_wheels ∝ ω·value; an Ackermann base steers tan φ = value·κ, so it curves at value/urdf
        return f"the robot turns at {value / urdf:.3g}× the commanded rate"
    if b.kind in ("mecanum", "omni") and what in ("track", "wheelbase") and b.wheelbase and b.track:
        other = b.wheelbase if what == "track" else b.track     # the wheels turn with (track + wheelbase)/2
        return f"the robot turns at {(value + other) / (urdf + other):.3g}× the commanded rate"
    if b.kind == "swerve" and what in ("track", "wheelbase") and b.wheelbase and b.track:
        # modules steered for rotation about the wrong corners: the least-squares body rate is
        # ω (wb·wb' + tr·tr') / (wb² + tr²), the modules scrubbing the rest
        other = b.wheelbase if what == "track" else b.track
        ratio = (urdf * value + other * other) / (urdf * urdf + other * other)
        return f"the robot turns at {ratio:.3g}× the commanded rate, its modules scrubbing"
    if b.kind == "ackermann" and what == "track":
        return (f"in a curve the driven wheels' speeds differ by {value / urdf:.3g}× what the URDF's track needs "
                "(they slip against each other)")
    if b.kind == "ackermann" and what == "kingpin" and b.wheelbase and b.steer_limit:
        L = b.wheelbase
        R = L / math.tan(min(b.steer_limit, math.pi / 2 - 1e-6))    # the rear axle's centre at full lock
        off = math.atan(L / (R - value / 2)) - math.atan(L / (R - urdf / 2))
        return (f"at full lock (±{b.steer_limit:.3g} rad) the inner wheel steers {abs(math.degrees(off)):.2g}° off "
                "the angle the URDF's geometry needs (the steered wheels scrub)")
    return f"the wheels are commanded for a {value:.4g} m {_WORDS.get(what, what)}: they scrub in every turn"


@rule("G016", "drive-controller-geometry", "error",
      bad=ros2_control_example(),
      message="controllers.yaml, diff_drive_base_controller: wheel_separation 0.4 m, but the URDF's track is 0.3 m: "
              "the robot turns at 1.33× the commanded rate",
      good=ros2_control_example("fixed.yaml"),
      files={**controllers_yaml(sep="0.4"), **controllers_yaml(name="fixed.yaml")},
      note="controllers.yaml (wheel_separation 0.4) and fixed.yaml (0.3), next to the model, hold the "
           "controller's parameters",
      fix=FixInfo("never", "safe", "the number is in the controller's YAML, outside the URDF: the message names "
                  "the file and the key to change (the URDF's geometry is the robot's; the YAML follows it)."))
def controller_geometry(ctx):
    """A ros2_control drive controller's geometry (after its multipliers) must match the URDF.

    The controller YAML a `<parameters>` names (diff_drive_controller `wheel_separation`,
    `wheel_radius`; mecanum `wheel_separation_x/y` or `kinematics.*`; the steering controllers'
    `wheelbase`, `traction_track_width`, `traction_wheels_radius`...) turns a twist into wheel
    speeds with its own numbers: a track 0.4 m on wheels 0.3 m apart turns 1.33× too fast, a
    radius too large drives too slowly, a wheelbase off makes a car-like base curve too much or
    too little. The effect is worked out per kind (model/drive.base): a mecanum base turns with
    (wheelbase + track) / 2, a swerve base steered for the wrong corners at the least-squares
    rate (wb·wb' + tr·tr') / (wb² + tr²). A difference that the controller's multiplier alone makes (the
    number itself matches the URDF) is a calibration: on a skid-steer base the separation
    multiplier stands for the wheels' sideways slip (ROSbot XL: 0.248 m × 1.3, "ICR
    coefficient ... 1.3 looked approximately alright" on their floor), so it is information;
    on other kinds a warning (a real robot's calibration that the simulated one, whose geometry
    is exact, does not need). Fix: the YAML's key named in the message.
    """
    b = D.base(ctx.robot)
    if b is None:
        return
    for d in D.declared(ctx.robot):
        if d.source != "controller":
            continue
        t, c = d.term, d.owner
        if _close(t.what, t.value, d.urdf):
            continue
        file = c.file.replace("\\", "/").rsplit("/", 1)[-1]
        said = f"{t.key} {t.raw:.4g} m"
        sev = None
        if t.multiplier is not None and t.multiplier != 1.0:
            said += f" × {t.multiplier_key} {t.multiplier:.4g} = {t.value:.4g} m"
            if _close(t.what, t.raw, d.urdf):
                skid = b.kind == "skid_steer" and t.what == "track"
                sev = "info" if skid else "warning"
        msg = (f"{file}, {c.name}: {said}, but the URDF's {_WORDS.get(t.what, t.what)} is {d.urdf:.4g} m: "
               + _effect(b, t.what, t.value, d.urdf))
        if sev == "info":
            msg += (" on wheels that do not slip; on a skid-steer base the multiplier stands for the wheels' "
                    "sideways slip (a calibration)")
        elif sev == "warning":
            msg += " (the multiplier alone makes the difference: a calibration of the real robot)"
        yield Finding(msg, c.loc or b.loc,
                      {"file": c.file, "controller": c.name, "key": t.key, "value": t.raw, "multiplier": t.multiplier,
                       "multiplier_key": t.multiplier_key, "effective": t.value, "urdf": d.urdf, "what": t.what,
                       "kind": b.kind}, severity=sev)


@rule("G017", "drive-plugin-geometry", "error",
      bad=ackermann_example(base="0.65"),
      message="gz::sim::systems::AckermannSteering: wheel_base 0.65 m, but the URDF's wheelbase is 0.5 m: "
              "the robot turns at 1.3× the commanded rate",
      good=ackermann_example(),
      fix=FixInfo("sometimes", "safe", "the system's parameter becomes the URDF's number when the parameter is "
                  "written (a default is not inserted). Safe for the reason G001 gives."))
def plugin_geometry(ctx):
    """A mecanum or Ackermann plugin's geometry must match the URDF.

    gz-sim's MecanumDrive (`wheel_separation`, `wheelbase`, `wheel_radius`) and
    AckermannSteering (`wheel_base`, `wheel_separation`, `kingpin_width`, `wheel_radius`)
    compute wheel speeds and steering angles from their own numbers, and use defaults (1 m,
    1 m, 0.8 m, 0.2 m) when a parameter is missing. A wheelbase off by 30 % makes a car-like
    base curve 1.3× as tightly as commanded; a mecanum base turns with (wheelbase + track) / 2;
    a kingpin width off sets the inner and outer wheels for different turning centres (the
    angle error at full lock is given). Gazebo classic's gazebo_ros_ackermann_drive measures
    its geometry on the model (only its steering limit is compared, by G018). Fix: the URDF's
    number, given.
    """
    b = D.base(ctx.robot)
    if b is None:
        return
    for d in D.declared(ctx.robot):
        t, p = d.term, d.owner
        if d.source != "plugin" or t.what == "steer_limit" or _close(t.what, t.value, d.urdf):
            continue
        said = f"{t.key} not given: it uses its default {t.value:.4g} m" if t.default else f"{t.key} {t.value:.4g} m"
        yield Finding(f"{p.name or p.library}: {said}, but the URDF's {_WORDS.get(t.what, t.what)} is "
                      f"{d.urdf:.4g} m: " + _effect(b, t.what, t.value, d.urdf), p.loc,
                      {"plugin": p.name, "param": t.key, "value": t.value, "default": t.default, "urdf": d.urdf,
                       "what": t.what, "kind": b.kind, "fix": round(d.urdf, 6)},
                      fix=None if t.default else _param_fix(p, t.key, round(d.urdf, 6)))


@rule("G018", "drive-steering-limit", "warning",
      bad=ackermann_example(limit="0.8"),
      message="gz::sim::systems::AckermannSteering: steering_limit 0.8 rad, but the steering joints stop at "
              "±0.5 rad (left_steering_joint): minimum turning radius 0.9152 m instead of 0.4856 m",
      good=ackermann_example(),
      fix=FixInfo("sometimes", "safe", "the plugin's limit becomes the steering joints' limit when the parameter "
                  "is written: it then steers only as far as the joints go (the joint limit is the robot's)."))
def steering_limit(ctx):
    """A plugin's steering limit must not exceed the steering joints' limit in the URDF.

    gz-sim's AckermannSteering (`steering_limit`, default 0.5 rad) and Gazebo classic's
    gazebo_ros_ackermann_drive (`max_steer`, default 0.6 rad) steer up to their own limit;
    the joint stops at its URDF limit first, so the tightest turn is wheelbase / tan(joint
    limit), wider than the plugin commands, and the plugin's wheel speeds assume a curve the
    robot does not drive. A limit below the joint's is a choice (the plugin steers less) and
    not reported. ros2_control's steering controllers have no steering limit parameter
    (the joint's limits apply). Fix: the joint's limit, given.
    """
    b = D.base(ctx.robot)
    if b is None or b.steer_limit is None or not b.wheelbase:
        return
    lim = b.steer_limit
    joint = D.steering_stop(ctx.robot, b)
    for d in D.declared(ctx.robot):
        t, p = d.term, d.owner
        if t.what != "steer_limit" or t.value <= lim + 0.01:
            continue
        turn = lambda a: b.wheelbase / math.tan(min(a, math.pi / 2 - 1e-6))    # noqa: E731
        said = f"{t.key} not given: it uses its default {t.value:.3g} rad" if t.default else \
            f"{t.key} {t.value:.3g} rad"
        yield Finding(f"{p.name or p.library}: {said}, but the steering joints stop at ±{lim:.3g} rad ({joint}): "
                      f"minimum turning radius {turn(lim):.4g} m instead of {turn(t.value):.4g} m", p.loc,
                      {"plugin": p.name, "param": t.key, "value": t.value, "default": t.default, "urdf": lim,
                       "joint": joint, "min_turn_radius": turn(lim), "plugin_min_turn_radius": turn(t.value),
                       "fix": round(lim, 6)},
                      fix=None if t.default else _param_fix(p, t.key, round(lim, 6)))


def _ratio(x: float) -> str:
    return f"{x:.2g}×" if abs(x) >= 0.005 else "0×"


@rule("G019", "mecanum-roller-friction", "error",
      bad=mecanum_example(rollers=False),
      message="mecanum base (plugin gz-sim-mecanum-drive-system) without modelled rollers: with its wheels' "
              "contact friction (every wheel mu 1, mu2 1, no fdir1) a sideways command drives sideways at 0×; a "
              "mecanum wheel's contact needs mu2 0 across an fdir1 at 45° to its axle, front-left and rear-right "
              "along one diagonal, front-right and rear-left along the other",
      good=mecanum_example())
def mecanum_rollers(ctx):
    """A mecanum base driven wheel by wheel must be able to roll sideways in simulation.

    Unless its rollers are links of their own, a mecanum wheel is a plain cylinder to the
    simulator; what makes it mecanum is its contact friction: `mu` along an `fdir1` at 45° to
    the axle and `mu2` 0 across it (gz-sim's mecanum example, ROSbot XL), so the contact
    pushes only along that diagonal, front-left and rear-right along one, front-right and
    rear-left along the other. model/drive.roller_response measures the twist the four
    contacts give for a unit sideways and turning command (the least-squares body motion under
    each wheel's constraint, the wheel speeds from the mecanum kinematics): plain wheels
    (isotropic friction, the default) drive sideways at 0×; the diagonals the wrong way round
    drive sideways backwards (-1×) and turn 4.4× too fast on ROSbot XL. A base moved by a
    body-force plugin (Ridgeback) is not judged: its wheels carry no load sideways by design.
    Fix: the friction set-up above in each wheel's `<gazebo reference>` block.
    """
    r = ctx.robot
    rr = D.roller_response(r)
    if rr is None:
        return
    b = D.base(r)
    vx, vy, wz = rr.sideways
    turn = rr.turn[2]
    if abs(vy - 1) <= 0.15 and abs(vx) <= 0.15 and abs(wz) <= 0.15 and abs(turn - 1) <= 0.15:
        return
    desc = {(c.mu, c.mu2, c.fdir1 and (round(c.fdir1[0], 2), round(c.fdir1[1], 2))) for c in rr.contacts}
    if len(desc) == 1:
        c = rr.contacts[0]
        said = f"every wheel mu {c.mu:g}, mu2 {c.mu2:g}, " + (
            f"fdir1 ({c.fdir1[0]:.2g} {c.fdir1[1]:.2g})" if c.fdir1 else "no fdir1")
    else:
        said = "; ".join(f"{c.link} mu {c.mu:g}, mu2 {c.mu2:g}, "
                         + (f"fdir1 ({c.fdir1[0]:.2g} {c.fdir1[1]:.2g})" if c.fdir1 else "no fdir1")
                         for c in rr.contacts)
    effect = [f"a sideways command drives sideways at {_ratio(vy)}"]
    if abs(vx) > 0.15:
        effect.append(f"forward at {_ratio(vx)}")
    if abs(wz) > 0.15:
        effect.append(f"turning {wz:.2g} rad/s per m/s")
    msg = f"mecanum base ({b.why}) without modelled rollers: with its wheels' contact friction ({said}) " + \
        ", ".join(effect)
    if abs(turn - 1) > 0.15:
        msg += f", and it turns at {_ratio(turn)} the commanded rate"
    yield Finding(msg + "; a mecanum wheel's contact needs mu2 0 across an fdir1 at 45° to its axle, front-left and "
                  "rear-right along one diagonal, front-right and rear-left along the other", b.loc,
                  {"sideways": list(rr.sideways), "turn": list(rr.turn), "forward": list(rr.forward),
                   "contacts": [{"link": c.link, "mu": c.mu, "mu2": c.mu2, "fdir1": c.fdir1 and list(c.fdir1),
                                 "written": c.written} for c in rr.contacts]})


@rule("G007", "plugin-unknown-parameter", "warning",
      bad=_drive(extra="<torque>5</torque>"),
      message="gazebo_ros_diff_drive (ROS 1) does not read <torque> (ROS 1 gazebo_ros_diff_drive reads wheelTorque)",
      good=_drive(),
      fix=FixInfo("sometimes", "safe", "a parameter the plugin does not read is removed (safe: nothing reads it); "
                  "one that is a near miss of exactly one parameter the plugin reads is renamed to it (unsafe: the "
                  "plugin starts reading the value). A parameter of another version of the plugin is left alone."))
def unknown_params(ctx):
    """A parameter that the (recognised) plugin does not read.

    Plugins read their parameters by name and ignore the rest silently: a ROS 1 name in a
    ROS 2 plugin (`wheelSeparation` vs `wheel_separation`), a typo, or a legacy one
    (`torque` next to `wheelTorque`). Fix: the name the plugin reads (given), or delete it.
    """

    for p, d in drives(ctx):
        spec = d.spec
        seen = set()
        for c in p.node.elements:
            if c.ns:                       # namespaced: an extension, not a parameter
                continue
            k = c.tag
            if k in spec.known or k in seen:
                continue
            seen.add(k)
            hint = IGNORED_HINT.get(k)
            guess = suggest(k, spec.known)
            other = next((o.label for o in (ROS1, ROS2, GZ) if o is not spec and k in o.known), None)
            msg = f"{spec.label} does not read <{k}>"
            if hint:
                msg += f" ({hint})"
            elif other:
                msg += f" (it is a {other} parameter)"
            if guess and not hint:
                msg += f"; did you mean <{guess}>?"
            yield Finding(msg, p.loc, {"plugin": p.name, "param": k, "suggestion": guess},
                          fix=_unread_fix(p, c, k, spec.known, hint, other))


def _param_fix(plugin, key: str, value, insert: bool = False) -> Fix | None:
    """Set the plugin's parameter ``key`` (or add it, with ``insert``)."""
    if key in plugin.params:
        return Fix((SetValue(plugin, key, value),), "safe", f"<{key}> {value}")
    if insert:
        return Fix((InsertInto(plugin, f"<{key}>{value}</{key}>"),), "safe", f"<{key}>{value}</{key}> added")
    return None


def _unread_fix(plugin, el, key: str, known, hint, other) -> Fix | None:
    """G007's fix: rename a near miss of exactly one known parameter, else remove what nothing reads."""
    if other:
        return None
    import difflib      # a near miss is rare: most runs never ask

    near = difflib.get_close_matches(key, sorted(known), n=2, cutoff=0.8)
    if len(near) == 1 and not hint:
        return Fix((RenameTag(el, near[0]),), "unsafe", f"<{key}> renamed <{near[0]}>")
    return Fix((RemoveElement(el),), "safe", f"<{key}> removed")


@rule("G008", "electric-plugin-attribute", "error",
      bad=ELECTRIC_IMU.format(attr="filename"),
      message='controller imu_controller declares its library with filename="libgazebo_ros_imu.so"; the Electric '
              "controller loader reads plugin=, so it is never loaded",
      good=ELECTRIC_IMU.format(attr="plugin"))
def electric_filename(ctx):
    """An Electric-era `<controller:...>` must name its library with `plugin=`, not `filename=`.

    The Gazebo 0.x controller loader reads `plugin=`; with `filename=` the controller is
    not loaded and its topics never appear (the seed's webcam). Fix: `plugin="lib....so"`
    (or run `myrabot-desc convert`, which writes modern `<plugin filename=...>`).
    """
    for p in ctx.robot.plugins():
        if p.dialect == "electric" and p.file_attr == "filename":
            yield Finding(f"controller {p.name} declares its library with filename=\"{p.filename}\"; the Electric "
                          "controller loader reads plugin=, so it is never loaded", p.loc,
                          {"plugin": p.name, "fix": f'plugin="{p.filename}"'})


@rule("G009", "material-resolves", "warning",
      bad='<gazebo reference="base_link">\n  <material>MyRobot/Black</material>\n</gazebo>',
      message="material MyRobot/Black (on base_link) is not a stock Gazebo material nor in any script found (0 read)",
      good='<gazebo reference="base_link">\n  <material>Gazebo/Black</material>\n</gazebo>')
def material_resolves(ctx):
    """A Gazebo material name must resolve: a stock `Gazebo/*` name or a script the model ships.

    Gazebo classic looks the name up in the OGRE scripts on its media path; an unknown
    name renders the default white/grey (and gz-sim never reads scripts). Searched: the
    stock table, the model's packages (materials/scripts, Media/materials/scripts) and
    the folders next to the model. Fix: define the material in a script of the package
    (and export it) or use a stock name.
    """

    names = [(g, g.properties.get("material")) for g in ctx.robot.gazebo if g.properties.get("material")]
    if all(is_stock(name) for _g, name in names):
        return                          # (a stock name resolves whatever the scripts hold)
    from myrabot_desc.materials.resolve import resolver_for     # the scripts' reader: a name not in stock

    res = resolver_for(ctx.robot)

    missing: dict[str, list] = {}
    for g, name in names:
        if name in missing or not res.defines(name):
            missing.setdefault(name, []).append(g)
    for name, blocks in missing.items():
        links = sorted({g.reference or "the model" for g in blocks})
        guess = suggest(name, res.names())
        yield Finding(f"material {name} (on {', '.join(links[:4])}{', ...' if len(links) > 4 else ''}) is not a stock "
                      f"Gazebo material nor in any script found ({len(res.scripts)} read)"
                      + (f"; did you mean {guess}?" if guess else ""),
                      blocks[0].loc, {"material": name, "links": links, "scripts": [str(s) for s in res.scripts],
                                      "suggestion": guess})


def _two_lasers(topic2: str) -> str:
    """Example snippet: two lasers on their own links, publishing `scan` and `topic2`."""
    out = []
    for name, topic, y in (("front_laser", "scan", "0.1"), ("rear_laser", topic2, "-0.1")):
        out.append(f'''<link name="{name}"/>
<joint name="{name}_joint" type="fixed">
  <origin xyz="0 {y} 0.2"/>
  <parent link="base_link"/>
  <child link="{name}"/>
</joint>
<gazebo reference="{name}">
  <sensor type="ray" name="{name}">
    <plugin name="{name}_controller" filename="libgazebo_ros_laser.so">
      <topicName>{topic}</topicName>
      <frameName>{name}</frameName>
    </plugin>
  </sensor>
</gazebo>''')
    return "\n".join(out)


@rule("G010", "topic-unique", "warning",
      bad=_two_lasers("scan"),
      message="topic /scan is published by 2 plugins: front_laser_controller (topicName), "
              "rear_laser_controller (topicName)",
      good=_two_lasers("scan_rear"))
def topic_unique(ctx):
    """Two sensors or plugins publish on the same topic.

    Two publishers of one topic interleave their messages (two LaserScans on /scan from
    different frames): consumers see both. Topics are resolved as the plugins do: under
    the robot namespace, and for gazebo_ros camera plugins under their `<cameraName>`
    (two cameras publishing `image_raw` under their own names do not collide), and for
    ROS 2 ray sensors by their `~/out` remapping. Range sensors (sonars, IR) sharing a topic
    are not reported: each Range message names its frame, and a ring of sonars on one topic is
    a common design. Fix: distinct topicName values, remappings or namespaces.
    """
    seen: dict[str, list] = {}
    for p in ctx.robot.plugins():
        for full, key in published_topics(p):     # model/plugins.py: the names convert carries over
            seen.setdefault(full, []).append((p, key))
    for t, users in sorted(seen.items()):
        if len(users) > 1 and not all(publishes_ranges(u) for u, _k in users):
            names = [f"{u.name or u.library} ({k})" for u, k in users]
            yield Finding(f"topic {t} is published by {len(users)} plugins: {', '.join(names)}", users[1][0].loc,
                          {"topic": t, "publishers": names})


@rule("G011", "electric-dialect", "info",
      bad=ELECTRIC_IMU.format(attr="plugin"),
      message="1 Electric-era controllers and 0 sensors (<controller:…>/<sensor:…>): today's Gazebo ignores them; "
              "`myrabot-desc convert` translates them",
      good=MODERN_IMU)
def electric_dialect(ctx):
    """The model uses the pre-SDF Electric dialect (`<controller:…>`, `<sensor:…>`, `<interface:…>`).

    Gazebo classic ≥ 1.0 and gz-sim do not read it; angles are in degrees there. Fix:
    `myrabot-desc convert` translates it to SDF sensors and plugins.
    """
    n_ctrl = sum(1 for p in ctx.robot.plugins() if p.dialect == "electric")
    n_sens = sum(1 for s in ctx.robot.sensors() if s.dialect == "electric")
    if n_ctrl or n_sens:
        first = next((p.loc for p in ctx.robot.plugins() if p.dialect == "electric"), None) or \
            next((s.loc for s in ctx.robot.sensors() if s.dialect == "electric"), None)
        yield Finding(f"{n_ctrl} Electric-era controllers and {n_sens} sensors (<controller:…>/<sensor:…>): "
                      "today's Gazebo ignores them; `myrabot-desc convert` translates them", first,
                      {"controllers": n_ctrl, "sensors": n_sens})


@rule("G012", "drive-parameter-conflict", "warning",
      bad=_drive(extra="<torque>10</torque>"),
      message="gazebo_ros_diff_drive (ROS 1): <torque> 10 and <wheelTorque> 5 disagree; the plugin reads wheelTorque (5)",
      good=_drive())
def drive_conflict(ctx):
    """Two parameters for the same thing with different values (torque 10 vs wheelTorque 5).

    Only one of them is read, so the other value is a trap for the reader. Fix: keep the
    one the plugin reads (named in the message).
    """
    pairs = [("torque", "wheelTorque")]
    for p, d in drives(ctx):
        spec = d.spec
        for a, b in pairs:
            va, vb = D.number(p, a)[0], D.number(p, b)[0]
            if va is not None and vb is not None and va != vb and spec is ROS1:
                yield Finding(f"{spec.label}: <{a}> {va:g} and <{b}> {vb:g} disagree; the plugin reads {b} ({vb:g})",
                              p.loc, {"plugin": p.name, a: va, b: vb})
