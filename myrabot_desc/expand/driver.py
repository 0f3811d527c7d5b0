"""Build: xacro (old or new) -> URDF, without ROS, safely, with a source map.

We drive the real ROS ``xacro`` library and hook it at a few points:

* reading files: expat straight into xacro's minidom, DTDs and entities refused
  (domread.py; lxml gives the verdict on whatever expat stops at); size, include
  depth and include-cycle limits; reads only under the input's folder, the resolved
  package roots and ``--allow-path`` folders; the legacy upgrade (legacy.py);
  each element gets a ``_mdsrc`` attribute naming its file:line (xacro copies
  attributes through macro expansion, so expanded elements keep the line of the
  macro body they came from);
* ``$(find)`` -> our package resolver (packages.py); ``$(env)``/``$(optenv)``
  refused under ``--no-env``; ``$(eval)`` and ``${}`` through the allow-list
  (safe_eval.py) unless ``--unsafe-eval``;
* node replacement -> the linear-time splice of fast.py.

Start-up counts (``build`` must beat the xacro CLI on small robots): nothing
here imports lxml, click or dataclasses, and PyYAML and xacro's command-line module
are placeholders until used (_LazyModule).

After expansion the annotations are read off (document order) and removed, so
the text we write is byte-identical to the xacro CLI's for the same input.
"""

from __future__ import annotations

import _thread
import os
import re
import sys
from pathlib import Path

from myrabot_desc import xmltree
from myrabot_desc.diagnostics import Diagnostic, Loc
from myrabot_desc.errors import InputError
from myrabot_desc.expand import domread, safe_eval, yaml_load
from myrabot_desc.expand import fast as xacro_fast
from myrabot_desc.expand import legacy as lg
from myrabot_desc.expand.domread import SRC_ATTR, XSRC_ATTR
from myrabot_desc.expand.fast import pretty_xml
from myrabot_desc.expand.packages import PackageResolver, split_package_uri
from myrabot_desc.expand.provenance import SourceMap, Tracker, src_index
from myrabot_desc.safety import Limits, _short, display, may_open, read_checked, safe_parser, scan_tag_attr
from myrabot_desc.sanitize import clean, clean_lines


class BuildResult:
    """What a build gives back (a plain class: ``dataclasses`` costs ~10 ms of start-up)."""

    def __init__(self, text: str, locations: list, diagnostics: list, deps: list, source: Path,
                 package_roots: dict | None = None, src_name: str | None = None):
        self.text = text                    # the URDF document (pretty-printed, with banner)
        self.locations = locations          # Loc | None per output element, in document order
        self.diagnostics = diagnostics      # X-code warnings/errors (Diagnostic)
        self.deps = deps                    # files read (input, includes, YAML)
        self.source = source
        self.package_roots = {} if package_roots is None else package_roots
        self._src_name = src_name or str(source)
        self._root = None
        self.source_map = None              # provenance.SourceMap: where each output value was written

    @property
    def root(self):
        """The URDF's root element, parsed safely on first use (the loader reads it; ``build`` never
        does): by expat into xmltree's elements, or by lxml for what expat leaves to it (see
        xmltree.py). InputError when lxml cannot read the output (e.g. an attribute value over
        its 10 MB cap, built by ${}s)."""
        if self._root is None:
            self._root = _parse_output(self.text, self._src_name)
        return self._root

    @property
    def errors(self) -> list:
        return [d for d in self.diagnostics if d.severity == "error"]


# libxml2 (lxml without huge_tree) refuses a text or attribute value over 10,000,000 bytes
LXML_MAX_TEXT = 10_000_000


def _parse_output(text: str, src_name: str):
    data = text.encode("utf-8")
    try:
        return xmltree.parse(data)      # no lxml for the usual document (its import: ~15 ms of a check)
    except xmltree.Refused:
        pass
    from lxml import etree

    try:
        return etree.fromstring(data, parser=safe_parser())
    except etree.XMLSyntaxError as exc:
        line = exc.position[0] if exc.position else "?"
        why = re.sub(r",? line \d+, column \d+$", "", " ".join((exc.msg or str(exc)).split())).strip()
        raise InputError(f"the expanded document is not well-formed XML (line {line} of the output: "
                         f"{_short(why, 200)})", Loc(src_name)) from None


_lock = _thread.allocate_lock()   # (not threading: its import costs ~1 ms of every build's start)

# URDF (and common extension) vocabulary at <robot> level: anything else there
# is either a macro call that went unexpanded or an unknown element.
ROBOT_CHILDREN = {"link", "joint", "material", "gazebo", "transmission", "sensor", "ros2_control", "mujoco",
                  "drake", "klampt", "webots", "plugin", "version"}
XACRO_WORDS = {"macro", "property", "include", "insert_block", "arg", "if", "unless", "call", "element",
               "attribute"}


def build_file(path, mappings: dict | None = None, *, packages: dict | None = None, package_paths=(),
               legacy: str = "auto", unsafe_eval: bool = False, no_env: bool = False, allow_paths=(),
               limits: Limits | None = None, resolve_uris: bool = False, overlay: dict | None = None,
               sources: bool = True) -> BuildResult:
    """Expand ``path`` into URDF. Raises InputError for input that cannot be built. ``overlay``: resolved
    path -> bytes read instead of that file (``check --fix`` proves its edits before writing them).
    ``sources``: record where each value was written (``BuildResult.source_map``; the `build` command,
    which writes the text only, saves the ~3 % it costs)."""
    src = Path(path)
    if not src.exists():
        raise InputError(f"no such file: {src}")
    if not src.is_file():
        raise InputError(f"not a file: {src}")
    import gc

    with _lock:
        # Expansion allocates millions of small DOM objects and frees almost none; the
        # cyclic collector would rescan them over and over (a third of the time at 4,000 calls).
        gc_was_on = gc.isenabled()
        gc.disable()
        try:
            b = _Build(src, mappings or {}, packages or {}, list(package_paths), legacy, unsafe_eval, no_env,
                       list(allow_paths), limits or Limits(), resolve_uris)
            b.src_name = os.fspath(path)   # as given, like xacro's banner and location lines ("./x.xacro")
            b.overlay = overlay or {}
            b.tracking = sources
            return b.run()
        finally:
            if gc_was_on:
                gc.enable()


class _Build:
    def __init__(self, src, mappings, packages, package_paths, legacy, unsafe_eval, no_env, allow_paths,
                 limits, resolve_uris):
        if legacy not in ("auto", "on", "off"):
            raise InputError(f"--legacy must be auto, on or off, not {legacy!r}")
        self.src = src
        self.src_name = str(src)
        self.robot = True        # the input's root is <robot>: legacy upgrade (auto) and URDF findings apply
        self.messages = sys.stderr   # where the file's own xacro.message()/print_location() text goes
        self.mappings = {str(k): str(v) for k, v in mappings.items()}
        self.resolver = PackageResolver(packages, package_paths, input_file=src)
        self.legacy = legacy
        self.unsafe_eval = unsafe_eval
        self.no_env = no_env
        self.allow_roots = [src.resolve().parent] + [Path(p).expanduser().resolve() for p in allow_paths]
        self.limits = limits
        self.resolve_uris = resolve_uris
        self.locs: list[Loc] = []          # index -> Loc for _mdsrc annotations
        self.offsets: list = []            # index -> byte offset of that element's start tag (or None)
        self.file_data: dict[str, tuple] = {}   # shown name -> (path, bytes) of each model file read
        self.track = None                  # provenance.Tracker while xacro expands
        self.source_map = None             # SourceMap, after render
        self.overlay: dict = {}            # resolved path -> bytes to read instead of the file
        self.tracking = True               # record the source map (provenance.py)
        self.last_loc: Loc | None = None
        self.call_stack: list[tuple[str, Loc | None]] = []
        self.diagnostics: list[Diagnostic] = []
        self.macro_names: set[str] = set()
        # the macros a bare element can call: not those of a file included with ns= (xacro, old
        # and new, resolves a bare or prefixed name in the caller's scope; ns.name is the only way in)
        self.bare_macros: set[str] = set()
        self.upgraded: dict[str, tuple] = {}   # mdsrc index of an upgraded element -> (kind, tag, file)
        self.upgrade_used: set[str] = set()    # ... of those xacro evaluated (not in a branch not taken)
        self.macro_files: dict[str, str] = {}
        # resolved path -> [bytes, domread.Parsed not yet handed to xacro (or None), name shown]
        self.trees: dict[Path, list] = {}
        self._real_roots: dict[Path, Path] = {}
        self._keys: dict[Path, Path] = {}
        self.deps: list[str] = []
        self.body_sizes: dict[int, int] = {}   # macro body -> elements it holds
        self.expanded = 0                      # elements produced by macro calls so far
        self.calls = 0
        self.env_used: dict[str, tuple[str, bool]] = {}   # $(env)/$(optenv) name -> (value, was set)
        self.includes = 0                      # includes processed (the input counts as one)

    # ------------------------------------------------------------ reading files
    def allowed(self, path: Path) -> bool:
        real = path.resolve()
        if any(real.is_relative_to(r) for r in self.allow_roots):
            return True
        resolved = self._real_roots     # a package root's real path, resolved once per build
        for p in self.resolver.roots():
            r = resolved.get(p)
            if r is None:
                r = resolved[p] = p.resolve()
            if real.is_relative_to(r):
                return True
        return False

    def key(self, path: Path) -> Path:
        """A file's resolved path, as the key of the parse cache and of the include-cycle check
        (resolved once per build; allowed() resolves afresh each time it is asked)."""
        k = self._keys.get(path)
        if k is None:
            k = self._keys[path] = path.resolve()
        return k

    def read_parsed(self, path: Path, asked_at: Loc | None = None):
        """One file parsed safely (domread.Parsed, its elements annotated); cached per resolved path."""
        key = self.key(path)
        entry = self.trees.get(key)
        if entry is None:
            data = self._read_bytes(path, asked_at)
            fname = display(path)
            entry = self.trees[key] = [data, domread.parse(data, fname, self.locs, self.offsets if self.tracking
                                                           else None), fname]
            self.file_data.setdefault(fname, (key, data))
        elif entry[1] is None:       # handed to xacro already (which changes it): parse again
            entry[1] = domread.parse(entry[0], entry[2], self.locs, self.offsets if self.tracking else None)
        return entry[1]

    def read_tree(self, path: Path, asked_at: Loc | None = None):
        """The root element of one file (see read_parsed)."""
        return self.read_parsed(path, asked_at).doc.documentElement

    def take_parsed(self, path: Path, asked_at: Loc | None):
        """One file for xacro, which changes it: a fresh parse each time (the prescan's own
        parse is used once)."""
        parsed = self.read_parsed(path, asked_at)
        self.trees[self.key(path)][1] = None
        return parsed

    def _read_bytes(self, path: Path, asked_at: Loc | None) -> bytes:
        if self.overlay:
            data = self.overlay.get(self.key(path))
            if data is not None:
                return data

        try:
            size = path.stat().st_size
        except OSError as exc:
            raise InputError(f"cannot read {path}: {exc.strerror}", asked_at) from None
        if size > self.limits.max_input_bytes:
            raise InputError(f"{path} is {size} bytes, over the {self.limits.max_input_bytes}-byte limit "
                             "(see --max-input-bytes or MYRABOT_DESC_MAX_INPUT_BYTES)", asked_at)
        try:    # a regular file only (a FIFO would block), read no further than the limit
            return read_checked(path, None, self.limits.max_input_bytes)
        except InputError as exc:
            raise InputError(exc.message, asked_at or exc.loc, code=exc.code) from None

    # ------------------------------------------------------------ prescan
    def prescan(self, path: Path, seen: set, depth: int = 0, in_ns: bool = False) -> None:
        """Collect macro names over the include tree (needed to spot bare calls); ``in_ns``: the
        file is reached through an include with ``ns=``."""
        key = (self.key(path), in_ns)
        if key in seen or depth > self.limits.max_include_depth:
            return
        seen.add(key)
        try:
            parsed = self.read_parsed(path)
        except InputError:
            return  # reported properly when xacro reaches the include

        root = parsed.doc.documentElement
        for name in lg.macro_names(root, parsed.noted):
            self.macro_names.add(name)
            if not in_ns:
                self.bare_macros.add(name)
            self.macro_files.setdefault(name, display(path))
        for spec, ns in lg.includes(root, parsed.noted):
            target = self._guess_include(spec, path)
            if target is not None:
                self.prescan(target, seen, depth + 1, in_ns or ns)

    def _guess_include(self, spec: str, including: Path) -> Path | None:
        def find(m):
            p = self.resolver.find(m.group(1))
            return str(p) if p else m.group(0)

        s = re.sub(r"\$\(find\s+([^)\s]+)\)", find, spec)
        s = re.sub(r"\$\(dirname\)", str(including.parent), s)
        if "$" in s or any(ch in s for ch in "*?["):
            return None
        try:
            p = Path(s)
            if not p.is_absolute():
                p = including.parent / p
                if not p.exists() and self.legacy == "on":
                    p = self.src.parent / s
            return p if p.is_file() and self.allowed(p) else None
        except (OSError, ValueError):   # a name too long for the file system: xacro reports it
            return None

    # ------------------------------------------------------------ annotate + hand to minidom
    def load_dom(self, path: Path, asked_at: Loc | None):
        """The file's document for xacro, its elements annotated with their source lines (by
        domread while parsing), legacy syntax upgraded when that is asked for."""

        parsed = self.take_parsed(path, asked_at)
        doc = parsed.doc
        if (self.legacy == "on" or self.legacy == "auto" and self.robot) and \
                (any(lg.is_legacy_tag(el) for el in parsed.plain_words) or parsed.plain_tags & self.bare_macros):
            self._upgrade(doc.documentElement, path)
        return doc

    def _upgrade(self, root, path: Path) -> None:
        els = lg.elements(root)
        locs = self.locs
        line_of = {el: locs[int(el.getAttribute(SRC_ATTR))].line for el in els if el.hasAttribute(SRC_ATTR)}
        upgraded: list = []
        lg.upgrade(root, self.bare_macros, line_of, els, upgraded)
        shown = display(path)
        for el, kind in upgraded:       # reported once xacro has evaluated them (_report_upgrades)
            if el.hasAttribute(SRC_ATTR):
                self.upgraded[el.getAttribute(SRC_ATTR)] = (kind, el.tagName[6:], shown)
        # the renamed elements are xacro's now: their annotation moves to xacro:mdsrc, which
        # xacro's attribute checks ignore
        uri = lg.xacro_uri(root)
        for el in els:
            if el.namespaceURI == uri and el.hasAttribute(SRC_ATTR):
                value = el.getAttribute(SRC_ATTR)
                el.removeAttribute(SRC_ATTR)
                el.setAttributeNS(uri, XSRC_ATTR, value)

    def _report_upgrades(self) -> None:
        """X001 once per construct and file, for the upgraded elements xacro evaluated: one in an
        xacro:if branch not taken (or a macro never called) changed nothing, so is not reported."""
        found: dict[tuple[str, str], list] = {}
        for index, (kind, tag, shown) in self.upgraded.items():
            if index not in self.upgrade_used:
                continue
            entry = found.setdefault((shown, kind), [0, self.locs[int(index)].line or 0, []])
            entry[0] += 1
            entry[1] = min(entry[1], self.locs[int(index)].line or 0)
            if kind == "bare macro call" and tag not in entry[2]:
                entry[2].append(tag)
        order = {shown: i for i, shown in enumerate(dict.fromkeys(v[2] for v in self.upgraded.values()))}
        for (shown, kind), (count, line, names) in sorted(found.items(), key=lambda kv: (order[kv[0][0]], kv[0][1])):
            new = "xacro:" + kind.strip("<>") if kind.startswith("<") else "xacro:NAME"
            if names:
                kind += " (" + ", ".join(f"<{n}>" for n in names[:4]) + (", ..." if len(names) > 4 else "") + ")"
            times = f" ({count} times)" if count > 1 else ""
            self.diagnostics.append(Diagnostic(
                "X001", "warning", f"legacy {kind} upgraded to <{new}>{times}; xacro 2.x would copy it "
                "into the URDF unexpanded", Loc(shown, line)))

    # ------------------------------------------------------------ run
    def run(self) -> BuildResult:
        _lazy_yaml()
        _lazy_xacro_cli()
        import xacro

        if "cli" not in vars(xacro):        # its placeholder: reachable as xacro.cli, like the module
            xacro.cli = sys.modules["xacro.cli"]

        self.prescan(self.src, set())
        # Any XML expands, as with xacro (SDF, SRDF, launch files...). Electric-era syntax and the
        # URDF findings (X002, X003) belong to robots: elsewhere <arg>/<include> are roslaunch's.
        top = self.read_tree(self.src)
        self.robot = top.tagName == "robot" and top.namespaceURI is None
        self.messages = sys.stderr
        with _Hooks(self):
            xacro.init_stacks(self.src_name)
            xacro.all_includes = []
            self.check_include(self.src, None)
            doc = self.load_dom(self.src, None)
            import io

            chatter = io.StringIO()  # xacro prints its own warnings; we report them as X008
            try:
                saved = sys.stdout, sys.stderr
                sys.stdout = sys.stderr = chatter
                try:
                    xacro.process_doc(doc, mappings=dict(self.mappings), verbosity=1)
                finally:
                    sys.stdout, sys.stderr = saved
            except InputError:
                raise
            except xacro.XacroException as exc:
                raise self._xacro_error(exc) from None
            except RecursionError:
                raise InputError("macros nest too deeply (Python recursion limit); is a macro calling itself?",
                                 self.last_loc, self._stack()) from None
            except RuntimeError as exc:  # xmlutils.reqd_attrs raises RuntimeError for a missing attribute
                raise InputError(str(exc), self.last_loc, self._stack()) from None
            except OSError as exc:  # a 5000-character include name (ENAMETOOLONG), a folder...
                name = _short(str(exc.filename or ""), 120)
                raise InputError(f"cannot read {name}: {exc.strerror or exc}", self.last_loc, self._stack()) from None
            except (NameError, TypeError, ValueError, LookupError, AttributeError, ArithmeticError) as exc:
                raise InputError(f"{type(exc).__name__}: {exc}", self.last_loc, self._stack()) from None
            self.deps = [str(self.src)] + [d for d in dict.fromkeys(xacro.all_includes)]
        self._report_upgrades()
        self._xacro_warnings(chatter.getvalue())
        if self.env_used:
            self.diagnostics.append(Diagnostic(
                "X007", "info", f"the build depends on the environment: {_env_summary(self.env_used)}; pin them as "
                "xacro args or in the CI job", Loc(display(self.src)),
                {"environment": _shown_env(self.env_used)}))
        text, locations = self.render(doc)
        self.check_unexpanded(doc, locations)
        result = BuildResult(text=text, locations=locations, diagnostics=self.diagnostics, deps=self.deps,
                             source=self.src, package_roots=dict(self.resolver.used), src_name=display(self.src))
        result.source_map = self.source_map
        if len(text) > LXML_MAX_TEXT:   # only such a document can hold a value past lxml's cap: refuse it here
            result.root                 # (what check/convert would refuse) rather than write it
        return result

    def _xacro_warnings(self, text: str) -> None:
        counts: dict[str, int] = {}
        for line in text.splitlines():
            line = line.strip()
            if line.lower().startswith("warning:"):
                msg = line.split(":", 1)[1].strip()
                counts[msg] = counts.get(msg, 0) + 1
        for msg, n in counts.items():
            times = f" ({n} times)" if n > 1 else ""
            self.diagnostics.append(Diagnostic("X008", "warning", f"xacro: {msg}{times}", Loc(display(self.src))))

    def check_include(self, path: Path, asked_at: Loc | None) -> None:
        import xacro

        if not self.allowed(path):
            raise InputError(f"refusing to read {path}: outside the input's folder and the package roots "
                             "(use --allow-path DIR to allow it)", asked_at or self.last_loc, code="X006")
        stack = [self.key(Path(f)) for f in (xacro.filestack or [])[:-1] if f]
        if self.key(path) in stack:
            chain = " -> ".join(str(p) for p in stack + [path])
            raise InputError(f"include cycle: {chain}", asked_at or self.last_loc)
        self.includes += 1
        if self.includes > self.limits.max_includes:
            raise InputError(f"over {self.limits.max_includes} includes in one build (repeats counted); is a "
                             "file included over and over? (see --max-includes or MYRABOT_DESC_MAX_INCLUDES)",
                             asked_at or self.last_loc)
        if len(xacro.filestack or []) > self.limits.max_include_depth:
            raise InputError(f"includes nest deeper than {self.limits.max_include_depth} "
                             "(see --max-include-depth or MYRABOT_DESC_MAX_INCLUDE_DEPTH)", asked_at or self.last_loc)

    def count_expansion(self, name, macros, symbols, loc) -> None:
        """Add the elements a macro call will produce; stop before a call bomb runs for hours
        (each macro calling the previous one twice doubles the output per level)."""
        import xacro

        try:
            m = xacro.resolve_macro(name, macros, symbols)[2]
        except Exception:  # unknown macro: xacro reports it
            return
        size = self.body_sizes.get(id(m.body))
        if size is None:
            size = self.body_sizes[id(m.body)] = len(m.body.getElementsByTagName("*")) + 1
        self.expanded += size
        self.calls += 1
        if self.calls > self.limits.max_macro_calls:
            raise InputError(f"over {self.limits.max_macro_calls} macro calls (macro '{name}'); is a macro "
                             "calling others in a loop? (see --max-macro-calls or MYRABOT_DESC_MAX_MACRO_CALLS)",
                             loc or self.last_loc, self._stack())
        if self.expanded > self.limits.max_output_elements:
            raise InputError(f"macro expansion produces over {self.limits.max_output_elements} elements "
                             f"(macro '{name}'); is a macro calling others in a loop? "
                             "(see --max-elements or MYRABOT_DESC_MAX_ELEMENTS)", loc or self.last_loc, self._stack())

    def _stack(self) -> list[str]:
        out = []
        for name, loc in reversed(self.call_stack[-8:]):
            out.append(f"in macro '{name}' called at {loc}" if loc else f"in macro '{name}'")
        if len(self.call_stack) > 8:
            out.append(f"... {len(self.call_stack) - 8} more macro calls")
        return out

    def _xacro_error(self, exc) -> InputError:
        msg = str(exc).strip()
        inner = getattr(exc, "exc", None)
        for _ in range(50):  # xacro wraps once per lazy property level ("when evaluating expression ...")
            if isinstance(inner, InputError):
                return inner
            inner = getattr(inner, "exc", None)
            if inner is None:
                break
        msg = _short(msg.replace("\n", " ").replace("  ", " "), 600)
        return InputError(msg, self.last_loc, self._stack())

    # ------------------------------------------------------------ after expansion
    def render(self, doc) -> tuple[str, list]:
        """The URDF text as xacro writes it, and the source Loc (or None) of each element in document order.

        The annotations are read off and left out while writing (xacro_fast.pretty_xml)."""
        import xml.dom.minidom

        banner = [xml.dom.minidom.Comment(c) for c in [
            " %s " % ("=" * 83),
            " |    This document was autogenerated by xacro from %-30s | " % re.sub(r"-+", "-", self.src_name),
            " |    EDITING THIS FILE BY HAND IS NOT RECOMMENDED  %-30s | " % "",
            " %s " % ("=" * 83)]]
        first = doc.firstChild
        for comment in banner:
            doc.insertBefore(comment, first)
        marks: list = []
        origins: list | None = [] if self.track is not None else None
        text = pretty_xml(doc, skip_attr=SRC_ATTR, skip_suffix=":mdsrc", marks=marks, origins=origins,
                          recorded=self.track.origins if self.track is not None else None)
        if len(marks) > self.limits.max_output_elements:
            raise InputError(f"the expanded URDF has over {self.limits.max_output_elements} elements")
        n = len(self.locs)
        index = [int(m) if m and m.isdigit() and int(m) < n else None for m in marks]
        locs = self.locs
        locations = [None if i is None else locs[i] for i in index]
        if self.tracking:
            self.source_map = SourceMap(index, origins, self.locs, self.offsets, self.file_data)
        return text, locations

    def check_unexpanded(self, doc, locations: list) -> None:
        """X002: leftover macro calls / xacro keywords; X003: macro-only file (both for <robot>
        only: in other XML a plain <foo> or <include> is just that); X004: bad package://.

        Read off the expanded document, element by element as the output lists them (the
        ``locations``); "plain" means what a parser of the output sees: no prefix and no
        default namespace in scope."""
        root = doc.documentElement
        walk = []      # (element, plain, parent is root, inside a plain <gazebo>), document order
        stack = [(root, root.getAttribute("xmlns") != "", False, False)]
        while stack:
            el, in_ns, top, in_gazebo = stack.pop()
            plain = not in_ns and ":" not in el.tagName
            walk.append((el, plain, top, in_gazebo))
            kids = []
            for c in el.childNodes:
                if c.nodeType == c.ELEMENT_NODE:
                    ns = c.getAttribute("xmlns") != "" if c.hasAttribute("xmlns") else in_ns
                    kids.append((c, ns, el is root, in_gazebo or (plain and el.tagName == "gazebo")))
            kids.reverse()
            stack.extend(kids)
        loc_of = dict(zip((w[0] for w in walk), locations))
        found_links = False
        for el, plain, top, in_gazebo in walk if self.robot else ():
            tag = el.tagName
            if plain and top and tag in ("link", "joint"):
                found_links = True
            if not plain:
                continue
            loc = loc_of.get(el)
            if tag in XACRO_WORDS and (el.getAttribute("name") or el.getAttribute("filename") or
                                       el.getAttribute("value")) and not in_gazebo:
                self.diagnostics.append(Diagnostic(
                    "X002", "error", f"<{tag}> was not expanded: xacro keywords need the xacro: prefix "
                    "(run with --legacy auto, the default)", loc))
            elif top and tag not in ROBOT_CHILDREN:
                where = self.macro_files.get(tag) or _defined_nearby(tag, self.src, self.resolver.roots())
                if where:
                    self.diagnostics.append(Diagnostic(
                        "X002", "error", f"<{tag}> looks like a call of macro '{tag}' (defined in {where}), "
                        "but it was not expanded: the file defining it is not included, so everything it "
                        "would add is missing", loc, {"macro": tag, "defined_in": where}))
                elif el.hasAttribute("parent") or any(c.nodeType == c.ELEMENT_NODE and c.tagName == "origin"
                                                      for c in el.childNodes):
                    self.diagnostics.append(Diagnostic(
                        "X002", "error", f"<{tag}> looks like a macro call (it has parent=/an <origin> block) "
                        "but no macro of that name is defined or included; it was left unexpanded", loc,
                        {"macro": tag}))
        if self.robot and not found_links and self.macro_names:
            names = sorted(self.macro_names)
            shown = ", ".join(names[:5]) + (", ..." if len(names) > 5 else "")
            self.diagnostics.append(Diagnostic(
                "X003", "warning", f"this file defines {len(names)} macro(s) ({shown}) and instantiates none: "
                "the URDF has no links", Loc(display(self.src), 1)))

        seen = set()
        for el, *_ in walk:
            uri = el.getAttribute("filename")
            if not uri or not uri.startswith("package://"):
                continue
            parts = split_package_uri(uri)
            if parts and parts[0] not in seen and self.resolver.find(parts[0]) is None:
                seen.add(parts[0])
                self.diagnostics.append(Diagnostic(
                    "X004", "warning", f"package '{parts[0]}' of {uri} cannot be found (give -p "
                    f"{parts[0]}=PATH or --package-path)", loc_of.get(el)))




MAX_NEARBY_FILES = 500
MAX_NEARBY_BYTES = 2_000_000


def _defined_nearby(name: str, src: Path, roots) -> str | None:
    """A .xacro file next to the input (or in a resolved package) that defines macro ``name``.
    Regular files inside each folder only (no FIFO, no symlink out), a linear scan of each."""

    folders = [src.parent] + [Path(r) for r in roots]
    seen: set = set()
    for folder in folders:
        if not folder.is_dir():
            continue
        top = [folder.resolve()]
        for f in sorted(folder.rglob("*.xacro")):
            if f in seen or len(seen) > MAX_NEARBY_FILES:
                continue
            seen.add(f)
            if not may_open(f, top):
                continue
            try:
                text = read_checked(f, None, MAX_NEARBY_BYTES).decode("utf-8", errors="replace")
            except InputError:
                continue
            if name in text and name in scan_tag_attr(text, "macro", "name"):
                return str(f)
    return None


SHOW_ENV = "MYRABOT_DESC_SHOW_ENV_VALUES"


def _shown_env(env_used: dict) -> dict:
    """name -> what X007 may show: the file's default when the variable was unset (model text),
    None when it was set (its value is the runner's: a model must not be able to print a CI secret
    into a report or a log), unless MYRABOT_DESC_SHOW_ENV_VALUES=1."""
    show = os.environ.get(SHOW_ENV, "") not in ("", "0")
    return {k: (v if show or not was_set else None) for k, (v, was_set) in sorted(env_used.items())}


def _env_summary(env_used: dict, most: int = 8) -> str:
    """The variables a build read, for X007's one line: each by name (set) or with the default it
    fell back to; a base like Husky's reads ~90 ``$(optenv)``, so then the set ones and the unset
    ones by name, at most ``most`` of each (the JSON data has them all)."""
    shown = _shown_env(env_used)
    items = sorted(env_used.items())

    def one(k, was_set):
        v = shown[k]
        if was_set:
            return f"{k}={v!r}" if v is not None else f"{k} (set)"
        return f"{k}={v!r} (unset: default)"

    if len(items) <= most:
        return ", ".join(one(k, was_set) for k, (_v, was_set) in items)

    def some(names):
        more = len(names) - most
        return ", ".join(names[:most]) + (f", and {more} more" if more > 0 else "")

    set_ = [f"{k}={shown[k]!r}" if shown[k] is not None else k for k, (_v, was_set) in items if was_set]
    unset = [k for k, (_v, was_set) in items if not was_set]
    if not unset:
        told = f"all set ({some(set_)})"
    elif not set_:
        told = f"all unset, defaults used ({some(unset)})"
    else:
        told = f"{len(set_)} set ({some(set_)}) and {len(unset)} unset, defaults used ({some(unset)})"
    return f"{len(items)} variables, {told} (check --format json lists every one)"


class _LazyModule(type(sys)):
    """A placeholder for a module, imported on first use of any of its names.

    (Not importlib.util.LazyLoader: on Python 3.11 the ``import`` statement itself reads the
    module's ``__spec__``, which makes LazyLoader load it there and then.)"""

    def __getattr__(self, name):
        if name == "__path__" and not self.__dict__.get("is_package", True):
            raise AttributeError(name)      # the import system asks it of any module ``from`` imports
        if sys.modules.get(self.__name__) is self:
            del sys.modules[self.__name__]
        real = _real_module(self.__name__)
        self.__dict__.update(real.__dict__)     # later look-ups find the names directly
        return getattr(real, name)


def _real_module(name: str):
    import importlib

    if name != "yaml" or "yaml" in sys.modules:
        return importlib.import_module(name)
    import re

    compile_ = re.compile

    def compile_deferred(pattern, flags=0):    # only while PyYAML's modules run, see below
        if pattern == _PYYAML_NON_PRINTABLE:
            return _DeferredPattern(compile_, pattern, flags)
        return compile_(pattern, flags)

    re.compile = compile_deferred
    try:
        return importlib.import_module(name)
    finally:
        re.compile = compile_


# PyYAML's pure-Python reader compiles this character class when imported (~5 ms, a third of
# PyYAML's import and a tenth of a small robot's build). We read YAML through libyaml, which makes
# the same check itself, so the pattern is only needed if the pure-Python reader runs (it words
# our error messages): it is compiled then. If PyYAML changes the pattern, it is compiled as before.
_PYYAML_NON_PRINTABLE = "[^\x09\x0A\x0D\x20-\x7E\x85\xA0-\uD7FF\uE000-\uFFFD\U00010000-\U0010ffff]"


class _DeferredPattern:
    """A compiled regular expression that is compiled on first use."""

    def __init__(self, compile_, pattern, flags):
        self._compile = (compile_, pattern, flags)

    def __getattr__(self, name):       # first use: compile, and keep the real methods from now on
        compile_, pattern, flags = self._compile
        real = compile_(pattern, flags)
        for attr in ("search", "match", "fullmatch", "sub", "subn", "split", "findall", "finditer"):
            setattr(self, attr, getattr(real, attr))
        self.pattern, self.flags = pattern, real.flags
        return getattr(real, name)


def _lazy_xacro_cli() -> None:
    """xacro imports its command-line module (optparse, textwrap, gettext: ~3 ms) for the
    ``process_args`` of its own main(): a placeholder until anything else of it is used."""
    if "xacro" in sys.modules or "xacro.cli" in sys.modules:
        return
    stub = _LazyModule("xacro.cli")
    stub.is_package = False

    def process_args(*args, **kwargs):
        if sys.modules.get("xacro.cli") is stub:
            del sys.modules["xacro.cli"]
        return _real_module("xacro.cli").process_args(*args, **kwargs)

    stub.process_args = process_args
    sys.modules["xacro.cli"] = stub


def load_engine() -> None:
    """Import xacro as a build does (lazy PyYAML and command-line module), before building: a
    caller that forks to build twice (``diff``) imports it once instead of in both processes."""
    _lazy_yaml()
    _lazy_xacro_cli()
    import xacro  # noqa: F401
    import xacro.substitution_args  # noqa: F401


def _lazy_yaml() -> None:
    """Put a lazy PyYAML in sys.modules before xacro imports it (xacro.substitution_args imports
    it at module top, ~15 ms): it loads on first use, which for a build is our own YAML loader
    (yaml_load.py) when a file calls load_yaml; most robots never do."""
    if "yaml" not in sys.modules and "xacro" not in sys.modules:
        sys.modules["yaml"] = _LazyModule("yaml")


def _message_functions(print_location) -> dict:
    """xacro's message functions of its ``xacro`` namespace (before its wrapper adds the location)."""
    from xacro import color

    return {"message": color.message, "warning": color.warning, "error": color.error,
            "print_location": print_location}


def _to_stream(f, name: str, build: _Build, print_location):
    """``${xacro.message(...)}`` & co. as in xacro (same text, location lines after warning and
    error), written where the build's caller reads its errors: the file author's own output, not
    xacro's chatter (which becomes X008)."""
    def wrapper(*args, **kwargs):
        import contextlib
        import io

        location = kwargs.pop("print_location", name in ("warning", "error"))
        kwargs.pop("file", None)
        buf = io.StringIO()
        with contextlib.redirect_stderr(buf):   # color.message reads sys.stderr when called
            f(*(clean(a) for a in args), **kwargs)      # one message, one line
            if location:
                print_location()
        # the file's own text (and YAML values it prints): no terminal escapes, no CI commands
        build.messages.write(clean_lines(buf.getvalue()))
        return ""
    return wrapper


def _install_messages(build: _Build, print_location) -> dict:
    """Route the file's ``xacro.message``/``warning``/``error``/``print_location`` calls to the
    build's stream (in the symbol table in use now); returns what to put back."""
    import xacro

    ns = xacro._global_symbols.get("xacro")
    saved = {}
    if ns is not None:
        for name, f in _message_functions(print_location).items():
            if name in ns:
                saved[name] = (ns, ns[name])
                dict.__setitem__(ns, name, _to_stream(f, name, build, print_location))
    return saved


def _restore_messages(saved: dict) -> None:
    for name, (ns, f) in saved.items():
        dict.__setitem__(ns, name, f)


class _Hooks:
    """Install our hooks into the xacro module for one build; restore them after."""

    def __init__(self, build: _Build):
        self.b = build

    def __enter__(self):
        import xacro.substitution_args as sa

        import xacro

        b = self.b
        self.saved = {
            (xacro, "parse"): xacro.parse, (xacro, "eval_all"): xacro.eval_all,
            (xacro, "handle_macro_call"): xacro.handle_macro_call, (xacro, "check_attrs"): xacro.check_attrs,
            (xacro, "grab_macro"): xacro.grab_macro, (xacro, "grab_property"): xacro.grab_property,
            (xacro, "replace_node"): xacro.replace_node,
            (xacro, "remove_previous_comments"): xacro.remove_previous_comments,
            (xacro, "safe_eval"): xacro.safe_eval, (xacro, "eval_text"): xacro.eval_text,
            (xacro, "print_location"): xacro.print_location,
            (sa, "_eval_find"): sa._eval_find,
            (sa, "_eval_env"): sa._eval_env, (sa, "_eval_optenv"): sa._eval_optenv, (sa, "_eval"): sa._eval,
        }
        self.saved_dict = dict(sa._eval_dict)
        self.saved_recursion = sys.getrecursionlimit()
        sys.setrecursionlimit(max(self.saved_recursion, b.limits.max_macro_depth * 12 + 2000))
        xacro_fast.reset()
        track = b.track = xacro_fast._track[0] = Tracker(xacro.Table, b.mappings) if b.tracking else None
        unclaimed = track.unclaimed if track is not None else [0]

        orig_eval_all = xacro_fast.eval_all   # xacro's eval_all, statement for statement, faster
        orig_macro = xacro.handle_macro_call
        orig_check_attrs = xacro.check_attrs
        orig_grab_macro = xacro.grab_macro
        orig_grab_property = xacro.grab_property

        def loc_of(node, attr):
            if node.nodeType != node.ELEMENT_NODE or not node.hasAttribute(attr):
                return None
            v = node.getAttribute(attr)
            return b.locs[int(v)] if v.isdigit() and int(v) < len(b.locs) else None

        upgraded, upgrade_used = b.upgraded, b.upgrade_used

        def take_xloc(node):
            loc = loc_of(node, XSRC_ATTR)
            if node.nodeType == node.ELEMENT_NODE and node.hasAttribute(XSRC_ATTR):
                if upgraded:
                    v = node.getAttribute(XSRC_ATTR)
                    if v in upgraded:
                        upgrade_used.add(v)     # xacro evaluates an element the upgrade renamed
                node.removeAttribute(XSRC_ATTR)
            if loc:
                b.last_loc = loc
            return loc

        locs = b.locs

        def eval_all(node, macros, symbols):
            attrs = getattr(node, "_attrs", None)
            a = attrs.get(SRC_ATTR) if attrs else None
            if a is not None:
                v = a._value
                if v.isdigit() and int(v) < len(locs):
                    b.last_loc = locs[int(v)]
            if unclaimed[0]:
                track.claim(symbols, xacro.macrostack[-1] if xacro.macrostack else None)
            orig_eval_all(node, macros, symbols)

        def handle_macro_call(node, macros, symbols):
            if not node.tagName.startswith("xacro:"):
                return False
            dynamic = node.tagName == "xacro:call"     # xacro renames it and comes back here
            if not dynamic and track is not None:
                track.call(node, symbols)
            loc = take_xloc(node)
            name = node.tagName[6:]
            if len(b.call_stack) >= b.limits.max_macro_depth:
                raise InputError(f"macro calls nest deeper than {b.limits.max_macro_depth} (macro '{name}'); "
                                 "is a macro calling itself? (see --max-macro-depth or MYRABOT_DESC_MAX_MACRO_DEPTH)",
                                 loc or b.last_loc, b._stack())
            b.count_expansion(name, macros, symbols, loc)
            b.call_stack.append((name, loc))
            try:
                result = orig_macro(node, macros, symbols)
            finally:
                if not dynamic and track is not None:
                    track.done()
            b.call_stack.pop()
            return result

        def check_attrs(tag, required, optional):
            take_xloc(tag)
            return orig_check_attrs(tag, required, optional)

        def grab_macro(elt, macros):
            src = src_index(elt, XSRC_ATTR)
            name = elt.getAttribute("name")
            take_xloc(elt)
            orig_grab_macro(elt, macros)
            macro = dict.get(macros, name[6:] if name.startswith("xacro:") else name)
            if macro is not None:
                macro._md_src = src

        def grab_property(elt, table):
            pre = track.before_property(elt, table) if track is not None else None
            take_xloc(elt)
            orig_grab_property(elt, table)
            if pre is not None:
                track.after_property(pre, table)

        def parse(inp, filename=None):
            if inp is not None:
                return self.saved[(xacro, "parse")](inp, filename)
            asked = b.last_loc
            uri = str(filename)[str(filename).find("package://"):] if "package://" in str(filename) else None
            if uri and not Path(filename).is_file():
                # xacro (ROS 1 and 2) includes paths, not URIs (it joins this one to the including
                # file's folder): a common slip from mesh filenames

                pkg, rest = split_package_uri(uri) or ("PKG", "")
                xacro.filestack.pop()
                raise InputError(f"include of {uri}: xacro includes files by path and does not resolve "
                                 f"package:// URIs; write $(find {pkg})/{rest}", asked, b._stack())
            path = Path(filename)
            if not path.is_absolute():
                path = Path(xacro.root_dir) / path
            if not path.is_file() and b.legacy == "on" and not Path(filename).is_absolute():
                alt = b.src.parent / Path(filename).name
                if alt.is_file():
                    path = alt
            if not b.allowed(path):       # outside the roots: refused whether or not it exists
                b.check_include(path, asked)
            if not path.is_file():
                xacro.filestack.pop()
                err = FileNotFoundError(2, "No such file or directory", str(path))
                raise xacro.XacroException(f"include not found: {path}", exc=err)
            b.check_include(path, asked)
            return b.load_dom(path, asked)

        def eval_find(pkg):
            path = b.resolver.find(pkg)
            if path is None:
                raise InputError(f"unknown package '{pkg}' in $(find {pkg}) (give -p {pkg}=PATH or "
                                 "--package-path DIR)", b.last_loc, b._stack())
            return str(path)

        def refuse_env(name, *args, **kwargs):
            raise InputError(f"$(env {name}) / $(optenv {name}) is refused by --no-env", b.last_loc, b._stack())

        def refuse(expr, reason):
            raise InputError(f"refused expression ${{{_short(expr.strip())}}}: {reason} (--unsafe-eval allows it for "
                             "trusted files)", b.last_loc, b._stack(), code="X005")

        def subst_eval(s, context):
            if "arg" not in context:
                context["arg"] = {}
            functions = {"arg": lambda name: sa.convert_value(sa._eval_arg(name, args=context["arg"]), "auto"),
                         "dirname": lambda: sa._eval_dirname(context["filename"])}
            functions.update(sa._eval_dict)
            if not b.unsafe_eval:
                try:
                    tree = safe_eval.check_subst_eval(s, set(functions))
                    value = safe_eval.eval_bounded(s, tree, sa._DictWrapper(context["arg"], functions))
                except safe_eval.RefusedExpression as exc:
                    raise InputError(f"refused expression $(eval {_short(s.strip())}): {exc}", b.last_loc,
                                     b._stack(), code="X005") from None
                return str(value)
            return str(eval(s, {"__builtins__": {}}, sa._DictWrapper(context["arg"], functions)))

        def load_yaml(filename):
            """xacro's load_yaml through our YAML loader and path check (xacro's own registers
            unsandboxed tag constructors on PyYAML's shared SafeLoader)."""

            spec = xacro.abs_filename_spec(filename)
            p = Path(spec)
            try:
                data = read_checked(p, b.allow_roots + b.resolver.roots(), b.limits.max_input_bytes, "YAML file")
                value = yaml_load.loads(data.decode("utf-8", errors="replace"), display(p))
            except InputError as exc:
                line = f":{exc.loc.line}" if exc.loc and exc.loc.line and exc.loc.file == display(p) else ""
                msg = exc.message if exc.message.startswith(("refusing", "no such", "cannot read")) else \
                    f"{p.name}{line}: {exc.message}"
                raise InputError(msg, b.last_loc, b._stack(), code=exc.code) from None
            xacro.all_includes.append(spec)
            return xacro.YamlListWrapper.wrap(value)

        self.saved_globals = xacro._global_symbols
        xacro._global_symbols = safe_eval.fresh_namespace(load_yaml)   # nothing a build does reaches the next
        xacro.parse = parse
        xacro.eval_all = eval_all
        xacro.handle_macro_call = handle_macro_call
        xacro.check_attrs = check_attrs
        xacro.grab_macro = grab_macro
        xacro.grab_property = grab_property
        xacro.replace_node = xacro_fast.replace_node
        xacro.remove_previous_comments = xacro_fast.remove_previous_comments
        xacro.eval_text = xacro_fast.make_eval_text()
        xacro_fast.install_clone()

        def too_many_elements():
            raise InputError(f"the expansion produces over {b.limits.max_output_elements} elements (macro bodies "
                             "and blocks inserted); is a macro or block repeating itself? (see --max-elements "
                             "or MYRABOT_DESC_MAX_ELEMENTS)", b.last_loc, b._stack())

        xacro_fast.set_clone_limit(b.limits.max_output_elements, too_many_elements)
        if not b.unsafe_eval:
            xacro.safe_eval = safe_eval.make_safe_eval(self.saved[(xacro, "safe_eval")], refuse,
                                                       b.limits.max_eval_seconds)
        sa._eval_find = eval_find
        sa._eval_dict["find"] = eval_find
        sa._eval = subst_eval
        if b.no_env:
            sa._eval_env = refuse_env
            sa._eval_optenv = refuse_env
            sa._eval_dict["env"] = refuse_env
            sa._eval_dict["optenv"] = refuse_env
        else:   # X007: remember each variable the build read and the value it got
            import os

            def noted(read):
                def note(name, *args, **kwargs):
                    value = read(name, *args, **kwargs)
                    b.env_used[str(name)] = (str(value), name in os.environ)
                    return value
                return note
            sa._eval_env = sa._eval_dict["env"] = noted(sa._eval_env)
            sa._eval_optenv = sa._eval_dict["optenv"] = noted(sa._eval_optenv)
        self.saved_messages = _install_messages(b, self.saved[(xacro, "print_location")])
        return self

    def __exit__(self, *exc):
        import xacro.substitution_args as sa

        import xacro

        _restore_messages(self.saved_messages)

        for (mod, name), value in self.saved.items():
            setattr(mod, name, value)
        sa._eval_dict.clear()
        sa._eval_dict.update(self.saved_dict)
        xacro._global_symbols = self.saved_globals
        if "yaml.constructor" in sys.modules:   # PyYAML was loaded (not just its lazy placeholder)

            yaml_load.scrub_globals()
        sys.setrecursionlimit(self.saved_recursion)
        xacro_fast.uninstall_clone()
        xacro_fast.set_clone_limit(float("inf"), lambda: None)
        xacro_fast.reset()
        xacro.substitution_args_context["arg"] = {}
        return False
