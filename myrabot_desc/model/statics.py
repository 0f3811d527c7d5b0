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
for a fixed base, which tests/model/test_physics_facts.py compares it with. It is computed here from
the model's own kinematics (model/kinematics.py): moving one joint moves its subtree rigidly, so
each sample is a few small products, and ``check`` does not pay Pinocchio's import (a fifth of a
one-robot check) for it. An ordinary robot takes them in pure Python (``_gravity_needs_py``: numpy's
import would cost more than the sweep), a large one with numpy (``_gravity_needs_np``), below.

Every joint's samples change the torques of the joints above and below it, so the full table is
O(joints x depth): on a 5,000-link chain, some 3 x 10^8 torques. On a large deep tree only the
turns that can change a joint's maximum or worst pose are evaluated (``_Sweep``: upper bounds
aggregated along the tree), with the same maxima and poses, to the bit: the cost is linear in the
tree's size plus the turns kept (one kept for a joint below it is evaluated on every joint below it,
as a BLAS product's bits depend on its shape). A long chain turning about tilted or horizontal axes,
where the turns above a joint tie with its own, still keeps most turns: O(joints x depth) there.
"""

import math

from myrabot_desc.model.kinematics import _axis_angle_rows, axis_angle, norm_rows, pose_matrix, pose_stack, poses_at, \
    stack_by_identity, walk, world_transforms, world_transforms_from
from myrabot_desc.model.transforms import compose, pose_T, rotate
from myrabot_desc.records import Struct

SAMPLES = 13             # values per joint range: 15 degrees apart on a half-turn range
MOVING = ("revolute", "continuous", "prismatic")
GRAVITY = 9.81             # m/s², along the root frame's -z (Pinocchio's and MuJoCo's default)


class Need(Struct):
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
    lo, hi = _sampled_range(joint)
    if hi - lo < 1e-12:
        return [lo]
    return [lo + (hi - lo) * k / (n - 1) for k in range(n)]


def _sample_rows(np, joints, n: int = SAMPLES) -> dict:
    """joint -> sample_values(joint, n) as an array, the same floats (the same operations, in
    numpy for all the joints at once)."""
    ranges = [_sampled_range(j) for j in joints]
    out = {}
    wide = [k for k, (lo, hi) in enumerate(ranges) if not hi - lo < 1e-12]
    for k, (lo, hi) in enumerate(ranges):
        if hi - lo < 1e-12:
            out[joints[k].name] = np.array([lo])
    if wide:
        lo = np.array([ranges[k][0] for k in wide])[:, None]
        hi = np.array([ranges[k][1] for k in wide])[:, None]
        rows = lo + (hi - lo) * np.arange(n, dtype=float) / (n - 1)
        for k, row in zip(wide, rows):
            out[joints[k].name] = row
    return out


def _sampled_range(joint) -> tuple[float, float]:
    lo = hi = None
    if joint.type != "continuous" and joint.limit is not None:
        lo, hi = joint.limit.lower, joint.limit.upper
    if lo is None or hi is None or not (math.isfinite(lo) and math.isfinite(hi)) or hi < lo:
        lo, hi = (-math.pi, math.pi) if joint.type != "prismatic" else (0.0, 0.0)
    if joint.type != "prismatic":
        lo, hi = max(lo, -math.pi), min(hi, math.pi)
    return lo, hi


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


def _setup(robot, joints):
    """What both forms start from: the rest pose, its world transforms, the moving joints they place
    (mimic joints follow theirs), the names of those asked for and the links with a usable mass."""
    rest = robot.rest_pose()
    W = world_transforms(robot, rest)        # at all zeros, the zero configuration check keeps per robot
    movers = [j for j in robot.joints.values() if j.type in MOVING and j.mimic is None
              and j.parent in W and j.child in W]
    names = [j.name for j in movers if joints is None or j.name in joints]
    links = [link for link in robot.links.values() if link.name in W and link.inertial is not None
             and link.inertial.mass > 0 and math.isfinite(link.inertial.mass)]
    return rest, W, movers, names, links


def gravity_needs(robot, samples: int = SAMPLES, joints=None) -> list[Need]:
    """One :class:`Need` per moving, non-mimic joint (``joints``: only these), in file order.

    An ordinary robot takes the pure-Python form (``_gravity_needs_py``: importing numpy costs
    more than its whole sweep), a large one or one that is not a tree the numpy forms; they give
    the same needs and worst poses (tests/model/test_statics_pure.py)."""
    if len(robot.links) <= PURE_LINKS:
        out = _gravity_needs_py(robot, samples, joints)
        if out is not None:
            return out
    return _gravity_needs_np(robot, samples, joints)


# The pure form's bounds, in links and in torques evaluated (_gravity_needs_py counts them): about
# 30 ms of pure sweep, a 60-link chain or a 200-link star, where numpy's products cost a few ms
# but importing numpy some 130. Every robot of the corpus and of example-robot-data is within them.
PURE_LINKS = 1000
PURE_WORK = 100_000
TURN = 20


def _gravity_needs_py(robot, samples: int = SAMPLES, joints=None) -> list[Need] | None:
    """``gravity_needs`` in pure Python: the plain stream, every (joint, sample) torque of the joints
    each turn changes evaluated, by the same formulas as the numpy form (within an ulp or so of its
    stacked products). None when the model is not a tree, a number is not finite, or the sweep is
    larger than ``PURE_WORK``: the numpy form then."""
    rest = robot.rest_pose()
    order, via, _ = walk(robot)
    W = poses_at(robot, rest)[0]
    if W is None:
        return None
    parent_of = {}                         # link -> its parent link, over the joints among the links placed
    for j in robot.joints.values():
        if j.parent in W and j.child in W:
            if j.child in parent_of:
                return None                # a link hanging from two joints
            parent_of[j.child] = j.parent
    # the walk's order is a preorder from its roots; a tree's links each have one parent, placed before it
    seen = set()
    for link in order:
        up = parent_of.get(link)
        if (up is None) != (via[link] is None) or (up is not None and up not in seen):
            return None
        seen.add(link)
    movers = [j for j in robot.joints.values() if j.type in MOVING and j.mimic is None
              and j.parent in W and j.child in W]
    names = [j.name for j in movers if joints is None or j.name in joints]
    if not names:
        return []
    col = {robot.joints[n].child: k for k, n in enumerate(names)}        # child link -> column
    # the size of the sweep first (counts), then the columns each turn changes
    n_up, n_down = {}, dict.fromkeys(order, 0)
    for link in order:
        up = parent_of.get(link)
        n_up[link] = (link in col) + (n_up[up] if up is not None else 0)
    for link in reversed(order):
        up = parent_of.get(link)
        if up is not None:
            n_down[up] += n_down[link] + (link in col)
    followers = {j.mimic.joint for j in robot.joints.values() if j.mimic is not None}
    # in torques evaluated: a turn's sample (its rotation) costs about TURN of them, a whole pose 4 per link
    work = samples * sum(n_up[j.child] + n_down[j.child] + TURN + (4 * len(order) if j.name in followers else 0)
                         for j in movers)
    if work > PURE_WORK:
        return None
    above, turns = {}, {}                 # link -> the columns, and the movers' links, at or above it
    moved = {j.child for j in movers}
    below = {link: [] for link in moved}  # a mover's link -> the columns strictly below it
    for link in order:
        up = parent_of.get(link)
        mine = [col[link]] if link in col else []
        above[link] = mine + above[up] if up is not None else mine
        mine = [link] if link in moved else []
        turns[link] = mine + turns[up] if up is not None else mine
        if link in col:
            for t in turns[link]:
                if t != link:
                    below[t].append(col[link])
    own = _own_moments(robot, order, W)
    M, Q = _subtree_moments(order, parent_of, own)
    if not all(math.isfinite(m) for m in M.values()) or not all(math.isfinite(x) for q in Q.values() for x in q):
        return None
    frames = {j.name: _frame_py(j, W) for j in movers}
    P = [frames[n][0] for n in names]
    A = [frames[n][1] for n in names]
    if not all(math.isfinite(x) for v in P + A for x in v):
        return None
    prism = [robot.joints[n].type == "prismatic" for n in names]
    Mc = [M[robot.joints[n].child] for n in names]
    G = GRAVITY
    r_rest, B, t_rest = [], [], []
    for k in range(len(names)):
        (qx, qy, qz), (px, py, pz), (ax, ay, az), m = Q[robot.joints[names[k]].child], P[k], A[k], Mc[k]
        mx, my, mz = qx - m * px, qy - m * py, qz - m * pz               # M_i (C_i - p_i)
        r = 0.0 if prism[k] else G * (ay * mx - ax * my)
        r_rest.append(r)
        B.append((ay * mz - az * my, az * mx - ax * mz, ax * my - ay * mx))
        t_rest.append(abs(-G * az * m) if prism[k] else abs(r))
    best = list(t_rest)
    where: list = [(None, 0.0)] * len(names)

    def record(name, x, cols, T):
        for k, t in zip(cols, T):
            b = best[k]
            if t > b + 1e-9 * (1 + b):
                where[k] = (name, x)
            if t > b:
                best[k] = t

    for j in movers:
        values = sample_values(j, samples)
        up, down = above[j.child], below[j.child]
        if not up and not down:
            continue
        cols = up + down
        if j.name in followers:          # a mimic joint follows it: the whole pose
            for x in values:
                T = _torques_at(robot, order, via, parent_of, rest, W, own, frames, {j.name: x}, names, cols)
                record(j.name, x, cols, T)
            continue
        p0, a0 = frames[j.name]
        cj = j.child
        Qj, Mj = Q[cj], M[cj]
        for x in values:
            d = x - rest.get(j.name, 0.0)
            if j.type == "prismatic":
                R = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
                t = (d * a0[0], d * a0[1], d * a0[2])
            else:
                R = _axis_angle_rows(a0, math.sqrt(a0[0] * a0[0] + a0[1] * a0[1] + a0[2] * a0[2]), d)
                Rp = rotate(R, p0)
                t = (p0[0] - Rp[0], p0[1] - Rp[1], p0[2] - Rp[2])
            RQ = rotate(R, Qj)
            sx, sy = RQ[0] + Mj * t[0] - Qj[0], RQ[1] + Mj * t[1] - Qj[1]    # the moment change of the subtree
            T = [t_rest[k] if prism[k] else abs(r_rest[k] + G * (sx * A[k][1] - sy * A[k][0])) for k in up]
            if down:                     # gravity in the turned frames: g R = -G (R's last row)
                gx, gy, gz = -G * R[2][0], -G * R[2][1], -G * R[2][2]
                for k in down:
                    if prism[k]:
                        a = A[k]
                        T.append(abs((gx * a[0] + gy * a[1] + gz * a[2]) * Mc[k]))
                    else:
                        b = B[k]
                        T.append(abs(gx * b[0] + gy * b[1] + gz * b[2]))
            record(j.name, x, cols, T)
    out = []
    for k, n in enumerate(names):
        j = robot.joints[n]
        out.append(Need(n, best[k], t_rest[k], where[k][0], float(where[k][1]), effort_of(j),
                        "N" if j.type == "prismatic" else "N·m"))
    return out


def _own_moments(robot, links, W) -> dict:
    """link -> (mass, mass moment m c in the world) of the ``links`` with a usable mass."""
    out = {}
    for link in links:
        inertial = robot.links[link].inertial if link in robot.links else None
        if inertial is not None and inertial.mass > 0 and math.isfinite(inertial.mass):
            m = float(inertial.mass)
            c = compose(W[link], pose_T(inertial.origin))[1]
            out[link] = (m, (m * c[0], m * c[1], m * c[2]))
    return out


def _subtree_moments(order, parent_of, own) -> tuple[dict, dict]:
    """link -> the mass of its subtree, and -> the subtree's mass moment (sum of m c)."""
    M = dict.fromkeys(order, 0.0)
    Q = dict.fromkeys(order, (0.0, 0.0, 0.0))
    for link, (m, mc) in own.items():
        M[link], Q[link] = m, mc
    for link in reversed(order):          # children before their parents
        up = parent_of.get(link)
        if up is not None:
            M[up] += M[link]
            a, b = Q[up], Q[link]
            Q[up] = (a[0] + b[0], a[1] + b[1], a[2] + b[2])
    return M, Q


def _frame_py(j, W):
    """(origin, unit axis) of joint j in the world, from the link poses ``W``."""
    R, p = compose(W[j.parent], pose_T(j.origin))
    a = rotate(R, [float(v) for v in j.axis])
    n = math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])
    return p, ((a[0] / n, a[1] / n, a[2] / n) if n > 0 else a)


def _torques_at(robot, order, via, parent_of, rest, W, own, frames, moved, names, cols) -> list[float]:
    """|torque| of the columns ``cols`` with the joints ``moved`` off the rest pose (mimic joints
    following), from the whole pose: the links below the joints that move placed again, the others'
    poses (``W``), moments (``own``) and joint frames (``frames``) kept from the rest pose."""
    q = dict(rest)
    q.update(moved)
    W2, placed = poses_at(robot, q, W, rest)
    own = {**own, **_own_moments(robot, placed, W2)}
    M, Q = _subtree_moments(order, parent_of, own)
    G = GRAVITY
    out = []
    for k in cols:
        j = robot.joints[names[k]]
        (px, py, pz), (ax, ay, az) = _frame_py(j, W2) if j.parent in placed else frames[j.name]
        m, (qx, qy, qz) = M[j.child], Q[j.child]
        out.append(abs(-G * az * m) if j.type == "prismatic" else abs(G * (ay * (qx - m * px) - ax * (qy - m * py))))
    return out


def _gravity_needs_np(robot, samples: int = SAMPLES, joints=None) -> list[Need]:
    """``gravity_needs`` with numpy: for a large robot or one that is not a tree.

    The masses and moments of every subtree are summed once, bottom-up; moving one joint changes
    only the torques of the joints above it (the moment of its subtree turns) and below it (gravity
    turns in their frames), the others keep their rest value; of those, only the ones that can
    matter are evaluated (``_Sweep``; the module's doc gives the cost). A model that is not a tree
    (a link hanging from two joints) takes the dense form (``_gravity_needs_dense``)."""
    import numpy as np

    rest, W, movers, names, links = _setup(robot, joints)
    if not names:
        return []
    tree = _preorder(robot, W)
    if tree is None:
        return _gravity_needs_dense(robot, samples, joints)
    order, pos, parent, levels, end = tree
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
    P, A = frames.rows(names)
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
    vals = _sample_rows(np, movers, samples)
    turned = [j for j in movers if j.type != "prismatic" and j.name not in followers and len(vals[j.name]) == samples]
    alone = _alone(robot, movers, names, pos, parent, end, {j.name for j in turned})
    # of those, one turning about the vertical: its axis's x and y are 0, so each product of its torque
    # (at rest or turned) is by 0 and its turns change nothing; no rotations for it
    upright = set()
    if alone:
        a = frames.rows(alone)[1]
        upright = {n for n, flat in zip(alone, ((a[:, 0] == 0) & (a[:, 1] == 0)).tolist()) if flat}
    if upright:
        alone = [n for n in alone if n not in upright]
        turned = [j for j in turned if j.name not in upright]
    R_all, R_of = None, {}
    if turned:          # every revolute joint's sampled rotations at once
        R_all = _rotations(frames.rows([j.name for j in turned])[1],
                           np.array([vals[j.name] for j in turned])
                           - np.array([rest.get(j.name, 0.0) for j in turned])[:, None])
        R_of = {j.name: k for k, j in enumerate(turned)}
    if alone:
        _turn_alone(np, robot, alone, names, vals, frames, pos, R_all, R_of, Qtot, Mtot, prism, t_rest, r_rest,
                    A, best, where)
    done = upright.union(alone)
    deep = [j for j in movers if j.name not in done]
    if deep:
        _Sweep(np, robot, rest, W, names, links, deep, followers, vals, frames, R_all, R_of, pos, parent, levels, end,
               ci, Qtot, Mtot, M, A, B, prism, t_rest, r_rest, torques, best, where).run()
    out = []
    best_of, rest_of = best.tolist(), t_rest.tolist()     # the floats float() of each gives, in one call
    for k, n in enumerate(names):
        j = robot.joints[n]
        out.append(Need(n, best_of[k], rest_of[k], where[k][0], float(where[k][1]), effort_of(j),
                        "N" if j.type == "prismatic" else "N·m"))
    return out


def _alone(robot, movers, names, pos, parent, end, turned) -> list[str]:
    """The turned joints whose torques no other joint changes and that change no other joint's: a
    leaf link's joint with no moving joint above it (a star's spokes, wheels on a fixed base). Their
    turns commute with every other, so they are taken together (_turn_alone)."""
    asked = set(names)
    mover_at = set()
    for m in movers:
        mover_at.add(pos[m.child])
    above = [False] * len(parent)            # a moving joint somewhere above this place (preorder: parents first)
    # the arrays as Python ints once: a numpy scalar per place and joint costs more than the test
    for place, up in enumerate(parent.tolist()):
        above[place] = up >= 0 and (above[up] or up in mover_at)
    end = end.tolist()
    out = []
    for j in movers:
        cj = pos[j.child]
        if j.name in asked and j.name in turned and end[cj] == cj + 1 and not above[cj]:
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
    p0 = frames.rows(alone)[0]
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


class _Sweep:
    """gravity_needs' turns of the joints that are not alone, each (joint, sample) torque evaluated
    only where it can change a maximum or a worst pose.

    Joint k's worst pose is the last torque of its stream (the moving joints in file order, each
    over its samples, from its rest torque) that beats the running maximum by more than
    1e-9 (1 + maximum); its torque is the stream's maximum V_k. A torque t is left out (skipped) only
    when an upper bound u >= t, float rounding included, shows one of:

    - u <= the rest torque: t never beats the running maximum and never raises it;
    - u < L_k, a cut a margin below a lower bound on V_k (the rest torque, k's own turn, ...).

    Replaying the evaluated torques alone, from the rest torque, gives the whole stream's maximum
    and worst pose when the rest torque is >= L_k (every skipped torque is then of the first kind),
    or when the first evaluated torque >= L_k beats L_k + 1e-9 (1 + L_k): before it the running
    maximum is below L_k in both streams, so both take it, and after it every skipped torque is
    below the running maximum. A joint for which neither holds (a near tie at the cut) is replayed
    with L_k = its rest torque. Torques known to be equal to the bit are counted once, the first.

    The bounds, with r_k, A_k, B_k as in gravity_needs and s the moment change of the turned subtree:
    a joint j at or below revolute k gives |r_k + G (s_x A_k,y - s_y A_k,x)| <= |r_k| + G |A_k,xy| rho_j
    (rho_j: the largest horizontal |s| over j's samples); a joint j above k turns gravity to g' and
    gives |g' . B_k| <= |g . B_k| + |B_k| delta_j (delta_j: the largest |g' - g|; A_k M_k for a
    prismatic k). Whole joints are skipped by the least cut over the joints above (a prefix minimum)
    or below (a subtree minimum), so a joint that changes nothing that matters costs O(1). A
    vertical turn (or a slide) leaves g' = (0, 0, -G) exactly: its torques below are one constant per
    joint, counted at the first such joint above. The torques kept are computed by the same numpy
    expressions, on the same rows for the products a BLAS call makes, so they are the same to the bit.
    """

    def __init__(self, np, robot, rest, W, names, links, deep, followers, vals, frames, R_all, R_of, pos, parent,
                 levels, end, ci, Qtot, Mtot, M, A, B, prism, t_rest, r_rest, torques, best, where):
        self.np, self.robot, self.rest, self.W, self.names, self.links = np, robot, rest, W, names, links
        self.deep, self.followers, self.vals, self.frames = deep, followers, vals, frames
        self.R_all, self.R_of, self.pos, self.parent, self.levels, self.end, self.ci = \
            R_all, R_of, pos, parent, levels, end, ci
        self.Qtot, self.Mtot, self.M, self.A, self.B, self.prism = Qtot, Mtot, M, A, B, prism
        self.t_rest, self.r_rest, self.torques, self.best, self.where = t_rest, r_rest, torques, best, where
        self.g = np.array([0.0, 0.0, -GRAVITY])
        deep_names = {j.name for j in deep}
        # the columns still to do (an alone joint's only moves with its own turn, done)
        self.active = np.array([n in deep_names for n in names])
        self.by_tin = np.argsort(ci, kind="stable")
        self.tin_sorted = ci[self.by_tin]
        self.up = _asked_above(robot, names, None, pos, parent) if len(levels) <= 64 else None
        self.full = None
        self.cj = np.array([pos[j.child] for j in deep], dtype=np.int64)
        self.Rs, self.ts = [None] * len(deep), [None] * len(deep)   # the exact rotations and translations
        self.plain = len(deep) * len(levels) < self.PLAIN
        if not self.plain:
            self._bounds()

    def _bounds(self):
        """Per turned joint: rho, delta, whether its turn is vertical; per column its rest-pose
        lower bound on the maximum and the constant of the vertical turns above it."""
        np, G = self.np, GRAVITY
        deep, n = self.deep, len(self.deep)
        rho = np.full(n, np.inf)
        delta = np.full(n, np.inf)
        vertical = np.zeros(n, dtype=bool)
        self_lb = np.full(len(self.names), -np.inf)
        k_of = {name: k for k, name in enumerate(self.names)}
        free = [q for q, j in enumerate(deep) if j.name not in self.followers]
        turned = [q for q in free if deep[q].name in self.R_of]
        rest_q = [q for q in free if deep[q].name not in self.R_of]
        groups = []
        if turned:
            R = self.R_all[[self.R_of[deep[q].name] for q in turned]]
            p0 = np.array([self.frames[deep[q].name][0] for q in turned])
            t = p0[:, None, :] - (R @ p0[:, None, :, None])[..., 0]
            groups.append((turned, R, t, p0))
        if rest_q:
            S = max(len(self.vals[deep[q].name]) for q in rest_q)
            Rl, tl, pl = [], [], []
            for q in rest_q:
                j = deep[q]
                p0, a0 = self.frames[j.name]
                d = np.asarray(self.vals[j.name]) - self.rest.get(j.name, 0.0)
                if j.type == "prismatic":
                    R = np.broadcast_to(np.eye(3), (len(d), 3, 3))
                    t = d[:, None] * a0
                else:
                    R = _rotations(a0[None, :], d[None, :])[0]
                    t = p0 - R @ p0
                self.Rs[q], self.ts[q] = R, t
                pad = S - len(d)                    # the last sample again: same maxima
                Rl.append(np.concatenate([R, np.repeat(R[-1:], pad, 0)]) if pad else R)
                tl.append(np.concatenate([t, np.repeat(t[-1:], pad, 0)]) if pad else t)
                pl.append(p0)
            groups.append((rest_q, np.array(Rl), np.array(tl), np.array(pl)))
        for qs, R, t, p0 in groups:
            qs = np.array(qs)
            cj = self.cj[qs]
            Qj, Mj = self.Qtot[cj], self.Mtot[cj]
            shift = np.einsum("nc,nsrc->nsr", Qj, R) + Mj[:, None, None] * t - Qj[:, None, :]
            err = 1e-11 * (3 * np.abs(Qj).sum(1) + Mj * (3 * np.abs(p0).sum(1) + np.abs(t).sum(2).max(1)))
            m0 = np.abs(shift[:, :, 0]).max(1) + err
            m1 = np.abs(shift[:, :, 1]).max(1) + err
            rho[qs] = np.hypot(m0, m1)
            row = R[:, :, 2, :]
            delta[qs] = G * np.sqrt(((row - np.array([0.0, 0.0, 1.0])) ** 2).sum(2)).max(1)
            vertical[qs] = ((row[..., 0] == 0) & (row[..., 1] == 0) & (row[..., 2] == 1)).all(1)
            ks = np.array([k_of.get(deep[q].name, -1) for q in qs])
            i = np.flatnonzero(ks >= 0)
            i = i[~self.prism[ks[i]]]
            if len(i):               # a joint's own turn: about a lower bound on its maximum (the cut is checked)
                k, r, Ak = ks[i], self.r_rest[ks[i]][:, None], self.A[ks[i]]
                v = np.abs(r + G * (shift[i, :, 0] * Ak[:, 1:2] - shift[i, :, 1] * Ak[:, 0:1])).max(1)
                scale = np.abs(r[:, 0]) + G * np.hypot(Ak[:, 0], Ak[:, 1]) * rho[qs[i]]
                self_lb[k] = np.maximum(self_lb[k], v - 1e-10 * scale)
        self.rho, self.delta, self.vertical = rho, delta, vertical
        # the torque under a vertical turn above (exactly these products: g' has two zeros)
        self.c_rest = np.abs(np.where(self.prism, (self.g @ self.A.T) * self.M, self.g @ self.B.T))
        self.W_k = np.where(self.prism, np.linalg.norm(self.A, axis=1) * self.M, np.linalg.norm(self.B, axis=1))
        self.a_h = GRAVITY * np.hypot(self.A[:, 0], self.A[:, 1])
        # the first vertical turn strictly above each column (prefix minimum down the tree)
        parent = self.parent.tolist()
        own = [-1] * len(parent)
        for q in np.flatnonzero(vertical).tolist():
            own[int(self.cj[q])] = q
        first_v = [-1] * len(parent)
        for c in range(len(parent)):              # preorder: a parent before its children
            up = parent[c]
            f = first_v[up] if up >= 0 else -1
            first_v[c] = own[c] if f < 0 else f
        up = self.parent[self.ci]
        f = np.where(up >= 0, np.array(first_v)[np.maximum(up, 0)], -1)
        f[~self.active] = -1
        self.ev_at = {}
        for k, q in zip(np.flatnonzero(f >= 0).tolist(), f[f >= 0].tolist()):
            self.ev_at.setdefault(q, []).append(k)
        self.V_lo = np.maximum(np.maximum(self.t_rest, self_lb), np.where(f >= 0, self.c_rest, -np.inf))

    PLAIN = 4096        # joints x depth below which every torque is evaluated: fewer than the bounds cost
    CUT = 1e-6          # L_k = (the lower bound on V_k) - CUT (1 + it): far below the 1e-9 of a tie

    def run(self):
        np = self.np
        if self.plain:
            self._pass(None, self.active)
            return
        # only the bounds must be rigorous: a cut above V_k leaves no evaluated torque over it, and the check fails
        L = np.where(self.active, self.V_lo - self.CUT * (1 + self.V_lo), np.inf)
        first = self._pass(L, self.active)
        bad = self.active & (self.t_rest < L) & ~(first > L + 1e-9 * (1 + L))
        if bad.any():          # a near tie at the cut: these columns again, every torque above rest kept
            for k in np.flatnonzero(bad).tolist():
                self.best[k] = self.t_rest[k]
                self.where[k] = (None, 0.0)
            self._pass(np.where(bad, self.t_rest, np.inf), bad)

    def _pass(self, L, active):
        """Every turn's torques that may matter on the columns ``active``, replayed; each column's first
        torque at or above its cut ``L`` (None: every torque, without cuts)."""
        np, G = self.np, GRAVITY
        if L is None:
            for q, j in enumerate(self.deep):
                self._turn_all(q, j, active, None, None)
            return None
        parent, ci, t_rest = self.parent.tolist(), self.ci, self.t_rest
        Lc = np.maximum(L, t_rest) * (1 - 1e-10)
        with np.errstate(divide="ignore", invalid="ignore"):
            kappa = np.where(active & ~self.prism & (self.a_h > 0), (Lc - np.abs(self.r_rest)) / self.a_h, np.inf)
            tau = np.where(active & (self.W_k > 0), (Lc - self.c_rest) / self.W_k, np.inf)
        kappa = np.where(np.isnan(kappa), -np.inf, kappa)
        tau = np.where(np.isnan(tau), -np.inf, tau)
        places = len(parent)
        k_at, t_at = [math.inf] * places, [math.inf] * places
        for k, c in enumerate(ci.tolist()):
            k_at[c], t_at[c] = float(kappa[k]), float(tau[k])
        k_min = [0.0] * places                      # least kappa at or above each place
        for c in range(places):
            up = parent[c]
            k_min[c] = min(k_at[c], k_min[up]) if up >= 0 else k_at[c]
        t_sub = list(t_at)                          # least tau at or below each place
        t_strict = [math.inf] * places              # ... strictly below
        for c in range(places - 1, -1, -1):         # reversed preorder: children before their parent
            up = parent[c]
            if up >= 0:
                if t_sub[c] < t_sub[up]:
                    t_sub[up] = t_sub[c]
                if t_sub[c] < t_strict[up]:
                    t_strict[up] = t_sub[c]
        first = np.full(len(t_rest), np.nan)
        for q, j in enumerate(self.deep):
            cj = int(self.cj[q])
            values = self.vals[j.name]
            cols = self.ev_at.get(q)
            if cols:
                cols = np.array([k for k in cols if active[k]], dtype=np.int64)
                if len(cols):
                    self._record(j.name, cols, self.c_rest[cols][None, :], values[:1], L, first)
            if j.name in self.followers:
                self._turn_all(q, j, active, L, first)
                continue
            reach = self.rho[q] * (1 + 1e-9)
            above = below = None
            if reach >= k_min[cj]:
                above = self._above(cj)
                above = above[kappa[above] <= reach]
            if not self.vertical[q] and (self.delta[q] + 1e-11 * G) * (1 + 1e-9) >= t_strict[cj]:
                below = self._below(cj)
            if (above is None or not len(above)) and (below is None or not len(below)):
                continue
            T, idx = self._turn(q, j, above, below)
            keep = active[idx]
            if not keep.all():
                T, idx = T[:, keep], idx[keep]
            if len(idx):
                self._record(j.name, idx, T, values, L, first)
        return first

    def _turn_all(self, q, j, active, L, first):
        """Joint j's turn on every asked joint above and below it, replayed (a joint a mimic joint
        follows: the whole pose, the slow way)."""
        np = self.np
        cj = int(self.cj[q])
        values = self.vals[j.name]
        if j.name in self.followers:
            idx = np.concatenate([self._above(cj), self._below(cj)])
            idx = idx[active[idx]]
            if not len(idx):
                return
            if self.full is None:
                self.full = _FullTree(self.robot, self.rest, self.W, self.names, self.links, self.pos,
                                      self.parent, self.levels, self.M, self.prism)
            T = np.array([self.full.torques(j.name, x, self.torques) for x in values])[:, idx]
        else:
            above, below = self._above(cj), self._below(cj)
            if not len(above) and not len(below):
                return
            T, idx = self._turn(q, j, above, below)
        self._record(j.name, idx, T, values, L, first)

    def _above(self, cj):
        """The asked joints whose child is at or above place cj."""
        np = self.np
        if self.up is not None:
            return np.array(self.up(cj), dtype=np.int64)
        return np.flatnonzero((self.ci <= cj) & (self.end[self.ci] > cj))

    def _below(self, cj):
        """The asked joints strictly below place cj (gravity_needs' order: by their child's place)."""
        np = self.np
        if self.end[cj] > cj + 1:
            lo, hi = np.searchsorted(self.tin_sorted, [cj + 1, self.end[cj]])
            return self.by_tin[lo:hi]
        return self.by_tin[:0]

    def _turn(self, q, j, above, below):
        """Joint j's torques over its samples on the asked joints ``above`` (at or above it; any rows)
        and ``below`` (all of them: a BLAS product's bits depend on its shape)."""
        np, G, g = self.np, GRAVITY, self.g
        p0, a0 = self.frames[j.name]
        cj = int(self.cj[q])
        if self.Rs[q] is not None:
            R, t = self.Rs[q], self.ts[q]
        elif j.type == "prismatic":
            d = self.vals[j.name] - self.rest.get(j.name, 0.0)
            R = np.broadcast_to(np.eye(3), (len(d), 3, 3))
            t = d[:, None] * a0
        else:
            if j.name in self.R_of:
                R = self.R_all[self.R_of[j.name]]
            else:
                R = _rotations(a0[None, :], (self.vals[j.name] - self.rest.get(j.name, 0.0))[None, :])[0]
            t = p0 - R @ p0
        parts, idx = [], []
        if above is not None and len(above):
            shift = self.Qtot[cj] @ np.swapaxes(R, 1, 2) + self.Mtot[cj] * t - self.Qtot[cj]
            parts.append(np.abs(np.where(self.prism[above], self.t_rest[above],
                                         self.r_rest[above] + G * (np.outer(shift[:, 0], self.A[above, 1])
                                                                   - np.outer(shift[:, 1], self.A[above, 0])))))
            idx.append(above)
        if below is not None and len(below):
            g_below = g @ R                                        # gravity in the turned frames
            parts.append(np.abs(np.where(self.prism[below], (g_below @ self.A[below].T) * self.M[below],
                                         g_below @ self.B[below].T)))
            idx.append(below)
        if len(parts) == 1:
            return parts[0], idx[0]
        return np.concatenate(parts, axis=1), np.concatenate(idx)

    def _record(self, name, idx, T, values, L, first):
        """Replay the torques T (samples x columns idx) into the running maxima and worst poses (a
        later torque takes the pose only beyond 1e-9 (1 + maximum)), and note each column's first
        torque at or above its cut."""
        np = self.np
        best, where = self.best, self.where
        b = best[idx]
        top = T.max(axis=0)
        gain = top > b + 1e-9 * (1 + b)       # only these columns move their worst pose
        if gain.any():
            cols, Tg = idx[gain], T[:, gain]
            bg = best[cols]
            for x, t in zip(values, Tg):
                better = t > bg + 1e-9 * (1 + bg)
                for k in cols[better]:
                    where[k] = (name, x)
                bg = np.maximum(bg, t)
        best[idx] = np.maximum(b, top)
        if first is None:
            return
        fresh = np.isnan(first[idx])
        if fresh.any():
            at = np.flatnonzero(fresh)
            hit = T[:, at] >= L[idx[at]]
            some = hit.any(axis=0)
            if some.any():
                s = hit.argmax(axis=0)[some]
                first[idx[at[some]]] = T[s, at[some]]


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
            here = pos[link] = len(order)
            order.append(link)
            parent.append(up)
            depth.append(dep)
            kids = children.get(link)
            if kids:                    # (most links are leaves: no generator for them)
                stack.extend((jj.child, here, dep + 1) for jj in reversed(kids) if jj.child in W)
    if len(order) != len(W):
        return None
    parent = np.array(parent, dtype=np.int64)
    depth = np.array(depth, dtype=np.int64)
    by_depth = np.argsort(-depth, kind="stable")
    cuts = np.flatnonzero(np.diff(depth[by_depth])) + 1
    levels = [by_depth[a:b] for a, b in zip([0, *cuts.tolist()], [*cuts.tolist(), len(by_depth)])]
    size = _subtree_sums(np.ones(len(order)), parent, levels).astype(np.int64)
    end = np.arange(len(order)) + size
    return order, pos, parent, levels, end


class _Frames:
    """joint -> (its origin, its unit axis) in the world: rows of two arrays, a joint's made when it
    is asked for (a view per joint is 40,000 objects in a 20,000-link star); ``rows`` gives many
    joints' at once, the same floats as stacking their rows."""

    __slots__ = ("index", "origins", "axes")

    def __init__(self, names, origins, axes):
        self.index = {n: k for k, n in enumerate(names)}
        self.origins, self.axes = origins, axes

    def __getitem__(self, name):
        k = self.index[name]
        return self.origins[k], self.axes[k]

    def rows(self, names):
        """(origins, axes) of the joints ``names`` (at least one), one row each."""
        k = [self.index[n] for n in names]
        return self.origins[k], self.axes[k]


def _joint_frames(np, robot, W, names) -> dict | _Frames:
    """joint -> (its origin, its unit axis) in the world, from the link poses ``W``."""
    if not names:
        return {}
    # every joint's products at once: stacked products give each joint's numbers to the bit
    joints = [robot.joints[n] for n in names]
    F = stack_by_identity([W[j.parent] for j in joints], (4, 4)) @ pose_stack(j.origin for j in joints)
    axes = (F[:, :3, :3] @ stack_by_identity([j.axis for j in joints], (3, 1)))[:, :, 0]
    norms = norm_rows(np, axes)[:, None]
    unit = np.where(norms > 0, axes / np.where(norms > 0, norms, 1.0), axes)
    return _Frames(names, F[:, :3, 3], unit)


def _subtree_sums(values, parent, levels):
    """``values`` (one row per link place) summed over each link's subtree, deepest level first."""
    import numpy as np

    out = np.array(values, dtype=float, copy=True)
    if len(levels) * 8 > len(out):        # deep and narrow: one Python add per link, in np.add.at's order
        rows, up = out.tolist(), parent.tolist()
        flat = out.ndim == 1
        for c in np.concatenate(levels).tolist():
            p = up[c]
            if p >= 0:
                if flat:
                    rows[p] += rows[c]
                else:
                    rows[p] = [a + b for a, b in zip(rows[p], rows[c])]
        return np.array(rows, dtype=float).reshape(out.shape)
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

    rest, W, movers, names, links = _setup(robot, joints)
    if not names:
        return []
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
