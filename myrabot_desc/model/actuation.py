"""How each joint is commanded: in velocity (a wheel), in position, or not at all (passive).

The answer comes from what the model declares (``model/drive.py``): ros_control transmissions and
``<ros2_control>`` blocks with their interfaces, and the drive plugins with their wheels. A model
that says which joints it commands leaves the others passive (a suspension, a caster, TurtleBot
4's wheel drops); one that says nothing of its actuators gets position control on every joint
that has a range or a transmission. Mimic joints follow their source (an equality constraint in a
simulator) and are not commanded themselves.
"""

from __future__ import annotations

from myrabot_desc.model import drive as D
from myrabot_desc.records import Struct

UNCOMMANDED_TYPES = ("fixed", "floating", "planar")


class Command(Struct):
    kind: str | None          # 'velocity', 'position', or None (passive)
    why: str = ""             # for a passive joint: why nothing commands it


def velocity_commanded(robot) -> list[str]:
    """Joints commanded in velocity, in the order they are declared: joints with a velocity
    interface (ros_control, ros2_control), the wheels of every declared drive, and the base's wheels
    that nothing else commands (model/drive.base)."""
    out, _ = D.velocity_joints(robot)
    out = [n for n in out if n in robot.joints]
    for d in D.find(robot):
        out += [j for j in d.joints if j in robot.joints and j not in out]
    # wheels the base rolls on that nothing declares (recognised by name or shape): a wheel turns at a
    # speed; a position servo would turn it to the commanded angle and stop it there
    b = D.base(robot)
    if b is not None:
        declared = D.commanded_joints(robot)
        out += [n for n in b.wheels if n in robot.joints and n not in out and n not in declared
                and robot.joints[n].type in ("continuous", "revolute") and robot.joints[n].mimic is None]
    return out


def joint_commands(robot) -> dict[str, Command]:
    """Joint name -> how it is commanded, for every revolute, continuous and prismatic joint."""
    wheels = set(velocity_commanded(robot))
    with_transmission = {n for t in robot.transmissions for n in t.joints}
    commanded = D.commanded_joints(robot)
    out: dict[str, Command] = {}
    for j in robot.joints.values():
        if j.type in UNCOMMANDED_TYPES:
            continue
        if j.mimic is not None:
            out[j.name] = Command(None, f"mimics '{j.mimic.joint}' (an equality constraint)")
        elif j.name in wheels:
            out[j.name] = Command("velocity")
        elif commanded and j.name not in commanded:
            out[j.name] = Command(None, "no transmission, ros2_control block or drive commands it: passive")
        elif j.type == "continuous" and j.limit is None and j.name not in with_transmission:
            out[j.name] = Command(None, "continuous joint with no <limit> and no transmission: passive")
        else:
            out[j.name] = Command("position")
    return out
