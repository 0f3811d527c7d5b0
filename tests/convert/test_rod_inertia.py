"""A near-singular, rod-like inertia converts to SDF that `ign sdf -k` accepts and MJCF that MuJoCo
loads (issue 25). The rod: example-robot-data's FingerEdu lower link, whose author gave it the
Solo lower leg's rod inertia (ixx = iyy = 0.00012, izz = 0); planted here with the moments of the
issue, 1.256e-4, 1.2560011e-4 and 1.4e-15 (A + B - C = -1.1e-10), also turned off its axes."""

from __future__ import annotations

import math
import shutil
import subprocess

import pytest

from helpers import ERD, invoke
from myrabot_desc.model.inertia import eigh3, repaired

FINGER = ERD / "finger_edu_description" / "robots" / "finger_edu.urdf"
REAL = '<inertia ixx="0.00012" ixy="0.00000" ixz="0.00000" iyy="0.00012" iyz="0.00000" izz="0.00000"/>'
# the same moments about axes turned 0.3 rad about x: iyy, iyz, izz of R diag(a, b, c) R^T
_c, _s = math.cos(0.3), math.sin(0.3)
_b, _cc, _a = 1.2560011e-4, 1.4e-15, 1.256e-4
TURNED = (f'<inertia ixx="{_a!r}" ixy="0" ixz="0" iyy="{_c * _c * _b + _s * _s * _cc!r}" '
          f'iyz="{_c * _s * (_b - _cc)!r}" izz="{_s * _s * _b + _c * _c * _cc!r}"/>')
PLANTS = {
    "diagonal": '<inertia ixx="1.256e-4" ixy="0" ixz="0" iyy="1.2560011e-4" iyz="0" izz="1.4e-15"/>',
    "turned": TURNED,
}


def _planted(tmp_path, which):
    text = FINGER.read_text()
    assert text.count(REAL) == 1
    f = tmp_path / "finger_edu.urdf"
    f.write_text(text.replace(REAL, PLANTS[which]))
    return f


def _moments(text: str, link: str):
    from lxml import etree

    el = etree.fromstring(text.encode()).find(f".//link[@name='{link}']/inertial/inertia")
    v = {k: float(el.findtext(k)) for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")}
    return eigh3(((v["ixx"], v["ixy"], v["ixz"]), (v["ixy"], v["iyy"], v["iyz"]), (v["ixz"], v["iyz"], v["izz"])))[0]


@pytest.mark.parametrize("which", sorted(PLANTS))
def test_rod_converts_to_sdf_ign_accepts(tmp_path, which):
    out = tmp_path / "out.sdf"
    res = invoke("convert", _planted(tmp_path, which), "--to", "sdf", "-o", out)
    assert res.exit_code == 0, res.output[-1500:]
    a, b, c = _moments(out.read_text(), "finger_lower_link")     # as written: 12 digits
    assert a + b >= c and a + c >= b
    assert a >= 1e-6 * c * 0.99 and math.isclose(c, 1.2560011e-4, rel_tol=1e-6)
    if shutil.which("ign"):
        p = subprocess.run(["ign", "sdf", "-k", str(out)], capture_output=True, text=True, timeout=120)
        assert p.returncode == 0 and "invalid inertia" not in p.stdout + p.stderr, p.stdout + p.stderr


@pytest.mark.parametrize("which", sorted(PLANTS))
def test_rod_converts_to_mjcf_mujoco_loads(tmp_path, which):
    mujoco = pytest.importorskip("mujoco")
    out = tmp_path / "finger.xml"
    res = invoke("convert", _planted(tmp_path, which), "--to", "mjcf", "-o", out)
    assert res.exit_code == 0, res.output[-1500:]
    m = mujoco.MjModel.from_xml_path(str(out))
    i = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, "finger_lower_link")
    small, mid, big = sorted(m.body_inertia[i])     # with the fixed finger tip merged into the body
    assert small + mid >= big and big >= 1.2560011e-4 and m.body_mass[i] > 0.0307
    # still a rod: before, the repaired tensor broke A + B >= C and MuJoCo's balanceinertia set the
    # body's moments to their mean (smallest 8.39e-5 kg m^2 about the rod's own axis)
    assert small < 1e-5


def test_repair_keeps_both_triangle_sides():
    """The repair raised a and b alike by c/(a+b)(1+1e-9): b became 1.2560011012e-4 > c, and
    b - c = 1.3e-13 > a = 1.4e-15, so b <= a + c broke; now a has a floor of 1e-6 c."""
    from types import SimpleNamespace

    fixed, changed = repaired(SimpleNamespace(mass=0.0307, ixx=1.256e-4, iyy=1.2560011e-4, izz=1.4e-15,
                                              ixy=0.0, ixz=0.0, iyz=0.0))
    a, b, c = sorted((fixed[0][0], fixed[1][1], fixed[2][2]))
    assert changed and a + b >= c and math.isclose(a, 1.2560011e-10, rel_tol=1e-6)
    assert fixed[1][1] == 1.2560011e-4      # the largest is kept
