"""The robot model: a typed, read-only view of one URDF document.

Built once (``load_robot`` in loader.py) from a URDF element tree (xmltree's, or lxml's
for what expat leaves to it); every item keeps
its source location (the xacro file:line it came from when the URDF was built
from xacro) and ``ref``, the element it was read from, an opaque handle for
``Robot.sources`` (where each value was written). Checks, converters, the
simulator, the viewer and ``info`` read this model; none of them reads the XML
(only the raw-syntax rules of checks/urdf_syntax.py, which judge the XML itself).
Markup that convert carries into SDF as it is (a sensor's body, a plugin, a
``<gazebo>`` block's ``<visual>`` or ``<joint>``) is an immutable node tree
(model/nodes.py); values are read through one parser (model/values.py).

Pure Python on purpose (no numpy at import): ``build`` and ``--help`` stay fast.
The parts are immutable records (:class:`myrabot_desc.records.Struct`, declared and behaving
like ``typing.NamedTuple``): read-only like frozen dataclasses, but each costs ~10 µs to define
instead of ~1.3 ms (a dataclass) or ~0.15 ms (a NamedTuple), which every command that loads a
model pays at start. Like tuples they compare by value, not by type.
"""

import math
from itertools import repeat
from pathlib import Path

from myrabot_desc.diagnostics import Loc
from myrabot_desc.expand.packages import resolve_resource_uri
from myrabot_desc.model import values as V
from myrabot_desc.model.nodes import Node
from myrabot_desc.model.nodes import node as node_of
from myrabot_desc.model.pin_model import build_model
from myrabot_desc.model.tree import maps
from myrabot_desc.records import Struct
from myrabot_desc.safety import parse_xml_bytes

Vec3 = tuple[float, float, float]


class Pose(Struct):
    xyz: Vec3 = (0.0, 0.0, 0.0)
    rpy: Vec3 = (0.0, 0.0, 0.0)

    @property
    def is_identity(self) -> bool:
        return not any(self.xyz) and not any(self.rpy)


# ---------------------------------------------------------------- geometry
class Box(Struct):
    size: Vec3
    kind = "box"


class Cylinder(Struct):
    radius: float
    length: float
    kind = "cylinder"


class Sphere(Struct):
    radius: float
    kind = "sphere"


class Mesh(Struct):
    filename: str                 # as written in the URDF (package://..., file://..., relative)
    scale: Vec3 = (1.0, 1.0, 1.0)
    path: Path | None = None      # resolved file on disk, or None when it cannot be resolved
    kind = "mesh"


Geometry = Box | Cylinder | Sphere | Mesh


class Material(Struct):
    name: str
    rgba: tuple[float, float, float, float] | None = None
    texture: str | None = None
    loc: Loc | None = None
    ref: object = None               # the URDF element it was read from, for Robot.sources (opaque)


class Visual(Struct):
    origin: Pose
    geometry: Geometry | None
    name: str | None = None
    material_name: str | None = None
    material: Material | None = None   # resolved against robot-level materials when only named
    loc: Loc | None = None
    ref: object = None               # the URDF element it was read from, for Robot.sources (opaque)


class Collision(Struct):
    origin: Pose
    geometry: Geometry | None
    name: str | None = None
    loc: Loc | None = None
    ref: object = None               # the URDF element it was read from, for Robot.sources (opaque)


class Inertial(Struct):
    mass: float
    origin: Pose
    ixx: float = 0.0
    ixy: float = 0.0
    ixz: float = 0.0
    iyy: float = 0.0
    iyz: float = 0.0
    izz: float = 0.0
    loc: Loc | None = None
    ref: object = None               # the URDF element it was read from, for Robot.sources (opaque)

    def tensor(self):
        """3x3 inertia matrix (numpy) in the inertial frame."""
        import numpy as np

        return np.array([[self.ixx, self.ixy, self.ixz],
                         [self.ixy, self.iyy, self.iyz],
                         [self.ixz, self.iyz, self.izz]], dtype=float)


class Link(Struct):
    name: str
    inertial: Inertial | None = None
    visuals: tuple[Visual, ...] = ()
    collisions: tuple[Collision, ...] = ()
    loc: Loc | None = None
    ref: object = None               # the URDF element it was read from, for Robot.sources (opaque)

    @property
    def mass(self) -> float:
        return self.inertial.mass if self.inertial else 0.0


# ---------------------------------------------------------------- joints
class Limit(Struct):
    lower: float | None = None
    upper: float | None = None
    effort: float | None = None
    velocity: float | None = None


class Mimic(Struct):
    joint: str
    multiplier: float = 1.0
    offset: float = 0.0


class Dynamics(Struct):
    damping: float = 0.0
    friction: float = 0.0


JOINT_TYPES = ("revolute", "continuous", "prismatic", "fixed", "floating", "planar")


class Joint(Struct):
    name: str
    type: str
    parent: str
    child: str
    origin: Pose = Pose()
    axis: Vec3 = (1.0, 0.0, 0.0)      # URDF default when <axis> is absent
    limit: Limit | None = None
    mimic: Mimic | None = None
    dynamics: Dynamics | None = None
    loc: Loc | None = None
    ref: object = None               # the URDF element it was read from, for Robot.sources (opaque)

    @property
    def moves(self) -> bool:
        return self.type not in ("fixed",)


# ---------------------------------------------------------------- gazebo extensions
class Plugin(Struct):
    """A Gazebo plugin or Electric-era controller.

    ``dialect``: 'electric' for ``<controller:NAME plugin|filename=...>``, 'classic' for
    ``<plugin name filename>`` (Gazebo classic, ROS 1/2), 'gz' for gz-sim systems
    (``filename="gz-sim-..."`` or ``name="gz::sim::systems::..."``).
    ``params``: direct child element name -> its value (text, else ``value=``; the first
    occurrence of each childless element). ``node``: the whole element (model/nodes.Node), which
    convert copies or quotes as it is. Numbers, booleans and vectors of a parameter are read
    through model/values.py (``number``, ``boolean``, ``vector``); ``robot.origin(plugin, KEY)``
    says where a parameter was written.
    """

    name: str | None
    filename: str | None
    dialect: str
    params: dict[str, str]
    node: Node
    reference: str | None = None      # the <gazebo reference> it sits in, or the sensor's link
    sensor: str | None = None         # name of the enclosing sensor, if any
    file_attr: str | None = None      # which attribute carried the library: 'filename' or 'plugin'
    loc: Loc | None = None
    ref: object = None                   # the URDF element it was read from, for Robot.sources (opaque)

    @property
    def library(self) -> str:
        return (self.filename or "").rsplit("/", 1)[-1]

    @property
    def tag(self) -> str:
        """The element's local name: 'plugin', or an Electric controller's kind ('gazebo_ros_create')."""
        return self.node.tag

    def values(self, key: str) -> list[str]:
        """Every value of a (repeatable) parameter, in order: a direct child's text or ``value=``."""
        return [v for v in (c.value for c in self.node.all(key)) if v]

    def text(self, *keys: str) -> str | None:
        """The first value of the first of ``keys`` the plugin gives."""
        for k in keys:
            v = self.values(k)
            if v:
                return v[0]
        return None

    def param(self, key: str):
        """The parameter's element (a Node: its loc, text, children), None when not given."""
        return self.node.child(key)

    def number(self, key: str, default=None):
        return V.number(self.text(key), default)

    def vector(self, key: str, n: int | None = None, default=None):
        return V.vector(self.text(key), n, default)

    def boolean(self, key: str, default=None):
        """A boolean parameter as the plugin reads it (sdf::Element::Get<bool>: model/values.SDF)."""
        return V.boolean(self.text(key), default)


class Camera(Struct):
    """A sensor's camera as written: ``<camera>`` (SDF, radians) or the Electric
    ``<sensor:camera>``'s own parameters (``hfov`` in degrees: ``unit``)."""

    hfov: float | None = None         # horizontal field of view, in ``unit``
    width: float | None = None        # pixels
    height: float | None = None
    format: str | None = None
    near: float | None = None         # clip planes (m)
    far: float | None = None
    unit: str = "rad"                 # 'rad' (SDF) or 'deg' (Electric)
    count: int = 1                    # <camera> elements (a multicamera has several)


class ScanAxis(Struct):
    samples: float | None = None
    resolution: float | None = None
    min_angle: float | None = None    # in the ray's ``unit``
    max_angle: float | None = None


class Noise(Struct):
    type: str | None = None
    mean: float | None = None
    stddev: float | None = None


class Ray(Struct):
    """A ray (laser, sonar) sensor's scan and range as written: SDF ``<ray>`` or ``<lidar>``
    (``tag``, radians) or the Electric ``<sensor:ray>`` (``tag`` 'electric', degrees)."""

    tag: str                          # 'ray' | 'lidar' | 'electric'
    horizontal: ScanAxis | None = None
    vertical: ScanAxis | None = None
    range_min: float | None = None    # m
    range_max: float | None = None
    range_resolution: float | None = None
    noise: Noise | None = None
    unit: str = "rad"                 # 'rad' or 'deg'
    range_count: float | None = None  # Electric rangeCount (ranges returned over rayCount rays)


class Sonar(Struct):
    """An SDF ``<sonar>`` (Gazebo classic's sonar sensor): a cone of ``radius`` at ``max``."""

    min: float | None = None
    max: float | None = None
    radius: float | None = None


class Sensor(Struct):
    """A ``<sensor type=...>`` (classic/SDF) or Electric ``<sensor:camera|ray ...>``.

    Typed: what check and convert read (rate, topic, pose, camera, rays, sonar); ``node`` is the
    whole element (convert carries an SDF sensor's body into SDF as it is)."""

    name: str | None
    type: str                         # 'camera', 'ray', 'depth', 'imu', ... (Electric: 'camera', 'ray')
    dialect: str                      # 'electric' or 'sdf'
    reference: str | None             # link the sensor is attached to
    node: Node
    plugins: tuple[Plugin, ...] = ()
    loc: Loc | None = None
    ref: object = None                   # the URDF element it was read from, for Robot.sources (opaque)
    update_rate: float | None = None  # Hz (SDF <update_rate>, Electric <updateRate>)
    always_on: bool | None = None     # SDF <always_on>, Electric <alwaysActive>
    visualize: str | None = None      # SDF <visualize>, Electric <displayRays> ('true', 'fan'...), as written
    topic: str | None = None          # SDF <topic>
    pose: tuple | None = None         # SDF <pose> (x y z roll pitch yaw), Electric <origin> (x y z)
    camera: Camera | None = None
    rays: tuple[Ray, ...] = ()        # SDF: one per <ray>/<lidar> element; Electric: one
    sonar: Sonar | None = None

    def param(self, *path: str) -> str | None:
        """Text (else ``value=``) of a descendant element by path, e.g. param('camera', 'horizontal_fov')."""
        n = self.node.find(*path)
        if n is None:
            return None
        return (n.text or "").strip() or n.get("value")


class GazeboBlock(Struct):
    """One ``<gazebo>`` element. ``properties``: its childless children such as material, mu1,
    mu2, kp, kd, fdir1/fdir, selfCollide, turnGravityOff, as written (text or ``value=``);
    ``values``: the same typed as their reader takes them (model/gazebo.py: numbers, vectors,
    flags with sdformat's spellings). ``node``: the whole block (its ``<visual>``, ``<collision>``,
    ``<joint>``... which convert copies into SDF)."""

    reference: str | None
    node: Node
    properties: dict[str, str]
    plugins: tuple[Plugin, ...] = ()
    sensors: tuple[Sensor, ...] = ()
    loc: Loc | None = None
    ref: object = None                   # the URDF element it was read from, for Robot.sources (opaque)
    values: dict = {}


class TransmissionJoint(Struct):
    """A joint a transmission names: ``<joint>`` or a vendor's ``<flexJoint>``, ``<gap_joint>``..."""

    name: str
    tag: str
    interfaces: tuple[str, ...] = ()  # <hardwareInterface> texts as written ('hardware_interface/VelocityJointInterface')
    loc: Loc | None = None
    ref: object = None


class Actuator(Struct):
    name: str | None
    interfaces: tuple[str, ...] = ()
    reduction: float | None = None    # <mechanicalReduction>
    loc: Loc | None = None
    ref: object = None


class Transmission(Struct):
    """A ros_control ``<transmission>``: ``joints`` the names of its ``<joint>`` children (as
    urdfdom reads them), ``named`` every element below it that names a joint (PR2's
    ``<flexJoint>``, ``<gap_joint>``...), ``actuators`` its actuators."""

    name: str | None
    joints: tuple[str, ...] = ()
    type: str | None = None           # <type> text or type= (ROS 1 old style)
    loc: Loc | None = None
    ref: object = None
    node: Node | None = None
    named: tuple[TransmissionJoint, ...] = ()
    actuators: tuple[Actuator, ...] = ()


class ControlJoint(Struct):
    """A ``<joint>`` (or ``<sensor>``, ``<gpio>``) of a ``<ros2_control>`` block."""

    name: str
    command_interfaces: tuple[str, ...] = ()    # their name= ('' for a nameless one)
    state_interfaces: tuple[str, ...] = ()
    params: dict = {}
    loc: Loc | None = None
    ref: object = None
    kind: str = "joint"


class Ros2Control(Struct):
    """A ``<ros2_control>`` block: its hardware plugin and the joints it commands."""

    name: str | None
    type: str | None = None
    hardware: str | None = None       # <hardware><plugin> text
    hardware_params: dict = {}
    joints: tuple[ControlJoint, ...] = ()
    sensors: tuple[ControlJoint, ...] = ()
    loc: Loc | None = None
    ref: object = None
    node: Node | None = None


class Declared:
    """A top-level ``<link>``, ``<joint>`` or ``<material>`` as written, duplicates and nameless ones
    included (the typed dicts keep one per name): what check's T002 and T004 judge. ``loc`` is
    looked up when asked (a 20,000-link file has 40,000 of these and few duplicates)."""

    __slots__ = ("tag", "name", "child", "ref", "_robot")

    def __init__(self, tag: str, name: str | None, child: str | None, ref, robot):
        self.tag, self.name, self.child, self.ref, self._robot = tag, name, child, ref, robot

    @property
    def loc(self) -> Loc | None:
        return self._robot.loc_of(self.ref)


# ---------------------------------------------------------------- the robot
class SourceLines:
    """``Robot.element_locs`` of a URDF read from one file: each element's location is that file
    and the element's own line, so nothing is stored per element. ``values()`` gives the location
    of every element, as the id -> Loc dict of a built model does."""

    __slots__ = ("file", "root")

    def __init__(self, file: str, root):
        self.file, self.root = file, root

    def loc(self, el) -> Loc | None:
        """The element's location, None for a comment or an element of another document."""
        if el is None or not isinstance(el.tag, str) or el.getroottree().getroot() is not self.root:
            return None
        return Loc(self.file, el.sourceline)

    def values(self):
        return (Loc(self.file, el.sourceline) for el in self.root.iter() if isinstance(el.tag, str))


class Robot:
    """One robot: its parts by name, where it was read from, and the facts derived from it.

    A plain class, not a dataclass: a dataclass compiles its generated methods when it is defined
    (~0.6 ms a class), which every command that loads a model would pay at start."""

    def __init__(self, name: str, links: dict[str, Link], joints: dict[str, Joint],
                 materials: dict[str, Material], gazebo: tuple[GazeboBlock, ...],
                 transmissions: tuple[Transmission, ...], root_element: object, source: Path | None,
                 urdf_text: str, loc: Loc | None = None, package_roots: dict[str, Path] | None = None,
                 allow_roots: tuple = (), build_warnings: list | None = None, from_xacro: bool = False,
                 load_issues: list | None = None, element_locs: dict | SourceLines | None = None,
                 _elements: list | None = None, source_map: object = None, source_bytes: bytes | None = None,
                 derived: dict | None = None, ros2_control: tuple = ()):
        self.name = name
        self.links = links
        self.joints = joints
        self.materials = materials
        self.gazebo = gazebo
        self.transmissions = transmissions
        self.root_element = root_element            # the <robot> element (xmltree's or lxml's)
        self.source = source                        # the file the user gave (xacro or urdf)
        self.urdf_text = urdf_text                  # the URDF document as text (built or read)
        self.loc = loc
        self.package_roots = {} if package_roots is None else package_roots   # packages the build resolved
        self.allow_roots = allow_roots    # --allow-path folders: meshes and textures may come from them too
        self.build_warnings = [] if build_warnings is None else build_warnings   # Diagnostics from build (X codes)
        self.from_xacro = from_xacro
        # Problems found while reading (bad numbers, unknown joint types...) that checks report.
        self.load_issues = [] if load_issues is None else load_issues
        # id(element of root_element) -> Loc, for consumers that walk the raw XML (check's T005/T006);
        # a SourceLines for a URDF read from one file (use loc_of rather than this map).
        self.element_locs = {} if element_locs is None else element_locs
        self._elements = [] if _elements is None else _elements   # keeps those elements (lxml's proxies) and ids alive
        # Where the build says each output value came from (expand/provenance.SourceMap), or for a
        # URDF read from one file its bytes: Robot.sources reads spans from them when asked.
        self.source_map = source_map
        self.source_bytes = source_bytes
        # Facts derived from the robot, built once by whoever needs them first (``derive``); the robot
        # is not modified after loading, so they stay true for its lifetime.
        self.derived = {} if derived is None else derived
        self.ros2_control = ros2_control            # Ros2Control blocks, in file order

    def __repr__(self) -> str:
        return f"Robot(name={self.name!r}, links={len(self.links)}, joints={len(self.joints)}, source={self.source!r})"

    def derive(self, key, build):
        """``build()``, built once for this robot under ``key``: the one cache of facts derived from
        a robot (its tree maps, transforms, drives, source spans, check's and sim's facts). A key
        names what the fact depends on besides the robot (check's mesh reading, sim's wheels)."""
        d = self.derived
        if key in d:
            return d[key]
        value = d[key] = build()
        return value

    def declared(self, tag: str) -> list[Declared]:
        """Every top-level ``<tag>`` element (link, joint, material) as written, in file order:
        duplicates and nameless ones included (``links``/``joints``/``materials`` keep one per name)."""
        def build():
            out = []
            add = out.append
            for el in self.root_element.iterchildren(tag):
                child = None
                if tag == "joint":
                    for c in el:            # the first <child> (a loop costs less than an iterator)
                        if c.tag == "child":
                            child = c.get("link")
                            break
                add(Declared(tag, el.get("name"), child, el, self))
            return tuple(out)
        return list(self.derive(("declared", tag), build))

    def declare(self, tag: str, elements, names, children=None) -> None:
        """Give ``declared(tag)`` from what the reader read already: the top-level ``<tag>`` elements in
        document order, their names, and (joints) their first ``<child>``'s link."""
        self.derived[("declared", tag)] = tuple(map(Declared, repeat(tag), names, repeat(None) if children is None
                                                    else children, elements, repeat(self)))

    def loc_of(self, el) -> Loc | None:
        """Source location of an element of ``root_element`` (None when unknown)."""
        if type(self.element_locs) is dict:
            return self.element_locs.get(id(el))
        return self.element_locs.loc(el)

    def node(self, part) -> Node | None:
        """``part``'s element as a Node (markup as written, for what no typed field holds: a joint's
        ``<safety_controller>``), or None for a part not read from a document."""
        ref = getattr(part, "ref", None)
        return None if ref is None else node_of(ref, self.loc_of)

    def top_nodes(self) -> list:
        """The robot's top-level elements as Nodes, in document order."""
        return self.derive("top_nodes", lambda: list(node_of(self.root_element, self.loc_of).elements))

    @property
    def sources(self):
        """Where each value was written (model/sources.Sources): ``robot.sources.origin(part.ref, attr)``."""
        from myrabot_desc.model.sources import Sources     # spans are read for a fix or a diff only

        def build():
            plain = None
            if self.source_map is None and self.source_bytes is not None:
                plain = (str(self.loc.file) if self.loc else str(self.source), self.source, self.source_bytes)
            return Sources(self.root_element, self.source_map, plain)
        return self.derive("sources", build)

    def origin(self, part, field: str):
        """Where ``field`` of ``part`` was written (model/sources.Origin): ``robot.origin(joint, "limit.effort")``."""
        return self.sources.field(part, field)

    def source_files(self) -> list[str]:
        """The files the model's elements came from (the input and, for xacro, its includes), in
        order of first use; one file for a URDF read from one file, without visiting its elements."""
        if type(self.element_locs) is dict:
            return list(dict.fromkeys(loc.file for loc in self.element_locs.values() if loc is not None))
        return [self.element_locs.file]

    def source_data(self) -> dict[str, bytes]:
        """Shown file name -> the bytes the model was built or read from, as far as they are kept (the
        build's source map, or a URDF file's bytes): what its comments say, without reading again."""
        if self.source_map is not None:
            return {name: data for name, (_path, data) in self.source_map.files.items()}
        if self.source_bytes is not None and type(self.element_locs) is not dict:
            return {self.element_locs.file: self.source_bytes}
        return {}

    def rest_pose(self) -> dict[str, float]:
        """Every moving, non-mimic joint at 0, or at its nearer limit when its finite range leaves
        0 out (a quadruped's knee): the pose render, the viewer and the MJCF ``home`` start from.
        Built once per robot, a fresh copy each call (callers change theirs)."""
        def build():
            out = {}
            for j in self.joints.values():
                if j.type not in ("revolute", "continuous", "prismatic") or j.mimic is not None:
                    continue
                lo, hi = (j.limit.lower, j.limit.upper) if j.limit is not None and j.type != "continuous" \
                    else (None, None)
                ok = lo is not None and hi is not None and math.isfinite(lo) and math.isfinite(hi) and lo <= hi
                out[j.name] = min(max(0.0, float(lo)), float(hi)) if ok else 0.0
            return out
        return dict(self.derive("rest_pose", build))

    # -------------------------------------------------------- tree helpers
    def child_joints(self, link: str) -> list[Joint]:
        return list(maps(self).child_joints.get(link, ()))

    def joints_by_parent(self) -> dict[str, list[Joint]]:
        """Parent link -> the joints hanging from it, in document order (for walking the tree). Built
        once per robot and shared (model/tree.maps): read it, never change it."""
        return maps(self).child_joints

    def parent_joint(self, link: str) -> Joint | None:
        return maps(self).parent_joint.get(link)

    @property
    def roots(self) -> list[str]:
        """The links no joint hangs from, in file order: a fresh list each call, made once per robot
        (a 20,000-link check asks seven times) and again only if its link or joint map is replaced
        or resized, as world_transforms' zero configuration."""
        key = (id(self.links), len(self.links), id(self.joints), len(self.joints))
        got = self.derived.get("roots")
        if got is None or got[0] != key:
            children = {j.child for j in self.joints.values()}
            got = self.derived["roots"] = (key, [n for n in self.links if n not in children])
        return list(got[1])

    @property
    def root(self) -> str | None:
        r = self.roots
        return r[0] if len(r) == 1 else None

    @property
    def total_mass(self) -> float:
        return sum(link.mass for link in self.links.values())

    def plugins(self) -> list[Plugin]:
        """Every plugin/controller, top-level or inside sensors."""
        out: list[Plugin] = []
        for g in self.gazebo:
            out.extend(g.plugins)
            for s in g.sensors:
                out.extend(s.plugins)
        return out

    def sensors(self) -> list[Sensor]:
        return [s for g in self.gazebo for s in g.sensors]

    def resolve_uri(self, uri: str) -> Path | None:
        """package://, file:// or a relative path -> a file on disk, or None."""

        base = self.source.parent if self.source else Path.cwd()
        return resolve_resource_uri(uri, self.package_roots, base, self.allow_roots)

    def pinocchio(self, floating: bool = False):
        """A Pinocchio model of this robot (built on demand; see pin_bridge)."""

        return build_model(self, floating=floating)

    def to_yourdfpy(self, load_meshes: bool = False, build_scene_graph: bool = True):
        """This robot as a ``yourdfpy.URDF``, for Python users of yourdfpy (the tests use it as an
        independent check of our kinematics).

        Built from ``urdf_text`` read by our own parser (no DTD, entities or network) and cleaned as
        ``yourdfpy.URDF.load`` cleans a file; mesh file names go through :meth:`resolve_uri`, so only
        files under the input's folder and the package roots can be opened, and one that does not
        resolve is left out, as yourdfpy leaves out a file it cannot find. Meshes are loaded (by
        trimesh, through yourdfpy) only with ``load_meshes``."""
        import yourdfpy
        from lxml import etree

        root = parse_xml_bytes(self.urdf_text.encode("utf-8"), str(self.source or "<urdf>"))
        etree.strip_tags(root, etree.Comment)
        etree.cleanup_namespaces(root)

        def filename(fname: str) -> str:
            path = self.resolve_uri(fname)
            return str(path) if path is not None else ""

        return yourdfpy.URDF(robot=yourdfpy.URDF._parse_robot(xml_element=root), build_scene_graph=build_scene_graph,
                             load_meshes=load_meshes, filename_handler=filename)
