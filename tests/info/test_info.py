"""The model, the Pinocchio bridge and `info`."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from helpers import FIXTURES
from myrabot_desc.commands.main import main
from myrabot_desc.errors import InputError
from myrabot_desc.model.loader import load_robot

FIX = FIXTURES
ERD = Path(sys.prefix) / "lib" / f"python{sys.version_info.major}.{sys.version_info.minor}" / "site-packages" / \
    "cmeel.prefix" / "share" / "example-robot-data" / "robots"
ROBOTS = ["ur_description/urdf/ur5_robot.urdf", "panda_description/urdf/panda.urdf",
          "solo_description/robots/solo12.urdf", "talos_data/robots/talos_reduced.urdf",
          "tiago_description/robots/tiago.urdf", "a1_description/urdf/a1.urdf"]


@pytest.mark.parametrize("rel", ROBOTS)
def test_info_total_mass_and_com_match_pinocchio(rel):
    import pinocchio as pin

    path = ERD / rel
    r = CliRunner().invoke(main, ["info", str(path), "--json"])
    assert r.exit_code == 0, r.output
    s = json.loads(r.output)
    model = pin.buildModelFromUrdf(str(path), pin.JointModelFreeFlyer())
    data = model.createData()
    q = pin.neutral(model)
    assert s["total_mass"] == pytest.approx(pin.computeTotalMass(model), rel=1e-6)
    assert s["center_of_mass"] == pytest.approx(list(pin.centerOfMass(model, data, q)), abs=1e-5)
    mimics = sum(1 for j in load_robot(path).joints.values()   # panda's second finger; talos' fixed mimics
                 if j.mimic and j.type in ("revolute", "continuous", "prismatic"))
    assert s["dof"] == model.nv - 6 - mimics


def test_frames_match_pinocchio_forward_kinematics():
    import pinocchio as pin

    robot = load_robot(ERD / "panda_description/urdf/panda.urdf")
    s = CliRunner().invoke(main, ["info", str(ERD / "panda_description/urdf/panda.urdf"), "--json"])
    frames = {f["frame"]: f["xyz"] for f in json.loads(s.output)["frames"]}
    model = robot.pinocchio()
    data = model.createData()
    pin.framesForwardKinematics(model, data, pin.neutral(model))
    for name in ("panda_link7", "panda_hand", "panda_leftfinger"):
        assert frames[name] == pytest.approx(list(data.oMf[model.getFrameId(name)].translation), abs=1e-6)


def test_model_reads_the_korean_robot_as_written():
    robot = load_robot(FIX / "wander_bot/urdf/robot.xacro")
    assert robot.root == "base_footprint"
    assert robot.joints["left_wheel_joint"].origin.xyz == (0.1, 0.15, 0.0)
    assert robot.links["scanner_link"].inertial.iyy == 10.0
    assert robot.links["left_wheel"].collisions[0].geometry.radius == 0.08
    plugin = robot.plugins()[0]
    assert plugin.dialect == "classic" and plugin.params["wheelSeparation"] == "0.4"
    assert robot.links["base_link"].loc.file.endswith("robot.xacro") and robot.links["base_link"].loc.line


def test_model_reads_the_electric_dialect():
    seed = FIX / "seed_myrabot"
    robot = load_robot(seed / "myrabot_fer_modelo/urdf/myrabot.urdf.xacro", package_paths=[seed])
    roomba = next(p for p in robot.plugins() if p.library == "libgazebo_ros_roomba.so")
    assert roomba.dialect == "electric" and roomba.params["wheel_separation"] == ".260"
    webcam = next(p for p in robot.plugins() if p.name == "webcam_camera_controller")
    assert webcam.file_attr == "filename"
    cam = next(s for s in robot.sensors() if s.name == "camera")
    assert cam.type == "camera" and cam.reference == "camera_link" and cam.param("hfov") == "60"
    # <mu1 value="10"/> (attribute style) reads like <mu1>0.5</mu1>
    wheel = next(g for g in robot.gazebo if g.reference == "left_wheel_link")
    assert wheel.properties["mu1"] == "10"
    assert any(d.code == "X002" for d in robot.build_warnings)


def test_pinocchio_errors_carry_urdfdoms_reason(tmp_path):
    f = tmp_path / "two_roots.urdf"
    f.write_text('<robot name="r"><link name="a"/><link name="b"/></robot>')
    robot = load_robot(f)
    with pytest.raises(InputError) as e:
        robot.pinocchio()
    assert "Two root links found" in str(e.value)


def test_info_text_shows_tree_limits_mass_frames():
    r = CliRunner().invoke(main, ["info", str(ERD / "ur_description/urdf/ur5_robot.urdf")])
    assert r.exit_code == 0
    assert "6 degrees of freedom" in r.output
    assert "shoulder_pan_joint: revolute axis 0 0 1" in r.output
    assert "[-6.28319, 6.28319] rad" in r.output
    assert "frames (world position" in r.output


def test_info_bad_input_is_exit_2(tmp_path):
    f = tmp_path / "x.urdf"
    f.write_text("<sdf version='1.9'><model name='m'/></sdf>")
    r = CliRunner().invoke(main, ["info", str(f)])
    assert r.exit_code == 2 and "not <robot>" in r.output and "x.urdf:1" in r.output
