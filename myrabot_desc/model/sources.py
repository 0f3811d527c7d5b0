"""Where each value of the robot was written: the source file, line, column and byte span of the
text that produced it, and how it reached the URDF.

Every value of the built URDF is one of:

* ``literal``   written as it is in the element the URDF element was copied from (a URDF file, or
  the xacro file: in a macro body, every expansion of the macro shares that text);
* ``property``  ``${name}`` of a ``<xacro:property>``; ``written`` is the definition's literal, or
  None when the definition is itself computed;
* ``param``     ``${name}`` of a macro parameter given at the call site (``written``: the call's
  literal, or where the caller got it);
* ``default``   ``${name}`` of a macro parameter's default (``params="name:=0.1"``);
* ``arg``       ``$(arg name)`` (or ``${name}`` of a property holding it): the ``<xacro:arg>``
  default, or the command line (no span);
* ``expr``      computed by an expression: ``expr`` is where it is written;
* ``unknown``   not found in the source (an attribute made by ``<xacro:attribute>``, a file read
  through lxml's fallback, a value of a generated document).

``Origin.hops`` is the way from the use to the text: each hop (kind, name, span). The spans are
found by reading the start tags of the source files at the byte offsets the build recorded
(expand/provenance.py), when first asked: loading a robot costs nothing more.
"""

import re
from bisect import bisect_left
from pathlib import Path

from myrabot_desc.diagnostics import Loc
from myrabot_desc.records import Struct

_NEWLINE = re.compile(rb"\n")
_TAG = re.compile(rb"<([^\s/>]+)")
_ATTR = re.compile(rb"\s*([^\s=/>]+)\s*=\s*(?:\"([^\"]*)\"|'([^']*)')")
_TAG_END = re.compile(rb"\s*/?>")
_ENTITIES = (("&lt;", "<"), ("&gt;", ">"), ("&quot;", '"'), ("&apos;", "'"))
_CHARREF = re.compile(r"&#(x[0-9a-fA-F]+|[0-9]+);")


def unescape(text: str) -> str:
    """An attribute value or text as XML reads it (entities and character references)."""
    if "&" not in text:
        return text
    for a, b in _ENTITIES:
        text = text.replace(a, b)
    text = _CHARREF.sub(lambda m: chr(int(m.group(1)[1:], 16) if m.group(1)[0] == "x" else int(m.group(1))), text)
    return text.replace("&amp;", "&")


class Span(Struct):
    """A piece of text in a source file: bytes ``start:end`` of ``path``; ``line``/``col`` (1-based,
    col in characters) of its first character; ``text`` as written (XML-escaped)."""

    file: str                 # as shown in reports (the build's display name)
    path: Path | None
    line: int
    col: int
    start: int
    end: int
    text: str

    @property
    def loc(self) -> Loc:
        return Loc(self.file, self.line)

    @property
    def value(self) -> str:
        return unescape(self.text)

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.col}"


class Hop(Struct):
    kind: str                 # literal | property | param | default | arg | expr | unknown
    name: str | None
    span: Span | None


class Origin(Struct):
    """How one value reached the URDF (see the module doc)."""

    kind: str
    name: str | None          # property, parameter or arg name
    at: Span | None           # the attribute (or text) of the element as written there: literal or ``${...}``
    written: Span | None      # the literal that produced the value (None: computed or unknown)
    expr: Span | None         # where the expression is written, for a computed value
    hops: tuple[Hop, ...] = ()

    @property
    def computed(self) -> bool:
        """No literal produced it: an expression, or a command-line arg."""
        return self.written is None

    @property
    def from_command_line(self) -> bool:
        """The value is an xacro arg given on the command line (``NAME:=VALUE``)."""
        return bool(self.hops) and self.hops[-1].kind == "arg" and self.hops[-1].span is None


class _File:
    """One source file's bytes and the start-tag offsets of its elements."""

    __slots__ = ("name", "path", "data", "_ends", "_newlines")

    def __init__(self, name: str, path: Path | None, data: bytes):
        self.name, self.path, self.data = name, path, data
        self._ends = None
        self._newlines = None

    def element_end(self, offset: int) -> int | None:
        """The byte just past the end of the element whose start tag is at ``offset`` (its end tag's
        ``>``, or the start tag's own for ``<x/>``)."""
        if self._ends is None:
            from xml.parsers import expat

            ends: dict[int, int] = {}
            stack: list[int] = []
            p = expat.ParserCreate()
            p.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)

            def start(name, attrs):
                stack.append(p.CurrentByteIndex)

            def end(name):
                at = p.CurrentByteIndex
                begin = stack.pop()
                if self.data.startswith(b"</", at):
                    ends[begin] = self.data.index(b">", at) + 1
                else:                      # <x/>: the end is reported at the start tag
                    st = self.start_tag(begin)
                    ends[begin] = st[2] if st else at
            p.StartElementHandler, p.EndElementHandler = start, end
            try:
                p.Parse(self.data, True)
            except expat.ExpatError:
                pass
            self._ends = ends
        return self._ends.get(offset)

    def line_col(self, offset: int) -> tuple[int, int]:
        # the newlines' offsets, found once: counting them up to each offset made placing every
        # value of a large file (--fix, --diff) quadratic in its size
        nl = self._newlines
        if nl is None:
            nl = self._newlines = [m.start() for m in _NEWLINE.finditer(self.data)]
        k = bisect_left(nl, offset)            # newlines before offset
        start = nl[k - 1] + 1 if k else 0
        return k + 1, len(self.data[start:offset].decode("utf-8", "replace")) + 1

    def span(self, start: int, end: int) -> Span:
        line, col = self.line_col(start)
        return Span(self.name, self.path, line, col, start, end, self.data[start:end].decode("utf-8", "replace"))

    def start_tag(self, offset: int):
        """(tag span, {attribute: value span}, end of the start tag, self-closing) of the start tag at
        ``offset``, or None when no start tag is there."""
        data = self.data
        m = _TAG.match(data, offset)
        if m is None:
            return None
        attrs = {}
        pos = m.end()
        while True:
            a = _ATTR.match(data, pos)
            if a is None:
                break
            g = 2 if a.group(2) is not None else 3
            attrs[a.group(1).decode("utf-8", "replace")] = (a.start(g), a.end(g), a.start(1))
            pos = a.end()
        e = _TAG_END.match(data, pos)
        if e is None:
            return None
        return (m.start(1), m.end(1)), attrs, e.end(), data[e.end() - 2:e.end()] == b"/>"


class Sources:
    """The source spans of one robot's values (``Robot.sources``)."""

    def __init__(self, root, source_map=None, plain: tuple | None = None):
        """``root``: the URDF's root element; ``source_map``: the build's (expand/provenance.SourceMap);
        ``plain``: (name, path, bytes) of a URDF read from one file."""
        self.root = root
        self.map = source_map
        self._plain = plain
        self._files: dict[str, _File] = {}
        self._index: dict | None = None         # id(output element) -> document-order index
        self._elements: list | None = None
        self._plain_offsets: list | None = None
        self._counts: dict | None = None
        self._uses: dict | None = None

    # -------------------------------------------------------- elements
    def _doc_index(self, el) -> int | None:
        if self._index is None:
            self._elements = [e for e in self.root.iter() if isinstance(e.tag, str)]
            self._index = {id(e): i for i, e in enumerate(self._elements)}
        return self._index.get(id(el))

    def _file(self, name: str) -> _File | None:
        f = self._files.get(name)
        if f is None:
            if self.map is not None:
                entry = self.map.files.get(name)
                if entry is None:
                    return None
                f = _File(name, entry[0], entry[1])
            elif self._plain is not None and self._plain[0] == name:
                f = _File(*self._plain)
            else:
                return None
            self._files[name] = f
        return f

    def _source_element(self, eid: int) -> tuple[_File | None, int | None]:
        """(file, start-tag offset) of source element ``eid`` of the build's list."""
        m = self.map
        if m is None:
            return self._plain_element(eid)
        if eid is None or eid >= len(m.locs):
            return None, None
        f = self._file(m.locs[eid].file)
        return f, m.offsets[eid]

    def _plain_element(self, eid: int):
        if self._plain is None:
            return None, None
        if self._plain_offsets is None:
            from xml.parsers import expat

            offsets: list = []
            p = expat.ParserCreate()
            p.StartElementHandler = lambda name, attrs: offsets.append(p.CurrentByteIndex)
            p.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)
            try:
                p.Parse(self._plain[2], True)
            except expat.ExpatError:
                offsets = []          # (lxml read it; expat does not: no spans)
            self._plain_offsets = offsets
        f = self._file(self._plain[0])
        return f, (self._plain_offsets[eid] if eid < len(self._plain_offsets) else None)

    def _source_of(self, el) -> int | None:
        """The source element (index in the build's list) output element ``el`` came from."""
        i = self._doc_index(el)
        if i is None:
            return None
        if self.map is None:
            return i
        return self.map.index[i] if i < len(self.map.index) else None

    def data(self, name: str) -> bytes:
        """The bytes of source file ``name`` as the build read them (b'' when unknown)."""
        f = self._file(name)
        return f.data if f is not None else b""

    def line_col(self, name: str, offset: int) -> tuple[int, int]:
        """Line and column (characters, from 1) of byte ``offset`` of source file ``name``; (1, 1) when
        the file is unknown."""
        f = self._file(name)
        return f.line_col(offset) if f is not None else (1, 1)

    def files(self) -> dict:
        """Shown name -> path of every source file the robot was read from."""
        if self.map is not None:
            return {name: entry[0] for name, entry in self.map.files.items()}
        return {self._plain[0]: self._plain[1]} if self._plain is not None else {}

    def expansions(self, el) -> int:
        """How many elements of the URDF were made from the source element ``el`` was made from (a
        macro body expanded N times: N; a plain element: 1)."""
        src = self._source_of(el)
        if src is None or self.map is None:
            return 1
        if self._counts is None:
            counts: dict = {}
            for i in self.map.index:
                counts[i] = counts.get(i, 0) + 1
            self._counts = counts
        return self._counts.get(src, 1)

    # -------------------------------------------------------- spans
    def tag(self, el) -> Span | None:
        """The element's tag name where it is written (in a macro body: shared by every expansion)."""
        f, off = self._source_element(self._source_of(el))
        if f is None or off is None:
            return None
        st = f.start_tag(off)
        return f.span(*st[0]) if st else None

    def start_tag(self, el) -> Span | None:
        """The element's whole start tag, ``<`` to ``>``."""
        f, off = self._source_element(self._source_of(el))
        if f is None or off is None:
            return None
        st = f.start_tag(off)
        return f.span(off, st[2]) if st else None

    def element_span(self, el) -> Span | None:
        """The whole element where it is written, start tag to end tag (to remove or to move it)."""
        f, off = self._source_element(self._source_of(el))
        if f is None or off is None:
            return None
        end = f.element_end(off)
        return f.span(off, end) if end is not None else None

    def attribute(self, el, attr: str) -> Span | None:
        """The whole ``name="value"`` of an attribute where it is written (to remove it)."""
        f, off = self._source_element(self._source_of(el))
        st = f.start_tag(off) if f is not None and off is not None else None
        if st is None or attr not in st[1]:
            return None
        s, e, name_start = st[1][attr]
        return f.span(name_start, e + 1)

    def _attr_span(self, src: int | None, attr: str | None, name: str | None = None) -> Span | None:
        f, off = self._source_element(src)
        if f is None or off is None or attr is None:
            return None
        st = f.start_tag(off)
        if st is None:
            return None
        if attr == "#text":
            return _text_span(f, st)
        a = st[1].get(attr)
        if a is None:
            return None
        if attr == "params" and name is not None:   # a macro parameter's default, inside params=
            return _default_span(f, a[0], a[1], name)
        return f.span(a[0], a[1])

    # -------------------------------------------------------- origins
    def origin(self, el, attr: str) -> Origin:
        """Where the value of attribute ``attr`` (or ``'#text'``) of output element ``el`` was written."""
        i = self._doc_index(el)
        if i is None:
            return Origin("unknown", None, None, None, None)
        src = self.map.index[i] if self.map is not None and i < len(self.map.index) else (i if self.map is None else None)
        at = self._attr_span(src, attr)
        recorded = self.map.origins[i] if self.map is not None and i < len(self.map.origins) else None
        org = recorded.get(attr) if recorded else None
        if org is None:
            if at is None:
                return Origin("unknown", None, None, None, None)
            if "$" in at.text and self.map is not None:
                # written with ${} but the build recorded nothing: xacro evaluated it elsewhere
                return Origin("expr", None, at, None, at, (Hop("expr", None, at),))
            return Origin("literal", None, at, at, None, (Hop("literal", None, at),))
        hops = []
        expr = None
        written = None
        while org is not None:
            kind, name, osrc, oattr, inner = org
            span = self._attr_span(osrc, oattr, name if kind == "default" else None)
            hops.append(Hop(kind, name, span))
            if kind == "expr":
                expr = span
                break
            if inner is None:
                written = span
                break
            org = inner
        first = hops[0]
        if first.kind == "arg" and first.span is None:
            return Origin("arg", first.name, at, None, None, tuple(hops))
        return Origin(first.kind, first.name, at, written, expr, tuple(hops))

    def child(self, ref, tag: str):
        """The handle of the first child element of ``ref`` named ``tag`` (None if there is none)."""
        return _child(ref, tag)

    def uses(self) -> dict:
        """Every value of the URDF by where it is written: (file, start) -> [(handle, attribute)], the
        element text as '#text'. A literal used by several values (a property, a macro body) has several.
        Found once per robot (--fix plans twice on a model no fix changed); read it, never change it."""
        if self._uses is not None:
            return self._uses
        found: dict = {}
        for el in self.root.iter():
            if not isinstance(el.tag, str):
                continue
            names = list(el.attrib)
            if (el.text or "").strip() and len(el) == 0:
                names.append("#text")
            for a in names:
                o = self.origin(el, a)
                if o.written is not None:
                    found.setdefault((o.written.file, o.written.start), []).append((el, a))
        self._uses = found
        return found

    @staticmethod
    def describe(ref, attr: str) -> str:
        """'<inertia ixx> of link base_link' style, short: the value's element and its owning part."""
        owner = ref
        while owner is not None and owner.tag not in ("link", "joint", "gazebo", "material"):
            owner = owner.getparent()
        who = f"{owner.tag} {owner.get('name') or owner.get('reference') or ''}".strip() if owner is not None else ""
        a = "text" if attr == "#text" else attr
        return f"<{ref.tag} {a}>" + (f" of {who}" if who else "")

    def field(self, part, name: str) -> Origin:
        """Where field ``name`` of a model part was written: ``field(joint, "limit.effort")``,
        ``field(link.inertial, "ixx")``, ``field(plugin, "wheelSeparation")`` (see FIELDS).

        A name FIELDS does not list is a path of child elements from the part's element, dotted
        (``field(plugin, "ros.namespace")``, ``field(sensor, "camera.horizontal_fov")``), read as
        the text of the last one, or as its ``value=`` when it has no text (``<mu1 value="0.5"/>``);
        a last step ``@NAME`` is an attribute (``field(node, "@name")``)."""
        el = getattr(part, "ref", None)
        table = FIELDS.get(type(part).__name__)
        fallback = not (table and name in table)
        if fallback:
            steps = name.split(".")
            attr = steps.pop()[1:] if steps[-1].startswith("@") else "#text"
            path = tuple(steps)
        else:
            path, attr = table[name]
        for tag in path:
            el = _child(el, tag)
        if el is None:
            return Origin("unknown", None, None, None, None)
        if fallback and attr == "#text" and not (el.text or "").strip() and el.get("value") is not None:
            attr = "value"
        return self.origin(el, attr)


def _child(el, tag: str):
    """The first child element named ``tag`` ('*': any element; a prefix ends with ':')."""
    if el is None:
        return None
    for c in el:
        t = c.tag
        if isinstance(t, str) and (t == tag or tag == "*" or t.rsplit("}", 1)[-1] == tag):
            return c
    return None


def _pose_fields(prefix=()):
    return {"origin.xyz": (prefix + ("origin",), "xyz"), "origin.rpy": (prefix + ("origin",), "rpy")}


_GEOMETRY = {"geometry.size": (("geometry", "box"), "size"), "geometry.radius": (("geometry", "*"), "radius"),
             "geometry.length": (("geometry", "cylinder"), "length"),
             "geometry.filename": (("geometry", "mesh"), "filename"), "geometry.scale": (("geometry", "mesh"), "scale")}

# part type -> field -> (child tags from the part's element, attribute or '#text'). A name not listed
# is a dotted path of child elements (a plugin's parameter, a sensor's camera.horizontal_fov), see field().
FIELDS: dict[str, dict[str, tuple]] = {
    "Link": {"name": ((), "name")},
    "Inertial": {"mass": (("mass",), "value"), **{k: (("inertia",), k) for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")},
                 **_pose_fields()},
    "Joint": {"name": ((), "name"), "type": ((), "type"), "parent": (("parent",), "link"), "child": (("child",), "link"),
              "axis": (("axis",), "xyz"), **_pose_fields(),
              **{f"limit.{k}": (("limit",), k) for k in ("lower", "upper", "effort", "velocity")},
              **{f"mimic.{k}": (("mimic",), k) for k in ("joint", "multiplier", "offset")},
              **{f"dynamics.{k}": (("dynamics",), k) for k in ("damping", "friction")}},
    "Visual": {"name": ((), "name"), **_pose_fields(), **_GEOMETRY, "material": (("material",), "name")},
    "Collision": {"name": ((), "name"), **_pose_fields(), **_GEOMETRY},
    "Material": {"name": ((), "name"), "rgba": (("color",), "rgba"), "texture": (("texture",), "filename")},
    "Plugin": {"name": ((), "name"), "filename": ((), "filename")},
    "Sensor": {"name": ((), "name"), "type": ((), "type")},
    "GazeboBlock": {"reference": ((), "reference")},
    "Transmission": {"name": ((), "name")},
    "TransmissionJoint": {"name": ((), "name")},
    "Actuator": {"name": ((), "name")},
    "Ros2Control": {"name": ((), "name"), "type": ((), "type")},
    "ControlJoint": {"name": ((), "name")},
}


def _text_span(f: _File, st) -> Span | None:
    """The text content right after a start tag (stripped), up to the next markup."""
    if st[3]:
        return None
    data = f.data
    start = st[2]
    end = data.find(b"<", start)
    if end < 0:
        return None
    raw = data[start:end]
    s = start + (len(raw) - len(raw.lstrip()))
    e = end - (len(raw) - len(raw.rstrip()))
    return f.span(s, max(s, e))


_PARAM = re.compile(rb"(?:^|\s)([^\s:=]+):=(\^\|?)?('[^']*'|\"[^\"]*\"|[^\s]*)")


def _default_span(f: _File, start: int, end: int, name: str) -> Span | None:
    """The default of parameter ``name`` inside a macro's ``params="..."`` value."""
    text = f.data[start:end]
    for m in _PARAM.finditer(text):
        if m.group(1).decode("utf-8", "replace") == name:
            s, e = m.start(3), m.end(3)
            if m.group(3)[:1] in (b"'", b'"'):
                s, e = s + 1, e - 1
            return f.span(start + s, start + e)
    return None
