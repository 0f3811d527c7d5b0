"""MJCF of real bases of every drive kind (issue 25, tests/corpus/drives.yaml): a mecanum or planar
base gets a planar base (slides base_x, base_y and hinge base_yaw with velocity actuators) and moves
in MuJoCo as commanded, standing on the floor; wheels recognised only by shape get velocity
actuators; a swerve base is free, not welded."""

from __future__ import annotations

import math

import pytest

from helpers import drive_args, drive_robots, invoke

mujoco = pytest.importorskip("mujoco")
ROBOTS = {r["id"]: r for r in drive_robots()}
pytestmark = pytest.mark.skipif(not ROBOTS, reason="the real-robot corpus is not here")
BODY_MOVED = ["rosbot_xl_mecanum", "ridgeback", "mpo_700_planar_move", "mpo_700_gz_velocity"]


def _mjcf(args, tmp_path):
    out = tmp_path / "robot.xml"
    res = invoke("convert", "--to", "mjcf", "-q", *args, "-o", out)
    assert res.exit_code == 0, res.output[-2000:]
    return out


def drive_in_mujoco(scene, twist, seconds=2.0):
    """Hold a body twist (vx, vy, w) for ``seconds``: each step the world-frame slides get the twist
    turned by the base's yaw. The achieved body twist over the second half (chord at the mid
    heading), and the lowest collision point's height at the end."""
    from myrabot_desc.convert.mjcf.home import floor_lift

    m = mujoco.MjModel.from_xml_path(str(scene))
    d = mujoco.MjData(m)
    mujoco.mj_resetDataKeyframe(m, d, mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_KEY, "home"))
    act = [mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_ACTUATOR, n) for n in ("base_x", "base_y", "base_yaw")]
    q = [m.jnt_qposadr[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, n)] for n in ("base_x", "base_y", "base_yaw")]
    vx, vy, w = twist
    n = int(round(seconds / m.opt.timestep))
    for i in range(n):
        th = d.qpos[q[2]]
        d.ctrl[act] = (vx * math.cos(th) - vy * math.sin(th), vx * math.sin(th) + vy * math.cos(th), w)
        mujoco.mj_step(m, d)
        if i == n // 2:
            p0 = d.qpos[q].copy()
    p1 = d.qpos[q].copy()
    t = (n - n // 2 - 1) * m.opt.timestep
    mid = (p0[2] + p1[2]) / 2
    dx, dy = p1[0] - p0[0], p1[1] - p0[1]
    got = ((math.cos(mid) * dx + math.sin(mid) * dy) / t, (-math.sin(mid) * dx + math.cos(mid) * dy) / t,
           (p1[2] - p0[2]) / t)
    mujoco.mj_forward(m, d)
    # the robot's own geoms: the floor (world body) left out
    return got, -floor_lift(mujoco, m, d, moving_only=True)


@pytest.mark.parametrize("rid", BODY_MOVED)
def test_a_mecanum_or_planar_base_moves_as_commanded(rid, tmp_path):
    out = _mjcf(drive_args(ROBOTS[rid]), tmp_path)
    text = out.read_text()
    assert "freejoint" not in text and 'name="base_yaw"' in text
    for twist in ((0.3, 0.2, 0.4), (0.0, 0.3, 0.0), (0.2, 0.0, -0.5)):
        got, low = drive_in_mujoco(tmp_path / "scene.xml", twist)
        for c, a in zip(twist, got):
            assert a == pytest.approx(c, abs=0.15 * max(abs(x) for x in twist)), (twist, got)
        assert abs(low) < 0.002, f"{rid}: the lowest point is {low:+.4f} m from the floor"


def test_wheels_recognised_only_by_shape_get_velocity_actuators(tmp_path):
    """Two continuous joints carrying cylinders about a level axle, nothing declared: velocity servos
    (a position servo would turn the wheel to the commanded angle and stop)."""
    wheel = ('<link name="{n}_link"><inertial><mass value="0.5"/><inertia ixx="0.001" iyy="0.001" izz="0.001" '
             'ixy="0" ixz="0" iyz="0"/></inertial><collision><origin rpy="1.5708 0 0"/><geometry>'
             '<cylinder radius="0.05" length="0.02"/></geometry></collision></link><joint name="{n}" '
             'type="continuous"><parent link="base_link"/><child link="{n}_link"/><origin xyz="0 {y} 0"/>'
             '<axis xyz="0 1 0"/><limit effort="5" velocity="10"/></joint>')
    f = tmp_path / "rover.urdf"
    f.write_text('<robot name="rover"><link name="base_link"><inertial><mass value="5"/><inertia ixx="0.1" '
                 'iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial><collision><origin xyz="0.1 0 0"/>'
                 '<geometry><box size="0.3 0.2 0.05"/></geometry></collision></link>'
                 + wheel.format(n="jl", y=0.15) + wheel.format(n="jr", y=-0.15) + "</robot>")
    out = _mjcf([f], tmp_path)
    m = mujoco.MjModel.from_xml_path(str(out))
    for name in ("jl", "jr"):
        a = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_ACTUATOR, name)
        assert a >= 0 and m.actuator_biasprm[a][1] == 0 and m.actuator_biasprm[a][2] < 0   # -kv on the speed
    assert (m.jnt_type == mujoco.mjtJoint.mjJNT_FREE).any()


def test_a_swerve_base_is_free_not_welded(tmp_path):
    out = _mjcf(drive_args(ROBOTS["mpo_700"]), tmp_path)
    m = mujoco.MjModel.from_xml_path(str(out))
    assert (m.jnt_type == mujoco.mjtJoint.mjJNT_FREE).any()


def test_an_ackermann_car_with_effort_minus_one_converts_without_a_force_cap(tmp_path):
    """Audibot writes effort and velocity -1 (SDF's "no limit") on every joint: MuJoCo refused the
    actuators' reversed ranges; now no force or speed limit, and the wheels are velocity-driven."""
    out = _mjcf(drive_args(ROBOTS["audibot"]), tmp_path)
    m = mujoco.MjModel.from_xml_path(str(out))
    for name in ("wheel_rl_joint", "wheel_rr_joint"):
        a = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_ACTUATOR, name)
        assert a >= 0 and m.actuator_biasprm[a][2] < 0 and not m.actuator_forcelimited[a]
        assert not m.jnt_actfrclimited[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, name)]
    for name in ("steer_fl_joint", "steer_fr_joint"):           # steering in position
        a = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_ACTUATOR, name)
        assert a >= 0 and m.actuator_biasprm[a][1] < 0


def test_a_swerve_base_moves_as_commanded_by_its_modules(tmp_path):
    """MPO-700 (nothing declared; four steered casters on revolute joints): each module's steering
    position actuator points it along the velocity of its steering axis and its wheel's velocity
    actuator rolls at that speed / r (sign by the wheel's axis): the base follows the twist."""
    from myrabot_desc.model import drive as D
    from myrabot_desc.model.loader import load_robot

    r = ROBOTS["mpo_700"]
    out = _mjcf(drive_args(r), tmp_path)
    robot = load_robot(str(drive_args(r)[0]), package_paths=[drive_args(r)[-1]])
    b = D.base(robot)
    kids = robot.joints_by_parent()
    mods = []
    for s in b.steering:
        wj = next(c.name for c in kids[robot.joints[s].child] if c.name in b.wheels)
        w = D.wheel(robot, wj)
        mods.append((s, wj, D.joint_position(robot, s), w.radius, w.forward_sign))
    cx = sum(p[0] for _, _, p, _, _ in mods) / len(mods)
    cy = sum(p[1] for _, _, p, _, _ in mods) / len(mods)
    for twist in ((0.3, 0.0, 0.0), (0.0, 0.3, 0.0), (0.2, 0.1, 0.3)):
        m = mujoco.MjModel.from_xml_path(str(tmp_path / "scene.xml"))
        d = mujoco.MjData(m)
        mujoco.mj_resetDataKeyframe(m, d, m.key("home").id)
        vx, vy, wz = twist
        for s, wj, p, radius, sign in mods:
            mvx, mvy = vx - wz * (p[1] - cy), vy + wz * (p[0] - cx)
            d.ctrl[m.actuator(s).id] = math.atan2(mvy, mvx)
            d.ctrl[m.actuator(wj).id] = math.hypot(mvx, mvy) / radius * sign
        root = m.body(robot.root).id
        free = next(j for j in range(m.njnt) if m.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE)
        qa = m.jnt_qposadr[free]
        n = int(round(3.0 / m.opt.timestep))

        def yaw():
            R = d.xmat[root].reshape(3, 3)
            return math.atan2(R[1, 0], R[0, 0])

        for i in range(n):
            mujoco.mj_step(m, d)
            if i == n // 2:
                p0, y0 = d.qpos[qa:qa + 3].copy(), yaw()
        p1, y1 = d.qpos[qa:qa + 3].copy(), yaw()
        t = (n - n // 2 - 1) * m.opt.timestep
        mid = (y0 + y1) / 2
        dx, dy = p1[0] - p0[0], p1[1] - p0[1]
        got = ((math.cos(mid) * dx + math.sin(mid) * dy) / t, (-math.sin(mid) * dx + math.cos(mid) * dy) / t,
               math.remainder(y1 - y0, 2 * math.pi) / t)
        for c, a in zip(twist, got):
            assert a == pytest.approx(c, abs=0.15 * max(abs(x) for x in twist)), (twist, got)
        assert abs(p1[2] - p0[2]) < 0.002          # rolling on the floor, not sinking or hopping


def test_an_ackermann_car_drives_as_commanded_by_its_steering_and_wheels(tmp_path):
    """Audibot (1820 kg): each steering hinge points along its axis's velocity about the rear axle's
    centre (the Ackermann law), each wheel rolls at its own path speed: straight and within the
    steering lock, the car follows the twist (the rear axle centre, base_footprint, measured)."""
    from myrabot_desc.model import drive as D
    from myrabot_desc.model.loader import load_robot

    r = ROBOTS["audibot"]
    _mjcf(drive_args(r), tmp_path)
    robot = load_robot(str(drive_args(r)[0]), package_paths=[drive_args(r)[-1]])
    b = D.base(robot)
    steered = {robot.joints[n].child for n in b.steering}
    rx = sum(D.joint_position(robot, n)[0] for n in b.wheels if robot.joints[n].parent not in steered) / 2
    for v, w in ((2.0, 0.0), (2.0, 0.45), (3.0, -0.5)):         # radii 4.4 m and 6 m: over the 3.88 m minimum
        m = mujoco.MjModel.from_xml_path(str(tmp_path / "scene.xml"))
        d = mujoco.MjData(m)
        mujoco.mj_resetDataKeyframe(m, d, m.key("home").id)
        for s in b.steering:
            p = D.joint_position(robot, s)
            d.ctrl[m.actuator(s).id] = math.atan2(w * (p[0] - rx), v - w * p[1])
        for n in b.wheels:
            wh, p = D.wheel(robot, n), D.joint_position(robot, n)
            d.ctrl[m.actuator(n).id] = math.hypot(v - w * p[1], w * (p[0] - rx)) / wh.radius * wh.forward_sign
        root = m.body(robot.root).id
        free = next(j for j in range(m.njnt) if m.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE)
        qa = m.jnt_qposadr[free]
        n_steps = int(round(4.0 / m.opt.timestep))

        def yaw():
            R = d.xmat[root].reshape(3, 3)
            return math.atan2(R[1, 0], R[0, 0])

        for i in range(n_steps):
            mujoco.mj_step(m, d)
            if i == n_steps // 2:
                p0, y0 = d.qpos[qa:qa + 3].copy(), yaw()
        p1, y1 = d.qpos[qa:qa + 3].copy(), yaw()
        t = (n_steps - n_steps // 2 - 1) * m.opt.timestep
        assert math.hypot(p1[0] - p0[0], p1[1] - p0[1]) / t == pytest.approx(v, rel=0.15)
        assert math.remainder(y1 - y0, 2 * math.pi) / t == pytest.approx(w, rel=0.15, abs=0.01)
        assert abs(p1[2] - p0[2]) < 0.002
