"""Collision checks of the arm against the rest of the robot and the scene (Pinocchio + coal).

Pairs: every collision object carried by the arm's joints (the ``base`` joint's
subtree) against every object that is not (the structure, the Roomba, the
sensors, and the table and cans when a scene is given). Pairs that already touch
at the reference (home) pose are contacts by design, such as the base servo
sitting between its mounting plates; they are left out and listed, as an SRDF
"disable collisions: Default" would.

Every distinct pose goes through a broadphase (bounding boxes) before the exact
test; the closest approach is searched in the order of bounding-box lower bounds.
Both report what testing every pair would (tests/sim/test_programs.py checks that).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from myrabot_desc.model import meshes
from myrabot_desc.model.kinematics import pose_matrix
from myrabot_desc.sim.result import Check

# Distance queries cost ~10 collision tests each; the closest approach is found at the
# joints' extremes (always probed) plus this many evenly spread poses.
PROBES = 12
# The closest-approach search skips a pair whose bounding boxes are farther apart than the
# closest distance found so far plus this much (room for the distance solver's tolerance).
SLACK = 1e-3


@dataclass
class CollisionReport:
    checked_configs: int
    pairs: int
    ignored: list[tuple[str, str]] = field(default_factory=list)     # touching at rest
    hits: list[tuple[float, str, str]] = field(default_factory=list)  # (time, arm object, other)
    min_distance: float | None = None
    min_pair: tuple[str, str] | None = None

    @property
    def collided(self) -> bool:
        return bool(self.hits)


class ArmCollider:
    def __init__(self, arm, scene=(), triangles=None):
        """``triangles``: path -> (vertices, faces) of a mesh file, model/meshes.triangles when None
        (sim/prepared.py shares one read of each file between the collider and the support)."""
        import coal
        import numpy as np
        import pinocchio as pin

        self.arm = arm
        robot = arm.robot
        model = arm.model
        self.notes = []
        gm = geometry_model(model, robot, self.notes, triangles)
        # scene objects: fixed in the robot's root frame (the base stands still in escoja/seguir)
        for obj in scene:
            for name, shape, M in obj.coal_shapes():
                go = pin.GeometryObject(name, 0, 0, pin.SE3(M[:3, :3], M[:3, 3]), shape)
                gm.addGeometryObject(go)
        self.gmodel = gm
        arm_joints = set()
        base_jid = arm.jid[0]
        for jid in range(1, model.njoints):
            j = jid
            while j > 0:
                if j == base_jid:
                    arm_joints.add(jid)
                    break
                j = model.parents[j]
        self.arm_objs = [i for i, g in enumerate(gm.geometryObjects) if g.parentJoint in arm_joints]
        others = [i for i, g in enumerate(gm.geometryObjects) if g.parentJoint not in arm_joints]
        # Bounding spheres: an object farther from the base joint than the arm can reach is never hit.
        data = model.createData()
        q = arm.full_q(np.zeros(len(arm.names)))
        pin.forwardKinematics(model, data, q)
        gd0 = pin.GeometryData(gm)
        pin.updateGeometryPlacements(model, data, gm, gd0)
        centre = data.oMi[base_jid].translation

        def sphere(i):
            g = gm.geometryObjects[i].geometry
            g.computeLocalAABB()
            c = gd0.oMg[i].act(np.asarray(g.aabb_center))
            return c, float(g.aabb_radius)

        reach = 0.0
        for i in self.arm_objs:
            c, r = sphere(i)
            reach = max(reach, float(np.linalg.norm(c - centre)) + r)
        self.reach = reach
        self.other_objs = []
        for i in others:
            c, r = sphere(i)
            if float(np.linalg.norm(c - centre)) - r <= reach + 0.01:
                self.other_objs.append(i)
        self.skipped_far = len(others) - len(self.other_objs)
        # the pairs as added (arm and other objects are disjoint: Pinocchio drops none as a duplicate),
        # not read back through Pinocchio's slow accessors
        self.pairs = [(a, b) for a in self.arm_objs for b in self.other_objs]
        for a, b in self.pairs:
            gm.addCollisionPair(pin.CollisionPair(a, b))
        self.gdata = pin.GeometryData(gm)
        cold_gjk(self.gdata)
        # Broadphase: Pinocchio's manager runs the exact test only on the active pairs whose
        # bounding boxes overlap (it says whether any pair collides, not which)
        self.broadphase = pin.BroadPhaseManager_NaiveCollisionManager(model, gm, self.gdata)
        # local bounding boxes (centres, half extents) of the objects, for distance lower bounds
        self.box_c, self.box_h = np.zeros((gm.ngeoms, 3)), np.zeros((gm.ngeoms, 3))
        for i in self.arm_objs + self.other_objs:
            bb = gm.geometryObjects[i].geometry.aabb_local
            lo, hi = np.asarray(bb.min_), np.asarray(bb.max_)
            self.box_c[i], self.box_h[i] = (lo + hi) / 2, (hi - lo) / 2
        self.np = np
        self.coal = coal

    def _name(self, i: int) -> str:
        return self.gmodel.geometryObjects[i].name

    def _names(self, k: int) -> tuple[str, str]:
        a, b = self.pairs[k]
        return self._name(a), self._name(b)

    def check(self, times, qarms, q_ref) -> CollisionReport:
        """Check arm configurations (rows of ``qarms``, at ``times``); q_ref defines resting contacts."""
        import pinocchio as pin

        np = self.np
        model, data, gm, gd = self.arm.model, self.arm.data, self.gmodel, self.gdata
        pin.computeCollisions(model, data, gm, gd, self.arm.full_q(q_ref), False)
        ignored = []
        active = []
        results = gd.collisionResults
        for k in range(len(self.pairs)):
            if results[k].isCollision():
                ignored.append(self._names(k))
                gd.deactivateCollisionPair(k)
            else:
                active.append(k)
        rep = CollisionReport(checked_configs=len(qarms), pairs=len(active), ignored=ignored)
        try:
            for t, qa in zip(times, qarms):
                q = self.arm.full_q(qa)
                if pin.computeCollisions(model, data, self.broadphase, q, False):   # True if any active pair hits
                    pin.computeCollisions(model, data, gm, gd, q, False)          # every active pair: which
                    for k in active:
                        if gd.collisionResults[k].isCollision():
                            rep.hits.append((float(t), *self._names(k)))
            # distances (the closest approach, informative) cost ten times a collision test: take
            # PROBES evenly spread poses plus each joint's extremes, where the arm reaches farthest
            qa_all = np.asarray(qarms)
            probe = set(np.linspace(0, len(qa_all) - 1, min(PROBES, len(qa_all))).astype(int).tolist())
            if len(qa_all):
                probe |= set(qa_all.argmin(axis=0).tolist()) | set(qa_all.argmax(axis=0).tolist())
            best = self._closest([qa_all[i] for i in sorted(probe)], active)
        finally:
            for k in range(len(self.pairs)):
                gd.activateCollisionPair(k)
        if best is not None:
            rep.min_distance, rep.min_pair = float(best[0]), self._names(best[1])
        return rep

    def _closest(self, poses, active):
        """(distance, pair) of the closest approach over ``poses``: the smallest distance, on a tie
        the earlier pose and then the earlier pair (what a full scan in that order keeps).

        Every (pose, pair) gets a lower bound, the gap between the two objects' bounding
        boxes in the root frame (none when the boxes overlap: the distance is negative when
        the objects penetrate); distances are computed in the order of those bounds until
        the next bound exceeds the best distance found (+ SLACK).
        """
        import pinocchio as pin

        np = self.np
        if not poses or not active:
            return None
        model, data, gm, gd = self.arm.model, self.arm.data, self.gmodel, self.gdata
        first = [self.pairs[k][0] for k in active]
        second = [self.pairs[k][1] for k in active]
        objs = sorted(set(first) | set(second))
        col = {i: n for n, i in enumerate(objs)}
        ia, ib = np.array([col[i] for i in first]), np.array([col[i] for i in second])
        H = []                                   # placements of the objects at each pose
        for qa in poses:
            pin.updateGeometryPlacements(model, data, gm, gd, self.arm.full_q(qa))
            oMg = gd.oMg
            H.append([oMg[i].homogeneous for i in objs])
        H = np.array(H)
        R = H[..., :3, :3]
        centre = np.einsum("pnij,nj->pni", R, self.box_c[objs]) + H[..., :3, 3]
        half = np.einsum("pnij,nj->pni", np.abs(R), self.box_h[objs])
        gap = np.maximum(np.abs(centre[:, ia] - centre[:, ib]) - half[:, ia] - half[:, ib], 0.0)
        d = np.sqrt((gap * gap).sum(axis=2))
        lb = np.where(d > 0, d, -np.inf).ravel()     # overlapping boxes: any depth of penetration
        best = (np.inf, 0, 0)
        placed = None
        for flat in np.argsort(lb, kind="stable"):
            if lb[flat] > best[0] + SLACK:
                break
            p, j = divmod(int(flat), len(active))
            if p != placed:
                pin.updateGeometryPlacements(model, data, gm, gd, self.arm.full_q(poses[p]))
                placed = p
            d = pin.computeDistance(gm, gd, active[j]).min_distance
            best = min(best, (d, p, j))
        return None if best[0] == np.inf else (best[0], active[best[2]])


def unique_configs(t, q, resolution: float = 0.005, limit: int = 1500):
    """Distinct arm configurations (quantised to ``resolution`` rad), first time each is seen.

    Trajectories are continuous, so only the samples where the quantised pose
    changes are candidates; those are then de-duplicated (a swing revisits the
    same poses every cycle).
    """
    import numpy as np

    key = np.round(np.ascontiguousarray(q.T) / resolution).astype(np.int64)    # a row per joint
    code = np.zeros(key.shape[1], dtype=np.int64)
    for row in key:                        # mixed-radix code of a pose (ranges are small)
        lo = int(row.min())
        code = code * (int(row.max()) - lo + 1) + (row - lo)
    cand = np.flatnonzero(np.r_[True, code[1:] != code[:-1]])
    _, first = np.unique(code[cand], return_index=True)
    first = np.sort(cand[first])
    if len(first) > limit:
        first = first[np.linspace(0, len(first) - 1, limit).astype(int)]
    return t[first], q[first]


def cold_gjk(gdata):
    """No GJK warm start from a pair's previous query: Pinocchio turns it on, and then a result
    depends on the poses checked before (a 0.3 mm penetration of the gripper into the webcam
    optics went unseen after about one pose in 50).

    ``gdata`` must be fresh from ``pin.GeometryData(gm)``: its constructor gives every pair the
    same request, so one request with the flag off is copied over all of them in C++ (not set on each
    request in Python, through a deprecation warning apiece)."""
    import warnings

    import coal

    n = len(gdata.collisionRequests)
    if n == 0:
        return
    creq, dreq = gdata.collisionRequests[0], gdata.distanceRequests[0]
    with warnings.catch_warnings():         # coal deprecates the flag, but it is what turns the cache on
        warnings.simplefilter("ignore", DeprecationWarning)
        creq.enable_cached_gjk_guess = False
        dreq.enable_cached_gjk_guess = False
    requests = coal.StdVec_CollisionRequest()
    requests.extend([creq] * n)
    gdata.collisionRequests = requests
    requests = coal.StdVec_DistanceRequest()
    requests.extend([dreq] * n)
    gdata.distanceRequests = requests


def geometry_model(model, robot, notes: list, triangles=None):
    """A Pinocchio GeometryModel of the robot's collision shapes, from our model (meshes read
    through model/meshes.py, with its roots and limits); named ``{link}_{index}`` as Pinocchio's
    URDF reader names them. A mesh that cannot be read is left out, with a note."""
    import pinocchio as pin

    gm = pin.GeometryModel()
    skipped = []
    for ln, link in robot.links.items():
        if not model.existFrame(ln):
            continue
        fid = model.getFrameId(ln)
        f = model.frames[fid]
        for i, c in enumerate(link.collisions):
            shape = coal_shape(c.geometry, triangles)
            if shape is None:
                if c.geometry is not None and c.geometry.kind == "mesh":
                    skipped.append(c.geometry.filename)
                continue
            M = f.placement.homogeneous @ pose_matrix(c.origin)
            gm.addGeometryObject(pin.GeometryObject(f"{ln}_{i}", f.parentJoint, fid,
                                                    pin.SE3(M[:3, :3], M[:3, 3]), shape))
    if skipped:
        names = sorted(set(skipped))
        notes.append(f"{len(skipped)} collision mesh(es) could not be read and were left out "
                     f"({', '.join(names[:3])}{', ...' if len(names) > 3 else ''})")
    return gm


def coal_shape(g, triangles=None):
    """A coal collision shape of a URDF geometry (meshes as bounding-volume hierarchies, their
    triangles read by ``triangles``, model/meshes.triangles when None), or None."""
    import coal

    if g is None:
        return None
    if g.kind == "box":
        return coal.Box(*g.size)
    if g.kind == "cylinder":
        return coal.Cylinder(g.radius, g.length)
    if g.kind == "sphere":
        return coal.Sphere(g.radius)
    if g.kind == "mesh" and g.path is not None:
        import numpy as np

        try:            # the lean STL/COLLADA readers: trimesh (and scipy) only for other formats
            v, f = (triangles or meshes.triangles)(g.path)
        except meshes.MeshError:
            return None
        bvh = coal.BVHModelOBBRSS()
        bvh.beginModel(len(f), len(v))
        bvh.addVertices(np.asarray(v, dtype=float) * np.asarray(g.scale, dtype=float))
        bvh.addTriangles(np.asarray(f, dtype=np.int64))
        bvh.endModel()
        return bvh
    return None


def collision_check(res, arm, t, arm_q, q_home, name: str, expected: str, scene=(), poses=None,
                    collider=None) -> None:
    """Check the run's arm poses for collisions and append the verdict line to ``res``.

    ``poses``: ``unique_configs(t, arm_q)`` when the caller has it already; ``collider``: an
    ArmCollider of ``arm`` and ``scene`` to reuse.
    """

    tt, qq = unique_configs(t, arm_q) if poses is None else poses
    col = ArmCollider(arm, scene) if collider is None else collider
    rep = col.check(tt, qq, q_home)
    detail = f"{rep.checked_configs} arm poses, {rep.pairs} pairs"
    if rep.min_pair:
        detail += f"; closest {rep.min_distance * 1000:.1f} mm ({rep.min_pair[0]} – {rep.min_pair[1]})"
    if rep.ignored:
        detail += f"; touching at home, ignored: {', '.join(a + ' – ' + b for a, b in rep.ignored[:3])}" \
                  + (f" and {len(rep.ignored) - 3} more" if len(rep.ignored) > 3 else "")
    res.notes.extend(col.notes)
    first = rep.hits[0] if rep.hits else None
    res.checks.append(Check(name, not rep.collided,
                            "none" if not first else f"{first[1]} – {first[2]} at {first[0]:.3f} s", "",
                            expected, detail))
