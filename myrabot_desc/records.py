"""Small records without dataclasses or ``typing.NamedTuple``.

A dataclass compiles its generated methods when it is defined (~0.6 ms a class), a NamedTuple its
constructor (~0.1–0.2 ms, with typing's checks of each annotation), which every command would pay
at start for records it may never build: the model alone defines some sixty.

- :class:`Struct`: an immutable tuple with named fields, declared like a NamedTuple (annotated
  fields, defaults, methods) and behaving like one (tuple equality and hash, ``_replace``,
  ``_asdict``, pickling), defined in ~10 µs.
- :class:`Record` and :class:`Frozen`: a record that declares its fields as ``__slots__`` (in
  constructor order) and writes its own ``__init__`` (defaults, a new list or dict per instance);
  the base gives the rest, as ``@dataclass`` would: equality with a record of the same class only,
  ``Name(field=value, ...)`` as repr, and for :class:`Frozen` immutability, a hash and pickling
  through the constructor.
"""

from __future__ import annotations

from types import FunctionType

try:
    from _collections import _tuplegetter      # what collections.namedtuple's fields are
except ImportError:                             # (other Pythons)
    from operator import itemgetter as _itemgetter

    def _tuplegetter(index, doc):
        return property(_itemgetter(index), doc=doc)

_tuple_new = tuple.__new__
_NEW_CODE: dict = {}        # arity -> the code of ``lambda _cls, _0, _1...: _tuple_new(_cls, (_0, _1...))``


def _constructor(qualname: str, names: tuple, defaults: tuple) -> FunctionType:
    """``__new__(cls, <names>)`` with ``defaults`` for the last fields. Compiling a constructor is
    what makes a NamedTuple slow to define, so one is compiled per arity and given each class's
    field names (a code object's local names are its parameters' names). The compiled text is ours
    alone: only the number of fields varies, as in collections.namedtuple."""
    code = _NEW_CODE.get(len(names))
    if code is None:
        args = "".join(f"_{i}, " for i in range(len(names)))
        code = _NEW_CODE[len(names)] = eval(f"lambda _cls, {args}: _tuple_new(_cls, ({args}))",
                                            {"_tuple_new": _tuple_new}).__code__
    new = FunctionType(code.replace(co_varnames=("_cls", *names)), {"_tuple_new": _tuple_new}, "__new__",
                       defaults or None)
    new.__qualname__ = f"{qualname}.__new__"
    return new


class _StructType(type):
    def __new__(mcls, name, bases, ns):
        ns.setdefault("__slots__", ())
        ann = ns.get("__annotations__")
        if ann is None and "__annotate__" in ns:        # Python 3.14: annotations evaluated on demand
            ann = ns["__annotate__"](1)
        if not ann or "_fields" in ns:                  # Struct itself, or a subclass adding methods only
            return super().__new__(mcls, name, bases, ns)
        names, defaults = tuple(ann), {}
        for i, n in enumerate(names):
            if n in ns:
                defaults[n] = ns[n]
            elif defaults:
                raise TypeError(f"{name}: field {n} without a default follows a field with one")
            ns[n] = _tuplegetter(i, None)
        ns.update(_fields=names, _field_defaults=defaults, __match_args__=names,
                  __new__=_constructor(ns.get("__qualname__", name), names, tuple(defaults.values())))
        return super().__new__(mcls, name, bases, ns)


class Struct(tuple, metaclass=_StructType):
    """An immutable record with named fields, as ``typing.NamedTuple`` declares and behaves::

        class Pose(Struct):
            xyz: Vec3 = (0.0, 0.0, 0.0)
            rpy: Vec3 = (0.0, 0.0, 0.0)

    Like tuples, two structs compare by value, not by type."""

    __slots__ = ()
    _fields: tuple = ()
    _field_defaults: dict = {}

    def __repr__(self) -> str:
        return f"{self.__class__.__name__}({', '.join([f'{n}={v!r}' for n, v in zip(self._fields, self)])})"

    def __getnewargs__(self) -> tuple:
        return tuple(self)

    @classmethod
    def _make(cls, iterable):
        return cls(*iterable)

    def _replace(self, **changes):
        new = self.__class__(*map(changes.pop, self._fields, self))
        if changes:
            raise TypeError(f"unexpected field names: {list(changes)!r}")
        return new

    def _asdict(self) -> dict:
        return dict(zip(self._fields, self))


set_field = object.__setattr__      # how a Frozen record's __init__ fills its fields


class Record:
    """A mutable record, compared by value (so unhashable)."""

    __slots__ = ()

    def _values(self) -> tuple:
        return tuple([getattr(self, n) for n in self.__slots__])

    def __eq__(self, other):
        if other.__class__ is self.__class__:
            return self._values() == other._values()
        return NotImplemented

    __hash__ = None

    def __repr__(self) -> str:
        return f"{self.__class__.__qualname__}({', '.join(f'{n}={getattr(self, n)!r}' for n in self.__slots__)})"


class Frozen(Record):
    """An immutable record, hashed by its fields (a dict field makes it unhashable)."""

    __slots__ = ()

    def __setattr__(self, name, value):
        raise AttributeError(f"cannot assign to field '{name}'")

    def __delattr__(self, name):
        raise AttributeError(f"cannot delete field '{name}'")

    def __hash__(self):
        return hash(self._values())

    def __reduce__(self):
        return (self.__class__, self._values())
