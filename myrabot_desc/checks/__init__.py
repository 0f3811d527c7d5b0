"""``check``: lint a robot model with a registry of small rules (see docs/rules.md).

Library use::

    from myrabot_desc.model.loader import load_robot
    from myrabot_desc.checks import run_checks, CheckOptions
    diags = run_checks(load_robot("robot.urdf.xacro"), CheckOptions(inertia=True))
"""

from __future__ import annotations

from myrabot_desc.checks import suppress
from myrabot_desc.checks.context import CheckOptions, Context
from myrabot_desc.checks.registry import load_all, matches, to_diagnostic
from myrabot_desc.diagnostics import SEVERITY_ORDER, sort_diagnostics  # noqa: F401  (library API)

__all__ = ["CheckOptions", "Context", "run_checks", "check_robot", "sort_diagnostics"]



def check_robot(robot, options: CheckOptions | None = None, select=(), ignore=(), unused: bool = True):
    """Run every rule on ``robot``; return (diagnostics, context). Build and load diagnostics come first.

    Inline suppressions in the model's sources (``<!-- myrabot-desc: ignore[CODES] -->``,
    checks/suppress.py) drop the findings they cover; with ``unused`` each one that silenced
    nothing is an X009 finding (``check`` over several files passes False and decides over the
    whole run, from ``ctx.suppressions_seen``/``ctx.suppressions_used``)."""

    rules = load_all()
    ctx = Context(robot, options)
    out = list(robot.build_warnings) + list(robot.load_issues)
    for code, r in rules.items():
        if select and not matches(code, select):
            continue
        if ignore and matches(code, ignore):
            continue
        for f in r.func(ctx) or ():
            d = to_diagnostic(r, f)
            out.append(d)
            if f.fix is not None:
                ctx.fixes.append((d, f.fix))
    if select:
        out = [d for d in out if matches(d.code, select)]
    if ignore:
        out = [d for d in out if not matches(d.code, ignore)]

    def enabled(code):
        return (not select or matches(code, select)) and not (ignore and matches(code, ignore))

    ctx.suppressed = []
    out, seen, used = suppress.apply(out, robot, enabled, dropped=ctx.suppressed)
    if not enabled("X009"):
        out, seen = [d for d in out if d.code != "X009"], []
    ctx.suppressions_seen, ctx.suppressions_used = seen, used
    if unused:
        out += suppress.unused_diagnostics(seen, set(used))
    return sort_diagnostics(out), ctx


def run_checks(robot, options: CheckOptions | None = None, select=(), ignore=()):
    """Diagnostics for ``robot`` (sorted: errors, warnings, info; then by code)."""
    return check_robot(robot, options, select, ignore)[0]
