"""P003 decides without Pinocchio when the inertias prove the dynamics finite: the proof must never
say finite where Pinocchio's RNEA or ABA returns NaN. Random trees with links on fixed joints whose
own inertia is indefinite or missing (judged with their rigid body), checked against Pinocchio."""

from __future__ import annotations

import random

import numpy as np
import pytest

from helpers import corpus_model, corpus_robot
from myrabot_desc.checks.physics import _dynamics_surely_finite
from myrabot_desc.model.loader import read_urdf_text


def _inertial(rng: random.Random) -> str:
    kind = rng.choice(["pd", "pd", "indefinite", "zero", "none", "massless"])
    if kind == "none":
        return ""
    mass = 0.0 if kind == "massless" else rng.uniform(0.01, 2.0)
    if kind == "zero":
        t = (0.0,) * 6
    elif kind == "indefinite":      # a small tensor with a negative principal moment, as PAL's antennas
        s = rng.uniform(1e-9, 1e-4)
        t = (s, 3 * s, s, s, 0.5 * s, s)
    else:
        a, b, c = (rng.uniform(1e-4, 1e-2) for _ in range(3))
        t = (a + b, 0.1 * a, 0.0, b + c, 0.0, a + c)
    xyz = " ".join(f"{rng.uniform(-0.1, 0.1):.3f}" for _ in range(3))
    rpy = " ".join(f"{rng.uniform(-3, 3):.3f}" for _ in range(3))
    return (f'<inertial><origin xyz="{xyz}" rpy="{rpy}"/><mass value="{mass}"/>'
            f'<inertia ixx="{t[0]}" ixy="{t[1]}" ixz="{t[2]}" iyy="{t[3]}" iyz="{t[4]}" izz="{t[5]}"/></inertial>')


def _tree(seed: int) -> str:
    rng = random.Random(seed)
    n = rng.randint(2, 7)
    out = ['<robot name="r">', f'<link name="l0">{_inertial(rng)}</link>']
    for i in range(1, n):
        kind = rng.choice(["fixed", "fixed", "revolute", "continuous", "prismatic"])
        axis = " ".join(f"{rng.uniform(-1, 1):.3f}" for _ in range(3))
        xyz = " ".join(f"{rng.uniform(-0.3, 0.3):.3f}" for _ in range(3))
        out.append(f'<link name="l{i}">{_inertial(rng)}</link>')
        out.append(f'<joint name="j{i}" type="{kind}"><parent link="l{rng.randrange(i)}"/><child link="l{i}"/>'
                   f'<origin xyz="{xyz}" rpy="0.3 0 0.2"/><axis xyz="{axis}"/>'
                   '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>')
    out.append("</robot>")
    return "\n".join(out)


def _pinocchio_finite(robot) -> bool:
    import pinocchio as pin

    model = robot.pinocchio(floating=False)
    data = model.createData()
    rng = np.random.default_rng(0)
    for _ in range(4):
        q = pin.integrate(model, pin.neutral(model), rng.uniform(-1, 1, model.nv))
        v, tau = rng.uniform(-1, 1, model.nv), rng.uniform(-1, 1, model.nv)
        with np.errstate(all="ignore"):
            t = pin.rnea(model, data, q, v, np.zeros(model.nv))
            a = pin.aba(model, data, q, v, tau)
        if not (np.all(np.isfinite(t)) and np.all(np.isfinite(a))):
            return False
    return True


def test_the_proof_never_says_finite_where_pinocchio_returns_nan(tmp_path):
    proved = by_body = 0
    for seed in range(400):
        robot = read_urdf_text(_tree(seed), tmp_path / f"r{seed}.urdf")
        if not robot.joints or not _dynamics_surely_finite(robot):
            continue
        proved += 1
        assert _pinocchio_finite(robot), f"seed {seed}: proved finite, Pinocchio returns NaN"
        moving = {j.child for j in robot.joints.values() if j.type != "fixed"}
        by_body += any(link.inertial is None and name in moving or link.inertial is not None
                       and (link.inertial.ixy == 3 * link.inertial.ixx)
                       for name, link in robot.links.items())
    assert proved >= 40 and by_body >= 10, (proved, by_body)      # the body test itself was exercised


def test_an_indefinite_link_on_a_fixed_joint_under_a_heavy_body_needs_no_pinocchio(tmp_path):
    """PAL's antenna (principal moments -3.5e-8, 3.5e-8, 9.1e-8 at 1 g) fixed to a moving body."""
    text = """<robot name="r"><link name="base"/>
    <link name="arm"><inertial><mass value="2"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>
    </inertial></link>
    <joint name="j" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
    <link name="antenna"><inertial><mass value="1e-06"/>
      <inertia ixx="2.371e-08" ixy="6.119e-08" ixz="1.179e-08" iyy="2.833e-08" iyz="7.74e-09" izz="3.849e-08"/>
    </inertial></link>
    <joint name="a" type="fixed"><parent link="arm"/><child link="antenna"/><origin xyz="0.1 0 0"/></joint>
    </robot>"""
    robot = read_urdf_text(text, tmp_path / "r.urdf")
    assert _dynamics_surely_finite(robot) and _pinocchio_finite(robot)
    heavy = text.replace('<mass value="2"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>',
                         '<mass value="1e-06"/><inertia ixx="1e-9" ixy="0" ixz="0" iyy="1e-9" iyz="0" izz="1e-9"/>')
    assert not _dynamics_surely_finite(read_urdf_text(heavy, tmp_path / "h.urdf"))   # the sum is indefinite


@pytest.mark.parametrize("robot_id", ["pmb2", "tiago"])
def test_pal_robots_are_proved_finite(robot_id):
    robot = corpus_model(corpus_robot(robot_id))
    assert _dynamics_surely_finite(robot)
    assert _pinocchio_finite(robot)
