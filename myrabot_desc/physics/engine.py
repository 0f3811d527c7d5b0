"""A robot in MuJoCo for ``sim settle``, ``sim sweep`` and ``sim drive --engine mujoco``: the model is our
own ``convert --to mjcf`` (its actuators, free or welded base, ``home`` keyframe), built in memory,
on a floor.

``convert_mjcf`` writes its MJCF and meshes to a folder: here that folder is a temporary one outside
the working folder, read back into memory (the MJCF text and its meshes as MuJoCo assets) and removed
before anything is simulated, so a run leaves no file behind. MuJoCo's warnings become our notes (its
default handler appends them to MUJOCO_LOG.TXT in the working folder).

The engine maps MuJoCo's names back to the model: bodies are rigid bodies named after the link heading
them (links fixed to it are fused in), collision geoms are ``LINK_collision`` / ``LINK_collision_K``
(the K-th ``<collision>`` of that link, whose file:line the model knows), actuators are named after
their joints.
"""

from __future__ import annotations

import contextlib
import math
import re

from myrabot_desc.convert.mjcf import compile as compile_mjcf
from myrabot_desc.convert.mjcf import convert_mjcf
from myrabot_desc.errors import InputError
from myrabot_desc.model import drive as D
from myrabot_desc.model.legs import stance
from myrabot_desc.model.statics import effort_of
from myrabot_desc.model.support import CONTACT_TOL
from myrabot_desc.safety import limit
from myrabot_desc.sim.result import Check

FLOOR = "floor"
# A joint needing between 1x and this many times its effort limit to hold what it carries at the start
# pose is taken to have a counterbalance the URDF does not describe (PR2's shoulders: 1.7x), or a motor
# stronger than it says: its actuator may push up to 1.25x the need, and a note says so. Past it the
# joint sags and the run fails (check P006 uses the same ratio between its warning and its error).
COUNTERBALANCE_RATIO = 2.0
TURNED_OVER = 60.0       # degrees of tilt from how a base settled past which it has turned over
_GEOM_NAME = re.compile(r"^(?P<link>.*)_collision(?:_(?P<k>\d+))?(?:_\d+)?$")


def import_mujoco():
    return compile_mjcf.import_mujoco("sim --engine mujoco, settle and sweep")


@contextlib.contextmanager
def warnings_to(mujoco, notes: list):
    """MuJoCo's warnings into ``notes`` (its own handler writes MUJOCO_LOG.TXT in the working folder)."""
    previous = mujoco.get_mju_user_warning()
    mujoco.set_mju_user_warning(lambda msg: notes.append("MuJoCo: " + str(msg).strip()))
    try:
        yield
    finally:
        mujoco.set_mju_user_warning(previous)


def decide_base(robot, base: str, q: dict | None = None) -> tuple[str, str]:
    """('free' | 'fixed', why). ``planar``: free, and a mecanum, omni or planar base gets convert's
    planar base (``convert --to mjcf`` does so under ``--base auto``). ``auto``: a wheeled base (model/drive.is_mobile) or a robot that stands
    on legs (model/legs.stance) is free; anything else is welded where it stands."""
    if base in ("free", "fixed"):
        return base, f"--base {base}"
    if base == "planar":
        return "free", "a base moved as a body in the plane (slides and a yaw hinge)"
    if D.is_mobile(robot):
        return "free", "a wheeled base (it declares a drive or has wheels)"
    s = stance(robot, q)
    if s.legged:
        return "free", f"it stands on legs: {s.why}"
    return "fixed", f"welded where it stands: {s.why}"


def mjcf_in_memory(robot, base: str):
    """(MJCF text, {file name: bytes} of its meshes, convert's MjcfResult) of ``convert --to mjcf``,
    through a temporary folder that is gone when this returns."""
    import tempfile
    from pathlib import Path

    with tempfile.TemporaryDirectory(prefix="myrabot-desc-sim-") as folder:
        out = Path(folder) / "robot.xml"
        res = convert_mjcf(robot, str(out), base=base, scene=None, allow_errors=True)
        assets = {p.relative_to(folder).as_posix(): p.read_bytes() for p in Path(folder).rglob("*")
                  if p.is_file() and p != out}
        text = out.read_text(encoding="utf-8")
    return text, assets, res


class Engine:
    """The compiled model on a floor, with the maps from MuJoCo's ids to the robot's names."""

    def __init__(self, robot, base: str = "auto", q0: dict | None = None, floor: bool = True,
                 keep_excludes: bool = True):
        self.robot = robot
        self.notes: list[str] = []
        self.mujoco = mj = import_mujoco()
        self.base, self.base_why = decide_base(robot, base, q0)
        with warnings_to(mj, self.notes):
            text, assets, res = mjcf_in_memory(robot, "auto" if base == "planar" else self.base)
            self.convert_notes = [str(w) for w in getattr(res.notes, "warnings", [])]
            self.report = res.report
            spec = mj.MjSpec.from_string(text, assets=assets)
            self.excluded = [(e.bodyname1, e.bodyname2) for e in spec.excludes]
            if not keep_excludes:
                for e in list(spec.excludes):
                    spec.delete(e)
            if floor:
                spec.worldbody.add_geom(name=FLOOR, type=mj.mjtGeom.mjGEOM_PLANE, size=[0, 0, 0.05])
            spec.option.enableflags |= int(mj.mjtEnableBit.mjENBL_ENERGY)
            self.spec = spec
            self.model = m = spec.compile()
        self.data = mj.MjData(m)
        self.writer_gravcomp = {m.body(b).name for b in range(m.nbody) if m.body_gravcomp[b] > 0}
        m.body_gravcomp[:] = 0.0             # our own policy: see hold_policy
        self.floor = mj.mj_name2id(m, mj.mjtObj.mjOBJ_GEOM, FLOOR) if floor else -1
        free = [j for j in range(m.njnt) if m.jnt_type[j] == mj.mjtJoint.mjJNT_FREE]
        self.free_joint = free[0] if free else None
        self.free_adr = int(m.jnt_qposadr[free[0]]) if free else None
        self.root_body = int(m.jnt_bodyid[free[0]]) if free else None
        hinge_slide = (int(mj.mjtJoint.mjJNT_HINGE), int(mj.mjtJoint.mjJNT_SLIDE))
        self.joint_ids = {m.joint(j).name: j for j in range(m.njnt) if int(m.jnt_type[j]) in hinge_slide
                          and m.joint(j).name in robot.joints}
        self.actuators = {m.actuator(a).name: a for a in range(m.nu)}
        self.velocity_actuators = {n for n, a in self.actuators.items()
                                   if m.actuator_biasprm[a][1] == 0 and m.actuator_biasprm[a][2] != 0}
        self.position_actuators = {n for n in self.actuators if n not in self.velocity_actuators}
        self.geom_link = {}                  # geom id -> (link, collision index)
        for g in range(m.ngeom):
            name = m.geom(g).name
            hit = _GEOM_NAME.match(name) if name else None
            if hit and hit.group("link") in robot.links:
                self.geom_link[g] = (hit.group("link"), int(hit.group("k") or 0))
        self.body_name = [m.body(b).name for b in range(m.nbody)]
        limit_steps = limit("max_physics_steps")
        self.max_steps = limit_steps

    # ------------------------------------------------------------------ names and places
    def link_of_geom(self, g: int) -> str:
        hit = self.geom_link.get(g)
        return hit[0] if hit else self.body_name[self.model.geom_bodyid[g]] or "world"

    def collision_loc(self, g: int):
        """The file:line of the <collision> a geom comes from (None when unknown)."""
        hit = self.geom_link.get(g)
        if hit is None:
            return None
        link = self.robot.links.get(hit[0])
        if link is None or hit[1] >= len(link.collisions):
            return link.loc if link is not None else None
        return link.collisions[hit[1]].loc

    def body_of_link(self, link: str) -> int:
        """The MuJoCo body a link ended up in (its own, or the one it is fused into)."""
        mj, m = self.mujoco, self.model
        cur = link
        for _ in range(len(self.robot.joints) + 1):
            b = mj.mj_name2id(m, mj.mjtObj.mjOBJ_BODY, cur)
            if b >= 0:
                return b
            j = self.robot.parent_joint(cur)
            if j is None:
                break
            cur = j.parent
        return 0

    # ------------------------------------------------------------------ poses
    def qpos_for(self, q: dict):
        """qpos with the joints at ``q`` (others at the ``home`` keyframe's values), mimic joints where
        their targets put them, a free base lowered or raised so that its lowest collision point touches
        the floor."""
        import numpy as np

        mj, m, d = self.mujoco, self.model, self.data
        if m.nkey:
            mj.mj_resetDataKeyframe(m, d, 0)
        else:
            mj.mj_resetData(m, d)
        full = dict(q)
        for j in self.robot.joints.values():
            if j.mimic is not None and j.mimic.joint in full:
                full[j.name] = j.mimic.offset + j.mimic.multiplier * full[j.mimic.joint]
        for name, value in full.items():
            jid = self.joint_ids.get(name)
            if jid is not None:
                d.qpos[m.jnt_qposadr[jid]] = value
        if self.free_adr is not None:
            d.qpos[self.free_adr + 3:self.free_adr + 7] = (1.0, 0.0, 0.0, 0.0)
            mj.mj_kinematics(m, d)
            low = self.lowest_point()
            if np.isfinite(low):
                d.qpos[self.free_adr + 2] -= low
        mj.mj_forward(m, d)
        return d.qpos.copy()

    def _collision_geoms(self):
        m = self.model
        return [g for g in range(m.ngeom) if g != self.floor and (m.geom_contype[g] or m.geom_conaffinity[g])
                and m.geom_bodyid[g] != 0]

    def geom_bottom(self, g: int) -> float:
        """The lowest world z of geom ``g`` (after mj_kinematics): exact for primitives and mesh vertices."""
        import numpy as np

        mj, m, d = self.mujoco, self.model, self.data
        t = m.geom_type[g]
        R = d.geom_xmat[g].reshape(3, 3)
        z = float(d.geom_xpos[g][2])
        sz = m.geom_size[g]
        if t == mj.mjtGeom.mjGEOM_MESH:
            a, n = m.mesh_vertadr[m.geom_dataid[g]], m.mesh_vertnum[m.geom_dataid[g]]
            return float(z + (m.mesh_vert[a:a + n] @ R[2]).min())
        if t == mj.mjtGeom.mjGEOM_SPHERE:
            return z - sz[0]
        if t == mj.mjtGeom.mjGEOM_CAPSULE:
            return z - abs(R[2, 2]) * sz[1] - sz[0]
        if t == mj.mjtGeom.mjGEOM_CYLINDER:
            return z - abs(R[2, 2]) * sz[1] - sz[0] * math.sqrt(max(0.0, 1 - R[2, 2] ** 2))
        if t == mj.mjtGeom.mjGEOM_BOX:
            return z - float(np.abs(R[2]) @ sz)
        if t == mj.mjtGeom.mjGEOM_ELLIPSOID:
            return z - float(np.sqrt(((R[2] * sz) ** 2).sum()))
        return math.inf

    def lowest_point(self) -> float:
        """The lowest world z of the robot's collision geoms (after mj_kinematics)."""
        return min((self.geom_bottom(g) for g in self._collision_geoms()), default=math.inf)

    def touching_floor(self, qpos, tol: float = CONTACT_TOL) -> list:
        """(body id, link) of every collision geom within ``tol`` of the floor at ``qpos``: what the
        robot stands on there (model/support.py's 5 mm), a welded robot's resting parts included."""
        mj, m, d = self.mujoco, self.model, self.data
        d.qpos[:] = qpos
        mj.mj_kinematics(m, d)
        return sorted({(int(m.geom_bodyid[g]), self.link_of_geom(g)) for g in self._collision_geoms()
                       if self.geom_bottom(g) <= tol}, key=lambda x: x[1])

    def hold(self, qpos) -> None:
        """Controls that hold ``qpos``: position actuators at their joints' values, wheels at rest."""
        m, d = self.model, self.data
        for name, a in self.actuators.items():
            jid = m.actuator_trnid[a][0]
            d.ctrl[a] = 0.0 if name in self.velocity_actuators else float(qpos[m.jnt_qposadr[jid]])

    # ------------------------------------------------------------------ holding torque
    def gravity_torques(self) -> dict:
        """joint -> |gravity torque| on it in the current state (qfrc_bias at rest: gravity alone)."""
        m, d = self.model, self.data
        return {n: abs(float(d.qfrc_bias[m.jnt_dofadr[j]])) for n, j in self.joint_ids.items()}

    def holding_torques(self, qpos, seconds: float = 0.0) -> dict:
        """joint -> the torque (force) holding ``qpos`` takes: gravity alone (qfrc_bias) when
        ``seconds`` is 0, else the mean |actuator force| over the second half of a run with no force
        limits (a robot standing on its feet: the legs carry the body through the ground)."""
        import numpy as np

        mj, m, d = self.mujoco, self.model, self.data
        if not seconds:
            d.qpos[:] = qpos
            d.qvel[:] = 0.0
            mj.mj_forward(m, d)
            return self.gravity_torques()
        saved, grav = m.actuator_forcelimited.copy(), m.body_gravcomp.copy()
        try:
            m.actuator_forcelimited[:] = 0
            m.body_gravcomp[:] = 0.0
            mj.mj_resetData(m, d)
            d.qpos[:] = qpos
            self.hold(qpos)
            n = max(2, int(seconds / m.opt.timestep))
            acc, count = np.zeros(m.nu), 0
            for k in range(n):
                mj.mj_step(m, d)
                if k >= n // 2:
                    acc += np.abs(d.actuator_force)
                    count += 1
        finally:
            m.actuator_forcelimited[:] = saved
            m.body_gravcomp[:] = grav
        mean = acc / max(count, 1)
        return {name: float(mean[a]) for name, a in self.actuators.items()}

    def hold_policy(self, needs: dict, contact_loads: bool = False) -> tuple[list, list]:
        """Joints whose holding torque ``needs`` exceeds the effort limit: up to COUNTERBALANCE_RATIO
        times it, a counterbalance (or a motor stronger than the URDF says) is assumed: the bodies the
        joint moves are gravity-compensated, as a counterbalance spring does (as ``convert --to mjcf``
        does past 80% of the limit); a joint that carries the robot through the ground
        (``contact_loads``: a leg) gets its actuator's force limit raised to 1.25x the need instead,
        which compensation cannot give. Beyond the ratio the joint keeps its limit and sags.
        Returns (helped [(joint, need, effort)], too weak [(joint, need, effort)])."""
        m = self.model
        raised, weak = [], []
        for name in sorted(self.position_actuators):
            j = self.robot.joints.get(name)
            effort = effort_of(j) if j is not None else None
            need = needs.get(name, 0.0)
            if effort is None or not need > effort:
                continue
            if need <= COUNTERBALANCE_RATIO * effort:
                if contact_loads:
                    a = self.actuators[name]
                    m.actuator_forcerange[a] = [-1.25 * need, 1.25 * need]
                else:
                    top = m.jnt_bodyid[self.joint_ids[name]]
                    for b in range(m.nbody):
                        up = b
                        while up > top:
                            up = m.body_parentid[up]
                        if up == top:
                            m.body_gravcomp[b] = 1.0
                raised.append((name, need, effort))
            else:
                weak.append((name, need, effort))
        return raised, weak

    def exclude_touching(self, qpos) -> list:
        """Exclude from collision the body pairs of the robot in contact at ``qpos`` (the start pose,
        where convert excluded those at its home pose): they start touching, and a contact that
        starts inside another pushes the robot apart. Returns the (body, body) names excluded."""
        mj, m, d = self.mujoco, self.model, self.data
        d.qpos[:] = qpos
        mj.mj_forward(m, d)
        pairs = set()
        for g1, g2 in (d.contact.geom if d.ncon else ()):
            if self.floor in (g1, g2):
                continue
            b1, b2 = self.body_name[m.geom_bodyid[g1]], self.body_name[m.geom_bodyid[g2]]
            pairs.add(tuple(sorted((b1 or "world", b2 or "world"))))
        if not pairs:
            return []
        with warnings_to(mj, self.notes):
            for b1, b2 in sorted(pairs):
                self.spec.add_exclude(bodyname1=b1, bodyname2=b2)
            self.model = m = self.spec.compile()
        self.data = mj.MjData(m)
        m.body_gravcomp[:] = 0.0
        self.data.qpos[:] = qpos
        mj.mj_forward(m, self.data)
        return sorted(pairs)

    # ------------------------------------------------------------------ contacts
    def floor_loads(self, wheel_bodies, forward):
        """(share of the floor's normal force on ``wheel_bodies``, friction force of the other floor
        contacts along ``forward``: positive drags the base back)."""
        import numpy as np

        mj, m, d = self.mujoco, self.model, self.data
        f = np.zeros(6)
        on_wheels = total = drag = 0.0
        for i in range(d.ncon):
            c = d.contact[i]
            if self.floor not in (c.geom1, c.geom2):
                continue
            mj.mj_contactForce(m, d, i, f)
            world = c.frame.reshape(3, 3).T @ f[:3]      # the force on geom2 (the floor is geom1 or 2)
            if c.geom2 == self.floor:
                world = -world
            body = m.geom_bodyid[c.geom2 if c.geom1 == self.floor else c.geom1]
            total += abs(float(f[0]))
            if body in wheel_bodies:
                on_wheels += abs(float(f[0]))
            else:
                drag -= float(world @ forward)
        return (on_wheels / total if total > 0 else None), drag

    def on_floor(self, exclude=()) -> set:
        """The links whose collisions touch the floor now, but for those of the bodies ``exclude``."""
        m, d = self.model, self.data
        out = set()
        for i in range(d.ncon):
            g1, g2 = int(d.contact[i].geom1), int(d.contact[i].geom2)
            if self.floor in (g1, g2):
                g = g2 if g1 == self.floor else g1
                if int(m.geom_bodyid[g]) not in exclude:
                    out.add(self.link_of_geom(g))
        return out

    def rubbing(self, bodies) -> set:
        """(body in ``bodies``, other link) pairs of the robot's own collisions in contact now."""
        m, d = self.model, self.data
        out = set()
        for i in range(d.ncon):
            g1, g2 = int(d.contact[i].geom1), int(d.contact[i].geom2)
            if self.floor in (g1, g2):
                continue
            b1, b2 = int(m.geom_bodyid[g1]), int(m.geom_bodyid[g2])
            if b1 in bodies:
                out.add((b1, self.link_of_geom(g2)))
            if b2 in bodies:
                out.add((b2, self.link_of_geom(g1)))
        return out

    def steps(self, seconds: float) -> int:
        n = int(math.ceil(seconds / self.model.opt.timestep))
        if n > self.max_steps:
            raise InputError(f"{seconds:g} s at MuJoCo's {self.model.opt.timestep:g} s step is {n} steps, over the "
                             f"{self.max_steps} allowed (MYRABOT_DESC_MAX_PHYSICS_STEPS)")
        return n


class Path:
    """Samples of a point fixed in a body: time, world x and y, and the body's yaw, unwrapped; and
    how far the body tilts from the way it stood at the first sample (a base that turned over)."""

    def __init__(self):
        self.t: list[float] = []
        self.x: list[float] = []
        self.y: list[float] = []
        self.yaw: list[float] = []
        self.tilt: list[float] = []      # degrees from how it stood at the first sample
        self.max_tilt = 0.0
        self.turned_over: int | None = None   # the first sample tilted past TURNED_OVER
        self._last = None
        self._up0 = None

    def sample(self, t: float, R, p) -> None:
        """Record the point at world position ``p`` of a body with rotation ``R`` at time ``t``."""
        yaw = math.atan2(R[1, 0], R[0, 0])
        turned = 0.0 if self._last is None else self.yaw[-1] + math.remainder(yaw - self._last, 2 * math.pi)
        self._last = yaw
        # the world's up in the body frame, against the first sample's: a root frame that is not
        # upright in the model still starts at 0
        up = (float(R[2, 0]), float(R[2, 1]), float(R[2, 2]))
        if self._up0 is None:
            self._up0 = up
        cos = sum(a * b for a, b in zip(up, self._up0))
        tilt = math.degrees(math.acos(max(-1.0, min(1.0, cos))))
        self.max_tilt = max(self.max_tilt, tilt)
        if self.turned_over is None and tilt > TURNED_OVER:
            self.turned_over = len(self.t)
        self.t.append(t)
        self.x.append(float(p[0]))
        self.y.append(float(p[1]))
        self.yaw.append(turned)
        self.tilt.append(tilt)

    def upright(self, segments):
        """The "stays upright" check of a run, and the segment (of ``segments``, dicts with their
        "end" sample) in which the body turned over, None when it did not or while it settled."""
        k = self.turned_over
        i = None if k is None else next((i for i, s in enumerate(segments) if k <= s["end"]), None)
        why = ""
        if k is not None:
            where = f" in segment {i + 1}" if i is not None else " while it settled"
            why = (f"it turned over at t = {self.t[k]:.2f} s{where}: the segments from there are not measured "
                   "(their rates would be those of a body on its side)")
        check = Check("stays upright", k is None, round(self.max_tilt, 1), "deg",
                      f"tilts less than {TURNED_OVER:g} deg from how it settled", why)
        return check, None if i is None else segments[i]

    def series(self) -> dict:
        import numpy as np

        return {"base_x_m": np.asarray(self.x), "base_y_m": np.asarray(self.y), "base_yaw_rad": np.asarray(self.yaw),
                "base_tilt_deg": np.asarray(self.tilt)}

    def body_twist(self, a: int, b: int) -> tuple[float, float, float]:
        """The mean body-frame (vx, vy, w) between samples ``a`` and ``b`` (each step's chord at its
        mid heading)."""
        import numpy as np

        T = self.t[b] - self.t[a]
        dx, dy = np.diff(self.x[a:b + 1]), np.diff(self.y[a:b + 1])
        h = (np.asarray(self.yaw[a:b]) + np.asarray(self.yaw[a + 1:b + 1])) / 2
        return (float(np.sum(np.cos(h) * dx + np.sin(h) * dy)) / T, float(np.sum(-np.sin(h) * dx + np.cos(h) * dy)) / T,
                (self.yaw[b] - self.yaw[a]) / T)
