"""Adopting the lint in a repository that has history: ``--baseline`` (old findings known, new ones
fail, stable when lines move), ``--changed-since`` (a real git history: tests/fixtures/model_history/
tb3_sequence, six commits of turtlebot3_description), ``check -r`` and ``.gitignore``, JUnit XML."""

from __future__ import annotations

import json
import shutil
import sys
from pathlib import Path
from xml.etree import ElementTree

import pytest
import yaml

from helpers import TESTS, invoke

sys.path.insert(0, str(TESTS / "diff"))
from history import HISTORY, commit_all, git, replace_tree  # noqa: E402

OLD_BOT = """<?xml version="1.0"?>
<robot name="old_bot">
  <link name="base_link">
    <inertial><mass value="2.0"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <collision><geometry><box size="0.4 0.3 0.1"/></geometry></collision>
  </link>
  <link name="arm">
    <inertial><mass value="0"/><inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial>
  </link>
  <joint name="arm_joint" type="revolute">
    <parent link="base_link"/><child link="arm"/>
    <axis xyz="0 0 1"/><limit lower="1" upper="-1" effort="0" velocity="1"/>
  </joint>
</robot>
"""
NEW_ERROR = """  <link name="tool">
    <inertial><mass value="0.5"/><inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>
  </link>
  <joint name="tool_joint" type="revolute">
    <parent link="base_link"/><child link="tool"/>
    <axis xyz="0 0 1"/><limit lower="2" upper="-2" effort="1" velocity="1"/>
  </joint>
</robot>
"""


def codes(out: str) -> list[str]:
    return sorted(d["code"] for f in json.loads(out)["files"] for d in f["diagnostics"])


def test_baseline_old_findings_pass_new_ones_fail_lines_may_move(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    model = tmp_path / "urdf" / "robot.urdf"
    model.parent.mkdir()
    model.write_text(OLD_BOT)
    r = invoke("check", model)
    assert r.exit_code == 1                                    # T015 and P003 are errors
    r = invoke("check", model, "--baseline", "baseline.json")
    assert r.exit_code == 0, r.output                          # recorded: today's findings are known
    doc = json.loads((tmp_path / "baseline.json").read_text())
    assert doc["schema"] == "myrabot-desc/baseline/1"
    assert sorted(f["code"] for f in doc["findings"]) == ["I002", "P003", "P004", "T011", "T015"]
    assert {f["model"] for f in doc["findings"]} == {"urdf/robot.urdf"}
    assert all("line" not in f for f in doc["findings"])
    r = invoke("check", model, "--baseline", "baseline.json", "--format", "json")
    assert r.exit_code == 0 and codes(r.output) == []
    # lines move: a comment block at the top, blank lines inside
    moved = OLD_BOT.replace('<robot name="old_bot">', '<robot name="old_bot">\n  <!-- a\n  comment -->\n\n')
    moved = moved.replace("  <joint", "\n\n\n  <joint")
    model.write_text(moved)
    r = invoke("check", model, "--format", "json")
    assert r.exit_code == 1 and "T015" in codes(r.output)     # the findings are still there...
    r = invoke("check", model, "--baseline", "baseline.json", "--format", "json")
    assert r.exit_code == 0 and codes(r.output) == []          # ...and still known
    # a new error fails, and only it is reported
    model.write_text(moved.replace("</robot>\n", NEW_ERROR))
    r = invoke("check", model, "--baseline", "baseline.json", "--format", "json")
    assert r.exit_code == 1
    new = [d for f in json.loads(r.output)["files"] for d in f["diagnostics"]]
    assert [d["code"] for d in new if d["severity"] == "error"] == ["T015"]
    assert "tool_joint" in next(d["message"] for d in new if d["code"] == "T015")
    # --update-baseline accepts it
    assert invoke("check", model, "--baseline", "baseline.json", "--update-baseline").exit_code == 0
    assert invoke("check", model, "--baseline", "baseline.json").exit_code == 0


def test_a_broken_baseline_is_one_line_exit_2(tmp_path):
    (tmp_path / "b.json").write_text("{not json")
    (tmp_path / "r.urdf").write_text(OLD_BOT)
    r = invoke("check", tmp_path / "r.urdf", "--baseline", tmp_path / "b.json")
    assert r.exit_code == 2
    assert r.output.strip().count("\n") == 0 and "b.json:1: error: not a baseline file" in r.output


# ------------------------------------------------------------------------------- --changed-since
SEQ = HISTORY / "tb3_sequence"


@pytest.fixture(scope="module")
def tb3_history(tmp_path_factory):
    """The six real commits of tb3_sequence as a git repository; (repo, commits, sequence.yaml)."""
    meta = yaml.safe_load((SEQ / "sequence.yaml").read_text())
    repo = tmp_path_factory.mktemp("tb3") / "turtlebot3"
    repo.mkdir()
    git(repo, "init", "-q", "-b", "main")
    shas, selected = [], {}
    for step in meta["steps"]:
        replace_tree(repo, SEQ / "seq" / str(step["n"]))
        commit_all(repo)
        git(repo, "commit", "-q", "--allow-empty", "-m", f"{step['commit'][:7]} {step['subject']}")
        shas.append(git(repo, "rev-parse", "HEAD").strip())
        if step["n"]:   # what --changed-since HEAD~1 picks right after this commit
            selected[step["n"]] = checked(repo, "HEAD~1")
    return repo, shas, meta, selected


def checked(repo: Path, rev: str) -> list[str]:
    """The models `check -r . --changed-since REV` checks, by name (turtlebot3_NAME.urdf.xacro)."""
    import os

    cwd = os.getcwd()
    os.chdir(repo)
    try:
        r = invoke("check", "-r", ".", "--changed-since", rev, "--format", "json", "--quiet")
    finally:
        os.chdir(cwd)
    assert r.exit_code in (0, 1), r.output
    out = r.output[r.output.index("{"):]
    return sorted(Path(f["file"]).name.removeprefix("turtlebot3_").removesuffix(".urdf.xacro")
                  for f in json.loads(out)["files"])


def test_changed_since_each_commit_checks_the_models_it_touched(tb3_history):
    _repo, _shas, meta, selected = tb3_history
    for step in meta["steps"][1:]:
        assert selected[step["n"]] == sorted(step["models_whose_sources_changed"]), step["n"]


def test_changed_since_an_older_revision(tb3_history):
    repo, shas, meta, _selected = tb3_history
    for k, models in meta["changed_since"].items():
        assert checked(repo, shas[int(k)]) == sorted(models), k
    assert checked(repo, "HEAD") == []


def test_changed_since_sees_uncommitted_edits_and_a_bad_revision(tb3_history, tmp_path):
    repo, _shas, _meta, _selected = tb3_history
    work = tmp_path / "clone"
    shutil.copytree(repo, work)
    common = work / "turtlebot3_description" / "urdf" / "common_properties.xacro"
    common.write_text(common.read_text() + "\n")
    assert checked(work, "HEAD") == ["burger", "waffle_pi", "waffle_pi_naked"]   # an include of all three
    r = invoke("check", work, "-r", "--changed-since", "no-such-rev")
    assert r.exit_code == 2 and "unknown revision 'no-such-rev'" in r.output


def test_diff_along_the_history_matches_the_oracle(tb3_history, tmp_path, monkeypatch):
    """diff --rev of each model across each commit: a change exactly where the oracle saw the built
    robot change (a re-committed mesh stand-in of the same extents is no change)."""
    repo, shas, meta, _selected = tb3_history
    monkeypatch.chdir(repo)
    for step in meta["steps"][1:]:
        n = step["n"]
        for model, path in meta["models"].items():
            r = invoke("diff", path, "--rev", f"{shas[n - 1]}..{shas[n]}", "--no-check")
            want = step["built_robot"][model]
            assert r.exit_code == (1 if want == "changed" else 0), (n, model, r.output)


# ------------------------------------------------------------------------------- .gitignore, JUnit
def test_recursive_check_skips_what_git_ignores(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    git(tmp_path, "init", "-q")
    for d in ("robots", "build_out", "generated", "scratch"):
        (tmp_path / d).mkdir()
        (tmp_path / d / "r.urdf").write_text(OLD_BOT)
    (tmp_path / "generated" / "keep.urdf").write_text(OLD_BOT)
    (tmp_path / ".gitignore").write_text("build_out/\ngenerated/*\n!generated/keep.urdf\n")
    (tmp_path / "scratch" / ".gitignore").write_text("*.urdf\n")
    r = invoke("check", "-r", ".", "--format", "json", "--isolated")
    files = sorted(f["file"] for f in json.loads(r.output)["files"])
    assert files == ["generated/keep.urdf", "robots/r.urdf"]


def test_a_tracked_model_is_checked_whatever_gitignore_says(tmp_path, monkeypatch):
    """As in git, .gitignore hides untracked files only: a pull request adding a pattern cannot drop a
    committed robot from `check -r` (a folder with glob characters in its name included)."""
    monkeypatch.chdir(tmp_path)
    git(tmp_path, "init", "-q")
    for d in ("robots", "odd [x]*"):
        (tmp_path / d).mkdir()
        (tmp_path / d / "r.urdf").write_text(OLD_BOT)
    commit_all(tmp_path, "robots")
    (tmp_path / "robots" / "scratch.urdf").write_text(OLD_BOT)
    (tmp_path / ".gitignore").write_text("robots/\n")
    (tmp_path / "odd [x]*" / ".gitignore").write_text("*.urdf\n")
    r = invoke("check", "-r", ".", "--format", "json", "--isolated")
    assert sorted(f["file"] for f in json.loads(r.output)["files"]) == ["odd [x]*/r.urdf", "robots/r.urdf"]
    r = invoke("check", "robots", "--format", "json", "--isolated")          # a named folder as well
    assert [f["file"] for f in json.loads(r.output)["files"]] == ["robots/r.urdf"]
    monkeypatch.setenv("PATH", str(tmp_path / "no-git-here"))     # git missing: the patterns decide
    r = invoke("check", "-r", ".", "--format", "json", "--isolated")
    assert r.exit_code == 2 and "ignored by .gitignore" in r.output


def test_junit_one_test_per_model_one_failure_per_error(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "bad.urdf").write_text(OLD_BOT)
    (tmp_path / "broken.urdf").write_text("<robot name='x'><link name='a'></robot>")
    r = invoke("check", "bad.urdf", "broken.urdf", "--format", "junit", "--isolated", "-o", "check.xml")
    assert r.exit_code == 2
    assert r.output.startswith("broken.urdf:")          # the file that could not be read, on stderr
    root = ElementTree.parse(tmp_path / "check.xml").getroot()
    suite = root.find("testsuite")
    assert suite.get("tests") == "2" and suite.get("failures") == "2" and suite.get("errors") == "1"
    cases = {c.get("name"): c for c in suite.findall("testcase")}
    assert sorted(f.get("type") for f in cases["bad.urdf"].findall("failure")) == ["P003", "T015"]
    assert "I002" in cases["bad.urdf"].find("system-out").text
    assert cases["broken.urdf"].find("error") is not None
    r = invoke("check", "bad.urdf", "--format", "junit", "--strict", "--isolated")
    assert len(ElementTree.fromstring(r.output).find("testsuite/testcase").findall("failure")) == 4
