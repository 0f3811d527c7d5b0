"""Small shared pieces: warnings, number formatting, rigid transforms, XML helpers."""

from __future__ import annotations

from dataclasses import dataclass, field

from lxml import etree

from myrabot_desc.model import values as V
from myrabot_desc.model.transforms import EYE3, rpy_of


@dataclass
class Notes:
    """Warnings gathered during a conversion (printed on stderr by the CLI)."""

    warnings: list[str] = field(default_factory=list)
    # the texts already in ``warnings``: a model with a warning per joint (mimics, planar joints)
    # would otherwise compare each new one with all the others
    _seen: set = field(default_factory=set, init=False, repr=False, compare=False)

    def __post_init__(self):
        self._seen.update(self.warnings)

    def warn(self, message: str, loc=None) -> None:
        text = f"{loc}: warning: {message}" if loc else f"warning: {message}"
        if text not in self._seen:
            self._seen.add(text)
            self.warnings.append(text)


def warn_load_issues(robot, notes: Notes, fate: str = "left out of the conversion") -> None:
    """What the loader could not read (a NaN, a nameless link...): say so at its file:line
    rather than convert silently around it. ``fate``: what the converter does with it."""
    for d in robot.load_issues:
        notes.warn(f"{d.code} {d.message}: {fate} (run check)", d.loc)


def num(x: float) -> str:
    """Shortest stable text for a float: 12 significant digits, no -0, no 1e-17 noise."""
    if type(x) is float:
        s = _NUM_TEXT.get(x)
        if s is not None:
            return s
    else:
        x = float(x)
    if -1e-12 < x < 1e-12:
        return "0"
    s = f"{x:.12g}"
    if s == "-0":
        s = "0"
    if len(_NUM_TEXT) < _NUM_TEXT_MAX:
        _NUM_TEXT[x] = s
    return s


# A model repeats its numbers (0, 1, a link's size...): each one's text is formatted once. Keys are
# floats only; equal floats (0.0 and -0.0 included) have the same text. Bounded for long processes.
_NUM_TEXT: dict = {}
_NUMS_TEXT: dict = {}
_NUM_TEXT_MAX = 1 << 16


def nums(values) -> str:
    if type(values) is tuple:       # a vector as the model holds it (an axis, a size): often repeated
        s = _NUMS_TEXT.get(values)
        if s is None:
            s = " ".join([num(v) for v in values])
            if len(_NUMS_TEXT) < _NUM_TEXT_MAX:
                _NUMS_TEXT[values] = s
        return s
    return " ".join([num(v) for v in values])


def to_float(text, default=None):
    """model/values.number (convert/mjcf.py's name for it, until its rewrite)."""
    return V.number(text, default)


def pose_text(T) -> str:
    """An SDF <pose> text of a transform (see model/transforms.py)."""
    R, p = T
    if R == EYE3:       # no rotation (signed zeros included): rpy_of's angles are all zeros
        return nums(p) + " 0 0 0"
    return nums(list(p) + list(rpy_of(R)))


# ---------------------------------------------------------------- XML
def sub(parent, tag: str, text=None, **attrs):
    """Append a child element; ``text`` may be a str, a number or a sequence of numbers."""
    # the exact-type tests first: a 20,000-link model makes half a million of these
    if attrs:
        el = _SubElement(parent, tag, {k.rstrip("_"): v if type(v) is str else str(v)
                                       for k, v in attrs.items() if v is not None})
    else:
        el = _SubElement(parent, tag)
    if text is not None:
        kind = type(text)
        if kind is str:
            el.text = text
        elif kind is float or kind is int:
            el.text = num(text)
        elif kind is tuple or kind is list:
            el.text = nums(text)
        elif isinstance(text, bool):
            el.text = "true" if text else "false"
        elif isinstance(text, (int, float)):
            el.text = num(text)
        elif isinstance(text, (list, tuple)):
            el.text = nums(text)
        else:
            el.text = str(text)
    return el


_SubElement = etree.SubElement


def comment(parent, text: str):
    # XML comments may not contain "--"
    c = etree.Comment(" " + text.replace("--", "- -") + " ")
    parent.append(c)
    return c


def local(tag) -> str:
    """A tag without its namespace (convert/mjcf.py's, on its copy of the robot, until its rewrite)."""
    return etree.QName(tag).localname if isinstance(tag, str) else ""


def element_of(node, parent=None):
    """A new lxml element (with its subtree) from a model node (model/nodes.Node): markup that
    convert carries into SDF as it is. Under ``parent`` when given (the node's tail kept)."""
    if node.kind == "comment":
        el = etree.Comment(node.text)
    elif node.kind == "pi":
        el = etree.ProcessingInstruction(node.target, node.text)
    elif node.kind == "entity":
        el = etree.Entity(node.tag.strip("&;"))
    else:
        tag = f"{{{node.ns}}}{node.tag}" if node.ns else node.tag
        if parent is None:
            el = etree.Element(tag, nsmap=_namespaces(node) or None)
        else:
            el = etree.SubElement(parent, tag)
        for k, v in node.attrs:
            el.set(k, v)
        el.text = node.text
        for c in node.children:
            element_of(c, el)
        if parent is not None:
            el.tail = node.tail
        return el
    if parent is not None:
        parent.append(el)
        el.tail = node.tail
    return el


def _namespaces(node) -> dict:
    """prefix -> namespace of every namespaced element below ``node``, in document order (what a
    copy of the element declares on its top)."""
    out: dict = {}
    for n in node.iter():
        if n.ns and n.ns not in out.values():
            out.setdefault(n.prefix, n.ns)
    return out


def xml_text(node) -> str:
    """A model node (model/nodes.Node) as compact one-line-ish XML text (for comments)."""
    e = element_of(node)
    etree.cleanup_namespaces(e)
    return etree.tostring(e, encoding="unicode", with_tail=False)


def pretty(root, xml_declaration: bool = True) -> str:
    etree.indent(root, space="  ")
    body = etree.tostring(root, encoding="unicode", pretty_print=True)
    return ('<?xml version="1.0" encoding="utf-8"?>\n' if xml_declaration else "") + body
