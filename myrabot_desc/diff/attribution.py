"""Which line of the change wrote a changed value.

The model says where each value is written (``robot.origin``): a literal, a property's definition,
a macro parameter at its call, or the expression that computes it. When that place is not among
the lines the change touched, the value came from somewhere the change did touch: a property the
expression reads (``${track/2}`` and ``<xacro:property name="track">`` on a changed line), or a
YAML file the build loaded (``max_effort: 54.0`` on a changed line of joint_limits.yaml). This
module pairs the source files of the two sides, finds the changed lines of the new side, and moves
each change's ``where`` to the changed line that wrote it, when one is found:

1. the origin's own line, or a hop of it (the call site of a parameter, a property's definition),
   when that line changed;
2. a changed line defining a property or arg that the expression names;
3. a changed line that holds the new number: of a YAML file (several: the one whose keys name the
   part, ``wrist_1_joint: max_effort``), or an attribute of a model file (a macro call's argument).
"""

from __future__ import annotations

import difflib
import re
from pathlib import Path

from myrabot_desc.diff.compare import Where
from myrabot_desc.model.sources import Span

MAX_BYTES = 2_000_000
YAML_SUFFIXES = (".yaml", ".yml")
_IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_DEF = re.compile(rb"<(?:xacro:)?(?:property|arg)\b[^>]*?\bname\s*=\s*[\"']([^\"']+)[\"']")
_NUM = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
_STOP = {"link", "joint", "the", "of", "origin", "xyz", "rpy", "limit"}


class Lines:
    """The new side's changed lines, per file (resolved path -> {line: text})."""

    def __init__(self):
        self.changed: dict[Path, dict[int, str]] = {}
        self.names: dict[Path, str] = {}

    def line_changed(self, span) -> bool:
        if span is None or span.path is None:
            return False
        return span.line in self.changed.get(Path(span.path).resolve(), {})


def _read(p: Path) -> bytes | None:
    try:
        if p.is_file() and p.stat().st_size <= MAX_BYTES:
            return p.read_bytes()
    except OSError:
        pass
    return None


def _changed_lines(old: bytes | None, new: bytes) -> dict[int, str]:
    a = old.decode("utf-8", "replace").splitlines() if old is not None else []
    b = new.decode("utf-8", "replace").splitlines()
    out = {}
    for tag, _i1, _i2, j1, j2 in difflib.SequenceMatcher(None, a, b, autojunk=False).get_opcodes():
        if tag in ("replace", "insert"):
            for j in range(j1, j2):
                out[j + 1] = b[j]
    return out


def changed_lines(new_robot, roots: list[tuple[Path, Path]]) -> Lines:
    """The changed lines of the new side's model files and of the YAML files under its folders.
    ``roots``: (new folder, old folder) pairs; a file is paired with the same path under the old
    folder of the deepest new folder holding it."""
    out = Lines()
    roots = sorted(((Path(n).resolve(), Path(o).resolve()) for n, o in roots), key=lambda r: -len(str(r[0])))
    files: dict[Path, str] = {}
    for name, p in new_robot.sources.files().items():
        if p is not None:
            files[Path(p).resolve()] = name
    for new_root, _old in roots:
        if not new_root.is_dir():
            continue
        count = 0
        for p in sorted(new_root.rglob("*")):
            if p.suffix in YAML_SUFFIXES and ".git" not in p.parts:
                files.setdefault(p.resolve(), str(p))
                count += 1
                if count > 500:
                    break
    for path, name in files.items():
        counterpart = None
        for new_root, old_root in roots:
            if path.is_relative_to(new_root):
                counterpart = old_root / path.relative_to(new_root)
                break
        if counterpart is None:
            continue
        data = _read(path)
        if data is None:
            continue
        old = _read(counterpart)
        if old == data:
            continue
        ch = _changed_lines(old, data)
        if ch:
            out.changed[path] = ch
            out.names[path] = name
    return out


def _yaml_keys(path: Path) -> dict[int, list[str]]:
    """Line -> the keys leading to it (by indentation), for a YAML file."""
    data = _read(path)
    if data is None:
        return {}
    stack: list[tuple[int, str]] = []
    out = {}
    for i, line in enumerate(data.decode("utf-8", "replace").splitlines(), 1):
        s = line.split("#", 1)[0].rstrip()
        if not s.strip():
            continue
        ind = len(s) - len(s.lstrip(" -"))
        m = re.match(r"\s*(?:-\s+)?([^:\s][^:]*?)\s*:(\s|$)", s)
        while stack and stack[-1][0] >= ind:
            stack.pop()
        keys = [k for _i, k in stack]
        if m:
            keys = keys + [m.group(1)]
            stack.append((ind, m.group(1)))
        out[i] = keys
    return out


def _tokens(*texts) -> set[str]:
    out = set()
    for t in texts:
        for w in re.split(r"[^A-Za-z0-9]+", str(t).lower()):
            if w and w not in _STOP:
                out.add(w)
    return out


def refine(items, lines: Lines):
    """The items with each new-side ``where`` moved to the changed line that wrote the value (see
    the module doc); unchanged when none is found."""
    if not lines.changed:
        return list(items)
    yaml_keys: dict[Path, dict] = {}
    out = []
    for it in items:
        w = it.where
        if isinstance(w, Where) and w.side == "new":
            w = _refine_one(it, w, lines, yaml_keys) or w
            it = it._replace(where=w)
        out.append(it)
    return out


def _refine_one(it, w: Where, lines: Lines, yaml_keys) -> Where | None:
    computed = w.kind == "expr" or "${" in (w.span.text or "")
    if lines.line_changed(w.span) and not computed:
        return None
    for h in w.hops:                                       # 1. a literal hop on a changed line
        if lines.line_changed(h.span) and "$" not in (h.span.text or ""):
            return Where(h.span, h.kind if h.kind != "literal" else "literal", h.name, "new", w.hops)
    if w.kind == "element":                                 # an element: its place, or a call site that changed
        for h in w.hops:
            if lines.line_changed(h.span) and h.kind in ("param", "default"):
                return Where(h.span, h.kind, h.name, "new", w.hops)
        return None
    text = " ".join(h.span.text for h in w.hops if h.span is not None) or w.span.text
    idents = set(_IDENT.findall(text)) if "$" in text else set()
    if w.name:
        idents.add(w.name)
    for path, changed in lines.changed.items():            # 2. a property or arg the expression names
        if path.suffix in YAML_SUFFIXES:
            continue
        for line, t in changed.items():
            m = _DEF.search(t.encode())
            if m and m.group(1).decode() in idents and "${" not in t:
                return Where(_line_span(lines, path, line, t, m.start()), "property", m.group(1).decode(), "new")
    for path, changed in lines.changed.items():            # 2b. a YAML key the expression names
        if path.suffix not in YAML_SUFFIXES or not idents:
            continue
        keys = yaml_keys.get(path)
        if keys is None:
            keys = yaml_keys[path] = _yaml_keys(path)
        hits = [(sum(k in idents for k in keys.get(line, [])), line, t) for line, t in changed.items()
                if keys.get(line) and keys[line][-1] in idents]
        if hits:
            _n, line, t = max(hits)
            return Where(_line_span(lines, path, line, t, len(t) - len(t.lstrip())), "yaml", None, "new")
    if not it.values:
        return None
    want = _tokens(it.subject, it.what)
    best = None                                            # 3. a changed line with the new number
    for path, changed in lines.changed.items():
        is_yaml = path.suffix in YAML_SUFFIXES
        keys = yaml_keys.get(path) if is_yaml else {}
        if keys is None:
            keys = yaml_keys[path] = _yaml_keys(path)
        for line, t in changed.items():
            if is_yaml:
                value = t.split("#", 1)[0].split(":", 1)[-1]
            else:
                value = " ".join(re.findall(r"=\s*[\"']([^\"']*)[\"']", t))
            nums = [float(x) for x in _NUM.findall(value)]
            if not any(any(abs(n - v) <= 1e-12 + 1e-9 * abs(v) for v in it.values) for n in nums):
                continue
            path_keys = keys.get(line, [])
            score = len(want & _tokens(*path_keys)) + (10 if it.subject in path_keys else 0) + (0.5 if is_yaml else 0)
            if best is None or score > best[0]:
                best = (score, path, line, t, is_yaml)
    if best is not None:
        _s, path, line, t, is_yaml = best
        col = len(t) - len(t.lstrip())
        return Where(_line_span(lines, path, line, t, col), "yaml" if is_yaml else "changed-line", None, "new")
    return None


def _line_span(lines: Lines, path: Path, line: int, text: str, col: int):
    return Span(lines.names.get(path, str(path)), path, line, col + 1, 0, 0, text.strip())
