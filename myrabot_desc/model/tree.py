"""Facts about a robot's joint tree, each computed in linear time and without recursion.

A hostile (or just large) model may hold 20,000 links in a star or 5,000 in a chain: walking up
from every link with a list of seen links is cubic in the chain length (2,000 links took 17.5 s
and gigabytes), and recursive walks overflow the C stack (Pinocchio crashes past ~4,000 joints
deep). Everything here is a dict lookup per joint or one iterative pass.
"""

from __future__ import annotations

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
    cached = robot.__dict__.get("_tree_maps")
    if cached is None or cached.key != (id(robot.joints), len(robot.joints)):
        cached = TreeMaps(robot.joints)
        robot.__dict__["_tree_maps"] = cached
    return cached


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
