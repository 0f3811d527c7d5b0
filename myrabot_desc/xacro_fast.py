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


# Token lists of attribute/text strings: the same strings recur in every macro
# expansion, and xacro re-lexes them with regexes each time.
_tokens: dict[str, tuple] = {}
_MAX_CACHE = 200_000


def make_eval_text():
    """Drop-in for xacro.eval_text with cached lexing and a no-'$' fast path."""
    import os

    import xacro

    lexer = xacro.LEXER
    EXPR, EXT, TEXT, DDB = lexer.EXPR, lexer.EXTENSION, lexer.TEXT, lexer.DOLLAR_DOLLAR_BRACE

    def tokens(text):
        t = _tokens.get(text)
        if t is None:
            lex = xacro.QuickLexer(lexer)
            lex.lex(text)
            out = []
            while lex.peek():
                out.append(lex.next())
            t = tuple(out)
            if len(_tokens) < _MAX_CACHE:
                _tokens[text] = t
        return t

    def eval_text(text, symbols):
        if "$" not in text:
            return text
        results = []
        for kind, s in tokens(text):
            if kind == EXPR:
                expr = s[2:-1]
                try:
                    results.append(xacro.safe_eval(eval_text(expr, symbols), symbols))
                except Exception as e:
                    raise xacro.XacroException(exc=e, suffix=os.linesep + "when evaluating expression '%s'" % expr)
            elif kind == EXT:
                results.append(xacro.eval_extension("$(%s)" % eval_text(s[2:-1], symbols)))
            elif kind == TEXT:
                results.append(s)
            elif kind == DDB:
                results.append(s[1:])
        if len(results) == 1:
            return results[0]
        return "".join(map(str, results))

    return eval_text


def clone_node(node, deep, doc):
    """Drop-in for minidom._clone_node for the node kinds xacro clones (macro bodies, blocks).

    Same result as minidom's, without its per-attribute lookups and per-child
    appendChild bookkeeping; other node kinds go to minidom's own function.
    """
    from xml.dom import minidom

    t = node.nodeType
    if t == ELEMENT:
        qn = node.nodeName
        clone = minidom.Element(qn, node.namespaceURI, minidom._nssplit(qn)[0])
        clone.ownerDocument = doc
        src = node._attrs
        if src:
            attrs, attrs_ns = {}, {}
            for attr in src.values():
                aq = attr.nodeName
                prefix, local = minidom._nssplit(aq)
                a = minidom.Attr(aq, attr.namespaceURI, local, prefix)
                a.value = attr.value
                a.ownerDocument = doc
                a.ownerElement = clone
                a.specified = attr.specified
                attrs[aq] = a
                attrs_ns[(attr.namespaceURI, local)] = a
            clone._attrs, clone._attrsNS = attrs, attrs_ns
        if deep and node.childNodes:
            kids = clone.childNodes
            prev = None
            for child in node.childNodes:
                c = clone_node(child, deep, doc)
                c.parentNode = clone
                c.previousSibling = prev
                if prev is not None:
                    prev.nextSibling = c
                kids.append(c)
                prev = c
            prev.nextSibling = None
        return clone
    if t == TEXT:
        c = minidom.Text()
        c.data = node.data
        c.ownerDocument = doc
        return c
    if t == COMMENT:
        c = minidom.Comment(node.data)
        c.ownerDocument = doc
        return c
    return _orig_clone(node, deep, doc)


ELEMENT = xml.dom.Node.ELEMENT_NODE
_orig_clone = None


def install_clone():
    global _orig_clone
    from xml.dom import minidom

    if _orig_clone is None:
        _orig_clone = minidom._clone_node
    minidom._clone_node = clone_node


def uninstall_clone():
    from xml.dom import minidom

    if _orig_clone is not None:
        minidom._clone_node = _orig_clone
