"""The arm through Pinocchio: forward kinematics, pointing, inverse kinematics; its centre of mass
(model/kinematics).

"Point at" (escoja, seguir), as we define it:

* the **gripper axis** is the forearm's direction continued through the wrist: the
  unit vector from the ``arti2`` joint to the ``arti3`` joint at the zero
  configuration, carried by the wrist link (so it turns with ``arti3``). On the
  simple arm it is the line along the finger plates, from the wrist axis to the
  fingertip midpoint;
* the **tip** is the farthest point of the wrist/gripper collision geometry along
  that axis (0.136 m past the ``arti3`` axis on the simple arm);
* the **pointing error** is the angle between the gripper axis and the ray from the
  ``arti3`` joint to the object's centre (the can's mid-height point).

The IK asks for a zero pointing error with the tip a stand-off distance from the
object's centre (its radius plus 5 cm by default), and resolves the one
remaining degree of freedom toward the home posture. It is solved with
``scipy.optimize.least_squares`` over Pinocchio's forward kinematics, within
the URDF joint limits.
"""

from __future__ import annotations

import math

from myrabot_desc.errors import InputError
from myrabot_desc.model.kinematics import center_of_mass, centers_of_mass, pose_matrix, world_transforms
from myrabot_desc.model.pin_model import build_model
from myrabot_desc.model.shapes import surface_points

ARM_JOINTS = ("base", "arti1", "arti2", "arti3", "pinza")
ALT_NAMES = {"base": ("base_brazo",)}


class Arm:
    def __init__(self, robot, joints=ARM_JOINTS):
        import numpy as np
        import pinocchio as pin

        self.robot = robot
        self.names = []
        for j in joints:
            name = j if j in robot.joints else next((a for a in ALT_NAMES.get(j, ()) if a in robot.joints), None)
            if name is None:
                raise InputError(f"{robot.name}: no arm joint {j!r} (the programs drive the MYRAbot arm: "
                                 f"{', '.join(joints)})", robot.loc)
            self.names.append(name)
        self.model = build_model(robot, lean=True)
        self.data = self.model.createData()
        self.q0 = pin.neutral(self.model)
        self.idx_q = []
        self.jid = []
        for n in self.names:
            if not self.model.existJointName(n):
                raise InputError(f"arm joint {n} is not movable in the Pinocchio model", robot.joints[n].loc)
            jid = self.model.getJointId(n)
            self.jid.append(jid)
            self.idx_q.append(self.model.joints[jid].idx_q)
        self.idx_q = np.array(self.idx_q)
        self.lower = np.array([_lim(robot.joints[n], "lower", -math.pi) for n in self.names])
        self.upper = np.array([_lim(robot.joints[n], "upper", math.pi) for n in self.names])
        self.velocity = [(robot.joints[n].limit.velocity if robot.joints[n].limit else None) for n in self.names]
        self._wrist_setup()

    # ------------------------------------------------------------ configuration
    def full_q(self, qarm):
        q = self.q0.copy()
        q[self.idx_q] = qarm
        return q

    def fk(self, qarm):
        import pinocchio as pin

        pin.forwardKinematics(self.model, self.data, self.full_q(qarm))
        return self.data.oMi

    def _wrist_setup(self):
        """Gripper axis in the wrist joint frame, and the tip distance along it."""
        import numpy as np

        oMi = self.fk(np.zeros(len(self.names)))
        j2, j3 = self.jid[2], self.jid[3]
        p2, p3 = oMi[j2].translation.copy(), oMi[j3].translation.copy()
        d = p3 - p2
        if np.linalg.norm(d) < 1e-9:
            raise InputError("arm: arti2 and arti3 coincide; the gripper axis is undefined", self.robot.loc)
        d /= np.linalg.norm(d)
        R3 = oMi[j3].rotation
        self.axis_local = R3.T @ d
        # tip: the farthest collision point of the wrist's subtree along the axis

        robot = self.robot
        jname = self.names[3]
        sub = _subtree_links(robot, robot.joints[jname].child)
        tf = world_transforms(robot)
        T3 = tf[robot.joints[jname].child]
        best = 0.0

        for ln in sub:
            link = robot.links[ln]
            for c in link.collisions or link.visuals:
                if c.geometry is None:
                    continue
                pts = np.asarray(surface_points(c.geometry, 720, loc=c.loc))
                M = tf[ln] @ pose_matrix(c.origin)
                w = pts @ M[:3, :3].T + M[:3, 3]
                best = max(best, float(((w - T3[:3, 3]) @ d).max()))
        self.tip_length = best if best > 0 else float(np.linalg.norm(p3 - p2))

    def wrist(self, qarm):
        """(wrist joint position, gripper axis, tip point) in the root frame."""
        oMi = self.fk(qarm)
        M = oMi[self.jid[3]]
        a = M.rotation @ self.axis_local
        p = M.translation.copy()
        return p, a, p + self.tip_length * a

    def pointing_error(self, qarm, target) -> float:
        import numpy as np

        p, a, _ = self.wrist(qarm)
        d = np.asarray(target, dtype=float) - p
        n = np.linalg.norm(d)
        if n < 1e-9:
            return 0.0
        return math.degrees(math.acos(max(-1.0, min(1.0, float(a @ d) / n))))

    # ------------------------------------------------------------ IK
    def ik_point(self, target, standoff: float, q_home, q_init=None):
        """Joint angles (radians, every arm joint; the gripper stays at q_home) pointing at target.

        With ``q_init`` (tracking) one solve warm-started there; without it a few
        starts over the base yaw and shoulder bend, keeping the best.
        """
        import numpy as np

        target = np.asarray(target, dtype=float)
        q_home = np.asarray(q_home, dtype=float)
        free = [0, 1, 2, 3]
        lo, hi = self.lower[free] + 1e-6, self.upper[free] - 1e-6

        def res(x):
            q = q_home.copy()
            q[free] = x
            p, a, tip = self.wrist(q)
            d = target - p
            dn = d / (np.linalg.norm(d) or 1.0)
            return np.concatenate([a - dn, [(np.linalg.norm(target - tip) - standoff) * 0.5],
                                   (x - q_home[free]) * 0.01])

        if q_init is not None:
            starts = [np.clip(np.asarray(q_init, dtype=float)[free], lo, hi)]
        else:
            starts = []
            for yaw in np.linspace(-math.pi, math.pi, 8, endpoint=False):
                for bend in (-0.6, 0.6):
                    s = q_home[free].copy()
                    s[0], s[1] = yaw, bend
                    starts.append(np.clip(s, lo, hi))
        best = None
        for s in starts:
            x, cost = _levenberg_marquardt(res, s, lo, hi)
            if best is None or cost < best[1]:
                best = (x, cost)
        q = q_home.copy()
        q[free] = best[0]
        return q

    # ------------------------------------------------------------ mass
    def com(self, qarm):
        """The whole robot's centre of mass with the arm at ``qarm`` (model/kinematics, as check,
        the viewer and the stance compute it)."""
        return center_of_mass(self.robot, dict(zip(self.names, (float(v) for v in qarm))))[1]

    def coms(self, qarms):
        """``com`` of each row of ``qarms``, at once (model/kinematics.centers_of_mass)."""
        import numpy as np

        Q = np.asarray(qarms, dtype=float).reshape(-1, len(self.names))
        return centers_of_mass(self.robot, {n: Q[:, k] for k, n in enumerate(self.names)})[1]


def _levenberg_marquardt(res, x0, lo, hi, iters: int = 100):
    """Small box-projected Levenberg-Marquardt (4 unknowns: scipy's overhead would dominate)."""
    import numpy as np

    x = np.clip(np.asarray(x0, dtype=float), lo, hi)
    r = res(x)
    cost = float(r @ r)
    lam = 1e-3
    h = 1e-7
    for _ in range(iters):
        J = np.empty((len(r), len(x)))
        for i in range(len(x)):
            xp = x.copy()
            xp[i] += h if xp[i] + h <= hi[i] else -h
            J[:, i] = (res(xp) - r) / (xp[i] - x[i])
        A = J.T @ J
        g = J.T @ r
        improved = False
        while lam < 1e10:
            dx = np.linalg.solve(A + lam * np.diag(np.diag(A) + 1e-12), -g)
            xn = np.clip(x + dx, lo, hi)
            rn = res(xn)
            cn = float(rn @ rn)
            if cn < cost:
                step = float(np.abs(xn - x).max())
                x, r, cost = xn, rn, cn
                lam = max(lam / 10, 1e-12)
                improved = True
                break
            lam *= 10
        if not improved or step < 1e-10:
            break
    return x, 0.5 * cost


def _lim(joint, attr, default):
    lim = joint.limit
    v = getattr(lim, attr) if lim is not None else None
    return default if v is None else float(v)


def _subtree_links(robot, link: str) -> list[str]:
    out, stack = [], [link]
    while stack:
        ln = stack.pop()
        out.append(ln)
        stack.extend(j.child for j in robot.child_joints(ln))
    return out
