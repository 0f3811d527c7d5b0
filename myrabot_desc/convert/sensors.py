"""Gazebo sensors → gz-sim sensors (anchors §6.3), the Electric dialect included.

Electric (``<sensor:camera>``, ``<sensor:ray>`` with ``<controller:...>`` inside) writes
angles in degrees; SDF wants radians. Classic SDF sensors (``<sensor type="ray">``
with ROS plugins inside) are upgraded in place: ``ray`` → ``gpu_lidar`` (``<ray>`` →
``<lidar>``), ``depth`` → ``depth_camera``; the ROS plugins disappear (gz-sim sensors
publish on ``<topic>`` themselves) and their topic and frame are carried over.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from lxml import etree

from myrabot_desc.convert.common import element_of, num, sub, xml_text
from myrabot_desc.model import plugins as P
from myrabot_desc.model import values as V
from myrabot_desc.model.parts import Sonar
from myrabot_desc.model.transforms import transform

SONAR_NOTE = ("gz-sim has no sonar sensor: this is a narrow gpu_lidar with the seed's rays; the old plugin "
              "published sensor_msgs/Range = the minimum over its rays, so take min(ranges) downstream")


@dataclass
class SensorOut:
    link: str                       # the URDF link it is attached to
    T: object                       # pose in that link's frame: a common.Tf (R, p)
    sdf: object                     # the SDF <sensor> element written (None: not converted)
    comments: list[str] = field(default_factory=list)
    source: str = ""                # 'electric' | 'sdf' | 'controller'


def noise_el(parent, stddev, attr=False):
    """Gaussian noise; IMU axes take the type as an attribute (SDF 1.9), lidar/camera as a child."""
    n = sub(parent, "noise", type_="gaussian" if attr else None)
    if not attr:
        sub(n, "type", "gaussian")
    sub(n, "mean", 0.0)
    sub(n, "stddev", stddev)
    return n


def _header(name, type_, always_on=True, rate=None, visualize=None, topic=None, frame=None):
    s = etree.Element("sensor", name=name, type=type_)
    sub(s, "always_on", bool(always_on))
    if rate is not None:
        sub(s, "update_rate", rate)
    if visualize is not None:
        sub(s, "visualize", bool(visualize))
    if topic:
        sub(s, "topic", topic)
    if frame:
        sub(s, "gz_frame_id", frame)
    return s


# ---------------------------------------------------------------- Electric dialect
def _or(value, default):
    return default if value is None else value


def _electric_camera(sensor, notes):
    cam = sensor.camera
    ctrl = sensor.plugins[0] if sensor.plugins else None
    kind = P.kind(ctrl) if ctrl else None
    comments = []
    size = (_or(cam.width, 320), _or(cam.height, 240))
    hfov_deg = _or(cam.hfov, 60.0)
    near, far = _or(cam.near, 0.1), _or(cam.far, 100.0)
    rate = sensor.update_rate
    fmt = cam.format or "R8G8B8"
    type_ = "camera"
    topic = frame = None
    if ctrl is not None:
        rate = V.number(P.param(ctrl, "updateRate"), rate)
        image_topic = P.param(ctrl, "imageTopicName")
        cam_name = P.param(ctrl, "cameraName")
        frame = P.param(ctrl, "frameName")
        loaded = not (ctrl.dialect == "electric" and ctrl.file_attr == "filename")
        if kind == "openni_kinect" and loaded:
            type_ = "rgbd_camera"
            base = image_topic.rsplit("/", 1)[0] if image_topic and "/" in image_topic.strip("/") else cam_name
            topic = base or sensor.name
            comments.append(f"openni_kinect controller '{ctrl.name}' -> rgbd_camera: "
                            f"gz-sim publishes {topic}/image, {topic}/depth_image, {topic}/points, "
                            f"{topic}/camera_info; the seed's ROS topics were "
                            + ", ".join(v for v in (image_topic, P.param(ctrl, "pointCloudTopicName"),
                                                    P.param(ctrl, "cameraInfoTopicName")) if v)
                            + " (map them with ros_gz_bridge)")
        else:
            topic = P.resolve(image_topic, cam_name) or cam_name
            if kind == "openni_kinect" and not loaded:
                comments.append(f"controller '{ctrl.name}' was written with filename= instead of plugin=, so "
                                "Gazebo 1.0 never loaded it (no depth): converted as a plain camera on its "
                                f"image topic {image_topic}")
                notes.warn(f"Electric controller '{ctrl.name}' uses filename= (ignored by Gazebo 1.0): "
                           "sensor converted as a plain camera", ctrl.loc)
        dist = {k: V.number(P.param(ctrl, f"distortion_{k}"), 0.0) for k in ("k1", "k2", "k3", "t1", "t2")}
    else:
        dist = {}
    s = _header(sensor.name or "camera", type_, True, rate, None, topic, frame)
    cam = sub(s, "camera")
    sub(cam, "horizontal_fov", math.radians(hfov_deg))
    img = sub(cam, "image")
    sub(img, "width", int(size[0]))
    sub(img, "height", int(size[1]))
    sub(img, "format", fmt)
    clip = sub(cam, "clip")
    sub(clip, "near", near)
    sub(clip, "far", far)
    if any(dist.values()):
        d = sub(cam, "distortion")
        for k, tag in (("k1", "k1"), ("k2", "k2"), ("k3", "k3"), ("t1", "p1"), ("t2", "p2")):
            sub(d, tag, dist[k])
    if frame:
        sub(cam, "optical_frame_id", frame)
    comments.insert(0, f"from Electric <sensor:camera name=\"{sensor.name}\">: hfov {num(hfov_deg)} deg = "
                       f"{num(math.radians(hfov_deg))} rad")
    T = transform(sensor.pose or (0, 0, 0))
    return s, comments, T


def _electric_ray(sensor, notes):
    ray = sensor.rays[0]
    h, v = ray.horizontal, ray.vertical
    ctrl = sensor.plugins[0] if sensor.plugins else None
    kind = P.kind(ctrl) if ctrl else None
    rays = int(_or(h.samples, 1))
    ranges = int(_or(ray.range_count, rays))
    amin, amax = _or(h.min_angle, 0.0), _or(h.max_angle, 0.0)
    vrays = v.samples if v is not None else None
    vmin, vmax = (_or(v.min_angle, 0.0), _or(v.max_angle, 0.0)) if v is not None else (0.0, 0.0)
    rmin, rmax = _or(ray.range_min, 0.0), _or(ray.range_max, 10.0)
    rres = _or(ray.range_resolution, 0.01)
    rate = sensor.update_rate
    vis = sensor.visualize
    comments = []
    topic = frame = noise = None
    if ctrl is not None:
        rate = V.number(P.param(ctrl, "updateRate"), rate)
        topic = P.param(ctrl, "topicName")
        frame = P.param(ctrl, "frameName", "frameId")
        noise = V.number(P.param(ctrl, "gaussianNoise"))
    sonar = kind == "sonar"
    if ctrl is None:
        topic = sensor.name
        comments.append(f"Electric <sensor:ray name=\"{sensor.name}\"> had no controller (the base plugin read "
                        "it by name); published here on its own topic")
    s = _header(sensor.name or "ray", "gpu_lidar", _or(sensor.always_on, True), rate,
                vis not in (None, "false", "0"), topic, frame)
    lidar = sub(s, "lidar")
    scan = sub(lidar, "scan")
    h = sub(scan, "horizontal")
    sub(h, "samples", rays)
    sub(h, "resolution", ranges / rays if rays else 1)
    sub(h, "min_angle", math.radians(amin))
    sub(h, "max_angle", math.radians(amax))
    if vrays is not None:
        v = sub(scan, "vertical")
        sub(v, "samples", int(vrays))
        sub(v, "resolution", 1)
        sub(v, "min_angle", math.radians(vmin))
        sub(v, "max_angle", math.radians(vmax))
    rng = sub(lidar, "range")
    sub(rng, "min", rmin)
    sub(rng, "max", rmax)
    sub(rng, "resolution", rres)
    if noise:
        noise_el(lidar, noise)
    what = f"{rays}x{int(vrays) if vrays else 1} rays, {num(amin)}..{num(amax)} deg"
    if vrays is not None:
        what += f" by {num(vmin)}..{num(vmax)} deg"
    comments.insert(0, f"from Electric <sensor:ray name=\"{sensor.name}\">: {what} (radians below)")
    if sonar:
        comments.append(SONAR_NOTE + (f"; plugin fov {P.param(ctrl, 'fov')}, radiation {P.param(ctrl, 'radiation')}"
                                      if P.param(ctrl, 'fov') else ""))
    T = transform(sensor.pose or (0, 0, 0))
    return s, comments, T


# ---------------------------------------------------------------- SDF/classic dialect
_TYPE_MAP = {"ray": "gpu_lidar", "gpu_ray": "gpu_lidar", "lidar": "gpu_lidar", "depth": "depth_camera",
             "gps": "navsat", "multicamera": "camera", "sonar": "gpu_lidar"}


def _sdf_sensor(sensor, notes, folded=()):
    s = element_of(sensor.node)
    etree.strip_attributes(s, "reference")
    old_type = (s.get("type") or "").strip()
    new_type = _TYPE_MAP.get(old_type, old_type)
    if new_type != old_type:
        s.set("type", new_type)
    comments = []
    for child, n in zip(list(s), sensor.node.children):
        if n.tag == "pose" or n.tag == "plugin":
            s.remove(child)
        elif n.tag == "ray":
            child.tag = "lidar"
    pose = sensor.pose
    if old_type == "sonar":
        son = sensor.sonar or Sonar()
        rmin, rmax, radius = _or(son.min, 0.0), _or(son.max, 5.0), _or(son.radius, 0.1)
        half = math.atan2(radius, rmax)
        old = s.find("sonar")
        if old is not None:
            s.remove(old)
        lidar = sub(s, "lidar")
        scan = sub(lidar, "scan")
        for axis in ("horizontal", "vertical"):
            a = sub(scan, axis)
            sub(a, "samples", 5)
            sub(a, "resolution", 1)
            sub(a, "min_angle", -half)
            sub(a, "max_angle", half)
        r = sub(lidar, "range")
        sub(r, "min", rmin)
        sub(r, "max", rmax)
        sub(r, "resolution", 0.01)
        comments.append(SONAR_NOTE + f"; cone radius {num(radius)} m at {num(rmax)} m")
    if old_type == "multicamera":
        cams = s.findall("camera")
        for extra in cams[1:]:
            s.remove(extra)
        if len(cams) > 1:
            notes.warn(f"multicamera '{sensor.name}': gz-sim has no multicamera, only its first camera is kept",
                       sensor.loc)
    if new_type != old_type:
        comments.append(f"classic type '{old_type}' -> '{new_type}'")
    topic = frame = None
    for p in sensor.plugins:
        kind = P.kind(p)
        topic = topic or P.sensor_topic(p)
        if kind in P.CAMERA_KINDS:
            frame = frame or P.param(p, "frameName", "frame_name")
        elif kind in P.RAY_KINDS:
            frame = frame or P.param(p, "frameName", "frame_name", "frameId")
            if kind == "imu":
                frame = frame or P.param(p, "bodyName")
        comments.append(f"ROS plugin '{p.name}' ({p.library}) dropped: gz-sim sensors publish themselves; "
                        "its topic and frame are used here")
    for p in folded:             # a model-level IMU plugin measuring this sensor's link: one sensor, not two
        topic = topic or P.sensor_topic(p, default="imu")
        frame = frame or P.param(p, "frameName", "frame_name") or _imu_body(p)
        rate = V.number(P.param(p, "updateRate", "update_rate"))
        if rate and s.find("update_rate") is None:
            sub(s, "update_rate", rate)
        noise = _imu_noise(s, p)
        comments.append(f"IMU plugin '{p.name}' ({p.library}) on this link folded into this sensor: its topic, "
                        "frame, rate" + (" and gaussianNoise (as the stddev)" if noise else "")
                        + " kept (gz-sim sensors publish themselves)")
    for p in sensor.plugins:     # a ROS IMU sensor plugin adds its own gaussianNoise to the readings
        noise = _imu_noise(s, p) if P.kind(p) == "imu" else None
        if noise:
            comments.append(f"the plugin's gaussianNoise {num(noise)} is the stddev of every axis")
    if topic and s.find("topic") is None:
        sub(s, "topic", topic.lstrip("~/") if topic.startswith("~/") else topic)
    if frame and s.find("gz_frame_id") is None:
        sub(s, "gz_frame_id", frame)
        cam = s.find("camera")
        if cam is not None and cam.find("optical_frame_id") is None:
            sub(cam, "optical_frame_id", frame)
    T = transform(pose[:3], pose[3:6]) if pose and len(pose) >= 6 else transform()
    return s, comments, T


# ---------------------------------------------------------------- controllers that are sensors
def _imu_noise(s, p):
    """The IMU plugin ``p``'s gaussianNoise as the stddev of every axis of sensor ``s`` (as the
    plugins used it), unless ``s`` already has an ``<imu>`` block; returns the noise applied."""
    noise = V.number(P.param(p, "gaussianNoise", "gaussian_noise"))
    if not noise or s.find("imu") is not None:
        return None
    imu = sub(s, "imu")
    for group in ("angular_velocity", "linear_acceleration"):
        g = sub(imu, group)
        for axis in "xyz":
            noise_el(sub(g, axis), noise, attr=True)
    return noise


def _imu_body(p):
    return P.param(p, "bodyName", "body_name", "frameName", "frame_name") or p.reference


def _imu_sensor(robot, link):
    """The first SDF ``<sensor type="imu">`` on a link, or None."""
    def build():
        out: dict = {}
        for s in robot.sensors():
            if s.dialect == "sdf" and s.type == "imu":
                out.setdefault(s.reference, s)
        return out
    return robot.derive("convert.imu_sensors", build).get(link)


def imu_sensor_on(p, robot) -> str | None:
    """Name of the imu sensor already on the link a model-level IMU plugin measures (it is folded
    into that sensor by ``translate_sensor``), or None."""
    s = _imu_sensor(robot, _imu_body(p))
    return None if s is None else (s.name or "imu")


def _folded_imu_plugins(sensor, robot):
    if sensor.type != "imu" or _imu_sensor(robot, sensor.reference) is not sensor:
        return ()

    def build():        # body -> its IMU plugins, in document order
        out: dict = {}
        for g in robot.gazebo:
            for p in g.plugins:
                if P.kind(p) == "imu":
                    out.setdefault(_imu_body(p), []).append(p)
        return out
    return tuple(robot.derive("convert.imu_plugins", build).get(sensor.reference, ()))


def imu_from_plugin(p, robot, notes) -> SensorOut | None:
    """gazebo_ros_imu (Electric controller or classic model plugin): an ``imu`` sensor on bodyName."""
    body = _imu_body(p)
    if body not in robot.links:
        notes.warn(f"IMU plugin '{p.name}': body '{body}' is not a link; IMU not converted", p.loc)
        return None
    rate = V.number(P.param(p, "updateRate", "update_rate"))
    topic = P.sensor_topic(p, default="imu")
    s = _header(f"{p.name or 'imu'}", "imu", True, rate, None, topic, P.param(p, "frameName", "frame_name") or body)
    _imu_noise(s, p)
    xyz = V.vector(P.param(p, "xyzOffsets", "xyzOffset")) or [0, 0, 0]
    # the plugin built a Quaternion from this vector: radians, even in the Electric dialect
    rpy = V.vector(P.param(p, "rpyOffsets", "rpyOffset")) or [0, 0, 0]
    comments = [f"from {'Electric controller' if p.dialect == 'electric' else 'plugin'} '{p.name}' "
                f"({P.key(p)}) on {body}; gaussianNoise used as the stddev, as the plugin did"]
    return SensorOut(body, transform(xyz, rpy), s, comments, "controller")


def translate_sensor(sensor, robot, notes) -> SensorOut | None:
    link = sensor.reference
    if link not in robot.links:
        notes.warn(f"sensor '{sensor.name}' refers to '{link}', which is not a link; not converted", sensor.loc)
        return None
    if sensor.dialect == "electric":
        if sensor.type == "camera":
            s, comments, T = _electric_camera(sensor, notes)
        elif sensor.type == "ray":
            s, comments, T = _electric_ray(sensor, notes)
        else:
            notes.warn(f"Electric sensor type '{sensor.type}' has no gz-sim equivalent; kept as a comment",
                       sensor.loc)
            return SensorOut(link, transform(), None, [f"not converted: {xml_text(sensor.node)}"], "electric")
        for p in sensor.plugins[1:]:
            comments.append(f"extra controller not converted: {xml_text(p.node)}")
        return SensorOut(link, T, s, comments, "electric")
    s, comments, T = _sdf_sensor(sensor, notes, _folded_imu_plugins(sensor, robot))
    return SensorOut(link, T, s, comments, "sdf")
