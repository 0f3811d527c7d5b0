"""``sim settle``: does the robot stand? N seconds in MuJoCo from its start pose, the actuators holding it.

The robot starts at its start pose (physics/pose.py) with a free base lowered onto the floor, or
welded where it stands (engine.decide_base), every position actuator holding its joint there and
every wheel at rest. Checks, over the run:

* finite: no NaN and no MuJoCo instability warning;
* free base: height drift, tilt and horizontal drift of the root within tolerance;
* ground contacts: only the bodies that touched the ground at the start (feet, wheels, casters)
  touch it; a welded robot's moving bodies not at all;
* self-contacts: no two bodies of the robot that convert did not exclude penetrate each other
  (and, with an SRDF, none overlaps at the start unless the SRDF lets the pair touch);
* joint drift: every position-held joint stays within DRIFT of its start value;
* holding torque: every held joint needs at most twice its effort limit to hold the start pose (gravity
  on what it carries; for a robot on legs, measured holding it with unlimited actuators); between 1x
  and 2x a counterbalance is assumed (engine.COUNTERBALANCE_RATIO), as check P006 warns;
* energy: the kinetic energy never exceeds the potential energy of the centre of mass above the floor
  (all gravity could give it): more comes from an unstable integration.

A failure is explained in model terms at its file:line: the centre of mass outside the support
polygon of the ground contacts (by how much), a joint that cannot hold (the torque it needs, measured
by holding the pose with unlimited actuators, against its effort limit), a link penetrating another
(by how much, both collisions' file:line), the lightest body when the integration blows up.
"""

from __future__ import annotations

import math
import time

from myrabot_desc.model.collisions import TOUCH, Scene
from myrabot_desc.model.kinematics import center_of_mass
from myrabot_desc.model.srdf import load_srdf
from myrabot_desc.model.statics import effort_of
from myrabot_desc.model.support import ground_support, signed_distance
from myrabot_desc.physics.engine import COUNTERBALANCE_RATIO, Engine
from myrabot_desc.physics.pose import start_pose
from myrabot_desc.physics.result import Cause, PhysicsResult, printable
from myrabot_desc.sim.result import Check

HEIGHT_TOL = 0.02        # m: the root may sink or rise this much (soft contacts, compliant joints)
SHIFT_TOL = 0.02         # m: horizontal drift of the root
TILT_TOL = 3.0           # degrees
DRIFT = {"hinge": 0.1, "slide": 0.01}    # rad, m: a held joint's largest excursion from its start value
SAMPLE_RATE = 100.0      # Hz: series, contacts and drift are sampled this often
EDGE = 0.005             # m: a centre of mass closer than this to the support polygon's edge does not stand (P001)
HOLD_SECONDS = 0.5       # s: how long a legged robot is held with unlimited actuators to measure what it needs
NEAR_FLOOR = 0.05        # m: see the welded robot's ground contacts
SETTLED_SPEED = 0.05     # rad/s (m/s): a joint moving slower than this at the end has come to rest


def run(robot, *, duration: float = 3.0, base: str = "auto", pose_file=None, srdf=None, state=None,
        progress=None) -> PhysicsResult:
    import numpy as np

    wall0 = time.perf_counter()
    srdf_doc = load_srdf(srdf) if srdf else None
    start = start_pose(robot, pose_file, srdf_doc, state)
    if srdf_doc is not None and not srdf_doc.describes_collisions:
        srdf_doc = None                          # group states only: it says nothing of which pairs may touch
    eng = Engine(robot, base, start.q)
    mj, m, d = eng.mujoco, eng.model, eng.data
    res = PhysicsResult("settle", robot.name, f"MuJoCo {mj.__version__}", duration, float(m.opt.timestep))
    res.info["start pose"] = start.source
    res.info["base"] = f"{eng.base} ({eng.base_why})"
    res.notes.extend(start.notes)
    free = eng.free_adr is not None
    qpos0 = eng.qpos_for(start.q)
    touching = eng.exclude_touching(qpos0)
    mj, m, d = eng.mujoco, eng.model, eng.data
    legged = free and eng.base_why.startswith("it stands on legs")
    needs = eng.holding_torques(qpos0, HOLD_SECONDS if legged else 0.0)
    raised, weak = eng.hold_policy(needs, contact_loads=legged)
    for name, need, effort in raised:
        res.notes.append(f"joint {name} needs {need:.3g} to hold the start pose, over its effort limit {effort:g} "
                         f"(at most {COUNTERBALANCE_RATIO:g}x): a counterbalance or a stronger motor than the URDF "
                         "says is assumed, " + ("its force limit raised to what it needs" if legged else
                                          "the bodies it moves gravity-compensated") + " (check P006 warns)")
    mass, com = center_of_mass(robot, start.q)
    res.info["mass"] = f"{mass:.4g} kg"

    # what touches the ground at the start, and where the centre of mass is over it
    sup = ground_support(robot, start.q, meshes=True) if free else None
    feet = eng.touching_floor(qpos0)
    feet_bodies = {b for b, _ in feet}
    if feet:
        res.info["ground contacts at the start"] = ", ".join(sorted({link for _, link in feet}))
    # overlaps at the start (the same test as check's P005), the SRDF's exclusions respected
    overlaps = _start_overlaps(robot, start.q, srdf_doc)
    if eng.excluded:
        res.info["pairs convert --to mjcf excludes"] = f"{len(eng.excluded)} (touching at its home pose)"
    if touching:
        res.notes.append(f"{len(touching)} body pair(s) touch at the start pose and are left out of collision: "
                         + ", ".join(f"{a}/{b}" for a, b in touching[:6]) + (", ..." if len(touching) > 6 else "")
                         + ("" if srdf_doc is not None else " (check P005 reports overlaps at the rest pose)"))
    passive = [n for n in eng.joint_ids if n not in eng.actuators and robot.joints[n].mimic is None]
    if passive:
        res.info["passive joints"] = f"{len(passive)} ({', '.join(passive[:4])}{', ...' if len(passive) > 4 else ''})"

    # the run
    d.qpos[:] = qpos0
    d.qvel[:] = 0.0
    eng.hold(qpos0)
    mj.mj_forward(m, d)
    n = eng.steps(duration)
    every = max(1, int(round(1.0 / (SAMPLE_RATE * m.opt.timestep))))
    held = {name: eng.joint_ids[name] for name in eng.position_actuators if name in eng.joint_ids}
    adr = {name: int(m.jnt_qposadr[j]) for name, j in held.items()}
    q0 = {name: float(qpos0[a]) for name, a in adr.items()}
    root = eng.root_body
    z0 = float(d.xpos[root][2]) if free else 0.0
    xy0 = d.xpos[root][:2].copy() if free else None
    zaxis0 = d.xmat[root].reshape(3, 3)[:, 2].copy() if free else None
    e0 = float(d.energy[0] + d.energy[1])
    ts, zs, tilts, energies, drifts, kinetic = [], [], [], [], [], []
    height0 = float(d.subtree_com[0][2]) if m.nbody else 0.0       # the centre of mass above the floor
    joint_series = {name: [] for name in held}
    worst_drift: dict = {}
    first_over: dict = {}                # joint -> first time past its tolerance
    fall_t = None                        # first time the base tilted or sank past its tolerance
    ground: dict = {}                    # body -> first time it touched the floor
    self_hits: dict = {}                 # (geom, geom) -> (depth, time)
    blew_up = None
    for k in range(n + 1):
        if k:
            mj.mj_step(m, d)
        if k % every and k != n:
            continue
        t = k * m.opt.timestep
        if not (np.isfinite(d.qpos).all() and np.isfinite(d.qvel).all()) or \
                d.warning[mj.mjtWarning.mjWARN_BADQACC].number:
            blew_up = t
            break
        ts.append(t)
        energies.append(float(d.energy[0] + d.energy[1]) - e0)
        kinetic.append(float(d.energy[1]))
        if free:
            zs.append(float(d.xpos[root][2]) - z0)
            zaxis = d.xmat[root].reshape(3, 3)[:, 2]
            tilts.append(math.degrees(math.acos(max(-1.0, min(1.0, float(zaxis @ zaxis0))))))
            if fall_t is None and (tilts[-1] > TILT_TOL or abs(zs[-1]) > HEIGHT_TOL):
                fall_t = t
        worst = 0.0
        for name, a in adr.items():
            x = float(d.qpos[a]) - q0[name]
            joint_series[name].append(float(d.qpos[a]))
            if abs(x) > abs(worst_drift.get(name, 0.0)):
                worst_drift[name] = x
            kind = "slide" if m.jnt_type[held[name]] == mj.mjtJoint.mjJNT_SLIDE else "hinge"
            worst = max(worst, abs(x) / DRIFT[kind])
            if abs(x) > DRIFT[kind] and name not in first_over:
                first_over[name] = t
        drifts.append(worst)
        if d.ncon:
            geoms, dist = d.contact.geom, d.contact.dist
            for (g1, g2), dd in zip(geoms, dist):
                if g1 == eng.floor or g2 == eng.floor:
                    g = g2 if g1 == eng.floor else g1
                    b = int(m.geom_bodyid[g])
                    if b not in feet_bodies and b != 0 and b not in ground:
                        ground[b] = (t, eng.link_of_geom(g), g)
                elif dd < -TOUCH:
                    key = (int(min(g1, g2)), int(max(g1, g2)))
                    if -dd > self_hits.get(key, (0.0, 0.0))[0]:
                        self_hits[key] = (-float(dd), t)
        if progress:
            progress(k / n)
    res.steps = k
    res.t = np.asarray(ts)
    if free:
        res.series["base_dz_m"] = np.asarray(zs)
        res.series["tilt_deg"] = np.asarray(tilts)
    res.series["energy_change_J"] = np.asarray(energies)
    res.series["joint_drift_share"] = np.asarray(drifts)
    for name, vals in joint_series.items():
        col = f"{name}_{'m' if robot.joints[name].type == 'prismatic' else 'rad'}"
        res.series[col] = np.asarray(vals)
        res.joints.append(col)

    # ------------------------------------------------------------ checks
    res.add(Check("finite", blew_up is None, "yes" if blew_up is None else f"NaN at {blew_up:.3f} s", "",
                  "no NaN, no instability warning"),
            [] if blew_up is None else [_lightest(robot, eng)])
    ratios = {n_: needs[n_] / effort_of(robot.joints[n_]) for n_ in held
              if effort_of(robot.joints[n_]) and n_ in needs}
    top = max(ratios, key=ratios.get, default=None)
    res.add(Check("holding torque", not weak, ratios[top] if top else 0.0, "x effort",
                  f"every held joint needs <= {COUNTERBALANCE_RATIO:g}x its effort limit at the start pose",
                  f"worst: {top}" if top else ""),
            [_cannot_hold(robot, name, need, "at the start pose") for name, need, _ in weak[:4]])
    support_causes = _support_causes(robot, sup, com, start.q) if free else []
    if free and zs:
        dz, tilt = zs[-1], max(tilts)
        shift = float(np.linalg.norm(d.xpos[root][:2] - xy0)) if blew_up is None else float("nan")
        fell = abs(dz) > HEIGHT_TOL or tilt > TILT_TOL
        res.add(Check("height drift", abs(dz) <= HEIGHT_TOL, dz, "m", f"|dz| <= {HEIGHT_TOL:g} m"),
                support_causes if abs(dz) > HEIGHT_TOL and not tilt > TILT_TOL else [])
        res.add(Check("tilt", tilt <= TILT_TOL, tilt, "deg", f"<= {TILT_TOL:g} deg"),
                support_causes if tilt > TILT_TOL else [])
        res.add(Check("horizontal drift", not shift > SHIFT_TOL, shift, "m", f"<= {SHIFT_TOL:g} m"),
                support_causes if shift > SHIFT_TOL and not fell else [])
    if not free:
        # a welded robot stands on its mount: a moving link that started within NEAR_FLOOR of the floor and
        # touches it while every joint holds has been let down by the actuators' compliance (a note)
        bottoms = _start_bottoms(eng, qpos0)
        for b, (t, link, g) in list(ground.items()):
            if bottoms.get(g, math.inf) <= NEAR_FLOOR:
                res.notes.append(f"link {link} touches the floor at {t:.2f} s; it started "
                                 f"{bottoms[g] * 1000:.0f} mm above it and the compliant position actuators "
                                 "let it down")
                del ground[b]
    names = sorted(link for _, link, _ in ground.values())
    started = sorted({link for _, link in feet})
    res.add(Check("ground contacts", not ground, ", ".join(names) if names else
                  ("only " + ", ".join(started) if started else "none"), "",
                  "only what it stood on at the start (feet, wheels, casters)"),
            [Cause(f"link {link} touches the ground at {t:.2f} s: it is not one of the contacts it started on"
                   + (" (falling)" if fall_t is not None and t >= fall_t else ""),
                   eng.collision_loc(g) or (robot.links[link].loc if link in robot.links else None))
             for t, link, g in sorted(ground.values())[:4]])
    self_causes = [Cause(f"link {o.link_b} penetrates link {o.link_a} by {o.depth * 1000:.1f} mm at the start pose "
                         f"({o.shape_b} into {o.shape_a} at {_w(o.loc_a)}); the SRDF does not let them touch", o.loc_b)
                   for o in overlaps] if srdf_doc is not None else []
    if overlaps and srdf_doc is None:
        res.notes.append(f"{len(overlaps)} link pair(s) overlap at the start pose and do not collide here "
                         "(nothing says they may touch; an SRDF that disables the pairs it allows, given with "
                         "--srdf, makes that an error; check P005): "
                         + "; ".join(f"{o.link_b} into {o.link_a} {o.depth * 1000:.1f} mm ({_w(o.loc_b)})"
                                     for o in overlaps[:4]) + ("; ..." if len(overlaps) > 4 else ""))
    if len(self_causes) > 6:
        self_causes = self_causes[:6] + [Cause(f"and {len(self_causes) - 6} more pairs at the start pose")]
    hits = sorted(self_hits.items(), key=lambda kv: -kv[1][0])
    for (g1, g2), (depth, t) in hits[:4]:
        la, lb = eng.link_of_geom(g1), eng.link_of_geom(g2)
        during = " (while falling)" if fall_t is not None and t >= fall_t else ""
        self_causes.append(Cause(f"link {lb} penetrates link {la} by {depth * 1000:.1f} mm at {t:.2f} s{during} "
                                 f"({la}'s collision at {_w(eng.collision_loc(g1))})", eng.collision_loc(g2)))
    worst_self = max([o.depth for o in overlaps] + [h[1][0] for h in hits], default=0.0)
    res.add(Check("self-contacts", not self_causes, worst_self * 1000, "mm",
                  f"no two bodies of the robot penetrate each other by more than {TOUCH * 1000:g} mm"), self_causes)
    drift_name = max(worst_drift, key=lambda n_: abs(worst_drift[n_]) / _tol(m, mj, held[n_]), default=None)
    over = [n_ for n_ in worst_drift if abs(worst_drift[n_]) > _tol(m, mj, held[n_])]
    # a joint that went past its tolerance fails when it cannot hold (its actuator at its force limit)
    # or has not come to rest; one that settled there within its effort is compliant: a note
    saturated = _saturated(eng)
    moving = {n_ for n_ in over if abs(float(d.qvel[m.jnt_dofadr[held[n_]]])) > SETTLED_SPEED}
    drifting = sorted((n_ for n_ in over if n_ in saturated or n_ in moving or blew_up is not None),
                      key=lambda n_: -abs(worst_drift[n_]) / _tol(m, mj, held[n_]))
    for n_ in sorted(set(over) - set(drifting)):
        a = eng.actuators[n_]
        res.notes.append(f"joint {n_} settles {abs(worst_drift[n_]):.3g} "
                         f"{'m' if robot.joints[n_].type == 'prismatic' else 'rad'} from its start within its effort: "
                         f"the MJCF's position actuator is compliant there (kp {float(m.actuator_gainprm[a][0]):.4g})")
    before = [n_ for n_ in drifting if fall_t is None or first_over.get(n_, 0.0) <= fall_t]
    drift_causes = _hold_causes(robot, eng, qpos0, before, needs, legged) if before else []
    after = [n_ for n_ in drifting if n_ not in before]
    if after:
        drift_causes.append(Cause(f"{', '.join(after[:5])}{', ...' if len(after) > 5 else ''} moved after the robot "
                                  f"fell at {fall_t:.2f} s (see the tilt)", robot.joints[after[0]].loc))
    res.add(Check("joint drift", not drifting, abs(worst_drift[drift_name]) if drift_name else 0.0,
                  ("m" if robot.joints[drift_name].type == "prismatic" else "rad") if drift_name else "rad",
                  f"every held joint within {DRIFT['hinge']:g} rad / {DRIFT['slide']:g} m of its start, "
                  "or at rest within its effort", f"largest: {drift_name}" if drift_name else ""), drift_causes)
    gave = _passive_moved(robot, eng, qpos0) if free and not all(
        c.passed for c in res.checks if c.name in ("height drift", "tilt")) else []
    if gave:
        commanded = sorted(eng.actuators)
        more = ", ..." if len(gave) > 6 else ""
        res.causes.append(Cause(f"joints {', '.join(gave[:6])}{more} are passive in the MJCF "
                                f"and give way under the load: the model says what it commands (transmissions, "
                                f"ros2_control, drives) and names only {', '.join(commanded[:4])}"
                                f"{', ...' if len(commanded) > 4 else ''}", robot.joints[gave[0]].loc,
                                next(c.name for c in res.checks
                                     if c.name in ("height drift", "tilt") and not c.passed)))
    if free and fall_t is not None and not before and not support_causes and not gave and joint_series:
        k = min(range(len(ts)), key=lambda i: abs(ts[i] - fall_t))
        moved = sorted(((abs(vals[k] - q0[n_]) / _tol(m, mj, held[n_]), n_) for n_, vals in joint_series.items()),
                       reverse=True)[:2]
        if moved and moved[0][0] > 0.2:
            what = ", ".join(f"{n_} {abs(joint_series[n_][k] - q0[n_]):.3g} "
                             f"{'m' if robot.joints[n_].type == 'prismatic' else 'rad'} (kp "
                             f"{float(m.actuator_gainprm[eng.actuators[n_]][0]):.4g})" for _, n_ in moved)
            first = next(c for c in res.checks if c.name in ("tilt", "height drift", "horizontal drift")
                         and not c.passed)
            res.causes.append(Cause(f"when it tipped at {fall_t:.2f} s the joints that had given most were {what}: "
                                    "their position actuators are too compliant to hold the stance",
                                    robot.joints[moved[0][1]].loc, first.name))
    if free and before:                      # a joint that gave way before the fall explains it
        for c in res.checks:
            if c.name in ("height drift", "tilt", "horizontal drift") and not c.passed and \
                    not any(x.check == c.name for x in res.causes):
                res.causes.append(Cause(f"joint {before[0]} gave way (see joint drift)",
                                        robot.joints[before[0]].loc, c.name))
    bound = max(mass * 9.81 * max(height0, 0.01), 1e-3)
    peak = max(kinetic) if kinetic else 0.0
    res.add(Check("energy", peak <= bound and blew_up is None, peak, "J",
                  f"kinetic energy <= {bound:.3g} J, all the potential energy of its centre of mass above the floor"),
            [_lightest(robot, eng)] if peak > bound or blew_up is not None else [])
    res.notes.extend(eng.notes)
    res.wall = time.perf_counter() - wall0
    if progress:
        progress(1.0)
    return res


def _w(loc) -> str:
    return f"{loc.file}:{loc.line}" if loc is not None and loc.line else (loc.file if loc is not None else "?")


def _tol(m, mj, jid) -> float:
    return DRIFT["slide" if m.jnt_type[jid] == mj.mjtJoint.mjJNT_SLIDE else "hinge"]


def _start_overlaps(robot, q, srdf_doc) -> list:
    """The overlaps at the start pose that nothing allows (an SRDF's, when given), one per link pair,
    hull-only ones left out: check P005's test."""
    seen, out = set(), []
    for o in Scene(robot, True, srdf_doc).overlaps(q):
        key = frozenset((o.link_a, o.link_b))
        if o.allowed is None and not o.hull_only and key not in seen:
            seen.add(key)
            out.append(o)
    return out


def _support_causes(robot, sup, com, q) -> list:
    """Why a free robot falls, from where it stands: its centre of mass against its support polygon."""
    if sup is None:
        return [Cause("nothing of the robot can touch the ground (no collision geometry)", robot.loc)]
    root = robot.links[robot.root].loc if robot.root in robot.links else robot.loc
    poly = sup.polygon
    dist = signed_distance(poly, com[:2])
    contacts = ", ".join(sup.links)
    if len(poly) <= 2:
        what = "one point" if len(poly) == 1 else "one line"
        return [Cause(f"no static support: the ground contacts ({contacts}) touch in {what}, no area to stand on; "
                      f"the centre of mass (x {com[0]:.4g} y {com[1]:.4g}) is {abs(dist) * 1000:.1f} mm off it", root)]
    if dist < 0:
        return [Cause(f"the centre of mass (x {com[0]:.4g} y {com[1]:.4g}) is {-dist * 1000:.1f} mm outside the "
                      f"support polygon of {contacts}", root)]
    if dist < EDGE:
        xs, ys = [p[0] for p in poly], [p[1] for p in poly]
        return [Cause(f"the centre of mass (x {com[0]:.4g} y {com[1]:.4g}) is only {dist * 1000:.1f} mm inside the "
                      f"edge of the support polygon of {contacts} (x {min(xs):.3g} to {max(xs):.3g}, "
                      f"y {min(ys):.3g} to {max(ys):.3g}): the slightest sway tips it", root)]
    return []


def _passive_moved(robot, eng, qpos0) -> list:
    """Joints with no actuator (not mimic) that moved past DRIFT from the start."""
    m, mj, d = eng.model, eng.mujoco, eng.data
    out = []
    for name, jid in eng.joint_ids.items():
        if name in eng.actuators or robot.joints[name].mimic is not None:
            continue
        a = m.jnt_qposadr[jid]
        if abs(float(d.qpos[a] - qpos0[a])) > _tol(m, mj, jid):
            out.append(name)
    return out


def _start_bottoms(eng, qpos0) -> dict:
    """geom -> its lowest point above the floor at the start pose (the current state is kept)."""
    mj, m, d = eng.mujoco, eng.model, eng.data
    saved = d.qpos.copy()
    d.qpos[:] = qpos0
    mj.mj_kinematics(m, d)
    out = {g: eng.geom_bottom(g) for g in eng._collision_geoms()}
    d.qpos[:] = saved
    mj.mj_kinematics(m, d)
    return out


def _saturated(eng) -> set:
    """Joints whose actuator pushes at its force limit now."""
    m, d = eng.model, eng.data
    out = set()
    for name, a in eng.actuators.items():
        top = max(abs(m.actuator_forcerange[a][0]), abs(m.actuator_forcerange[a][1]))
        if m.actuator_forcelimited[a] and abs(float(d.actuator_force[a])) >= 0.99 * top:
            out.add(name)
    return out


def _cannot_hold(robot, name, need, when: str = "") -> Cause:
    """"joint J cannot hold: torque needed T > effort E" at the joint, with where the effort is written."""
    j = robot.joints[name]
    effort = effort_of(j)
    unit = "N" if j.type == "prismatic" else "N·m"
    written = robot.origin(j, "limit.effort").written
    at = f" (effort written at {written.file}:{written.line})" if written is not None and j.loc is not None \
        and (written.file, written.line) != (j.loc.file, j.loc.line) else ""
    return Cause(f"joint {name} cannot hold: torque needed {need:.3g} {unit} > effort {effort:g} {unit}"
                 f"{' ' + when if when else ''}{at}", j.loc)


def _hold_causes(robot, eng, qpos0, drifting, needs, measured: bool) -> list:
    """For each joint that drifted: the torque holding the start pose takes (gravity on what it
    carries; for a robot on legs, measured with unlimited actuators) against its effort limit."""
    if not measured:                         # a fixed or wheeled base: measure it too, the way legs are
        needs = dict(needs, **{k: v for k, v in eng.holding_torques(qpos0, HOLD_SECONDS).items() if k in drifting})
    causes = []
    for name in drifting[:4]:
        j = robot.joints[name]
        effort = effort_of(j)
        unit = "N" if j.type == "prismatic" else "N·m"
        t = needs.get(name)
        if effort is not None and t is not None and t > effort:
            causes.append(_cannot_hold(robot, name, t))
        else:
            a = eng.actuators[name]
            kp = float(eng.model.actuator_gainprm[a][0])
            load = f"the {t:.3g} {unit} it carries" if t is not None else "its load"
            within = f" (within its effort {effort:g} {unit})" if effort is not None else ""
            causes.append(Cause(f"joint {name} gives way under {load}{within}: its position gain kp {kp:.4g} "
                                "is too soft to hold it", j.loc))
    return causes


def _lightest(robot, eng) -> Cause:
    """The lightest moving body: where an unstable integration usually starts."""
    m = eng.model
    moving = [b for b in range(1, m.nbody) if m.body_weldid[b] != 0]
    if not moving:
        return Cause("the integration is unstable", robot.loc)
    b = min(moving, key=lambda x: float(m.body_mass[x]))
    name = eng.body_name[b]
    link = robot.links.get(name)
    loc = (link.inertial.loc if link is not None and link.inertial is not None else None) or \
        (link.loc if link is not None else robot.loc)
    return Cause(printable(f"the integration is unstable: the lightest moving body, {name}, has "
                           f"{float(m.body_mass[b]):.3g} kg and inertia {float(min(m.body_inertia[b])):.3g} kg·m² "
                           "against the actuators and contacts that push it"), loc)
