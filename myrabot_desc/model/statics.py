"""Gravity torque against effort: the torque (or force) each joint needs to hold what it carries
still against gravity, at its worst over a sampled range, next to its effort limit.

The robot stands on its root (the base is fixed: an arm on its table, a mobile base on its wheels,
a legged robot's trunk held), gravity along the root frame's -z. Each moving joint in turn goes
through ``SAMPLES`` evenly spaced values over its range (a full turn for a continuous joint), the
others at ``Robot.rest_pose`` (mimic joints where their targets put them); every joint keeps its
largest ``|torque|`` and the pose it came from. A legged robot's numbers are what each joint needs
to hold its own limb lifted; standing on the feet is ``sim settle``'s question.

The torque on joint i is ``a_i . (M_i (C_i - p_i) x g)`` (``a_i`` its axis and ``p_i`` its origin
in the world, ``M_i`` and ``C_i`` the mass and centre of mass of everything below it), the force
on a prismatic joint ``a_i . M_i g``: Pinocchio's generalized gravity ``computeGeneralizedGravity``
for a fixed base, which tests/check/test_statics.py compares it with. It is computed here with
numpy from the model's own kinematics (model/kinematics.py): moving one joint moves its subtree
rigidly, so each sample is a few small array products, and ``check`` does not pay Pinocchio's
import (a fifth of a one-robot check) for it.
"""

from __future__ import annotations

import math
from typing import NamedTuple

from myrabot_desc.model.kinematics import axis_angle, pose_matrix, world_transforms

SAMPLES = 13             # values per joint range: 15 degrees apart on a half-turn range
MOVING = ("revolute", "continuous", "prismatic")
GRAVITY = 9.81             # m/s², along the root frame's -z (Pinocchio's and MuJoCo's default)


class Need(NamedTuple):
    joint: str
    torque: float            # N·m (N for a prismatic joint): the largest |gravity torque| sampled
    at_rest: float           # the same at the rest pose
    pose_joint: str | None   # the joint moved in the worst pose (None: the rest pose)
    pose_value: float        # its value there
    effort: float | None     # the effort limit (None: not given, or 0 as ROS-Industrial writes it)
    unit: str                # "N·m" or "N"

    @property
    def ratio(self) -> float:
        return self.torque / self.effort if self.effort else math.inf


def effort_of(joint) -> float | None:
    """A joint's effort limit, None when absent or 0 (ROS-Industrial's "not given")."""
    e = joint.limit.effort if joint.limit is not None else None
    return float(e) if e is not None and math.isfinite(e) and e > 0 else None


def sample_values(joint, n: int = SAMPLES) -> list[float]:
    """``n`` values over the joint's range (a full turn when it has none; one turn at most)."""
    lo = hi = None
    if joint.type != "continuous" and joint.limit is not None:
        lo, hi = joint.limit.lower, joint.limit.upper
    if lo is None or hi is None or not (math.isfinite(lo) and math.isfinite(hi)) or hi < lo:
        lo, hi = (-math.pi, math.pi) if joint.type != "prismatic" else (0.0, 0.0)
    if joint.type != "prismatic":
        lo, hi = max(lo, -math.pi), min(hi, math.pi)
    if hi - lo < 1e-12:
        return [lo]
    return [lo + (hi - lo) * k / (n - 1) for k in range(n)]


def _subtrees(robot, names):
    """link -> index, and per joint the links below it (its child included)."""
    children = robot.joints_by_parent()
    below = {}
    for n in names:
        seen, stack = [], [robot.joints[n].child]
        while stack:
            link = stack.pop()
            if link in seen:
                continue
            seen.append(link)
            stack.extend(j.child for j in children.get(link, ()))
        below[n] = seen
    return below


def gravity_needs(robot, samples: int = SAMPLES, joints=None) -> list[Need]:
    """One :class:`Need` per moving, non-mimic joint (``joints``: only these), in file order."""
    import numpy as np

    rest = robot.rest_pose()
    W = world_transforms(robot, rest)
    movers = [j for j in robot.joints.values() if j.type in MOVING and j.mimic is None
              and j.parent in W and j.child in W]
    names = [j.name for j in movers if joints is None or j.name in joints]
    if not names:
        return []
    links = [link for link in robot.links.values() if link.name in W and link.inertial is not None
             and link.inertial.mass > 0 and math.isfinite(link.inertial.mass)]
    index = {link.name: k for k, link in enumerate(links)}
    m = np.array([link.inertial.mass for link in links], dtype=float)
    c = np.array([(W[link.name] @ pose_matrix(link.inertial.origin))[:3, 3] for link in links]).reshape(-1, 3)
    # every moving joint (the sampled ones and the ones whose torque is asked): frames at rest
    every = [j.name for j in movers]
    frames = {}
    for n in every:
        j = robot.joints[n]
        F = W[j.parent] @ pose_matrix(j.origin)
        a = F[:3, :3] @ np.asarray(j.axis, dtype=float)
        norm = np.linalg.norm(a)
        frames[n] = (F[:3, 3], a / norm if norm > 0 else a)
    below = _subtrees(robot, every)
    S = np.zeros((len(names), len(links)))
    for r, n in enumerate(names):
        for link in below[n]:
            if link in index:
                S[r, index[link]] = 1.0
    P = np.array([frames[n][0] for n in names])
    A = np.array([frames[n][1] for n in names])
    prism = np.array([robot.joints[n].type == "prismatic" for n in names])
    M = S @ m
    g = np.array([0.0, 0.0, -GRAVITY])
    followers = {j.mimic.joint for j in robot.joints.values() if j.mimic is not None}

    def torques(c_now, P_now, A_now):
        """|torque| of every asked joint; the arrays may carry a leading axis of poses."""
        moment = S @ (m[:, None] * c_now) - M[:, None] * P_now          # M_i (C_i - p_i)
        rot = (A_now * np.cross(moment, g)).sum(axis=-1)
        lin = (A_now @ g) * M
        return np.abs(np.where(prism, lin, rot))

    t_rest = torques(c, P, A)
    best = t_rest.copy()
    where = [(None, 0.0)] * len(names)
    for j in movers:
        values = sample_values(j, samples)
        if j.name in followers:          # a mimic follows it: the whole pose, the slow way
            T = np.array([_full(robot, rest, j.name, x, names, (links, m), torques) for x in values])
        else:
            p0, a0 = frames[j.name]
            moved_links = np.zeros(len(links), dtype=bool)
            for link in below[j.name]:
                if link in index:
                    moved_links[index[link]] = True
            moved_joints = np.array([robot.joints[n].child in below[j.name] and n != j.name for n in names])
            d = np.asarray(values) - rest.get(j.name, 0.0)
            if j.type == "prismatic":
                R = np.broadcast_to(np.eye(3), (len(d), 3, 3))
                t = d[:, None] * a0
            else:
                R = np.array([axis_angle(a0, x) for x in d])
                t = p0 - R @ p0
            Rt = np.swapaxes(R, 1, 2)
            c_now = np.where(moved_links[:, None], c @ Rt + t[:, None, :], c)
            P_now = np.where(moved_joints[:, None], P @ Rt + t[:, None, :], P)
            A_now = np.where(moved_joints[:, None], A @ Rt, A)
            T = torques(c_now, P_now, A_now)
        for x, t in zip(values, T):
            better = t > best + 1e-9 * (1 + best)
            for k in np.flatnonzero(better):
                where[k] = (j.name, x)
            best = np.maximum(best, t)
    out = []
    for k, n in enumerate(names):
        j = robot.joints[n]
        out.append(Need(n, float(best[k]), float(t_rest[k]), where[k][0], float(where[k][1]), effort_of(j),
                        "N" if j.type == "prismatic" else "N·m"))
    return out


def _full(robot, rest, name, x, names, masses, torques):
    """The torques with joint ``name`` at ``x`` from the whole pose's transforms (mimic joints
    follow it)."""
    import numpy as np

    links, m = masses
    q = dict(rest)
    q[name] = x
    W = world_transforms(robot, q)
    c = np.array([(W[link.name] @ pose_matrix(link.inertial.origin))[:3, 3] for link in links]).reshape(-1, 3)
    P, A = [], []
    for n in names:
        j = robot.joints[n]
        F = W[j.parent] @ pose_matrix(j.origin)
        a = F[:3, :3] @ np.asarray(j.axis, dtype=float)
        norm = np.linalg.norm(a)
        P.append(F[:3, 3])
        A.append(a / norm if norm > 0 else a)
    return torques(c, np.array(P), np.array(A))
