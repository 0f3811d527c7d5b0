"""The conversion report (`convert --report FILE`): every element of the source with its fate
in the target, pinned on small real robots against what `ign sdf -p` and MuJoCo's own URDF
compiler keep and drop on the same files; and the refusal of models that cannot be converted."""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import pytest
from click.testing import CliRunner
from lxml import etree

from helpers import TESTS
from myrabot_desc.commands.main import main
from myrabot_desc.convert.report import Report
from myrabot_desc.convert.sdf import SdfOptions, to_sdf
from myrabot_desc.model.loader import load_robot

HERE = TESTS
GRIPPER = HERE / "fixtures" / "convert" / "gazebo_joints.urdf"
BAD = HERE / "bad"
IGN = shutil.which("ign") is not None
needs_ign = pytest.mark.skipif(not IGN, reason="`ign sdf` not installed")


def ign_print(path: Path):
    p = subprocess.run(["ign", "sdf", "-p", str(path)], capture_output=True, text=True, timeout=60)
    assert p.returncode == 0, p.stderr
    return etree.fromstring(p.stdout.encode(), etree.XMLParser(recover=True))


def fates(report: Report, kind: str) -> dict[str, str]:
    return {e.name: e.fate for e in report.entries if e.kind == kind}


@needs_ign
def test_gazebo_block_joints_kept_like_ign(tmp_path):
    """A parallel linkage's closing joint and a screw joint declared in <gazebo>: ign keeps them,
    so do we (they used to vanish silently); ign lumps the fixed 'nut' link away, we keep it."""
    theirs = ign_print(GRIPPER)
    their_joints = {e.get("name"): e.get("type") for e in theirs.iter("joint")}
    assert their_joints == {"a_joint": "revolute", "b_joint": "revolute", "coupler_joint": "revolute",
                            "coupler_to_b": "revolute", "lead_screw": "screw"}
    out = tmp_path / "g.sdf"
    r = CliRunner().invoke(main, ["convert", str(GRIPPER), "-o", str(out), "--report", str(tmp_path / "r.json")])
    assert r.exit_code == 0, r.output
    ours = etree.parse(str(out)).getroot()
    our_joints = {e.get("name"): e.get("type") for e in ours.iter("joint")}
    assert their_joints.items() <= our_joints.items() and our_joints["nut_joint"] == "fixed"
    assert ours.findtext(".//joint[@name='lead_screw']/thread_pitch") == "0.002"
    assert {e.get("name") for e in theirs.iter("link")} == {"base", "finger_a", "finger_b", "coupler"}
    assert {e.get("name") for e in ours.iter("link")} == {"base", "finger_a", "finger_b", "coupler", "nut"}
    p = subprocess.run(["ign", "sdf", "-k", str(out)], capture_output=True, text=True)
    assert p.returncode == 0 and "Valid" in p.stdout
    rep = json.loads((tmp_path / "r.json").read_text())
    got = {(e["kind"], e["name"]): (e["fate"], e["loc"]) for e in rep["elements"]}
    assert got[("gazebo-joint", "coupler_to_b")] == ("kept", f"{GRIPPER}:14")
    assert got[("gazebo-joint", "lead_screw")] == ("kept", f"{GRIPPER}:20")
    assert rep["counts"] == {"kept": 17, "translated": 0, "approximated": 0, "dropped": 0}
    assert "sdf: 17 source elements: 17 kept, 0 translated, 0 approximated, 0 dropped" in r.output
    # lumped like ign: 'nut' becomes a frame, the gazebo joints still attach (SDF 1.9 joints may name frames)
    text, res = to_sdf(load_robot(str(GRIPPER)), SdfOptions(lump=True), report=(rep2 := Report("sdf")))
    assert fates(rep2, "link")["nut"] == "translated" and "lead_screw" in res.joints


def test_gazebo_block_joints_in_mjcf_are_reported_dropped(tmp_path):
    """MuJoCo's URDF reader sees no <gazebo> block: the closing and screw joints are listed as dropped."""
    pytest.importorskip("mujoco")
    rep_path = tmp_path / "r.txt"
    r = CliRunner().invoke(main, ["convert", str(GRIPPER), "--to", "mjcf", "-o", str(tmp_path / "m" / "g.xml"),
                                  "--report", str(rep_path)])
    assert r.exit_code == 0, r.output
    text = rep_path.read_text()
    assert f"{GRIPPER}:14: gazebo-joint 'coupler_to_b': dropped: declared in a <gazebo> block" in text
    assert f"{GRIPPER}:12: joint 'nut_joint': translated: fixed joint: 'nut' fused into its parent body" in text
    assert text.splitlines()[0] == ("mjcf: 17 source elements: 12 kept, 3 translated, 0 approximated, "
                                    "2 dropped (2 gazebo-joints)")


def test_mjcf_report_against_mujocos_own_urdf_compiler(tmp_path):
    """MuJoCo's own compiler on the same URDF: it keeps the 3 URDF hinges, fuses 'nut', discards the
    visuals by default and silently ignores the <gazebo> joints; our report names each of those."""
    mujoco = pytest.importorskip("mujoco")
    text = GRIPPER.read_text().replace("<robot name=\"gripper\">",
                                       "<robot name=\"gripper\"><mujoco><compiler discardvisual=\"false\"/></mujoco>")
    m = mujoco.MjModel.from_xml_string(text)
    theirs = {m.joint(i).name for i in range(m.njnt)}
    assert theirs == {"a_joint", "b_joint", "coupler_joint"}
    assert {m.body(i).name for i in range(m.nbody)} == {"world", "finger_a", "finger_b", "coupler"}
    from myrabot_desc.convert.mjcf import convert_mjcf

    res = convert_mjcf(load_robot(str(GRIPPER)), str(tmp_path / "o" / "g.xml"))
    rep = res.report
    joints = fates(rep, "joint")
    assert {n for n, f in joints.items() if f != "dropped"} >= theirs
    assert joints["nut_joint"] == "translated" and fates(rep, "link")["nut"] == "translated"
    assert fates(rep, "link")["base"] == "translated"              # welded to the world (what MuJoCo does)
    assert fates(rep, "gazebo-joint") == {"coupler_to_b": "dropped", "lead_screw": "dropped"}
    ours = mujoco.MjModel.from_xml_path(str(tmp_path / "o" / "g.xml"))
    assert {ours.joint(i).name for i in range(ours.njnt)} == theirs
    assert ours.nu == 3                                             # MuJoCo alone writes no actuator


@needs_ign
def test_bundled_report_against_ign(tmp_path):
    """MYRAbot: ign lumps 68 of 76 links and drops the Electric sensors; the report says every link
    is kept (fixed joints kept), and lists the 8 plugins with no gz-sim equivalent as dropped."""
    robot = load_robot(None)
    urdf = tmp_path / "myrabot.urdf"
    urdf.write_text(robot.urdf_text)
    theirs = ign_print(urdf)
    assert len({e.get("name") for e in theirs.iter("link")}) == 8
    rep = Report("sdf")
    to_sdf(robot, report=rep)
    links = fates(rep, "link")
    assert len(links) == 76 and set(links.values()) == {"kept"}
    assert set(fates(rep, "sensor").values()) == {"translated"} and len(fates(rep, "sensor")) >= 10
    dropped = {e.name for e in rep.entries if e.fate == "dropped"}
    assert len(dropped) == 8 and all(rep.get("plugin", n) for n in dropped)
    assert fates(rep, "joint")["left_wheel_joint"] == "translated"      # continuous -> revolute
    assert rep.counts()["dropped"] == 8


# ------------------------------------------------------------------ refusals
@pytest.mark.parametrize("rel,expect", [
    ("tree/cycle.urdf", "link 'a' is the child of 2 joints ('j1', 'j3'): not a tree"),
    ("numbers/mass_text.urdf", "not a number"),
    ("meshes/garbage_dae.urdf", "garbage.dae is not readable COLLADA"),
    ("meshes/empty_stl.urdf", "empty.stl is empty (0 bytes)"),
    ("meshes/truncated_stl.urdf", "is not a binary STL"),
])
@pytest.mark.parametrize("target", ["sdf", "mjcf"])
def test_refused_with_reasons_nothing_written_unless_allowed(tmp_path, rel, expect, target):
    src = BAD / rel
    out = tmp_path / "o" / ("r.sdf" if target == "sdf" else "r.xml")
    r = CliRunner().invoke(main, ["convert", str(src), "--to", target, "-o", str(out)])
    assert r.exit_code == 2, r.output
    assert r.output.startswith(f"{src}:") and ": error: " in r.output.splitlines()[0] and expect in r.output
    assert not (tmp_path / "o").exists()
    if target == "mjcf":
        pytest.importorskip("mujoco")
    rep = tmp_path / "rep.json"
    r = CliRunner().invoke(main, ["convert", str(src), "--to", target, "-o", str(out), "--allow-errors",
                                  "--report", str(rep)])
    assert r.exit_code == 0, r.output
    assert out.exists()
    elements = json.loads(rep.read_text())["elements"]
    errors = [e for e in elements if e["kind"] == "error"]
    assert errors and all(e["fate"] == "dropped" and e["loc"].startswith(str(src)) for e in errors)
    assert any(expect in e["name"] for e in errors)


def test_several_roots_refused_with_each_reason(tmp_path):
    urdf = tmp_path / "two.urdf"
    urdf.write_text("""<robot name="two">
  <link name="a"/>
  <link name="b"/>
  <link name="c"><collision><geometry><mesh filename="nope.stl"/></geometry></collision></link>
  <joint name="j" type="fixed"><parent link="a"/><child link="c"/></joint>
  <joint name="k" type="fixed"><parent link="b"/><child link="c"/></joint>
</robot>""")
    r = CliRunner().invoke(main, ["convert", str(urdf), "-o", str(tmp_path / "x.sdf")])
    assert r.exit_code == 2
    lines = r.output.strip().splitlines()
    assert lines == [
        f"{urdf}:6: error: link 'c' is the child of 2 joints ('j', 'k'): not a tree",
        f"{urdf}:1: error: the model has 2 root links ('a', 'b'): a URDF is one tree",
        f"{urdf}:4: error: collision mesh nope.stl of link 'c': cannot be found",
    ]
    assert not (tmp_path / "x.sdf").exists()
