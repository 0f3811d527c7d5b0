"""gravity_needs' numpy form (model/statics.py) against the plain algorithm, kept here as the reference: every
(joint, sample) torque evaluated, O(joints x depth) on a deep tree. gravity_needs skips the torques
that cannot change a maximum or a worst pose; the results must be the same (torques within 1e-12
relative, the same worst pose) on random trees, the bundled robot, the corpus and
example-robot-data. (An ordinary robot takes the pure-Python form, which
tests/model/test_statics_pure.py compares with this one.)"""

from __future__ import annotations

import math
import random

import pytest

from helpers import ERD, ROOT, corpus_model, corpus_robots, cpu_time
from myrabot_desc.model import statics as S
from myrabot_desc.model.kinematics import _norms
from myrabot_desc.model.loader import load_robot
from myrabot_desc.model.statics import _gravity_needs_np as gravity_needs

np = pytest.importorskip("numpy")


# ------------------------------------------------------------------ the reference: every torque evaluated
def reference_needs(robot, samples: int = S.SAMPLES, joints=None) -> list[S.Need]:
    """One :class:`Need` per moving, non-mimic joint (``joints``: only these), in file order.

    Linear in the tree's size for a wide tree, O(joints x depth) for a deep one: the masses and
    moments of every subtree are summed once, bottom-up; moving one joint changes only the torques
    of the joints above it (the moment of its subtree turns) and below it (gravity turns in their
    frames), the others keep their rest value. A model that is not a tree (a link hanging from two
    joints) takes the dense form (``_gravity_needs_dense``)."""
    import numpy as np

    rest = robot.rest_pose()
    W = S.world_transforms(robot, rest)
    movers = [j for j in robot.joints.values() if j.type in S.MOVING and j.mimic is None
              and j.parent in W and j.child in W]
    names = [j.name for j in movers if joints is None or j.name in joints]
    if not names:
        return []
    tree = _preorder(robot, W)
    if tree is None:
        return S._gravity_needs_dense(robot, samples, joints)
    order, pos, parent, levels, end = tree
    links = [link for link in robot.links.values() if link.name in W and link.inertial is not None
             and link.inertial.mass > 0 and math.isfinite(link.inertial.mass)]
    L = len(order)
    own_m = np.zeros(L)
    own_mc = np.zeros((L, 3))
    if links:
        k = np.array([pos[link.name] for link in links])
        own_m[k] = [link.inertial.mass for link in links]
        origins = S.pose_stack(link.inertial.origin for link in links)
        c = (np.array([W[link.name] for link in links]) @ origins)[:, :3, 3]
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
    g = np.array([0.0, 0.0, -S.GRAVITY])
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
    r_rest = np.where(prism, 0.0, S.GRAVITY * (A[:, 1] * (Q[:, 0] - M * P[:, 0]) - A[:, 0] * (Q[:, 1] - M * P[:, 1])))
    B = np.cross(A, Q - M[:, None] * P)
    by_tin = np.argsort(ci, kind="stable")           # asked joints by their child's place in preorder
    tin_sorted = ci[by_tin]
    up = _asked_above(robot, names, order, pos, parent) if len(levels) <= 64 else None   # shallow: walk up
    full = None
    vals = {j.name: sample_values(j, samples) for j in movers}
    turned = [j for j in movers if j.type != "prismatic" and j.name not in followers and len(vals[j.name]) == samples]
    R_of = {}
    if turned:          # every revolute joint's sampled rotations at once
        R_all = S._rotations(np.array([frames[j.name][1] for j in turned]),
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
                full = S._FullTree(robot, rest, W, names, links, pos, parent, levels, M, prism)
            T = np.array([full.torques(j.name, x, torques) for x in values])[:, idx]
        else:
            p0, a0 = frames[j.name]
            d = np.asarray(values) - rest.get(j.name, 0.0)
            if j.type == "prismatic":
                R = np.broadcast_to(np.eye(3), (len(d), 3, 3))
                t = d[:, None] * a0
            else:
                R = R_all[R_of[j.name]] if j.name in R_of else S._rotations(a0[None, :], d[None, :])[0]
                t = p0 - R @ p0
            shift = Qtot[cj] @ np.swapaxes(R, 1, 2) + Mtot[cj] * t - Qtot[cj]   # the turned subtree's moment change
            T_above = np.abs(np.where(prism[above], t_rest[above],
                                      r_rest[above] + S.GRAVITY * (np.outer(shift[:, 0], A[above, 1])
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
        out.append(S.Need(n, float(best[k]), float(t_rest[k]), where[k][0], float(where[k][1]), S.effort_of(j),
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
                        r_rest[K][:, None] + S.GRAVITY * (shift[:, :, 0] * A[K, 1][:, None]
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




def sample_values(joint, n: int = S.SAMPLES) -> list[float]:
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
    F = np.array([W[j.parent] for j in joints]) @ S.pose_stack(j.origin for j in joints)
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


# ------------------------------------------------------------------ comparing
def same(new, old, what=""):
    assert [n.joint for n in new] == [n.joint for n in old], what
    for a, b in zip(new, old):
        assert a.torque == b.torque or abs(a.torque - b.torque) <= 1e-12 * max(abs(a.torque), abs(b.torque)), \
            (what, a, b)
        assert a.at_rest == b.at_rest, (what, a, b)
        assert (a.pose_joint, a.pose_value) == (b.pose_joint, b.pose_value), (what, a, b)
        assert (a.effort, a.unit) == (b.effort, b.unit), (what, a, b)


def compare(robot, what="", joints=None):
    """gravity_needs as it runs, and with the bounds on however small the tree, against the reference."""
    old = reference_needs(robot, joints=joints)
    same(gravity_needs(robot, joints=joints), old, what)
    plain, S._Sweep.PLAIN = S._Sweep.PLAIN, 0
    try:
        same(gravity_needs(robot, joints=joints), old, f"{what} (bounds)")
    finally:
        S._Sweep.PLAIN = plain


MIMIC = 0.08           # the share of mimic joints
AXES = ["0 0 1", "0 1 0", "1 0 0", "0 0 -1", "1 1 0", "0.3 -0.2 1", "1 2 3", "0 0.001 1"]


def random_urdf(rng: random.Random, n: int, shape: str) -> str:
    """n links: a chain, a star, a chain with branches or a random tree; every kind of moving joint
    (and fixed ones), vertical, horizontal and tilted axes, with and without rpy, limits of every
    kind, zero and missing masses, mimic joints."""
    out = ['<robot name="r">']

    def link(i):
        m = rng.choice([0.0, 0.0, 0.5, 1.0, 1.0, 2.5, rng.uniform(0.01, 5)])
        if rng.random() < 0.15:
            return f'<link name="l{i}"/>'
        xyz = rng.choice(["0 0 0", "0.05 0 0", f"{rng.uniform(-0.1, 0.1):.3f} {rng.uniform(-0.1, 0.1):.3f} 0.02"])
        return (f'<link name="l{i}"><inertial><origin xyz="{xyz}"/><mass value="{m}"/><inertia ixx="1e-3" ixy="0" '
                'ixz="0" iyy="1e-3" iyz="0" izz="1e-3"/></inertial></link>')

    out.append(link(0))
    movers = []
    for i in range(1, n):
        if shape == "chain":
            up = i - 1
        elif shape == "star":
            up = 0
        elif shape == "branchy":
            up = i - 1 if i % 4 else max(0, i - rng.randint(2, 6))
        else:
            up = rng.randrange(i)
        kind = rng.choice(["revolute", "revolute", "continuous", "prismatic", "fixed"])
        axis = rng.choice(AXES)
        rpy = rng.choice(["0 0 0", "0 0 0", "0 0 0.3", f"{rng.uniform(-1, 1):.2f} {rng.uniform(-1, 1):.2f} 0"])
        xyz = rng.choice(["0.01 0 0.01", "0.1 0 0", "0 0 0.2", f"{rng.uniform(-0.3, 0.3):.2f} 0.05 0.1"])
        lim = rng.choice(['<limit lower="-1" upper="1" effort="10" velocity="1"/>',
                          '<limit lower="-3.14159" upper="3.14159" effort="0" velocity="1"/>',
                          '<limit lower="0.2" upper="0.2" effort="5" velocity="1"/>',
                          '<limit lower="0.5" upper="2.0" effort="5" velocity="1"/>',
                          '<limit lower="-0.1" upper="0.3" effort="5" velocity="1"/>',
                          '<limit effort="3" velocity="1"/>', ""])
        if kind in ("revolute", "prismatic") and not lim:
            lim = '<limit lower="-1" upper="1" effort="10" velocity="1"/>'
        mimic = ""
        if kind != "fixed" and movers and rng.random() < MIMIC:
            mimic = f'<mimic joint="{rng.choice(movers)}" multiplier="{rng.choice([1, -1, 0.5])}" offset="0.1"/>'
        elif kind != "fixed":
            movers.append(f"j{i}")
        out.append(link(i))
        out.append(f'<joint name="j{i}" type="{kind}"><parent link="l{up}"/><child link="l{i}"/>'
                   f'<origin xyz="{xyz}" rpy="{rpy}"/><axis xyz="{axis}"/>{lim}{mimic}</joint>')
    out.append("</robot>")
    return "\n".join(out)


def planar_urdf(n: int, axis: str, spread: bool) -> str:
    """A chain whose joints all turn about one horizontal axis: the torques of a joint tie between
    its own turn and every turn above it (the worst pose is decided by the tie-breaking)."""
    inertial = ('<inertial><mass value="0.1"/><inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/>'
                '</inertial>')
    out = ['<robot name="p">', f'<link name="l0">{inertial}</link>']
    for i in range(1, n):
        lim = f'<limit lower="{-0.5 - 0.1 * (i % 3) if spread else -1}" upper="1" effort="1" velocity="1"/>'
        out.append(f'<link name="l{i}">{inertial}</link>')
        out.append(f'<joint name="j{i}" type="revolute"><parent link="l{i - 1}"/><child link="l{i}"/>'
                   f'<origin xyz="0.1 0 0"/><axis xyz="{axis}"/>{lim}</joint>')
    return "\n".join(out + ["</robot>"])


@pytest.mark.parametrize("shape", ["chain", "star", "branchy", "random"])
def test_random_trees_as_before(tmp_path, shape):
    rng = random.Random(shape)
    for trial in range(40):
        n = rng.choice([2, 3, 5, 12, 30, 80]) if trial % 10 else 150
        f = tmp_path / f"{shape}{trial}.urdf"
        f.write_text(random_urdf(rng, n, shape))
        r = load_robot(str(f))
        compare(r, f"{shape} {trial}")
        if trial % 5 == 0:
            some = {j for j in r.joints if rng.random() < 0.5}
            compare(r, f"{shape} {trial} some", joints=some)


@pytest.mark.parametrize("axis", ["0 1 0", "1 0 0", "0 0 1", "0 0.6 0.8"])
@pytest.mark.parametrize("spread", [False, True])
def test_planar_chains_tie_as_before(tmp_path, axis, spread):
    f = tmp_path / "p.urdf"
    f.write_text(planar_urdf(60, axis, spread))
    compare(load_robot(str(f)), axis)


def _tree_urdf(kind: str, n: int) -> str:
    """bench/gen_tree.py's chain or star of n links."""
    import sys

    sys.path.insert(0, str(ROOT / "bench"))
    try:
        from gen_tree import tree_urdf
    finally:
        sys.path.remove(str(ROOT / "bench"))
    return tree_urdf(kind, n)


def test_generated_chain_and_star_as_before(tmp_path):
    for kind, n in (("chain", 400), ("star", 400)):
        f = tmp_path / f"{kind}.urdf"
        f.write_text(_tree_urdf(kind, n))
        compare(load_robot(str(f)), kind)


def test_deep_chain_is_not_joints_times_depth(tmp_path):
    """The 5,000-link chain: some 3 x 10^8 (joint, sample) torques for the plain algorithm (3 s and more of
    CPU), about 0.1 s here with its rest-pose transforms (made once per robot, as check does);
    the limit leaves room for a loaded machine."""
    from myrabot_desc.model.kinematics import world_transforms

    f = tmp_path / "chain.urdf"
    f.write_text(_tree_urdf("chain", 5000))
    r = load_robot(str(f))
    world_transforms(r)
    with cpu_time() as t:
        needs = gravity_needs(r)
    assert len(needs) == 4999 and t.seconds < 1.0
    assert all(n.torque == 0.0 and n.pose_joint is None for n in needs)      # vertical axes: no torque


@pytest.mark.parametrize("cut", [0.0, 1e-10, 1e-3])
def test_any_cut_as_before(tmp_path, monkeypatch, cut):
    """The cut below each joint's maximum only decides how many torques are evaluated: at the
    maximum's lower bound itself most joints fall back to a second pass, far below it few do."""
    monkeypatch.setattr(S._Sweep, "CUT", cut)
    rng = random.Random(int(cut * 1e12) + 3)
    for trial in range(12):
        f = tmp_path / f"t{trial}.urdf"
        f.write_text(random_urdf(rng, rng.choice([5, 30, 80]), ["chain", "branchy", "random"][trial % 3]))
        compare(load_robot(str(f)), f"cut {cut} {trial}")
    for axis in ("0 1 0", "0 0.6 0.8"):
        f = tmp_path / "p.urdf"
        f.write_text(planar_urdf(40, axis, True))
        compare(load_robot(str(f)), f"cut {cut} planar {axis}")


def test_bundled_robot_as_before():
    compare(load_robot(None), "bundled")


def test_corpus_as_before():
    done = 0
    for rb in corpus_robots():
        try:
            r = corpus_model(rb)
        except Exception:          # an entry this environment cannot build (covered elsewhere)
            continue
        compare(r, rb["id"])
        done += 1
    assert done >= 30


def test_example_robot_data_as_before():
    files = sorted(ERD.glob("*/urdf/*.urdf")) + sorted(ERD.glob("*/robots/*.urdf"))
    if not files:
        pytest.skip("example-robot-data is not installed")
    done = 0
    for f in files:
        try:
            r = load_robot(f)
        except Exception:          # a file this loader refuses (covered elsewhere)
            continue
        compare(r, f.name)
        done += 1
    assert done >= 60


def test_upright_leaf_joints_as_before(tmp_path):
    """Leaf joints turning about the vertical (the axis up or down, an origin yawed or not) are not
    turned; their needs stay 0 at rest, as the reference gives, beside tilted and stacked joints."""
    inertial = ('<inertial><origin xyz="0.05 0.02 0.1"/><mass value="0.7"/><inertia ixx="1e-3" ixy="0" ixz="0" '
                'iyy="1e-3" iyz="0" izz="1e-3"/></inertial>')
    axes, rpys = ["0 0 1", "0 0 -1", "1 0 0", "0 1 1", "0.3 0.2 1"], ["0 0 0", "0 0 0.7", "0.2 0 0"]
    out = ['<?xml version="1.0"?>', '<robot name="upright">', f'<link name="l0">{inertial}</link>']
    for i in range(1, 120):
        parent = f"l{i - 1}" if i % 7 == 0 else "l0"
        kind = ("revolute", "continuous", "revolute", "prismatic")[i % 4]
        out += [f'<link name="l{i}">{inertial}</link>',
                f'<joint name="j{i}" type="{kind}"><parent link="{parent}"/><child link="l{i}"/>'
                f'<origin xyz="{0.1 * (i % 13)} {0.05 * (i % 5)} 0.02" rpy="{rpys[i % 3]}"/>'
                f'<axis xyz="{axes[i % 5]}"/><limit lower="-1" upper="1.3" effort="1" velocity="1"/></joint>']
    f = tmp_path / "upright.urdf"
    f.write_text("\n".join(out + ["</robot>"]) + "\n")
    robot = load_robot(str(f))
    compare(robot, "upright")
    upright = [n for n in gravity_needs(robot) if n.torque == 0 and n.unit == "N·m"]
    assert upright and all(n.at_rest == 0 and n.pose_joint is None for n in upright)


def test_joint_frames_rows_are_each_joints_rows(tmp_path):
    """gravity_needs takes many joints' frames at once (_Frames.rows): the same floats, to the bit,
    as stacking each joint's own (origin, axis)."""
    star = tmp_path / "star.urdf"
    star.write_text(_tree_urdf("star", 60))
    for robot in (load_robot(None), load_robot(star)):
        W = S.world_transforms(robot, robot.rest_pose())
        names = [j.name for j in robot.joints.values() if j.type in S.MOVING and j.parent in W and j.child in W]
        frames = S._joint_frames(np, robot, W, names)
        for some in (names, names[::-2], names[:1]):
            origins, axes = frames.rows(some)
            assert origins.tobytes() == np.array([frames[n][0] for n in some]).tobytes()
            assert axes.tobytes() == np.array([frames[n][1] for n in some]).tobytes()
