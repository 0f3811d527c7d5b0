"""The one YAML loader for every YAML file we read (xacro's ``load_yaml``, sim layouts, configs).

PyYAML's loaders are shared by the whole process: xacro's ``load_yaml`` registers its unit tags
(``!radians``, ``!degrees``...) on ``yaml.SafeLoader`` itself, with constructors that evaluate the
tagged text with xacro's unsandboxed evaluator, and they stay there after the build. Our loader
is a SafeLoader subclass with its own constructor table, started from PyYAML's safe base table
(never from SafeLoader's, which xacro may have touched): the unit tags evaluate numbers and
simple arithmetic with :func:`arith` (no names but ``pi``/``e``/``tau``, no calls), every other
tag is refused, and aliases may not expand past a size limit (a "billion laughs" is small on
disk). :func:`scrub_globals` removes what xacro left on PyYAML's loaders.

PyYAML is imported when a document is first parsed, not with this module: a build that calls no
``load_yaml`` does not load it (bench/bench_start.py).
"""

from __future__ import annotations

import ast
import math
import operator

from myrabot_desc.diagnostics import Loc
from myrabot_desc.errors import InputError
from myrabot_desc.safety import display, read_checked

MAX_NODES = 1_000_000          # items a document may expand to (aliases counted each time used)

# xacro's unit tags and the factor to the base unit (radians, metres)
UNITS = {"!radians": 1.0, "!degrees": math.pi / 180.0, "!meters": 1.0, "!millimeters": 0.001,
         "!foot": 0.3048, "!inches": 0.0254}
_CONSTANTS = {"pi": math.pi, "e": math.e, "tau": math.tau}
_BINOPS = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul, ast.Div: operator.truediv,
           ast.FloorDiv: operator.floordiv, ast.Mod: operator.mod, ast.Pow: operator.pow}
_UNARY = {ast.UAdd: operator.pos, ast.USub: operator.neg}


def arith(text: str) -> float:
    """A number written as arithmetic (``90``, ``-pi/2``, ``3*25.4``): numbers, + - * / // % **,
    parentheses, pi, e and tau. Anything else raises ValueError."""
    if len(text) > 200:
        raise ValueError("too long for a number")
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except (SyntaxError, RecursionError, MemoryError):
        raise ValueError(f"not a number: {text!r}") from None

    def ev(n):
        if isinstance(n, ast.Constant) and type(n.value) in (int, float):
            return n.value
        if isinstance(n, ast.Name) and n.id in _CONSTANTS:
            return _CONSTANTS[n.id]
        if isinstance(n, ast.UnaryOp) and type(n.op) in _UNARY:
            return _UNARY[type(n.op)](ev(n.operand))
        if isinstance(n, ast.BinOp) and type(n.op) in _BINOPS:
            a, b = ev(n.left), ev(n.right)
            if isinstance(n.op, ast.Pow):
                a, b = float(a), float(b)     # float power: an overflow error, never a huge int
            return _BINOPS[type(n.op)](a, b)
        raise ValueError(f"only numbers and arithmetic are allowed: {text!r}")

    try:
        return float(ev(tree.body))
    except (ArithmeticError, RecursionError) as exc:
        raise ValueError(f"{text!r}: {exc}") from None


def _unit_constructor(factor):
    from yaml.constructor import ConstructorError

    def construct(loader, node):
        value = loader.construct_scalar(node)
        try:
            return arith(str(value)) * factor
        except ValueError as exc:
            raise ConstructorError(None, None, f"{node.tag} {exc}", node.start_mark) from None
    return construct


def _located(construct):
    """A constructor whose Python errors (a 5,000-digit integer over Python's digit limit, a date
    like 2024-13-45, a float overflow) become a ConstructorError at the value's line."""
    def wrapper(loader, node):
        try:
            return construct(loader, node)
        except (ValueError, OverflowError, TypeError) as exc:
            from yaml.constructor import ConstructorError

            if isinstance(exc, ConstructorError):
                raise
            what = str(exc).split(";")[0][:160]
            raise ConstructorError(None, None, f"cannot read the value {_short_value(node)} ({what})",
                                   node.start_mark) from None
    return wrapper


def _short_value(node) -> str:
    v = node.value if isinstance(node.value, str) else ""
    return repr(v if len(v) <= 40 else v[:40] + "...")


def _refuse_tag(loader, suffix, node):
    from yaml.constructor import ConstructorError

    raise ConstructorError(None, None, f"the YAML tag {node.tag!r} is not allowed", node.start_mark)


def _safe_loader():
    """The Loader: a SafeLoader subclass with a constructor table of its own (see the module
    docstring), made on first use."""
    global _LOADER
    if _LOADER is None:
        import yaml
        from yaml.constructor import SafeConstructor

        class Loader(yaml.SafeLoader):
            yaml_constructors = dict(SafeConstructor.yaml_constructors)
            yaml_multi_constructors = {"!": _refuse_tag, "tag:": _refuse_tag}

        for tag, factor in UNITS.items():
            Loader.yaml_constructors[tag] = _unit_constructor(factor)
        Loader.yaml_constructors[None] = SafeConstructor.construct_undefined
        for tag, f in list(Loader.yaml_constructors.items()):
            Loader.yaml_constructors[tag] = _located(f)
        _LOADER = Loader
    return _LOADER


_LOADER = None


def _too_big(node) -> bool:
    """Items the composed document expands to (an alias counts as its whole target, each time)."""
    import yaml

    memo: dict[int, int] = {}
    stack = [(node, False)]
    while stack:              # iterative post-order: no recursion on deep documents
        n, done = stack.pop()
        if id(n) in memo and not done:
            continue
        if not done:
            memo[id(n)] = MAX_NODES + 1     # a node reaching itself is too large
            stack.append((n, True))
            kids = [c for pair in n.value for c in pair] if isinstance(n, yaml.MappingNode) else \
                n.value if isinstance(n, yaml.SequenceNode) else []
            stack.extend((c, False) for c in kids if id(c) not in memo)
            continue
        kids = [c for pair in n.value for c in pair] if isinstance(n, yaml.MappingNode) else \
            n.value if isinstance(n, yaml.SequenceNode) else []
        memo[id(n)] = min(1 + sum(memo.get(id(c), 1) for c in kids), MAX_NODES + 1)
    return memo.get(id(node), 0) > MAX_NODES


def _fast_loader():
    """Loader with libyaml's event parser under PyYAML's own Python composer, resolver and our
    constructor table: the same values as Loader, ~8x faster (a UR arm's four parameter files:
    ~30 ms -> ~4 ms). The composer stays in Python on purpose: libyaml's own composer recurses
    in C, where a deeply nested file would overflow the C stack instead of raising
    RecursionError; libyaml's parser keeps its nesting on the heap. None without libyaml."""
    global _FAST
    if _FAST is None:
        import yaml

        _FAST = False
        if getattr(yaml, "__with_libyaml__", False):
            from yaml._yaml import CParser
            from yaml.composer import Composer
            from yaml.constructor import SafeConstructor
            from yaml.resolver import Resolver

            Loader = _safe_loader()

            class FastLoader(Composer, SafeConstructor, Resolver, CParser):
                yaml_constructors = Loader.yaml_constructors
                yaml_multi_constructors = Loader.yaml_multi_constructors

                def __init__(self, stream):
                    CParser.__init__(self, stream)
                    Composer.__init__(self)
                    SafeConstructor.__init__(self)
                    Resolver.__init__(self)

            _FAST = FastLoader
    return _FAST or None


_FAST = None


def loads(text: str, name: str):
    """Parse one YAML document; InputError at ``name:line`` for anything wrong with it."""
    fast = _fast_loader()
    if fast is not None:
        try:
            return _load(fast, text, name)
        except InputError:
            pass        # PyYAML's pure-Python reader words the error (the same on every machine)
    return _load(_safe_loader(), text, name)


def _load(loader_class, text: str, name: str):
    import yaml

    try:
        loader = loader_class(text)     # the pure-Python reader refuses control characters here
    except yaml.reader.ReaderError as exc:
        line = text.count("\n", 0, exc.position) + 1
        raise InputError(f"not valid YAML ({str(exc).splitlines()[0]})", Loc(name, line)) from None
    try:
        node = loader.get_single_node()
        if node is None:
            return None
        if "&" in text and _too_big(node):   # no anchor ("&name"), no alias: nothing can repeat
            raise InputError(f"YAML aliases expand to over {MAX_NODES} items (an alias bomb)", Loc(name))
        return loader.construct_document(node)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None) or getattr(exc, "context_mark", None)
        problem = getattr(exc, "problem", None) or str(exc)
        raise InputError(f"not valid YAML ({problem})", Loc(name, mark.line + 1 if mark else None)) from None
    except RecursionError:
        raise InputError("YAML nests too deeply", Loc(name)) from None
    finally:
        loader.dispose()


def load_path(path, max_bytes: int, roots=None, name: str | None = None):
    """Read and parse a YAML file (through safety.open_checked when ``roots`` are given)."""
    data = read_checked(path, roots, max_bytes, what="YAML file")
    return loads(data.decode("utf-8", errors="replace"), name or display(path))


def scrub_globals() -> None:
    """Take xacro's unit constructors off PyYAML's shared loaders (xacro puts them there)."""
    import yaml

    for cls in (yaml.SafeLoader, yaml.Loader, yaml.FullLoader, yaml.UnsafeLoader,
                getattr(yaml, "CSafeLoader", None)):
        table = cls.__dict__.get("yaml_constructors") if cls is not None else None
        if not table:
            continue
        for tag in UNITS:
            f = table.get(tag)
            if f is not None and "xacro" in (getattr(f, "__module__", "") or getattr(getattr(f, "__self__", None),
                                                                                   "__module__", "") or ""):
                del table[tag]
            elif f is not None and getattr(getattr(f, "__func__", None), "__qualname__", "").startswith("ConstructUnits"):
                del table[tag]
