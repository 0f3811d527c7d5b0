"""T: the kinematic tree and joint definitions."""

from __future__ import annotations

import math
import re

from myrabot_desc.checks.rule import Finding, Fix, FixInfo, SetValue, rule
from myrabot_desc.checks.urdf_syntax import only_candidate, suggest
from myrabot_desc.model.drive import commanded_joints
from myrabot_desc.model.parts import JOINT_TYPES
from myrabot_desc.model.tree import cycles

# Example snippets (placed in checks.rule.TEMPLATE, whose only link is base_link).
_ARM_LINK = """<link name="arm">
  <inertial>
    <mass value="0.5"/>
    <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/>
  </inertial>
</link>"""


def _arm(inner: str, jtype: str = "revolute", name: str = "shoulder") -> str:
    """A link `arm` on joint `name` under base_link; `inner` goes inside the <joint>."""
    body = "\n".join("  " + line for line in inner.splitlines())
    return (f'{_ARM_LINK}\n<joint name="{name}" type="{jtype}">\n  <parent link="base_link"/>\n'
            f'  <child link="arm"/>\n{body}\n</joint>')


_LIMIT = '<limit lower="-1.5" upper="1.5" effort="5" velocity="2"/>'


@rule("T001", "single-root", "error",
      bad='<link name="island"/>',
      message="2 root links (base_link, island): a URDF is one tree; connect them with joints",
      good='<link name="island"/>\n<joint name="island_joint" type="fixed">\n  <parent link="base_link"/>\n'
           '  <child link="island"/>\n</joint>')
def single_root(ctx):
    """The links must form one tree with exactly one root link.

    Two roots mean a part floats unattached (urdfdom: "Two root links found"); no root
    means every link is someone's child (a cycle). A robot without links is T017. Fix:
    connect the extra root with a joint (often a fixed joint to the base) or remove the
    stray link.
    """
    r = ctx.robot
    if not r.links:
        return                       # T017
    roots = r.roots
    if len(roots) > 1:
        yield Finding(f"{len(roots)} root links ({', '.join(roots[:6])}{'...' if len(roots) > 6 else ''}): "
                      "a URDF is one tree; connect them with joints", r.links[roots[1]].loc,
                      {"roots": roots})
    elif not roots:
        yield Finding("no root link: every link is the child of a joint (the joints form a cycle)", r.loc)


@rule("T017", "no-links", "info",
      bad='<?xml version="1.0"?>\n<robot name="placeholder"/>\n',
      message="the robot has no links (an empty placeholder, or a file of macros that another file "
              "includes): nothing to check",
      good='<!-- one link or more: the template has base_link -->')
def no_links(ctx):
    """A robot without any link: a placeholder (`empty.urdf`) or a macro library named on the command line.

    Repositories keep such files on purpose (a placeholder for a generated model, a
    parts file of macros that the robot includes; `check -r` skips the included ones,
    but pre-commit passes every changed file). Nothing in them can be checked, so this
    is information, not an error. When the file was meant to be a robot, the build's
    X003 says which macros it defines. Fix: none needed; check the file that includes it.
    """
    r = ctx.robot
    if not r.links:
        yield Finding("the robot has no links (an empty placeholder, or a file of macros that another file "
                      "includes): nothing to check", r.loc)


def _repeats(pairs) -> dict:
    """key -> its values in order, for the keys of (key, value) ``pairs`` met more than once
    (one pass: no list per key for the keys met once, 20,000 links of a star)."""
    first: dict = {}
    dups: dict = {}
    for key, value in pairs:
        if key in first:
            dups.setdefault(key, [first[key]]).append(value)
        else:
            first[key] = value
    return dups


@rule("T002", "no-cycle", "error",
      bad='<link name="a"/>\n<link name="b"/>\n'
          '<joint name="base_a" type="fixed"><parent link="base_link"/><child link="a"/></joint>\n'
          '<joint name="base_b" type="fixed"><parent link="base_link"/><child link="b"/></joint>\n'
          '<joint name="a_b" type="fixed"><parent link="a"/><child link="b"/></joint>',
      message="link b is the child of 2 joints (base_b, a_b): a link has one parent",
      good='<link name="a"/>\n<link name="b"/>\n'
           '<joint name="base_a" type="fixed"><parent link="base_link"/><child link="a"/></joint>\n'
           '<joint name="a_b" type="fixed"><parent link="a"/><child link="b"/></joint>\n'
           '<!-- close the loop in SDF (<gazebo><joint>) or MJCF (equality) -->')
def no_cycle(ctx):
    """No link may have two parent joints, and the joints may not form a cycle.

    URDF describes a tree; closed chains need simulator-specific extensions (an SDF
    `<joint>` inside `<gazebo>`, MuJoCo equality constraints). Fix: keep one parent
    joint per link and close the loop in the simulator's own format.
    """
    r = ctx.robot
    first_named: dict = {}               # joint name -> its first declaration
    children = []                        # (child link, joint name), in document order
    for j in r.declared("joint"):        # every <joint> as written: the typed joints keep one per name
        first_named.setdefault(j.name, j)
        if j.child is not None:
            children.append((j.child, j.name))
    for link, js in sorted(_repeats(children).items()):
        names = ", ".join(n if n is not None else "(unnamed)" for n in js)
        yield Finding(f"link {link} is the child of {len(js)} joints ({names}): a link has one parent",
                      first_named[js[1]].loc or r.loc, {"link": link, "joints": js})
    # cycles: each link walked once (model/tree.py; the walk per link was cubic in a chain's length)

    for cyc in cycles({j.child: j.parent for j in r.joints.values()}, r.links):
        yield Finding(f"the joints form a cycle through links {' -> '.join(cyc + [cyc[0]])}",
                      r.links[cyc[0]].loc, {"links": sorted(cyc)})


@rule("T003", "joint-links-exist", "error",
      bad=_ARM_LINK + '\n<joint name="arm_joint" type="fixed">\n  <parent link="base_lnk"/>\n  <child link="arm"/>\n</joint>',
      message="joint arm_joint: parent link 'base_lnk' does not exist; did you mean base_link?",
      good=_arm("", "fixed", "arm_joint"))
def joint_links_exist(ctx):
    """Every joint's parent and child name existing links.

    A misspelt link name breaks the tree (urdfdom: "parent link [x] of joint [j] not
    found"). Fix: use the exact link name (did-you-mean is given).
    """

    r = ctx.robot
    for j in r.joints.values():
        for role, name in (("parent", j.parent), ("child", j.child)):
            if name not in r.links:
                guess = suggest(name or "", r.links)
                yield Finding(f"joint {j.name}: {role} link '{name}' does not exist"
                              + (f"; did you mean {guess}?" if guess else ""), j.loc,
                              {"joint": j.name, "role": role, "link": name, "suggestion": guess})


@rule("T004", "unique-names", "error",
      bad='<link name="wheel"/>\n<link name="wheel"/>  <!-- a macro called twice without a prefix -->\n'
          '<joint name="wheel_joint" type="fixed"><parent link="base_link"/><child link="wheel"/></joint>',
      message="2 top-level <link> elements are named 'wheel'",
      good='<link name="left_wheel"/>\n<link name="right_wheel"/>\n'
           '<joint name="left_wheel_joint" type="fixed"><parent link="base_link"/><child link="left_wheel"/></joint>\n'
           '<joint name="right_wheel_joint" type="fixed"><parent link="base_link"/><child link="right_wheel"/></joint>')
def unique_names(ctx):
    """Link, joint and top-level material names are unique.

    urdfdom refuses the whole file ("link 'x' is not unique", "material 'x' is not
    unique"); lenient parsers keep one of them silently. Typical cause: a xacro macro
    instantiated twice without a prefix. Fix: rename, or add a prefix parameter to the macro.
    """
    r = ctx.robot
    for tag in ("link", "joint", "material"):
        named = ((d.name, d) for d in r.declared(tag) if d.name is not None)
        for name, ds in sorted(_repeats(named).items()):
            yield Finding(f"{len(ds)} top-level <{tag}> elements are named '{name}'", ds[1].loc or r.loc,
                          {"kind": tag, "name": name, "count": len(ds)})


def _is_limited(j) -> bool:
    return j.type in ("revolute", "prismatic")


@rule("T008", "axis-nonzero", "error",
      bad=_arm('<axis xyz="0 0 0"/>\n' + _LIMIT),
      message="joint shoulder (revolute) has axis 0 0 0: no direction",
      good=_arm('<axis xyz="0 0 1"/>\n' + _LIMIT))
def axis_nonzero(ctx):
    """A moving joint's axis must be a non-zero vector.

    `<axis xyz="0 0 0"/>` gives no direction: Pinocchio's dynamics turn NaN and MuJoCo
    refuses the model. Fix: a unit vector such as `0 0 1`.
    """
    for j in ctx.robot.joints.values():
        if j.type in ("revolute", "continuous", "prismatic", "planar"):
            n = math.sqrt(sum(a * a for a in j.axis))
            if not n > 1e-9:
                yield Finding(f"joint {j.name} ({j.type}) has axis {_v(j.axis)}: no direction", j.loc,
                              {"joint": j.name, "axis": list(j.axis)})


@rule("T009", "limits-present", "error",
      bad=_arm('<axis xyz="0 0 1"/>'),
      message="revolute joint shoulder has no <limit>",
      good=_arm('<axis xyz="0 0 1"/>\n' + _LIMIT))
def limits_present(ctx):
    """Revolute and prismatic joints need a `<limit>` with effort and velocity.

    urdfdom (and so Pinocchio, check_urdf, Gazebo) rejects a revolute/prismatic joint
    without `<limit>`, and a `<limit>` without effort or velocity. Fix: add
    `<limit lower=".." upper=".." effort=".." velocity=".."/>`, or make the joint continuous.
    """
    for j in ctx.robot.joints.values():
        if not _is_limited(j):
            continue
        if j.limit is None:
            yield Finding(f"{j.type} joint {j.name} has no <limit>", j.loc, {"joint": j.name})
            continue
        missing = [k for k in ("effort", "velocity") if getattr(j.limit, k) is None]
        if missing:
            yield Finding(f"{j.type} joint {j.name}: <limit> has no {' and no '.join(missing)}", j.loc,
                          {"joint": j.name, "missing": missing})


@rule("T015", "limits-ordered", "error",
      bad=_arm('<axis xyz="0 0 1"/>\n<limit lower="1.5" upper="-1.5" effort="5" velocity="2"/>'),
      message="joint shoulder: lower 1.5 > upper -1.5",
      good=_arm('<axis xyz="0 0 1"/>\n' + _LIMIT))
def limits_ordered(ctx):
    """A joint's lower limit must not exceed its upper limit.

    lower > upper leaves no legal position (Pinocchio's random configurations and
    MuJoCo's ranges break). Fix: swap them.
    """
    for j in ctx.robot.joints.values():
        lim = j.limit
        if _is_limited(j) and lim and lim.lower is not None and lim.upper is not None and lim.lower > lim.upper:
            yield Finding(f"joint {j.name}: lower {lim.lower:g} > upper {lim.upper:g}", j.loc,
                          {"joint": j.name, "lower": lim.lower, "upper": lim.upper,
                           "fix": {"lower": lim.upper, "upper": lim.lower}})


@rule("T011", "limits-positive", "warning",
      bad=_arm('<axis xyz="0 0 1"/>\n<limit lower="-1.5" upper="1.5" effort="0" velocity="0"/>'),
      message="joint shoulder: effort 0, velocity 0 (must be > 0)",
      good=_arm('<axis xyz="0 0 1"/>\n' + _LIMIT))
def limits_positive(ctx):
    """Effort and velocity limits should be positive.

    An effort of 0 means no actuator can move the joint in Gazebo (and ros2_control). A
    velocity of 0 freezes it in controllers that honour limits. A negative value is what
    SDF writes for "no limit" (its default effort and velocity are -1, "not enforced if
    negative"): urdfdom reads it as it is, sdformat's URDF→SDF conversion copies it, so
    Gazebo enforces no limit, and `convert` (SDF controllers, MJCF actuators) reads it the
    same way; a ROS controller that clamps commands to ±limit gets an empty range, so it is a
    warning (Audibot writes -1 on every joint). Fix: the actuator's rated torque/force and
    speed. An effort of 0 on a
    passive joint (a suspension that no transmission, ros2_control block or drive
    commands, in a model that declares its actuators) says just that: not reported.
    """

    commanded = None
    for j in ctx.robot.joints.values():
        lim = j.limit
        if not lim or j.type == "fixed":
            continue
        bad = {k: getattr(lim, k) for k in ("effort", "velocity") if getattr(lim, k) is not None and getattr(lim, k) <= 0}
        if bad.get("effort") == 0 and j.mimic is None:
            commanded = commanded_joints(ctx.robot) if commanded is None else commanded
            if commanded and j.name not in commanded:
                del bad["effort"]
        if bad:
            neg = all(v < 0 for v in bad.values())
            why = ("negative: SDF's \"no limit\", which Gazebo and convert read it as; a ROS controller that "
                   "clamps commands to ±limit gets an empty range" if neg else "must be > 0")
            yield Finding(f"joint {j.name}: " + ", ".join(f"{k} {v:g}" for k, v in bad.items()) + f" ({why})",
                          j.loc, {"joint": j.name, **bad, "no_limit": neg})


@rule("T012", "mimic-target", "error",
      bad=_arm('<axis xyz="0 0 1"/>\n' + _LIMIT, name="finger_left") + "\n"
          + _arm('<axis xyz="0 0 1"/>\n' + _LIMIT + '\n<mimic joint="finger_lft"/>', name="finger_right")
          .replace('"arm"', '"arm2"'),
      message="joint finger_right mimics 'finger_lft', which does not exist; did you mean finger_left?",
      good=_arm('<axis xyz="0 0 1"/>\n' + _LIMIT, name="finger_left") + "\n"
           + _arm('<axis xyz="0 0 1"/>\n' + _LIMIT + '\n<mimic joint="finger_left"/>', name="finger_right")
           .replace('"arm"', '"arm2"'))
def mimic_target(ctx):
    """A `<mimic joint=...>` must name another existing, moving joint.

    A dangling mimic is dropped silently by some parsers and rejected by others
    (urchin). Fix: the exact name of the driving joint.
    """

    r = ctx.robot
    for j in r.joints.values():
        if not j.mimic:
            continue
        t = j.mimic.joint
        if t not in r.joints:
            guess = suggest(t, r.joints)
            yield Finding(f"joint {j.name} mimics '{t}', which does not exist" + (f"; did you mean {guess}?" if guess else ""),
                          j.loc, {"joint": j.name, "target": t, "suggestion": guess})
        elif t == j.name:
            yield Finding(f"joint {j.name} mimics itself", j.loc, {"joint": j.name})
        elif r.joints[t].type == "fixed" and j.type != "fixed":
            # both fixed (a gripper macro's default): nothing moves, nothing to follow
            yield Finding(f"joint {j.name} mimics {t}, a fixed joint", j.loc, {"joint": j.name, "target": t})


@rule("T013", "limits-zero-range", "warning",
      bad=_arm('<axis xyz="0 1 0"/>\n<limit effort="5" velocity="10"/>', name="wheel_joint"),
      message="revolute joint wheel_joint has range [0, 0] (no lower/upper given: both default to 0): it cannot move",
      good=_arm('<axis xyz="0 1 0"/>\n<limit effort="5" velocity="10"/>', "continuous", "wheel_joint"))
def zero_range(ctx):
    """A revolute/prismatic joint whose `<limit>` leaves lower = upper cannot move.

    URDF defaults lower and upper to 0, so `<limit effort=".." velocity=".."/>` alone
    locks the joint (Pinocchio and Gazebo use [0, 0]). Fix: give lower and upper, or
    make the joint continuous (or fixed, if it is not meant to move).
    """
    for j in ctx.robot.joints.values():
        lim = j.limit
        if _is_limited(j) and lim:
            lo = 0.0 if lim.lower is None else lim.lower
            hi = 0.0 if lim.upper is None else lim.upper
            if lo == hi:
                why = " (no lower/upper given: both default to 0)" if lim.lower is None and lim.upper is None else ""
                yield Finding(f"{j.type} joint {j.name} has range [{lo:g}, {hi:g}]{why}: it cannot move", j.loc,
                              {"joint": j.name, "lower": lo, "upper": hi})


@rule("T014", "axis-normalised", "info",
      bad=_arm('<axis xyz="0 0 10"/>\n' + _LIMIT),
      message="joint shoulder axis 0 0 10 has length 10; parsers normalise it",
      good=_arm('<axis xyz="0 0 1"/>\n' + _LIMIT))
def axis_normalised(ctx):
    """A joint axis should be a unit vector.

    Parsers normalise it, but a non-unit axis usually means a typo (`0 0 10`). Fix:
    write the unit vector.
    """
    for j in ctx.robot.joints.values():
        if j.type in ("revolute", "continuous", "prismatic"):
            n = math.sqrt(sum(a * a for a in j.axis))
            if n > 1e-9 and abs(n - 1) > 1e-3:
                yield Finding(f"joint {j.name} axis {_v(j.axis)} has length {n:.4g}; parsers normalise it",
                              j.loc, {"joint": j.name, "norm": n})


@rule("T016", "joint-type-known", "error",
      bad=_arm('<axis xyz="0 0 1"/>\n' + _LIMIT, "revolut"),
      message="joint shoulder has type 'revolut', not a URDF joint type; did you mean revolute?",
      good=_arm('<axis xyz="0 0 1"/>\n' + _LIMIT),
      fix=FixInfo("sometimes", "safe", "the type becomes the one URDF joint type it is a near miss of, when there "
                  "is exactly one. Safe: no URDF parser accepts the file as it is (urdfdom refuses it), so there "
                  "is no behaviour to keep."))
def joint_type_known(ctx):
    """A joint's type must be one of revolute, continuous, prismatic, fixed, floating, planar.

    urdfdom rejects the file ("has no known type"); MuJoCo reads an unknown type as a
    ball joint. Fix: one of the six URDF types (did-you-mean is given).
    """

    for j in ctx.robot.joints.values():
        if j.type not in JOINT_TYPES:
            guess = suggest(j.type, JOINT_TYPES)
            one = only_candidate(j.type, JOINT_TYPES)
            yield Finding(f"joint {j.name} has type '{j.type}', not a URDF joint type"
                          + (f"; did you mean {guess}?" if guess else ""), j.loc,
                          {"joint": j.name, "type": j.type, "suggestion": guess},
                          fix=Fix((SetValue(j, "type", one),), "safe", f"type {one}") if one else None)


def _v(v) -> str:
    return " ".join(f"{x:g}" for x in v)


_BRACED = re.compile(r"(?<!\$)\{[A-Za-z_][A-Za-z0-9_.]*\}")     # {word} not preceded by $


@rule("T018", "name-unexpanded-brace", "warning",
      bad='<link name="{prefix}arm"/>  <!-- ${ns}{prefix}arm: the $ of ${prefix} is missing -->\n'
          '<joint name="arm_joint" type="fixed"><parent link="base_link"/><child link="{prefix}arm"/></joint>',
      message="link {prefix}arm has '{prefix}' in its name: a xacro ${prefix} written without its $",
      good='<link name="arm"/>\n'
           '<joint name="arm_joint" type="fixed"><parent link="base_link"/><child link="arm"/></joint>')
def unexpanded_brace(ctx):
    """A link or joint name holds `{word}`: an xacro `${word}` written without its `$`.

    xacro expands `${prefix}` but copies `{prefix}` as it stands, so `${ns}{prefix}${name}`
    builds names with a literal `{prefix}` in them: valid to urdfdom, and nothing that
    looks the frame up by its intended name (TF, controllers, MoveIt) finds it. Fix: the
    missing `$`.
    """
    r = ctx.robot
    for kind, items in (("link", r.links.values()), ("joint", r.joints.values())):
        for item in items:
            m = _BRACED.search(item.name or "")
            if m:
                word = m.group(0)
                yield Finding(f"{kind} {item.name} has '{word}' in its name: a xacro ${word} written without its $",
                              item.loc, {"kind": kind, "name": item.name, "text": word})
