"""kinematics.pose_stack: every pose's pose_matrix, the same bits, whichever rpy objects the poses
share (one object in a row, equal tuples, lists, zeros of either sign)."""

from __future__ import annotations

import pytest

from myrabot_desc.model.kinematics import pose_matrix, pose_stack, stack_by_identity
from myrabot_desc.model.parts import Pose

np = pytest.importorskip("numpy")


def test_pose_stack_is_each_pose_matrix():
    shared, turned, signed = (0.0, 0.0, 0.0), (0.1, -0.2, 0.3), (-0.0, 0.0, -0.0)
    poses = [Pose((1.0, 2.0, 3.0), shared), Pose((0.5, 0.0, 0.0), shared), Pose((0.0, 0.0, 0.0), signed),
             Pose((0.0, 1.0, 0.0), signed), Pose((0.0, 0.0, 1.0), (0.0, 0.0, 0.0)), Pose((2.0, 0.0, 0.0), turned),
             Pose((2.0, 0.0, 0.0), (0.1, -0.2, 0.3)), Pose((0.0, 0.0, 0.0), [0.0, 1.5, -0.0]),
             Pose((0.0, 0.0, 0.0), [-0.0, 1.5, 0.0]), Pose((3.0, 3.0, 3.0), shared), Pose((1.0, 1.0, 1.0), turned)]
    for k in range(len(poses) + 1):             # every prefix: the shortcut for a repeated rpy at each place
        got = pose_stack(poses[:k])
        assert got.shape == (k, 4, 4)
        for pose, m in zip(poses[:k], got):
            want = np.asarray(pose_matrix(pose), dtype=float)
            assert m.tobytes() == want.tobytes(), pose
    assert pose_stack(iter(poses)).tobytes() == pose_stack(poses).tobytes()


def test_stack_by_identity_is_the_plain_stack():
    # repeated objects, equal but distinct ones, zeros of either sign, arrays and tuples: the same bits
    m, z, nz = tuple(float(k) for k in range(16)), (0.0, 0.0, 0.0), (-0.0, 0.0, -0.0)
    a = np.array([1.5, -2.0, 3.25])
    for objs, shape in (([m, m, tuple(m), m], (4, 4)), ([z, nz, z, (0.0, 0.0, 0.0), nz], (3,)),
                        ([a, a, np.array([1.5, -2.0, 3.25]), z], (3,)), ([], (4, 4))):
        got = stack_by_identity(objs, shape)
        want = np.array(objs, dtype=float).reshape(-1, *shape)
        assert got.shape == want.shape and got.tobytes() == want.tobytes()
