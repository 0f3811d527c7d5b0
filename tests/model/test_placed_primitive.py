"""model/shapes.placed_primitive, the pure-Python solid of one unrotated primitive that I006/I007
use for most links, gives combine()'s floats bit for bit, and leaves to combine every case where it
could not (a rotation, non-finite numbers, a mesh)."""

from __future__ import annotations

import random

from myrabot_desc.model.kinematics import pose_matrix
from myrabot_desc.model.loader import load_robot
from myrabot_desc.model.shapes import combine, placed_primitive, shape_props

SHAPES = ['<box size="{a} {b} {c}"/>', '<cylinder radius="{a}" length="{b}"/>', '<sphere radius="{a}"/>']


def _robot(tmp_path, n: int, seed: int):
    rnd = random.Random(seed)
    links = []
    for i in range(n):
        shape = rnd.choice(SHAPES).format(a=rnd.uniform(1e-4, 3), b=rnd.choice([rnd.uniform(1e-4, 3), 0.1]),
                                          c=rnd.uniform(1e-3, 2))
        xyz = " ".join(str(rnd.choice([0, -0.0, rnd.uniform(-5, 5), 1e-300, 123456.789])) for _ in range(3))
        rpy = rnd.choice(["0 0 0", "-0.0 0 -0.0", "0 0 1.5707963", "0.1 0 0", "3.14159 0 0"])
        mass = rnd.choice([1.0, rnd.uniform(1e-6, 500), 3e-7, 1e6])
        links.append(f'<link name="l{i}"><inertial><mass value="{mass}"/>'
                     f'<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>'
                     f'<collision><origin xyz="{xyz}" rpy="{rpy}"/><geometry>{shape}</geometry></collision></link>')
    joints = [f'<joint name="j{i}" type="fixed"><parent link="l0"/><child link="l{i}"/></joint>' for i in range(1, n)]
    f = tmp_path / "r.urdf"
    f.write_text(f'<robot name="r">{"".join(links)}{"".join(joints)}</robot>')
    return load_robot(f)


def test_same_floats_as_combine(tmp_path):
    robot = _robot(tmp_path, 600, seed=7)
    taken = 0
    for link in robot.links.values():
        (c,) = link.collisions
        mass = link.inertial.mass
        fast = placed_primitive(c.geometry, c.origin, mass)
        if fast is NotImplemented:       # a rotation, or a centroid the mass split moves by an ulp
            continue
        taken += 1
        ref = combine([(*shape_props(c.geometry), pose_matrix(c.origin))], mass)
        assert repr((fast.volume, fast.com, fast.inertia, fast.mass)) == \
            repr((ref.volume, ref.com, ref.inertia, ref.mass)), link.name
    assert taken > 200


def test_rotations_and_meshes_go_to_combine(tmp_path):
    robot = _robot(tmp_path, 60, seed=3)
    for link in robot.links.values():
        (c,) = link.collisions
        if any(v != 0 for v in c.origin.rpy):
            assert placed_primitive(c.geometry, c.origin, 1.0) is NotImplemented
    mesh = tmp_path / "m.urdf"
    mesh.write_text('<robot name="m"><link name="a"><collision><geometry><mesh filename="x.stl"/></geometry>'
                    '</collision></link></robot>')
    (c,) = load_robot(mesh).links["a"].collisions
    assert placed_primitive(c.geometry, c.origin, 1.0) is NotImplemented
