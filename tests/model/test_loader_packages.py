"""The reader finds the packages a URDF names (package://) however the URI is written, and skips the
scan of every attribute only when none can name one."""

from __future__ import annotations

import pytest

from myrabot_desc.model.loader import _may_name_packages, load_robot
from myrabot_desc.safety import parse_xml_bytes

MESH = '<link name="a"><visual><geometry><mesh filename="{}"/></geometry></visual></link>'


@pytest.fixture
def pkgs(tmp_path):
    p = tmp_path / "pkgs" / "mypkg"
    p.mkdir(parents=True)
    (p / "package.xml").write_text("<package><name>mypkg</name></package>")
    return tmp_path / "pkgs"


@pytest.mark.parametrize("uri,decl", [
    ("package://mypkg/m.stl", ""),
    ("&#112;ackage://mypkg/m.stl", ""),                       # a character reference spells it
    ("package&#x3a;//mypkg/m.stl", ""),
    ("package://mypkg/m.stl", '<?xml version="1.0" encoding="ISO-8859-1"?>'),
])
def test_packages_are_found(tmp_path, pkgs, uri, decl):
    f = tmp_path / "r.urdf"
    f.write_bytes(f'{decl}<robot name="r">{MESH.format(uri)}</robot>'.encode("latin-1"))
    assert "mypkg" in load_robot(f, package_paths=[pkgs]).package_roots


def test_scan_skipped_only_without_a_possible_uri():
    def may(doc: str) -> bool:
        return _may_name_packages(parse_xml_bytes(doc.encode(), "x"), doc)
    assert not may(f'<robot name="r">{MESH.format("meshes/m.stl")}</robot>')
    assert may(f'<robot name="r">{MESH.format("package://p/m.stl")}</robot>')
    assert may('<robot name="r"><!-- package: in a comment --></robot>')
    assert may('<robot name="r&#32;x"/>')
    assert may('<?xml version="1.0" encoding="ISO-8859-1"?><robot name="r"/>')


@pytest.mark.parametrize("data", [b"", b" ", b"\n\t\r\x0b\x0c  \n"])
def test_blank_file_is_empty(data):
    from myrabot_desc.errors import InputError

    with pytest.raises(InputError, match="empty file"):
        parse_xml_bytes(data, "x")
