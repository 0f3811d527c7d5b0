"""`build`'s click-free fast path (commands/entry.py + commands/fastbuild.py) behaves exactly like the click command.

* parse_plain reads every plain command line into the same values as click's parser does;
* the same argv gives the same exit code, stdout, stderr and written bytes on both paths, for
  good and bad command lines (the bad ones fall back to click, which gives its own messages);
* a plain build imports neither click, lxml, PyYAML (until a file calls load_yaml) nor
  dataclasses/typing/inspect (issue 13: start-up is most of a small robot's build).
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from helpers import TESTS
from myrabot_desc.commands.build import build_cmd
from myrabot_desc.commands.fastbuild import BUILD_OPTS, fast_build
from myrabot_desc.commands.options import INPUT_OPTS, parse_plain

HERE = TESTS
MATH = HERE / "fixtures" / "xacro" / "math_yaml.urdf.xacro"
MACRO_ONLY = HERE / "fixtures" / "xacro" / "macro_only.urdf.xacro"
LEGACY = HERE / "fixtures" / "legacy" / "old"
LEGACY_TOP = LEGACY / "robot_pkg" / "urdf" / "robot.urdf.xacro"
CORPUS = HERE / "corpus"
D435 = CORPUS / "realsense2_description" / "urdf" / "test_d435_camera.urdf.xacro"

PLAIN = [
    [str(MATH)],
    [str(MATH), "-o", "out.urdf"],
    [str(MATH), "--output=out.urdf", "--legacy=on"],
    ["-o", "-", str(MATH), "use_wheels:=false"],
    [str(MATH), "--deps"],
    ["--resolve-uris", str(D435), "--package-path", str(CORPUS), "-o", "-"],
    ["-p", "a=b", "--package", "c=d=e", str(MATH), "--allow-path", "/tmp", "--no-env", "--unsafe-eval"],
    ["--max-macro-calls", "1", str(MATH)],
    ["--max-elements=5", "--max-input-bytes", "007", str(MATH)],
    ["{LEG}", "--legacy", "off"],
    ["{LEG}", "--legacy", "off", "--allow-errors", "-o", "out.urdf"],
    ["{LEG}", "-o", "out.urdf"],
    [str(LEGACY_TOP), "--package-path", str(LEGACY)],
    [str(MACRO_ONLY), "-o", "out.urdf"],
    ["no_such_file.xacro"],
    [str(MATH), "-o", "."],
    [str(MATH), "-o", ""],
    ["", "-o", "out.urdf"],
]
NEEDS_CLICK = [
    ["--help"],
    ["-h"],
    [str(MATH), "--help"],
    ["-p", "no_equals_sign", str(MATH)],
    [str(MATH), str(MACRO_ONLY)],
    ["--legacy", "maybe", str(MATH)],
    ["--max-elements", "0", str(MATH)],
    ["--max-elements", "-3", str(MATH)],
    ["--max-elements", "1e3", str(MATH)],
    ["--bogus", str(MATH)],
    [str(MATH), "-o"],
    ["-oout.urdf", str(MATH)],
    ["--deps=1", str(MATH)],
    ["--", str(MATH)],
    ["-", "-o", "out.urdf"],
    [str(MATH), "-o", "--deps"],
]


@pytest.mark.parametrize("argv", PLAIN, ids=lambda a: " ".join(Path(x).name if "/" in x else x for x in a))
def test_parse_plain_reads_what_click_reads(argv):
    values = parse_plain(argv, INPUT_OPTS + BUILD_OPTS)
    assert values is not None
    ctx = build_cmd.make_context("build", list(argv))
    assert values == ctx.params


@pytest.mark.parametrize("argv", NEEDS_CLICK, ids=" ".join)
def test_unusual_command_lines_go_to_click(argv):
    assert fast_build(argv) is None


# Electric-era syntax: upgraded by default (X001), left and reported (X002, exit 1) with --legacy off
LEG_TEXT = '<robot name="r">\n<macro name="leg"><link name="leg"/></macro>\n<link name="base"/>\n<leg/>\n</robot>\n'


def _run(path: str, argv, cwd: Path):
    leg = cwd / "leg.urdf.xacro"
    leg.write_text(LEG_TEXT)
    argv = [str(leg) if a == "{LEG}" else a for a in argv]
    code = f"import sys; from myrabot_desc.{path} import main; sys.exit(main())"
    p = subprocess.run([sys.executable, "-c", code, "build", *argv], cwd=cwd, capture_output=True, timeout=120)
    out = cwd / "out.urdf"
    return p.returncode, p.stdout.replace(str(cwd).encode(), b"CWD"), p.stderr.replace(str(cwd).encode(), b"CWD"), \
        out.read_bytes().replace(str(cwd).encode(), b"CWD") if out.is_file() else None


@pytest.mark.parametrize("argv", PLAIN + NEEDS_CLICK, ids=lambda a: " ".join(Path(x).name if "/" in x else x for x in a))
def test_same_result_on_both_paths(argv, tmp_path):
    (tmp_path / "fast").mkdir()
    (tmp_path / "click").mkdir()
    fast = _run("commands.entry", argv, tmp_path / "fast")            # the console script's entry
    slow = _run("commands.main", argv, tmp_path / "click")             # the click group, always
    assert fast == slow
    assert b"Traceback" not in fast[2]


def test_outcomes_are_the_expected_ones(tmp_path):
    """Not only equal on both paths: right (so the parity above cannot hold by both failing)."""
    rc, out, err, written = _run("commands.entry", [str(MATH), "-o", "out.urdf"], tmp_path)
    assert (rc, err) == (0, b"wrote out.urdf\n") and written.count(b"<link ") == 4
    rc, out, err, _ = _run("commands.entry", ["{LEG}", "--legacy", "off"], tmp_path)
    assert rc == 1 and b"error: X002" in err and err.endswith(b"nothing written (use --allow-errors to write anyway)\n")
    rc, out, err, _ = _run("commands.entry", ["--max-macro-calls", "1", str(MATH)], tmp_path)
    assert rc == 2 and b"over 1 macro calls" in err and out == b""
    rc, out, err, _ = _run("commands.entry", ["--legacy", "maybe", str(MATH)], tmp_path)
    assert rc == 2 and b"Invalid value for '--legacy'" in err


def test_a_plain_build_imports_no_click_lxml_yaml(tmp_path):
    code = ("import sys; from myrabot_desc.commands.entry import main; code = main(); "
            "heavy = ['click', 'lxml', 'yaml.reader', 'dataclasses', 'typing', 'inspect']; "
            "print([m for m in heavy if m in sys.modules], file=sys.stderr); sys.exit(code)")
    argv = ["build", str(D435), "--package-path", str(CORPUS), "-o", str(tmp_path / "d435.urdf")]
    p = subprocess.run([sys.executable, "-c", code, *argv], capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    assert p.stderr.splitlines()[-1] == "[]"
    assert (tmp_path / "d435.urdf").read_text().count("<link ") == 3
    # a file that calls load_yaml loads PyYAML (through our loader) and still builds
    argv = ["build", str(MATH), "-o", str(tmp_path / "math.urdf")]
    p = subprocess.run([sys.executable, "-c", code, *argv], capture_output=True, text=True, timeout=120)
    assert p.returncode == 0 and p.stderr.splitlines()[-1] == "['yaml.reader']", p.stderr


def test_display_is_remembered_per_working_folder_and_bounded(tmp_path, monkeypatch):
    """safety.display (every location a build records) is remembered, but per working folder,
    and the memory stays bounded in a long-lived process."""
    import os

    from myrabot_desc import safety

    f = tmp_path / "pkg" / "r.urdf"
    f.parent.mkdir()
    f.write_text("<robot name='r'/>")
    (tmp_path / "link").symlink_to(tmp_path / "pkg")
    monkeypatch.chdir(tmp_path)
    assert safety.display(f) == safety.display("pkg/r.urdf") == os.path.join("pkg", "r.urdf")
    assert safety.display("link/r.urdf") == os.path.join("pkg", "r.urdf")     # symlinks resolved
    monkeypatch.chdir(tmp_path / "pkg")
    assert safety.display(f) == "r.urdf"
    other = tmp_path / "other"
    other.mkdir()
    monkeypatch.chdir(other)
    assert safety.display(f) == str(f.resolve())        # outside the working folder: absolute
    for i in range(5000):
        safety.display(f"x{i}.urdf")
    assert len(safety._DISPLAYED) <= 4096


def test_build_help_loads_neither_the_build_engine_nor_the_model():
    """`build --help` (and a command line only click takes) costs click and the option tables: the
    expansion and the model load when a build runs (start-up, bench/bench_start.py)."""
    code = ("import sys, contextlib, io\nfrom myrabot_desc.commands.entry import main\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n    try:\n        main(['build', '--help'])\n"
            "    except SystemExit:\n        pass\n"
            "print([m for m in ('myrabot_desc.commands.fastbuild', 'myrabot_desc.expand.driver', 'myrabot_desc.model',"
            " 'xacro', 'lxml') if m in sys.modules])")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert p.returncode == 0 and p.stdout.strip() == "[]", p.stdout + p.stderr
