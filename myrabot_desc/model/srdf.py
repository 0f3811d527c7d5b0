"""An SRDF (MoveIt's semantic robot description) as the model's own statements next to the URDF: which
link pairs may touch (``<disable_collisions>``, ``<disable_default_collisions>`` with its
``<enable_collisions>``) and its named reference configurations (``<group_state>``: example-robot-data
ships ``half_sitting`` and ``standing`` ones, which Pinocchio users load with
``loadReferenceConfigurations``).

The file is untrusted like a model: it is read through ``safety.read_checked`` (a regular file, the
input size limit) and parsed by ``xmltree.parse_safely`` (expat, with the checks and the verdicts of
``safety.parse_xml_bytes``: no DTD, entities or network). Each statement keeps the file:line it was
written at.
"""

from myrabot_desc.diagnostics import Loc
from myrabot_desc.errors import InputError
from myrabot_desc.records import Struct
from myrabot_desc.safety import display, limit, read_checked
from myrabot_desc.xmltree import parse_safely


class Disabled(Struct):
    """A link pair the SRDF lets touch, with its reason ("Adjacent", "Never", "Default"...)."""

    link1: str
    link2: str
    reason: str
    loc: Loc


class State(Struct):
    """A ``<group_state>``: joint name -> value (a tuple for a multi-valued joint such as a
    floating ``root_joint``: x y z qx qy qz qw)."""

    name: str
    group: str
    joints: dict
    loc: Loc


class Srdf(Struct):
    path: str
    disabled: dict            # frozenset({link1, link2}) -> Disabled
    never: dict               # link -> Loc of <disable_default_collisions link=...>
    enabled: frozenset        # frozenset({link1, link2}) pairs <enable_collisions> turns back on
    states: dict              # name -> State (the first of a name wins, as MoveIt reads them)

    @property
    def describes_collisions(self) -> bool:
        """It says which pairs may touch (an SRDF holding only group states says nothing about it)."""
        return bool(self.disabled or self.never or self.enabled)

    def allows(self, a: str, b: str) -> Disabled | None:
        """The statement that lets links ``a`` and ``b`` touch, or None."""
        pair = frozenset((a, b))
        d = self.disabled.get(pair)
        if d is not None:
            return d
        if pair in self.enabled:
            return None
        for link in (a, b):
            if link in self.never:
                return Disabled(a, b, f"disable_default_collisions of {link}", self.never[link])
        return None

    def state(self, name: str) -> State:
        s = self.states.get(name)
        if s is None:
            known = ", ".join(sorted(self.states)) or "none"
            raise InputError(f"no group_state named '{name}' in the SRDF (it has: {known})", Loc(self.path))
        return s


def _local(tag) -> str:
    return tag.rsplit("}", 1)[-1] if isinstance(tag, str) else ""


def _values(text: str | None, loc: Loc):
    parts = (text or "").split()
    try:
        vals = tuple(float(p) for p in parts)
    except ValueError:
        raise InputError(f"joint value {text!r} is not a number", loc) from None
    if not vals:
        raise InputError("joint without a value", loc)
    return vals[0] if len(vals) == 1 else vals


def load_srdf(path) -> Srdf:
    """Read an SRDF file; InputError (file:line) for a file that is not one."""
    name = display(path)
    data = read_checked(path, None, limit("max_input_bytes"), what="SRDF file")
    root = parse_safely(data, name)
    if _local(root.tag) != "robot":
        raise InputError(f"not an SRDF: the root element is <{_local(root.tag)}>, not <robot>",
                         Loc(name, root.sourceline))
    disabled, never, enabled, states = {}, {}, set(), {}
    for el in root:
        tag = _local(el.tag)
        loc = Loc(name, el.sourceline)
        if tag in ("disable_collisions", "enable_collisions"):
            a, b = el.get("link1"), el.get("link2")
            if not a or not b:
                raise InputError(f"<{tag}> needs link1 and link2", loc)
            if tag == "enable_collisions":
                enabled.add(frozenset((a, b)))
            else:
                disabled.setdefault(frozenset((a, b)), Disabled(a, b, el.get("reason") or "", loc))
        elif tag == "disable_default_collisions":
            if el.get("link"):
                never.setdefault(el.get("link"), loc)
        elif tag == "group_state":
            sname = el.get("name")
            if not sname:
                raise InputError("<group_state> without a name", loc)
            joints = {}
            for j in el:
                if _local(j.tag) == "joint" and j.get("name"):
                    joints[j.get("name")] = _values(j.get("value"), Loc(name, j.sourceline))
            states.setdefault(sname, State(sname, el.get("group") or "", joints, loc))
    return Srdf(name, disabled, never, frozenset(enabled), states)
