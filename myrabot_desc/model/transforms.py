"""Rigid transforms in pure Python, once for every consumer.

A conversion needs a few hundred 4x4 products, and importing numpy for them would cost more
than the whole conversion (convert stays under half of `ign sdf -p`). A transform is a pair
(R, p): R a 3x3 rotation as row tuples, p a 3-tuple translation; it maps x to R x + p.
The numpy twins for bulk work (sim, check) are in kinematics.py.
"""

from __future__ import annotations

import math

Mat3 = tuple[tuple[float, float, float], tuple[float, float, float], tuple[float, float, float]]
Tf = tuple[Mat3, tuple[float, float, float]]

EYE3: Mat3 = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))


IDENTITY: Tf = (EYE3, (0.0, 0.0, 0.0))


def transform(xyz=(0.0, 0.0, 0.0), rpy=(0.0, 0.0, 0.0)) -> Tf:
    """The transform of an origin, URDF convention R = Rz(yaw) Ry(pitch) Rx(roll)."""
    r, p, y = rpy
    r, p, y = float(r), float(p), float(y)
    if r == 0.0 and p == 0.0 and y == 0.0:
        # most origins have no rotation: the matrix of three +0.0 angles, computed once (a -0.0
        # angle leaves other signed zeros, which rpy_of reads)
        R = _NO_ROTATION if (math.copysign(1.0, r) > 0 and math.copysign(1.0, p) > 0
                             and math.copysign(1.0, y) > 0) else _rotation(r, p, y)
    else:
        R = _rotation(r, p, y)
    x, yy, z = xyz
    return R, (float(x), float(yy), float(z))


def _rotation(r: float, p: float, y: float) -> Mat3:
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return ((cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr),
            (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr),
            (-sp, cp * sr, cp * cr))


_NO_ROTATION = _rotation(0.0, 0.0, 0.0)


def pose_T(pose) -> Tf:
    """Transform of a model.Pose (or None = identity)."""
    if pose is None or pose.is_identity:
        return IDENTITY
    return transform(pose.xyz, pose.rpy)


def matmul3(A, B) -> Mat3:
    """A @ B for 3x3 matrices given as rows."""
    cols = tuple(zip(*B))
    return tuple(tuple(a[0] * c[0] + a[1] * c[1] + a[2] * c[2] for c in cols) for a in A)


def transpose3(A) -> Mat3:
    return tuple(zip(*A))


def rotate(R, v) -> tuple[float, float, float]:
    """R @ v."""
    return tuple(r[0] * v[0] + r[1] * v[1] + r[2] * v[2] for r in R)


def place(T: Tf, points) -> list[tuple[float, float, float]]:
    """R x + p of each (x, y, z) point: a shape's points placed by the transform T = (R, p)."""
    (a, b, c), (d, e, f), (g, h, i) = T[0]
    px, py, pz = T[1]
    return [(a * x + b * y + c * z + px, d * x + e * y + f * z + py, g * x + h * y + i * z + pz) for x, y, z in points]


def compose(A: Tf, B: Tf) -> Tf:
    """A then B in A's frame: the 4x4 product A @ B."""
    if B is IDENTITY:       # most origins are identities: skip the arithmetic
        return A
    if A is IDENTITY:
        return B
    Ra, pa = A
    Rb, pb = B
    q = rotate(Ra, pb)
    return matmul3(Ra, Rb), (q[0] + pa[0], q[1] + pa[1], q[2] + pa[2])


def rpy_of(R) -> tuple[float, float, float]:
    """Roll, pitch, yaw of a rotation matrix (inverse of ``transform``).

    Zeros are taken as +0 (``x + 0.0``): a product of rotations can leave a -0.0 that
    would turn a yaw of pi into -pi through atan2.
    """
    R = [[x + 0.0 for x in row] for row in R]
    sp = -R[2][0]
    sp = max(-1.0, min(1.0, sp))
    pitch = math.asin(sp)
    if abs(sp) < 1.0 - 1e-12:
        roll = math.atan2(R[2][1], R[2][2])
        yaw = math.atan2(R[1][0], R[0][0])
    else:  # gimbal lock: put everything in yaw
        roll = 0.0
        yaw = math.atan2(-R[0][1], R[1][1])
    return roll, pitch, yaw



def is_identity(T: Tf, tol: float = 1e-12) -> bool:
    if T is IDENTITY:
        return True
    R, p = T
    return (all(abs(v) <= tol for v in p)
            and all(abs(R[i][j] - (1.0 if i == j else 0.0)) <= tol for i in range(3) for j in range(3)))

