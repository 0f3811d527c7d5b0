"""Locations and diagnostics shared by build warnings and check findings.

Plain classes, not dataclasses: ``dataclasses`` imports ``inspect`` (~10 ms), which ``build``
would pay at every start for two small records.
"""

from __future__ import annotations

from myrabot_desc.sanitize import clean

SEVERITIES = ("error", "warning", "info")


class Loc:
    """A place in a source file (a xacro or URDF file); line is 1-based. Immutable, hashable."""

    __slots__ = ("file", "line")

    def __init__(self, file: str, line: int | None = None):
        object.__setattr__(self, "file", file)
        object.__setattr__(self, "line", line)

    def __setattr__(self, name, value):
        raise AttributeError(f"cannot assign to field '{name}'")

    def __delattr__(self, name):
        raise AttributeError(f"cannot delete field '{name}'")

    def __eq__(self, other):
        if other.__class__ is self.__class__:
            return (self.file, self.line) == (other.file, other.line)
        return NotImplemented

    def __hash__(self):
        return hash((self.file, self.line))

    def __repr__(self) -> str:
        return f"Loc(file={self.file!r}, line={self.line!r})"

    def __reduce__(self):
        return (Loc, (self.file, self.line))

    def __str__(self) -> str:
        return f"{self.file}:{self.line}" if self.line else self.file


class Diagnostic:
    """One finding: a stable code, a severity, a message with the numbers that matter."""

    __slots__ = ("code", "severity", "message", "loc", "data")

    def __init__(self, code: str, severity: str, message: str, loc: Loc | None = None, data: dict | None = None):
        self.code = code
        self.severity = severity
        self.message = message
        self.loc = loc
        # Machine-readable extras (numbers, suggested fix) for JSON output.
        self.data = {} if data is None else data

    def _fields(self) -> tuple:
        return (self.code, self.severity, self.message, self.loc, self.data)

    def __eq__(self, other):
        if other.__class__ is self.__class__:
            return self._fields() == other._fields()
        return NotImplemented

    __hash__ = None     # mutable, compared by value (as the dataclass it was)

    def __repr__(self) -> str:
        return (f"Diagnostic(code={self.code!r}, severity={self.severity!r}, message={self.message!r}, "
                f"loc={self.loc!r}, data={self.data!r})")

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
