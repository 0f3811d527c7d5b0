"""check --fix / --unsafe-fixes / --diff: repairs written where the values are, proven first.

The wander_bot of seed B is repaired in a copy and then drives as commanded; every corpus robot
with a real fixable error is repaired in a copy of its real sources, the real xacro CLI still
builds them, and the build differs from the unfixed one only in what the fixes touched.
"""

from __future__ import annotations

import difflib
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from helpers import CORPUS, FIXTURES, SHIM, WANDER, corpus_robot, invoke
from myrabot_desc.checks import CheckOptions
from myrabot_desc.fix.run import fix_model

XACRO = Path(sys.executable).parent / "xacro"
CLI = [str(Path(sys.executable).parent / "myrabot-desc")]


def _codes(report: dict) -> list[str]:
    return sorted(d["code"] for f in report["files"] for d in f["diagnostics"])


@pytest.fixture
def wander(tmp_path):
    dest = tmp_path / "wander_bot"
    shutil.copytree(WANDER, dest)
    return dest


def _run(*args, cwd):
    return subprocess.run([*CLI, *map(str, args)], capture_output=True, text=True, cwd=cwd, timeout=300)


# ---------------------------------------------------------------- seed B's wander_bot
def test_wander_bot_fixed_then_drives_as_commanded(wander):
    before = json.loads(_run("check", "--inertia", "--format", "json", "urdf/robot.xacro", cwd=wander).stdout)
    fixed = _run("check", "--fix", "--unsafe-fixes", "--inertia", "urdf/robot.xacro", cwd=wander)
    assert fixed.returncode == 0                             # P001 (no caster): a caster added (unsafe)
    assert "Fixed 12 findings (3 remaining)." in fixed.stderr
    after = json.loads(_run("check", "--inertia", "--format", "json", "urdf/robot.xacro", cwd=wander).stdout)
    gone = {"G001", "G002", "G007", "G012", "I005", "I006", "I007", "P001", "P002", "T006"}
    assert gone <= set(_codes(before)) and not gone & set(_codes(after))
    assert _codes(after) == ["G014", "P004", "T007"]
    drive = _run("sim", "drive", "urdf/robot.xacro", "--json", cwd=wander)
    verdict = json.loads(drive.stdout)
    ratios = {c["name"]: c["value"] for c in verdict["checks"]}
    assert verdict["passed"] and ratios == {"speed ratio": 1.0, "turn-rate ratio": 1.0}     # shipped: 0.8 and 1.33


def test_wander_bot_diff_touches_only_the_values(wander):
    r = _run("check", "--diff", "--unsafe-fixes", "--inertia", "urdf/robot.xacro", cwd=wander)
    assert r.returncode == 1
    removed = [ln[1:].strip() for ln in r.stdout.splitlines() if ln.startswith("-") and not ln.startswith("---")]
    added = [ln[1:].strip() for ln in r.stdout.splitlines() if ln.startswith("+") and not ln.startswith("+++")]
    placeholder = '<inertia ixx="1.0" ixy="0" ixz="0" iyy="1.0" iyz="0" izz="1.0"/>'
    assert removed == ["<alwaysOn>true</alwaysOn>", "<torque>10</torque>",               # G007: read by no one
                       "<wheelSeparation>0.4</wheelSeparation>", "<wheelDiameter>0.2</wheelDiameter>",
                       '<box size="0.3 0.24 0.1" rpy="0 0 0"/>', placeholder,
                       '<origin xyz="0 0 0.03" rpy="0 0 0"/>',                        # base_footprint_fixed
                       placeholder, placeholder, '<inertia ixx="1.0" ixy="0" ixz="0" iyy="10.0" iyz="0" izz="1.0"/>']
    assert added == ["<wheelSeparation>0.3</wheelSeparation>", "<wheelDiameter>0.16</wheelDiameter>",
                     '<box size="0.3 0.24 0.1"/>',
                     '<inertia ixx="0.006042" ixy="0" ixz="0" iyy="0.008333" iyz="0" izz="0.01271"/>',
                     '<link name="caster_link">',                                      # P001: a caster behind
                     '<visual><geometry><sphere radius="0.02"/></geometry></visual>',  # the axle, on the ground
                     '<collision><geometry><sphere radius="0.02"/></geometry></collision>',
                     '</link>', '<joint name="caster_joint" type="fixed">', '<parent link="base_link"/>',
                     '<child link="caster_link"/>', '<origin xyz="-0.1 0 -0.06" rpy="0 0 0"/>', '</joint>',
                     '<origin xyz="0 0 0.08" rpy="0 0 0"/>',                          # 50 mm up: wheels on z 0
                     '<inertia ixx="0.001808" ixy="0" ixz="0" iyy="0.0032" iyz="0" izz="0.001808"/>',
                     '<inertia ixx="0.001808" ixy="0" ixz="0" iyy="0.0032" iyz="0" izz="0.001808"/>',
                     '<inertia ixx="0.0005146" ixy="0" ixz="0" iyy="0.0005146" iyz="0" izz="0.0006125"/>']
    assert r.stderr.strip() == "Would fix 12 findings (3 remaining)."
    assert (wander / "urdf" / "robot.xacro").read_bytes() == (WANDER / "urdf" / "robot.xacro").read_bytes()


def test_safe_fixes_alone_and_idempotent(wander):
    first = invoke("check", "--fix", wander / "urdf" / "robot.xacro")
    assert "Fixed 5 findings" in first.stderr and "7 more with --unsafe-fixes" in first.stderr
    snapshot = {p: p.read_bytes() for p in (wander / "urdf").iterdir()}
    again = invoke("check", "--fix", wander / "urdf" / "robot.xacro")
    assert "Fixed 0 findings" in again.stderr
    assert {p: p.read_bytes() for p in (wander / "urdf").iterdir()} == snapshot
    nothing = invoke("check", "--diff", wander / "urdf" / "robot.xacro")
    assert nothing.exit_code == 0 and nothing.stdout == ""


# ---------------------------------------------------------------- what the edit keeps
def test_formatting_kept_crlf_comments_quotes_and_attribute_order(tmp_path):
    src = (b'<?xml version="1.0"?>\r\n<!-- a comment -->\r\n<robot name=\'r\'>\r\n'
           b"  <link name='base'>\r\n    <collision><geometry><box size='0.3 0.25 0.1'/></geometry></collision>\r\n"
           b"    <inertial>  <!-- keep me -->\r\n      <mass value='1.0'/>\r\n"
           b"      <inertia izz='1e0'   iyy='1.0' ixx='1.0' ixy='0' ixz='0' iyz='0'/>\r\n    </inertial>\r\n"
           b"  </link>\r\n</robot>\r\n")
    f = tmp_path / "r.urdf"
    f.write_bytes(src)
    r = invoke("check", "--fix", "--unsafe-fixes", f)
    assert "Fixed 1 finding " in r.stderr
    out = f.read_bytes()
    assert out == src.replace(b"izz='1e0'   iyy='1.0' ixx='1.0'", b"izz='1.271e-02'   iyy='0.008333' ixx='0.006042'")


def test_all_or_nothing_when_one_file_cannot_be_written(wander, monkeypatch):
    """Two files to fix (robot.xacro and robot.gazebo); staging the second fails: neither changes."""
    import myrabot_desc.output as out

    real_open, calls = os.open, []

    def failing_open(path, flags, mode=0o777, *a, **k):
        if str(path).endswith(".tmp"):
            calls.append(path)
            if len(calls) == 2:
                raise OSError(28, "No space left on device")
        return real_open(path, flags, mode, *a, **k)

    monkeypatch.setattr(out.os, "open", failing_open)
    before = {p: p.read_bytes() for p in (wander / "urdf").iterdir()}
    r = invoke("check", "--fix", wander / "urdf" / "robot.xacro")
    assert r.exit_code == 2 and "No space left on device" in r.output
    assert len(calls) == 2
    assert {p: p.read_bytes() for p in (wander / "urdf").iterdir()} == before
    assert not [p for p in (wander / "urdf").iterdir() if p.name.endswith(".tmp")]


def test_a_file_changed_meanwhile_is_not_overwritten(wander):
    from myrabot_desc.fix.run import fix_tasks
    from myrabot_desc.fix.write import write_fixed
    from myrabot_desc.checks.run import Task
    from myrabot_desc.errors import InputError

    task = Task(str(wander / "urdf" / "robot.xacro"), {}, CheckOptions(), (), (), (), False, None)
    run = fix_tasks([task], unsafe=False)
    gazebo = wander / "urdf" / "robot.gazebo"
    gazebo.write_bytes(gazebo.read_bytes() + b"<!-- edited meanwhile -->\n")
    with pytest.raises(InputError, match="changed while it was being fixed"):
        write_fixed(run.files)
    assert b"<wheelSeparation>0.4<" in gazebo.read_bytes()


# ---------------------------------------------------------------- where the value came from
def _copy_corpus(tmp_path) -> Path:
    dest = tmp_path / "corpus"
    shutil.copytree(CORPUS, dest)
    return dest


def _fix_corpus(root: Path, robot: dict, unsafe=True, **kw):
    args = dict(a.split(":=", 1) for a in robot.get("args", "").split())
    return fix_model(root / robot["top"], dict(mappings=args, package_paths=[root / robot.get("package_path", ".")]),
                     CheckOptions(inertia=True), unsafe=unsafe, writable=[root], **kw)


def test_value_computed_by_an_expression_is_reported_not_edited(tmp_path):
    """rotors' firefly: the rotor inertia is `${0.0833333 * mass * (y*y + z*z)}`."""
    root = _copy_corpus(tmp_path)
    res = _fix_corpus(root, corpus_robot("firefly"))
    computed = [n for n in res.not_fixed if n.code == "I006"]
    assert computed and all("is computed by ${" in n.reason and n.where is not None for n in computed)
    n = computed[0]
    assert n.where.file.endswith("multirotor_base.xacro") and "0.0833333 * mass" in n.where.text
    assert "should come to" in n.reason
    assert not any(f.name.endswith("multirotor_base.xacro") for f in res.files)


def test_property_used_in_several_places_is_an_unsafe_definition_edit(tmp_path):
    """jackal's real `dummy_inertia` property makes imu_link's ixx, iyy and izz; planted: a 1 cm cube
    collision on imu_link, so that I006 wants 1.667e-08 for all three."""
    root = _copy_corpus(tmp_path)
    top = root / "jackal_description" / "urdf" / "jackal.urdf.xacro"
    text = top.read_text()
    text = text.replace('<link name="imu_link">\n    <inertial>',
                        '<link name="imu_link">\n    <collision><geometry><box size="0.01 0.01 0.01"/></geometry>'
                        '</collision>\n    <inertial>', 1)
    top.write_text(text)
    robot = corpus_robot("jackal")
    safe = _fix_corpus(root, robot, unsafe=False)
    left = [c for c in safe.unsafe if c.code == "I006" and "imu_link" in c.message]
    assert len(left) == 1 and not [c for c in safe.applied if "imu_link" in c.message]
    (ch,) = left
    assert any("edits property dummy_inertia at tests" in n or "edits property dummy_inertia" in n for n in ch.notes)
    assert any("makes 3 values" in n for n in ch.notes)
    fixed = _fix_corpus(root, robot, unsafe=True)
    (f,) = [f for f in fixed.files if f.name.endswith("jackal.urdf.xacro")]
    assert b'<xacro:property name="dummy_inertia" value="1.66667e-08"/>' in f.new or \
        b'<xacro:property name="dummy_inertia" value="1.667e-08"/>' in f.new
    assert not [d for d in fixed.after if d.code == "I006" and "imu_link" in d.message]


# ---------------------------------------------------------------- the corpus, in copies of its real sources
FIXABLE = ["irb2400", "lrmate200id", "create_2", "pioneer3at", "pr2", "pmb2", "robotiq_2f_85", "firefly"]
TAGS = {"I001": {"inertial", "/inertial", "mass", "inertia", "origin"}, "I004": {"inertia"}, "I005": {"inertia"},
        "I006": {"inertia"}}


def _xacro(root: Path, robot: dict) -> str:
    env = dict(os.environ, PYTHONPATH=str(SHIM), CORPUS_PACKAGE_PATH=str(root / robot.get("package_path", ".")))
    p = subprocess.run([str(XACRO), str(root / robot["top"]), *robot.get("args", "").split()],
                       capture_output=True, text=True, env=env, timeout=120)
    assert p.returncode == 0, p.stderr[-2000:]
    return p.stdout


@pytest.mark.corpus
@pytest.mark.parametrize("robot_id", FIXABLE)
def test_corpus_errors_fixed_in_the_real_sources(robot_id, tmp_path):
    robot = corpus_robot(robot_id)
    root = _copy_corpus(tmp_path)
    unfixed = _xacro(root, robot)
    res = _fix_corpus(root, robot)
    errors_before = {d.code for d in res.before if d.severity == "error"}
    fixed_codes = {c.code for c in res.applied}
    assert errors_before & fixed_codes, (errors_before, fixed_codes)
    new_errors = {d.code for d in res.after if d.severity == "error"} - errors_before
    assert not new_errors
    assert not {d.code for d in res.after} & {c.code for c in res.applied if c.code.startswith("G")}
    for f in res.files:
        f.path.write_bytes(f.new)
    fixed = _xacro(root, robot)
    allowed = set().union(*(TAGS.get(c, {"*"}) for c in fixed_codes))
    changed = [ln for ln in difflib.unified_diff(unfixed.splitlines(), fixed.splitlines(), lineterm="", n=0)
               if ln[:1] in "+-" and not ln.startswith(("+++", "---"))]
    assert changed
    tags = {m.group(1) for ln in changed for m in [re.match(r"[+-]\s*<(/?[\w:]+)", ln)] if m}
    assert "*" in allowed or tags <= allowed, (tags, allowed, changed[:6])


# ---------------------------------------------------------------- every rule's documented fix
def _rules_with_fix():
    from myrabot_desc.checks.registry import load_all

    return [c for c, r in load_all().items() if r.fix.availability != "never"]


def test_every_fix_is_documented_with_its_safety():
    from myrabot_desc.checks.registry import load_all

    for code, r in load_all().items():
        f = r.fix
        assert f.availability in ("always", "sometimes", "never"), code
        if f.availability != "never":
            assert f.safety in ("safe", "unsafe") and len(f.how) > 60, code
    assert set(_rules_with_fix()) >= {"I001", "I004", "I005", "I006", "G001", "G002", "G007", "G013",
                                      "T005", "T006", "T016", "S003", "P002"}
    text = (Path(__file__).resolve().parents[2] / "docs" / "rules.md").read_text()
    assert text.count("**`--fix`:** ") == len(load_all())


# 'sometimes' fixes whose example is a case the fix leaves alone, and where the fix is tested instead
ELSEWHERE = {"I004": "pmb2 (corpus)", "P002": "wander_bot"}


@pytest.mark.parametrize("code", _rules_with_fix())
def test_fix_repairs_the_rules_own_example(code, tmp_path, monkeypatch):
    """The fix applied to the rule's `bad` example leaves no finding of that code (the example of a
    'sometimes' fix is one the fix applies to)."""
    from myrabot_desc.checks.registry import load_all
    from myrabot_desc.checks.rule import document

    ex = load_all()[code].example
    monkeypatch.chdir(tmp_path)
    for name, text in ex.files.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text)
    f = tmp_path / ex.filename
    f.write_text(document(ex.bad))
    opts = CheckOptions(inertia="inertia" in ex.options, meshes="meshes" in ex.options)
    res = fix_model(f, options=opts, unsafe=True)
    if code in ELSEWHERE:              # a 'sometimes' fix whose example is a case it leaves alone
        assert load_all()[code].fix.availability == "sometimes" and not res.files
        return
    assert [c for c in res.applied if c.code == code], (res.not_fixed, res.refused)
    assert not [d for d in res.after if d.code == code]
    for ff in res.files:
        ff.path.write_bytes(ff.new)
    again = fix_model(f, options=opts, unsafe=True)
    assert not again.applied and not again.files          # idempotent


def test_lazy_fix_is_built_once_when_read_and_gives_the_eager_edits(tmp_path):
    """I006's fix is made only when --fix/--diff reads it, and it is the Fix the rule made eagerly."""
    from myrabot_desc.checks import check_robot
    from myrabot_desc.checks.inertia_geometry import tensor_fix
    from myrabot_desc.checks.registry import load_all
    from myrabot_desc.checks.rule import Fix, LazyFix, SetValue, document
    from myrabot_desc.model.loader import load_robot

    made = []

    def build(part, value):
        made.append(value)
        return Fix((SetValue(part, "mass", value),), "unsafe", "mass")

    lazy = LazyFix(build, "p", 2.0)
    assert not made
    assert (lazy.edits, lazy.safety, lazy.title) == ((SetValue("p", "mass", 2.0),), "unsafe", "mass")
    assert lazy.get() is lazy.get() and made == [2.0]

    f = tmp_path / "robot.urdf"
    f.write_text(document(load_all()["I006"].example.bad))
    robot = load_robot(f)
    _diags, ctx = check_robot(robot)
    [(d, fix)] = [(d, fx) for d, fx in ctx.fixes if d.code == "I006"]
    assert isinstance(fix, LazyFix)
    eager = tensor_fix(robot.links["chassis"].inertial, d.data["computed_tensor"],
                       "inertia of chassis from its collision geometry")
    assert fix.get() == eager and (fix.edits, fix.safety, fix.title) == (eager.edits, eager.safety, eager.title)
