"""sim building blocks: the lab's servo units, the servo motion, exact diff-drive arcs."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from helpers import ROOT
from myrabot_desc.sim import servo as sv


def test_servo_conversion_table_of_arm_facts():
    """arm-facts.md §8.1: the 'code q' column, integer truncation included."""
    table = {0: -2.62, 205: -1.5728, 304: -1.0667, 480: -0.1765, 511: -0.0195, 512: -0.0020,
             680: 0.8532, 718: 1.0452, 818: 1.5513, 1023: 2.6160}
    for u, q in table.items():
        assert sv.units_to_rad(u) == pytest.approx(q, abs=5e-5), u
    assert sv.units_to_rad_exact(511) == pytest.approx(-0.0046, abs=5e-5)
    # reverse mapping: q = 0 -> 511, ±π/2 -> 204 / 818, ±2.62 -> 0 / 1023
    assert sv.rad_to_units(0.0) == 511
    assert sv.rad_to_units(-math.pi / 2) == 204 and sv.rad_to_units(math.pi / 2) == 818
    assert sv.rad_to_units(-2.62) == 0 and sv.rad_to_units(2.62) == 1023


def test_round_trip_quirk():
    """Commanding u and reading it back loses units: 511 -> 508, 718 -> 716, 304 -> 303."""
    assert [sv.rad_to_units(sv.units_to_rad(u)) for u in (511, 718, 304)] == [508, 716, 303]


@given(st.integers(min_value=0, max_value=1023))
def test_command_is_whole_degrees_and_low(u):
    q = sv.units_to_rad(u)
    deg = (q + sv.OFFSET) * 180 / sv.PI
    assert abs(deg - round(deg)) < 1e-9                      # whole degrees
    assert 0 <= sv.units_to_rad_exact(u) - q < math.radians(1.0) + 1e-12   # truncated, never high


@given(st.floats(min_value=-2.5, max_value=2.5))
def test_nearest_units_within_half_a_degree(q):
    u = sv.units_for_angle(q, "nearest")
    assert abs(sv.units_to_rad(u) - q) <= math.radians(0.5) + 1e-9
    lab = sv.units_for_angle(q, "lab")
    assert abs(sv.units_to_rad(u) - q) <= abs(sv.units_to_rad(lab) - q) + 1e-12


def test_servo_speed():
    assert sv.speed_rad_s(400) == pytest.approx(400 * 0.111 * 2 * math.pi / 60)    # 4.65 rad/s
    assert sv.speed_rad_s(400, 3.0) == 3.0
    assert sv.speed_rad_s(0) == pytest.approx(1023 * 0.111 * 2 * math.pi / 60)     # 0 = full speed


def test_servo_motion_piecewise_linear():
    s = sv.Servo(0.0, 2.0)
    s.command(0.0, 1.0)
    s.command(0.25, -1.0)                    # turn back midway, from 0.5
    t = np.array([0.0, 0.1, 0.25, 0.5, 1.0, 2.0])
    assert s.positions(t) == pytest.approx([0.0, 0.2, 0.5, 0.0, -1.0, -1.0])
    assert s.arrival() == pytest.approx(0.25 + 1.5 / 2.0)


def _wheel(name, xy, radius):
    """A wheel (model/drive.Wheel) on a lateral axle at ``xy``, rolling forward for a positive rate."""
    from myrabot_desc.model.drive import Wheel

    return Wheel(name, name, (xy[0], xy[1], radius), (0.0, 1.0, 0.0), (xy[0], xy[1], radius), radius)


def test_exact_arcs_match_the_closed_form():
    """A constant twist for 10 s: the integrated pose equals the circle's, to rounding."""
    from myrabot_desc.sim.diffdrive import DiffDrive, WheelBase, integrate

    wl = _wheel("l", (0.0, 0.13), 0.033)
    wr = _wheel("r", (0.0, -0.13), 0.033)
    d = DiffDrive(urdf=WheelBase(wl, wr), plugin=None, wheels="urdf")
    v, w, T = 0.1, 0.3, 10.0
    for rate in (1000, 10):                  # exact at any step: no Euler drift
        tr = integrate(d, [(0, v, w)], int(T * rate), 1 / rate)
        th = w * T
        assert tr.x[-1] == pytest.approx(v / w * math.sin(th), abs=1e-12)
        assert tr.y[-1] == pytest.approx(v / w * (1 - math.cos(th)), abs=1e-12)
        assert tr.yaw[-1] == pytest.approx(th, abs=1e-12)


def test_base_origin_off_the_axle():
    """A base whose origin is behind the axle still turns about the axle midpoint."""
    from myrabot_desc.sim.diffdrive import DiffDrive, WheelBase, integrate

    wl = _wheel("l", (0.1, 0.15), 0.08)
    wr = _wheel("r", (0.1, -0.15), 0.08)
    d = DiffDrive(urdf=WheelBase(wl, wr), plugin=None, wheels="urdf")
    tr = integrate(d, [(0, 0.0, 1.0)], 1000, math.pi / 1000)     # spin in place by π
    assert (tr.axle_x[-1], tr.axle_y[-1]) == pytest.approx((0.1, 0.0), abs=1e-12)
    assert (tr.x[-1], tr.y[-1]) == pytest.approx((0.2, 0.0), abs=1e-12)


def test_support_polygon_and_margin():
    from myrabot_desc.model.support import Support
    from myrabot_desc.sim.stability import margin

    sup = Support(ground_z=0.0, contacts={}, polygon=[(0.13, 0), (0, 0.13), (-0.13, 0), (0, -0.13)], lowest=None)
    assert margin(sup, (0, 0, 0.2)) == pytest.approx(0.13 / math.sqrt(2))
    # a lateral 1 g pushes the loaded point 0.2 m outward, to (0, -0.2): 0.07 m beyond the diamond's
    # corner (the distance to the polygon, model/support.py, not to an edge's line: 0.0495)
    assert margin(sup, (0, 0, 0.2), (0, 9.81)) == pytest.approx(-0.07)
    assert margin(sup, (0, 0, 0.2), (-9.81, -9.81)) == pytest.approx(-(0.2 * math.sqrt(2) - 0.13 / math.sqrt(2)))


@given(st.lists(st.tuples(st.floats(0.0, 3.0), st.floats(-2.5, 2.5)), min_size=1, max_size=6),
       st.floats(0.1, 5.0))
def test_servo_vectorised_matches_the_scalar_formulas(cmds, speed):
    """at_many and rad_to_units_array give the very numbers of at and rad_to_units, and
    positions equals at between commands (vuelta's message search relies on both)."""
    s = sv.Servo(0.0, speed, -2.6, 2.6)
    for t, goal in sorted(cmds):
        s.command(t, goal)
    t0 = s.segments[-1][0]
    times = t0 + np.linspace(0.0, 3.0, 301)
    q = s.at_many(times)
    assert q.tolist() == [s.at(float(t)) for t in times]
    assert sv.rad_to_units_array(q).tolist() == [sv.rad_to_units(float(x)) for x in q]
    assert s.positions(times) == pytest.approx(q, abs=1e-15)


def test_mesh_vertices_fast_path_equals_trimesh(tmp_path):
    """meshio.vertices reads binary STL itself: the same distinct points trimesh gives, on every
    bundled mesh; ASCII STL goes through trimesh; broken files are one-line InputErrors."""

    import trimesh

    from myrabot_desc.errors import InputError
    from myrabot_desc.model import meshes as meshio

    meshes = sorted((ROOT / "meshes").glob("*.stl"))
    assert len(meshes) == 11
    for p in meshes:
        ours = meshio.vertices(p)
        ref = np.unique(np.asarray(trimesh.load(str(p), force="mesh").vertices), axis=0)
        assert np.array_equal(ours, ref), p.name
    box = trimesh.creation.box((1, 2, 3))
    ascii_stl = tmp_path / "box.stl"
    ascii_stl.write_bytes(trimesh.exchange.stl.export_stl_ascii(box).encode())
    assert np.allclose(np.sort(meshio.vertices(ascii_stl), axis=0), np.sort(box.vertices, axis=0))
    good = meshes[0].read_bytes()
    truncated = tmp_path / "truncated.stl"
    truncated.write_bytes(good[:-20])           # no longer 84 + 50 n bytes: trimesh decides
    nan = tmp_path / "nan.stl"
    nan.write_bytes(good[:84 + 12] + np.array([np.nan] * 3, "<f4").tobytes() + good[84 + 24:])
    for bad in (truncated, nan, tmp_path / "missing.stl"):
        with pytest.raises(InputError, match=bad.name):
            meshio.vertices(bad, None)


def test_convex_hull_square_line_and_random():
    from myrabot_desc.model.hull2d import convex_hull

    square = [(0, 0), (1, 0), (1, 1), (0, 1), (0.5, 0.5), (0.5, 0), (1, 0.5), (1e-12, 0)]
    assert convex_hull(square) == [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]   # CCW, collinear dropped
    assert convex_hull([(0, 0), (1, 1), (2, 2), (0.5, 0.5)]) == [(0.0, 0.0), (2.0, 2.0)]  # a line: its ends
    assert convex_hull([(3, 4), (3, 4)]) == [(3.0, 4.0)]
    spatial = pytest.importorskip("scipy.spatial")
    rng = np.random.default_rng(7)
    for n in (3, 10, 100, 2000):
        pts = rng.normal(size=(n, 2))
        ours = convex_hull(pts)
        ref = spatial.ConvexHull(pts)
        assert len(ours) == len(ref.vertices)
        assert {tuple(np.round(p, 9)) for p in pts[ref.vertices]} == set(ours)
        area = 0.5 * sum(a[0] * b[1] - b[0] * a[1] for a, b in zip(ours, ours[1:] + ours[:1]))
        assert area == pytest.approx(ref.volume, rel=1e-6)        # positive: counter-clockwise (points rounded)
