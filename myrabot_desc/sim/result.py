"""A simulation run's outcome: time series, checks (the verdict), summary, JSON and CSV."""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field


@dataclass
class Check:
    name: str
    passed: bool
    value: object                 # the measured number (or text)
    unit: str = ""
    expected: str = ""            # what passing means, in words and numbers
    detail: str = ""

    def as_dict(self) -> dict:
        return {"name": self.name, "passed": bool(self.passed), "value": _plain(self.value), "unit": self.unit,
                "expected": self.expected, "detail": self.detail}


@dataclass
class Series:
    """One plotted curve: label, unit and values on the result's time grid (or its own)."""

    label: str
    values: object
    unit: str = ""
    t: object = None
    group: str = "joints"


@dataclass
class SimResult:
    program: str
    robot: str
    rate: float
    duration: float
    t: object                                  # numpy, N+1 samples
    base: object                               # diffdrive.BaseTrack
    arm_names: list[str] = field(default_factory=list)
    arm_q: object = None                       # (N+1, n) radians
    wheel_names: tuple[str, str] = ("left_wheel_joint", "right_wheel_joint")
    checks: list[Check] = field(default_factory=list)
    info: dict = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    series: list[Series] = field(default_factory=list)
    scene: list = field(default_factory=list)          # scene objects (for the plot)
    moving: list = field(default_factory=list)         # (label, xs, ys) paths of moved objects
    footprint: list = field(default_factory=list)      # robot outline (root frame, convex)
    outline_of: object = None                          # or a function giving it, called when first needed
    wall: float = 0.0

    def outline(self) -> list:
        """The robot's outline: only the plot draws it, so a run may leave the computing to here."""
        if not self.footprint and self.outline_of is not None:
            self.footprint = self.outline_of()
        return self.footprint

    @property
    def passed(self) -> bool:
        return bool(all(c.passed for c in self.checks))

    # ------------------------------------------------------------ text
    def summary(self) -> str:
        n = len(self.t) - 1
        lines = [f"sim {self.program} · {self.robot} · {self.duration:g} s at {self.rate:g} Hz "
                 f"({n} steps, {self.wall:.2f} s wall)"]
        w = max((len(c.name) for c in self.checks), default=10)
        for c in self.checks:
            val = _fmt(c.value)
            unit = f" {c.unit}" if c.unit and val not in ("none", "-") else ""
            exp = f"   ({c.expected})" if c.expected else ""
            lines.append(f"  {'PASS' if c.passed else 'FAIL'}  {c.name:<{w}}  {val}{unit}{exp}")
            if c.detail:
                lines.append(f"        {'':<{w}}  {c.detail}")
        for k, v in self.info.items():
            lines.append(f"  info  {k}: {_fmt(v)}")
        for note in self.notes:
            lines.append(f"  note  {note}")
        lines.append(f"verdict: {'PASS' if self.passed else 'FAIL'}")
        return "\n".join(lines) + "\n"

    def as_json(self) -> str:
        d = {"program": self.program, "robot": self.robot, "rate": self.rate, "duration": self.duration,
             "steps": len(self.t) - 1, "passed": self.passed, "verdict": "pass" if self.passed else "fail",
             "checks": [c.as_dict() for c in self.checks],
             "info": {k: _plain(v) for k, v in self.info.items()}, "notes": list(self.notes),
             "final_pose": {"x": float(self.base.x[-1]), "y": float(self.base.y[-1]),
                            "yaw": float(self.base.yaw[-1])}}
        return json.dumps(d, indent=2, sort_keys=False) + "\n"

    # ------------------------------------------------------------ csv
    def csv_bytes(self) -> bytes:
        """One table like the seed's merged joint_states: base pose, arm joints, then wheels.

        Each column name carries its unit: time_s, base_x_m, base_yaw_rad, arti1_rad (the arm's
        servos are revolute), left_wheel_joint_rad (wheel angle)."""
        import io

        import numpy as np

        cols = [self.t, self.base.x, self.base.y, self.base.yaw]
        head = ["time_s", "base_x_m", "base_y_m", "base_yaw_rad"]
        if self.arm_q is not None:
            for i, n in enumerate(self.arm_names):
                cols.append(self.arm_q[:, i])
                head.append(f"{n}_rad")
        cols += [self.base.wheel_left, self.base.wheel_right]
        head += [f"{n}_rad" for n in self.wheel_names]
        data = np.column_stack(cols)
        buf = io.StringIO()
        buf.write(",".join(head) + "\n")
        np.savetxt(buf, data, delimiter=",", fmt="%.6f")
        return buf.getvalue().replace("-0.000000", "0.000000").encode()


def _plain(v):
    if isinstance(v, float):
        return None if math.isnan(v) else round(v, 6)
    if hasattr(v, "item"):
        return _plain(v.item())
    if isinstance(v, (list, tuple)):
        return [_plain(x) for x in v]
    if isinstance(v, dict):
        return {k: _plain(x) for k, x in v.items()}
    return v


def _fmt(v) -> str:
    if isinstance(v, float):
        if math.isnan(v):
            return "-"
        a = abs(v)
        return f"{v:.4f}" if a < 100 else f"{v:.1f}"
    if isinstance(v, (list, tuple)):
        return ", ".join(_fmt(x) for x in v)
    if isinstance(v, dict):
        return ", ".join(f"{k} {_fmt(x)}" for k, x in v.items())
    return str(v)


def ratio_checks(v_ratios: list, w_ratios: list, tolerance: float) -> list:
    """The speed and turn-rate verdicts of a drive: the worst achieved/commanded ratio of the
    segments that command each, within ``tolerance`` of 1."""
    out = []
    for name, ratios in (("speed ratio", v_ratios), ("turn-rate ratio", w_ratios)):
        if ratios:
            worst = max(ratios, key=lambda x: abs(x - 1.0))
            out.append(Check(name, abs(worst - 1) <= tolerance, float(worst), "",
                             f"achieved/commanded = 1 ±{tolerance:.0%}"))
    return out
