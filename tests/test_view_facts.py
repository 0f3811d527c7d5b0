"""view/facts.py: the equivalent inertia box and the support polygon, on known numbers."""

from __future__ import annotations

import math

import numpy as np
import pytest

from myrabot_desc.model.loader import load_robot
from myrabot_desc.model.parts import Inertial, Pose
from myrabot_desc.view.facts import box_size, inertia_box, support


def _box_inertial(m, a, b, c, origin=Pose()):
    return Inertial(mass=m, origin=origin, ixx=m * (b * b + c * c) / 12, iyy=m * (a * a + c * c) / 12,
                    izz=m * (a * a + b * b) / 12)


def test_box_of_a_box_is_the_box():
    size, valid = box_size(2.0, [2.0 * (0.2**2 + 0.3**2) / 12, 2.0 * (0.1**2 + 0.3**2) / 12,
                                 2.0 * (0.1**2 + 0.2**2) / 12])
    assert valid
    assert size == pytest.approx((0.1, 0.2, 0.3), rel=1e-9)


def test_triangle_inequality_broken_is_flagged():
    size, valid = box_size(1.0, [1.0, 0.1, 0.1])       # I1 > I2 + I3: no body has it
    assert not valid
    assert size[0] == 0.0 and size[1] > 0 and size[2] > 0


def test_inertia_box_pose_follows_origin_and_principal_axes():
    yaw = 0.7
    ine = _box_inertial(3.0, 0.4, 0.1, 0.2, Pose((0.1, -0.2, 0.3), (0.0, 0.0, yaw)))
    # rotate the tensor into the link frame: a tilted box, given by the origin rpy here
    box = inertia_box(ine)
    assert sorted(box.size) == pytest.approx([0.1, 0.2, 0.4], rel=1e-9)
    assert box.pose[:3, 3] == pytest.approx([0.1, -0.2, 0.3])
    # the 0.4 m edge lies along the origin's rotated x axis
    k = int(np.argmax(box.size))
    axis = box.pose[:3, k]
    assert abs(axis @ [math.cos(yaw), math.sin(yaw), 0.0]) == pytest.approx(1.0, abs=1e-9)
    assert np.linalg.det(box.pose[:3, :3]) == pytest.approx(1.0)


def test_massless_has_no_box():
    assert inertia_box(None) is None
    assert inertia_box(Inertial(mass=0.0, origin=Pose())) is None


def test_bundled_support_polygon_holds_the_centre_of_mass():
    robot = load_robot()
    s = support(robot)
    assert s is not None
    # the Roomba base stands on its two wheels and the castors
    assert {"left_wheel_link", "right_wheel_link"} <= set(s.contacts)
    assert len(s.polygon) >= 3
    assert s.mass == pytest.approx(4.6048, abs=1e-3)
    assert 0 < s.margin < 0.2
    assert s.com[2] - s.ground_z == pytest.approx(0.173, abs=0.002)


def test_support_moves_with_the_arm():
    robot = load_robot()
    s0 = support(robot)
    s1 = support(robot, {"base": math.pi / 2, "arti1": 1.2})
    assert s1.com[:2] != pytest.approx(s0.com[:2], abs=1e-3)
    assert s1.ground_z == pytest.approx(s0.ground_z, abs=1e-9)


@pytest.mark.parametrize("geom,volume", [
    (("box", (0.1, 0.2, 0.3)), 0.1 * 0.2 * 0.3),
    (("cylinder", 0.05, 0.4), None),
    (("sphere", 0.07), None),
])
def test_primitive_meshes_are_closed_and_outward(geom, volume):
    """The scene's primitives: closed surfaces, faces outward (positive volume), the right size."""
    import trimesh

    from myrabot_desc.model.parts import Box, Cylinder, Sphere
    from myrabot_desc.view.scene import primitive_mesh

    g = {"box": Box, "cylinder": Cylinder, "sphere": Sphere}[geom[0]](*geom[1:])
    v, f = primitive_mesh(g)
    m = trimesh.Trimesh(v, f, process=True)
    assert m.is_watertight and m.is_winding_consistent
    if geom[0] == "box":
        assert m.volume == pytest.approx(volume, rel=1e-6)
        assert m.extents == pytest.approx([0.1, 0.2, 0.3], rel=1e-6)
    elif geom[0] == "cylinder":
        assert m.volume == pytest.approx(math.pi * 0.05 ** 2 * 0.4, rel=0.01)       # 32 sections
        assert m.extents == pytest.approx([0.1, 0.1, 0.4], rel=1e-3)
    else:
        assert m.volume == pytest.approx(4 / 3 * math.pi * 0.07 ** 3, rel=0.05)
        assert m.extents == pytest.approx([0.14, 0.14, 0.14], rel=0.01)
