"""False alarms and missed findings seen on real description packages, each pinned at its rule.

The inputs are written the way the real packages write them (a small diff-drive robot's lidar
with a full scan in radians, a service robot's seven gazebo_ros cameras under their own names,
a drone's top-level `.gazebo` xacro file built with args, macro-only parts files, fingers with
degenerate inertias).
"""

from __future__ import annotations

import json
import textwrap
from pathlib import Path

import pytest
from click.testing import CliRunner

from helpers import CORPUS
from myrabot_desc.checks import CheckOptions, run_checks
from myrabot_desc.diagnostics import sort_diagnostics
from myrabot_desc.commands.main import main
from myrabot_desc.model.loader import is_xacro, load_robot

HEAD = '<?xml version="1.0"?>\n<robot name="{name}" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
BASE = """  <link name="base_footprint"/>
  <link name="base_link">
    <inertial><mass value="1.5"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.02"/></inertial>
  </link>
  <joint name="base_joint" type="fixed"><parent link="base_footprint"/><child link="base_link"/></joint>
"""


def write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(textwrap.dedent(text))
    return path


def check_json(*args):
    res = CliRunner().invoke(main, ["check", "--format", "json", *map(str, args)])
    doc = json.loads(res.stdout)
    return res.exit_code, doc["files"][0]


def line_of(path: Path, needle: str) -> int:
    return next(i for i, line in enumerate(path.read_text().splitlines(), 1) if needle in line)


# ---------------------------------------------------------------- S006: a full scan in radians
LIDAR = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <gazebo reference="base_scan">
    <material>Gazebo/FlatBlack</material>
    <sensor type="ray" name="lds_lfcd_sensor">
      <visualize>$(arg laser_visual)</visualize>
      <update_rate>5</update_rate>
      <ray>
        <scan>
          <horizontal>
            <samples>360</samples>
            <resolution>1</resolution>
            <min_angle>0.0</min_angle>
            <max_angle>{max_angle}</max_angle>
          </horizontal>
        </scan>
        <range><min>0.120</min><max>3.5</max><resolution>0.015</resolution></range>
      </ray>
      <plugin name="gazebo_ros_lds_lfcd_controller" filename="libgazebo_ros_laser.so">
        <topicName>scan</topicName>
        <frameName>base_scan</frameName>
      </plugin>
    </sensor>
  </gazebo>
</robot>
"""


def lidar_robot(tmp_path, max_angle):
    gz = write(tmp_path / "urdf" / "small_bot.gazebo.xacro", LIDAR.format(max_angle=max_angle))
    top = write(tmp_path / "urdf" / "small_bot.urdf.xacro", HEAD.format(name="small_bot") + """\
  <xacro:arg name="laser_visual" default="false"/>
  <xacro:include filename="small_bot.gazebo.xacro"/>
""" + BASE + """\
  <link name="base_scan">
    <inertial><mass value="0.1"/><inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial>
  </link>
  <joint name="scan_joint" type="fixed"><origin xyz="-0.032 0 0.172"/>
    <parent link="base_link"/><child link="base_scan"/></joint>
</robot>
""")
    return gz, top


@pytest.mark.parametrize("written", ["6.28319", "6.2832", "6.28318530718", "-6.28319"])
def test_full_scan_written_with_few_decimals_is_radians(tmp_path, written):
    _, top = lidar_robot(tmp_path, written)
    code, f = check_json(top)
    assert [d for d in f["diagnostics"] if d["code"] == "S006"] == []


def test_degrees_still_fire_at_the_max_angle_element(tmp_path):
    gz, top = lidar_robot(tmp_path, "360")
    code, f = check_json(top)
    (d,) = [d for d in f["diagnostics"] if d["code"] == "S006"]
    assert d["severity"] == "error" and code == 1
    assert d["data"]["value"] == 360 and d["data"]["fix"] == pytest.approx(6.283185, abs=1e-6)
    assert d["file"].endswith("small_bot.gazebo.xacro")
    assert d["line"] == line_of(gz, "<max_angle>") != line_of(gz, "<plugin")


# ---------------------------------------------------------------- G010: cameras under their names
def camera(name, cam, image="image_raw", info="camera_info"):
    return f"""  <link name="{name}_frame"/>
  <joint name="{name}_joint" type="fixed"><parent link="base_link"/><child link="{name}_frame"/></joint>
  <gazebo reference="{name}_frame">
    <sensor type="camera" name="{name}_sensor">
      <camera><horizontal_fov>1.0</horizontal_fov></camera>
      <plugin name="{name}_controller" filename="libgazebo_ros_camera.so">
        <cameraName>{cam}</cameraName>
        <imageTopicName>{image}</imageTopicName>
        <cameraInfoTopicName>{info}</cameraInfoTopicName>
        <frameName>{name}_frame</frameName>
      </plugin>
    </sensor>
  </gazebo>
"""


SEVEN = [("high_def", "prosilica"), ("wide_stereo_l", "wide_stereo/left"), ("wide_stereo_r", "wide_stereo/right"),
         ("narrow_stereo_l", "narrow_stereo/left"), ("narrow_stereo_r", "narrow_stereo/right"),
         ("l_forearm_cam", "l_forearm_cam"), ("r_forearm_cam", "r_forearm_cam")]


def test_seven_cameras_publishing_image_raw_under_their_names_do_not_collide(tmp_path):
    p = write(tmp_path / "service_bot.urdf", HEAD.format(name="service_bot") + BASE
              + "".join(camera(n, c) for n, c in SEVEN) + "</robot>\n")
    code, f = check_json(p)
    assert [d for d in f["diagnostics"] if d["code"] == "G010"] == []


def test_cameras_sharing_a_name_or_an_absolute_topic_collide(tmp_path):
    p = write(tmp_path / "twins.urdf", HEAD.format(name="twins") + BASE + camera("left", "stereo")
              + camera("right", "stereo") + camera("a", "front", image="/image_raw")
              + camera("b", "rear", image="/image_raw") + "</robot>\n")
    code, f = check_json(p)
    got = {d["data"]["topic"]: d["data"]["publishers"] for d in f["diagnostics"] if d["code"] == "G010"}
    assert set(got) == {"/image_raw", "/stereo/camera_info", "/stereo/image_raw"}
    assert got["/stereo/image_raw"] == ["left_controller (imageTopicName)", "right_controller (imageTopicName)"]
    assert got["/image_raw"] == ["a_controller (imageTopicName)", "b_controller (imageTopicName)"]


def test_lasers_without_camera_names_still_collide_under_the_robot_namespace(tmp_path):
    laser = """  <gazebo reference="{l}"><sensor type="ray" name="{l}">
    <plugin name="{l}_controller" filename="libgazebo_ros_laser.so">
      <robotNamespace>/bot</robotNamespace><topicName>scan</topicName><frameName>{l}</frameName>
      <cameraName>ignored_by_lasers</cameraName>
    </plugin></sensor></gazebo>
  <link name="{l}"/><joint name="{l}_joint" type="fixed"><parent link="base_link"/><child link="{l}"/></joint>
"""
    p = write(tmp_path / "lasers.urdf", HEAD.format(name="lasers") + BASE + laser.format(l="front")
              + laser.format(l="rear") + "</robot>\n")
    code, f = check_json(p)
    assert [d["data"]["topic"] for d in f["diagnostics"] if d["code"] == "G010"] == ["/bot/scan"]


# ---------------------------------------------------------------- T001/T017: placeholders and parts files
def test_placeholder_and_macro_only_files_are_information(tmp_path):
    empty = write(tmp_path / "urdf" / "empty.urdf", '<?xml version="1.0"?>\n<robot name="empty"/>\n')
    parts = write(tmp_path / "urdf" / "wheel.urdf.xacro", HEAD.format(name="wheel") + """\
  <xacro:macro name="wheel" params="prefix parent">
    <link name="${prefix}_wheel"/>
    <joint name="${prefix}_wheel_joint" type="continuous">
      <parent link="${parent}"/><child link="${prefix}_wheel"/><axis xyz="0 1 0"/>
    </joint>
  </xacro:macro>
</robot>
""")
    res = CliRunner().invoke(main, ["check", "--format", "json", str(empty), str(parts)])
    assert res.exit_code == 0, res.output
    files = {Path(f["file"]).name: f for f in json.loads(res.stdout)["files"]}
    for name in ("empty.urdf", "wheel.urdf.xacro"):
        codes = [(d["code"], d["severity"]) for d in files[name]["diagnostics"]]
        assert ("T017", "info") in codes and not [c for c in codes if c[0] == "T001"]
        assert files[name]["counts"]["error"] == 0
    assert ("X003", "warning") in [(d["code"], d["severity"]) for d in files["wheel.urdf.xacro"]["diagnostics"]]


# ---------------------------------------------------------------- I005: degenerate finger tensors
def finger_robot(tmp_path, inertia):
    return write(tmp_path / "hand.urdf", HEAD.format(name="hand") + BASE + f"""\
  <link name="finger_1">
    <inertial><mass value="0.05"/><inertia {inertia}/></inertial>
    <collision><geometry><box size="0.02 0.02 0.08"/></geometry></collision>
  </link>
  <joint name="finger_1_joint" type="revolute"><parent link="base_link"/><child link="finger_1"/>
    <axis xyz="0 1 0"/><limit lower="0" upper="1.5" effort="2" velocity="3"/></joint>
</robot>
""")


@pytest.mark.parametrize("inertia, moments", [
    ('ixx="0.002" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"', (0.0, 0.0, 0.002)),
    ('ixx="0.001" ixy="0.001" ixz="0.001" iyy="0.001" iyz="0.001" izz="0.001"', (0.0, 0.0, 0.003)),
])
def test_zero_moments_that_break_the_triangle_are_errors(tmp_path, inertia, moments):
    diags = run_checks(load_robot(finger_robot(tmp_path, inertia)))
    (d,) = [d for d in diags if d.code == "I005"]
    assert d.severity == "error" and d.data["principal"] == pytest.approx(moments, abs=1e-12)
    assert "0 + 0 = 0 <" in d.message
    assert [x for x in diags if x.code == "I004"] == []        # not "a point mass or a rod"


def test_rods_and_point_masses_stay_warnings(tmp_path):
    rod = run_checks(load_robot(finger_robot(tmp_path, 'ixx="0.002" ixy="0" ixz="0" iyy="0.002" iyz="0" izz="0"')))
    assert [(d.code, d.severity) for d in rod if d.code in ("I004", "I005")] == [("I004", "warning")]
    point = run_checks(load_robot(finger_robot(tmp_path, 'ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"')))
    assert [(d.code, d.severity) for d in point if d.code in ("I004", "I005")] == [("I004", "warning")]


def test_convert_repairs_what_check_calls_a_triangle_error(tmp_path):
    from myrabot_desc.model.inertia import repaired

    robot = load_robot(finger_robot(tmp_path, 'ixx="0.002" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"'))
    fixed, changed = repaired(robot.links["finger_1"].inertial)
    assert changed and fixed[1][1] + fixed[2][2] >= fixed[0][0]


# ---------------------------------------------------------------- xacro decided by content
DRONE_TOP = """<?xml version="1.0"?>
<!-- a drone's top file: named .gazebo, built with mav_name:=... -->
<robot name="$(arg mav_name)" xmlns:xacro="http://ros.org/wiki/xacro">
  <xacro:arg name="mav_name" default="drone"/>
  <xacro:property name="namespace" value="$(arg mav_name)"/>
  <xacro:include filename="base.xacro"/>
  <xacro:multirotor namespace="${namespace}"/>
</robot>
"""
DRONE_BASE = """<?xml version="1.0"?>
<robot xmlns:xacro="http://ros.org/wiki/xacro">
  <xacro:macro name="multirotor" params="namespace">
    <link name="${namespace}/base_link">
      <inertial><mass value="1.5"/><inertia ixx="0.0347" ixy="0" ixz="0" iyy="0.0458" iyz="0" izz="0.0977"/></inertial>
      <collision><geometry><box size="0.1 0.1 0.16"/></geometry></collision>
    </link>
    <xacro:rotor n="0" namespace="${namespace}"/>
    <xacro:rotor n="1" namespace="${namespace}"/>
  </xacro:macro>
  <xacro:macro name="rotor" params="n namespace">
    <link name="${namespace}/rotor_${n}">
      <inertial><mass value="0.005"/><inertia ixx="1e-6" ixy="0" ixz="0" iyy="4e-5" iyz="0" izz="4e-5"/></inertial>
    </link>
    <joint name="${namespace}/rotor_${n}_joint" type="continuous">
      <origin xyz="0.2 ${0.1 * n} 0.02"/><axis xyz="0 0 1"/>
      <parent link="${namespace}/base_link"/><child link="${namespace}/rotor_${n}"/>
    </joint>
  </xacro:macro>
</robot>
"""


def test_a_gazebo_named_top_file_with_args_is_built(tmp_path):
    top = write(tmp_path / "urdf" / "mav_generic.gazebo", DRONE_TOP)
    write(tmp_path / "urdf" / "base.xacro", DRONE_BASE)
    robot = load_robot(top, mappings={"mav_name": "firefly"})
    assert robot.name == "firefly" and sorted(robot.links) == ["firefly/base_link", "firefly/rotor_0",
                                                               "firefly/rotor_1"]
    code, f = check_json(top, "mav_name:=firefly")
    assert (f["robot"], f["links"], f["joints"]) == ("firefly", 3, 2)
    assert not [d for d in f["diagnostics"] if d["code"] in ("T001", "T017")]
    res = CliRunner().invoke(main, ["info", str(top), "mav_name:=firefly"])
    assert res.exit_code == 0 and "robot 'firefly'" in res.output and "3 links, 2 joints" in res.output
    out = tmp_path / "firefly.sdf"
    res = CliRunner().invoke(main, ["convert", str(top), "mav_name:=firefly", "-o", str(out)])
    # rotors' real base inertia breaks the triangle inequality (I005): convert refuses it, and converts on request
    assert res.exit_code == 2 and "error: I005" in res.output and not out.exists(), res.output
    res = CliRunner().invoke(main, ["convert", str(top), "mav_name:=firefly", "-o", str(out), "--allow-errors"])
    assert res.exit_code == 0, res.output
    assert out.read_text().count("<link name=") == 3


def test_xacro_by_content_not_by_a_declared_namespace(tmp_path):
    generated = b'<?xml version="1.0"?>\n<!-- generated by xacro from ${robot}.urdf.xacro -->\n' \
                b'<robot name="r" xmlns:xacro="http://wiki.ros.org/xacro"><link name="a"/></robot>\n'
    assert not is_xacro(Path("r.urdf"), generated)                 # declaration only; ${} only in a comment
    assert is_xacro(Path("r.gazebo"), b'<robot xmlns:x="http://www.ros.org/wiki/xacro"><x:include filename="a"/></robot>')
    assert is_xacro(Path("r.urdf"), b'<robot name="$(arg name)"/>')
    assert is_xacro(Path("r.urdf.xacro"), None) and not is_xacro(Path("r.urdf"), None)
    assert not is_xacro(Path("r.urdf"), b'<robot name="r"><link name="a"/></robot>')   # no "$", no "xacro"
    # a comment's removal joins what is around it: "$" then "{" is a substitution
    assert is_xacro(Path("r.urdf"), b'<robot name="$<!-- c -->{n}"/>')


# ---------------------------------------------------------------- P003 points at the joint
def test_dynamics_finding_points_at_the_first_massless_joint(tmp_path):
    p = write(tmp_path / "gripper.urdf", HEAD.format(name="gripper") + BASE + """\
  <link name="l_finger"/>
  <joint name="l_gripper_joint" type="prismatic"><parent link="base_link"/><child link="l_finger"/>
    <axis xyz="0 1 0"/><limit lower="0" upper="0.04" effort="10" velocity="0.1"/></joint>
</robot>
""")
    (d,) = [d for d in run_checks(load_robot(p), CheckOptions()) if d.code == "P003"]
    assert d.loc.line == line_of(p, 'joint name="l_gripper_joint"') and "l_gripper_joint" in d.message


# ---------------------------------------------------------------- the same on the real-robot corpus


def corpus_check(*args):
    res = CliRunner().invoke(main, ["check", "--format", "json", "--package-path", str(CORPUS), *map(str, args)])
    assert res.exit_code in (0, 1), res.output[-2000:]
    return json.loads(res.stdout)["files"]


@pytest.mark.parametrize("top", ["turtlebot3_burger.urdf.xacro", "turtlebot3_waffle_pi.urdf.xacro"])
def test_corpus_turtlebot3_full_scan_is_not_degrees(top):
    gz = CORPUS / "turtlebot3_description" / "urdf" / top.replace(".urdf.", ".gazebo.")
    assert "<max_angle>6.28319</max_angle>" in gz.read_text()
    (f,) = corpus_check(CORPUS / "turtlebot3_description" / "urdf" / top, "--select", "S006")
    assert f["links"] > 5 and f["diagnostics"] == []


def test_corpus_pr2_cameras_and_gripper_dynamics():
    (f,) = corpus_check(CORPUS / "pr2_description" / "robots" / "pr2.urdf.xacro", "--select", "G010,P003")
    cams = [p for p in f["diagnostics"] if p["code"] == "G010"]
    assert cams == []                                   # 7 cameras publish image_raw under their cameraName
    (p3,) = [p for p in f["diagnostics"] if p["code"] == "P003"]
    src = CORPUS / "pr2_description" / "urdf" / "gripper_v0" / "gripper.urdf.xacro"
    assert Path(p3["file"]).name == src.name
    assert 'name="${side}_gripper_joint"' in src.read_text().splitlines()[p3["line"] - 1]


def test_corpus_firefly_gazebo_top_file_builds_with_args():
    args = ("mav_name:=firefly namespace:=firefly enable_logging:=false enable_ground_truth:=true "
            "enable_mavlink_interface:=false log_file:=firefly wait_to_record_bag:=false").split()
    (f,) = corpus_check(CORPUS / "rotors_description" / "urdf" / "mav_generic_odometry_sensor.gazebo", *args)
    assert (f["robot"], f["links"], f["joints"]) == ("firefly", 12, 11)
    assert not [d for d in f["diagnostics"] if d["code"] in ("T001", "T017")]


def test_corpus_parts_files_named_on_the_command_line_are_not_errors():
    parts = [CORPUS / "turtlebot3_description" / "urdf" / "common_properties.xacro",
             CORPUS / "pr2_description" / "urdf" / "sensors" / "wge100_camera.gazebo.xacro"]
    res = CliRunner().invoke(main, ["check", "--format", "json", "--package-path", str(CORPUS), *map(str, parts)])
    assert res.exit_code == 0, res.output[-2000:]
    for f in json.loads(res.stdout)["files"]:
        assert f["links"] == 0 and f["counts"]["error"] == 0
        assert ("T017", "info") in [(d["code"], d["severity"]) for d in f["diagnostics"]]


# ---------------------------------------------------------------- I006: ratios below 1 stay readable
def test_i006_ratio_below_one_is_a_plain_number(tmp_path):
    """Unitree B2's lidar_link (6.55e-08 kg worth of inertia on a real part) printed
    "ratio 1/142875/1/142875/1/115344": the ratios are joined with "/", so a fraction is a number."""
    f = tmp_path / "r.urdf"
    f.write_text('<robot name="r"><link name="lidar"><inertial><mass value="0.5"/><inertia ixx="1e-09" ixy="0" '
                 'ixz="0" iyy="1e-09" iyz="0" izz="2e-09"/></inertial><collision><geometry><box size="0.1 0.1 0.1"/>'
                 '</geometry></collision></link></robot>')
    d = [x for x in run_checks(load_robot(f), CheckOptions(inertia=True)) if x.code == "I006"]
    assert len(d) == 1
    assert "(ratio 1.2e-06×/1.2e-06×/2.4e-06×)" in d[0].message, d[0].message


# ---------------------------------------------------------------- T011: a passive joint's effort 0
def test_t011_leaves_a_passive_joints_effort_zero_alone(tmp_path):
    """TurtleBot 4's wheel-drop joints (prismatic, effort 0 velocity 0, in no ros2_control block) are
    passive: effort 0 says so; the commanded arm joint with effort 0 is still reported."""
    inertial = '<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>'
    f = tmp_path / "r.urdf"
    f.write_text(f'<robot name="r"><link name="base">{inertial}</link><link name="drop">{inertial}</link>'
                 f'<link name="arm">{inertial}</link>'
                 '<joint name="wheel_drop" type="prismatic"><parent link="base"/><child link="drop"/><axis xyz="0 0 1"/>'
                 '<limit lower="0" upper="0.035" effort="0" velocity="0"/></joint>'
                 '<joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>'
                 '<limit lower="-1" upper="1" effort="0" velocity="1"/></joint>'
                 '<ros2_control name="s" type="system"><hardware><plugin>mock_components/GenericSystem</plugin>'
                 '</hardware><joint name="shoulder"><command_interface name="position"/></joint></ros2_control></robot>')
    t011 = {d.data["joint"]: d.message for d in run_checks(load_robot(f)) if d.code == "T011"}
    assert t011 == {"wheel_drop": "joint wheel_drop: velocity 0 (must be > 0)",
                    "shoulder": "joint shoulder: effort 0 (must be > 0)"}


# ---------------------------------------------------------------- G005: ros2_control wheels named against their side
def test_g005_wheel_named_left_on_the_right(tmp_path):
    """ros2_control_demos' DiffBot: left_wheel_joint sits at y -0.05 (both axes +y); its controller
    is given left_wheel_names: [left_wheel_joint], so the real robot turns the wrong way."""
    inertial = '<inertial><mass value="0.3"/><inertia ixx="3e-05" iyy="3e-05" izz="3e-05" ixy="0" ixz="0" iyz="0"/></inertial>'
    wheel = ('<joint name="{n}_wheel_joint" type="continuous"><parent link="base_link"/><child link="{n}_wheel"/>'
             '<origin xyz="0 {y} -0.025"/><axis xyz="0 1 0"/></joint><link name="{n}_wheel">' + inertial +
             '<collision><origin rpy="1.5708 0 0"/><geometry><cylinder radius="0.015" length="0.02"/></geometry>'
             '</collision></link>')
    def diffbot(left_y):
        f = tmp_path / f"diffbot{left_y}.urdf"
        f.write_text('<robot name="diffbot"><link name="base_link"/>' + wheel.format(n="left", y=left_y)
                     + wheel.format(n="right", y=-left_y) + '<ros2_control name="d" type="system"><hardware><plugin>'
                     'mock_components/GenericSystem</plugin></hardware><joint name="left_wheel_joint"><command_interface '
                     'name="velocity"/></joint><joint name="right_wheel_joint"><command_interface name="velocity"/>'
                     '</joint></ros2_control></robot>')
        return [d for d in run_checks(load_robot(f)) if d.code == "G005"]

    g005 = diffbot(-0.05)
    assert [(d.data["joint"], d.severity) for d in g005] == [("left_wheel_joint", "warning"),
                                                            ("right_wheel_joint", "warning")]
    assert "left_wheel_joint is named left but sits at y -0.05 (the right side" in g005[0].message
    assert diffbot(0.05) == []


def test_findings_of_one_code_are_in_line_order(tmp_path):
    """moveit_resources' panda.urdf (no inertials): I001 came out at lines 119, 139, 183, 19, 195, 39...
    (the location sorted as text); lines are numbers."""
    inertial_free = "".join(f'<link name="l{i}"><visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual></link>\n'
                            f'<joint name="j{i}" type="revolute"><parent link="l{i - 1}"/><child link="l{i}"/>'
                            '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>\n'
                            for i in range(1, 13))
    f = tmp_path / "p.urdf"
    f.write_text('<robot name="p">\n<link name="l0"/>\n' + inertial_free + "</robot>\n")
    lines = [d.loc.line for d in sort_diagnostics(run_checks(load_robot(f))) if d.code == "I001"]
    assert len(lines) == 12 and lines == sorted(lines) and lines[0] < 10 < lines[-1]


def test_sort_orders_every_kind_of_location():
    """Loc with and without a line, no location, and any object holding file/line or neither, in the
    report's order (severity, code, file, line as a number, message)."""
    from types import SimpleNamespace

    from myrabot_desc.diagnostics import Diagnostic, Loc

    ds = [Diagnostic("I001", "warning", "b", Loc("a.urdf", 119)), Diagnostic("I001", "warning", "a", Loc("a.urdf", 19)),
          Diagnostic("I001", "warning", "c", Loc("a.urdf")), Diagnostic("I001", "warning", "d", None),
          Diagnostic("I001", "warning", "e", SimpleNamespace(file="a.urdf", line=5)),
          Diagnostic("I001", "warning", "f", "b.urdf:3"), Diagnostic("I001", "error", "g", Loc("z.urdf", 1)),
          Diagnostic("G001", "warning", "h", Loc("z.urdf", 2))]
    assert "".join(d.message for d in sort_diagnostics(ds)) == "ghdceabf"


# ---------------------------------------------------------------- I010: a collision that covers part of the link
def test_i010_measures_the_visual_mesh_of_a_link_with_a_partial_collision(tmp_path):
    """Unitree go1/go2 hips: the collision is a cylinder off to one side, the motor (and the centre
    of mass) only in the visual mesh: not reported. A centre of mass outside both still is."""
    import trimesh

    trimesh.creation.box(extents=(0.2, 0.3, 0.1)).export(tmp_path / "hip.stl")
    link = ('<link name="{n}"><inertial><origin xyz="{com} 0 0"/><mass value="1"/><inertia ixx="0.01" iyy="0.01" '
            'izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial><visual><geometry><mesh filename="hip.stl"/></geometry>'
            '</visual><collision><origin xyz="0 0.12 0" rpy="1.5708 0 0"/><geometry><cylinder radius="0.02" '
            'length="0.04"/></geometry></collision></link>')
    f = tmp_path / "r.urdf"
    f.write_text('<robot name="r">' + link.format(n="hip", com=0) + link.format(n="far", com=1.0)
                 + '<joint name="j" type="revolute"><parent link="hip"/><child link="far"/><axis xyz="1 0 0"/>'
                 '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>')
    i010 = [d for d in run_checks(load_robot(f), CheckOptions(inertia=True)) if d.code == "I010"]
    assert [d.data["link"] for d in i010] == ["far"]
    assert "outside the box bounding its geometry (-0.1 -0.15 -0.05 .. 0.1 0.15 0.05)" in i010[0].message
