"""The Robot → MJCF through MuJoCo's own URDF compiler (anchors §5).

MuJoCo reads URDF itself but stumbles on what real descriptions contain: it cannot
resolve ``package://`` (#1432), strips mesh paths, reads no DAE, discards visuals by
default, welds a massless root to the world (a REP-105 ``base_footprint`` robot stops
being mobile) and rejects inertias that break A + B >= C. So we hand it a prepared
URDF: meshes copied into ``<OUT stem>_meshes/`` next to the output under unique names
(DAE and others converted to STL with trimesh, MSH past 200000 faces), explicit rgba
from the URDF colours and the resolved Gazebo materials (a texture contributes its
mean colour), repaired inertias, a placeholder inertial for massless moving links, and
a free joint for mobile bases. MuJoCo compiles it and saves the MJCF; collision geoms
go to group 3 (hidden by the viewer's defaults), visuals stay in group 1 with their
colours.
"""

from __future__ import annotations

import contextlib
import shutil
import tempfile
from dataclasses import dataclass
from pathlib import Path

from lxml import etree

from myrabot_desc.convert.common import Notes, local, num, nums, warn_load_issues
from myrabot_desc.errors import InputError
from myrabot_desc.model.inertia import describe, repaired

TINY_MASS = 1e-3
TINY_INERTIA = 1e-6
MUJOCO_MESH_EXT = {".stl", ".obj", ".msh"}
STL_MAX_FACES = 200000


@dataclass
class MjcfResult:
    text: str
    notes: Notes
    nbody: int
    njnt: int
    ngeom: int
    nmesh: int
    free: bool
    mesh_dir: str | None

    @property
    def summary(self) -> str:
        return (f"{self.nbody} bodies, {self.njnt} joints, {self.ngeom} geoms, {self.nmesh} meshes"
                f"{', free base' if self.free else ''}")


def _parse(text: str):
    parser = etree.XMLParser(resolve_entities=False, no_network=True, remove_comments=True, huge_tree=False)
    return etree.fromstring(text.encode("utf-8"), parser)


def is_mobile(robot) -> bool:
    """A drive plugin, or wheels: continuous joints whose child is called *wheel*/*caster*/*castor*."""
    from myrabot_desc.convert.sensors import plugin_kind

    if any(plugin_kind(p) in ("diff_drive", "skid_steer") for p in robot.plugins()):
        return True
    return any(j.type == "continuous" and any(w in j.child.lower() for w in ("wheel", "caster", "castor"))
               for j in robot.joints.values())


class _Prep:
    """Which mesh files MuJoCo gets, under which unique names (it keys meshes by file stem)."""

    def __init__(self, robot, notes, mesh_dirname):
        self.robot = robot
        self.notes = notes
        self.mesh_dirname = mesh_dirname
        self.meshes: dict[Path, str | None] = {}     # source file -> file name in the mesh folder (None: unusable)
        self.loaded: dict[Path, object] = {}         # converted meshes (trimesh), by source
        self.names: set[str] = set()
        self.missing: list[str] = []
        self.empty: list[str] = []
        self.converted: list[str] = []

    def mesh_name(self, src: Path) -> str | None:
        key = src.resolve()
        if key in self.meshes:
            return self.meshes[key]
        from myrabot_desc.model import meshes as meshio

        ext = src.suffix.lower()
        mesh = None
        try:  # size and triangle limits before anything reads or copies it
            meshio.precheck(key)
        except meshio.MeshError as exc:
            self.notes.warn(f"mesh {src}: {exc}; geometry left out")
            self.meshes[key] = None
            return None
        if ext not in MUJOCO_MESH_EXT or (ext == ".stl" and not _binary_stl_ok(key)):
            try:
                mesh = meshio.load(key, process=False)
            except meshio.MeshError as exc:  # unreadable: leave the geometry out, say which file
                self.notes.warn(f"mesh {src}: {exc}; geometry left out")
                mesh = None
            if mesh is None or mesh.is_empty or len(mesh.faces) == 0:
                self.empty.append(src.name)
                self.meshes[key] = None
                return None
            # MuJoCo's STL reader takes binary files of at most 200000 faces; its own MSH has no such
            # limit and is written in milliseconds (OBJ text took seconds for a 350k-face trunk)
            out_ext = ".stl" if len(mesh.faces) <= STL_MAX_FACES else ".msh"
            self.loaded[key] = mesh
            self.converted.append(src.name)
        else:
            out_ext = ext
        stem = "".join(ch if ch.isalnum() or ch in "-_" else "_" for ch in src.stem) or "mesh"
        name, k = f"{stem}{out_ext}", 2
        while name.lower() in self.names:
            name, k = f"{stem}_{k}{out_ext}", k + 1
        self.names.add(name.lower())
        self.meshes[key] = name
        return name

    def write_meshes(self, folder: Path) -> None:
        folder.mkdir(parents=True, exist_ok=True)
        for src, name in sorted(((s, n) for s, n in self.meshes.items() if n), key=lambda kv: kv[1]):
            dest = folder / name
            mesh = self.loaded.get(src)
            if mesh is None:
                shutil.copyfile(src, dest)
            elif dest.suffix == ".msh":
                _write_msh(dest, mesh)
            else:
                mesh.export(str(dest), file_type="stl")


def _write_msh(dest: Path, mesh) -> None:
    """MuJoCo's binary MSH: int32 nvertex, nnormal, ntexcoord, nface; float32 vertices; int32 faces."""
    import numpy as np

    v = np.ascontiguousarray(mesh.vertices, dtype="<f4")
    f = np.ascontiguousarray(mesh.faces, dtype="<i4")
    with open(dest, "wb") as fh:
        fh.write(np.array([len(v), 0, 0, len(f)], dtype="<i4").tobytes())
        fh.write(v.tobytes())
        fh.write(f.tobytes())


def _binary_stl_ok(path: Path) -> bool:
    """A binary STL MuJoCo can read: size = 84 + 50 n with 1 <= n <= 200000."""
    try:
        size = path.stat().st_size
        with open(path, "rb") as fh:
            head = fh.read(84)
    except OSError:
        return False
    if len(head) < 84:
        return False
    n = int.from_bytes(head[80:84], "little")
    return size == 84 + 50 * n and 1 <= n <= STL_MAX_FACES


def prepare_urdf(robot, notes: Notes, base: str, mesh_dirname: str):
    """The URDF MuJoCo gets, and the mesh plan."""
    from myrabot_desc.convert.appearance import Appearance, texture_mean_rgb
    from myrabot_desc.convert.gazebo import GazeboProps

    root = _parse(robot.urdf_text)
    prep = _Prep(robot, notes, mesh_dirname)
    # Gazebo and ROS-only content means nothing to MuJoCo (and the Electric namespaces confuse it)
    for el in list(root):
        if not isinstance(el.tag, str) or local(el.tag) in ("gazebo", "transmission") or el.tag.startswith("{"):
            root.remove(el)
    props = GazeboProps(robot, Notes())
    look = Appearance(robot, notes)
    colours: dict[str, tuple] = {}
    links_xml = {el.get("name"): el for el in root.findall("link")}
    for name, link_el in links_xml.items():
        link = robot.links.get(name)
        gz_mat = props.get(name).get("material")
        visuals = link_el.findall("visual")
        for k, vis in enumerate(visuals):
            model_vis = link.visuals[k] if link is not None and k < len(link.visuals) else None
            lk = look.look(model_vis, gz_mat, link.loc if link else None) if model_vis is not None else None
            for m in vis.findall("material"):
                vis.remove(m)
            if lk is not None:
                rgb = tuple(lk.diffuse[:3])
                mean = texture_mean_rgb(lk.texture) if lk.texture else None
                if mean is not None:
                    rgb = tuple(round(a * b, 4) for a, b in zip(rgb, mean))
                rgba = rgb + ((lk.diffuse[3] if len(lk.diffuse) > 3 else 1.0) * (1.0 - lk.transparency),)
                mname = colours.setdefault(nums(rgba), f"rgba_{len(colours)}")
                m = etree.SubElement(vis, "material", name=mname)
                etree.SubElement(m, "color", rgba=nums(rgba))
        for part in visuals + link_el.findall("collision"):
            mesh = part.find("geometry/mesh")
            if mesh is None:
                continue
            fn = mesh.get("filename", "")
            try:
                src = robot.resolve_uri(fn)
            except Exception:
                src = None
            if src is None or not Path(src).is_file():
                prep.missing.append(fn)
                link_el.remove(part)
                continue
            name = prep.mesh_name(Path(src))
            if name is None:
                link_el.remove(part)
                continue
            mesh.set("filename", name)
        # inertia: repaired like the SDF path, so both simulators see the same body
        ine_el = link_el.find("inertial")
        if link is not None and link.inertial is not None and link.inertial.mass > 0 and ine_el is not None:
            tensor, changed = repaired(link.inertial)
            if changed:
                notes.warn(f"link '{name}': inertia breaks A + B >= C, raised {describe(link.inertial, tensor)}",
                           link.inertial.loc)
                t = ine_el.find("inertia")
                if t is None:
                    t = etree.SubElement(ine_el, "inertia")
                for key, (a, b) in {"ixx": (0, 0), "ixy": (0, 1), "ixz": (0, 2), "iyy": (1, 1), "iyz": (1, 2),
                                    "izz": (2, 2)}.items():
                    t.set(key, num(tensor[a][b]))
    if prep.missing:
        shown = ", ".join(sorted(set(prep.missing))[:5])
        notes.warn(f"{len(prep.missing)} mesh geometry(ies) left out: file not found ({shown})")
    if prep.empty:
        notes.warn(f"{len(prep.empty)} mesh file(s) with no triangles left out: {', '.join(sorted(set(prep.empty)))}")

    # massless links that move would stop MuJoCo ("mass and inertia of moving bodies ...")
    tiny = []
    moving_children = {j.child for j in robot.joints.values() if j.type not in ("fixed",)}
    world_root = "world" in robot.links and robot.root == "world"
    free = False
    roots = [r for r in robot.roots if r != "world"] if not world_root else \
        [j.child for j in robot.joints.values() if j.parent == "world"]
    if base == "free" or (base == "auto" and is_mobile(robot)):
        free = True
    for r in roots:
        link = robot.links.get(r)
        j_world = next((j for j in robot.joints.values() if j.parent == "world" and j.child == r), None)
        kind = "floating" if free else ("fixed" if base == "fixed" else None)
        if kind is not None:
            if j_world is not None:
                j_el = root.find(f"joint[@name='{j_world.name}']")
                if j_el is not None:
                    j_el.set("type", kind)
            else:
                _add_world_joint(root, r, kind)
        if free:
            moving_children.add(r)
    for name in moving_children:
        link = robot.links.get(name)
        if link is not None and link.mass <= 0 and name in links_xml:
            _tiny_inertial(links_xml[name])
            tiny.append(name)
    if tiny:
        notes.warn(f"{len(tiny)} massless moving link(s) given a placeholder inertial ({TINY_MASS} kg) "
                   f"for MuJoCo: " + ", ".join(sorted(tiny)))

    mj = root.find("mujoco")
    if mj is None:
        mj = etree.Element("mujoco")
        root.insert(0, mj)
    comp = mj.find("compiler")
    if comp is None:
        comp = etree.SubElement(mj, "compiler")
    comp.set("discardvisual", "false")
    comp.set("meshdir", mesh_dirname + "/")
    comp.set("strippath", "false")
    comp.set("angle", "radian")
    return root, prep, free


def _add_world_joint(root, child, type_):
    if root.find("link[@name='world']") is None:
        root.insert(1, etree.Element("link", name="world"))
    j = etree.SubElement(root, "joint", name=f"{child}_{'free' if type_ == 'floating' else 'fixed'}_joint",
                         type=type_)
    etree.SubElement(j, "parent", link="world")
    etree.SubElement(j, "child", link=child)


def _tiny_inertial(link_el):
    for old in link_el.findall("inertial"):
        link_el.remove(old)
    ine = etree.Element("inertial")
    etree.SubElement(ine, "mass", value=num(TINY_MASS))
    etree.SubElement(ine, "inertia", ixx=num(TINY_INERTIA), ixy="0", ixz="0", iyy=num(TINY_INERTIA), iyz="0",
                     izz=num(TINY_INERTIA))
    link_el.insert(0, ine)


def _postprocess(text: str, robot, mesh_dirname: str, free: bool, version: str) -> str:
    root = _parse(text)
    comp = root.find("compiler")
    if comp is not None:
        comp.set("meshdir", mesh_dirname + "/")
    for g in root.iter("geom"):
        if g.get("group") is None and g.get("contype") is None:
            # collision geom: hidden by the viewer's default groups; MuJoCo's URDF reader copies the
            # last visual rgba onto collisions, which would only mislead
            g.set("group", "3")
            if "rgba" in g.attrib:
                del g.attrib["rgba"]
    for ine in root.iter("inertial"):
        # mj_saveLastXML prints 6 digits: a tensor with A + B == C (a thin rod, or our repair) can
        # print as A + B < C and then not load again; nudge such rounding-level cases back
        d = ine.get("diaginertia")
        if d:
            a, b, c = sorted(float(x) for x in d.split())
            vals = [float(x) for x in d.split()]
            if a + b < c * (1 + 1e-5):
                f = c * (1 + 2e-5) / (a + b) if a + b > 0 else 1.0
                big = vals.index(c)
                vals = [v if i == big else v * f for i, v in enumerate(vals)]
                ine.set("diaginertia", " ".join(f"{v:.9g}" for v in vals))
    src = robot.source.name if robot.source else "URDF"
    root.insert(0, etree.Comment(f" generated by myrabot-desc convert from {src} through MuJoCo {version}'s URDF "
                                 f"compiler; visuals in group 1, collisions in group 3"
                                 f"{'; free base' if free else ''} "))
    etree.indent(root, space="  ")
    return etree.tostring(root, encoding="unicode", pretty_print=True)


@contextlib.contextmanager
def _c_stdout_to(notes):
    """MuJoCo's C code prints warnings ("joint 'j' has equal lower and upper limits") straight on
    the process's stdout/stderr: catch both descriptors and turn the lines into our warnings."""
    import os
    import sys

    sys.stdout.flush()
    sys.stderr.flush()
    saved = os.dup(1), os.dup(2)
    with tempfile.TemporaryFile() as tmp:
        os.dup2(tmp.fileno(), 1)
        os.dup2(tmp.fileno(), 2)
        try:
            yield
        finally:
            sys.stdout.flush()
            sys.stderr.flush()
            os.dup2(saved[0], 1)
            os.dup2(saved[1], 2)
            os.close(saved[0])
            os.close(saved[1])
            tmp.seek(0)
            for line in tmp.read().decode("utf-8", "replace").splitlines():
                line = line.strip()
                if line:
                    notes.warn("MuJoCo: " + line.removeprefix("WARNING: "))


@contextlib.contextmanager
def _warnings_to(mujoco, notes):
    """MuJoCo's own warnings ("XML contains a 'NaN'") as our warnings. Its default handler
    also appends them to MUJOCO_LOG.TXT in the working directory: a file the user never
    asked for, and written even when the conversion fails."""
    previous = mujoco.get_mju_user_warning()
    mujoco.set_mju_user_warning(lambda msg: notes.warn("MuJoCo: " + str(msg).strip()))
    try:
        yield
    finally:
        mujoco.set_mju_user_warning(previous)


def _compile(mujoco, spec, notes):
    """Compile; a mesh too thin to have a volume (a decal, a flat nub) gets shell inertia and we retry."""
    import re

    shelled = []
    while True:
        try:
            model = spec.compile()
            break
        except ValueError as exc:
            m = re.search(r"mesh volume is too small: (\S+?)\s*\.", str(exc))
            mesh = next((x for x in spec.meshes if m and x.name == m.group(1)), None)
            if mesh is None or mesh.inertia == mujoco.mjtMeshInertia.mjMESH_INERTIA_SHELL or len(shelled) > 1000:
                raise
            mesh.inertia = mujoco.mjtMeshInertia.mjMESH_INERTIA_SHELL
            shelled.append(mesh.name)
    if shelled:
        notes.warn(f"{len(shelled)} mesh(es) too thin for a volume use shell inertia in MuJoCo: {', '.join(shelled)}")
    return model


MAX_BODY_DEPTH = 1000  # MuJoCo fails past 1024 nested bodies, after seconds of work (quadratic)


def _check_depth(robot) -> None:
    """Refuse a body chain MuJoCo cannot take before spending seconds in its compiler."""
    children = robot.joints_by_parent()
    child_links = {j.child for j in robot.joints.values()}
    depth: dict[str, int] = {}
    stack = [(name, 1) for name in robot.links if name not in child_links]
    while stack:
        name, d = stack.pop()
        if name in depth:       # cycles and shared children are the tree rules' business
            continue
        depth[name] = d
        if d > MAX_BODY_DEPTH:
            raise InputError(f"the kinematic chain is over {MAX_BODY_DEPTH} links deep (at link '{name}'): "
                             "MuJoCo cannot nest bodies that deep", robot.links[name].loc
                             if name in robot.links else robot.loc)
        stack.extend((j.child, d + 1) for j in children.get(name, ()))


def convert_mjcf(robot, output: str, base: str = "auto") -> MjcfResult:
    import os

    # We never render: without this, `import mujoco` loads pyGLFW, which spawns a Python
    # subprocess to probe libglfw (a process per conversion, seen by the hardening audit).
    os.environ.setdefault("MUJOCO_GL", "disable")
    try:
        import mujoco
    except ImportError:
        raise InputError("MJCF needs the mujoco package: pip install mujoco") from None
    from myrabot_desc.output import OutputDir, write_output

    notes = Notes()
    if not robot.links:
        raise InputError("the model has no links: nothing to convert", robot.loc)
    _check_depth(robot)
    warn_load_issues(robot, notes, "passed to MuJoCo as written")   # it reads the URDF's XML
    out = Path(output) if output != "-" else None
    mesh_dirname = f"{out.stem}_meshes" if out else "meshes"
    urdf_root, prep, free = prepare_urdf(robot, notes, base, mesh_dirname)
    if out is None and prep.meshes:
        raise InputError(f"this model has {len(prep.meshes)} mesh file(s): MJCF to stdout cannot carry them, "
                         "give -o OUT.xml")
    urdf_text = etree.tostring(urdf_root, encoding="unicode")

    def compile_in(folder: Path) -> tuple[str, object]:
        prep.write_meshes(folder / mesh_dirname)
        tmp_urdf = folder / ".robot.urdf"
        tmp_urdf.write_text(urdf_text, encoding="utf-8")
        try:
            with _c_stdout_to(notes), _warnings_to(mujoco, notes):
                spec = mujoco.MjSpec.from_file(str(tmp_urdf))
                model = _compile(mujoco, spec, notes)
                text = spec.to_xml()
        except ValueError as exc:
            msg = str(exc).strip().splitlines()
            raise InputError(f"MuJoCo rejected the model: {' '.join(m.strip() for m in msg if m.strip())}",
                             robot.loc) from None
        finally:
            tmp_urdf.unlink(missing_ok=True)
        return _postprocess(text, robot, mesh_dirname, free, mujoco.__version__), model

    if out is None:
        with tempfile.TemporaryDirectory() as d:
            text, model = compile_in(Path(d))
        write_output("-", text)
    else:
        with OutputDir(out.parent if str(out.parent) else ".") as stage:
            text, model = compile_in(stage)
            (stage / out.name).write_text(text, encoding="utf-8")
        if prep.converted:
            notes.warn(f"{len(prep.converted)} mesh(es) converted to STL/MSH for MuJoCo (it reads STL, OBJ, MSH); "
                       "their embedded colours are replaced by the URDF/Gazebo colour")
    free = bool((model.jnt_type == mujoco.mjtJoint.mjJNT_FREE).any())
    return MjcfResult(text, notes, model.nbody, model.njnt, model.ngeom, model.nmesh, free,
                      str(out.parent / mesh_dirname) if out and prep.meshes else None)
