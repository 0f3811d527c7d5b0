"""gravity_needs' two forms (model/statics.py): the pure-Python sweep an ordinary robot takes and the
numpy one of large robots give the same needs, to rounding, and the same worst pose (the same sample
of the same joint) on real robots (that P006 of the bundled robot then imports no numpy:
tests/check/test_lean_rules.py)."""

from __future__ import annotations

import math
import random
import sys

import pytest

from helpers import ERD, ROOT, corpus_models, erd_models, erd_urdfs
from myrabot_desc.model import statics as S
from myrabot_desc.model.loader import load_robot
from test_gravity_needs_reference import planar_urdf, random_urdf


def _close(a: float, b: float, scale: float) -> bool:
    return math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-12 * scale)


def same_needs(robot, what: str, joints=None) -> bool:
    """Whether the pure form ran (not too large, a tree); when it did, its needs are the numpy form's."""
    pure = S._gravity_needs_py(robot, joints=joints)
    if pure is None:
        return False
    ref = S._gravity_needs_np(robot, joints=joints)
    assert [n.joint for n in pure] == [n.joint for n in ref], what
    scale = 1 + max((n.torque for n in ref), default=0.0)
    for a, b in zip(pure, ref):
        assert _close(a.torque, b.torque, scale) and _close(a.at_rest, b.at_rest, scale), (what, a, b)
        assert (a.pose_joint, a.pose_value) == (b.pose_joint, b.pose_value), (what, a, b)
        assert (a.effort, a.unit) == (b.effort, b.unit), (what, a, b)
        assert type(a.torque) is type(a.at_rest) is type(a.pose_value) is float, (what, a)
    return True


def test_bundled_robot():
    assert same_needs(load_robot(None), "bundled")


def test_corpus():
    pure = [same_needs(r, name) for name, r in corpus_models()]
    assert len(pure) >= 30 and sum(pure) >= 25


def test_example_robot_data():
    if not erd_urdfs():
        pytest.skip("example-robot-data is not installed")
    pure = [same_needs(r, name) for name, r in erd_models()]
    assert len(pure) >= 60 and sum(pure) >= 55


def test_asked_joints_and_a_pose_off_zero(tmp_path):
    """Only some joints asked; a knee whose range leaves 0 out (the rest pose off q = 0) and a
    gripper whose second finger mimics the first (the whole pose for the first's turns)."""
    r = load_robot(ERD / "pr2_description/urdf/pr2.urdf")
    asked = [j.name for j in r.joints.values() if j.type in S.MOVING][::3]
    assert same_needs(r, "pr2 (some joints)", joints=set(asked))
    assert any(j.mimic is not None for j in r.joints.values())
    solo = load_robot(ERD / "solo_description/robots/solo12.urdf")
    assert same_needs(solo, "solo12")


@pytest.mark.parametrize("shape", ["chain", "star", "branchy", "random"])
def test_random_trees(tmp_path, shape):
    """Every kind of moving joint, vertical, horizontal and tilted axes, limits leaving 0 out, zero
    and missing masses, mimic joints (the reference test's trees)."""
    rng = random.Random(shape)
    pure = 0
    for trial in range(30):
        f = tmp_path / f"{shape}{trial}.urdf"
        f.write_text(random_urdf(rng, rng.choice([2, 3, 5, 12, 30, 60]), shape))
        r = load_robot(str(f))
        pure += same_needs(r, f"{shape} {trial}")
        if trial % 5 == 0:
            same_needs(r, f"{shape} {trial} some", joints={j for j in r.joints if rng.random() < 0.5})
    assert pure >= 20


@pytest.mark.parametrize("axis", ["0 1 0", "1 0 0", "0 0.6 0.8"])
@pytest.mark.parametrize("spread", [False, True])
def test_planar_chains_tie_alike(tmp_path, axis, spread):
    """Joints about one horizontal axis: a joint's own turn ties with every turn above it, and the
    worst pose is the tie-breaking's (the first turn, in file order, beyond 1e-9 (1 + maximum))."""
    f = tmp_path / "p.urdf"
    f.write_text(planar_urdf(50, axis, spread))
    assert same_needs(load_robot(str(f)), axis)


def test_large_robots_take_numpy(tmp_path, monkeypatch):
    """Past the bounds the numpy form runs; a deep chain under them still takes the pure one."""
    sys.path.insert(0, str(ROOT / "bench"))
    from gen_tree import tree_urdf

    numpy_form = S._gravity_needs_np
    for kind, n, pure in (("star", S.PURE_LINKS + 1, False), ("chain", 400, False), ("chain", 40, True)):
        f = tmp_path / f"{kind}{n}.urdf"
        f.write_text(tree_urdf(kind, n))
        r = load_robot(f)
        took = []
        monkeypatch.setattr(S, "_gravity_needs_np", lambda *a, **k: took.append(1) or numpy_form(*a, **k))
        S.gravity_needs(r)
        assert bool(took) != pure, (kind, n)
        if pure:
            assert same_needs(r, f.name)
