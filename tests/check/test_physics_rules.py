"""P005 (self-collision at the rest pose) and P006 (gravity torque against effort) through `check`, on real
robots and on planted defects: a hand collision moved into a non-adjacent link, an effort limit of
0.1 N·m on a shoulder that needs 52 N·m."""

from __future__ import annotations

import json
import re


from helpers import ERD, WANDER, corpus_args, corpus_robot, invoke, planted_panda, weak
from myrabot_desc.checks.registry import load_all

PANDA = ERD / "panda_description/urdf/panda.urdf"
PANDA_SRDF = ERD / "panda_description/srdf/panda.srdf"
PR2 = ERD / "pr2_description/urdf/pr2.urdf"


def _json(*args):
    r = invoke("check", "--format", "json", *args)
    assert r.exit_code in (0, 1), r.output[-2000:]
    return r.exit_code, [d for f in json.loads(r.stdout)["files"] for d in f["diagnostics"]]


def _codes(diags, code):
    return [d for d in diags if d["code"] == code]


# ------------------------------------------------------------------ P005
def test_franka_hand_and_fifth_link_overlap_41_mm():
    code, diags = _json("--inertia", "--select", "P005", PANDA)
    got = {tuple(d["data"]["links"]): (d["severity"], round(d["data"]["depth"] * 1000, 1)) for d in diags}
    assert got == {("panda_link5", "panda_hand"): ("warning", 41.4), ("panda_link5", "panda_link7"): ("warning", 5.7)}
    hand = next(d for d in diags if d["data"]["links"][1] == "panda_hand")
    assert hand["message"].startswith("panda_hand overlaps panda_link5 by 41.4 mm at the rest pose (mesh hand.stl "
                                      "into mesh link5.stl at ")
    assert "2 moving joints apart (panda_joint6, panda_joint7)" in hand["message"]
    assert hand["line"] and hand["data"]["other"].endswith(":134")          # both collisions' file:line
    assert code == 0                                                       # warnings: not an error without an SRDF


def test_corpus_franka_stand_ins_show_the_same_class():
    """The corpus' franka_description (box stand-ins of the real meshes' extents) with the hand: 63.0 mm,
    at the file:line of franka_description's collision macro."""
    code, diags = _json("--inertia", "--select", "P005", *corpus_args(corpus_robot("panda_gazebo_hand")))
    hand = next(d for d in diags if d["data"]["links"] == ["panda_link5", "panda_hand"])
    assert round(hand["data"]["depth"] * 1000, 1) == 63.0 and hand["severity"] == "warning"
    assert hand["file"].endswith("franka_description/robots/common/utils.xacro") and hand["line"]


def test_srdf_disables_the_designed_pairs_and_makes_the_rest_errors(tmp_path):
    code, diags = _json("--inertia", "--select", "P005", "--srdf", PANDA_SRDF, PANDA)
    assert diags == [] and code == 0                         # both are "Default" pairs of Franka's SRDF
    planted = planted_panda(tmp_path)
    code, diags = _json("--inertia", "--select", "P005", "--srdf", PANDA_SRDF, planted)
    assert code == 1
    assert [(d["severity"], d["data"]["links"], round(d["data"]["depth"] * 1000, 1)) for d in diags] == \
        [("error", ["panda_link2", "panda_link5"], 31.2)]
    assert "3 moving joints apart (panda_joint3, panda_joint4, panda_joint5)" in diags[0]["message"]
    assert f"the SRDF {PANDA_SRDF}" in diags[0]["message"] or "does not disable the pair" in diags[0]["message"]
    code, diags = _json("--inertia", "--select", "P005", planted)          # without it: a warning
    assert code == 0 and {d["severity"] for d in diags} == {"warning"}


def test_hull_only_overlaps_are_information():
    code, diags = _json("--inertia", "--select", "P005", PR2)
    base = next(d for d in diags if d["data"]["links"] == ["base_link", "r_shoulder_pan_link"])
    assert base["severity"] == "info" and base["data"]["hull_only"] and round(base["data"]["depth"] * 1000) == 256
    assert "the meshes themselves do not touch" in base["message"]


def test_without_meshes_only_primitives_are_tested():
    code, diags = _json("--select", "P005", PANDA)
    assert diags == []                                      # Franka's collisions are meshes: read with --inertia


def test_bad_srdf_is_one_error_line(tmp_path):
    bad = tmp_path / "bad.srdf"
    bad.write_text("<robot name='x'>\n<disable_collisions link1='a'/>\n</robot>\n")
    r = invoke("check", "--select", "P005", "--srdf", bad, WANDER / "urdf" / "robot.xacro")
    assert r.exit_code == 2 and re.search(r"bad\.srdf:2: error: <disable_collisions> needs link1 and link2", r.output)
    assert "Traceback" not in r.output
    r = invoke("check", "--select", "P005", "--srdf", tmp_path / "missing.srdf", PANDA)
    assert r.exit_code == 2 and "no such SRDF file" in r.output


def test_the_srdf_is_part_of_the_cache_key(tmp_path):
    from myrabot_desc.checks.cache import reset
    from myrabot_desc.checks.cache import task_key as _key
    from myrabot_desc.checks.context import CheckOptions
    from myrabot_desc.checks.run import Task

    srdf = tmp_path / "r.srdf"
    srdf.write_text("<robot name='r'/>\n")
    t = lambda s: Task(str(PANDA), {}, CheckOptions(srdf=s), (), (), (), False, str(tmp_path))   # noqa: E731
    k1 = _key(t(str(srdf)))
    assert k1 != _key(t(None))
    srdf.write_text("<robot name='r'>\n<disable_collisions link1='a' link2='b'/>\n</robot>\n")
    reset()                     # (file contents are hashed once per run)
    assert _key(t(str(srdf))) != k1


# ------------------------------------------------------------------ P006
def test_planted_effort_below_gravity_is_an_error(tmp_path):
    """0.1 N·m on PR2's right shoulder, which needs 52.1 N·m."""
    code, diags = _json("--select", "P006", weak(tmp_path, PR2, "r_shoulder_lift_joint"))
    got = {d["data"]["joint"]: (d["severity"], round(d["data"]["torque"], 1), d["data"]["effort"]) for d in diags}
    assert got == {"r_shoulder_lift_joint": ("error", 52.1, 0.1), "l_shoulder_lift_joint": ("warning", 52.1, 30.0)}
    assert code == 1
    err = next(d for d in diags if d["severity"] == "error")
    assert err["message"] == ("joint r_shoulder_lift_joint needs 52.1 N·m to hold what it carries against gravity "
                              "(with r_shoulder_lift_joint at -0.0436 rad, the others at rest), over its effort limit "
                              "0.1 N·m (5.2e+02x)")


def test_counterbalanced_shoulder_is_a_warning_and_passive_joints_are_left_alone():
    code, diags = _json("--select", "P006", PR2)
    assert {(d["data"]["joint"], d["severity"]) for d in diags} == {("r_shoulder_lift_joint", "warning"),
                                                                     ("l_shoulder_lift_joint", "warning")}
    code, diags = _json("--select", "P006", *corpus_args(corpus_robot("tiago")))
    # TIAGo's suspension joints carry 116 N·m on a 100 N·m "effort", but nothing commands them: passive
    assert not [d for d in diags if "suspension" in d["message"]]


def test_rules_say_why_they_have_no_fix():
    rules = load_all()
    for code in ("P005", "P006"):
        assert rules[code].fix.availability == "never" and rules[code].fix.how


def test_links_all_at_one_place_are_one_finding_not_millions_of_pairs(tmp_path, monkeypatch):
    """300 boxes at one place meet in 44,850 pairs: over the limit (here 1,000), P005 says so once
    instead of testing each pair."""
    link = ('<link name="l{i}"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" '
            'izz="0.01"/></inertial><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>')
    joint = ('<joint name="j{i}" type="revolute"><parent link="l{p}"/><child link="l{i}"/><axis xyz="0 0 1"/>'
             '<limit lower="-1" upper="1" effort="100" velocity="1"/></joint>')
    body = link.format(i=0) + "".join(link.format(i=i) + joint.format(i=i, p=i - 1) for i in range(1, 300))
    f = tmp_path / "pile.urdf"
    f.write_text(f'<robot name="pile">\n{body}\n</robot>\n')
    monkeypatch.setenv("MYRABOT_DESC_MAX_COLLISION_PAIRS", "1000")
    code, diags = _json("--select", "P005", f)
    assert [(d["severity"], d["message"]) for d in diags] == [
        ("warning", "self-collision: over 1000 pairs of collision shapes meet at this pose (the links are probably "
                    "all at one place); not tested pair by pair (MYRABOT_DESC_MAX_COLLISION_PAIRS)")]
