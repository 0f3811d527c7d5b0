"""The robot's tree in the spec: one MuJoCo body per link, its joint, inertial and geoms.

Every link becomes a body placed by its parent joint; a link fixed to its parent (or a root
welded to the world) becomes a body without a joint, which MuJoCo's ``fusestatic`` fuses into
its parent at the first compile, as its URDF reader does (its geoms keep their place in a
``<frame>``, its mass and inertia are added to the parent's). The link named ``world`` is the
world body.

- joints: revolute and continuous -> hinge, prismatic -> slide, floating -> free, planar -> two
  slides and a hinge (``NAME_TX``, ``NAME_TY``, ``NAME_RZ``); a range when the limit has lower <
  upper (equal or reversed limits leave the joint unlimited, said once), the effort as the
  joint's actuator force range, ``<dynamics>`` damping and friction (``frictionloss``), Gazebo's
  joint springs. A joint whose child already has a parent joint (a closed loop, only with
  --allow-errors) is left out: MuJoCo's bodies form a tree.
- the base: a free joint for a mobile base (``--base free``, or ``auto`` and model/drive.py's
  ``is_mobile``), else welded to the world (``--base fixed`` welds a root joined to ``world`` by
  a moving joint too). With ``auto``, a base moved as a body (mecanum, omni, planar: model/drive's
  ``BODY_MOVED``; the rollers are not modelled, and a planar-move plugin moves the body itself)
  gets a planar base instead: ``base_x``, ``base_y`` (world slides) and ``base_yaw`` (a hinge about
  z), each with a velocity actuator, at its standing height.
- inertials: as the URDF gives them (a link without ``<inertial>`` is massless, as urdfdom, KDL
  and Pinocchio read it: ``inertiafromgeom`` is false), tensors that break A + B >= C repaired
  like the SDF path (model/inertia.py); a moving body with no mass even with its fused links gets
  a 1 g placeholder (MuJoCo refuses massless moving bodies).
- geoms: visuals in group 1 (no contacts, no mass) with one explicit rgba each (the Gazebo
  material, else the URDF colour; a texture contributes its mean colour); collisions in group 3
  (hidden by the viewer's defaults), named after their link (``LINK_collision``, ``_1``...), with
  Gazebo's friction below the floor's (priority over it; mu 0 is frictionless). A primitive of
  size 0 is left out (MuJoCo refuses it), and so is a mesh that cannot be found or read.
- mimic joints: joint equality constraints (``polycoef`` offset, multiplier).
"""

from __future__ import annotations

from pathlib import Path

from myrabot_desc.convert.appearance import Appearance, texture_mean_rgb
from myrabot_desc.convert.common import num, nums
from myrabot_desc.convert.mjcf.gazebo_physics import MAX_FRICTION, joint_springs, link_friction
from myrabot_desc.convert.report import part_name
from myrabot_desc.model import drive as D
from myrabot_desc.model.tree import rigid_bodies
from myrabot_desc.model.inertia import describe, repaired
from myrabot_desc.model.transforms import matmul3, transform, transpose3
from myrabot_desc.records import Struct

TINY_MASS = 1e-3
TINY_INERTIA = 1e-6
WORLD = "world"


class Tree(Struct):
    """What the body builder left out or made up, for the writer to refuse or say."""

    collision_errors: list                 # (message, loc) of collision meshes left out
    placeholders: list[str]                # moving bodies given the 1 g placeholder
    planar_base: tuple[str, ...] = ()      # the planar base's joints (base_x, base_y, base_yaw), if any


PLANAR_BASE = ("base_x", "base_y", "base_yaw")


def planar_base(robot, base: str) -> bool:
    """A base moved as a body (mecanum, omni, planar) under ``--base auto``: slides and a yaw hinge."""
    if base != "auto" or len(robot.roots) != 1:
        return False
    b = D.base(robot)
    return b is not None and b.kind in D.BODY_MOVED and not (set(PLANAR_BASE) & set(robot.joints))


def base_is_free(robot, base: str) -> bool:
    return base == "free" or (base == "auto" and D.is_mobile(robot))


def spanning_joints(robot, report) -> list:
    """The joints of the tree MuJoCo builds: each link's first parent joint; a later one (a closed
    loop) is reported dropped, as is a joint naming a link the model does not have."""
    seen: set[str] = set()
    out = []
    for j in robot.joints.values():
        if j.parent not in robot.links or j.child not in robot.links:
            report.set("joint", j.name, "dropped", "its parent or child link is not in the model")
        elif j.child in seen:
            report.set("joint", j.name, "dropped", f"'{j.child}' already has a parent joint: MuJoCo bodies form a tree")
        else:
            seen.add(j.child)
            out.append(j)
    return out


def top_links(robot, joints) -> list[str]:
    """The links that hang from MuJoCo's world body: the roots, or the children of ``world``."""
    children = {j.child for j in joints}
    roots = [n for n in robot.links if n not in children]
    if WORLD in roots:
        return [n for n in roots if n != WORLD] + [j.child for j in joints if j.parent == WORLD]
    return roots


def build_tree(mujoco, spec, robot, plan, notes, report, base: str) -> Tree:
    """Add the robot's bodies, joints, geoms and mimic equalities to ``spec``."""
    joints = spanning_joints(robot, report)
    kids: dict[str, list] = {}
    for j in joints:
        kids.setdefault(j.parent, []).append(j)
    tops = top_links(robot, joints)
    free = base_is_free(robot, base)
    planar = free and planar_base(robot, base)
    placeholders = _massless_moving(robot, joints, tops, free, base)
    builder = _Builder(mujoco, spec, robot, plan, notes, report, placeholders)

    from_world = {j.child: j for j in joints if j.parent == WORLD}
    if WORLD in robot.links and WORLD not in {j.child for j in joints}:
        builder.geoms(spec.worldbody, robot.links[WORLD])
    stack = []
    for name in tops:
        body = spec.worldbody.add_body(name=name)
        j = from_world.get(name)
        if j is not None:
            builder.place(body, j.origin)
        if free and planar:
            # world-frame slides, then the yaw: the body twist (vx, vy) is R(yaw)·ctrl (as gz VelocityControl)
            for jn, kind, axis in zip(PLANAR_BASE, (mujoco.mjtJoint.mjJNT_SLIDE, mujoco.mjtJoint.mjJNT_SLIDE,
                                                    mujoco.mjtJoint.mjJNT_HINGE), ((1, 0, 0), (0, 1, 0), (0, 0, 1))):
                body.add_joint(name=jn, type=kind, axis=list(axis))
        elif free:
            body.add_freejoint(name=j.name if j is not None else f"{name}_free_joint")
        elif j is not None and base != "fixed":
            builder.joint(body, j)
        stack.append((name, body))
    stack.reverse()
    while stack:
        name, body = stack.pop()
        builder.link(body, robot.links[name])
        made = []
        for j in kids.get(name, ()):
            child = body.add_body(name=j.child)
            builder.place(child, j.origin)
            builder.joint(child, j)
            made.append((j.child, child))
        stack.extend(reversed(made))
    builder.mimics(joints)
    builder.finish()
    if planar:
        b = D.base(robot)
        for n in b.wheels:        # unmodelled rollers: an isotropic wheel-floor friction would fight the sideways motion
            j = robot.joints.get(n)
            if j is not None and j.type != "fixed":
                spec.add_exclude(bodyname1="world", bodyname2=j.child)
        report.set("drive", b.kind, "approximated",
                   f"a {b.kind} base ({b.why}) moved as a body: world slides base_x, base_y and a hinge base_yaw, "
                   "each with a velocity actuator (a body twist is R(yaw)·(vx, vy)); "
                   + ("its rollers are not modelled: the wheels do not touch the world (contact exclusions) and "
                      "spin at their velocity actuators' command" if b.kind != "planar" else "its plugin moved the body"))
    return Tree(builder.collision_errors, placeholders, PLANAR_BASE if planar else ())


def _massless_moving(robot, joints, tops, free: bool, base: str) -> list[str]:
    """Links that head a moving body (the child of a moving joint, a free root) whose mass, with
    every link fused into it through fixed joints, is zero."""
    from_world = {j.child: j for j in joints if j.parent == WORLD}
    moving = [j.child for j in joints if j.type != "fixed" and j.parent != WORLD]
    for name in tops:
        j = from_world.get(name)
        if free or (j is not None and j.type != "fixed" and base != "fixed"):
            moving.append(name)
    masses = rigid_bodies(robot, stop={WORLD}).masses(robot)
    return [n for n in moving if masses.get(n, 0.0) <= 0]


class _Builder:
    def __init__(self, mujoco, spec, robot, plan, notes, report, placeholders):
        self.mj, self.spec, self.robot, self.plan = mujoco, spec, robot, plan
        self.notes, self.report = notes, report
        self.placeholders = set(placeholders)
        self.look = Appearance(robot, notes)
        self.gz_material: dict[str, str] = {}
        for g in robot.gazebo:
            if g.reference is not None and "material" in g.properties:
                self.gz_material[g.reference] = g.properties["material"]
        self.springs = joint_springs(robot)
        self.friction = link_friction(robot)
        self.visual_names = {v.name for link in robot.links.values() for v in link.visuals if v.name}
        self.geom_names: set[str] = set()
        self.collision_errors: list = []
        self.quats: dict = {}
        self.texture_means: dict = {}         # texture file -> its mean colour (None: unreadable)

    # ------------------------------------------------------------ poses
    def quat(self, rpy) -> list[float]:
        key = tuple(rpy)
        q = self.quats.get(key)
        if q is None:
            import numpy as np

            q = np.zeros(4)
            self.mj.mju_euler2Quat(q, np.array(key, dtype=float), "XYZ")      # URDF: fixed axes x, y, z
            q = self.quats[key] = [float(x) for x in q]
        return q

    def place(self, el, origin) -> None:
        el.pos = list(origin.xyz)
        if any(origin.rpy):
            el.quat = self.quat(origin.rpy)

    # ------------------------------------------------------------ joints
    def joint(self, body, j) -> None:
        mj = self.mj
        if j.type == "fixed":
            return
        if j.type == "floating":
            body.add_freejoint(name=j.name)
            return
        if j.type == "planar":
            self._planar(body, j)
            return
        js = body.add_joint(name=j.name, type=mj.mjtJoint.mjJNT_SLIDE if j.type == "prismatic"
                            else mj.mjtJoint.mjJNT_HINGE, axis=list(j.axis))
        self._dynamics(js, j)
        lim = j.limit
        if lim is not None:
            if j.type != "continuous" and lim.lower is not None and lim.upper is not None:
                if lim.lower < lim.upper:
                    js.range = [lim.lower, lim.upper]
                else:
                    self.notes.warn(f"joint '{j.name}' has {'equal' if lim.lower == lim.upper else 'reversed'} "
                                    f"lower and upper limits ({num(lim.lower)}, {num(lim.upper)}): left unlimited",
                                    j.loc)
            # a negative effort is SDF's "no limit" (Audibot's -1), not a 1 N·m cap
            effort = lim.effort if lim.effort and lim.effort > 0 else 0.0
            if effort > 0:
                js.actfrcrange = [-effort, effort]
        spring = self.springs.get(j.name)
        if spring is not None:
            js.stiffness = [spring[0], 0.0, 0.0]      # MuJoCo 4: (linear, and two higher-order terms)
            js.springref = spring[1]

    def _dynamics(self, js, j) -> None:
        if j.dynamics is not None:
            if j.dynamics.damping:
                js.damping = [j.dynamics.damping, 0.0, 0.0]
            if j.dynamics.friction:
                js.frictionloss = j.dynamics.friction

    def _planar(self, body, j) -> None:
        """Slides along two axes across the plane's normal and a hinge about it (MuJoCo's URDF reader's)."""
        import numpy as np

        mj = self.mj
        q, R = np.zeros(4), np.zeros(9)
        mj.mju_quatZ2Vec(q, np.array(j.axis, dtype=float))
        mj.mju_quat2Mat(R, q)
        R = R.reshape(3, 3)
        names = []
        for suffix, kind, axis in (("_TX", mj.mjtJoint.mjJNT_SLIDE, R[:, 0]), ("_TY", mj.mjtJoint.mjJNT_SLIDE, R[:, 1]),
                                   ("_RZ", mj.mjtJoint.mjJNT_HINGE, j.axis)):
            js = body.add_joint(name=j.name + suffix, type=kind, axis=[float(a) for a in axis])
            self._dynamics(js, j)
            names.append(j.name + suffix)
        self.report.set("joint", j.name, "translated", f"planar -> two slides and a hinge ({', '.join(names)})")

    def mimics(self, joints) -> None:
        mj = self.mj
        movable = {j.name for j in joints if j.type in ("revolute", "continuous", "prismatic")}
        for j in joints:
            if j.mimic is None:
                continue
            m = j.mimic
            if j.name not in movable or m.joint not in movable:
                why = (f"'{j.name}' is a {j.type} joint" if j.name not in movable else
                       f"'{m.joint}' is not a revolute, continuous or prismatic joint of the tree")
                self.report.set("mimic", j.name, "dropped", f"mimics '{m.joint}', but {why}: nothing to constrain")
                self.notes.warn(f"<mimic> of joint '{j.name}' left out: {why} (a mimic needs two revolute, "
                                "continuous or prismatic joints)", j.loc)
                continue
            eq = self.spec.add_equality(type=mj.mjtEq.mjEQ_JOINT, objtype=mj.mjtObj.mjOBJ_JOINT, name1=j.name,
                                        name2=m.joint)
            eq.data[0:5] = [m.offset, m.multiplier, 0.0, 0.0, 0.0]
            self.report.set("mimic", j.name, "translated", f"equality constraint: {j.name} = {num(m.offset)} + "
                            f"{num(m.multiplier)} * {m.joint}")

    # ------------------------------------------------------------ links
    def link(self, body, link) -> None:
        self.inertial(body, link)
        self.geoms(body, link)

    def inertial(self, body, link) -> None:
        if link.name in self.placeholders:
            body.mass, body.ipos, body.inertia = TINY_MASS, [0.0, 0.0, 0.0], [TINY_INERTIA] * 3
            body.explicitinertial = True
            self.report.set("inertial", link.name, "approximated",
                            f"a moving body with no mass (even with its fixed children): {TINY_MASS} kg placeholder "
                            "(MuJoCo needs mass on every moving body)")
            return
        ine = link.inertial
        if ine is None:       # massless, as urdfdom reads it (inertiafromgeom is false)
            return
        tensor = None
        if ine.mass > 0:
            tensor, changed = repaired(ine)
            if changed:
                how = describe(ine, tensor)
                self.notes.warn(f"link '{link.name}': inertia breaks A + B >= C, raised {how}", ine.loc)
                self.report.set("inertial", link.name, "approximated", f"inertia breaks A + B >= C: raised {how}")
        else:
            tensor = ((ine.ixx, ine.ixy, ine.ixz), (ine.ixy, ine.iyy, ine.iyz), (ine.ixz, ine.iyz, ine.izz))
        body.mass = ine.mass
        body.ipos = list(ine.origin.xyz)
        body.iquat, body.inertia = self._principal(tensor, ine.origin.rpy)
        body.explicitinertial = True

    def _principal(self, tensor, rpy):
        """(iquat, diagonal) of a tensor given in the inertial origin's frame: its principal axes
        in the link frame and moments, as MuJoCo's compiler finds them (``mju_eig3``)."""
        import numpy as np

        R, _ = transform((0.0, 0.0, 0.0), rpy)
        T = matmul3(matmul3(R, tensor), transpose3(R))
        if all(abs(x) <= 0.0 for row in T for x in row):
            return [1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0]
        w, V, q = np.zeros(3), np.zeros(9), np.zeros(4)
        self.mj.mju_eig3(w, V, q, np.array(T, dtype=float).flatten())
        return [float(x) for x in q], [max(float(x), 0.0) for x in w]

    # ------------------------------------------------------------ geoms
    def geoms(self, body, link) -> None:
        gz_mat = self.gz_material.get(link.name)
        for k, v in enumerate(link.visuals):
            g = self._geom(body, link, v, "visual", k)
            if g is None:
                continue
            g.contype, g.conaffinity, g.group, g.density = 0, 0, 1, 0.0
            if v.name:
                if v.name in self.geom_names:
                    self.notes.warn(f"link '{link.name}': a second visual named '{v.name}': left unnamed", v.loc)
                else:
                    g.name = v.name
                    self.geom_names.add(v.name)
            lk = self.look.look(v, gz_mat, link.loc)
            if lk is not None:
                rgb = tuple(lk.diffuse[:3])
                mean = None
                if lk.texture:
                    if lk.texture not in self.texture_means:
                        self.texture_means[lk.texture] = texture_mean_rgb(lk.texture)
                    mean = self.texture_means[lk.texture]
                if mean is not None:
                    rgb = tuple(round(a * b, 4) for a, b in zip(rgb, mean))
                alpha = (lk.diffuse[3] if len(lk.diffuse) > 3 else 1.0) * (1.0 - lk.transparency)
                g.rgba = [float(x) for x in rgb + (alpha,)]
        mu = self.friction.get(link.name)
        for k, c in enumerate(link.collisions):
            g = self._geom(body, link, c, "collision", k)
            if g is None:
                continue
            g.group = 3
            # named after their link (MuJoCo keeps the name): contacts and the report say which link
            # touches what; visual names stay as written
            base_name = f"{link.name}_collision" + (f"_{k}" if k else "")
            name, n = base_name, 2
            while name in self.visual_names or name in self.geom_names:
                name, n = f"{base_name}_{n}", n + 1
            self.geom_names.add(name)
            g.name = name
            if mu is not None and mu < MAX_FRICTION:
                g.friction = [mu, float(g.friction[1]), float(g.friction[2])]
                g.priority = 1        # Gazebo's ground has mu 100: the robot's own mu decides
                if mu == 0:
                    g.condim = 1      # frictionless (a caster Gazebo lets slide)

    def _geom(self, body, link, part, kind: str, k: int):
        """A geom for one visual or collision, or None (reported) when MuJoCo cannot have it."""
        mj = self.mj
        geo = part.geometry
        rname = part_name(link.name, k)
        if geo is None:
            self.report.set(kind, rname, "dropped", "no geometry that can be read")
            return None
        flat = _flat(geo)
        if flat:      # MuJoCo refuses a geom of size 0 (a placeholder `<box size="0 0 0"/>`)
            self.report.set(kind, rname, "dropped", f"{flat}: no volume, MuJoCo refuses a geom of size 0")
            self.notes.warn(f"link '{link.name}': {kind} {flat} left out (MuJoCo refuses a geom of size 0)", part.loc)
            return None
        if geo.kind == "mesh":
            src = self.plan.source(geo)
            if src is None:
                self.report.set(kind, rname, "dropped", f"mesh {geo.filename}: file not found")
                return None
            asset = self.plan.asset(src, geo.scale)
            if asset is None:
                why = self.plan.why.get(src, "unreadable")
                if kind == "collision":
                    self.collision_errors.append((f"collision mesh {geo.filename} of link '{link.name}': {why}",
                                                  part.loc))
                self.report.set(kind, rname, "dropped", f"mesh {geo.filename}: {why}")
                return None
            if self.plan.is_converted(src):
                self.report.set(kind, rname, "translated", f"mesh {src.name} converted to "
                                f"{Path(self.plan.file_name(src)).suffix[1:].upper()}"
                                + (" (its embedded colours replaced by the URDF/Gazebo colour)" if kind == "visual"
                                   else ""))
            g = body.add_geom(type=mj.mjtGeom.mjGEOM_MESH, meshname=asset)
        elif geo.kind == "box":
            g = body.add_geom(type=mj.mjtGeom.mjGEOM_BOX, size=[s / 2 for s in geo.size])
        elif geo.kind == "cylinder":
            g = body.add_geom(type=mj.mjtGeom.mjGEOM_CYLINDER, size=[geo.radius, geo.length / 2, 0.0])
        else:
            g = body.add_geom(type=mj.mjtGeom.mjGEOM_SPHERE, size=[geo.radius, 0.0, 0.0])
        self.place(g, part.origin)
        return g

    def finish(self) -> None:
        self.plan.warn_left_out()


def _flat(geo) -> str | None:
    """'box size 0 0 0' when a box, cylinder or sphere has a size of zero (or less)."""
    if geo.kind == "box" and any(s <= 0 for s in geo.size):
        return f"box size {nums(geo.size)}"
    if geo.kind == "cylinder" and (geo.radius <= 0 or geo.length <= 0):
        return f"cylinder radius {num(geo.radius)} length {num(geo.length)}"
    if geo.kind == "sphere" and geo.radius <= 0:
        return f"sphere radius {num(geo.radius)}"
    return None


def placeholder_warning(notes, placeholders) -> None:
    if placeholders:
        notes.warn(f"{len(placeholders)} moving link(s) have no mass, even with the links fixed to them: given "
                   f"{TINY_MASS} kg each for MuJoCo: " + ", ".join(sorted(placeholders)))
