"""`check` on the seed robots as their authors wrote them (seed-spec.md §6.3, §7.3–7.5)."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from helpers import FIXTURES
from myrabot_desc.commands.main import main

FIX = FIXTURES
WANDER = FIX / "wander_bot" / "urdf" / "robot.xacro"
SEED = FIX / "seed_myrabot"
SEED_ASSEMBLY = SEED / "myrabot_fer_modelo" / "urdf" / "myrabot.urdf.xacro"
SONAR = FIX / "check" / "sonar" / "myrabot_sonar.urdf.xacro"


def run_json(*args):
    res = CliRunner().invoke(main, ["check", "--format", "json", *map(str, args)])
    assert res.exit_code in (0, 1), res.output
    doc = json.loads(res.stdout)
    assert doc["schema"] == "myrabot-desc/check-report/1"
    return res.exit_code, doc["files"][0]["diagnostics"]


def by_code(diags, code):
    return [d for d in diags if d["code"] == code]


def one(diags, code, **match):
    found = [d for d in by_code(diags, code) if all(d["data"].get(k) == v for k, v in match.items())]
    assert len(found) == 1, (code, match, [d["message"] for d in by_code(diags, code)])
    return found[0]


# ---------------------------------------------------------------- seed B: the Korean wander_bot
@pytest.fixture(scope="module")
def wander():
    return run_json(WANDER, "--inertia")


def test_wander_exit_code_is_errors(wander):
    assert wander[0] == 1


def test_wander_wheel_separation_0_4_vs_0_30(wander):
    d = one(wander[1], "G001")
    assert d["severity"] == "error"
    assert d["data"]["value"] == 0.4 and d["data"]["urdf"] == pytest.approx(0.30)
    assert "wheelSeparation 0.4 m" in d["message"] and "0.3 m apart" in d["message"]
    assert d["file"].endswith("robot.gazebo") and d["line"] == 4


def test_wander_wheel_diameter_0_2_vs_0_16(wander):
    d = one(wander[1], "G002")
    assert d["data"]["value"] == 0.2 and d["data"]["urdf"] == pytest.approx(0.16)
    assert "0.8× the commanded speed" in d["message"]


def test_wander_scanner_tensor_is_impossible(wander):
    d = one(wander[1], "I005", link="scanner_link")
    assert sorted(d["data"]["principal"]) == pytest.approx([1.0, 1.0, 10.0])
    assert d["file"].endswith("robot.xacro")


def test_wander_inertias_about_100x_too_large(wander):
    ratios = {d["data"]["link"]: d["data"]["ratios"] for d in by_code(wander[1], "I006")}
    assert set(ratios) == {"base_link", "left_wheel", "right_wheel", "scanner_link"}
    # seed-spec §6.3: base 80–166×, wheels 312–553×
    assert ratios["base_link"] == pytest.approx([1 / 0.0060417, 1 / 0.0083333, 1 / 0.0127083], rel=1e-3)
    assert ratios["left_wheel"] == pytest.approx([1 / 0.0018083, 1 / 0.0032, 1 / 0.0018083], rel=1e-3)
    assert all(r > 50 for rs in ratios.values() for r in rs)


def test_wander_no_support_com_behind_axle_no_caster(wander):
    d = one(wander[1], "P001")
    assert d["severity"] == "error"
    assert d["data"]["contacts"] == ["left_wheel", "right_wheel"]
    assert d["data"]["com"][0] == pytest.approx(0.0875)
    assert "12.5 mm behind" in d["message"] and "no caster" in d["message"]
    # pivoting about the axle (r 0.08), the box's rear bottom edge (0.25 m behind, 0.02 m below the
    # axle) lands after acos(-0.08/0.2508) - atan2(0.25, -0.02) = 14.0° (seed-spec's flat estimate: 13.5°)
    assert d["data"]["tip_angle_deg"] == pytest.approx(14.0, abs=0.05) and d["data"]["rests_on"] == "base_link"


def test_wander_wheels_below_ground_at_spawn(wander):
    d = one(wander[1], "P002")
    assert d["data"]["min_z"] == pytest.approx(-0.05)
    assert {"left_wheel", "right_wheel"} <= set(d["data"]["links"])


def test_wander_rpy_on_box_with_line(wander):
    d = one(wander[1], "T006", attribute="rpy", element="box")
    assert d["file"].endswith("robot.xacro") and d["line"] == 22


def test_wander_stray_ros_block(wander):
    d = one(wander[1], "T007")
    assert "/cmd_vel:=cmd_vel" in d["message"] and d["line"] == 124


def test_wander_torque_ignored(wander):
    params = {d["data"]["param"] for d in by_code(wander[1], "G007")}
    assert {"torque", "alwaysOn"} <= params
    assert "reads wheelTorque (5)" in one(wander[1], "G012")["message"]


def test_wander_suggest_prints_ready_inertia_lines():
    res = CliRunner().invoke(main, ["check", "--inertia", "--suggest", str(WANDER)])
    assert res.exit_code == 1
    assert 'base_link: <inertia ixx="0.006042" ixy="0" ixz="0" iyy="0.008333" iyz="0" izz="0.01271"/>' in res.output
    assert 'left_wheel: <inertia ixx="0.001808" ixy="0" ixz="0" iyy="0.0032" iyz="0" izz="0.001808"/>' in res.output


# ---------------------------------------------------------------- seed A: MYRAbot as the wiki wrote it
@pytest.fixture(scope="module")
def seed():
    return run_json(SEED_ASSEMBLY, "--package-path", SEED)


def test_seed_placeholder_inertias_with_ratios(seed):
    d = one(seed[1], "I006", link="e_start_button_1_link")     # seed-spec §7.4: 4.9e5 / 4.9e5 / 2.5e5
    assert d["data"]["ratios"] == pytest.approx([4.86e5, 4.86e5, 2.47e5], rel=0.01)
    d = one(seed[1], "I006", link="e_base_1_link")             # 44 / 44 / 22
    assert d["data"]["ratios"] == pytest.approx([43.7, 43.7, 21.9], rel=0.01)
    p = [d for d in by_code(seed[1], "I009") if d["data"]["tensor"]["ixx"] == 0.01][0]
    assert len(p["data"]["links"]) >= 24 and p["data"]["mass_min"] == 0.0001 and p["data"]["mass_max"] == 0.1


def test_seed_impossible_roomba_and_cliff_tensors(seed):
    assert sorted(one(seed[1], "I005", link="base_link")["data"]["principal"]) == pytest.approx([0.01, 0.01, 0.5])
    assert one(seed[1], "I005", link="leftfront_cliff_sensor_link")["file"].endswith("roomba.xacro")
    g = one(seed[1], "I007", link="base_link")                 # √(0.5/3.6) = 0.373 m on a 0.17 m disc
    assert g["data"]["radius_of_gyration"] == pytest.approx(0.3727, rel=1e-3)
    assert g["data"]["reach"] == pytest.approx(0.17, rel=0.01)


def test_seed_gaezebo_typo(seed):
    d = one(seed[1], "T005", element="gaezebo")
    assert d["data"]["suggestion"] == "gazebo" and d["file"].endswith("roomba.xacro")


def test_seed_webcam_filename_attribute(seed):
    d = one(seed[1], "G008")
    assert "webcam_camera_controller" in d["message"] and d["file"].endswith("webcam.xacro")
    s = one(seed[1], "S003")                                   # frameName is not an optical frame
    assert s["data"]["frame"] == "e_webcam_optica_link"


def test_seed_unresolvable_materials_and_meshes(seed):
    mats = {d["data"]["material"] for d in by_code(seed[1], "G009")}
    assert {"myrabot_fer/Black", "myrabot_fer/White"} <= mats
    pkgs = {d["data"]["package"] for d in by_code(seed[1], "M001")}
    assert "myrabot_robot_model" in pkgs                        # §7.2: the half-renamed package


def test_seed_missing_sonars_from_build(seed):
    x = [d for d in by_code(seed[1], "X002") if "ultrasonidos" in d["message"]]
    assert len(x) == 5 and all(d["file"].endswith("myrabot.urdf.xacro") for d in x)
    assert not [d for d in by_code(seed[1], "T005") if d["data"]["element"] == "ultrasonidos"]   # said once


def test_seed_sonar_fov_in_degrees():
    code, diags = run_json(SONAR, "--package-path", SEED)
    d = one(diags, "S006")
    assert d["data"]["value"] == 32 and d["data"]["fix"] == pytest.approx(0.5585, abs=1e-4)
    assert d["file"].endswith("ultrasonidos.xacro")
    assert one(diags, "S005")["severity"] == "warning"          # minRange 0
    assert code == 1


# ---------------------------------------------------------------- the bundled MYRAbot
def test_bundled_myrabot_has_no_error_with_inertia():
    res = CliRunner().invoke(main, ["check", "--inertia", "--format", "json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    errors = [d for d in doc["files"][0]["diagnostics"] if d["severity"] == "error"]
    assert errors == []
    assert doc["files"][0]["links"] > 50
