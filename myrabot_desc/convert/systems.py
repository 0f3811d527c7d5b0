"""Model-level plugins → gz-sim systems.

- diff-drive plugins (Electric Create/Roomba, classic ROS 1 ``wheelSeparation``/``wheelDiameter``,
  ROS 2 ``wheel_separation``/``wheel_diameter``, gz ``DiffDrive``) → ``gz-sim-diff-drive-system``
  with the separation and radius measured on the URDF's wheels (anchors §6.4);
- joint states → ``gz-sim-joint-state-publisher-system``;
- arm joints → one ``gz-sim-joint-position-controller-system`` each;
- IMU controllers → an ``imu`` sensor (returned to the caller);
- gz-sim systems already in the file are kept; anything else becomes an XML comment.
"""

from __future__ import annotations

import copy
import math

from lxml import etree

from myrabot_desc.convert.common import local, num, sub, to_bool, to_float, xml_text
from myrabot_desc.convert.sensors import (
    imu_from_plugin,
    plugin_kind,
    pparam,
    ros_namespace,
    ros_remap,
)
from myrabot_desc.model.transforms import IDENTITY, compose, pose_T, rotate

DIFF_DRIVE = ("gz-sim-diff-drive-system", "gz::sim::systems::DiffDrive")
JOINT_STATES = ("gz-sim-joint-state-publisher-system", "gz::sim::systems::JointStatePublisher")
POSITION = ("gz-sim-joint-position-controller-system", "gz::sim::systems::JointPositionController")


def link_transforms(robot):
    """World transform of every link at q = 0 (joint origins only)."""
    out = {}
    todo = list(robot.roots)
    for r in todo:
        out[r] = IDENTITY
    children = robot.joints_by_parent()
    while todo:
        link = todo.pop()
        for j in children.get(link, []):
            if j.child in out:
                continue
            out[j.child] = compose(out[link], pose_T(j.origin))
            todo.append(j.child)
    return out


def wheel_radius(robot, joint_name):
    """Radius of the wheel driven by this joint: its first cylinder/sphere collision (or visual)."""
    j = robot.joints.get(joint_name)
    if j is None:
        return None
    link = robot.links.get(j.child)
    if link is None:
        return None
    for geo in [c.geometry for c in link.collisions] + [v.geometry for v in link.visuals]:
        if geo is not None and getattr(geo, "kind", None) in ("cylinder", "sphere"):
            return geo.radius
    return None


def wheel_separation(robot, left, right, transforms):
    """Distance between the two wheel joints along the left wheel's axis (the track width)."""
    jl, jr = robot.joints.get(left), robot.joints.get(right)
    if jl is None or jr is None or jl.parent not in transforms or jr.parent not in transforms:
        return None
    Rl, pl = compose(transforms[jl.parent], pose_T(jl.origin))
    _, pr = compose(transforms[jr.parent], pose_T(jr.origin))
    axis = rotate(Rl, [float(v) for v in jl.axis])
    n = math.hypot(*axis)
    d = [pl[k] - pr[k] for k in range(3)]
    if n < 1e-9:
        return math.hypot(*d)
    return abs(sum(d[k] * axis[k] for k in range(3)) / n)


class Systems:
    def __init__(self, robot, model_name, notes):
        self.robot = robot
        self.model_name = model_name
        self.notes = notes
        self.elements: list = []         # <plugin> elements and comments, in order
        self.sensors: list = []          # SensorOut from IMU controllers
        self.unknown: list[str] = []
        self.wants_joint_states = False
        self.drive_joints: set[str] = set()
        self.has_control = False

    # ------------------------------------------------------------ entry
    def translate(self, plugins) -> None:
        for p in plugins:
            kind = plugin_kind(p)
            if kind == "imu":
                out = imu_from_plugin(p, self.robot, self.notes)
                if out is not None:
                    self.sensors.append(out)
                self.has_control = True
            elif kind in ("diff_drive", "skid_steer"):
                self._diff_drive(p, kind)
            elif kind == "joint_state":
                self.wants_joint_states = True
                self.has_control = True
            elif kind == "ros_control":
                self.wants_joint_states = True
                self.has_control = True
                self.elements.append(("comment", f"{p.library or p.name}: ros_control is replaced by gz-sim "
                                                 "joint position controllers and the joint state publisher"))
            elif kind == "gz":
                self.elements.append(("comment", f"kept from the source ({p.loc})" if p.loc else "kept from the source"))
                el = copy.deepcopy(p.element)
                self.elements.append(("plugin", el))
                self.has_control = True
            else:
                self.unknown.append(f"{p.name or '?'} ({p.library or local(p.element.tag)})")
                self.elements.append(("comment", f"not converted (no gz-sim equivalent known): {xml_text(p.element)}"))
        self._arm()
        if self.wants_joint_states:
            el = etree.Element("plugin", filename=JOINT_STATES[0], name=JOINT_STATES[1])
            sub(el, "topic", "joint_states")
            self.elements.append(("comment", "joint states (the source published /joint_states)"))
            self.elements.append(("plugin", el))
        if self.unknown:
            self.notes.warn(f"{len(self.unknown)} plugin(s) with no gz-sim equivalent kept as XML comments: "
                            + ", ".join(self.unknown))

    # ------------------------------------------------------------ diff drive
    def _diff_drive(self, p, kind):
        r = self.robot
        self.has_control = True
        if kind == "skid_steer":
            lefts = [v for v in (pparam(p, "leftFrontJoint"), pparam(p, "leftRearJoint")) if v]
            rights = [v for v in (pparam(p, "rightFrontJoint"), pparam(p, "rightRearJoint")) if v]
        else:
            lefts = [c.text.strip() for c in p.element if local(c.tag) in ("left_joint", "leftJoint",
                                                                           "left_wheel_joint") and c.text]
            rights = [c.text.strip() for c in p.element if local(c.tag) in ("right_joint", "rightJoint",
                                                                             "right_wheel_joint") and c.text]
        missing = [j for j in lefts + rights if j not in r.joints]
        if not lefts or not rights or missing:
            self.notes.warn(f"diff-drive plugin '{p.name}': wheel joints {missing or 'not given'} not found; "
                            "kept as a comment", p.loc)
            self.unknown.append(f"{p.name} ({p.library})")
            self.elements.append(("comment", f"not converted (wheel joints missing): {xml_text(p.element)}"))
            return
        self.drive_joints.update(lefts + rights)
        # what the plugin itself says
        sep_said = to_float(pparam(p, "wheel_separation", "wheelSeparation"))
        diam_said = to_float(pparam(p, "wheel_diameter", "wheelDiameter"))
        rad_said = to_float(pparam(p, "wheel_radius"), diam_said / 2 if diam_said else None)
        T = link_transforms(r)
        sep = wheel_separation(r, lefts[0], rights[0], T)
        rad = wheel_radius(r, lefts[0])
        src = []
        if sep is None:
            sep = sep_said
            src.append("separation from the plugin")
        if rad is None:
            rad = rad_said
            src.append("radius from the plugin (the wheel has no cylinder or sphere)")
        if sep is None or rad is None:
            self.notes.warn(f"diff-drive plugin '{p.name}': cannot tell the wheel separation/radius; kept as a "
                            "comment", p.loc)
            self.elements.append(("comment", f"not converted: {xml_text(p.element)}"))
            return
        for what, said, got in (("wheel_separation", sep_said, sep), ("wheel_radius", rad_said, rad)):
            if said is not None and abs(said - got) > 5e-4:
                self.notes.warn(f"diff-drive '{p.name}': the plugin says {what} {num(said)} m but the URDF's "
                                f"wheels give {num(got)} m; using the URDF", p.loc)
        ns = pparam(p, "robotNamespace")
        ns = None if ns in (None, "/") else ns.strip("/")
        ns = ns or ros_namespace(p)
        cmd = (pparam(p, "commandTopic", "command_topic") or ros_remap(p, "cmd_vel", "/cmd_vel") or "cmd_vel")
        odom = (pparam(p, "odometryTopic", "odometry_topic") or ros_remap(p, "odom", "/odom") or "odom")
        if ns and not cmd.startswith("/"):
            cmd, odom = f"{ns}/{cmd}", (odom if odom.startswith("/") else f"{ns}/{odom}")
        rate = to_float(pparam(p, "updateRate", "update_rate", "odom_publish_frequency"))
        el = etree.Element("plugin", filename=DIFF_DRIVE[0], name=DIFF_DRIVE[1])
        for j in lefts:
            sub(el, "left_joint", j)
        for j in rights:
            sub(el, "right_joint", j)
        sub(el, "wheel_separation", round(sep, 9))
        sub(el, "wheel_radius", round(rad, 9))
        sub(el, "topic", cmd)
        sub(el, "odom_topic", odom)
        sub(el, "frame_id", pparam(p, "odometryFrame", "odometry_frame") or "odom")
        sub(el, "child_frame_id", pparam(p, "robotBaseFrame", "robot_base_frame") or (r.root or "base_link"))
        if rate:
            sub(el, "odom_publish_frequency", rate)
        acc = to_float(pparam(p, "wheelAcceleration", "max_wheel_acceleration"))
        if acc:
            # gz limits the vehicle, not the wheel: a = alpha * r (anchors §6.4)
            sub(el, "max_linear_acceleration", acc * rad)
            sub(el, "min_linear_acceleration", -acc * rad)
        note = (f"from '{p.name}' ({p.library or local(p.element.tag)}): wheel_separation and wheel_radius "
                f"measured on the URDF ({lefts[0]}/{rights[0]})")
        if src:
            note += "; " + "; ".join(src)
        nn = pparam(p, "node_namespace")
        if nn:
            note += (f"; the Electric plugin listened on {nn}/cmd_vel while the seed's programs publish cmd_vel: "
                     "cmd_vel is used")
        self.elements.append(("comment", note))
        self.elements.append(("plugin", el))
        # Create/Roomba and the classic plugin with publishWheelJointState publish joint states
        if kind == "diff_drive" and (p.dialect == "electric" or "roomba" in _lib(p) or "create" in _lib(p)
                                     or to_bool(pparam(p, "publishWheelJointState", "publish_wheel_joint_state"))):
            self.wants_joint_states = True

    # ------------------------------------------------------------ arm joints
    def _arm(self):
        r = self.robot
        joints = []
        for t in r.transmissions:
            joints.extend(j for j in t.joints if j not in joints)
        source = "transmission"
        if not joints and self.has_control:
            source = "limits"
            joints = [j.name for j in r.joints.values()
                      if j.type in ("revolute", "prismatic") and j.limit is not None and j.mimic is None
                      and j.limit.lower is not None and j.limit.upper is not None and j.limit.upper > j.limit.lower]
        joints = [n for n in joints if n in r.joints and n not in self.drive_joints
                  and r.joints[n].type in ("revolute", "prismatic", "continuous") and r.joints[n].mimic is None]
        if not joints:
            return
        self.wants_joint_states = True
        self.elements.append(("comment", f"position controllers for the {len(joints)} arm joint(s) "
                                         f"({'from the transmissions' if source == 'transmission' else 'revolute/prismatic with limits'}); "
                                         "command topic /model/<model>/joint/<joint>/0/cmd_pos"))
        for name in joints:
            j = r.joints[name]
            el = etree.Element("plugin", filename=POSITION[0], name=POSITION[1])
            sub(el, "joint_name", name)
            sub(el, "topic", f"/model/{self.model_name}/joint/{name}/0/cmd_pos")
            effort = j.limit.effort if j.limit and j.limit.effort else None
            if effort:
                # full effort at 0.1 rad (or m) of error; damping a tenth of that
                sub(el, "p_gain", effort / 0.1)
                sub(el, "i_gain", 0)
                sub(el, "d_gain", effort / 1.0)
                sub(el, "cmd_max", effort)
                sub(el, "cmd_min", -effort)
            else:
                sub(el, "p_gain", 1)
                sub(el, "d_gain", 0.1)
            if j.limit and j.limit.lower is not None and j.limit.upper is not None and j.limit.lower > 0:
                sub(el, "initial_position", j.limit.lower)
            elif j.limit and j.limit.upper is not None and j.limit.upper < 0:
                sub(el, "initial_position", j.limit.upper)
            self.elements.append(("plugin", el))


def _lib(p) -> str:
    return ((p.filename or "") + " " + (local(p.element.tag) if p.element is not None else "")).lower()
