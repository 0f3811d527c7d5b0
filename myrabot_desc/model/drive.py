"""How a robot drives: the one answer that check, convert, sim and the MJCF writer share.

``find(robot)`` lists every drive the model declares; ``measure(robot, drive)`` measures its
wheels on the URDF (radius about the joint axis, separation along the axle). ``base(robot)`` says
what kind of base it is (differential, skid_steer, mecanum, omni, ackermann, swerve, planar) with its
wheelbase, track, wheel radius and steering lock, and the numbers its ros2_control controller
(the YAML a plugin's ``<parameters>`` names) drives with: see "drive kinds" below. Both are pure
Python (convert must not import numpy); a mesh wheel is read through model/meshes.

Recognised declarations. Parameter names, defaults and units were read from the plugins'
sources (gazebo_ros_pkgs ``gazebo_ros_diff_drive.cpp`` ROS 1 and ROS 2,
``gazebo_ros_skid_steer_drive.cpp``, kobuki_gazebo_plugins, gz-sim ``DiffDrive.cc``):

* Gazebo 0.x Electric controllers ``gazebo_ros_create``/``gazebo_ros_roomba`` (the bundled
  MYRAbot) and ``gazebo_ros_kobuki`` (rosbuild): ``left_wheel_joint``/``right_wheel_joint``, ``wheel_separation``,
  ``wheel_diameter``, ``torque``; ``front_castor_joint``/``rear_castor_joint`` name casters.
* ROS 1 ``gazebo_ros_diff_drive``: ``leftJoint``/``rightJoint``, ``wheelSeparation``
  (default 0.34 m), ``wheelDiameter`` (0.15 m), ``wheelTorque`` (5 N·m), ``updateRate`` (100 Hz),
  ``wheelAcceleration`` (0 = none). The acceleration is of the wheel *surface*, m/s²: the plugin
  ramps ``wheel_speed_instr_`` (m/s) by ``wheel_accel * dt`` and divides by the radius only when
  it sets the joint velocity. ``legacyMode`` (Indigo–Melodic) defaults to true and then
  commands the left joint with the right wheel's speed and vice versa: the robot turns the
  wrong way (Noetic's plugin no longer reads the flag).
* ROS 2 ``gazebo_ros_diff_drive``: ``num_wheel_pairs`` (1), ``left_joint``/``right_joint`` once
  per pair, ``wheel_separation``/``wheel_diameter`` once per pair (0.34/0.15 m),
  ``max_wheel_torque`` (5 N·m), ``max_wheel_acceleration`` (0; m/s² of the surface, same ramp),
  ``update_rate`` (100 Hz).
* gz-sim ``DiffDrive``: ``left_joint``/``right_joint`` (repeatable), ``wheel_separation`` (1 m),
  ``wheel_radius`` (0.2 m), ``max_linear_acceleration`` (m/s² of the vehicle).
* Vendor plugins of small round bases (``gazebo_ros_kobuki`` and its clones):
  ``left_wheel_joint_name``/``right_wheel_joint_name``, ``wheel_separation``,
  ``wheel_diameter``, ``torque``.
* ROS 1 ``gazebo_ros_skid_steer_drive``: ``leftFrontJoint``/``leftRearJoint``/
  ``rightFrontJoint``/``rightRearJoint``, ``wheelSeparation`` (0.4 m), ``wheelDiameter``
  (0.15 m), ``torque`` (5 N·m), ``updateRate`` (100 Hz); every left wheel turns at
  (v − ω s/2)/r and every right one at (v + ω s/2)/r: a diff drive over both pairs.
* ros_control: ``<transmission>`` joints whose ``hardwareInterface`` is (…/)
  ``VelocityJointInterface``, and ros2_control ``<joint>`` blocks with
  ``<command_interface name="velocity"/>``. They are a diff drive when lateral-axis wheels
  stand on both sides of the base (left at +y, REP-103).
* Wheel joints named by the user (``sim drive --wheels A,B``).
"""

import math

from myrabot_desc.errors import InputError
from myrabot_desc.expand.packages import resource_roots
from myrabot_desc.expand.yaml_load import load_path
from myrabot_desc.model import values as V
from myrabot_desc.model.kinematics import rest_poses
from myrabot_desc.model.shapes import surface_points
from myrabot_desc.model.transforms import IDENTITY, compose, place, pose_T, rotate
from myrabot_desc.records import Struct
from myrabot_desc.safety import display, limit

ALIGNED = 0.99          # |cos| between a cylinder's axis and the joint axis for "a wheel drawn as a cylinder"
LATERAL = 0.9           # |y| of a wheel axis (root frame) for "turns across the direction of travel"
POINTS_N = 720          # samples around a circle when a wheel is measured from its points
LEVEL = 0.17            # |z| of a wheel axis (root frame, q = 0): a wheel rolls about a level axle (10°)


class Spec(Struct):
    """One plugin dialect's parameter names and the defaults the plugin uses when one is missing."""

    dialect: str                      # 'electric' | 'ros1' | 'ros2' | 'gz' | 'vendor' | 'skid'
    label: str
    left: tuple[str, ...]             # keys naming left wheel joints (front first)
    right: tuple[str, ...]
    separation: str
    diameter: str | None = None
    radius: str | None = None
    torque: str | None = None
    accel: str | None = None          # the acceleration key
    accel_unit: str = ""              # 'wheel m/s^2' (surface, per wheel) or 'vehicle m/s^2'
    rate: str | None = None
    fixed_ok: tuple[str, ...] = ()    # keys that may name non-wheel joints (casters)
    known: frozenset = frozenset()
    defaults: tuple = ()              # ((key, value), ...) the plugin's own defaults

    def units(self) -> dict[str, str]:
        """Each numeric parameter's key -> its unit (as the plugin reads it)."""
        out = {}
        for key, unit in ((self.separation, "m"), (self.diameter, "m"), (self.radius, "m"), (self.torque, "N·m"),
                          (self.accel, self.accel_unit), (self.rate, "Hz")):
            if key:
                out[key] = unit
        return out


class Quantity(Struct):
    """A drive plugin's numeric parameter: its value (None when it is not a number), unit and the
    parameter as written (a Node: ``loc``, ``text``; ``robot.origin(drive.plugin, key)`` for its span)."""

    key: str
    value: float | None
    unit: str
    node: object = None


COMMON_CLASSIC = {"robotNamespace"}
ROS1 = Spec(
    "ros1", "gazebo_ros_diff_drive (ROS 1)", ("leftJoint",), ("rightJoint",), "wheelSeparation", "wheelDiameter",
    torque="wheelTorque", accel="wheelAcceleration", accel_unit="wheel m/s^2", rate="updateRate",
    known=frozenset(COMMON_CLASSIC | {
        "leftJoint", "rightJoint", "wheelSeparation", "wheelDiameter", "wheelAcceleration", "wheelTorque",
        "commandTopic", "odometryTopic", "odometryFrame", "robotBaseFrame", "updateRate", "publishWheelTF",
        "publishOdomTF", "publishWheelJointState", "odometrySource", "legacyMode", "publishTf", "rosDebugLevel"}),
    defaults=(("wheelSeparation", 0.34), ("wheelDiameter", 0.15), ("wheelTorque", 5.0),
              ("wheelAcceleration", 0.0), ("updateRate", 100.0)))
ROS2 = Spec(
    "ros2", "gazebo_ros_diff_drive (ROS 2)", ("left_joint",), ("right_joint",), "wheel_separation", "wheel_diameter",
    torque="max_wheel_torque", accel="max_wheel_acceleration", accel_unit="wheel m/s^2", rate="update_rate",
    known=frozenset({
        "ros", "left_joint", "right_joint", "wheel_separation", "wheel_diameter", "max_wheel_torque",
        "max_wheel_acceleration", "update_rate", "publish_odom", "publish_odom_tf", "publish_wheel_tf",
        "odometry_frame", "robot_base_frame", "odometry_source", "covariance_x", "covariance_y",
        "covariance_yaw", "num_wheel_pairs"}),
    defaults=(("wheel_separation", 0.34), ("wheel_diameter", 0.15), ("max_wheel_torque", 5.0),
              ("max_wheel_acceleration", 0.0), ("update_rate", 100.0)))
GZ = Spec(
    "gz", "gz-sim DiffDrive", ("left_joint",), ("right_joint",), "wheel_separation", radius="wheel_radius",
    accel="max_linear_acceleration", accel_unit="vehicle m/s^2", rate="odom_publish_frequency",
    known=frozenset({
        "left_joint", "right_joint", "wheel_separation", "wheel_radius", "odom_publish_frequency", "topic",
        "odom_topic", "tf_topic", "frame_id", "child_frame_id", "min_velocity", "max_velocity",
        "min_acceleration", "max_acceleration", "min_jerk", "max_jerk", "odom_covariance"}
        | {f"{m}_{k}_{q}" for m in ("min", "max") for k in ("linear", "angular")
           for q in ("velocity", "acceleration", "jerk")}),
    defaults=(("wheel_separation", 1.0), ("wheel_radius", 0.2)))
CREATE = Spec(
    "electric", "gazebo_ros_create/roomba (Electric)", ("left_wheel_joint",), ("right_wheel_joint",),
    "wheel_separation", "wheel_diameter", torque="torque", rate="updateRate",
    fixed_ok=("front_castor_joint", "rear_castor_joint"),
    known=frozenset({"alwaysOn", "updateRate", "robotNamespace", "node_namespace", "left_wheel_joint",
                     "right_wheel_joint", "front_castor_joint", "rear_castor_joint", "wheel_separation",
                     "wheel_diameter", "base_geom", "torque"}))
VENDOR = Spec(
    "vendor", "gazebo_ros_kobuki-style base plugin", ("left_wheel_joint_name",), ("right_wheel_joint_name",),
    "wheel_separation", "wheel_diameter", torque="torque",
    known=frozenset({"publish_tf", "left_wheel_joint_name", "right_wheel_joint_name", "wheel_separation",
                     "wheel_diameter", "torque", "velocity_command_timeout", "cliff_sensor_left_name",
                     "cliff_sensor_center_name", "cliff_sensor_right_name", "cliff_detection_threshold",
                     "bumper_name", "imu_name", "base_prefix", "update_rate", "updateRate"}))
SKID = Spec(
    "skid", "gazebo_ros_skid_steer_drive (ROS 1)", ("leftFrontJoint", "leftRearJoint"),
    ("rightFrontJoint", "rightRearJoint"), "wheelSeparation", "wheelDiameter", torque="torque", rate="updateRate",
    known=frozenset(COMMON_CLASSIC | {
        "leftFrontJoint", "rightFrontJoint", "leftRearJoint", "rightRearJoint", "wheelSeparation",
        "wheelDiameter", "torque", "commandTopic", "odometryTopic", "odometryFrame", "robotBaseFrame",
        "updateRate", "broadcastTF", "covariance_x", "covariance_y", "covariance_yaw"}),
    defaults=(("wheelSeparation", 0.4), ("wheelDiameter", 0.15), ("torque", 5.0), ("updateRate", 100.0)))
# The Electric-era kobuki controller (rosbuild kobuki_description) reads the Create controller's keys.
KOBUKI_ELECTRIC = CREATE._replace(label="gazebo_ros_kobuki (Electric)")
PLUGIN_SPECS = (ROS1, ROS2, GZ, CREATE, KOBUKI_ELECTRIC, VENDOR, SKID)


class Drive(Struct):
    """A declared drive: the wheels it turns and the numbers it believes.

    ``source``: 'plugin', 'ros_control' (transmissions), 'ros2_control', 'user' or 'guess'
    (continuous joints named like wheels, sided by position; sim only). Numbers are None when not given
    (``spec.defaults`` says what the plugin then uses). ``accel`` is in ``spec.accel_unit``.
    """

    source: str
    label: str
    left: tuple[str, ...]             # wheel joints as declared (may not exist: see missing())
    right: tuple[str, ...]
    spec: Spec | None = None
    plugin: object = None             # model.parts.Plugin
    separation: float | None = None   # the plugin's (m)
    radius: float | None = None       # the plugin's (m; diameter / 2)
    torque: float | None = None       # N·m per wheel
    accel: float | None = None
    update_rate: float | None = None  # Hz
    legacy: bool = False              # ROS 1 legacyMode: left/right commands swapped (turns the wrong way)
    legacy_explicit: bool = False     # legacyMode given (else the default applied)
    loc: object = None
    bad: tuple[tuple[str, str], ...] = ()   # (key, text) numbers that do not parse

    @property
    def joints(self) -> tuple[str, ...]:
        return self.left + self.right

    @property
    def skid(self) -> bool:
        return len(self.left) > 1 or len(self.right) > 1

    def missing(self, robot) -> list[str]:
        return [j for j in self.joints if j not in robot.joints]

    @property
    def name(self) -> str | None:
        """The plugin's name (else its element's tag or library); None for a drive without a plugin."""
        p = self.plugin
        return None if p is None else (p.name or p.tag or p.library)

    @property
    def library(self) -> str | None:
        p = self.plugin
        return None if p is None else (p.library or p.tag)

    def quantities(self) -> dict[str, Quantity]:
        """The numeric parameters the plugin gives, with their units (``Spec.units``)."""
        p, spec = self.plugin, self.spec
        if p is None or spec is None:
            return {}
        out = {}
        for key, unit in spec.units().items():
            node = p.param(key)
            if node is not None:
                out[key] = Quantity(key, number(p, key)[0], unit, node)
        return out

    def with_defaults(self):
        """(this drive with the plugin's own defaults where it gives no separation or wheel size,
        notes saying which defaults were used): the numbers the plugin runs with."""
        spec = self.spec
        if spec is None:
            return self, []
        defaults = dict(spec.defaults)
        notes = []
        sep, rad = self.separation, self.radius
        if sep is None and spec.separation in defaults:
            sep = defaults[spec.separation]
            notes.append(f"the plugin gives no {spec.separation}: it uses its default {sep:g} m")
        if rad is None:
            key = spec.radius or spec.diameter
            if key in defaults:
                rad = defaults[key] if spec.radius else defaults[key] / 2
                notes.append(f"the plugin gives no {key}: it uses its default {defaults[key]:g} m")
        return self._replace(separation=sep, radius=rad), notes


class Wheel(Struct):
    """One wheel as built (root frame, q = 0)."""

    joint: str
    link: str
    origin: tuple[float, float, float]     # the joint origin (on the rotation axis)
    axis: tuple[float, float, float]       # unit joint axis
    centre: tuple[float, float, float]     # centre of the shape that gives the radius (else the origin)
    radius: float | None
    shape: object = None                   # the collision/visual item that gives the radius
    round: bool = False                    # a sphere, or a cylinder about the joint axis
    forward_sign: float = 1.0              # +1 if a positive joint rate drives the base forward (+x)
    problem: object = None                 # the InputError of a wheel mesh that could not be read

    @property
    def xy(self) -> tuple[float, float]:
        return self.origin[0], self.origin[1]


class Geometry(Struct):
    """The wheels of a drive as the URDF builds them."""

    left: tuple[Wheel, ...]
    right: tuple[Wheel, ...]
    separation: float | None       # between the left and right wheel centres along the left axle (m)
    radius: float | None           # mean radius of the wheels that have one (m)

    @property
    def wheels(self) -> tuple[Wheel, ...]:
        return self.left + self.right


# ------------------------------------------------------------------ the plugins' parameters
def number(plugin, key: str | None):
    """(value, ok) of a numeric parameter: (None, True) when absent, (None, False) when not a
    finite number (model/values.py)."""
    if key is None:
        return None, True
    t = plugin.text(key)
    if t is None:
        return None, True
    try:
        return V.parse_number(t), True
    except V.ValueProblem:
        return None, False


# ------------------------------------------------------------------ which plugin is a drive
def plugin_spec(p) -> Spec | None:
    """The dialect of a drive plugin, or None when the plugin does not drive wheels."""
    lib = (p.library or "").lower()
    name = (p.name or "").lower()
    tag = p.tag.lower()
    if p.dialect == "electric":
        if any(k in s for s in (lib, name, tag) for k in ("create", "roomba")):
            return CREATE
        if "kobuki" in lib or "kobuki" in tag or "left_wheel_joint" in p.params:
            return KOBUKI_ELECTRIC
        return None
    if p.dialect == "gz":
        return GZ if ("diff-drive" in lib or "diff_drive" in lib or "diffdrive" in name.replace("::", "")) else None
    if "skid_steer" in lib:
        return SKID
    if "diff_drive" in lib or "diffdrive" in lib.replace("_", ""):
        ros1 = any(k in p.params for k in ("leftJoint", "rightJoint", "wheelSeparation", "wheelDiameter"))
        ros2 = any(k in p.params for k in ("left_joint", "right_joint", "wheel_separation", "wheel_diameter", "ros"))
        return ROS2 if ros2 and not ros1 else ROS1
    if "create" in lib or "roomba" in lib:
        return CREATE
    if "left_wheel_joint_name" in p.params or "right_wheel_joint_name" in p.params or "kobuki" in lib:
        return VENDOR
    return None


def from_plugin(p, spec: Spec) -> Drive:
    left = tuple(v for k in spec.left for v in p.values(k))
    right = tuple(v for k in spec.right for v in p.values(k))
    bad = []

    def num(key):
        v, ok = number(p, key)
        if not ok:
            bad.append((key, p.text(key)))
        return v

    sep = num(spec.separation)
    if spec.radius:
        rad = num(spec.radius)
    else:
        dia = num(spec.diameter)
        rad = dia / 2 if dia is not None else None
    legacy = explicit = False
    if spec is ROS1:
        t = p.text("legacyMode")
        explicit = t is not None
        # the plugin reads it with sdf's Get<bool>: true/1, else false (a misspelling is false)
        legacy = V.boolean(t, False) if explicit else True
    return Drive("plugin", spec.label, left, right, spec, p, sep, rad, num(spec.torque), num(spec.accel),
                 num(spec.rate), legacy, explicit, p.loc, tuple(bad))


# ------------------------------------------------------------------ ros_control
VELOCITY_IFACES = ("VelocityJointInterface",)
POSITION_IFACES = ("PositionJointInterface",)


def velocity_joints(robot) -> tuple[list[str], str | None]:
    """Joints commanded in velocity (a velocity interface and no position one), in file order, and
    where they were declared ('ros_control' transmissions or 'ros2_control' blocks)."""
    out, source = [], None
    for t in robot.transmissions:
        for j in t.named:
            if j.tag != "joint":
                continue
            ifaces = [i.rsplit("/", 1)[-1] for i in j.interfaces]
            if any(i in VELOCITY_IFACES for i in ifaces) and not any(i in POSITION_IFACES for i in ifaces) \
                    and j.name not in out:
                out.append(j.name)
                source = source or "ros_control"
    for block in robot.ros2_control:
        for j in block.joints:
            cmds = j.command_interfaces
            if "velocity" in cmds and "position" not in cmds and j.name not in out:
                out.append(j.name)
                source = source or "ros2_control"
    return out, source


def ros_wheel_joints(robot) -> tuple[list[str], str | None]:
    """The joints ros_control/ros2_control commands in velocity that are wheels, in file order, and
    where they were declared: those named like a wheel (whatever their type: a fixed or revolute
    wheel is still the wheel the controller drives) and moving ones that carry a round shape about
    a lateral axis (an arm's pitch joint commanded in velocity is neither). Unlike
    ``from_velocity_joints`` they need not stand on both sides: check judges them even when a
    wheel moved to the other side leaves no left/right pair."""
    names, source = velocity_joints(robot)
    T = link_transforms(robot)
    out = []
    for n in names:
        j = robot.joints.get(n)
        if j is None:
            continue
        low = n.lower()
        if ("wheel" in low or "wheel" in j.child.lower()) and "caster" not in low and "castor" not in low:
            out.append(n)
            continue
        if j.type in ("continuous", "revolute"):
            w = wheel(robot, n, T, read_meshes=False)
            if w is not None and w.round and abs(w.axis[1]) >= LATERAL:
                out.append(n)
    return out, source


def virtual_joints(robot) -> dict[str, tuple[str, ...]]:
    """Moving joints that stand for others: other moving joints mimic them, and their child link has
    no collision and no mass (a bicycle model's virtual steering and traction joints, CarlikeBot's
    ``virtual_front_wheel_joint``): joint -> the joints that mimic it. Their links may be drawn but
    are no physical body; the joints that mimic them move the real wheels. Built once per robot."""
    def build():
        followers: dict[str, list[str]] = {}
        for j in robot.joints.values():
            if j.mimic is not None and j.type != "fixed":
                followers.setdefault(j.mimic.joint, []).append(j.name)
        out = {}
        for name, fs in followers.items():
            j = robot.joints.get(name)
            link = robot.links.get(j.child) if j is not None else None
            if j is None or j.type == "fixed" or link is None or link.collisions or link.mass > 0:
                continue
            out[name] = tuple(fs)
        return out
    return dict(robot.derive("drive.virtual_joints", build))


def commanded_joints(robot) -> set[str]:
    """Joints something commands: named in a transmission or with a command interface in a
    ``<ros2_control>`` block, or turned by a declared drive. Empty when the model says nothing of
    its actuators (then nobody can tell a passive joint from an actuated one)."""
    out = {n for t in robot.transmissions for n in t.joints}
    for t in robot.transmissions:      # PR2's wrist and gripper transmissions: <flexJoint>, <gap_joint>...
        out |= {j.name for j in t.named}
    for block in robot.ros2_control:
        out |= {j.name for j in block.joints if j.command_interfaces}
    for d in find(robot):
        out |= set(d.joints)
    return {n for n in out if n in robot.joints}


def position_joints(robot) -> list[str]:
    """Joints commanded in position by ros2_control (a ``position`` command interface), in file order."""
    out = []
    for block in robot.ros2_control:
        for j in block.joints:
            if j.name not in out and "position" in j.command_interfaces:
                out.append(j.name)
    return out


def _sided(robot, names, T=None) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """Split wheel joints into left (+y) and right (−y) by where they sit in the root frame;
    joints whose axis is not lateral, or that sit on the centre line, are left out."""
    T = T if T is not None else link_transforms(robot)
    left, right = [], []
    for n in names:
        j = robot.joints.get(n)
        if j is None or j.type not in ("continuous", "revolute") or j.parent not in T:
            continue
        R, p = compose(T[j.parent], pose_T(j.origin))
        a = _unit(rotate(R, j.axis))
        if a is None or abs(a[1]) < LATERAL or abs(p[1]) < 1e-4:
            continue
        (left if p[1] > 0 else right).append(n)
    return tuple(left), tuple(right)


def from_velocity_joints(robot, T=None) -> Drive | None:
    names, source = velocity_joints(robot)
    if not names:
        return None
    left, right = _sided(robot, names, T)
    if not left or not right:
        return None
    label = "ros_control velocity wheels" if source == "ros_control" else "ros2_control velocity wheels"
    return Drive(source, label, left, right)


def user_drive(robot, left, right) -> Drive:
    """Wheel joints named by the user (left list, right list)."""
    return Drive("user", "wheel joints given", tuple(left), tuple(right), loc=robot.loc)


def guess_drive(robot) -> Drive | None:
    """Continuous joints named like wheels ("wheel" in the name, casters left out), split into
    left (+y) and right (−y) by where they sit on the base, as ``_sided`` does for ros_control
    wheels: sim's fallback when nothing declares a drive. Names vary (``left_wheel_joint``,
    ``wheel_left_joint``, Fetch's ``l_wheel_joint``); where a wheel sits does not."""
    names = [j.name for j in robot.joints.values() if j.type == "continuous" and "wheel" in j.name.lower()
             and "caster" not in j.name.lower() and "castor" not in j.name.lower()]
    left, right = _sided(robot, names)
    if not left or not right:
        return None
    return Drive("guess", "continuous joints named like wheels", left, right, loc=robot.loc)


def find(robot) -> list[Drive]:
    """Every drive the model declares, plugins first (in file order), then ros_control velocity wheels
    (unless a plugin already drives those joints). Built once per robot."""
    def build():
        out = []
        for p in robot.plugins():
            s = plugin_spec(p)
            if s is not None:
                out.append(from_plugin(p, s))
        rc = from_velocity_joints(robot)
        if rc is not None and not any(set(rc.joints) & set(d.joints) for d in out):
            out.append(rc)
        return tuple(out)
    return list(robot.derive("drive.find", build))


def plugin_drives(robot) -> list[Drive]:
    return [d for d in find(robot) if d.source == "plugin"]


def main_drive(robot, left=(), right=(), guess: bool = False) -> Drive | None:
    """The drive that moves the base: the user's wheels, else the first declared drive whose wheel
    joints exist, else (guess=True) joints named like wheels."""
    if left or right:
        return user_drive(robot, left, right)
    ds = find(robot)
    for d in ds:
        if d.left and d.right and not d.missing(robot):
            return d
    if ds:
        return ds[0]
    return guess_drive(robot) if guess else None


def wheel_joints(robot) -> list[str]:
    """Joints that drive or carry wheels: those of every declared drive, then continuous joints
    whose child's collision is a cylinder about a level joint axis (an undeclared wheel; a
    rotor's cylinder spins about a vertical axis and is no wheel). Built once per robot."""
    def build():
        out: list[str] = []
        for d in find(robot):
            out += [n for n in d.joints if n in robot.joints and n not in out]
        T = link_transforms(robot)
        for j in robot.joints.values():
            if j.type == "continuous" and j.name not in out:
                w = wheel(robot, j.name, T, read_meshes=False)      # a cylinder about the axle: no mesh needed
                if w is not None and w.round and w.shape.geometry.kind == "cylinder" and abs(w.axis[2]) < LEVEL:
                    out.append(j.name)
        return tuple(out)
    return list(robot.derive("drive.wheel_joints", build))


def is_mobile(robot) -> bool:
    """A wheeled base: it declares a drive or has wheels (``wheel_joints``), or ``base`` knows how it
    moves (steered modules on revolute joints, a planar plugin over fixed wheels). check's P rules,
    the MJCF writer's free base and the viewer ask this one question."""
    return bool(wheel_joints(robot)) or base(robot) is not None


# ------------------------------------------------------------------ geometry (pure Python)
def link_transforms(robot) -> dict:
    """World transform (R, p) of every link at q = 0 with the root at the origin (model/kinematics)."""
    return rest_poses(robot)


def _unit(v):
    n = math.sqrt(sum(x * x for x in v))
    return None if n < 1e-12 else tuple(x / n for x in v)


def _dot(a, b) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def wheel_shapes(link):
    """The shapes a wheel is measured on: its collisions, else its visuals."""
    cols = [c for c in link.collisions if c.geometry is not None]
    return cols or [v for v in link.visuals if v.geometry is not None]


def wheel(robot, joint_name: str, T=None, read_meshes: bool = True) -> Wheel | None:
    """Measure one wheel: the largest distance of its collision (else visual) geometry from the
    joint axis. A sphere gives its radius, a cylinder about the axis (|cos| > 0.99) its radius;
    any other shape (box, tilted cylinder, mesh) the farthest of its points from the axis line.
    ``read_meshes=False`` leaves mesh shapes out (a caller that only asks "is this a round wheel?")."""
    j = robot.joints.get(joint_name)
    if j is None or j.child not in robot.links:
        return None
    T = T if T is not None else link_transforms(robot)
    if j.parent not in T:
        return None
    Rj, pj = compose(T[j.parent], pose_T(j.origin))
    axis = _unit(rotate(Rj, j.axis)) or (0.0, 1.0, 0.0)
    best, best_item, best_round, centre, problem = None, None, False, pj, None
    for it in wheel_shapes(robot.links[j.child]):
        g = it.geometry
        Rs, ps = compose((Rj, pj), pose_T(it.origin))
        if g.kind == "sphere":
            r, rnd = g.radius, True
        elif g.kind == "cylinder" and abs(_dot((Rs[0][2], Rs[1][2], Rs[2][2]), axis)) > ALIGNED:
            r, rnd = g.radius, True
        elif g.kind == "mesh" and not read_meshes:
            continue
        else:
            pts = _world_points(g, it, Rs, ps)
            if isinstance(pts, Exception):
                problem = problem or pts
                continue
            if not pts:
                continue
            r, rnd = _radial_extent(pts, pj, axis), False
        if best is None or r > best:
            best, best_item, best_round = r, it, rnd
            centre = ps if rnd else _axial_mid(pts, pj, axis)
    fwd = axis[1]          # (axis × z)[0]: a positive rate about +y rolls the base forward
    return Wheel(joint_name, j.child, pj, axis, centre, best, best_item, best_round,
                 math.copysign(1.0, fwd) if fwd else 1.0, problem)


def _world_points(g, it, Rs, ps):
    try:
        pts = surface_points(g, POINTS_N, loc=getattr(it, "loc", None))
    except InputError as exc:      # an unreadable mesh: no measured radius from it (the wheel keeps why)
        return exc
    except Exception as exc:       # a reader's own failure on a malformed file: the same, in one line
        return InputError(f"mesh {getattr(g, 'filename', '?')} cannot be read ({type(exc).__name__})",
                          getattr(it, "loc", None))
    return place((Rs, ps), _rows(pts))


def _rows(pts):
    return pts.tolist() if hasattr(pts, "tolist") else pts


def _radial_extent(pts, origin, axis) -> float:
    """The farthest of the points from the axis line through origin."""
    best = 0.0
    for q in pts:
        d = (q[0] - origin[0], q[1] - origin[1], q[2] - origin[2])
        a = _dot(d, axis)
        best = max(best, _dot(d, d) - a * a)
    return math.sqrt(max(best, 0.0))


def _axial_mid(pts, origin, axis):
    """The wheel's mid-plane point on its axis (the middle of the points' extent along the axis)."""
    s = [_dot((q[0] - origin[0], q[1] - origin[1], q[2] - origin[2]), axis) for q in pts]
    m = (min(s) + max(s)) / 2
    return tuple(origin[k] + m * axis[k] for k in range(3))


def separation(left: tuple[Wheel, ...], right: tuple[Wheel, ...]) -> float | None:
    """Track width: the left and right wheel centres (means of each side) along the first left wheel's axle."""
    if not left or not right:
        return None
    cl = [sum(w.centre[k] for w in left) / len(left) for k in range(3)]
    cr = [sum(w.centre[k] for w in right) / len(right) for k in range(3)]
    d = (cl[0] - cr[0], cl[1] - cr[1], cl[2] - cr[2])
    return abs(_dot(d, left[0].axis))


def measure(robot, drive: Drive) -> Geometry:
    """The drive's wheels measured on the URDF (joints that do not exist are left out); built once
    per robot and pair of wheel sets."""
    def build():
        T = link_transforms(robot)
        left = tuple(w for w in (wheel(robot, n, T) for n in drive.left) if w is not None)
        right = tuple(w for w in (wheel(robot, n, T) for n in drive.right) if w is not None)
        radii = [w.radius for w in left + right if w.radius is not None]
        return Geometry(left, right, separation(left, right), sum(radii) / len(radii) if radii else None)
    return robot.derive(("drive.measure", tuple(drive.left), tuple(drive.right)), build)


def turn_sign(drive: Drive) -> float:
    """−1 when the plugin swaps the wheels (ROS 1 legacyMode): it turns the other way."""
    return -1.0 if drive.legacy else 1.0


# ------------------------------------------------------------------ drive kinds
# What a base is, beyond "left and right wheels": each kind as real packages declare it.
#   * ros2_control controllers named in the controller YAML a gz/gazebo ros2_control plugin's
#     <parameters> names (the controller_manager's ``type:`` of each controller);
#   * planar body-velocity plugins: Gazebo classic ``gazebo_ros_planar_move`` (ROS 1 and 2),
#     gz-sim ``VelocityControl``, and body-force vendor plugins (Ridgeback's ``*force_based_move``);
#     over wheels that spin such a plugin stands in for mecanum wheels (nothing models the rollers);
#   * gz-sim ``MecanumDrive`` / ``AckermannSteering`` systems, classic ``gazebo_ros_ackermann_drive``;
#   * steering by the URDF: a moving joint about a vertical axis that carries a wheel, or that
#     ros2_control commands in position next to velocity wheels (a bicycle model's virtual joints).
#     Steering on one axle is Ackermann, on two or more (front and rear) swerve.
KINDS = ("differential", "skid_steer", "mecanum", "omni", "ackermann", "swerve", "planar")
BODY_MOVED = ("mecanum", "omni", "planar")      # simulated as a body moved in the plane (rollers not modelled)
VERTICAL = 0.9          # |z| of a joint axis (root frame) for "steers about a vertical axis"
FULL_TURN = 2 * math.pi - 1e-6    # a revolute range this wide is unlimited (MPO-700: ±1e16)

# controller type (ros2_control, lower case, as a substring) -> kind
CONTROLLER_KINDS = (("mecanum", "mecanum"), ("omni", "omni"), ("swerve", "swerve"), ("ackermann", "ackermann"),
                    ("bicycle", "ackermann"), ("tricycle", "ackermann"), ("diff_drive", "differential"))
PLANAR_LIBS = ("planar_move", "force_based_move", "velocity-control", "velocity_control", "velocitycontrol")


class Controller(Struct):
    """A drive controller read from the ros2_control YAML a plugin's ``<parameters>`` names."""

    name: str
    type: str
    params: dict
    file: str                         # the YAML as written in <parameters>
    plugin: object = None             # the plugin whose <parameters> names it (for locations)

    @property
    def loc(self):
        p = self.plugin
        if p is None:
            return None
        node = p.param("parameters")
        return (node.loc if node is not None else None) or p.loc


class Base(Struct):
    """How the base moves: its kind, the joints that drive and steer it, its geometry on the URDF
    (joint origins at q = 0 in the root frame; radius as ``wheel`` measures it) and the numbers the
    declared controller drives with (after its multipliers), None where nothing gives one."""

    kind: str
    why: str                          # what says so, for messages
    wheels: tuple[str, ...]           # driven (spinning) wheel joints
    steering: tuple[str, ...] = ()
    wheelbase: float | None = None    # front to rear axle (m); swerve: between the steering axes
    track: float | None = None        # left to right (m): driven wheels; swerve: steering axes
    radius: float | None = None
    steer_limit: float | None = None  # rad each way; None when the steering turns freely
    drive: Drive | None = None        # the find() drive it refines (wheels sided left/right)
    plugin: object = None             # the plugin/system that declares the kind
    controller: Controller | None = None
    ctrl_wheelbase: float | None = None
    ctrl_track: float | None = None
    ctrl_radius: float | None = None
    loc: object = None

    @property
    def holonomic(self) -> bool:
        """Moves sideways as commanded (an omni twist): mecanum, omni, planar, swerve."""
        return self.kind in ("mecanum", "omni", "planar", "swerve")

    @property
    def min_turn_radius(self) -> float | None:
        """Ackermann: the rear axle's centre at full lock, wheelbase / tan(limit) (m)."""
        if self.kind != "ackermann" or not self.wheelbase or not self.steer_limit:
            return None
        return self.wheelbase / math.tan(min(self.steer_limit, math.pi / 2 - 1e-6))


def _controller_yaml(robot, text: str):
    """The parsed YAML a ``<parameters>`` names, read through the one YAML loader and only from
    the folders meshes may come from (the path gate); None when it names no such file."""
    uri = text.strip()
    if not uri or not uri.lower().endswith((".yaml", ".yml")):
        return None
    path = robot.resolve_uri(uri)
    if path is None or not path.is_file():
        return None
    base = robot.source.parent if robot.source else path.parent
    return load_path(path, limit("max_input_bytes"), resource_roots(base, robot.package_roots), display(path))


def _nodes(doc, depth: int = 0):
    """(node name, its ros__parameters) of a ros2 parameters file. A key may carry the node's
    namespace (``/**/name:``) or be a namespace with its nodes nested below (``/**:`` then ``name:``);
    the nesting is followed a few levels (the loader bounds what aliases expand to)."""
    if not isinstance(doc, dict):
        return
    for key, val in doc.items():
        if not isinstance(val, dict):
            continue
        p = val.get("ros__parameters")
        if isinstance(p, dict):
            yield str(key).rsplit("/", 1)[-1], p
        elif depth < 4:
            yield from _nodes(val, depth + 1)


def _ros_params(doc, name: str) -> dict | None:
    """``name``'s ros__parameters in a ros2 parameters file (the first node of that name)."""
    return next((p for n, p in _nodes(doc) if n == name), None)


def controllers(robot) -> list[Controller]:
    """The drive controllers of every controller YAML the robot's plugins name in ``<parameters>``."""
    def build():
        out = []
        for p in robot.plugins():
            for text in p.values("parameters"):
                doc = _controller_yaml(robot, text)
                cm = _ros_params(doc, "controller_manager") or {}
                named = []
                for name, v in cm.items():
                    ctype = v.get("type") if isinstance(v, dict) else None
                    if isinstance(ctype, str) and _controller_kind(ctype):
                        named.append((str(name), ctype))
                # a controller may give its type among its own parameters (ros2_control_demos'
                # example 11: the spawner reads it from the controller's section)
                for name, own in _nodes(doc):
                    ctype = own.get("type")
                    if isinstance(ctype, str) and _controller_kind(ctype) and name not in {n for n, _ in named}:
                        named.append((name, ctype))
                out += [Controller(n, t, _ros_params(doc, n) or {}, text.strip(), p) for n, t in named]
        return tuple(out)
    return list(robot.derive("drive.controllers", build))


def _controller_kind(ctype: str) -> str | None:
    t = ctype.lower()
    return next((k for s, k in CONTROLLER_KINDS if s in t), None)


def _num(params: dict, *keys):
    """The first of ``keys`` that is a finite number in a controller's parameters."""
    for k in keys:
        v = params.get(k)
        if isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v):
            return float(v)
    return None


def _times(v, m):
    return None if v is None else v * (m if m is not None else 1.0)


class Term(Struct):
    """One geometric number a controller or plugin drives with: what it is, the key as written,
    the value before and after its multiplier (controllers) or the plugin's default when the key is
    not written."""

    what: str                         # 'track' | 'wheelbase' | 'radius' | 'kingpin' | 'half_sum' | 'steer_limit'
    key: str
    raw: float
    multiplier: float | None = None
    multiplier_key: str | None = None
    default: bool = False             # the plugin's own default (the key is not written)

    @property
    def value(self) -> float:
        return self.raw * (self.multiplier if self.multiplier is not None else 1.0)


def _term(params: dict, what: str, keys, mult_keys=()):
    key = next((k for k in keys if _num(params, k) is not None), None)
    if key is None:
        return None
    mkey = next((k for k in mult_keys if _num(params, k) is not None), None)
    return Term(what, key, _num(params, key), _num(params, mkey) if mkey else None, mkey)


# Parameter names of ros2_controllers' diff_drive_controller, mecanum_drive_controller (its
# ``kinematics.*`` and Husarion's/ROS 1's ``wheel_separation_x/y``) and the steering controllers
# (ackermann, bicycle, tricycle: current ``traction_*``/``steering_*`` names, then the deprecated
# ``rear_*``/``front_*`` ones; front steering, the default, makes the rear wheels the traction ones).
RADIUS_KEYS = ("wheel_radius", "traction_wheels_radius", "traction_wheel_radius", "rear_wheels_radius",
               "rear_wheel_radius", "kinematics.wheels_radius")
RADIUS_MULT = ("wheel_radius_multiplier", "left_wheel_radius_multiplier")


def controller_terms(c: Controller) -> list[Term]:
    """The geometric numbers a drive controller turns with, each with its multiplier."""
    p = dict(c.params)
    kin = p.get("kinematics")
    if isinstance(kin, dict):       # ros2_controllers' mecanum_drive_controller nests them
        p.update({f"kinematics.{k}": v for k, v in kin.items()})
    kind = _controller_kind(c.type)
    out = [_term(p, "radius", RADIUS_KEYS, RADIUS_MULT)]
    if kind == "differential":
        out.append(_term(p, "track", ("wheel_separation",), ("wheel_separation_multiplier",)))
    else:
        out.append(_term(p, "wheelbase", ("wheel_separation_x", "wheelbase", "wheel_base"),
                         ("wheel_separation_multiplier_x", "wheel_separation_multiplier")))
        out.append(_term(p, "track", ("wheel_separation_y", "traction_track_width", "rear_wheel_track", "wheel_track",
                                      "track_width"),
                         ("wheel_separation_multiplier_y", "wheel_separation_multiplier")))
        out.append(_term(p, "kingpin", ("steering_track_width", "front_wheel_track")))
        out.append(_term(p, "half_sum", ("kinematics.sum_of_robot_center_projection_on_X_Y_axis",)))
    return [t for t in out if t is not None]


def controller_numbers(c: Controller) -> tuple[float | None, float | None, float | None]:
    """(wheelbase, track, wheel radius) the controller turns with, its multipliers applied."""
    got = {t.what: t.value for t in controller_terms(c)}
    return got.get("wheelbase"), got.get("track"), got.get("radius")


# gz-sim MecanumDrive / AckermannSteering and Gazebo classic gazebo_ros_ackermann_drive: each
# geometric parameter with the default the system uses when it is not written (read from gz-sim's
# MecanumDrive.cc, AckermannSteering.cc and gazebo_ros_pkgs' gazebo_ros_ackermann_drive.cpp; the
# classic plugin measures its wheelbase, track and radius on the model itself).
PLUGIN_TERMS = {
    ("gz", "mecanum"): (("track", "wheel_separation", 1.0), ("wheelbase", "wheelbase", 1.0),
                        ("radius", "wheel_radius", 0.2)),
    ("gz", "ackermann"): (("wheelbase", "wheel_base", 1.0), ("track", "wheel_separation", 1.0),
                          ("kingpin", "kingpin_width", 0.8), ("radius", "wheel_radius", 0.2),
                          ("steer_limit", "steering_limit", 0.5)),
    ("classic", "ackermann"): (("steer_limit", "max_steer", 0.6),),
}


def plugin_terms(p) -> list[Term]:
    """The geometric numbers a mecanum or Ackermann plugin drives with (its defaults where a key
    is not written); [] for any other plugin."""
    kind = plugin_kind(p)
    table = PLUGIN_TERMS.get(("gz" if p.dialect == "gz" else "classic", kind or ""), ())
    steering_only = kind == "ackermann" and V.boolean(p.text("steering_only"), False)
    out = []
    for what, key, default in table:
        if steering_only and what in ("radius", "kingpin"):
            continue          # AckermannSteering reads them only when it drives the wheels
        v, ok = number(p, key)
        if not ok:
            continue          # not a number: the plugin fails on it, nothing to compare
        out.append(Term(what, key, default, default=True) if v is None else Term(what, key, v))
    return out


class Declared(Struct):
    """A number a drive's controller or plugin declares about the base, beside the URDF's."""

    term: Term
    urdf: float                       # the same quantity measured on the URDF
    owner: object                     # the Controller or the Plugin
    source: str                       # 'controller' | 'plugin'


def kingpin_width(robot, b: "Base") -> float | None:
    """The distance between the steering axes (left to right) on the URDF, in the root frame."""
    if not b.steering:
        return None
    T = link_transforms(robot)
    return _spread(_axis_and_origin(robot, robot.joints[n], T)[1][1] for n in b.steering)


def declared(robot) -> list[Declared]:
    """Every geometric number the base's controllers and mecanum/Ackermann plugins drive with, with
    its URDF counterpart (``base``'s wheelbase, track, wheel radius and steering lock, the steering
    axes' spread): what check's G016-G018 compare. Numbers with no URDF counterpart are left out."""
    def build():
        b = base(robot)
        if b is None:
            return ()
        urdf = {"wheelbase": b.wheelbase, "track": b.track, "radius": b.radius, "steer_limit": b.steer_limit,
                "kingpin": kingpin_width(robot, b),
                "half_sum": (b.wheelbase + b.track) / 2 if b.wheelbase and b.track else None}
        out = []
        for c in controllers(robot):
            out += [Declared(t, urdf[t.what], c, "controller") for t in controller_terms(c)
                    if urdf.get(t.what)]
        for p in robot.plugins():
            out += [Declared(t, urdf[t.what], p, "plugin") for t in plugin_terms(p) if urdf.get(t.what)]
        return tuple(out)
    return list(robot.derive("drive.declared", build))


def _axis_and_origin(robot, j, T):
    if j.parent not in T:
        return None, None
    R, p = compose(T[j.parent], pose_T(j.origin))
    return _unit(rotate(R, j.axis)), p


def _free(j) -> bool:
    lim = j.limit
    return j.type == "continuous" or (lim is not None and lim.lower is not None and lim.upper is not None
                                       and lim.upper - lim.lower >= FULL_TURN)


def _spins(robot, j, T) -> bool:
    """A joint that rolls a wheel: moving about a lateral axis, turning freely, and named like a
    wheel or carrying a round shape about its axis (an arm's pitch joint is neither)."""
    if j.type not in ("continuous", "revolute") or not _free(j):
        return False
    a, _ = _axis_and_origin(robot, j, T)
    if a is None or abs(a[2]) > LEVEL:
        return False
    if "wheel" in j.name.lower() or "wheel" in j.child.lower():
        return True
    w = wheel(robot, j.name, T, read_meshes=False)
    return w is not None and w.round


def _steering(robot, T, wheels: set, commanded_pos: set) -> list[str]:
    """Joints about a vertical axis that carry a wheel, or that ros2_control commands in position
    beside velocity wheels (a virtual bicycle joint), and the joints that mimic those."""
    if not wheels:
        return []       # both reasons need a wheel: no joint's frame is worth computing
    children = robot.joints_by_parent()
    out = []
    for j in robot.joints.values():
        if j.type not in ("continuous", "revolute") or j.mimic is not None:
            continue
        a, _ = _axis_and_origin(robot, j, T)
        if a is None or abs(a[2]) < VERTICAL:
            continue
        carries = any(c.name in wheels for c in children.get(j.child, []))
        if carries or (j.name in commanded_pos and wheels):
            out.append(j.name)
    for j in robot.joints.values():
        if j.mimic is not None and j.mimic.joint in out and j.name not in out:
            out.append(j.name)
    return out


def joint_position(robot, name: str):
    """Where a joint sits in the root frame at q = 0 (its origin), None when it hangs off no root."""
    j = robot.joints.get(name)
    return None if j is None else _axis_and_origin(robot, j, link_transforms(robot))[1]


def joint_turn_sign(robot, name: str) -> float:
    """+1 if a positive angle of a (steering) joint turns what it carries to the left (its axis along
    the root frame's +z), -1 if along -z."""
    j = robot.joints.get(name)
    a = None if j is None else _axis_and_origin(robot, j, link_transforms(robot))[0]
    return -1.0 if a is not None and a[2] < 0 else 1.0


def _spread(values) -> float | None:
    vals = list(values)
    return max(vals) - min(vals) if len(vals) > 1 else None


def _locks(robot, names) -> list[tuple[float, str]]:
    """(steering lock in rad each way, joint) of the joints that do not turn freely."""
    out = []
    for n in names:
        j = robot.joints[n]
        if _free(j) or j.limit is None or j.limit.lower is None or j.limit.upper is None:
            continue
        out.append((min(abs(j.limit.lower), abs(j.limit.upper)), n))
    return out


def _limit(robot, names) -> float | None:
    """The smallest steering lock (rad each way) of the joints; None when they turn freely."""
    locks = _locks(robot, names)
    return min(locks)[0] if locks else None


def steering_stop(robot, b: "Base") -> str | None:
    """The steering joint whose limit is the base's steering lock (the first to stop)."""
    locks = _locks(robot, b.steering)
    return min(locks)[1] if locks else None


def plugin_kind(p) -> str | None:
    lib = (p.library or "").lower() + " " + (p.name or "").lower().replace("::", "")
    if any(s in lib for s in PLANAR_LIBS):
        return "planar"
    if "mecanum" in lib:
        return "mecanum"
    if "ackermann" in lib:
        return "ackermann"
    return None


def base(robot) -> Base | None:
    """How the robot's base moves (see the section comment), None for a robot that does not move
    on wheels or a body-velocity plugin. Built once per robot."""
    return robot.derive("drive.base", lambda: _base(robot))


def _base(robot) -> Base | None:
    T = link_transforms(robot)
    declared = main_drive(robot)
    pos = set(position_joints(robot))
    vel, _ = velocity_joints(robot)
    spinning = [j.name for j in robot.joints.values() if _spins(robot, j, T)]
    spinning += [n for n in vel if n not in spinning and n in robot.joints and _spins(robot, robot.joints[n], T)]
    for j in robot.joints.values():     # wheels that mimic a driven (virtual) wheel
        if j.mimic is not None and j.mimic.joint in spinning and j.name not in spinning:
            spinning.append(j.name)
    steering = _steering(robot, T, set(spinning), pos)
    on_modules = {c.name for n in steering for c in robot.joints_by_parent().get(robot.joints[n].child, [])}
    on_base = [n for n in spinning if n not in on_modules and n not in steering]
    if steering and on_base and \
            any(w in n.lower() for n in steering for w in ("caster", "castor", "swivel")):
        steering = []       # passive casters beside wheels on the base (PMB2, Pioneer 3-DX)
    if declared is not None and declared.left and declared.right and not set(declared.joints) & on_modules:
        steering = []       # a declared drive whose wheels sit on the base: the vertical joints are casters

    ctrl = next(iter(controllers(robot)), None)
    plugin = next((p for p in robot.plugins() if plugin_kind(p)), None)
    kind, why = None, None
    if ctrl is not None:
        kind, why = _controller_kind(ctrl.type), f"ros2_control {ctrl.type} ({ctrl.file.rsplit('/', 1)[-1]})"
    elif plugin is not None:
        kind, why = plugin_kind(plugin), f"plugin {plugin.library or plugin.name}"
        if kind == "planar" and len(spinning) >= 4 and not steering:
            # a body-velocity/force plugin over wheels that spin: the wheels are mecanum, the plugin
            # does what their rollers would (Ridgeback: "movement is handled by applying forces")
            kind, why = "mecanum", why + " over spinning wheels"
    elif steering:
        front = {round(_axis_and_origin(robot, robot.joints[n], T)[1][0], 3) for n in steering}
        kind = "swerve" if len(front) > 1 else "ackermann"
        why = "steered wheels on the URDF"
    elif declared is not None and declared.left and declared.right:
        kind, why = ("skid_steer" if declared.skid else "differential"), declared.label
    if kind is None:
        g = guess_drive(robot)
        if g is None:       # wheels recognised by shape alone (a cylinder about a level axle), sided by place
            left, right = _sided(robot, [n for n in wheel_joints(robot) if robot.joints[n].type == "continuous"], T)
            g = Drive("guess", "continuous joints shaped like wheels", left, right, loc=robot.loc) \
                if left and right else None
        if g is None:
            return None
        kind, why, declared = ("skid_steer" if g.skid else "differential"), g.label, g
    if kind == "differential" and declared is not None and declared.skid:
        kind = "skid_steer"

    # the wheels that drive it: the declared drive's, else those that spin (planar: named like wheels)
    if kind == "planar":
        wheels = [j.name for j in robot.joints.values() if "wheel" in j.name.lower()
                  and "caster" not in j.name.lower() and "castor" not in j.name.lower()]
    elif declared is not None and declared.joints and kind in ("differential", "skid_steer", "mecanum", "omni"):
        wheels = [n for n in declared.joints if n in robot.joints]
    else:
        wheels = [n for n in spinning if n not in steering]
    wheels = tuple(wheels)
    ws = [w for w in (wheel(robot, n, T) for n in wheels) if w is not None]
    radii = [w.radius for w in ws if w.radius is not None and w.radius > 1e-6]
    radius = sum(radii) / len(radii) if radii else None
    sxy = [_axis_and_origin(robot, robot.joints[n], T)[1] for n in steering]
    if kind == "swerve":
        wheelbase = _spread(p[0] for p in sxy)
        track = _spread(p[1] for p in sxy)
    elif kind == "ackermann":
        steered_links = {robot.joints[n].child for n in steering}
        rear = [w for w in ws if robot.joints[w.joint].parent not in steered_links]
        steer_x = sum(p[0] for p in sxy) / len(sxy) if sxy else None
        rear_x = sum(w.origin[0] for w in rear) / len(rear) if rear else None
        wheelbase = abs(steer_x - rear_x) if steer_x is not None and rear_x is not None else None
        track = _spread(w.origin[1] for w in rear)
    else:
        wheelbase = _spread(w.origin[0] for w in ws)
        sided = declared is not None and declared.left and declared.right and kind != "planar"
        track = measure(robot, declared).separation if sided else _spread(w.origin[1] for w in ws)
    cb, ct, cr = controller_numbers(ctrl) if ctrl is not None else (None, None, None)
    src = plugin if plugin is not None and ctrl is None else (declared.plugin if declared is not None else None)
    loc = (src.loc if src is not None else None) or (declared.loc if declared is not None else None) \
        or (robot.joints[(wheels or tuple(steering))[0]].loc if (wheels or steering) else robot.loc)
    return Base(kind, why, wheels, tuple(steering), wheelbase, track, radius,
                _limit(robot, steering) if steering else None,
                declared if kind in ("differential", "skid_steer", "mecanum", "omni") else None,
                plugin, ctrl, cb, ct, cr, loc)


# ------------------------------------------------------------------ mecanum wheels' contact
# A simulator has no rollers unless the URDF models them as links: a mecanum wheel is a plain
# cylinder whose contact friction is made anisotropic (gz-sim's mecanum example, ROSbot XL): ``mu``
# along ``fdir1`` at 45° to the axle, ``mu2`` 0 across it, so the contact pushes only along fdir1,
# as a wheel whose rollers turn freely across that direction. The twist such contacts give for a
# commanded one is measurable on the URDF: the least-squares body twist under each wheel's
# constraints (surface speeds from the mecanum inverse kinematics).
FRICTION_DEFAULT = 1.0      # sdformat's <ode><mu>/<mu2> and Gazebo classic's mu1/mu2 when not written


class Contact(Struct):
    """A wheel link's friction as the simulator reads it: ``mu`` along ``fdir1`` (root frame, unit,
    None when not given: then both coefficients act in every direction), ``mu2`` across it."""

    link: str
    mu: float
    mu2: float
    fdir1: tuple[float, float, float] | None
    written: str                      # 'sdf' (<collision><surface>...), 'classic' (mu1/mu2/fdir1) or 'default'


def _collision_rotation(robot, link: str, T):
    R, _ = T.get(link, IDENTITY)
    cols = robot.links[link].collisions if link in robot.links else ()
    return compose((R, (0.0, 0.0, 0.0)), pose_T(cols[0].origin))[0] if cols else R


def wheel_contact(robot, link: str, T=None) -> Contact:
    """The contact friction of a wheel link: a ``<gazebo reference>`` block's SDF
    ``<collision><surface><friction><ode>`` (``fdir1`` in the collision frame, or the frame its
    ``expressed_in`` names), else its classic ``mu1``/``mu2``/``fdir1`` (collision frame), else the
    defaults (1, 1, no direction)."""
    T = T if T is not None else link_transforms(robot)
    for g in robot.gazebo:
        if g.reference != link:
            continue
        ode = g.node.find("collision", "surface", "friction", "ode")
        if ode is not None and (ode.child("mu") is not None or ode.child("mu2") is not None):
            f = ode.child("fdir1")
            vec = ode.vector("fdir1", n=3)
            frame = next((v for k, v in f.attrs if k.rsplit("}", 1)[-1] == "expressed_in"), None) if f else None
            R = T[frame][0] if frame in T else _collision_rotation(robot, link, T)
            mu, mu2 = (ode.number(k, default=FRICTION_DEFAULT) for k in ("mu", "mu2"))
            return Contact(link, mu, mu2, _unit(rotate(R, vec)) if vec else None, "sdf")
        v = g.values
        if "mu1" in v or "mu2" in v:
            vec = v.get("fdir1")
            R = _collision_rotation(robot, link, T)
            # an unreadable value is T010 (the loader's); here the default keeps the rest judged
            mu1, mu2 = (float(v[k]) if isinstance(v.get(k), (int, float)) else FRICTION_DEFAULT for k in ("mu1", "mu2"))
            return Contact(link, mu1, mu2,
                           _unit(rotate(R, vec)) if vec else None, "classic")
    return Contact(link, FRICTION_DEFAULT, FRICTION_DEFAULT, None, "default")


class RollerResponse(Struct):
    """What a mecanum base driven by its wheels does for unit commands, given its wheels' contact:
    achieved (vx, vy, ωz) for a forward (vx 1), a sideways (vy 1) and a turning (ωz 1) command."""

    contacts: tuple[Contact, ...]
    forward: tuple[float, float, float]
    sideways: tuple[float, float, float]
    turn: tuple[float, float, float]


def _solve3(A, b):
    """x of the 3×3 normal equations A x = b (Cramer), None when A is zero."""
    def det(M):
        return (M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0])
                + M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]))
    scale = (abs(A[0][0]) + abs(A[1][1]) + abs(A[2][2])) / 3
    if scale == 0:
        return None
    # a tiny ridge: a direction no contact holds gets 0 (the minimum-norm least-squares answer: the
    # wheels do not move the base that way) instead of a division by a rounding error
    A = [[A[i][k] + (1e-9 * scale if i == k else 0.0) for k in range(3)] for i in range(3)]
    d = det(A)
    out = []
    for k in range(3):
        M = [list(r) for r in A]
        for i in range(3):
            M[i][k] = b[i]
        out.append(det(M) / d)
    return tuple(out)


def roller_response(robot) -> RollerResponse | None:
    """The twist the wheels' contacts give a mecanum base driven wheel by wheel (a mecanum
    controller or plugin; a body-force plugin moves the body itself: None), for unit commands."""
    def build():
        b = base(robot)
        if b is None or b.kind != "mecanum" or len(b.wheels) != 4:
            return None
        if b.controller is None and (b.plugin is None or plugin_kind(b.plugin) != "mecanum"):
            return None
        T = link_transforms(robot)
        ws = [wheel(robot, n, T, read_meshes=False) for n in b.wheels]
        if any(w is None for w in ws) or len({(w.origin[0] > 0, w.origin[1] > 0) for w in ws}) != 4:
            return None         # four wheels, one at each corner
        children = robot.joints_by_parent()
        if any(c.type != "fixed" for w in ws for c in children.get(robot.joints[w.joint].child, [])):
            return None         # rollers modelled as links: the physics rolls them
        cx = sum(w.origin[0] for w in ws) / 4
        cy = sum(w.origin[1] for w in ws) / 4
        L = (_spread(w.origin[0] for w in ws) + _spread(w.origin[1] for w in ws)) / 2
        contacts = tuple(wheel_contact(robot, robot.joints[w.joint].child, T) for w in ws)
        rows = []       # (direction in the plane, wheel index)
        for i, c in enumerate(contacts):
            if c.mu > 0 and c.mu2 > 0 or c.fdir1 is None:
                if c.mu > 0 or c.mu2 > 0:
                    rows += [((1.0, 0.0), i), ((0.0, 1.0), i)]
            else:
                f = c.fdir1 if c.mu > 0 else (-c.fdir1[1], c.fdir1[0], 0.0)   # the direction that grips
                d = _unit((f[0], f[1], 0.0))
                if d is not None:
                    rows.append(((d[0], d[1]), i))

        def achieved(cmd):
            vx, vy, wz = cmd
            A = [[0.0] * 3 for _ in range(3)]
            rhs = [0.0] * 3
            for (dx, dy), i in rows:
                x, y = ws[i].origin[0] - cx, ws[i].origin[1] - cy
                s = vx - math.copysign(1.0, x * y) * vy - math.copysign(1.0, y) * L * wz   # surface speed
                row = (dx, dy, -y * dx + x * dy)
                target = s * dx                   # the wheel's surface moves along x
                for p in range(3):
                    rhs[p] += row[p] * target
                    for q in range(3):
                        A[p][q] += row[p] * row[q]
            return _solve3(A, rhs)

        got = [achieved(c) for c in ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))]
        if any(g is None for g in got):
            return None         # the contacts do not hold the base (frictionless wheels)
        return RollerResponse(contacts, *got)
    return robot.derive("drive.roller_response", build)
