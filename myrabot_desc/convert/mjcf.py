"""The Robot → MJCF through MuJoCo's own URDF compiler (anchors §5), ready for MuJoCo's viewer.

MuJoCo reads URDF itself but stumbles on what real descriptions contain: it cannot
resolve ``package://`` (#1432), strips mesh paths, reads no DAE, discards visuals by
default, welds a massless root to the world (a REP-105 ``base_footprint`` robot stops
being mobile) and rejects inertias that break A + B >= C. So we hand it a prepared
URDF, an edited copy of the model's parsed tree (no second parse of the text): meshes
copied into ``<OUT stem>_meshes/`` next to the output under unique names (DAE and others
converted to STL with trimesh, MSH past 200000 faces), explicit rgba from the URDF colours
and the resolved Gazebo materials (a texture contributes its mean colour), repaired
inertias, collision geoms named after their link, and a free joint for mobile bases.

Mass: a link without ``<inertial>`` is massless, as urdfdom, KDL and Pinocchio read it
(the URDF spec's default), not MuJoCo's 1000 kg/m^3 of its geoms (``inertiafromgeom``
false). Gazebo/sdformat instead drops such a link with its subtree; `convert --to sdf`
keeps it with a placeholder. Only a moving body that has no mass even with the links
fused into it by fixed joints gets a 1 g placeholder (MuJoCo refuses massless moving
bodies), listed in a warning and the report.

MuJoCo compiles it; then, on the compiled spec, we add what MuJoCo Menagerie's models
have: the ``implicitfast`` integrator, position actuators for joints (full effort at
0.05 rad / 5 mm of error, bounded for stability by the joint-space inertia, critically
damped; none on a joint that nothing commands when the model says what it commands),
velocity actuators for wheels (sized against the robot they roll, with an armature when the
wheel is light), Gazebo's joint springs and its friction below the floor's (a sliding
caster), a ``home`` keyframe (joints at 0 clamped into
their range, the free base raised so that its lowest collision point touches z = 0; a
welded robot's weld moved the same way), and contact exclusions for the body pairs
MuJoCo's own collision pass finds touching at home. Mimic joints become equality
constraints (MuJoCo's compiler does that since 2026). A ``scene.xml`` next to the model
includes it with a floor and a light. Collision geoms go to group 3 (hidden by the
viewer's defaults), visuals stay in group 1 with their colours.
"""

from __future__ import annotations

import contextlib
import copy
import math
from dataclasses import dataclass
from pathlib import Path

from lxml import etree

from myrabot_desc.convert.appearance import Appearance, texture_mean_rgb
from myrabot_desc.convert.common import Notes, local, num, nums, to_float, warn_load_issues
from myrabot_desc.convert.gazebo import GazeboProps
from myrabot_desc.convert.preflight import Problem, refuse_or_record
from myrabot_desc.convert.report import Report, part_name, seed
from myrabot_desc.errors import InputError
from myrabot_desc.model import drive as D
from myrabot_desc.model import meshes as meshio
from myrabot_desc.model.inertia import describe, repaired
from myrabot_desc.output import OutputDir, write_output
from myrabot_desc.safety import limit

# shutil and tempfile are imported where they are used: `convert --to sdf` imports this module
# too (commands/convert.py), and they cost it ~4 ms.

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
    nu: int = 0
    scene: str | None = None
    report: Report | None = None

    @property
    def summary(self) -> str:
        return (f"{self.nbody} bodies, {self.njnt} joints, {self.ngeom} geoms, {self.nmesh} meshes"
                f"{', free base' if self.free else ''}"
                f"{f', {self.nu} actuators' if self.nu else ''}{f', scene {Path(self.scene).name}' if self.scene else ''}")


def _parse(text: str):
    parser = etree.XMLParser(resolve_entities=False, no_network=True, remove_comments=True, huge_tree=False)
    return etree.fromstring(text.encode("utf-8"), parser)


def is_mobile(robot) -> bool:
    """A wheeled base (a declared drive or wheel joints): model/drive.py's answer, the one check uses."""

    return D.is_mobile(robot)


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
        self.why: dict[Path, str] = {}               # source -> why it cannot be used
        self.collision_errors: list = []              # (message, loc) of collision meshes left out

    def mesh_name(self, src: Path) -> str | None:
        key = src.resolve()
        if key in self.meshes:
            return self.meshes[key]

        ext = src.suffix.lower()
        mesh = None
        try:  # size and triangle limits before anything reads or copies it
            meshio.precheck(key)
        except meshio.MeshError as exc:
            self.notes.warn(f"mesh {src}: {exc}; geometry left out")
            self.why[key] = str(exc)
            self.meshes[key] = None
            return None
        if ext not in MUJOCO_MESH_EXT or (ext == ".stl" and not _binary_stl_ok(key)):
            try:
                mesh = meshio.load(key, process=False)
            except meshio.MeshError as exc:  # unreadable: leave the geometry out, say which file and why
                mesh = meshio.lenient_dae(key, self.notes) if ext == ".dae" and "holds no triangles" in str(exc) else None
                if mesh is None:
                    self.notes.warn(f"mesh {src}: {exc}; geometry left out")
                    self.why[key] = str(exc)
                    self.meshes[key] = None
                    return None
            if mesh is None or mesh.is_empty or len(mesh.faces) == 0:
                self.empty.append(src.name)
                self.why[key] = "holds no triangles"
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
                import shutil

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


def wheel_joints(robot) -> set[str]:
    """Joints driven in velocity (wheels): the drive model's answer (model/drive.py), joints with
    a velocity interface and every declared drive's wheels."""

    names, _ = D.velocity_joints(robot)
    return set(names) | {j for d in D.find(robot) for j in d.joints if j in robot.joints}


def prepare_urdf(robot, notes: Notes, base: str, mesh_dirname: str, report: Report | None = None):
    """The URDF MuJoCo gets (an edited copy of the model's parsed tree), and the mesh plan."""

    report = report if report is not None else Report("mjcf")
    root = copy.deepcopy(robot.root_element)
    prep = _Prep(robot, notes, mesh_dirname)
    # Gazebo and ROS-only content means nothing to MuJoCo (and the Electric namespaces confuse it)
    for el in list(root):
        if not isinstance(el.tag, str) or local(el.tag) in ("gazebo", "transmission") or el.tag.startswith("{"):
            root.remove(el)
    _drop_unreadable_numbers(root)
    # a link with two parents (a closed loop) only gets here with --allow-errors: its first joint stays
    has_parent: set[str] = set()
    for j_el in root.findall("joint"):
        c = j_el.find("child")
        child = c.get("link") if c is not None else None
        if child in has_parent:
            root.remove(j_el)
            report.set("joint", j_el.get("name") or "?", "dropped", f"'{child}' already has a parent joint: "
                       "MuJoCo bodies form a tree")
        elif child:
            has_parent.add(child)
    props = GazeboProps(robot, Notes())
    look = Appearance(robot, notes)
    colours: dict[str, tuple] = {}
    links_xml: dict[str, object] = {}
    for el in root.findall("link"):
        links_xml.setdefault(el.get("name"), el)
    geom_names = {v.get("name") for el in links_xml.values() for v in el.findall("visual") if v.get("name")}
    for link_name, link_el in links_xml.items():
        link = robot.links.get(link_name)
        gz_mat = props.get(link_name).get("material")
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
        collisions = link_el.findall("collision")
        # collision geoms named after their link (MuJoCo keeps the name): contacts and the report say
        # which link touches what; visual names stay as written
        for k, col in enumerate(collisions):
            base_name = f"{link_name}_collision" + (f"_{k}" if k else "")
            gname, n = base_name, 2
            while gname in geom_names:
                gname, n = f"{base_name}_{n}", n + 1
            geom_names.add(gname)
            col.set("name", gname)
        for kind, parts in (("visual", visuals), ("collision", collisions)):
            for k, part in enumerate(parts):
                rname = part_name(link_name, k)
                flat = _flat_primitive(part)
                if flat:    # MuJoCo refuses a geom of size 0 (a placeholder `<box size="0 0 0"/>`)
                    link_el.remove(part)
                    report.set(kind, rname, "dropped", f"{flat}: no volume, MuJoCo refuses a geom of size 0")
                    src_parts = (link.visuals if kind == "visual" else link.collisions) if link is not None else ()
                    notes.warn(f"link '{link_name}': {kind} {flat} left out (MuJoCo refuses a geom of size 0)",
                               src_parts[k].loc if k < len(src_parts) else None)
                    continue
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
                    report.set(kind, rname, "dropped", f"mesh {fn}: file not found")
                    continue
                name = prep.mesh_name(Path(src))
                if name is None:
                    link_el.remove(part)
                    if kind == "collision":
                        c = link.collisions[k] if link is not None and k < len(link.collisions) else None
                        prep.collision_errors.append(
                            (f"collision mesh {fn} of link '{link_name}': {prep.why.get(Path(src).resolve())}",
                             c.loc if c is not None else None))
                    report.set(kind, rname, "dropped", f"mesh {fn}: {prep.why.get(Path(src).resolve(), 'unreadable')}")
                    continue
                if Path(src).resolve() in prep.loaded:
                    report.set(kind, rname, "translated", f"mesh {Path(src).name} converted to {Path(name).suffix[1:].upper()}"
                               + (" (its embedded colours replaced by the URDF/Gazebo colour)" if kind == "visual" else ""))
                mesh.set("filename", name)
        # inertia: repaired like the SDF path, so both simulators see the same body
        ine_el = link_el.find("inertial")
        if link is not None and link.inertial is not None and link.inertial.mass > 0 and ine_el is not None:
            tensor, changed = repaired(link.inertial)
            if changed:
                how = describe(link.inertial, tensor)
                notes.warn(f"link '{link_name}': inertia breaks A + B >= C, raised {how}", link.inertial.loc)
                report.set("inertial", link_name, "approximated", f"inertia breaks A + B >= C: raised {how}")
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

    world_root = "world" in robot.links and robot.root == "world"
    free = False
    roots = [r for r in robot.roots if r != "world"] if not world_root else \
        [j.child for j in robot.joints.values() if j.parent == "world"]
    if base == "free" or (base == "auto" and is_mobile(robot)):
        free = True
    for r in roots:
        j_world = next((j for j in robot.joints.values() if j.parent == "world" and j.child == r), None)
        kind = "floating" if free else ("fixed" if base == "fixed" else None)
        if kind is not None:
            if j_world is not None:
                j_el = root.find(f"joint[@name='{j_world.name}']")
                if j_el is not None:
                    j_el.set("type", kind)
            else:
                _add_world_joint(root, r, kind)

    # Links without <inertial> are massless, as urdfdom, KDL and Pinocchio read them (not MuJoCo's
    # 1000 kg/m^3 of their geoms). MuJoCo fuses fixed children into their parent body; a moving body
    # that has no mass even with them would stop it, so only those get a placeholder.
    tiny = []
    for name in _massless_moving_bodies(robot, roots if free else []):
        if name in links_xml:
            _tiny_inertial(links_xml[name])
            tiny.append(name)
            report.set("inertial", name, "approximated",
                       f"a moving body with no mass (even with its fixed children): {TINY_MASS} kg placeholder "
                       "(MuJoCo needs mass on every moving body)")
    if tiny:
        notes.warn(f"{len(tiny)} moving link(s) have no mass, even with the links fixed to them: given "
                   f"{TINY_MASS} kg each for MuJoCo: " + ", ".join(sorted(tiny)))

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
    comp.set("inertiafromgeom", "false")
    return root, prep, free


def _flat_primitive(part) -> str | None:
    """'box size 0 0 0' when a box, cylinder or sphere of this visual/collision has a zero size."""
    g = part.find("geometry")
    shape = next((c for c in g if isinstance(c.tag, str)), None) if g is not None else None
    if shape is None or shape.tag not in ("box", "cylinder", "sphere"):
        return None
    attrs = {"box": ("size",), "cylinder": ("radius", "length"), "sphere": ("radius",)}[shape.tag]
    try:
        vals = [float(v) for a in attrs for v in (shape.get(a) or "1").split()]
    except ValueError:
        return None
    if any(v <= 0 for v in vals):
        return f"{shape.tag} " + " ".join(f"{a} {shape.get(a)}" for a in attrs)
    return None


NUMERIC = {"xyz", "rpy", "value", "ixx", "ixy", "ixz", "iyy", "iyz", "izz", "size", "radius", "length", "lower",
           "upper", "effort", "velocity", "damping", "friction", "scale", "multiplier", "offset", "rgba"}


def _drop_unreadable_numbers(root) -> None:
    """Numeric attributes that are not numbers (the loader reported them, and only --allow-errors
    gets here): left out, so MuJoCo applies the URDF default as the loader did."""
    for el in root.iter():
        if not isinstance(el.tag, str):
            continue
        for attr in [a for a in el.attrib if a in NUMERIC]:
            try:
                [float(v) for v in el.get(attr).split()]
            except ValueError:
                if attr == "rgba":
                    del el.attrib[attr]
                else:     # the loader's defaults (MuJoCo requires some of these attributes)
                    el.set(attr, {"scale": "1 1 1", "xyz": "0 0 0", "rpy": "0 0 0", "size": "0 0 0"}.get(attr, "0"))


def _massless_moving_bodies(robot, free_roots) -> list[str]:
    """Links MuJoCo makes moving bodies (children of moving joints, free roots) whose mass, with
    every link fused into them through fixed joints, is zero."""
    children = robot.joints_by_parent()

    def fused_mass(name, seen):
        if name in seen:
            return 0.0
        seen.add(name)
        link = robot.links.get(name)
        m = link.mass if link is not None else 0.0
        return m + sum(fused_mass(j.child, seen) for j in children.get(name, ()) if j.type == "fixed")

    moving = [j.child for j in robot.joints.values() if j.type not in ("fixed",) and j.parent in robot.links]
    moving += [r for r in free_roots if r not in moving]
    return [n for n in moving if n in robot.links and fused_mass(n, set()) <= 0]


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


def _postprocess(text: str, robot, mesh_dirname: str, free: bool, version: str, balance: bool = False) -> str:
    root = _parse(text)
    comp = root.find("compiler")
    if comp is not None:
        comp.set("meshdir", mesh_dirname + "/")
        if balance:      # the saved inertias are the URDF's: MuJoCo must balance them again on load
            comp.set("balanceinertia", "true")
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
            vals = [float(x) for x in d.split()]
            order = sorted(range(3), key=lambda i: vals[i])
            a, b, c = (vals[i] for i in order)
            if a + b < c * (1 + 1e-5):
                # raise the smallest moment only (scaling the two smaller ones fails when two are equal)
                vals[order[0]] = max(a, c * (1 + 2e-5) - b)
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
    import tempfile

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
            if "A + B >= C" in str(exc) and not spec.compiler.balanceinertia:
                # a body whose fused links add up to a flat tensor (a point mass on an axis): MuJoCo's
                # own repair, only for the bodies that need it
                b = re.search(r"Element name '([^']*)'", str(exc))
                notes.warn(f"body '{b.group(1) if b else '?'}' (with the links fixed to it) has an inertia that breaks "
                           "A + B >= C: MuJoCo's balanceinertia raises the bodies that do")
                spec.compiler.balanceinertia = True
                continue
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
    """Refuse a body chain MuJoCo cannot take, or more bodies than the limit, before spending
    seconds in its compiler: MuJoCo's parse and compile, run several times here, and the search
    for bodies touching at rest grow faster than the link count."""

    most = limit("max_mjcf_bodies")
    if len(robot.links) > most:
        raise InputError(f"the robot has {len(robot.links)} links, over the {most} that `convert --to mjcf` takes "
                         "(MYRABOT_DESC_MAX_MJCF_BODIES): MuJoCo's compile and the contact search would take "
                         "minutes and gigabytes", robot.loc)
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


# Position actuators reach the joint's effort limit at this error (rad, or m for prismatic joints),
# and are held to a natural frequency of at most OMEGA_DT / timestep (explicit springs beyond it
# ring or diverge on light links); critically damped.
FULL_EFFORT_AT = {"hinge": 0.05, "slide": 0.005}
OMEGA_DT = 0.5
# Wheels: velocity actuators. implicitfast integrates a velocity servo implicitly, stable at any
# gain, but a force clamped at its range is integrated explicitly: one clamped step on a light
# wheel overshoots by effort*dt/I and the model diverges (ros2_control_demos' DiffBot: 0.3 kg,
# r 1.5 cm wheels, effort 100 N·m, gain 1000: gone to x 69 m, z 72 m). So with an effort limit
# the gain reaches it only at WHEEL_CLAMP_AT times the velocity limit (no command inside
# ctrlrange clamps, from rest), and at least ROLLING_CLAMPED x the rolling gain below, at which a
# clamped step on a loaded wheel does not overshoot.
# Without one, nothing clamps, and the gain is stiff against what the wheel turns: itself and its
# share of the robot rolling on it (m/n r²), plus WHEEL_OVER_DAMPING times its joint damping.
WHEEL_CLAMP_AT = 2.0
WHEEL_OVER_DAMPING = 50.0
ROLLING_CLAMPED = 0.5
# A stiff velocity servo on a light wheel rolling on the floor makes MuJoCo's contacts unstable
# even unclamped (DiffBot, settled, then commanded 0.5 rad/s: thrown 1.3 m up). The wheel joint
# gets an armature (a motor's rotor inertia, which URDF does not describe) so that one step of
# the servo changes its speed by at most 1/WHEEL_SERVO_STEP of the error: kv dt / (I + armature).
WHEEL_SERVO_STEP = 10.0


SPRING_KEYS = ("springStiffness", "springReference")


def joint_springs(robot) -> dict[str, tuple[float, float]]:
    """joint -> (stiffness, reference) from Gazebo's ``<springStiffness>``/``<springReference>``
    (a passive suspension or wheel drop): MuJoCo's joint ``stiffness`` and ``springref``."""

    out = {}
    for g in robot.gazebo:
        if g.reference in robot.joints and any(k in g.properties for k in SPRING_KEYS):
            k = to_float(g.properties.get("springStiffness"))
            ref = to_float(g.properties.get("springReference"))
            old = out.get(g.reference, (0.0, 0.0))
            out[g.reference] = (k if k is not None else old[0], ref if ref is not None else old[1])
    return {n: v for n, v in out.items() if v[0] > 0 and math.isfinite(v[0]) and math.isfinite(v[1])}


FRICTION_KEYS = ("mu1", "mu2")
# MuJoCo's floor has friction 1 and a contact takes the larger of its two geoms' unless one has
# priority. Gazebo's mu above 1 (Kobuki's wheels: 10) would make MuJoCo's soft contacts sink and
# stick (the rosbuild Kobuki sank 1 cm and stopped): those parts keep the floor's 1.
MAX_FRICTION = 1.0


def link_friction(robot) -> dict[str, float]:
    """link -> sliding friction from Gazebo's ``<mu1>``/``<mu2>`` (the smaller: MuJoCo's is
    isotropic). Gazebo takes the smaller of two surfaces' mu and its ground plane has 100, so the
    robot's value is the contact's; in MuJoCo its geoms get that friction and priority over the
    floor. A caster with mu 0 slides (Kobuki's); without it, it drags with the floor's 1."""

    out = {}
    for g in robot.gazebo:
        if g.reference not in robot.links:
            continue
        mus = [to_float(g.properties.get(k)) for k in FRICTION_KEYS]
        mus = [m for m in mus if m is not None and math.isfinite(m) and m >= 0]
        if mus:
            out[g.reference] = min(mus + ([out[g.reference]] if g.reference in out else []))
    return out


def _joint_plan(robot, wheels):
    """URDF joint name -> 'velocity' | 'position' | None (passive, with why). A model that says
    which joints its transmissions, ros2_control blocks and drives command leaves the others
    passive (a suspension, a caster, TurtleBot 4's wheel drops); one that says nothing gets a
    position actuator on every limited joint."""

    with_transmission = {n for t in robot.transmissions for n in t.joints}
    commanded = D.commanded_joints(robot)
    plan = {}
    for j in robot.joints.values():
        if j.type in ("fixed", "floating", "planar"):
            continue
        if j.mimic is not None:
            plan[j.name] = (None, f"mimics '{j.mimic.joint}' (an equality constraint)")
        elif j.name in wheels:
            plan[j.name] = ("velocity", "")
        elif commanded and j.name not in commanded:
            plan[j.name] = (None, "no transmission, ros2_control block or drive commands it: passive")
        elif j.type == "continuous" and j.limit is None and j.name not in with_transmission:
            plan[j.name] = (None, "continuous joint with no <limit> and no transmission: passive")
        else:
            plan[j.name] = ("position", "")
    return plan


def _rolling_kv(robot, joint, inertia: float, dt: float, mass_share: float) -> float:
    """A wheel's velocity gain without an effort limit: (its own inertia + its share of the robot's
    mass at its radius) / timestep, plus WHEEL_OVER_DAMPING x its joint damping (see WHEEL_CLAMP_AT)."""

    w = D.wheel(robot, joint.name, read_meshes=True)
    r = w.radius if w is not None and w.radius else 0.0
    damping = joint.dynamics.damping if joint.dynamics is not None else 0.0
    return (inertia + mass_share * r * r) / dt + WHEEL_OVER_DAMPING * damping


def _lowest_point(mujoco, np, m, d, geoms) -> float:
    """The lowest world z over these geoms (exact for primitives and mesh vertices)."""
    low = np.inf
    for g in geoms:
        t = m.geom_type[g]
        R = d.geom_xmat[g].reshape(3, 3)
        z = d.geom_xpos[g][2]
        sz = m.geom_size[g]
        if t == mujoco.mjtGeom.mjGEOM_MESH:
            a, n = m.mesh_vertadr[m.geom_dataid[g]], m.mesh_vertnum[m.geom_dataid[g]]
            v = m.mesh_vert[a:a + n]
            low = min(low, float(z + (v @ R[2]).min()))
        elif t == mujoco.mjtGeom.mjGEOM_SPHERE:
            low = min(low, z - sz[0])
        elif t == mujoco.mjtGeom.mjGEOM_CAPSULE:
            low = min(low, z - abs(R[2, 2]) * sz[1] - sz[0])
        elif t == mujoco.mjtGeom.mjGEOM_CYLINDER:
            low = min(low, z - abs(R[2, 2]) * sz[1] - sz[0] * np.sqrt(max(0.0, 1 - R[2, 2] ** 2)))
        elif t == mujoco.mjtGeom.mjGEOM_BOX:
            low = min(low, z - float(np.abs(R[2]) @ sz))
        elif t == mujoco.mjtGeom.mjGEOM_ELLIPSOID:
            low = min(low, z - float(np.sqrt(((R[2] * sz) ** 2).sum())))
    return float(low)


def home_qpos(mujoco, model, robot):
    """The robot's rest pose (``Robot.rest_pose``: 0, or the nearer limit) as MuJoCo's qpos."""
    qpos = model.qpos0.copy()
    rest = robot.rest_pose()
    for j in robot.joints.values():       # a mimic joint where its equality constraint puts it
        if j.mimic is not None and j.mimic.joint in rest:
            rest[j.name] = j.mimic.offset + j.mimic.multiplier * rest[j.mimic.joint]
    for name, value in rest.items():
        jid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
        if jid >= 0:
            qpos[model.jnt_qposadr[jid]] = value
    return qpos


def _lift_to_floor(mujoco, np, model, d, moving_only: bool) -> float:
    """How far up the robot must go for its lowest collision point to touch z = 0 (0 without one)."""
    geoms = [g for g in range(model.ngeom) if (model.geom_contype[g] or model.geom_conaffinity[g])
             and model.geom_type[g] != mujoco.mjtGeom.mjGEOM_PLANE and not (moving_only and model.geom_bodyid[g] == 0)]
    low = _lowest_point(mujoco, np, model, d, geoms) if geoms else np.inf
    return -low if np.isfinite(low) else 0.0


def fixed_base_lift(mujoco, model, robot) -> float:
    """A welded robot's lift so that it stands on the floor at home (its root's weld moves)."""
    import numpy as np

    d = mujoco.MjData(model)
    d.qpos[:] = home_qpos(mujoco, model, robot)
    mujoco.mj_forward(model, d)
    return _lift_to_floor(mujoco, np, model, d, moving_only=False)


def _make_ready(mujoco, spec, model, robot, notes, report, free):
    """Actuators, the `home` keyframe and contact exclusions, on the compiled spec."""
    import numpy as np

    spec.option.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
    plan = _joint_plan(robot, wheel_joints(robot))
    for link, mu in link_friction(robot).items():
        if mu >= MAX_FRICTION:
            continue
        for gs in spec.geoms:
            if gs.name == f"{link}_collision" or gs.name.startswith(f"{link}_collision_"):
                gs.friction = [mu, float(gs.friction[1]), float(gs.friction[2])]
                gs.priority = 1        # Gazebo's ground has mu 100: the robot's own mu decides
                if mu == 0:
                    gs.condim = 1      # frictionless (a caster Gazebo lets slide)
    for name, (stiffness, reference) in joint_springs(robot).items():
        js = spec.joint(name)
        if js is not None:
            js.stiffness = [stiffness, 0.0, 0.0]      # MuJoCo 4: (linear, and two higher-order terms)
            js.springref = reference
    d = mujoco.MjData(model)
    # home: the rest pose (0, or the nearer limit), the free base lifted onto the floor
    qpos = home_qpos(mujoco, model, robot)
    d.qpos[:] = qpos
    mujoco.mj_forward(model, d)
    lift = 0.0
    if free:
        fj = next(j for j in range(model.njnt) if model.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE)
        lift = _lift_to_floor(mujoco, np, model, d, moving_only=True)
        qpos[model.jnt_qposadr[fj] + 2] += lift
        d.qpos[:] = qpos
        mujoco.mj_forward(model, d)
    # a joint whose effort limit cannot hold its subtree against gravity at home (PR2's shoulders
    # rely on a spring counterbalance the URDF does not describe): that subtree is gravity-compensated
    compensated = []
    for name, (kind, _) in plan.items():
        jid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
        j = robot.joints[name]
        effort = j.limit.effort if j.limit is not None and j.limit.effort else None
        if jid < 0 or kind != "position" or not effort:
            continue
        need = abs(float(d.qfrc_bias[model.jnt_dofadr[jid]]))
        if need > 0.8 * effort:
            root_body = model.jnt_bodyid[jid]
            for b in range(model.nbody):
                a = b
                while a > root_body:
                    a = model.body_parentid[a]
                if a == root_body and spec.body(model.body(b).name) is not None:
                    spec.body(model.body(b).name).gravcomp = 1.0
            compensated.append(name)
            report.set("joint", name, report.get("joint", name).fate if report.get("joint", name) else "kept",
                       f"holding its subtree at home takes {need:.3g} N*m or N, over 80% of its effort limit "
                       f"{num(effort)}: the bodies it moves are gravity-compensated (gravcomp), as a real "
                       "counterbalance would")
    if compensated:
        notes.warn(f"{len(compensated)} joint(s) cannot hold what they carry at home within their effort limit: "
                   f"the bodies they move are gravity-compensated in MuJoCo: {', '.join(compensated)}")
    # bodies that touch at rest (MuJoCo already skips parent-child pairs): excluded
    excluded = set()
    for _ in range(50):
        pairs = {tuple(sorted((model.body(model.geom_bodyid[c.geom1]).name, model.body(model.geom_bodyid[c.geom2]).name)))
                 for c in d.contact[:d.ncon]}
        pairs -= excluded
        if not pairs:
            break
        for b1, b2 in sorted(pairs):
            ex = spec.add_exclude()
            ex.bodyname1, ex.bodyname2 = b1 or "world", b2 or "world"
            excluded.add((b1, b2))
        model = spec.compile()
        d = mujoco.MjData(model)
        d.qpos[:] = qpos
        mujoco.mj_forward(model, d)
    if excluded:
        report.set("contact", "self-collision", "approximated",
                   f"{len(excluded)} body pair(s) touching at rest excluded from collision: "
                   + ", ".join(f"{a}-{b}" for a, b in sorted(excluded)))
    # actuators, sized by the joint-space inertia at home: its diagonal, the last entry of each row
    # of MuJoCo's sparse lower-triangular M (mj_fullM would make a dense nv x nv copy: 3.2 GB at
    # 20,000 joints)
    diag = d.M[model.M_rowadr + model.M_rownnz - 1]
    dt = model.opt.timestep
    n_wheels = sum(1 for kind, _ in plan.values() if kind == "velocity")
    wheel_share = float(model.body_mass.sum()) / max(n_wheels, 1)     # the mass each wheel rolls
    ctrl = []
    n_pos = n_vel = 0
    for name, (kind, why) in plan.items():
        jid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
        if jid < 0:
            continue
        j = robot.joints[name]
        if kind is None:
            report.set("joint", name, report.get("joint", name).fate if report.get("joint", name) else "kept",
                       f"no actuator: {why}")
            continue
        dof = model.jnt_dofadr[jid]
        inertia = max(float(diag[dof]), 1e-9)
        effort = j.limit.effort if j.limit is not None and j.limit.effort else None
        act = spec.add_actuator()
        act.name, act.target, act.trntype = name, name, mujoco.mjtTrn.mjTRN_JOINT
        if effort:
            act.forcelimited = mujoco.mjtLimited.mjLIMITED_TRUE
            act.forcerange = [-effort, effort]
        if kind == "velocity":
            vel = j.limit.velocity if j.limit is not None and j.limit.velocity else None
            rolling = _rolling_kv(robot, j, inertia, dt, wheel_share)
            kv = float(f"{max(effort / (WHEEL_CLAMP_AT * vel), ROLLING_CLAMPED * rolling) if effort and vel else rolling:.4g}")
            act.set_to_velocity(kv=float(num(kv)))
            if vel:
                act.ctrllimited = mujoco.mjtLimited.mjLIMITED_TRUE
                act.ctrlrange = [-vel, vel]
            ctrl.append(0.0)
            n_vel += 1
            detail = f"velocity actuator (kv {num(kv)}{f', force {num(effort)}' if effort else ''})"
            own = float(diag[dof]) - float(model.dof_armature[dof])
            armature = float(f"{kv * dt / WHEEL_SERVO_STEP - own:.3g}")
            if armature > 0:      # a light wheel under a stiff servo: the motor's rotor inertia (see WHEEL_SERVO_STEP)
                spec.joint(name).armature = max(armature, float(model.dof_armature[dof]))
                detail += f", armature {num(armature)} kg·m² (the motor's rotor, which the URDF does not give)"
        else:
            slide = model.jnt_type[jid] == mujoco.mjtJoint.mjJNT_SLIDE
            kp_max = inertia * (OMEGA_DT / dt) ** 2
            kp = min(effort / FULL_EFFORT_AT["slide" if slide else "hinge"], kp_max) if effort else kp_max
            kp = float(f"{kp:.4g}")
            act.set_to_position(kp=float(num(kp)), dampratio=1.0)
            if model.jnt_limited[jid]:
                act.ctrllimited = mujoco.mjtLimited.mjLIMITED_TRUE
                act.ctrlrange = list(model.jnt_range[jid])
            ctrl.append(float(qpos[model.jnt_qposadr[jid]]))
            n_pos += 1
            detail = f"position actuator (kp {num(kp)}, critically damped{f', force {num(effort)}' if effort else ''})"
            if j.limit is not None and j.limit.effort == 0:
                detail += "; effort limit 0 read as not given (ROS-Industrial writes 0): no force limit"
        old = report.get("joint", name)
        report.set("joint", name, old.fate if old else "kept", (old.detail + "; " if old and old.detail else "")
                   + detail)
    key = spec.add_key()
    key.name = "home"
    key.qpos = [float(x) for x in qpos]
    if ctrl:
        key.ctrl = ctrl
    return n_pos, n_vel, lift


SCENE = """<mujoco model="{name} scene">
  <!-- generated by myrabot-desc convert: the robot on a floor; python -m mujoco.viewer --mjcf {scene} -->
  <include file="{robot}"/>

  <statistic center="{cx} {cy} {cz}" extent="{extent}"/>

  <visual>
    <headlight diffuse="0.6 0.6 0.6" ambient="0.3 0.3 0.3" specular="0 0 0"/>
    <rgba haze="0.15 0.25 0.35 1"/>
    <global azimuth="120" elevation="-20"/>
  </visual>

  <asset>
    <texture type="skybox" builtin="gradient" rgb1="0.3 0.5 0.7" rgb2="0 0 0" width="512" height="3072"/>
    <texture type="2d" name="groundplane" builtin="checker" mark="edge" rgb1="0.2 0.3 0.4" rgb2="0.1 0.2 0.3"
      markrgb="0.8 0.8 0.8" width="300" height="300"/>
    <material name="groundplane" texture="groundplane" texuniform="true" texrepeat="5 5" reflectance="0.2"/>
  </asset>

  <worldbody>
    <light pos="0 0 {light}" dir="0 0 -1" directional="true"/>
    <geom name="floor" size="0 0 0.05" type="plane" material="groundplane"/>
  </worldbody>
</mujoco>
"""


def scene_text(mujoco, model, robot_file: str, scene_file: str, name: str) -> str:
    """Menagerie's scene.xml: floor, light, the robot included."""
    import numpy as np

    d = mujoco.MjData(model)
    if model.nkey:
        mujoco.mj_resetDataKeyframe(model, d, 0)
    mujoco.mj_forward(model, d)
    pts = d.xpos[1:] if model.nbody > 1 else np.zeros((1, 3))
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    c = (lo + hi) / 2
    extent = max(float(np.linalg.norm(hi - lo)), 0.5)
    return SCENE.format(name=name.replace('"', "'"), robot=robot_file, scene=scene_file, cx=num(round(c[0], 3)),
                        cy=num(round(c[1], 3)), cz=num(round(c[2], 3)), extent=num(round(extent, 3)),
                        light=num(round(max(hi[2], 0) + 1.5, 3)))


def convert_mjcf(robot, output: str, base: str = "auto", scene: str | None = "scene.xml",
                 report: Report | None = None, allow_errors: bool = True) -> MjcfResult:
    """The MJCF of ``robot`` at ``output`` (plus its meshes and ``scene``). A collision mesh that
    MuJoCo cannot get stops the conversion unless ``allow_errors``."""
    import os

    # We never render: without this, `import mujoco` loads pyGLFW, which spawns a Python
    # subprocess to probe libglfw (a process per conversion, seen by the hardening audit).
    os.environ.setdefault("MUJOCO_GL", "disable")
    try:
        import mujoco
    except ImportError:
        raise InputError("MJCF needs the mujoco package: pip install mujoco") from None

    notes = Notes()
    if not robot.links:
        raise InputError("the model has no links: nothing to convert", robot.loc)
    _check_depth(robot)
    report = report if report is not None else Report("mjcf")
    seed(report, robot)
    warn_load_issues(robot, notes, "passed to MuJoCo as written")   # it reads the URDF's XML
    out = Path(output) if output != "-" else None
    if out is not None and scene and out.name == scene:
        raise InputError(f"the output is named {scene}, the name of the scene file written next to it: "
                         "choose another name")
    mesh_dirname = f"{out.stem}_meshes" if out else "meshes"
    urdf_root, prep, free = prepare_urdf(robot, notes, base, mesh_dirname, report)
    if prep.collision_errors and not allow_errors:
        refuse_or_record([Problem(m, loc) for m, loc in prep.collision_errors], False)
    if out is None and prep.meshes:
        raise InputError(f"this model has {len(prep.meshes)} mesh file(s): MJCF to stdout cannot carry them, "
                         "give -o OUT.xml")
    urdf_text = etree.tostring(urdf_root, encoding="unicode")
    ready = {}

    def compile_in(folder: Path) -> tuple[str, object]:
        prep.write_meshes(folder / mesh_dirname)
        tmp_urdf = folder / ".robot.urdf"
        tmp_urdf.write_text(urdf_text, encoding="utf-8")
        try:
            with _c_stdout_to(notes), _warnings_to(mujoco, notes):
                spec = mujoco.MjSpec.from_file(str(tmp_urdf))
                model = _compile(mujoco, spec, notes)
                if not free and scene:
                    lift = fixed_base_lift(mujoco, model, robot)
                    if abs(lift) > 1e-9:     # weld the root higher (or lower) so the robot stands on the floor
                        tmp_urdf.write_text(etree.tostring(_weld_at(urdf_root, robot, lift), encoding="unicode"),
                                            encoding="utf-8")
                        spec = mujoco.MjSpec.from_file(str(tmp_urdf))
                        model = _compile(mujoco, spec, notes)
                        report.set("link", robot.root or "root", "translated",
                                   f"root welded to the world {num(round(lift, 6))} m up, its lowest collision "
                                   "point on the floor")
                ready["counts"] = _make_ready(mujoco, spec, model, robot, notes, report, free)
                model = spec.compile()
                text = spec.to_xml()
        except ValueError as exc:
            msg = str(exc).strip().splitlines()
            raise InputError(f"MuJoCo rejected the model: {' '.join(m.strip() for m in msg if m.strip())}",
                             robot.loc) from None
        finally:
            tmp_urdf.unlink(missing_ok=True)
        return _postprocess(text, robot, mesh_dirname, free, mujoco.__version__,
                            bool(spec.compiler.balanceinertia)), model

    _report_mjcf(robot, report, free, base)
    scene_written = None
    if out is None:
        import tempfile

        with tempfile.TemporaryDirectory() as d:
            text, model = compile_in(Path(d))
        write_output("-", text)
    else:
        with OutputDir(out.parent if str(out.parent) else ".") as stage:
            text, model = compile_in(stage)
            (stage / out.name).write_text(text, encoding="utf-8")
            if scene:
                (stage / scene).write_text(scene_text(mujoco, model, out.name, scene, robot.name or out.stem),
                                           encoding="utf-8")
                scene_written = str(out.parent / scene)
        if prep.converted:
            notes.warn(f"{len(prep.converted)} mesh(es) converted to STL/MSH for MuJoCo (it reads STL, OBJ, MSH); "
                       "their embedded colours are replaced by the URDF/Gazebo colour")
    free = bool((model.jnt_type == mujoco.mjtJoint.mjJNT_FREE).any())
    n_pos, n_vel, _ = ready.get("counts", (0, 0, 0.0))
    return MjcfResult(text, notes, model.nbody, model.njnt, model.ngeom, model.nmesh, free,
                      str(out.parent / mesh_dirname) if out and prep.meshes else None,
                      model.nu, scene_written, report)


def _weld_at(urdf_root, robot, lift):
    """A copy of the prepared URDF whose roots hang from `world` by fixed joints ``lift`` m up."""
    root = copy.deepcopy(urdf_root)
    to_world = {j.find("child").get("link"): j for j in root.findall("joint")
                if j.find("parent") is not None and j.find("parent").get("link") == "world"
                and j.find("child") is not None}
    for r in (list(to_world) if robot.root == "world" else [r for r in robot.roots if r != "world"]):
        j_el = to_world.get(r)
        if j_el is None:
            _add_world_joint(root, r, "fixed")
            j_el = root.findall("joint")[-1]
        o = j_el.find("origin")
        if o is None:
            o = etree.SubElement(j_el, "origin")
        xyz = [float(v) for v in (o.get("xyz") or "0 0 0").split()]
        xyz[2] += lift
        o.set("xyz", nums(xyz))
    return root


def _report_mjcf(robot, report, free, base):
    """What MuJoCo's URDF compiler does with each element, beyond what prepare_urdf recorded."""
    root = robot.root
    for j in robot.joints.values():
        if j.type == "fixed":
            report.set("joint", j.name, "translated", f"fixed joint: '{j.child}' fused into its parent body")
            report.set("link", j.child, "translated", f"fused into the body of '{j.parent}' (fixed joint "
                                                       f"'{j.name}'); its geoms and mass kept there")
        elif j.type == "continuous":
            report.set("joint", j.name, "translated", "continuous -> unlimited hinge")
        elif j.type == "floating":
            report.set("joint", j.name, "translated", "floating -> free joint")
        elif j.type == "planar":
            report.set("joint", j.name, "dropped", "MuJoCo's URDF reader has no planar joint")
        if j.mimic is not None:
            report.set("mimic", j.name, "translated", f"equality constraint: {j.name} = "
                       f"{num(j.mimic.offset)} + {num(j.mimic.multiplier)} * {j.mimic.joint}")
        if j.dynamics is not None and j.dynamics.friction:
            report.set("joint", j.name, "translated", f"friction {num(j.dynamics.friction)} -> frictionloss")
    for name in robot.roots:
        if free:
            report.set("link", name, "translated", "root: a body with a free joint (mobile base)")
        elif base == "fixed" or not free:
            report.set("link", name, "translated", "root welded to the world (static: its mass has no effect)")
    for t in robot.transmissions:
        report.set("transmission", t.name or "?", "translated",
                   "read for the joints' interfaces; MuJoCo actuators written from the joint limits")

    springs, friction = joint_springs(robot), link_friction(robot)
    for g in robot.gazebo:
        for key in g.properties:
            if key in FRICTION_KEYS and g.reference in friction:
                mu = friction[g.reference]
                if mu <= MAX_FRICTION:
                    report.set("gazebo", f"{g.reference}/{key}", "translated", f"collision friction {num(mu)}"
                               + (" (over the floor's)" if mu < MAX_FRICTION else " (the floor's)"), g.loc)
                else:
                    report.set("gazebo", f"{g.reference}/{key}", "approximated",
                               f"mu {num(mu)}: the floor's friction {num(MAX_FRICTION)} (more makes MuJoCo's "
                               "contacts sink)", g.loc)
                continue
            if key in SPRING_KEYS and g.reference in springs:
                report.set("gazebo", f"{g.reference}/{key}", "translated",
                           "joint " + ("stiffness" if key == "springStiffness" else "springref"), g.loc)
                continue
            report.set("gazebo", f"{g.reference or 'model'}/{key}", "dropped", "Gazebo-only setting", g.loc)
        for p in g.plugins:
            drive = D.plugin_spec(p) is not None
            report.set("plugin", p.name or p.library or "?", "dropped",
                       "Gazebo drive plugin: its wheel joints get velocity actuators" if drive else
                       "Gazebo plugin: no MuJoCo equivalent", p.loc)
        if g.reference is None:
            for c in g.element:
                if isinstance(c.tag, str) and c.tag in ("joint", "link", "frame", "model"):
                    report.set(f"gazebo-{c.tag}", c.get("name") or "?", "dropped",
                               "declared in a <gazebo> block (SDF): MuJoCo's URDF reader does not see it",
                               robot.loc_of(c) or g.loc)
        for sn in g.sensors:
            report.set("sensor", sn.name or "?", "dropped", "Gazebo sensor: not converted to MuJoCo sensors", sn.loc)
            for p in sn.plugins:
                report.set("plugin", p.name or p.library or "?", "dropped", "a ROS sensor plugin", p.loc)
