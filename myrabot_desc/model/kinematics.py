"""Forward kinematics over the model (numpy; no Pinocchio needed for frames).

URDF convention: a joint's origin places the child frame in the parent frame;
rpy is fixed-axis X, Y, Z, i.e. R = Rz(yaw) @ Ry(pitch) @ Rx(roll).
"""

from __future__ import annotations

import math

import numpy as np

from myrabot_desc.model.parts import Joint, Pose, Robot


def rpy_matrix(rpy) -> np.ndarray:
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def pose_matrix(pose: Pose) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3] = rpy_matrix(pose.rpy)
    T[:3, 3] = pose.xyz
    return T


def axis_angle(axis, angle: float) -> np.ndarray:
    a = np.asarray(axis, dtype=float)
    n = np.linalg.norm(a)
    if n == 0:
        return np.eye(3)
    x, y, z = a / n
    c, s, C = math.cos(angle), math.sin(angle), 1 - math.cos(angle)
    return np.array([[c + x * x * C, x * y * C - z * s, x * z * C + y * s],
                     [y * x * C + z * s, c + y * y * C, y * z * C - x * s],
                     [z * x * C - y * s, z * y * C + x * s, c + z * z * C]])


def joint_motion(joint: Joint, q: float) -> np.ndarray:
    """Transform of the joint's own motion by position q (revolute/continuous/prismatic)."""
    T = np.eye(4)
    if joint.type in ("revolute", "continuous"):
        T[:3, :3] = axis_angle(joint.axis, q)
    elif joint.type == "prismatic":
        a = np.asarray(joint.axis, dtype=float)
        n = np.linalg.norm(a)
        if n:
            T[:3, 3] = a / n * q
    return T


def world_transforms(robot: Robot, q: dict[str, float] | None = None, root_pose: np.ndarray | None = None
                     ) -> dict[str, np.ndarray]:
    """World (root-frame) 4x4 transform of every link reachable from the root(s).

    Joints not in ``q`` sit at 0. Mimic joints follow their target. Cycles are
    cut (each link is placed once).
    """
    q = dict(q or {})
    for j in robot.joints.values():
        if j.mimic and j.mimic.joint in q and j.name not in q:
            q[j.name] = q[j.mimic.joint] * j.mimic.multiplier + j.mimic.offset
    children = robot.joints_by_parent()
    out: dict[str, np.ndarray] = {}
    base = np.eye(4) if root_pose is None else root_pose
    for root in robot.roots or list(robot.links)[:1]:
        stack = [(root, base)]
        while stack:
            link, T = stack.pop()
            if link in out:
                continue
            out[link] = T
            for j in children.get(link, []):
                if j.child not in out:
                    stack.append((j.child, T @ pose_matrix(j.origin) @ joint_motion(j, q.get(j.name, 0.0))))
    return out


def joint_world_transforms(robot: Robot, q: dict[str, float] | None = None) -> dict[str, np.ndarray]:
    """World transform of every joint frame (the joint origin, before its motion)."""
    links = world_transforms(robot, q)
    return {j.name: links[j.parent] @ pose_matrix(j.origin) for j in robot.joints.values() if j.parent in links}


def center_of_mass(robot: Robot, q: dict[str, float] | None = None) -> tuple[float, np.ndarray]:
    """Total mass and centre of mass (world frame) of every link with an inertial."""
    T = world_transforms(robot, q)
    total, acc = 0.0, np.zeros(3)
    for name, link in robot.links.items():
        if link.inertial is None or name not in T or link.inertial.mass <= 0:
            continue
        p = (T[name] @ pose_matrix(link.inertial.origin))[:3, 3]
        total += link.inertial.mass
        acc += link.inertial.mass * p
    return total, (acc / total if total > 0 else np.full(3, np.nan))


def require_tree(robot: Robot) -> str:
    """The root link, or InputError when the joints do not form one tree over the links.

    check reports these as T-rules and goes on; commands that move the robot (sim) need a tree:
    a joint naming a missing link, a link with two parents, a cycle or a second root would
    otherwise surface as a KeyError deep inside.
    """
    from myrabot_desc.errors import InputError

    parent_of: dict[str, str] = {}
    for j in robot.joints.values():
        for end in (j.parent, j.child):
            if end not in robot.links:
                raise InputError(f"joint '{j.name}' names link '{end}', which does not exist", j.loc)
        if j.child in parent_of:
            raise InputError(f"link '{j.child}' has two parent joints: a URDF must be a tree", j.loc)
        parent_of[j.child] = j.name
    roots = [n for n in robot.links if n not in parent_of]
    if len(roots) != 1:
        names = ", ".join(roots[:5]) if roots else "none: the joints form a cycle"
        raise InputError(f"the model needs exactly one root link, it has {len(roots)} ({names})", robot.loc)
    children = robot.joints_by_parent()
    seen, stack = set(), [roots[0]]
    while stack:
        n = stack.pop()
        seen.add(n)
        stack.extend(j.child for j in children.get(n, ()) if j.child not in seen)
    if len(seen) != len(robot.links):
        lost = sorted(set(robot.links) - seen)
        raise InputError(f"links {', '.join(lost[:5])} are not reachable from the root '{roots[0]}' "
                         "(the joints form a cycle)", robot.links[lost[0]].loc)
    return roots[0]
