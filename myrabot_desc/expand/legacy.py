"""Upgrade ROS Electric/Fuerte xacro syntax to ``xacro:`` form before expansion.

Old files use un-prefixed ``<macro>``, ``<property>``, ``<include>``,
``<insert_block>``, ``<arg>``, ``<if>``, ``<unless>`` and call macros by bare
name (``<roomba/>``, ``<kinect parent="...">``), with or without an xacro
namespace declaration. xacro 2.x copies all of that into its output silently
(anchors.md §1.4). We rename those elements in the minidom tree the build hands
to xacro; a bare call is an element whose name is a macro defined anywhere in
the include tree.
"""

from __future__ import annotations

XACRO_NS = "http://www.ros.org/wiki/xacro"
XMLNS_NS = "http://www.w3.org/2000/xmlns/"
ELEMENT = 1

# tag -> attribute that must be present for the element to be read as xacro
# (guards against SDF's own <include>, which has no filename attribute, and roslaunch's
# <arg name= value=>: a xacro arg always had a default)
LEGACY_TAGS = {
    "macro": "name",
    "property": "name",
    "include": "filename",
    "insert_block": "name",
    "arg": "default",
    "if": "value",
    "unless": "value",
}


def elements(root) -> list:
    """``root`` and every element below it, in document order."""
    out, stack = [], [root]
    while stack:
        el = stack.pop()
        out.append(el)
        kids = [c for c in el.childNodes if c.nodeType == ELEMENT]
        kids.reverse()
        stack.extend(kids)
    return out


def is_plain(el) -> bool:
    """An element without a namespace (no prefix, no default namespace)."""
    return el.namespaceURI is None


def is_legacy_tag(el) -> bool:
    """An un-prefixed element that old xacro read as one of its own.

    As xacro 1.x did, an <include> with element children is not a xacro include."""
    tag = el.tagName
    if not is_plain(el) or tag not in LEGACY_TAGS or not el.hasAttribute(LEGACY_TAGS[tag]):
        return False
    return not (tag == "include" and any(c.nodeType == ELEMENT for c in el.childNodes))


def xacro_uri(root) -> str | None:
    """The namespace URI bound to the ``xacro`` prefix on the root element, if any."""
    return root.getAttribute("xmlns:xacro") or None


def is_xacro(el, uri: str | None) -> bool:
    return uri is not None and el.namespaceURI == uri


def _named(els, uri, word: str, attr: str) -> list[str]:
    out = []
    for el in els:
        if (el.namespaceURI is None and el.tagName == word) or (is_xacro(el, uri) and el.localName == word):
            value = el.getAttribute(attr)
            if value:
                out.append(value)
    return out


def macro_names(root, els=None) -> set[str]:
    """Names of macros defined in this document, prefixed or not."""
    return set(_named(els if els is not None else elements(root), xacro_uri(root), "macro", "name"))


def include_filenames(root, els=None) -> list[str]:
    """The filename spec of every include, prefixed or not."""
    return [spec for spec, _ in includes(root, els)]


def includes(root, els=None) -> list[tuple[str, bool]]:
    """(filename spec, has ns=) of every include, prefixed or not. A file included with ``ns=``
    puts its macros in that name space: xacro reaches them only as ``ns.name``, never bare."""
    uri = xacro_uri(root)
    out = []
    for el in els if els is not None else elements(root):
        if (el.namespaceURI is None and el.tagName == "include") or (is_xacro(el, uri) and el.localName == "include"):
            value = el.getAttribute("filename")
            if value:
                out.append((value, bool(el.getAttribute("ns"))))
    return out


def _inside_macro(el, name: str, uri) -> bool:
    """The element sits in the body of the macro ``name`` itself: as a call it would recurse
    forever, so it is markup of the same name (rosbot_xl's macro ``imu`` writes an SDF ``<imu>``)."""
    p = el.parentNode
    while p is not None and getattr(p, "tagName", None) is not None:
        if ((p.namespaceURI is None and p.tagName == "macro") or (is_xacro(p, uri) and p.localName == "macro")) \
                and p.getAttribute("name") == name:
            return True
        p = p.parentNode
    return False


def upgrade(root, known_macros: set[str], line_of: dict, els=None, upgraded: list | None = None):
    """Rename legacy elements in place (declaring the xacro namespace on the root when the file
    has none, as Electric-era files often do); return {kind: (count, first_line, macro names)}.
    ``line_of``: element -> source line; ``upgraded`` collects (element, kind) of each one renamed."""
    uri = xacro_uri(root)
    if uri is None:
        uri = XACRO_NS
        root.setAttributeNS(XMLNS_NS, "xmlns:xacro", uri)
    found: dict[str, list] = {}
    for el in list(els if els is not None else elements(root)):
        if not is_plain(el):
            continue
        tag = el.tagName
        if is_legacy_tag(el):
            kind = f"<{tag}>"
        elif tag in known_macros and not _inside_macro(el, tag, uri):
            kind = "bare macro call"
        else:
            continue
        el.tagName = el.nodeName = "xacro:" + tag
        el.prefix = "xacro"
        el.namespaceURI = uri
        if upgraded is not None:
            upgraded.append((el, kind))
        entry = found.setdefault(kind, [0, line_of.get(el) or 0, []])
        entry[0] += 1
        if kind == "bare macro call" and tag not in entry[2]:
            entry[2].append(tag)
    return {k: tuple(v) for k, v in found.items()}
