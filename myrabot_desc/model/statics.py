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

from myrabot_desc.model.kinematics import _norms, axis_angle, pose_matrix, pose_stack, world_transforms, \
    world_transforms_from

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
    """One :class:`Need` per moving, non-mimic joint (``joints``: only these), in file order.

    Linear in the tree's size for a wide tree, O(joints x depth) for a deep one: the masses and
    moments of every subtree are summed once, bottom-up; moving one joint changes only the torques
    of the joints above it (the moment of its subtree turns) and below it (gravity turns in their
    frames), the others keep their rest value. A model that is not a tree (a link hanging from two
    joints) takes the dense form (``_gravity_needs_dense``)."""
    import numpy as np

    rest = robot.rest_pose()
    W = world_transforms(robot, rest)
    movers = [j for j in robot.joints.values() if j.type in MOVING and j.mimic is None
              and j.parent in W and j.child in W]
    names = [j.name for j in movers if joints is None or j.name in joints]
    if not names:
        return []
    tree = _preorder(robot, W)
    if tree is None:
        return _gravity_needs_dense(robot, samples, joints)
    order, pos, parent, levels, end = tree
    links = [link for link in robot.links.values() if link.name in W and link.inertial is not None
             and link.inertial.mass > 0 and math.isfinite(link.inertial.mass)]
    L = len(order)
    own_m = np.zeros(L)
    own_mc = np.zeros((L, 3))
    if links:
        k = np.array([pos[link.name] for link in links])
        own_m[k] = [link.inertial.mass for link in links]
        c = (np.array([W[link.name] for link in links]) @ pose_stack(link.inertial.origin for link in links))[:, :3, 3]
        own_mc[k] = own_m[k][:, None] * c
    Mtot = _subtree_sums(own_m, parent, levels)
    Qtot = _subtree_sums(own_mc, parent, levels)
    every = [j.name for j in movers]
    frames = _joint_frames(np, robot, W, every)
    ci = np.array([pos[robot.joints[n].child] for n in names])        # each asked joint's child, in preorder
    P = np.array([frames[n][0] for n in names])
    A = np.array([frames[n][1] for n in names])
    prism = np.array([robot.joints[n].type == "prismatic" for n in names])
    M, Q = Mtot[ci], Qtot[ci]
    g = np.array([0.0, 0.0, -GRAVITY])
    followers = {j.mimic.joint for j in robot.joints.values() if j.mimic is not None}

    def torques(Q_now, P_now, A_now, M_now, prism_now, g_now=g):
        """|torque| of joints with subtree moment sums ``Q_now``; a leading axis of poses allowed."""
        moment = Q_now - M_now[:, None] * P_now          # M_i (C_i - p_i)
        rot = (A_now * np.cross(moment, g_now)).sum(axis=-1)
        lin = (A_now * g_now).sum(axis=-1) * M_now
        return np.abs(np.where(prism_now, lin, rot))

    t_rest = torques(Q, P, A, M, prism)
    best = t_rest.copy()
    where = [(None, 0.0)] * len(names)
    # with g along -z, a_i . (moment x g) = G (a_y m_x - a_x m_y): linear in the moment, so turning a
    # subtree adds the same change to every joint above it; below it, a_i . (mu_i x g') = g' . (a_i x mu_i)
    r_rest = np.where(prism, 0.0, GRAVITY * (A[:, 1] * (Q[:, 0] - M * P[:, 0]) - A[:, 0] * (Q[:, 1] - M * P[:, 1])))
    B = np.cross(A, Q - M[:, None] * P)
    by_tin = np.argsort(ci, kind="stable")           # asked joints by their child's place in preorder
    tin_sorted = ci[by_tin]
    up = _asked_above(robot, names, order, pos, parent) if len(levels) <= 64 else None   # shallow: walk up
    full = None
    vals = {j.name: sample_values(j, samples) for j in movers}
    turned = [j for j in movers if j.type != "prismatic" and j.name not in followers and len(vals[j.name]) == samples]
    R_of = {}
    if turned:          # every revolute joint's sampled rotations at once
        R_all = _rotations(np.array([frames[j.name][1] for j in turned]),
                           np.array([vals[j.name] for j in turned])
                           - np.array([rest.get(j.name, 0.0) for j in turned])[:, None])
        R_of = {j.name: k for k, j in enumerate(turned)}
    alone = _alone(robot, movers, names, pos, parent, end, R_of)
    if alone:
        _turn_alone(np, robot, alone, names, vals, frames, pos, R_all, R_of, Qtot, Mtot, prism, t_rest, r_rest,
                    A, best, where)
    alone = set(alone)
    for j in movers:
        if j.name in alone:
            continue
        values = vals[j.name]
        cj = pos[j.child]
        if end[cj] > cj + 1:
            lo, hi = np.searchsorted(tin_sorted, [cj + 1, end[cj]])
            below = by_tin[lo:hi]                      # the asked joints under j (j itself excluded)
        else:
            below = by_tin[:0]
        if up is not None:
            above = np.array(up(cj), dtype=np.int64)
        else:
            above = np.flatnonzero((ci <= cj) & (end[ci] > cj))
        idx = np.concatenate([above, below]) if len(below) else above
        if not len(idx):
            continue
        if j.name in followers:          # a mimic follows it: the whole pose, the slow way
            if full is None:
                full = _FullTree(robot, rest, W, names, links, pos, parent, levels, M, prism)
            T = np.array([full.torques(j.name, x, torques) for x in values])[:, idx]
        else:
            p0, a0 = frames[j.name]
            d = np.asarray(values) - rest.get(j.name, 0.0)
            if j.type == "prismatic":
                R = np.broadcast_to(np.eye(3), (len(d), 3, 3))
                t = d[:, None] * a0
            else:
                R = R_all[R_of[j.name]] if j.name in R_of else _rotations(a0[None, :], d[None, :])[0]
                t = p0 - R @ p0
            shift = Qtot[cj] @ np.swapaxes(R, 1, 2) + Mtot[cj] * t - Qtot[cj]   # the turned subtree's moment change
            T_above = np.abs(np.where(prism[above], t_rest[above],
                                      r_rest[above] + GRAVITY * (np.outer(shift[:, 0], A[above, 1])
                                                                 - np.outer(shift[:, 1], A[above, 0]))))
            if len(below):
                g_below = g @ R                                        # gravity in the turned frames
                T_below = np.abs(np.where(prism[below], (g_below @ A[below].T) * M[below], g_below @ B[below].T))
                T = np.concatenate([T_above, T_below], axis=1)
            else:
                T = T_above
        b = best[idx]
        gain = T.max(axis=0) > b + 1e-9 * (1 + b)       # only these columns move their worst pose
        if gain.any():
            cols, Tg = idx[gain], T[:, gain]
            bg = best[cols]
            for x, t in zip(values, Tg):
                better = t > bg + 1e-9 * (1 + bg)
                for k in cols[better]:
                    where[k] = (j.name, x)
                bg = np.maximum(bg, t)
        best[idx] = np.maximum(b, T.max(axis=0))
    out = []
    for k, n in enumerate(names):
        j = robot.joints[n]
        out.append(Need(n, float(best[k]), float(t_rest[k]), where[k][0], float(where[k][1]), effort_of(j),
                        "N" if j.type == "prismatic" else "N·m"))
    return out


def _alone(robot, movers, names, pos, parent, end, R_of) -> list[str]:
    """The turned joints whose torques no other joint changes and that change no other joint's: a
    leaf link's joint with no moving joint above it (a star's spokes, wheels on a fixed base). Their
    turns commute with every other, so they are taken together (_turn_alone)."""
    asked = set(names)
    mover_at = set()
    for m in movers:
        mover_at.add(pos[m.child])
    above = [False] * len(parent)            # a moving joint somewhere above this place (preorder: parents first)
    for place in range(len(parent)):
        up = int(parent[place])
        above[place] = up >= 0 and (above[up] or up in mover_at)
    out = []
    for j in movers:
        cj = pos[j.child]
        if j.name in asked and j.name in R_of and end[cj] == cj + 1 and not above[cj]:
            out.append(j.name)
    return out


def _turn_alone(np, robot, alone, names, vals, frames, pos, R_all, R_of, Qtot, Mtot, prism, t_rest, r_rest, A,
                best, where) -> None:
    """gravity_needs' turn of each joint of ``alone`` over its samples, all at once: the same products
    as one joint at a time (the torque of the joint itself only), the same worst pose kept."""
    k_of = {n: k for k, n in enumerate(names)}
    K = np.array([k_of[n] for n in alone])
    cj = np.array([pos[robot.joints[n].child] for n in alone])
    R = R_all[[R_of[n] for n in alone]]                                    # (J, samples, 3, 3)
    p0 = np.array([frames[n][0] for n in alone])
    t = p0[:, None, :] - (R @ p0[:, None, :, None])[..., 0]
    shift = ((Qtot[cj][:, None, None, :] @ np.swapaxes(R, -1, -2))[:, :, 0, :] + Mtot[cj][:, None, None] * t
             - Qtot[cj][:, None, :])
    T = np.abs(np.where(prism[K][:, None], t_rest[K][:, None],
                        r_rest[K][:, None] + GRAVITY * (shift[:, :, 0] * A[K, 1][:, None]
                                                        - shift[:, :, 1] * A[K, 0][:, None])))
    b = best[K]
    gain = T.max(axis=1) > b + 1e-9 * (1 + b)
    bg = b.copy()
    for v in range(T.shape[1]):
        t_v = T[:, v]
        better = (t_v > bg + 1e-9 * (1 + bg)) & gain
        for i in np.flatnonzero(better):
            where[K[i]] = (alone[i], vals[alone[i]][v])
        bg = np.maximum(bg, t_v)
    best[K] = np.maximum(b, T.max(axis=1))


def _rotations(axes, angles):
    """Rotation matrices (k, n, 3, 3) about each of ``axes`` (k, 3) by its row of ``angles`` (k, n)
    (Rodrigues; a zero axis gives the identity)."""
    import numpy as np

    axes = np.asarray(axes, dtype=float)
    norm = np.linalg.norm(axes, axis=1)
    a = axes / np.where(norm > 0, norm, 1.0)[:, None]
    x, y, z = a[:, 0], a[:, 1], a[:, 2]
    zero = np.zeros(len(a))
    K = np.stack([np.stack([zero, -z, y], 1), np.stack([z, zero, -x], 1), np.stack([-y, x, zero], 1)], 1)
    c, s = np.cos(angles)[:, :, None, None], np.sin(angles)[:, :, None, None]
    return np.eye(3) + s * K[:, None] + (1 - c) * (K @ K)[:, None]


def _preorder(robot, W):
    """(links in depth-first preorder, link -> place, parent place per place (-1 at a root), places
    by depth (deepest first), end of each subtree's places); None when the links reached are not a
    tree (a link hanging from two joints)."""
    import numpy as np

    children = robot.joints_by_parent()
    has_parent = set()
    for j in robot.joints.values():
        if j.parent in W and j.child in W:
            if j.child in has_parent:
                return None
            has_parent.add(j.child)
    order, pos, parent, depth = [], {}, [], []
    for root in (name for name in W if name not in has_parent):
        stack = [(root, -1, 0)]
        while stack:
            link, up, dep = stack.pop()
            if link in pos:
                return None
            pos[link] = len(order)
            order.append(link)
            parent.append(up)
            depth.append(dep)
            here = pos[link]
            stack.extend((jj.child, here, dep + 1) for jj in reversed(children.get(link, ()))
                         if jj.child in W)
    if len(order) != len(W):
        return None
    parent = np.array(parent, dtype=np.int64)
    depth = np.array(depth, dtype=np.int64)
    by_depth = np.argsort(-depth, kind="stable")
    cuts = np.flatnonzero(np.diff(depth[by_depth])) + 1
    levels = np.split(by_depth, cuts)
    size = _subtree_sums(np.ones(len(order)), parent, levels).astype(np.int64)
    end = np.arange(len(order)) + size
    return order, pos, parent, levels, end


def _joint_frames(np, robot, W, names) -> dict:
    """joint -> (its origin, its unit axis) in the world, from the link poses ``W``."""
    if not names:
        return {}
    # every joint's products at once: stacked products give each joint's numbers to the bit
    joints = [robot.joints[n] for n in names]
    F = np.array([W[j.parent] for j in joints]) @ pose_stack(j.origin for j in joints)
    axes = (F[:, :3, :3] @ np.array([j.axis for j in joints], dtype=float).reshape(-1, 3, 1))[:, :, 0]
    frames = {}
    for n, Fj, a, norm in zip(names, F, axes, _norms(axes.tolist())):
        frames[n] = (Fj[:3, 3], a / norm if norm > 0 else a)
    return frames


def _subtree_sums(values, parent, levels):
    """``values`` (one row per link place) summed over each link's subtree, deepest level first."""
    import numpy as np

    out = np.array(values, dtype=float, copy=True)
    for level in levels:
        up = parent[level]
        keep = up >= 0
        if keep.any():
            np.add.at(out, up[keep], out[level[keep]])
    return out


def _asked_above(robot, names, order, pos, parent):
    """For a shallow tree: place -> indices of the asked joints on the path from it to its root
    (the joint whose child it is included)."""
    joint_of = {pos[robot.joints[n].child]: k for k, n in enumerate(names)}

    def up(place):
        out = []
        while place >= 0:
            k = joint_of.get(place)
            if k is not None:
                out.append(k)
            place = int(parent[place])
        return out

    return up


def _gravity_needs_dense(robot, samples: int = SAMPLES, joints=None) -> list[Need]:
    """``gravity_needs`` of a model that is not a tree: a dense joint x link matrix of the links below each joint."""
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
    frames = _joint_frames(np, robot, W, every)
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


class _FullTree:
    """``gravity_needs``' torques with one joint moved and the mimic joints following it, from the
    pose's transforms. Only the links below the joints that move are placed again
    (``world_transforms_from``); the rest keep their rest-pose rows, made once by the same products."""

    def __init__(self, robot, rest, W, names, links, pos, parent, levels, M, prism):
        import numpy as np

        self.robot, self.rest, self.W, self.names, self.links = robot, rest, W, names, links
        self.pos, self.parent, self.levels, self.M, self.prism = pos, parent, levels, M, prism
        self.own_mc = np.zeros((len(pos), 3))
        for link in links:
            self.own_mc[pos[link.name]] = self._moment(link, W)
        self.P = np.array([self._frame(robot.joints[n], W)[0] for n in names]).reshape(-1, 3)
        self.A = np.array([self._frame(robot.joints[n], W)[1] for n in names]).reshape(-1, 3)
        self.ci = [pos[robot.joints[n].child] for n in names]
        self._rows: dict = {}

    @staticmethod
    def _moment(link, W):
        return link.inertial.mass * (W[link.name] @ pose_matrix(link.inertial.origin))[:3, 3]

    @staticmethod
    def _frame(j, W):
        import numpy as np

        F = W[j.parent] @ pose_matrix(j.origin)
        a = F[:3, :3] @ np.asarray(j.axis, dtype=float)
        norm = np.linalg.norm(a)
        return F[:3, 3], (a / norm if norm > 0 else a)

    def torques(self, name, x, torques):
        q = dict(self.rest)
        q[name] = x
        W, moved = world_transforms_from(self.robot, self.W, self.rest, q)
        rows = self._rows.get(moved)
        if rows is None:         # the links and joint frames that move: the same for every sample of a joint
            rows = self._rows[moved] = ([link for link in self.links if link.name in moved],
                                        [(k, self.robot.joints[n]) for k, n in enumerate(self.names)
                                         if self.robot.joints[n].parent in moved])
        own_mc, P, A = self.own_mc.copy(), self.P.copy(), self.A.copy()
        for link in rows[0]:
            own_mc[self.pos[link.name]] = self._moment(link, W)
        for k, j in rows[1]:
            P[k], A[k] = self._frame(j, W)
        Qtot = _subtree_sums(own_mc, self.parent, self.levels)
        return torques(Qtot[self.ci], P, A, self.M, self.prism)


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
