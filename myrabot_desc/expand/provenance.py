"""Where each value of the expanded document was written: recorded while xacro expands.

A value written as a literal needs nothing recorded: its element's source annotation names the
element it was copied from, and the attribute is there as written. Only values that hold ``$``
get an origin, decided when xacro evaluates them:

    (kind, name, src, attr, inner)

* ``kind``  'property' (a ``<xacro:property>``), 'param' (a macro parameter given at the call),
  'default' (a macro parameter's default in ``params=``), 'arg' (a ``<xacro:arg>`` default, or the
  command line when ``src`` is None), 'expr' (computed: anything else);
* ``name``  the property, parameter or arg name (None for 'expr');
* ``src``   the index of the source element where the text is written (the build's list of
  source elements), or None when it is not in a file;
* ``attr``  the attribute of that element holding the text ('value', 'default', the parameter's
  name at a call site, 'params', or '#text' for element text);
* ``inner`` the origin of that text when it is not a literal itself (a property defined as
  ``${other}``, a parameter passed ``${prop}``), else None.

A value that is exactly ``${name}`` or ``$(arg name)`` takes the origin of that name; anything
else is 'expr', written at the element's own attribute (not recorded: the ``$`` in the source
text says so). The model turns these tuples into
source spans (model/sources.py).

Plain tuples and no imports beyond xacro's: this runs inside every build.
"""

from __future__ import annotations

import re

# the whole text is one ${name} (group 1) or one $(arg name) (group 2)
ONE = re.compile(r"\s*\$(?:\{\s*([A-Za-z_]\w*)\s*\}|\(\s*arg\s+([^\s()]+)\s*\))\s*")
SRC_ATTR = "_mdsrc"
XSRC_ATTR = "xacro:mdsrc"


def src_index(node, attr: str = SRC_ATTR) -> int | None:
    attrs = node._attrs
    a = attrs.get(attr) if attrs else None
    if a is None:
        return None
    v = a._value
    return int(v) if v.isdigit() else None


class Tracker:
    """The origins of one build's ``$`` values (see the module doc)."""

    def __init__(self, table_class, cli_args):
        self.Table = table_class
        self.origins: dict = {}          # expanded element -> {attribute or '#text': origin}
        self.args: dict = {}             # arg name -> origin of its default
        self.cli_args = set(cli_args)    # args given on the command line
        self.pending: list = []          # macro calls being expanded: [caller symbols, origins, claimed]
        self.unclaimed = [0]             # how many of them no body table has claimed yet (checked per element)

    # -------------------------------------------------------- classification
    def symbol(self, name: str, symbols):
        """The recorded origin of ``name`` as ``symbols`` sees it, or None."""
        t = symbols
        Table = self.Table
        while isinstance(t, Table):
            if dict.__contains__(t, name):
                org = t.__dict__.get("_md_org")
                return org.get(name) if org else None
            t = t.parent
        return None

    def arg(self, name: str):
        if name in self.cli_args:
            return ("arg", name, None, None, None)
        return self.args.get(name)

    def classify(self, raw: str, symbols, src, attr):
        """The origin of the text ``raw`` (holding '$'), written at ``src``/``attr``."""
        m = ONE.fullmatch(raw)
        if m is not None:
            name = m.group(1)
            org = self.symbol(name, symbols) if name is not None else self.arg(m.group(2))
            if org is not None:
                return org
        return ("expr", None, src, attr, None)

    # -------------------------------------------------------- what eval_all sees
    def attr(self, node, name: str, raw: str, symbols) -> None:
        """An attribute about to be evaluated. Only a value that is exactly one name or arg is
        recorded: any other ``$`` text is an expression, which Sources reads off the source itself."""
        m = ONE.fullmatch(raw)
        if m is None:
            return
        key = m.group(1)
        org = self.symbol(key, symbols) if key is not None else self.arg(m.group(2))
        if org is not None:
            d = self.origins.get(node)
            if d is None:
                d = self.origins[node] = {}
            d[name] = org

    def text(self, node, raw: str, symbols) -> None:
        self.attr(node, "#text", raw, symbols)

    def arg_default(self, name: str, src, default: str, symbols) -> None:
        inner = self.classify(default, symbols, src, "default") if "$" in default else None
        self.args[name] = ("arg", name, src, "default", inner)

    # -------------------------------------------------------- definitions
    def before_property(self, elt, table):
        """What grab_property is about to define (read before xacro removes the element)."""
        g = elt.getAttribute
        name = g("name")
        if not name or "$" in name:
            return None
        attr = "value" if elt.hasAttribute("value") else "default" if elt.hasAttribute("default") else None
        if attr is None:            # a block property, or remove=
            return None
        if attr == "default" and name in table:
            return None             # keeps the earlier definition
        raw = g(attr)
        src = src_index(elt, XSRC_ATTR)
        inner = self.classify(raw, table, src, attr) if "$" in raw else None
        return name, ("property", name, src, attr, inner), g("scope")

    def after_property(self, pre, table) -> None:
        name, org, scope = pre
        target = table
        if scope == "global":
            target = table.top() if hasattr(table, "top") else table
        elif scope == "parent":
            target = table.parent
            if not isinstance(target, self.Table):
                return
            import xacro

            if not isinstance(table, xacro.NameSpace):
                while isinstance(target, xacro.NameSpace):
                    target = target.parent
        if not isinstance(target, self.Table) or not dict.__contains__(target, name):
            return
        org_map = target.__dict__.get("_md_org")
        if org_map is None:
            org_map = target._md_org = {}
        org_map[name] = org

    def call(self, node, symbols) -> None:
        """A macro call about to expand: the origins of the parameters it gives, claimed by the table
        of the body's evaluation (``claim``), which adds the defaults."""
        src = src_index(node, XSRC_ATTR)
        out = {}
        attrs = node._attrs
        if attrs:
            for a in attrs.values():
                name, raw = a._name, a._value
                if name.startswith("xacro:"):
                    continue
                inner = self.classify(raw, symbols, src, name) if "$" in raw else None
                out[name] = ("param", name, src, name, inner)
        self.pending.append([symbols, out, False])
        self.unclaimed[0] += 1

    def claim(self, symbols, macro) -> None:
        """The first evaluation under a new table during a call is the body's: its parameters, and
        the defaults of those the call did not give (``macro``: xacro's, on its macro stack)."""
        top = self.pending[-1]
        if top[2] or symbols is top[0] or not isinstance(symbols, self.Table):
            return
        top[2] = True
        self.unclaimed[0] -= 1
        out, caller = top[1], top[0]
        if macro is not None:
            msrc = getattr(macro, "_md_src", None)
            for param in macro.params:
                if param in out or param[:1] == "*":
                    continue
                fwd, default = macro.defaultmap.get(param, (None, None))
                org = self.symbol(fwd, caller) if fwd is not None else None
                if org is None and default is not None:
                    inner = self.classify(default, caller, msrc, "params") if "$" in default else None
                    org = ("default", param, msrc, "params", inner)
                if org is not None:
                    out[param] = org
        org_map = symbols.__dict__.get("_md_org")
        if org_map is None:
            symbols._md_org = out
        else:
            org_map.update(out)

    def done(self) -> None:
        if not self.pending.pop()[2]:
            self.unclaimed[0] -= 1


class SourceMap:
    """What a build records of where its output came from (read by model/sources.py).

    ``index[i]``: the source element output element ``i`` (document order) was copied from, or
    None; ``origins[i]``: {attribute or '#text': origin} for its ``$`` values, or None;
    ``locs[j]``/``offsets[j]``: source element ``j``'s Loc and the byte offset of its start tag
    in its file (None where unknown); ``files``: shown name -> (path, bytes) of each file read.
    """

    __slots__ = ("index", "origins", "locs", "offsets", "files")

    def __init__(self, index, origins, locs, offsets, files):
        self.index, self.origins, self.locs, self.offsets, self.files = index, origins, locs, offsets, files
