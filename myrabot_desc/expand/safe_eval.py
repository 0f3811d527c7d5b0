"""Safe evaluation of xacro ``${}`` (and ``$(eval)``) expressions from untrusted model files.

xacro evaluates expressions with Python's ``eval`` and only refuses names starting with ``__``;
attribute access through strings escapes that (``${fmt.format(xacro.load_yaml)}`` with
``fmt="{0.__globals__[os]}"`` reaches the os module), and a namespace's dict methods can be
passed around (``sorted(..., key=python.pop)`` emptied the shared symbol table). Here:

1. **Vetting** (static, on the AST): every expression form xacro 2.x evaluates and real files
   use -- literals, names, arithmetic, comparisons, ``in``, boolean logic, conditional
   expressions, subscripts and slices, calls (with ``*``/``**``), attributes, list/set/dict
   comprehensions, generator expressions and ``lambda``. Refused: names and attributes
   starting with ``__`` (attributes: any leading ``_``), the built-ins that reach code or
   files (DENIED_NAMES), ``format``/``format_map`` (a format field reads attributes: the known
   escape), ``:=``, f-strings, ``yield``.
2. **Rewriting** (the compiled code checks at run time what the AST cannot know):
   ``x.name`` -> ``_md_attr(x, 'name')``, which allows only the methods of plain values that
   compute a value (ALLOWED_METHODS), keys of xacro namespaces (``math.pi``, ``xacro.load_yaml``,
   an include's ``ns.prop``) and keys of YAML dicts (``cfg.wheel.radius``), and nothing of any
   other object (functions, classes, generators); calls -> ``_md_call(f, ...)``, which bounds
   what a call may allocate (``replace``/``join``/``ljust``/``str()``/``range()``, factorial...)
   and routes the functions handed to ``map``/``filter``/``sorted``/``min``/``max`` through the
   same bounds; ``+ * % ** <<`` on non-literals -> bounded helpers (strings, lists, ``bytes``
   and every ``%`` form, mapping keys included); each comprehension loop -> ``_md_iter``, each
   lambda body -> ``_md_enter``/``_md_leave`` (nesting depth), counted as work.
3. **Budgets** per build (Budget): work units (loop steps + items allocated), CPU time spent
   in expressions, characters printed; any one result stays under MAX_SEQUENCE_LEN items. A
   single built-in call runs in C, where the budget cannot stop it (signal handlers run between
   bytecodes): the built-ins whose cost grows with their arguments have them bounded first
   (_precheck: factorial/comb/perm, gcd/lcm, round, prod, the sizes of what grows, and the items
   a set/dict call hashes, grouped by hash in one pass: hash_collisions).
4. **A fresh namespace per build** (fresh_namespace): xacro's global symbols rebuilt for each
   build, without ``type``/``vars``, with our YAML loader, a bounded ``range`` and a ``tokenize``
   whose separators cannot form a regular expression; nothing one model does reaches the next.

Why each allowed method is safe: the str/bytes/tuple/frozenset/number ones return a new value
computed from the receiver and arguments; the list/dict/set mutators (``append pop sort update``...)
change only containers the build itself made (namespaces are per build and expose keys, never
methods), and those that grow one are size-checked before they run, as are the str methods whose
result can be much larger than their input (``replace join center ljust rjust zfill expandtabs``).
"""

from __future__ import annotations

import ast
import math
import re
import time

FORBIDDEN_ATTRS = {"format", "format_map", "mro", "gi_frame", "f_globals", "f_locals", "f_back", "gi_code",
                   "cr_frame", "tb_frame", "func_globals"}
# Built-ins that reach code, files, objects' insides or the interpreter: none is in the namespace;
# calling one by name is refused with a clear message (a property or macro parameter may still be
# *named* ``id`` or ``type``).
DENIED_NAMES = {"eval", "exec", "compile", "open", "getattr", "setattr", "delattr", "hasattr", "globals", "locals",
                "vars", "type", "input", "breakpoint", "help", "object", "super", "classmethod", "staticmethod",
                "property", "memoryview", "iter", "next", "exit", "quit", "dir", "id", "callable", "print",
                "aiter", "anext"}

# Builtins xacro exposes (kept for the "redefined" check and for docs).
SAFE_BUILTINS = {"abs", "bool", "float", "int", "len", "max", "min", "round", "str", "sum", "sorted", "any",
                 "all", "divmod", "tuple", "list", "reversed", "zip", "enumerate", "map", "filter", "range",
                 "dict", "set", "frozenset", "complex", "ord", "repr", "slice", "hash", "isinstance", "issubclass"}
XACRO_HELPERS = {"load_yaml", "dotify", "arg", "message", "warning", "error", "fatal", "tokenize",
                 "print_location", "abs_filename"}
MATH_FUNCS = {n for n, v in vars(math).items() if not n.startswith("_") and callable(v)}
NAMESPACES = ("math", "xacro", "python")

# Methods of plain values that compute a value and change nothing (see the module docstring).
_STR_METHODS = frozenset(
    "capitalize casefold center count endswith expandtabs find index isalnum isalpha isascii isdecimal isdigit "
    "isidentifier islower isnumeric isprintable isspace istitle isupper join ljust lower lstrip partition "
    "removeprefix removesuffix replace rfind rindex rjust rpartition rsplit rstrip split splitlines startswith "
    "strip swapcase title upper zfill".split())
_SEQ_METHODS = frozenset({"count", "index"})
_DICT_METHODS = frozenset({"get", "keys", "values", "items", "copy"})
_SET_METHODS = frozenset({"union", "intersection", "difference", "symmetric_difference", "issubset",
                          "issuperset", "isdisjoint", "copy"})
_NUM_ATTRS = frozenset({"real", "imag", "conjugate", "bit_length", "is_integer", "as_integer_ratio",
                        "numerator", "denominator"})
# Methods that change a list/dict/set the build itself made (``levels.pop(0)``, real robots use
# them). Every namespace is rebuilt for each build and xacro's namespaces expose keys only, so no
# such object outlives its build; the ones that grow a container are size-checked first (_precheck).
_LIST_MUTATORS = frozenset({"append", "extend", "insert", "pop", "remove", "reverse", "sort", "clear"})
_DICT_MUTATORS = frozenset({"pop", "popitem", "setdefault", "update", "clear"})
_SET_MUTATORS = frozenset({"add", "discard", "remove", "pop", "update", "clear"})
_GROWERS = {"append": 1, "insert": 1, "add": 1, "setdefault": 1, "extend": None, "update": None}
ALLOWED_METHODS = {
    str: _STR_METHODS, bytes: (_STR_METHODS - {"casefold", "format", "isdecimal", "isidentifier", "isnumeric",
                                               "isprintable"}) | {"decode", "hex"},
    list: _SEQ_METHODS | {"copy"} | _LIST_MUTATORS, tuple: _SEQ_METHODS,
    range: _SEQ_METHODS | {"start", "stop", "step"},
    dict: _DICT_METHODS | _DICT_MUTATORS, set: _SET_METHODS | _SET_MUTATORS, frozenset: _SET_METHODS,
    int: _NUM_ATTRS, float: _NUM_ATTRS, bool: _NUM_ATTRS, complex: _NUM_ATTRS,
}
_GROWS = {"replace", "join", "center", "ljust", "rjust", "zfill", "expandtabs"}

MAX_POW_RESULT_BITS = 4096       # ints larger than this are refused
MAX_SEQUENCE_LEN = 1_000_000     # 'a' * n or [0] * n, and any one result
MAX_TOTAL_CHARS = 20_000_000     # characters all expressions of one build may produce
MAX_WORK = 10_000_000            # loop steps + items allocated by all expressions of one build
MAX_EVAL_SECONDS = 3.0           # CPU time all expressions of one build may take
MAX_LAMBDA_DEPTH = 100           # lambdas calling lambdas (the C stack is not for hostile recursion)
MAX_FORMAT_WIDTH = 1000          # '%1000d'
MAX_FACTORIAL_ARG = 5000         # math.factorial / comb / perm
MAX_INT_ARGS_BITS = 4 * MAX_POW_RESULT_BITS   # the integers one gcd()/lcm()/prod() call takes, in all
MAX_SAME_HASH = 64               # distinct items of one set/dict sharing one hash value
MAX_ROUND_DIGITS = 1000          # round(x, -n)
MAX_DISPLAY_ITEMS = 10_000       # {k: v, ...} written out in one expression


class RefusedExpression(Exception):
    """The expression is outside the allow-list or over a bound (code X005)."""


# ------------------------------------------------------------------ vetting
_BASE_NODES = (
    ast.Expression, ast.Constant, ast.Name, ast.Load, ast.BinOp, ast.UnaryOp, ast.BoolOp, ast.Compare,
    ast.IfExp, ast.Subscript, ast.Slice, ast.Tuple, ast.List, ast.Dict, ast.Attribute, ast.Call, ast.keyword,
    ast.operator, ast.unaryop, ast.boolop, ast.cmpop,
)
_ALLOWED_NODES = _BASE_NODES + (ast.Set, ast.Starred, ast.ListComp, ast.SetComp, ast.DictComp, ast.GeneratorExp,
                                ast.comprehension, ast.Store, ast.Lambda, ast.arguments, ast.arg)


def check_expression(expr: str) -> ast.Expression:
    """Parse and vet a ``${}`` expression; raise RefusedExpression with a reason."""
    return _vet(expr, None, _ALLOWED_NODES)


def check_subst_eval(expr: str, allowed_calls: set[str]) -> ast.Expression:
    """Vet a ``$(eval ...)`` expression: the plain forms only, its own function names."""

    def calls(func):
        if not (isinstance(func, ast.Name) and func.id in allowed_calls):
            raise RefusedExpression("only find, env, optenv, arg, dirname and math functions may be called")

    return _vet(expr, calls, _BASE_NODES)


def _vet(expr: str, check_call, allowed_nodes) -> ast.Expression:
    try:
        tree = ast.parse(expr.strip(), mode="eval")
    except SyntaxError as exc:
        raise RefusedExpression(f"invalid expression ({exc.msg})") from None
    except (RecursionError, MemoryError):
        raise RefusedExpression("expression nests too deeply") from None
    try:
        nodes = list(ast.walk(tree))
    except RecursionError:
        raise RefusedExpression("expression nests too deeply") from None
    for node in nodes:
        if not isinstance(node, allowed_nodes):
            raise RefusedExpression(f"{type(node).__name__} is not allowed in a model file")
        name = node.id if isinstance(node, ast.Name) else node.arg if isinstance(node, ast.arg) else None
        if name is not None and (name.startswith("__") or name.startswith("_md_")):
            raise RefusedExpression(f"name {name!r} is not allowed")
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in DENIED_NAMES:
            raise RefusedExpression(f"call of {node.func.id!r} is not allowed")
        if isinstance(node, ast.Attribute) and (node.attr.startswith("_") or node.attr in FORBIDDEN_ATTRS):
            raise RefusedExpression(f"attribute {node.attr!r} is not allowed")
        if isinstance(node, ast.keyword) and node.arg and node.arg.startswith("__"):
            raise RefusedExpression(f"keyword {node.arg!r} is not allowed")
        if isinstance(node, ast.Constant) and isinstance(node.value, str) and "__" in node.value \
                and "{" in node.value:
            raise RefusedExpression("format-style string reaching dunder attributes is not allowed")
        if isinstance(node, (ast.Dict, ast.Set)) and len(node.keys if isinstance(node, ast.Dict) else node.elts) \
                > MAX_DISPLAY_ITEMS:
            raise RefusedExpression(f"a dict or set display of over {MAX_DISPLAY_ITEMS} items is not allowed")
        if isinstance(node, ast.Call) and check_call is not None:
            check_call(node.func)
    return tree


# ------------------------------------------------------------------ budgets
class Budget:
    """What all expressions of one build may still spend."""

    __slots__ = ("work", "chars", "seconds", "started", "depth", "nesting", "max_seconds")

    def __init__(self, max_seconds: float = MAX_EVAL_SECONDS):
        self.work = MAX_WORK
        self.chars = MAX_TOTAL_CHARS
        self.seconds = 0.0          # spent by finished top-level evaluations
        self.started = None         # CPU-time start of the running top-level evaluation (process_time)
        self.depth = 0              # lambda nesting
        self.nesting = 0            # evaluations running inside evaluations (lazy properties)
        self.max_seconds = max_seconds

    def spend(self, n: int) -> None:
        self.work -= n
        if self.work < 0:
            raise RefusedExpression(f"expressions did over {MAX_WORK} steps/items in all (a loop or size bomb)")

    def clock(self) -> None:
        t = self.seconds + (time.process_time() - self.started if self.started is not None else 0.0)
        if t > self.max_seconds:
            raise RefusedExpression(f"expressions ran for over {self.max_seconds:g} s in all (a loop bomb?)")


_budget = [Budget()]       # the budget of the evaluation running now (builds hold a lock)


def _b() -> Budget:
    return _budget[0]


# ------------------------------------------------------------------ bounded helpers
_SIZED = (str, bytes, bytearray, list, tuple, dict, set, frozenset)


def _bounded_pow(a, b):
    if isinstance(a, int) and isinstance(b, int) and not isinstance(a, bool) and b > 0 and abs(a) > 1:
        if b * max(abs(a).bit_length(), 1) > MAX_POW_RESULT_BITS:
            raise RefusedExpression(f"{a}**{b} is too large")
    return a ** b


def weight(x, cap: int = MAX_SEQUENCE_LEN, _memo=None) -> int:
    """Items a value expands to when printed (strings count their characters, nested
    containers their contents; a list repeating one object counts it each time). Stops
    counting once past ``cap``."""
    if isinstance(x, (str, bytes, bytearray)):
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
        if isinstance(seq, (str, bytes, bytearray, list, tuple)) and isinstance(n, int):
            if len(seq) * n > MAX_SEQUENCE_LEN or (n > 1 and weight(seq) * n > MAX_SEQUENCE_LEN):
                raise RefusedExpression(f"sequence repetition of {weight(seq) * n} items is too large")
            _b().spend(len(seq) * max(n, 0))
            return a * b
    if isinstance(a, int) and isinstance(b, int) and a.bit_length() + b.bit_length() > 4 * MAX_POW_RESULT_BITS:
        raise RefusedExpression("a product of numbers this large is not allowed")
    return a * b


def _bounded_add(a, b):
    if isinstance(a, _SIZED) and isinstance(b, _SIZED):
        n = weight(a) + weight(b)
        if n > MAX_SEQUENCE_LEN:
            raise RefusedExpression(f"a concatenation of {n} items is too large")
        _b().spend(len(a) + len(b))
    return a + b


# '%' then an optional mapping key, flags, width and precision (either may be '*').
_PERCENT_SPEC = re.compile(r"%(?:\([^)]*\))?[#0\- +]*(\*|\d+)?(?:\.(\*|\d+))?")


def _bounded_mod(a, b):
    """``'%0999999999d' % 1`` (or ``'%(a)0999999999d' % d``, or bytes) would build a gigabyte:
    cap every %-format width and precision, and the size of what is formatted."""
    if isinstance(a, (str, bytes, bytearray)):
        text = a if isinstance(a, str) else bytes(a).decode("latin-1")
        for m in _PERCENT_SPEC.finditer(text):
            for part in m.groups():
                if part == "*" or (part and int(part) > MAX_FORMAT_WIDTH):
                    raise RefusedExpression(f"%-format width {part} is too large")
        n = len(a) + weight(b)
        if n > MAX_SEQUENCE_LEN:
            raise RefusedExpression(f"%-formatting {n} items is too large")
        _b().spend(n)
    return a % b


def _bounded_lshift(a, b):
    if isinstance(b, int) and b > MAX_POW_RESULT_BITS:
        raise RefusedExpression(f"<< {b} is too large")
    return a << b


_BIG_CALLS = {"factorial", "comb", "perm"}
# Calls that hash every item they are given (a set, a dict, set algebra): one call runs in C, where
# no budget check can stop it, so what it is given is checked first (hash_collisions)
_HASHING = {set, frozenset, dict}
_HASHING_METHODS = {"union", "intersection", "difference", "symmetric_difference", "issubset", "issuperset",
                    "isdisjoint", "update", "intersection_update", "difference_update",
                    "symmetric_difference_update"}


def hash_collisions(items) -> None:
    """Refuse items that would make one set/dict call quadratic: many distinct items with one hash
    value (integers equal modulo 2**61 - 1 hash alike, and every probe then compares them all). One
    linear pass groups the items by hash; a group past MAX_SAME_HASH must be one value repeated."""
    groups: dict = {}
    for x in items:
        try:
            h = hash(x)
        except TypeError:
            continue            # unhashable: the call itself says so
        g = groups.get(h)
        if g is None:
            groups[h] = [x]
        elif len(g) < MAX_SAME_HASH:
            g.append(x)
        elif x is not g[0] and x != g[0]:
            raise RefusedExpression(f"over {MAX_SAME_HASH} different values with one hash value (a hash "
                                    "collision bomb)")


def _hash_inputs(f, name, recv, args, kwargs) -> list | None:
    """The items a hashing call will hash, or None when it hashes nothing of the caller's."""
    if f in _HASHING:
        if not args:
            return None
        src = args[0]
        if f is dict:
            if isinstance(src, dict):
                return list(src.keys())
            return [kv[0] for kv in src if isinstance(kv, (tuple, list)) and kv]
        return list(src)
    if type(recv) in (set, frozenset) and name in _HASHING_METHODS:
        return [x for a in args for x in a] + list(recv)
    if type(recv) is dict and name == "update" and args:
        return list(args[0].keys()) if isinstance(args[0], dict) else \
            [kv[0] for kv in args[0] if isinstance(kv, (tuple, list)) and kv]
    return None


def _precheck(f, args, kwargs) -> None:
    """Refuse a call whose cost or result would be too large, before it runs."""
    name = getattr(f, "__name__", "")
    recv = getattr(f, "__self__", None)
    if type(recv) in (str, bytes) and name in _GROWS:
        size = _grown_size(recv, name, args)
        if size > MAX_SEQUENCE_LEN:
            raise RefusedExpression(f"{name}() would build {size} characters, too large")
        return
    if type(recv) in (list, dict, set) and name in _GROWERS:
        extra = _GROWERS[name]
        if extra is None:
            extra = sum(len(a) if isinstance(a, _SIZED) else MAX_SEQUENCE_LEN + 1 for a in args) + len(kwargs)
        if len(recv) + extra > MAX_SEQUENCE_LEN:
            raise RefusedExpression(f"{name}() would grow a container past {MAX_SEQUENCE_LEN} items")
        _b().spend(extra)
        return
    if name in _BIG_CALLS and any(isinstance(a, int) and abs(a) > MAX_FACTORIAL_ARG for a in args):
        raise RefusedExpression(f"{name}() of a number over {MAX_FACTORIAL_ARG} is too large")
    if name in ("gcd", "lcm") and getattr(f, "__module__", None) == "math":
        if len(args) > MAX_SEQUENCE_LEN:
            raise RefusedExpression(f"{name}() of over {MAX_SEQUENCE_LEN} numbers is too large")
        bits = sum(a.bit_length() for a in args if isinstance(a, int))
        if bits > MAX_INT_ARGS_BITS:
            raise RefusedExpression(f"{name}() of numbers of {bits} bits in all is too large "
                                    f"(at most {MAX_INT_ARGS_BITS})")
        _b().spend(len(args))
    if f is round and len(args) > 1 and isinstance(args[1], int) and abs(args[1]) > MAX_ROUND_DIGITS:
        raise RefusedExpression(f"round() to {args[1]} digits is not allowed (at most {MAX_ROUND_DIGITS})")
    if f in _HASHING or (type(recv) in (set, frozenset, dict) and name in _HASHING_METHODS):
        items = _hash_inputs(f, name, recv, args, kwargs)
        if items is not None:
            if len(items) > MAX_SEQUENCE_LEN:
                raise RefusedExpression(f"{name}() of over {MAX_SEQUENCE_LEN} items is too large")
            _b().spend(len(items))
            hash_collisions(items)
    if f is sum and (len(args) > 1 or "start" in kwargs):
        start = args[1] if len(args) > 1 else kwargs["start"]
        if not isinstance(start, (int, float)):
            raise RefusedExpression("sum() with a non-number start is not allowed")
    if name == "prod" and args and isinstance(args[0], (list, tuple)):
        bits = sum(abs(v).bit_length() for v in args[0] if isinstance(v, int))
        if bits > 4 * MAX_POW_RESULT_BITS:
            raise RefusedExpression("prod() of numbers this large is not allowed")
    if f in (str, repr, ascii) and args and weight(args[0]) > MAX_SEQUENCE_LEN:
        raise RefusedExpression(f"{name}() of over {MAX_SEQUENCE_LEN} items is too large")


def _grown_size(s, name, args) -> int:
    if name == "join":
        items = args[0] if args else ()
        total, n = 0, 0
        for it in items:      # a list (materialized by _md_call) of strings
            total += len(it) if isinstance(it, (str, bytes)) else 0
            n += 1
        return total + len(s) * max(n - 1, 0)
    if name == "replace":
        old = args[0] if args else ""
        new = args[1] if len(args) > 1 else ""
        count = args[2] if len(args) > 2 and isinstance(args[2], int) and args[2] >= 0 else None
        hits = s.count(old) if isinstance(old, type(s)) else 0
        if count is not None:
            hits = min(hits, count)
        return len(s) + hits * max(len(new) - len(old), 0) if isinstance(new, (str, bytes)) else len(s)
    if name == "expandtabs":
        tab = args[0] if args and isinstance(args[0], int) else 8
        return len(s) + s.count("\t" if isinstance(s, str) else b"\t") * max(tab, 0)
    width = args[0] if args and isinstance(args[0], int) else 0
    return max(len(s), width)


_HIGHER: dict = {}    # function object -> where its callable argument is: 0 (map, filter) or "key"


def _charged(g):
    """A function handed to map/filter/sorted/min/max: called through the same bounds."""
    if g is None:
        return None

    def call(*args, **kwargs):
        return _md_call(g, *args, **kwargs)

    return call


def _md_call(f, *args, **kwargs):
    b = _b()
    kind = _HIGHER.get(f) if type(f).__hash__ is not None else None
    if kind is not None:
        if kind == 0 and args:
            args = (_charged(args[0]),) + args[1:]
        elif kind == "key" and "key" in kwargs:
            kwargs["key"] = _charged(kwargs["key"])
    else:
        fname = getattr(f, "__name__", "")
        if fname in ("join", "extend", "update") and args and not isinstance(args[0], _SIZED) \
                and type(getattr(f, "__self__", None)) in (str, bytes, list, dict, set):
            args = (list(args[0]),) + args[1:]      # a generator: its steps counted, then its size checked
        elif (f in _HASHING or (fname in _HASHING_METHODS and type(getattr(f, "__self__", None)) in
                                (set, frozenset))) and args and not isinstance(args[0], _SIZED):
            args = (list(_md_iter(args[0])),) + args[1:]      # a generator or a range: materialised, counted
        elif fname == "sort" and "key" in kwargs and type(getattr(f, "__self__", None)) is list:
            kwargs["key"] = _charged(kwargs["key"])
    _precheck(f, args, kwargs)
    result = f(*args, **kwargs)
    if isinstance(result, _SIZED):
        n = len(result)
        if n > MAX_SEQUENCE_LEN:
            raise RefusedExpression(f"the result has over {MAX_SEQUENCE_LEN} items/characters")
        b.work -= n
    b.work -= 1
    if b.work < 0:
        b.spend(0)
    return result


def _md_iter(iterable):
    """A comprehension's loop: each step counts; the clock is read every 4096 steps."""
    b = _b()
    n = 0
    for item in iterable:
        n += 1
        if not n & 4095:
            b.spend(4096)
            b.clock()
        yield item
    b.spend(n & 4095)


def _md_enter():
    b = _b()
    b.depth += 1
    if b.depth > MAX_LAMBDA_DEPTH:
        raise RefusedExpression(f"lambdas nest deeper than {MAX_LAMBDA_DEPTH}")
    b.work -= 1
    if not b.work & 4095:
        b.spend(0)
        b.clock()
    return 0


def _md_leave(_token, value):
    _b().depth -= 1
    return value


def _md_attr(obj, name):
    """``obj.name`` for the values an expression may look into (see the module docstring)."""
    import xacro

    t = type(obj)
    allowed = ALLOWED_METHODS.get(t)
    if allowed is not None:
        if name in allowed:
            return getattr(obj, name)
        raise RefusedExpression(f"attribute {name!r} of a {t.__name__} is not allowed")
    if isinstance(obj, xacro.NameSpace):        # math.pi, xacro.load_yaml, an include's ns.prop: keys only
        try:
            return obj[name]
        except KeyError:
            raise NameError(f"name '{name}' is not defined") from None
    if isinstance(obj, xacro.YamlDictWrapper):  # cfg.wheel.radius: keys (xacro's dotted access)
        if name in _DICT_METHODS:
            return getattr(obj, name)
        if hasattr(dict, name):
            raise RefusedExpression(f"attribute {name!r} of a YAML dict is not allowed")
        return xacro.YamlListWrapper.wrap(dict.__getitem__(obj, name)) if name in obj else obj.__getattr__(name)
    for base in (dict, list, tuple, str, set, frozenset, int, float):
        if isinstance(obj, base):                 # YAML list wrappers, bool subclasses...
            if name in ALLOWED_METHODS[base]:
                return getattr(obj, name)
            raise RefusedExpression(f"attribute {name!r} of a {base.__name__} is not allowed")
    raise RefusedExpression(f"attribute {name!r} of a {t.__name__} is not allowed (only plain values, "
                            "YAML data and xacro's namespaces have attributes here)")


class _Rewrite(ast.NodeTransformer):
    """Route attributes, calls, loops, lambdas and the growing operators through the helpers."""

    def __init__(self, bound_names: set):
        self.bound = bound_names

    def visit_BinOp(self, node):
        self.generic_visit(node)
        helper = {ast.Pow: "_md_pow", ast.Mult: "_md_mul", ast.Mod: "_md_mod", ast.LShift: "_md_lshift",
                  ast.Add: "_md_add"}.get(type(node.op))
        if helper is None or not _needs_bound(node):
            return node
        return ast.copy_location(ast.Call(func=ast.Name(helper, ast.Load()), args=[node.left, node.right],
                                          keywords=[]), node)

    def visit_Attribute(self, node):
        self.generic_visit(node)
        return ast.copy_location(ast.Call(func=ast.Name("_md_attr", ast.Load()),
                                          args=[node.value, ast.Constant(node.attr)], keywords=[]), node)

    def visit_Call(self, node):
        direct = isinstance(node.func, ast.Name) and node.func.id in _PURE_MATH and node.func.id not in self.bound
        self.generic_visit(node)
        if direct:      # sin(x), radians(90): the genuine function (checked before the run), bounded args
            return node
        return ast.copy_location(ast.Call(func=ast.Name("_md_call", ast.Load()), args=[node.func, *node.args],
                                          keywords=node.keywords), node)

    def visit_comprehension(self, node):
        self.generic_visit(node)
        node.iter = ast.copy_location(ast.Call(func=ast.Name("_md_iter", ast.Load()), args=[node.iter],
                                               keywords=[]), node.iter)
        return node

    def visit_Lambda(self, node):
        self.generic_visit(node)
        enter = ast.Call(func=ast.Name("_md_enter", ast.Load()), args=[], keywords=[])
        node.body = ast.copy_location(ast.Call(func=ast.Name("_md_leave", ast.Load()), args=[enter, node.body],
                                               keywords=[]), node.body)
        return node


# Math functions whose cost does not grow with their arguments' values (called directly).
_PURE_MATH = MATH_FUNCS - _BIG_CALLS - {"prod", "fsum", "dist", "hypot", "sumprod", "lcm", "gcd", "isqrt",
                                        "ldexp", "pow", "exp", "expm1", "exp2"}


def _call_name(func) -> str:
    return func.id if isinstance(func, ast.Name) else func.attr if isinstance(func, ast.Attribute) else ""


_ARITHMETIC = (ast.Add, ast.Sub, ast.Mult, ast.Div, ast.FloorDiv, ast.Mod)


def _is_number(node, depth: int = 0) -> bool:
    """A number literal, or ``+ - * / // %`` and unary ``+ -`` of number literals only (``0.1 + 17 *
    0.001``): a number, no larger than its text allows. Deeper than a few levels it counts as unknown
    (bounded at run time), which keeps this test linear in the tree's size."""
    if isinstance(node, ast.Constant):
        return type(node.value) in (int, float, bool)
    if depth >= 8:
        return False
    if isinstance(node, ast.UnaryOp):
        return isinstance(node.op, (ast.UAdd, ast.USub)) and _is_number(node.operand, depth + 1)
    return isinstance(node, ast.BinOp) and isinstance(node.op, _ARITHMETIC) and \
        _is_number(node.left, depth + 1) and _is_number(node.right, depth + 1)


def _needs_bound(node) -> bool:
    """A node the rewrite changes. A ``*``/``+``/``%`` of two numbers made of number literals only
    (``17 * 0.001``, ``0.1 + 17 * 0.001``: what generated files pass to every macro call) cannot grow
    a sequence, so it is left to Python (and folded)."""
    if isinstance(node, (ast.Attribute, ast.Lambda, ast.comprehension)):
        return True
    if isinstance(node, ast.Call):
        return not (isinstance(node.func, ast.Name) and node.func.id in _PURE_MATH)
    return isinstance(node, ast.BinOp) and (isinstance(node.op, (ast.Pow, ast.LShift)) or (
        isinstance(node.op, (ast.Mult, ast.Mod, ast.Add)) and not (_is_number(node.left) and _is_number(node.right))))


_HELPERS = {"_md_pow": _bounded_pow, "_md_mul": _bounded_mul, "_md_mod": _bounded_mod, "_md_add": _bounded_add,
            "_md_lshift": _bounded_lshift, "_md_call": _md_call, "_md_attr": _md_attr, "_md_iter": _md_iter,
            "_md_enter": _md_enter, "_md_leave": _md_leave}


def _bound_names(tree) -> set:
    out = set()
    for n in ast.walk(tree):
        if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store):
            out.add(n.id)
        elif isinstance(n, ast.arg):
            out.add(n.arg)
    return out


def bounded_code(tree: ast.Expression):
    """Compile a vetted tree with the run-time checks (skipping the rewrite when nothing needs it)."""
    if any(_needs_bound(n) for n in ast.walk(tree)):
        tree = ast.fix_missing_locations(_Rewrite(_bound_names(tree)).visit(tree))
    return compile(tree, "<expression>", "eval")


def check_result(value, budget: Budget | None = None):
    """Refuse a result too large to print, and count printed characters against the budget."""
    if isinstance(value, (str, bytes, list, tuple, dict, set, frozenset)):
        n = weight(value)
        if n > MAX_SEQUENCE_LEN:
            raise RefusedExpression(f"the result has over {MAX_SEQUENCE_LEN} items/characters")
        if budget is not None:
            budget.chars -= n
            if budget.chars < 0:
                raise RefusedExpression(f"expressions produced over {MAX_TOTAL_CHARS} characters in all")
    return value


class _Scope(dict):
    """eval's globals: every name read goes to xacro's symbol table (also inside lambdas and
    comprehensions, as with xacro, which passes its table as globals); our helpers live in
    this dict's own ``__builtins__`` entry, where no expression can name them."""

    __slots__ = ("table",)

    def __init__(self, table):
        dict.__init__(self, __builtins__=_HELPERS)
        self.table = table

    def __getitem__(self, key):
        if key[:4] == "_md_":     # our helpers: never a property of the same name
            raise KeyError(key)
        return self.table[key]

    def __contains__(self, key):
        return key in self.table

    def __setitem__(self, key, value):
        raise RefusedExpression("assignment is not allowed")


def _run(code, table, budget: Budget):
    saved = _budget[0]
    _budget[0] = budget
    top = budget.nesting == 0
    depth = budget.depth
    if top:
        budget.started = time.process_time()
    budget.nesting += 1
    try:
        value = eval(code, _Scope(table))
    except (RecursionError, MemoryError) as exc:
        raise RefusedExpression(f"too deep or too large ({type(exc).__name__})") from None
    except OverflowError as exc:
        raise RefusedExpression(f"a number is too large ({exc})") from None
    finally:
        budget.nesting -= 1
        budget.depth = depth
        if top:
            budget.seconds += time.process_time() - budget.started
            budget.started = None
        _budget[0] = saved
    if top:
        budget.clock()
    return check_result(value, budget)


def eval_bounded(expr: str, tree: ast.Expression, namespace):
    """Evaluate a vetted ``$(eval)`` tree with the bounded operators; RefusedExpression when too large."""
    return _run(bounded_code(tree), namespace, Budget())


# ------------------------------------------------------------------ the namespace of one build
def _bounded_range(*args):
    r = range(*args)
    if len(r) > MAX_SEQUENCE_LEN:
        raise RefusedExpression(f"range of {len(r)} numbers is too large")
    return r


def _tokenize(s, sep=",; ", skip_empty=True):
    """xacro.tokenize with its separators as characters (not a pattern a model can write)."""
    results = re.split("[" + "".join(re.escape(c) for c in str(sep)) + "]", s) if sep else [s]
    return [item for item in results if item] if skip_empty else results


def fresh_namespace(load_yaml):
    """xacro's global symbols, built anew for one build (no object is shared with another build)."""
    import xacro

    g = xacro.create_global_symbols()
    py, xa = g["python"], g["xacro"]
    for name in ("type", "vars"):
        dict.pop(py, name, None)
    msg = "Using {name}() directly is deprecated. Use {ns}.{name}() instead."

    def deprecated(f, name, ns):
        def wrapper(*args, **kwargs):
            xacro.warning(msg.format(name=name, ns=ns))
            return _md_call(f, *args, **kwargs)
        wrapper.__name__ = name
        return wrapper

    dict.__setitem__(py, "range", _bounded_range)
    dict.__setitem__(g, "range", deprecated(_bounded_range, "range", "python"))
    dict.__setitem__(g, "sorted", deprecated(sorted, "sorted", "python"))
    dict.__setitem__(xa, "load_yaml", load_yaml)
    dict.__setitem__(g, "load_yaml", deprecated(load_yaml, "load_yaml", "xacro"))
    dict.__setitem__(xa, "tokenize", _tokenize)
    return g


for _f in (map, filter):
    _HIGHER[_f] = 0
for _f in (sorted, min, max):
    _HIGHER[_f] = "key"


def _genuine(table) -> tuple[dict, dict]:
    out = {}
    for name in SAFE_BUILTINS | MATH_FUNCS | {"load_yaml", "dotify"}:
        if name in table:
            out[name] = table[name]
    return out, {ns: table[ns] for ns in NAMESPACES if ns in table}


def _lookup(mapping, key):
    try:
        return mapping[key]  # xacro's Table resolves parents and lazy values in __getitem__
    except (KeyError, NameError):
        return None


# A number literal that is a whole token (not part of a name, attribute, 0x/1_000/1j literal).
_NUMBER = re.compile(r"(?<![\w.])(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?(?![\w.])")


_UNSEEN = object()


def _calls_of(tree) -> tuple:
    """The helper names and namespaces an expression calls (checked to be genuine before a run)."""
    out = []
    for n in ast.walk(tree):
        if isinstance(n, ast.Call):
            f = n.func
            if isinstance(f, ast.Name):
                out.append(("name", f.id))
            elif isinstance(f, ast.Attribute) and isinstance(f.value, ast.Name) and f.value.id in NAMESPACES:
                out.append(("ns", f.value.id))
    return tuple(out)


def _plain_name(expr: str) -> bool:
    """A bare property name: it vets as its tree would (one Name, which _vet refuses only when it
    starts with ``__`` or ``_md_``), with nothing to rewrite and no call to check."""
    import keyword

    return expr.isidentifier() and not keyword.iskeyword(expr) and not expr.startswith(("__", "_md_"))


def _prepare_by_shape(expr: str, shapes: dict):
    """(code, calls) for ``expr`` from the vetting of its *shape*, or None for the full path.

    Generated files pass a different number to every macro call (``${0.1 + 17 * 0.001}``),
    so each expression text is new and vetting walks its tree again. Vetting never looks
    at the value of a number literal (only at node types, names, attributes, strings, and
    whether an operand is a number), so an expression vets exactly as its shape with every
    number replaced by 1. Only quote-free expressions whose shape vets and needs no rewrite
    take this path; everything else (refusals and their messages included) goes through
    check_expression and bounded_code as before.
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
                entry = _calls_of(tree)
        except Exception:  # refused or unparsable shape: the full path reports it
            entry = None
        if len(shapes) < MAX_PREPARED:
            shapes[shape] = entry
    if entry is None:
        return None
    try:
        return compile(expr.strip(), "<expression>", "eval"), entry
    except Exception:  # e.g. a literal the shape hid (09, too many digits): the full path reports it
        return None


# Vetted, compiled expressions by their text, shared by the builds of one process (a diff builds two
# revisions that mostly write the same expressions): what ``prepare`` makes depends on the text alone,
# the helpers an expression calls are checked against each build's table at every call. Bounded.
_PREPARED: dict[str, tuple] = {}
_SHAPES: dict[str, tuple | None] = {}
MAX_PREPARED = 100_000


def make_safe_eval(original_safe_eval, refuse, max_seconds: float = MAX_EVAL_SECONDS):
    """A drop-in for ``xacro.safe_eval`` (for one build); ``refuse(expr, reason)`` raises our error."""
    import xacro

    genuine, genuine_ns = _genuine(xacro._global_symbols)
    cache = _PREPARED
    budget = Budget(max_seconds)
    shapes = _SHAPES

    def prepare(expr):
        """Vet and compile once per expression text; remember which helpers it calls."""
        if _plain_name(expr):      # ${name}: most expressions of a real robot
            return compile(expr, "<expression>", "eval"), ()
        fast = _prepare_by_shape(expr, shapes)
        if fast is not None:
            return fast
        tree = check_expression(expr)
        return bounded_code(tree), _calls_of(tree)

    def safe_eval(expr, globals, locals=None):
        table = locals if locals is not None else globals
        try:
            entry = cache.get(expr)
            if entry is None:
                if not isinstance(expr, str):
                    raise RefusedExpression(f"not an expression: {type(expr).__name__}")
                entry = prepare(expr)
                if len(cache) < MAX_PREPARED:
                    cache[expr] = entry
            code, calls = entry
            for kind, name in calls:
                if kind == "name":
                    if name in genuine and _lookup(table, name) is not genuine[name]:
                        raise RefusedExpression(f"{name!r} was redefined; only the genuine helper may be called")
                elif _lookup(table, name) is not genuine_ns.get(name):
                    raise RefusedExpression(f"namespace {name!r} was redefined")
            return _run(code, table, budget)
        except RefusedExpression as exc:
            refuse(expr, str(exc))
            raise  # pragma: no cover  (refuse raises)

    return safe_eval
