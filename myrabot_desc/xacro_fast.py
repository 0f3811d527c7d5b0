"""Linear-time node replacement for xacro's minidom expansion.

xacro 2.1.1 replaces every macro call with ``parent.insertBefore(child, node)``
per child, and minidom's insertBefore/removeChild locate nodes with
``list.index``/``list.remove``: O(siblings) each, so a file with N top-level macro
calls expands in O(N²) (1,000 calls 3.1 s, 4,000 calls 47 s; ros/xacro #292, #57).

Here the whole replacement is one list splice, and the position of the node is
found from a per-parent hint (xacro walks siblings left to right, so the node is
at or just after the hint). The resulting tree is exactly the one xacro builds;
tests compare the output byte for byte with plain xacro.
"""

from __future__ import annotations

import xml.dom

TEXT = xml.dom.Node.TEXT_NODE
COMMENT = xml.dom.Node.COMMENT_NODE

# id(parent) -> (parent, hint index). Elements use __slots__, so hints live here.
_hints: dict[int, tuple[object, int]] = {}
# Where xacro's shared "\n\n" text node currently sits: (parent, index).
_singleton_pos: list = [None, 0]


def reset() -> None:
    _hints.clear()
    _singleton_pos[0] = None


def _index(parent, node) -> int:
    kids = parent.childNodes
    entry = _hints.get(id(parent))
    hint = entry[1] if entry is not None and entry[0] is parent else 0
    if hint < len(kids) and kids[hint] is node:
        return hint
    try:
        return kids.index(node, min(hint, len(kids)))
    except ValueError:
        return kids.index(node)


def _set_hint(parent, value: int) -> None:
    _hints[id(parent)] = (parent, value)


def _shift_hint(parent, at: int, delta: int) -> None:
    entry = _hints.get(id(parent))
    if entry is not None and entry[0] is parent and entry[1] > at:
        _hints[id(parent)] = (parent, entry[1] + delta)


def _link(kids, start: int, stop: int) -> None:
    """Repair sibling pointers of kids[start-1 .. stop]."""
    prev = kids[start - 1] if start > 0 else None
    for i in range(start, stop):
        c = kids[i]
        c.previousSibling = prev
        if prev is not None:
            prev.nextSibling = c
        prev = c
    nxt = kids[stop] if stop < len(kids) else None
    if prev is not None:
        prev.nextSibling = nxt
    if nxt is not None:
        nxt.previousSibling = prev


def _detach(node) -> None:
    """Remove ``node`` from its parent (if any), keeping hints consistent."""
    parent = node.parentNode
    if parent is None:
        return
    import xacro

    if node is xacro._empty_text_node and _singleton_pos[0] is parent:
        i = _singleton_pos[1]
        kids = parent.childNodes
        if not (i < len(kids) and kids[i] is node):
            i = _index(parent, node)
    else:
        i = _index(parent, node)
    kids = parent.childNodes
    del kids[i]
    _shift_hint(parent, i, -1)
    _link(kids, i, i)
    node.parentNode = node.previousSibling = node.nextSibling = None


def replace_node(node, by, content_only=False):
    """Drop-in for xacro.xmlutils.replace_node."""
    parent = node.parentNode
    new = []
    if by is not None:
        for doc in (by if isinstance(by, list) else [by]):
            if content_only:
                kids = list(doc.childNodes)
                doc.childNodes[:] = []
                new.extend(kids)
            else:
                if doc.parentNode is not None and doc is not node:
                    _detach(doc)
                new.append(doc)
    kids = parent.childNodes
    i = _index(parent, node)
    kids[i:i + 1] = new
    for c in new:
        c.parentNode = parent
    _link(kids, i, i + len(new))
    node.parentNode = node.previousSibling = node.nextSibling = None
    _set_hint(parent, i + len(new))


def _insert_before(parent, new, ref) -> None:
    if new.parentNode is not None:
        _detach(new)
    kids = parent.childNodes
    i = _index(parent, ref)
    kids.insert(i, new)
    new.parentNode = parent
    _shift_hint(parent, i - 1, +1)
    _link(kids, i, i + 1)
    return i


def remove_previous_comments(node):
    """Drop-in for xacro.remove_previous_comments with O(1) amortized moves."""
    import xacro

    nxt = node.nextSibling
    previous = node.previousSibling
    while previous:
        if previous.nodeType == TEXT and previous.data.isspace() and previous.data.count('\n') <= 1:
            previous = previous.previousSibling  # skip a single empty text node (max 1 newline)
        if previous and previous.nodeType == COMMENT:
            comment = previous
            previous = previous.previousSibling
            _detach(comment)
        else:
            empty = xacro._empty_text_node
            if nxt and empty is not nxt:
                i = _insert_before(node.parentNode, empty, nxt)
                _singleton_pos[0], _singleton_pos[1] = node.parentNode, i
            return
