"""The one output sanitiser: text from a model, a file name or a YAML value made safe to print.

Everything the tool prints that it did not write itself (link and joint names, messages that
quote them, file and folder names, ``xacro.message`` text, cached findings) passes through
:func:`clean` on its way to a terminal, a CI log or a report:

* control characters (C0, DEL, C1), line and paragraph separators, bidirectional overrides and
  lone surrogates (undecodable bytes of a file name) are written as escapes: ``\\n``, ``\\r``,
  ``\\t``, ``\\x1b``, ``\\u2028``; a file name's undecodable byte 0xff is ``\\xff``. So one value
  is one line, and no terminal escape sequence (colours, cursor moves, title or clipboard
  writes) reaches the terminal;
* a GitHub Actions workflow command cannot start: the runner reads a line as a command when it
  starts with ``::`` after its leading blanks, or holds ``##[`` anywhere (the old form); a
  value that starts so has its first ``:`` written ``\\x3a``, and ``##[`` becomes ``#\\x23[``.

The result is plain printable text (the same value cleaned twice is unchanged). It is for
terminals and logs; JSON and SARIF escape control characters themselves and only need
:func:`json_safe` (no lone surrogates, which no UTF-8 encoder writes).
"""

from __future__ import annotations

_NAMED = {"\n": "\\n", "\r": "\\r", "\t": "\\t"}
# Unicode's own line breaks and the invisible direction controls ("Trojan Source")
_EXTRA = frozenset("\u2028\u2029\u200e\u200f\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069\ufeff")


def _bad(ch: str) -> bool:
    o = ord(ch)
    return o < 0x20 or 0x7F <= o < 0xA0 or ch in _EXTRA or 0xD800 <= o < 0xE000


def _escape(ch: str) -> str:
    named = _NAMED.get(ch)
    if named:
        return named
    o = ord(ch)
    if 0xDC80 <= o <= 0xDCFF:            # an undecodable byte kept by surrogateescape (file names)
        return f"\\x{o - 0xDC00:02x}"
    return f"\\x{o:02x}" if o < 0x100 else f"\\u{o:04x}"


def clean(text) -> str:
    """``text`` (any value: str() of it) as one printable line; see the module docstring."""
    s = text if isinstance(text, str) else str(text)
    if s.isprintable() and "::" not in s and "##[" not in s:
        return s                         # the common case: nothing to do, no copy
    out = "".join(_escape(ch) if _bad(ch) else ch for ch in s)
    stripped = out.lstrip()
    if stripped.startswith("::"):
        lead = len(out) - len(stripped)
        out = out[:lead] + "\\x3a" + out[lead + 1:]
    if "##[" in out:
        out = out.replace("##[", "#\\x23[")
    return out


def clean_lines(text) -> str:
    """Several lines of untrusted text (a ``xacro.message`` call's output): each line cleaned,
    the line breaks kept (a trailing one too)."""
    s = text if isinstance(text, str) else str(text)
    end = "\n" if s.endswith("\n") else ""
    body = s[:-1] if end else s
    return "\n".join(clean(line) for line in body.split("\n")) + end


def json_safe(text) -> str:
    """A string JSON can carry as UTF-8: lone surrogates (a non-UTF-8 file name's bytes) escaped
    as in :func:`clean`; everything else as it is (the JSON encoder escapes control characters)."""
    s = text if isinstance(text, str) else str(text)
    try:
        s.encode("utf-8")
        return s
    except UnicodeEncodeError:
        return "".join(_escape(ch) if 0xD800 <= ord(ch) < 0xE000 else ch for ch in s)
