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


def test_rest_pose_puts_a_joint_at_its_nearer_limit_when_zero_is_outside(tmp_path):
    """render, the viewer's sliders and the MJCF `home` keyframe start from one rest pose: 0, or the
    nearer limit (Unitree A1's knee: [-2.697, -0.916] -> -0.916; it was drawn at 0)."""
    from click.testing import CliRunner

    from myrabot_desc.commands.main import main
    from myrabot_desc.view.scene import build_scene

    inertial = '<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>'
    f = tmp_path / "knee.urdf"
    f.write_text(f'<robot name="k"><link name="thigh">{inertial}</link><link name="calf">{inertial}'
                 '<visual><origin xyz="0 0 -0.1"/><geometry><box size="0.02 0.02 0.2"/></geometry></visual></link>'
                 '<joint name="calf_joint" type="revolute"><parent link="thigh"/><child link="calf"/>'
                 '<axis xyz="0 1 0"/><limit effort="33.5" lower="-2.6965" upper="-0.9163" velocity="21"/></joint>'
                 '<joint name="free_turn" type="continuous"><parent link="thigh"/><child link="tip"/></joint>'
                 f'<link name="tip">{inertial}</link></robot>')
    scene = build_scene(load_robot(f))
    assert scene.rest() == {"calf_joint": pytest.approx(-0.9163), "free_turn": 0.0}
    R = scene.transforms({})["calf"][:3, :3]
    assert math.atan2(R[0, 2], R[2, 2]) == pytest.approx(-0.9163)        # drawn bent, as MuJoCo's home
    assert scene.pose({"calf_joint": -2.0}) == {"calf_joint": -2.0, "free_turn": 0.0}
    import mujoco

    out = tmp_path / "m" / "knee.xml"
    assert CliRunner().invoke(main, ["convert", str(f), "--to", "mjcf", "--base", "fixed", "-o", str(out)]).exit_code == 0
    m = mujoco.MjModel.from_xml_path(str(out))
    assert m.key("home").qpos[m.jnt_qposadr[m.joint("calf_joint").id]] == pytest.approx(scene.rest()["calf_joint"])
