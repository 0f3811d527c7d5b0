"""convert --to sdf gives each drive kind the gz-sim system that drives it (issue 25), on real bases
of tests/corpus/drives.yaml: MecanumDrive, AckermannSteering, VelocityControl; no DiffDrive on
wheels that are not a differential pair; the conversion report says what the drive became."""

from __future__ import annotations

import json

import pytest
from lxml import etree

from helpers import drive_args, drive_robots, invoke
from test_sdf_and_world import IGN, ign_check

ROBOTS = {r["id"]: r for r in drive_robots()}

pytestmark = pytest.mark.skipif(not ROBOTS, reason="the real-robot corpus is not here")

# robot -> (the system its base gets, the report's fate of its drive)
EXPECTED = {
    "rosbot_xl_mecanum": ("gz-sim-mecanum-drive-system", "translated"),
    # frictionless wheels (mu1 = mu2 = 0) moved by a body force in the source: MecanumDrive could not move it
    "ridgeback": ("gz-sim-velocity-control-system", "translated"),
    "audibot": ("gz-sim-ackermann-steering-system", "translated"),
    "mpo_700_planar_move": ("gz-sim-velocity-control-system", "translated"),
    "mpo_700_gz_velocity": ("ignition-gazebo-velocity-control-system", "kept"),
    "swerve_robot": (None, "approximated"),
    "rosbot_xl_diff": ("gz-sim-diff-drive-system", None),
}


def _convert(rid, tmp_path):
    out = tmp_path / f"{rid}.sdf"
    res = invoke("convert", *drive_args(ROBOTS[rid]), "-o", out, "--report", tmp_path / "report.json")
    assert res.exit_code == 0, res.output[-2000:]
    report = json.loads((tmp_path / "report.json").read_text())
    return out, etree.parse(str(out)).getroot(), report


@pytest.mark.parametrize("rid", list(EXPECTED))
def test_each_kind_gets_its_system(rid, tmp_path):
    system, fate = EXPECTED[rid]
    out, root, report = _convert(rid, tmp_path)
    libs = [p.get("filename") for p in root.iter("plugin")]
    if system:
        assert libs.count(system) == 1, libs
    if rid != "rosbot_xl_diff":
        assert "gz-sim-diff-drive-system" not in libs, libs
    drives = [e for e in report["elements"] if e["kind"] == "drive"]
    assert [e["fate"] for e in drives] == ([fate] if fate else [])
    if IGN:
        ign_check(out)


def test_mecanum_and_ackermann_numbers_are_the_urdfs(tmp_path):
    _, root, _ = _convert("rosbot_xl_mecanum", tmp_path)
    m = next(p for p in root.iter("plugin") if p.get("filename") == "gz-sim-mecanum-drive-system")
    assert [m.findtext(k) for k in ("front_left_joint", "front_right_joint", "back_left_joint", "back_right_joint")] \
        == ["fl_wheel_joint", "fr_wheel_joint", "rl_wheel_joint", "rr_wheel_joint"]
    meas = ROBOTS["rosbot_xl_mecanum"]["measured"]
    assert float(m.findtext("wheelbase")) == pytest.approx(meas["wheelbase"])
    assert float(m.findtext("wheel_separation")) == pytest.approx(meas["track"])
    assert float(m.findtext("wheel_radius")) == pytest.approx(meas["wheel_radius"])

    _, root, _ = _convert("audibot", tmp_path)
    a = next(p for p in root.iter("plugin") if p.get("filename") == "gz-sim-ackermann-steering-system")
    meas = ROBOTS["audibot"]["measured"]
    assert (a.findtext("left_steering_joint"), a.findtext("right_steering_joint")) == ("steer_fl_joint", "steer_fr_joint")
    assert float(a.findtext("wheel_base")) == pytest.approx(meas["wheelbase"])
    assert float(a.findtext("kingpin_width")) == pytest.approx(meas["front_track"])
    assert float(a.findtext("wheel_separation")) == pytest.approx(meas["rear_track"])
    assert float(a.findtext("steering_limit")) == pytest.approx(meas["steering_limit"])
    # the steering hinges are AckermannSteering's, not position controllers'
    steered = {p.findtext("joint_name") for p in root.iter("plugin")
               if p.get("filename") == "gz-sim-joint-position-controller-system"}
    assert not steered & {"steer_fl_joint", "steer_fr_joint"}


def test_a_skid_steer_diffdrive_says_what_its_controller_yaml_turns_with(tmp_path):
    """rosbot_xl's diff_drive_controller turns with 0.248 x 1.3 = 0.3224 m: the report says so next to
    the URDF's 0.248 m the DiffDrive uses."""
    out = tmp_path / "r.sdf"
    res = invoke("convert", *drive_args(ROBOTS["rosbot_xl_diff"]), "-o", out)
    assert res.exit_code == 0
    eff = ROBOTS["rosbot_xl_diff"]["dialects"]["ros2_control"]["effective"]["wheel_separation"]
    assert f"wheel_separation {eff:g} m (its YAML, multipliers applied)" in res.output
    dd = next(p for p in etree.parse(str(out)).getroot().iter("plugin")
              if p.get("filename") == "gz-sim-diff-drive-system")
    assert float(dd.findtext("wheel_separation")) == pytest.approx(ROBOTS["rosbot_xl_diff"]["measured"]["wheel_separation"])
