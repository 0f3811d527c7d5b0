"""Facts about a robot's joint tree, each computed in linear time and without recursion.

A hostile (or just large) model may hold 20,000 links in a star or 5,000 in a chain: walking up
from every link with a list of seen links is cubic in the chain length (2,000 links took 17.5 s
and gigabytes), and recursive walks overflow the C stack (Pinocchio crashes past ~4,000 joints
deep). Everything here is a dict lookup per joint or one iterative pass.
"""

from myrabot_desc.model.transforms import IDENTITY, compose, pose_T
from myrabot_desc.records import Struct

# Deepest chain of joints handed to Pinocchio: its URDF parser recurses once per joint and dies
# with SIGSEGV between 3,000 and 5,000 (8 MB stack); real robots are under 100 deep.
MAX_TREE_DEPTH = 1000


class TreeMaps:
    """child link -> its (first) parent joint; parent link -> its joints (document order)."""

    __slots__ = ("key", "parent_joint", "child_joints")

    def __init__(self, joints: dict):
        self.key = (id(joints), len(joints))
        self.parent_joint: dict = {}
        self.child_joints: dict = {}
        for j in joints.values():
            self.parent_joint.setdefault(j.child, j)
            self.child_joints.setdefault(j.parent, []).append(j)


def maps(robot) -> TreeMaps:
    """The maps of ``robot``, built once (rebuilt if its joints dict is replaced or resized)."""
    cached = robot.derived.get("tree.maps")
    if cached is None or cached.key != (id(robot.joints), len(robot.joints)):
        cached = robot.derived["tree.maps"] = TreeMaps(robot.joints)
    return cached


def parents(robot) -> dict[str, list]:
    """child link -> every joint naming it as child, in document order (a tree has one each)."""
    def build():
        out: dict[str, list] = {}
        for j in robot.joints.values():
            out.setdefault(j.child, []).append(j)
        return out
    return robot.derive("tree.parents", build)


def reachable(robot) -> set[str]:
    """The links a walk down from the root links reaches (links on a cycle are not reached)."""
    def build():
        children = robot.joints_by_parent()
        roots = robot.roots
        seen, todo = set(roots), list(roots)
        while todo:
            for j in children.get(todo.pop(), ()):
                if j.child not in seen:
                    seen.add(j.child)
                    todo.append(j.child)
        return frozenset(seen)
    return robot.derive("tree.reachable", build)


def is_tree(robot) -> bool:
    """One root, every joint's links exist, each link has one parent, every link reached."""
    def build():
        r = robot
        if r.root is None:
            return False
        if any(j.parent not in r.links or j.child not in r.links for j in r.joints.values()):
            return False
        if any(len(js) > 1 for js in parents(r).values()):
            return False
        return len(reachable(r)) == len(r.links)
    return robot.derive("tree.is_tree", build)


class Bodies(Struct):
    """The links merged into rigid bodies across fixed joints (see ``rigid_bodies``)."""

    host: dict          # link -> the link heading its body (itself when not merged)
    offset: dict        # link -> its pose in the host's frame (model/transforms (R, p); identity for a host)
    merged: tuple       # the fixed joints merged, in walk order

    def members(self, head: str) -> list[str]:
        return [n for n, h in self.host.items() if h == head]

    def masses(self, robot) -> dict[str, float]:
        """head link -> the mass of its body (negative masses count as 0)."""
        out: dict[str, float] = {}
        for link, head in self.host.items():
            out[head] = out.get(head, 0.0) + max(robot.links[link].mass, 0.0)
        return out


def rigid_bodies(robot, keep=frozenset(), stop=frozenset()) -> Bodies:
    """Every link's rigid body: a link on a fixed joint belongs to its parent's body, unless the
    joint is in ``keep`` or its parent in ``stop``. One walk down from the roots (breadth first, in
    document order); links it does not reach (on a cycle) are bodies of their own.

    The mass and inertia checks ask with nothing kept (the bodies as physics sees them); the SDF
    writer's ``--lump`` with the joints whose lumping is off kept and the ``world`` link as a stop
    (model/gazebo.preserved_joints), as sdformat lumps."""
    def build():
        children = robot.joints_by_parent()
        host: dict = {}
        offset: dict = {}
        merged = []
        order = list(robot.roots)
        for r in order:
            host[r], offset[r] = r, IDENTITY
        i = 0
        while i < len(order):
            parent = order[i]
            i += 1
            for j in children.get(parent, []):
                if j.child in host or j.child not in robot.links:     # (a joint to no link: T003)
                    continue
                if j.type == "fixed" and parent not in stop and j.name not in keep:
                    host[j.child] = host[parent]
                    offset[j.child] = compose(offset[parent], pose_T(j.origin))
                    merged.append(j)
                else:
                    host[j.child], offset[j.child] = j.child, IDENTITY
                order.append(j.child)
        for n in robot.links:          # links outside the tree (cycles): bodies of their own
            if n not in host:
                host[n], offset[n] = n, IDENTITY
        return Bodies(host, offset, tuple(merged))
    return robot.derive(("tree.rigid_bodies", frozenset(keep), frozenset(stop)), build)


def body_masses(robot) -> dict[str, float]:
    """body head link -> total mass of the rigid body (every fixed joint merged)."""
    return robot.derive("tree.body_masses", lambda: rigid_bodies(robot).masses(robot))


def moving(robot, link: str) -> bool:
    """True when some non-fixed joint lies between the root and this link."""
    cur, hops = link, 0
    while hops <= len(robot.joints):
        pj = robot.parent_joint(cur)
        if pj is None:
            return False
        if pj.type != "fixed":
            return True
        cur, hops = pj.parent, hops + 1
    return False


def cycles(parent: dict[str, str], order) -> list[list[str]]:
    """Every cycle of the child -> parent map, once each, as the walk up from the first link of
    ``order`` that reaches it meets it: [a, b, ..., z] where z's parent is a. Linear (each link
    is walked once: 0 unseen, 1 on the current walk, 2 done)."""
    state: dict[str, int] = {}
    out: list[list[str]] = []
    for start in order:
        if state.get(start):
            continue
        path: list[str] = []
        index: dict[str, int] = {}
        cur = start
        while cur is not None and not state.get(cur):
            state[cur] = 1
            index[cur] = len(path)
            path.append(cur)
            cur = parent.get(cur)
        if cur is not None and state.get(cur) == 1:
            out.append(path[index[cur]:])
        for n in path:
            state[n] = 2
    return out


def depth(robot) -> int:
    """Joints on the longest root-to-leaf chain (iterative; links on a cycle count as unreachable)."""
    m = maps(robot)
    children = {j.child for j in robot.joints.values()}
    best = 0
    todo = [(n, 0) for n in robot.links if n not in children]
    seen: set = set()
    while todo:
        link, d = todo.pop()
        if link in seen:
            continue
        seen.add(link)
        best = max(best, d)
        todo.extend((j.child, d + 1) for j in m.child_joints.get(link, ()))
    return best
