"""Small records without dataclasses.

A dataclass compiles its generated methods when it is defined (~0.6 ms a class), which every
command would pay at start for records it may never build. A record here declares its fields as
``__slots__`` (in constructor order) and writes its own ``__init__`` (defaults, a new list or dict
per instance); the base gives the rest, as ``@dataclass`` would: equality with a record of the same
class only, ``Name(field=value, ...)`` as repr, and for :class:`Frozen` immutability, a hash and
pickling through the constructor.
"""

from __future__ import annotations

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
