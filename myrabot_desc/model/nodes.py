"""Markup the robot carries as it is, as an immutable tree: a sensor's body, a plugin with its
parameters, a ``<gazebo>`` block's ``<visual>``, ``<light>`` or ``<joint>`` that convert copies
into SDF.

A :class:`Node` is one element (or a comment or processing instruction inside one): its local
tag, namespace and prefix, attributes in document order, text, tail, children, where it was
written (``loc``, the xacro file:line) and ``ref``, the opaque handle ``Robot.sources`` reads
spans with. The loader builds them (``node``); consumers read them and, to write them out, build
their own elements from them (convert/common.element_of). Nobody outside model/ touches the
robot's XML elements.

Values inside are text; read them through model/values.py (``node.number("mu1")``).
"""

from __future__ import annotations

from myrabot_desc import xmltree
from myrabot_desc.diagnostics import Loc
from myrabot_desc.model import values as V


class Node:
    """One element (or comment, processing instruction, entity reference) as written. Immutable:
    its children are read from the element the first time they are asked for (most nodes of a
    large model are never walked), then kept."""

    __slots__ = ("tag", "attrs", "text", "loc", "ref", "ns", "prefix", "tail", "kind", "target", "_kids", "_loc_of")

    def __init__(self, tag: str, attrs: tuple = (), text: str | None = None, children: tuple | None = (),
                 loc: Loc | None = None, ref: object = None, ns: str = "", prefix: str | None = None,
                 tail: str | None = None, kind: str = "element", target: str | None = None, loc_of=None):
        self.tag = tag                # local name ('' for a comment or processing instruction)
        self.attrs = attrs            # ((name, value), ...) in document order (Clark {ns}name when namespaced)
        self.text = text              # text before the first child (a comment's or PI's content)
        self.loc = loc                # the xacro file:line it came from
        self.ref = ref                # the URDF element, for Robot.sources (opaque)
        self.ns = ns                  # namespace URI ('' for none)
        self.prefix = prefix          # the namespace prefix as written (Electric 'controller', 'sensor')
        self.tail = tail              # text after the element, before its next sibling
        self.kind = kind              # 'element' | 'comment' | 'pi' | 'entity'
        self.target = target          # a processing instruction's target
        self._kids = children         # None: not read yet (from ref, with loc_of)
        self._loc_of = loc_of

    def __repr__(self) -> str:
        return f"Node(<{self.tag or self.kind}> {dict(self.attrs)!r} at {self.loc})"

    @property
    def children(self) -> tuple:
        """The child nodes (elements, comments...), in document order."""
        k = self._kids
        if k is None:
            k = self._kids = tuple(node(c, self._loc_of) for c in self.ref)
        return k

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
    """The Node of element ``el``, xmltree's or lxml's (its children read when first asked for);
    ``loc_of(el)``: an element's location (the loader's)."""
    tag = el.tag
    if not isinstance(tag, str):
        if tag is xmltree.Comment:
            return Node("", text=el.text, tail=el.tail, kind="comment")
        if tag is xmltree.ProcessingInstruction:
            return Node("", text=el.text, tail=el.tail, kind="pi", target=el.target)
        from lxml import etree          # (an element lxml read: see xmltree.py)

        if isinstance(el, etree._Comment):
            return Node("", text=el.text, tail=el.tail, kind="comment")
        if isinstance(el, etree._ProcessingInstruction):
            return Node("", text=el.text, tail=el.tail, kind="pi", target=el.target)
        return Node(el.text or "", tail=el.tail, kind="entity")       # an entity reference: &name;
    ns, local = "", tag
    if tag[0] == "{":
        ns, local = tag[1:].split("}", 1)
    return Node(local, tuple(el.items()), el.text, None if len(el) else (), loc_of(el), el, ns,
                el.prefix if ns else None, el.tail, loc_of=loc_of)
