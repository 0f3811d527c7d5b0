"""The rule registry: one small function per rule, each with a stable code.

A rule is a function ``f(ctx) -> Iterable[Finding]`` decorated with :func:`rule`.
Its docstring's first line is the rule's summary (shown by ``--format sarif`` and
in docs/rules.md). The code never changes meaning; the registry fills in code,
severity and rule name when it turns findings into Diagnostics.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Iterable

from myrabot_desc.diagnostics import Diagnostic, Loc

FAMILIES = {
    "X": "build (xacro)",
    "T": "tree and URDF syntax",
    "I": "inertia",
    "S": "sensors and frames",
    "G": "Gazebo and plugins",
    "M": "meshes",
    "P": "physics and stability",
}


@dataclass
class Finding:
    """What a rule yields: the message with the numbers, where, and machine data."""

    message: str
    loc: Loc | None = None
    data: dict = field(default_factory=dict)
    severity: str | None = None      # overrides the rule's default (documented per rule)


@dataclass(frozen=True)
class Rule:
    code: str
    name: str                        # kebab-case, e.g. "triangle-inequality"
    severity: str                    # default severity: error | warning | info
    func: Callable
    needs: str | None = None         # 'meshes' (loads mesh files) or None
    summary: str = ""

    @property
    def doc(self) -> str:
        return (self.func.__doc__ or "").strip()


RULES: dict[str, Rule] = {}


def rule(code: str, name: str, severity: str, needs: str | None = None):
    """Register ``func`` as rule ``code``."""

    def deco(func):
        if code in RULES:
            raise RuntimeError(f"duplicate rule code {code}")
        summary = (func.__doc__ or "").strip().splitlines()[0] if func.__doc__ else name
        RULES[code] = Rule(code, name, severity, func, needs, summary)
        return func

    return deco


# Codes produced outside the rule functions (by the build, or for whole-file problems).
EXTERNAL = {
    "X001": ("legacy-upgraded", "warning", "Electric/Fuerte xacro syntax was upgraded during the build."),
    "X002": ("unexpanded-macro-call", "error", "A tag looks like a macro call that xacro passed through unexpanded."),
    "X003": ("macro-only-file", "warning", "The top-level file defines macros but instantiates none (empty robot)."),
    "X004": ("package-resolves", "warning", "A package:// URI names a package that cannot be found."),
    "X005": ("expression-refused", "error", "A ${} expression was refused by the safe evaluator."),
    "X006": ("path-outside-allowed", "error", "An include or load_yaml reaches outside the allowed folders."),
    "X000": ("input-unprocessable", "error", "The file could not be processed (exit code 2)."),
    "T010": ("value-parses", "error", "A number or vector in the URDF cannot be read (the reader used the default)."),
}


def load_all() -> dict[str, Rule]:
    """Import every family module (they register on import) and return the registry."""
    from myrabot_desc.checks import (  # noqa: F401  (imported for registration)
        frames,
        inertia,
        inertia_geometry,
        meshes,
        physics,
        plugins,
        tree,
        urdf_syntax,
    )

    return dict(sorted(RULES.items()))


def matches(code: str, patterns: Iterable[str]) -> bool:
    """A code matches 'I', 'I00', 'I005' or 'ALL' (prefix match, case-insensitive)."""
    code = code.upper()
    return any(p == "ALL" or code.startswith(p) for p in (p.strip().upper() for p in patterns) if p)


def to_diagnostic(r: Rule, f: Finding) -> Diagnostic:
    data = dict(f.data)
    data.setdefault("rule", r.name)
    return Diagnostic(r.code, f.severity or r.severity, f.message, f.loc, data)
