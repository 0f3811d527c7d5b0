"""What the robot is (``myrabot-desc info``): the summary as plain data, and the text it prints."""

from __future__ import annotations

import math

from myrabot_desc.model.kinematics import center_of_mass, world_transforms
from myrabot_desc.safety import display
from myrabot_desc.sanitize import clean


def summarize(robot) -> dict:
    """Everything ``info`` shows, as plain data (also the --json output)."""
    T = world_transforms(robot)
    mass, com = center_of_mass(robot)
    dof = [j for j in robot.joints.values() if j.type in ("revolute", "continuous", "prismatic") and not j.mimic]
    frames = []
    for name in _tree_order(robot):
        if name in T:
            p = T[name][:3, 3]
            frames.append({"frame": name, "xyz": [round(float(v), 6) for v in p]})
    joints = []
    for j in robot.joints.values():
        joints.append({"name": j.name, "type": j.type, "parent": j.parent, "child": j.child,
                       "axis": list(j.axis) if j.type != "fixed" else None,
                       "limit": None if j.limit is None else {"lower": j.limit.lower, "upper": j.limit.upper,
                                                              "effort": j.limit.effort,
                                                              "velocity": j.limit.velocity}})
    return {
        "name": robot.name,
        "source": display(robot.source) if robot.source else None,
        "links": len(robot.links),
        "joints": len(robot.joints),
        "roots": robot.roots,
        "dof": len(dof),
        "movable_joints": [j.name for j in dof],
        "total_mass": round(mass, 6),
        "center_of_mass": [round(float(v), 6) for v in com] if mass > 0 else None,
        "sensors": [{"name": s.name, "type": s.type, "link": s.reference} for s in robot.sensors()],
        "plugins": [{"name": p.name, "library": p.library} for p in robot.plugins()],
        "joint_list": joints,
        "frames": frames,
    }


def _tree_order(robot) -> list[str]:
    children = robot.joints_by_parent()
    order, seen = [], set()
    for root in robot.roots or list(robot.links)[:1]:
        stack = [root]
        while stack:
            link = stack.pop()
            if link in seen:
                continue
            seen.add(link)
            order.append(link)
            stack.extend(j.child for j in reversed(children.get(link, [])))
    return order


def tree_lines(robot) -> list[str]:
    """The link tree, drawn with box characters; each child shows the joint that carries it."""
    children = robot.joints_by_parent()
    lines, seen = [], set()
    for root in robot.roots or list(robot.links)[:1]:
        stack = [(root, "", None, True)]          # iterative: chains can be thousands deep
        while stack:
            link, prefix, via, last = stack.pop()
            label = clean(link)        # names are model text: one printable line each
            if via is not None:
                ax = "" if via.type == "fixed" else " axis " + " ".join(f"{a:g}" for a in via.axis)
                label = f"{clean(link)}  [{clean(via.name)}: {clean(via.type)}{ax}]"
            if link in seen:
                lines.append(prefix + ("└─ " if last else "├─ ") + label + "  (cycle!)")
                continue
            seen.add(link)
            lines.append(prefix + ("" if via is None else ("└─ " if last else "├─ ")) + label)
            kids = children.get(link, [])
            inner = prefix + ("" if via is None else ("   " if last else "│  "))
            for i, j in reversed(list(enumerate(kids))):
                stack.append((j.child, inner, j, i == len(kids) - 1))
    return lines


def _fmt_limit(j) -> str:
    if j.type == "continuous":       # the type column already says "continuous"
        if j.limit is None or (j.limit.effort is None and j.limit.velocity is None):
            return "no position limits"
        return f"no position limits, effort {j.limit.effort}, velocity {j.limit.velocity}"
    if j.limit is None:
        return "no <limit>"
    lo, hi = j.limit.lower, j.limit.upper
    rng = f"[{lo:g}, {hi:g}] {'m' if j.type == 'prismatic' else 'rad'}" if lo is not None and hi is not None else "[?]"
    if j.type == "revolute" and lo is not None and hi is not None:
        rng += f" ({math.degrees(lo):.0f}° .. {math.degrees(hi):.0f}°)"
    return f"{rng}, effort {j.limit.effort}, velocity {j.limit.velocity}"


def text_lines(robot, s: dict, tree: bool = True) -> list[str]:
    """The lines ``info`` prints for ``robot`` and its summary ``s`` (:func:`summarize`)."""
    out = []
    add = out.append
    add(f"robot {clean(repr(s['name']))}  ({clean(s['source'])})")
    add(f"  {s['links']} links, {s['joints']} joints, {s['dof']} degrees of freedom, root: "
        f"{', '.join(map(clean, s['roots'])) or 'none (cycle?)'}")
    com = s["center_of_mass"]
    add(f"  total mass {s['total_mass']:.4f} kg; centre of mass at zero configuration "
        + (f"({com[0]:.4f}, {com[1]:.4f}, {com[2]:.4f}) m" if com else "undefined (no mass)"))
    if tree:
        add("\ntree:")
        for line in tree_lines(robot):
            add("  " + line)
    movable = [j for j in robot.joints.values() if j.type in ("revolute", "continuous", "prismatic")]
    if movable:
        add("\nmovable joints:")
        w = max(len(clean(j.name)) for j in movable)
        for j in movable:
            add(f"  {clean(j.name):<{w}}  {j.type:<10} {_fmt_limit(j)}")
    if s["sensors"]:
        add("\nsensors:")
        for x in s["sensors"]:
            add(f"  {clean(x['name'])} ({clean(x['type'])}) on {clean(x['link'])}")
    add("\nframes (world position at zero configuration, m):")
    w = max((len(clean(f["frame"])) for f in s["frames"]), default=5)
    for f in s["frames"]:
        x, y, z = f["xyz"]
        add(f"  {clean(f['frame']):<{w}}  {x:9.4f} {y:9.4f} {z:9.4f}")
    return out
