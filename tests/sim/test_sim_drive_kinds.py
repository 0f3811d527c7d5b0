"""`sim drive` runs each drive kind's kinematic model (issue 25) on the real bases of
tests/corpus/drives.yaml: omni twist for mecanum and planar, per-module steering for swerve, the
bicycle model with its minimum turning radius for Ackermann; the same verdict lines as a diff drive."""

from __future__ import annotations

import json
import math

import pytest

from helpers import FIXTURES, drive_args, drive_robots, invoke

ROBOTS = {r["id"]: r for r in drive_robots()}
pytestmark = pytest.mark.skipif(not ROBOTS, reason="the real-robot corpus is not here")


def _drive(rid, *twists, extra=()):
    args = ["sim", "drive", "--json", *extra, *drive_args(ROBOTS[rid])]
    for t in twists:
        args += ["--twist", t]
    res = invoke(*args)
    assert res.exit_code in (0, 1), res.output[-2000:]
    doc = json.loads(res.stdout)
    return doc, {c["name"]: c for c in doc["checks"]}


@pytest.mark.parametrize("rid", ["rosbot_xl_mecanum", "ridgeback", "swerve_robot", "mpo_700", "mpo_700_planar_move",
                                 "mpo_700_gz_velocity"])
def test_holonomic_bases_move_sideways_and_spin_as_commanded(rid):
    doc, checks = _drive(rid, "0.2,0.2,0,2", "0,0,0.5,2", "0.2,-0.1,0.3,2")
    assert doc["info"]["drive kind"] == ROBOTS[rid]["drive_kind"]
    assert doc["passed"], doc["checks"]
    assert checks["speed ratio"]["value"] == pytest.approx(1.0, abs=1e-6)
    assert checks["turn-rate ratio"]["value"] == pytest.approx(1.0, abs=1e-6)
    seg = doc["info"]["segments"][0]
    assert (seg["vx"], seg["vy"]) == pytest.approx((0.2, 0.2), abs=1e-6)


def test_mecanum_wheel_rates_are_the_inverse_kinematics(tmp_path):
    """Sideways at 0.2 m/s for 2 s: the front-left wheel turns -0.2/r per second, the front-right +0.2/r
    (r 0.05 m, the controller YAML's and the URDF's)."""
    csv = tmp_path / "d.csv"
    _drive("rosbot_xl_mecanum", "0,0.2,0,2", extra=("--csv", str(csv)))
    head, *rows = csv.read_text().splitlines()
    cols = head.split(",")
    last = dict(zip(cols, map(float, rows[-1].split(","))))
    r = ROBOTS["rosbot_xl_mecanum"]["dialects"]["ros2_control"]["params"]["wheel_radius"]
    assert last["fl_wheel_joint_rad"] == pytest.approx(-0.2 / r * 2, rel=1e-3)
    assert last["fr_wheel_joint_rad"] == pytest.approx(0.2 / r * 2, rel=1e-3)
    assert last["base_y_m"] == pytest.approx(0.4, abs=1e-3) and abs(last["base_x_m"]) < 1e-6


def test_ackermann_turns_down_to_its_minimum_radius_and_no_tighter():
    m = ROBOTS["audibot"]["measured"]
    r_min = m["wheelbase"] / math.tan(m["steering_limit"])            # 3.876 m
    doc, checks = _drive("audibot", "2.0,0.45,4")                     # a 4.44 m radius: within the lock
    assert doc["passed"] and doc["info"]["minimum turning radius"] == f"{r_min:.4f} m"
    doc, checks = _drive("audibot", "0.2,0.4,4", "0,0.5,2")            # 0.5 m, then on the spot
    assert not doc["passed"]
    # at the lock the bicycle turns at v tan(lock) / L
    held = 0.2 * math.tan(m["steering_limit"]) / m["wheelbase"]
    assert checks["turn-rate ratio"]["value"] == pytest.approx(0.0)   # the worst: no turn on the spot
    assert doc["info"]["segments"][0]["w"] == pytest.approx(held, rel=1e-4)
    assert any("cannot turn on the spot" in n for n in doc["notes"])
    assert any("minimum turning radius" in n for n in doc["notes"])


def test_the_bicycle_model_of_a_virtual_steering_joint():
    doc, checks = _drive("carlikebot", "0.5,0.5,3")
    assert doc["info"]["drive kind"] == "ackermann" and doc["passed"]


def test_a_sideways_twist_for_a_differential_base_is_one_error_line():
    wander = FIXTURES / "wander_bot"
    res = invoke("sim", "drive", str(wander / "urdf/robot.xacro"), "-p", f"wander_bot={wander}",
                 "--twist", "0.2,0.1,0,2")
    assert res.exit_code == 2
    lines = [x for x in res.output.splitlines() if x.strip()]
    assert len(lines) == 1 and ": error: " in lines[0] and "sideways" in lines[0]


@pytest.mark.parametrize("rid", ["rosbot_xl_mecanum", "ridgeback", "mpo_700", "mpo_700_planar_move"])
def test_the_mujoco_engine_drives_holonomic_bases_as_their_kinematic_model(rid):
    """Mecanum and planar bases slide on convert's planar base, the MPO-700 rolls on its four steered
    modules: sideways, on the spot and in an arc, MuJoCo's twist is the kinematic model's within 10 %
    (the module base within 5 % sideways), and the base keeps to the floor."""
    doc, checks = _drive(rid, "0.2,0.2,0,2", "0,0,0.5,2", "0.2,-0.1,0.3,2", extra=("--engine", "mujoco"))
    assert doc["passed"], doc["checks"]
    assert doc["info"]["drive kind"] == ROBOTS[rid]["drive_kind"] and doc["engine"].startswith("MuJoCo")
    assert checks["speed vs kinematic"]["value"] == pytest.approx(1.0, abs=0.1)
    assert checks["turn rate vs kinematic"]["value"] == pytest.approx(1.0, abs=0.1)
    assert abs(checks["stays on the floor"]["value"]) <= 0.005
    seg = doc["info"]["segments"][0]
    assert (seg["vx"], seg["vy"]) == pytest.approx((0.2, 0.2), abs=0.01)
    moved = "planar base" in doc["info"]["moved by"]
    assert moved == (ROBOTS[rid]["drive_kind"] != "swerve")


def test_the_mujoco_engine_steers_an_ackermann_car_along_its_bicycle_model():
    """Audibot (1820 kg) in a 4.4 m arc: each front wheel at its own Ackermann angle, each wheel at its
    own path speed; speed and turn rate within 10 % of the bicycle model."""
    doc, checks = _drive("audibot", "2.0,0.45,4", extra=("--engine", "mujoco"))
    assert doc["passed"], doc["checks"]
    seg = doc["info"]["segments"][0]
    assert seg["vx"] == pytest.approx(2.0, rel=0.05) and seg["w"] == pytest.approx(0.45, rel=0.1)


def test_the_mujoco_engine_names_a_wheel_that_rubs_on_the_chassis():
    """swerve_robot as the corpus keeps it: its meshes are stand-in boxes (the repository's binaries
    were absent from the snapshot; tests/corpus/README.md), so each wheel is a 0.186 m square: 0.15 rad
    into a turn its corner meets the chassis box and the wheel stops at its 1 N·m effort. The base
    stays where it is, and each cause names the wheel joint (at its xacro line) and chassis_link."""
    doc, checks = _drive("swerve_robot", "0.2,0,0,2", extra=("--engine", "mujoco"))
    assert not doc["passed"]
    assert abs(checks["speed vs kinematic"]["value"]) < 0.05
    causes = [c for c in doc["causes"] if c["check"] == "speed vs kinematic"]
    assert causes and all("its collision meets chassis_link" in c["cause"] and c["file"].endswith("wheel.xacro")
                          for c in causes)


def test_the_mujoco_engine_names_the_wheels_that_drag_a_car():
    """CarlikeBot's front wheels are steered but have no joint to roll them (its bicycle's virtual
    joints drive and steer): in MuJoCo they slide, and the car makes 14 % of the commanded speed.
    The cause names them and the force they drag with."""
    doc, checks = _drive("carlikebot", "0.2,0,3", extra=("--engine", "mujoco"))
    assert not doc["passed"]
    assert checks["speed vs kinematic"]["value"] < 0.5
    text = " ".join(c["cause"] for c in doc["causes"])
    assert "front_left_wheel, front_right_wheel touch the floor without a joint that rolls them" in text
