"""Our SDF keeps what sdformat's own URDF converter keeps (issue 25), over sdformat's 23 URDF test
fixtures (tests/fixtures/sdformat_urdf, source, revision and licence in its README), each with the
SDF `ign sdf -p` made of it (`NAME.ref.sdf`).

Compared per document (the two converters lump fixed joints differently, so per link would compare
different links): the names of the lights and projectors, the wind flags, the velocity decays
(linear, angular) and the collisions' contact min_depth."""

from __future__ import annotations

import math
import shutil
import subprocess
from pathlib import Path

import pytest
from lxml import etree

from helpers import FIXTURES
from myrabot_desc.convert.report import Report
from myrabot_desc.convert.sdf import to_sdf
from myrabot_desc.model.loader import load_robot

HERE = FIXTURES / "sdformat_urdf"
URDFS = sorted(HERE.rglob("*.urdf"))
IGN = shutil.which("ign") is not None


def _facts(root) -> dict:
    def decay(e):
        return tuple(float(e.findtext(k)) if e.findtext(k) is not None else math.nan for k in ("linear", "angular"))

    return {
        "light": sorted(e.get("name") for e in root.iter("light")),
        "projector": sorted(e.get("name") for e in root.iter("projector")),
        "enable_wind": sorted(e.text.strip() in ("1", "true") for e in root.iter("enable_wind")),
        "velocity_decay": sorted(decay(e) for e in root.iter("velocity_decay")),
        "min_depth": sorted(float(e.text) for e in root.iter("min_depth")),
    }


def _ref(urdf: Path):
    # one reference holds a plugin element named ignition::corrected_offsets, which lxml refuses
    # as a tag: recover mode reads the rest
    return etree.parse(str(urdf.with_name(urdf.name[:-5] + ".ref.sdf")), etree.XMLParser(recover=True)).getroot()


def test_the_fixtures_are_all_here():
    assert len(URDFS) == 23
    assert all(u.with_name(u.name[:-5] + ".ref.sdf").is_file() for u in URDFS)


@pytest.mark.parametrize("urdf", URDFS, ids=lambda p: p.stem)
def test_sdf_keeps_what_ign_keeps(urdf, tmp_path):
    text, _ = to_sdf(load_robot(str(urdf)))
    ours = etree.fromstring(text.encode())
    assert _facts(ours) == _facts(_ref(urdf))
    if IGN:
        out = tmp_path / "out.sdf"
        out.write_text(text)
        p = subprocess.run(["ign", "sdf", "-k", str(out)], capture_output=True, text=True, timeout=120)
        assert p.returncode == 0, p.stdout[-1500:] + p.stderr[-1500:]


def test_gazebo_extensions_in_numbers_and_each_light_named_in_the_report():
    """urdf_gazebo_extensions.urdf: 6 lights and 6 projectors, link1's <velocity_decay> block
    (0.1, 0.2), link2's dampingFactor 0.1 as both halves, enable_wind 1 and 0."""
    urdf = HERE / "integration" / "urdf_gazebo_extensions.urdf"
    rep = Report("sdf")
    text, _ = to_sdf(load_robot(str(urdf)), report=rep)
    root = etree.fromstring(text.encode())
    links = {el.get("name"): el for el in root.iter("link")}
    assert links["link1"].findtext("enable_wind") == "true" and links["link2"].findtext("enable_wind") == "false"
    assert [links["link1"].findtext(f"velocity_decay/{k}") for k in ("linear", "angular")] == ["0.1", "0.2"]
    assert [links["link2"].findtext(f"velocity_decay/{k}") for k in ("linear", "angular")] == ["0.1", "0.1"]
    # a light's pose is kept in the frame it names; one without relative_to is in its link's frame
    rel = next(e for e in root.iter("light") if e.get("name") == "lightPoseRelative")
    assert rel.find("pose").get("relative_to") == "link0" and rel.getparent().get("name") == "linkSensorPoseRelative"
    named = sorted(e.name for e in rep.entries if e.kind == "gazebo" and ("/light" in e.name or "/projector" in e.name))
    assert len(named) == 12 and "linkSensorNoPose/light 'lightNoPose'" in named
    assert not [e for e in rep.entries if e.kind == "gazebo" and e.fate == "dropped"]


def test_min_depth_survives_an_empty_injected_ode():
    """fixed_joint_reduction_collision_visual_extension.urdf: <minDepth>0.007 and an injected
    <collision><surface><contact><ode/> in the same block; the empty <ode/> used to replace the
    one holding min_depth."""
    urdf = HERE / "integration" / "fixed_joint_reduction_collision_visual_extension.urdf"
    root = etree.fromstring(to_sdf(load_robot(str(urdf)))[0].encode())
    assert [e.text for e in root.iter("min_depth")] == ["0.007"]
    assert sorted(e.text for e in root.iter("max_contacts")) == ["166", "177"]
