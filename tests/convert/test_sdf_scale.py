"""convert on large models: linear in the model's size, with the same output as the general code.

Each link looked through every sensor for its own, each IMU sensor through every sensor and every
plugin; the number formatting and the inertia check take shortcuts that must give the same text and
the same tensor; a one-shot process keeps what it made rather than free it, a test process does not.
"""

from __future__ import annotations

import math
import subprocess
import sys
from types import SimpleNamespace

import pytest
from click.testing import CliRunner
from hypothesis import given, settings
from hypothesis import strategies as st

from helpers import cpu_time
from myrabot_desc.commands import convert as convert_command
from myrabot_desc.commands.main import main
from myrabot_desc.convert import common
from myrabot_desc.convert.common import num, nums
from myrabot_desc.convert.sdf import to_sdf
from myrabot_desc.model.inertia import decomposed_repair, repaired, tensor
from myrabot_desc.model.loader import load_robot


def _star(n: int) -> str:
    """n massless spokes around a base, each with a box and an IMU sensor."""
    out = ['<?xml version="1.0"?>', f'<robot name="s{n}">', '<link name="l0"/>']
    for i in range(1, n):
        out.append(f'<link name="l{i}"><collision><geometry><box size="0.02 0.02 0.02"/></geometry></collision>'
                   '</link>')
        out.append(f'<joint name="j{i}" type="fixed"><parent link="l0"/><child link="l{i}"/>'
                   f'<origin xyz="{0.3 * i:.1f} 0 0.01"/></joint>')
        out.append(f'<gazebo reference="l{i}"><sensor name="imu{i}" type="imu"><update_rate>100</update_rate>'
                   '</sensor></gazebo>')
    return "\n".join(out + ["</robot>"]) + "\n"


def _sdf_cpu(tmp_path, n: int) -> tuple[float, str]:
    """The best of two conversions' CPU, the collector off (a test process's heap is large and
    unrelated: its passes would be timed with the conversion)."""
    import gc

    src = tmp_path / f"star{n}.urdf"
    src.write_text(_star(n))
    best = math.inf
    for _ in range(2):
        robot = load_robot(src)
        gc.collect()
        gc.disable()
        try:
            with cpu_time() as t:
                text, res = to_sdf(robot)
        finally:
            gc.enable()
        assert len(res.sensors) == n - 1
        best = min(best, t.seconds)
    return best, text


def test_sdf_of_a_star_with_a_sensor_on_every_link_grows_linearly(tmp_path):
    """Four times the links and sensors cost about four times the CPU (quadratic was twelve; the
    limit leaves room for a loaded machine, where linear code measured up to 7.6)."""
    _sdf_cpu(tmp_path, 50)                     # imports and first-use caches out of the timing
    small, _ = _sdf_cpu(tmp_path, 600)
    large, text = _sdf_cpu(tmp_path, 2400)
    assert large / small < 9, (small, large)
    assert text.count("<sensor ") == 2399 and '<sensor name="imu2399" type="imu">' in text


def test_num_text_is_the_formula_and_the_same_twice():
    def formula(x):
        x = float(x)
        if -1e-12 < x < 1e-12:
            return "0"
        s = f"{x:.12g}"
        return "0" if s == "-0" else s

    values = [0.0, -0.0, 1e-13, -1e-13, 1.0, 1, True, 0.1, 1 / 3, -2.5e-7, 1e300, math.inf, -math.inf, 12345678901234.0,
              math.nan]
    for x in values:
        assert num(x) == formula(x), x
        assert num(x) == formula(x), x          # the second time from the cache
    assert nums((0.0, -0.0, 1.0)) == nums([0.0, -0.0, 1.0]) == "0 0 1"
    assert nums((0, 0, 1)) == nums((0.0, 0.0, 1.0)) == "0 0 1"


def test_num_cache_is_bounded(monkeypatch):
    monkeypatch.setattr(common, "_NUM_TEXT", {})
    monkeypatch.setattr(common, "_NUMS_TEXT", {})
    monkeypatch.setattr(common, "_NUM_TEXT_MAX", 10)
    for k in range(100):
        assert num(k + 0.5) == f"{k + 0.5:.12g}"
        assert nums((k + 0.25, 1.0)) == f"{k + 0.25:.12g} 1"
    assert len(common._NUM_TEXT) <= 10 and len(common._NUMS_TEXT) <= 10


def _repaired_by_decomposition(ine):
    """model/inertia.repaired without its diagonal shortcut: every tensor through eigh3."""
    I = tensor(ine)
    return (I, False) if ine.mass <= 0 else decomposed_repair(ine, I)


moment = st.one_of(st.floats(-1.0, 10.0, allow_nan=False), st.sampled_from([0.0, -0.0, 1e-13, 1e-12, 2e-12, 1.0]))


@settings(max_examples=300, deadline=None)
@given(moment, moment, moment, st.sampled_from([0.0, 1.0, -1.0]))
def test_repaired_diagonal_shortcut_gives_the_decomposition_answer(xx, yy, zz, mass):
    ine = SimpleNamespace(mass=mass, ixx=xx, ixy=0.0, ixz=0.0, iyy=yy, iyz=0.0, izz=zz)
    assert repaired(ine) == _repaired_by_decomposition(ine)
    assert all(math.isfinite(x) for row in repaired(ine)[0] for x in row)


def test_subnormal_moments_are_repaired_to_finite_numbers():
    """A rod whose two small moments are subnormal (c / (a + b) overflows) gets c shared as any rod."""
    ine = SimpleNamespace(mass=1.0, ixx=1.0, ixy=0.0, ixz=0.0, iyy=5e-324, iyz=0.0, izz=5e-324)
    (t, changed) = repaired(ine)
    assert changed and all(math.isfinite(x) for row in t for x in row)
    assert sorted(t[k][k] for k in range(3)) == pytest.approx([0.5, 0.5, 1.0], rel=1e-6)


def test_repaired_diagonal_edges():
    for xx, yy, zz in [(1.0, 1.0, 2.0), (1.0, 1.0, 2.0 + 1e-10), (1.0, 1.0, 2.1), (1e-13, 1e-13, 1e-13),
                       (0.0, 1.0, 1.0), (1.0, 2.0, 3.0), (3.0, 1.0, 2.0)]:
        ine = SimpleNamespace(mass=1.0, ixx=xx, ixy=0.0, ixz=0.0, iyy=yy, iyz=0.0, izz=zz)
        assert repaired(ine) == _repaired_by_decomposition(ine), (xx, yy, zz)


def test_in_process_convert_keeps_nothing_and_leaves_the_collector_on(tmp_path):
    """Only a one-shot process (the console script) leaves the collector off and keeps what it made."""
    src = tmp_path / "s.urdf"
    src.write_text(_star(5))
    r = CliRunner().invoke(main, ["convert", str(src), "-o", str(tmp_path / "o.sdf"), "-q"])
    assert r.exit_code == 0, r.output
    assert convert_command._KEPT == []
    import gc

    assert gc.isenabled()


def test_console_script_output_is_the_in_process_output(tmp_path):
    src = tmp_path / "s.urdf"
    src.write_text(_star(30))
    r = CliRunner().invoke(main, ["convert", str(src), "-o", str(tmp_path / "a.sdf"), "-q"])
    assert r.exit_code == 0, r.output
    code = ("import sys\nfrom myrabot_desc.commands.entry import main\n"
            f"sys.argv = ['myrabot-desc', 'convert', {str(src)!r}, '-q', '-o', {str(tmp_path / 'b.sdf')!r}]\n"
            "sys.exit(main())")
    subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert (tmp_path / "a.sdf").read_bytes() == (tmp_path / "b.sdf").read_bytes()


def test_mjcf_over_the_body_limit_is_refused_before_mujoco_is_imported(tmp_path):
    src = tmp_path / "s.urdf"
    src.write_text(_star(5))
    code = ("import os, sys\nos.environ['MYRABOT_DESC_MAX_MJCF_BODIES'] = '3'\n"
            "from myrabot_desc.commands.entry import main\n"
            f"sys.argv = ['myrabot-desc', 'convert', '--to', 'mjcf', {str(src)!r}, '-o', "
            f"{str(tmp_path / 'm' / 'o.xml')!r}]\n"
            "try:\n    main()\nexcept SystemExit as e:\n    print('EXIT', e.code)\n"
            "print('MUJOCO', 'mujoco' in sys.modules)")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert "EXIT 2" in p.stdout and "MUJOCO False" in p.stdout, (p.stdout, p.stderr)
    assert "the robot has 5 links, over the 3 that `convert --to mjcf` takes" in p.stderr


def test_notes_keep_each_warning_once_in_order():
    from myrabot_desc.convert.common import Notes

    n = Notes(["warning: first"])
    for k in (3, 1, 3, 2, 1):
        n.warn(f"w{k}", f"f.urdf:{k}")
    n.warn("first")
    assert n.warnings == ["warning: first", "f.urdf:3: warning: w3", "f.urdf:1: warning: w1",
                          "f.urdf:2: warning: w2"]
    assert Notes() == Notes() and repr(Notes()) == "Notes(warnings=[])"


def test_dropped_gazebo_elements_numbered_per_reference():
    from myrabot_desc.convert.common import Notes
    from myrabot_desc.convert.gazebo import GazeboProps

    src = ('<robot name="r"><link name="a"/><link name="b"/>'
           + '<gazebo reference="a"><foo>1</foo></gazebo>' * 3 + '<gazebo reference="b"><foo>1</foo></gazebo>'
           + '</robot>')
    import tempfile
    from pathlib import Path

    with tempfile.TemporaryDirectory() as d:
        p = Path(d) / "r.urdf"
        p.write_text(src)
        props = GazeboProps(load_robot(p), Notes())
    assert [(ref, label) for ref, label, _ in props.dropped] == [("a", "foo"), ("a", "foo #2"), ("a", "foo #3"),
                                                                  ("b", "foo")]
