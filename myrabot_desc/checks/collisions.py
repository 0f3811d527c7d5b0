"""P005: self-collision at the rest pose (model/collisions.py), the SRDF's exclusions respected."""

from __future__ import annotations

from myrabot_desc.checks.rule import Finding, FixInfo, rule
from myrabot_desc.model.collisions import Scene, TooManyPairs

_ARM = """<link name="body">
  <collision><geometry><box size="0.2 0.2 0.4"/></geometry></collision>
</link>
<joint name="body_joint" type="fixed">
  <parent link="base_link"/>
  <child link="body"/>
  <origin xyz="0 0 0.2"/>
</joint>
<link name="arm">
  <inertial>
    <origin xyz="0.15 0 0"/>
    <mass value="0.5"/>
    <inertia ixx="0.00021" ixy="0" ixz="0" iyy="0.00385" iyz="0" izz="0.00385"/>
  </inertial>
  <collision><origin xyz="0.15 0 0"/><geometry><box size="0.3 0.05 0.05"/></geometry></collision>
</link>
<joint name="shoulder" type="revolute">
  <parent link="body"/>
  <child link="arm"/>
  <origin xyz="0.1 0 0.15"/>
  <axis xyz="0 1 0"/>
  <limit lower="-1.5" upper="1.5" effort="20" velocity="1"/>
</joint>
<link name="hand">
  <inertial>
    <origin xyz="{x} 0 -0.1"/>
    <mass value="0.2"/>
    <inertia ixx="0.00073" ixy="0" ixz="0" iyy="0.00073" iyz="0" izz="0.00012"/>
  </inertial>
  <collision><origin xyz="{x} 0 -0.1"/><geometry><box size="0.06 0.06 0.2"/></geometry></collision>
</link>
<joint name="wrist" type="revolute">
  <parent link="arm"/>
  <child link="hand"/>
  <origin xyz="0.3 0 0"/>
  <axis xyz="1 0 0"/>
  <limit lower="-1.5" upper="1.5" effort="5" velocity="1"/>
</joint>"""


def srdf_of(ctx):
    """The SRDF given with --srdf (read once per check), or None."""
    got = ctx.__dict__.get("_srdf", False)
    if got is False:
        got = None
        if getattr(ctx.opts, "srdf", None):
            from myrabot_desc.model.srdf import load_srdf     # (its reader only for --srdf)

            got = load_srdf(ctx.opts.srdf)
        ctx.__dict__["_srdf"] = got
    return got


def joints_between(robot, a: str, b: str) -> list[str]:
    """The moving joints on the tree path between links ``a`` and ``b``, from ``a``'s side."""
    def up(link):
        chain, seen = [], set()
        while link not in seen:
            seen.add(link)
            j = robot.parent_joint(link)
            if j is None:
                break
            chain.append(j)
            link = j.parent
        return chain

    ca, cb = up(a), up(b)
    common = {j.name for j in ca} & {j.name for j in cb}
    path = [j for j in ca if j.name not in common] + [j for j in reversed(cb) if j.name not in common]
    return [j.name for j in path if j.type != "fixed"]


@rule("P005", "self-collision", "warning",
      bad=_ARM.format(x="-0.29"),
      message="hand overlaps body by 20.0 mm at the rest pose (box 0.06×0.06×0.2 m into box 0.2×0.2×0.4 m at "
              "robot.urdf:10); they are 2 moving joints apart (shoulder, wrist), not parent and child",
      good=_ARM.format(x="-0.26"),
      fix=FixInfo("never", "", "which shape is wrong (or whether the pair may touch, which an SRDF's "
                  "<disable_collisions> states) is a design fact that no value in the model gives; "
                  "the finding gives the depth and where both shapes are written."))
def self_collision(ctx):
    """Collision shapes of two links that overlap at the rest pose although nothing lets them.

    At ``Robot.rest_pose`` (every joint at 0, or its nearer limit), the collision shapes of
    links on different rigid bodies (links joined by fixed joints are one body) that are not
    parent and child (joined by one moving joint) must not overlap: MuJoCo, PyBullet, Drake and
    MoveIt collide them, so the robot starts in collision (MoveIt refuses to plan from there;
    ``convert --to mjcf`` has to exclude the pair). Boxes, spheres and cylinders are exact; a
    mesh is read with ``--inertia`` or ``--meshes`` and collides as its convex hull, as those
    simulators do; the finding gives the depth of the two convex shapes, where they meet, the
    moving joints between the links and where both shapes are written. Overlaps up to 1 mm are
    parts resting against each other and are not reported.

    Severity. Real descriptions overlap at rest by design: compact hips (Talos' first and third
    leg links, 93 mm), a 7-DoF arm's wrist links (Franka's panda_link5 and panda_hand, 41 mm at
    its rest pose), gripper linkages that close a loop the URDF cannot state, a safety box
    around a hand. An SRDF says which pairs may touch (MoveIt's setup assistant disables the
    pairs "in collision at the default pose" this way), so: **without** ``--srdf`` an overlap
    is a warning (nothing in the URDF tells a designed overlap from a mistake); **with**
    ``--srdf FILE`` the pairs it disables are not reported and an overlap it does not allow is
    an error (an SRDF with no ``<disable_collisions>`` at all, only group states, says nothing
    about collisions and changes nothing). A pair whose convex hulls overlap while the meshes'
    triangles do not touch (the hull of a concave part reaching into another: PR2's shoulder in
    its base) is information: the parts do not collide, but hull-based simulators see them
    touching.
    Fix: move or shrink the shape that is wrong, or, where the overlap is by design, disable
    the pair in the robot's SRDF.
    """
    if not ctx.tree_ok:
        return
    srdf = srdf_of(ctx)
    if srdf is not None and not srdf.describes_collisions:
        srdf = None                              # group states only: it says nothing of which pairs may touch
    scene = Scene(ctx.robot, (lambda g: ctx.mesh(g)) if ctx.opts.load_meshes else False, srdf)
    worst: dict = {}
    try:
        overlaps = scene.overlaps(ctx.robot.rest_pose())
    except TooManyPairs as exc:                  # said once, in numbers, instead of millions of pairs
        yield Finding(exc.message, ctx.robot.loc, {"limit": "max_collision_pairs"})
        return
    for o in overlaps:
        key = frozenset((o.link_a, o.link_b))
        if key not in worst:                     # deepest first
            worst[key] = o
    for o in worst.values():
        if o.allowed is not None:
            continue
        a, b = (o.link_a, o.link_b)
        loc_b, loc_a = o.loc_b, o.loc_a
        between = joints_between(ctx.robot, a, b)
        data = {"links": [a, b], "depth": round(o.depth, 6), "point": [round(x, 6) for x in o.point],
                "joints_between": between, "hull_only": o.hull_only,
                "other": f"{loc_a.file}:{loc_a.line}" if loc_a is not None else None}
        if o.hull_only:
            yield Finding(f"the convex hulls of {a} and {b} overlap by {o.depth * 1000:.1f} mm at the rest pose "
                          f"({o.shape_b} and {o.shape_a} at {_where(loc_a)}), the meshes themselves do not touch: "
                          "MuJoCo and PyBullet collide the hulls", loc_b, data, severity="info")
            continue
        apart = (f"{len(between)} moving joint{'s' if len(between) != 1 else ''} apart ({', '.join(between)})"
                 if between else "joined by no moving joint")
        tail = f"; the SRDF {srdf.path} does not disable the pair" if srdf is not None else ""
        yield Finding(f"{b} overlaps {a} by {o.depth * 1000:.1f} mm at the rest pose ({o.shape_b} into "
                      f"{o.shape_a} at {_where(loc_a)}); they are {apart}, not parent and child{tail}",
                      loc_b, data, severity="error" if srdf is not None else None)


def _where(loc) -> str:
    return f"{loc.file}:{loc.line}" if loc is not None else "?"
