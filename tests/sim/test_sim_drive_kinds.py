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


def test_the_mujoco_engine_refuses_a_base_it_would_drive_as_a_diff_drive():
    res = invoke("sim", "drive", "--engine", "mujoco", *drive_args(ROBOTS["rosbot_xl_mecanum"]))
    assert res.exit_code == 2
    lines = [x for x in res.output.splitlines() if x.strip()]
    assert len(lines) == 1 and ": error: " in lines[0] and "mecanum base" in lines[0]
