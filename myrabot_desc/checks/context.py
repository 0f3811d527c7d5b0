"""What rules share: the robot, the options, and lazily computed facts (poses, bodies, wheels)."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

from myrabot_desc.diagnostics import Loc
from myrabot_desc.model import shapes as geometry
from myrabot_desc.model.kinematics import world_transforms


@dataclass
class CheckOptions:
    inertia: bool = False        # compare inertias with geometry, meshes included (loads meshes)
    suggest: bool = False        # print ready <inertia/> lines (with inertia)
    meshes: bool = False         # load mesh files (scale, watertight, normals)
    srdf: str | None = None      # an SRDF whose <disable_collisions> the self-collision rule respects

    @property
    def load_meshes(self) -> bool:
        return self.meshes or self.inertia


class Context:
    def __init__(self, robot, options: CheckOptions | None = None):
        self.robot = robot
        self.opts = options or CheckOptions()
        self._mesh_cache: dict = {}
        self.suggestions: list[tuple[str, str]] = []   # (link, "<inertia .../>") for --suggest
        self.suppressions_seen: list = []   # (file, line, code) of inline suppressions (check_robot fills them)
        self.suppressions_used: list = []
        self.fixes: list = []               # (Diagnostic, rule.Fix) of the findings a rule knows how to repair

    # ---------------------------------------------------------------- locations
    def loc_of(self, el) -> Loc | None:
        """Source location of a raw URDF element (the loader maps every element of the tree;
        the robot's own location for anything else)."""
        return self.robot.loc_of(el) or self.robot.loc

    # ---------------------------------------------------------------- kinematics
    @cached_property
    def world(self) -> dict:
        """link -> 4x4 world pose at q = 0 with the root at the origin."""

        return world_transforms(self.robot)

    @cached_property
    def tree_ok(self) -> bool:
        """One root, every joint's links exist, each link has at most one parent."""
        r = self.robot
        if r.root is None:
            return False
        parents: dict[str, int] = {}
        for j in r.joints.values():
            if j.parent not in r.links or j.child not in r.links:
                return False
            parents[j.child] = parents.get(j.child, 0) + 1
        if any(n > 1 for n in parents.values()):
            return False
        return len(self.reachable) == len(r.links)

    @cached_property
    def reachable(self) -> set[str]:
        r = self.robot
        seen, todo = set(), [r.root] if r.root else []
        while todo:
            n = todo.pop()
            if n in seen:
                continue
            seen.add(n)
            todo.extend(j.child for j in r.child_joints(n))
        return seen

    @cached_property
    def body_of(self) -> dict[str, str]:
        """link -> the link that heads its rigid body (fixed joints merged upward)."""
        r = self.robot
        out: dict[str, str] = {}
        for name in r.links:
            cur, hops = name, 0
            while hops <= len(r.joints):
                pj = r.parent_joint(cur)
                if pj is None or pj.type != "fixed" or pj.parent not in r.links:
                    break
                cur, hops = pj.parent, hops + 1
            out[name] = cur
        return out

    @cached_property
    def body_mass(self) -> dict[str, float]:
        """body head link -> total mass of the rigid body (the head plus fixed-attached links)."""
        out: dict[str, float] = {}
        for link, head in self.body_of.items():
            out[head] = out.get(head, 0.0) + max(self.robot.links[link].mass, 0.0)
        return out

    def moving(self, link: str) -> bool:
        """True when some non-fixed joint lies between the root and this link."""
        r = self.robot
        cur, hops = link, 0
        while hops <= len(r.joints):
            pj = r.parent_joint(cur)
            if pj is None:
                return False
            if pj.type != "fixed":
                return True
            cur, hops = pj.parent, hops + 1
        return False

    # ---------------------------------------------------------------- geometry
    def shapes(self, link, prefer: str = "collision"):
        """(kind, [items]) with items having .geometry and .origin: collisions, else visuals."""
        cols = [c for c in link.collisions if c.geometry is not None]
        vis = [v for v in link.visuals if v.geometry is not None]
        if prefer == "collision":
            return ("collision", cols) if cols else ("visual", vis)
        return ("visual", vis) if vis else ("collision", cols)

    def mesh(self, geom):
        """The MeshFacts of a Mesh geometry (scaled; model/meshes.py), or None / an error string; cached."""

        key = (str(geom.path), tuple(geom.scale))
        if key not in self._mesh_cache:
            self._mesh_cache[key] = geometry.load_mesh(geom) if geom.path else None
        return self._mesh_cache[key]
