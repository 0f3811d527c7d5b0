"""The real-robot corpus (tests/corpus, see its README): every robot as its authors wrote it.

For each robot of tests/corpus/robots.yaml:
  - `build` (default mode) is byte-identical to the real xacro CLI (PyPI `xacro`, ROS 2 branch) run
    with tests/corpus_shim on PYTHONPATH, which answers its `$(find pkg)` from CORPUS_PACKAGE_PATH;
    files in ROS Electric/Fuerte syntax (`legacy: true`) are compared with `--legacy off`, since
    the default build upgrades what xacro 2.x copies verbatim;
  - `check --inertia`, `info`, `convert --to sdf`, `convert --to mjcf` end with exit 0 or 1, no
    traceback.

Where today's tool refuses a robot, its cases are xfail(strict=True) naming the construct (XFAIL
below): a fix makes them pass and strict xfail then fails until the entry is removed.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from click.testing import CliRunner

from myrabot_desc.cli import main

HERE = Path(__file__).resolve().parent
CORPUS = HERE / "corpus"
SHIM = HERE / "corpus_shim"
ROBOTS = yaml.safe_load((CORPUS / "robots.yaml").read_text())["robots"]
XACRO = Path(sys.executable).with_name("xacro")

_DICT = "X005: the safe evaluator refuses the call dict(...) (xacro built-in; a ros2_control initial_positions dict)"
_SPLIT = "X005: the safe evaluator refuses str methods: ${xyz.split(' ')[0]} in franka_description/robots/common/utils.xacro:93"
_SUFFIX = ("a xacro file not named .xacro (rotors' .gazebo top file, built with args) is read as plain URDF by "
           "check/info/convert: robot '$(arg mav_name)', 0 links, while build expands it to 12 links")
_ALL = ("build", "check", "info", "sdf", "mjcf")
# robot id -> {case: reason}: what fails today. The refused builds fail every case (each needs the build).
XFAIL = {
    "ur5e_mocked": dict.fromkeys(_ALL, _DICT + " in ur_description/urdf/ur_mocked.urdf.xacro:60"),
    "gen3_robotiq_2f_85": dict.fromkeys(_ALL, _DICT + " in kortex_description/robots/gen3.xacro:58"),
    "panda": dict.fromkeys(_ALL, _SPLIT),
    "fr3": dict.fromkeys(_ALL, _SPLIT),
    "husky_pacs": dict.fromkeys(_ALL, "X005: the safe evaluator refuses str methods: ${name.upper()} in "
                                      "husky_description/urdf/pacs.urdf.xacro:434 (PACS accessory, HUSKY_PACS_ENABLED=true)"),
    "firefly": dict.fromkeys(("check", "info", "sdf", "mjcf"), _SUFFIX),
    "pioneer3at": {"mjcf": "convert --to mjcf exits 2: the URDF's <box size=\"0 0 0\"/> geometries (7, in "
                           "p2os_urdf/defs/pioneer3at_body.xacro) go to MuJoCo, which rejects a size-0 geom"},
}

pytestmark = pytest.mark.corpus


def _ids(robots):
    return [r["id"] for r in robots]


def _params(robots, case):
    out = []
    for r in robots:
        reason = XFAIL.get(r["id"], {}).get(case)
        marks = [pytest.mark.xfail(strict=True, reason=reason)] if reason else []
        out.append(pytest.param(r, marks=marks, id=r["id"]))
    return out


def _package_path(robot) -> Path:
    return CORPUS / robot.get("package_path", ".")


def _cli_args(robot) -> list[str]:
    return [str(CORPUS / robot["top"]), *robot.get("args", "").split(), "--package-path", str(_package_path(robot))]


def _invoke(robot, *argv):
    """Run our CLI in-process, with the robot's environment (its $(optenv) accessories)."""
    env = {k: str(v) for k, v in robot.get("env", {}).items()}
    res = CliRunner().invoke(main, list(argv), env=env, catch_exceptions=True)
    if res.exception is not None and not isinstance(res.exception, SystemExit):
        import traceback

        pytest.fail("".join(traceback.format_exception(res.exception)))
    assert "Traceback" not in res.output
    return res


def _xacro(robot) -> str:
    env = dict(os.environ, PYTHONPATH=str(SHIM), CORPUS_PACKAGE_PATH=str(_package_path(robot)))
    env.update({k: str(v) for k, v in robot.get("env", {}).items()})
    p = subprocess.run([str(XACRO), str(CORPUS / robot["top"]), *robot.get("args", "").split()],
                       capture_output=True, text=True, env=env, timeout=120)
    assert p.returncode == 0, p.stderr[-2000:]
    return p.stdout


def test_manifest_is_complete():
    """20+ robots of every kind; every file the manifest names exists; ids unique."""
    assert len(ROBOTS) >= 20
    assert len(set(_ids(ROBOTS))) == len(ROBOTS)
    kinds = {r["kind"] for r in ROBOTS}
    assert kinds == {"arm", "mobile", "mobile_manipulator", "gripper", "sensor", "aerial"}
    assert {r["ros"] for r in ROBOTS} == {1, 2}
    assert {r["build"] for r in ROBOTS} == {"catkin", "ament", "rosbuild"}
    for r in ROBOTS:
        assert (CORPUS / r["top"]).is_file(), r["top"]
        assert set(r) <= {"id", "top", "args", "env", "kind", "ros", "build", "package_path", "legacy", "drive"}


def test_shim_resolves_like_our_resolver():
    """The test-only ament shim and `build`'s resolver agree on every corpus package."""
    from myrabot_desc.packages import PackageResolver

    sys.path.insert(0, str(SHIM))
    try:
        os.environ["CORPUS_PACKAGE_PATH"] = str(CORPUS)
        from ament_index_python.packages import PackageNotFoundError, get_package_share_directory

        ours = PackageResolver(package_paths=[CORPUS], use_environment=False)
        names = [p.parent.name for p in CORPUS.glob("*/package.xml")]
        assert len(names) >= 20
        for name in names:
            assert Path(get_package_share_directory(name)) == ours.find(name) == CORPUS / name
        with pytest.raises(PackageNotFoundError):
            get_package_share_directory("no_such_package")
    finally:
        sys.path.remove(str(SHIM))
        os.environ.pop("CORPUS_PACKAGE_PATH", None)
        for mod in [m for m in sys.modules if m.startswith("ament_index_python")]:
            del sys.modules[mod]


@pytest.mark.parametrize("robot", _params(ROBOTS, "build"))
def test_build_equals_xacro(robot):
    want = _xacro(robot)
    assert robot.get("legacy") or _links(want) > 0
    # xacro 2.x copies legacy tags verbatim; so does `build --legacy off`, which reports them as X002
    # errors and writes only with --allow-errors.
    extra = ["--legacy", "off", "--allow-errors"] if robot.get("legacy") else []
    res = _invoke(robot, "build", *_cli_args(robot), *extra, "-o", "-")
    assert res.exit_code == (1 if extra else 0), res.stderr[-2000:]
    assert res.stdout == want


@pytest.mark.parametrize("robot", [r for r in ROBOTS if r.get("legacy")], ids=lambda r: r["id"])
def test_legacy_default_build_upgrades(robot):
    """Where xacro 2.x leaves legacy macro calls in the URDF, the default build expands them (X001)."""
    res = _invoke(robot, "build", *_cli_args(robot), "-o", "-")
    assert res.exit_code == 0, res.stderr[-2000:]
    assert "X001" in res.stderr
    assert res.stdout.count("<link ") > _xacro(robot).count("<link ")


def _links(urdf: str) -> int:
    from lxml import etree

    return len(etree.fromstring(urdf.encode()).findall("link"))


@pytest.mark.parametrize("robot", _params(ROBOTS, "check"))
def test_check_inertia_runs(robot):
    res = _invoke(robot, "check", "--inertia", "--format", "json", *_cli_args(robot))
    assert res.exit_code in (0, 1), res.output[-2000:]
    import json

    codes = {d["code"] for f in json.loads(res.stdout)["files"] for d in f["diagnostics"]}
    assert "T001" not in codes  # "no links": every corpus robot has links


@pytest.mark.parametrize("robot", _params(ROBOTS, "info"))
def test_info_runs(robot):
    """`info` reads the robot build makes: same number of links."""
    import json

    res = _invoke(robot, "info", "--json", *_cli_args(robot))
    assert res.exit_code in (0, 1), res.output[-2000:]
    doc = json.loads(res.stdout)
    built = _invoke(robot, "build", *_cli_args(robot), "-o", "-")
    assert doc["links"] == _links(built.stdout) > 0


@pytest.mark.parametrize("robot", _params(ROBOTS, "sdf"))
def test_convert_sdf_runs(robot, tmp_path):
    res = _invoke(robot, "convert", "--to", "sdf", *_cli_args(robot), "-o", str(tmp_path / "robot.sdf"))
    assert res.exit_code in (0, 1), res.output[-2000:]
    assert (tmp_path / "robot.sdf").stat().st_size > 0


@pytest.mark.parametrize("robot", _params(ROBOTS, "mjcf"))
def test_convert_mjcf_runs(robot, tmp_path):
    res = _invoke(robot, "convert", "--to", "mjcf", *_cli_args(robot), "-o", str(tmp_path / "mjcf" / "robot.xml"))
    assert res.exit_code in (0, 1), res.output[-2000:]
    assert (tmp_path / "mjcf" / "robot.xml").stat().st_size > 0


def test_standins_match_their_table():
    """Every stand-in mesh is the box its standins.json entry records (regenerate: tools/corpus_standins.py write)."""
    import json

    sys.path.insert(0, str(HERE.parent / "tools"))
    try:
        import corpus_standins
    finally:
        sys.path.pop(0)
    table = json.loads((CORPUS / "standins.json").read_text())
    assert len(table) >= 150
    for rel, entry in table.items():
        assert (CORPUS / rel).read_bytes() == corpus_standins.standin_bytes(rel, entry), rel
    import trimesh

    for rel in ("husky_description/meshes/wheel.dae", "turtlebot3_description/meshes/bases/burger_base.stl"):
        lo, hi = trimesh.load(str(CORPUS / rel), force="mesh").bounds
        assert [round(float(v), 6) for v in (*lo, *hi)] == [round(v, 6) for v in (*table[rel]["min"], *table[rel]["max"])]
