"""What a Gazebo plugin is and which ROS topics it uses, worked out once: check's G010 (two
publishers of one topic) and convert (the gz-sim sensors and systems that replace the plugins,
carrying their topics over) both ask here.

ROS name resolution, as the plugins do it: a relative name lives under the plugin's namespace
(ROS 1 ``<robotNamespace>``, ROS 2 ``<ros><namespace>``), and for plugins built on gazebo_ros's
camera utilities also under ``<cameraName>`` (ROS 1 GazeboRosCameraUtils advertises every topic
on a node handle in ``<robotNamespace>/<cameraName>``); an absolute name (``/scan``) is itself.
Pure Python (convert imports it without numpy).
"""

from __future__ import annotations

CAMERA_KINDS = ("camera", "openni_kinect", "depth_camera")
RAY_KINDS = ("laser", "sonar", "imu")
_KINDS = (
    ("openni_kinect", ("gazebo_ros_openni_kinect", "gazebo_ros_kinect")),
    ("depth_camera", ("gazebo_ros_depth_camera",)),
    ("camera", ("gazebo_ros_camera", "gazebo_ros_prosilica", "gazebo_ros_multicamera", "gazebo_ros_triggered_camera",
                "gazebo_ros_triggered_multicamera", "gazebo_ros_wideanglecamera")),
    ("laser", ("gazebo_ros_laser", "gazebo_ros_gpu_laser", "gazebo_ros_ray_sensor", "gazebo_ros_block_laser",
               "gazebo_ros_head_hokuyo")),
    ("sonar", ("gazebo_ros_sonar", "gazebo_ros_range", "hector_gazebo_ros_sonar")),
    ("imu", ("gazebo_ros_imu", "gazebo_ros_imu_sensor", "hector_gazebo_ros_imu")),
    ("diff_drive", ("gazebo_ros_roomba", "gazebo_ros_create", "gazebo_ros_diff_drive", "gazebo_ros_kobuki",
                    "gazebo_ros_diffdrive", "diff_drive_controller", "gz-sim-diff-drive-system",
                    "ignition-gazebo-diff-drive-system", "diffdrive")),
    ("skid_steer", ("gazebo_ros_skid_steer_drive",)),
    ("joint_state", ("gazebo_ros_joint_state_publisher", "gz-sim-joint-state-publisher-system",
                     "ignition-gazebo-joint-state-publisher-system", "jointstatepublisher")),
    ("ros_control", ("gazebo_ros_control", "gazebo_ros_controller_manager", "gazebo_ros2_control", "gz_ros2_control",
                     "ign_ros2_control", "gz_ros2_control-system", "ign_ros2_control-system")),
)
# Parameters that name a topic the plugin uses (the command topics are subscribed: subscribers may share)
TOPIC_KEYS = ("topicName", "topic", "imageTopicName", "cameraInfoTopicName", "pointCloudTopicName",
              "depthImageTopicName", "depthImageCameraInfoTopicName", "odometryTopic", "odometry_topic",
              "commandTopic", "command_topic", "odom_topic", "tf_topic")
SUBSCRIBED = ("commandTopic", "command_topic")
# A drive plugin's command and odometry topics and frames, every dialect's name for each, in the
# order they are looked for (ROS 1, ROS 2 / vendor, gz-sim)
COMMAND_KEYS = ("commandTopic", "command_topic", "topic")
ODOMETRY_KEYS = ("odometryTopic", "odometry_topic", "odom_topic")
ODOMETRY_FRAME_KEYS = ("odometryFrame", "odometry_frame", "frame_id")
BASE_FRAME_KEYS = ("robotBaseFrame", "robot_base_frame", "child_frame_id")

def key(p) -> str:
    """The plugin's library without lib/.so (Electric controllers: the tag; gz systems: the name)."""
    lib = (p.filename or "").rsplit("/", 1)[-1]
    if lib.startswith("lib"):
        lib = lib[3:]
    for ext in (".so", ".dylib", ".dll"):
        if lib.endswith(ext):
            lib = lib[: -len(ext)]
    if lib:
        return lib.lower()
    if p.dialect == "electric":
        return p.tag.lower()
    return (p.name or "").rsplit("::", 1)[-1].lower()


def kind(p) -> str:
    """A short kind for a plugin/controller: 'openni_kinect', 'depth_camera', 'camera', 'laser', 'sonar',
    'imu', 'diff_drive', 'skid_steer', 'joint_state', 'ros_control', 'gz', or 'unknown'."""
    k = key(p)
    for name, keys in _KINDS:
        if k in keys:
            return name
    if k.startswith(("gz-sim-", "ignition-gazebo-")) or (p.name or "").startswith(("gz::sim", "ignition::gazebo")):
        return "gz"
    return "unknown"


def node_kind(n) -> str:
    """kind() of a ``<plugin>`` element no typed Plugin holds (one nested in the ``<visual>`` of a
    ``<gazebo reference>`` block, which Gazebo classic loads as a visual plugin)."""
    from types import SimpleNamespace

    return kind(SimpleNamespace(filename=n.get("filename"), name=n.get("name"), dialect="sdf", tag=n.tag))


def param(p, *names) -> str | None:
    """The first of ``names`` the plugin gives a non-empty value, stripped."""
    for n in names:
        v = p.params.get(n)
        if v not in (None, "") and v.strip():
            return v.strip()
    return None


def namespace(p) -> str:
    """The plugin's ROS namespace ('' for none or '/'; an absolute one keeps its leading slash):
    ROS 1 robotNamespace, else the ROS 2 ``<ros><namespace>``."""
    ns = param(p, "robotNamespace")
    if not ns:
        inner = p.node.find("ros", "namespace")
        ns = (inner.text or "") if inner is not None else ""
    return (ns or "").strip().rstrip("/")


def remap(p, *froms) -> str | None:
    """ROS 2 ``<ros><remapping>~/out:=scan</remapping>`` target for one of ``froms``."""
    for r in p.node.iter():
        if r.tag in ("remapping", "argument") and r.text and ":=" in r.text:
            a, b = r.text.strip().split(":=", 1)
            if a.strip() in froms:
                return b.strip()
    return None


def camera_scope(p) -> str:
    """``cameraName`` of a camera plugin (its topics live under it), else ''."""
    if kind(p) not in CAMERA_KINDS:
        return ""
    return (param(p, "cameraName", "camera_name") or "").strip("/")


def resolve(name: str | None, *scope: str | None) -> str | None:
    """``name`` under the scope parts (outermost first, empty ones skipped); an absolute name or
    scope part starts over. None when there is no name."""
    if not name:
        return None
    out = ""
    for part in (*scope, name):
        if not part:
            continue
        out = part if part.startswith("/") or not out else out.rstrip("/") + "/" + part
    return out


def sensor_topic(p, default: str | None = None) -> str | None:
    """The data topic of a ROS sensor plugin (camera image, scan, range, imu), as the model names
    it: relative unless the model gave an absolute name. ``default`` when the plugin names none."""
    k = kind(p)
    ns = namespace(p)
    if k in CAMERA_KINDS:
        image = param(p, "imageTopicName", "image_topic_name") or remap(p, "image_raw", "~/image_raw")
        return resolve(image or "image_raw", ns, camera_scope(p))
    if k in RAY_KINDS:
        return resolve(param(p, "topicName", "topic_name") or remap(p, "~/out", "out") or default, ns)
    return None


def published_topics(p) -> list[tuple[str, str]]:
    """[(absolute topic, parameter)] the plugin publishes, from the topic parameters it gives and,
    for a ROS 2 ray sensor, its ``~/out`` remapping (names with an unexpanded ``$`` left out: they
    are not known)."""
    ns, camera = namespace(p), camera_scope(p)
    if "$" in camera:
        camera = ""
    given = [(param(p, k), k) for k in TOPIC_KEYS if k not in SUBSCRIBED]
    if kind(p) in RAY_KINDS and not param(p, "topicName", "topic_name"):
        given.append((remap(p, "~/out", "out"), "remapping ~/out"))
    out = []
    for t, k in given:
        if not t or "$" in t:
            continue
        full = resolve(t, ns, camera)
        out.append((full if full.startswith("/") else "/" + full, k))
    return out


def publishes_ranges(p) -> bool:
    """A sonar/IR range plugin (sensor_msgs/Range): several may share one topic by design, as
    each message names its frame (a base's ring of sonars on one topic)."""
    return kind(p) == "sonar" or (param(p, "output_type", "outputType") or "").endswith("Range")


def drive_topics(p, default_command: str | None = None) -> tuple[str, str]:
    """(command topic, odometry topic) of a drive plugin, resolved in its namespace as its node
    resolves them: the topic parameters of any dialect, else the ROS 2 remappings of ``cmd_vel``
    and ``odom``, else ``default_command`` (a vendor plugin's own) or ``cmd_vel``, and ``odom``."""
    cmd = param(p, *COMMAND_KEYS) or remap(p, "cmd_vel", "/cmd_vel") or default_command or "cmd_vel"
    odom = param(p, *ODOMETRY_KEYS) or remap(p, "odom", "/odom") or "odom"
    ns = namespace(p)
    return resolve(cmd, ns), resolve(odom, ns)


def drive_frames(p, base_default: str) -> tuple[str, str]:
    """(odometry frame, base frame) a drive plugin stamps its odometry with."""
    return param(p, *ODOMETRY_FRAME_KEYS) or "odom", param(p, *BASE_FRAME_KEYS) or base_default
