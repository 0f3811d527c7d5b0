"""`myrabot-desc check` as CI uses it: formats, selection, exit codes, several files and folders."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

from click.testing import CliRunner

from helpers import ROOT, FIXTURES
from myrabot_desc.commands.main import main

FIX = FIXTURES
WANDER = FIX / "wander_bot" / "urdf" / "robot.xacro"
SEED = FIX / "seed_myrabot"
SEED_URDF_DIR = SEED / "myrabot_fer_modelo" / "urdf"


def invoke(*args):
    return CliRunner().invoke(main, ["check", *map(str, args)])


def test_text_grouped_by_severity_with_summary():
    res = invoke(WANDER)
    assert res.exit_code == 1
    out = res.output
    assert out.index("errors (") < out.index("warnings (") < out.index("info (")
    assert out.rstrip().splitlines()[-1].startswith("4 errors, ") and out.rstrip().endswith("in 1 file")
    assert "\x1b[" not in out                                     # no colour when not on a terminal


def test_a_terminal_gets_the_styled_report_and_a_pipe_the_same_text_plain():
    """The report is styled for a terminal only; through a pipe it is made plain (not styled and
    stripped) and is the terminal's text without its styles."""
    import os

    from myrabot_desc.commands.console import unstyle

    cmd = [sys.executable, "-m", "myrabot_desc", "check", "--no-cache", str(WANDER)]
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    master, slave = os.openpty()
    p = subprocess.Popen(cmd, stdout=slave, stderr=subprocess.DEVNULL, stdin=subprocess.DEVNULL, cwd=ROOT, env=env)
    os.close(slave)
    chunks = []
    while True:
        try:
            chunk = os.read(master, 65536)
        except OSError:                 # EIO: the child closed the terminal
            break
        if not chunk:
            break
        chunks.append(chunk)
    os.close(master)
    assert p.wait(timeout=120) == 1
    styled = b"".join(chunks).decode().replace("\r\n", "\n")
    piped = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT, env=env, timeout=120)
    assert "\x1b[1m" in styled and "\x1b[" not in piped.stdout
    assert unstyle(styled) == piped.stdout and "4 errors, " in piped.stdout


def test_json_schema_is_stable():
    res = invoke(WANDER, "--format", "json")
    doc = json.loads(res.stdout)
    assert set(doc) == {"schema", "tool", "summary", "files"}
    assert doc["summary"] == {"files": 1, "failed": 0, "errors": 4, "warnings": doc["summary"]["warnings"],
                              "info": doc["summary"]["info"]}
    f = doc["files"][0]
    assert set(f) == {"file", "robot", "links", "joints", "status", "failure", "counts", "diagnostics", "suggestions"}
    assert f["status"] == "errors" and f["robot"] == "mobile_robot"
    d = f["diagnostics"][0]
    assert set(d) == {"code", "severity", "rule", "message", "file", "line", "data"}
    # deterministic: same bytes twice
    assert invoke(WANDER, "--format", "json").stdout == res.stdout


def test_github_annotations():
    res = invoke(WANDER, "--format", "github")
    lines = res.stdout.splitlines()
    g1 = next(l for l in lines if "G001" in l)
    assert g1.startswith("::error file=tests/fixtures/wander_bot/urdf/robot.gazebo,line=4,title=G001 drive-wheel-separation::")
    assert any(l.startswith("::warning file=") for l in lines)
    assert any(l.startswith("::notice ") for l in lines)


def test_sarif_2_1_0(tmp_path):
    out = tmp_path / "check.sarif"
    res = invoke(WANDER, "--format", "sarif", "-o", out)
    assert res.exit_code == 1 and res.stdout == ""
    doc = json.loads(out.read_text())
    assert doc["version"] == "2.1.0"
    run = doc["runs"][0]
    ids = [r["id"] for r in run["tool"]["driver"]["rules"]]
    assert ids == sorted(ids) and {"T001", "I005", "G001", "P001", "X002"} <= set(ids)
    r = next(x for x in run["results"] if x["ruleId"] == "I005")
    assert r["level"] == "error" and ids[r["ruleIndex"]] == "I005"
    loc = r["locations"][0]["physicalLocation"]
    assert loc["artifactLocation"]["uri"] == "tests/fixtures/wander_bot/urdf/robot.xacro"
    assert loc["region"]["startLine"] == 112


def test_select_ignore_strict():
    doc = json.loads(invoke(WANDER, "--format", "json", "--select", "G,P001").stdout)
    assert {d["code"] for d in doc["files"][0]["diagnostics"]} <= {"G001", "G002", "G007", "G012", "G014", "P001"}
    res = invoke(WANDER, "--select", "T")                         # only warnings left: exit 0 ...
    assert res.exit_code == 0
    assert invoke(WANDER, "--select", "T", "--strict").exit_code == 1   # ... unless --strict
    doc = json.loads(invoke(WANDER, "--format", "json", "--ignore", "I,P,G").stdout)
    assert not [d for d in doc["files"][0]["diagnostics"] if d["code"][0] in "IPG"]


def test_folder_lints_top_level_models_only():
    doc = json.loads(invoke(SEED_URDF_DIR, "--package-path", SEED, "--format", "json", "--select", "X").stdout)
    names = [Path(f["file"]).name for f in doc["files"]]
    # roomba.xacro, kinect.xacro, ... are included by myrabot.urdf.xacro; ultrasonidos.xacro is not
    assert names == ["myrabot.urdf.xacro", "ultrasonidos.xacro"]
    sonar = doc["files"][1]["diagnostics"]
    assert "X003" in [d["code"] for d in sonar]                   # a macro-only file


def test_recursive_finds_every_model_of_a_tree(tmp_path):
    """-r: the seed's three packages in one call; the parts that the top-level files include
    are left out (brazo.xacro too: myrabot.urdf.xacro includes it from the other package),
    hidden and build folders are skipped; without -r a folder holding only folders is a usage
    error that points at -r."""
    import shutil

    tree = tmp_path / "ws"
    shutil.copytree(SEED, tree / "src")
    shutil.copytree(SEED, tree / "build" / "src")                  # a build tree: skipped
    shutil.copytree(SEED, tree / ".hidden" / "src")
    res = invoke(tree, "-r", "--package-path", tree / "src", "--format", "json", "--select", "X")
    files = sorted(Path(f["file"]).relative_to(tree).as_posix() for f in json.loads(res.stdout)["files"])
    assert files == ["src/myrabot_fer_modelo/urdf/myrabot.urdf.xacro",
                     "src/myrabot_fer_modelo/urdf/ultrasonidos.xacro",
                     "src/objetos_fer_modelos/urdf/lata_cerveza.xacro",
                     "src/objetos_fer_modelos/urdf/lata_cola.xacro",
                     "src/objetos_fer_modelos/urdf/mesa.xacro"]
    res = invoke(tree)
    assert res.exit_code == 2 and "no .urdf or .xacro model files in this folder (-r looks in its subfolders" \
        in res.output


def test_unprocessable_file_is_exit_2_one_line_others_still_checked(tmp_path):
    bad = tmp_path / "broken.urdf"
    bad.write_text("<robot name='x'><link name='a'></robot>")
    res = invoke(bad, WANDER, "--format", "json")
    assert res.exit_code == 2
    doc = json.loads(res.stdout)
    assert [f["status"] for f in doc["files"]] == ["failed", "errors"]
    err = [l for l in res.stderr.splitlines() if l]
    assert len(err) == 1 and "broken.urdf" in err[0] and "Traceback" not in res.output
    text = invoke(bad)
    assert text.exit_code == 2 and "Traceback" not in text.output


def test_missing_file_exit_2(tmp_path):
    res = invoke(tmp_path / "nope.urdf")
    assert res.exit_code == 2 and "no such file" in res.output


def test_list_rules_and_help():
    res = invoke("--list-rules")
    assert res.exit_code == 0 and "I005  error    inertia-triangle" in res.output
    h = invoke("--help")
    assert "Examples:" in h.output and "--format github" in h.output


def test_no_trimesh_without_inertia():
    code = ("import sys; from click.testing import CliRunner; from myrabot_desc.commands.main import main;"
            f"r = CliRunner().invoke(main, ['check', {str(WANDER)!r}]);"
            "print(r.exit_code, 'trimesh' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split()
    assert out == ["1", "False"]


def test_docs_rules_md_documents_every_rule_and_is_current():
    from myrabot_desc.checks.docs import render
    from myrabot_desc.checks.registry import EXTERNAL, load_all

    text = (ROOT / "docs" / "rules.md").read_text()
    assert text == render(), "regenerate: python -m myrabot_desc.checks.docs > docs/rules.md"
    for code in [*load_all(), *EXTERNAL]:
        assert f"### {code}\n" in text
        assert "**Example.**" in text.split(f"### {code}\n", 1)[1].split("\n### ", 1)[0], code


def test_report_colours_are_click_styles():
    """checks/report writes its ANSI styles itself (no click below the command layer): the same
    bytes click.style writes, so a terminal shows what it showed."""
    import click

    from myrabot_desc.checks.report import STYLE, style

    for kw in [*STYLE.values(), dict(bold=True), dict(fg="green")]:
        assert style("P004 text", **kw) == click.style("P004 text", **kw)
