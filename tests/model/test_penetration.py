"""model/penetration.py: the depth of two overlapping primitives in closed form.

The depth is the smallest support value h_D(n) = h_A(n) + h_B(-n) of the Minkowski difference over
unit directions n; each random pair is checked on that definition (the normal gives the depth, no
direction gives less, moving the second shape by the depth parts them and by less does not, as
coal sees it) and against coal's own depth. The point lies on both shapes' surfaces within half
the depth.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from myrabot_desc.model.penetration import SNAP, Contact, Solid, penetration

coal = pytest.importorskip("coal")

KINDS = ["sphere", "box", "cylinder"]


def _rotation(rng, aligned: bool):
    if aligned:                             # one of the 24 rotations that keep the axes on the axes
        P = np.eye(3)[rng.permutation(3)] * rng.choice([-1.0, 1.0], size=3)[:, None]
        return P * np.sign(np.linalg.det(P))
    Q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    return Q * np.sign(np.linalg.det(Q))


def _solid(rng, kind, R, c) -> Solid:
    if kind == "box":
        h = tuple(float(x) for x in rng.uniform(0.01, 0.3, 3))
    else:
        r = float(rng.uniform(0.01, 0.2))
        h = (r, r, r) if kind == "sphere" else (r, r, float(rng.uniform(0.01, 0.3)))
    return Solid(kind, h, tuple(tuple(map(float, row)) for row in R), tuple(map(float, c)))


def _coal_shape(s: Solid):
    if s.kind == "box":
        return coal.Box(*(2 * x for x in s.half))
    if s.kind == "sphere":
        return coal.Sphere(s.half[0])
    return coal.Cylinder(s.half[0], 2 * s.half[2])


def _coal(a: Solid, b: Solid, shift=(0.0, 0.0, 0.0)):
    """coal's depth of a and b (b moved by ``shift``), None when it finds them apart."""
    req = coal.CollisionRequest()
    req.enable_contact = True
    req.num_max_contacts = 1
    res = coal.CollisionResult()
    ta = coal.Transform3s(np.array(a.R), np.array(a.c))
    tb = coal.Transform3s(np.array(b.R), np.array(b.c) + np.asarray(shift))
    if not coal.collide(_coal_shape(a), ta, _coal_shape(b), tb, req, res):
        return None
    return abs(float(res.getContact(0).penetration_depth))


def _h(s: Solid, n):
    """The support values of s along unit directions n (one, or rows), independent of the module."""
    m = np.asarray(n) @ np.array(s.R)               # the directions in s's frame
    h = s.half
    if s.kind == "box":
        local = np.abs(m) @ np.array(h)
    elif s.kind == "sphere":
        local = h[0] * np.linalg.norm(m, axis=-1)
    else:
        local = h[0] * np.hypot(m[..., 0], m[..., 1]) + h[2] * np.abs(m[..., 2])
    return local + np.asarray(n) @ np.array(s.c)


def _inside_by(s: Solid, x) -> float:
    """How far x is inside s (negative: outside), independent of the module."""
    p = np.array(s.R).T @ (np.asarray(x) - np.array(s.c))
    h = np.array(s.half)
    if s.kind == "sphere":
        return h[0] - float(np.linalg.norm(p))
    if s.kind == "box":
        q = np.abs(p) - h
        return -float(np.linalg.norm(np.maximum(q, 0))) if (q > 0).any() else -float(q.max())
    q = np.array([math.hypot(p[0], p[1]) - h[0], abs(p[2]) - h[2]])
    return -float(np.linalg.norm(np.maximum(q, 0))) if (q > 0).any() else -float(q.max())


def _random_pairs(seed: int, count: int):
    rng = np.random.default_rng(seed)
    for trial in range(count):
        ka, kb = rng.choice(KINDS, size=2)
        aligned = trial % 2 == 0
        Ra, Rb = _rotation(rng, aligned), _rotation(rng, aligned)
        if aligned and ka == kb == "cylinder":          # parallel axes, each turned about its own
            t = rng.uniform(-math.pi, math.pi)
            Rb = Ra @ np.array([[math.cos(t), -math.sin(t), 0], [math.sin(t), math.cos(t), 0], [0, 0, 1]])
        a = _solid(rng, str(ka), Ra, np.zeros(3))
        b = _solid(rng, str(kb), Rb, rng.uniform(-0.3, 0.3, 3))
        yield trial, a, b


def test_random_pairs_meet_the_definition_of_depth():
    rng = np.random.default_rng(11)
    settled: dict = {}
    for trial, a, b in _random_pairs(1, 3600):
        got = penetration(a, b)
        if got is NotImplemented:
            # two cylinders, or a cylinder and a box, at an angle: coal's
            assert {a.kind, b.kind} <= {"box", "cylinder"} and "cylinder" in (a.kind, b.kind), trial
            continue
        key = tuple(sorted((a.kind, b.kind)))
        settled[key] = settled.get(key, 0) + (got is not None)
        if got is None:
            assert (_coal(a, b) or 0.0) < 1e-6, trial
            continue
        n = np.array(got.normal)
        assert abs(float(n @ n) - 1) < 1e-12
        assert abs(_h(a, n) + _h(b, -n) - got.depth) < 1e-12, trial
        v = rng.normal(size=(2000, 3))
        v /= np.linalg.norm(v, axis=1)[:, None]
        assert (_h(a, v) + _h(b, -v)).min() >= got.depth - 1e-12, trial
        assert (_coal(a, b, n * (got.depth + 1e-7)) or 0.0) < 1e-6, trial          # parted
        if got.depth > 1e-4:
            assert _coal(a, b, n * (got.depth - 5e-5)) is not None, trial         # not yet
        for s in (a, b):
            assert _inside_by(s, got.point) >= -got.depth / 2 - 1e-9, trial
    # every kind of pair was settled many times
    assert len(settled) == 6 and min(settled.values()) > 40, settled


def test_depth_is_coals_where_coal_is_exact_and_never_deeper():
    """Spheres, boxes and a sphere outside a shape: coal's closed forms and its exact box test agree
    to rounding; curved pairs (coal's EPA) to its tolerance. coal pushes a sphere whose centre is
    inside a cylinder out through the side even when a cap is nearer: its depth is then too deep,
    and the definition test above shows this one is the least."""
    worst: dict = {}
    deeper = 0
    for trial, a, b in _random_pairs(2, 2400):
        got = penetration(a, b)
        if got is NotImplemented or got is None:
            continue
        ref = _coal(a, b)
        assert ref is not None and ref >= got.depth - 2e-6, trial
        key = tuple(sorted((a.kind, b.kind)))
        sphere, other = (a, b) if a.kind == "sphere" else (b, a)
        if key == ("cylinder", "sphere") and _inside_by(other, sphere.c) > 0:
            deeper += ref > got.depth + 1e-6
            continue
        worst[key] = max(worst.get(key, 0.0), abs(ref - got.depth))
    assert worst[("sphere", "sphere")] < 1e-12 and worst[("box", "sphere")] < 1e-12
    assert worst[("cylinder", "sphere")] < 1e-12
    assert worst[("box", "box")] < 1e-9
    assert worst[("box", "cylinder")] < 2e-6 and worst[("cylinder", "cylinder")] < 2e-6
    assert deeper > 10


def test_a_sphere_inside_a_cylinder_leaves_by_the_nearer_cap():
    cyl = Solid("cylinder", (0.1, 0.1, 0.2), ((1.0, 0, 0), (0, 1.0, 0), (0, 0, 1.0)), (0.0, 0.0, 0.0))
    ball = Solid("sphere", (0.05,) * 3, cyl.R, (0.02, 0.0, 0.19))
    got = penetration(ball, cyl)
    assert got.depth == pytest.approx(0.05 + 0.01) and got.normal == (0.0, 0.0, -1.0)
    assert got.point == pytest.approx((0.02, 0.0, 0.2 - 0.03))
    assert _coal(ball, cyl) == pytest.approx(0.05 + 0.08)       # coal: out through the side


def test_a_small_box_inside_a_large_one():
    eye = ((1.0, 0, 0), (0, 1.0, 0), (0, 0, 1.0))
    big = Solid("box", (0.1, 0.06, 0.09), eye, (0.0, 0.0, 0.0))
    finger = Solid("box", (0.0065, 0.001, 0.006), eye, (0.02, 0.03, -0.05))
    got = penetration(big, finger)
    # the nearest way out: along +y, 0.06 - 0.03 + 0.001
    assert got.depth == pytest.approx(0.031) and got.normal == (0.0, 1.0, 0.0)
    assert got.point == pytest.approx((0.02, 0.06 - 0.031 / 2, -0.05))      # the finger's face, halfway out


def test_parallel_within_snap_and_at_an_angle():
    eye = ((1.0, 0, 0), (0, 1.0, 0), (0, 0, 1.0))
    box = Solid("box", (0.2, 0.14, 0.085), eye, (0.0, 0.0, 0.0))

    def wheel(angle):
        c, s = math.cos(math.pi / 2 + angle), math.sin(math.pi / 2 + angle)
        return Solid("cylinder", (0.0375, 0.0375, 0.0157), ((1.0, 0, 0), (0, c, -s), (0, s, c)), (-0.19, 0.0, 0.06))

    size = math.hypot(0.0375, 0.0157)
    near = penetration(box, wheel(0.5 * SNAP / size))            # rpy 1.5707...: the Pioneer's caster
    assert isinstance(near, Contact)
    assert abs(near.depth - _coal(box, wheel(0.5 * SNAP / size))) < 2e-6
    assert penetration(box, wheel(2 * SNAP / size)) is NotImplemented
    assert penetration(wheel(0.3), box) is NotImplemented
    a = Solid("cylinder", (0.05, 0.05, 0.1), eye, (0.0, 0.0, 0.0))
    b = Solid("cylinder", (0.05, 0.05, 0.1), ((1.0, 0, 0), (0, 0, -1.0), (0, 1.0, 0)), (0.0, 0.05, 0.0))
    assert penetration(a, b) is NotImplemented


def test_apart_and_touching_give_none():
    eye = ((1.0, 0, 0), (0, 1.0, 0), (0, 0, 1.0))
    for kind in KINDS:
        a = Solid(kind, (0.1, 0.1, 0.1), eye, (0.0, 0.0, 0.0))
        for other in KINDS:
            assert penetration(a, Solid(other, (0.1, 0.1, 0.1), eye, (0.2, 0.0, 0.0))) is None       # touching
            assert penetration(a, Solid(other, (0.1, 0.1, 0.1), eye, (0.0, 0.0, 0.25))) is None      # apart
            got = penetration(a, Solid(other, (0.1, 0.1, 0.1), eye, (0.19, 0.0, 0.0)))
            assert got.depth == pytest.approx(0.01) and got.normal == pytest.approx((1.0, 0.0, 0.0))


def test_the_point_is_the_middle_of_a_partial_patch():
    eye = ((1.0, 0, 0), (0, 1.0, 0), (0, 0, 1.0))
    # a rotor disc (axis y) pushed 13 mm into a trunk's side, its centre 22 mm beyond the trunk's end:
    # the patch runs from the disc's near edge to the end of the trunk, x 0.2955 .. 0.3235
    trunk = Solid("box", (0.3235, 0.15, 0.075), eye, (0.0, 0.0, 0.0))
    rotor = Solid("cylinder", (0.05, 0.05, 0.01), ((1.0, 0, 0), (0, 0, -1.0), (0, 1.0, 0)), (0.3455, 0.147, 0.0))
    got = penetration(trunk, rotor)
    assert got.depth == pytest.approx(0.013) and got.normal == pytest.approx((0.0, 1.0, 0.0))
    assert got.point == pytest.approx(((0.2955 + 0.3235) / 2, 0.15 - 0.013 / 2, 0.0))
    # two parallel rods side by side, overlapping along z from 0.1 to 0.3: the middle, 0.2
    rod = Solid("cylinder", (0.02, 0.02, 0.2), eye, (0.0, 0.0, 0.0))
    other = Solid("cylinder", (0.03, 0.03, 0.1), eye, (0.045, 0.0, 0.2))
    got = penetration(rod, other)
    assert got.depth == pytest.approx(0.005)
    assert got.point == pytest.approx((0.02 - 0.0025, 0.0, 0.2))
    # two boxes' edges crossing, neither at its middle: the one point where they meet
    c, s = math.cos(math.pi / 4), math.sin(math.pi / 4)
    turned = ((1.0, 0, 0), (0, c, -s), (0, s, c))          # about x: an edge along x faces -y and -z
    tilt = ((c, 0, s), (0, 1.0, 0), (-s, 0, c))            # about y: an edge along y faces +x and +z
    a = Solid("box", (0.1, 0.1, 0.1), tilt, (0.0, 0.0, 0.0))
    b = Solid("box", (0.1, 0.1, 0.1), turned, (0.03, 0.0, 0.1 * math.sqrt(2) * 2 - 0.01))
    a = a._replace(c=(0.0, -0.04, 0.0))
    got = penetration(a, b)
    assert got.depth == pytest.approx(0.01) and got.normal == pytest.approx((0.0, 0.0, 1.0))
    top = 0.1 * math.sqrt(2)
    assert got.point == pytest.approx((0.0, 0.0, top - 0.005))


def test_a_pose_that_is_not_a_number_is_left_to_coal():
    eye = ((1.0, 0, 0), (0, 1.0, 0), (0, 0, 1.0))
    for kind in KINDS:
        a = Solid(kind, (0.1, 0.1, 0.1), eye, (0.0, 0.0, 0.0))
        assert penetration(a, Solid("box", (0.1, 0.1, 0.1), eye, (math.nan, 0.0, 0.0))) is NotImplemented
        assert penetration(Solid(kind, (math.inf, 0.1, 0.1), eye, (0.0, 0.0, 0.0)), a) is NotImplemented
