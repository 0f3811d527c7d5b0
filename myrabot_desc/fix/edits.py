"""Text edits of source files: only the characters of a value change.

An edit replaces bytes ``start:end`` of one file with new text. Formatting, comments, attribute
order, quotes and line endings around it are the file's own; a number is written in the file's
style (``.260`` stays without its leading zero, ``1e-3`` keeps an exponent).
"""

import math
import re
from pathlib import Path

from myrabot_desc.records import Struct


class Edit(Struct):
    """Replace bytes ``start:end`` of ``path`` (shown as ``file``) with ``new``."""

    file: str
    path: Path
    start: int
    end: int
    new: str


class Conflict(Exception):
    """Two edits change overlapping text differently."""


def apply(data: bytes, edits) -> bytes:
    """``data`` with ``edits`` (all of one file) applied; identical edits count once."""
    todo = sorted(set((e.start, e.end, e.new) for e in edits))
    out = []
    pos = 0
    last = None
    for start, end, new in todo:
        if start < pos or (start, end) == last:
            raise Conflict(f"bytes {start}-{end} are edited twice")
        last = (start, end)
        out.append(data[pos:start])
        out.append(new.encode("utf-8"))
        pos = end
    out.append(data[pos:])
    return b"".join(out)


_EXP = re.compile(r"[eE]")


def number(x: float, like: str = "", digits: int = 6) -> str:
    """``x`` with ``digits`` significant digits, in the style of ``like`` (the text it replaces)."""
    if x == 0 or not math.isfinite(x):
        return "0" if x == 0 else repr(x)
    s = f"{x:.{digits}g}"
    if _EXP.search(like):                            # the file writes exponents: 1.271e-02
        mant, exp = f"{x:.{digits - 1}e}".split("e")
        if "." in mant:
            mant = mant.rstrip("0").rstrip(".")
        s = f"{mant}e{exp}"
        return s.replace("e", "E") if "E" in like else s
    if "e" in s:
        decimals = max(0, digits - 1 - math.floor(math.log10(abs(x))))
        s = f"{x:.{decimals}f}"
        if "." in s:
            s = s.rstrip("0").rstrip(".")
    if s in ("-0", "0"):
        return "0"
    if re.match(r"^-?\.\d", like.strip()):          # the file writes .26, not 0.26
        s = re.sub(r"^(-?)0\.", r"\1.", s)
    return s


def numbers(values, like: str = "") -> str:
    """A vector in the style of ``like`` (its separator is one space, as URDF writes them)."""
    parts = like.split()
    return " ".join(number(v, parts[i] if i < len(parts) else "") for i, v in enumerate(values))


def removal(data: bytes, start: int, end: int) -> tuple[int, int]:
    """The bytes to remove for ``start:end`` (an element or an attribute) so that no blank line or
    double space is left: the whitespace before it on its line, and its line break when it was
    alone on the line."""
    s = start
    while s > 0 and data[s - 1:s] in (b" ", b"\t"):
        s -= 1
    e = end
    line_start = s == 0 or data[s - 1:s] == b"\n"
    rest = e
    while rest < len(data) and data[rest:rest + 1] in (b" ", b"\t"):
        rest += 1
    if line_start and data[rest:rest + 2] == b"\r\n":
        return s, rest + 2
    if line_start and data[rest:rest + 1] == b"\n":
        return s, rest + 1
    if data[e:e + 1] in (b"/", b">") and s < start:      # an attribute right before /> or >
        return s, end
    return s, end
