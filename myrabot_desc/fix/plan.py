"""From a rule's fix (model terms) to edits of the source files (byte spans).

Where the value came from decides the edit (model/sources.py):

* written in the element itself, or passed as a literal at a macro call: the literal is replaced
  in place. When that literal makes several values (a macro body expanded for both wheels, a
  parameter used by a visual and a collision), the edit is safe only if this run sets every one of
  them to the same value; otherwise it is unsafe and the report lists the other uses;
* a ``<xacro:property>``, a macro parameter's default or an arg's default whose definition is a
  literal: the definition is edited; every use changes with it, so the edit is unsafe and the report
  lists the uses;
* computed by an expression, or an arg given on the command line: not edited; the report gives the
  value needed and where the expression is written.
"""

from myrabot_desc.checks.rule import (
    InsertAfter,
    InsertInto,
    RemoveAttribute,
    RemoveElement,
    RenameAttribute,
    RenameTag,
    SetValue,
)
from myrabot_desc.fix.edits import Edit, number, numbers, removal
from myrabot_desc.records import Struct


class Change(Struct):
    """One finding's repair: its edits, applied together."""

    code: str
    message: str
    title: str
    safety: str                      # safe | unsafe
    edits: tuple                     # Edit, ...
    notes: tuple = ()                # why unsafe, the other uses of an edited definition


class NotFixed(Struct):
    """A finding whose rule has a fix that cannot be written into the sources (or was not applied)."""

    code: str
    message: str
    reason: str
    where: object = None             # Span of the expression (or None)


def _escape(text: str) -> str:
    """Text safe in an attribute value and in element text alike."""
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;").replace('"', "&quot;")


def _text(value, like: str) -> str:
    if isinstance(value, (tuple, list)):
        return numbers(value, like)
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return number(float(value), like)
    return str(value)


def _element(sources, part, field):
    """The handle of ``part``'s element (a part's ``ref``, or a handle the syntax rules pass as it is),
    or of its child named ``field``."""
    ref = getattr(part, "ref", part)
    return sources.child(ref, field) if field is not None else ref


def _child_indent(data: bytes, span, outer: str) -> str:
    """The indentation of the first child line of the element at ``span`` (outer + 2 spaces if none)."""
    first = data.find(b"\n", span.start, span.end)
    while 0 <= first < span.end:
        nxt = data.find(b"\n", first + 1, span.end)
        line = data[first + 1:nxt if nxt >= 0 else span.end]
        text = line.lstrip(b" \t")
        if text.strip() and not text.startswith(b"</"):
            return line[:len(line) - len(text)].decode("utf-8", "replace")
        if nxt < 0:
            break
        first = nxt
    return outer + "  "


def _where(span) -> str:
    return f"{span.file}:{span.line}" if span is not None else "?"


def last_kind(o) -> str:
    return o.hops[-1].kind if o.hops else o.kind


class Planner:
    """Turns (Diagnostic, Fix) pairs of one robot into Changes and NotFixed."""

    def __init__(self, robot):
        self.robot = robot
        self.sources = robot.sources
        self._uses = None

    def uses(self, key) -> list:
        """Every value (element, attribute) of the URDF produced by the literal at ``key`` (file, start)."""
        if self._uses is None:
            self._uses = self.sources.uses()
        return self._uses.get(key, [])

    def plan(self, fixes) -> tuple[list[Change], list[NotFixed]]:
        resolved, not_fixed = [], []
        sites: dict = {}             # (file, start, end) -> [new texts, edits of this run there]
        for diag, fix in fixes:
            edits, notes, safety, problem = [], [], fix.safety, None
            for intent in fix.edits:
                r = self._resolve(intent)
                if isinstance(r, NotFixed):
                    problem = r
                    break
                es, kind, note, uses = r
                if note:
                    notes.append(note)
                if kind in ("property", "default", "arg"):
                    safety = "unsafe"
                    notes.extend(self._shared_note(e, uses) for e in es)
                for e in es:
                    edits.append((e, uses))
                    site = sites.setdefault((e.file, e.start, e.end), [set(), 0])
                    site[0].add(e.new)
                    site[1] += 1
            if problem is not None:
                not_fixed.append(problem._replace(code=diag.code, message=diag.message))
            elif edits:              # (no edits: every value already holds what the fix would write)
                resolved.append((diag, fix, safety, edits, notes))
        changes = []
        for diag, fix, safety, edits, notes in resolved:
            conflict = None
            for e, uses in edits:
                texts, count = sites[(e.file, e.start, e.end)]
                if len(texts) > 1:
                    conflict = (f"{e.file}:{self._line(e)} is written once for {uses} uses (a macro body or a "
                                "shared value), but the fixes need different text there")
                    break
                if uses > count:
                    safety = "unsafe"
                    notes.append(self._shared_note(e, uses))
            if conflict:
                not_fixed.append(NotFixed(diag.code, diag.message, conflict))
                continue
            changes.append(Change(diag.code, diag.message, fix.title, safety, tuple(e for e, _u in edits),
                                  tuple(dict.fromkeys(notes))))
        return changes, not_fixed

    def _shared_note(self, e: Edit, uses: int) -> str:
        key = (e.file, e.start)
        values = self.uses(key) if self._uses is None or key in self._uses else []
        if values:
            others = sorted({self.sources.describe(el, a) for el, a in values})
            return (f"{e.file}:{self._line(e)} makes {len(values)} values ({', '.join(others[:6])}"
                    + (", ..." if len(others) > 6 else "") + "): each of them changes")
        return f"{e.file}:{self._line(e)} is in a macro body expanded {uses} times: each expansion changes"

    def _line(self, e: Edit) -> int:
        return self.sources.data(e.file).count(b"\n", 0, e.start) + 1

    def _resolve(self, intent):
        """(Edit, origin kind, note, span of an edited literal or None) or NotFixed."""
        src = self.sources
        if isinstance(intent, SetValue):
            el = _element(src, intent.part, None)
            o = src.field(intent.part, intent.field) if el is not None else None
            if o is None or o.kind == "unknown" or (o.written is None and o.expr is None and not o.from_command_line):
                return NotFixed("", "", f"{intent.field}: where it is written is not known")
            if o.written is None:
                need = _text(intent.value, "")
                if o.from_command_line:
                    return NotFixed("", "", f"{intent.field} is the xacro arg {o.name} given on the command line; "
                                    f"give {need}")
                return NotFixed("", "", f"{intent.field} is computed by {o.expr.text} at {_where(o.expr)}; it should "
                                f"come to {need}", o.expr)
            w = o.written
            new = _escape(_text(intent.value, w.value))
            if new == w.text:
                return [], last_kind(o), None, 1
            last = o.hops[-1].kind if o.hops else o.kind
            note = None
            if last in ("property", "default", "arg"):
                what = {"property": f"property {o.hops[-1].name}", "default": f"the default of parameter {o.hops[-1].name}",
                        "arg": f"the default of arg {o.hops[-1].name}"}[last]
                note = f"edits {what} at {_where(w)}"
            return [Edit(w.file, w.path, w.start, w.end, new)], last, note, len(self.uses((w.file, w.start)))
        if isinstance(intent, RemoveAttribute):
            span = src.attribute(intent.ref, intent.attr)
            if span is None:
                return NotFixed("", "", f"attribute {intent.attr}: where it is written is not known")
            s, e = removal(src.data(span.file), span.start, span.end)
            return [Edit(span.file, span.path, s, e, "")], "literal", None, src.expansions(intent.ref)
        if isinstance(intent, RenameAttribute):
            span = src.attribute(intent.ref, intent.attr)
            if span is None:
                return NotFixed("", "", f"attribute {intent.attr}: where it is written is not known")
            return [Edit(span.file, span.path, span.start, span.start + len(intent.attr.encode()), intent.new)], \
                "literal", None, src.expansions(intent.ref)
        if isinstance(intent, InsertInto):
            el = _element(src, intent.part, None)
            span = src.element_span(el) if el is not None else None
            if span is None:
                return NotFixed("", "", "where to insert is not known")
            data = src.data(span.file)
            closing = data.rfind(b"</", span.start, span.end)
            if closing < 0:
                return NotFixed("", "", "the element is written <empty/>: nothing to insert into")
            nl = "\r\n" if b"\r\n" in data[span.start:span.end] else "\n"
            line_start = data.rfind(b"\n", 0, span.start) + 1
            outer = data[line_start:span.start].decode("utf-8", "replace")
            outer = outer if not outer.strip() else ""
            inner = _child_indent(data, span, outer)
            body = (nl + inner).join(intent.text.strip("\n").splitlines())
            cl_line = data.rfind(b"\n", 0, closing) + 1
            if cl_line > span.start and not data[cl_line:closing].strip():
                at, text = cl_line, inner + body + nl          # its own line, before the closing tag's
            else:
                at, text = closing, nl + inner + body + nl + outer
            return [Edit(span.file, span.path, at, at, text)], "literal", None, src.expansions(el)
        if isinstance(intent, RemoveElement):
            el = _element(src, intent.part, intent.field)
            span = src.element_span(el) if el is not None else None
            if span is None:
                return NotFixed("", "", f"<{intent.field}>: where it is written is not known")
            s, e = removal(src.data(span.file), span.start, span.end)
            return [Edit(span.file, span.path, s, e, "")], "literal", None, src.expansions(el)
        if isinstance(intent, RenameTag):
            return self._rename(intent)
        if isinstance(intent, InsertAfter):
            el = _element(src, intent.part, None)
            span = src.element_span(el) if el is not None else None
            if span is None:
                return NotFixed("", "", "where to insert is not known")
            data = src.data(span.file)
            line_start = data.rfind(b"\n", 0, span.start) + 1
            indent = data[line_start:span.start].decode("utf-8", "replace")
            indent = indent if not indent.strip() else ""
            nl = "\r\n" if b"\r\n" in data[:span.end + 2] else "\n"
            body = (nl + indent).join(intent.text.strip("\n").splitlines())
            return [Edit(span.file, span.path, span.end, span.end, nl + indent + body)], "literal", None, \
                src.expansions(el)
        raise TypeError(f"unknown fix edit {intent!r}")

    def _rename(self, intent):
        src = self.sources
        tag = src.tag(intent.ref)
        whole = src.element_span(intent.ref)
        if tag is None or whole is None:
            return NotFixed("", "", "where the element is written is not known")
        data = src.data(whole.file)
        edits = [Edit(tag.file, tag.path, tag.start, tag.end, intent.tag)]
        closing = data.rfind(b"</", whole.start, whole.end)
        if closing > tag.end and data[closing + 2:closing + 2 + len(tag.text)] == tag.text.encode():
            edits.append(Edit(tag.file, tag.path, closing + 2, closing + 2 + len(tag.text), intent.tag))
        return edits, "literal", None, src.expansions(intent.ref)
