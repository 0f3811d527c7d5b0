"""``myrabot-desc diff`` as a command: exit codes as ``git diff --exit-code``, one line for bad input,
two files or two git revisions (the work tree untouched), the drive's effect, the three formats and
what they do with hostile model text."""

from __future__ import annotations

import json
import os
import shutil
import tempfile

from pathlib import Path

from helpers import ROOT, WANDER, invoke
from history import git

BUNDLED = ROOT / "xacro" / "myrabot.urdf.xacro"
BOT = """<?xml version="1.0"?>
<robot name="bot">
  <link name="base_link">
    <inertial><origin xyz="0 0 0.05"/><mass value="{mass}"/>
      <inertia ixx="0.02" ixy="0" ixz="0" iyy="0.03" iyz="0" izz="0.04"/></inertial>
    <collision><geometry><box size="0.4 0.3 0.1"/></geometry></collision>
  </link>
  <link name="{sensor}">
    <inertial><mass value="0.1"/><inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial>
  </link>
  <joint name="sensor_joint" type="fixed">
    <parent link="base_link"/><child link="{sensor}"/><origin xyz="{x} 0 0.2" rpy="0 0 {yaw}"/>
  </joint>
</robot>
"""


def bot(path, mass=2.0, x=0.1, yaw=0.0, sensor="laser"):
    path.write_text(BOT.format(mass=mass, x=x, yaw=yaw, sensor=sensor))
    return path


def test_a_model_against_itself_prints_nothing_and_exits_0():
    r = invoke("diff", BUNDLED, BUNDLED)
    assert r.exit_code == 0 and r.output == ""
    r = invoke("diff", BUNDLED, BUNDLED, "--format", "json")
    assert r.exit_code == 0 and json.loads(r.output)["changes"] == {}


def test_the_same_model_in_two_folders_is_no_change(tmp_path):
    """Each side's own folders (package roots, $(find) paths) are not a change."""
    for side in ("a", "b"):
        shutil.copytree(WANDER, tmp_path / side)
    r = invoke("diff", tmp_path / "a" / "urdf" / "robot.xacro", tmp_path / "b" / "urdf" / "robot.xacro")
    assert r.exit_code == 0 and r.output == ""


def test_numbers_and_where(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    bot(tmp_path / "old.urdf")
    bot(tmp_path / "new.urdf", mass=2.5, x=0.125, yaw=0.5)
    r = invoke("diff", "old.urdf", "new.urdf", "--format", "json", "--no-check")
    assert r.exit_code == 1
    ch = json.loads(r.output)["changes"]
    assert ch["links_changed"]["base_link"]["mass_kg"] == {"old": 2.0, "new": 2.5, "delta": 0.5}
    assert ch["joints_changed"]["sensor_joint"]["xyz_mm"]["delta"] == [25.0, 0.0, 0.0]
    assert ch["joints_changed"]["sensor_joint"]["rpy_deg"]["new"] == [0.0, 0.0, 28.6479]
    moved = ch["frames_moved_zero_pose"]["laser"]
    assert moved["distance_mm"] == 25.0 and moved["rotated_deg"] == 28.6479
    assert ch["total_mass_kg"] == {"old": 2.1, "new": 2.6, "delta": 0.5}
    # centre of mass: (2*0.05 + 0.1*0.2)/2.1 z, (0.1*0.1)/2.1 x -> (2.5*0.05 + 0.1*0.2)/2.6, 0.0125/2.6
    assert ch["centre_of_mass_mm"]["old"] == [4.7619, 0.0, 57.1429]
    assert ch["centre_of_mass_mm"]["new"] == [4.8077, 0.0, 55.7692]
    items = {(i["subject"], i["what"]): i for i in json.loads(r.output)["items"]}
    assert items[("base_link", "mass")]["where"] == "new.urdf:4:52"
    assert items[("sensor_joint", "origin xyz")]["where"] == "new.urdf:12:65"
    # renamed by structure: the same fixed joint, the child link renamed
    bot(tmp_path / "renamed.urdf", sensor="laser_link")
    ch = json.loads(invoke("diff", "old.urdf", "renamed.urdf", "--format", "json").output)["changes"]
    assert ch["links_renamed"][0]["old"] == "laser" and ch["links_renamed"][0]["new"] == "laser_link"
    assert set(ch) == {"links_renamed"}


def test_the_drive_and_what_it_does(tmp_path):
    """wander_bot's plugin wheelSeparation 0.4 -> 0.424: the wheels are 0.3 m apart, so the same
    cmd_vel turns it 1.06× faster; check's G001 says 1.33× -> 1.41×."""
    for side in ("a", "b"):
        shutil.copytree(WANDER, tmp_path / side)
    gz = tmp_path / "b" / "urdf" / "robot.gazebo"
    gz.write_text(gz.read_text().replace("<wheelSeparation>0.4<", "<wheelSeparation>0.424<"))
    r = invoke("diff", tmp_path / "a" / "urdf" / "robot.xacro", tmp_path / "b" / "urdf" / "robot.xacro",
               "--format", "json")
    assert r.exit_code == 1
    doc = json.loads(r.output)
    drive = doc["changes"]["drive"]
    assert drive["old"]["plugin"]["separation_mm"] == 400.0 and drive["new"]["plugin"]["separation_mm"] == 424.0
    assert drive["effect"] == {"turn_factor": 1.06}
    assert drive["effect_text"] == ["turns 1.06× faster for the same command"]
    assert doc["items"][0]["change"] == "turns 1.06× faster for the same command"     # the largest first
    assert [f["code"] for f in doc["changes"]["findings_changed"]] == ["G001"]
    assert "1.41×" in doc["changes"]["findings_changed"][0]["new"]
    text = invoke("diff", tmp_path / "a" / "urdf" / "robot.xacro", tmp_path / "b" / "urdf" / "robot.xacro").output
    assert "plugin wheel separation: 400 mm -> 424 mm (+24 mm)" in text and "robot.gazebo:12:24" in text


def test_bad_input_is_one_line_exit_2(tmp_path):
    bot(tmp_path / "ok.urdf")
    (tmp_path / "broken.urdf.xacro").write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="x">\n'
                                                '  <link name="${undefined_thing}"/>\n</robot>\n')
    for args in ([tmp_path / "ok.urdf", tmp_path / "missing.urdf"], [tmp_path / "ok.urdf", tmp_path / "broken.urdf.xacro"]):
        r = invoke("diff", *args)
        assert r.exit_code == 2
        assert len(r.output.strip().splitlines()) == 1 and "error" in r.output, r.output
    assert "broken.urdf.xacro:2" in invoke("diff", tmp_path / "ok.urdf", tmp_path / "broken.urdf.xacro").output
    assert invoke("diff", tmp_path / "ok.urdf").exit_code == 2               # OLD NEW or FILE --rev
    assert invoke("diff", tmp_path / "ok.urdf", "--rev", "A...B").exit_code == 2


def test_revisions_are_read_through_git_not_checked_out(tmp_path, monkeypatch):
    repo = tmp_path / "repo"
    (repo / "urdf").mkdir(parents=True)
    git(repo, "init", "-q", "-b", "main")
    bot(repo / "urdf" / "bot.urdf")
    git(repo, "add", "-A")
    git(repo, "commit", "-q", "-m", "one")
    bot(repo / "urdf" / "bot.urdf", mass=3.0)
    git(repo, "commit", "-q", "-am", "two")
    bot(repo / "urdf" / "bot.urdf", mass=3.0, x=0.2)          # uncommitted
    before = (repo / "urdf" / "bot.urdf").read_bytes()
    status = git(repo, "status", "--porcelain")
    temp_before = set(os.listdir(tempfile.gettempdir()))
    monkeypatch.chdir(repo)
    r = invoke("diff", "urdf/bot.urdf", "--rev", "HEAD~1..HEAD", "--format", "json", "--no-check")
    assert r.exit_code == 1
    ch = json.loads(r.output)["changes"]
    assert set(ch["links_changed"]) == {"base_link"} and "joints_changed" not in ch
    items = json.loads(r.output)["items"]
    assert next(i for i in items if i["what"] == "mass")["where"] == "urdf/bot.urdf:4:52"
    ch = json.loads(invoke("diff", "urdf/bot.urdf", "--rev", "HEAD", "--format", "json").output)["changes"]
    assert set(ch["joints_changed"]) == {"sensor_joint"} and "links_changed" not in ch     # HEAD vs the work tree
    assert invoke("diff", "urdf/bot.urdf", "--rev", "HEAD~1..HEAD~1").exit_code == 0
    r = invoke("diff", "urdf/bot.urdf", "--rev", "nope..HEAD")
    assert r.exit_code == 2 and "unknown revision 'nope'" in r.output
    # the work tree, the index and the temporary folder are as they were
    assert (repo / "urdf" / "bot.urdf").read_bytes() == before
    assert git(repo, "status", "--porcelain") == status
    assert not {n for n in set(os.listdir(tempfile.gettempdir())) - temp_before if n.startswith("myrabot-desc-rev-")}


def test_markdown_comment_and_hostile_names(tmp_path):
    bot(tmp_path / "old.urdf")
    bot(tmp_path / "new.urdf", sensor="x|y&lt;img src=a onerror=b&gt;&#x202e;", mass=4.0)
    r = invoke("diff", tmp_path / "old.urdf", tmp_path / "new.urdf", "--format", "markdown", "--image",
               "https://example.org/before-after.png")
    assert r.exit_code == 1
    md = r.output
    assert md.startswith("<!-- myrabot-desc diff -->\n### Robot model diff")
    assert "| | what | before | after | change | where |" in md
    assert "<img" not in md and "x\\|y&lt;img" in md and "\u202e" not in md
    assert "![before / after](https://example.org/before-after.png)" in md
    rows = [line for line in md.splitlines() if line.startswith("| link") or line.startswith("| joint")]
    assert rows and "renamed" in rows[0]                  # a rename is larger than a mass change
    text = invoke("diff", tmp_path / "old.urdf", tmp_path / "new.urdf").output
    assert "\u202e" not in text
    assert invoke("diff", tmp_path / "old.urdf", tmp_path / "old.urdf", "--format", "markdown").output.endswith(
        "No change to the built robot.\n")


def test_action_diff_step_posts_then_updates_one_comment(tmp_path):
    """The Action's pull-request step, run by bash as written: a fake `gh` records the API calls; the
    first run posts a comment (the Markdown diff of each file), the second finds it by its marker and
    updates it."""
    import subprocess
    import sys

    import yaml

    step = next(s for s in yaml.safe_load((ROOT / "action.yml").read_text())["runs"]["steps"]
                if s.get("name") == "Robot diff comment")
    assert "pull_request" in step["if"] and "inputs.diff" in step["if"]
    repo = tmp_path / "repo"
    repo.mkdir()
    git(repo, "init", "-q", "-b", "main")
    bot(repo / "bot.urdf")
    git(repo, "add", "-A")
    git(repo, "commit", "-q", "-m", "base")
    base = git(repo, "rev-parse", "HEAD").strip()
    bot(repo / "bot.urdf", mass=2.4)
    git(repo, "commit", "-q", "-am", "heavier")
    head = git(repo, "rev-parse", "HEAD").strip()
    fake = tmp_path / "bin"
    fake.mkdir()
    calls = tmp_path / "calls"
    (fake / "gh").write_text(
        "#!/bin/bash\n"
        f'echo "$*" >> {calls}\n'
        'for a in "$@"; do case "$a" in body=@*) cp "${a#body=@}" ' + str(tmp_path / "posted.md") + ";; esac; done\n"
        f'if [ "$2" != "-X" ] && [ -f {tmp_path / "posted.md"} ] && [[ "$*" == *--jq* ]]; then echo 4242; fi\n')
    (fake / "gh").chmod(0o755)
    env = {**os.environ, "MD_DIFF": "bot.urdf", "MD_DIFF_ARGS": "--no-check", "MD_BASE": base, "MD_HEAD": head,
           "MD_PR": "7", "MD_REPO": "o/r", "GH_TOKEN": "x", "RUNNER_TEMP": str(tmp_path),
           "PATH": f"{fake}{os.pathsep}{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}"}
    for _ in range(2):
        p = subprocess.run(["bash", "-e", "-c", step["run"]], cwd=repo, env=env, capture_output=True, text=True)
        assert p.returncode == 0, p.stderr
    posted = (tmp_path / "posted.md").read_text()
    assert posted.startswith("<!-- myrabot-desc diff -->") and "| link | **base\\_link** mass | 2 kg | 2.4 kg |" in posted
    lines = calls.read_text().splitlines()
    assert [line.split()[0:3] for line in lines if "comments" in line and "--jq" not in line] == [
        ["api", "repos/o/r/issues/7/comments", "-F"], ["api", "-X", "PATCH"]]
    assert "repos/o/r/issues/comments/4242" in lines[-1]


ARM = """<?xml version="1.0"?>
<robot name="arm">
  <link name="base"/>
  <link name="upper"><inertial><origin xyz="0 0 0.25"/><mass value="1"/>
    <inertia ixx="0.02" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.001"/></inertial></link>
  <link name="tool"/>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <axis xyz="0 1 0"/><limit lower="{lower}" upper="1.5" effort="10" velocity="1"/></joint>
  <joint name="wrist" type="fixed"><parent link="upper"/><child link="tool"/><origin xyz="0 0 0.5"/></joint>
  {gazebo}
</robot>
"""
CAMERA = ('<gazebo reference="tool"><sensor type="camera" name="{name}"><update_rate>30</update_rate>'
          '</sensor></gazebo>')


def test_rest_pose_limits_and_sensors(tmp_path):
    """The shoulder's range [0.2, 1.5] rad leaves 0 out: the rest pose holds it at 0.2 rad. Raising the
    lower limit to 0.3 moves nothing at the zero pose and the tool by 0.5 m × 0.1 rad at rest."""
    (tmp_path / "old.urdf").write_text(ARM.format(lower="0.2", gazebo=""))
    (tmp_path / "new.urdf").write_text(ARM.format(lower="0.3", gazebo=CAMERA.format(name="cam")))
    (tmp_path / "renamed.urdf").write_text(ARM.format(lower="0.3", gazebo=CAMERA.format(name="tool_camera")))
    r = invoke("diff", tmp_path / "old.urdf", tmp_path / "new.urdf", "--format", "json", "--no-check")
    ch = json.loads(r.output)["changes"]
    assert ch["joints_changed"]["shoulder"]["limit"] == {"lower_deg": {"old": 11.4592, "new": 17.1887}}
    assert "frames_moved_zero_pose" not in ch
    rest = ch["frames_moved_rest_pose"]
    assert set(rest) == {"upper", "tool"}
    assert rest["upper"]["rotated_deg"] == 5.7296 and rest["upper"]["distance_mm"] == 0.0
    assert abs(rest["tool"]["distance_mm"] - 1000 * 2 * 0.5 * __import__("math").sin(0.05)) < 1e-3   # chord
    assert ch["sensors_added"] == [{"name": "cam", "type": "camera", "link": "tool"}]
    ch = json.loads(invoke("diff", tmp_path / "new.urdf", tmp_path / "renamed.urdf", "--format", "json").output)["changes"]
    assert ch["sensors_renamed"] == [{"old": "cam", "new": "tool_camera"}]


def test_before_after_picture(tmp_path):
    """--picture renders both robots (rest pose, iso view) side by side, as `render` does (MuJoCo
    offscreen in a subprocess: the GL backend is fixed when mujoco is first imported)."""
    import ctypes.util
    import subprocess
    import sys

    import pytest

    if not any(ctypes.util.find_library(n) for n in ("EGL", "OSMesa")):
        pytest.skip("no libEGL or libOSMesa: `make install` installs them")
    import numpy as np
    from PIL import Image

    from myrabot_desc.render import BACKGROUND

    for side in ("a", "b"):
        shutil.copytree(WANDER, tmp_path / side)
    x = tmp_path / "b" / "urdf" / "robot.xacro"
    x.write_text(x.read_text().replace('<origin xyz="0.1 0.15 0"', '<origin xyz="0.1 0.2 0"')
                 .replace('<origin xyz="0.1 -0.15 0"', '<origin xyz="0.1 -0.2 0"'))
    env = {k: v for k, v in os.environ.items() if k != "MUJOCO_GL"}
    p = subprocess.run([sys.executable, "-m", "myrabot_desc", "diff", str(tmp_path / "a" / "urdf" / "robot.xacro"), str(x),
                        "--picture", str(tmp_path / "ba.png"), "--format", "markdown", "--no-check"],
                       capture_output=True, text=True, env=env, timeout=180)
    assert p.returncode == 1, p.stderr
    assert f"![before / after]({tmp_path / 'ba.png'})" in p.stdout
    assert "turns 0.75× as fast for the same command" in p.stdout        # plugin 0.4 m, wheels 0.3 -> 0.4 m apart
    with Image.open(tmp_path / "ba.png") as im:
        img = np.asarray(im.convert("RGB")).astype(int)
    assert img.shape == (450, 1200, 3)
    fg = np.abs(img - np.array(BACKGROUND)).sum(axis=2) > 6
    left, right = fg[60:, :590], fg[60:, 610:]
    assert left.sum() > 10000 and right.sum() > 10000 and (left != right).sum() > 1000


def test_the_second_revision_links_the_files_the_first_holds(tmp_path):
    """vcs.export(like=...): a file with the same bytes as the other revision's is the same file
    (linked, not written again); a changed one, a new one and a symbolic link are its own."""
    from myrabot_desc.vcs import export

    repo = tmp_path / "repo"
    (repo / "urdf").mkdir(parents=True)
    git(repo, "init", "-q")
    (repo / "urdf" / "same.xacro").write_text("<robot/>\n")
    (repo / "urdf" / "changed.xacro").write_text("<robot name='a'/>\n")
    (repo / "urdf" / "link.xacro").symlink_to("same.xacro")
    git(repo, "add", "-A")
    git(repo, "commit", "-q", "-m", "a")
    (repo / "urdf" / "changed.xacro").write_text("<robot name='b'/>\n")
    (repo / "urdf" / "new.xacro").write_text("<robot/>\n")
    git(repo, "add", "-A")
    git(repo, "commit", "-q", "-m", "b")
    a, b = tmp_path / "a", tmp_path / "b"
    a.mkdir()
    b.mkdir()
    export(repo, "HEAD~1", a)
    export(repo, "HEAD", b, like=a)
    assert (b / "urdf" / "same.xacro").stat().st_ino == (a / "urdf" / "same.xacro").stat().st_ino
    assert (b / "urdf" / "changed.xacro").read_text() == "<robot name='b'/>\n"
    assert (b / "urdf" / "changed.xacro").stat().st_ino != (a / "urdf" / "changed.xacro").stat().st_ino
    assert (b / "urdf" / "new.xacro").read_text() == "<robot/>\n" and not (a / "urdf" / "new.xacro").exists()
    assert (b / "urdf" / "link.xacro").is_symlink() and (b / "urdf" / "link.xacro").read_text() == "<robot/>\n"


def test_the_same_report_with_the_second_build_forked_or_not(tmp_path, monkeypatch):
    """diff builds the other side in a forked process when a core is idle, else in this one."""
    from myrabot_desc.diff import run

    bot(tmp_path / "old.urdf")
    bot(tmp_path / "new.urdf", mass=2.5, x=0.125, yaw=0.5)
    out = []
    for idle in (True, False):
        monkeypatch.setattr(run, "_idle_core", lambda idle=idle: idle)
        r = invoke("diff", tmp_path / "old.urdf", tmp_path / "new.urdf", "--format", "json")
        assert r.exit_code == 1
        out.append(json.loads(r.output)["changes"])
    assert out[0] == out[1] and out[0]
