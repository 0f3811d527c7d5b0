"""Facts the viewer and the renderer draw that no other command computed yet.

Plain functions over the model (numpy imported inside). They are meant to move next to the
model's other derived facts; nothing here depends on viser or MuJoCo.

* :func:`inertia_box`: the uniform box with a link's mass and principal moments (what Gazebo's
  "view inertia" draws): a box far larger or smaller than the link's geometry is a wrong inertia.
* :func:`support`: the ground contacts, their support polygon and the centre of mass projected on
  the ground, at any joint configuration: model/support.stance (check's P001 asks the same at zero).
"""

from __future__ import annotations

from myrabot_desc.model.kinematics import pose_matrix
from myrabot_desc.model.support import stance as support  # noqa: F401  (the viewer's ground overlay)
from myrabot_desc.records import Struct


class InertiaBox(Struct):
    size: tuple[float, float, float]     # edge lengths (m) along the principal axes
    pose: object                         # 4x4 numpy: link frame -> box centre and principal axes
    valid: bool                          # False when the moments break the triangle inequality


def box_size(mass: float, moments) -> tuple[tuple[float, float, float], bool]:
    """Edges (a, b, c) of the uniform box with ``mass`` and principal ``moments`` (I1, I2, I3).

    A box has I1 = m (b^2 + c^2) / 12 and so on, hence a^2 = 6 (I2 + I3 - I1) / m. Moments that
    break the triangle inequality have no box: that edge is 0 and ``valid`` is False.
    """
    import math

    i1, i2, i3 = (float(x) for x in moments)
    sq = (6.0 * (i2 + i3 - i1) / mass, 6.0 * (i1 + i3 - i2) / mass, 6.0 * (i1 + i2 - i3) / mass)
    tol = 1e-9 * max(abs(i1), abs(i2), abs(i3), 1e-300) * 6.0 / mass
    valid = all(s >= -tol for s in sq)
    return tuple(math.sqrt(max(s, 0.0)) for s in sq), valid


def inertia_box(inertial) -> InertiaBox | None:
    """The equivalent inertia box of a URDF ``Inertial`` (None for a massless or missing one)."""
    import numpy as np

    if inertial is None or not inertial.mass > 0:
        return None
    moments, axes = np.linalg.eigh(inertial.tensor())
    if np.linalg.det(axes) < 0:            # a rotation, not a reflection
        axes[:, 2] = -axes[:, 2]
    size, valid = box_size(inertial.mass, moments)
    R = np.eye(4)
    R[:3, :3] = axes
    return InertiaBox(size=size, pose=pose_matrix(inertial.origin) @ R, valid=valid)
