"""``check``: lint a robot model with a registry of small rules (see docs/rules.md).

Library use::

    from myrabot_desc.model.loader import load_robot
    from myrabot_desc.checks import run_checks, CheckOptions
    diags = run_checks(load_robot("robot.urdf.xacro"), CheckOptions(inertia=True))
"""

from __future__ import annotations

from myrabot_desc.checks.context import CheckOptions, Context

__all__ = ["CheckOptions", "Context", "run_checks", "check_robot", "sort_diagnostics"]

SEVERITY_ORDER = {"error": 0, "warning": 1, "info": 2}


def check_robot(robot, options: CheckOptions | None = None, select=(), ignore=()):
    """Run every rule on ``robot``; return (diagnostics, context). Build and load diagnostics come first."""
    from myrabot_desc.checks.registry import load_all, matches, to_diagnostic

    rules = load_all()
    ctx = Context(robot, options)
    out = list(robot.build_warnings) + list(robot.load_issues)
    for code, r in rules.items():
        if select and not matches(code, select):
            continue
        if ignore and matches(code, ignore):
            continue
        for f in r.func(ctx) or ():
            out.append(to_diagnostic(r, f))
    if select:
        out = [d for d in out if matches(d.code, select)]
    if ignore:
        out = [d for d in out if not matches(d.code, ignore)]
    return sort_diagnostics(out), ctx


def sort_diagnostics(diags) -> list:
    """Errors, warnings, info; then by code, location and message (the report order)."""
    return sorted(diags, key=lambda d: (SEVERITY_ORDER.get(d.severity, 3), d.code, str(d.loc or ""), d.message))


def run_checks(robot, options: CheckOptions | None = None, select=(), ignore=()):
    """Diagnostics for ``robot`` (sorted: errors, warnings, info; then by code)."""
    return check_robot(robot, options, select, ignore)[0]
