"""The robot model: a typed, read-only view of one URDF document.

Built once (``load_robot`` in loader.py) from a URDF lxml tree; every item keeps
its source location (the xacro file:line it came from when the URDF was built
from xacro). Checks, converters, the simulator and ``info`` read this model;
none of them parses the XML again. Raw lxml elements are kept where a consumer
needs the original markup (``<gazebo>`` blocks, the Electric ``controller:`` /
``sensor:`` dialect, transmissions).

Pure Python on purpose (no numpy at import): ``build`` and ``--help`` stay fast.
The parts are immutable records (``typing.NamedTuple``): read-only like frozen
dataclasses, but each costs ~0.1 ms to define instead of ~1.3 ms, which was 20 ms of
every command that loads a model. Like tuples they compare by value, not by type.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, NamedTuple

from myrabot_desc.diagnostics import Loc
from myrabot_desc.expand.packages import resolve_resource_uri
from myrabot_desc.model.pin_model import build_model
from myrabot_desc.model.sources import Sources
from myrabot_desc.model.tree import maps
from myrabot_desc.safety import parse_xml_bytes

Vec3 = tuple[float, float, float]


class Pose(NamedTuple):
    xyz: Vec3 = (0.0, 0.0, 0.0)
    rpy: Vec3 = (0.0, 0.0, 0.0)

    @property
    def is_identity(self) -> bool:
        return not any(self.xyz) and not any(self.rpy)


# ---------------------------------------------------------------- geometry
class Box(NamedTuple):
    size: Vec3
    kind = "box"


class Cylinder(NamedTuple):
    radius: float
    length: float
    kind = "cylinder"


class Sphere(NamedTuple):
    radius: float
    kind = "sphere"


class Mesh(NamedTuple):
    filename: str                 # as written in the URDF (package://..., file://..., relative)
    scale: Vec3 = (1.0, 1.0, 1.0)
    path: Path | None = None      # resolved file on disk, or None when it cannot be resolved
    kind = "mesh"


Geometry = Box | Cylinder | Sphere | Mesh


class Material(NamedTuple):
    name: str
    rgba: tuple[float, float, float, float] | None = None
    texture: str | None = None
    loc: Loc | None = None
    ref: Any = None               # the URDF element it was read from, for Robot.sources (opaque)


class Visual(NamedTuple):
    origin: Pose
    geometry: Geometry | None
    name: str | None = None
    material_name: str | None = None
    material: Material | None = None   # resolved against robot-level materials when only named
    loc: Loc | None = None
    ref: Any = None               # the URDF element it was read from, for Robot.sources (opaque)


class Collision(NamedTuple):
    origin: Pose
    geometry: Geometry | None
    name: str | None = None
    loc: Loc | None = None
    ref: Any = None               # the URDF element it was read from, for Robot.sources (opaque)


class Inertial(NamedTuple):
    mass: float
    origin: Pose
    ixx: float = 0.0
    ixy: float = 0.0
    ixz: float = 0.0
    iyy: float = 0.0
    iyz: float = 0.0
    izz: float = 0.0
    loc: Loc | None = None
    ref: Any = None               # the URDF element it was read from, for Robot.sources (opaque)

    def tensor(self):
        """3x3 inertia matrix (numpy) in the inertial frame."""
        import numpy as np

        return np.array([[self.ixx, self.ixy, self.ixz],
                         [self.ixy, self.iyy, self.iyz],
                         [self.ixz, self.iyz, self.izz]], dtype=float)


class Link(NamedTuple):
    name: str
    inertial: Inertial | None = None
    visuals: tuple[Visual, ...] = ()
    collisions: tuple[Collision, ...] = ()
    loc: Loc | None = None
    ref: Any = None               # the URDF element it was read from, for Robot.sources (opaque)

    @property
    def mass(self) -> float:
        return self.inertial.mass if self.inertial else 0.0


# ---------------------------------------------------------------- joints
class Limit(NamedTuple):
    lower: float | None = None
    upper: float | None = None
    effort: float | None = None
    velocity: float | None = None


class Mimic(NamedTuple):
    joint: str
    multiplier: float = 1.0
    offset: float = 0.0


class Dynamics(NamedTuple):
    damping: float = 0.0
    friction: float = 0.0


JOINT_TYPES = ("revolute", "continuous", "prismatic", "fixed", "floating", "planar")


class Joint(NamedTuple):
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
    ref: Any = None               # the URDF element it was read from, for Robot.sources (opaque)

    @property
    def moves(self) -> bool:
        return self.type not in ("fixed",)


# ---------------------------------------------------------------- gazebo extensions
class Plugin(NamedTuple):
    """A Gazebo plugin or Electric-era controller.

    ``dialect``: 'electric' for ``<controller:NAME plugin|filename=...>``, 'classic' for
    ``<plugin name filename>`` (Gazebo classic, ROS 1/2), 'gz' for gz-sim systems
    (``filename="gz-sim-..."`` or ``name="gz::sim::systems::..."``).
    ``params``: direct child element name -> text (first occurrence; attribute
    ``value=`` is accepted as text). ``element`` is the raw lxml element.
    """

    name: str | None
    filename: str | None
    dialect: str
    params: dict[str, str]
    element: Any
    reference: str | None = None      # the <gazebo reference> it sits in, or the sensor's link
    sensor: str | None = None         # name of the enclosing sensor, if any
    file_attr: str | None = None      # which attribute carried the library: 'filename' or 'plugin'
    loc: Loc | None = None

    @property
    def library(self) -> str:
        return (self.filename or "").rsplit("/", 1)[-1]


class Sensor(NamedTuple):
    """A ``<sensor type=...>`` (classic/SDF) or Electric ``<sensor:camera|ray ...>``."""

    name: str | None
    type: str                         # 'camera', 'ray', 'depth', 'imu', ... (Electric: 'camera', 'ray')
    dialect: str                      # 'electric' or 'sdf'
    reference: str | None             # link the sensor is attached to
    element: Any
    plugins: tuple[Plugin, ...] = ()
    loc: Loc | None = None

    def param(self, *path: str) -> str | None:
        """Text of a descendant element by path, e.g. param('camera', 'horizontal_fov')."""
        el = self.element
        for p in path:
            el = next((c for c in el if _local(c.tag) == p), None)
            if el is None:
                return None
        return (el.text or "").strip() or el.get("value")


class GazeboBlock(NamedTuple):
    """One ``<gazebo>`` element. ``properties``: simple children such as material,
    mu1, mu2, kp, kd, fdir1/fdir, selfCollide, turnGravityOff (text or value=)."""

    reference: str | None
    element: Any
    properties: dict[str, str]
    plugins: tuple[Plugin, ...] = ()
    sensors: tuple[Sensor, ...] = ()
    loc: Loc | None = None


class Transmission(NamedTuple):
    name: str | None
    element: Any
    joints: tuple[str, ...] = ()
    loc: Loc | None = None


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


@dataclass
class Robot:
    name: str
    links: dict[str, Link]
    joints: dict[str, Joint]
    materials: dict[str, Material]
    gazebo: tuple[GazeboBlock, ...]
    transmissions: tuple[Transmission, ...]
    root_element: Any                     # lxml <robot> element (annotation-free)
    source: Path | None                   # the file the user gave (xacro or urdf)
    urdf_text: str                        # the URDF document as text (built or read)
    loc: Loc | None = None
    package_roots: dict[str, Path] = field(default_factory=dict)   # packages the build resolved
    build_warnings: list = field(default_factory=list)              # Diagnostics from build (X codes)
    from_xacro: bool = False
    # Problems found while reading (bad numbers, unknown joint types...) that checks report.
    load_issues: list = field(default_factory=list)
    # id(lxml element of root_element) -> Loc, for consumers that walk the raw XML (check's T005/T006);
    # a SourceLines for a URDF read from one file (use loc_of rather than this map).
    element_locs: dict | SourceLines = field(default_factory=dict, repr=False)
    _elements: list = field(default_factory=list, repr=False)      # keeps those lxml proxies (and ids) alive
    # Where the build says each output value came from (expand/provenance.SourceMap), or for a
    # URDF read from one file its bytes: Robot.sources reads spans from them when asked.
    source_map: Any = field(default=None, repr=False, compare=False)
    source_bytes: bytes | None = field(default=None, repr=False, compare=False)
    # Facts derived from the robot, built once by whoever needs them first (sim/prepared.py);
    # the robot is not modified after loading, so they stay true for its lifetime.
    derived: dict = field(default_factory=dict, repr=False, compare=False)

    def loc_of(self, el) -> Loc | None:
        """Source location of an element of ``root_element`` (None when unknown)."""
        if type(self.element_locs) is dict:
            return self.element_locs.get(id(el))
        return self.element_locs.loc(el)

    @property
    def sources(self):
        """Where each value was written (model/sources.Sources): ``robot.sources.origin(part.ref, attr)``."""
        s = self.derived.get("sources")
        if s is None:
            plain = None
            if self.source_map is None and self.source_bytes is not None:
                plain = (str(self.loc.file) if self.loc else str(self.source), self.source, self.source_bytes)
            s = self.derived["sources"] = Sources(self.root_element, self.source_map, plain)
        return s

    def origin(self, part, field: str):
        """Where ``field`` of ``part`` was written (model/sources.Origin): ``robot.origin(joint, "limit.effort")``."""
        return self.sources.field(part, field)

    def source_files(self) -> list[str]:
        """The files the model's elements came from (the input and, for xacro, its includes), in
        order of first use; one file for a URDF read from one file, without visiting its elements."""
        if type(self.element_locs) is dict:
            return list(dict.fromkeys(loc.file for loc in self.element_locs.values() if loc is not None))
        return [self.element_locs.file]

    def rest_pose(self) -> dict[str, float]:
        """Every moving, non-mimic joint at 0, or at its nearer limit when its finite range leaves
        0 out (a quadruped's knee): the pose render, the viewer and the MJCF ``home`` start from."""
        import math

        out = {}
        for j in self.joints.values():
            if j.type not in ("revolute", "continuous", "prismatic") or j.mimic is not None:
                continue
            lo, hi = (j.limit.lower, j.limit.upper) if j.limit is not None and j.type != "continuous" else (None, None)
            ok = lo is not None and hi is not None and math.isfinite(lo) and math.isfinite(hi) and lo <= hi
            out[j.name] = min(max(0.0, float(lo)), float(hi)) if ok else 0.0
        return out

    # -------------------------------------------------------- tree helpers
    def child_joints(self, link: str) -> list[Joint]:
        return list(maps(self).child_joints.get(link, ()))

    def joints_by_parent(self) -> dict[str, list[Joint]]:
        """Parent link -> the joints hanging from it, in document order (for walking the tree)."""
        out: dict[str, list[Joint]] = {}
        for j in self.joints.values():
            out.setdefault(j.parent, []).append(j)
        return out

    def parent_joint(self, link: str) -> Joint | None:
        return maps(self).parent_joint.get(link)

    @property
    def roots(self) -> list[str]:
        children = {j.child for j in self.joints.values()}
        return [n for n in self.links if n not in children]

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
        return resolve_resource_uri(uri, self.package_roots, base)

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


def _local(tag) -> str:
    """Element tag without namespace; Electric 'sensor:camera' keeps its prefix name."""
    if not isinstance(tag, str):
        return ""
    return tag.rsplit("}", 1)[-1]


def deg(x: float) -> float:
    return math.degrees(x)
