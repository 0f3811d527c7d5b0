"""An allow-list check for xacro ``${}`` expressions from untrusted model files.

xacro's own guard only refuses *names* starting with ``__``; attribute access
through strings escapes it (``${fmt.format(xacro.load_yaml)}`` with
``fmt="{0.__globals__[os]}"`` reaches the os module; anchors.md §1.6). We parse
the expression, walk its AST and allow only: literals, names, arithmetic,
comparisons, boolean logic, conditional expressions, subscripts, attribute
reads (data from YAML), and calls of math functions and xacro's documented
helpers. No name or attribute starting with ``_``, no ``format``/``format_map``,
no comprehensions or lambdas. Calls are checked again at run time: the called
object must be the genuine helper (a property cannot smuggle another function
in under an allowed name). ``**`` and sequence repetition are bounded so that
``${9**9**9}`` or ``${'a'*10**10}`` cannot hang or exhaust memory.
"""

from __future__ import annotations

import ast
import math
import re

FORBIDDEN_ATTRS = {"format", "format_map", "mro", "gi_frame", "f_globals", "f_locals", "f_back"}

# Builtins xacro exposes that are safe to call with bounded arguments.
SAFE_BUILTINS = {"abs", "bool", "float", "int", "len", "max", "min", "round", "str", "sum", "sorted", "any",
                 "all", "divmod", "tuple", "list", "reversed", "zip", "enumerate"}
XACRO_HELPERS = {"load_yaml", "dotify", "arg", "message", "warning", "error", "fatal", "tokenize",
                 "print_location", "abs_filename"}
MATH_FUNCS = {n for n, v in vars(math).items() if not n.startswith("_") and callable(v)}
NAMESPACES = {"math": MATH_FUNCS, "xacro": XACRO_HELPERS, "python": SAFE_BUILTINS}

_ALLOWED_NODES = (
    ast.Expression, ast.Constant, ast.Name, ast.Load, ast.BinOp, ast.UnaryOp, ast.BoolOp, ast.Compare,
    ast.IfExp, ast.Subscript, ast.Slice, ast.Tuple, ast.List, ast.Dict, ast.Attribute, ast.Call, ast.keyword,
    ast.operator, ast.unaryop, ast.boolop, ast.cmpop,
)

MAX_POW_RESULT_BITS = 4096       # ints larger than this are refused
MAX_SEQUENCE_LEN = 1_000_000     # 'a' * n or [0] * n, and any one result
MAX_TOTAL_CHARS = 20_000_000     # characters all expressions of one build may produce
MAX_FORMAT_WIDTH = 1000          # '%1000d'
MAX_FACTORIAL_ARG = 5000         # math.factorial / comb / perm


class RefusedExpression(Exception):
    """The expression is outside the allow-list (code X005)."""


def check_expression(expr: str) -> ast.Expression:
    """Parse and vet a ``${}`` expression; raise RefusedExpression with a reason."""
    return _vet(expr, _check_call_target)


def check_subst_eval(expr: str, allowed_calls: set[str]) -> None:
    """Vet a ``$(eval ...)`` expression: same rules, its own function names."""

    def calls(func):
        if not (isinstance(func, ast.Name) and func.id in allowed_calls):
            raise RefusedExpression("only find, env, optenv, arg, dirname and math functions may be called")

    return _vet(expr, calls)


def _vet(expr: str, check_call) -> ast.Expression:
    try:
        tree = ast.parse(expr.strip(), mode="eval")
    except SyntaxError as exc:
        raise RefusedExpression(f"invalid expression ({exc.msg})") from None
    except (RecursionError, MemoryError):
        raise RefusedExpression("expression nests too deeply") from None
    for node in ast.walk(tree):
        if not isinstance(node, _ALLOWED_NODES):
            raise RefusedExpression(f"{type(node).__name__} is not allowed in a model file")
        if isinstance(node, ast.Name) and node.id.startswith("_"):
            raise RefusedExpression(f"name {node.id!r} is not allowed (leading underscore)")
        if isinstance(node, ast.Attribute) and (node.attr.startswith("_") or node.attr in FORBIDDEN_ATTRS):
            raise RefusedExpression(f"attribute {node.attr!r} is not allowed")
        if isinstance(node, ast.Constant) and isinstance(node.value, str) and "__" in node.value \
                and "{" in node.value:
            raise RefusedExpression("format-style string reaching dunder attributes is not allowed")
        if isinstance(node, ast.Call):
            check_call(node.func)
    return tree


def _check_call_target(func: ast.expr) -> None:
    if isinstance(func, ast.Name):
        if func.id in SAFE_BUILTINS or func.id in MATH_FUNCS or func.id in ("load_yaml", "dotify"):
            return
        raise RefusedExpression(f"call of {func.id!r} is not allowed (only math functions and xacro helpers)")
    if isinstance(func, ast.Attribute) and isinstance(func.value, ast.Name) and func.value.id in NAMESPACES:
        if func.attr in NAMESPACES[func.value.id]:
            return
        raise RefusedExpression(f"call of {func.value.id}.{func.attr} is not allowed")
    raise RefusedExpression("only math functions and xacro helpers may be called")


def _bounded_pow(a, b):
    if isinstance(a, int) and isinstance(b, int) and not isinstance(a, bool) and b > 0 and abs(a) > 1:
        if b * max(abs(a).bit_length(), 1) > MAX_POW_RESULT_BITS:
            raise RefusedExpression(f"{a}**{b} is too large")
    return a ** b


def weight(x, cap: int = MAX_SEQUENCE_LEN, _memo=None) -> int:
    """Items a value expands to when printed (strings count their characters, nested
    containers their contents; a list repeating one object counts it each time). Stops
    counting once past ``cap``."""
    if isinstance(x, (str, bytes)):
        return len(x)
    if not isinstance(x, (list, tuple, dict, set, frozenset)):
        return 1
    memo = {} if _memo is None else _memo
    if id(x) in memo:
        return memo[id(x)]
    memo[id(x)] = cap + 1          # a container reaching itself counts as too large
    items = x.items() if isinstance(x, dict) else x
    total = len(x)
    for item in items:
        total += weight(item, cap, memo)
        if total > cap:
            break
    memo[id(x)] = total
    return total


def _bounded_mul(a, b):
    for seq, n in ((a, b), (b, a)):
        if isinstance(seq, (str, list, tuple)) and isinstance(n, int):
            if len(seq) * n > MAX_SEQUENCE_LEN or (n > 1 and weight(seq) * n > MAX_SEQUENCE_LEN):
                raise RefusedExpression(f"sequence repetition of {weight(seq) * n} items is too large")
    return a * b


_PERCENT_SPEC = re.compile(r"%[#0\- +]*(\*|\d+)?(?:\.(\*|\d+))?")


def _bounded_mod(a, b):
    """``'%0999999999d' % 1`` would build a gigabyte string: cap %-format widths."""
    if isinstance(a, str):
        for m in _PERCENT_SPEC.finditer(a):
            for part in m.groups():
                if part == "*" or (part and int(part) > MAX_FORMAT_WIDTH):
                    raise RefusedExpression(f"%-format width {part} is too large")
    return a % b


def _bounded_lshift(a, b):
    if isinstance(b, int) and b > MAX_POW_RESULT_BITS:
        raise RefusedExpression(f"<< {b} is too large")
    return a << b


_BIG_CALLS = {"factorial", "comb", "perm"}


def _bounded_call(func, *args, **kwargs):
    """Calls whose cost grows with an argument's value (math.factorial(10**7) runs for minutes)."""
    name = getattr(func, "__name__", "")
    if name in _BIG_CALLS and any(isinstance(a, int) and abs(a) > MAX_FACTORIAL_ARG for a in args):
        raise RefusedExpression(f"{name}() of a number over {MAX_FACTORIAL_ARG} is too large")
    if name == "sum" and (len(args) > 1 or "start" in kwargs):
        start = args[1] if len(args) > 1 else kwargs["start"]
        if not isinstance(start, (int, float)):
            raise RefusedExpression("sum() with a non-number start is not allowed")
    if name == "prod" and args and isinstance(args[0], (list, tuple)):
        bits = sum(abs(v).bit_length() for v in args[0] if isinstance(v, int))
        if bits > 4 * MAX_POW_RESULT_BITS:
            raise RefusedExpression("prod() of numbers this large is not allowed")
    return func(*args, **kwargs)


class _Bound(ast.NodeTransformer):
    """Route **, *, %, << and calls through the bounded helpers."""

    def visit_BinOp(self, node):
        self.generic_visit(node)
        helper = {ast.Pow: "_md_pow", ast.Mult: "_md_mul", ast.Mod: "_md_mod",
                  ast.LShift: "_md_lshift"}.get(type(node.op))
        if helper is None or not _needs_bound(node):
            return node
        return ast.copy_location(ast.Call(func=ast.Name(helper, ast.Load()), args=[node.left, node.right],
                                          keywords=[]), node)

    def visit_Call(self, node):
        self.generic_visit(node)
        if _call_name(node.func) not in _BIG_CALLS | {"sum", "prod"}:
            return node
        return ast.copy_location(ast.Call(func=ast.Name("_md_call", ast.Load()), args=[node.func, *node.args],
                                          keywords=node.keywords), node)


def _call_name(func) -> str:
    return func.id if isinstance(func, ast.Name) else func.attr if isinstance(func, ast.Attribute) else ""


def _is_number(node) -> bool:
    return isinstance(node, ast.Constant) and type(node.value) in (int, float, bool)


def _needs_bound(node) -> bool:
    """A ``*``, ``**``, ``%``, ``<<`` or costly call to route through the helpers: a product of two
    number literals (``17 * 0.001``) cannot repeat a sequence, so it is left to Python (and folded)."""
    if isinstance(node, ast.Call):
        return _call_name(node.func) in _BIG_CALLS | {"sum", "prod"}
    return isinstance(node, ast.BinOp) and (isinstance(node.op, (ast.Pow, ast.LShift)) or (
        isinstance(node.op, (ast.Mult, ast.Mod)) and not (_is_number(node.left) and _is_number(node.right))))


_HELPERS = {"_md_pow": _bounded_pow, "_md_mul": _bounded_mul, "_md_mod": _bounded_mod,
            "_md_lshift": _bounded_lshift, "_md_call": _bounded_call}


def bounded_code(tree: ast.Expression):
    """Compile a vetted tree with the bounded operators (skipping the rewrite when nothing needs it)."""
    if any(_needs_bound(n) for n in ast.walk(tree)):
        tree = ast.fix_missing_locations(_Bound().visit(tree))
    return compile(tree, "<expression>", "eval")


def check_result(value, budget: list | None = None):
    """Refuse a result too large to print, and count printed characters against ``budget``
    (a one-item list: characters left for the whole build)."""
    if isinstance(value, (str, list, tuple, dict, set, frozenset)):
        n = weight(value)
        if n > MAX_SEQUENCE_LEN:
            raise RefusedExpression(f"the result has over {MAX_SEQUENCE_LEN} items/characters")
        if budget is not None:
            budget[0] -= n
            if budget[0] < 0:
                raise RefusedExpression(f"expressions produced over {MAX_TOTAL_CHARS} characters in all")
    return value


def eval_bounded(expr: str, tree: ast.Expression, namespace):
    """Evaluate a vetted ``$(eval)`` tree with the bounded operators; RefusedExpression when too large."""
    scope = {"__builtins__": {}, **_HELPERS}
    try:
        return check_result(eval(bounded_code(tree), scope, namespace))
    except (RecursionError, MemoryError) as exc:
        raise RefusedExpression(f"too deep or too large ({type(exc).__name__})") from None


def _genuine_callables(symbols) -> dict:
    """The real helper objects from xacro's global symbol table (identity checks)."""
    import xacro

    g = xacro._global_symbols
    out = {}
    for name in SAFE_BUILTINS | MATH_FUNCS | {"load_yaml", "dotify"}:
        if name in g:
            out[name] = g[name]
    return out


def _lookup(mapping, key):
    try:
        return mapping[key]  # xacro's Table resolves parents and lazy values in __getitem__
    except (KeyError, NameError):
        return None


# A number literal that is a whole token (not part of a name, attribute, 0x/1_000/1j literal).
_NUMBER = re.compile(r"(?<![\w.])(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?(?![\w.])")


_UNSEEN = object()


def _prepare_by_shape(expr: str, shapes: dict):
    """(code, calls) for ``expr`` from the vetting of its *shape*, or None for the full path.

    Generated files pass a different number to every macro call (``${0.1 + 17 * 0.001}``),
    so each expression text is new and vetting walks its tree again. Vetting never looks
    at the value of a number literal (only at node types, names, attributes, strings, and
    whether an operand is a number), so an expression vets exactly as its shape with every
    number replaced by 1. Only quote-free expressions whose shape vets and needs no bounded
    operator take this path; everything else (refusals and their messages included) goes
    through check_expression and bounded_code as before.
    """
    if "'" in expr or '"' in expr:
        return None
    shape = _NUMBER.sub("1", expr)
    if shape == expr:
        return None
    entry = shapes.get(shape, _UNSEEN)
    if entry is _UNSEEN:
        entry = None
        try:
            tree = check_expression(shape)
            if not any(_needs_bound(n) for n in ast.walk(tree)):
                entry = tuple(("name", n.func.id) if isinstance(n.func, ast.Name) else ("ns", n.func.value.id)
                              for n in ast.walk(tree) if isinstance(n, ast.Call))
        except Exception:  # refused or unparsable shape: the full path reports it
            entry = None
        if len(shapes) < 100_000:
            shapes[shape] = entry
    if entry is None:
        return None
    try:
        return compile(expr.strip(), "<expression>", "eval"), entry
    except Exception:  # e.g. a literal the shape hid (09, too many digits): the full path reports it
        return None


def make_safe_eval(original_safe_eval, refuse):
    """A drop-in for ``xacro.safe_eval``; ``refuse(expr, reason)`` raises our error."""
    import xacro

    genuine = _genuine_callables(None)
    genuine_ns = {ns: xacro._global_symbols[ns] for ns in NAMESPACES if ns in xacro._global_symbols}

    cache: dict[str, tuple] = {}
    budget = [MAX_TOTAL_CHARS]

    shapes: dict[str, tuple | None] = {}

    def prepare(expr):
        """Vet and compile once per expression text; remember which helpers it calls."""
        fast = _prepare_by_shape(expr, shapes)
        if fast is not None:
            return fast
        tree = check_expression(expr)
        calls = []
        for node in ast.walk(tree):
            if isinstance(node, ast.Call):
                f = node.func
                calls.append(("name", f.id) if isinstance(f, ast.Name) else ("ns", f.value.id))
        return bounded_code(tree), tuple(calls)   # most expressions need no bounding: no rewrite

    def safe_eval(expr, globals, locals=None):
        try:
            entry = cache.get(expr)
            if entry is None:
                entry = cache[expr] = prepare(expr)
            code, calls = entry
            for kind, name in calls:
                if kind == "name":
                    val = _lookup(locals, name) if locals and name in locals else _lookup(globals, name)
                    if val is not genuine.get(name):
                        raise RefusedExpression(f"{name!r} was redefined; only the genuine helper may be called")
                elif _lookup(globals, name) is not genuine_ns.get(name):
                    raise RefusedExpression(f"namespace {name!r} was redefined")
        except RefusedExpression as exc:
            refuse(expr, str(exc))
            raise  # pragma: no cover  (refuse raises)
        # The symbol table goes in as *locals*: CPython reads globals with a plain dict
        # lookup, which would bypass xacro's Table (parent scopes, lazy properties).
        scope = {"__builtins__": {}, **_HELPERS}
        try:
            return check_result(eval(code, scope, locals if locals is not None else globals), budget)
        except RefusedExpression as exc:
            refuse(expr, str(exc))
            raise
        except (RecursionError, MemoryError) as exc:
            refuse(expr, f"too deep or too large ({type(exc).__name__})")
            raise

    return safe_eval
