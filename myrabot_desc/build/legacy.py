"""Upgrade ROS Electric/Fuerte xacro syntax to ``xacro:`` form before expansion.

Old files use un-prefixed ``<macro>``, ``<property>``, ``<include>``,
``<insert_block>``, ``<arg>``, ``<if>``, ``<unless>`` and call macros by bare
name (``<roomba/>``, ``<kinect parent="...">``), with or without an xacro
namespace declaration. xacro 2.x copies all of that into its output silently
(anchors.md §1.4). We rename those elements in the lxml tree; a bare call is an
element whose name is a macro defined anywhere in the include tree.
"""

from __future__ import annotations

from lxml import etree

XACRO_NS = "http://www.ros.org/wiki/xacro"

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


def is_legacy_tag(el) -> bool:
    """An un-prefixed element that old xacro read as one of its own.

    As xacro 1.x did, an <include> with element children is not a xacro include."""
    tag = el.tag
    if tag not in LEGACY_TAGS or el.get(LEGACY_TAGS[tag]) is None:
        return False
    return not (tag == "include" and any(isinstance(c.tag, str) for c in el))


def local_name(el) -> str:
    tag = el.tag
    return tag.rsplit("}", 1)[-1] if isinstance(tag, str) else ""


def is_plain(el) -> bool:
    """An element without a namespace (no prefix, no default namespace)."""
    return isinstance(el.tag, str) and not el.tag.startswith("{")


def xacro_uri(root) -> str | None:
    """The namespace URI bound to the ``xacro`` prefix in this document, if any."""
    return root.nsmap.get("xacro")


def is_xacro(el, uri: str | None) -> bool:
    return isinstance(el.tag, str) and uri is not None and el.tag.startswith("{" + uri + "}")


def macro_names(root) -> set[str]:
    """Names of macros defined in this document, prefixed or not."""
    uri = xacro_uri(root)
    names = set()
    for el in root.iter():
        if not isinstance(el.tag, str):
            continue
        if (is_plain(el) and el.tag == "macro") or (is_xacro(el, uri) and local_name(el) == "macro"):
            name = el.get("name")
            if name:
                names.add(name)
    return names


def include_filenames(root) -> list[tuple[str, int]]:
    """(filename spec, line) of every include, prefixed or not."""
    uri = xacro_uri(root)
    out = []
    for el in root.iter():
        if not isinstance(el.tag, str):
            continue
        if (is_plain(el) and el.tag == "include") or (is_xacro(el, uri) and local_name(el) == "include"):
            if el.get("filename"):
                out.append((el.get("filename"), el.sourceline or 0))
    return out


def needs_upgrade(root, known_macros: set[str]) -> bool:
    for el in root.iter():
        if is_plain(el) and (is_legacy_tag(el) or el.tag in known_macros):
            return True
    return False


def upgrade(root, known_macros: set[str]):
    """Rename legacy elements in place; return (new_root, {kind: (count, first_line, macro names)}).

    ``new_root`` differs from ``root`` only when the xacro namespace had to be
    declared (files from the Electric era often have none).
    """
    uri = xacro_uri(root)
    if uri is None:
        root = _with_xacro_ns(root)
        uri = XACRO_NS
    found: dict[str, list] = {}
    for el in list(root.iter()):
        if not is_plain(el):
            continue
        tag = el.tag
        if is_legacy_tag(el):
            kind = f"<{tag}>"
        elif tag in known_macros:
            kind = "bare macro call"
        else:
            continue
        el.tag = "{%s}%s" % (uri, tag)
        entry = found.setdefault(kind, [0, el.sourceline or 0, []])
        entry[0] += 1
        if kind == "bare macro call" and tag not in entry[2]:
            entry[2].append(tag)
    return root, {k: tuple(v) for k, v in found.items()}


def _with_xacro_ns(root):
    """Copy of ``root`` whose nsmap binds ``xacro``; children moved, not copied."""
    nsmap = dict(root.nsmap)
    nsmap["xacro"] = XACRO_NS
    new = etree.Element(root.tag, attrib=dict(root.attrib), nsmap=nsmap)
    new.sourceline = root.sourceline
    new.text = root.text
    new.tail = root.tail
    for child in list(root):
        new.append(child)
    return new
