"""Model text, file names and YAML values reach terminals and CI logs only through the one
sanitiser (myrabot_desc/sanitize.py): one line each, no control characters or terminal escapes,
no GitHub workflow command. Before, a link name holding an encoded newline wrote ``::error`` and
``::add-mask::`` lines that a runner executes, a folder named like a workflow command did the same
with ``check -r .``, ``xacro.message`` printed escape sequences from YAML raw, and a non-UTF-8 file
name with a SARIF output was an internal error.
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

sys.path.insert(0, str(Path(__file__).parent))
from limited import run, within_budget, write  # noqa: E402

from myrabot_desc.sanitize import clean, clean_lines, json_safe  # noqa: E402

# a name that closes the line and opens runner commands; C1 CSI (U+009B) and a bidi override too
HOSTILE = "base&#10;::add-mask::secret&#13;::error file=x::forged&#155;31m&#x202e;&#x2028;##[warning]v1"


def commands_in(text: str) -> list[str]:
    """Lines a GitHub runner would execute (``::`` after leading blanks; ``##[`` anywhere), and
    lines holding a terminal escape or another control character."""
    bad = []
    for line in text.split("\n"):
        if line.lstrip().startswith("::") and not line.startswith(("::error file=", "::warning file=",
                                                                   "::notice file=")):
            bad.append(line)
        if "##[" in line or any(ord(c) < 32 and c != "\t" or 0x7F <= ord(c) < 0xA0 for c in line):
            bad.append(line)
        if any(c in line for c in "\u2028\u2029\u202e"):
            bad.append(line)
    return bad


@pytest.fixture
def model(tmp_path):
    m = write(tmp_path / "inj.urdf", f"""<robot name="{HOSTILE}">
  <link name="{HOSTILE}"/>
  <link name="b"/>
  <joint name="j{HOSTILE}" type="revolut"><parent link="{HOSTILE}"/><child link="b"/></joint>
</robot>
""")
    return m


@pytest.mark.parametrize("argv", [["check", "--isolated"], ["check", "--isolated", "--format", "github"],
                                  ["info"], ["convert", "--allow-errors", "-o", "{tmp}/o.sdf"],
                                  ["convert", "-o", "{tmp}/o.sdf"]])
def test_names_cannot_break_lines_or_command_the_runner(tmp_path, model, argv):
    r = run([a.replace("{tmp}", str(tmp_path)) for a in argv] + [model], cwd=tmp_path)
    assert not within_budget(r), within_budget(r)
    out = r.stdout + r.stderr
    assert "add-mask" in out or argv[0] == "convert"        # the names are shown, escaped
    assert commands_in(r.stdout) == [] and commands_in(r.stderr) == []
    if "github" in argv:   # each annotation is one line starting with the level the tool chose
        assert all(ln.startswith(("::error file=", "::warning file=", "::notice file=")) or ln[0].isdigit()
                   for ln in r.stdout.splitlines())


def test_a_folder_named_like_a_workflow_command(tmp_path):
    folder = tmp_path / "::error title=pwned::a folder" / "::add-mask::x"
    write(folder / "r.urdf", '<robot name="r"><link name="a"/><link name="b"/></robot>\n')
    write(folder / "bad.urdf", "<robot")
    for fmt in ("text", "github", "sarif", "json"):
        r = run(["check", "-r", ".", "--isolated", "--format", fmt], cwd=tmp_path)
        assert r.code == 2 and not within_budget(r), (r.stdout, r.stderr)
        assert commands_in(r.stdout) == [] and commands_in(r.stderr) == [], (fmt, r.stdout, r.stderr)


def test_the_stderr_line_for_an_unprocessable_file_is_clean(tmp_path):
    write(tmp_path / "x.urdf", f"<robot name='r'><link name='{HOSTILE}'/><joint/></robot junk>")
    r = run(["check", "--isolated", "--format", "github", "x.urdf"], cwd=tmp_path)
    assert r.code == 2 and r.stderr.strip() and commands_in(r.stderr) == []


def test_xacro_message_from_yaml_is_escaped(tmp_path):
    write(tmp_path / "v.yaml", 'text: "line\\n::add-mask::tok \\e[2J\\e]0;t\\a ##[error]x"\n')
    write(tmp_path / "m.urdf.xacro", '<robot name="m" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
          '  <xacro:property name="v" value="${xacro.load_yaml(\'v.yaml\')}"/>\n'
          '  ${xacro.message(v.text)}${xacro.warning(v.text)}\n  <link name="a"/>\n</robot>\n')
    r = run(["build", "m.urdf.xacro", "-o", tmp_path / "o.urdf"], cwd=tmp_path)
    assert r.code == 0 and "add-mask" in r.stderr
    assert commands_in(r.stderr) == [] and "\x1b" not in r.stderr


@pytest.mark.skipif(sys.platform != "linux", reason="needs a file system that takes any bytes in names")
def test_a_non_utf8_file_name_in_every_report(tmp_path):
    folder = os.fsencode(tmp_path) + b"/r\xff\xfe"
    os.makedirs(folder)
    with open(folder + b"/bad\xff.urdf", "w") as f:
        f.write('<robot name="r"><link name="a"><inertial><mass value="-1"/>'
                '<inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link></robot>\n')
    for fmt in ("sarif", "json", "text", "github"):
        r = run(["check", "-r", ".", "--isolated", "--format", fmt, "-o", tmp_path / f"report.{fmt}"], cwd=tmp_path)
        assert r.code == 1 and not within_budget(r), (fmt, r.stderr)
        text = (tmp_path / f"report.{fmt}").read_bytes().decode("utf-8")      # valid UTF-8
        if fmt in ("sarif", "json"):
            doc = json.loads(text)
            if fmt == "sarif":
                uri = doc["runs"][0]["results"][0]["locations"][0]["physicalLocation"]["artifactLocation"]["uri"]
                assert uri == "r%FF%FE/bad%FF.urdf"
        assert commands_in(text) == []


# ------------------------------------------------------------------ the sanitiser itself
@settings(max_examples=500, deadline=None)
@given(st.text(alphabet=st.characters(blacklist_categories=()), max_size=60))
def test_clean_gives_one_printable_line_and_is_stable(s):
    out = clean(s)
    assert "\n" not in out and "\r" not in out and "\x1b" not in out
    assert not any(ord(c) < 32 or 0x7F <= ord(c) < 0xA0 or 0xD800 <= ord(c) < 0xE000 for c in out)
    assert not out.lstrip().startswith("::") and "##[" not in out
    assert clean(out) == out
    out.encode("utf-8")


def test_clean_examples():
    assert clean("wheel_left") == "wheel_left"                  # the common case is untouched
    assert clean("gazebo::DiffDrive") == "gazebo::DiffDrive"    # :: inside a name is harmless
    assert clean("a\nb\tc\x1b[31m") == "a\\nb\\tc\\x1b[31m"
    assert clean("  ::add-mask::x") == "  \\x3a:add-mask::x"
    assert clean("x ##[error]y") == "x #\\x23[error]y"
    assert clean(os.fsdecode(b"bad\xff.urdf")) == "bad\\xff.urdf"
    assert clean_lines("a\n::b\n") == "a\n\\x3a:b\n"
    assert json_safe(os.fsdecode(b"r\xff")) == "r\\xff" and json_safe("\n") == "\n"
