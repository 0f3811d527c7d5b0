"""Every rule's documented example, run through `check`: the bad one fires with its code and the
message docs/rules.md prints, the good one is quiet for that code.

The examples live next to each rule (the @rule decorator) and, for codes raised by the build or
the reader, in checks/external.py; docs/rules.md is generated from the same objects.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from helpers import ROOT
from myrabot_desc.checks import CheckOptions, check_robot
from myrabot_desc.checks.external import EXTERNAL_RULES
from myrabot_desc.checks.registry import RULES
from myrabot_desc.checks.rule import document
from myrabot_desc.commands.main import main
from myrabot_desc.errors import InputError
from myrabot_desc.model.loader import load_robot

EXAMPLES = {**{c: r.example for c, r in RULES.items()}, **{c: r.example for c, r in EXTERNAL_RULES.items()}}


def write(tmp_path: Path, ex, which: str) -> Path:
    """The example's model (and its extra files) under tmp_path/which; returns that folder."""
    folder = tmp_path / which
    for name, text in ex.files.items():
        f = folder / name
        f.parent.mkdir(parents=True, exist_ok=True)
        f.write_text(text)
    model = folder / ex.filename
    model.parent.mkdir(parents=True, exist_ok=True)
    model.write_text(document(ex.bad if which == "bad" else ex.good))
    return folder


def run(folder: Path, ex, monkeypatch):
    """(diagnostics, failure line): the library calls `check` makes, run in the example's folder
    so that paths in messages are as short as the docs show them."""
    monkeypatch.chdir(folder)
    opts = CheckOptions(**{o: True for o in ex.options})
    try:
        robot = load_robot(Path(ex.filename))
    except InputError as exc:
        return [], str(exc).splitlines()[0]
    return check_robot(robot, opts)[0], None


def messages(diags, failure, code):
    got = [d.message for d in diags if d.code == code]
    if failure and (code == "X000" or f"error: {code} " in failure):
        got.append(failure.split(f"error: {code} ", 1)[-1] if code != "X000" else failure)
    return got


def test_every_code_has_an_example():
    assert set(EXAMPLES) == set(RULES) | set(EXTERNAL_RULES)
    for code, ex in EXAMPLES.items():
        assert ex.bad and ex.message, code


@pytest.mark.parametrize("code", sorted(EXAMPLES))
def test_bad_example_fires_with_its_message(code, tmp_path, monkeypatch):
    ex = EXAMPLES[code]
    diags, failure = run(write(tmp_path, ex, "bad"), ex, monkeypatch)
    got = messages(diags, failure, code)
    assert ex.message in got, (code, got, failure, [str(d) for d in diags])


@pytest.mark.parametrize("code", sorted(c for c, ex in EXAMPLES.items() if ex.good is not None))
def test_good_example_is_quiet(code, tmp_path, monkeypatch):
    ex = EXAMPLES[code]
    diags, failure = run(write(tmp_path, ex, "good"), ex, monkeypatch)
    assert failure is None, failure
    assert messages(diags, failure, code) == [], (code, [str(d) for d in diags if d.code == code])


@pytest.mark.parametrize("code", ["I005", "S006", "T017", "M003", "X000"])
def test_cli_prints_the_documented_line(code, tmp_path, monkeypatch):
    """The command line prints the same code and message (json report, or the failure line)."""
    ex = EXAMPLES[code]
    monkeypatch.chdir(write(tmp_path, ex, "bad"))
    flags = [f"--{o}" for o in ex.options]
    res = CliRunner().invoke(main, ["check", "--format", "json", *flags, ex.filename])
    doc = json.loads(res.stdout)
    (f,) = doc["files"]
    if code == "X000":
        assert res.exit_code == 2 and f["failure"] == ex.message
        return
    hits = [d for d in f["diagnostics"] if d["code"] == code]
    assert ex.message in [d["message"] for d in hits]
    assert res.exit_code == (1 if any(d["severity"] == "error" for d in f["diagnostics"]) else 0)
    # the documented finding carries the severity its rule declares (these rules override none)
    assert {d["severity"] for d in hits if d["message"] == ex.message} == {RULES[code].severity}


def test_docs_show_each_example_as_tested():
    """docs/rules.md is generated from these examples (python -m myrabot_desc.checks.docs)."""
    from myrabot_desc.checks.docs import render

    text = (ROOT / "docs" / "rules.md").read_text()
    assert text == render(), "regenerate: python -m myrabot_desc.checks.docs > docs/rules.md"
    for code, ex in EXAMPLES.items():
        section = text.split(f"### {code}\n", 1)[1].split("\n### ", 1)[0]
        assert ex.bad.rstrip("\n") in section and ex.message in section, code
