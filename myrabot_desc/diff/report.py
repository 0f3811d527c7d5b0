"""The diff as text (terminal), JSON (stable schema) and Markdown (a pull-request comment).

Every model text (names, messages, file names) is escaped for where it goes: control characters
out of the terminal, Markdown's table syntax out of the comment.
"""

from __future__ import annotations

import json
import re

from myrabot_desc.diff.run import DiffResult, where_text

JSON_SCHEMA = "myrabot-desc/diff-report/1"
MARKER = "<!-- myrabot-desc diff -->"
_CTRL = re.compile(r"[\x00-\x08\x0b-\x1f\x7f-\x9f\u202a-\u202e\u2066-\u2069]")


def clean(text) -> str:
    """Model text made safe for a terminal or a CI log (no escape sequences, no bidi overrides)."""
    return _CTRL.sub("?", str(text))


def md(text) -> str:
    """Model text made safe inside a Markdown table cell."""
    t = clean(text).replace("\n", " ").replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
    t = re.sub(r"([\\`*_{}\[\]|#!~])", r"\\\1", t)
    return t.replace("@", "@\u200b")


def _rows(res: DiffResult):
    for it in res.items:
        yield it, where_text(it.where, res.shown, res.shown_old)


def text(res: DiffResult) -> str:
    if not res.items:
        return ""
    out = [f"--- {clean(res.old_label)}", f"+++ {clean(res.new_label)}"]
    section = None
    for it, where in _rows(res):
        head = f"{it.section} {clean(it.subject)}: {clean(it.what)}"
        if it.old and it.new:
            body = f"{clean(it.old)} -> {clean(it.new)} ({clean(it.change)})"
        elif it.new:
            body = f"{clean(it.change)}: {clean(it.new)}" if it.change != it.new else clean(it.new)
        elif it.old:
            body = f"{clean(it.change)}: {clean(it.old)}"
        else:
            body = clean(it.change)
        line = f"  {head}: {body}"
        if where:
            line += f"  [{clean(where)}]"
        out.append(line)
        section = it.section
    del section
    n = len(res.items)
    out.append(f"{n} change{'s' if n != 1 else ''}")
    return "\n".join(out) + "\n"


def to_json(res: DiffResult, version: str) -> str:
    doc = {
        "schema": JSON_SCHEMA,
        "tool": {"name": "myrabot-desc", "version": version},
        "old": res.old_label,
        "new": res.new_label,
        "changed": bool(res.items),
        "changes": res.data,
        "items": [{"section": it.section, "subject": it.subject, "what": it.what, "old": it.old, "new": it.new,
                   "change": it.change, "size": round(it.size, 6), "where": where} for it, where in _rows(res)],
    }
    return json.dumps(doc, indent=2, ensure_ascii=False, default=str) + "\n"


def markdown(res: DiffResult, limit: int = 25, image: str | None = None) -> str:
    """A pull-request comment: a short table, largest changes first; ``image``: a before/after picture URL."""
    out = [MARKER, f"### Robot model diff: `{md(res.new_label)}`", ""]
    if not res.items:
        out.append("No change to the built robot.")
        return "\n".join(out) + "\n"
    summary = _summary(res)
    if summary:
        out += [summary, ""]
    out += ["| | what | before | after | change | where |", "|---|---|---|---|---|---|"]
    rows = list(_rows(res))
    for it, where in rows[:limit]:
        out.append(f"| {it.section} | **{md(it.subject)}** {md(it.what)} | {md(it.old)} | {md(it.new)} | "
                   f"{md(it.change)} | {md(where or '')} |")
    if len(rows) > limit:
        out += ["", f"… and {len(rows) - limit} smaller changes (`myrabot-desc diff --format json` lists them all)."]
    if image:
        out += ["", f"![before / after]({image})"]
    return "\n".join(out) + "\n"


def _summary(res: DiffResult) -> str:
    d = res.data
    parts = []
    for key, label in (("links_added", "links added"), ("links_removed", "links removed"),
                       ("joints_added", "joints added"), ("joints_removed", "joints removed")):
        if d.get(key):
            parts.append(f"{len(d[key])} {label}")
    if d.get("links_renamed") or d.get("joints_renamed"):
        parts.append(f"{len(d.get('links_renamed', [])) + len(d.get('joints_renamed', []))} renamed")
    if "total_mass_kg" in d and d["total_mass_kg"]["delta"]:
        m = d["total_mass_kg"]
        parts.append(f"mass {m['old']:.3f} → {m['new']:.3f} kg")
    if "centre_of_mass_mm" in d:
        mv = d["centre_of_mass_mm"]["moved"]
        parts.append(f"centre of mass moved {sum(x * x for x in mv) ** 0.5:.1f} mm")
    eff = (d.get("drive") or {}).get("effect_text") or []
    parts += eff
    n_add = len(d.get("findings_added", []))
    n_rem = len(d.get("findings_removed", []))
    if n_add or n_rem:
        parts.append(f"check: {n_add} new finding{'s' if n_add != 1 else ''}, {n_rem} gone")
    return md("; ".join(parts)) if parts else ""
