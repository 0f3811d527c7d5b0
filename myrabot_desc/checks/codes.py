"""Every code ``check`` can report, and what to say about a code that does not exist.

A ``--select Z999`` that matches nothing would silently turn the lint off, so unknown codes
and prefixes are errors with a did-you-mean (command line and configuration alike).
"""

from __future__ import annotations

from myrabot_desc.checks.report import rule_table


def known_codes() -> list[str]:
    """Every code (imports the rule modules: asked only when there is a code to check)."""
    global _KNOWN
    if _KNOWN is None:
        _KNOWN = [row[0] for row in rule_table()]
    return _KNOWN


_KNOWN: list[str] | None = None


def closest(word: str, choices) -> str | None:
    import difflib

    m = difflib.get_close_matches(word, list(choices), n=1, cutoff=0.6)
    return m[0] if m else None


def unknown_code_message(pattern: str, known) -> str | None:
    """None when ``pattern`` (a code, a prefix such as ``I`` or ``G01``, or ``ALL``) selects a
    known code; else the message, with the nearest code."""
    p = pattern.strip().upper()
    if not p or p == "ALL" or any(c.startswith(p) for c in known):
        return None
    guess = closest(p, known) or closest(p, sorted({c[0] for c in known}))
    if guess is None and p[:1] in {c[0] for c in known}:
        guess = next(c for c in sorted(known) if c[0] == p[0])
    return f"unknown rule code '{pattern}'" + (f"; did you mean '{guess}'?" if guess else "") + \
        " (`myrabot-desc check --list-rules` lists them)"


def split_codes(values) -> list[str]:
    return [c.strip().upper() for v in values for c in v.split(",") if c.strip()]
