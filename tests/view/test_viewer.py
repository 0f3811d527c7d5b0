"""view without a browser: the command starts and serves the page, --watch reloads keeping the
joint values, findings name their links, other robots load, bad input exits 2."""

from __future__ import annotations

import os
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import numpy as np
import pytest

from helpers import ROOT
from myrabot_desc.commands.common import ModelInputs as Inputs

FIX = ROOT / "tests" / "fixtures"
ERD = Path(sys.prefix) / "lib" / f"python{sys.version_info.major}.{sys.version_info.minor}" / "site-packages" / \
    "cmeel.prefix" / "share" / "example-robot-data" / "robots"

ARM = """<?xml version="1.0"?>
<robot name="arm">
  <material name="red"><color rgba="0.9 0.1 0.1 1"/></material>
  <link name="base"><visual><geometry><box size="0.2 0.2 0.1"/></geometry><material name="red"/></visual>
    <inertial><mass value="1"/><inertia ixx="0.004" iyy="0.004" izz="0.007" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="upper"><visual><origin xyz="0 0 0.2"/><geometry><cylinder radius="0.03" length="0.4"/></geometry></visual>
    <collision><origin xyz="0 0 0.2"/><geometry><cylinder radius="0.03" length="0.4"/></geometry></collision>
    <inertial><origin xyz="0 0 0.2"/><mass value="0.5"/><inertia ixx="0.0068" iyy="0.0068" izz="0.0002" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/><origin xyz="0 0 {z}"/>
    <axis xyz="0 1 0"/><limit lower="-1.5" upper="1.5" effort="1" velocity="1"/></joint>
  <link name="finger"/>
  <joint name="finger_joint" type="prismatic"><parent link="upper"/><child link="finger"/><origin xyz="0 0 0.4"/>
    <limit lower="0" upper="0.05" effort="1" velocity="1"/><mimic joint="shoulder" multiplier="0.01"/></joint>
</robot>
"""


def wait_for(cond, timeout=120.0, what="condition"):
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if cond():
            return
        time.sleep(0.05)
    raise AssertionError(f"timed out waiting for {what}")


@pytest.fixture()
def arm(tmp_path):
    p = tmp_path / "arm.urdf"
    p.write_text(ARM.format(z="0.05"))
    return p


def test_watch_reloads_and_keeps_the_joint_values(arm):
    from myrabot_desc.view.server import Viewer

    v = Viewer(Inputs(files=[str(arm)]).load, port=0, shared=True)
    try:
        assert list(v.scene.joints) == ["shoulder"]              # the mimic joint follows, no slider
        assert str(arm) in v.files()
        v.set_joints({"shoulder": 0.7, "nope": 1.0})
        assert v.q == {"shoulder": 0.7}
        v.set_toggle("inertia", True)
        z0 = v.link_poses["upper"][2, 3]
        v.watch(interval=0.05)
        time.sleep(0.1)
        arm.write_text(ARM.format(z="0.25"))
        wait_for(lambda: v.generation == 2, what="the reload")
        assert v.q == {"shoulder": 0.7}
        assert v._sliders["shoulder"].value == pytest.approx(0.7)
        assert v.toggles["inertia"] is True
        assert v.link_poses["upper"][2, 3] == pytest.approx(z0 + 0.2)
        # the rebuilt scene's nodes sit where the links are, moved or not
        for link in ("base", "upper"):
            assert v._link_nodes[link].position == pytest.approx(v.link_poses[link][:3, 3])
        # the mimic joint followed: the finger slid 0.007 m along z of the upper arm
        T = v.link_poses
        rel = np.linalg.inv(T["upper"]) @ T["finger"]
        assert rel[:3, 3] == pytest.approx([0.007, 0, 0.4], abs=1e-9)     # the URDF's default axis is x
        # a broken save keeps the last good model on screen and says why
        arm.write_text("<robot name='arm'><link name='base'>")
        wait_for(lambda: v.error is not None, what="the failed reload")
        assert v.generation == 2 and "arm.urdf" in v.error
        assert v.robot.name == "arm"
    finally:
        v.stop()


def test_findings_name_their_links():
    from myrabot_desc.checks import CheckOptions, check_robot
    from myrabot_desc.model.loader import load_robot
    from myrabot_desc.view.overlays import finding_links

    robot = load_robot()
    diags, _ = check_robot(robot, CheckOptions(inertia=True))
    by_code = {}
    for d in diags:
        by_code.setdefault(d.code, []).append(finding_links(robot, d))
    assert ["e_pilar_link"] in by_code["I008"]
    assert ["front_wheel_link"] in by_code["G004"]        # a joint named: its child link
    assert all(links for links in by_code["S005"])         # a sensor named: the link it sits on


def test_view_shows_an_example_robot_data_robot():
    from myrabot_desc.view.server import Viewer

    urdf = ERD / "ur_description/urdf/ur5_robot.urdf"
    if not urdf.is_file():
        pytest.skip("example-robot-data is not installed")
    v = Viewer(Inputs(files=[str(urdf)]).load, port=0, findings=False, shared=True)
    try:
        assert set(v.scene.joints) >= {"shoulder_pan_joint", "elbow_joint", "wrist_3_joint"}
        assert sum(p.layer == "visual" for p in v.scene.parts) >= 7
        assert not v.scene.problems
        before = v.link_poses["wrist_3_link"][:3, 3].copy()
        v.set_joints({"shoulder_pan_joint": 1.0})
        after = v.link_poses["wrist_3_link"][:3, 3]
        # turning the base about z keeps the height and the distance to the axis
        assert after[2] == pytest.approx(before[2])
        assert np.hypot(*after[:2]) == pytest.approx(np.hypot(*before[:2]))
        assert np.linalg.norm(after - before) > 0.1
    finally:
        v.stop()


def test_cli_prints_the_url_and_serves_the_page():
    env = dict(os.environ)
    p = subprocess.Popen([sys.executable, "-m", "myrabot_desc", "view", "--port", "0", "--no-watch", "--no-check"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    try:
        url = p.stdout.readline().strip()
        assert url.startswith("http://127.0.0.1:"), url
        with urllib.request.urlopen(url, timeout=10) as r:
            assert r.status == 200
            assert b"<html" in r.read(4096).lower()
    finally:
        p.terminate()
        p.wait(timeout=20)


def test_cli_bad_input_exits_2(tmp_path):
    bad = tmp_path / "bad.urdf"
    bad.write_text("<robot name='x'><link name='a'>")
    p = subprocess.run([sys.executable, "-m", "myrabot_desc", "view", str(bad), "--port", "0"],
                       capture_output=True, text=True, timeout=60)
    assert p.returncode == 2
    assert p.stderr.strip().startswith(f"{bad}:") and "error:" in p.stderr
    assert "Traceback" not in p.stderr and p.stdout == ""


def test_help_has_an_example():
    p = subprocess.run([sys.executable, "-m", "myrabot_desc", "view", "--help"], capture_output=True, text=True)
    assert p.returncode == 0 and "myrabot-desc view robot.urdf.xacro" in p.stdout
    # --help imports no viser
    code = "import sys; from myrabot_desc.commands.main import main; import myrabot_desc.commands.view; " \
           "print('viser' in sys.modules, 'mujoco' in sys.modules, 'matplotlib' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True).stdout.strip()
    assert out == "False False False"


def test_wheels_as_the_plugin_believes_them_against_the_urdf():
    """wander_bot's diff-drive plugin says 0.1 m wheels 0.4 m apart; the URDF built 0.08 m, 0.3 m."""
    from myrabot_desc.view.server import Viewer

    wander = FIX / "wander_bot"
    v = Viewer(Inputs(files=[str(wander / "urdf" / "robot.xacro")], packages={"wander_bot": str(wander)}).load,
               port=0, findings=False, shared=True)
    try:
        assert v._nodes["wheels"] == []                 # an overlay is built when first switched on
        v.set_toggle("wheels", True)
        assert "URDF: radius 0.08 m, separation 0.3 m" in v.wheel_text
        assert "radius 0.1 m, separation 0.4 m" in v.wheel_text
        assert len(v._nodes["wheels"]) == 5            # two URDF rims, two plugin rims, the numbers
        d = v.drive
        assert d.plugin.separation == pytest.approx(0.4) and d.urdf.separation == pytest.approx(0.3)
    finally:
        v.stop()


def test_rest_pose_button_goes_to_the_model_rest_pose():
    """A calf whose range excludes 0 (go1's, [-2.818, -0.888]) rests at its nearer limit, -0.888, as in
    render, MJCF's home and convert's controllers, not at its lower limit."""
    from myrabot_desc.model.loader import load_robot
    from myrabot_desc.view.scene import build_scene

    urdf = ERD / "go1_description/urdf/go1.urdf"
    scene = build_scene(load_robot(urdf))
    rest = scene.rest()
    assert rest["FR_calf_joint"] == pytest.approx(-0.888, abs=1e-9)
    assert rest["FR_hip_joint"] == 0.0
    assert scene.pose(None) == rest
