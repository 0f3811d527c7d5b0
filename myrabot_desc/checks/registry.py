"""The rule registry: a plain list of the rule modules and the rules they define.

Each rule module imports only :mod:`myrabot_desc.checks.rule` (the decorator); this
module imports the rule modules and collects the functions the decorator marked, so
nothing imports back. The code never changes meaning; :func:`to_diagnostic` fills in
code, severity and rule name when findings become Diagnostics.
"""

from __future__ import annotations

from collections.abc import Iterable

from myrabot_desc.checks import (
    collisions,
    frames,
    inertia,
    inertia_geometry,
    meshes,
    physics,
    plugins,
    statics,
    tree,
    urdf_syntax,
)
from myrabot_desc.checks.external import EXTERNAL  # noqa: F401  (re-exported: codes outside the rule functions)
from myrabot_desc.checks.rule import FAMILIES, Finding, Rule  # noqa: F401  (re-exported for library users)
from myrabot_desc.diagnostics import Diagnostic

MODULES = (tree, urdf_syntax, inertia, inertia_geometry, frames, plugins, meshes, physics, collisions, statics)


def _collect() -> dict[str, Rule]:
    rules: dict[str, Rule] = {}
    for module in MODULES:
        for obj in vars(module).values():
            r = getattr(obj, "rule", None)
            if isinstance(r, Rule) and r.func is obj:
                if r.code in rules:
                    raise RuntimeError(f"duplicate rule code {r.code}")
                rules[r.code] = r
    return dict(sorted(rules.items()))


RULES: dict[str, Rule] = _collect()


def load_all() -> dict[str, Rule]:
    """Every rule, by code (sorted)."""
    return RULES


def matches(code: str, patterns: Iterable[str]) -> bool:
    """A code matches 'I', 'I00', 'I005' or 'ALL' (prefix match, case-insensitive)."""
    code = code.upper()
    return any(p == "ALL" or code.startswith(p) for p in (p.strip().upper() for p in patterns) if p)


def to_diagnostic(r: Rule, f: Finding) -> Diagnostic:
    """``f`` as rule ``r``'s Diagnostic, with the finding's own data: nothing changes a diagnostic's
    data, and the reports name the rule from its code (no copy per finding: a big robot has 40,000)."""
    return Diagnostic(r.code, f.severity or r.severity, f.message, f.loc, f.data)
