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


def warn_load_issues(robot, notes: Notes, fate: str = "left out of the conversion") -> None:
    """What the loader could not read (a NaN, a nameless link...): say so at its file:line
    rather than convert silently around it. ``fate``: what the converter does with it."""
    for d in robot.load_issues:
        notes.warn(f"{d.code} {d.message}: {fate} (run check)", d.loc)


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


# ---------------------------------------------------------------- rigid transforms
# Pure Python on purpose: a conversion needs a few hundred 4x4 products, and importing
# numpy for them would cost more than the whole conversion (issue 8: convert under half
# of `ign sdf -p`). A transform is a pair (R, p): R a 3x3 rotation as row tuples, p a
# 3-tuple translation; it maps x to R x + p.
Mat3 = tuple[tuple[float, float, float], tuple[float, float, float], tuple[float, float, float]]
Tf = tuple[Mat3, tuple[float, float, float]]

EYE3: Mat3 = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
IDENTITY: Tf = (EYE3, (0.0, 0.0, 0.0))


def transform(xyz=(0.0, 0.0, 0.0), rpy=(0.0, 0.0, 0.0)) -> Tf:
    """The transform of an origin, URDF convention R = Rz(yaw) Ry(pitch) Rx(roll)."""
    r, p, y = (float(v) for v in rpy)
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    R = ((cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr),
         (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr),
         (-sp, cp * sr, cp * cr))
    x, yy, z = (float(v) for v in xyz)
    return R, (x, yy, z)


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


def pose_text(T: Tf) -> str:
    R, p = T
    return nums(list(p) + list(rpy_of(R)))


def is_identity(T: Tf, tol: float = 1e-12) -> bool:
    if T is IDENTITY:
        return True
    R, p = T
    return (all(abs(v) <= tol for v in p)
            and all(abs(R[i][j] - (1.0 if i == j else 0.0)) <= tol for i in range(3) for j in range(3)))


# ---------------------------------------------------------------- XML
def sub(parent, tag: str, text=None, **attrs):
    """Append a child element; ``text`` may be a str, a number or a sequence of numbers."""
    if attrs:
        el = etree.SubElement(parent, tag, {k.rstrip("_"): str(v) for k, v in attrs.items() if v is not None})
    else:
        el = etree.SubElement(parent, tag)
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
