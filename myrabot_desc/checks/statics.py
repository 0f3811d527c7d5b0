"""P006: the torque gravity puts on each joint against its effort limit (Pinocchio, model/statics.py)."""

from __future__ import annotations

import math

from myrabot_desc.checks.rule import Finding, FixInfo, rule
from myrabot_desc.errors import InputError
from myrabot_desc.model import drive as D
from myrabot_desc.model.statics import gravity_needs

# A joint needing up to this many times its effort limit is a warning, beyond it an error. PR2's
# shoulder_lift needs 1.7x its 30 N·m: a spring counterbalance the URDF does not describe carries the
# rest. Twice the rated torque is more than a motor holds, counterbalanced or not.
ERROR_RATIO = 2.0
# Below this a joint without an effort limit is not listed (a finger, a sensor mount).
NOTABLE = 1.0                # N·m or N

_LINK = """<link name="upper_arm">
  <inertial>
    <origin xyz="0.25 0 0"/>
    <mass value="2"/>
    <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.04" iyz="0" izz="0.04"/>
  </inertial>
</link>
<joint name="shoulder" type="revolute">
  <parent link="base_link"/>
  <child link="upper_arm"/>
  <axis xyz="0 1 0"/>
  <limit lower="-1.5" upper="1.5" effort="{effort}" velocity="1"/>
</joint>"""


def _fmt(x: float) -> str:
    return f"{x:.3g}"


@rule("P006", "effort-below-gravity", "error",
      bad=_LINK.format(effort="0.1"),
      message="joint shoulder needs 4.91 N·m to hold what it carries against gravity (at the rest pose), over its "
              "effort limit 0.1 N·m (49x)",
      good=_LINK.format(effort="12"),
      fix=FixInfo("never", "", "the effort limit is the motor's rating (its datasheet, with the gear ratio): raising "
                  "it to what gravity needs would make the model claim a motor the robot does not have. The "
                  "finding gives the torque needed, the pose where it is needed and the limit."))
def effort_below_gravity(ctx):
    """A joint whose effort limit cannot hold what it carries against gravity.

    The base stands still on its root (an arm on its table, a mobile base on its wheels, a
    legged robot's trunk held); gravity along the root's -z. Each moving joint in turn goes
    through 13 values over its range (a full turn for a continuous joint) with the others at
    the rest pose; Pinocchio gives the gravity torque on every joint at each, and each joint
    keeps its worst (model/statics.py). A joint needing more than its ``<limit effort>``
    sags in every simulator that enforces the limit (Gazebo, MuJoCo's ``forcerange``) and on
    the real motor.

    Severity: an error when the torque needed is over twice the effort limit (no motor holds
    that); a warning between 1x and 2x, the room a spring counterbalance or a brake the URDF
    does not describe can make up (PR2's shoulders need 1.7x their 30 N·m and rely on one).
    Passive joints (the model says which joints its transmissions, ros2_control blocks and
    drives command, and this one is not among them: a suspension, a caster) carry their load
    on springs and stops and are not checked; mimic joints follow their target. Joints without
    an effort limit (absent, or 0 as ROS-Industrial writes it) are listed once, as information,
    when they carry over 1 N·m: nothing says their motors can hold it.
    Fix: the motor's real rating (with its gear ratio), a lighter or shorter link, or a
    counterbalance.
    """
    if not ctx.tree_ok or not any(j.type in ("revolute", "continuous", "prismatic") for j in ctx.robot.joints.values()):
        return
    if ctx.robot.total_mass <= 0:
        return
    try:
        needs = gravity_needs(ctx.robot)
    except InputError:
        return                       # P003 says why Pinocchio cannot read the model
    commanded = D.commanded_joints(ctx.robot)
    unlimited = []
    for n in needs:
        j = ctx.robot.joints[n.joint]
        if commanded and n.joint not in commanded:
            continue
        if n.effort is None:
            if n.torque > NOTABLE:
                unlimited.append(n)
            continue
        if not n.torque > n.effort or not math.isfinite(n.torque):
            continue
        if n.pose_joint is None:
            where = "at the rest pose"
        else:
            unit = "m" if ctx.robot.joints[n.pose_joint].type == "prismatic" else "rad"
            where = f"with {n.pose_joint} at {n.pose_value:.3g} {unit}, the others at rest"
        ratio = n.torque / n.effort
        data = {"joint": n.joint, "torque": round(n.torque, 6), "at_rest": round(n.at_rest, 6), "effort": n.effort,
                "ratio": round(ratio, 4), "pose": {n.pose_joint: round(n.pose_value, 6)} if n.pose_joint else {},
                "unit": n.unit}
        written = ctx.robot.origin(j, "limit.effort").written
        if written is not None and j.loc is not None and (written.file, written.line) != (j.loc.file, j.loc.line):
            data["effort_written_at"] = f"{written.file}:{written.line}"
        yield Finding(f"joint {n.joint} needs {_fmt(n.torque)} {n.unit} to hold what it carries against gravity "
                      f"({where}), over its effort limit {n.effort:g} {n.unit} ({ratio:.2g}x)",
                      j.loc, data, severity=None if ratio > ERROR_RATIO else "warning")
    if unlimited:
        unlimited.sort(key=lambda n: -n.torque)
        shown = ", ".join(f"{n.joint} {_fmt(n.torque)} {n.unit}" for n in unlimited[:6])
        more = f" and {len(unlimited) - 6} more" if len(unlimited) > 6 else ""
        yield Finding(f"{len(unlimited)} joint(s) hold load against gravity without an effort limit ({shown}{more}): "
                      "nothing says their motors can", ctx.robot.joints[unlimited[0].joint].loc,
                      {"joints": {n.joint: round(n.torque, 6) for n in unlimited}}, severity="info")
