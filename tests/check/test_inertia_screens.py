"""The solid-body rules (I006, I007, I008, I010) judge an ordinary robot in pure Python. I006: a
pure-Python screen clears the links that cannot be reported, numpy measures the others; the screen
must never clear a finding: on real robots, the findings with it equal the findings of numpy on
every link. I007 and I010 measure every link of primitives in pure Python, numpy only the links with
meshes: their findings equal numpy's measure of every link, within a few ulps (I007: up to the axis'
sign)."""

from __future__ import annotations

import json
import math

import pytest

from helpers import ERD, corpus_env, corpus_model, corpus_robots
from myrabot_desc.checks import inertia as I
from myrabot_desc.checks import inertia_geometry as IG
from myrabot_desc.checks.context import CheckOptions, Context
from myrabot_desc.model.kinematics import pose_matrix
from myrabot_desc.model.loader import load_robot

RULES = (IG.inertia_vs_geometry, IG.radius_of_gyration, IG.density, IG.origin_inside, I.positive_definite, I.triangle)


def _findings(robot, unscreened: bool, monkeypatch) -> list:
    with monkeypatch.context() as m:
        if unscreened:           # numpy's measure of every link: what the rules did before the screens
            m.setattr(IG, "_beyond_limit", lambda solid: solid)
        ctx = Context(robot, CheckOptions())
        out = []
        for rule in RULES:
            for f in rule(ctx) or ():
                fix = None if f.fix is None else (f.fix.title, [getattr(e, "value", None) for e in f.fix.edits])
                out.append((rule.__name__, f.message, json.dumps(f.data, sort_keys=True, default=repr),
                            f.severity, fix))
        return out


def _same_outside(robot) -> int:
    """Asserts I010's findings (pure Python on the links of primitives) are numpy's verdict on every
    link: the same links, origins and centroids, distances and boxes within a few ulps; how many."""
    ctx = Context(robot, CheckOptions())
    mine = {f.data["link"]: f for f in IG.origin_inside(ctx)}
    ref = IG._numpy_outside(ctx, None)
    assert set(mine) == set(ref)
    for name, f in mine.items():
        data = ref[name][1]
        assert f.data["origin"] == data["origin"] and f.data["centroid"] == pytest.approx(data["centroid"], rel=1e-12)
        assert f.data["distance"] == pytest.approx(data["distance"], rel=1e-12)
    return len(mine)


def _axis(message: str) -> list:
    return [float(v) for v in message.split("about axis (")[1].split(")")[0].split()]


def _same_gyration(robot) -> int:
    """Asserts I007's findings (pure Python on the links of primitives) are numpy's measure of every
    link: the same links, numbers within a few ulps, the axis (sign canonical) within its rounding;
    the number of findings."""
    ctx = Context(robot, CheckOptions())
    mine = {f.data["link"]: f for f in IG.radius_of_gyration(ctx)}
    found, key_of = {}, {}
    IG._numpy_gyration(ctx, set(IG.solids(ctx)), found, key_of)
    ref = {name: found[key] for name, key in key_of.items() if found[key]}
    assert set(mine) == set(ref)
    for name, f in mine.items():
        tail, kg, reach, moment = ref[name]
        assert [f.data["radius_of_gyration"], f.data["reach"], f.data["moment"]] == \
            pytest.approx([kg, reach, moment], rel=1e-12)
        assert _axis(f.message) == pytest.approx(_axis(tail), abs=0.011)
    return len(mine)


def _check(robot, monkeypatch):
    assert _findings(robot, False, monkeypatch) == _findings(robot, True, monkeypatch)
    _same_outside(robot)
    _same_gyration(robot)
    # the pure-Python solids and points are within a few ulps of numpy's, and the volumes the same
    ctx = Context(robot, CheckOptions())
    hulls, pure, some = IG.hull_points(ctx), IG.pure_hull_points(ctx), IG.pure_hull_points(ctx, 8)
    for name, s in IG.solids(ctx).items():
        assert (hulls[name] is None) == (pure[name] is None) == (some[name] is None)
        if pure[name] is not None:
            # the points I007 and I010 try first are some of the points, bit for bit
            assert set(some[name]) <= set(pure[name])
            assert len(some[name]) < len(pure[name]) or all(it.geometry.kind == "box" for it in IG._hull_items(s.link))
            flat = [v for q in pure[name] for v in q]
            assert hulls[name].ravel().tolist() == pytest.approx(flat, rel=1e-12, abs=1e-15 * max(map(abs, flat)))
        if s.props is None:
            continue
        # what I006 reports (pure Python) is within a few ulps of numpy's products
        com, t = _numpy_framed(s)
        t9, pcom = IG._unrotated(s.props, s.link.inertial.origin) or IG._rotated(s)
        scale = float(abs(t).max())
        assert com.tolist() == pytest.approx(list(pcom), rel=1e-12, abs=1e-15)
        assert t.ravel().tolist() == pytest.approx(t9, rel=1e-12, abs=1e-14 * scale)


def _numpy_framed(s):
    """(com, tensor) of Solid ``s`` in its inertial frame, by numpy, less the round-off of rotations."""
    import numpy as np

    T = pose_matrix(s.link.inertial.origin)
    R, p = T[:3, :3], T[:3, 3]
    t = R.T @ np.array(s.props.inertia, dtype=float) @ R
    t[abs(t) < 1e-6 * abs(t).max()] = 0.0
    return R.T @ (np.array(s.props.com, dtype=float) - p), t


@pytest.mark.parametrize("entry", corpus_robots(), ids=lambda r: r["id"])
def test_screens_keep_the_findings_of_corpus_robots(entry, monkeypatch):
    for k, v in corpus_env(entry).items():
        monkeypatch.setenv(k, v)
    _check(corpus_model(entry), monkeypatch)


@pytest.mark.parametrize("path", sorted(ERD.glob("*/urdf/*.urdf")), ids=lambda p: p.stem)
def test_screens_keep_the_findings_of_erd_robots(path, monkeypatch):
    _check(load_robot(path, package_paths=[ERD]), monkeypatch)


def test_screens_clear_the_bundled_robot():
    """No link of the bundled robot is a suspect of I006, nor reported by I007 or I010."""
    ctx = Context(load_robot(None), CheckOptions())
    solid = [(n, s) for n, s in IG.solids(ctx).items() if s.props is not None]
    assert len(solid) > 40
    assert IG._beyond_limit(solid) == []
    assert list(IG.radius_of_gyration(ctx)) == [] and list(IG.origin_inside(ctx)) == []


def test_combine_pure_matches_combine():
    """Rotated and offset primitives (the shapes combine_pure measures) against numpy's combine."""
    from types import SimpleNamespace as NS

    from myrabot_desc.model import shapes as G
    from myrabot_desc.model.transforms import pose_T

    shapes = [NS(kind="box", size=(0.3, 0.2, 0.1)), NS(kind="cylinder", radius=0.05, length=0.4),
              NS(kind="sphere", radius=0.07)]
    poses = [NS(xyz=(0.1, -0.2, 0.05), rpy=(1.5707963, 0.0, 0.3), is_identity=False),
             NS(xyz=(0.0, 0.3, 0.0), rpy=(0.0, 0.7, -2.0), is_identity=False),
             NS(xyz=(-0.4, 0.0, 0.2), rpy=(0.0, 0.0, 0.0), is_identity=False)]
    for mass in (0.5, 3.0):
        parts = [(*G.shape_props(g), o) for g, o in zip(shapes, poses)]
        want = G.combine([(*p[:3], pose_matrix(p[3])) for p in parts], mass)
        got = G.combine_pure([(*p[:3], pose_T(p[3])) for p in parts], mass)
        assert got.volume == want.volume and got.mass == want.mass
        assert list(got.com) == pytest.approx(list(want.com), rel=1e-13)
        for a, b in zip(got.inertia, want.inertia):
            assert list(a) == pytest.approx(list(b), rel=1e-12, abs=1e-15)
        assert all(math.isfinite(v) for row in got.inertia for v in row)


def test_pure_measures_equal_numpy_on_every_link(tmp_path, monkeypatch):
    """Unrotated primitives and diagonal tensors, made to be reported by I007 and I010 on every link:
    equal moments in every order (LAPACK's selection sort), shapes that end on a plane through the
    origin, visuals that widen the box, several shapes a link."""
    import random

    rnd = random.Random(7)
    kinds = ['<box size="{a} {b} {c}"/>', '<cylinder radius="{a}" length="{b}"/>', '<sphere radius="{a}"/>']
    out = ['<robot name="r">', '<link name="base"/>']
    for n in range(120):
        shapes = []
        for _ in range(rnd.choice((1, 1, 2, 3))):
            a, b, c = (rnd.choice((0.05, 0.1, 0.2, rnd.uniform(0.01, 0.3))) for _ in range(3))
            xyz = " ".join(str(rnd.choice((0, -0.0, 0.05, -0.1, rnd.uniform(-0.3, 0.3)))) for _ in range(3))
            shapes.append(f'<origin xyz="{xyz}"/><geometry>{rnd.choice(kinds).format(a=a, b=b, c=c)}</geometry>')
        body = "".join(f"<collision>{g}</collision>" for g in shapes[:2])
        body += "".join(f"<visual>{g}</visual>" for g in shapes[1:])
        moments = rnd.choice(((2, 2, 1), (1, 2, 2), (2, 1, 2), (3, 3, 3), (0, 1, 0), (1, 5, 3)))
        scale = rnd.choice((1e-4, 1e-2, 1.0, 30.0))
        ixx, iyy, izz = (m * scale for m in moments)
        xyz = " ".join(str(rnd.choice((0, 0.05, rnd.uniform(-1, 1)))) for _ in range(3))
        out.append(f'<link name="l{n}"><inertial><origin xyz="{xyz}"/><mass value="{rnd.uniform(0.1, 3)}"/>'
                   f'<inertia ixx="{ixx}" ixy="0" ixz="0" iyy="{iyy}" iyz="0" izz="{izz}"/></inertial>{body}</link>')
        out.append(f'<joint name="j{n}" type="fixed"><parent link="base"/><child link="l{n}"/></joint>')
    path = tmp_path / "r.urdf"
    path.write_text("\n".join(out + ["</robot>"]))
    robot = load_robot(path)
    assert _same_outside(robot) > 60
    assert _same_gyration(robot) > 40
    assert _findings(robot, False, monkeypatch) == _findings(robot, True, monkeypatch)


def test_pure_gyration_equals_numpy_on_rotated_tensors_and_shapes(tmp_path):
    """I007's pure measure (eigh3, the points of pure_hull_points) against numpy's eigh: seeded random
    links with non-diagonal tensors, rotated inertial frames and rotated shapes, most of them reported."""
    import random

    import numpy as np

    from myrabot_desc.model.kinematics import rpy_matrix

    rnd = random.Random(11)
    kinds = ['<box size="{a} {b} {c}"/>', '<cylinder radius="{a}" length="{b}"/>', '<sphere radius="{a}"/>']

    def rpy():
        return " ".join(repr(rnd.uniform(-3.2, 3.2)) for _ in range(3))

    out = ['<robot name="r">', '<link name="base"/>']
    for n in range(300):
        shapes = []
        for _ in range(rnd.choice((1, 1, 2, 3))):
            a, b, c = (rnd.uniform(0.01, 0.3) for _ in range(3))
            xyz = " ".join(repr(rnd.uniform(-0.2, 0.2)) for _ in range(3))
            shapes.append(f'<origin xyz="{xyz}" rpy="{rpy()}"/>'
                          f'<geometry>{rnd.choice(kinds).format(a=a, b=b, c=c)}</geometry>')
        body = "".join(f"<collision>{g}</collision>" for g in shapes)
        mass = rnd.uniform(0.1, 5)
        # distinct principal moments (their axes well defined), radii of gyration 0.02 to 0.6 m
        kg = sorted(rnd.uniform(0.02, 0.6) for _ in range(3))
        if kg[1] - kg[0] < 0.01 or kg[2] - kg[1] < 0.01:
            continue
        R = rpy_matrix([rnd.uniform(-3.2, 3.2) for _ in range(3)])
        t = (R @ np.diag([mass * k * k for k in kg]) @ R.T).tolist()
        xyz = " ".join(repr(rnd.uniform(-0.1, 0.1)) for _ in range(3))
        out.append(f'<link name="l{n}"><inertial><origin xyz="{xyz}" rpy="{rpy()}"/><mass value="{mass!r}"/>'
                   f'<inertia ixx="{t[0][0]!r}" ixy="{t[0][1]!r}" ixz="{t[0][2]!r}" iyy="{t[1][1]!r}" '
                   f'iyz="{t[1][2]!r}" izz="{t[2][2]!r}"/></inertial>{body}</link>')
        out.append(f'<joint name="j{n}" type="fixed"><parent link="base"/><child link="l{n}"/></joint>')
    path = tmp_path / "r.urdf"
    path.write_text("\n".join(out + ["</robot>"]))
    robot = load_robot(path)
    assert len(robot.links) > 250
    assert _same_gyration(robot) > 100
    ctx = Context(robot, CheckOptions())
    pure, some = IG.pure_hull_points(ctx), IG.pure_hull_points(ctx, 8)
    assert all(set(some[n]) <= set(pure[n]) for n in IG.solids(ctx) if pure[n] is not None)


def test_pure_origin_inside_equals_numpy_on_rotated_shapes(tmp_path):
    """I010's pure verdict against numpy's on links of rotated collision and visual shapes, their
    centres of mass scattered so that about half lie outside."""
    import random

    rnd = random.Random(13)
    kinds = ['<box size="{a} {b} {c}"/>', '<cylinder radius="{a}" length="{b}"/>', '<sphere radius="{a}"/>']

    def shape():
        a, b, c = (rnd.uniform(0.01, 0.3) for _ in range(3))
        xyz = " ".join(repr(rnd.uniform(-0.2, 0.2)) for _ in range(3))
        rpy = " ".join(repr(rnd.uniform(-3.2, 3.2)) for _ in range(3))
        return f'<origin xyz="{xyz}" rpy="{rpy}"/><geometry>{rnd.choice(kinds).format(a=a, b=b, c=c)}</geometry>'

    out = ['<robot name="r">', '<link name="base"/>']
    for n in range(200):
        body = "".join(f"<collision>{shape()}</collision>" for _ in range(rnd.choice((1, 2))))
        body += "".join(f"<visual>{shape()}</visual>" for _ in range(rnd.choice((0, 1, 2))))
        xyz = " ".join(repr(rnd.uniform(-0.45, 0.45)) for _ in range(3))
        out.append(f'<link name="l{n}"><inertial><origin xyz="{xyz}"/><mass value="1"/>'
                   f'<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>{body}</link>')
        out.append(f'<joint name="j{n}" type="fixed"><parent link="base"/><child link="l{n}"/></joint>')
    path = tmp_path / "r.urdf"
    path.write_text("\n".join(out + ["</robot>"]))
    assert 40 < _same_outside(load_robot(path)) < 190


def test_pure_gyration_takes_a_nearly_unit_axis_by_its_products(monkeypatch):
    """An axis with two zero components and the third a rounding short of 1 (a Jacobi rotation can
    leave one) is measured with the products, not taken for a unit axis."""
    from types import SimpleNamespace as NS

    from myrabot_desc.model.parts import Pose

    one = 1.0 - 2.0 ** -53
    i = NS(ixx=0.5, ixy=0.0, ixz=0.0, iyy=0.4, iyz=0.0, izz=0.3, mass=1.0, origin=Pose((0.0, 0.0, 0.0), (0.0, 0.0, 0.0)))
    monkeypatch.setattr(IG, "eigh3", lambda t: ([0.3, 0.4, 0.5], [[0.0, 0.0, one], [0.0, one, 0.0], [one, 0.0, 0.0]]))
    pts = [(0.1, 0.2, 0.3), (-0.2, 0.1, 0.0)]
    got = IG._pure_gyration(i, pts, {"l": pts}, "l")
    assert got is not None and got[2] == pytest.approx(0.2236, abs=1e-4)     # the farthest point from the x axis
