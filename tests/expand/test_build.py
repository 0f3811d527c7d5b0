"""build: xacro (modern and Electric-era) -> URDF without ROS."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner
from lxml import etree

from helpers import TESTS
from myrabot_desc.expand.driver import build_file
from myrabot_desc.commands.main import main
from myrabot_desc.errors import InputError

HERE = TESTS
FIX = HERE / "fixtures"
LEGACY = FIX / "legacy"
SEED = FIX / "seed_myrabot"
XFIX = FIX / "xacro"
ERD = Path(sys.prefix) / "lib" / f"python{sys.version_info.major}.{sys.version_info.minor}" / "site-packages" / \
    "cmeel.prefix" / "share" / "example-robot-data"


def body(text: str) -> str:
    """The URDF without xacro's banner comment (it names the source file)."""
    return "\n".join(line for line in text.splitlines() if not line.startswith("<!--"))


def run(*args, cwd=None):
    return CliRunner().invoke(main, list(args), catch_exceptions=False)


# ------------------------------------------------------------------ legacy upgrade
def test_legacy_files_build_to_the_same_urdf_as_modern_ones():
    old = build_file(LEGACY / "old/robot_pkg/urdf/robot.urdf.xacro", package_paths=[LEGACY / "old"])
    new = build_file(LEGACY / "new/robot_pkg/urdf/robot.urdf.xacro", package_paths=[LEGACY / "new"])
    assert body(old.text) == body(new.text)
    root = etree.fromstring(old.text.encode())
    assert [j.get("name") for j in root.findall("joint")] == ["base_joint", "arm_1_joint", "arm_2_joint"]
    # ${205/255} is true division, as in xacro's Electric evaluator (float arithmetic)
    assert root.find(".//color").get("rgba").startswith("0.8039215686")
    # the include inside a macro file worked: box_inertia expanded inside the arm
    assert float(root.find("link[@name='arm_1_link']/inertial/inertia").get("izz")) == pytest.approx(
        0.1 * (0.02 ** 2 + 0.02 ** 2) / 12)
    assert not new.diagnostics  # the modern files need no upgrade


def test_legacy_constructs_are_reported_once_per_kind_and_file_with_lines():
    res = build_file(LEGACY / "old/robot_pkg/urdf/robot.urdf.xacro", package_paths=[LEGACY / "old"])
    x001 = [d for d in res.diagnostics if d.code == "X001"]
    keys = [(d.loc.file, d.message.split(" upgraded")[0]) for d in x001]
    assert len(keys) == len(set(keys))
    top = {d.message.split(" upgraded")[0]: d.loc.line for d in x001 if d.loc.file.endswith("robot.urdf.xacro")}
    assert top == {"legacy <include>": 8, "legacy <property>": 11, "legacy bare macro call (<base>, <arm>)": 13}
    assert any("(2 times)" in d.message and d.loc.file.endswith("arm_macros.xacro") for d in x001)


def test_legacy_off_leaves_tags_and_reports_them_as_x002(tmp_path):
    f = tmp_path / "old.urdf.xacro"
    f.write_text('<robot name="r">\n<macro name="leg"><link name="leg"/></macro>\n<link name="base"/>\n'
                 '<leg/>\n</robot>\n')
    off = build_file(f, legacy="off")
    assert [(d.code, d.loc.line) for d in off.diagnostics] == [("X002", 2), ("X002", 4)]
    on = build_file(f)
    assert [d.code for d in on.diagnostics] == ["X001", "X001"]
    assert '<link name="leg"/>' in on.text


def test_a_tag_named_like_the_macro_it_sits_in_is_no_bare_call():
    """rosbot_xl's xacro:macro ``imu`` writes an SDF ``<imu>``: as a legacy call it would recurse
    (auto mode upgraded it and the build failed with xacro's "Unused block"); xacro copies it."""
    from helpers import CORPUS

    top = CORPUS / "rosbot_xl_description/urdf/rosbot_xl.urdf.xacro"
    if not top.is_file():
        pytest.skip("the real-robot corpus is not here")
    res = build_file(top, {"use_sim": "true", "simulation_engine": "ignition-gazebo", "lidar_model": "None",
                           "camera_model": "None"}, package_paths=[CORPUS])
    assert not [d for d in res.diagnostics if d.code == "X001"]
    assert "<imu>" in res.text and "<angular_velocity>" in res.text


def test_seed_assembly_builds_and_reports_the_missing_sonars_with_lines():
    res = build_file(SEED / "myrabot_fer_modelo/urdf/myrabot.urdf.xacro", package_paths=[SEED])
    x002 = [d for d in res.errors if d.code == "X002"]
    assert [d.loc.line for d in x002] == [45, 49, 53, 57, 61]
    assert all("ultrasonidos.xacro" in d.message for d in x002)
    root = etree.fromstring(res.text.encode())
    links = {link.get("name") for link in root.findall("link")}
    assert {"base_footprint", "camera_link", "e_webcam_optica_link", "hombro_link"} <= links
    assert not any(n.startswith("ultrasonidos") for n in links)
    # the un-prefixed M_PI property and <insert_block> of kinect.xacro were expanded
    rgb = root.find("joint[@name='camera_rgb_optical_joint']/origin")
    assert rgb.get("rpy") == "-1.570795 0 -1.570795"
    # package://myrabot_robot_model is the seed's second package name: reported, not fatal
    assert any(d.code == "X004" and "myrabot_robot_model" in d.message for d in res.diagnostics)


def test_build_cli_exit_1_and_nothing_written_on_x002(tmp_path):
    out = tmp_path / "seed.urdf"
    r = CliRunner().invoke(main, ["build", str(SEED / "myrabot_fer_modelo/urdf/myrabot.urdf.xacro"),
                                  "--package-path", str(SEED), "-o", str(out)])
    assert r.exit_code == 1
    assert "X002" in r.output and "myrabot.urdf.xacro:45" in r.output
    assert not out.exists()
    r = CliRunner().invoke(main, ["build", str(SEED / "myrabot_fer_modelo/urdf/myrabot.urdf.xacro"),
                                  "--package-path", str(SEED), "-o", str(out), "--allow-errors"])
    assert r.exit_code == 1 and out.exists()


def test_macro_only_file_warns_x003():
    res = build_file(XFIX / "macro_only.urdf.xacro")
    x003 = [d for d in res.diagnostics if d.code == "X003"]
    assert len(x003) == 1 and "2 macro(s) (caster, wheel)" in x003[0].message


# ------------------------------------------------------------------ packages
def test_example_robot_data_xacro_and_find_resolve(tmp_path):
    top = tmp_path / "quad.urdf.xacro"
    top.write_text("""<?xml version="1.0"?>
<robot name="quad" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(find example-robot-data)/robots/hector_description/robots/quadrotor_base.urdf.xacro"/>
  <xacro:quadrotor_base_macro/>
</robot>
""")
    res = build_file(top)
    root = etree.fromstring(res.text.encode())
    assert root.find("link[@name='base_link']") is not None
    assert "example-robot-data" in res.package_roots
    assert res.package_roots["example-robot-data"].samefile(ERD)
    # the shipped macro-only file itself builds, with X003
    alone = build_file(ERD / "robots/hector_description/robots/quadrotor_base.urdf.xacro")
    assert "X003" in [d.code for d in alone.diagnostics]


def test_include_of_a_package_uri_says_how_to_write_it():
    """example-robot-data's own hector quadrotor_base.xacro includes a package:// URI, which no
    xacro resolves (it joins it to the folder): the error says to use $(find)."""
    with pytest.raises(InputError) as e:
        build_file(ERD / "robots/hector_description/robots/quadrotor_base.xacro")
    msg = str(e.value)
    assert "quadrotor_base.xacro:3: error: include of package://example-robot-data/robots/" in msg
    assert "write $(find example-robot-data)/robots/hector_description/urdf/quadrotor_base.urdf.xacro" in msg


def test_explicit_package_mapping_wins_and_unknown_package_is_an_error(tmp_path):
    top = tmp_path / "r.urdf.xacro"
    top.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                   '<xacro:include filename="$(find nowhere_pkg)/urdf/x.xacro"/>\n</robot>\n')
    with pytest.raises(InputError) as e:
        build_file(top)
    assert "unknown package 'nowhere_pkg'" in str(e.value) and "r.urdf.xacro:2" in str(e.value)
    res = build_file(LEGACY / "new/robot_pkg/urdf/robot.urdf.xacro",
                     packages={"robot_pkg": str(LEGACY / "new/robot_pkg"),
                               "parts_pkg": str(LEGACY / "new/parts_pkg")})
    assert "arm_2_link" in res.text


# ------------------------------------------------------------------ safe expressions
ESCAPES = {
    "import": '<link name="${__import__(\'os\').system(\'true\')}"/>',
    "subclasses": '<link name="${\'\'.__class__.__base__.__subclasses__()}"/>',
    "format": '<xacro:property name="fmt" value="{0.__globals__[os]}"/><link name="${fmt.format(xacro.load_yaml)}"/>',
    "format_map": '<xacro:property name="fmt" value="{x}"/><link name="${fmt.format_map(dict(x=1))}"/>',
    "eval_open": '<link name="$(eval open(\'/etc/passwd\').read())"/>',
    "lambda_code": '<link name="${(lambda: 1).__code__}"/>',
    "pow_bomb": '<link name="${9**9**9}"/>',
    "redefined": '<xacro:property name="radians" value="${xacro.load_yaml}"/><link name="${radians(\'x.yaml\')}"/>',
}


@pytest.mark.parametrize("case", sorted(ESCAPES))
def test_code_injection_is_refused(tmp_path, case):
    f = tmp_path / "evil.urdf.xacro"
    f.write_text('<robot name="e" xmlns:xacro="http://www.ros.org/wiki/xacro">\n' + ESCAPES[case] + "\n</robot>\n")
    out = tmp_path / "out.urdf"
    r = CliRunner().invoke(main, ["build", str(f), "-o", str(out)])
    assert r.exit_code == 2, r.output
    assert "refused expression" in r.output and "evil.urdf.xacro:2" in r.output
    assert "Traceback" not in r.output
    assert not out.exists()


def test_unsafe_eval_turns_the_guard_off(tmp_path):
    f = tmp_path / "fmt.urdf.xacro"
    f.write_text('<robot name="e" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                 '<xacro:property name="fmt" value="{0}-x"/><link name="${fmt.format(1)}"/></robot>')
    assert build_file(f, unsafe_eval=True).text.count('name="1-x"') == 1
    with pytest.raises(InputError):
        build_file(f)


def test_ordinary_robot_math_and_yaml_pass_the_guard():
    res = build_file(XFIX / "math_yaml.urdf.xacro")
    root = etree.fromstring(res.text.encode())
    assert root.find("joint[@name='left_wheel_joint']/origin").get("xyz") == "0 0.15 0.05"
    assert root.find("joint[@name='right_wheel_joint']/origin").get("xyz") == "0 -0.15 0.05"
    lim = root.find("joint[@name='tilt']/limit")
    assert float(lim.get("lower")) == pytest.approx(-0.5235987755982988)
    assert lim.get("effort") == "2" and lim.get("velocity") == "1.2"
    assert any(str(XFIX / "params.yaml") in d or d.endswith("params.yaml") for d in res.deps)
    no = build_file(XFIX / "math_yaml.urdf.xacro", {"use_wheels": "false"})
    assert "left_wheel" not in no.text


def test_no_env_refuses_env(tmp_path):
    f = tmp_path / "env.urdf.xacro"
    f.write_text('<robot name="e"><link name="$(optenv HOME x)"/></robot>')
    assert "<link name=" in build_file(f).text
    with pytest.raises(InputError) as e:
        build_file(f, no_env=True)
    assert "--no-env" in str(e.value)


def test_includes_and_yaml_outside_the_package_roots_are_refused(tmp_path):
    inner = tmp_path / "pkg"
    inner.mkdir()
    (tmp_path / "secret.xacro").write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro"/>')
    (tmp_path / "secret.yaml").write_text("a: 1\n")
    f = inner / "r.urdf.xacro"
    f.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                 '<xacro:include filename="../secret.xacro"/>\n</robot>')
    with pytest.raises(InputError) as e:
        build_file(f)
    assert "outside the input's folder" in str(e.value)
    assert build_file(f, allow_paths=[tmp_path]).text
    f.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                 '<link name="${xacro.load_yaml(\'/etc/passwd\')}"/>\n</robot>')
    with pytest.raises(InputError) as e:
        build_file(f)
    assert "refusing to read /etc/passwd" in str(e.value)


# ------------------------------------------------------------------ errors
BAD = {
    "malformed": ('<robot name="r">\n<link name="a">\n</robot>\n', "malformed XML", ":3"),
    "missing_include": ('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                        '<xacro:include filename="nope.xacro"/>\n</robot>', "include not found", ":2"),
    "undefined_property": ('<robot name="r">\n<link name="${nope}"/>\n</robot>', "name 'nope' is not defined",
                           ":2"),
    "undefined_macro": ('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n\n<xacro:nope/>\n</robot>',
                        "unknown macro name: xacro:nope", ":3"),
    "undefined_arg": ('<robot name="r">\n<link name="$(arg nope)"/>\n</robot>', "nope", ":2"),
    "entities": ('<?xml version="1.0"?>\n<!DOCTYPE r [<!ENTITY a "aaaa">]>\n<robot name="&a;"/>',
                 "DTDs and entity declarations are not allowed", ":2"),
    "empty": ("", "empty file", ""),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_input_exit_2_one_message_nothing_written(tmp_path, case):
    text, message, line = BAD[case]
    f = tmp_path / f"{case}.urdf.xacro"
    f.write_text(text)
    out = tmp_path / "out.urdf"
    r = CliRunner().invoke(main, ["build", str(f), "-o", str(out)])
    assert r.exit_code == 2
    assert message in r.output
    assert f"{case}.urdf.xacro{line}" in r.output
    assert "Traceback" not in r.output
    assert not out.exists() and list(tmp_path.iterdir()) == [f]


def test_include_cycle_is_an_error(tmp_path):
    (tmp_path / "a.xacro").write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                                      '<xacro:include filename="b.xacro"/></robot>')
    (tmp_path / "b.xacro").write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                                      '<xacro:include filename="a.xacro"/></robot>')
    with pytest.raises(InputError) as e:
        build_file(tmp_path / "a.xacro")
    assert "include cycle" in str(e.value) and "b.xacro:2" in str(e.value)


def test_infinite_macro_recursion_is_stopped_with_the_macro_stack(tmp_path):
    f = tmp_path / "rec.urdf.xacro"
    f.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                 '<xacro:macro name="m" params="n"><xacro:m n="${n+1}"/></xacro:macro>\n'
                 '<xacro:m n="0"/>\n</robot>')
    with pytest.raises(InputError) as e:
        build_file(f)
    assert "nest deeper than 200" in str(e.value)
    assert "in macro 'm' called at" in str(e.value)


# ------------------------------------------------------------------ output
def test_output_is_deterministic_and_to_stdout_with_dash():
    src = str(LEGACY / "new/robot_pkg/urdf/robot.urdf.xacro")
    a = run("build", src, "--package-path", str(LEGACY / "new"), "-o", "-")
    b = run("build", src, "--package-path", str(LEGACY / "new"))
    assert a.exit_code == 0 and a.stdout == b.stdout and a.stdout.startswith("<?xml")
    assert "autogenerated by xacro from" in a.stdout


def test_deps_lists_every_file_read():
    r = run("build", str(XFIX / "math_yaml.urdf.xacro"), "--deps")
    files = r.stdout.split()
    assert files[0].endswith("math_yaml.urdf.xacro") and files[-1].endswith("params.yaml")


def test_resolve_uris(tmp_path):
    f = tmp_path / "m.urdf.xacro"
    f.write_text('<robot name="m"><link name="a"><visual><geometry>'
                 '<mesh filename="package://example-robot-data/robots/ur_description/meshes/ur5/collision/base.stl"/>'
                 '</geometry></visual></link></robot>')
    r = run("build", str(f), "--resolve-uris")
    assert 'filename="file:///' in r.stdout and "ur5/collision/base.stl" in r.stdout


def _plain_xacro(path: Path, resolver_paths=()) -> str:
    """What the unmodified xacro library produces (with $(find) mapped to our resolver)."""
    import xacro.substitution_args as sa

    import xacro
    from myrabot_desc.expand.packages import PackageResolver

    resolver = PackageResolver(package_paths=resolver_paths, input_file=path)
    saved = sa._eval_find
    sa._eval_find = lambda pkg: str(resolver.find(pkg))
    try:
        xacro.all_includes = []
        doc = xacro.process_file(str(path))
        return doc.toprettyxml(indent="  ")
    finally:
        sa._eval_find = saved


@pytest.mark.parametrize("n", [1, 10, 200, 1000])
def test_output_is_byte_identical_to_plain_xacro_on_generated_files(tmp_path, n):
    sys.path.insert(0, str(HERE.parent / "bench"))
    from gen_flat import flat_xacro

    f = tmp_path / f"flat{n}.xacro"
    f.write_text(flat_xacro(n))
    assert build_file(f).text == _plain_xacro(f)


@pytest.mark.parametrize("rel", ["legacy/new/robot_pkg/urdf/robot.urdf.xacro", "xacro/math_yaml.urdf.xacro",
                                 "xacro/macro_only.urdf.xacro", "wander_bot/urdf/robot.xacro"])
def test_output_is_byte_identical_to_plain_xacro_on_test_files(rel):
    path = FIX / rel
    assert build_file(path, package_paths=[LEGACY / "new"]).text == _plain_xacro(path, [LEGACY / "new"])


def test_help_imports_nothing_heavy():
    code = ("import sys; from myrabot_desc.commands.main import main\n"
            "try:\n    main(['--help'])\nexcept SystemExit:\n    pass\n"
            "heavy = [m for m in ('trimesh', 'yourdfpy', 'pinocchio', 'mujoco', 'numpy') if m in sys.modules]\n"
            "print('HEAVY', heavy)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert "HEAVY []" in out


def test_build_command_imports_nothing_heavy():
    code = ("import sys; from myrabot_desc.commands.main import main\n"
            f"try:\n    main(['build', {str(XFIX / 'math_yaml.urdf.xacro')!r}, '-o', '/dev/null'])\n"
            "except SystemExit:\n    pass\n"
            "heavy = [m for m in ('trimesh', 'yourdfpy', 'pinocchio', 'mujoco') if m in sys.modules]\n"
            "print('HEAVY', heavy)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert "HEAVY []" in out
