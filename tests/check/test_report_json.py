"""checks/report._dumps_safe writes what ``json.dumps(_json_safe(doc), indent=2, ensure_ascii=False)``
writes (json's indenting encoder is pure Python and was most of a 40,000-finding report's time), on
real reports and on the awkward values a hostile model can put in one."""

from __future__ import annotations

import json

import pytest

from helpers import ERD, WANDER, invoke
from myrabot_desc.checks.report import _dumps_safe, _json_safe


def _ref(doc) -> str:
    return json.dumps(_json_safe(doc), indent=2, ensure_ascii=False)


AWKWARD = [
    {},
    [],
    {"a": [], "b": {}, "c": [[]], "d": [{}]},
    {"nan": float("nan"), "inf": float("inf"), "-inf": float("-inf"), "f": 0.1, "z": -0.0, "big": 1e308,
     "i": 10 ** 30, "t": True, "f2": False, "n": None},
    {"tuple": (1, "x\u202e", [2]), "list": ["x\u202e", ("\x1b[31m",)]},
    {"text": "quote \" back \\ nl \n tab \t bell \x07 rtl \u202e esc \x1b[2J emoji \U0001F600 lone \udc80"},
    {"key \u202e with rtl": 1},
    {1: "int key", "a": 2},
    {"a": "same", "a\u202e": "becomes the same key once cleaned?"},
    {"deep": [[[[{"x": [1, 2.5, "s"]}]]]]},
]


@pytest.mark.parametrize("doc", AWKWARD, ids=range(len(AWKWARD)))
def test_same_text_as_json_dumps(doc):
    assert _dumps_safe(doc) == _ref(doc)


@pytest.mark.parametrize("fmt", ["json", "sarif"])
def test_real_reports_parse_and_are_json_dumps_text(fmt, tmp_path):
    files = [str(WANDER / "urdf" / "robot.xacro"), "-p", f"wander_bot={WANDER}",
             str(ERD / "talos_data/robots/talos_reduced.urdf")]
    r = invoke("check", "--no-cache", "--inertia", "--format", fmt, *files)
    assert r.exit_code in (0, 1), r.output[-2000:]
    doc = json.loads(r.stdout)
    assert r.stdout == _ref(doc) + "\n"          # what json.dumps writes of what it reads back
    assert _dumps_safe(doc) == _ref(doc)
