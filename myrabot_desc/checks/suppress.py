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

from pathlib import Path

from myrabot_desc import xmltree
from myrabot_desc.checks.codes import known_codes, unknown_code_message
from myrabot_desc.diagnostics import Diagnostic, Loc, sort_diagnostics
from myrabot_desc.errors import InputError
from myrabot_desc.records import Struct
from myrabot_desc.safety import limit, read_checked, safe_parser

MARKER = b"myrabot-desc:"
_WS = " \t\r\n\f\v"


def comment_suppressions(text: str):
    """(kind, codes text) of every ``myrabot-desc: ignore[...]`` / ``ignore-file[...]`` in a comment,
    as the pattern ``myrabot-desc:\\s*(ignore-file|ignore)\\s*\\[([^\\]]*)\\]`` finds them, in one
    pass: each character is looked at a bounded number of times (a regular expression retried at
    every repeated marker of an unclosed comment is quadratic)."""
    out = []
    marker = "myrabot-desc:"
    pos, n = 0, len(text)
    close = -1                       # the first ']' at or after the last place looked from
    while True:
        p = text.find(marker, pos)
        if p < 0:
            return out
        q = p + len(marker)
        while q < n and text[q] in _WS:
            q += 1
        kind = "ignore-file" if text.startswith("ignore-file", q) else "ignore" if text.startswith("ignore", q) \
            else None
        if kind is None:
            pos = p + 1
            continue
        q += len(kind)
        while q < n and text[q] in _WS:
            q += 1
        if q >= n or text[q] != "[":
            pos = p + 1
            continue
        if close <= q:
            close = text.find("]", q + 1)
            if close < 0:
                return out               # no ']' after here: no later marker can close either
        out.append((kind, text[q + 1:close]))
        pos = close + 1


class Suppression(Struct):
    file: str            # as the findings name it (display path)
    line: int            # the comment's line
    codes: tuple         # codes or prefixes, upper case
    start: int           # first line covered
    end: int             # last line covered
    whole_file: bool


_cache: dict = {}        # (device, inode, mtime_ns, ctime_ns, size) -> [Suppression] (one read per file per process)
_by_content: dict = {}   # (file, bytes with a marker) -> [Suppression]; holds the bytes: bounded
_BY_CONTENT_MOST = 64


def suppressions_in(file: str) -> list[Suppression]:
    """Every suppression comment of one source file (cached per file version: the file itself, by
    device and inode, whatever name it is read by; the two revisions ``diff --rev`` exports share
    the files they have in common)."""
    p = Path(file)
    try:
        st = p.stat()
        key = (st.st_dev, st.st_ino, st.st_mtime_ns, st.st_ctime_ns, st.st_size)
    except OSError:
        return []
    if key in _cache:
        return [s._replace(file=file) for s in _cache[key]]

    out: list[Suppression] = []
    try:
        if st.st_size <= limit("max_input_bytes"):
            data = read_checked(p, None, limit("max_input_bytes"))   # a regular file, bounded
            if MARKER in data:
                out = _parse(data, file)
    except (OSError, InputError):
        pass
    _cache[key] = out
    return out


def suppressions_of(file: str, data: bytes) -> list[Suppression]:
    """Every suppression comment of ``data``, the bytes of ``file`` a model was built from; cached by
    content, as ``suppressions_in`` caches a file by version (a ``check -r`` of one robot's variants,
    the two revisions of a ``diff``, build the same includes)."""
    if MARKER not in data:
        return []
    key = (file, data)
    if key not in _by_content:
        if len(_by_content) >= _BY_CONTENT_MOST:      # a long `check -r`: keep the memory, not every file
            _by_content.clear()
        _by_content[key] = _parse(data, file)
    return _by_content[key]


def _parse(data: bytes, file: str) -> list[Suppression]:
    try:
        root = xmltree.parse(data)      # the same tree lxml reads, lines included, without importing it
        comment = xmltree.Comment
    except xmltree.Refused:             # what expat leaves to lxml (see xmltree.py)
        from lxml import etree

        try:
            root = etree.fromstring(data, parser=safe_parser())
        except (etree.XMLSyntaxError, ValueError):
            return []
        comment = etree.Comment
    comments = list(root.itersiblings(comment, preceding=True)) + list(root.iter(comment)) + \
        list(root.itersiblings(comment))
    found = [(c, kind, body) for c in comments if MARKER.decode() in (c.text or "")
             for kind, body in comment_suppressions(c.text or "")]
    if not found:
        return []
    # linear facts of the tree, once: each element's last line (its subtree's), each comment's next
    # element sibling (20,000 comments in a row asked for it 20,000 times)
    ends: dict = {}
    for el in reversed(list(root.iter())):     # children come after their parent in document order
        if isinstance(el.tag, str):
            ln = el.sourceline or 0
            for ch in el:
                if isinstance(ch.tag, str):
                    ln = max(ln, ends[ch])
            ends[el] = ln
    following: dict = {}

    def next_element(c):
        if c not in following:
            parent = c.getparent()
            sibs = list(parent) if parent is not None else \
                list(root.itersiblings(preceding=True))[::-1] + [root] + list(root.itersiblings())
            nxt = None
            for sib in reversed(sibs):
                if isinstance(sib.tag, str):
                    nxt = sib
                else:
                    following[sib] = nxt
        return following.get(c)

    out = []
    for c, kind, body in found:
        codes = tuple(x.strip().upper() for x in body.split(",") if x.strip())
        if not codes:
            continue
        line = c.sourceline or 1
        if kind == "ignore-file":
            out.append(Suppression(file, line, codes, 1, 10**9, True))
            continue
        target = _target(c, root, next_element)
        start = target.sourceline or line
        end = max(ends.get(target, start), start)
        out.append(Suppression(file, line, codes, start, end, False))
    return out


def _target(comment, root, next_element):
    """The element a comment applies to (see the module docstring)."""
    parent = comment.getparent()
    last_line = (comment.sourceline or 0) + (comment.text or "").count("\n")
    if parent is not None and parent.sourceline == comment.sourceline:
        return parent
    nxt = next_element(comment)
    if nxt is not None and nxt.sourceline is not None and nxt.sourceline <= last_line + 1:
        return nxt
    if parent is None:                 # a comment outside <robot>: the whole document
        return root
    return parent


def _first_covering(diags, by_file) -> list:
    """For each finding, the first suppression of its file (in file order) that covers it (as
    :func:`covers`), or None: one sweep over the lines of each file, with the suppressions in
    force kept per code prefix in heaps, so that n findings and m suppressions cost
    O((n + m) log m) instead of n x m."""
    import heapq

    out = [None] * len(diags)
    wanted: dict[str, list] = {}
    for i, d in enumerate(diags):
        if d.loc is not None and d.loc.file in by_file:
            wanted.setdefault(d.loc.file, []).append(i)
    for file, idx in wanted.items():
        sups = by_file[file]
        order = sorted(range(len(sups)), key=lambda k: sups[k].start)
        pending = 0
        active: dict[str, list] = {}          # code prefix -> heap of (file order, end)
        # a finding without a line is covered by whole-file suppressions only
        nolines = [i for i in idx if diags[i].loc.line is None]
        for i in nolines:
            d = diags[i]
            out[i] = next((s for s in sups if s.whole_file and any(d.code.startswith(c) for c in s.codes)), None)
        for i in sorted((i for i in idx if diags[i].loc.line is not None), key=lambda i: diags[i].loc.line):
            d = diags[i]
            line = d.loc.line
            while pending < len(order) and sups[order[pending]].start <= line:
                k = order[pending]
                for c in set(sups[k].codes):
                    heapq.heappush(active.setdefault(c, []), (k, sups[k].end))
                pending += 1
            best = None
            for n in range(len(d.code) + 1):
                heap = active.get(d.code[:n])
                while heap and heap[0][1] < line:        # ended: lines only grow, it never covers again
                    heapq.heappop(heap)
                if heap and (best is None or heap[0][0] < best):
                    best = heap[0][0]
            out[i] = sups[best] if best is not None else None
    return out


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
    built = robot.source_data()
    for f in source_files(robot):
        data = built.get(f)
        s = suppressions_in(f) if data is None else suppressions_of(f, data)
        if s:
            by_file[f] = s
    if not by_file:
        return diags, [], []
    known = known_codes()
    kept, used = [], set()
    hits = _first_covering(diags, by_file)
    for d, hit in zip(diags, hits):
        if hit is None:
            kept.append(d)
        else:
            code = next(c for c in hit.codes if d.code.startswith(c))
            used.add((hit.file, hit.line, code))
            if dropped is not None:
                dropped.append((d, (hit.file, hit.line, code)))
    seen = []
    matches: dict[str, list] = {}
    for sups in by_file.values():
        for s in sups:
            for c in s.codes:
                matching = matches.get(c)
                if matching is None:
                    matching = matches[c] = [k for k in known if k.startswith(c)]
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
