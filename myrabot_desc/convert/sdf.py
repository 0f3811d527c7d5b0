"""The Robot model → an SDF 1.9 ``<model>`` for gz-sim, losing nothing.

``ign sdf -p`` (sdformat 12) lumps fixed joints, so sensor frames vanish, and drops a
massless link together with its subtree (anchors §6.1). Here fixed joints are kept by
default; with ``lump=True`` they are merged like sdformat does (combined inertia,
``<parent>_fixed_joint_lump__<child>_visual`` names) and every removed link and joint
stays as an SDF ``<frame>``. Massless links are kept with a placeholder inertial and
a warning. SDF 1.9 is what sdformat 12 (Debian 12's ``ign sdf``) validates; newer
gz-sim reads it as well.
"""

from __future__ import annotations

from dataclasses import dataclass

from lxml import etree

from myrabot_desc.convert.appearance import Appearance, material_element
from myrabot_desc.convert.common import (
    Notes,
    comment,
    element_of,
    num,
    nums,
    pose_text,
    pretty,
    sub,
    warn_load_issues,
)
from myrabot_desc.convert.gazebo import GazeboProps
from myrabot_desc.convert.report import Report, part_name, seed
from myrabot_desc.convert.sensors import translate_sensor
from myrabot_desc.convert.systems import Systems
from myrabot_desc.convert.uris import UriMapper
from myrabot_desc.errors import InputError
from myrabot_desc.model import plugins
from myrabot_desc.model.gazebo import EMITTERS, emitters
from myrabot_desc.model.inertia import combined, describe, repaired
from myrabot_desc.model.tree import rigid_bodies
from myrabot_desc.model.transforms import (
    EYE3,
    IDENTITY,
    compose,
    is_identity,
    pose_T,
    transform,
)

SDF_VERSION = "1.9"
# the per-link and per-joint elements are made with lxml's own call: sub()'s conversions are for
# values of any type, these are known
_SE = etree.SubElement
# Placeholder for massless links: 1 g with the inertia of a 5 cm sphere. Enough for DART to
# treat the body as regular, negligible next to any real part of a robot.
TINY_MASS = 1e-3
TINY_INERTIA = 1e-6


@dataclass
class SdfOptions:
    lump: bool = False
    uri_style: str = "absolute"


@dataclass
class SdfResult:
    model: object                   # the <model> element
    notes: Notes
    links: list[str]
    frames: list[str]
    joints: list[str]
    sensors: list[str]
    resource_dirs: list[str]


def _inertial_el(parent, members, host_T, repairs, repairs_by_link):
    """One SDF <inertial> for the link's members (a single one kept as written, several combined)."""
    parts = []
    for m in members:
        ine = m.inertial
        if ine is None or ine.mass <= 0:
            continue
        tensor, changed = repaired(ine)
        if changed:
            repairs.append(f"{m.name} {describe(ine, tensor)}")
            repairs_by_link[m.name] = describe(ine, tensor)
        parts.append((ine, compose(host_T[m.name], pose_T(ine.origin)), tensor))
    if not parts:
        return None
    el = _SE(parent, "inertial")
    if len(parts) == 1:
        ine, T, t = parts[0]
        if not is_identity(T):
            _SE(el, "pose").text = pose_text(T)
        _SE(el, "mass").text = num(ine.mass)
    else:
        M, com, t = combined([(i.mass, T, ti) for i, T, ti in parts])    # in the host link's axes
        T = (EYE3, com)
        if not is_identity(T):
            sub(el, "pose", pose_text(T))
        sub(el, "mass", M)
    inertia = _SE(el, "inertia")
    (xx, xy, xz), (_, yy, yz), (_, _, zz) = t
    _SE(inertia, "ixx").text = num(xx)
    _SE(inertia, "ixy").text = num(xy)
    _SE(inertia, "ixz").text = num(xz)
    _SE(inertia, "iyy").text = num(yy)
    _SE(inertia, "iyz").text = num(yz)
    _SE(inertia, "izz").text = num(zz)
    return el


def _geometry_el(parent, geo, uris):
    g = _SE(parent, "geometry")
    kind = getattr(geo, "kind", None)
    if kind == "box":
        _SE(_SE(g, "box"), "size").text = nums(geo.size)
    elif kind == "cylinder":
        c = sub(g, "cylinder")
        sub(c, "radius", geo.radius)
        sub(c, "length", geo.length)
    elif kind == "sphere":
        sub(sub(g, "sphere"), "radius", geo.radius)
    elif kind == "mesh":
        m = sub(g, "mesh")
        sub(m, "uri", uris.map(geo.filename, geo.path))
        if tuple(geo.scale) != (1.0, 1.0, 1.0):
            sub(m, "scale", geo.scale)
    else:
        sub(g, "empty")
    return g


def build_model(robot, opts: SdfOptions | None = None, notes: Notes | None = None,
                name: str | None = None, report: Report | None = None) -> SdfResult:
    opts = opts or SdfOptions()
    notes = notes if notes is not None else Notes()
    report = report if report is not None else Report("sdf")
    if not robot.links:
        raise InputError("the model has no links: nothing to convert", robot.loc)
    for j in robot.joints.values():  # a joint to nowhere cannot be placed (check reports it as T-rules)
        for end in (j.parent, j.child):
            if end not in robot.links:
                raise InputError(f"joint '{j.name}' names link '{end}', which does not exist: nothing to "
                                 "attach it to (run check for the whole picture)", j.loc)
    warn_load_issues(robot, notes)
    seed(report, robot)
    props = GazeboProps(robot, notes)
    uris = UriMapper(robot, opts.uri_style, notes)
    look = Appearance(robot, notes)
    model_name = name or robot.name or "robot"
    model = etree.Element("model", name=model_name)
    src = robot.source.name if robot.source else "URDF"
    comment(model, f"generated by myrabot-desc convert from {src} "
                   f"({'fixed joints lumped, removed links kept as frames' if opts.lump else 'fixed joints kept'})")

    world_links = {n for n, l in robot.links.items()
                   if n == "world" and not l.visuals and not l.collisions and l.inertial is None}
    mp = props.values(None)
    if mp.get("static") is not None:
        sub(model, "static", mp["static"])
    sc = mp.get("selfCollide")
    sc = sc if sc is not None else mp.get("self_collide")
    if sc is not None:
        sub(model, "self_collide", sc)

    # ---- which link hosts each URDF link (itself, or the link it is lumped into: model/tree.rigid_bodies,
    # lumping off for the joints <gazebo> keeps, and never into the world)
    if opts.lump:
        bodies = rigid_bodies(robot, keep=props.preserved, stop=frozenset(world_links))
        host, host_T, lumped_joints = bodies.host, bodies.offset, list(bodies.merged)
    else:
        host = {n: n for n in robot.links}
        host_T = dict.fromkeys(robot.links, IDENTITY)
        lumped_joints = []

    kept = [n for n in robot.links if host[n] == n and n not in world_links]
    members: dict = {n: [] for n in kept}          # one pass: a 20,000-link robot was quadratic here
    for m in robot.links:
        if host[m] in members:
            members[host[m]].append(robot.links[m])
    lumped_links = [n for n in robot.links if host[n] != n]
    lumped_ids = {id(j) for j in lumped_joints}      # identity: NamedTuples compare field by field
    emitted_joints = [j for j in robot.joints.values() if id(j) not in lumped_ids]

    # ---- names: links first; joints and frames must not clash with them (SDF 1.8+ rule)
    taken = set(kept)
    frame_names = {}
    for n in lumped_links:
        frame_names[n] = _unique(n, taken)
    joint_names = {}
    for j in robot.joints.values():
        joint_names[j.name] = _unique(j.name, taken)
        if joint_names[j.name] != j.name:
            notes.warn(f"joint '{j.name}' has the name of a link; renamed '{joint_names[j.name]}' in SDF", j.loc)

    # ---- sensors (from <gazebo reference> blocks) and systems (model-level plugins)
    sensor_outs = []
    sensor_fates = {}
    joint_sensors: dict[str, list] = {}
    for s in robot.sensors():
        if s.reference in robot.joints and s.reference not in robot.links and s.dialect == "sdf":
            # a force/torque sensor sits in a joint (SDF allows it): copied there, ROS plugins left out
            joint_sensors.setdefault(s.reference, []).append(s)
            sensor_fates[id(s)] = ("kept", f"in joint '{s.reference}' (SDF sensors may sit in joints)")
            continue
        out = translate_sensor(s, robot, notes)
        if out is not None:
            sensor_outs.append(out)
        sensor_fates[id(s)] = (("translated", f"an SDF sensor on '{out.link}'" + (f" ({out.comments[0]})"
                                                                                 if out.comments else ""))
                               if out is not None and out.sdf is not None else
                               ("dropped", "; ".join(out.comments) if out is not None and out.comments
                                else "not converted"))
    systems = Systems(robot, model_name, notes)
    systems.translate([p for g in robot.gazebo for p in g.plugins])
    sensor_outs.extend(systems.sensors)

    parent_joint = {j.child: j for j in emitted_joints}
    kept_set = set(kept)
    link_sensors: dict[str, list] = {}              # host link -> its sensors, in sensor_outs' order
    for so in sensor_outs:
        if so.link in host and host[so.link] in kept_set:
            link_sensors.setdefault(host[so.link], []).append(so)
    massless = []
    repairs = []
    repairs_by_link: dict[str, str] = {}
    sensor_names = []
    for n in kept:
        el = _SE(model, "link", name=n)
        pj = parent_joint.get(n)
        if pj is not None and pj.type not in ("floating", "planar"):
            if pj.parent in world_links:
                if not pj.origin.is_identity:
                    _SE(el, "pose").text = pose_text(pose_T(pj.origin))
            else:
                _SE(el, "pose", relative_to=joint_names[pj.name])
        props.apply_link(el, n)
        if _inertial_el(el, members[n], host_T, repairs, repairs_by_link) is None:
            massless.append(n)
            ine = sub(el, "inertial")
            sub(ine, "mass", TINY_MASS)
            t = sub(ine, "inertia")
            for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz"):
                sub(t, k, TINY_INERTIA if k in ("ixx", "iyy", "izz") else 0.0)
        for m in members[n]:
            lumped = m.name != n
            T = host_T[m.name]
            gz_mat = props.get(m.name).get("material")
            for k, v in enumerate(m.visuals):
                if v.geometry is None:
                    continue
                vname = _part_name(n, m.name, v.name, "visual", k, lumped)
                ve = sub(el, "visual", name=vname)
                P = compose(T, pose_T(v.origin))
                if not is_identity(P):
                    sub(ve, "pose", pose_text(P))
                _geometry_el(ve, v.geometry, uris)
                lk = look.look(v, gz_mat, m.loc)
                if lk is not None:
                    if lk.transparency > 0:
                        sub(ve, "transparency", lk.transparency)
                    material_element(ve, lk, uris)
                props.apply_visual(ve, m.name)
            for k, c in enumerate(m.collisions):
                if c.geometry is None:
                    continue
                cname = _part_name(n, m.name, c.name, "collision", k, lumped)
                ce = _SE(el, "collision", name=cname)
                P = compose(T, pose_T(c.origin))
                if not is_identity(P):
                    _SE(ce, "pose").text = pose_text(P)
                _geometry_el(ce, c.geometry, uris)
                props.apply_collision(ce, m.name)
        link_sensor_names: set[str] = set()
        for so in link_sensors.get(n, ()):
            for text in so.comments:
                comment(el, text)
            se = so.sdf
            if se is None:
                continue
            P = compose(host_T[so.link], so.T)
            old = se.find("pose")
            if old is not None:
                se.remove(old)
            if not is_identity(P):
                se.insert(0, etree.Element("pose"))
                se[0].text = pose_text(P)
            base, k = se.get("name") or "sensor", 2
            while se.get("name") in link_sensor_names:      # sdformat: unique in a link
                se.set("name", f"{base}_{k}")
                k += 1
            if se.get("name") != base:
                notes.warn(f"two sensors named '{base}' on link '{n}': the second is '{se.get('name')}'")
            link_sensor_names.add(se.get("name"))
            el.append(se)
            sensor_names.append(se.get("name"))
    for so in sensor_outs:
        if so.link not in host or host[so.link] not in kept_set:
            notes.warn(f"sensor on '{so.link}' dropped: that link is not in the model")
    emitter_fates = _emitters(robot, model, host, host_T, kept, notes)
    if props.commented:
        notes.warn(f"{len(props.commented)} Gazebo classic plugin(s) in <gazebo> <visual>/<collision> blocks kept as "
                   "XML comments (no gz-sim equivalent): " + ", ".join(n for n, _ in props.commented))

    if repairs:
        notes.warn(f"{len(repairs)} inertia tensor(s) break the triangle inequality (sdformat and gz-sim reject "
                   "them); the two smaller principal moments were raised until A + B = C (see check --inertia): "
                   + "; ".join(repairs))
    if massless:
        notes.warn(f"{len(massless)} massless link(s) kept with a placeholder inertial (mass {TINY_MASS} kg, "
                   f"inertia {TINY_INERTIA} kg*m^2) so that gz-sim keeps them and their sensors: "
                   + ", ".join(massless))

    # ---- joints
    out_joints = []
    for j in emitted_joints:
        jn = joint_names[j.name]
        if j.type == "floating":
            comment(model, f"URDF floating joint '{j.name}' ({j.parent} -> {j.child}): links in a model are "
                           "free unless jointed, so it is left out")
            continue
        if j.type == "planar":
            notes.warn(f"planar joint '{j.name}' has no SDF equivalent; '{j.child}' left free", j.loc)
            comment(model, f"URDF planar joint '{j.name}' not converted (no SDF type)")
            continue
        if j.child in world_links:
            continue
        type_ = "revolute" if j.type == "continuous" else j.type
        je = _SE(model, "joint", name=jn, type=type_)
        if j.parent in world_links:
            parent = "world"
        else:
            parent = host[j.parent]
            _SE(je, "pose", relative_to=parent).text = pose_text(compose(host_T[j.parent], pose_T(j.origin)))
        _SE(je, "parent").text = parent
        _SE(je, "child").text = j.child
        axis = None
        if j.type != "fixed":
            axis = _SE(je, "axis")
            _SE(axis, "xyz").text = nums(j.axis)
            lim = j.limit
            if lim is not None:
                bounds = j.type != "continuous" and lim.lower is not None and lim.upper is not None
                if bounds or lim.effort is not None or lim.velocity is not None:
                    le = _SE(axis, "limit")
                    if bounds:
                        _SE(le, "lower").text = num(lim.lower)
                        _SE(le, "upper").text = num(lim.upper)
                    if lim.effort is not None:
                        _SE(le, "effort").text = num(lim.effort)
                    if lim.velocity is not None:
                        _SE(le, "velocity").text = num(lim.velocity)
            if j.dynamics is not None and (j.dynamics.damping or j.dynamics.friction):
                d = sub(axis, "dynamics")
                sub(d, "damping", j.dynamics.damping)
                sub(d, "friction", j.dynamics.friction)
            if j.mimic is not None:
                comment(je, f"URDF mimic of '{j.mimic.joint}' (multiplier {j.mimic.multiplier}, offset "
                            f"{j.mimic.offset}) needs SDF 1.11; not converted")
                notes.warn(f"mimic on joint '{j.name}' not converted (SDF 1.9 has no mimic)", j.loc)
        props.apply_joint(je, axis, j.name)
        for sn in joint_sensors.pop(j.name, ()):
            el = element_of(sn.node)
            el.tail = sn.node.tail
            for pl in [c for c in el if isinstance(c.tag, str) and c.tag == "plugin"]:
                el.remove(pl)
            je.append(el)
            sensor_names.append(el.get("name"))
        out_joints.append(jn)

    # ---- frames for everything lumping removed
    frames = []
    for n in lumped_links:
        if n in world_links:
            continue
        fe = sub(model, "frame", name=frame_names[n], attached_to=host[n])
        sub(fe, "pose", pose_text(host_T[n]), relative_to=host[n])
        frames.append(frame_names[n])
    for j in lumped_joints:
        fe = sub(model, "frame", name=joint_names[j.name], attached_to=frame_names.get(j.child, j.child))
        frames.append(joint_names[j.name])
    if lumped_links:
        notes_text = f"{len(lumped_links)} lumped link(s) and {len(lumped_joints)} fixed joint(s) kept as frames"
        comment(model, notes_text)

    # ---- systems
    renamed = {k: v for k, v in joint_names.items() if k != v}
    for kind, item in systems.elements:
        if kind == "comment":
            comment(model, item)
        else:
            for c in item.iter("left_joint", "right_joint", "joint_name"):
                if c.text and c.text.strip() in renamed:
                    c.text = renamed[c.text.strip()]
            model.append(item)
    for jname, sns in joint_sensors.items():     # their joint was lumped or left out
        for sn in sns:
            sensor_fates[id(sn)] = ("dropped", f"its joint '{jname}' is not a joint of the SDF model")
            notes.warn(f"sensor '{sn.name}' in joint '{jname}' dropped: that joint is not in the model", sn.loc)
    extra_joints = _model_extras(model, robot, notes, report, taken | set(out_joints) | set(frames))
    out_joints.extend(extra_joints)
    uris.finish()
    look.finish()
    _report_sdf(robot, report, opts, host, world_links, frame_names, joint_names, lumped_joints, repairs_by_link,
                massless, props, systems, sensor_fates, emitter_fates)
    return SdfResult(model, notes, kept, frames, out_joints, sensor_names, sorted(uris.resource_dirs))


def _emitters(robot, model, host, host_T, kept, notes) -> list:
    """The lights and projectors of the links' <gazebo> blocks, into the SDF link that hosts their
    link (as ``ign sdf -p`` does), the pose carried through fixed-joint lumping; [(emitter, host or None)]."""
    out = []
    found = emitters(robot)
    links = {el.get("name"): el for el in model.findall("link")} if found else {}
    for e in found:
        n = host.get(e.reference)
        el = links.get(n) if n in kept else None
        if el is None:
            notes.warn(f"{e.kind} '{e.name}' of link '{e.reference}' dropped: that link is not in the model", e.loc)
            out.append((e, None))
            continue
        new = element_of(e.node)
        T, old = host_T[e.reference], new.find("pose")
        if e.relative_to is None and (e.pose is not None or old is None and not is_identity(T)):
            # a pose relative_to a named frame stays as written; an unreadable one too
            if old is not None:
                new.remove(old)
            P = compose(T, transform(e.pose[:3], e.pose[3:]) if e.pose is not None else IDENTITY)
            if not is_identity(P):
                new.insert(0, etree.Element("pose"))
                new[0].text = pose_text(P)
        el.append(new)
        out.append((e, n))
    return out


# what a model-level <gazebo> block may carry into the SDF <model> verbatim (sdformat copies them too)
MODEL_CHILDREN = ("joint", "link", "frame", "model", "include", "gripper")


def _model_extras(model, robot, notes, report, taken) -> list[str]:
    """Joints, links, frames... declared in model-level ``<gazebo>`` blocks (a parallel linkage's
    closing joint, a screw joint): copied into the model as ``ign sdf -p`` does."""
    out = []
    for g in robot.gazebo:
        if g.reference is not None:
            continue
        for c in g.node.elements:
            if c.ns or c.tag not in MODEL_CHILDREN:
                continue
            name = c.get("name") or ""
            loc = c.loc or g.loc
            el = element_of(c)
            el.tail = c.tail
            if name and name in taken:
                # PR2's grippers: a <gazebo> joint named like a URDF joint (ign keeps only one of the two)
                new = _unique(f"{name}_gazebo", taken)
                el.set("name", new)
                notes.warn(f"<gazebo> {c.tag} '{name}' has the name of another element of the model: kept as "
                           f"'{new}'", loc)
                report.set(f"gazebo-{c.tag}", name, "translated", f"copied into the model from a <gazebo> block, "
                           f"renamed '{new}' (the URDF has an element of that name)", loc)
            else:
                taken.add(name)
                report.set(f"gazebo-{c.tag}", name or "?", "kept", "copied into the model from a <gazebo> block", loc)
            comment(model, f"from a <gazebo> block ({loc})" if loc else "from a <gazebo> block")
            model.append(el)
            if c.tag == "joint":
                out.append(el.get("name"))
    return out


def _report_sdf(robot, report, opts, host, world_links, frame_names, joint_names, lumped_joints, repairs_by_link,
                massless, props, systems, sensor_fates, emitter_fates=()) -> None:
    """The fate of every source element in the SDF (seed() marked them all kept)."""

    lumped = {j.name for j in lumped_joints}
    massless = set(massless)
    for n, link in robot.links.items():
        if n in world_links:
            report.set("link", n, "translated", "the URDF 'world' link is the SDF world: joints to it attach there")
        elif host[n] != n:
            report.set("link", n, "translated", f"lumped into '{host[n]}' (fixed joint), kept as <frame "
                                                f"name=\"{frame_names[n]}\">")
            if link.inertial is not None and link.inertial.mass > 0:
                report.set("inertial", n, "translated", f"combined into the inertial of '{host[n]}'")
        for k, v in enumerate(link.visuals):
            if v.geometry is None:
                report.set("visual", part_name(n, k), "dropped", "no geometry the loader could read")
        for k, c in enumerate(link.collisions):
            if c.geometry is None:
                report.set("collision", part_name(n, k), "dropped", "no geometry the loader could read")
        if n in repairs_by_link:
            report.set("inertial", n, "approximated", f"breaks A + B >= C: raised {repairs_by_link[n]}")
        if n in massless:
            report.set("inertial", n, "approximated", f"massless: placeholder {TINY_MASS} kg, inertia "
                                                      f"{TINY_INERTIA} kg*m^2 (gz-sim drops massless links)")
    for j in robot.joints.values():
        if j.name in lumped:
            report.set("joint", j.name, "translated", f"fixed joint lumped: kept as <frame name=\"{joint_names[j.name]}\">")
        elif j.type == "floating":
            report.set("joint", j.name, "dropped", "floating: links in an SDF model are free unless jointed")
        elif j.type == "planar":
            report.set("joint", j.name, "dropped", f"planar: no SDF joint type; '{j.child}' left free")
        elif j.child in world_links:
            report.set("joint", j.name, "dropped", "its child is the world")
        elif j.type == "continuous":
            report.set("joint", j.name, "translated", "continuous -> revolute without limits")
        elif joint_names[j.name] != j.name:
            report.set("joint", j.name, "translated", f"renamed '{joint_names[j.name]}' (a link has its name)")
        if j.mimic is not None:
            report.set("mimic", j.name, "dropped", "SDF 1.9 has no mimic (1.11 has): kept as a comment")
    for g in robot.gazebo:
        for key in g.properties:
            ref = g.reference or "model"
            if f"{key} ({ref})" in props.unknown or (key in EMITTERS and ref in robot.links):
                continue        # each dropped element below; lights and projectors by name (emitters)
            report.set("gazebo", f"{ref}/{key}", "translated", "SDF link/collision/joint property", g.loc)
    for name, n in props.commented:
        report.set("plugin", name, "dropped", "a Gazebo classic plugin in a <gazebo> <visual>/<collision>: no gz-sim "
                   "equivalent, kept as an XML comment", n.loc)
    for ref, label, loc in props.dropped:
        report.set("gazebo", f"{ref}/{label}", "dropped", "no SDF equivalent", loc)
    for e, where in emitter_fates:
        name = f"{e.reference}/{e.kind} '{e.name}'" if e.name else f"{e.reference}/{e.kind}"
        if where is None:
            report.set("gazebo", name, "dropped", f"its link '{e.reference}' is not in the model", e.loc)
        else:
            report.set("gazebo", name, "kept", f"an SDF <{e.kind}> of link '{where}'", e.loc)
    for g in robot.gazebo:
        for pl in g.plugins:
            kind = plugins.kind(pl)
            fate, detail = {
                "imu": ("translated", "an SDF imu sensor"),
                "joint_state": ("translated", "gz-sim JointStatePublisher"),
                "ros_control": ("translated", "gz-sim joint position controllers and the joint state publisher"),
                "gz": ("kept", "a gz-sim system"),
            }.get(kind, ("dropped", "no gz-sim equivalent: kept as an XML comment"))
            if id(pl) in systems.replaced:
                fate, detail = "translated", systems.replaced[id(pl)]
            elif kind in ("diff_drive", "skid_steer"):
                ok = bool(systems.drive_joints) and any(v in systems.drive_joints for v in pl.params.values())
                fate, detail = (("translated", "gz-sim DiffDrive, separation and radius measured on the URDF")
                                if ok else ("dropped", "wheel joints or geometry not found: kept as a comment"))
            report.set("plugin", pl.name or pl.library or "?", fate, detail, pl.loc)
    if systems.drive_fate is not None:          # what the base's kind became (mecanum, planar, Ackermann, swerve)
        report.set("drive", systems.base.kind, *systems.drive_fate, systems.base.loc)
    for sn in robot.sensors():
        fate, detail = sensor_fates.get(id(sn), ("dropped", "not converted"))
        report.set("sensor", sn.name or "?", fate, detail, sn.loc)
        for pl in sn.plugins:
            report.set("plugin", pl.name or pl.library or "?", "dropped",
                       "a ROS sensor plugin: gz-sim sensors publish themselves (topic and frame carried over)",
                       pl.loc)
    for t in robot.transmissions:
        report.set("transmission", t.name or "?", "translated",
                   "read for the controllers: gz-sim has no transmissions")


def _unique(name, taken):
    out, k = name, 1
    while out in taken:
        out = f"{name}_joint" if k == 1 else f"{name}_{k}"
        k += 1
    taken.add(out)
    return out


def _part_name(host, member, given, kind, k, lumped):
    base = given or (f"{member}_{kind}" if k == 0 else f"{member}_{kind}_{k}")
    if lumped:
        return f"{host}_fixed_joint_lump__{base}" if given else f"{host}_fixed_joint_lump__{member}_{kind}" + (
            f"_{k}" if k else "")
    return base


def to_sdf(robot, opts: SdfOptions | None = None, report: Report | None = None) -> tuple[str, SdfResult]:
    res = build_model(robot, opts, report=report)
    root = etree.Element("sdf", version=SDF_VERSION)
    root.append(res.model)
    return pretty(root), res
