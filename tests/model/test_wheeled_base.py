"""One answer to "is this a wheeled base?" (model/drive.py): check's P rules (which call it) and
the MJCF writer's free base ask the same function, on every corpus robot."""

from __future__ import annotations


import pytest

from helpers import ROOT, corpus_model, corpus_robots
from myrabot_desc.convert.mjcf.bodies import base_is_free
from myrabot_desc.model import drive as D
from myrabot_desc.model.loader import load_robot



@pytest.mark.corpus
@pytest.mark.parametrize("r", corpus_robots(), ids=lambda r: r["id"])
def test_mobile_is_the_manifest_kind(r):
    """Wheeled bases (mobile, mobile_manipulator) and nothing else; the firefly's six rotors are
    cylinders about continuous joints too, but vertical: no wheels (check used to call it mobile)."""
    robot = corpus_model(r)
    want = r["kind"] in ("mobile", "mobile_manipulator")
    assert D.is_mobile(robot) is want
    assert base_is_free(robot, "auto") is want        # (check's P rules call D.is_mobile itself)
    if r["id"] == "firefly":
        assert sum(j.type == "continuous" for j in robot.joints.values()) == 6 and D.wheel_joints(robot) == []


def test_bundled_and_wander_bot_wheels():
    assert D.wheel_joints(load_robot()) == ["left_wheel_joint", "right_wheel_joint"]
    wander = load_robot(ROOT / "tests" / "fixtures" / "wander_bot" / "urdf" / "robot.xacro",
                        package_paths=[ROOT / "tests" / "fixtures"])
    assert D.is_mobile(wander) and len(D.wheel_joints(wander)) == 2


def test_undeclared_wheel_needs_a_level_axle(tmp_path):
    """No drive declared: a cylinder about a level continuous joint is a wheel, about a vertical
    one (a rotor, a turntable) is not."""
    body = ('<link name="b"/><link name="w"><collision><origin rpy="{rpy}"/><geometry><cylinder radius="0.05" '
            'length="0.02"/></geometry></collision></link><joint name="j" type="continuous"><parent link="b"/>'
            '<child link="w"/><axis xyz="{axis}"/></joint>')
    for rpy, axis, want in (("1.5708 0 0", "0 1 0", True), ("0 0 0", "0 0 1", False)):
        p = tmp_path / "r.urdf"
        p.write_text(f'<robot name="r">{body.format(rpy=rpy, axis=axis)}</robot>')
        assert D.is_mobile(load_robot(p)) is want


def _two_wheels(tmp_path, left: str, right: str, caster: str = "caster_wheel_joint"):
    wheel = ('<link name="{n}"><collision><geometry><cylinder radius="0.06" length="0.03"/></geometry></collision>'
             '</link><joint name="{j}" type="continuous"><parent link="base"/><child link="{n}"/>'
             '<origin xyz="{x} {y} 0.06" rpy="-1.5708 0 0"/><axis xyz="0 0 1"/></joint>')
    p = tmp_path / "b.urdf"
    p.write_text('<robot name="b"><link name="base"><inertial><mass value="10"/><inertia ixx="0.1" iyy="0.1" '
                 'izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>'
                 + wheel.format(n="lw", j=left, x=0, y=0.19) + wheel.format(n="rw", j=right, x=0, y=-0.19)
                 + wheel.format(n="cw", j=caster, x=-0.2, y=0.05) + "</robot>")
    return load_robot(p)


@pytest.mark.parametrize("left, right", [("l_wheel_joint", "r_wheel_joint"),        # Fetch
                                         ("wheel_left_joint", "wheel_right_joint"),  # TurtleBot 2/3
                                         ("left_wheel", "right_wheel")])
def test_sim_finds_wheels_by_where_they_sit(tmp_path, left, right):
    """sim's fallback drive sides continuous *wheel* joints by position (left at +y), whatever
    their names say, and leaves casters out."""
    d = D.guess_drive(_two_wheels(tmp_path, left, right))
    assert (d.left, d.right, d.source) == ((left,), (right,), "guess")


def test_sim_drive_on_a_fetch_like_base(tmp_path):
    """`sim drive` on a base without a drive plugin whose wheels are l_wheel_joint/r_wheel_joint
    (Fetch's names): it drives on the URDF's wheel geometry (separation 0.38 m, radius 0.06 m)."""
    from click.testing import CliRunner

    from myrabot_desc.commands.main import main

    _two_wheels(tmp_path, "l_wheel_joint", "r_wheel_joint")
    r = CliRunner().invoke(main, ["sim", "drive", str(tmp_path / "b.urdf")])
    assert r.exit_code == 0, r.output
    assert "URDF wheel separation: 0.3800" in r.output and "URDF wheel radius: 0.0600" in r.output
    assert "l_wheel_joint, r_wheel_joint" in r.output and "verdict: PASS" in r.output


def test_sim_drive_refuses_wheels_that_mimic_one_joint(tmp_path):
    """A car-like base (ros2_control_demos' CarlikeBot): both rear wheels <mimic> one virtual joint,
    so they cannot turn at different speeds; sim drive used to pass it turning on the spot."""
    from click.testing import CliRunner

    from myrabot_desc.commands.main import main

    _two_wheels(tmp_path, "rear_left_wheel_joint", "rear_right_wheel_joint", caster="virtual_rear_wheel_joint")
    f = tmp_path / "b.urdf"
    text = f.read_text()
    for side in ("left", "right"):
        text = text.replace(f'<joint name="rear_{side}_wheel_joint" type="continuous">',
                            f'<joint name="rear_{side}_wheel_joint" type="continuous">'
                            '<mimic joint="virtual_rear_wheel_joint" multiplier="1.0"/>')
    f.write_text(text)
    r = CliRunner().invoke(main, ["sim", "drive", str(f)])
    assert r.exit_code == 2 and "Traceback" not in r.output
    assert "turn together (<mimic> of 'virtual_rear_wheel_joint'): not a differential drive" in r.output


def test_sim_drive_says_when_the_named_left_wheel_sits_on_the_right(tmp_path):
    """--left-wheel names a joint at -y (DiffBot's left_wheel_joint): sim drives by the geometry and
    says that a controller given these names turns the wrong way (it used to say nothing)."""
    from click.testing import CliRunner

    from myrabot_desc.commands.main import main

    _two_wheels(tmp_path, "a_joint", "b_joint")            # a at +y, b at -y
    f = str(tmp_path / "b.urdf")
    r = CliRunner().invoke(main, ["sim", "drive", f, "--left-wheel", "b_joint", "--right-wheel", "a_joint"])
    assert r.exit_code == 0, r.output
    assert "the left wheel you named, b_joint, sits on the right (y -0.190 m" in r.output
    r = CliRunner().invoke(main, ["sim", "drive", f, "--left-wheel", "a_joint", "--right-wheel", "b_joint"])
    assert r.exit_code == 0 and "you named" not in r.output


def test_sim_drive_refuses_a_limited_joint_as_a_wheel(tmp_path):
    """`--wheels FR_calf_joint,FL_calf_joint` on a quadruped (limits [-2.697, -0.916]) drove the knees
    12.6 rad round and passed; a wheel must turn freely."""
    from click.testing import CliRunner

    from myrabot_desc.commands.main import main

    _two_wheels(tmp_path, "l_knee", "r_knee")
    f = tmp_path / "b.urdf"
    f.write_text(f.read_text().replace('<joint name="l_knee" type="continuous">', '<joint name="l_knee" type="revolute">'
                                       '<limit lower="-2.697" upper="-0.916" effort="33" velocity="21"/>'))
    r = CliRunner().invoke(main, ["sim", "drive", str(f), "--wheels", "l_knee,r_knee"])
    assert r.exit_code == 2 and "Traceback" not in r.output
    assert "wheel joint l_knee is revolute with limits [-2.697, -0.916]: a wheel turns freely" in r.output
