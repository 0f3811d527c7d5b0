"""What a rule module needs: :class:`Finding`, :class:`Rule`, :class:`Example` and the :func:`rule` decorator.

A rule is a function ``f(ctx) -> Iterable[Finding]`` decorated with :func:`rule`. The
decorator only attaches a :class:`Rule` to the function (``f.rule``); it registers
nothing. ``checks/registry.py`` imports the rule modules and collects them, so no rule
module imports the registry (no import knot).

Each rule carries its example next to it (ruff's "what, why, example, fix"): ``bad``
is a URDF (or xacro) that makes the rule fire with ``message``, ``good`` the fixed
version that keeps it quiet. Either is a whole document (it starts with ``<?xml`` or
``<robot``) or a snippet that :func:`document` places into :data:`TEMPLATE`, a minimal
robot of one link. tests/check/test_rule_examples.py runs every example through ``check``,
and docs/rules.md is generated from them (``python -m myrabot_desc.checks.docs``).

The records are :mod:`myrabot_desc.records`' (not dataclasses, whose definition every ``check``
would pay at start): immutable and equal only to a record of their own class, as the frozen
dataclasses they were; not NamedTuples, under which a fix's InsertInto and InsertAfter of the same
text would be equal.
"""

from __future__ import annotations

from collections.abc import Callable

from myrabot_desc.records import Frozen, Record
from myrabot_desc.records import set_field as _set

FAMILIES = {
    "X": "build (xacro)",
    "T": "tree and URDF syntax",
    "I": "inertia",
    "S": "sensors and frames",
    "G": "Gazebo and plugins",
    "M": "meshes",
    "P": "physics and stability",
}

# The robot a snippet example is placed in: one link with a valid mass and inertia and no
# geometry, so the snippet alone decides what fires. "{snippet}" is replaced, indented.
TEMPLATE = """<?xml version="1.0"?>
<robot name="example" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="base_link">
    <inertial>
      <mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>
    </inertial>
  </link>
{snippet}
</robot>
"""


def is_document(text: str) -> bool:
    s = text.lstrip()
    return s.startswith("<?xml") or s.startswith("<robot")


def document(text: str) -> str:
    """The whole file for an example: the text itself, or the snippet inside TEMPLATE."""
    if is_document(text):
        return text if text.endswith("\n") else text + "\n"
    body = "\n".join(("  " + line) if line.strip() else "" for line in text.strip("\n").splitlines())
    return TEMPLATE.replace("{snippet}", body)


class Example(Frozen):
    """A rule's example: ``bad`` fires with ``message``; ``good`` is quiet for the code."""

    __slots__ = ("bad", "message", "good", "options", "files", "filename", "note")

    def __init__(self, bad: str,
                 message: str,                    # as check prints it after "CODE " (numbers included)
                 good: str | None = None,         # None: nothing to show (a summary such as P004)
                 options: tuple = (),             # CheckOptions flags the example needs: "inertia", "meshes"
                 files: dict | None = None,       # extra files next to the model: name -> text (default {})
                 filename: str = "robot.urdf",    # the model's file name ("robot.urdf.xacro" for xacro)
                 note: str = ""):                 # one line shown with the example (what the extra files are)
        _set(self, "bad", bad)
        _set(self, "message", message)
        _set(self, "good", good)
        _set(self, "options", options)
        _set(self, "files", {} if files is None else files)
        _set(self, "filename", filename)
        _set(self, "note", note)


# ---------------------------------------------------------------- fixes
# A rule says what would repair a finding in terms of the model (set this field of this part to this
# value, remove this attribute...); `check --fix` (fix/) finds where each value was written
# (Robot.sources) and edits the source there. The intents hold model parts, never file positions.

class FixInfo(Frozen):
    """A rule's documented fix: ``availability`` always | sometimes | never; ``safety`` safe |
    unsafe (what ``--fix`` alone applies, as ruff: safe fixes keep the model's meaning or restore one
    the model states elsewhere); ``how``: what is edited, and why it is safe or not."""

    __slots__ = ("availability", "safety", "how")

    def __init__(self, availability: str, safety: str, how: str):
        _set(self, "availability", availability)
        _set(self, "safety", safety)
        _set(self, "how", how)


NO_FIX = FixInfo("never", "", "")


class SetValue(Frozen):
    """Set ``field`` of model ``part`` (see model/sources.FIELDS; a plugin's parameter by name) to
    ``value``: a number, a tuple of numbers or a text."""

    __slots__ = ("part", "field", "value")

    def __init__(self, part: object, field: str, value: object):
        _set(self, "part", part)
        _set(self, "field", field)
        _set(self, "value", value)


class RemoveAttribute(Frozen):
    """Remove attribute ``attr`` of the URDF element ``ref`` (where it is written)."""

    __slots__ = ("ref", "attr")

    def __init__(self, ref: object, attr: str):
        _set(self, "ref", ref)
        _set(self, "attr", attr)


class RemoveElement(Frozen):
    """Remove the child element ``field`` of ``part`` (a plugin parameter: its name), or the part's own
    element when ``field`` is None."""

    __slots__ = ("part", "field")

    def __init__(self, part: object, field: str | None = None):
        _set(self, "part", part)
        _set(self, "field", field)


class RenameTag(Frozen):
    """Rename the URDF element ``ref`` (start and end tag) to ``tag``."""

    __slots__ = ("ref", "tag")

    def __init__(self, ref: object, tag: str):
        _set(self, "ref", ref)
        _set(self, "tag", tag)


class RenameAttribute(Frozen):
    """Rename attribute ``attr`` of the URDF element ``ref`` to ``new`` (its value stays)."""

    __slots__ = ("ref", "attr", "new")

    def __init__(self, ref: object, attr: str, new: str):
        _set(self, "ref", ref)
        _set(self, "attr", attr)
        _set(self, "new", new)


class InsertInto(Frozen):
    """Append the XML ``text`` as the last child of ``part``'s element, at its children's indentation."""

    __slots__ = ("part", "text")

    def __init__(self, part: object, text: str):
        _set(self, "part", part)
        _set(self, "text", text)


class InsertAfter(Frozen):
    """Insert the XML ``text`` after ``part``'s element, in the same file, at its indentation."""

    __slots__ = ("part", "text")

    def __init__(self, part: object, text: str):
        _set(self, "part", part)
        _set(self, "text", text)


class Fix(Frozen):
    """What repairs one finding: its edits, applied together or not at all."""

    __slots__ = ("edits", "safety", "title")

    def __init__(self, edits: tuple,
                 safety: str = "safe",            # safe | unsafe
                 title: str = ""):                # "wheelSeparation 0.4 -> 0.3"
        _set(self, "edits", edits)
        _set(self, "safety", safety)
        _set(self, "title", title)


class LazyFix:
    """A :class:`Fix` made by ``build(*args)`` when first read, and read as that Fix: for a rule that
    can find every link of a large model (I006), whose edits only ``--fix`` and ``--diff`` read."""

    __slots__ = ("_build", "_args", "_fix")

    def __init__(self, build: Callable[..., Fix], *args):
        self._build, self._args, self._fix = build, args, None

    def get(self) -> Fix:
        if self._fix is None:
            self._fix = self._build(*self._args)
        return self._fix

    edits = property(lambda self: self.get().edits)
    safety = property(lambda self: self.get().safety)
    title = property(lambda self: self.get().title)


class Finding(Record):
    """What a rule yields: the message with the numbers, where, and machine data."""

    __slots__ = ("message", "loc", "data", "severity", "fix")

    def __init__(self, message: str,
                 loc: object = None,              # diagnostics.Loc or None
                 data: dict | None = None,        # (default {})
                 severity: str | None = None,     # overrides the rule's default (documented per rule)
                 fix: Fix | LazyFix | None = None):   # how --fix repairs it, when the rule knows
        self.message = message
        self.loc = loc
        self.data = {} if data is None else data
        self.severity = severity
        self.fix = fix


class Rule(Frozen):
    __slots__ = ("code", "name", "severity", "func", "example", "needs", "summary", "fix")

    def __init__(self, code: str,
                 name: str,                       # kebab-case, e.g. "inertia-triangle"
                 severity: str,                   # default severity: error | warning | info
                 func: Callable,
                 example: Example,
                 needs: str | None = None,        # 'meshes' (loads mesh files) or None
                 summary: str = "",
                 fix: FixInfo = NO_FIX):
        _set(self, "code", code)
        _set(self, "name", name)
        _set(self, "severity", severity)
        _set(self, "func", func)
        _set(self, "example", example)
        _set(self, "needs", needs)
        _set(self, "summary", summary)
        _set(self, "fix", fix)

    @property
    def doc(self) -> str:
        return (self.func.__doc__ or "").strip()


def rule(code: str, name: str, severity: str, *, bad: str, message: str, good: str | None,
         needs: str | None = None, options: tuple = (), files: dict | None = None,
         filename: str = "robot.urdf", note: str = "", fix: FixInfo = NO_FIX):
    """Mark ``func`` as rule ``code`` with its example (see the module docstring) and its fix."""

    def deco(func):
        summary = (func.__doc__ or "").strip().splitlines()[0] if func.__doc__ else name
        ex = Example(bad, message, good, tuple(options), dict(files or {}), filename, note)
        func.rule = Rule(code, name, severity, func, ex, needs, summary, fix)
        return func

    return deco
