"""Inline suppressions: XML comments in the model's source files.

    <!-- myrabot-desc: ignore[I008,S005] the shell is hollow -->
    <link name="shell"> ... </link>

A comment silences those codes (or prefixes) for one element of the *source* file and
everything inside it:

* on the same line as an element's start tag, or on the line just before it: that element;
* anywhere else inside an element (e.g. as its last child): the enclosing element;
* ``ignore-file[CODES]`` anywhere: every finding located in that file.

Findings carry the xacro file:line they come from, so a comment inside a macro applies to
every expansion of the macro. A suppression that silenced nothing in the whole run (for a
code the run checked) is reported as X009, like ruff's RUF100.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import NamedTuple

from myrabot_desc.checks.codes import known_codes, unknown_code_message
from myrabot_desc.diagnostics import Diagnostic, Loc, sort_diagnostics
from myrabot_desc.safety import limit, safe_parser

COMMENT_RE = re.compile(r"myrabot-desc:\s*(ignore-file|ignore)\s*\[([^\]]*)\]")
MARKER = b"myrabot-desc:"


class Suppression(NamedTuple):
    file: str            # as the findings name it (display path)
    line: int            # the comment's line
    codes: tuple         # codes or prefixes, upper case
    start: int           # first line covered
    end: int             # last line covered
    whole_file: bool


_cache: dict = {}        # (resolved path, mtime_ns, size) -> [Suppression] (one read per file per process)


def suppressions_in(file: str) -> list[Suppression]:
    """Every suppression comment of one source file (cached per file version)."""
    p = Path(file)
    try:
        st = p.stat()
        key = (str(p.resolve()), st.st_mtime_ns, st.st_size)
    except OSError:
        return []
    if key in _cache:
        return [s._replace(file=file) for s in _cache[key]]

    out: list[Suppression] = []
    try:
        if st.st_size <= limit("max_input_bytes"):
            data = p.read_bytes()
            if MARKER in data:
                out = _parse(data, file)
    except OSError:
        pass
    _cache[key] = out
    return out


def _parse(data: bytes, file: str) -> list[Suppression]:
    from lxml import etree

    try:
        root = etree.fromstring(data, parser=safe_parser())
    except (etree.XMLSyntaxError, ValueError):
        return []
    comments = list(root.itersiblings(etree.Comment, preceding=True)) + list(root.iter(etree.Comment)) + \
        list(root.itersiblings(etree.Comment))
    out = []
    for c in comments:
        for m in COMMENT_RE.finditer(c.text or ""):
            codes = tuple(x.strip().upper() for x in m.group(2).split(",") if x.strip())
            if not codes:
                continue
            line = c.sourceline or 1
            if m.group(1) == "ignore-file":
                out.append(Suppression(file, line, codes, 1, 10**9, True))
                continue
            target = _target(c, root)
            start = target.sourceline or line
            end = max((e.sourceline or start) for e in target.iter())
            out.append(Suppression(file, line, codes, start, end, False))
    return out


def _target(comment, root):
    """The element a comment applies to (see the module docstring)."""
    parent = comment.getparent()
    last_line = (comment.sourceline or 0) + (comment.text or "").count("\n")
    if parent is not None and parent.sourceline == comment.sourceline:
        return parent
    nxt = comment.getnext()
    while nxt is not None and not isinstance(nxt.tag, str):
        nxt = nxt.getnext()
    if nxt is not None and nxt.sourceline is not None and nxt.sourceline <= last_line + 1:
        return nxt
    if parent is None:                 # a comment outside <robot>: the whole document
        return root
    return parent


def covers(s: Suppression, code: str, line: int | None) -> bool:
    if not any(code.startswith(c) for c in s.codes):
        return False
    return s.whole_file or (line is not None and s.start <= line <= s.end)


def source_files(robot) -> list[str]:
    """The source files the model's elements came from (the input and, for xacro, its includes)."""
    files = dict.fromkeys(robot.source_files())
    if robot.loc is not None:
        files.setdefault(robot.loc.file)
    return list(files)


def apply(diags: list, robot, enabled, dropped: list | None = None) -> tuple[list, list, list]:
    """Drop the suppressed findings. Returns (kept findings, keys of the suppressions seen for codes
    the run checks, keys that silenced something); a key is (file, line, code).
    Suppressions naming unknown codes come back as X009 findings straight away. ``dropped``, when
    given, receives (finding, key) for each finding dropped (SARIF lists them as suppressed)."""

    by_file: dict[str, list[Suppression]] = {}
    for f in source_files(robot):
        s = suppressions_in(f)
        if s:
            by_file[f] = s
    if not by_file:
        return diags, [], []
    known = known_codes()
    kept, used = [], set()
    for d in diags:
        hit = None
        if d.loc is not None:
            for s in by_file.get(d.loc.file, ()):
                if covers(s, d.code, d.loc.line):
                    hit = s
                    break
        if hit is None:
            kept.append(d)
        else:
            code = next(c for c in hit.codes if d.code.startswith(c))
            used.add((hit.file, hit.line, code))
            if dropped is not None:
                dropped.append((d, (hit.file, hit.line, code)))
    seen = []
    for sups in by_file.values():
        for s in sups:
            for c in s.codes:
                matching = [k for k in known if k.startswith(c)]
                if not matching:
                    kept.append(Diagnostic("X009", "warning", f"suppression: {unknown_code_message(c, known)}",
                                           Loc(s.file, s.line), {"rule": "unused-suppression", "code": c}))
                elif any(enabled(k) for k in matching):
                    seen.append((s.file, s.line, c))
    return kept, sorted(set(seen)), sorted(used)


def unused_diagnostics(seen, used: set) -> list:
    """X009 for each suppression comment whose codes (of those ``seen``) silenced nothing."""
    unused: dict[tuple, list[str]] = {}
    for key in map(tuple, seen):
        if key not in used:
            unused.setdefault(key[:2], []).append(key[2])
    return [Diagnostic("X009", "warning", f"unused suppression ignore[{','.join(codes)}]: no {'/'.join(codes)} "
                       "finding here in this run; remove it", Loc(file, line),
                       {"rule": "unused-suppression", "codes": codes})
            for (file, line), codes in unused.items()]


def unused_findings(results) -> None:
    """After the whole run: X009 for every suppression no checked model used, added to the first
    result (in input order) whose model read that file."""

    used = set()
    for r in results:
        used.update(map(tuple, r.suppressions_used))
    reported = set()
    for r in results:
        fresh = [k for k in map(tuple, r.suppressions_seen) if k not in reported]
        reported.update(fresh)
        extra = unused_diagnostics(fresh, used)
        if extra:
            r.diagnostics = sort_diagnostics(list(r.diagnostics) + extra)
