"""The raw-XML rules: T005/T006's walk on hostile trees (namespaces, comments, free-form bodies,
misplaced elements) and on a wide dirty tree, T007's <ros> blocks (checks/urdf_syntax.py)."""

from __future__ import annotations

import pytest

from helpers import cpu_time
from myrabot_desc.checks.urdf_syntax import _problems
from myrabot_desc.model.loader import load_robot
from myrabot_desc.safety import parse_xml_bytes
from myrabot_desc.xmltree import parse_safely

XSI = 'xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"'
CLEAN_LINK = ('<link name="a"><inertial><origin xyz="0 0 0"/><mass value="1"/>'
              '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>'
              '<visual><geometry><mesh filename="m.stl" scale="1 1 1"/></geometry>'
              '<material name="m"><color rgba="1 0 0 1"/></material></visual></link>')

# (name, document, the walk finds something)
HOSTILE = [
    ("clean", f'<robot name="r">{CLEAN_LINK}</robot>', False),
    ("comments and PIs", f'<?pi a?><robot name="r"><!-- c --><?pi b?>{CLEAN_LINK}<!-- d --></robot>', False),
    ("text in known elements", '<robot name="r">text<link name="a">more<visual>x</visual></link></robot>', False),
    ("namespaced elements and attributes",
     '<robot name="r" xmlns:f="urn:f" f:a="1" xml:lang="en"><f:thing bogus="1"><bogus/></f:thing>'
     '<link name="a" f:b="2"><f:inner><nonsense/></f:inner></link></robot>', False),
    ("free-form bodies", '<robot name="r"><gazebo reference="a" any="1"><mu1>1</mu1><x y="z"><deep/></x></gazebo>'
     '<link name="a"><contact><lateral_friction value="1"/></contact></link>'
     '<transmission name="t"><joint name="j"/><bogus/></transmission></robot>', False),
    ("unknown attribute", '<robot name="r"><link name="a" mass="1"/></robot>', True),
    ("unknown attribute deep", '<robot name="r"><link name="a"><collision><geometry>'
     '<box size="1 1 1" rpy="0 0 1"/></geometry></collision></link></robot>', True),
    ("unknown element", '<robot name="r"><gaezebo reference="a"><link name="b" bad="1"/></gaezebo></robot>', True),
    ("unknown nested element", '<robot name="r"><link name="a"><visual><geometry><box size="1 1 1"><sub/></box>'
     '</geometry></visual></link></robot>', True),
    ("known element in the wrong place", '<robot name="r"><link name="a"><origin xyz="0 0 0"/></link></robot>', True),
    ("element of a free-form tag elsewhere", '<robot name="r"><joint name="j"><gazebo/></joint></robot>', True),
    ("attribute on the root", '<robot name="r" bogus="1"/>', True),
    ("namespaced root", '<x:robot xmlns:x="urn:x" name="r"><link name="a" bad="1"/></x:robot>', True),
    ("namespaced root, clean", '<x:robot xmlns:x="urn:x" name="r"><link name="a"/></x:robot>', False),
    ("default namespace", '<robot xmlns="urn:x" name="r"><link bad="1"/></robot>', False),
    ("other root", '<link name="a"><bogus/></link>', True),
    ("unknown root", '<sdf><bogus/></sdf>', False),
    ("xsi:type", f'<robot name="r" {XSI}><link name="a" xsi:type="t_gazebo"><bogus/></link></robot>', True),
    ("xsi:type, clean", f'<robot name="r" {XSI}><link name="a" xsi:type="t_link"/></robot>', False),
    ("xsi:schemaLocation", f'<robot name="r" {XSI} xsi:noNamespaceSchemaLocation="http://example.com/x.xsd">'
     '<link name="a" bad="1"/></robot>', True),
]


@pytest.mark.parametrize("name,doc,dirty", HOSTILE, ids=[h[0] for h in HOSTILE])
def test_hostile_trees(name, doc, dirty):
    assert bool(_problems(parse_xml_bytes(doc.encode(), name))) == dirty


def test_every_problem_at_every_depth_once():
    # leaves (origin, box, limit...) are judged in their parent's loop: their attributes, any child
    doc = ('<robot name="r" bad0="1" xmlns:f="urn:f"><link name="a" bad1="1"><visual bad2="1"><origin xyz="0 0 0" '
           'bad3="1" f:ok="1"><!-- c --><f:ok/><sub1/></origin><geometry><box size="1 1 1" bad4="1"><sub2><x/></sub2>'
           '</box></geometry><material name="m"><color rgba="1 0 0 1" bad5="1"/></material><bogus1/></visual></link>'
           '<joint name="j" type="fixed"><limit effort="1" bad6="1"/><bogus2><y/></bogus2><gazebo/></joint>'
           '<gazebo bad="1"><origin bad="1"/></gazebo></robot>')
    for root in (parse_xml_bytes(doc.encode(), "doc"), parse_safely(doc.encode(), "doc")):
        found = sorted((parent, problem) for _el, parent, problem in _problems(root))
        assert found == [("box", ("attribute", "bad4")), ("box", ("element", "sub2")),
                         ("color", ("attribute", "bad5")), ("joint", ("element", "bogus2")),
                         ("joint", ("element", "gazebo")), ("limit", ("attribute", "bad6")),
                         ("link", ("attribute", "bad1")),
                         ("origin", ("attribute", "bad3")), ("origin", ("element", "sub1")),
                         ("robot", ("attribute", "bad0")), ("visual", ("attribute", "bad2")),
                         ("visual", ("element", "bogus1"))]
        assert {el.tag for el, _p, (kind, _n) in _problems(root) if kind == "element"} == {
            "sub1", "sub2", "bogus1", "bogus2", "gazebo"}


def test_a_typo_in_every_link_of_a_star_stays_fast():
    # a shortcut that validates clean trees in C (an XML Schema made from SCHEMA) is no option: lxml's
    # cost of refusing a tree grows about as the cube of its errors, seconds here; the walk is linear
    n = 8_000
    inertial = ('<inertial><mass value="0.1"/><inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/>'
                '</inertial>')
    doc = '<robot name="star">\n' + "".join(
        f'<link name="l{i}">{inertial}<collision><geometry><box size="1 1 1" rpy="0 0 1"/></geometry></collision>'
        f'</link>\n<joint name="j{i}" type="revolute"><parent link="l0"/><child link="l{i}"/>'
        '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>\n' for i in range(1, n + 1)) + "</robot>\n"
    root = parse_xml_bytes(doc.encode(), "star")
    with cpu_time() as t:
        found = _problems(root)
    assert len(found) == n and t.seconds < 3


def test_ros_blocks_at_robot_level_in_any_namespace(tmp_path):
    from myrabot_desc.checks import CheckOptions, run_checks

    f = tmp_path / "r.urdf"
    f.write_text('<robot name="r" xmlns:f="urn:f"><link name="a"/><!-- <ros/> --><?ros x?>\n'
                 '<ros><namespace>/a</namespace></ros>\n<f:ros><argument>x</argument></f:ros>\n<rosx/>\n'
                 '<gazebo><ros><namespace>/inside</namespace></ros></gazebo></robot>')
    found = [d for d in run_checks(load_robot(f), CheckOptions()) if d.code == "T007"]
    assert [(d.loc.line, d.data["content"]) for d in found] == [(2, "<namespace>/a"), (3, "<argument>x")]
