"""Make an inertia tensor loadable, with the smallest change that does it.

sdformat rejects a link whose principal moments break the triangle inequality
(``ign sdf -k``: "A link named X has invalid inertia"), and gz-sim then refuses the
whole world; MuJoCo stops with "inertia must satisfy A + B >= C". The seed's
Roomba has ``ixx = iyy = 0.01, izz = 0.5``. We keep the mass, the centre of mass
and the principal axes, and *raise* the two smaller principal moments by the
same factor until A + B = C: no moment decreases, so the body gets no easier to
spin than its author wrote (lowering moments makes a simulation stiffer).
An all-zero tensor on a mass (a point mass, which no simulator accepts) becomes the
inertia of a solid sphere of water of that mass. ``check --inertia`` explains the
finding; the converter warns and repairs.
"""

from __future__ import annotations

import math

from myrabot_desc.model.transforms import Mat3, matmul3, transpose3

# Pure Python like the transforms in common.py: a 3x3 symmetric eigenproblem is a few
# Jacobi sweeps, far cheaper than importing numpy for it.


MIN_FRACTION = 1e-6     # the smallest principal moment a repair leaves, as a fraction of the largest


def tensor(ine) -> Mat3:
    """The 3x3 inertia matrix of a model.Inertial, in its inertial frame."""
    return ((ine.ixx, ine.ixy, ine.ixz), (ine.ixy, ine.iyy, ine.iyz), (ine.ixz, ine.iyz, ine.izz))


def combined(parts) -> tuple[float, tuple, list[list[float]]]:
    """(mass, centre of mass, tensor about it) of rigidly joined parts: ``parts`` is
    [(mass, (R, p) of the part's inertial frame, its tensor in that frame)], all poses in one
    frame, the total mass positive. The parallel axis theorem about the combined centre of mass,
    in that frame's axes (what sdformat's lumping and Pinocchio's fixed joints make of them)."""
    M = sum(m for m, _, _ in parts)
    com = tuple(sum(m * T[1][k] for m, T, _ in parts) / M for k in range(3))
    t = [[0.0] * 3 for _ in range(3)]
    for m, (R, p), ti in parts:
        d = [p[k] - com[k] for k in range(3)]
        dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2]
        rt = matmul3(matmul3(R, ti), transpose3(R))
        for a in range(3):
            for b in range(3):
                t[a][b] += rt[a][b] + m * ((dd if a == b else 0.0) - d[a] * d[b])
    return M, com, t


def eigh3(A) -> tuple[list[float], list[list[float]]]:
    """Eigenvalues (ascending) and eigenvectors (columns of V) of a symmetric 3x3 matrix.

    Cyclic Jacobi rotations: each zeroes one off-diagonal term; a handful of sweeps
    reach machine precision for 3x3.
    """
    r0, r1, r2 = A
    if r0[1] == 0.0 and r0[2] == 0.0 and r1[2] == 0.0 and r1[0] == 0.0 and r2[0] == 0.0 and r2[1] == 0.0:
        # already diagonal (most URDF inertias): the sweeps below would stop before the first rotation
        d = (float(r0[0]), float(r1[1]), float(r2[2]))
        order = sorted(range(3), key=d.__getitem__)
        return [d[i] for i in order], [[1.0 if k == i else 0.0 for i in order] for k in range(3)]
    a = [list(map(float, r)) for r in A]
    V = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    scale = max(abs(x) for r in a for x in r) or 1.0
    for _ in range(50):
        off = abs(a[0][1]) + abs(a[0][2]) + abs(a[1][2])
        if off <= 1e-17 * scale:
            break
        for p, q in ((0, 1), (0, 2), (1, 2)):
            if a[p][q] == 0.0:
                continue
            theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q])
            t = math.copysign(1.0, theta) / (abs(theta) + math.sqrt(theta * theta + 1.0))
            c = 1.0 / math.sqrt(t * t + 1.0)
            s = t * c
            for k in range(3):       # a <- a J (columns p, q)
                akp, akq = a[k][p], a[k][q]
                a[k][p], a[k][q] = c * akp - s * akq, s * akp + c * akq
            for k in range(3):       # a <- J^T a (rows p, q)
                apk, aqk = a[p][k], a[q][k]
                a[p][k], a[q][k] = c * apk - s * aqk, s * apk + c * aqk
            for k in range(3):
                vkp, vkq = V[k][p], V[k][q]
                V[k][p], V[k][q] = c * vkp - s * vkq, s * vkp + c * vkq
    order = sorted(range(3), key=lambda i: a[i][i])
    return [a[i][i] for i in order], [[V[k][i] for i in order] for k in range(3)]


def principal_moments(ine) -> list[float]:
    """The principal moments of a model.Inertial, ascending (what check's I004/I005 judge)."""
    if ine.ixy == 0.0 and ine.ixz == 0.0 and ine.iyz == 0.0:
        # eigh3's diagonal case without its eigenvectors: the same stable sort of the same floats
        return sorted((float(ine.ixx), float(ine.iyy), float(ine.izz)))
    return eigh3(tensor(ine))[0]


def from_eigen(w, V) -> Mat3:
    """V diag(w) V^T, symmetrised."""
    M = matmul3([[V[i][j] * w[j] for j in range(3)] for i in range(3)], transpose3(V))
    return tuple(tuple((M[i][j] + M[j][i]) / 2 for j in range(3)) for i in range(3))


def repaired(ine) -> tuple[Mat3, bool]:
    """(tensor, changed) for a model.Inertial: the tensor itself when valid, else the repair."""
    I = tensor(ine)
    if ine.mass <= 0:
        return I, False
    if ine.ixy == 0.0 and ine.ixz == 0.0 and ine.iyz == 0.0:
        # a diagonal tensor (most URDF inertias) that is no point mass and needs no repair: the
        # tests below on eigh3's sort of the same three floats, without the decomposition
        a, b, c = sorted((float(ine.ixx), float(ine.iyy), float(ine.izz)))
        if a > 0 and c > 1e-12 and not a + b < c - 1e-9 * c:
            return I, False
    return decomposed_repair(ine, I)


def decomposed_repair(ine, I) -> tuple[Mat3, bool]:
    """``repaired`` of a massive Inertial ``ine`` (tensor ``I``) by the eigen-decomposition: every
    tensor, diagonal ones included (the shortcut above gives its answer without it)."""
    if max(abs(x) for r in I for x in r) <= 1e-12:
        # a point mass: give it the inertia of a solid sphere of water of that mass
        r = (3 * ine.mass / (4 * math.pi * 1000.0)) ** (1 / 3)
        m = 0.4 * ine.mass * r * r
        return ((m, 0.0, 0.0), (0.0, m, 0.0), (0.0, 0.0, m)), True
    w, V = eigh3(I)
    scale = max(max(abs(x) for x in w), 1e-12)
    tol = 1e-9 * scale
    changed = False
    if w[0] <= 0:
        # non-positive moment: make it a small positive fraction of the largest
        w = [max(x, MIN_FRACTION * scale) for x in w]
        changed = True
    a, b, c = w
    if a + b < c - tol:
        f = c / (a + b) * (1 + 1e-9)    # a hair over, so rounding never lands below
        if math.isinf(f):               # subnormal a and b: c / (a + b) overflows, their shares do not
            a, b, f = a / (a + b), b / (a + b), c * (1 + 1e-9)
        # A rod (moments 1.4e-15, 1.256e-4, 1.2560011e-4): raised alike, the smallest stays
        # negligible and the hair over makes b exceed c by more than a, breaking b <= a + c; and
        # 1.4e-15 is written as 0. The smallest gets a floor of 1e-6 of the largest, a margin on
        # both sides that 12-digit text and the readers' eigen-decompositions keep.
        w = [max(a * f, MIN_FRACTION * c), b * f, c]
        changed = True
    if not changed:
        return I, False
    return from_eigen(w, V), True


def describe(ine, fixed) -> str:
    d = lambda M: f"({M[0][0]:.4g}, {M[1][1]:.4g}, {M[2][2]:.4g})"  # noqa: E731
    return f"diagonal {d(tensor(ine))} -> {d(fixed)}"
