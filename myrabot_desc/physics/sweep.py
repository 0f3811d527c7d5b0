"""``sim sweep``: each movable joint through its range, the others at rest, in MuJoCo.

The robot is welded where it stands and has no floor; MuJoCo's collision pass runs on every body pair
except parent and child (one moving joint apart), the pairs already touching at the rest pose (those
are check P005's findings; ``convert --to mjcf`` excludes them) and the pairs an SRDF given with
``--srdf`` lets touch. Each joint visits ``samples`` evenly spaced values over its range (a full turn
for a continuous joint; wheels, which turn in place, are left out) with mimic joints following. At
every pose:

* self-collisions: two bodies penetrating each other by more than 1 mm, with the depth, the joint and
  value that brings them together, and both collisions' file:line;
* gravity torque: MuJoCo's bias force at rest (gravity alone, the base held) on every joint, against
  its effort limit; the worst of each joint is kept with its pose. Over twice the effort limit fails
  (check P006's error); between 1x and 2x is a note (P006's warning: a counterbalance can make it up).
"""

from __future__ import annotations

import time

from myrabot_desc.errors import InputError
from myrabot_desc.model.collisions import TOUCH
from myrabot_desc.model.srdf import load_srdf
from myrabot_desc.model.statics import effort_of, sample_values
from myrabot_desc.safety import limit
from myrabot_desc.physics.engine import COUNTERBALANCE_RATIO, Engine
from myrabot_desc.physics.result import Cause, PhysicsResult
from myrabot_desc.sim.result import Check

DEFAULT_SAMPLES = 25


def run(robot, *, samples: int = DEFAULT_SAMPLES, srdf=None, progress=None) -> PhysicsResult:
    wall0 = time.perf_counter()
    srdf_doc = load_srdf(srdf) if srdf else None
    if srdf_doc is not None and not srdf_doc.describes_collisions:
        srdf_doc = None
    rest = robot.rest_pose()
    eng = Engine(robot, "fixed", rest, floor=False, keep_excludes=False)
    mj, m, d = eng.mujoco, eng.model, eng.data
    res = PhysicsResult("sweep", robot.name, f"MuJoCo {mj.__version__}", 0.0, float(m.opt.timestep))
    res.info["base"] = "welded where it stands (no floor)"
    qrest = eng.qpos_for(rest)

    # pairs touching at rest: left out (check P005 reports them), and the SRDF's
    at_rest = _contacts(eng, qrest, srdf_doc)
    skip = set(at_rest)
    if at_rest:
        res.info["pairs touching at the rest pose, left out"] = ", ".join(
            f"{a}/{b} {depth * 1000:.1f} mm" for (a, b), (depth, _, _) in sorted(at_rest.items())[:8]) + \
            (f" and {len(at_rest) - 8} more" if len(at_rest) > 8 else "")
    wheels = eng.velocity_actuators
    joints = [name for name in eng.joint_ids if name not in wheels and robot.joints[name].mimic is None]
    if wheels:
        res.notes.append(f"wheels not swept (they turn in place): {', '.join(sorted(wheels))}")
    total = len(joints) * samples
    if total > limit("max_sweep_poses"):
        raise InputError(f"{len(joints)} joints x {samples} samples is {total} poses, over the "
                         f"{limit('max_sweep_poses')} allowed (MYRABOT_DESC_MAX_SWEEP_POSES)", robot.loc)
    dof = {name: int(m.jnt_dofadr[j]) for name, j in eng.joint_ids.items()}
    efforts = {name: effort_of(robot.joints[name]) for name in eng.joint_ids}
    worst_torque: dict = {}              # joint -> (torque, swept joint, value)
    hits: dict = {}                      # (link, link) -> (depth, swept joint, value, geom, geom)
    poses = 0
    for k, name in enumerate(joints):
        for x in sample_values(robot.joints[name], samples):
            q = dict(rest)
            q[name] = x
            qpos = eng.qpos_for(q)
            poses += 1
            worst_ratio, worst_joint = 0.0, ""
            for jn, a in dof.items():
                t = abs(float(d.qfrc_bias[a]))
                if t > worst_torque.get(jn, (0.0,))[0]:
                    worst_torque[jn] = (t, name, x)
                if efforts.get(jn) and t / efforts[jn] > worst_ratio:
                    worst_ratio, worst_joint = t / efforts[jn], jn
            deepest, pair = 0.0, ""
            for key, (depth, g1, g2) in _contacts(eng, qpos, srdf_doc, read=False).items():
                if key in skip:
                    continue
                if depth > hits.get(key, (0.0,))[0]:
                    hits[key] = (depth, name, x, g1, g2)
                if depth > deepest:
                    deepest, pair = depth, f"{key[0]}/{key[1]}"
            res.table.append({"joint": name, "value": round(x, 6), "worst_torque_ratio": round(worst_ratio, 6),
                              "worst_torque_joint": worst_joint, "deepest_mm": round(deepest * 1000, 3),
                              "pair": pair})
        if progress:
            progress((k + 1) / max(len(joints), 1))
    res.steps = poses
    res.info["joints swept"] = f"{len(joints)}, {samples} values each"

    causes = []
    for (la, lb), (depth, name, x, g1, g2) in sorted(hits.items(), key=lambda kv: -kv[1][0])[:6]:
        unit = "m" if robot.joints[name].type == "prismatic" else "rad"
        causes.append(Cause(f"link {lb} penetrates link {la} by {depth * 1000:.1f} mm with {name} at {x:.3g} {unit}, "
                            f"the others at rest ({la}'s collision at {_w(eng.collision_loc(g1))})",
                            eng.collision_loc(g2) or (robot.joints[name].loc)))
    deepest = max((h[0] for h in hits.values()), default=0.0)
    res.add(Check("self-collisions", not hits, f"{len(hits)} pair(s)" if hits else "none", "",
                  f"no two bodies of the robot penetrate each other by more than {TOUCH * 1000:g} mm",
                  f"deepest {deepest * 1000:.1f} mm" if hits else ""), causes)

    ratios = {jn: t / efforts[jn] for jn, (t, _, _) in worst_torque.items() if efforts.get(jn)}
    over = sorted((jn for jn, r in ratios.items() if r > 1.0), key=lambda jn: -ratios[jn])
    fail = [jn for jn in over if ratios[jn] > COUNTERBALANCE_RATIO]
    torque_causes = []
    for jn in over:
        t, name, x = worst_torque[jn]
        j = robot.joints[jn]
        unit = "N" if j.type == "prismatic" else "N·m"
        text = (f"joint {jn} needs {t:.3g} {unit} with {name} at {x:.3g}, the others at rest: over its effort "
                f"limit {efforts[jn]:g} {unit} ({ratios[jn]:.2g}x)")
        if jn in fail:
            torque_causes.append(Cause(text, j.loc))
        else:
            res.notes.append(text + f"; up to {COUNTERBALANCE_RATIO:g}x a counterbalance can make it up "
                             "(check P006 warns)")
    top = max(ratios, key=ratios.get, default=None)
    res.add(Check("gravity torque within effort", not fail, ratios[top] if top else 0.0, "x effort",
                  f"<= {COUNTERBALANCE_RATIO:g}x the effort limit on every joint", f"worst: {top}" if top else ""),
            torque_causes)
    unlimited = sorted((jn for jn in worst_torque if not efforts.get(jn) and worst_torque[jn][0] > 1.0),
                       key=lambda jn: -worst_torque[jn][0])
    if unlimited:
        res.notes.append("no effort limit on " + ", ".join(f"{jn} (needs up to {worst_torque[jn][0]:.3g})"
                                                          for jn in unlimited[:5]))
    res.info["largest gravity torque"] = {jn: round(worst_torque[jn][0], 4) for jn in
                                          sorted(worst_torque, key=lambda x: -worst_torque[x][0])[:6]}
    res.notes.extend(eng.notes)
    res.wall = time.perf_counter() - wall0
    return res


def _w(loc) -> str:
    return f"{loc.file}:{loc.line}" if loc is not None and loc.line else (loc.file if loc is not None else "?")


def _contacts(eng, qpos, srdf_doc, read: bool = True) -> dict:
    """(link, link) -> (deepest penetration, geom, geom) of the robot's self-contacts at ``qpos``
    deeper than TOUCH, the SRDF's allowed pairs left out (``read``: set the pose first)."""
    mj, m, d = eng.mujoco, eng.model, eng.data
    if read:
        d.qpos[:] = qpos
        mj.mj_forward(m, d)
    out: dict = {}
    if not d.ncon:
        return out
    for (g1, g2), dist in zip(d.contact.geom, d.contact.dist):
        if -dist <= TOUCH:
            continue
        la, lb = eng.link_of_geom(g1), eng.link_of_geom(g2)
        if srdf_doc is not None and (srdf_doc.allows(la, lb) or srdf_doc.allows(
                eng.body_name[m.geom_bodyid[g1]], eng.body_name[m.geom_bodyid[g2]])):
            continue
        key = tuple(sorted((la, lb)))
        g1, g2 = (g1, g2) if (la, lb) == key else (g2, g1)
        if -dist > out.get(key, (0.0,))[0]:
            out[key] = (-float(dist), int(g1), int(g2))
    return out
