"""records.py: the records every layer builds, in place of dataclasses and typing.NamedTuple."""

import copy
import pickle
import re
from pathlib import Path
from typing import NamedTuple

import pytest

import myrabot_desc
from myrabot_desc.model.parts import Inertial, Pose, Visual
from myrabot_desc.records import Frozen, Record, Struct, set_field


class Point(Struct):
    x: float
    y: float = 0.0
    label: str | None = None
    kind = "point"                  # not annotated: a class attribute, not a field

    @property
    def norm1(self) -> float:
        return abs(self.x) + abs(self.y)


class Named(Point):
    def shout(self) -> str:
        return (self.label or "").upper()


class PointNT(NamedTuple):          # the behaviour a Struct keeps
    x: float
    y: float = 0.0
    label: str | None = None


def test_a_struct_is_built_and_read_as_a_namedtuple():
    for cls in (Point, PointNT):
        p = cls(1.0, label="a")
        assert (p.x, p.y, p.label) == (1.0, 0.0, "a")
        assert p == (1.0, 0.0, "a") and hash(p) == hash((1.0, 0.0, "a"))
        assert cls(x=2.0, y=3.0) == cls(2.0, 3.0)
        assert p._replace(y=5.0) == cls(1.0, 5.0, "a")
        assert p._asdict() == {"x": 1.0, "y": 0.0, "label": "a"}
        assert cls._fields == ("x", "y", "label")
        assert cls._field_defaults == {"y": 0.0, "label": None}
        assert cls._make([1, 2, "b"]) == cls(1, 2, "b")
        assert repr(p) == f"{cls.__name__}(x=1.0, y=0.0, label='a')"
        x, y, label = p
        assert (x, y, label) == (1.0, 0.0, "a")


def test_a_struct_is_immutable_and_has_no_instance_dict():
    p = Point(1.0)
    with pytest.raises(AttributeError):
        p.x = 2.0
    with pytest.raises(AttributeError):
        p.extra = 1
    with pytest.raises(AttributeError):
        Named(1.0).extra = 1          # a subclass adding methods keeps __slots__ = ()


def test_a_struct_keeps_its_methods_class_attributes_and_errors():
    assert Point(3.0, -4.0).norm1 == 7.0
    assert Point.kind == Point(0.0).kind == "point"
    assert Named(1.0, 2.0, "hi").shout() == "HI" and Named._fields == Point._fields
    with pytest.raises(TypeError, match="missing 1 required positional argument: 'x'"):
        Point()
    with pytest.raises(TypeError, match="unexpected keyword argument 'z'"):
        Point(1.0, z=2.0)
    with pytest.raises(TypeError, match="unexpected field names"):
        Point(1.0)._replace(z=1)
    with pytest.raises(TypeError, match="field b without a default follows"):
        class Bad(Struct):
            a: int = 0
            b: int
    match Point(1.0, 2.0):
        case Point(a, b):
            assert (a, b) == (1.0, 2.0)


def test_a_struct_pickles_and_copies_as_itself():
    for p in (Point(1.0, 2.0, "a"), Named(1.0), Pose((1.0, 2.0, 3.0)),
              Inertial(2.0, Pose(), ixx=1.0, izz=3.0)):
        for q in (pickle.loads(pickle.dumps(p)), copy.copy(p), copy.deepcopy(p)):
            assert q == p and type(q) is type(p)


def test_the_models_structs_take_each_field_by_name_and_by_position():
    # the constructor is the per-arity one given the class's field names: each value lands in its field
    values = [object() for _ in Visual._fields]
    for v in (Visual(*values), Visual(**dict(zip(Visual._fields, values)))):
        assert [getattr(v, n) for n in Visual._fields] == values == list(v)
    assert Inertial(1.0, Pose()).ixx == 0.0 and Inertial(1.0, Pose(), izz=2.0).izz == 2.0


class Box(Record):
    __slots__ = ("w", "items")

    def __init__(self, w, items=None):
        self.w = w
        self.items = [] if items is None else items


class Key(Frozen):
    __slots__ = ("a", "b")

    def __init__(self, a, b=0):
        set_field(self, "a", a)
        set_field(self, "b", b)


class OtherKey(Frozen):
    __slots__ = ("a", "b")

    def __init__(self, a, b=0):
        set_field(self, "a", a)
        set_field(self, "b", b)


def test_records_compare_by_class_and_value():
    assert Box(1) == Box(1, []) and Box(1) != Box(2)
    assert repr(Box(1, [2])) == "Box(w=1, items=[2])"
    with pytest.raises(TypeError):
        hash(Box(1))
    b = Box(1)
    b.w = 3                            # a Record is mutable
    assert b.w == 3
    assert Key(1) == Key(1, 0) and hash(Key(1)) == hash(Key(1, 0))
    assert Key(1) != OtherKey(1)       # unlike Structs: a record of another class is never equal
    with pytest.raises(AttributeError, match="cannot assign to field 'a'"):
        Key(1).a = 2
    assert pickle.loads(pickle.dumps(Key(1, 2))) == Key(1, 2)


def test_the_package_declares_its_tuples_here():
    """No typing.NamedTuple or collections.namedtuple: each compiles a constructor when its class is
    defined, which every command's start pays. (Dataclasses, which do too, are kept off check's path
    by tests/check/test_lean_rules.py; sim and convert still define some.)"""
    pattern = re.compile(r"\(\s*NamedTuple\s*\)|\bnamedtuple\(")
    found = [f"{p.name}: {m.group(0).strip()}" for p in Path(myrabot_desc.__file__).parent.rglob("*.py")
             for m in pattern.finditer(p.read_text(encoding="utf-8"))]
    assert found == []
