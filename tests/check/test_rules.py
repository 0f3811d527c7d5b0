"""One small synthetic URDF per rule family: the rule fires with the right numbers, and stays quiet on a good model."""

from __future__ import annotations

import textwrap

import pytest

from myrabot_desc.checks import CheckOptions, run_checks
from myrabot_desc.model.loader import load_robot

INERT = '<inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>'


def robot(tmp_path, body: str, name="t.urdf"):
    p = tmp_path / name
    p.write_text(f'<?xml version="1.0"?>\n<robot name="t">\n{textwrap.dedent(body)}\n</robot>\n')
    return load_robot(p)


def codes(r, **opts):
    return [d.code for d in run_checks(r, CheckOptions(**opts))]


def diag(r, code, **opts):
    ds = [d for d in run_checks(r, CheckOptions(**opts)) if d.code == code]
    assert ds, (code, [str(d) for d in run_checks(r, CheckOptions(**opts))])
    return ds[0]


def link(name, extra=INERT):
    return f'<link name="{name}">{extra}</link>'


def joint(name, parent, child, jtype="fixed", more=""):
    return f'<joint name="{name}" type="{jtype}"><parent link="{parent}"/><child link="{child}"/>{more}</joint>'


def test_good_arm_has_no_error(tmp_path):
    r = robot(tmp_path, link("base") + link("l1", INERT + '<collision><geometry><box size="0.3 0.3 0.3"/></geometry></collision>')
              + joint("j1", "base", "l1", "revolute", '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="5" velocity="1"/>'))
    assert [d for d in run_checks(r) if d.severity == "error"] == []


def test_tree_two_roots_cycle_missing_duplicate(tmp_path):
    r = robot(tmp_path, link("a") + link("b") + link("island"))
    assert "3 root links (a, b, island)" in diag(r, "T001").message
    r = robot(tmp_path, link("a") + link("b") + link("a") + joint("j", "a", "ghost") + joint("k", "a", "b"))
    assert "'ghost' does not exist" in diag(r, "T003").message
    assert "named 'a'" in diag(r, "T004").message
    r = robot(tmp_path, link("root") + link("a") + link("b") + joint("r", "root", "a") + joint("ab", "a", "b")
              + joint("ba", "b", "a"))
    assert "child of 2 joints" in diag(r, "T002").message


def test_joint_axis_limits_mimic_type(tmp_path):
    r = robot(tmp_path, link("a") + link("b") + link("c") + link("d") + link("e")
              + joint("j0", "a", "b", "revolute", '<axis xyz="0 0 0"/><limit lower="1" upper="-1" effort="-2" velocity="1"/>')
              + joint("j1", "a", "c", "prismatic")
              + joint("j2", "a", "d", "continuous", '<mimic joint="j9"/>')
              + joint("j3", "a", "e", "revolut"))
    assert "axis 0 0 0" in diag(r, "T008").message
    assert "has no <limit>" in diag(r, "T009").message
    assert "lower 1 > upper -1" in diag(r, "T015").message
    t11 = diag(r, "T011")
    # negative is SDF's "no limit" (Gazebo and convert read it so): a warning that says so
    assert t11.severity == "warning" and "effort -2 (negative: SDF's \"no limit\"" in t11.message
    assert "mimics 'j9'" in diag(r, "T012").message
    assert "did you mean revolute?" in diag(r, "T016").message


def test_zero_range_limit(tmp_path):
    r = robot(tmp_path, link("a") + link("b") + joint("j", "a", "b", "revolute", '<limit effort="1" velocity="1"/>'))
    assert "range [0, 0]" in diag(r, "T013").message


def test_unknown_elements_and_attributes(tmp_path):
    r = robot(tmp_path, link("a") + link("b") + joint("j", "a", "b", "continuous", '<dynamics damping="0.1" fricction="0.5"/>')
              + '<gaezebo reference="a"/><ros><namespace>/x</namespace></ros>')
    assert diag(r, "T005").data["suggestion"] == "gazebo"
    d = diag(r, "T006")
    assert d.data["attribute"] == "fricction" and d.data["suggestion"] == "friction"
    assert d.loc.line == 3                                     # the line of <dynamics> in the file
    assert "<namespace>/x" in diag(r, "T007").message


def test_massless_moving_link_mass_nan(tmp_path):
    r = robot(tmp_path, link("a") + link("b", '<visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>')
              + joint("j", "a", "b", "continuous", '<axis xyz="0 0 1"/>'))
    assert diag(r, "I001").data["link"] == "b"
    p = diag(r, "P003")
    assert "NaN" in p.message and p.data["massless_joints"] == ["j"]


def test_massless_frame_without_geometry_warns(tmp_path):
    r = robot(tmp_path, link("a") + link("v", "") + link("c") + joint("j", "a", "v", "continuous")
              + joint("k", "v", "c", "continuous"))
    d = diag(r, "I002")
    assert d.severity == "warning" and d.data["children"] == ["c"]


def test_not_positive_definite_and_triangle(tmp_path):
    bad = '<inertial><mass value="1"/><inertia ixx="-0.1" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>'
    tri = '<inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>'
    r = robot(tmp_path, link("a", bad) + link("b", tri) + joint("j", "a", "b"))
    assert diag(r, "I004").data["principal"][0] == pytest.approx(-0.1)
    assert sorted(diag(r, "I005").data["principal"]) == pytest.approx([0.1, 0.1, 1.0])


def test_inertia_vs_box_and_density_and_origin(tmp_path):
    # a 0.1 m aluminium-ish cube of 2.7 kg: I = m a²/6 = 0.0045; declared 0.45 (100×); origin 0.5 m away
    body = ('<inertial><origin xyz="0.5 0 0"/><mass value="2.7"/>'
            '<inertia ixx="0.45" ixy="0" ixz="0" iyy="0.45" iyz="0" izz="0.45"/></inertial>'
            '<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>')
    r = robot(tmp_path, link("a", body))
    d = diag(r, "I006")
    assert d.data["computed"] == pytest.approx([0.0045] * 3) and d.data["ratios"] == pytest.approx([100] * 3)
    assert diag(r, "I007").data["radius_of_gyration"] == pytest.approx((0.45 / 2.7) ** 0.5)
    assert diag(r, "I010").data["distance"] == pytest.approx(0.45)
    assert "I008" not in codes(r)                              # 2700 kg/m³ is plausible
    light = body.replace('value="2.7"', 'value="0.01"')
    assert diag(robot(tmp_path, link("a", light)), "I008").data["density"] == pytest.approx(10.0)


def test_placeholder_reused(tmp_path):
    links = "".join(link(f"l{i}", f'<inertial><mass value="{m}"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>')
                    for i, m in enumerate((0.001, 0.01, 0.1)))
    r = robot(tmp_path, links + joint("a", "l0", "l1") + joint("b", "l0", "l2"))
    d = diag(r, "I009")
    assert d.data["mass_min"] == 0.001 and d.data["mass_max"] == 0.1


DIFF = """
<link name="base_footprint"/>
<link name="base_link">
  <inertial><origin xyz="-0.05 0 0"/><mass value="2"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.02"/></inertial>
  <collision><origin xyz="0 0 0.05"/><geometry><box size="0.3 0.3 0.05"/></geometry></collision>
</link>
<joint name="fp" type="fixed"><origin xyz="0 0 0.05"/><parent link="base_footprint"/><child link="base_link"/></joint>
{wheels}
<link name="caster"><inertial><mass value="0.01"/><inertia ixx="1e-6" ixy="0" ixz="0" iyy="1e-6" iyz="0" izz="1e-6"/></inertial>
  <collision><geometry><sphere radius="0.025"/></geometry></collision></link>
<joint name="cj" type="fixed"><origin xyz="-0.12 0 -0.025"/><parent link="base_link"/><child link="caster"/></joint>
<gazebo><plugin name="dd" filename="{lib}">{params}</plugin></gazebo>
"""
WHEEL = """
<link name="{n}_wheel"><inertial><mass value="0.2"/><inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial>
  <collision><origin rpy="1.5708 0 0"/><geometry><cylinder radius="0.05" length="0.02"/></geometry></collision></link>
<joint name="{n}_joint" type="continuous"><origin xyz="0 {y} 0"/><parent link="base_link"/><child link="{n}_wheel"/><axis xyz="0 {ax} {az}"/></joint>
"""


def diff_robot(tmp_path, lib, params, left_y=0.15, axis=(1, 0)):
    wheels = WHEEL.format(n="left", y=left_y, ax=axis[0], az=axis[1]) + WHEEL.format(n="right", y=-0.15, ax=1, az=0)
    return robot(tmp_path, DIFF.format(wheels=wheels, lib=lib, params=params))


def test_gz_diff_drive_good(tmp_path):
    r = diff_robot(tmp_path, "gz-sim-diff-drive-system",
                   "<left_joint>left_joint</left_joint><right_joint>right_joint</right_joint>"
                   "<wheel_separation>0.3</wheel_separation><wheel_radius>0.05</wheel_radius>")
    c = codes(r)
    assert not {"G001", "G002", "G003", "G004", "G005", "G007", "P001", "P002"} & set(c), c


def test_gz_diff_drive_radius_and_typo(tmp_path):
    r = diff_robot(tmp_path, "gz-sim-diff-drive-system",
                   "<left_joint>left_joint</left_joint><right_joint>right_joint</right_joint>"
                   "<wheel_separation>0.5</wheel_separation><wheel_radius>0.1</wheel_radius>"
                   "<odom_publisher_frequency>30</odom_publisher_frequency>")
    assert diag(r, "G001").data["urdf"] == pytest.approx(0.3)
    g2 = diag(r, "G002")
    assert g2.data["param"] == "wheel_radius" and g2.data["urdf"] == pytest.approx(0.05)
    assert "odom_publish_frequency" in diag(r, "G007").message


def test_ros2_diff_drive_ignored_topics_and_bad_joints(tmp_path):
    r = diff_robot(tmp_path, "libgazebo_ros_diff_drive.so",
                   "<left_joint>left_jiont</left_joint><right_joint>right_joint</right_joint>"
                   "<wheel_separation>0.3</wheel_separation><wheel_diameter>0.1</wheel_diameter>"
                   "<command_topic>cmd</command_topic>", axis=(0, 1))
    assert diag(r, "G003").data["suggestion"] == "left_joint"
    assert "remap it" in diag(r, "G007").message


def test_axis_along_z_and_swapped_wheels(tmp_path):
    r = diff_robot(tmp_path, "libgazebo_ros_diff_drive.so",
                   "<legacyMode>false</legacyMode><leftJoint>left_joint</leftJoint><rightJoint>right_joint</rightJoint>",
                   left_y=-0.15, axis=(0, 1))     # (in legacy mode the swapped names would turn the right way)
    msgs = [d.message for d in run_checks(r) if d.code == "G005"]
    assert any("not across the direction of travel" in m for m in msgs)
    assert any("swapped" in m for m in msgs)


def test_support_polygon_with_caster_ok_and_com_outside(tmp_path):
    params = "<leftJoint>left_joint</leftJoint><rightJoint>right_joint</rightJoint>"
    assert "P001" not in codes(diff_robot(tmp_path, "libgazebo_ros_diff_drive.so", params))
    r = robot(tmp_path, DIFF.format(wheels=WHEEL.format(n="left", y=0.15, ax=1, az=0) + WHEEL.format(n="right", y=-0.15, ax=1, az=0),
                                    lib="libgazebo_ros_diff_drive.so", params=params).replace('origin xyz="-0.05 0 0"', 'origin xyz="0.2 0 0"'))
    d = diag(r, "P001")
    assert "outside the support polygon" in d.message and d.data["distance"] < 0


def test_gazebo_reference_and_plugin_frames(tmp_path):
    r = robot(tmp_path, link("base") + '<gazebo reference="bsae"><sensor name="imu" type="imu">'
              '<plugin name="p" filename="libgazebo_ros_imu_sensor.so"><frame_name>imu_lnk</frame_name></plugin>'
              '</sensor></gazebo><gazebo reference="base"><material>Gazebo/Grey</material></gazebo>'
              '<gazebo><plugin name="p3d" filename="libgazebo_ros_p3d.so"><bodyName>base</bodyName>'
              '<frameName>world</frameName></plugin></gazebo>')
    s1 = diag(r, "S001")
    assert s1.severity == "error" and s1.data["suggestion"] == "base"
    s2 = [d for d in run_checks(r) if d.code == "S002"]
    assert [d.data["value"] for d in s2] == ["imu_lnk"]          # 'world' is a valid frame
    assert "G009" not in codes(r)                                # stock material resolves


CAMERA = """
<link name="base"/>
<link name="cam"><inertial><mass value="0.1"/><inertia ixx="1e-5" ixy="0" ixz="0" iyy="1e-5" iyz="0" izz="1e-5"/></inertial></link>
<joint name="cj" type="fixed"><origin xyz="0.1 0 0.2"/><parent link="base"/><child link="cam"/></joint>
<link name="cam_optical"/>
<joint name="oj" type="fixed"><origin rpy="{rpy}"/><parent link="cam"/><child link="cam_optical"/></joint>
<gazebo reference="cam"><sensor name="c" type="camera"><camera><horizontal_fov>{fov}</horizontal_fov>
<clip><near>0.5</near><far>0.1</far></clip></camera>
<plugin name="cp" filename="libgazebo_ros_camera.so"><frame_name>cam_optical</frame_name></plugin></sensor></gazebo>
"""


def test_camera_optical_frame_fov_and_clip(tmp_path):
    good = robot(tmp_path, CAMERA.format(rpy="-1.5708 0 -1.5708", fov="1.047"))
    assert "S003" not in codes(good)
    assert diag(good, "S005").data == {"sensor": "c", "min": 0.5, "max": 0.1}
    bad = robot(tmp_path, CAMERA.format(rpy="0 0 0", fov="60"))
    assert diag(bad, "S003").data["frame"] == "cam_optical"
    d = diag(bad, "S006")
    assert d.data["value"] == 60 and d.data["fix"] == pytest.approx(1.0472, abs=1e-4)


def test_duplicate_topics(tmp_path):
    r = robot(tmp_path, link("base") + '<gazebo><plugin name="a" filename="libgazebo_ros_laser.so"><topicName>scan</topicName>'
              '</plugin><plugin name="b" filename="libgazebo_ros_block_laser.so"><topicName>/scan</topicName></plugin></gazebo>')
    assert diag(r, "G010").data["topic"] == "/scan"


def test_mesh_missing_scale_watertight_inverted(tmp_path):
    import trimesh

    big = trimesh.creation.box((100, 100, 100))                 # a 0.1 m part exported in millimetres
    big.export(tmp_path / "big.stl")
    inv = trimesh.creation.box((0.1, 0.1, 0.1))
    inv.invert()
    inv.export(tmp_path / "inv.stl")
    opened = trimesh.creation.box((0.1, 0.1, 0.1))
    opened.update_faces(list(range(10)))
    opened.export(tmp_path / "open.stl")
    geo = lambda f: f'<collision><geometry><mesh filename="{f}"/></geometry></collision>'   # noqa: E731
    r = robot(tmp_path, link("a", INERT + geo("big.stl")) + link("b", INERT + geo("inv.stl"))
              + link("c", INERT + geo("open.stl")) + link("d", INERT + geo("nothere.stl"))
              + joint("j1", "a", "b") + joint("j2", "a", "c") + joint("j3", "a", "d"))
    assert "M002" not in codes(r)                               # contents only with --inertia/--meshes
    assert "no such file" in diag(r, "M001").message
    assert diag(r, "M002", meshes=True).data["extent"] == pytest.approx(100)
    assert diag(r, "M004", meshes=True).data["volume"] < 0
    assert diag(r, "M003", meshes=True).data["link"] == "c"
    assert "not watertight" in [d for d in run_checks(r, CheckOptions(inertia=True)) if d.code == "I011"
                                and d.data["link"] == "c"][0].message


def test_g016_swerve_controller_wheelbase(tmp_path):
    """A swerve base (four steered modules at x ±0.2, y ±0.15) whose controller YAML says wheelbase
    0.5: steered for rotation about the wrong corners, it turns at the least-squares rate
    (0.4·0.5 + 0.3²)/(0.4² + 0.3²) = 1.16× the commanded one."""
    parts = [link("base_link")]
    for n, x, y in (("fl", 0.2, 0.15), ("fr", 0.2, -0.15), ("rl", -0.2, 0.15), ("rr", -0.2, -0.15)):
        parts.append(link(f"{n}_module") + joint(f"{n}_steering_joint", "base_link", f"{n}_module", "revolute",
                     f'<origin xyz="{x} {y} 0"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="10" velocity="5"/>'))
        parts.append(link(f"{n}_wheel", INERT + '<collision><origin rpy="1.5708 0 0"/><geometry><cylinder radius="0.05" '
                                                'length="0.03"/></geometry></collision>')
                     + joint(f"{n}_wheel_joint", f"{n}_module", f"{n}_wheel", "continuous",
                             '<origin xyz="0 0 -0.05"/><axis xyz="0 1 0"/>'))
    parts.append('<gazebo><plugin filename="gz_ros2_control-system" name="gz_ros2_control::GazeboSimROS2ControlPlugin">'
                 "<parameters>c.yaml</parameters></plugin></gazebo>")
    (tmp_path / "c.yaml").write_text("controller_manager:\n  ros__parameters:\n    swerve:\n"
                                     "      type: swerve_drive_controller/SwerveDriveController\n"
                                     "swerve:\n  ros__parameters:\n    wheelbase: 0.5\n    track_width: 0.3\n"
                                     "    wheel_radius: 0.05\n")
    g = diag(robot(tmp_path, "\n".join(parts)), "G016")
    assert g.message == ("c.yaml, swerve: wheelbase 0.5 m, but the URDF's wheelbase is 0.4 m: the robot turns at "
                         "1.16× the commanded rate, its modules scrubbing")
    assert (0.4 * 0.5 + 0.3 ** 2) / (0.4 ** 2 + 0.3 ** 2) == pytest.approx(1.16)
