"""What a fix run says: each change as plain data (JSON, SARIF), a summary, a unified diff."""

from __future__ import annotations

import difflib
import re

_CONTROL = re.compile(r"[\x00-\x1f\x7f-\x9f]")


def display_text(text: str) -> str:
    """A file name as a terminal or CI log may show it: control characters escaped."""
    return _CONTROL.sub(lambda m: f"\\x{ord(m.group()):02x}", text)


def change_data(change, sources, status: str) -> dict:
    """A Change as JSON-ready data. ``sources``: the model's sources (model/sources.Sources), whose
    files the edits' offsets refer to; ``status``: applied (written by --fix), proposed (what --fix
    would write), unsafe (needs --unsafe-fixes), refused (the rebuilt model did not prove it)."""
    edits = []
    for e in change.edits:
        data = sources.data(e.file)
        line, col = sources.line_col(e.file, e.start)
        edits.append({"file": e.file, "line": line, "column": col, "start": e.start, "end": e.end,
                      "old": data[e.start:e.end].decode("utf-8", "replace"), "new": e.new})
    return {"code": change.code, "message": change.message, "title": change.title, "safety": change.safety,
            "status": status, "edits": edits, "notes": list(change.notes)}


def not_fixed_data(n) -> dict:
    """A fix that cannot be written into the sources (status not-editable), with the reason."""
    w = n.where
    return {"code": n.code, "message": n.message, "status": "not-editable", "reason": n.reason,
            "where": f"{w.file}:{w.line}:{w.col}" if w is not None else None}


def unified_diff(files) -> str:
    """One unified diff of every FileFix (old -> new), as `git diff` shows a change."""
    out = []
    for f in files:
        old = f.old.decode("utf-8", "replace").splitlines(keepends=True)
        new = f.new.decode("utf-8", "replace").splitlines(keepends=True)
        name = display_text(f.name)
        out.extend(difflib.unified_diff(old, new, f"a/{name}", f"b/{name}"))
    text = "".join(out)
    return text if not text or text.endswith("\n") else text + "\n"


def summary(applied: int, unsafe_left: int, not_fixed: int, refused: int, remaining: int, wrote: bool) -> str:
    """'Fixed 7 findings (3 remaining); 2 more with --unsafe-fixes; ...' (ruff's words, ours)."""
    verb = "Fixed" if wrote else "Would fix"
    parts = [f"{verb} {applied} finding{'s' if applied != 1 else ''} ({remaining} remaining)"]
    if unsafe_left:
        parts.append(f"{unsafe_left} more with --unsafe-fixes")
    if not_fixed:
        parts.append(f"{not_fixed} not editable in the sources (computed or given on the command line)")
    if refused:
        parts.append(f"{refused} refused (the rebuilt model did not prove them)")
    return "; ".join(parts) + "."
