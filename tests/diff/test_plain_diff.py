"""`diff`'s click-free path (commands/entry.py + commands/fastdiff.py) behaves like the click command.

* parse_plain reads a plain diff command line into the values click's parser gives;
* the same argv gives the same exit code, stdout, stderr and written report on both paths, for
  good and bad command lines (the bad ones fall back to click, which gives its own messages);
* a plain diff imports no click (a diff's target is twice the time of two builds, which import
  none).
"""

from __future__ import annotations

import subprocess
import sys

import pytest

from helpers import WANDER
from myrabot_desc.commands.diff import diff_cmd
from myrabot_desc.commands.options import DIFF_OPTS, INPUT_OPTS, parse_plain

OLD_BOT = """<?xml version="1.0"?>
<robot name="bot">
  <link name="base_link">
    <inertial><origin xyz="0 0 0.05"/><mass value="{mass}"/>
      <inertia ixx="0.02" ixy="0" ixz="0" iyy="0.03" iyz="0" izz="0.04"/></inertial>
    <collision><geometry><box size="0.4 0.3 0.1"/></geometry></collision>
  </link>
  <link name="laser"/>
  <joint name="laser_joint" type="fixed">
    <parent link="base_link"/><child link="laser"/><origin xyz="{x} 0 0.2"/>
  </joint>
</robot>
"""

PLAIN = [
    ["old.urdf", "new.urdf"],
    ["old.urdf", "new.urdf", "--format", "json", "--no-check"],
    ["old.urdf", "new.urdf", "--format=markdown", "--limit", "3", "-o", "report.md"],
    ["--select", "I,P", "--ignore=P004", "old.urdf", "new.urdf", "--exit-zero"],
    ["old.urdf", "old.urdf"],
    ["old.urdf", "missing.urdf"],
]
UNPARSED = [                                       # the plain parser leaves these to click
    ["--help"],
    ["old.urdf", "new.urdf", "--limit", "0"],
    ["old.urdf", "new.urdf", "--format", "yaml"],
    ["old.urdf", "new.urdf", "-o", "."],           # a folder
    ["old.urdf", "new.urdf", "--bogus"],
]
NEEDS_CLICK = UNPARSED + [                         # usage problems the plain path hands to click
    ["old.urdf"],
    ["old.urdf", "--rev", "a...b"],
]


def _files(cwd):
    (cwd / "old.urdf").write_text(OLD_BOT.format(mass=2.0, x=0.1))
    (cwd / "new.urdf").write_text(OLD_BOT.format(mass=2.5, x=0.125))


def _run(module: str, argv, cwd):
    code = f"import sys; from myrabot_desc.{module} import main; sys.exit(main())"
    p = subprocess.run([sys.executable, "-c", code, "diff", *argv], cwd=cwd, capture_output=True, timeout=120)
    report = cwd / "report.md"
    return p.returncode, p.stdout, p.stderr, report.read_bytes() if report.is_file() else None


@pytest.mark.parametrize("argv", PLAIN)
def test_parse_plain_reads_what_click_reads(argv):
    values = parse_plain(argv, INPUT_OPTS + DIFF_OPTS)
    ctx = diff_cmd.make_context("diff", list(argv))
    assert values == dict(ctx.params)


@pytest.mark.parametrize("argv", UNPARSED)
def test_unusual_command_lines_go_to_click(argv):
    assert parse_plain(argv, INPUT_OPTS + DIFF_OPTS) is None


@pytest.mark.parametrize("argv", PLAIN + NEEDS_CLICK, ids=" ".join)
def test_same_result_on_both_paths(argv, tmp_path):
    for side in ("fast", "click"):
        (tmp_path / side).mkdir()
        _files(tmp_path / side)
    fast = _run("commands.entry", argv, tmp_path / "fast")            # the console script's entry
    slow = _run("commands.main", argv, tmp_path / "click")             # the click group, always
    assert fast == slow
    assert b"Traceback" not in fast[2]


def test_outcomes_are_the_expected_ones(tmp_path):
    """Not only equal on both paths: right (so the parity above cannot hold by both failing)."""
    _files(tmp_path)
    rc, out, err, _ = _run("commands.entry", ["old.urdf", "new.urdf"], tmp_path)
    assert rc == 1 and b"mass: 2 kg -> 2.5 kg" in out and err == b"", (out, err)
    rc, out, err, _ = _run("commands.entry", ["old.urdf", "old.urdf"], tmp_path)
    assert (rc, out, err) == (0, b"", b"")
    rc, out, err, written = _run("commands.entry", ["old.urdf", "new.urdf", "--format", "markdown", "-o", "report.md"],
                                 tmp_path)
    assert rc == 1 and out == b"" and b"### Robot model diff" in written
    rc, out, err, _ = _run("commands.entry", ["old.urdf"], tmp_path)
    assert rc == 2 and b"expected OLD NEW" in err


def test_a_plain_diff_imports_no_click(tmp_path):
    code = ("import sys; from myrabot_desc.commands.entry import main; code = main(); "
            "print([m for m in ['click'] if m in sys.modules], file=sys.stderr); sys.exit(code)")
    robot = WANDER / "urdf" / "robot.xacro"
    p = subprocess.run([sys.executable, "-c", code, "diff", str(robot), str(robot)], capture_output=True, text=True,
                       timeout=120)
    assert p.returncode == 0, p.stderr
    assert p.stderr.splitlines()[-1] == "[]"
