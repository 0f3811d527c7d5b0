"""xmltree (the element tree check reads the build's output into, without lxml) reads every document
expat reads as lxml (safety.safe_parser) does: the same nodes in the same order, tags, prefixes,
attributes in order, text, tails, parents and lines; and refuses (for lxml to judge) whatever expat
stops at or might read otherwise: DTDs, entities, unbound prefixes, other encodings, libxml2's limits.
"""

from __future__ import annotations

import pytest
from lxml import etree

from helpers import ROOT
from myrabot_desc import xmltree
from myrabot_desc.safety import safe_parser


def _kind(n) -> str:
    if n.tag is etree.Comment or n.tag is xmltree.Comment:
        return "comment"
    if n.tag is etree.ProcessingInstruction or n.tag is xmltree.ProcessingInstruction:
        return "pi"
    return "element"


def _walk(root) -> list:
    """Every node of the document (the root's siblings too) as plain values."""
    nodes = list(reversed(list(root.itersiblings(preceding=True)))) + list(root.iter()) + list(root.itersiblings())
    out = []
    for n in nodes:
        kind = _kind(n)
        p = n.getparent()
        out.append((kind, n.tag if kind == "element" else None, n.text, n.tail, n.sourceline, len(n),
                    n.items() if kind == "element" else None, n.prefix if kind == "element" else None,
                    p.tag if p is not None else None, n.target if kind == "pi" else None))
    return out


def _same(data: bytes) -> None:
    ours = xmltree.parse(data)
    theirs = etree.fromstring(data, parser=safe_parser())
    assert _walk(ours) == _walk(theirs)
    assert ours.getroottree().docinfo.encoding == theirs.getroottree().docinfo.encoding


MODEL_FILES = sorted(p for folder in ("tests/corpus", "tests/bad", "xacro") for p in (ROOT / folder).rglob("*")
                     if p.suffix in (".xacro", ".urdf", ".xml", ".srdf", ".gazebo", ".sdf"))


def test_every_model_file_reads_as_lxml_reads_it_or_is_left_to_lxml():
    read = 0
    for path in MODEL_FILES:
        data = path.read_bytes()
        try:
            xmltree.parse(data)
        except xmltree.Refused:
            continue
        _same(data)
        read += 1
    assert read > 0.9 * len(MODEL_FILES) and len(MODEL_FILES) > 500, (read, len(MODEL_FILES))


@pytest.mark.parametrize("data", [
    # lines: libxml2 takes the line of the ">" ending a start tag, comment or instruction; it counts
    # no lone CR; a ">" may stand in a quoted value
    b'<?xml version="1.0"?>\n<!-- a\n b -->\n<r\n a="x>y"\n>\n<b c=\'1\'\n/>t&amp;<![CDATA[q]]>\n<?pi\n x?></r>\n',
    b'<?xml version="1.0"?>\r\n<!-- a\r\n b -->\r\n<r\r\n a="x>y"\r\n>\r\n<b c=\'1\'\r\n/>t<?p\r\n?></r>\r\n',
    b'<r\r a="1"\r><b/>\r</r>',
    # namespaces: Clark tags and attributes, the prefix as written, the default namespace, xml:
    b'<robot xmlns:s="http://s" xmlns="http://d"><s:a s:x="1" y="2" xml:lang="en"/><b xmlns=""/></robot>',
    # empty CDATA, comment and instruction; text around them
    b'<r><![CDATA[]]><!----><?p?>x<a/>y<!--c-->z</r>',
    # an encoding expat and libxml2 read alike
    '<?xml version="1.0" encoding="ISO-8859-1"?><r a="é">ü</r>'.encode("latin-1"),
    # past libxml2's 65,535 lines (it reads an element's line off its neighbours there)
    b"<r>\n" + b"<a x='1'\n/>text\n<b/>\n" * 22000 + b"</r>",
])
def test_reads_as_lxml(data):
    _same(data)


@pytest.mark.parametrize("data", [
    b'<!DOCTYPE r [<!ENTITY e "x">]><r>&e;</r>',
    b'<r>&undefined;</r>',
    b'<r><a:b/></r>',                                       # lxml reads an unbound prefix; expat stops
    '<?xml version="1.0" encoding="windows-1252"?><r a="é"/>'.encode("cp1252"),
    '<r/>'.encode("utf-16"),
    b"<a>" * 251 + b"</a>" * 251,                          # libxml2's depth limit is near
    b"<r " + b"x" * 50_001 + b'="1"/>',                   # libxml2's longest name
    b'<r xmlns:' + b"x" * 50_001 + b'="u"/>',
    b"<r><?" + b"x" * 50_001 + b" d?></r>",
    b"<r>" + b"x" * 10_000_001 + b"</r>",                  # libxml2's longest text
    b"<r><a></r>",
])
def test_leaves_to_lxml(data):
    with pytest.raises(xmltree.Refused):
        xmltree.parse(data)


def test_the_api_the_model_reads():
    root = xmltree.parse(b'<robot name="r"><link name="a"><visual/><!--c--><collision/></link>'
                         b'<ros/><x:ros xmlns:x="u"/><joint name="j"/><joint name="k"/></robot>')
    link = root[0]
    assert (root.get("name"), root.get("nope", "d"), list(root.keys()), root.items()) == \
        ("r", "d", ["name"], [("name", "r")])
    assert [c.tag for c in link] == ["visual", xmltree.Comment, "collision"] and len(link) == 3
    assert link.find("collision") is link[2] and link.find("inertial") is None
    assert [j.get("name") for j in root.findall("joint")] == [j.get("name") for j in root.iterchildren("joint")]
    assert [c.tag for c in root.iterchildren("{*}ros")] == ["ros", "{u}ros"]
    assert link[0].getparent() is link and root.getparent() is None
    assert root.getroottree().getroot() is root
    assert [n.tag for n in root.iter("visual", "collision")] == ["visual", "collision"]
    assert list(link.iter()) == [link, *link]
    assert link[0] != link[2] and link[0] == link[0] and len({link[0], link[2]}) == 2   # equal only to itself
    assert xmltree.attribute_values(root, "name") == ["r", "a", "j", "k"]


MESH_FILES = sorted((ROOT / "tests" / "corpus").rglob("*.dae")) + sorted((ROOT / "tests" / "bad").rglob("*.dae"))


def _primitive(tag, attrs) -> bool:
    return tag in ("triangles", "polylist", "polygons", "trifans", "tristrips") and attrs.get("count", "0") != "0"


def test_any_element_answers_as_the_tree_and_refuses_alike():
    """The scan without a tree (a COLLADA file's triangles for M005) reads what parse reads."""
    seen = 0
    for path in MODEL_FILES[::7] + MESH_FILES:
        data = path.read_bytes()
        try:
            root = xmltree.parse(data)
        except xmltree.Refused:
            with pytest.raises(xmltree.Refused):
                xmltree.any_element(data, _primitive)
            continue
        want = any(_primitive(n.tag.rsplit("}", 1)[-1], n.attrib) for n in root.iter() if isinstance(n.tag, str))
        assert xmltree.any_element(data, _primitive) == want, path
        seen += want
    assert seen > 20


def test_a_collada_files_verdict_is_lxmls():
    """meshes.unreadable (M005) with the scan gives the verdict of the lxml walk it replaces."""
    from myrabot_desc.errors import InputError
    from myrabot_desc.model import meshes
    from myrabot_desc.safety import parse_xml_bytes

    compared = refused = 0
    for path in MESH_FILES:
        got = meshes.unreadable(path)
        if got is not None and "is not readable COLLADA" not in got and "holds no triangles (no <" not in got:
            continue                      # refused before any XML is read (limits, compression, size)
        try:
            root = parse_xml_bytes(path.read_bytes(), path.name)
        except InputError as exc:
            assert got == f"{path.name} is not readable COLLADA: {exc.message}"
            refused += 1
            continue
        found = any(_primitive(el.tag.rsplit("}", 1)[-1], el.attrib) for el in root.iter() if isinstance(el.tag, str))
        assert (got is None) == found, path
        compared += 1
    assert compared > 100 and refused > 0, (compared, refused)
