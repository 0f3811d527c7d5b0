"""build_model(lean=True): Pinocchio is given the URDF cut to its joints and links' inertials
(model/pin_model.lean_urdf) and builds the Model the whole document gives, bit for bit."""

from __future__ import annotations

import numpy as np
import pytest

from helpers import corpus_model, corpus_robot, erd_models
from myrabot_desc.model.loader import load_robot, read_urdf_bytes
from myrabot_desc.model.pin_model import build_model, lean_urdf


def assert_same_model(a, b):
    assert (a.name, a.nq, a.nv, a.njoints, a.nframes) == (b.name, b.nq, b.nv, b.njoints, b.nframes)
    assert list(a.names) == list(b.names) and list(a.parents) == list(b.parents)
    assert [j.shortname() for j in a.joints] == [j.shortname() for j in b.joints]
    assert [j.idx_q for j in a.joints] == [j.idx_q for j in b.joints]
    for x, y in zip(a.inertias, b.inertias):
        assert x.mass == y.mass and np.array_equal(x.lever, y.lever) and np.array_equal(x.inertia, y.inertia)
    for x, y in zip(a.jointPlacements, b.jointPlacements):
        assert np.array_equal(x.homogeneous, y.homogeneous)
    for x, y in zip(a.frames, b.frames):
        assert (x.name, x.parentJoint, x.parentFrame, x.type) == (y.name, y.parentJoint, y.parentFrame, y.type)
        assert np.array_equal(x.placement.homogeneous, y.placement.homogeneous)
        assert x.inertia == y.inertia
    for field in ("lowerPositionLimit", "upperPositionLimit", "velocityLimit", "effortLimit", "damping",
                  "friction", "rotorInertia", "armature"):
        assert np.array_equal(getattr(a, field), getattr(b, field)), field
    assert a == b                   # Pinocchio's own comparison: every member, exactly


def _robots():
    yield "bundled", load_robot(None)
    for rid in ("panda", "pr2", "tiago", "husky", "turtlebot3_waffle_pi", "ur5e"):
        yield rid, corpus_model(corpus_robot(rid))


@pytest.mark.parametrize("floating", [False, True])
def test_the_lean_urdf_gives_the_whole_documents_model(floating):
    """The bundled robot and corpus robots built from xacro, with Gazebo blocks, transmissions,
    visuals and collisions (what the cut leaves out), some with comments inside links and joints."""
    seen = 0
    for rid, robot in _robots():
        lean = lean_urdf(robot)
        assert lean is not None and len(lean) < 0.8 * len(robot.urdf_text), rid
        assert "<visual" not in lean and "<collision" not in lean and "<gazebo" not in lean, rid
        whole = build_model(robot, floating=floating)
        assert_same_model(build_model(robot, floating=floating, lean=True), whole)
        seen += whole.nq > 6
    assert seen >= 4


def test_the_lean_urdf_of_urdf_files():
    """example-robot-data's URDF files, read from the file (not built): the same Model."""
    n = 0
    for name, robot in erd_models():
        try:
            whole = build_model(robot)
        except Exception:               # what Pinocchio refuses is not compared
            continue
        assert_same_model(build_model(robot, lean=True), whole)
        n += 1
    assert n >= 10


def test_the_cut_of_an_awkward_document(tmp_path):
    """Comments and CDATA holding end tags, a link whose last child is a visual, an inertial after a
    collision, an empty and a self-closed link, a comment after the root: the cut keeps each joint
    and inertial whole and the Model is the whole document's; a document read by lxml is given whole."""
    text = """<?xml version="1.0"?>
<!-- before -->
<robot name="awk" xmlns:x="urn:x">
  <material name="m"><color rgba="1 0 0 1"/></material>
  <link name="a"/>
  <link name="b"><!-- </link> --><visual><geometry><box size="1 1 1"/></geometry></visual>
    <collision><geometry><sphere radius="0.1"/></geometry></collision>
    <inertial><mass value="2.5"/><origin xyz="0.1 0 0" rpy="0 0.3 0"/>
      <inertia ixx="0.1" ixy="0.01" ixz="0" iyy="0.2" iyz="0" izz="0.3"/></inertial>
    <visual><geometry><mesh filename="x.stl"/></geometry><!-- </visual></link> --></visual>
  </link>
  <x:thing><link name="not_a_link"/></x:thing>
  <joint name="j1" type="revolute"><!-- <joint name="fake"> -->
    <parent link="a"/><child link="b"/><origin xyz="0 0 1" rpy="0.1 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-1.5" upper="1.5" effort="10" velocity="2"/><dynamics damping="0.5" friction="0.25"/>
  </joint>
  <gazebo reference="b"><![CDATA[</link></robot>]]></gazebo>
  <link name="c"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <joint name="j2" type="prismatic"><parent link="b"/><child link="c"/>
    <limit lower="0" upper="0.5" effort="1" velocity="1"/></joint>
  <link name="d"></link>
  <joint name="j3" type="fixed"><parent link="c"/><child link="d"/></joint>
</robot>
<!-- after -->
"""
    f = tmp_path / "awk.urdf"
    f.write_text(text)
    robot = read_urdf_bytes(f.read_bytes(), f)
    lean = lean_urdf(robot)
    assert lean == (
        '<robot name="awk" xmlns:x="urn:x">\n  <link name="a"/>\n  <link name="b"><inertial><mass value="2.5"/>'
        '<origin xyz="0.1 0 0" rpy="0 0.3 0"/>\n      '
        '<inertia ixx="0.1" ixy="0.01" ixz="0" iyy="0.2" iyz="0" izz="0.3"/>'
        '</inertial>\n    </link><joint name="j1" type="revolute"><!-- <joint name="fake"> -->\n    '
        '<parent link="a"/><child link="b"/><origin xyz="0 0 1" rpy="0.1 0 0"/><axis xyz="0 1 0"/>\n    '
        '<limit lower="-1.5" upper="1.5" effort="10" velocity="2"/><dynamics damping="0.5" friction="0.25"/>\n  '
        '</joint>\n  <link name="c"><inertial>'
        '<mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link><joint name="j2" '
        'type="prismatic"><parent link="b"/><child link="c"/>\n    '
        '<limit lower="0" upper="0.5" effort="1" velocity="1"/>'
        '</joint>\n  <link name="d"></link>\n  <joint name="j3" type="fixed"><parent link="c"/><child link="d"/>'
        '</joint>'
        '\n</robot>')
    model = build_model(robot, lean=True)
    assert model.nq == 2 and list(model.names) == ["universe", "j1", "j2"]
    assert_same_model(model, build_model(robot))
    # past LEAN_READ_BYTES the loader reads with lxml, whose elements do not say where they start
    f.write_text(text.replace("<!-- after -->", f"<!-- {'x' * 600_000} -->"))
    big = read_urdf_bytes(f.read_bytes(), f)
    assert lean_urdf(big) is None
    assert_same_model(build_model(big, lean=True), model)
