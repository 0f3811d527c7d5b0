"""Load a robot: build a xacro file or read a URDF file, then read it into the model.

``load_robot(None)`` loads the bundled MYRAbot (``xacro/myrabot.urdf.xacro`` of
the ``myrabot_description`` package shipped with this tool).
"""

from __future__ import annotations

import re
from pathlib import Path

from myrabot_desc.diagnostics import Diagnostic, Loc
from myrabot_desc.errors import InputError
from myrabot_desc.expand.driver import build_file
from myrabot_desc.expand.packages import (  # noqa: F401  (BUNDLED_ASSEMBLY, bundled_path, data_root: library API)
    BUNDLED_ASSEMBLY,
    PackageResolver,
    bundled_path,
    data_root,
    outside_roots,
    resolve_resource_uri,
    split_package_uri,
)
from myrabot_desc.model import values as V
from myrabot_desc.model.gazebo import NUMBERS, VECTORS, typed_properties
from myrabot_desc.model.nodes import node
from myrabot_desc.model.parts import (
    Actuator,
    Box,
    Camera,
    Collision,
    ControlJoint,
    Cylinder,
    Dynamics,
    GazeboBlock,
    Inertial,
    Joint,
    Limit,
    Link,
    Material,
    Mesh,
    Mimic,
    Noise,
    Plugin,
    Pose,
    Ray,
    Robot,
    Ros2Control,
    ScanAxis,
    Sensor,
    Sonar,
    SourceLines,
    Sphere,
    Transmission,
    TransmissionJoint,
    Visual,
)
from myrabot_desc.safety import Limits, parse_xml_bytes, read_input
from myrabot_desc.xmltree import attribute_values, parse_safely

# Sizes, offsets, masses and inertias beyond this (SI units) are typing errors or attacks: 1e300
# overflows volumes and inertias downstream. Joint limits and dynamics are exempt (1e16 is a
# common "unlimited").
MAX_MAGNITUDE = 1e6

# xacro's namespace as files declare it (any prefix); a generated URDF often keeps the declaration
# with nothing in it, so a file counts as xacro only when it *uses* the namespace or a substitution.
_XACRO_NS = re.compile(rb"""xmlns:([A-Za-z_][\w.-]*)\s*=\s*["']https?://(?:www\.|wiki\.)?ros\.org/(?:wiki/)?xacro/?["']""")
_SUBSTITUTION = re.compile(rb"\$\{|\$\((?:arg|find|env|optenv|eval|dirname|cwd)\s")
_COMMENT = re.compile(rb"<!--.*?(?:-->|\Z)", re.S)
_PREFIXED_TAG = re.compile(rb"<([A-Za-z_][\w.-]*):[A-Za-z_]")


def is_xacro(path: Path, data: bytes | None = None) -> bool:
    """True for a ``.xacro`` name, or for content that uses xacro whatever the name (a drone's top-level
    ``.gazebo`` file built with args): an element in the xacro namespace (``<xacro:include>``), or a
    ``${...}`` / ``$(arg ...)`` substitution, outside comments. ``data``: the file's bytes when read."""
    if path.name.endswith(".xacro"):
        return True
    if data is None:
        return False
    if b"$" not in data and b"xacro" not in data:
        return False        # neither pattern below can match (removing comments adds no character)
    text = _COMMENT.sub(b"", data)
    if _SUBSTITUTION.search(text):
        return True
    prefixes = {m.group(1) for m in _XACRO_NS.finditer(text)}
    # one pass over the prefixed tags (a search per declaration would be quadratic on hostile files)
    return bool(prefixes) and any(m.group(1) in prefixes for m in _PREFIXED_TAG.finditer(text))


def load_robot(path=None, **build_options) -> Robot:
    """Build (xacro: see is_xacro) or read (plain URDF) ``path`` into a Robot. None = bundled MYRAbot."""
    src = Path(path) if path is not None else bundled_path()
    if not src.exists():
        raise InputError(f"no such file: {src}")
    if src.is_dir():
        raise InputError(f"{src} is a folder; give a .urdf or .xacro file")
    data = None
    overlay = build_options.get("overlay")
    if overlay and src.resolve() in overlay:
        data = overlay[src.resolve()]
    elif not is_xacro(src):
        limit = (build_options.get("limits") or Limits()).max_input_bytes
        try:
            size = src.stat().st_size
        except OSError as exc:
            raise InputError(f"cannot read {src}: {exc.strerror}") from None
        if size > limit:
            raise InputError(f"{src} is {size} bytes, over the {limit}-byte limit")
        data = read_input(src, limit)       # bounded: /dev/zero or an endless pipe stops at the limit
    if data is None or is_xacro(src, data):
        result = build_file(src, build_options.pop("mappings", None), **build_options)
        return read_urdf_text(result.text, src, locations=result.locations, package_roots=result.package_roots,
                              root=result.root, source_map=result.source_map,
                              build_warnings=result.diagnostics, from_xacro=True,
                              packages=build_options.get("packages"),
                              package_paths=build_options.get("package_paths", ()),
                              allow_paths=build_options.get("allow_paths") or ())
    return read_urdf_bytes(data, src, packages=build_options.get("packages"),
                           package_paths=build_options.get("package_paths", ()),
                           allow_paths=build_options.get("allow_paths") or ())


# A URDF file up to this size is read by expat into xmltree's elements, saving lxml's import (~15 ms);
# past it lxml's parse in C saves more than that: xmltree builds each element in Python, ~1 us more
# an element of a plain file, where lxml makes few proxies (on generated stars the two are level
# near 1,300 links, 500 kB). A built document is always read by expat (driver.BuildResult.root):
# there the loader maps every element, and lxml's proxies cost more than that.
LEAN_READ_BYTES = 500_000


def read_urdf_bytes(data: bytes, src: Path, packages=None, package_paths=(), allow_paths=()) -> Robot:
    root = parse_safely(data, str(src)) if len(data) <= LEAN_READ_BYTES else parse_xml_bytes(data, str(src))
    text = data.decode("utf-8", errors="replace")
    robot = _read(root, text, src, None, {}, [], False, packages, package_paths, allow_paths)
    robot.source_bytes = data
    return robot


def read_urdf_text(text: str, src: Path, locations=None, package_roots=None, build_warnings=None,
                   from_xacro=False, packages=None, package_paths=(), root=None, source_map=None,
                   allow_paths=()) -> Robot:
    """Read URDF text into a Robot; ``root`` is the text already parsed (the build hands it over)."""

    if root is None:
        root = parse_safely(text.encode("utf-8"), str(src))
    robot = _read(root, text, src, locations, package_roots or {}, list(build_warnings or []), from_xacro,
                  packages, package_paths, allow_paths)
    robot.source_map = source_map
    return robot


# What a file that is not a URDF robot is, by its root element (for the message that refuses it).
DOCUMENT_KINDS = {"sdf": "an SDF model", "gazebo": "an SDF model (old <gazebo> root)", "mujoco": "a MuJoCo MJCF model",
                  "launch": "a roslaunch file", "world": "a world file", "html": "an HTML page"}


def what_document(tag: str) -> str:
    """'an SDF model (root <sdf>, not <robot>)'... for a root element tag (lxml's: {ns}name)."""
    if tag.startswith("{"):
        ns, name = tag[1:].split("}", 1)
        return f"the root element is <{name}> in namespace {ns}, not a plain <robot>"
    if tag in DOCUMENT_KINDS:
        return f"{DOCUMENT_KINDS[tag]} (root <{tag}>, not <robot>)"
    return f"the root element is <{tag}>, not <robot>"


# ---------------------------------------------------------------- reading
class _Reader:
    def __init__(self, root, src: Path, locations):
        self.src = src
        self.allow_roots: tuple = ()        # --allow-path folders (meshes may come from them)
        self.issues: list[Diagnostic] = []
        # text -> value of the numbers read at the usual limit: a model repeats the same few texts
        # ("0", "1e-4", "0 0 1") in every link, and each parse is a float() and its checks
        self._numbers: dict[str, float] = {}
        self._unlimited: dict[str, float] = {}     # the same for numbers read without a limit
        self._vectors: dict[str, tuple] = {}
        elements = [el for el in root.iter() if isinstance(el.tag, str)] if locations is not None else ()
        if locations is not None and len(locations) == len(elements):
            self.loc_of: dict[int, Loc] | SourceLines = {}
            last = None
            parent_loc: dict[int, Loc] = {}
            for el, loc in zip(elements, locations):
                if loc is None:
                    p = el.getparent()
                    loc = parent_loc.get(id(p)) if p is not None else last
                parent_loc[id(el)] = loc
                self.loc_of[id(el)] = loc
                last = loc or last
            self._keep = elements  # keep proxies alive so id() stays valid
        else:
            # one file: an element's location is its line, read when asked (a map of every element
            # held 2 x 260,000 objects for a 20,000-link star, and the garbage collector rescanned them)
            self.loc_of = SourceLines(str(src), root)
            self._keep = []
        # loc(el): an element's Loc (None for None), without testing the kind of map at each call
        if type(self.loc_of) is dict:
            get = self.loc_of.get
            self.loc = lambda el: None if el is None else get(id(el))
        else:
            file = self.loc_of.file
            by_line: dict = {}      # line -> its Loc: immutable, so the elements of one line share it

            def loc(el):
                if el is None:
                    return None
                line = el.sourceline
                found = by_line.get(line)
                if found is None:
                    found = by_line[line] = Loc(file, line)
                return found
            self.loc = loc

    def issue(self, el, message: str, code: str = "T010") -> None:
        self.issues.append(Diagnostic(code, "error", message, self.loc(el)))

    def num(self, el, attr: str, default: float | None = 0.0, limit: float | None = MAX_MAGNITUDE) -> float | None:
        raw = el.get(attr)
        if raw is None:
            return default
        cache = self._numbers if limit is MAX_MAGNITUDE else self._unlimited if limit is None else None
        if cache is not None:
            v = cache.get(raw)
            if v is not None:
                return v
        try:
            v = V.parse_number(raw, limit)
        except V.ValueProblem as exc:
            self.issue(el, V.problem(el.tag, raw, exc.reason, attr))
            return default
        if cache is not None:
            cache[raw] = v
        return v

    def nums(self, el, attrs: tuple, default: float | None, limit: float | None = MAX_MAGNITUDE) -> list:
        """[num(el, a, default, limit) for a in attrs], the texts seen before taken from the cache."""
        cache = self._numbers if limit is MAX_MAGNITUDE else self._unlimited if limit is None else {}
        get = el.get
        out = []
        for a in attrs:
            raw = get(a)
            v = cache.get(raw) if raw is not None else default
            out.append(v if v is not None or raw is None else self.num(el, a, default, limit))
        return out

    def vec(self, el, attr: str, default=(0.0, 0.0, 0.0), n: int = 3) -> tuple:
        raw = el.get(attr) if el is not None else None
        if raw is None:
            return default
        v = self._vectors.get(raw) if n == 3 else None
        if v is not None:
            return v
        try:
            v = V.parse_vector(raw, n, MAX_MAGNITUDE)
        except V.ValueProblem as exc:
            self.issue(el, V.problem(el.tag, raw, exc.reason, attr))
            return default
        if n == 3:
            self._vectors[raw] = v
        return v

    def pose(self, el, kids: dict | None = None) -> Pose:
        """The <origin> of ``el``; ``kids``: _kids(el) when the caller has it."""
        o = (kids if kids is not None else _kids(el)).get("origin") if el is not None else None
        if o is None:
            return _NO_ORIGIN
        return Pose(self.vec(o, "xyz"), self.vec(o, "rpy"))

    def geometry(self, kids: dict, robot_src_dir: Path, package_roots, resolve):
        """The shape in the <geometry> among ``kids`` (_kids of a <visual> or <collision>)."""
        g = kids.get("geometry")
        if g is None:
            return None
        shape = tag = None
        for c in g:                     # the first element (a generator costs more than the search)
            tag = c.tag
            if isinstance(tag, str):
                shape = c
                break
        if shape is None:
            self.issue(g, "<geometry> is empty")
            return None
        if tag == "box":
            return Box(self.vec(shape, "size"))
        if tag == "cylinder":
            return Cylinder(self.num(shape, "radius"), self.num(shape, "length"))
        if tag == "sphere":
            return Sphere(self.num(shape, "radius"))
        if tag == "mesh":
            fn = shape.get("filename", "")
            path = resolve(fn) if fn else None
            if fn and path is None:
                if outside_roots(fn, package_roots, robot_src_dir, self.allow_roots) is not None:
                    self.issue(shape, f"mesh {fn} lies outside the allowed folders (the model's package and folder): not read "
                               "(a model may only use files of its own package or of the packages it names)",
                               code="X006")
            return Mesh(fn, self.vec(shape, "scale", (1.0, 1.0, 1.0)), path)
        self.issue(shape, f"unknown geometry <{shape.tag}>")
        return None

    def material(self, el) -> Material | None:
        if el is None:
            return None
        kids = _kids(el)
        color = kids.get("color")
        rgba = self.vec(color, "rgba", None, 4) if color is not None else None
        tex = kids.get("texture")
        return Material(el.get("name", ""), rgba, tex.get("filename") if tex is not None else None, self.loc(el), el)

    def inertial(self, kids: dict) -> Inertial | None:
        """The <inertial> among ``kids`` (_kids of a <link>)."""
        i = kids.get("inertial")
        if i is None:
            return None
        ik = _kids(i)
        m = ik.get("mass")
        mass = self.num(m, "value", 0.0) if m is not None else 0.0
        t = ik.get("inertia")
        ixx, ixy, ixz, iyy, iyz, izz = self.nums(t, _INERTIA, 0.0) if t is not None else _NO_INERTIA
        return Inertial(mass, self.pose(i, ik), ixx, ixy, ixz, iyy, iyz, izz, self.loc(i), i)


_INERTIA = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
_NO_INERTIA = (0.0,) * 6
_LIMIT = ("lower", "upper", "effort", "velocity")


_NO_ORIGIN = Pose()    # one shared (immutable) identity for every element without <origin>
_X_AXIS = (1.0, 0.0, 0.0)   # URDF's axis when <axis> or its xyz is absent


def _kids(el) -> dict:
    """tag -> the first child element with that tag: ``el.find(tag)`` for every tag in one pass (find
    compiles its path on each call, ~5 µs: most of reading a 20,000-link tree went there). Comments
    and processing instructions are in it too, under their own tags, which no element's name is:
    every caller looks up a name."""
    out = {}
    put = out.setdefault
    for c in el:
        put(c.tag, c)
    return out


def _may_name_packages(root, text: str) -> bool:
    """False when no attribute of the document ``text`` (parsed as ``root``) can hold ``package:``:
    the text lacks it, and no character reference (``&#112;``) can spell it. Only for a document whose
    encoding writes ASCII as ASCII (the text of a file is its bytes read as UTF-8)."""
    ascii_as_ascii = (root.getroottree().docinfo.encoding or "").upper() in ("UTF-8", "US-ASCII", "ASCII")
    return "package:" in text or "&#" in text or not ascii_as_ascii


def _read(*args) -> Robot:
    """_read_model with the cyclic garbage collector paused: reading allocates ~300,000 long-lived
    records and makes no cycles, and each full collection on the way rescans all of them."""
    import gc

    paused = gc.isenabled()
    gc.disable()
    try:
        return _read_model(*args)
    finally:
        if paused:
            gc.enable()


def _read_model(root, text, src: Path, locations, package_roots, build_warnings, from_xacro, packages,
                package_paths, allow_paths=()) -> Robot:
    if root.tag != "robot":
        loc = locations[0] if locations and locations[0] is not None else Loc(str(src), root.sourceline)
        raise InputError(f"{what_document(root.tag)}: check, convert, info and sim read URDF robots; "
                         "`build` expands any xacro file", loc)
    r = _Reader(root, src, locations)

    # Resolve every package named by a package:// URI (meshes, textures).
    roots = dict(package_roots)
    resolver = None
    # the attributes themselves, as plain strings: a third faster than their elements (in C: 260,000
    # elements in a big tree); and none at all when no value can start with package:// (the scan of
    # every attribute is most of the cost)
    named = attribute_values(root, "filename") if _may_name_packages(root, text) else ()
    for fn in named:
        parts = split_package_uri(fn) if fn else None
        if parts and parts[0] not in roots:
            if resolver is None:
                resolver = PackageResolver(packages, package_paths, input_file=src)
            p = resolver.find(parts[0])
            if p is not None:
                roots[parts[0]] = p
    base = src.parent
    extra = r.allow_roots = tuple(Path(p).expanduser().resolve() for p in allow_paths)

    resolved: dict[str, Path | None] = {}

    def resolve(uri: str):
        # models name the same mesh many times (visual and collision, repeated parts); each
        # resolution stats and realpaths the candidates
        if uri not in resolved:
            resolved[uri] = resolve_resource_uri(uri, roots, base, extra)
        return resolved[uri]

    top: dict = {"material": [], "link": [], "joint": [], "gazebo": [], "transmission": []}
    control = []
    for el in root:                     # the top-level elements by tag, in one pass
        found = top.get(el.tag)
        if found is not None:
            found.append(el)
        elif isinstance(el.tag, str) and _local(el) == "ros2_control":
            control.append(el)

    materials: dict[str, Material] = {}
    for m in top["material"]:
        mat = r.material(m)
        if mat.name:
            materials.setdefault(mat.name, mat)

    loc, pose, geometry, kids_of = r.loc, r.pose, r.geometry, _kids     # (locals: 20,000 links and joints)
    links: dict[str, Link] = {}
    link_names = []                     # every <link>'s name as written, for Robot.declared
    for el in top["link"]:
        name = el.get("name")
        link_names.append(name)
        if not name:
            r.issue(el, "<link> without a name")
            continue
        visuals = []
        first: dict = {}
        vis_els, col_els = [], []
        for c in el:
            t = c.tag
            if t == "visual":
                vis_els.append(c)
            elif t == "collision":
                col_els.append(c)
            first.setdefault(t, c)          # (a comment's tag is no element's name)
        for v in vis_els:
            vk = kids_of(v)
            mel = vk.get("material")
            mat = r.material(mel) if mel is not None else None
            mname = mat.name if mat else None
            if mat is not None and mat.rgba is None and mat.texture is None and mname in materials:
                mat = materials[mname]
            if mat is not None and mname and mname not in materials and (mat.rgba or mat.texture):
                materials[mname] = mat
            visuals.append(Visual(pose(v, vk), geometry(vk, base, roots, resolve), v.get("name"), mname, mat,
                                  loc(v), v))
        collisions = []
        for c in col_els:
            ck = kids_of(c)
            collisions.append(Collision(pose(c, ck), geometry(ck, base, roots, resolve), c.get("name"), loc(c), c))
        if name in links:
            continue  # duplicates are reported by the tree rules from the XML
        links[name] = Link(name, r.inertial(first), tuple(visuals), tuple(collisions), loc(el), el)

    joints: dict[str, Joint] = {}
    joint_names, joint_children = [], []
    vec, nums = r.vec, r.nums
    for el in top["joint"]:
        name = el.get("name")
        jtype = el.get("type", "")
        kids = kids_of(el)
        p, c = kids.get("parent"), kids.get("child")
        child = c.get("link") if c is not None else None
        joint_names.append(name)
        joint_children.append(child)
        if not name:
            r.issue(el, "<joint> without a name")
            continue
        parent = p.get("link") if p is not None else None
        if not parent or not child:
            r.issue(el, f"joint '{name}' needs <parent link=...> and <child link=...>")
            continue
        axis_el = kids.get("axis")
        axis = vec(axis_el, "xyz", _X_AXIS) if axis_el is not None else _X_AXIS
        lim = kids.get("limit")
        limit = Limit(*nums(lim, _LIMIT, None, limit=None)) if lim is not None else None
        mim = kids.get("mimic")
        mimic = Mimic(mim.get("joint", ""), r.num(mim, "multiplier", 1.0), r.num(mim, "offset", 0.0)) \
            if mim is not None else None
        dyn = kids.get("dynamics")
        dynamics = Dynamics(r.num(dyn, "damping", 0.0, limit=None), r.num(dyn, "friction", 0.0, limit=None)) \
            if dyn is not None else None
        if name in joints:
            continue
        joints[name] = Joint(name, jtype, parent, child, pose(el, kids), axis, limit, mimic, dynamics, loc(el), el)

    gazebo = tuple(_gazebo_block(r, g) for g in top["gazebo"])
    transmissions = tuple(_transmission(r, t) for t in top["transmission"])
    ros2_control = tuple(_ros2_control(r, b) for b in control)

    robot = Robot(name=root.get("name", ""), links=links, joints=joints, materials=materials, gazebo=gazebo,
                  transmissions=transmissions, root_element=root, source=src, urdf_text=text, loc=r.loc(root),
                  package_roots=roots, allow_roots=extra, build_warnings=build_warnings, from_xacro=from_xacro,
                  load_issues=r.issues, element_locs=r.loc_of, _elements=r._keep, ros2_control=ros2_control)
    # the elements, names and <child> links read above, rather than a second pass over 40,000 elements
    # (for the few top-level materials too: lxml's iterchildren("material") tests every child)
    robot.declare("link", top["link"], link_names)
    robot.declare("joint", top["joint"], joint_names, joint_children)
    robot.declare("material", top["material"], [m.get("name") for m in top["material"]])
    return robot


# ---------------------------------------------------------------- gazebo extensions
def _ns(el) -> str:
    tag = el.tag if isinstance(el.tag, str) else ""
    return tag[1:].split("}", 1)[0] if tag.startswith("{") else ""


def _local(el) -> str:
    return el.tag.rsplit("}", 1)[-1] if isinstance(el.tag, str) else ""


def _text(el) -> str:
    t = (el.text or "").strip()
    return t if t else (el.get("value") or "").strip()


def _params(el) -> dict[str, str]:
    out: dict[str, str] = {}
    for c in el:
        if isinstance(c.tag, str) and len(c) == 0:
            out.setdefault(_local(c), _text(c))
    return out


def _plugin(r: _Reader, el, reference, sensor) -> Plugin:
    n = node(el, r.loc)
    if _ns(el).endswith("#controller"):
        fattr = "plugin" if el.get("plugin") is not None else ("filename" if el.get("filename") is not None else None)
        return Plugin(el.get("name"), el.get(fattr) if fattr else _local(el), "electric", _params(el), n,
                      reference, sensor, fattr, r.loc(el), el)
    fn = el.get("filename") or ""
    name = el.get("name") or ""
    dialect = "gz" if fn.startswith(("gz-sim", "ignition-gazebo", "libgz-sim", "libignition-gazebo")) or \
        name.startswith(("gz::sim", "ignition::gazebo")) else "classic"
    return Plugin(el.get("name"), el.get("filename"), dialect, _params(el), n, reference, sensor,
                  "filename" if el.get("filename") is not None else None, r.loc(el), el)


def _axis(n, *path) -> ScanAxis | None:
    a = n.find(*path)
    if a is None:
        return None
    return ScanAxis(a.number("samples"), a.number("resolution"), a.number("min_angle"), a.number("max_angle"))


def _noise(n) -> Noise | None:
    if n is None:
        return None
    return Noise(n.text_at("type") or n.get("type"), n.number("mean"), n.number("stddev"))


def _typed_sensor(n, electric: bool, stype: str) -> dict:
    """The typed fields of a sensor (model/parts.Sensor) from its node."""
    if electric:
        out = {"update_rate": n.number("updateRate"), "always_on": n.boolean("alwaysActive"),
               "visualize": n.text_at("displayRays"), "pose": n.vector("origin")}
        if stype == "camera":
            size = n.vector("imageSize")
            w, h = (size[0], size[1] if len(size) > 1 else None) if size else (n.number("imageWidth"),
                                                                            n.number("imageHeight"))
            out["camera"] = Camera(n.number("hfov"), w, h, n.text_at("imageFormat"), n.number("nearClip"),
                                   n.number("farClip"), "deg")
        elif stype == "ray":
            vrays = n.number("verticalRayCount")
            out["rays"] = (Ray("electric", ScanAxis(n.number("rayCount"), None, n.number("minAngle"), n.number("maxAngle")),
                               ScanAxis(vrays, None, n.number("verticalMinAngle"), n.number("verticalMaxAngle"))
                               if vrays is not None else None,
                               n.number("minRange"), n.number("maxRange"), n.number("resRange"), None, "deg",
                               n.number("rangeCount")),)
        return out
    out = {"update_rate": n.number("update_rate"), "always_on": n.boolean("always_on"),
           "visualize": n.text_at("visualize"), "topic": n.text_at("topic"), "pose": n.vector("pose")}
    cams = n.all("camera")
    if cams:
        c = cams[0]
        out["camera"] = Camera(c.number("horizontal_fov"), c.number("image", "width"), c.number("image", "height"),
                               c.text_at("image", "format"), c.number("clip", "near"), c.number("clip", "far"),
                               "rad", len(cams))
    rays = []
    for c in n.elements:
        if c.tag in ("ray", "lidar"):
            rays.append(Ray(c.tag, _axis(c, "scan", "horizontal"), _axis(c, "scan", "vertical"),
                            c.number("range", "min"), c.number("range", "max"), c.number("range", "resolution"),
                            _noise(c.child("noise"))))
    out["rays"] = tuple(rays)
    son = n.child("sonar")
    if son is not None:
        out["sonar"] = Sonar(son.number("min"), son.number("max"), son.number("radius"))
    return out


def _sensor(r: _Reader, el, reference) -> Sensor:
    electric = _ns(el).endswith("#sensor")
    stype = _local(el) if electric else (el.get("type") or "")
    plugins = []
    for c in el.iter():
        if c is el or not isinstance(c.tag, str):
            continue
        if _ns(c).endswith("#controller") or _local(c) == "plugin":
            plugins.append(_plugin(r, c, reference, el.get("name")))
    n = node(el, r.loc)
    return Sensor(el.get("name"), stype, "electric" if electric else "sdf", reference, n, tuple(plugins), r.loc(el),
                  el, **_typed_sensor(n, electric, stype))


def _gazebo_block(r: _Reader, g) -> GazeboBlock:
    ref = g.get("reference")
    props: dict[str, str] = {}
    plugins, sensors = [], []
    for c in g:
        if not isinstance(c.tag, str):
            continue
        ns, name = _ns(c), _local(c)
        if ns.endswith("#sensor") or (not ns and name == "sensor"):
            sensors.append(_sensor(r, c, ref))
        elif ns.endswith("#controller") or (not ns and name == "plugin"):
            plugins.append(_plugin(r, c, ref, None))
        elif len(c) == 0 and name not in props:
            props[name] = _text(c)
            _vet_property(r, c, name, props[name])
    return GazeboBlock(ref, node(g, r.loc), props, tuple(plugins), tuple(sensors), r.loc(g), g,
                       typed_properties(props))


def _vet_property(r: _Reader, el, name: str, text: str | None) -> None:
    """T010 for a number or vector property (mu1, kp, fdir1...) whose text sdformat cannot read: its
    converter (``ign sdf -p``, Gazebo's spawn) aborts with std::invalid_argument from stod."""
    if text is None or not text.strip() or (name not in NUMBERS and name not in VECTORS):
        return
    try:
        if name in NUMBERS:
            V.parse_number(text)
        else:
            V.parse_vector(text, VECTORS[name])
    except V.ValueProblem as exc:
        r.issue(el, V.problem(name, text.strip(), exc.reason) + " (sdformat's URDF converter aborts on it)")


# ---------------------------------------------------------------- transmissions, ros2_control
def _transmission(r: _Reader, t) -> Transmission:
    n = node(t, r.loc)
    named = tuple(TransmissionJoint(e.get("name"), e.tag, tuple((c.text or "").strip() for c in e.all("hardwareInterface")),
                                    e.loc, e.ref)
                  for e in n.iter() if e.tag.lower().endswith("joint") and e.get("name"))
    actuators = tuple(Actuator(a.get("name"), tuple((c.text or "").strip() for c in a.all("hardwareInterface")),
                               a.number("mechanicalReduction"), a.loc, a.ref) for a in n.all("actuator"))
    return Transmission(t.get("name"), tuple(j.get("name", "") for j in t.findall("joint")),
                        n.text_at("type") or t.get("type"), r.loc(t), t, n, named, actuators)


def _control_item(n, kind: str) -> ControlJoint:
    return ControlJoint(n.get("name"), tuple(c.get("name", "") for c in n.all("command_interface")),
                        tuple(c.get("name", "") for c in n.all("state_interface")),
                        {p.get("name"): (p.text or "").strip() for p in n.all("param") if p.get("name")},
                        n.loc, n.ref, kind)


def _ros2_control(r: _Reader, b) -> Ros2Control:
    n = node(b, r.loc)
    hw = n.child("hardware")
    return Ros2Control(b.get("name"), b.get("type"), hw.text_at("plugin") if hw is not None else None,
                       {p.get("name"): (p.text or "").strip() for p in hw.all("param") if p.get("name")}
                       if hw is not None else {},
                       tuple(_control_item(j, "joint") for j in n.all("joint") if j.get("name")),
                       tuple(_control_item(j, c) for c in ("sensor", "gpio") for j in n.all(c) if j.get("name")),
                       r.loc(b), b, n)
