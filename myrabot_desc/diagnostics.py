"""Locations and diagnostics shared by build warnings and check findings."""

from __future__ import annotations

from dataclasses import dataclass, field

SEVERITIES = ("error", "warning", "info")


@dataclass(frozen=True)
class Loc:
    """A place in a source file (a xacro or URDF file); line is 1-based."""

    file: str
    line: int | None = None

    def __str__(self) -> str:
        return f"{self.file}:{self.line}" if self.line else self.file


@dataclass
class Diagnostic:
    """One finding: a stable code, a severity, a message with the numbers that matter."""

    code: str
    severity: str
    message: str
    loc: Loc | None = None
    # Machine-readable extras (numbers, suggested fix) for JSON output.
    data: dict = field(default_factory=dict)

    def __str__(self) -> str:
        where = f"{self.loc}: " if self.loc else ""
        return f"{where}{self.severity}: {self.code} {self.message}"


SEVERITY_ORDER = {"error": 0, "warning": 1, "info": 2}


def sort_diagnostics(diags) -> list:
    """Errors, warnings, info; then by code, location and message (the report order)."""
    return sorted(diags, key=lambda d: (SEVERITY_ORDER.get(d.severity, 3), d.code, str(d.loc or ""), d.message))
