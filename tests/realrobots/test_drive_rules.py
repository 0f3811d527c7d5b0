"""G016-G019 on the real bases of every drive kind (tests/corpus/drives.yaml): no false alarm on the
robots as published, and each planted defect found with its numbers.

Planting: the URDF is built from the corpus, then edited as text (a controller YAML named by a
gz ros2_control plugin's <parameters>, a gz-sim MecanumDrive or AckermannSteering system given the
robot's own joints), and `check` runs on the edited file.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from click.testing import CliRunner

from helpers import CORPUS, drive_args, drive_robots
from myrabot_desc.commands.main import main

ROBOTS = {r["id"]: r for r in drive_robots()}
CODES = ("G016", "G017", "G018", "G019")
pytestmark = [pytest.mark.corpus,
              pytest.mark.skipif(not ROBOTS, reason="the real-robot corpus is not here")]


def _check(*args) -> list[dict]:
    res = CliRunner().invoke(main, ["check", *args, "--format", "json"])
    assert res.exit_code in (0, 1), res.output[-1500:]
    return json.loads(res.stdout)["files"][0]["diagnostics"]


def _built(rid: str, tmp_path) -> Path:
    out = tmp_path / f"{rid}.urdf"
    res = CliRunner().invoke(main, ["build", *drive_args(ROBOTS[rid]), "-o", str(out)])
    assert res.exit_code == 0, res.output[-1500:]
    return out


def _found(urdf: Path, code: str) -> list[dict]:
    return [d for d in _check(str(urdf), "--package-path", str(CORPUS)) if d["code"] == code]


@pytest.mark.parametrize("rid", list(ROBOTS))
def test_published_bases_have_no_geometry_alarm(rid):
    """As published, only ROSbot XL's skid-steer controller differs from its URDF, and by its
    multiplier alone (information: its YAML calls 1.3 an ICR coefficient for skid slip)."""
    got = [d for d in _check(*drive_args(ROBOTS[rid])) if d["code"] in CODES]
    if rid != "rosbot_xl_diff":
        assert got == []
        return
    assert len(got) == 1 and got[0]["code"] == "G016" and got[0]["severity"] == "info"
    d = got[0]["data"]
    assert (d["key"], d["value"], d["multiplier_key"], d["multiplier"]) == \
        ("wheel_separation", 0.248, "wheel_separation_multiplier", 1.3)
    assert d["effective"] == pytest.approx(0.3224) and d["urdf"] == pytest.approx(0.248, abs=1e-4)
    assert "the robot turns at 1.3× the commanded rate on wheels that do not slip" in got[0]["message"]


def _yaml_named(urdf: Path, old_yaml: Path, new_text: str) -> None:
    """Write ``new_text`` next to the URDF and make its <parameters> name it."""
    new = urdf.with_name("controllers.yaml")
    new.write_text(new_text)
    text = urdf.read_text()
    assert text.count(str(old_yaml)) == 1
    urdf.write_text(text.replace(str(old_yaml), str(new)))


def test_g016_mecanum_controller_planted(tmp_path):
    """ROSbot XL mecanum with its controller's wheel_separation_x 0.17 -> 0.25 and wheel_radius
    0.05 -> 0.06: the base turns with (x + y)/2, so (0.25 + 0.27)/(0.17 + 0.27) = 1.18× the
    commanded rate, and drives (and sideways) at 0.05/0.06 = 0.833× the commanded speed."""
    urdf = _built("rosbot_xl_mecanum", tmp_path)
    src = CORPUS / "rosbot_xl_controller/config/mecanum_drive_controller.yaml"
    text = src.read_text()
    assert text.count("wheel_separation_x: 0.170") == 1 and text.count("wheel_radius: 0.05") == 1
    _yaml_named(urdf, src, text.replace("wheel_separation_x: 0.170", "wheel_separation_x: 0.25")
                .replace("wheel_radius: 0.05", "wheel_radius: 0.06"))
    got = {d["data"]["key"]: d for d in _found(urdf, "G016")}
    assert set(got) == {"wheel_separation_x", "wheel_radius"}
    assert all(d["severity"] == "error" for d in got.values())
    assert got["wheel_separation_x"]["message"].endswith(
        "wheel_separation_x 0.25 m, but the URDF's wheelbase is 0.17 m: the robot turns at 1.18× the commanded rate")
    assert got["wheel_radius"]["message"].endswith(
        "the robot drives and sideways at 0.833× the commanded speed")
    assert (0.25 + 0.27) / (0.17 + 0.27) == pytest.approx(1.18, abs=0.005)


def _nested(text: str) -> str:
    """The same parameters file with its nodes nested under one ``/**:`` namespace (the layout of
    ros2_controllers' own examples) instead of ``/**/name:`` keys."""
    out = ["/**:"]
    for line in text.splitlines():
        if line.startswith("/**/"):
            line = line[len("/**/"):]
        if line != "---":
            out.append(("  " + line) if line.strip() else line)
    return "\n".join(out) + "\n"


def test_g016_reads_nodes_nested_under_a_namespace(tmp_path):
    """The planted mecanum YAML above, its nodes nested under ``/**:``: the same two findings."""
    urdf = _built("rosbot_xl_mecanum", tmp_path)
    src = CORPUS / "rosbot_xl_controller/config/mecanum_drive_controller.yaml"
    text = _nested(src.read_text())
    assert "/**/" not in text and "\n  rosbot_xl_base_controller:\n    ros__parameters:" in text
    _yaml_named(urdf, src, text)
    assert _found(urdf, "G016") == []
    urdf = _built("rosbot_xl_mecanum", tmp_path)
    _yaml_named(urdf, src, text.replace("wheel_separation_x: 0.170", "wheel_separation_x: 0.25"))
    (g,) = _found(urdf, "G016")
    assert g["data"]["key"] == "wheel_separation_x" and g["severity"] == "error"


def test_g016_skid_controller_number_itself_off_is_an_error(tmp_path):
    """ROSbot XL diff with wheel_separation 0.248 -> 0.3 (multiplier 1.3 kept): the number itself is
    off, so an error: 0.3 × 1.3 = 0.39 m on a 0.248 m track turns at 1.57×."""
    urdf = _built("rosbot_xl_diff", tmp_path)
    src = CORPUS / "rosbot_xl_controller/config/diff_drive_controller.yaml"
    text = src.read_text()
    assert text.count("wheel_separation: 0.248") == 1
    _yaml_named(urdf, src, text.replace("wheel_separation: 0.248", "wheel_separation: 0.3"))
    (g,) = _found(urdf, "G016")
    assert g["severity"] == "error" and g["data"]["effective"] == pytest.approx(0.39)
    assert "= 0.39 m, but the URDF's track is 0.248 m: the robot turns at 1.57× the commanded rate" in g["message"]


_GZ_CONTROL = ('<gazebo><plugin filename="gz_ros2_control-system" name="gz_ros2_control::GazeboSimROS2ControlPlugin">'
               '<parameters>{}</parameters></plugin></gazebo>\n</robot>')


def test_g016_bicycle_controller_of_carlikebot(tmp_path):
    """CarlikeBot's own bicycle_steering_controller YAML (its launch file loads it; here a gz
    ros2_control plugin names it): wheelbase 0.325 and traction_wheel_radius 0.05 agree with the
    URDF. With wheelbase 0.4 the car curves 0.4/0.325 = 1.23× as tightly as commanded."""
    urdf = _built("carlikebot", tmp_path)
    src = CORPUS / "ros2_control_demo_example_11/config/carlikebot_controllers.yaml"
    yaml_file = tmp_path / "controllers.yaml"
    yaml_file.write_text(src.read_text())
    urdf.write_text(urdf.read_text().replace("</robot>", _GZ_CONTROL.format(yaml_file)))
    assert _found(urdf, "G016") == []
    yaml_file.write_text(src.read_text().replace("wheelbase: 0.325", "wheelbase: 0.4"))
    (g,) = _found(urdf, "G016")
    assert g["data"]["controller"] == "bicycle_steering_controller" and g["data"]["kind"] == "ackermann"
    assert g["message"] == ("controllers.yaml, bicycle_steering_controller: wheelbase 0.4 m, but the URDF's "
                            "wheelbase is 0.325 m: the robot turns at 1.23× the commanded rate")


def _ackermann(**over) -> str:
    """gz-sim AckermannSteering on Audibot's joints with the numbers of Audibot's own plugin source
    (wheelbase 2.65, front track 1.638, radius 0.36) and the rear track 1.6 of its URDF."""
    p = {"wheel_base": "2.65", "kingpin_width": "1.638", "wheel_separation": "1.6", "wheel_radius": "0.36",
         "steering_limit": "0.5811"}
    p.update(over)
    body = "".join(f"<{k}>{v}</{k}>" for k, v in p.items() if v is not None)
    return ('<gazebo><plugin filename="gz-sim-ackermann-steering-system" name="gz::sim::systems::AckermannSteering">'
            "<left_joint>wheel_fl_joint</left_joint><left_joint>wheel_rl_joint</left_joint>"
            "<right_joint>wheel_fr_joint</right_joint><right_joint>wheel_rr_joint</right_joint>"
            "<left_steering_joint>steer_fl_joint</left_steering_joint>"
            f"<right_steering_joint>steer_fr_joint</right_steering_joint>{body}</plugin></gazebo>\n</robot>")


def test_g017_g018_ackermann_steering_planted_into_audibot(tmp_path):
    urdf = _built("audibot", tmp_path)
    base = urdf.read_text()
    urdf.write_text(base.replace("</robot>", _ackermann()))
    assert _found(urdf, "G017") == [] and _found(urdf, "G018") == []
    # a wheelbase 2.0 m on a 2.652 m car: it curves at 2.0/2.652 = 0.754× the commanded rate
    urdf.write_text(base.replace("</robot>", _ackermann(wheel_base="2.0")))
    (g,) = _found(urdf, "G017")
    assert g["data"]["param"] == "wheel_base" and g["data"]["fix"] == pytest.approx(2.652, abs=1e-3)
    assert g["message"].endswith("wheel_base 2 m, but the URDF's wheelbase is 2.652 m: the robot turns at "
                                 "0.754× the commanded rate")
    # kingpin_width not written: the system's default 0.8 m, where the steering axes are 1.638 m apart
    urdf.write_text(base.replace("</robot>", _ackermann(kingpin_width=None)))
    (g,) = _found(urdf, "G017")
    assert g["data"]["default"] is True and g["data"]["value"] == 0.8
    assert "kingpin_width not given: it uses its default 0.8 m" in g["message"] and "° off" in g["message"]
    # steering_limit 0.8 rad beyond the joints' ±0.6: minimum turning radius 3.876 m, not 2.576 m
    urdf.write_text(base.replace("</robot>", _ackermann(steering_limit="0.8")))
    (g,) = _found(urdf, "G018")
    assert g["data"]["min_turn_radius"] == pytest.approx(2.652 / math.tan(0.6), abs=1e-3)
    assert g["data"]["plugin_min_turn_radius"] == pytest.approx(2.652 / math.tan(0.8), abs=1e-3)
    assert "minimum turning radius 3.876 m instead of 2.576 m" in g["message"]


def _mecanum(**over) -> str:
    p = {"wheel_separation": "0.27", "wheelbase": "0.17", "wheel_radius": "0.05"}
    p.update(over)
    body = "".join(f"<{k}>{v}</{k}>" for k, v in p.items() if v is not None)
    return ('<gazebo><plugin filename="gz-sim-mecanum-drive-system" name="gz::sim::systems::MecanumDrive">'
            "<front_left_joint>fl_wheel_joint</front_left_joint><front_right_joint>fr_wheel_joint</front_right_joint>"
            "<back_left_joint>rl_wheel_joint</back_left_joint><back_right_joint>rr_wheel_joint</back_right_joint>"
            f"{body}</plugin></gazebo>\n</robot>")


def test_g017_mecanum_drive_planted_into_rosbot_xl(tmp_path):
    """gz-sim MecanumDrive on ROSbot XL's wheels with its URDF's numbers: quiet. Without
    wheel_radius the system uses 0.2 m on 0.05 m wheels: the base drives (and sideways) at 0.25×."""
    urdf = _built("rosbot_xl_mecanum", tmp_path)
    base = urdf.read_text()
    urdf.write_text(base.replace("</robot>", _mecanum()))
    assert _found(urdf, "G017") == []
    urdf.write_text(base.replace("</robot>", _mecanum(wheel_radius=None)))
    (g,) = _found(urdf, "G017")
    assert g["message"] == ("gz::sim::systems::MecanumDrive: wheel_radius not given: it uses its default 0.2 m, "
                            "but the URDF's wheel radius is 0.05 m: the robot drives and sideways at 0.25× the "
                            "commanded speed")


def test_g019_mecanum_roller_friction_planted_into_rosbot_xl(tmp_path):
    """ROSbot XL mecanum's wheels grip only along diagonals (mu 1 along fdir1, mu2 0): sideways 1×
    as published (no G019). With mu2 1 the wheels are plain and cannot roll sideways (0×); with the
    diagonals the wrong way round it drives sideways backwards and turns 4.4× too fast."""
    urdf = _built("rosbot_xl_mecanum", tmp_path)
    base = urdf.read_text()
    assert base.count("<mu2>0.0</mu2>") == 4
    urdf.write_text(base.replace("<mu2>0.0</mu2>", "<mu2>1.0</mu2>"))
    (g,) = _found(urdf, "G019")
    assert g["data"]["sideways"][1] == pytest.approx(0, abs=1e-9)
    assert "(every wheel mu 1, mu2 1, fdir1 (0.71 -0.71))" not in g["message"]
    assert "a sideways command drives sideways at 0×" in g["message"]
    fl, fr = '">1 -1 0</fdir1>', '">1 1 0</fdir1>'
    assert base.count(fl) == 2 and base.count(fr) == 2
    urdf.write_text(base.replace(fl, "@").replace(fr, fl).replace("@", fr))
    (g,) = _found(urdf, "G019")
    assert g["data"]["sideways"][1] == pytest.approx(-1) and g["data"]["turn"][2] == pytest.approx(4.4, abs=0.01)
    assert "a sideways command drives sideways at -1×, and it turns at 4.4× the commanded rate" in g["message"]
