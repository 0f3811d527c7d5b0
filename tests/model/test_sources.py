"""Where every value was written: Robot.sources / Robot.origin read the span back from the file.

For every value of the built URDF of the bundled robot, the seed files, wander_bot and every corpus
robot, the recorded span holds the text that produced it: a literal (in the element, a property's
definition, a macro call or a parameter default) equal to the value, or an expression (computed),
or an arg given on the command line. Nothing is 'unknown'.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest
import yaml

from myrabot_desc.model import drive as D
from myrabot_desc.model.loader import load_robot

ROOT = Path(__file__).resolve().parents[2]
FIX = ROOT / "tests" / "fixtures"
CORPUS = ROOT / "tests" / "corpus"
SEED = FIX / "seed_myrabot"


def _same(written: str, value: str) -> bool:
    """The literal and the value xacro wrote from it (xacro reads property and parameter literals as
    Python numbers and booleans: '.260' -> 0.26, 'false' -> False)."""
    a, b = written.strip(), value.strip()
    if a == b:
        return True
    if a.lower() in ("true", "false") and b in ("True", "False"):
        return a.lower() == b.lower()
    try:
        return [float(x) for x in a.split()] == [float(x) for x in b.split()]
    except ValueError:
        return False


def values(robot):
    """(element, attribute or '#text', value) for every value of the URDF."""
    for el in robot.root_element.iter():
        if not isinstance(el.tag, str):
            continue
        for k, v in el.attrib.items():
            yield el, k, v
        t = (el.text or "").strip()
        if t and len(el) == 0:
            yield el, "#text", t


def audit(robot) -> dict:
    kinds: dict[str, int] = {}
    wrong = []
    for el, attr, value in values(robot):
        o = robot.sources.origin(el, attr)
        kinds[o.kind] = kinds.get(o.kind, 0) + 1
        if o.kind == "unknown":
            wrong.append((el.tag, attr, value, "unknown"))
        elif o.written is not None:
            # the literal's own file says so: read it back from disk, not from the build's copy
            data = o.written.path.read_bytes()[o.written.start:o.written.end].decode()
            if data != o.written.text or not _same(o.written.value, value):
                wrong.append((el.tag, attr, value, str(o.written), o.written.text))
        elif o.expr is not None:
            if "$" not in o.expr.text:
                wrong.append((el.tag, attr, value, "expr without $", str(o.expr)))
        elif not o.from_command_line:
            wrong.append((el.tag, attr, value, o.kind, "no span"))
        if o.at is not None and o.kind != "literal" and "$" not in o.at.text:
            wrong.append((el.tag, attr, value, "use without $", str(o.at)))
    return {"kinds": kinds, "wrong": wrong}


def _corpus_robots():
    return yaml.safe_load((CORPUS / "robots.yaml").read_text())["robots"]


def _load_corpus(r):
    args = dict(a.split(":=", 1) for a in r.get("args", "").split())
    saved = dict(os.environ)
    os.environ.update({k: str(v) for k, v in r.get("env", {}).items()})
    try:
        return load_robot(CORPUS / r["top"], mappings=args, package_paths=[CORPUS / r.get("package_path", ".")],
                          legacy="off" if r.get("legacy") else "auto")
    finally:
        os.environ.clear()
        os.environ.update(saved)


def test_bundled_robot_every_value_has_its_span():
    a = audit(load_robot(None))
    assert a["wrong"] == []
    assert set(a["kinds"]) == {"literal", "expr", "property", "param", "default"}
    assert a["kinds"]["literal"] > 1000 and a["kinds"]["param"] > 300


@pytest.mark.parametrize("top", ["wander_bot/urdf/robot.xacro",
                                 "seed_myrabot/brazo_fer_modelo/urdf/brazo.xacro"])
def test_fixture_values_have_their_spans(top):
    a = audit(load_robot(FIX / top, package_paths=[SEED]))
    assert a["wrong"] == [] and set(a["kinds"]) == {"literal"}


def test_seed_assembly_values_have_their_spans():
    a = audit(load_robot(SEED / "myrabot_fer_modelo" / "urdf" / "myrabot.urdf.xacro", package_paths=[SEED]))
    assert a["wrong"] == []


@pytest.mark.corpus
@pytest.mark.parametrize("robot", _corpus_robots(), ids=lambda r: r["id"])
def test_corpus_values_have_their_spans(robot):
    a = audit(_load_corpus(robot))
    assert a["wrong"] == []


def test_wander_bot_plugin_parameter_is_a_literal_at_its_column():
    robot = load_robot(FIX / "wander_bot" / "urdf" / "robot.xacro")
    plugin = next(p for p in robot.plugins() if "wheelSeparation" in p.params)
    o = robot.origin(plugin, "wheelSeparation")
    assert (o.kind, o.written.file.endswith("robot.gazebo"), o.written.line, o.written.col, o.written.text) == \
        ("literal", True, 12, 24, "0.4")


def test_bundled_robot_property_parameter_and_expression():
    robot = load_robot(None)
    base = robot.links["base_link"]
    mass = robot.origin(base.inertial, "mass")
    assert mass.kind == "literal" and mass.written.text == "3.6" and mass.written.file == "xacro/roomba.xacro"
    ixx = robot.origin(base.inertial, "ixx")          # ${i_side}, a property computed from the mass
    assert (ixx.kind, ixx.name, ixx.computed, ixx.expr.file) == ("property", "i_side", True, "xacro/inertia.xacro")
    assert ixx.expr.text.startswith("${") and ixx.at.text == "${i_side}"
    wall = robot.origin(robot.joints["base_wall_sensor_joint"], "origin.xyz")   # a macro parameter at the call
    assert wall.kind == "param" and wall.name == "xyz" and wall.written.line == 116
    assert wall.at.file == "xacro/roomba.xacro" and wall.at.text == "${xyz}"


def test_property_used_in_several_places_points_to_its_one_definition():
    # jackal: the wheel radius property defines every wheel's collision cylinder
    robot = _load_corpus(next(r for r in _corpus_robots() if r["id"] == "jackal"))
    wheels = [lk for n, lk in robot.links.items() if "wheel" in n and lk.collisions]
    origins = {robot.origin(w.collisions[0], "geometry.radius") for w in wheels}
    assert len(wheels) == 4 and len(origins) == 1
    (o,) = origins
    assert o.kind == "property" and o.written is not None and float(o.written.value) == wheels[0].collisions[0].geometry.radius


def test_arg_from_the_command_line_has_no_span(tmp_path):
    f = tmp_path / "r.urdf.xacro"
    f.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                 '  <xacro:arg name="m" default="1.5"/>\n'
                 '  <link name="a"><inertial><mass value="$(arg m)"/>'
                 '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>\n</robot>\n')
    default = load_robot(f)
    o = default.origin(default.links["a"].inertial, "mass")
    assert (o.kind, o.name, o.written.line, o.written.text) == ("arg", "m", 2, "1.5")
    given = load_robot(f, mappings={"m": "3"})
    o = given.origin(given.links["a"].inertial, "mass")
    assert (o.kind, o.from_command_line, o.written) == ("arg", True, None)


def test_plain_urdf_spans_with_many_elements_on_a_line_crlf_quotes_and_entities(tmp_path):
    f = tmp_path / "r.urdf"
    f.write_bytes(b'<?xml version="1.0"?>\r\n<robot name="r">\r\n'
                  b'  <link name="a"><visual><origin xyz="0 0 1"/><geometry><box size=\'1 2 3\'/></geometry></visual>'
                  b'<visual name="x &amp; y"><origin xyz="0 0 2"/><geometry><sphere radius="0.5"/></geometry></visual>'
                  b'</link>\r\n  <link\r\n     name="b"/>\r\n'
                  b'  <joint name="j" type="fixed"><parent link="a"/><child link="b"/><origin xyz="1 2 3"/></joint>\r\n'
                  b'</robot>\r\n')
    robot = load_robot(f)
    a = robot.links["a"]
    second = robot.origin(a.visuals[1], "origin.xyz")
    assert (second.kind, second.written.line, second.written.text) == ("literal", 3, "0 0 2")
    box = robot.origin(a.visuals[0], "geometry.size")
    assert box.written.text == "1 2 3" and f.read_bytes()[box.written.start - 1:box.written.start] == b"'"
    assert robot.origin(a.visuals[1], "name").written.value == "x & y"
    b = robot.origin(robot.links["b"], "name")
    assert (b.written.line, b.written.col) == (5, 12)
    j = robot.origin(robot.joints["j"], "origin.xyz")
    assert (j.written.line, j.written.text) == (6, "1 2 3")
    assert audit(robot)["wrong"] == []


def _check_typed_origin(robot, part, name, value, wrong):
    o = robot.origin(part, name)
    if o.kind == "unknown":
        wrong.append((type(part).__name__, name, value, "unknown"))
    elif o.written is not None and not _same(o.written.value, value):
        wrong.append((type(part).__name__, name, value, str(o.written), o.written.text))


def typed_audit(robot) -> list:
    """Robot.origin of every typed part beyond links and joints (plugins and their parameters,
    <gazebo> properties, sensors, transmissions, ros2_control blocks): a span holding the value."""
    wrong: list = []
    for g in robot.gazebo:
        if g.reference is not None:
            _check_typed_origin(robot, g, "reference", g.reference, wrong)
        for key, text in g.properties.items():
            if text:
                _check_typed_origin(robot, g, key, text, wrong)
    for p in robot.plugins():
        for key, text in p.params.items():
            if text:
                _check_typed_origin(robot, p, key, text, wrong)
    for s in robot.sensors():
        if s.name:
            _check_typed_origin(robot, s, "name", s.name, wrong)
    for t in robot.transmissions:
        for j in t.named:
            _check_typed_origin(robot, j, "name", j.name, wrong)
    for b in robot.ros2_control:
        for j in b.joints:
            _check_typed_origin(robot, j, "name", j.name, wrong)
    return wrong


def test_typed_parts_of_the_bundled_robot_and_wander_bot_have_their_spans():
    bundled = load_robot(None)
    assert typed_audit(bundled) == []
    assert typed_audit(load_robot(FIX / "wander_bot" / "urdf" / "robot.xacro")) == []
    # <mu1 value="10"/>: the span is the value attribute's (the element has no text)
    block = next(g for g in bundled.gazebo if g.reference == "left_wheel_link")
    o = bundled.origin(block, "mu1")
    assert (o.kind, o.at.text, o.at.file) == ("literal", "10", "xacro/roomba_gazebo.xacro")
    assert bundled.origin(block.node.child("mu1"), "@value") == o        # a node's attribute: the same span
    # an Electric controller's parameter, its typed number and the drive's unit for it
    (roomba,) = D.find(bundled)
    q = roomba.quantities()["wheel_separation"]
    assert (q.value, q.unit) == (0.26, "m")
    o = bundled.origin(roomba.plugin, "wheel_separation")
    assert o.written is not None and float(o.written.value) == 0.26


@pytest.mark.corpus
def test_ros2_plugin_nested_parameter_and_ros2_control_have_their_spans():
    pmb2 = _load_corpus(next(r for r in _corpus_robots() if r["id"] == "pmb2"))
    assert typed_audit(pmb2) == []
    laser = next(p for p in pmb2.plugins() if p.node.find("ros", "remapping") is not None)
    o = pmb2.origin(laser, "ros.remapping")                 # a dotted path of child elements
    assert o.kind != "unknown" and o.at.text.startswith("~/out:=")
    demo = load_robot(FIX / "convert" / "diffbot_ros2_control_demos.urdf")
    (block,) = demo.ros2_control
    assert [j.name for j in block.joints] == ["left_wheel_joint", "right_wheel_joint"]
    assert typed_audit(demo) == []
    o = demo.origin(block.joints[0], "name")
    assert (o.kind, o.at.text) == ("literal", "left_wheel_joint")
