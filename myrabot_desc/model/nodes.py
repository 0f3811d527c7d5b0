"""Markup the robot carries as it is, as an immutable tree: a sensor's body, a plugin with its
parameters, a ``<gazebo>`` block's ``<visual>``, ``<light>`` or ``<joint>`` that convert copies
into SDF.

A :class:`Node` is one element (or a comment or processing instruction inside one): its local
tag, namespace and prefix, attributes in document order, text, tail, children, where it was
written (``loc``, the xacro file:line) and ``ref``, the opaque handle ``Robot.sources`` reads
spans with. The loader builds them (``node``); consumers read them and, to write them out, build
their own elements from them (convert/common.element_of). Nobody outside model/ touches the
robot's lxml elements.

Values inside are text; read them through model/values.py (``node.number("mu1")``).
"""

from __future__ import annotations

from typing import Any, NamedTuple

from myrabot_desc.diagnostics import Loc
from myrabot_desc.model import values as V


class Node(NamedTuple):
    tag: str                          # local name ('' for a comment or processing instruction)
    attrs: tuple = ()                 # ((name, value), ...) in document order (Clark {ns}name when namespaced)
    text: str | None = None           # text before the first child (a comment's or PI's content)
    children: tuple = ()              # Node, ...
    loc: Loc | None = None
    ref: Any = None                   # the URDF element, for Robot.sources (opaque)
    ns: str = ""                      # namespace URI ('' for none)
    prefix: str | None = None         # the namespace prefix as written (Electric 'controller', 'sensor')
    tail: str | None = None           # text after the element, before its next sibling
    kind: str = "element"             # 'element' | 'comment' | 'pi' | 'entity'
    target: str | None = None         # a processing instruction's target

    # ------------------------------------------------------------ reading
    @property
    def is_element(self) -> bool:
        return self.kind == "element"

    @property
    def elements(self) -> tuple:
        """The child elements (no comments)."""
        return tuple(c for c in self.children if c.kind == "element")

    def get(self, name: str, default=None):
        """An attribute's value."""
        for k, v in self.attrs:
            if k == name:
                return v
        return default

    @property
    def value(self) -> str:
        """The value a parameter element carries: its stripped text, else its ``value=`` attribute
        (``<mu1>0.5</mu1>`` and ``<mu1 value="0.5"/>``), stripped; '' when neither."""
        t = (self.text or "").strip()
        return t if t else (self.get("value") or "").strip()

    def child(self, *tags: str):
        """The first child element whose local name is one of ``tags``, or None."""
        for c in self.children:
            if c.kind == "element" and c.tag in tags:
                return c
        return None

    def all(self, tag: str) -> list:
        """Every child element named ``tag``, in order."""
        return [c for c in self.children if c.kind == "element" and c.tag == tag]

    def find(self, *path: str):
        """The descendant element at ``path`` (local names, first match at each step), or None."""
        n = self
        for p in path:
            n = n.child(p)
            if n is None:
                return None
        return n

    def iter(self):
        """This element and every element below it, depth first, in document order."""
        stack = [self]
        while stack:
            n = stack.pop()
            if n.kind != "element":
                continue
            yield n
            stack.extend(reversed(n.children))

    # ------------------------------------------------------------ typed values (model/values.py)
    def text_at(self, *path: str) -> str | None:
        """The value (text or ``value=``) of the element at ``path``, None when absent or empty."""
        n = self.find(*path)
        if n is None:
            return None
        return n.value or None

    def number(self, *path: str, default=None):
        return V.number(self.text_at(*path), default)

    def vector(self, *path: str, n: int | None = None, default=None):
        return V.vector(self.text_at(*path), n, default)

    def boolean(self, *path: str, default=None, spellings=V.SDF):
        return V.boolean(self.text_at(*path), default, spellings)


def node(el, loc_of) -> Node:
    """The Node tree of lxml element ``el``; ``loc_of(el)``: its location (the loader's)."""
    tag = el.tag
    if not isinstance(tag, str):
        from lxml import etree

        if isinstance(el, etree._Comment):
            return Node("", text=el.text, tail=el.tail, kind="comment", loc=None)
        if isinstance(el, etree._ProcessingInstruction):
            return Node("", text=el.text, tail=el.tail, kind="pi", target=el.target)
        return Node(el.text or "", tail=el.tail, kind="entity")       # an entity reference: &name;
    ns, local = "", tag
    if tag.startswith("{"):
        ns, local = tag[1:].split("}", 1)
    children = tuple(node(c, loc_of) for c in el)
    return Node(local, tuple(el.attrib.items()), el.text, children, loc_of(el), el, ns, el.prefix if ns else None,
                el.tail)
