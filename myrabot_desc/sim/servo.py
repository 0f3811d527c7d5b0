"""Servo units of the lab's code (Dynamixel AX-12, 10 bit) and the servo motion model.

Positions are 0…1023 over 300°, 511 at the centre. The lab's simulation bridge
(``modelo_brazo.cpp``, arm-facts.md §8.1) converts with C++ integer arithmetic::

    command:  q = ((u*300)/1023)*PI/180 - 2.62      # int division: whole degrees
    feedback: u = (int16)(((q + 2.62)*180/PI)*1023/300)  # truncated toward zero

with ``PI`` #defined as 3.14159265. The integer ``/1023`` truncates the command to
whole degrees, so the commanded angle is up to 1° low, and a command read back
through the feedback formula does not return the same number: 511 -> -0.0195 rad
-> 508, 718 -> 716, 304 -> 303. We reproduce both formulas exactly (``units_to_rad``
and ``rad_to_units``); ``units_to_rad_exact`` is the ideal mapping for comparison.

Speed: the AX-12 "moving speed" register counts 0.111 rpm per unit (0 means
"as fast as it can", 114 rpm). The bridge's own velocity command ``speed/511``
(integer division: 400 -> 0) is a second quirk that we document but do not
follow: the real servo moves at the register's speed, and the URDF joint's
``<limit velocity>`` caps it (the lab's Gazebo joints are limited to 3 rad/s).

The motion model is the servo's: straight at constant speed toward the latest
goal (no acceleration phase), so positions are piecewise linear in time and can
be evaluated in closed form on any time grid.
"""

from __future__ import annotations

import math

PI = 3.14159265                # the lab's #define, not math.pi
OFFSET = 2.62                  # rad; the URDF limits are ±2.62
UNITS_MAX = 1023
UNITS_HOME = 511
RPM_PER_UNIT = 0.111           # AX-12 moving-speed register
RAD_S_PER_UNIT = RPM_PER_UNIT * 2 * math.pi / 60
RAD_PER_UNIT = math.radians(300.0) / 1023     # 0.0051183 rad per unit


def units_to_rad(u: int) -> float:
    """The bridge's command conversion, integer truncation included."""
    u = int(u)
    return ((u * 300) // 1023) * PI / 180 - OFFSET if u >= 0 else _c_div(u * 300, 1023) * PI / 180 - OFFSET


def units_to_rad_exact(u: float) -> float:
    """The ideal conversion without truncation (for comparison only)."""
    return u * 300 / 1023 * PI / 180 - OFFSET


def rad_to_units(q: float) -> int:
    """The bridge's feedback conversion: C cast to int16 (truncation toward zero)."""
    return int(((q + OFFSET) * 180 / PI) * 1023 / 300)


def rad_to_units_array(q):
    """``rad_to_units`` of every element (numpy, the same operations in the same order: same numbers)."""
    import numpy as np

    return np.trunc(((q + OFFSET) * 180 / PI) * 1023 / 300)


def units_for_angle(q: float, mode: str = "nearest") -> int:
    """Units to command for a joint angle.

    ``lab``: the lab's own conversion (``controlador_moveit.cpp``), the truncating
    feedback formula; through the truncating command formula the joint then
    ends up to ~1.3° low. ``nearest``: the unit value whose commanded angle is
    nearest to ``q`` (at most 0.5° off: the command resolution is 1°).
    """
    u0 = rad_to_units(q)
    if mode == "lab":
        return u0
    best = min(range(u0 - 4, u0 + 5), key=lambda u: (abs(units_to_rad(u) - q), u))
    return max(0, min(UNITS_MAX, best))


def speed_rad_s(velocidad: int, urdf_limit: float | None = None) -> float:
    """Servo speed for a ``velocidad`` register value, capped by the URDF limit."""
    v = int(velocidad)
    s = (UNITS_MAX if v == 0 else min(max(v, 1), UNITS_MAX)) * RAD_S_PER_UNIT
    if urdf_limit is not None and urdf_limit > 0:
        s = min(s, urdf_limit)
    return s


def valid_command(u: int, velocidad: int = 0, par: int = 1) -> bool:
    """The bridge sends a command only if torque is on and both numbers are in 0…1023."""
    return par != 0 and 0 <= u <= UNITS_MAX and 0 <= velocidad <= UNITS_MAX


def _c_div(a: int, b: int) -> int:
    """C integer division (truncates toward zero)."""
    q = abs(a) // abs(b)
    return q if (a >= 0) == (b >= 0) else -q


class Servo:
    """One joint under position control: moves at ``speed`` toward the goal.

    Keeps its history as segments (t0, q0, goal, speed) so positions at any
    times are computed in one vectorised call (``positions``).
    """

    def __init__(self, q0: float, speed: float, lower: float | None = None, upper: float | None = None):
        self.speed = float(speed)
        self.lower, self.upper = lower, upper
        self.segments: list[tuple[float, float, float, float]] = [(0.0, float(q0), float(q0), self.speed)]

    def _clamp(self, q: float) -> float:
        if self.lower is not None:
            q = max(q, self.lower)
        if self.upper is not None:
            q = min(q, self.upper)
        return q

    def at(self, t: float) -> float:
        t0, q0, goal, s = self.segments[-1]
        d = goal - q0
        step = s * (t - t0)
        return goal if abs(d) <= step else q0 + math.copysign(step, d)

    def at_many(self, times):
        """``at`` at each of ``times`` (numpy; the same operations, so the same numbers)."""
        import numpy as np

        t0, q0, goal, s = self.segments[-1]
        d = goal - q0
        step = s * (np.asarray(times, dtype=float) - t0)
        return np.where(abs(d) <= step, goal, q0 + np.copysign(step, d))

    def command(self, t: float, goal: float, speed: float | None = None) -> None:
        q = self.at(t)
        self.segments.append((float(t), q, self._clamp(float(goal)), self.speed if speed is None else float(speed)))

    def arrival(self) -> float:
        """Time at which the last goal is (or was) reached."""
        t0, q0, goal, s = self.segments[-1]
        return t0 + (abs(goal - q0) / s if s > 0 else math.inf)

    def positions(self, times):
        """Positions at sorted times (numpy array), piecewise linear in closed form."""
        import numpy as np

        times = np.asarray(times, dtype=float)
        seg = np.array(self.segments)
        # segment i holds from its start until the next one starts (the first also before it)
        cuts = np.searchsorted(times, seg[1:, 0], side="left")
        n = np.diff(np.concatenate([[0], cuts, [len(times)]]))
        t0, q0, d, s = (np.repeat(c, n) for c in (seg[:, 0], seg[:, 1], seg[:, 2] - seg[:, 1], seg[:, 3]))
        step = s * np.maximum(times - t0, 0.0)
        return q0 + np.clip(d, -step, step)
