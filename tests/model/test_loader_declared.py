"""Robot.declared: what the reader hands over (the elements, names and <child> links it read) is what
a pass over the XML gives, duplicates, nameless and malformed elements included."""

from __future__ import annotations

from helpers import FIXTURES
from myrabot_desc.model.loader import LEAN_READ_BYTES, load_robot

ODD = """<?xml version="1.0"?>
<robot name="odd" xmlns:x="urn:x">
  <!-- a comment --><link name="a"/><link name="a"/><link/><link name=""/>
  <x:link name="namespaced"/><Link name="capital"/>
  <joint name="j1" type="fixed"><parent link="a"/><!-- c --><child link="b"/><child link="c"/></joint>
  <joint name="j1" type="fixed"><parent link="a"/><child link="d"/></joint>
  <joint type="fixed"><parent link="a"/><child link="e"/></joint>
  <joint name="j3" type="fixed"><parent link="a"/></joint>
  <joint name="j4" type="fixed"><parent link="a"/><child/></joint>
  <joint name="" type="fixed"><child link="f"/></joint>
  <gazebo><joint name="inside"/></gazebo>
  <material name="m"/><material name="m"/><material/><x:material name="namespaced"/>
</robot>
"""


def _as_read(robot, tag):
    return [(d.tag, d.name, d.child, d.ref) for d in robot.declared(tag)]


def _as_written(robot, tag):
    robot.derived.pop(("declared", tag), None)          # Robot.declared's own pass over the XML
    return _as_read(robot, tag)


def test_declared_from_the_reader_is_the_xml(tmp_path):
    odd = tmp_path / "odd.urdf"
    odd.write_text(ODD)
    big = tmp_path / "big.urdf"          # past LEAN_READ_BYTES: read by lxml, not xmltree
    pad = "".join(f'<link name="pad{k}"/><material name="pad{k}"/>\n' for k in range(LEAN_READ_BYTES // 40))
    big.write_text(ODD.replace("</robot>", pad + "</robot>"))
    assert big.stat().st_size > LEAN_READ_BYTES
    seed = FIXTURES / "seed_myrabot"
    for src in (odd, big, None, seed / "myrabot_fer_modelo" / "urdf" / "myrabot.urdf.xacro"):
        robot = load_robot(src, package_paths=[seed])
        for tag in ("link", "joint", "material"):
            read = _as_read(robot, tag)
            assert read == _as_written(robot, tag), (src, tag)
    robot = load_robot(odd)
    assert [d[1:3] for d in _as_read(robot, "joint")] == [("j1", "b"), ("j1", "d"), (None, "e"), ("j3", None),
                                                          ("j4", None), ("", "f")]
    assert [d[1] for d in _as_read(robot, "link")] == ["a", "a", None, ""]
    assert [d[1] for d in _as_read(robot, "material")] == ["m", "m", None]
