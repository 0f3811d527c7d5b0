"""Gazebo's physics settings in MuJoCo's terms: joint springs and contact friction.

Read from ``GazeboBlock.properties`` (``<gazebo reference="...">`` children; several blocks for one
reference merge in document order).
"""

from __future__ import annotations

import math

from myrabot_desc.convert.common import to_float

SPRING_KEYS = ("springStiffness", "springReference")
FRICTION_KEYS = ("mu1", "mu2")
# MuJoCo's floor has friction 1 and a contact takes the larger of its two geoms' unless one has
# priority. Gazebo's mu above 1 (Kobuki's wheels: 10) would make MuJoCo's soft contacts sink and
# stick (the rosbuild Kobuki sank 1 cm and stopped): those parts keep the floor's 1.
MAX_FRICTION = 1.0


def joint_springs(robot) -> dict[str, tuple[float, float]]:
    """joint -> (stiffness, reference) from Gazebo's ``<springStiffness>``/``<springReference>``
    (a passive suspension or wheel drop): MuJoCo's joint ``stiffness`` and ``springref``."""

    out = {}
    for g in robot.gazebo:
        if g.reference in robot.joints and any(k in g.properties for k in SPRING_KEYS):
            k = to_float(g.properties.get("springStiffness"))
            ref = to_float(g.properties.get("springReference"))
            old = out.get(g.reference, (0.0, 0.0))
            out[g.reference] = (k if k is not None else old[0], ref if ref is not None else old[1])
    return {n: v for n, v in out.items() if v[0] > 0 and math.isfinite(v[0]) and math.isfinite(v[1])}


def link_friction(robot) -> dict[str, float]:
    """link -> sliding friction from Gazebo's ``<mu1>``/``<mu2>`` (the smaller: MuJoCo's is
    isotropic). Gazebo takes the smaller of two surfaces' mu and its ground plane has 100, so the
    robot's value is the contact's; in MuJoCo its geoms get that friction and priority over the
    floor. A caster with mu 0 slides (Kobuki's); without it, it drags with the floor's 1."""

    out = {}
    for g in robot.gazebo:
        if g.reference not in robot.links:
            continue
        mus = [to_float(g.properties.get(k)) for k in FRICTION_KEYS]
        mus = [m for m in mus if m is not None and math.isfinite(m) and m >= 0]
        if mus:
            out[g.reference] = min(mus + ([out[g.reference]] if g.reference in out else []))
    return out
