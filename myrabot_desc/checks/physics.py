"""P: static support on the ground, spawn penetration, dynamics smoke (Pinocchio), mass summary."""

from __future__ import annotations

import math

from myrabot_desc.checks.examples import drive_example as _drive
from myrabot_desc.checks.inertia import principal
from myrabot_desc.checks.rule import Finding, Fix, FixInfo, InsertAfter, SetValue, rule
from myrabot_desc.errors import InputError
from myrabot_desc.model import drive as D
from myrabot_desc.model.inertia import combined, eigh3, principal_moments, tensor
from myrabot_desc.model.kinematics import center_of_mass
from myrabot_desc.model.parts import JOINT_TYPES
from myrabot_desc.model.pin_model import MAX_DOF
from myrabot_desc.model.shapes import surface_points
from myrabot_desc.model.support import collision_shapes, lowest, signed_distance, stance
from myrabot_desc.model.transforms import compose, place, pose_T
from myrabot_desc.model.tree import MAX_TREE_DEPTH, depth, rigid_bodies

_FINGER = """<link name="finger">{inertial}</link>
<joint name="finger_joint" type="revolute">
  <parent link="base_link"/>
  <child link="finger"/>
  <axis xyz="0 1 0"/>
  <limit lower="-1" upper="1" effort="2" velocity="3"/>
</joint>"""
_FINGER_MASS = ('\n  <inertial>\n    <mass value="0.02"/>\n'
                '    <inertia ixx="6.7e-06" ixy="0" ixz="0" iyy="6.7e-06" iyz="0" izz="1.3e-06"/>\n  </inertial>\n')

SPAWN_TOL = 0.002        # m: penetration Gazebo resolves without a visible jump


def _collision_world(ctx):
    """(link, collision item, world pose (R, p), mesh) of every collision shape at q = 0
    (model/support.collision_shapes; mesh shapes only with --inertia/--meshes, from check's cache)."""
    P = ctx.poses
    for link, it, mesh in collision_shapes(ctx.robot, P, (lambda g, loc: ctx.mesh(g)) if ctx.opts.load_meshes else None):
        yield link, it, compose(P[link.name], pose_T(it.origin)), mesh


def _placed_points(g, pose, n: int, mesh):
    """``surface_points(g, n, mesh)`` placed by the world pose (R, p): [(x, y, z)]."""
    pts = surface_points(g, n, mesh)
    return place(pose, pts.tolist() if hasattr(pts, "tolist") else pts)


def _sign(x: float) -> float:
    """numpy's sign of a float: 1, -1, or the zero (or NaN) itself."""
    return 1.0 if x > 0 else -1.0 if x < 0 else x


def support(ctx):
    """What the robot stands on at q = 0 (model/support.stance: the same function sim and the viewer
    use), or None without collision geometry or mass."""

    return ctx.fact("support", lambda: stance(ctx.robot, world=ctx.poses, low=_lowest(ctx)), meshes=True)


def _lowest(ctx):
    """model/support.lowest at q = 0: each collision shape's lowest points (P001's support, P002)."""
    return ctx.fact("lowest", lambda: lowest(ctx.robot, ctx.poses, ctx.mesh if ctx.opts.load_meshes else False),
                    meshes=True)


@rule("P001", "static-support", "error",
      bad=_drive(caster=False, x="0.1"),
      message="no static support: the ground contacts (left_wheel, right_wheel) lie on one line (x 0.1), with no "
              "caster; the centre of mass is 50.0 mm behind that line (centre of mass x 0.05 y 0); the robot tips "
              "until another part drags",
      good=_drive(x="0.1"),
      fix=FixInfo("sometimes", "unsafe", "when the ground contacts are two wheels on one line and the wheels hang "
                  "from one link: a caster (a sphere collision on a fixed joint, no mass) is added under that link, "
                  "on the side the centre of mass lies, 80% of the way to the body's edge, touching the ground. "
                  "Unsafe: where a caster goes (or whether the wheels should move instead) is a design choice."))
def static_support(ctx):
    """A wheeled robot at rest must stand: its centre of mass inside the support polygon of its ground contacts.

    With the joints at zero and the base lowered onto the ground, the collision shapes
    that touch the ground (wheels, casters, anything else) span a support polygon. A
    centre of mass outside it (or two wheels and no caster: a line, no area) tips the
    robot over until the chassis drags, which makes the drive erratic (seed B). Fix: a
    caster (a small sphere collision on a fixed joint reaching the ground) on the side
    the robot tips to, or move the wheels under the centre of mass.
    """
    if not ctx.tree_ok or not D.is_mobile(ctx.robot):
        return
    s = support(ctx)
    if s is None:
        return

    com = s.com
    zmin, hull, names = s.ground_z, s.polygon, s.links
    d = signed_distance(hull, com[:2])
    if d >= 0.005 or (len(hull) >= 3 and d > 0):
        return
    data = {"com": list(com), "contacts": names, "polygon": [list(p) for p in hull], "distance": d}
    if len(hull) <= 2:
        xs = sorted({round(p[0], 4) for p in hull})
        line = f" (x {xs[0]:.3g})" if len(xs) == 1 else ""
        ahead = ""
        if len(xs) == 1:
            dx = com[0] - xs[0]
            ahead = f"; the centre of mass is {abs(dx) * 1000:.1f} mm {'behind' if dx < 0 else 'ahead of'} that line"
        tip = _tip(ctx, hull, com, zmin) if len(hull) == 2 else None
        rest = (f"; it tips {tip[0]:.1f}° until {tip[1]} touches the ground and drags" if tip else
                "; the robot tips until another part drags")
        if tip:
            data["tip_angle_deg"], data["rests_on"] = tip
        msg = (f"no static support: the ground contacts ({', '.join(names)}) lie on one line{line}, with no caster"
               f"{ahead} (centre of mass x {com[0]:.4g} y {com[1]:.3g}){rest}")
        fix = _caster_fix(ctx, hull, com, zmin) if len(hull) == 2 else None
        yield Finding(msg, ctx.robot.links[ctx.robot.root].loc if ctx.robot.root else ctx.robot.loc, data,
                      severity=None if d < 0 else "warning", fix=fix)
        return
    msg = (f"no static support: the centre of mass (x {com[0]:.4g} y {com[1]:.3g}) is {abs(d) * 1000:.1f} mm "
           f"{'outside' if d < 0 else 'inside, but too close to the edge of'} the support polygon of "
           f"{', '.join(names)}")
    yield Finding(msg, ctx.robot.links[ctx.robot.root].loc if ctx.robot.root else ctx.robot.loc, data,
                  severity=None if d < 0 else "warning")


CASTER_RADIUS = 0.02     # m: the caster P001's fix adds (smaller where the body hangs lower)


def _caster_fix(ctx, hull, com, zmin) -> Fix | None:
    """P001's fix for two wheels on a line: a caster under the link the wheels hang from, on the side
    of the centre of mass, 80% of the way from the axle to that side's edge of the body, touching the
    ground (placed in that link's frame, so a fix that raises the link keeps it on the ground)."""
    r = ctx.robot
    wheel_joints = [r.joints[n] for n in D.wheel_joints(r) if n in r.joints]
    parents = {j.parent for j in wheel_joints}
    if len(parents) != 1 or len(wheel_joints) < 2:
        return None
    parent = parents.pop()
    if parent not in ctx.poses:
        return None
    (x0, y0), (x1, y1) = hull[0], hull[1]
    ux, uy = x1 - x0, y1 - y0
    norm = math.sqrt(ux * ux + uy * uy)
    if norm < 1e-6:
        return None
    ux, uy = ux / norm, uy / norm
    nx, ny = -uy, ux
    side = _sign((com[0] - x0) * nx + (com[1] - y0) * ny) or -1.0
    skip = {j.child for j in wheel_joints}
    reach, bottom = 0.0, None
    for link, it, pose, mesh in _collision_world(ctx):
        if link.name in skip:
            continue
        w = _placed_points(it.geometry, pose, 16, mesh)
        along = [((wx - x0) * nx + (wy - y0) * ny) * side for wx, wy, _ in w]
        reach = max(reach, max(along))
        below = [q[2] for q, a in zip(w, along) if a > 0.0]
        if below:
            bottom = min(below) if bottom is None else min(bottom, min(below))
    if reach < 0.02:                 # no body geometry on that side: as far as the track is wide
        reach = norm / 2
    clearance = (bottom - zmin) if bottom is not None else 2 * CASTER_RADIUS
    radius = CASTER_RADIUS if not 0 < clearance < 2 * CASTER_RADIUS else clearance / 2
    t = (com[0] - x0) * ux + (com[1] - y0) * uy
    at = (x0 + ux * t + nx * side * 0.8 * reach, y0 + uy * t + ny * side * 0.8 * reach, zmin + radius)
    R, p = ctx.poses[parent]
    d = (at[0] - p[0], at[1] - p[1], at[2] - p[2])
    local = [R[0][k] * d[0] + R[1][k] * d[1] + R[2][k] * d[2] for k in range(3)]     # the parent's frame: R^T (at - p)
    name, k = "caster_link", 2
    while name in r.links:
        name, k = f"caster_link_{k}", k + 1
    xyz = " ".join(f"{round(float(v), 4):g}" for v in local)
    geo = f'<geometry><sphere radius="{round(radius, 4):g}"/></geometry>'
    text = (f'<link name="{name}">\n  <visual>{geo}</visual>\n  <collision>{geo}</collision>\n</link>\n'
            f'<joint name="{name.replace("_link", "_joint")}" type="fixed">\n  <parent link="{parent}"/>\n'
            f'  <child link="{name}"/>\n  <origin xyz="{xyz}" rpy="0 0 0"/>\n</joint>')
    return Fix((InsertAfter(r.links[parent], text),), "unsafe", f"caster {name} added under {parent} at {xyz}")


def _tip(ctx, hull, com, zmin):
    """(angle in degrees, link): the body pivots about the wheel axle (the wheels roll) toward its
    centre of mass until another collision shape touches the ground; None if nothing would."""
    r = ctx.robot
    P = ctx.poses
    wheel_joints = [r.joints[n] for n in D.wheel_joints(ctx.robot) if n in r.joints]
    centres = [compose(P[j.parent], pose_T(j.origin))[1] for j in wheel_joints if j.parent in P]
    if len(centres) < 2:
        return None
    c0, c1 = centres[0], centres[-1]
    ux, uy = c1[0] - c0[0], c1[1] - c0[1]
    norm = math.sqrt(ux * ux + uy * uy)
    if norm < 1e-9:
        return None
    ux, uy = ux / norm, uy / norm
    nx, ny = -uy, ux
    side = _sign((com[0] - c0[0]) * nx + (com[1] - c0[1]) * ny) or 1.0
    axle_h = (c0[2] + c1[2]) / 2 - zmin
    skip = {j.child for j in wheel_joints}
    best = None
    for link, it, pose, mesh in _collision_world(ctx):
        if link.name in skip:
            continue
        theta = None
        for wx, wy, wz in _placed_points(it.geometry, pose, 32, mesh):
            d = ((wx - c0[0]) * nx + (wy - c0[1]) * ny) * side     # horizontal distance behind the axle, tipping side
            hz = wz - zmin - axle_h                                  # height relative to the axle
            R = math.hypot(d, hz)
            if d > 1e-6 and R > axle_h:
                a = math.degrees(math.acos(min(max(-axle_h / R, -1.0), 1.0)) - math.atan2(d, hz))
                theta = a if theta is None else min(theta, a)
        if theta is not None and theta > 0.01 and (best is None or theta < best[0]):
            best = (float(theta), link.name)
    return best


@rule("P002", "spawn-above-ground", "warning",
      bad=_drive(z="0.03"),
      message="with base_link at z 0, collision geometry reaches z -0.05 m (left_wheel, right_wheel): the robot "
              "spawns 50 mm into the ground",
      good=_drive(),
      fix=FixInfo("sometimes", "unsafe", "when the root link has no geometry and one child joint (base_footprint "
                  "→ base_link), that joint's origin z rises by the depth given, so every link below the root "
                  "rises with it and the lowest geometry touches z = 0. Unsafe: which origin moves is a choice "
                  "(the spawn height in a launch file is another); the root's other uses of that frame move too."))
def spawn_penetration(ctx):
    """Collision geometry below the ground when a wheeled robot is spawned with its root at z = 0.

    Mobile bases put their root (base_footprint) on the floor and are spawned at z = 0;
    a wheel reaching below it starts inside the ground and Gazebo pushes the model out
    with a jump. Fix: raise the base joint so the wheels touch z = 0 (the depth is given).
    """
    if not ctx.tree_ok or not D.is_mobile(ctx.robot):
        return

    below = [(z, name) for z, _, name in _lowest(ctx) if z < -SPAWN_TOL]
    if below:
        below.sort()
        depth = -below[0][0]
        names = sorted({n for _, n in below})
        yield Finding(f"with {ctx.robot.root} at z 0, collision geometry reaches z {below[0][0]:.3g} m "
                      f"({', '.join(names)}): the robot spawns {depth * 1000:.0f} mm into the ground",
                      ctx.robot.links[ctx.robot.root].loc, {"links": names, "min_z": below[0][0],
                                                            "fix": {"raise_by": depth}},
                      fix=_raise_fix(ctx.robot, depth))


def _raise_fix(robot, depth: float) -> Fix | None:
    """P002's fix: the root's one child joint rises by ``depth`` (root without geometry only)."""
    root = robot.links[robot.root]
    kids = robot.child_joints(root.name)
    if root.visuals or root.collisions or len(kids) != 1:
        return None
    j = kids[0]
    x, y, z = j.origin.xyz
    return Fix((SetValue(j, "origin.xyz", (x, y, round(z + depth, 6))),), "unsafe",
               f"joint {j.name} raised by {depth * 1000:.0f} mm")


@rule("P003", "dynamics-finite", "error",
      bad=_FINGER.format(inertial=""),
      message="ABA returns NaN at a random configuration: nothing below joint(s) finger_joint has mass",
      good=_FINGER.format(inertial=_FINGER_MASS))
def dynamics_finite(ctx):
    """Pinocchio's inverse and forward dynamics (RNEA, ABA) stay finite at random configurations.

    A joint whose subtree has no mass (or no inertia about the joint) makes the mass
    matrix singular: ABA returns NaN and every simulator struggles. The finding points at
    the first such joint. Fix: give the links below that joint a mass and inertia. When every
    such joint is a virtual one (other joints mimic it and its link is no body:
    model/drive.virtual_joints, a bicycle model's), the model is kinematic by design: a warning.
    """
    if not ctx.tree_ok or not ctx.robot.joints or _dynamics_surely_finite(ctx.robot, principal(ctx)):
        return
    massless = _massless_leaf(ctx.robot)
    if massless:
        yield _nan_finding(ctx.robot, "ABA", massless)
        return
    import numpy as np

    try:
        model = ctx.robot.pinocchio(floating=False)
    except InputError as exc:
        yield Finding(f"Pinocchio cannot build the model: {exc.message}", ctx.robot.loc, {"reason": exc.message})
        return
    if model.nv == 0:
        return
    import pinocchio as pin

    data = model.createData()
    rng = np.random.default_rng(0)
    bad = None
    for _ in range(4):
        q = pin.integrate(model, pin.neutral(model), rng.uniform(-1, 1, model.nv))
        v = rng.uniform(-1, 1, model.nv)
        tau = rng.uniform(-1, 1, model.nv)
        with np.errstate(all="ignore"):
            t = pin.rnea(model, data, q, v, np.zeros(model.nv))
            a = pin.aba(model, data, q, v, tau)
        if not (np.all(np.isfinite(t)) and np.all(np.isfinite(a))):
            bad = "RNEA" if not np.all(np.isfinite(t)) else "ABA"
            break
    if bad is None:
        return
    sub_mass = [0.0] * model.njoints
    for i in range(model.njoints - 1, 0, -1):
        sub_mass[i] += model.inertias[i].mass
        if model.parents[i] > 0:
            sub_mass[model.parents[i]] += sub_mass[i]
    massless = [model.names[i] for i in range(1, model.njoints) if sub_mass[i] <= 0]
    yield _nan_finding(ctx.robot, bad, massless)


def _nan_finding(robot, bad: str, massless: list) -> Finding:
    """P003's finding: the algorithm that returned NaN and the joints with no mass below them; a
    warning when all of them are virtual (model/drive.virtual_joints)."""
    first = robot.joints.get(massless[0]) if massless else None
    virtual = D.virtual_joints(robot)
    kinematic = bool(massless) and all(n in virtual for n in massless)
    return Finding(f"{bad} returns NaN at a random configuration"
                   + (f": nothing below joint(s) {', '.join(massless[:6])} has mass" if massless else
                      ": the mass matrix is singular")
                   + (" (virtual joints that other joints mimic: a kinematic model's, which a dynamics simulator "
                      "cannot integrate)" if kinematic else ""),
                   (first.loc if first else None) or robot.loc,
                   {"algorithm": bad, "massless_joints": massless, "virtual": kinematic},
                   severity="warning" if kinematic else None)


def _dynamics_surely_finite(robot, moments=None) -> bool:
    """True when Pinocchio need not be loaded (a third of check's time): urdfdom accepts what it
    reads (no bad values, known types, limits on revolute/prismatic) and every moving joint's
    child has a positive mass with a positive-definite inertia, every other link a non-negative
    mass and semi-definite inertia. Then each moving body's spatial inertia is positive
    definite, so is the mass matrix at every configuration, and RNEA/ABA stay finite. A link
    that fails its own test is judged with its rigid body (_bodies_definite): Pinocchio adds the
    links on fixed joints to the body above them, and only the sum must be definite.
    ``moments``: link -> principal moments (ascending) already computed, for the links that have them."""

    if robot.load_issues:
        return False
    for j in robot.joints.values():
        if j.type not in JOINT_TYPES:
            return False
        if j.type in ("revolute", "prismatic") and (j.limit is None or j.limit.effort is None
                                                    or j.limit.velocity is None):
            return False
    moving_children = {j.child for j in robot.joints.values() if j.type != "fixed"}
    weak = []
    for link in robot.links.values():
        ine = link.inertial
        positive = link.name in moving_children
        if ine is None:
            if positive:
                weak.append(link.name)
            continue
        if ine.mass < 0:
            return False
        w = moments.get(link.name) if moments else None
        if w is None:
            w = principal_moments(ine)          # eigh3's eigenvalues
        if not (_definite(ine.mass, w) if positive else w[0] >= 0):
            weak.append(link.name)
    return not weak or _bodies_definite(robot, weak)


def _definite(mass: float, w) -> bool:
    """A positive mass and principal moments ``w`` (ascending) of a positive-definite tensor."""
    return mass > 0 and w[0] > 1e-12 * max(w[2], 1e-300)


def _bodies_definite(robot, weak) -> bool:
    """The rigid bodies (model/tree.rigid_bodies) of the links ``weak`` each have a positive
    mass and a positive-definite inertia about their centre of mass: then their spatial inertia
    is positive definite (it is congruent to that inertia beside the mass times the identity).
    PAL's base antennas, for one, have a slightly indefinite inertia on a fixed joint under a
    heavy base."""
    bodies = rigid_bodies(robot)
    heads = {bodies.host[n] for n in weak}
    parts: dict = {h: [] for h in heads}
    for name, head in bodies.host.items():
        ine = robot.links[name].inertial
        if head in parts and ine is not None and ine.mass > 0:
            parts[head].append((ine.mass, compose(bodies.offset[name], pose_T(ine.origin)), tensor(ine)))
    for head, these in parts.items():
        if not these:
            return False
        mass, _, t = combined(these)
        if not all(map(math.isfinite, (mass, *t[0], *t[1], *t[2]))) or not _definite(mass, eigh3(t)[0]):
            return False
    return True


def _massless_leaf(robot) -> list[str] | None:
    """P003's finding without loading Pinocchio, when it surely fires: the joints Pinocchio would
    name, in its order, or None to ask Pinocchio. Sure when urdfdom accepts the model, every number
    is finite, every mass non-negative, every joint fixed, revolute, continuous or prismatic, and
    some moving joint has nothing below it but links without mass and inertia: its articulated
    inertia is zero, so ABA divides by zero there and returns NaN at every configuration, while
    RNEA (no division) stays finite. The joints named are those whose subtree weighs nothing, in
    the order Pinocchio numbers them: depth first from the root, a link's child joints by name
    (urdfdom keeps its joints in a std::map). PR2's gripper joints are such: this saves loading
    Pinocchio for them (a third of check's time)."""
    if robot.load_issues or len(robot.roots) != 1 or depth(robot) > MAX_TREE_DEPTH:
        return None
    moving = ("revolute", "continuous", "prismatic")
    fin = math.isfinite
    for j in robot.joints.values():
        if j.type not in moving and j.type != "fixed":
            return None
        if j.type in ("revolute", "prismatic") and (j.limit is None or j.limit.effort is None
                                                    or j.limit.velocity is None):
            return None
        if not all(fin(v) for v in (*j.origin.xyz, *j.origin.rpy, *j.axis)):
            return None
    for link in robot.links.values():
        ine = link.inertial
        if ine is not None and not (all(fin(v) for v in (ine.mass, ine.ixx, ine.ixy, ine.ixz, ine.iyy, ine.iyz,
                                                          ine.izz, *ine.origin.xyz, *ine.origin.rpy))
                                    and ine.mass >= 0):
            return None
    if sum(j.type in moving for j in robot.joints.values()) > MAX_DOF:
        return None
    children = robot.joints_by_parent()
    order, seen, stack = [], set(), [(robot.root, None)]
    while stack:                                   # depth first; children by joint name
        link, j = stack.pop()
        if link in seen or link not in robot.links:
            return None
        seen.add(link)
        order.append((link, j))
        stack.extend((c.child, c) for c in sorted(children.get(link, ()), key=lambda c: c.name)[::-1])
    if len(seen) != len(robot.links):
        return None
    heavy, inert = {}, {}                  # per link: something below weighs; something below has inertia
    for link, _j in reversed(order):
        ine = robot.links[link].inertial
        h = ine is not None and ine.mass > 0
        i = ine is not None and (ine.mass != 0 or any((ine.ixx, ine.ixy, ine.ixz, ine.iyy, ine.iyz, ine.izz)))
        for c in children.get(link, ()):
            h, i = h or heavy[c.child], i or inert[c.child]
        heavy[link], inert[link] = h, i
    joints = [j for _link, j in order if j is not None and j.type in moving]
    if not any(not inert[j.child] for j in joints):
        return None
    return [j.name for j in joints if not heavy[j.child]]


@rule("P004", "mass-summary", "info",
      bad=_drive(),
      message="total mass 2.1 kg; centre of mass (-0.00571 0 0.04) m in base_link, 0.04 m above the ground contacts",
      good=None)
def mass_summary(ctx):
    """Total mass and centre of mass at q = 0 (information).

    For a wheeled robot the height is above the ground contacts; otherwise above the root
    link's origin. A surprising total (0.59 kg for a wooden structure) points at masses
    that were never weighed. A robot without any mass gets a warning under this code.
    """
    if not ctx.tree_ok:
        return

    mass, com = center_of_mass(ctx.robot)
    if not mass > 0:
        yield Finding("the robot has no mass at all", ctx.robot.loc, {"mass": 0.0}, severity="warning")
        return
    ground = None
    if D.is_mobile(ctx.robot):
        s = support(ctx)
        ground = s.ground_z if s else None
    h = com[2] - (ground or 0.0)
    where = "above the ground contacts" if ground is not None else f"above {ctx.robot.root}'s origin"
    yield Finding(f"total mass {mass:.4g} kg; centre of mass ({com[0]:.3g} {com[1]:.3g} {com[2]:.3g}) m in "
                  f"{ctx.robot.root}, {h:.3g} m {where}", ctx.robot.loc,
                  {"mass": mass, "com": [float(c) for c in com], "com_height": float(h)})
