"""Self-collision's pure-Python screen (model/collisions.Scene._lean_near: bounding spheres, then
boxes, then the capsules that hold spheres and cylinders, at the rest pose without meshes) against
numpy's (Scene._near on world_transforms) and coal's: the same pairs on the bundled robot, the corpus
and example-robot-data but for spheres and cylinders that cannot overlap, so that a robot the screen
finds clean is one numpy's path and coal find clean (that P005 of the bundled robot then imports neither numpy nor
coal: tests/check/test_lean_rules.py)."""

from __future__ import annotations

import pytest

from helpers import ERD, corpus_models, erd_models, erd_urdfs
from myrabot_desc.model import collisions as col
from myrabot_desc.model.kinematics import world_transforms
from myrabot_desc.model.loader import load_robot

np = pytest.importorskip("numpy")

DEPTHS = (col.TOUCH, 0.0, -0.01, -0.05)      # negative: bounding volumes apart by up to 5 cm count, more pairs to judge


def compare(robot, name) -> int:
    """Assert the screen's pairs are numpy's for every depth, but for pairs within rounding of
    meeting (boxes touching to the last bit), which the screen leaves to numpy; how many pairs
    numpy kept."""
    scene = col.Scene(robot, False)
    q = robot.rest_pose()
    items = scene._placed(world_transforms(robot, q))
    judged = 0
    for md in DEPTHS:
        lean = scene._lean_near(q, md)
        assert lean is not None, name      # an ordinary robot: no meshes read, a few dozen shapes
        want = scene._near(np, items, md) if len(items) >= 2 else []
        assert lean == sorted(set(lean)), (name, md)
        for a, b in set(want) - set(lean):      # dropped: only spheres and cylinders clear of each other
            ia, ib = items[a], items[b]
            ca, cb = (col._core(i.collision.geometry, tuple(i.half.tolist())) for i in (ia, ib))
            assert ca and cb and col._capsules_clear(tuple(ia.centre.tolist()), ia.T[:3, :3].tolist(), ca,
                                                     tuple(ib.centre.tolist()), ib.T[:3, :3].tolist(), cb, md)
        want = [p for p in want if p in set(lean)]
        extra = [p for p in lean if p not in want]
        if extra:
            C = np.array([i.centre for i in items])
            R = np.array([i.T[:3, :3] for i in items])
            H = np.array([i.half for i in items])
            assert not col._clearly_apart(np, C, R, H, extra, md).any(), (name, md, extra)
            assert len(extra) <= 2, (name, md, extra)
        judged += len(want)
    return judged


def test_bundled_robot_screens_as_numpy():
    compare(load_robot(None), "bundled")


def test_corpus_screens_as_numpy():
    judged = [compare(r, name) for name, r in corpus_models()]
    assert len(judged) >= 30 and sum(judged) > 100


def test_example_robot_data_screens_as_numpy():
    if not erd_urdfs():
        pytest.skip("example-robot-data is not installed")
    judged = [compare(r, name) for name, r in erd_models()]
    assert len(judged) >= 60 and sum(judged) > 100


class _Ball:
    def __init__(self, centre, radius):
        self.centre, self.radius = centre, radius


def test_sphere_pairs_on_random_scenes_as_numpy():
    rng = np.random.default_rng(2)
    for trial in range(200):
        n = int(rng.integers(0, 120))
        C = rng.normal(size=(n, 3)) * float(rng.choice([0.01, 0.1, 1.0]))
        if trial % 3 == 0:
            C[:, 0] = np.round(C[:, 0], 1)          # many shapes at one x: long sweeps
        R = rng.uniform(0, 0.3, size=n) * float(rng.choice([0.1, 1.0, 3.0]))
        md = float(rng.choice([0.001, 0.0, -0.01]))
        want = col._sphere_pairs(np, [_Ball(c, r) for c, r in zip(C, R)], md)
        got = col._lean_sphere_pairs([tuple(c) for c in C.tolist()], R.tolist(), md, 10**9)
        assert got == want, trial


def test_box_screen_on_random_boxes_as_numpy():
    """_lean_apart drops a pair only where _boxes_meet says apart; random boxes it tells alike."""
    rng = np.random.default_rng(3)
    told = 0                            # apart by _boxes_meet, not clearly by the screen
    for trial in range(3000):
        boxes = []
        for _ in range(2):
            Q, _r = np.linalg.qr(rng.normal(size=(3, 3)))
            if trial % 4 == 0:
                Q = np.eye(3)[rng.permutation(3)]        # axis-aligned: parallel edges, exact touches
            boxes.append((rng.normal(size=3) * 0.2, Q * np.sign(np.linalg.det(Q)), rng.uniform(0.01, 0.2, size=3)))
        md = float(rng.choice([0.001, 0.0, -0.01]))
        (ca, Ra, ha), (cb, Rb, hb) = boxes
        apart = col._lean_apart(tuple(ca.tolist()), tuple(map(tuple, Ra.tolist())), tuple(ha.tolist()),
                                tuple(cb.tolist()), tuple(map(tuple, Rb.tolist())), tuple(hb.tolist()), md)
        meet = col._boxes_meet(np, boxes[0], boxes[1], md)
        assert not (apart and meet), trial
        told += not apart and not meet
    assert told <= 30                   # near-parallel edge axes the screen leaves to numpy


def test_overlaps_equal_without_the_screen(monkeypatch):
    """Scene.overlaps with the screen (the default) and without it (LEAN_MOST 0): the same overlaps."""
    files = [ERD / "panda_description/urdf/panda.urdf", ERD / "ur_description/urdf/ur5_robot.urdf",
             ERD / "talos_data/robots/talos_full_v2.urdf"]
    robots = [load_robot(None)] + [load_robot(f) for f in files if f.is_file()]
    for r in robots:
        for md in DEPTHS:
            lean, plain = _with_and_without_screen(r, md, monkeypatch)
            assert lean == plain, (r.name, md)


def _with_and_without_screen(robot, md, monkeypatch) -> tuple[list, list]:
    """Scene.overlaps at the rest pose with the pure screen, and without it (LEAN_MOST 0)."""
    lean = col.Scene(robot, False).overlaps(robot.rest_pose(), min_depth=md)
    monkeypatch.setattr(col, "LEAN_MOST", 0)
    plain = col.Scene(robot, False).overlaps(robot.rest_pose(), min_depth=md)
    monkeypatch.undo()
    return lean, plain


def test_screen_keeps_a_pair_numpy_keeps(tmp_path):
    """Two boxes on different links, 2 moving joints apart: apart by 1 mm the screen finds nothing;
    overlapping by 20 mm it keeps the pair, and overlaps() finds it."""
    def robot(x):
        f = tmp_path / "r.urdf"
        box = '<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>'
        f.write_text(f"""<robot name="r">
<link name="a">{box}</link><link name="m"/><link name="b">{box}</link>
<joint name="j1" type="revolute"><parent link="a"/><child link="m"/><axis xyz="0 0 1"/>
  <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
<joint name="j2" type="revolute"><parent link="m"/><child link="b"/><origin xyz="{x} 0 0"/><axis xyz="0 0 1"/>
  <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>""")
        return load_robot(f)

    far, near = robot(0.101), robot(0.08)
    assert col.Scene(far, False)._lean_near(far.rest_pose(), col.TOUCH) == []
    assert col.Scene(near, False)._lean_near(near.rest_pose(), col.TOUCH) == [(0, 1)]
    (o,) = col.Scene(near, False).overlaps(near.rest_pose())
    assert (o.link_a, o.link_b) == ("a", "b") and abs(o.depth - 0.02) < 1e-9


def _capsule_shape(rng):
    if rng.random() < 0.4:
        return "sphere", float(rng.uniform(0.005, 0.15)), 0.0
    return "cylinder", float(rng.uniform(0.005, 0.15)), float(rng.uniform(0.001, 0.2))


def test_capsule_screen_never_drops_what_coal_finds_overlapping():
    """_capsules_clear says a sphere or cylinder pair overlaps by at most min_depth only where coal's
    depth is at most that; random pairs around touching, a third of them dropped."""
    coal = pytest.importorskip("coal")
    rng = np.random.default_rng(5)
    req = coal.CollisionRequest()
    req.enable_contact = True
    req.num_max_contacts = 1
    cleared = 0
    for trial in range(3000):
        shapes = []
        for _ in range(2):
            Q, _r = np.linalg.qr(rng.normal(size=(3, 3)))
            if trial % 5 == 0:
                Q = np.eye(3)           # parallel axes: the rotors of a multicopter
            Q = Q * np.sign(np.linalg.det(Q))
            kind, r, half = _capsule_shape(rng)
            shapes.append((kind, r, half, rng.normal(size=3) * 0.15, Q))
        md = float(rng.choice([0.001, 0.0, -0.01]))
        (ka, ra, la, ca, Ra), (kb, rb, lb, cb, Rb) = shapes
        clear = col._capsules_clear(tuple(ca.tolist()), Ra.tolist(), (ra, la), tuple(cb.tolist()), Rb.tolist(),
                                    (rb, lb), md)
        if not clear:
            continue
        cleared += 1
        made = [coal.Sphere(r) if k == "sphere" else coal.Cylinder(r, 2 * h) for k, r, h, _, _ in shapes]
        res = coal.CollisionResult()
        if coal.collide(made[0], coal.Transform3s(Ra, ca), made[1], coal.Transform3s(Rb, cb), req, res):
            assert abs(float(res.getContact(0).penetration_depth)) <= max(md, 0.0) + 1e-9, trial
    assert cleared > 500


def test_segment_distance_against_sampled_points():
    rng = np.random.default_rng(6)
    t = np.linspace(0, 1, 201)
    for trial in range(300):
        p1, q1, p2, q2 = rng.normal(size=(4, 3))
        if trial % 4 == 0:
            q1 = p1.copy()                                  # a point
        if trial % 7 == 0:
            q2 = p2 + (q1 - p1) * 0.5                       # parallel segments
        a = p1 + t[:, None] * (q1 - p1)
        b = p2 + t[:, None] * (q2 - p2)
        sampled = float(np.sqrt(((a[:, None, :] - b[None, :, :]) ** 2).sum(2)).min())
        d = col._segment_distance(*(tuple(x.tolist()) for x in (p1, q1, p2, q2)))
        step = 0.02 * float(np.abs(q1 - p1).sum() + np.abs(q2 - p2).sum())     # the samples' spacing
        assert sampled - step <= d <= sampled + 1e-12, trial


def _close(a, b) -> bool:
    return (a._replace(depth=0.0, point=()) == b._replace(depth=0.0, point=()) and abs(a.depth - b.depth) < 1e-12
            and all(abs(x - y) < 1e-12 for x, y in zip(a.point, b.point)))


def _by_coal(robot, md, monkeypatch) -> list:
    """Scene.overlaps at the rest pose with every pair given to coal (no screen, no closed form)."""
    monkeypatch.setattr(col, "LEAN_MOST", 0)
    monkeypatch.setattr(col, "penetration", lambda a, b: NotImplemented)
    got = col.Scene(robot, False).overlaps(robot.rest_pose(), min_depth=md)
    monkeypatch.undo()
    return got


def test_sphere_models_overlap_as_coal_says(tmp_path, monkeypatch):
    """A collision model of spheres (Franka's *_sc links, random chains of balls): the pure overlaps
    (Scene._pure_overlaps, sphere against sphere in closed form) are coal's, pair for pair, depth and
    point within rounding."""
    pytest.importorskip("coal")
    from helpers import corpus_model, corpus_robot

    robots = [corpus_model(corpus_robot("fr3"))]
    rng = np.random.default_rng(7)
    for n in range(40):
        links, joints = [], []
        for i in range(int(rng.integers(3, 9))):
            balls = "".join(f'<collision><origin xyz="{x:.4f} {y:.4f} {z:.4f}"/><geometry><sphere radius="{r:.4f}"/>'
                            '</geometry></collision>'
                            for x, y, z, r in np.c_[rng.normal(size=(2, 3)) * 0.05, rng.uniform(0.01, 0.06, 2)])
            links.append(f'<link name="l{i}">{balls}</link>')
            if i:
                joints.append(f'<joint name="j{i}" type="revolute"><parent link="l{i - 1}"/><child link="l{i}"/>'
                              f'<origin xyz="0 0 {rng.uniform(0.02, 0.1):.3f}" rpy="{rng.uniform(-1, 1):.3f} 0 0"/>'
                              '<axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>')
        f = tmp_path / f"balls{n}.urdf"
        f.write_text('<robot name="balls">' + "".join(links + joints) + "</robot>")
        robots.append(load_robot(f))
    found = 0
    for r in robots:
        for md in DEPTHS:
            lean, plain = _with_and_without_screen(r, md, monkeypatch)
            coal_says = _by_coal(r, md, monkeypatch)
            assert len(lean) == len(plain) == len(coal_says), (r.name, md)
            assert all(map(_close, lean, plain)) and all(map(_close, lean, coal_says)), (r.name, md)
            found += len(lean)
    assert found > 50
