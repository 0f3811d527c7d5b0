"""Does the robot stand on legs? The free-base decision for humanoids and legged robots.

A robot stands on legs when, in the pose it stands in (the rest pose, or the standing pose given),
everything that touches the ground hangs from its root by limbs: chains of at least
``MIN_LIMB_JOINTS`` moving joints below the root's rigid body, and at least two different limbs
touch. "Touches the ground" is model/support.py's answer: the collision shapes within 5 mm of the
lowest point when the robot rests on it.

That tells the cases apart without names or conventions:

* a humanoid, a quadruped, a hexapod: only feet touch, on 2, 4, 6 legs of 3 to 7 joints each;
* an arm bolted to a table: its base (the root's body) is its lowest part;
* a mobile base: wheels hang from the root by one joint each (``model/drive.is_mobile`` decides
  those; a wheel-legged robot, wheels at the ends of legs, counts as legged);
* a URDF that fixes its root to a ``world`` link says it is welded, and is.

With ``--base auto``, ``sim`` (and the MJCF writer, see the brief for convert/mjcf.py) gives a
legged robot a free base, as a mobile one.
"""

from __future__ import annotations

from myrabot_desc.model import drive as D
from myrabot_desc.model.collisions import rigid_bodies
from myrabot_desc.model.support import ground_support
from myrabot_desc.records import Struct

MIN_LIMB_JOINTS = 2


class Stance(Struct):
    legged: bool
    feet: tuple            # the links touching the ground
    limbs: dict            # first joint below the root body -> the feet on that limb
    why: str               # one line: what the decision rests on


def welded_to_world(robot) -> bool:
    """The URDF fixes its root to a ``world`` link (a fixed joint from ``world``)."""
    return robot.root == "world" and any(j.parent == "world" and j.type == "fixed" for j in robot.joints.values())


def stance(robot, q: dict | None = None, meshes=True) -> Stance:
    """Whether the robot stands on legs at configuration ``q`` (the rest pose when None)."""
    if welded_to_world(robot):
        return Stance(False, (), {}, "its root is fixed to the 'world' link")
    if D.is_mobile(robot):
        return Stance(False, (), {}, "a wheeled base (model/drive.py: it declares a drive or has wheels)")
    sup = ground_support(robot, robot.rest_pose() if q is None else q, meshes=meshes)
    if sup is None:
        return Stance(False, (), {}, "it has no collision geometry to stand on")
    body_of = rigid_bodies(robot)
    root_body = body_of.get(robot.root, robot.root)
    limbs: dict = {}
    for link in sup.links:
        chain = []                       # moving joints from the link up to the root's body
        cur = link
        while body_of.get(cur, cur) != root_body:
            j = robot.parent_joint(cur)
            if j is None:
                break
            if j.type != "fixed":
                chain.append(j.name)
            cur = j.parent
        if len(chain) < MIN_LIMB_JOINTS:
            what = "the root's own body" if not chain else f"one joint ({chain[0]}) below the root"
            return Stance(False, tuple(sup.links), {}, f"{link} touches the ground {what}")
        limbs.setdefault(chain[-1], []).append(link)
    if len(limbs) < 2:
        return Stance(False, tuple(sup.links), limbs, "it touches the ground with one limb only")
    feet = ", ".join(sorted(sup.links))
    return Stance(True, tuple(sup.links), limbs,
                  f"it touches the ground only with {feet}, on {len(limbs)} limbs of "
                  f"{MIN_LIMB_JOINTS} or more joints")
