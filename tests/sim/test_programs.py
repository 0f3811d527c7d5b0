"""sim: the seed's programs on the bundled MYRAbot and the Korean wander_bot, through the CLI."""

from __future__ import annotations

import json
import math
import subprocess
import sys

import pytest
from click.testing import CliRunner

from helpers import ROOT
from myrabot_desc.commands.main import main

WANDER = ROOT / "tests" / "fixtures" / "wander_bot"
WANDER_XACRO = WANDER / "urdf" / "robot.xacro"


def run(*args):
    r = CliRunner().invoke(main, ["sim", *map(str, args)], catch_exceptions=False)
    return r


def run_json(*args):
    r = run(*args, "--json")
    assert r.exit_code in (0, 1), r.output
    return r.exit_code, json.loads(r.output)


def check(doc, name):
    return next(c for c in doc["checks"] if c["name"] == name)


# ---------------------------------------------------------------- vuelta
@pytest.fixture(scope="module")
def vuelta():
    return run_json("vuelta")


def test_vuelta_passes_on_the_bundled_robot(vuelta):
    code, doc = vuelta
    assert code == 0 and doc["verdict"] == "pass", doc


def test_vuelta_radius_and_period(vuelta):
    _, doc = vuelta
    assert check(doc, "circle radius")["value"] == pytest.approx(0.1 / 0.3, rel=1e-4)    # 0.333 m
    assert check(doc, "period")["value"] == pytest.approx(2 * math.pi / 0.3, abs=0.005)  # 20.94 s
    assert check(doc, "period")["value"] == pytest.approx(20.94, abs=0.01)


def test_vuelta_swing_count(vuelta):
    """Independent estimate of the swings: the base servo runs at its URDF velocity limit
    (the AX-12 at 400 units would do 4.65 rad/s) between the reversal readings, which the
    ±110 tolerance puts at 609 and 413 units (the seed's strict inequalities), with
    pose_arm at 100 Hz; reaching 304 costs one more message (cont1 = 1, then 718)."""
    from myrabot_desc.model.loader import load_robot
    from myrabot_desc.sim import servo as sv

    robot = load_robot(None)
    speed = min(sv.speed_rad_s(400), robot.joints["base"].limit.velocity)
    up = 609 * 300 / 1023 * sv.PI / 180 - sv.OFFSET          # first angle that reads 609
    down = 414 * 300 / 1023 * sv.PI / 180 - sv.OFFSET        # below it, the reading is <= 413
    half = (up - down) / speed
    first = (up - sv.units_to_rad(511)) / speed
    # each reversal waits for a reading (half a 10 ms message on average), the bottom one a
    # whole message more (cont1 = 1, then 718); the servo overshoots meanwhile and comes back,
    # so every lag counts twice
    cycle = 2 * half + 2 * (0.005 + 0.005 + 0.01)
    est = 1 + 2 * (25.0 - 1.0 - first - 0.005) / cycle      # reversals after the first 718
    _, doc = vuelta
    swings = check(doc, "arm swings")["value"]
    assert abs(swings - est) <= 2, (swings, est)
    assert doc["info"]["swing commands"] == swings + 1
    # the ±110 tolerance (32°) cuts the ±60° swing (718/304) to about ±30°
    lo, hi = (float(x) for x in doc["info"]["base joint range"].replace(" deg", "").split(" … "))
    assert 27 < hi < 31 and -33 < lo < -29


def test_vuelta_collision_and_tip_over(vuelta):
    _, doc = vuelta
    col = check(doc, "arm collision")
    assert col["passed"] and col["value"] == "none"
    assert "closest" in col["detail"]
    tip = check(doc, "tip-over margin")
    # Roomba support: wheels at y ±0.13, casters at x ±0.13 (a diamond); COM near the centre
    assert 0.06 < tip["value"] < 0.13
    assert "rear_wheel_link" in tip["detail"] and "front_wheel_link" in tip["detail"]


def test_vuelta_imports_no_trimesh_or_scipy():
    """The arm collider reads the bundled STL meshes with the lean reader (model/meshes.py):
    trimesh and with it scipy and networkx (~1 s CPU) are for formats it does not read."""
    code = ("import sys; from click.testing import CliRunner; from myrabot_desc.commands.main import main;"
            "r = CliRunner().invoke(main, ['sim', 'vuelta', '--duration', '5']);"
            "print(r.exit_code, sorted(m for m in ('trimesh', 'scipy', 'networkx') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.split(None, 1) == ["0", "[]\n"]


def test_vuelta_on_the_seed_files_as_written():
    """The Electric-era seed (legacy xacro, gazebo_ros_roomba 0.26/0.066, box arm) passes too;
    its meshes are missing, which the collision check says."""
    seed = ROOT / "tests" / "fixtures" / "seed_myrabot"
    code, doc = run_json("vuelta", seed / "myrabot_fer_modelo" / "urdf" / "myrabot.urdf.xacro",
                         "--package-path", seed)
    assert code == 0
    assert check(doc, "circle radius")["value"] == pytest.approx(1 / 3, rel=1e-4)
    assert any("11 collision mesh(es) could not be read and were left out" in n for n in doc["notes"])


def test_vuelta_press_twice_keeps_turning():
    """The seed sends no zero twist when switched off: the base keeps turning."""
    code, doc = run_json("vuelta", "--press", "1", "--press", "6", "--duration", "10", "--no-collisions")
    assert code == 0
    assert any("keeps turning" in n for n in doc["notes"])
    assert check(doc, "circle radius")["value"] == pytest.approx(1 / 3, rel=1e-4)


def test_vuelta_never_pressed_fails():
    code, doc = run_json("vuelta", "--press", "99", "--duration", "5", "--no-collisions")
    assert code == 1 and doc["verdict"] == "fail"


def test_vuelta_csv_and_plot(tmp_path):
    from PIL import Image

    csv, png = tmp_path / "v.csv", tmp_path / "v.png"
    r = run("vuelta", "--duration", "3", "--csv", csv, "--plot", png, "--no-collisions")
    assert r.exit_code == 0, r.output
    lines = csv.read_text().splitlines()
    assert lines[0] == ("time_s,base_x_m,base_y_m,base_yaw_rad,base_rad,arti1_rad,arti2_rad,arti3_rad,pinza_rad,"
                        "left_wheel_joint_rad,right_wheel_joint_rad")
    assert len(lines) == 1 + 3001
    last = [float(x) for x in lines[-1].split(",")]
    assert last[0] == pytest.approx(3.0)
    # 2 s of turning at 0.3 rad/s after the press at 1 s (the plugin updates at 40 Hz)
    assert last[3] == pytest.approx(0.6, abs=0.3 * 0.025 + 1e-6)
    # wheels: left (0.1 - 0.3*0.13)/0.033 = 1.85 rad/s, right 4.21 rad/s (seed-spec §5.1)
    assert last[-1] / last[-2] == pytest.approx((0.1 + 0.3 * 0.13) / (0.1 - 0.3 * 0.13), rel=1e-6)
    img = Image.open(png)
    assert img.size == (1400, 700) and img.format == "PNG"


def test_deterministic_output(tmp_path):
    a, b = tmp_path / "a.csv", tmp_path / "b.csv"
    for f in (a, b):
        assert run("vuelta", "--duration", "2", "--csv", f, "--no-collisions").exit_code == 0
    assert a.read_bytes() == b.read_bytes()


# ---------------------------------------------------------------- drive: the Korean robot
def test_wander_bot_plugin_vs_urdf():
    args = ("drive", WANDER_XACRO, "-p", f"wander_bot={WANDER}")
    code_p, plug = run_json(*args, "--wheels", "plugin")
    code_u, urdf = run_json(*args, "--wheels", "urdf")
    # plugin 0.4/0.2 vs URDF 0.30/0.16 (seed-spec §6.3)
    assert check(plug, "speed ratio")["value"] == pytest.approx(0.16 / 0.2, abs=1e-6)
    assert check(plug, "turn-rate ratio")["value"] == pytest.approx(0.8 * 0.4 / 0.30, abs=1e-6)
    assert code_p == 1 and plug["verdict"] == "fail"
    assert check(urdf, "speed ratio")["value"] == pytest.approx(1.0, abs=1e-6)
    assert check(urdf, "turn-rate ratio")["value"] == pytest.approx(1.0, abs=1e-6)
    assert code_u == 0
    assert plug["info"]["URDF wheel separation"] == pytest.approx(0.30)
    assert plug["info"]["plugin wheel separation"] == pytest.approx(0.4)
    # and the stance of §6.3: only two wheels, COM 12.5 mm behind the axle
    assert "12.5 mm behind" in plug["info"]["axle"]


def test_drive_custom_twist_and_bad_twist():
    args = ("drive", WANDER_XACRO, "-p", f"wander_bot={WANDER}")
    code, doc = run_json(*args, "--twist", "0.1,0.3,3")
    seg = doc["info"]["segments"][0]
    assert seg["v"] == pytest.approx(0.08, abs=1e-6) and seg["w"] == pytest.approx(0.32, abs=1e-6)
    r = run(*args, "--twist", "0.1,0.3")
    assert r.exit_code == 2 and "V,W,SECONDS" in r.output


def test_legacy_mode_default_turns_the_wrong_way(tmp_path):
    """ROS 1 gazebo_ros_diff_drive: legacyMode (default true) swaps the wheels' turn terms."""
    pkg = tmp_path / "wander_bot"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text((WANDER / "package.xml").read_text())
    (pkg / "urdf" / "robot.xacro").write_text(WANDER_XACRO.read_text())
    g = (WANDER / "urdf" / "robot.gazebo").read_text().replace("<legacyMode>false</legacyMode>", "")
    (pkg / "urdf" / "robot.gazebo").write_text(g)
    code, doc = run_json("drive", pkg / "urdf" / "robot.xacro", "-p", f"wander_bot={pkg}")
    assert check(doc, "turn-rate ratio")["value"] == pytest.approx(-0.8 * 0.4 / 0.30, abs=1e-6)
    assert any("legacyMode" in n for n in doc["notes"])


def test_drive_bundled_robot_matches():
    code, doc = run_json("drive", "--twist", "0.1,0.3,5")
    assert code == 0
    assert check(doc, "speed ratio")["value"] == pytest.approx(1.0, abs=1e-6)


def test_drive_without_plugin_uses_the_urdf_wheels(tmp_path):
    urdf = tmp_path / "bot.urdf"
    urdf.write_text("""<robot name="bot">
  <link name="base"/>
  <link name="lw"><collision><origin rpy="1.5708 0 0"/><geometry><cylinder radius="0.05" length="0.02"/></geometry></collision></link>
  <link name="rw"><collision><origin rpy="1.5708 0 0"/><geometry><cylinder radius="0.05" length="0.02"/></geometry></collision></link>
  <joint name="left_wheel" type="continuous"><parent link="base"/><child link="lw"/><origin xyz="0 0.1 0.05"/><axis xyz="0 1 0"/></joint>
  <joint name="right_wheel" type="continuous"><parent link="base"/><child link="rw"/><origin xyz="0 -0.1 0.05"/><axis xyz="0 1 0"/></joint>
</robot>""")
    code, doc = run_json("drive", urdf, "--twist", "0.2,1,2")
    assert code == 0 and doc["info"]["command geometry"] == "URDF"
    assert any("no drive plugin" in n and "URDF's own wheel geometry" in n for n in doc["notes"])
    code, doc = run_json("drive", urdf, "--wheels", "urdf", "--twist", "0.2,1,2")
    assert code == 0 and doc["info"]["URDF wheel separation"] == pytest.approx(0.2)
    # and the arm programs need the arm
    r = run("vuelta", urdf, "--wheels", "urdf")
    assert r.exit_code == 2 and "no arm joint 'base'" in r.output


def test_wheel_accel_limit_ramps():
    code, doc = run_json("drive", "--twist", "0.2,0,8", "--wheel-accel-max", "2")
    seg = doc["info"]["segments"][0]
    assert code == 0 and seg["v"] == pytest.approx(0.2, rel=1e-6)     # measured after the ramp
    # the ramp costs distance: 0.2/0.033 = 6.06 rad/s at 2 rad/s² takes 3.03 s, losing 0.2*3.03/2 m
    ramp = 0.2 / 0.033 / 2
    assert doc["final_pose"]["x"] == pytest.approx(0.2 * 8 - 0.2 * ramp / 2, abs=1e-6)


# ---------------------------------------------------------------- escoja and seguir
@pytest.mark.parametrize("obj, model, side", [("1", "lata_cocacola", -1), ("2", "lata_amstel", 1)])
def test_escoja_points_at_each_can(obj, model, side):
    code, doc = run_json("escoja", "--object", obj)
    assert code == 0, doc
    err = check(doc, "pointing error")
    assert err["passed"] and err["value"] < 1.0                 # nearest-unit conversion: ≤ 0.5° per joint
    assert model in err["expected"]
    assert check(doc, "returns home")["passed"]
    assert check(doc, "collision")["value"] == "none"
    base = doc["info"]["joint angles"]["base"]
    assert math.copysign(1, base) == side and 20 < abs(base) < 45
    # the lab's truncating conversion leaves the arm low: a larger error, still within 5°
    assert err["value"] < doc["info"]["pointing error, lab conversion"] < 5.0


def test_escoja_lab_units_and_bad_object():
    code, doc = run_json("escoja", "--object", "1", "--units", "lab")
    assert check(doc, "pointing error")["value"] == pytest.approx(2.83, abs=0.05)
    r = run("escoja", "--object", "3")
    assert r.exit_code == 2 and "2 selectable objects" in r.output


def test_seguir_tracks_the_can():
    code, doc = run_json("seguir")
    assert code == 0, doc
    tr = check(doc, "tracking error")
    assert tr["passed"] and tr["value"] < 5.0
    assert doc["info"]["tracking RMS while moving"] < 1.5
    assert doc["info"]["path"].startswith("152 steps of 0.005 m")
    assert check(doc, "collision")["value"] == "none"
    # a can moved faster than the arm re-aims: 2 Hz updates lose it
    code, slow = run_json("seguir", "--track-rate", "0.5")
    assert code == 1 and check(slow, "tracking error")["value"] > 5.0


def test_seguir_bad_keys():
    r = run("seguir", "--keys", "Z*3")
    assert r.exit_code == 2 and "unknown key" in r.output


def test_help_has_examples():
    for sub in ("vuelta", "escoja", "seguir", "drive"):
        r = run(sub, "--help")
        assert r.exit_code == 0 and "Examples:" in r.output and f"myrabot-desc sim {sub}" in r.output


# ---------------------------------------------------------------- the collision check
def test_vuelta_switched_off_mid_swing_hits_the_webcam():
    """Switched off at 6 s, the arm runs on to its last target (304, -60°) with no ±110
    reversal and the gripper goes into the webcam: the check must say so."""
    code, doc = run_json("vuelta", "--press", "1", "--press", "6", "--press", "9.5", "--duration", "20")
    col = check(doc, "arm collision")
    assert code == 1 and not col["passed"]
    assert col["value"] == "pinza_link_0 – e_webcam_2_link_0 at 6.243 s"
    assert "closest -8.3 mm (pinza_link_0 – e_webcam_2_link_0)" in col["detail"]


@pytest.fixture(scope="module")
def arm_and_colliders():
    from myrabot_desc.expand.packages import data_root
    from myrabot_desc.model.loader import load_robot
    from myrabot_desc.sim import collide, scene
    from myrabot_desc.sim.arm import Arm

    arm = Arm(load_robot(None))
    esc = scene.load_layout(data_root() / "layouts" / "escoja.yaml")
    return arm, [collide.ArmCollider(arm), collide.ArmCollider(arm, esc)]


def _every_pair(col, times, qarms, q_ref):
    """What the check reports, the slow way: every active pair at every pose, every distance."""
    import numpy as np
    import pinocchio as pin

    from myrabot_desc.sim.collide import PROBES, cold_gjk

    arm, gm = col.arm, col.gmodel
    gd = pin.GeometryData(gm)
    cold_gjk(gd)
    pin.computeCollisions(arm.model, arm.data, gm, gd, arm.full_q(q_ref), False)
    active = [k for k in range(len(gm.collisionPairs)) if not gd.collisionResults[k].isCollision()]
    name = col._name
    hits, best = [], (np.inf, None)
    probe = set(np.linspace(0, len(qarms) - 1, min(PROBES, len(qarms))).astype(int).tolist())
    probe |= set(qarms.argmin(axis=0).tolist()) | set(qarms.argmax(axis=0).tolist())
    for i, (t, qa) in enumerate(zip(times, qarms)):
        q = arm.full_q(qa)
        for k in active:
            cp = gm.collisionPairs[k]
            pin.updateGeometryPlacements(arm.model, arm.data, gm, gd, q)
            if pin.computeCollision(gm, gd, k):
                hits.append((float(t), name(cp.first), name(cp.second)))
        if i in probe:
            for k in active:
                d = pin.computeDistance(gm, gd, k).min_distance
                if d < best[0]:
                    best = (d, (name(gm.collisionPairs[k].first), name(gm.collisionPairs[k].second)))
    return hits, best


def test_broadphase_and_pruned_distances_match_every_pair(arm_and_colliders):
    """The check's broadphase and its bounded distance search report exactly what testing
    every pair at every pose does, on poses that hit the structure, the table and the cans,
    and on a vuelta-like swing that only comes close; and the same again when repeated
    (no dependence on the poses checked before)."""
    import numpy as np

    from myrabot_desc.sim import servo as sv

    arm, cols = arm_and_colliders
    q_home = np.array([sv.units_to_rad(sv.UNITS_HOME)] * 5)
    rng = np.random.default_rng(3)
    swing = np.tile(q_home, (60, 1))
    swing[:, 0] = np.linspace(-0.55, 0.55, 60)
    sets = [rng.uniform(arm.lower, arm.upper, size=(25, 5)),
            np.clip(q_home + rng.normal(0, 0.3, size=(25, 5)), arm.lower, arm.upper), swing]
    hit_any = clear_any = False
    for qarms in sets:
        times = np.arange(len(qarms)) * 0.01
        for col in cols:
            rep = col.check(times, qarms, q_home)
            hits, (dmin, pair) = _every_pair(col, times, qarms, q_home)
            assert rep.hits == hits
            assert (rep.min_distance, rep.min_pair) == (dmin, pair)
            again = col.check(times, qarms, q_home)
            assert (again.hits, again.min_distance) == (rep.hits, rep.min_distance)
            hit_any |= bool(hits)
            clear_any |= not hits
    assert hit_any and clear_any


def test_cold_gjk_gives_every_pair_the_request_set_one_by_one(arm_and_colliders):
    """cold_gjk copies one request with the warm start off over a fresh GeometryData's: every pair
    ends with what switching the flag off pair by pair gives (the serialized request, every field)."""
    import warnings

    import pinocchio as pin

    from myrabot_desc.sim.collide import cold_gjk

    _arm, cols = arm_and_colliders
    for col in cols:
        fast, slow = pin.GeometryData(col.gmodel), pin.GeometryData(col.gmodel)
        cold_gjk(fast)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", DeprecationWarning)
            for r in (*slow.collisionRequests, *slow.distanceRequests):
                assert r.enable_cached_gjk_guess      # what Pinocchio sets, and cold_gjk undoes
                r.enable_cached_gjk_guess = False
            assert not any(r.enable_cached_gjk_guess for r in (*fast.collisionRequests, *fast.distanceRequests))
        for kind in ("collisionRequests", "distanceRequests"):
            a, b = getattr(fast, kind), getattr(slow, kind)
            assert len(a) == len(b) == len(col.pairs) > 300
            assert [r.saveToString() for r in a] == [r.saveToString() for r in b]


def test_collider_pairs_are_pinocchios(arm_and_colliders):
    """The collider's pair list, written as the pairs are added, is Pinocchio's list read back."""
    _arm, cols = arm_and_colliders
    for col in cols:
        assert col.pairs == [(cp.first, cp.second) for cp in col.gmodel.collisionPairs]
        assert len(col.pairs) == len(col.arm_objs) * len(col.other_objs) > 300


def test_prepared_robot_gives_the_same_run():
    """The robot-derived parts (Pinocchio model, collision geometry, support polygon) are built
    once per Robot; a second run on it and a run on a freshly loaded one agree exactly."""
    import numpy as np

    from myrabot_desc.model.loader import load_robot
    from myrabot_desc.sim import prepared, vuelta

    robot = load_robot(None)
    a = vuelta.run(robot, duration=8)
    arm = prepared.arm(robot)
    b = vuelta.run(robot, duration=8)
    assert prepared.arm(robot) is arm
    prepared.clear(robot)
    assert prepared.arm(robot) is not arm
    c = vuelta.run(load_robot(None), duration=8)
    for r in (b, c):
        assert r.as_json() == a.as_json()
        assert np.array_equal(r.arm_q, a.arm_q) and np.array_equal(r.base.x, a.base.x)


def test_preparing_the_robot_reads_each_mesh_once(monkeypatch):
    """The collider's shapes and the support's lowest points come from one read of each mesh file,
    and the support's points are the ones its own reader gives (model/shapes.surface_points)."""
    import numpy as np

    from myrabot_desc.model import meshes
    from myrabot_desc.model.loader import load_robot
    from myrabot_desc.model.shapes import surface_points
    from myrabot_desc.sim import prepared, vuelta

    robot = load_robot(None)
    reads = []
    real = meshes.triangles
    monkeypatch.setattr(meshes, "triangles", lambda path, *a, **k: reads.append(str(path)) or real(path, *a, **k))
    monkeypatch.setattr(meshes, "vertices", lambda *a, **k: pytest.fail("the support read a mesh again"))
    vuelta.run(robot, duration=2)
    files = {str(c.geometry.path) for link in robot.links.values() for c in link.collisions
             if c.geometry is not None and c.geometry.kind == "mesh"}
    assert len(files) > 5 and sorted(reads) == sorted(files)
    monkeypatch.undo()
    of = prepared.mesh_vertices(robot)
    for link in robot.links.values():
        for c in link.collisions:
            if c.geometry is not None and c.geometry.kind == "mesh":
                assert np.array_equal(of(c.geometry), surface_points(c.geometry))
