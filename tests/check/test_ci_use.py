"""check as CI users live with it (issue 16): configuration, inline suppressions, unknown codes,
annotations and SARIF (validated against the OASIS 2.1.0 schema), workers and shards, progress,
the result cache, X007, and the pre-commit hook in a scratch repository."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from helpers import ROOT, DATA
from myrabot_desc.commands.main import main

SCHEMA = DATA / "sarif-schema-2.1.0.json"
CLI = [str(Path(sys.executable).parent / "myrabot-desc")]

PARTS = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="block" params="name">
    {comment}
    <link name="${{name}}">
      <inertial>
        <mass value="0.01"/>
        <inertia ixx="1.7e-5" iyy="1.7e-5" izz="1.7e-5" ixy="0" ixz="0" iyz="0"/>
      </inertial>
      <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
    </link>
  </xacro:macro>
</robot>
"""
ROBOT = """<?xml version="1.0"?>
<robot name="blocks" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="parts.xacro"/>
  <xacro:block name="a"/>
  <xacro:block name="b"/>
  <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>
</robot>
"""
# A plain URDF with one light link (I008 at line 3) and one heavy link.
URDF = """<?xml version="1.0"?>
<robot name="{name}">
  <link name="light"><inertial><mass value="0.01"/><inertia ixx="1.7e-5" iyy="1.7e-5" izz="1.7e-5" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
</robot>
"""


@pytest.fixture(autouse=True)
def _isolated_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("MYRABOT_DESC_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))        # the user's key lives there


def blocks(folder: Path, comment: str = "") -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "parts.xacro").write_text(PARTS.format(comment=comment))
    (folder / "robot.urdf.xacro").write_text(ROBOT)
    return folder / "robot.urdf.xacro"


def run(*args, cwd=None):
    old = os.getcwd()
    if cwd:
        os.chdir(cwd)
    try:
        return CliRunner().invoke(main, ["check", *map(str, args)])
    finally:
        os.chdir(old)


def codes(res) -> list[str]:
    doc = json.loads(res.stdout)
    return [d["code"] for f in doc["files"] for d in f["diagnostics"]]


# ---------------------------------------------------------------- configuration
def test_nearest_configuration_wins_and_per_file_ignores(tmp_path):
    (tmp_path / "pyproject.toml").write_text('[project]\nname = "x"\n\n[tool.myrabot-desc]\nignore = ["P004"]\n'
                                             'per-file-ignores = { "b/*.urdf" = ["I008"] }\n')
    for sub in ("a", "b", "c"):
        (tmp_path / sub).mkdir()
        (tmp_path / sub / "r.urdf").write_text(URDF.format(name=sub))
    # c has its own configuration: it wins over the pyproject above (P004 comes back)
    (tmp_path / "c" / "myrabot-desc.toml").write_text('select = ["P", "I"]\n')
    res = run("a/r.urdf", "b/r.urdf", "c/r.urdf", "--format", "json", cwd=tmp_path)
    doc = json.loads(res.stdout)
    got = {f["file"]: sorted({d["code"] for d in f["diagnostics"]}) for f in doc["files"]}
    assert got == {"a/r.urdf": ["I008"], "b/r.urdf": [], "c/r.urdf": ["I008", "P004"]}
    # --isolated reads none; --config uses one file for all
    res = run("a/r.urdf", "b/r.urdf", "--isolated", "--format", "json", cwd=tmp_path)
    assert sorted(codes(res)) == ["I008", "I008", "P004", "P004"]
    res = run("a/r.urdf", "b/r.urdf", "--config", "c/myrabot-desc.toml", "--format", "json", cwd=tmp_path)
    assert sorted(codes(res)) == ["I008", "I008", "P004", "P004"]


def test_configuration_options_and_args(tmp_path):
    model = tmp_path / "m.urdf.xacro"
    model.write_text('<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                     '  <xacro:arg name="mass" default="0.01"/>\n'
                     '  <link name="l"><inertial><mass value="$(arg mass)"/><inertia ixx="1.7e-5" iyy="1.7e-5" '
                     'izz="1.7e-5" ixy="0" ixz="0" iyz="0"/></inertial>\n'
                     '    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>\n</robot>\n')
    (tmp_path / "myrabot-desc.toml").write_text('select = ["I008"]\nstrict = true\n')
    res = run(model.name, cwd=tmp_path)
    assert res.exit_code == 1 and "I008" in res.output       # strict from the configuration
    # xacro args per file: 0.6 kg in a litre is a plausible density, the warning goes
    (tmp_path / "myrabot-desc.toml").write_text('select = ["I008"]\nstrict = true\n[args."*.urdf.xacro"]\nmass = 0.6\n')
    res = run(model.name, cwd=tmp_path)
    assert res.exit_code == 0, res.output


def test_unknown_configuration_key_is_an_error_at_its_line(tmp_path):
    (tmp_path / "r.urdf").write_text(URDF.format(name="r"))
    (tmp_path / "pyproject.toml").write_text('[project]\nname = "x"\n\n[tool.myrabot-desc]\nselect = ["I"]\n'
                                             'per-file-ignore = { "*.urdf" = ["I008"] }\n')
    res = run("r.urdf", cwd=tmp_path)
    assert res.exit_code == 2
    assert "pyproject.toml:6: error: unknown configuration key 'per-file-ignore'; did you mean " \
           "'per-file-ignores'?" in res.output
    (tmp_path / "pyproject.toml").write_text('[tool.myrabot-desc]\nignore = ["I08"]\n')
    res = run("r.urdf", cwd=tmp_path)
    assert res.exit_code == 2 and "pyproject.toml:2: error: ignore: unknown rule code 'I08'" in res.output
    (tmp_path / "pyproject.toml").write_text('[tool.myrabot-desc.limits]\nmax-mesh-byte = 10\n')
    res = run("r.urdf", cwd=tmp_path)
    assert res.exit_code == 2 and "pyproject.toml:2: error: unknown limit 'max-mesh-byte'; did you mean " \
                                  "'max-mesh-bytes'?" in res.output


def test_a_pyproject_that_does_not_name_us_is_not_parsed(tmp_path):
    """Walking up from a model, a project's pyproject.toml that cannot hold our table (it lists
    myrabot-desc as a dependency only) is passed over unparsed (no TOML parser is imported for it), so
    even one that is not valid TOML is no error; one that names our table still is, at its line, and
    a myrabot-desc.toml is always read."""
    (tmp_path / "r.urdf").write_text(URDF.format(name="r"))
    alone = run("r.urdf", "--isolated", cwd=tmp_path)
    (tmp_path / "pyproject.toml").write_text('[project]\nname = "x"\ndependencies = ["myrabot-desc"]\nversion = \n'
                                             '[project.scripts]\nmyrabot-desc = "x:y"\n')
    res = run("r.urdf", cwd=tmp_path)
    assert (res.exit_code, res.output) == (alone.exit_code, alone.output) and "I008" in res.output
    code = ("import sys; from myrabot_desc.commands.entry import main; code = main(); "
            "print('tomllib' in sys.modules or 'tomli' in sys.modules, file=sys.stderr); sys.exit(code)")
    p = subprocess.run([sys.executable, "-c", code, "check", "--no-cache", "r.urdf"], cwd=tmp_path,
                       capture_output=True, text=True, timeout=120, stdin=subprocess.DEVNULL)
    assert p.returncode == alone.exit_code and p.stderr.splitlines()[-1] == "False", p.stderr[-2000:]
    (tmp_path / "pyproject.toml").write_text('[project]\nname = "x"\nversion = \n\n[tool.myrabot-desc]\n')
    res = run("r.urdf", cwd=tmp_path)
    assert res.exit_code == 2 and "pyproject.toml:3: error: invalid TOML" in res.output, res.output
    (tmp_path / "pyproject.toml").unlink()
    (tmp_path / "myrabot-desc.toml").write_text('select = \n')
    res = run("r.urdf", cwd=tmp_path)
    assert res.exit_code == 2 and "myrabot-desc.toml:1: error: invalid TOML" in res.output, res.output


@pytest.mark.parametrize("text,ours", [
    ("[tool.myrabot-desc]", True), ('  [ tool . "myrabot-desc" ]', True), ("['tool'.'myrabot-desc']", True),
    ("[tool.myrabot-desc.per-file-ignores]", True), ("[tool]\nmyrabot-desc = {}", True),
    ('tool.myrabot-desc.select = ["I"]', True), ("tool = {myrabot-desc = {}}", True),
    ('"tool".myrabot-desc = {}', True), ("[[tool.myrabot-desc]]", True),
    ('[project]\nname = "myrabot-desc"', False), ('[project.scripts]\nmyrabot-desc = "a:b"', False),
    ('dependencies = ["myrabot-desc>=1"]', False), ('[tool.hatch]\nx = "myrabot-desc"', False),
    ("[tool.myrabot-descx]", False), ("tools.myrabot-desc = 1", False), ('[tool."myrabot-desc2"]', False)])
def test_which_pyproject_can_hold_our_table(text, ours):
    """Every way TOML can open [tool.myrabot-desc] is read; a project naming us elsewhere is not."""
    from myrabot_desc.checks.config import _OUR_TABLE

    assert bool(_OUR_TABLE.search(text)) is ours


@pytest.mark.parametrize("flag,value,hint", [("--select", "Z999", None), ("--ignore", "I0088", "I008"),
                                             ("--select", "G,Q", None)])
def test_unknown_code_exits_2_with_did_you_mean(flag, value, hint):
    res = run(flag, value)
    assert res.exit_code == 2
    assert "unknown rule code" in res.output
    if hint:
        assert f"did you mean '{hint}'?" in res.output


# ---------------------------------------------------------------- suppressions
def test_suppression_in_a_macro_applies_to_every_expansion_and_children(tmp_path):
    robot = blocks(tmp_path / "pkg")
    res = run(robot, "--format", "json", cwd=tmp_path)
    assert codes(res).count("I008") == 2                    # links a and b, both from parts.xacro:6
    # the comment before <link> covers the link and its <inertial> child (where I008 points)
    robot = blocks(tmp_path / "pkg", "<!-- myrabot-desc: ignore[I008] foam: light on purpose -->")
    res = run(robot, "--format", "json", cwd=tmp_path)
    assert "I008" not in codes(res) and "X009" not in codes(res)


def test_suppression_on_an_enclosing_element_and_file_level(tmp_path):
    folder = tmp_path / "pkg"
    robot = blocks(folder)
    text = PARTS.format(comment="").replace('  <xacro:macro name="block"',
                                            '  <!-- myrabot-desc: ignore[I] whole macro -->\n'
                                            '  <xacro:macro name="block"')
    (folder / "parts.xacro").write_text(text)
    res = run(robot, "--format", "json", cwd=tmp_path)
    assert "I008" not in codes(res) and "X009" not in codes(res)
    # file level, in a plain URDF
    urdf = tmp_path / "r.urdf"
    urdf.write_text(URDF.format(name="r").replace("</robot>", "  <!-- myrabot-desc: ignore-file[I008,P004] -->\n</robot>"))
    res = run(urdf, "--format", "json", cwd=tmp_path)
    assert codes(res) == []


def test_unused_suppression_is_reported(tmp_path):
    robot = blocks(tmp_path / "pkg", "<!-- myrabot-desc: ignore[I008,S005] -->")
    res = run(robot, "--format", "json", cwd=tmp_path)
    doc = json.loads(res.stdout)
    x009 = [d for d in doc["files"][0]["diagnostics"] if d["code"] == "X009"]
    assert len(x009) == 1 and x009[0]["file"] == "pkg/parts.xacro" and x009[0]["line"] == 4
    assert "ignore[S005]" in x009[0]["message"] and "I008" not in x009[0]["message"]
    # a code the run does not check is not "unused"; an unknown code always is reported
    res = run(robot, "--format", "json", "--ignore", "S", cwd=tmp_path)
    assert "X009" not in codes(res)
    blocks(tmp_path / "pkg", "<!-- myrabot-desc: ignore[I008,Q123] -->")
    res = run(robot, "--format", "json", cwd=tmp_path)
    assert "X009" in codes(res) and "unknown rule code 'Q123'" in res.stdout


@pytest.mark.parametrize("name", ["robot.urdf.xacro", "r.urdf"])
def test_suppressions_are_read_from_the_bytes_the_model_was_built_from(tmp_path, name):
    """The comments are looked for in what the findings come from (the build's bytes, a URDF's own),
    not read from disk again: an edit after the load changes neither the findings nor what silences
    them."""
    from myrabot_desc.checks import check_robot
    from myrabot_desc.model.loader import load_robot

    comment = "<!-- myrabot-desc: ignore[I008] foam -->"
    if name == "r.urdf":
        (tmp_path / name).write_text(URDF.format(name="r").replace("  <link", f"  {comment}\n  <link"))
        edited = tmp_path / name
    else:
        blocks(tmp_path, comment)
        edited = tmp_path / "parts.xacro"
    robot = load_robot(tmp_path / name)
    assert any(b"myrabot-desc: ignore[I008]" in data for data in robot.source_data().values())
    edited.write_text("not even XML")
    diags, ctx = check_robot(robot)
    assert "I008" not in [d.code for d in diags] and ctx.suppressions_used


# ---------------------------------------------------------------- annotations and SARIF
def _bad_and_good(tmp_path) -> list[Path]:
    (tmp_path / "bad.urdf").write_text('<?xml version="1.0"?>\n<robot name="x">\n  <link name="a">\n</robot>\n')
    (tmp_path / "good.urdf").write_text(URDF.format(name="good"))
    return [tmp_path / "bad.urdf", tmp_path / "good.urdf"]


def test_github_annotations_always_name_the_file(tmp_path):
    files = _bad_and_good(tmp_path)
    res = run(*[f.name for f in files], "--format", "github", cwd=tmp_path)
    assert res.exit_code == 2
    lines = [ln for ln in res.stdout.splitlines() if ln.startswith("::")]
    assert lines[0].startswith("::error file=bad.urdf,line=4,title=X000 input-unprocessable::")
    assert all("file=" in ln for ln in lines)
    assert any(ln.startswith("::warning file=good.urdf,line=3,title=I008") for ln in lines)


def test_sarif_is_valid_with_invocations_and_artifacts(tmp_path):
    jsonschema = pytest.importorskip("jsonschema")
    files = _bad_and_good(tmp_path)
    res = run(*[f.name for f in files], "--format", "sarif", cwd=tmp_path)
    doc = json.loads(res.stdout)
    schema = json.loads(SCHEMA.read_text())
    jsonschema.validate(doc, schema, cls=jsonschema.Draft4Validator)
    run0 = doc["runs"][0]
    inv = run0["invocations"][0]
    assert inv["exitCode"] == 2 and inv["executionSuccessful"] is False
    note = inv["toolExecutionNotifications"][0]
    assert note["descriptor"]["id"] == "X000"
    assert note["locations"][0]["physicalLocation"]["artifactLocation"]["uri"] == "bad.urdf"
    uris = [a["location"]["uri"] for a in run0["artifacts"]]
    assert uris == ["bad.urdf", "good.urdf"]
    for r in run0["results"]:
        art = r["locations"][0]["physicalLocation"]["artifactLocation"]
        assert uris[art["index"]] == art["uri"]
    assert all("helpUri" not in rule for rule in run0["tool"]["driver"]["rules"])   # no unchecked links
    # with a base URL from the configuration: links to the rule's heading
    (tmp_path / "myrabot-desc.toml").write_text('help-url = "https://example.org/docs/rules.md"\n')
    res = run("good.urdf", "--format", "sarif", cwd=tmp_path)
    rules = json.loads(res.stdout)["runs"][0]["tool"]["driver"]["rules"]
    assert {r["id"]: r["helpUri"] for r in rules}["I008"] == "https://example.org/docs/rules.md#i008"


def test_sarif_lists_suppressed_findings_with_their_suppression(tmp_path):
    """A finding silenced by an inline comment is in the SARIF report with ``suppressions`` (code
    scanning shows it dismissed), not left out; the text report still leaves it out. Rule texts have
    no docstring indentation."""
    jsonschema = pytest.importorskip("jsonschema")
    robot = blocks(tmp_path / "pkg", "<!-- myrabot-desc: ignore[I008] foam: light on purpose -->")
    for extra in ([], ["-j", "2"]):
        res = run(robot, "--format", "sarif", *extra, cwd=tmp_path)
        doc = json.loads(res.stdout)
        jsonschema.validate(doc, json.loads(SCHEMA.read_text()), cls=jsonschema.Draft4Validator)
        results = doc["runs"][0]["results"]
        i008 = [r for r in results if r["ruleId"] == "I008"]
        assert len(i008) == 2                                   # links a and b, both silenced
        for r in i008:
            (sup,) = r["suppressions"]
            assert sup["kind"] == "inSource" and sup["status"] == "accepted"
            assert sup["justification"] == "myrabot-desc: ignore[I008] at pkg/parts.xacro:4"
            assert sup["location"]["physicalLocation"]["region"] == {"startLine": 4}
        assert all("suppressions" not in r for r in results if r["ruleId"] != "I008")
        assert res.exit_code == 0
    assert "I008" not in run(robot, cwd=tmp_path).stdout
    rules = {r["id"]: r for r in doc["runs"][0]["tool"]["driver"]["rules"]}
    text = rules["G001"]["fullDescription"]["text"]
    assert "\n    " not in text and "\nThe plugin turns a twist" in text
    assert all("\n    " not in r["fullDescription"]["text"] for r in rules.values())


# ---------------------------------------------------------------- workers, shards, merge
def _many(tmp_path, n=7) -> Path:
    for i in range(n):
        d = tmp_path / "robots" / f"r{i}"
        d.mkdir(parents=True)
        (d / "r.urdf").write_text(URDF.format(name=f"r{i}").replace('0.01', f"0.0{i + 1}"))
    blocks(tmp_path / "robots" / "blocks", "<!-- myrabot-desc: ignore[I008,S005] -->")
    (tmp_path / "robots" / "broken.urdf").write_text("<robot")
    return tmp_path / "robots"


@pytest.mark.parametrize("fmt", ["text", "json", "sarif"])
def test_two_workers_give_the_same_bytes_as_one(tmp_path, fmt):
    _many(tmp_path)
    outs = []
    for jobs in ("1", "2"):
        p = subprocess.run(CLI + ["check", "-r", "robots", "-j", jobs, "--format", fmt, "--no-cache"], cwd=tmp_path,
                           capture_output=True)
        assert p.returncode == 2
        outs.append((p.stdout, p.stderr))
    assert outs[0] == outs[1]
    assert b"r6" in outs[0][0] and b"broken.urdf" in outs[0][0]


def test_shards_partition_the_files_and_merge(tmp_path):
    jsonschema = pytest.importorskip("jsonschema")
    _many(tmp_path)
    full = json.loads(run("-r", "robots", "--format", "json", cwd=tmp_path).stdout)
    every = [f["file"] for f in full["files"]]
    assert len(every) == 9
    parts = []
    for k in (1, 2, 3):
        res = run("-r", "robots", "--shard", f"{k}/3", "--format", "json", cwd=tmp_path)
        parts.append([f["file"] for f in json.loads(res.stdout)["files"]])
        res = run("-r", "robots", "--shard", f"{k}/3", "--format", "sarif", "-o", f"part{k}.sarif", cwd=tmp_path)
    assert sorted(sum(parts, [])) == sorted(every)
    assert all(not set(a) & set(b) for i, a in enumerate(parts) for b in parts[i + 1:])
    assert [len(p) for p in parts] == [3, 3, 3]
    assert run("-r", "robots", "--shard", "4/3").exit_code == 2
    # the merged shards hold exactly the unsharded results
    run("-r", "robots", "--format", "sarif", "-o", "all.sarif", cwd=tmp_path)
    res = run("--merge-sarif", "part1.sarif", "part2.sarif", "part3.sarif", "-o", "merged.sarif", cwd=tmp_path)
    assert res.exit_code == 0, res.output
    merged = json.loads((tmp_path / "merged.sarif").read_text())
    whole = json.loads((tmp_path / "all.sarif").read_text())
    jsonschema.validate(merged, json.loads(SCHEMA.read_text()), cls=jsonschema.Draft4Validator)

    def key(doc):
        run0 = doc["runs"][0]
        uris = [a["location"]["uri"] for a in run0["artifacts"]]
        out = []
        for r in run0["results"]:
            art = r["locations"][0]["physicalLocation"]["artifactLocation"]
            assert uris[art.pop("index")] == art["uri"]      # indexes differ, what they point at not
            out.append(json.dumps(r, sort_keys=True))
        return sorted(out)

    assert key(merged) == key(whole)
    assert len(merged["runs"][0]["invocations"]) == 3


def test_progress_on_a_terminal_even_with_output_to_a_file(tmp_path):
    import pty

    _many(tmp_path)
    for quiet in (False, True):
        master, slave = pty.openpty()
        p = subprocess.Popen(CLI + ["check", "-r", "robots", "--format", "json", "-o", "report.json", "-j", "1"]
                             + (["--quiet"] if quiet else []), cwd=tmp_path, stdout=subprocess.DEVNULL,
                             stderr=slave, stdin=subprocess.DEVNULL)
        os.close(slave)
        chunks = []
        while True:
            try:
                data = os.read(master, 4096)
            except OSError:
                break
            if not data:
                break
            chunks.append(data)
        p.wait()
        os.close(master)
        err = b"".join(chunks).decode(errors="replace")
        assert p.returncode == 2
        assert ("checking" in err) is not quiet
        assert json.loads((tmp_path / "report.json").read_text())["summary"]["files"] == 9


# ---------------------------------------------------------------- cache
def test_cache_gives_the_same_report_and_sees_an_edited_include(tmp_path):
    robot = blocks(tmp_path / "pkg")
    first = run(robot, "--format", "json", cwd=tmp_path)
    entries = list((tmp_path / "cache" / "check").glob("*.json"))
    assert len(entries) == 1
    second = run(robot, "--format", "json", cwd=tmp_path)
    assert first.stdout == second.stdout and codes(first).count("I008") == 2
    blocks(tmp_path / "pkg", "<!-- myrabot-desc: ignore[I008] -->")     # only the included file changes
    third = run(robot, "--format", "json", cwd=tmp_path)
    assert "I008" not in codes(third)
    assert len(list((tmp_path / "cache" / "check").glob("*.json"))) == 1   # one entry per file and options


def test_no_configuration_no_cache_written(tmp_path, monkeypatch):
    monkeypatch.delenv("MYRABOT_DESC_CACHE_DIR")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    user = tmp_path / "xdg" / "myrabot-desc" / "check"
    blocks(tmp_path / "pkg")
    run("pkg/robot.urdf.xacro", cwd=tmp_path)
    assert not user.exists() and not list(tmp_path.rglob(".myrabot-desc-cache"))
    (tmp_path / "pyproject.toml").write_text("[tool.myrabot-desc]\n")       # a project opts in
    run("pkg/robot.urdf.xacro", cwd=tmp_path)
    # entries go to the user's cache folder, never into the repository (unless --cache-dir says so)
    assert len(list(user.glob("*.json"))) == 1 and not list(tmp_path.rglob(".myrabot-desc-cache"))
    run("pkg/robot.urdf.xacro", "--cache-dir", ".myrabot-desc-cache", cwd=tmp_path)
    assert (tmp_path / ".myrabot-desc-cache" / ".gitignore").read_text().endswith("*\n")
    (tmp_path / "pyproject.toml").write_text("[tool.myrabot-desc]\ncache = false\n")
    shutil.rmtree(user)
    run("pkg/robot.urdf.xacro", cwd=tmp_path)
    assert not user.exists()


# ---------------------------------------------------------------- X007
def test_x007_lists_environment_variables_and_values(tmp_path, monkeypatch):
    model = tmp_path / "e.urdf.xacro"
    model.write_text('<?xml version="1.0"?>\n<robot name="e" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                     '  <link name="$(env LINT_TEST_BASE)"/>\n  <link name="$(optenv LINT_TEST_UNSET tool)"/>\n'
                     '  <joint name="j" type="fixed"><parent link="$(env LINT_TEST_BASE)"/><child link="tool"/>'
                     '</joint>\n</robot>\n')
    monkeypatch.setenv("LINT_TEST_BASE", "chassis")
    monkeypatch.delenv("LINT_TEST_UNSET", raising=False)
    res = run(model, "--format", "json", "--select", "X007", cwd=tmp_path)
    d = json.loads(res.stdout)["files"][0]["diagnostics"]
    assert [x["code"] for x in d] == ["X007"] and d[0]["severity"] == "info"
    # a value from the environment is never printed by default (a model could print a CI secret); the
    # default an unset $(optenv) fell back to is the file's own text
    assert d[0]["data"]["environment"] == {"LINT_TEST_BASE": None, "LINT_TEST_UNSET": "tool"}
    assert "chassis" not in res.stdout
    assert "LINT_TEST_BASE (set)" in d[0]["message"] and "LINT_TEST_UNSET='tool' (unset: default)" in d[0]["message"]
    monkeypatch.setenv("MYRABOT_DESC_SHOW_ENV_VALUES", "1")          # the runner may ask for them
    res = run(model, "--format", "json", "--select", "X007", cwd=tmp_path)
    assert json.loads(res.stdout)["files"][0]["diagnostics"][0]["data"]["environment"]["LINT_TEST_BASE"] == "chassis"
    # the cache notices a changed variable
    monkeypatch.setenv("LINT_TEST_BASE", "base")
    res = run(model, "--format", "json", "--select", "X007", cwd=tmp_path)
    assert json.loads(res.stdout)["files"][0]["diagnostics"][0]["data"]["environment"]["LINT_TEST_BASE"] == "base"


def test_x007_summarises_many_variables(tmp_path, monkeypatch):
    """A base like Husky reads ~90 $(optenv): the set ones and the unset ones are named (eight of
    each at most), and the JSON data has every variable (the defaults of the unset ones)."""
    names = [f"LINT_MANY_{i:02d}" for i in range(12)]
    links = "".join(f'  <link name="l{i}_$(optenv {n} d{i})"/>\n' for i, n in enumerate(names))
    model = tmp_path / "many.urdf.xacro"
    model.write_text('<?xml version="1.0"?>\n<robot name="m" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                     + links + "</robot>\n")
    for n in names:
        monkeypatch.delenv(n, raising=False)
    monkeypatch.setenv("LINT_MANY_03", "x")
    monkeypatch.setenv("LINT_MANY_07", "y")
    res = run(model, "--format", "json", "--select", "X007", cwd=tmp_path)
    d = json.loads(res.stdout)["files"][0]["diagnostics"][0]
    assert len(d["data"]["environment"]) == 12 and d["data"]["environment"]["LINT_MANY_11"] == "d11"
    assert ("12 variables, 2 set (LINT_MANY_03, LINT_MANY_07) and 10 unset, defaults used "
            "(LINT_MANY_00, LINT_MANY_01, LINT_MANY_02, LINT_MANY_04, LINT_MANY_05, LINT_MANY_06, LINT_MANY_08, "
            "LINT_MANY_09, and 2 more)") in d["message"]


# ---------------------------------------------------------------- pre-commit
@pytest.mark.slow
@pytest.mark.skipif(shutil.which("git") is None, reason="needs git")
def test_pre_commit_hook_in_a_scratch_repository(tmp_path):
    """The hook pinned by commit (``rev: <sha>``, as docs/check.md says: the repository has no tags)
    on a clone of this repository (pre-commit installs the core into its own environment) passes on
    a repository with a macro-only parts file and a suppressed finding, and fails (strict) when the
    suppression goes."""
    pc = Path(sys.executable).parent / "pre-commit"
    if not pc.exists():
        pytest.skip("pre-commit is not installed (pip install '.[test]')")
    env = {**os.environ, "PRE_COMMIT_HOME": str(tmp_path / "pc-home"), "GIT_AUTHOR_NAME": "t",
           "GIT_AUTHOR_EMAIL": "t@example.org", "GIT_COMMITTER_NAME": "t", "GIT_COMMITTER_EMAIL": "t@example.org"}
    env.pop("MYRABOT_DESC_CACHE_DIR", None)
    tool = tmp_path / "tool"
    subprocess.run(["git", "clone", "-q", str(ROOT), str(tool)], check=True, env=env)
    sha = subprocess.run(["git", "-C", str(tool), "rev-parse", "HEAD"], check=True, env=env, capture_output=True,
                         text=True).stdout.strip()
    repo = tmp_path / "repo"
    blocks(repo / "urdf", "<!-- myrabot-desc: ignore[I008] foam -->")
    (repo / "pyproject.toml").write_text('[tool.myrabot-desc]\nignore = ["P004"]\n')
    (repo / ".pre-commit-config.yaml").write_text(
        f"repos:\n  - repo: {tool}\n    rev: {sha}\n    hooks:\n      - id: myrabot-desc-check-strict\n")
    subprocess.run(["git", "init", "-q", str(repo)], check=True, env=env)
    subprocess.run(["git", "-C", str(repo), "add", "-A"], check=True, env=env)
    p = subprocess.run([str(pc), "run", "--all-files"], cwd=repo, env=env, capture_output=True, text=True)
    assert p.returncode == 0, p.stdout + p.stderr
    assert "Passed" in p.stdout
    # pre-commit installed the core only, and the tool names the commit it was pinned at
    hook_bin = next((tmp_path / "pc-home").glob("repo*/py_env-*/bin"))
    q = subprocess.run([str(hook_bin / "python"), "-c", "import importlib.util as u; "
                        "print([m for m in ('mujoco', 'viser', 'matplotlib', 'example_robot_data') if u.find_spec(m)])"],
                       capture_output=True, text=True, env=env)
    assert q.stdout.strip() == "[]", q.stdout + q.stderr
    q = subprocess.run([str(hook_bin / "myrabot-desc"), "--version"], capture_output=True, text=True, env=env)
    assert f"(commit {sha}; not a release)" in q.stdout, q.stdout + q.stderr
    blocks(repo / "urdf")                                # the suppression goes: I008 twice, strict fails
    subprocess.run(["git", "-C", str(repo), "add", "-A"], check=True, env=env)
    p = subprocess.run([str(pc), "run", "--all-files"], cwd=repo, env=env, capture_output=True, text=True)
    assert p.returncode == 1 and "Failed" in p.stdout
    assert "urdf/parts.xacro:6: I008 link a" in p.stdout


# ---------------------------------------------------------------- action, hooks, info
def test_action_check_step_runs_as_written(tmp_path):
    """The composite action's Check step, run by bash with the inputs it would get: annotations on
    stdout, a valid SARIF file, the exit code in GITHUB_OUTPUT."""
    import yaml

    action = yaml.safe_load((ROOT / "action.yml").read_text())
    assert action["runs"]["using"] == "composite"
    step = next(s for s in action["runs"]["steps"] if s.get("id") == "check")
    _many(tmp_path)
    out = tmp_path / "gh_output"
    env = {**os.environ, "MD_PATHS": "robots", "MD_ARGS": "--ignore P004", "MD_SHARD": "2/3",
           "MD_SARIF": "r.sarif", "GITHUB_OUTPUT": str(out),
           "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}"}
    p = subprocess.run(["bash", "-e", "-c", step["run"]], cwd=tmp_path, env=env, capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    assert out.read_text().strip() in ("exit-code=0", "exit-code=1", "exit-code=2")
    assert p.stdout.startswith("::") and "P004" not in p.stdout
    doc = json.loads((tmp_path / "r.sarif").read_text())
    assert doc["runs"][0]["invocations"][0]["properties"] == {"shard": "2/3"}
    assert len(doc["runs"][0]["artifacts"]) >= 3


def test_action_fix_step_writes_a_patch_that_applies(tmp_path):
    """The Action's Suggested fixes step on a copy of wander_bot: a patch that `git apply` takes, the
    same diff in the job summary, the work tree untouched; applied, the fixed codes are gone."""
    import yaml

    action = yaml.safe_load((ROOT / "action.yml").read_text())
    step = next(s for s in action["runs"]["steps"] if s.get("id") == "fix")
    shutil.copytree(ROOT / "tests/fixtures/wander_bot", tmp_path / "wander_bot")
    before = (tmp_path / "wander_bot/urdf/robot.gazebo").read_bytes()
    out, summary, temp = tmp_path / "gh_output", tmp_path / "summary.md", tmp_path / "runner"
    temp.mkdir()
    env = {**os.environ, "MD_PATHS": "wander_bot/urdf/robot.xacro", "MD_ARGS": "", "MD_FIX": "safe",
           "GITHUB_OUTPUT": str(out), "GITHUB_STEP_SUMMARY": str(summary), "RUNNER_TEMP": str(temp),
           "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}"}
    p = subprocess.run(["bash", "-e", "-c", step["run"]], cwd=tmp_path, env=env, capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    patch = temp / "myrabot-desc-fix.patch"
    assert out.read_text().strip() == f"fix-patch={patch}"
    assert (tmp_path / "wander_bot/urdf/robot.gazebo").read_bytes() == before
    text = patch.read_text()
    assert "+      <wheelSeparation>0.3</wheelSeparation>" in text and text in summary.read_text()
    subprocess.run(["git", "apply", "-p1", str(patch)], cwd=tmp_path, check=True)
    res = CliRunner().invoke(main, ["check", "--format", "json", str(tmp_path / "wander_bot/urdf/robot.xacro")])
    codes = {d["code"] for f in json.loads(res.output)["files"] for d in f["diagnostics"]}
    assert not codes & {"G001", "G002", "G007", "T006"}, codes


def test_pre_commit_hooks_are_valid():
    import yaml

    hooks = yaml.safe_load((ROOT / ".pre-commit-hooks.yaml").read_text())
    ids = {h["id"]: h for h in hooks}
    assert set(ids) == {"myrabot-desc-check", "myrabot-desc-check-strict", "myrabot-desc-fix"}
    assert ids["myrabot-desc-fix"]["entry"].split()[-1] == "--fix"
    for h in hooks:
        assert h["language"] == "python" and h["pass_filenames"] is False
        assert h["entry"].startswith("myrabot-desc check -r .")
        import re

        assert re.search(h["files"], "urdf/parts.xacro") and re.search(h["files"], "pyproject.toml")
        assert not re.search(h["files"], "src/main.py")


def test_info_says_continuous_once():
    res = CliRunner().invoke(main, ["info", "--no-tree"])
    assert res.exit_code == 0
    line = next(ln for ln in res.output.splitlines() if ln.strip().startswith("left_wheel_joint"))
    assert line.split()[1:] == ["continuous", "no", "position", "limits"]
