"""What rules share: the robot, the options, and the facts they ask for (the model's, built once per robot)."""

from __future__ import annotations

from myrabot_desc.diagnostics import Loc
from myrabot_desc.model import shapes as geometry
from myrabot_desc.model import tree
from myrabot_desc.model.kinematics import rest_poses, world_transforms
from myrabot_desc.records import Record


class CheckOptions(Record):
    """What a check run does beyond the rules' defaults."""

    __slots__ = ("inertia", "suggest", "meshes", "srdf")

    def __init__(self, inertia: bool = False,      # compare inertias with geometry, meshes included (loads meshes)
                 suggest: bool = False,            # print ready <inertia/> lines (with inertia)
                 meshes: bool = False,             # load mesh files (scale, watertight, normals)
                 srdf: str | None = None):         # an SRDF whose <disable_collisions> the self-collision rule respects
        self.inertia = inertia
        self.suggest = suggest
        self.meshes = meshes
        self.srdf = srdf

    @property
    def load_meshes(self) -> bool:
        return self.meshes or self.inertia


class Context:
    """One run of the rules on one robot. The facts the rules share are the model's (the tree and
    its rigid bodies: model/tree.py; link poses: model/kinematics.py), built once per robot
    (``Robot.derive``); ``fact`` keeps check's own the same way, keyed by what they depend on."""

    def __init__(self, robot, options: CheckOptions | None = None):
        self.robot = robot
        self.opts = options or CheckOptions()
        self.suggestions: list[tuple[str, str]] = []   # (link, "<inertia .../>") for --suggest
        self.suppressions_seen: list = []   # (file, line, code) of inline suppressions (check_robot fills them)
        self.suppressions_used: list = []
        self.suppressed: list = []          # (finding, (file, line, code)) dropped by a suppression
        self.fixes: list = []               # (Diagnostic, rule.Fix) of the findings a rule knows how to repair

    def fact(self, name: str, build, meshes: bool = False):
        """``build()`` once per robot (``Robot.derive``); ``meshes``: it depends on whether meshes
        are read (--inertia, --meshes), which is then part of its key."""
        return self.robot.derive(("check", name, self.opts.load_meshes) if meshes else ("check", name), build)

    # ---------------------------------------------------------------- locations
    def loc_of(self, el) -> Loc | None:
        """Source location of a raw URDF element, for the raw-syntax rules (checks/urdf_syntax.py);
        the robot's own location for anything else."""
        return self.robot.loc_of(el) or self.robot.loc

    # ---------------------------------------------------------------- kinematics (the model's)
    @property
    def world(self) -> dict:
        """link -> 4x4 world pose at q = 0 with the root at the origin."""
        return self.fact("world", lambda: world_transforms(self.robot))

    @property
    def poses(self) -> dict:
        """link -> (R, p) world pose at q = 0 (model/transforms.py), pure Python: ``world`` without
        numpy, for the rules that need a few frames of an ordinary robot."""
        return rest_poses(self.robot)

    @property
    def tree_ok(self) -> bool:
        """One root, every joint's links exist, each link has at most one parent (model/tree.is_tree)."""
        return tree.is_tree(self.robot)

    @property
    def reachable(self) -> set[str]:
        return tree.reachable(self.robot)

    @property
    def body_of(self) -> dict[str, str]:
        """link -> the link that heads its rigid body (fixed joints merged upward)."""
        return tree.rigid_bodies(self.robot).host

    @property
    def body_mass(self) -> dict[str, float]:
        """body head link -> total mass of the rigid body (the head plus fixed-attached links)."""
        return tree.body_masses(self.robot)

    def moving(self, link: str) -> bool:
        """True when some non-fixed joint lies between the root and this link."""
        return tree.moving(self.robot, link)

    # ---------------------------------------------------------------- geometry
    def shapes(self, link, prefer: str = "collision"):
        """(kind, [items]) with items having .geometry and .origin: collisions, else visuals."""
        cols = [c for c in link.collisions if c.geometry is not None]
        vis = [v for v in link.visuals if v.geometry is not None]
        if prefer == "collision":
            return ("collision", cols) if cols else ("visual", vis)
        return ("visual", vis) if vis else ("collision", cols)

    def mesh(self, geom):
        """The MeshFacts of a Mesh geometry (scaled; model/meshes.py), or None / an error string;
        read once per robot."""
        return self.robot.derive(("mesh", str(geom.path), tuple(geom.scale)),
                                 lambda: geometry.load_mesh(geom) if geom.path else None)
