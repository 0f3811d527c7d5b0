"""`check`'s click-free path (commands/entry.py + commands/fastcheck.py) behaves like the click command.

* parse_plain reads a plain check command line into the values click's parser gives;
* the same argv gives the same exit code, stdout, stderr and written files on both paths, for good
  and bad command lines (the bad ones fall back to click, which gives its own messages), --fix,
  --diff and a baseline included;
* a plain check imports no click (a lint run on every commit: click is a tenth of a small robot's
  check).
"""

from __future__ import annotations

import subprocess
import sys

import pytest

from helpers import WANDER
from myrabot_desc.commands.check import check_cmd
from myrabot_desc.commands.options import CHECK_OPTS, INPUT_OPTS, parse_plain

BOT = """<?xml version="1.0"?>
<robot name="bot">
  <link name="base_link">
    <inertial><origin xyz="0 0 0.05"/><mass value="2"/>
      <inertia ixx="0.2" ixy="0" ixz="0" iyy="0.3" iyz="0" izz="0.4"/></inertial>
    <collision><geometry><box size="0.4 0.3 0.1"/></geometry></collision>
  </link>
  <link name="laser"/>
  <joint name="laser_joint" type="fixed">
    <parent link="base_link"/><child link="laser"/><origin xyz="0.1 0 0.2"/>
  </joint>
</robot>
"""

PLAIN = [
    ["bot.urdf"],
    ["bot.urdf", "--no-cache", "--format", "json"],
    ["bot.urdf", "--format=sarif", "-o", "report.txt", "--strict"],
    ["--select", "I,T", "--ignore=I008", "bot.urdf", "-q", "--isolated"],
    ["bot.urdf", "--format", "github", "-j", "1", "--no-cache"],
    ["bot.urdf", "--baseline", "base.json"],
    ["bot.urdf", "--diff", "--unsafe-fixes"],
    ["bot.urdf", "--fix", "--unsafe-fixes"],
    ["--list-rules"],
    ["missing.urdf"],
    ["bot.urdf", "missing.urdf", "--format", "junit"],
]
UNPARSED = [                                       # the plain parser leaves these to click
    ["--help"],
    ["bot.urdf", "-j", "0"],
    ["bot.urdf", "--format", "yaml"],
    ["bot.urdf", "-o", "."],                       # a folder
    ["bot.urdf", "--cache-dir", "bot.urdf"],       # a file
    ["bot.urdf", "--bogus"],
    ["-qr", "."],                                  # bundled short options
]
NEEDS_CLICK = UNPARSED + [                         # usage problems the plain path hands to click
    ["bot.urdf", "--unsafe-fixes"],
    ["bot.urdf", "--update-baseline"],
    ["bot.urdf", "--select", "Q999"],
    ["."],                                         # a folder without models
]


def _files(cwd):
    (cwd / "bot.urdf").write_text(BOT)


def _run(module: str, argv, cwd):
    code = f"import sys; from myrabot_desc.{module} import main; sys.exit(main())"
    p = subprocess.run([sys.executable, "-c", code, "check", *argv], cwd=cwd, capture_output=True, timeout=120)
    written = {f.name: f.read_bytes() for f in sorted(cwd.iterdir())}
    return p.returncode, p.stdout, p.stderr, written


@pytest.mark.parametrize("argv", PLAIN, ids=" ".join)
def test_parse_plain_reads_what_click_reads(argv):
    values = parse_plain(argv, INPUT_OPTS + CHECK_OPTS)
    ctx = check_cmd.make_context("check", list(argv))
    assert values == dict(ctx.params)


@pytest.mark.parametrize("argv", UNPARSED, ids=" ".join)
def test_unusual_command_lines_go_to_click(argv, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    _files(tmp_path)
    assert parse_plain(argv, INPUT_OPTS + CHECK_OPTS) is None


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
    rc, out, err, _ = _run("commands.entry", ["bot.urdf", "--no-cache"], tmp_path)
    assert rc == 0 and b"I006 link base_link" in out and b"0 errors, 2 warnings" in out and err == b"", (out, err)
    rc, out, err, written = _run("commands.entry", ["bot.urdf", "--format", "json", "-o", "r.json"], tmp_path)
    assert rc == 0 and out == b"" and b'"code": "I006"' in written["r.json"]
    rc, out, err, written = _run("commands.entry", ["bot.urdf", "--fix", "--unsafe-fixes"], tmp_path)
    assert b'izz="0.04167"' in written["bot.urdf"] and b"Fixed 1 finding" in err, err
    rc, out, err, _ = _run("commands.entry", ["bot.urdf", "--unsafe-fixes"], tmp_path)
    assert rc == 2 and b"--unsafe-fixes goes with --fix or --diff" in err and b"Usage:" in err
    rc, out, err, _ = _run("commands.entry", ["missing.urdf"], tmp_path)
    assert rc == 2 and b"no such file: missing.urdf" in out


def test_a_plain_check_imports_no_click(tmp_path):
    code = ("import sys; from myrabot_desc.commands.entry import main; code = main(); "
            "print([m for m in ['click'] if m in sys.modules], file=sys.stderr); sys.exit(code)")
    robot = WANDER / "urdf" / "robot.xacro"
    p = subprocess.run([sys.executable, "-c", code, "check", "--no-cache", str(robot)], capture_output=True,
                       text=True, timeout=120, stdin=subprocess.DEVNULL)
    assert p.returncode in (0, 1), p.stderr
    assert p.stderr.splitlines()[-1] == "[]"


def test_a_report_for_a_file_is_the_terminal_report_unstyled(tmp_path):
    """render's text without styles (color=False, what a check writes to a file) is the styled text
    with its styles stripped, for findings of every severity, suggestions, a failure and a message
    or name that holds an escape character (written out by clean(), never an escape itself)."""
    from myrabot_desc.checks.context import CheckOptions
    from myrabot_desc.checks.report import FileResult, render
    from myrabot_desc.checks.run import Task, check_one
    from myrabot_desc.commands.console import unstyle
    from myrabot_desc.diagnostics import Diagnostic, Loc

    robot = tmp_path / "bot.urdf"
    robot.write_text(BOT)
    res = check_one(Task(str(robot), {}, CheckOptions(inertia=True, suggest=True), (), (), (), False, None))
    res.diagnostics.append(Diagnostic("T005", "error", "a message with \033[1m in it", Loc(str(robot), 3)))
    failed = FileResult(str(tmp_path / "gone\033[0m.urdf"), failure="cannot read gone\033[0m.urdf")
    assert res.diagnostics and res.suggestions
    for quiet in (False, True):
        styled = render("text", [res, failed], "0", quiet=quiet)
        assert "\033" in styled
        assert render("text", [res, failed], "0", quiet=quiet, color=False) == unstyle(styled)
