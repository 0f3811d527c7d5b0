"""``convert`` refuses what ``check`` calls an error in what it converts, and the smaller items of
this round: M001 and friends give one answer for a path outside the roots whether or not it exists,
$(optenv) values stay out of reports, a failing output leaves nothing, -o onto a FIFO does not
block, MuJoCo writes no MUJOCO_LOG.TXT, YAML values Python cannot construct and a mesh scale render
cannot draw are file:line errors.
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).parent))
from limited import run, within_budget, write  # noqa: E402

from helpers import BAD  # noqa: E402

ARM = """<robot name="r">
<link name="base"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
<link name="arm">{arm}</link>
<joint name="j" type="{type}"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""
INERTIAL = '<inertial><mass value="{m}"/><inertia ixx="{ixx}" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>'
CASES = {
    "revolut": (ARM.format(arm=INERTIAL.format(m=1, ixx=0.1), type="revolut"), "T016"),
    "mass_nan": (ARM.format(arm=INERTIAL.format(m="nan", ixx=0.1), type="revolute"), "T010"),
    "mass_inf": (ARM.format(arm=INERTIAL.format(m="inf", ixx=0.1), type="revolute"), "T010"),
    "mass_1e400": (ARM.format(arm=INERTIAL.format(m="1e400", ixx=0.1), type="revolute"), "T010"),
    "negative_moment": (ARM.format(arm=INERTIAL.format(m=1, ixx=-0.1), type="revolute"), "I004"),
    "intertia": (ARM.format(arm=INERTIAL.format(m=1, ixx=0.1).replace("<inertia ", "<intertia "), type="revolute"),
                 "no <inertia> element (it has <intertia>"),
    "garbage_collision": (ARM.format(arm=INERTIAL.format(m=1, ixx=0.1) + '<collision><geometry><mesh '
                                     'filename="junk.stl"/></geometry></collision>', type="revolute"), "junk.stl"),
}


@pytest.mark.parametrize("case", sorted(CASES))
@pytest.mark.parametrize("target", ["sdf", "world", "mjcf"])
def test_convert_refuses_what_check_calls_an_error(tmp_path, case, target):
    text, why = CASES[case]
    f = write(tmp_path / f"{case}.urdf", text)
    write(tmp_path / "junk.stl", "garbage " * 30)
    out = tmp_path / "out" / ("m.xml" if target == "mjcf" else "m.sdf")
    check = run(["check", "--isolated", f], cwd=tmp_path)
    assert check.code == 1, check.stdout                       # check calls it an error...
    r = run(["convert", "--to", target, f, "-o", out], cwd=tmp_path)
    assert not within_budget(r), within_budget(r)
    assert r.code == 2 and f"{case}.urdf:" in r.stderr and why in r.stderr, r.stderr      # ...so convert refuses
    assert not (tmp_path / "out").exists()
    report = tmp_path / "report.json"
    r = run(["convert", "--to", target, f, "-o", out, "--allow-errors", "--report", report], cwd=tmp_path)
    if target == "mjcf" and r.code == 2:          # MuJoCo itself cannot take some (a joint type 'revolut')
        assert "MuJoCo rejected the model" in r.stderr and not (tmp_path / "out").exists(), r.stderr
        return
    assert r.code == 0 and out.stat().st_size > 0, r.stderr
    entries = json.loads(report.read_text())
    listed = json.dumps(entries)
    assert "--allow-errors" in listed and (why.split(" (")[0] in listed or why in r.stderr), listed[:2000]


def test_check_reports_an_unreadable_collision_mesh_as_an_error(tmp_path):
    write(tmp_path / "junk.stl", "garbage " * 30)
    f = write(tmp_path / "g.urdf", CASES["garbage_collision"][0])
    r = run(["check", "--isolated", "--format", "json", f], cwd=tmp_path)
    d = [x for x in json.loads(r.stdout)["files"][0]["diagnostics"] if x["code"] == "M005"]
    assert r.code == 1 and d and d[0]["severity"] == "error" and d[0]["line"] == 3


def test_a_suppressed_finding_does_not_stop_convert(tmp_path):
    text = CASES["negative_moment"][0].replace('<link name="arm">', '<!-- myrabot-desc: ignore[I004] reviewed -->\n'
                                                                       '<link name="arm">')
    f = write(tmp_path / "s.urdf", text)
    r = run(["convert", f, "-o", tmp_path / "s.sdf"], cwd=tmp_path)
    assert r.code == 0, r.stderr


# ------------------------------------------------------------------ paths outside the roots
@pytest.mark.parametrize("command", [["check", "--isolated"], ["convert", "-o", "{tmp}/o.sdf"]])
def test_a_path_outside_the_roots_gets_one_answer_whether_it_exists_or_not(tmp_path, command):
    real = write(tmp_path / "elsewhere" / "exists.stl", "solid x\nendsolid x\n")
    outputs = []
    for target in (real, tmp_path / "elsewhere" / "missing.stl"):
        # (the model's roots: its folder and the one above it)
        f = write(tmp_path / "a" / "pkg" / "r.urdf", f'<robot name="r"><link name="b"><collision><geometry><mesh '
                  f'filename="{target}"/></geometry></collision></link></robot>\n')
        r = run([a.replace("{tmp}", str(tmp_path)) for a in command] + [f], cwd=tmp_path)
        outputs.append((r.code, (r.stdout + r.stderr).replace(str(target), "PATH")))
    assert outputs[0] == outputs[1], outputs
    assert "outside the allowed folders" in outputs[0][1]


def test_includes_and_yaml_outside_the_roots_get_one_answer(tmp_path):
    write(tmp_path / "elsewhere" / "exists.xacro", "<robot/>")
    outs = []
    for name in ("exists", "missing"):
        f = write(tmp_path / "pkg" / "r.urdf.xacro", f'<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                  f'<xacro:include filename="{tmp_path}/elsewhere/{name}.xacro"/></robot>\n')
        r = run(["build", f], cwd=tmp_path)
        outs.append((r.code, r.stderr.replace(name, "NAME")))
    assert outs[0] == outs[1] and outs[0][0] == 2 and "X006" in outs[0][1]


# ------------------------------------------------------------------ environment values
def test_optenv_values_stay_out_of_reports(tmp_path):
    f = write(tmp_path / "e.urdf.xacro", '<robot name="e" xmlns:xacro="http://www.ros.org/wiki/xacro">'
              '<xacro:property name="t" value="$(optenv CI_TOKEN_FOR_TEST none)"/><link name="l${len(t)}"/></robot>\n')
    for fmt in ("text", "json", "github", "sarif"):
        r = run(["check", "--isolated", "--format", fmt, f], cwd=tmp_path, env={"CI_TOKEN_FOR_TEST": "tok-12345"})
        assert "CI_TOKEN_FOR_TEST" in r.stdout and "tok-12345" not in r.stdout + r.stderr, fmt


# ------------------------------------------------------------------ outputs
def test_a_failing_output_leaves_no_other_output(tmp_path):
    if not os.path.exists("/dev/full"):
        pytest.skip("no /dev/full")
    r = run(["sim", "vuelta", "--plot", "p.png", "--csv", "/dev/full"], cwd=tmp_path)
    assert r.code == 2 and "/dev/full" in r.stderr and not (tmp_path / "p.png").exists()
    assert list(tmp_path.iterdir()) == []


def test_output_onto_a_fifo_nobody_reads_is_refused_without_blocking(tmp_path):
    os.mkfifo(tmp_path / "fifo")
    r = run(["build", "-o", tmp_path / "fifo"], cwd=tmp_path, timeout=30)
    assert r.code == 2 and "FIFO" in r.stderr and r.wall < 30


def test_mujoco_writes_no_log_into_the_working_folder(tmp_path):
    r = run(["convert", "--to", "mjcf", "--allow-errors", BAD / "numbers/mass_huge.urdf", "-o", tmp_path / "o" / "m.xml"],
            cwd=tmp_path)
    assert r.code == 0, r.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["o"]
    assert "WARNING" not in r.stdout


# ------------------------------------------------------------------ YAML values, mesh scale
@pytest.mark.parametrize("value, words", [("1" + "0" * 5000, "5001 digits"), ("2024-13-45", "month must be in 1..12")])
def test_yaml_values_python_cannot_construct_are_file_line_errors(tmp_path, value, words):
    layout = (BAD.parent.parent / "layouts" / "escoja.yaml").read_text()
    write(tmp_path / "l.yaml", layout.replace("x: 0.55", f"x: {value}", 1))
    line = layout[:layout.index("x: 0.55")].count("\n") + 1
    r = run(["sim", "escoja", "--layout", tmp_path / "l.yaml"], cwd=tmp_path)
    assert r.code == 2 and f"l.yaml:{line}: error: not valid YAML" in r.stderr and words in r.stderr, r.stderr
    write(tmp_path / "pose.yaml", f"joints:\n  base: {value}\n")
    r = run(["render", "--pose", tmp_path / "pose.yaml", "--size", "128x128", "-o", tmp_path / "r.png"], cwd=tmp_path)
    if "not installed" in r.stderr:
        pytest.skip(r.stderr)
    assert r.code == 2 and "pose.yaml:2: error: not valid YAML" in r.stderr, r.stderr


def test_a_mesh_scale_render_cannot_draw_is_a_file_line_error(tmp_path):
    write(tmp_path / "m" / "cube.stl", (BAD / "meshes" / "meshes" / "cube.stl").read_bytes())
    f = write(tmp_path / "tiny.urdf", '<robot name="r">\n<link name="base"><collision><geometry>'
              '<mesh filename="m/cube.stl" scale="5e-324 5e-324 5e-324"/></geometry></collision></link>\n</robot>\n')
    r = run(["render", "--collision", f, "--size", "128x128", "-o", tmp_path / "r.png"], cwd=tmp_path)
    if "not installed" in r.stderr:
        pytest.skip(r.stderr)
    assert r.code == 2 and "tiny.urdf:2: error: mesh m/cube.stl of link 'base' has scale" in r.stderr, r.stderr
    assert not (tmp_path / "r.png").exists()
