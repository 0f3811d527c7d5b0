"""A small read-only XML element tree built by expat: the part of lxml's API the model, the raw
syntax rules (checks/urdf_syntax.py) and the suppression comments (checks/suppress.py) read.

Importing lxml costs a check ~15-20 ms of CPU (it brings inspect, ast and typing along); expat is
in the standard library and already loaded by the build. ``parse`` reads what expat reads the way
lxml (with safety.safe_parser) reads it: the same tags (Clark ``{ns}local``), prefixes, attributes
in document order (namespace declarations left out), text, tails, comments and processing
instructions as nodes (tag ``Comment``/``ProcessingInstruction``, not a string), and the same
``sourceline`` (libxml2's: the line where the start tag, comment or instruction ends).

Whatever expat stops at, or might read differently from libxml2 (a DTD or entity, an unbound
prefix, an encoding other than UTF-8/ASCII/Latin-1, nesting or names past libxml2's limits, a
document over 10 MB), raises ``Refused``: the caller asks lxml, which gives the verdict and the
message as before, and reads on with lxml's tree (the model reads both).
"""

from __future__ import annotations

import gc
import re
from xml.parsers import expat

from myrabot_desc.safety import check_xml_bytes, parse_xml_bytes

# libxml2's limits without huge_tree: elements nested deeper than 256, names over 50,000
# characters, a text node over 10 MB (a smaller document cannot hold one). Past these, lxml judges.
MAX_DEPTH = 250
MAX_NAME = 50_000
MAX_BYTES = 10_000_000
_ENCODINGS = {"utf-8", "utf8", "us-ascii", "ascii", "iso-8859-1", "latin-1", "latin1"}
_SEP = "\x01"                    # expat's namespace separator: no XML name or URI can hold it
# a start tag from its "<" to its ">" (a quoted value may hold ">"): where libxml2's line is taken
# (compiled when a line is first asked for: `build` imports this module and never does)
_START_TAG = rb"<[^\"'>]*+(?:(?:\"[^\"]*+\"|'[^']*+')[^\"'>]*+)*+>"


class Refused(Exception):
    """expat did not read the document (or lxml might read it otherwise): ask lxml."""


def Comment():
    """The tag of a comment node (as lxml's ``etree.Comment``: not a string)."""


def ProcessingInstruction():
    """The tag of a processing instruction node (as lxml's ``etree.ProcessingInstruction``)."""


class Document(list):
    """The document around the root element: the list of the root and its siblings (comments,
    instructions), the bytes (lines are counted from them when asked), the declared encoding.
    ``getroottree()`` of any node and its own ``docinfo``, as lxml's ElementTree."""

    __slots__ = ("root", "data", "encoding", "nodes", "text", "_newlines", "_big")

    def __init__(self, data: bytes):
        super().__init__()
        self.root = None
        self.text = None                # (what the parser would give the document: dropped)
        self.data = data
        self.encoding = "UTF-8"         # lxml's for a document that declares none
        self.nodes: list = []           # every node inside the root (and the root), in document order
        self._newlines = None           # byte offsets of the b"\n"s (libxml2 counts no lone CR)
        self._big = None                # lxml's lines, past libxml2's 65,535 (see line_of)

    def line_of(self, node) -> int:
        data, pos = self.data, node._pos
        if node.tag is Comment:
            end = data.find(b"-->", pos) + 3
        elif node.tag is ProcessingInstruction:
            end = data.find(b"?>", pos) + 2
        else:
            m = re.compile(_START_TAG).match(data, pos)    # (re's cache keeps it compiled)
            end = m.end() if m else pos + 1
        if self._newlines is None:
            self._newlines = [m.start() for m in re.finditer(b"\n", data)]
        from bisect import bisect_left   # (lines are rarely asked for: not at import)

        line = bisect_left(self._newlines, end - 1) + 1
        if line < 65535:
            return line
        # libxml2 keeps 16 bits of an element's line and reads a larger one off its neighbours: ask it
        if self._big is None:
            lx = parse_xml_bytes(data, "<document>")
            self._big = {id(n): s.sourceline for n, s in zip(self._order(), _lxml_order(lx))}
        return self._big[id(node)]

    def _order(self) -> list:
        i = next(k for k, n in enumerate(self) if n is self.root)
        return self[:i] + self.nodes + self[i + 1:]

    def getroot(self):
        return self.root

    @property
    def docinfo(self):
        return self


class Element(list):
    """One element, comment or processing instruction (``tag`` tells which, as in lxml). The list
    is its children: iterating, ``len`` and indexing run in C, as lxml's do. Equal only to itself."""

    __slots__ = ("tag", "attrib", "text", "tail", "_parent", "_pos", "__dict__")
    # set on the few nodes that have them (the instance dict is made only then)
    prefix = None                       # the prefix of a namespaced tag as written (None: default namespace)
    target = None                       # a processing instruction's target
    _line = None                        # libxml2's line, found from _pos when first asked

    __eq__ = object.__eq__
    __ne__ = object.__ne__
    __hash__ = object.__hash__

    def __repr__(self) -> str:
        return f"<Element {self.tag if isinstance(self.tag, str) else self.tag.__name__}>"

    def get(self, key, default=None):
        return self.attrib.get(key, default)

    def keys(self):
        return self.attrib.keys()

    def items(self):
        return list(self.attrib.items())

    def values(self):
        return list(self.attrib.values())

    def iter(self, *tags):
        """This node and every node below it, in document order; with ``tags``, those with one of them."""
        doc = self._parent
        if type(doc) is Document and doc.root is self:
            nodes = doc.nodes
        else:
            nodes = []
            stack = [self]
            while stack:
                el = stack.pop()
                nodes.append(el)
                if el:
                    stack.extend(reversed(el))
        if not tags or tags == (None,):
            return iter(nodes)
        return (n for n in nodes if n.tag in tags)

    def iterchildren(self, *tags):
        """The children; with ``tags``, those with one of them (``{*}name``: in any namespace or none)."""
        if not tags:
            return list.__iter__(self)
        return (c for c in list.__iter__(self) if _matches(c.tag, tags))

    def find(self, tag: str):
        """The first child with this tag (a plain tag, not a path), or None."""
        for c in list.__iter__(self):
            if c.tag == tag:
                return c
        return None

    def findall(self, tag: str) -> list:
        """Every child with this tag (a plain tag, not a path)."""
        return [c for c in list.__iter__(self) if c.tag == tag]

    # -------------------------------------------------------- around
    def getparent(self):
        p = self._parent
        return p if type(p) is Element else None

    def getroottree(self) -> Document:
        p = self
        while type(p) is Element:
            p = p._parent
        return p

    def itersiblings(self, tag=None, preceding: bool = False):
        """The following (or, ``preceding``, the earlier, nearest first) siblings; with ``tag``, those with it."""
        p = self._parent
        sibs = list(p)
        i = next(k for k, s in enumerate(sibs) if s is self)
        seq = reversed(sibs[:i]) if preceding else iter(sibs[i + 1:])
        return seq if tag is None else (s for s in seq if s.tag == tag)

    @property
    def sourceline(self) -> int:
        """libxml2's line: the line of the ``>`` that ends the start tag (comment, instruction)."""
        line = self._line
        if line is None:
            line = self._line = self.getroottree().line_of(self)
        return line


def _matches(tag, tags) -> bool:
    for t in tags:
        if tag == t or (isinstance(tag, str) and t.startswith("{*}") and tag.rsplit("}", 1)[-1] == t[3:]):
            return True
    return False


def _lxml_order(root) -> list:
    """lxml's nodes in the order of Document._order."""
    return list(reversed(list(root.itersiblings(preceding=True)))) + list(root.iter()) + list(root.itersiblings())


def attribute_values(root, name: str) -> list:
    """The values of attribute ``name`` (un-namespaced) on the element and every element below it,
    in document order, of this tree or of lxml's."""
    if type(root) is not Element:
        return root.xpath(f"descendant-or-self::*/@{name}", smart_strings=False)
    return [v for v in (el.attrib.get(name) for el in root.iter()) if v is not None]


def _parser(data: bytes, doc=None):
    """An expat parser for ``data`` that raises Refused on what lxml should judge (a DTD or entity,
    an encoding of its own, a declared prefix past libxml2's longest name): ``_run`` parses with
    it. Refused at once for a document too big for libxml2 or in UTF-16. ``doc``: the Document
    that takes the declared encoding."""
    if len(data) > MAX_BYTES or data[:2] in (b"\xff\xfe", b"\xfe\xff") or b"\x00" in data[:4]:
        raise Refused                   # too big for libxml2 without huge_tree; UTF-16 (lines counted in bytes)
    p = expat.ParserCreate(namespace_separator=_SEP)
    p.namespace_prefixes = True
    p.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)

    def refuse(*args):
        raise Refused

    def xml_decl(version, encoding, standalone):
        if encoding is not None:
            if encoding.lower() not in _ENCODINGS:
                raise Refused           # expat's single-byte tables need not be libxml2's
            if doc is not None:
                doc.encoding = encoding

    p.XmlDeclHandler = xml_decl
    if b"xmlns:" in data:               # a prefix declared and never used is a name too
        p.StartNamespaceDeclHandler = lambda prefix, uri: prefix is not None and len(prefix) > MAX_NAME and refuse()
    p.StartDoctypeDeclHandler = refuse
    p.EntityDeclHandler = refuse
    p.UnparsedEntityDeclHandler = refuse
    p.ExternalEntityRefHandler = refuse
    p.SkippedEntityHandler = refuse
    return p


def _run(p, data: bytes) -> None:
    """Parse the whole of ``data`` with ``_parser``'s ``p``; Refused where expat stops or a name
    is longer than libxml2 takes."""
    paused = gc.isenabled()
    gc.disable()                        # a tree of long-lived nodes, no garbage: each collection would rescan them
    try:
        p.Parse(data, True)
    except (expat.ExpatError, ValueError, RecursionError):
        raise Refused from None
    finally:
        if paused:
            gc.enable()
    # every tag, attribute name and instruction target passed through expat's table of names
    if any(len(part) > MAX_NAME for n in p.intern if n for part in n.split(_SEP)[1:] or (n,)):
        raise Refused


def any_element(data: bytes, test) -> bool:
    """Whether ``test(local name, attributes)`` holds for an element of XML ``data``, read whole as
    ``parse`` reads it (Refused likewise) but without a tree or its text: a mesh's bytes are mostly
    numbers."""
    p = _parser(data)
    found = False
    depth = 0

    def start(name, attrs):
        nonlocal found, depth
        depth += 1
        if depth > MAX_DEPTH:
            raise Refused
        if not found and test(name.split(_SEP)[1] if _SEP in name else name, attrs):
            found = True

    def end(name):
        nonlocal depth
        depth -= 1

    p.StartElementHandler = start
    p.EndElementHandler = end
    _run(p, data)
    return found


def parse(data: bytes) -> Element:
    """The root element of XML ``data``; Refused for what lxml should judge (see the module docstring)."""
    doc = Document(data)
    p = _parser(data, doc)
    p.buffer_text = True
    add_node = doc.nodes.append

    cur = doc                           # the node whose children come next
    last = None                         # the child of cur that ended last (its tail comes next), or None
    texts: list = []
    depth = 0

    # Each handler hands the pending text to the node it belongs to itself: a shared helper would be
    # one more Python call per element, which a large document feels.
    def start(name, attrs):
        nonlocal cur, last, depth
        if texts:
            s = "".join(texts)
            texts.clear()
            if last is None:
                cur.text = s
            else:
                last.tail = s
        depth += 1
        if depth > MAX_DEPTH:
            raise Refused
        el = Element()
        if _SEP in name:
            el.tag, el.prefix = _clark(name)
        else:
            el.tag = name
        if attrs and _SEP in "".join(attrs):
            attrs = {_clark(k)[0]: v for k, v in attrs.items()}
        el.attrib = attrs
        el.text = el.tail = None
        el._pos = p.CurrentByteIndex
        el._parent = cur
        cur.append(el)
        add_node(el)
        cur = el
        last = None

    def end(name):
        nonlocal cur, last, depth
        if texts:
            s = "".join(texts)
            texts.clear()
            if last is None:
                cur.text = s
            else:
                last.tail = s
        depth -= 1
        last = cur
        cur = cur._parent

    def other(tag, text, target=None):
        """A comment or processing instruction."""
        nonlocal last
        if texts:
            s = "".join(texts)
            texts.clear()
            if last is None:
                cur.text = s
            else:
                last.tail = s
        n = Element()
        n.tag, n.attrib, n.text, n.tail, n._pos, n._parent = tag, {}, text, None, p.CurrentByteIndex, cur
        if target is not None:
            n.target = target
        cur.append(n)
        add_node(n)
        last = n

    p.StartElementHandler = start
    p.EndElementHandler = end
    p.CharacterDataHandler = texts.append
    p.StartCdataSectionHandler = lambda: texts.append("")      # <![CDATA[]]>: lxml's text is ''
    p.CommentHandler = lambda data: other(Comment, data)
    p.ProcessingInstructionHandler = lambda target, data: other(ProcessingInstruction, data, target)
    _run(p, data)
    before = None
    for i, n in enumerate(doc):
        n.tail = None                   # lxml keeps no text beside the root
        if type(n.tag) is str:
            doc.root, before = n, i
    nodes = doc.nodes                   # the root's own nodes: leave out its siblings
    del nodes[len(nodes) - (len(doc) - before - 1):]
    del nodes[:before]
    return doc.root


def parse_safely(data: bytes, name: str):
    """A model file's root element, as ``safety.parse_xml_bytes`` reads it (the same checks, the
    same verdict and message on what it refuses), in this tree wherever expat reads the file."""
    check_xml_bytes(data, name)
    try:
        return parse(data)
    except Refused:
        return parse_xml_bytes(data, name)


def _clark(name: str) -> tuple:
    """expat's ``uri SEP local [SEP prefix]`` as (``{uri}local``, prefix or None)."""
    if _SEP not in name:
        return name, None
    parts = name.split(_SEP)
    return "{" + parts[0] + "}" + parts[1], (parts[2] if len(parts) > 2 else None)
