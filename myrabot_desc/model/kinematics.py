"""Forward kinematics over the model (no Pinocchio needed for frames).

URDF convention: a joint's origin places the child frame in the parent frame;
rpy is fixed-axis X, Y, Z, i.e. R = Rz(yaw) @ Ry(pitch) @ Rx(roll).

Two forms of the same walk: pure Python (``rest_poses``, ``poses_at``, ``center_of_mass`` at rest),
what check reads of an ordinary robot, and numpy's stacked products (``world_transforms``,
``centers_of_mass``) for many links or many configurations. numpy is imported inside the functions
that use it (~100 ms): modules that only need the model import this one at their top without
paying for numpy until a stacked transform is computed.
"""

from __future__ import annotations

import math

from myrabot_desc.errors import InputError
from myrabot_desc.model.parts import Joint, Pose, Robot
from myrabot_desc.model.transforms import IDENTITY, Tf, compose, pose_T

TYPE_CHECKING = False      # typing's own costs a check ~3 ms to import; type checkers read this one too
if TYPE_CHECKING:
    import numpy as np


def _rotation(rpy) -> tuple:
    """The 3x3 rotation of ``rpy`` (fixed-axis X, Y, Z), row by row: 9 floats."""
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return (cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,
            sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,
            -sp, cp * sr, cp * cr)


def pose_stack(poses) -> np.ndarray:
    """pose_matrix of every pose as one (n, 4, 4) array (the same floats), filled from flat lists:
    a list per row and pose would be 100,000 objects for the garbage collector to rescan. Models
    repeat a few rpy (most origins have none): each rotation is computed once per call and put
    in place by one index."""
    import numpy as np

    xyz: list[float] = []
    add = xyz.extend
    turns: dict = {}            # rpy -> (that rpy, its row in rotations)
    rotations: list = []
    which: list[int] = []
    put = which.append
    last, row = object(), 0     # the pose before's rpy object and its row (poses share one rpy object)
    for pose in poses:
        rpy = pose.rpy
        if rpy is not last:
            last = rpy
            if type(rpy) is not tuple:
                rpy = tuple(rpy)
            seen = turns.get(rpy)
            # equal tuples hold the same floats unless one has a zero: 0.0 == -0.0, whose sines differ
            if seen is not None and (seen[0] is rpy or 0.0 not in rpy):
                row = seen[1]
            else:
                row = len(rotations)
                turns[rpy] = (rpy, row)
                rotations.append(_rotation(rpy))
        put(row)
        x, y, z = pose.xyz
        add((x, y, z))
    out = np.zeros((len(which), 4, 4))
    if which:
        out[:, :3, :3] = np.array(rotations, dtype=float).reshape(-1, 3, 3)[np.array(which, dtype=np.intp)]
        out[:, :3, 3] = np.array(xyz, dtype=float).reshape(-1, 3)
        out[:, 3, 3] = 1.0
    return out


def rpy_matrix(rpy) -> np.ndarray:
    import numpy as np

    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def pose_matrix(pose: Pose) -> np.ndarray:
    import numpy as np

    # from a flat tuple: an array from nested lists costs five times as much
    a, b, c, d, e, f, g, h, i = _rotation(pose.rpy)
    x, y, z = pose.xyz
    return np.array((a, b, c, x, d, e, f, y, g, h, i, z, 0.0, 0.0, 0.0, 1.0), dtype=float).reshape(4, 4)


def _norms(axes) -> list[float]:
    """np.linalg.norm of each axis, bit for bit (it is sqrt(a.dot(a)); the stacked 1x3 @ 3x1
    products take the same dot kernel), in one call instead of one per joint."""
    import numpy as np

    if not axes:
        return []
    return norm_rows(np, axes).tolist()


def norm_rows(np, axes):
    """``_norms`` of the rows of an n x 3 array (or list of triples) as an array: the same products
    on a contiguous copy, so the same bits whatever the caller's layout."""
    a = np.ascontiguousarray(axes, dtype=float).reshape(-1, 3)
    return np.sqrt((a[:, None, :] @ a[:, :, None])[:, 0, 0])


def stack_by_identity(objs: list, shape: tuple):
    """``np.array(objs, dtype=float).reshape(-1, *shape)``, each distinct object converted once and
    put in place by one index: models repeat the same motion, box or tuple objects thousands of times
    (a star's joints), and converting every one is most of the stacking. ``objs`` keeps them alive."""
    import numpy as np

    rows: dict = {}
    distinct: list = []
    which: list[int] = []
    for o in objs:
        k = rows.get(id(o))
        if k is None:
            k = rows[id(o)] = len(distinct)
            distinct.append(o)
        which.append(k)
    return np.array(distinct, dtype=float).reshape(-1, *shape)[np.array(which, dtype=np.intp)]


def axis_angle(axis, angle: float) -> np.ndarray:
    import numpy as np

    a = np.asarray(axis, dtype=float)
    n = np.linalg.norm(a)
    return np.array(_axis_angle_rows(a.tolist(), float(n), angle))


def _axis_angle_rows(axis, n: float, angle: float) -> list:
    if n == 0:
        return [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    x, y, z = axis[0] / n, axis[1] / n, axis[2] / n
    c, s, C = math.cos(angle), math.sin(angle), 1 - math.cos(angle)
    return [[c + x * x * C, x * y * C - z * s, x * z * C + y * s],
            [y * x * C + z * s, c + y * y * C, y * z * C - x * s],
            [z * x * C - y * s, z * y * C + x * s, c + z * z * C]]


def _motion_flat(joint: Joint, n: float, q: float) -> tuple:
    """joint_motion(joint, q) as 16 floats, row by row; ``n`` is the norm of the joint's axis."""
    if joint.type in ("revolute", "continuous"):
        (a, b, c), (d, e, f), (g, h, i) = _axis_angle_rows([float(v) for v in joint.axis], n, q)
        return (a, b, c, 0.0, d, e, f, 0.0, g, h, i, 0.0, 0.0, 0.0, 0.0, 1.0)
    t = (0.0, 0.0, 0.0)
    if joint.type == "prismatic" and n:
        t = [float(v) / n * q for v in joint.axis]
    return (1.0, 0.0, 0.0, t[0], 0.0, 1.0, 0.0, t[1], 0.0, 0.0, 1.0, t[2], 0.0, 0.0, 0.0, 1.0)


_MOVING = ("revolute", "continuous", "prismatic")


def joint_motion(joint: Joint, q: float) -> np.ndarray:
    """Transform of the joint's own motion by position q (revolute/continuous/prismatic)."""
    import numpy as np

    n = _norms([joint.axis])[0] if joint.type in _MOVING else 0.0
    return np.array(_motion_flat(joint, n, q), dtype=float).reshape(4, 4)


def world_transforms(robot: Robot, q: dict[str, float] | None = None, root_pose: np.ndarray | None = None
                     ) -> dict[str, np.ndarray]:
    """World (root-frame) 4x4 transform of every link reachable from the root(s).

    Joints not in ``q`` sit at 0. Mimic joints follow their target. Cycles are
    cut (each link is placed once: by the first joint a depth-first walk takes to it).

    The walk runs on names; the products are then taken one tree level at a time as stacked
    4x4 products (the same per-matrix kernel, so the same bits as one product per joint, but
    without a numpy call per joint: a 20,000-link star is two calls).

    The zero configuration (no ``q``, or one that puts every joint at 0, and no ``root_pose``) is
    computed once per robot (check asks for it from several rules, some at the rest pose); its
    arrays are read-only, each call gets its own dict.
    """
    if root_pose is None and (not q or _at_zero(robot, q)):
        key = (id(robot.joints), len(robot.joints), id(robot.links), len(robot.links))
        cached = robot.derived.get("world_transforms")
        if cached is None or cached[0] != key:
            cached = (key, _world_transforms(robot, {}, None, frozen=True))
            robot.derived["world_transforms"] = cached
        return dict(cached[1])
    return _world_transforms(robot, q, root_pose)


def rest_poses(robot: Robot) -> dict[str, Tf]:
    """``world_transforms(robot)`` in pure Python: link -> (R, p) (model/transforms.py) at q = 0 with
    the root at the origin, built once per robot. The same walk places the same links by the same
    joints; the products round as Python's floats do (within an ulp or so of numpy's stacked ones).
    What check's rules, the drive model and convert read of an ordinary robot: importing numpy for a
    few hundred 4x4 products costs more than the rules themselves."""
    def build():
        order, via, _ = walk(robot)
        out: dict[str, Tf] = {}
        for link in order:
            j = via[link]
            out[link] = IDENTITY if j is None else compose(out[j.parent], pose_T(j.origin))
        return out
    return robot.derive("kinematics.rest_poses", build)


def poses_at(robot: Robot, q: dict, W: dict | None = None, q0: dict | None = None) -> tuple[dict | None, set]:
    """``world_transforms(robot, q)`` in pure Python (mimic joints following): link -> (R, p), and
    the links placed; ``rest_poses`` at the zero pose. From ``W``, the poses at ``q0``, only the links
    below a joint whose position differs are placed again (a sweep moves one joint at a time). The
    poses are None for a position that is not a number. What an ordinary robot's rules need off
    q = 0 (a quadruped's knees and Franka's elbow rest there) without importing numpy."""
    if W is None and _at_zero(robot, q):
        P = rest_poses(robot)
        return P, set(P)
    q = _with_mimic(robot, q)
    if any(type(v) not in (float, int) for v in q.values()):
        return None, set()
    order, via, _ = walk(robot)
    changed = None
    if W is not None:
        q0 = _with_mimic(robot, q0)
        changed = {n for n in set(q) | set(q0) if q.get(n, 0.0) != q0.get(n, 0.0)}
    out: dict[str, Tf] = {}
    placed: set[str] = set()
    for link in order:
        j = via[link]
        if j is None:
            out[link] = IDENTITY if W is None else W[link]
            continue
        if changed is not None and j.name not in changed and j.parent not in placed:
            out[link] = W[link]
            continue
        placed.add(link)
        T = compose(out[j.parent], pose_T(j.origin))
        v = q.get(j.name, 0.0)
        if v != 0 and j.type in _MOVING:
            axis = [float(a) for a in j.axis]
            n = math.sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2])
            if j.type == "prismatic":
                if n:
                    T = compose(T, (IDENTITY[0], (axis[0] / n * v, axis[1] / n * v, axis[2] / n * v)))
            else:
                T = compose(T, (tuple(map(tuple, _axis_angle_rows(axis, n, v))), (0.0, 0.0, 0.0)))
        out[link] = T
    return out, placed


def _at_zero(robot: Robot, q: dict) -> bool:
    """Does ``q`` place every joint as no ``q`` does: each position, mimic joints' included, a
    Python 0 or +0.0 (``Robot.rest_pose`` of most robots; -0.0 would turn frames by a signed zero)."""
    values = _with_mimic(robot, q).values()
    # each distinct value object once (a rest pose repeats a few: 0.0, some limits; 20,000 in a star)
    for v in dict(zip(map(id, values), values)).values():
        if type(v) not in (float, int) or v != 0 or math.copysign(1.0, v) < 0:
            return False
    return True


def walk(robot: Robot) -> tuple[list[str], dict, dict]:
    """``_walk`` of the robot's own joints, made once per robot (every placement shares it)."""
    return robot.derive("kinematics.walk", lambda: _walk(robot, robot.joints_by_parent()))


def _walk(robot: Robot, children) -> tuple[list[str], dict, dict]:
    """(links in walk order from the roots, link -> the joint that placed it (None: a root), link
    -> the joints that placed its children); a link reached twice (a cycle, a second parent) keeps
    its first placement."""
    order: list[str] = []
    via: dict[str, Joint | None] = {}
    for root in robot.roots or list(robot.links)[:1]:
        stack: list[tuple[str, Joint | None]] = [(root, None)]
        while stack:
            link, j = stack.pop()
            if link in via:
                continue
            via[link] = j
            order.append(link)
            for c in children.get(link, []):
                if c.child not in via:
                    stack.append((c.child, c))
    kids: dict[str, list[Joint]] = {}
    for link in order:
        j = via[link]
        if j is not None:
            kids.setdefault(j.parent, []).append(j)
    return order, via, kids


def _world_transforms(robot: Robot, q, root_pose, frozen: bool = False) -> dict[str, np.ndarray]:
    import numpy as np

    q = _with_mimic(robot, q)
    base = np.eye(4) if root_pose is None else root_pose
    if frozen:
        base.flags.writeable = False
    order, via, kids = walk(robot)
    out: dict[str, np.ndarray] = {}
    level = [link for link in order if via[link] is None]
    for link in level:
        out[link] = base
    levels = []
    while level:
        joints = [j for link in level for j in kids.get(link, ())]
        if not joints:
            break
        levels.append(joints)
        level = [j.child for j in joints]
    # every joint's origin and motion at once (they do not depend on the parents): a 5,000-link
    # chain has 5,000 levels, and a few numpy calls per level instead of a dozen
    every = [j for joints in levels for j in joints]
    # each axis object's norm once (joints share the loader's axis tuples; the norm of one axis does
    # not depend on the others computed with it)
    axes = {id(j.axis): j.axis for j in every if j.type in _MOVING}
    norm = dict(zip(axes, _norms(list(axes.values()))))
    motions: list = []      # each joint's motion (16 floats; joints that move alike share the object)
    same: dict = {}     # (type, axis, q) -> its motion, for the same axis and position objects
    for j in every:
        qv, axis = q.get(j.name, 0.0), j.axis
        key = (j.type, axis, qv) if type(axis) is tuple else None
        seen = same.get(key) if key is not None else None
        # identical objects hold identical bits (equal ones may not: 0.0 == -0.0)
        if seen is not None and seen[0] is axis and seen[1] is qv:
            m = seen[2]
        else:
            m = _motion_flat(j, norm.get(id(axis), 0.0), qv)
            if key is not None:
                same[key] = (axis, qv, m)
        motions.append(m)
    P_all = pose_stack(j.origin for j in every)
    M_all = stack_by_identity(motions, (4, 4))
    k = 0
    for joints in levels:
        n = len(joints)
        parents = stack_by_identity([out[j.parent] for j in joints], (4, 4))     # (siblings share theirs)
        T = parents @ P_all[k:k + n] @ M_all[k:k + n]
        k += n
        if frozen:
            T.flags.writeable = False
        for i, j in enumerate(joints):
            out[j.child] = T[i]
    return {link: out[link] for link in order}


def _with_mimic(robot: Robot, q) -> dict:
    """``q`` with each mimic joint following its target (as ``world_transforms`` places them)."""
    q = dict(q or {})
    for j in robot.joints.values():
        if j.mimic and j.mimic.joint in q and j.name not in q:
            q[j.name] = q[j.mimic.joint] * j.mimic.multiplier + j.mimic.offset
    return q


def world_transforms_from(robot: Robot, W: dict, q0: dict, q: dict) -> tuple[dict, frozenset]:
    """``world_transforms(robot, q)`` from ``W = world_transforms(robot, q0)``, and the links whose
    transform was recomputed: only the links below a joint whose position differs between ``q0``
    and ``q`` (mimic joints included) are, with the same stacked products as ``world_transforms``
    (so the same bits); the others keep ``W``'s arrays. A sampled pose that moves one joint of a
    large robot costs the size of that joint's subtree, not of the robot."""
    import numpy as np

    a, b = _with_mimic(robot, q0), _with_mimic(robot, q)
    changed = frozenset(j.name for j in robot.joints.values() if a.get(j.name, 0.0) != b.get(j.name, 0.0))
    out = dict(W)
    if not changed:
        return out, frozenset()
    steps, dirty = _replan(robot, changed)
    for todo, P, norms in steps:
        parents = np.array([out[j.parent] for j in todo], dtype=float)
        flat: list[float] = []
        for j, n in zip(todo, norms):
            flat.extend(_motion_flat(j, n, b.get(j.name, 0.0)))
        T = parents @ P @ np.array(flat, dtype=float).reshape(-1, 4, 4)
        for k, j in enumerate(todo):
            out[j.child] = T[k]
    return out, dirty


def _replan(robot: Robot, changed: frozenset) -> tuple[list, frozenset]:
    """What ``world_transforms_from`` places again when the joints ``changed`` move, level by level
    from the roots: (the joints, their origins stacked, their axes' norms) per level, and the links
    placed again. The same for every position of those joints (a sweep samples each joint's range),
    so it is made once per robot and set of joints."""
    def build():
        order, via, kids = walk(robot)
        dirty: set[str] = set()
        steps = []
        level = [link for link in order if via[link] is None]
        while level:
            joints = [j for link in level for j in kids.get(link, ())]
            if not joints:
                break
            todo = [j for j in joints if j.name in changed or j.parent in dirty]
            if todo:
                moving = [j for j in todo if j.type in _MOVING]
                norm = dict(zip(map(id, moving), _norms([j.axis for j in moving])))
                steps.append((todo, pose_stack(j.origin for j in todo), [norm.get(id(j), 0.0) for j in todo]))
                dirty.update(j.child for j in todo)
            level = [j.child for j in joints]
        return steps, frozenset(dirty)

    return robot.derive(("kinematics.replan", changed), build)


def joint_world_transforms(robot: Robot, q: dict[str, float] | None = None) -> dict[str, np.ndarray]:
    """World transform of every joint frame (the joint origin, before its motion)."""
    links = world_transforms(robot, q)
    return {j.name: links[j.parent] @ pose_matrix(j.origin) for j in robot.joints.values() if j.parent in links}


def center_of_mass(robot: Robot, q: dict[str, float] | None = None) -> tuple[float, tuple]:
    """Total mass and centre of mass (world frame, (x, y, z)) of every link with an inertial. At rest
    (no ``q``, or every joint at 0) from ``rest_poses``, in pure Python (check asks for it)."""
    if not q or _at_zero(robot, q):
        P = rest_poses(robot)
        places = {}
        for name, link in robot.links.items():
            if link.inertial is not None and name in P and link.inertial.mass > 0:
                # place()'s products and sums for the one point, without a list per link
                ((a, b, c), (d, e, f), (g, h, i)), (px, py, pz) = P[name]
                x, y, z = link.inertial.origin.xyz
                places[name] = (a * x + b * y + c * z + px, d * x + e * y + f * z + py, g * x + h * y + i * z + pz)
    else:
        import numpy as np

        T = world_transforms(robot, q)
        links = [link for name, link in robot.links.items()
                 if link.inertial is not None and name in T and link.inertial.mass > 0]
        places = {}
        if links:   # the products stacked (same bits as one per link)
            W = np.array([T[link.name] for link in links], dtype=float) @ pose_stack(link.inertial.origin for link in links)
            places = dict(zip((link.name for link in links), map(tuple, W[:, :3, 3].tolist())))
    total = a0 = a1 = a2 = 0.0
    for name, (x, y, z) in places.items():     # the sums in link order
        m = robot.links[name].inertial.mass
        total += m
        a0, a1, a2 = a0 + m * x, a1 + m * y, a2 + m * z
    if not total > 0:
        return total, (math.nan, math.nan, math.nan)
    return total, (a0 / total, a1 / total, a2 / total)


def centers_of_mass(robot: Robot, q: dict) -> tuple[float, np.ndarray]:
    """``center_of_mass`` at many configurations at once: ``q`` maps joint names to equal-length
    sequences of positions (the other joints at 0, mimic joints following); the total mass and an
    (n, 3) array of centres of mass. The same walk and formulas as ``world_transforms``, each tree
    level one stacked product over every configuration (sim's arm sweeps hundreds of poses)."""
    import numpy as np

    q = {k: np.asarray(v, dtype=float).ravel() for k, v in q.items()}
    n = len(next(iter(q.values()))) if q else 1
    for j in robot.joints.values():
        if j.mimic and j.mimic.joint in q and j.name not in q:
            q[j.name] = q[j.mimic.joint] * j.mimic.multiplier + j.mimic.offset
    order, via, kids = walk(robot)
    # A link no joint of ``q`` moves has one pose for every configuration: it is computed once, as a
    # (1, 4, 4) stack that broadcasts (the same per-matrix kernel, so the same bits as n copies).
    # sim's arm moves a few links of the robot's dozens.
    eye = np.eye(4)[None]
    out: dict[str, np.ndarray] = {link: eye for link in order if via[link] is None}
    level = list(out)
    while level:
        joints = [j for link in level for j in kids.get(link, ())]
        if not joints:
            break
        moving = [j for j in joints if j.type in _MOVING]
        norm = dict(zip(map(id, moving), _norms([j.axis for j in moving])))
        still = [j for j in joints if j.name not in q and len(out[j.parent]) == 1]
        moved = [j for j in joints if j.name in q or len(out[j.parent]) != 1]
        for group, size in ((still, 1), (moved, n)):
            if not group:
                continue
            flat: list[float] = []
            for j in group:
                flat.extend(_motion_flat(j, norm.get(id(j), 0.0), 0.0))
            M = np.broadcast_to(np.array(flat, dtype=float).reshape(1, -1, 4, 4), (size, len(group), 4, 4)).copy()
            for k, j in enumerate(group):
                if j.name in q:
                    M[:, k] = _motions(j, norm.get(id(j), 0.0), q[j.name])
            parents = np.stack([np.broadcast_to(out[j.parent], (size, 4, 4)) for j in group], axis=1)
            T = parents @ pose_stack(j.origin for j in group) @ M
            for k, j in enumerate(group):
                out[j.child] = T[:, k]
        level = [j.child for j in joints]
    links = [link for name, link in robot.links.items()
             if link.inertial is not None and name in out and link.inertial.mass > 0]
    total, acc = 0.0, np.zeros((n, 3))
    for link in links:
        m = link.inertial.mass
        total += m
        acc = acc + m * (out[link.name] @ pose_matrix(link.inertial.origin))[:, :3, 3]
    return total, (acc / total if total > 0 else np.full((n, 3), np.nan))


def _motions(joint: Joint, n: float, values) -> np.ndarray:
    """``_motion_flat(joint, n, v)`` of every v in ``values`` as an (len, 4, 4) array, with the same
    float operations elementwise (the sines and cosines by math, as there)."""
    import numpy as np

    k = len(values)
    out = np.zeros((k, 4, 4))
    out[:, 0, 0] = out[:, 1, 1] = out[:, 2, 2] = out[:, 3, 3] = 1.0
    if joint.type in ("revolute", "continuous"):
        if n == 0:
            return out
        x, y, z = (float(v) / n for v in joint.axis)
        c = np.array([math.cos(v) for v in values.tolist()])
        s = np.array([math.sin(v) for v in values.tolist()])
        C = 1 - c
        out[:, 0, 0], out[:, 0, 1], out[:, 0, 2] = c + x * x * C, x * y * C - z * s, x * z * C + y * s
        out[:, 1, 0], out[:, 1, 1], out[:, 1, 2] = y * x * C + z * s, c + y * y * C, y * z * C - x * s
        out[:, 2, 0], out[:, 2, 1], out[:, 2, 2] = z * x * C - y * s, z * y * C + x * s, c + z * z * C
    elif joint.type == "prismatic" and n:
        for r, a in enumerate(joint.axis):
            out[:, r, 3] = float(a) / n * values
    return out


def require_tree(robot: Robot) -> str:
    """The root link, or InputError when the joints do not form one tree over the links.

    check reports these as T-rules and goes on; commands that move the robot (sim) need a tree:
    a joint naming a missing link, a link with two parents, a cycle or a second root would
    otherwise surface as a KeyError deep inside.
    """

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
