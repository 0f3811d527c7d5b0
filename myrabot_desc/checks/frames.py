"""S: sensors and frames (references, optical frames, massless sensor links, sensor parameters)."""

from __future__ import annotations

import math

from myrabot_desc.checks.rule import Finding, Fix, FixInfo, InsertAfter, InsertInto, SetValue, rule
from myrabot_desc.checks.urdf_syntax import suggest
from myrabot_desc.model import values as V
from myrabot_desc.model.gazebo import preserved_joints
from myrabot_desc.model.transforms import matmul3, transpose3

FRAME_PARAMS = ("bodyName", "frameName", "frameId", "frame_name", "robotBaseFrame", "robot_base_frame",
                "gz_frame_id", "ignition_frame_id", "optical_frame_id")
CAMERA_TYPES = {"camera", "depth", "depth_camera", "rgbd_camera", "rgbd", "multicamera", "wideanglecamera",
                "thermal_camera", "thermal", "segmentation_camera", "segmentation"}
RAY_TYPES = {"ray", "gpu_ray", "lidar", "gpu_lidar", "sonar"}


WORLD_FRAMES = {"world", "map", "odom", "earth"}    # frames outside the robot that plugins may name

# Example snippets (placed in checks.rule.TEMPLATE, whose only link is base_link).
_SENSOR_LINK = """<link name="{link}">
  <inertial>
    <mass value="0.05"/>
    <inertia ixx="1e-05" ixy="0" ixz="0" iyy="1e-05" iyz="0" izz="1e-05"/>
  </inertial>
</link>
<joint name="{link}_joint" type="fixed">
  <origin xyz="0.1 0 0.2" rpy="{rpy}"/>
  <parent link="base_link"/>
  <child link="{link}"/>
</joint>"""

_SONAR = _SENSOR_LINK.format(link="sonar_link", rpy="0 0 0") + """
<gazebo reference="sonar_link">
  <sensor type="ray" name="sonar_front">
    <ray>
      <scan><horizontal><samples>5</samples><min_angle>-0.25</min_angle><max_angle>0.25</max_angle></horizontal></scan>
      <range><min>0.02</min><max>4</max></range>
    </ray>
    <plugin name="sonar_front_controller" filename="libgazebo_ros_range.so">
      <topicName>sonar_front</topicName>
      <frameName>sonar_link</frameName>
      <fov>{fov}</fov>
    </plugin>
  </sensor>
</gazebo>"""

_LIDAR = _SENSOR_LINK.format(link="base_scan", rpy="0 0 0") + """
<gazebo reference="base_scan">
  <sensor type="ray" name="lds_lfcd_sensor">
    <ray>
      <scan><horizontal><samples>360</samples><min_angle>0.0</min_angle><max_angle>{max_angle}</max_angle></horizontal></scan>
      <range><min>{min}</min><max>{max}</max></range>
    </ray>
    <plugin name="gazebo_ros_lds_lfcd_controller" filename="libgazebo_ros_laser.so">
      <topicName>scan</topicName>
      <frameName>{frame}</frameName>
    </plugin>
  </sensor>
</gazebo>"""

_CAMERA = _SENSOR_LINK.format(link="camera_link", rpy="0 0 0") + """
<link name="camera_optical_frame"/>
<joint name="camera_optical_joint" type="fixed">
  <origin rpy="-1.5708 0 -1.5708"/>
  <parent link="camera_link"/>
  <child link="camera_optical_frame"/>
</joint>
<gazebo reference="camera_link">
  <sensor type="camera" name="front_camera">
    <camera>
      <horizontal_fov>{fov}</horizontal_fov>
      <image><width>640</width><height>480</height></image>
      <clip><near>0.05</near><far>50</far></clip>
    </camera>
    <plugin name="front_camera_controller" filename="libgazebo_ros_camera.so">
      <cameraName>front_camera</cameraName>
      <frameName>{frame}</frameName>
    </plugin>
  </sensor>
</gazebo>"""


def _frame_names(ctx) -> set[str]:
    return set(ctx.robot.links) | WORLD_FRAMES


def _clean(name: str) -> str:
    return (name or "").strip().lstrip("/")


@rule("S001", "gazebo-reference-exists", "error",
      bad=_LIDAR.format(max_angle="6.28319", min="0.12", max="3.5", frame="base_scan")
          .replace('<gazebo reference="base_scan">', '<gazebo reference="base_scn">'),
      message='<gazebo reference="base_scn"> names no link or joint; its content is lost (sensor '
              'lds_lfcd_sensor); did you mean base_scan?',
      good=_LIDAR.format(max_angle="6.28319", min="0.12", max="3.5", frame="base_scan"))
def gazebo_reference(ctx):
    """Every `<gazebo reference="X">` names an existing link or joint.

    A reference to nothing is skipped silently by the converter: the friction, the
    material, the sensor in that block never reach the simulator (for example a
    misspelt link, or a block emitted for a link whose macro was never called).
    Severity: error when the block holds a sensor or plugin, warning for properties only.
    Fix: the exact link name (did-you-mean is given).
    """

    r = ctx.robot
    names = set(r.links) | set(r.joints)
    for g in r.gazebo:
        if g.reference is not None and g.reference not in names:
            what = [*(f"sensor {s.name}" for s in g.sensors), *(f"plugin {p.name}" for p in g.plugins),
                    *sorted(g.properties)]
            guess = suggest(g.reference, names)
            sev = None if (g.sensors or g.plugins) else "warning"
            yield Finding(f"<gazebo reference=\"{g.reference}\"> names no link or joint; its content is lost"
                          + (f" ({', '.join(what[:5])})" if what else "")
                          + (f"; did you mean {guess}?" if guess else ""), g.loc,
                          {"reference": g.reference, "suggestion": guess, "content": what}, severity=sev)


@rule("S002", "plugin-frame-exists", "error",
      bad=_LIDAR.format(max_angle="6.28319", min="0.12", max="3.5", frame="base_scn"),
      message="plugin gazebo_ros_lds_lfcd_controller: frameName 'base_scn' is not a link of this robot; "
              "did you mean base_scan?",
      good=_LIDAR.format(max_angle="6.28319", min="0.12", max="3.5", frame="base_scan"))
def plugin_frames(ctx):
    """Plugin parameters that name a frame (bodyName, frameName, frameId, frame_name, robotBaseFrame...) name an existing link.

    The plugin stamps its messages (or applies its forces) in that frame; a frame that
    does not exist breaks TF lookups downstream (RViz shows nothing, the IMU plugin
    fails to find its body). Fix: the exact link name.
    """

    names = _frame_names(ctx)
    for p in ctx.robot.plugins():
        for key in FRAME_PARAMS:
            val = p.params.get(key)
            if val is None or not _clean(val) or "$" in val:
                continue
            if _clean(val) not in names:
                guess = suggest(_clean(val), names)
                yield Finding(f"plugin {p.name or p.library}: {key} '{val}' is not a link of this robot"
                              + (f"; did you mean {guess}?" if guess else ""), p.loc,
                              {"plugin": p.name, "param": key, "value": val, "suggestion": guess})


def _camera_frame(sensor):
    for p in sensor.plugins:
        for key in ("frameName", "frame_name", "gz_frame_id", "ignition_frame_id", "optical_frame_id"):
            if p.params.get(key):
                return _clean(p.params[key]), f"plugin {key}"
    for path in (("camera", "optical_frame_id"), ("gz_frame_id",), ("frame_id",)):
        v = sensor.param(*path)
        if v:
            return _clean(v), "/".join(path)
    return sensor.reference, "the sensor's link"


def _is_camera(sensor) -> bool:
    return sensor.type in CAMERA_TYPES


@rule("S003", "camera-optical-frame", "warning",
      bad=_CAMERA.format(fov="1.047", frame="camera_link"),
      message="camera front_camera stamps images in camera_link (plugin frameName), whose z axis is (0 0 1) in "
              "camera_link; the camera looks along camera_link's +x, so the image frame should be an optical "
              'frame (z forward): add a frame with rpy="-1.5708 0 -1.5708" under camera_link and use it (REP-103)',
      good=_CAMERA.format(fov="1.047", frame="camera_optical_frame"),
      fix=FixInfo("sometimes", "unsafe", "a link `<camera link>_optical_frame` on a fixed joint with rpy "
                  "\"-1.5708 0 -1.5708\" is added after the camera's link, and the camera's plugin names it "
                  "(frameName / frame_name, set or added). Unsafe: it adds a link and a joint, and the images' "
                  "frame changes for every consumer. A link written in a macro gets the frame in the macro body: "
                  "if the macro makes several cameras the names collide and the fix is refused."))
def optical_frame(ctx):
    """Cameras report in a REP-103 optical frame: z forward, x right, y down.

    A Gazebo camera looks along its link's +x, but image consumers (image_geometry,
    depth_image_proc, RViz) expect the image's frame to have z forward. Stamping images
    with the x-forward body frame puts point clouds and projections 90° off. Fix: a
    child frame `<name>_optical` with `rpy="-1.5708 0 -1.5708"` and that frame as the
    plugin's frameName / frame_name. A frame named `*_optical_frame` (or `*_optical`) is judged
    by its name too, camera plugin or not: under its parent it needs that rotation.
    """
    r = ctx.robot
    W = ctx.poses
    judged = set()
    for s in r.sensors():
        if not _is_camera(s) or s.reference not in W:
            continue
        frame, how = _camera_frame(s)
        if frame not in W:
            continue                     # S002 reports unknown frames
        judged.add(frame)
        R = matmul3(transpose3(W[s.reference][0]), W[frame][0])      # frame axes in the sensor link's frame
        z, x = [row[2] for row in R], [row[0] for row in R]
        if _optical(z, x):
            continue
        loc = next((p.loc for p in s.plugins if p.loc), s.loc)
        yield Finding(f"camera {s.name} stamps images in {frame} ({how}), whose z axis is "
                      f"({_r(z[0])} {_r(z[1])} {_r(z[2])}) in {s.reference}; the camera looks along {s.reference}'s +x, "
                      f"so the image frame should be an optical frame (z forward): add a frame with "
                      f"rpy=\"-1.5708 0 -1.5708\" under {s.reference} and use it (REP-103)", loc,
                      {"sensor": s.name, "frame": frame, "z_axis": z,
                       "fix": {"parent": s.reference, "rpy": [-math.pi / 2, 0.0, -math.pi / 2]}},
                      fix=_optical_fix(r, s, how))
    yield from _named_optical_frames(r, W, judged)


def _optical(z, x) -> bool:
    """Are these the axes of a REP-103 optical frame in a body frame: z along +x, x along -y?"""
    return z[0] > 0.98 and -x[1] > 0.98


def _named_optical_frames(r, W, judged):
    """S003 by REP-103's naming: a frame named ``*_optical_frame`` (or ``*_optical``) is an optical
    frame whatever plugin uses it, so under a body frame (x forward) its z is the parent's +x and its
    x the parent's -y. A frame under another optical frame (same axes) passes."""
    for name in r.links:
        if name in judged or name not in W or not name.endswith(("_optical_frame", "_optical")):
            continue
        pj = r.parent_joint(name)
        if pj is None or pj.parent not in W:
            continue
        R = matmul3(transpose3(W[pj.parent][0]), W[name][0])
        z, x = [row[2] for row in R], [row[0] for row in R]
        if _optical(z, x):
            continue
        if pj.parent.endswith(("_optical_frame", "_optical")) and all(
                abs(R[i][k] - (1.0 if i == k else 0.0)) <= 0.02 + 1e-05 * (i == k) for i in range(3) for k in range(3)):
            continue                     # np.allclose(R, I, atol=0.02)'s test
        yield Finding(f"frame {name} is named as a REP-103 optical frame (z forward, x right, y down), but its z "
                      f"axis is ({_r(z[0])} {_r(z[1])} {_r(z[2])}) and its x axis ({_r(x[0])} {_r(x[1])} {_r(x[2])}) "
                      f"in {pj.parent} (joint {pj.name}); under a body frame (x forward) it needs "
                      f"rpy=\"-1.5708 0 -1.5708\" (z along {pj.parent}'s +x, x along its -y)", pj.loc,
                      {"frame": name, "parent": pj.parent, "joint": pj.name, "z_axis": z,
                       "x_axis": x, "fix": {"parent": pj.parent, "rpy": [-math.pi / 2, 0.0, -math.pi / 2]}})


def _optical_fix(robot, sensor, how: str) -> Fix | None:
    """S003's fix: an optical frame under the camera's link, named by the camera's plugin."""
    plugin = next(iter(sensor.plugins), None)
    if plugin is None:
        return None
    link = sensor.reference
    name = f"{link}_optical_frame"
    edits = []
    if name not in robot.links:
        edits.append(InsertAfter(robot.links[link],
                                 f'<link name="{name}"/>\n<joint name="{link}_optical_joint" type="fixed">\n'
                                 f'  <parent link="{link}"/>\n  <child link="{name}"/>\n'
                                 f'  <origin xyz="0 0 0" rpy="-1.5708 0 -1.5708"/>\n</joint>'))
    if how.startswith("plugin "):
        edits.append(SetValue(plugin, how.split(" ", 1)[1], name))
    else:
        key = "frame_name" if any("_" in k for k in plugin.params) else "frameName"
        edits.append(InsertInto(plugin, f"<{key}>{name}</{key}>"))
    return Fix(tuple(edits), "unsafe", f"optical frame {name} added")


@rule("S004", "sensor-on-massless-link", "warning",
      bad='<link name="imu_link"/>\n<joint name="imu_joint" type="revolute">\n  <parent link="base_link"/>\n'
          '  <child link="imu_link"/>\n  <axis xyz="0 0 1"/>\n  <limit lower="-1" upper="1" effort="1" velocity="1"/>\n'
          '</joint>\n<gazebo reference="imu_link">\n  <sensor type="imu" name="imu"/>\n</gazebo>',
      message="sensor imu (imu) sits on massless leaf link imu_link: its joint is not fixed",
      good=_SENSOR_LINK.format(link="imu_link", rpy="0 0 0")
           + '\n<gazebo reference="imu_link">\n  <sensor type="imu" name="imu"/>\n</gazebo>')
def massless_sensor_link(ctx):
    """A sensor attached to a massless leaf link can vanish in URDF→SDF conversion.

    A link without mass survives conversion only when its fixed joint is lumped into
    the parent (then the sensor moves to the parent). If the joint is not fixed, or
    lumping is disabled for it, the link is dropped with its sensor (sdformat #199);
    the Electric-era converter ignored massless links altogether. Severity: error when
    the link will be dropped, warning for the Electric dialect, info when lumping keeps it.
    Fix: give the sensor link a small inertial (1 g, 1e-6 kg·m²).
    """
    r = ctx.robot
    lump_off = preserved_joints(r)
    for s in r.sensors():
        link = r.links.get(s.reference or "")
        if link is None or link.mass > 0 or r.child_joints(link.name):
            continue
        pj = r.parent_joint(link.name)
        if pj is None:
            continue
        if pj.type != "fixed" or pj.name in lump_off:
            sev, why = "error", ("its joint is not fixed" if pj.type != "fixed" else "fixed-joint lumping is off for it")
        elif s.dialect == "electric":
            sev, why = "warning", "the Electric-era converter ignores links without mass"
        else:
            sev, why = "info", f"it survives only because fixed-joint lumping moves the sensor onto {pj.parent}"
        yield Finding(f"sensor {s.name} ({s.type}) sits on massless leaf link {link.name}: {why}",
                      s.loc, {"sensor": s.name, "link": link.name, "joint": pj.name}, severity=sev)


def _r(x: float) -> str:
    v = round(float(x), 2)
    return f"{v + 0.0:g}"


def _ranges(s):
    """(min, max, label) pairs of a sensor, both dialects (its typed rays and camera)."""
    out = []
    cam = s.camera
    if s.dialect == "electric":
        if s.type == "ray" and s.rays:
            out.append((s.rays[0].range_min, s.rays[0].range_max, "minRange/maxRange"))
        if s.type == "camera" and cam is not None:
            out.append((cam.near, cam.far, "nearClip/farClip"))
    else:
        for root in ("ray", "lidar"):
            ray = next((r for r in s.rays if r.tag == root), None)
            if ray is not None:
                out.append((ray.range_min, ray.range_max, f"{root}/range"))
        if cam is not None:
            out.append((cam.near, cam.far, "camera/clip"))
    return [(a, b, lab) for a, b, lab in out if a is not None or b is not None]


@rule("S005", "sensor-range", "error",
      bad=_LIDAR.format(max_angle="6.28319", min="3.5", max="0.12", frame="base_scan"),
      message="sensor lds_lfcd_sensor: ray/range min 3.5 ≥ max 0.12",
      good=_LIDAR.format(max_angle="6.28319", min="0.12", max="3.5", frame="base_scan"))
def sensor_range(ctx):
    """A sensor's minimum range (near clip) must be below its maximum (far clip), and above 0 for rays.

    min ≥ max leaves nothing to measure. A ray sensor with min range 0 starts its rays
    inside its own link and can see itself (warning). Fix: the device's datasheet range
    (hobby sonars: about 0.02–4 m).
    """
    for s in ctx.robot.sensors():
        for lo, hi, label in _ranges(s):
            if lo is not None and hi is not None and lo >= hi:
                yield Finding(f"sensor {s.name}: {label} min {lo:g} ≥ max {hi:g}", s.loc,
                              {"sensor": s.name, "min": lo, "max": hi})
            elif lo is not None and lo <= 0 and (s.type in RAY_TYPES):
                yield Finding(f"sensor {s.name}: {label} min {lo:g} m: rays start inside the sensor's own link",
                              s.loc, {"sensor": s.name, "min": lo}, severity="warning")


RADIAN_PARAMS = {"fov": "sensor_msgs/Range.field_of_view"}
FULL_TURN = 2 * math.pi


def _slack(text: str | None) -> float:
    """Half a unit of the last digit written: 2π written as 6.28319 (or 6.2832, 6.3) is a full turn,
    not a value past it."""
    t = (text or "").strip().lower()
    if "." in t and "e" not in t:
        return max(0.5 * 10.0 ** -len(t.split(".", 1)[1]), 1e-6)
    return 1e-6


@rule("S006", "angle-units", "error",
      bad=_SONAR.format(fov="32"),
      message="sensor sonar_front: plugin sonar_front_controller fov 32 looks like degrees; expected radians "
              "(sensor_msgs/Range.field_of_view): 32° = 0.5585 rad",
      good=_SONAR.format(fov="0.5585"))
def angle_units(ctx):
    """Angles in degrees where radians are expected (sonar `fov 32`, SDF `horizontal_fov 60`).

    SDF sensors and ROS messages use radians; the Electric dialect's `hfov`, `minAngle`
    and `maxAngle` were degrees, so copied values keep their degree numbers. A sonar
    `fov` of 32 becomes a 32-radian cone in sensor_msgs/Range. A full turn written with
    few decimals (`max_angle 6.28319`, 2π rounded) is radians, not degrees. The finding
    points at the element holding the value. Fix: the value in radians (given: 32° = 0.5585 rad).
    """
    for s in ctx.robot.sensors():
        checks = []
        node = s.node
        if s.dialect == "electric":
            hf = V.number(s.param("hfov"))
            if hf is not None and not 0 < hf < 180:
                checks.append(("hfov", hf, "degrees in (0, 180)", node.child("hfov")))
        else:
            el = node.find("camera", "horizontal_fov")
            hf = V.number(s.param("camera", "horizontal_fov"))
            if hf is not None and not 0 < hf <= FULL_TURN + _slack(el.text if el is not None else None):
                checks.append(("camera/horizontal_fov", hf, "radians in (0, 2π]", el))
            for root in ("ray", "lidar"):
                for axis in ("horizontal", "vertical"):
                    for k in ("min_angle", "max_angle"):
                        el = node.find(root, "scan", axis, k)
                        v = V.number(s.param(root, "scan", axis, k))
                        if v is not None and abs(v) > FULL_TURN + _slack(el.text if el is not None else None):
                            checks.append((f"{root}/scan/{axis}/{k}", v, "radians in [-2π, 2π]", el))
        for p in s.plugins:
            for key, what in RADIAN_PARAMS.items():
                el = p.param(key)
                v = V.number(p.params.get(key))
                if v is not None and v > FULL_TURN + _slack(p.params.get(key)):
                    checks.append((f"plugin {p.name or p.library} {key}", v, f"radians ({what})", el))
        fallback = next((p.loc for p in s.plugins if p.loc), s.loc)
        for label, v, expected, el in checks:
            if "degrees" in expected:
                msg = f"sensor {s.name}: {label} {v:g} is out of range (expected {expected})"
                fix = None
            else:
                fix = math.radians(v)
                msg = (f"sensor {s.name}: {label} {v:g} looks like degrees; expected {expected}: "
                       f"{v:g}° = {fix:.4g} rad")
            yield Finding(msg, ((el.loc or ctx.robot.loc) if el is not None else None) or fallback,
                          {"sensor": s.name, "param": label, "value": v, "fix": fix})


@rule("S007", "camera-fov-range", "warning",
      bad=_CAMERA.format(fov="3.3", frame="camera_optical_frame"),
      message="camera front_camera: horizontal_fov 3.3 rad (189°) is outside a pinhole camera's range",
      good=_CAMERA.format(fov="1.047", frame="camera_optical_frame"))
def camera_fov(ctx):
    """A pinhole camera's horizontal field of view should lie between 0.05 rad and π.

    Gazebo renders a pinhole camera only up to just under π; wider views need a
    wide-angle camera type. Fix: the lens's real field of view (a webcam is ~1.0 rad).
    """
    for s in ctx.robot.sensors():
        if s.dialect == "electric" or s.type not in ("camera", "depth", "depth_camera", "rgbd_camera", "multicamera"):
            continue
        hf = s.camera.hfov if s.camera is not None else None
        if hf is not None and 0 < hf <= 2 * math.pi and not 0.05 <= hf < math.pi:
            yield Finding(f"camera {s.name}: horizontal_fov {hf:g} rad ({math.degrees(hf):.0f}°) is outside a pinhole "
                          "camera's range", s.loc, {"sensor": s.name, "horizontal_fov": hf})


_IMU = _SENSOR_LINK.format(link="imu_link", rpy="0 0 0") + """
<gazebo reference="imu_link">
  <sensor type="imu" name="imu">
    <always_on>true</always_on>
    <update_rate>{rate}</update_rate>
  </sensor>
</gazebo>"""


@rule("S008", "sensor-update-rate", "error",
      bad=_IMU.format(rate="-100"),
      message="sensor imu (imu): update_rate -100 Hz is negative",
      good=_IMU.format(rate="100"))
def sensor_update_rate(ctx):
    """A sensor's update rate must not be negative.

    Gazebo reads `<update_rate>` (Electric `<updateRate>`) as the sensor's frequency in Hz;
    0 means as fast as the simulation steps, and a negative value is no frequency at all
    (sdformat accepts the number; the sensor then never updates or updates every step,
    depending on the simulator). Fix: the device's rate in Hz (an IMU 100–400, a camera 30).
    """
    for s in ctx.robot.sensors():
        rate = s.update_rate
        if rate is not None and rate < 0:
            word = "updateRate" if s.dialect == "electric" else "update_rate"
            yield Finding(f"sensor {s.name} ({s.type}): {word} {rate:.4g} Hz is negative", s.loc,
                          {"sensor": s.name, "update_rate": rate})
