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


def repaired(ine):
    """(tensor, changed) for a model.Inertial: the tensor itself when valid, else the repair."""
    import numpy as np

    I = ine.tensor()
    if ine.mass <= 0:
        return I, False
    if abs(I).max() <= 1e-12:
        # a point mass: give it the inertia of a solid sphere of water of that mass
        r = (3 * ine.mass / (4 * np.pi * 1000.0)) ** (1 / 3)
        return np.eye(3) * 0.4 * ine.mass * r * r, True
    w, V = np.linalg.eigh(I)
    order = np.argsort(w)
    w, V = w[order], V[:, order]
    scale = max(abs(w).max(), 1e-12)
    tol = 1e-9 * scale
    changed = False
    if w[0] <= 0:
        # non-positive moment: make it a small positive fraction of the largest
        w = np.maximum(w, 1e-6 * scale)
        changed = True
    a, b, c = w
    if a + b < c - tol:
        f = c / (a + b) * (1 + 1e-9)    # a hair over, so rounding never lands below
        a, b = a * f, b * f
        w = np.array([a, b, c])
        changed = True
    if not changed:
        return I, False
    fixed = V @ np.diag(w) @ V.T
    return (fixed + fixed.T) / 2, True


def describe(ine, fixed) -> str:
    d = lambda M: f"({M[0][0]:.4g}, {M[1][1]:.4g}, {M[2][2]:.4g})"  # noqa: E731
    return f"diagonal {d(ine.tensor())} -> {d(fixed)}"
