"""Model XML straight into the minidom document that xacro expands, safely, each element
naming its source line.

expat (what xacro itself parses with) builds the document in one pass, so a build needs no
lxml: no second parse, no re-serialisation, and ~15 ms less start-up. Whatever expat stops at
(malformed XML, a DTD or entity declaration, an unknown encoding, nesting deeper than libxml2
allows) goes through safety.parse_xml_bytes instead, so a refused file gets the same message
as everywhere else, and a file only lxml reads (e.g. windows-1252) still builds.

While building, each element gets its source annotation (``_mdsrc="N"``, or ``xacro:mdsrc``
on elements of the xacro namespace, N indexing the build's list of Locs), and the elements
the build asks about later (macros, includes, un-prefixed xacro words, the un-prefixed tag
names) are noted: no walk of the tree afterwards.
"""

from __future__ import annotations

from xml.dom import expatbuilder, minidom
from xml.parsers import expat

from myrabot_desc.diagnostics import Loc
from myrabot_desc.safety import check_xml_bytes, parse_xml_bytes

# libxml2 refuses elements nested deeper than 256 and text nodes over 10 MB (no huge_tree):
# past these, lxml gives the verdict.
MAX_DEPTH = 250
MAX_EXPAT_BYTES = 10_000_000
SRC_ATTR = "_mdsrc"             # the source annotation (the build reads it off as it writes)
XSRC_ATTR = "xacro:mdsrc"       # ... on xacro elements (xacro's attribute checks skip xacro:*)
XSRC_LOCAL = "mdsrc"
NOTED = {"macro", "include"}    # local names of the elements noted (any namespace)
LEGACY_WORDS = {"macro", "property", "include", "insert_block", "arg", "if", "unless"}


class _Stop(Exception):
    """expat met something that lxml should judge."""


class Parsed:
    """A parsed file: the document, the elements noted while parsing, un-prefixed tag names."""

    __slots__ = ("doc", "noted", "plain_words", "plain_tags")

    def __init__(self, doc, noted, plain_words, plain_tags):
        self.doc = doc
        self.noted = noted              # elements named macro or include (any namespace), in order
        self.plain_words = plain_words  # un-prefixed elements named like a xacro word (legacy candidates)
        self.plain_tags = plain_tags    # every un-prefixed, un-namespaced tag name


class _Builder(expatbuilder.ExpatBuilderNS):
    """minidom's own builder (as xacro's minidom.parse uses), annotating each element with
    its source line, refusing any DTD or entity declaration, and bounding the nesting."""

    def __init__(self, locs: list, fname: str, lines=None, max_depth: int = MAX_DEPTH, offsets=None):
        super().__init__()
        self.locs = locs
        self.offsets = offsets          # byte offset of each element's start tag (None: not known)
        self.fname = fname
        self.lines = lines              # the lines to use (lxml's), else expat's own
        self.depth = 0
        self.max_depth = max_depth
        self.xacro_uri = False          # not known before the root element
        self.noted: list = []
        self.plain_words: list = []
        self.plain_tags: set = set()

    def install(self, parser):
        super().install(parser)
        parser.StartDoctypeDeclHandler = self._stop
        parser.EntityDeclHandler = self._stop
        parser.UnparsedEntityDeclHandler = self._stop
        parser.ExternalEntityRefHandler = self._stop
        parser.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)

    def _stop(self, *args):
        raise _Stop

    def start_element_handler(self, name, attributes):
        self.depth += 1
        if self.depth > self.max_depth:
            raise _Stop
        if self.xacro_uri is False:     # the root: the namespace its xacro prefix is bound to
            self.xacro_uri = next((u for p, u in self._ns_ordered_prefixes if p == "xacro"), None)
        super().start_element_handler(name, attributes)
        node = self.curNode
        line = self._parser.CurrentLineNumber if self.lines is None else next(self.lines)
        idx = str(len(self.locs))
        self.locs.append(Loc(self.fname, line))
        if self.offsets is not None:
            self.offsets.append(self._parser.CurrentByteIndex if self.lines is None else None)
        uri = node.namespaceURI
        if uri is not None and uri == self.xacro_uri:
            a = minidom.Attr(XSRC_ATTR, uri, XSRC_LOCAL, "xacro")
            key = (uri, XSRC_LOCAL)
        else:
            a = minidom.Attr(SRC_ATTR, None, SRC_ATTR, None)
            key = (None, SRC_ATTR)
        node._ensure_attributes()
        node._attrs[a.nodeName] = a
        node._attrsNS[key] = a
        a.ownerDocument = self.document
        a.value = idx
        a.ownerElement = node
        if uri is None:
            tag = node.tagName
            self.plain_tags.add(tag)
            if tag in LEGACY_WORDS:
                self.plain_words.append(node)
            if tag in NOTED:
                self.noted.append(node)
        elif node.localName in NOTED:
            self.noted.append(node)

    def end_element_handler(self, name):
        self.depth -= 1
        super().end_element_handler(name)


def _expat(data, locs, fname, lines=None, max_depth: int = MAX_DEPTH, offsets=None) -> Parsed:
    b = _Builder(locs, fname, lines, max_depth, offsets)
    doc = b.parseString(data)
    return Parsed(doc, b.noted, b.plain_words, b.plain_tags)


def parse(data: bytes, name: str, locs: list, offsets: list | None = None) -> Parsed:
    """A model file's bytes, parsed; each element's Loc appended to ``locs`` (its annotation
    is the index there) and, with ``offsets``, the byte offset of its start tag in ``data`` (None
    where lxml read the file). InputError (``name:line: error: ...``) for a file that may not or
    cannot be read."""

    check_xml_bytes(data, name)
    if len(data) <= MAX_EXPAT_BYTES:
        mark = len(locs)
        try:
            return _expat(data, locs, name, offsets=offsets)
        except (_Stop, expat.ExpatError, ValueError, RecursionError):
            del locs[mark:]
            if offsets is not None:
                del offsets[mark:]
    return _via_lxml(data, name, locs, offsets)


def _via_lxml(data: bytes, name: str, locs: list, offsets: list | None = None) -> Parsed:
    """lxml's verdict (and message) on the file; when it reads it, its text for expat."""
    from lxml import etree

    root = parse_xml_bytes(data, name)
    # comments and PIs around the root element belong to the document too (xacro keeps them)
    text = "".join(etree.tostring(s, encoding="unicode") for s in reversed(list(root.itersiblings(preceding=True))))
    text += etree.tostring(root, encoding="unicode", with_tail=False)
    text += "".join(etree.tostring(s, encoding="unicode") for s in root.itersiblings())
    lines = iter([el.sourceline for el in root.iter() if isinstance(el.tag, str)])
    # (the text is lxml's re-serialisation: its offsets are not the file's)
    return _expat(text.encode("utf-8"), locs, name, lines, max_depth=10**9, offsets=offsets)   # lxml bounded the depth
