"""One parser for numbers, vectors and booleans (model/values.py), and check and convert agreeing on
the values they both read.

Booleans follow the program that reads each value (sdformat's src/Param.cc for SDF values and
plugin parameters, src/parser_urdf.cc for <gazebo> extension flags): `preserveFixedJoint yes`
keeps the joint for sdformat, so for check's S004 and for convert --lump alike; `on` means
nothing to either.
"""

from __future__ import annotations

import json

import pytest

from helpers import invoke
from myrabot_desc.model import values as V
from myrabot_desc.model.gazebo import preserved_joints
from myrabot_desc.model.loader import load_robot


@pytest.mark.parametrize("text, want", [("0.5", 0.5), (" -2e3 ", -2000.0), (".260", 0.26), ("1", 1.0)])
def test_numbers(text, want):
    assert V.parse_number(text) == want and V.number(text) == want


@pytest.mark.parametrize("text, reason", [("abc", V.NOT_A_NUMBER), ("", V.NOT_A_NUMBER), ("nan", V.NOT_FINITE),
                                          ("inf", V.NOT_FINITE), ("1 2", V.NOT_A_NUMBER)])
def test_not_numbers_say_why_in_one_wording(text, reason):
    with pytest.raises(V.ValueProblem) as exc:
        V.parse_number(text)
    assert exc.value.reason == reason
    assert V.number(text, 7.0) == 7.0
    assert V.problem("mass", text, exc.value.reason, "value") == f'<mass value="{text}">: {reason}'
    assert V.problem("wheelSeparation", text, exc.value.reason) == \
        f"<wheelSeparation>{text}</wheelSeparation>: {reason}"


def test_limits_and_vectors():
    with pytest.raises(V.ValueProblem) as exc:
        V.parse_number("2e6", limit=1e6)
    assert exc.value.reason == "out of range (more than 1e+06 in magnitude)"
    assert V.parse_vector("1 2 3", 3) == (1.0, 2.0, 3.0)
    assert V.vector("1 2", 3) is None and V.vector("1 x 3", 3) is None and V.vector("1 2", None) == (1.0, 2.0)
    for text, reason in (("1 2", "expected 3 finite numbers"), ("1 x 3", "expected 3 numbers"),
                         ("1 nan 3", "expected 3 finite numbers")):
        with pytest.raises(V.ValueProblem) as exc:
            V.parse_vector(text, 3)
        assert exc.value.reason == reason


@pytest.mark.parametrize("text, sdf, extension", [
    ("true", True, True), ("TRUE", True, True), (" 1 ", True, True), ("yes", None, True), ("Yes", None, True),
    ("on", None, None), ("false", False, False), ("0", False, False), ("no", None, False), ("off", None, None),
    ("maybe", None, None), (None, None, None)])
def test_boolean_spellings_are_sdformats(text, sdf, extension):
    assert V.boolean(text) is sdf
    assert V.boolean(text, spellings=V.EXTENSION) is extension


def test_extension_flags_as_sdformat_reads_them():
    """parser_urdf.cc: a flag it does not spell as true is false; turnGravityOff the other way round."""
    assert [V.extension_flag(t) for t in ("yes", "1", "on", "garbage")] == [True, True, False, False]
    assert [V.extension_flag(t, inverted=True) for t in ("no", "0", "off", "garbage")] == [False, False, True, True]
    assert V.extension_flag(None) is None


def _sensor_on_fixed_massless_link(tmp_path, flag: str):
    f = tmp_path / f"r_{flag}.urdf"
    f.write_text(f'''<robot name="r">
  <link name="base_link">
    <inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
  <link name="imu_link"/>
  <joint name="imu_joint" type="fixed"><parent link="base_link"/><child link="imu_link"/></joint>
  <gazebo reference="imu_joint"><preserveFixedJoint>{flag}</preserveFixedJoint></gazebo>
  <gazebo reference="imu_link"><sensor type="imu" name="imu"/></gazebo>
</robot>
''')
    return f


@pytest.mark.parametrize("flag, preserved", [("true", True), ("yes", True), ("1", True), ("on", False),
                                             ("false", False)])
def test_check_and_convert_agree_on_preserve_fixed_joint(tmp_path, flag, preserved):
    """S004 (check) and --lump (convert) read the flag from one place (model/gazebo.preserved_joints)."""
    f = _sensor_on_fixed_massless_link(tmp_path, flag)
    robot = load_robot(f)
    assert robot.gazebo[0].values["preserveFixedJoint"] is preserved
    assert (preserved_joints(robot) == {"imu_joint"}) is preserved
    r = invoke("check", f, "--select", "S004", "--format", "json")
    (s004,) = [d for fl in json.loads(r.stdout)["files"] for d in fl["diagnostics"]]
    assert (s004["severity"] == "error" and "lumping is off" in s004["message"]) is preserved
    r = invoke("convert", f, "--to", "sdf", "--lump", "-o", "-")
    assert r.exit_code == 0, r.output
    assert ('<joint name="imu_joint" type="fixed">' in r.stdout) is preserved
    assert ('<frame name="imu_joint"' in r.stdout) is not preserved
