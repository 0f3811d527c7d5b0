"""Model-level plugins → gz-sim systems.

- the base's kind (model/drive.base) → the gz-sim system that drives it: mecanum wheels →
  ``gz-sim-mecanum-drive-system`` (frictionless wheels, moved by a body force in the source →
  ``gz-sim-velocity-control-system``), a planar body-velocity plugin → VelocityControl, Ackermann
  steering → ``gz-sim-ackermann-steering-system``; swerve has no system here: velocity controllers on
  its wheels and position controllers on its steering joints, and the report says so. No DiffDrive
  is put on wheels that are not a differential pair;
- every other drive the drive model recognises → ``gz-sim-diff-drive-system`` with the
  separation and radius measured on the URDF's wheels (anchors §6.4): two-wheel plugins of every
  dialect, skid-steer bases as a DiffDrive over both wheel pairs, and ros_control / ros2_control
  velocity wheels that stand on both sides of the base;
- other velocity-interface joints → one ``gz-sim-joint-controller-system`` (velocity) each;
- joint states → ``gz-sim-joint-state-publisher-system``;
- arm joints → one ``gz-sim-joint-position-controller-system`` each (never on a velocity joint);
- IMU controllers → an ``imu`` sensor (returned to the caller), unless the link already has one;
- gz-sim systems already in the file are kept; anything else becomes an XML comment.
"""

from __future__ import annotations

from lxml import etree

from myrabot_desc.convert.common import element_of, num, sub, xml_text
from myrabot_desc.convert.sensors import imu_from_plugin, imu_sensor_on
from myrabot_desc.model import drive as D
from myrabot_desc.model import plugins as P
from myrabot_desc.model import values as V

DIFF_DRIVE = ("gz-sim-diff-drive-system", "gz::sim::systems::DiffDrive")
JOINT_STATES = ("gz-sim-joint-state-publisher-system", "gz::sim::systems::JointStatePublisher")
POSITION = ("gz-sim-joint-position-controller-system", "gz::sim::systems::JointPositionController")
VELOCITY = ("gz-sim-joint-controller-system", "gz::sim::systems::JointController")
# gz-sim systems and their parameters (gz-sim MecanumDrive.hh, AckermannSteering.hh, VelocityControl.hh)
MECANUM = ("gz-sim-mecanum-drive-system", "gz::sim::systems::MecanumDrive")
ACKERMANN = ("gz-sim-ackermann-steering-system", "gz::sim::systems::AckermannSteering")
BODY_VELOCITY = ("gz-sim-velocity-control-system", "gz::sim::systems::VelocityControl")
DIFF_KINDS = ("differential", "skid_steer")


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
        self.base = D.base(robot)
        self.replaced: dict[int, str] = {}      # id(plugin) -> what the base's system replaced it with
        self.drive_fate: tuple[str, str] | None = None   # (fate, detail) of the base's kind, for the report

    # ------------------------------------------------------------ entry
    def translate(self, plugins) -> None:
        drives = {id(d.plugin): d for d in D.plugin_drives(self.robot)}
        self._base_system(plugins)
        for p in plugins:
            kind = P.kind(p)
            if id(p) in self.replaced:
                self.elements.append(("comment", f"{p.name or '?'} ({p.library or p.tag}): replaced by "
                                                 f"{self.replaced[id(p)]}: {xml_text(p.node)}"))
            elif id(p) in drives and set(drives[id(p)].joints) & self.drive_joints:
                self.replaced[id(p)] = "the base's own system (its wheels are not a differential pair)"
                self.elements.append(("comment", f"not converted (the base is {self.base.kind}, not a diff drive): "
                                                 f"{xml_text(p.node)}"))
            elif id(p) in drives:
                self._diff_drive(p, drives[id(p)])
            elif kind == "imu":
                merged = imu_sensor_on(p, self.robot)
                if merged is not None:
                    self.elements.append(("comment", f"IMU plugin '{p.name}' ({p.library or p.tag}): "
                                                     f"folded into the imu sensor '{merged}' of its link"))
                else:
                    out = imu_from_plugin(p, self.robot, self.notes)
                    if out is not None:
                        self.sensors.append(out)
                self.has_control = True
            elif kind in ("diff_drive", "skid_steer"):
                self.unknown.append(f"{p.name or '?'} ({p.library or p.tag})")
                self.elements.append(("comment", f"not converted (a drive plugin whose parameters are not known): "
                                                 f"{xml_text(p.node)}"))
            elif kind == "joint_state":
                self.wants_joint_states = True
                self.has_control = True
            elif kind == "ros_control":
                self.wants_joint_states = True
                self.has_control = True
                self.elements.append(("comment", f"{p.library or p.name}: ros_control is replaced by gz-sim "
                                                 "systems for the joints it commands (below) and the joint state "
                                                 "publisher"))
            elif kind == "gz":
                self.elements.append(("comment", f"kept from the source ({p.loc})" if p.loc else "kept from the source"))
                el = element_of(p.node)
                el.tail = p.node.tail
                self.elements.append(("plugin", el))
                self.has_control = True
            else:
                self.unknown.append(f"{p.name or '?'} ({p.library or p.tag})")
                self.elements.append(("comment", f"not converted (no gz-sim equivalent known): {xml_text(p.node)}"))
        self._velocity_wheels()
        self._arm()
        if self.wants_joint_states:
            el = etree.Element("plugin", filename=JOINT_STATES[0], name=JOINT_STATES[1])
            sub(el, "topic", "joint_states")
            self.elements.append(("comment", "joint states (the source published /joint_states)"))
            self.elements.append(("plugin", el))
        if self.unknown:
            self.notes.warn(f"{len(self.unknown)} plugin(s) with no gz-sim equivalent kept as XML comments: "
                            + ", ".join(self.unknown))

    # ------------------------------------------------------------ the base's kind
    def _base_system(self, plugins) -> None:
        """The gz-sim system for a base that is not a differential pair (mecanum, planar, Ackermann;
        swerve: said so, its joints get controllers below)."""
        b = self.base
        if b is None or b.kind in DIFF_KINDS:
            return
        kept = [p for p in plugins if P.kind(p) == "gz" and D.plugin_kind(p) == b.kind]
        if kept:        # the source already names the gz-sim system (VelocityControl...): kept as it is
            self.drive_fate = ("kept", f"{b.kind}: the source's own gz-sim system {kept[0].library}")
            return
        source = [p for p in plugins if D.plugin_kind(p) is not None]
        if b.kind in ("mecanum", "omni"):
            corners = self._corners(b)
            if corners is None or self._frictionless(b):
                why = ("its wheels are frictionless (mu1 = mu2 = 0): the source moves the body, not the wheels"
                       if corners is not None else "its wheels are not four corners")
                self._velocity_control(b, f"a {b.kind} base; {why}", source)
            else:
                self._mecanum(b, corners, source)
        elif b.kind == "planar":
            self._velocity_control(b, "a planar base moved as a body", source)
        elif b.kind == "ackermann":
            self._ackermann(b, source)
        elif b.kind == "swerve":
            self.drive_fate = ("approximated", "swerve: no gz-sim system is used; each wheel gets a velocity "
                                               "JointController and each steering joint a position controller")
            self.elements.append(("comment", "a swerve base (" + ", ".join(b.steering) + "): no gz-sim swerve "
                                             "system is used; its wheels get velocity and its steering joints "
                                             "position controllers below"))
            self.notes.warn("swerve base: no gz-sim swerve system used; the wheels and steering joints get their "
                            "own joint controllers (command them per module)", b.loc)

    def _corners(self, b):
        """{front_left, front_right, back_left, back_right: [joints]} by where each wheel sits."""
        r = self.robot
        T = D.link_transforms(r)
        ws = [w for w in (D.wheel(r, n, T, read_meshes=False) for n in b.wheels) if w is not None]
        if len(ws) < 4:
            return None
        cx = sum(w.origin[0] for w in ws) / len(ws)
        out = {k: [] for k in ("front_left", "front_right", "back_left", "back_right")}
        for w in ws:
            if abs(w.origin[1]) < 1e-4 or abs(w.origin[0] - cx) < 1e-4:
                return None
            out[("front" if w.origin[0] > cx else "back") + ("_left" if w.origin[1] > 0 else "_right")].append(w.joint)
        return out if all(out.values()) else None

    def _frictionless(self, b) -> bool:
        """Every wheel link has <mu1> and <mu2> 0 in its <gazebo reference> block."""
        mus = {}
        for g in self.robot.gazebo:
            if g.reference:
                for k in ("mu1", "mu2"):
                    if isinstance(g.values.get(k), (int, float)):
                        mus.setdefault(g.reference, {})[k] = g.values[k]
        links = [self.robot.joints[n].child for n in b.wheels if n in self.robot.joints]
        return bool(links) and all(mus.get(n, {}).get("mu1") == 0 and mus.get(n, {}).get("mu2") == 0 for n in links)

    def _replace(self, source, what: str) -> None:
        for p in source:
            self.replaced[id(p)] = what

    def _velocity_control(self, b, why: str, source) -> None:
        el = etree.Element("plugin", filename=BODY_VELOCITY[0], name=BODY_VELOCITY[1])
        sub(el, "topic", "cmd_vel")
        self.has_control = True
        self.drive_joints.update(b.wheels)
        self._replace(source, "gz-sim VelocityControl")
        self.drive_fate = ("translated", f"{b.kind}: gz-sim VelocityControl ({why}; cmd_vel sets the body's twist)")
        self.elements.append(("comment", f"{why} ({b.why}): gz-sim VelocityControl sets the body's twist from "
                                         "cmd_vel; no wheel is driven"))
        self.elements.append(("plugin", el))

    def _mecanum(self, b, corners, source) -> None:
        el = etree.Element("plugin", filename=MECANUM[0], name=MECANUM[1])
        for k in ("front_left", "front_right", "back_left", "back_right"):
            for j in corners[k]:
                sub(el, f"{k}_joint", j)
        sub(el, "wheelbase", round(b.wheelbase, 9))
        sub(el, "wheel_separation", round(b.track, 9))
        sub(el, "wheel_radius", round(b.radius, 9))
        sub(el, "topic", "cmd_vel")
        sub(el, "odom_topic", "odom")
        self.has_control = True
        self.drive_joints.update(b.wheels)
        self._replace(source, "gz-sim MecanumDrive")
        note = (f"a mecanum base ({b.why}): gz-sim MecanumDrive, wheelbase {num(b.wheelbase)} m, wheel_separation "
                f"{num(b.track)} m, wheel_radius {num(b.radius)} m measured on the URDF")
        for what, said, got in (("wheelbase", b.ctrl_wheelbase, b.wheelbase), ("track", b.ctrl_track, b.track),
                                ("wheel radius", b.ctrl_radius, b.radius)):
            if said is not None and abs(said - got) > 5e-4:
                self.notes.warn(f"mecanum controller: {what} {num(said)} m but the URDF gives {num(got)} m; "
                                "using the URDF", b.loc)
        self.drive_fate = ("translated", f"mecanum: gz-sim MecanumDrive over {len(b.wheels)} wheels")
        self.elements.append(("comment", note))
        self.elements.append(("plugin", el))

    def _ackermann(self, b, source) -> None:
        r = self.robot
        y = {n: D.joint_position(r, n)[1] for n in b.wheels + b.steering if D.joint_position(r, n) is not None}
        steered = {r.joints[n].child for n in b.steering}
        drive = [n for n in b.wheels if r.joints[n].parent not in steered and abs(y.get(n, 0.0)) > 1e-4]
        left_s = [n for n in b.steering if y.get(n, 0.0) > 1e-4]
        right_s = [n for n in b.steering if y.get(n, 0.0) < -1e-4]
        left = [n for n in drive if y[n] > 0]
        right = [n for n in drive if y[n] < 0]
        if not (left and right and left_s and right_s and b.wheelbase and b.radius and b.steer_limit):
            self.drive_fate = ("dropped", "ackermann: no left and right steering joint and driven wheel pair")
            self.notes.warn("Ackermann base: no left/right steering joints and driven wheels to give gz-sim "
                            "AckermannSteering; its joints get their own controllers", b.loc)
            return
        kingpin = y[left_s[0]] - y[right_s[0]]
        el = etree.Element("plugin", filename=ACKERMANN[0], name=ACKERMANN[1])
        for j in left:
            sub(el, "left_joint", j)
        for j in right:
            sub(el, "right_joint", j)
        sub(el, "left_steering_joint", left_s[0])
        sub(el, "right_steering_joint", right_s[0])
        sub(el, "kingpin_width", round(kingpin, 9))
        sub(el, "steering_limit", round(b.steer_limit, 9))
        sub(el, "wheel_base", round(b.wheelbase, 9))
        sub(el, "wheel_separation", round(b.track, 9))
        sub(el, "wheel_radius", round(b.radius, 9))
        sub(el, "topic", "cmd_vel")
        sub(el, "odom_topic", "odom")
        self.has_control = True
        self.drive_joints.update(b.wheels + b.steering)
        self._replace(source, "gz-sim AckermannSteering")
        self.drive_fate = ("translated", f"ackermann: gz-sim AckermannSteering (steering {left_s[0]}/{right_s[0]}, "
                                         f"driven {', '.join(left + right)})")
        self.elements.append(("comment", f"an Ackermann base ({b.why}): gz-sim AckermannSteering, wheel_base "
                                         f"{num(b.wheelbase)} m, kingpin_width {num(kingpin)} m, wheel_separation "
                                         f"{num(b.track)} m, wheel_radius {num(b.radius)} m, steering_limit "
                                         f"{num(b.steer_limit)} rad, measured on the URDF"))
        self.elements.append(("plugin", el))

    # ------------------------------------------------------------ diff drive
    def _diff_drive(self, p, d):
        r = self.robot
        self.has_control = True
        lefts, rights = list(d.left), list(d.right)
        missing = d.missing(r)
        if not lefts or not rights or missing:
            self.notes.warn(f"diff-drive plugin '{p.name}': wheel joints {missing or 'not given'} not found; "
                            "kept as a comment", p.loc)
            self.unknown.append(f"{p.name} ({p.library})")
            self.elements.append(("comment", f"not converted (wheel joints missing): {xml_text(p.node)}"))
            return
        self.drive_joints.update(lefts + rights)
        g = D.measure(r, d)
        sep, rad = g.separation, g.radius
        src = []
        if sep is None:
            sep = d.separation
            src.append("separation from the plugin")
        if rad is None:
            rad = d.radius
            src.append("radius from the plugin (the wheel has no geometry to measure)")
        if sep is None or rad is None:
            self.notes.warn(f"diff-drive plugin '{p.name}': cannot tell the wheel separation/radius; kept as a "
                            "comment", p.loc)
            self.elements.append(("comment", f"not converted: {xml_text(p.node)}"))
            return
        for what, said, got in (("wheel_separation", d.separation, sep), ("wheel_radius", d.radius, rad)):
            if said is not None and abs(said - got) > 5e-4:
                self.notes.warn(f"diff-drive '{p.name}': the plugin says {what} {num(said)} m but the URDF's "
                                f"wheels give {num(got)} m; using the URDF", p.loc)
        # kobuki-style base plugins subscribe <base_prefix>/commands/velocity (base_prefix: mobile_base)
        vendor = "mobile_base/commands/velocity" if d.spec is D.VENDOR else None
        cmd, odom = P.drive_topics(p, vendor)          # as the plugin's node resolved them
        frame, child = P.drive_frames(p, r.root or "base_link")
        el = self._drive_element(lefts, rights, sep, rad, cmd, odom, frame, child,
                                 d.update_rate, d.accel, d.spec.accel_unit if d.spec else "")
        note = (f"from '{p.name}' ({p.library or p.tag}): wheel_separation and wheel_radius "
                f"measured on the URDF ({lefts[0]}/{rights[0]})")
        if d.skid:
            note += f"; a skid-steer base: one DiffDrive over its {len(lefts)} left and {len(rights)} right wheels"
        if src:
            note += "; " + "; ".join(src)
        if d.accel and d.spec is not None and d.spec.accel_unit == "wheel m/s^2":
            note += (f"; {d.spec.accel} {num(d.accel)} m/s^2 is the wheel surface's acceleration: the vehicle's "
                     f"linear limit, and 2a/s = {num(2 * d.accel / sep)} rad/s^2 its angular one")
        if d.legacy:
            note += ("; the ROS 1 plugin ran in legacy mode (legacyMode " + ("true" if d.legacy_explicit else
                     "not given, default true") + "), which swaps the wheels: this DiffDrive turns the way REP-103 says")
        nn = P.param(p, "node_namespace")
        if nn:
            note += (f"; the Electric plugin listened on {nn}/cmd_vel while the seed's programs publish cmd_vel: "
                     "cmd_vel is used")
        self.elements.append(("comment", note))
        self.elements.append(("plugin", el))
        # Create/Roomba and the classic plugin with publishWheelJointState publish joint states
        if d.spec is not None and d.spec.dialect != "skid" and (
                p.dialect == "electric" or "roomba" in _lib(p) or "create" in _lib(p)
                or V.boolean(P.param(p, "publishWheelJointState", "publish_wheel_joint_state"))):
            self.wants_joint_states = True

    def _drive_element(self, lefts, rights, sep, rad, cmd, odom, frame, child, rate, accel, unit):
        el = etree.Element("plugin", filename=DIFF_DRIVE[0], name=DIFF_DRIVE[1])
        for j in lefts:
            sub(el, "left_joint", j)
        for j in rights:
            sub(el, "right_joint", j)
        sub(el, "wheel_separation", round(sep, 9))
        sub(el, "wheel_radius", round(rad, 9))
        sub(el, "topic", cmd)
        sub(el, "odom_topic", odom)
        sub(el, "frame_id", frame)
        sub(el, "child_frame_id", child)
        if rate:
            sub(el, "odom_publish_frequency", rate)
        if accel:
            # ROS plugins ramp the wheel surface speed (m/s^2) and gz limits the vehicle's: the same
            # number for straight motion (not multiplied by the radius); turning, each wheel's surface
            # change bounds the yaw acceleration by 2a/s.
            sub(el, "max_linear_acceleration", accel)
            sub(el, "min_linear_acceleration", -accel)
            if unit == "wheel m/s^2":
                sub(el, "max_angular_acceleration", round(2 * accel / sep, 9))
                sub(el, "min_angular_acceleration", round(-2 * accel / sep, 9))
        return el

    # ------------------------------------------------------------ ros_control velocity wheels
    def _velocity_wheels(self):
        """Velocity-interface joints: a DiffDrive where they make one (wheels on both sides with a
        lateral axis), a velocity JointController for the others."""
        r = self.robot
        names, source = D.velocity_joints(r)
        names = [n for n in names if n in r.joints and n not in self.drive_joints and r.joints[n].type != "fixed"]
        if not names:
            return
        self.has_control = True
        self.wants_joint_states = True
        d = D.from_velocity_joints(r)
        if self.base is not None and self.base.kind not in DIFF_KINDS:
            d = None            # wheels that are no differential pair (swerve): each its own controller
        if d is not None and not (set(d.joints) & self.drive_joints):
            g = D.measure(r, d)
            if g.separation and g.radius:
                el = self._drive_element(list(d.left), list(d.right), g.separation, g.radius, "cmd_vel", "odom",
                                         "odom", r.root or "base_link", None, None, "")
                b = self.base
                ctrl = ""
                if b is not None and b.controller is not None:
                    ctrl = (f"; the robot's {b.controller.type} ({b.controller.file.rsplit('/', 1)[-1]}) turns with "
                            + ", ".join(f"{k} {num(v)} m" for k, v in (("wheel_separation", b.ctrl_track),
                                                                        ("wheel_radius", b.ctrl_radius)) if v is not None)
                            + " after its multipliers")
                    for what, said, got in (("wheel_separation", b.ctrl_track, g.separation),
                                            ("wheel_radius", b.ctrl_radius, g.radius)):
                        if said is not None and abs(said - got) > 5e-4:
                            self.notes.warn(f"{b.controller.type}: {what} {num(said)} m (its YAML, multipliers "
                                            f"applied) but the URDF's wheels give {num(got)} m; the DiffDrive uses "
                                            "the URDF's", b.loc)
                self.elements.append(("comment", f"{d.label} ({', '.join(d.left)} at +y; {', '.join(d.right)} at "
                                                 f"-y): a diff drive; wheel_separation and wheel_radius measured on "
                                                 "the URDF" + (ctrl or " (no controller YAML named by the URDF)")))
                self.elements.append(("plugin", el))
                self.drive_joints.update(d.joints)
        rest = [n for n in names if n not in self.drive_joints]
        if not rest:
            return
        self.elements.append(("comment", f"velocity controllers for the {len(rest)} velocity-interface joint(s) "
                                         f"({source}); command topic /model/<model>/joint/<joint>/cmd_vel"))
        for name in rest:
            j = r.joints[name]
            el = etree.Element("plugin", filename=VELOCITY[0], name=VELOCITY[1])
            sub(el, "joint_name", name)
            sub(el, "topic", f"/model/{self.model_name}/joint/{name}/cmd_vel")
            if j.limit and j.limit.effort and j.limit.effort > 0:     # negative: SDF's "no limit"
                sub(el, "cmd_max", j.limit.effort)
                sub(el, "cmd_min", -j.limit.effort)
            self.elements.append(("plugin", el))
            self.drive_joints.add(name)

    # ------------------------------------------------------------ arm joints
    def _arm(self):
        r = self.robot
        joints = []
        for t in r.transmissions:
            joints.extend(j for j in t.joints if j not in joints)
        source = "transmission" if joints else "ros2_control"
        joints.extend(j for j in D.position_joints(r) if j not in joints)
        if not joints and self.has_control and not D.commanded_joints(r):   # a model that names none
            source = "limits"
            joints = [j.name for j in r.joints.values()
                      if j.type in ("revolute", "prismatic") and j.limit is not None and j.mimic is None
                      and j.limit.lower is not None and j.limit.upper is not None and j.limit.upper > j.limit.lower]
        velocity = set(D.velocity_joints(r)[0])
        joints = [n for n in joints if n in r.joints and n not in self.drive_joints and n not in velocity
                  and r.joints[n].type in ("revolute", "prismatic", "continuous") and r.joints[n].mimic is None]
        if not joints:
            return
        self.wants_joint_states = True
        self.elements.append(("comment", f"position controllers for the {len(joints)} arm joint(s) "
                                         f"({_ARM_SOURCE[source]}); "
                                         "command topic /model/<model>/joint/<joint>/0/cmd_pos"))
        rest = r.rest_pose()
        for name in joints:
            j = r.joints[name]
            el = etree.Element("plugin", filename=POSITION[0], name=POSITION[1])
            sub(el, "joint_name", name)
            sub(el, "topic", f"/model/{self.model_name}/joint/{name}/0/cmd_pos")
            effort = j.limit.effort if j.limit and j.limit.effort and j.limit.effort > 0 else None
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
            if rest.get(name):          # the rest pose: 0, or the nearer limit when 0 is outside the range
                sub(el, "initial_position", rest[name])
            self.elements.append(("plugin", el))


_ARM_SOURCE = {"transmission": "from the transmissions", "ros2_control": "position interfaces of ros2_control",
               "limits": "revolute/prismatic with limits"}


def _lib(p) -> str:
    return ((p.filename or "") + " " + p.tag).lower()
