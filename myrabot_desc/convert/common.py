"""Small shared pieces: warnings, number formatting, rigid transforms, XML helpers."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from lxml import etree


@dataclass
class Notes:
    """Warnings gathered during a conversion (printed on stderr by the CLI)."""

    warnings: list[str] = field(default_factory=list)

    def warn(self, message: str, loc=None) -> None:
        text = f"{loc}: warning: {message}" if loc else f"warning: {message}"
        if text not in self.warnings:
            self.warnings.append(text)


def num(x: float) -> str:
    """Shortest stable text for a float: 12 significant digits, no -0, no 1e-17 noise."""
    x = float(x)
    if abs(x) < 1e-12:
        x = 0.0
    s = f"{x:.12g}"
    return "0" if s in ("-0", "0") else s


def nums(values) -> str:
    return " ".join(num(v) for v in values)


def to_float(text, default=None):
    if text is None:
        return default
    try:
        return float(str(text).strip())
    except ValueError:
        return default


def to_floats(text) -> list[float] | None:
    if text is None:
        return None
    try:
        return [float(t) for t in str(text).split()]
    except ValueError:
        return None


def to_bool(text, default=None):
    if text is None:
        return default
    t = str(text).strip().lower()
    if t in ("1", "true", "yes", "on"):
        return True
    if t in ("0", "false", "no", "off"):
        return False
    return default


# ---------------------------------------------------------------- transforms (numpy, imported lazily)
def transform(xyz=(0.0, 0.0, 0.0), rpy=(0.0, 0.0, 0.0)):
    """4x4 transform, URDF convention R = Rz(yaw) Ry(pitch) Rx(roll)."""
    import numpy as np

    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    T = np.eye(4)
    T[:3, :3] = [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                 [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                 [-sp, cp * sr, cp * cr]]
    T[:3, 3] = xyz
    return T


def pose_T(pose):
    """Transform of a model.Pose (or None = identity)."""
    if pose is None:
        return transform()
    return transform(pose.xyz, pose.rpy)


def rpy_of(R) -> tuple[float, float, float]:
    """Roll, pitch, yaw of a rotation matrix (inverse of ``transform``)."""
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


def pose_text(T) -> str:
    return nums(list(T[:3, 3]) + list(rpy_of(T[:3, :3])))


def is_identity(T, tol: float = 1e-12) -> bool:
    import numpy as np

    return bool(np.allclose(T, np.eye(4), atol=tol))


# ---------------------------------------------------------------- XML
def sub(parent, tag: str, text=None, **attrs):
    """Append a child element; ``text`` may be a str, a number or a sequence of numbers."""
    el = etree.SubElement(parent, tag, {k.rstrip("_"): str(v) for k, v in attrs.items() if v is not None})
    if text is not None:
        if isinstance(text, bool):
            el.text = "true" if text else "false"
        elif isinstance(text, (int, float)):
            el.text = num(text)
        elif isinstance(text, (list, tuple)):
            el.text = nums(text)
        else:
            el.text = str(text)
    return el


def comment(parent, text: str):
    # XML comments may not contain "--"
    c = etree.Comment(" " + text.replace("--", "- -") + " ")
    parent.append(c)
    return c


def local(tag) -> str:
    return tag.rsplit("}", 1)[-1] if isinstance(tag, str) else ""


def ns_kind(tag) -> str | None:
    """'controller', 'sensor', 'interface'... for Electric-dialect elements, else None."""
    if isinstance(tag, str) and tag.startswith("{"):
        uri = tag[1:].split("}", 1)[0]
        if "#" in uri:
            return uri.rsplit("#", 1)[1]
    return None


def xml_text(el) -> str:
    """An element as compact one-line-ish XML text (for comments)."""
    import copy

    e = copy.deepcopy(el)
    etree.cleanup_namespaces(e)
    text = etree.tostring(e, encoding="unicode", with_tail=False)
    return text


def pretty(root, xml_declaration: bool = True) -> str:
    etree.indent(root, space="  ")
    body = etree.tostring(root, encoding="unicode", pretty_print=True)
    return ('<?xml version="1.0" encoding="utf-8"?>\n' if xml_declaration else "") + body
