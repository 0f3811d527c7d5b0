"""Model text on its way into the viewer's Markdown: escaped, so that a robot, link, joint or mesh
name, or a finding's message, is shown as the characters it holds and never read as Markdown or
HTML (viser renders both). Plain text fields (a button's label, a slider's name) need none of this.
"""

from __future__ import annotations

import re

_CONTROL = re.compile(r"[\x00-\x1f\x7f\u2028\u2029]")
# every ASCII punctuation character may be backslash-escaped in CommonMark; '<' and '&' become
# entities as well (an escaped '<' still reaches a raw-HTML-aware renderer as '<')
_SPECIAL = re.compile(r"[\\`*_{}\[\]()#+\-.!|~\"'$%=:;,/?@^]")


def visible(text: str) -> str:
    """Control characters and line breaks as visible escapes (``\\n``, ``\\x07``): one line."""
    def esc(m):
        c = m.group(0)
        return {"\n": "\\n", "\r": "\\r", "\t": "\\t"}.get(c, f"\\x{ord(c):02x}" if ord(c) < 256 else f"\\u{ord(c):04x}")

    return _CONTROL.sub(esc, str(text))


def md(text) -> str:
    """``text`` as literal Markdown inline text: one line, punctuation escaped, ``<``/``>``/``&``
    as entities."""
    out = _SPECIAL.sub(lambda m: "\\" + m.group(0), visible(text))
    return out.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def md_code(text) -> str:
    """``text`` as an inline code span (literal by definition) whose fence no backtick run in the
    text can close; one line."""
    body = visible(text)
    runs = [len(r) for r in re.findall(r"`+", body)]
    fence = "`" * (max(runs, default=0) + 1)
    pad = " " if body.startswith("`") or body.endswith("`") or not body.strip() else ""
    return f"{fence}{pad}{body}{pad}{fence}"


def md_code_block(text, lang: str = "") -> str:
    """A fenced code block whose fence is longer than any backtick run of ``text`` (so no line of
    it can close the block); control characters other than line breaks made visible."""
    body = _CONTROL.sub(lambda m: m.group(0) if m.group(0) == "\n" else visible(m.group(0)), str(text))
    runs = [len(r) for r in re.findall(r"`+", body)]
    fence = "`" * max(3, max(runs, default=0) + 1)
    return f"{fence}{lang}\n{body}\n{fence}\n"
