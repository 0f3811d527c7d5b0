"""The one parser for the numbers, vectors and booleans a robot description writes as text.

The loader (URDF attributes), the plugins' parameters (model/drive.py), the ``<gazebo>``
properties, the sensors, check's rules and convert all read values through these functions, so
that one text means one value everywhere, and a value that cannot be read is said in one
wording: ``<TAG ATTR="TEXT">: not a number`` (an attribute), ``<TAG>TEXT</TAG>: not a number``
(an element's text); the reasons are ``NOT_A_NUMBER``, ``NOT_FINITE``, ``expected(n)``,
``out_of_range(limit)``.

Numbers are Python's ``float`` of the stripped text, finite only (a NaN or an infinity in a
simulator's input is an error there too). Vectors are numbers separated by white space.

Booleans: which spellings mean true depends on the program that reads the value, and we follow
each one's source (sdformat, https://github.com/gazebosim/sdformat):

* ``SDF`` -- an SDF element's value (a sensor's ``<always_on>``, a plugin parameter read with
  ``sdf::Element::Get<bool>``, as gazebo_ros plugins read ``legacyMode`` or
  ``publishWheelJointState``): ``src/Param.cc`` lowercases the trimmed text and takes ``true``
  or ``1`` as true, ``false`` or ``0`` as false; anything else is an error ("Invalid boolean
  value") and the plugin gets ``false``.
* ``EXTENSION`` -- a URDF ``<gazebo>`` extension flag (``selfCollide``, ``preserveFixedJoint``,
  ``disableFixedJointLumping``, ``provideFeedback``, ``implicitSpringDamper``, ``static``...):
  ``src/parser_urdf.cc`` takes ``true`` or ``yes`` (any case) or ``1`` as true and anything
  else as false (``turnGravityOff`` the other way round: ``false``, ``no`` or ``0`` keep
  gravity, anything else turns it off). ``on``/``off`` mean nothing to either.

Pure Python (convert imports it without numpy).
"""

from __future__ import annotations

import math

NOT_A_NUMBER = "not a number"
NOT_FINITE = "not a finite number"

# spelling tables: (true spellings, false spellings), compared with the lowercased stripped text
SDF = (frozenset({"true", "1"}), frozenset({"false", "0"}))
EXTENSION = (frozenset({"true", "yes", "1"}), frozenset({"false", "no", "0"}))


def expected(n: int | None, finite: bool = False) -> str:
    return f"expected {n} {'finite ' if finite else ''}numbers" if n else "expected numbers"


def out_of_range(limit: float) -> str:
    return f"out of range (more than {limit:g} in magnitude)"


class ValueProblem(ValueError):
    """A text that is not the value asked for; ``reason`` is one of the module's wordings."""

    def __init__(self, reason: str):
        super().__init__(reason)
        self.reason = reason


def where(tag: str, text: str, attr: str | None = None) -> str:
    """How a value is shown in a message: ``<tag attr="text">`` or ``<tag>text</tag>``."""
    return f'<{tag} {attr}="{text}">' if attr else f"<{tag}>{text}</{tag}>"


def problem(tag: str, text: str, reason: str, attr: str | None = None) -> str:
    """The one wording of an unreadable value: ``<mass value="x">: not a number``."""
    return f"{where(tag, text, attr)}: {reason}"


# ------------------------------------------------------------------ numbers
def parse_number(text, limit: float | None = None) -> float:
    """The number written in ``text``; ValueProblem when it is not one, not finite, or beyond
    ``limit`` in magnitude."""
    try:
        v = float(text if isinstance(text, str) else str(text))
    except (TypeError, ValueError):
        raise ValueProblem(NOT_A_NUMBER) from None
    if not math.isfinite(v):
        raise ValueProblem(NOT_FINITE)
    if limit is not None and abs(v) > limit:
        raise ValueProblem(out_of_range(limit))
    return v


def number(text, default=None):
    """The number in ``text``, or ``default`` when there is no text or it is not a finite number."""
    if text is None:
        return default
    try:
        return parse_number(text)
    except ValueProblem:
        return default


def parse_vector(text, n: int | None = None, limit: float | None = None) -> tuple[float, ...]:
    """The numbers of ``text`` (white-space separated); ``n``: how many there must be."""
    try:
        vals = tuple(map(float, (text if isinstance(text, str) else str(text)).split()))
    except (TypeError, ValueError):
        raise ValueProblem(expected(n)) from None
    if (n is not None and len(vals) != n) or not all(map(math.isfinite, vals)):
        raise ValueProblem(expected(n, finite=True))
    if limit is not None and vals and max(map(abs, vals)) > limit:
        raise ValueProblem(out_of_range(limit))
    return vals


def vector(text, n: int | None = None, default=None):
    """The numbers of ``text``, or ``default`` when absent, unreadable or not ``n`` of them."""
    if text is None:
        return default
    try:
        return parse_vector(text, n)
    except ValueProblem:
        return default


# ------------------------------------------------------------------ booleans
def boolean(text, default=None, spellings=SDF):
    """True or False as the program that reads the value spells it (``SDF`` or ``EXTENSION``, see
    the module doc); ``default`` when there is no text or it is neither."""
    if text is None:
        return default
    t = str(text).strip().lower()
    yes, no = spellings
    if t in yes:
        return True
    if t in no:
        return False
    return default


def extension_flag(text, default=None, inverted: bool = False):
    """A ``<gazebo>`` extension flag as sdformat's URDF parser reads it: any value it does not
    spell as false is true for ``turnGravityOff`` (``inverted``), any it does not spell as true
    is false for the others; ``default`` when the flag is not given."""
    if text is None:
        return default
    b = boolean(text, None, EXTENSION)
    if b is None:
        return inverted
    return b
