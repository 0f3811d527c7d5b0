"""Locations and diagnostics shared by build warnings and check findings.

Records of :mod:`myrabot_desc.records`, not dataclasses: ``dataclasses`` imports ``inspect``
(~10 ms), which ``build`` would pay at every start for two small records.
"""

from __future__ import annotations

from myrabot_desc.records import Frozen, Record, set_field
from myrabot_desc.sanitize import clean

SEVERITIES = ("error", "warning", "info")


class Loc(Frozen):
    """A place in a source file (a xacro or URDF file); line is 1-based. Immutable, hashable."""

    __slots__ = ("file", "line")

    def __init__(self, file: str, line: int | None = None):
        set_field(self, "file", file)
        set_field(self, "line", line)

    # equality and hash without the generic field walk: a large robot compares and hashes 40,000
    def __eq__(self, other):
        if other.__class__ is self.__class__:
            return (self.file, self.line) == (other.file, other.line)
        return NotImplemented

    def __hash__(self):
        return hash((self.file, self.line))

    def __str__(self) -> str:
        return f"{self.file}:{self.line}" if self.line else self.file


class Diagnostic(Record):
    """One finding: a stable code, a severity, a message with the numbers that matter."""

    __slots__ = ("code", "severity", "message", "loc", "data")

    def __init__(self, code: str, severity: str, message: str, loc: Loc | None = None, data: dict | None = None):
        self.code = code
        self.severity = severity
        self.message = message
        self.loc = loc
        # Machine-readable extras (numbers, suggested fix) for JSON output.
        self.data = {} if data is None else data

    def __str__(self) -> str:
        where = f"{clean(self.loc)}: " if self.loc else ""
        return f"{where}{clean(self.severity)}: {clean(self.code)} {clean(self.message)}"


SEVERITY_ORDER = {"error": 0, "warning": 1, "info": 2}


def sort_diagnostics(diags) -> list:
    """Errors, warnings, info; then by code, file, line (as a number: 19 before 119) and message
    (the report order)."""
    order = SEVERITY_ORDER.get

    def key(d):
        loc = d.loc
        if loc.__class__ is Loc:        # (no str() of it made for nothing: a big robot has 40,000)
            file, line = loc.file, loc.line
        else:
            file, line = getattr(loc, "file", None), getattr(loc, "line", None)
            if file is None and not hasattr(loc, "file"):
                file = str(loc or "")
        return (order(d.severity, 3), d.code, file, line if line is not None else -1, d.message)
    return sorted(diags, key=key)
