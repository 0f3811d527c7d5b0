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
MAX_SEQUENCE_LEN = 1_000_000     # 'a' * n or [0] * n


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

    _vet(expr, calls)


def _vet(expr: str, check_call) -> ast.Expression:
    try:
        tree = ast.parse(expr.strip(), mode="eval")
    except SyntaxError as exc:
        raise RefusedExpression(f"invalid expression ({exc.msg})") from None
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


def _bounded_mul(a, b):
    for seq, n in ((a, b), (b, a)):
        if isinstance(seq, (str, list, tuple)) and isinstance(n, int) and len(seq) * n > MAX_SEQUENCE_LEN:
            raise RefusedExpression(f"sequence repetition of {len(seq) * n} items is too large")
    return a * b


class _Bound(ast.NodeTransformer):
    """Route ** and * through the bounded helpers."""

    def visit_BinOp(self, node):
        self.generic_visit(node)
        helper = {ast.Pow: "_md_pow", ast.Mult: "_md_mul"}.get(type(node.op))
        if helper is None or not _needs_bound(node):
            return node
        return ast.copy_location(ast.Call(func=ast.Name(helper, ast.Load()), args=[node.left, node.right],
                                          keywords=[]), node)


def _is_number(node) -> bool:
    return isinstance(node, ast.Constant) and type(node.value) in (int, float, bool)


def _needs_bound(node) -> bool:
    """A ``*`` or ``**`` to route through the helpers: a product of two number literals
    (``17 * 0.001``) cannot repeat a sequence, so it is left to Python (and folded)."""
    return isinstance(node, ast.BinOp) and (isinstance(node.op, ast.Pow) or (
        isinstance(node.op, ast.Mult) and not (_is_number(node.left) and _is_number(node.right))))


_HELPERS = {"_md_pow": _bounded_pow, "_md_mul": _bounded_mul}


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


def make_safe_eval(original_safe_eval, refuse):
    """A drop-in for ``xacro.safe_eval``; ``refuse(expr, reason)`` raises our error."""
    import xacro

    genuine = _genuine_callables(None)
    genuine_ns = {ns: xacro._global_symbols[ns] for ns in NAMESPACES if ns in xacro._global_symbols}

    cache: dict[str, tuple] = {}

    def prepare(expr):
        """Vet and compile once per expression text; remember which helpers it calls."""
        tree = check_expression(expr)
        calls = []
        bound = False
        for node in ast.walk(tree):
            if isinstance(node, ast.Call):
                f = node.func
                calls.append(("name", f.id) if isinstance(f, ast.Name) else ("ns", f.value.id))
            elif isinstance(node, ast.BinOp) and not bound:
                bound = _needs_bound(node)
        if bound:  # most expressions have no * or ** to bound: skip the (slow) rewrite
            tree = ast.fix_missing_locations(_Bound().visit(tree))
        code = compile(tree, "<expression>", "eval")
        return code, tuple(calls)

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
            return eval(code, scope, locals if locals is not None else globals)
        except RefusedExpression as exc:
            refuse(expr, str(exc))
            raise

    return safe_eval
