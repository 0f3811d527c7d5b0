"""Issue 17's big trees: the stacked computations (one numpy product per tree level or per group of
links, instead of one per joint or link) give the same bits as the one-per-item code they replace.

The references below are that per-item code, kept here as the specification. Trees are generated at
test time: bench/gen_tree.py's 2,000-link star and chain, and random trees with every kind of joint,
origin, shape and inertia. The speed targets themselves are in bench/bench_scale.py.
"""

from __future__ import annotations

import math
import random
import sys
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from helpers import ROOT
from myrabot_desc.checks import check_robot
from myrabot_desc.checks import inertia_geometry as IG
from myrabot_desc.checks.context import Context
from myrabot_desc.commands.main import main
from myrabot_desc.model import kinematics as K
from myrabot_desc.model.loader import load_robot

sys.path.insert(0, str(ROOT / "bench"))
from gen_tree import tree_urdf  # noqa: E402


def random_tree(n: int, seed: int) -> str:
    """A tree of n links: random parents, joint types, origins (with rotations), shapes and inertias."""
    rnd = random.Random(seed)

    def f(a=1.0):
        return f"{rnd.uniform(-a, a):.6g}"

    def shape():
        k = rnd.choice(["box", "cylinder", "sphere"])
        if k == "box":
            return f'<box size="{rnd.uniform(0.01, 0.5):.4g} {rnd.uniform(0.01, 0.5):.4g} {rnd.uniform(0.001, 0.5):.4g}"/>'
        if k == "cylinder":
            return f'<cylinder radius="{rnd.uniform(0.01, 0.3):.4g}" length="{rnd.uniform(0.01, 0.5):.4g}"/>'
        return f'<sphere radius="{rnd.uniform(0.001, 0.3):.4g}"/>'

    def origin():
        r = rnd.random()
        if r < 0.3:
            return ""
        if r < 0.5:
            return f'<origin xyz="{f(0.3)} {f(0.3)} {f(0.3)}"/>'
        return f'<origin xyz="{f(0.3)} {f(0.3)} {f(0.3)}" rpy="{f(3.2)} {f(1.6)} {f(3.2)}"/>'

    out = ['<?xml version="1.0"?>', f'<robot name="random_{seed}">']
    for i in range(n):
        body = []
        if rnd.random() < 0.9:
            a, b, c = (rnd.uniform(1e-5, 0.2) for _ in range(3))
            xy, xz, yz = (rnd.uniform(-1e-3, 1e-3) if rnd.random() < 0.5 else 0 for _ in range(3))
            body.append(f'<inertial>{origin()}<mass value="{rnd.uniform(0.01, 5):.5g}"/><inertia ixx="{a:.5g}" '
                        f'ixy="{xy:.3g}" ixz="{xz:.3g}" iyy="{b:.5g}" iyz="{yz:.3g}" izz="{c:.5g}"/></inertial>')
        for _ in range(rnd.randint(0, 3)):
            body.append(f'<visual>{origin()}<geometry>{shape()}</geometry></visual>')
        for _ in range(rnd.randint(0, 3)):
            body.append(f'<collision>{origin()}<geometry>{shape()}</geometry></collision>')
        out.append(f'<link name="l{i}">{"".join(body)}</link>')
        if i:
            t = rnd.choice(["revolute", "continuous", "prismatic", "fixed", "fixed"])
            lim = '<limit lower="-1" upper="1" effort="10" velocity="1"/>' if t in ("revolute", "prismatic") else ""
            mim = f'<mimic joint="j{i - 1}" multiplier="0.5" offset="0.1"/>' \
                if i > 2 and t == "revolute" and rnd.random() < 0.05 else ""
            out.append(f'<joint name="j{i}" type="{t}"><parent link="l{rnd.randrange(i)}"/><child link="l{i}"/>'
                       f'{origin()}<axis xyz="{f()} {f()} {f()}"/>{lim}{mim}</joint>')
    out.append("</robot>")
    return "\n".join(out) + "\n"


TREES = {"star": lambda: tree_urdf("star", 2000), "chain": lambda: tree_urdf("chain", 2000),
         "random1": lambda: random_tree(300, 1), "random2": lambda: random_tree(200, 2)}


@pytest.fixture(scope="module", params=list(TREES))
def robot(request, tmp_path_factory):
    path = tmp_path_factory.mktemp("trees") / f"{request.param}.urdf"
    path.write_text(TREES[request.param]())
    return load_robot(path)


def same(a, b) -> bool:
    """Equal to the bit, signed zeros included."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return a.shape == b.shape and a.tobytes() == b.tobytes()


# ---------------------------------------------------------------- the one-per-item references
def ref_pose(pose):
    T = np.eye(4)
    T[:3, :3] = K.rpy_matrix(pose.rpy)
    T[:3, 3] = pose.xyz
    return T


def ref_motion(joint, q):
    T = np.eye(4)
    a = np.asarray(joint.axis, dtype=float)
    n = np.linalg.norm(a)
    if joint.type in ("revolute", "continuous") and n != 0:
        x, y, z = a / n
        c, s, C = math.cos(q), math.sin(q), 1 - math.cos(q)
        T[:3, :3] = [[c + x * x * C, x * y * C - z * s, x * z * C + y * s],
                     [y * x * C + z * s, c + y * y * C, y * z * C - x * s],
                     [z * x * C - y * s, z * y * C + x * s, c + z * z * C]]
    elif joint.type == "prismatic" and n:
        T[:3, 3] = a / n * q
    return T


def ref_world(robot, q):
    q = dict(q)
    for j in robot.joints.values():
        if j.mimic and j.mimic.joint in q and j.name not in q:
            q[j.name] = q[j.mimic.joint] * j.mimic.multiplier + j.mimic.offset
    children = robot.joints_by_parent()
    out = {}
    for root in robot.roots or list(robot.links)[:1]:
        stack = [(root, np.eye(4))]
        while stack:
            link, T = stack.pop()
            if link in out:
                continue
            out[link] = T
            for j in children.get(link, []):
                if j.child not in out:
                    stack.append((j.child, T @ ref_pose(j.origin) @ ref_motion(j, q.get(j.name, 0.0))))
    return out


def ref_com(robot, q):
    T = ref_world(robot, q)
    total, acc = 0.0, np.zeros(3)
    for name, link in robot.links.items():
        if link.inertial is None or name not in T or link.inertial.mass <= 0:
            continue
        total += link.inertial.mass
        acc += link.inertial.mass * (T[name] @ ref_pose(link.inertial.origin))[:3, 3]
    return total, acc / total


def ref_hull(ctx, link):
    items = IG._hull_items(link)
    if items is None:
        return None
    out = []
    for it in items:
        T = ref_pose(it.origin)
        out.append(np.asarray(IG.G.surface_points(it.geometry, 32)) @ T[:3, :3].T + T[:3, 3])
    return np.vstack(out)


# ---------------------------------------------------------------- the tests
def test_world_transforms_and_centre_of_mass_match_one_product_per_joint(robot):
    rnd = random.Random(0)
    for q in ({}, {j: rnd.uniform(-3, 3) for j in robot.joints}):
        want, got = ref_world(robot, q), K.world_transforms(robot, q)
        assert list(got) == list(want)                       # same links, same (walk) order
        assert all(same(got[k], want[k]) for k in want)
        (m1, c1), (m2, c2) = ref_com(robot, q), K.center_of_mass(robot, q)
        if q:
            assert m1 == m2 and same(c1, np.array(c2))
        else:       # at rest from rest_poses, in Python's rounding: within an ulp or so of numpy's
            assert m1 == m2 and np.allclose(c1, c2, rtol=1e-12, atol=1e-15)
    rest = K.rest_poses(robot)
    want = ref_world(robot, {})
    assert list(rest) == list(want)
    assert all(np.allclose(np.array(rest[k][0]), want[k][:3, :3], rtol=0, atol=1e-12)
               and np.allclose(rest[k][1], want[k][:3, 3], rtol=1e-12, atol=1e-12) for k in want)
    for j in list(robot.joints.values())[:200]:
        assert same(K.joint_motion(j, 0.4), ref_motion(j, 0.4))
        assert same(K.pose_matrix(j.origin), ref_pose(j.origin))


def test_inertia_rules_match_one_computation_per_link(robot):
    ctx = Context(robot)
    solids = IG.solids(ctx)
    hulls = IG.hull_points(ctx)
    for name, s in solids.items():
        want = ref_hull(ctx, s.link)
        assert (hulls[name] is None) == (want is None) and (want is None or same(hulls[name], want))
    # I006: the data of each finding is its own link's framing (not a repeated link's), within a
    # few ulps of numpy's product for that link
    i006 = {f.data["link"]: f for f in IG.inertia_vs_geometry(ctx)}
    for name, s in solids.items():
        if s.props is None or name not in i006:
            continue
        t9, com = IG._unrotated(s.props, s.link.inertial.origin) or IG._rotated(s)
        comp = (tuple(t9[0:3]), tuple(t9[3:6]), tuple(t9[6:9]))
        assert same(i006[name].data["computed_tensor"], comp) and same(i006[name].data["computed_com"], com)
        assert i006[name].data["fix"] == IG.inertia_line(comp)
        T = ref_pose(s.link.inertial.origin)
        R, p = T[:3, :3], T[:3, 3]
        want = R.T @ np.array(s.props.inertia) @ R
        want[abs(want) < 1e-6 * abs(want).max()] = 0.0
        assert np.allclose(np.array(comp), want, rtol=1e-12, atol=1e-14 * abs(want).max())
        assert np.allclose(com, R.T @ (np.array(s.props.com) - p), rtol=1e-12, atol=1e-15)
    # I007: radius of gyration against the farthest point, per link (pure Python: eigh3's moments
    # and axes, within a few ulps of LAPACK's, and the axis up to its sign)
    i007 = {f.data["link"]: f for f in IG.radius_of_gyration(ctx)}
    expected = set()
    for name, s in solids.items():
        pts = ref_hull(ctx, s.link)
        if pts is None:
            continue
        i = s.link.inertial
        T = ref_pose(i.origin)
        local = (pts - T[:3, 3]) @ T[:3, :3]
        ev, vec = np.linalg.eigh(i.tensor())
        worst = None
        for k in range(3):
            if ev[k] <= 0:
                continue
            u = vec[:, k]
            reach = float(np.sqrt(np.maximum((local ** 2).sum(1) - (local @ u) ** 2, 0)).max())
            kg = math.sqrt(ev[k] / i.mass)
            if kg > 1.1 * reach + 1e-4 and (worst is None or kg / max(reach, 1e-9) > worst[0]):
                worst = (kg / max(reach, 1e-9), kg, reach, ev[k], u)
        if worst:
            expected.add(name)
            data = i007[name].data
            assert data["link"] == name
            assert [data["radius_of_gyration"], data["reach"], data["moment"]] == \
                pytest.approx([worst[1], worst[2], float(worst[3])], rel=1e-12)
            axis = i007[name].message.split("about axis (")[1].split(")")[0].split()
            assert [float(v) for v in axis] == pytest.approx(IG._canonical_axis(worst[4].tolist()), abs=0.011)
    assert set(i007) == expected
    # I010: the origin against the box of the points, per link
    i010 = {f.data["link"] for f in IG.origin_inside(ctx)}
    want = set()
    for name, s in solids.items():
        pts = ref_hull(ctx, s.link)
        if pts is None:
            continue
        lo, hi = pts.min(0), pts.max(0)
        margin = 0.1 * float((hi - lo).max()) + 0.005
        p = np.array(s.link.inertial.origin.xyz)
        if np.maximum(np.maximum(lo - margin - p, p - hi - margin), 0).max() > 0:
            want.add(name)
    assert i010 == want


def test_star_findings():
    """The 2,000-link star: each small link's inertia is 15x its box's (I006) and its radius of
    gyration beyond the box (I007); the first one's location is its own line."""
    import tempfile

    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "star.urdf"
        path.write_text(tree_urdf("star", 2000))
        robot = load_robot(path)
        diags, _ = check_robot(robot)
    codes = {}
    for x in diags:
        codes[x.code] = codes.get(x.code, 0) + 1
    assert codes["I006"] == 1999 and codes["I007"] == 1999
    assert not [x for x in diags if x.severity == "error"]
    first = next(x for x in diags if x.code == "I006" and "link l1:" in x.message)
    assert first.loc.line == 4 and first.loc.file == str(path)
    assert "ratio 15×/15×/15×" in first.message


def test_locations_of_a_plain_urdf(tmp_path):
    """A URDF read from one file maps elements to their lines on demand (no per-element map)."""
    path = tmp_path / "r.urdf"
    path.write_text(random_tree(20, 3))
    robot = load_robot(path)
    els = [el for el in robot.root_element.iter() if isinstance(el.tag, str)]
    assert [robot.loc_of(el).line for el in els] == [el.sourceline for el in els]
    assert {loc.file for loc in robot.element_locs.values()} == {str(path)} == set(robot.source_files())
    from lxml import etree

    assert robot.loc_of(etree.fromstring("<link/>")) is None


def test_duplicate_child_with_an_unnamed_joint(tmp_path):
    """T002 names an unnamed joint (it was an internal error)."""
    path = tmp_path / "d.urdf"
    path.write_text('<robot name="d"><link name="a"/><link name="b"/>'
                    '<joint type="fixed"><parent link="a"/><child link="b"/></joint>'
                    '<joint name="j2" type="fixed"><parent link="a"/><child link="b"/></joint></robot>')
    res = CliRunner().invoke(main, ["check", "--no-cache", "--select", "T002", str(path)])
    assert res.exit_code == 1, res.output
    assert "link b is the child of 2 joints ((unnamed), j2)" in res.output


def test_mjcf_refuses_more_links_than_its_limit(tmp_path, monkeypatch):
    """MuJoCo's parse/compile and the at-rest contact search grow faster than the link count
    (a 5,000-link star took 12 s and 2 GB, 20,000 ran out of MuJoCo's memory after 25 s): past
    MYRABOT_DESC_MAX_MJCF_BODIES the conversion is one error line, exit 2, nothing written."""
    src = tmp_path / "star.urdf"
    src.write_text(tree_urdf("star", 60))
    out = tmp_path / "out" / "star.xml"
    monkeypatch.setenv("MYRABOT_DESC_MAX_MJCF_BODIES", "50")
    r = CliRunner().invoke(main, ["convert", "--to", "mjcf", str(src), "-o", str(out)])
    assert r.exit_code == 2
    assert "the robot has 60 links, over the 50 that `convert --to mjcf` takes" in r.output
    assert not out.parent.exists() or not any(out.parent.iterdir())
    monkeypatch.setenv("MYRABOT_DESC_MAX_MJCF_BODIES", "60")
    r = CliRunner().invoke(main, ["convert", "--to", "mjcf", str(src), "-o", str(out)])
    assert r.exit_code == 0, r.output
    assert "60 bodies" in r.output
