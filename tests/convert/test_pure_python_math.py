"""The converter's pure-Python rigid transforms and inertia repair, checked against numpy.

The SDF path avoids numpy so that `convert` starts fast (issue 8); these tests pin its
small matrix code to numpy's answers on random inputs.
"""

from __future__ import annotations

import math
import subprocess
import sys
from types import SimpleNamespace

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from myrabot_desc.convert.common import pose_text
from myrabot_desc.model.inertia import eigh3, repaired, tensor
from myrabot_desc.model.transforms import IDENTITY, compose, is_identity, rpy_of, transform

angles = st.floats(-math.pi, math.pi, allow_nan=False)
coords = st.floats(-10, 10, allow_nan=False)
moments = st.floats(1e-6, 10, allow_nan=False)


def np_T(T):
    R, p = T
    M = np.eye(4)
    M[:3, :3] = R
    M[:3, 3] = p
    return M


def np_transform(xyz, rpy):
    r, p, y = rpy
    Rx = np.array([[1, 0, 0], [0, math.cos(r), -math.sin(r)], [0, math.sin(r), math.cos(r)]])
    Ry = np.array([[math.cos(p), 0, math.sin(p)], [0, 1, 0], [-math.sin(p), 0, math.cos(p)]])
    Rz = np.array([[math.cos(y), -math.sin(y), 0], [math.sin(y), math.cos(y), 0], [0, 0, 1]])
    M = np.eye(4)
    M[:3, :3] = Rz @ Ry @ Rx
    M[:3, 3] = xyz
    return M


@settings(max_examples=200, deadline=None)
@given(st.tuples(coords, coords, coords), st.tuples(angles, angles, angles),
       st.tuples(coords, coords, coords), st.tuples(angles, angles, angles))
def test_compose_and_rpy_match_numpy(xyz1, rpy1, xyz2, rpy2):
    A, B = transform(xyz1, rpy1), transform(xyz2, rpy2)
    assert np.allclose(np_T(A), np_transform(xyz1, rpy1), atol=1e-12)
    C = compose(A, B)
    assert np.allclose(np_T(C), np_transform(xyz1, rpy1) @ np_transform(xyz2, rpy2), atol=1e-9)
    # rpy_of inverts transform (up to the equivalent angles near gimbal lock)
    back = transform(C[1], rpy_of(C[0]))
    assert np.allclose(np_T(back), np_T(C), atol=1e-9)


def test_identity_and_pi_yaw_text():
    assert is_identity(IDENTITY)
    assert is_identity(compose(transform((1, 2, 3), (0.1, 0.2, 0.3)), transform((1, 2, 3), (0.1, 0.2, 0.3)))) is False
    assert not is_identity(transform((1e-9, 0, 0)))
    # a roll and pitch of pi is a yaw of pi: printed as +pi, not -pi from a -0.0 (a1's hips)
    T = compose(IDENTITY, transform((0, 0, 0), (math.pi, math.pi, 0)))
    assert pose_text(T).split()[-1] == "3.14159265359"


@settings(max_examples=300, deadline=None)
@given(st.tuples(moments, moments, moments), st.tuples(angles, angles, angles))
def test_eigh3_matches_numpy(w, rpy):
    R = np.array(transform((0, 0, 0), rpy)[0])
    I = R @ np.diag(w) @ R.T
    vals, V = eigh3(I.tolist())
    assert np.allclose(vals, np.linalg.eigvalsh(I), rtol=1e-9, atol=1e-12 * max(w))
    V = np.array(V)
    assert np.allclose(V @ np.diag(vals) @ V.T, I, atol=1e-10 * max(w))
    assert np.allclose(V.T @ V, np.eye(3), atol=1e-10)


def inertial(ixx, iyy, izz, ixy=0.0, ixz=0.0, iyz=0.0, mass=1.0):
    return SimpleNamespace(mass=mass, ixx=ixx, iyy=iyy, izz=izz, ixy=ixy, ixz=ixz, iyz=iyz)


def test_repaired_roomba_raises_the_two_small_moments():
    # the seed's Roomba: ixx = iyy = 0.01, izz = 0.5 breaks A + B >= C
    fixed, changed = repaired(inertial(0.01, 0.01, 0.5))
    assert changed
    assert fixed[2][2] == 0.5
    assert math.isclose(fixed[0][0], 0.25, rel_tol=1e-6) and math.isclose(fixed[1][1], 0.25, rel_tol=1e-6)
    assert fixed[0][0] + fixed[1][1] >= fixed[2][2]


def test_repaired_valid_tensor_untouched_and_point_mass():
    ine = inertial(0.1, 0.2, 0.25, ixy=0.01)
    t, changed = repaired(ine)
    assert not changed and t == tensor(ine)
    t, changed = repaired(inertial(0, 0, 0, mass=1.0))
    r = (3 / (4 * math.pi * 1000.0)) ** (1 / 3)     # a 1 kg sphere of water
    assert changed and math.isclose(t[0][0], 0.4 * r * r) and t[0][1] == 0.0


@settings(max_examples=200, deadline=None)
@given(st.tuples(moments, moments, moments), st.tuples(angles, angles, angles))
def test_repaired_is_loadable_and_never_lowers_a_moment(w, rpy):
    R = np.array(transform((0, 0, 0), rpy)[0])
    I = R @ np.diag(w) @ R.T
    ine = inertial(I[0, 0], I[1, 1], I[2, 2], I[0, 1], I[0, 2], I[1, 2])
    fixed, changed = repaired(ine)
    before = np.linalg.eigvalsh(I)
    after = np.linalg.eigvalsh(np.array(fixed))
    assert after[0] + after[1] >= after[2] * (1 - 1e-9)
    assert np.all(after >= before - 1e-9 * before.max())
    if not changed:
        assert fixed == tensor(ine)


def test_convert_to_sdf_does_not_import_numpy(tmp_path):
    code = ("import sys\nfrom myrabot_desc.commands.main import main\n"
            f"sys.argv = ['myrabot-desc', 'convert', '-q', '-o', {str(tmp_path / 'r.sdf')!r}]\n"
            "try:\n    main()\nexcept SystemExit as e:\n    assert not e.code, e.code\n"
            "print('HEAVY', [m for m in ('numpy', 'trimesh', 'pinocchio', 'mujoco') if m in sys.modules])")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert "HEAVY []" in out
    assert (tmp_path / "r.sdf").stat().st_size > 10_000
