"""The top-level ``--help`` is printed without click (commands/plain_help.py): the stored text is
exactly what click draws, at every terminal width where click would draw it the same."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from myrabot_desc.commands import help_text, plain_help
from myrabot_desc.commands.main import render_help

CLICK = ("import sys\nfrom myrabot_desc.commands.main import main\n"
         "main(sys.argv[1:], prog_name='myrabot-desc')")
ENTRY = ("import sys\nfrom myrabot_desc.commands.entry import main\nsys.argv[0] = 'myrabot-desc'\n"
         "try:\n    rc = main(sys.argv[1:])\nfinally:\n"
         "    print(sorted(m for m in ('click', 'myrabot_desc.commands.main') if m in sys.modules), file=sys.stderr)\n"
         "sys.exit(rc)")


def _run(code, args, columns):
    env = {**os.environ, "COLUMNS": str(columns)}
    return subprocess.run([sys.executable, "-c", code, *args], capture_output=True, text=True, env=env, timeout=120)


def test_the_stored_text_is_clicks_own():
    assert help_text.TEXT == render_help(), (
        "commands/help_text.py is stale: .venv/bin/python -m myrabot_desc.commands.main --write-help")


@pytest.mark.parametrize("columns", [80, 81, 200])
@pytest.mark.parametrize("flag", ["--help", "-h"])
def test_plain_help_equals_click_and_imports_no_click(flag, columns):
    ours, theirs = _run(ENTRY, [flag], columns), _run(CLICK, [flag], columns)
    assert (ours.returncode, ours.stdout) == (theirs.returncode, theirs.stdout) == (0, help_text.TEXT)
    assert ours.stderr.strip() == "[]"


@pytest.mark.parametrize("columns", [60, 79])
def test_a_narrow_terminal_gets_click_drawing_it(columns):
    ours, theirs = _run(ENTRY, ["--help"], columns), _run(CLICK, ["--help"], columns)
    assert (ours.returncode, ours.stdout) == (theirs.returncode, theirs.stdout)
    assert "click" in ours.stderr
    if columns == 60:
        assert ours.stdout != help_text.TEXT


def test_columns_follows_shutil(monkeypatch):
    import shutil

    for value in ("100", "0", "-3", "x", None):
        if value is None:
            monkeypatch.delenv("COLUMNS", raising=False)
        else:
            monkeypatch.setenv("COLUMNS", value)
        assert plain_help.columns() == shutil.get_terminal_size().columns


@pytest.mark.parametrize("args", [["--help"], ["check", "--help"], ["build"]])
def test_a_full_disk_is_one_line_and_exit_2(args):
    with open("/dev/full", "w") as full:
        p = subprocess.run([sys.executable, "-c", ENTRY, *args], stdout=full, stderr=subprocess.PIPE,
                           text=True, timeout=120)
    assert p.returncode == 2
    assert p.stderr.splitlines()[0] == "error: cannot write the output (No space left on device)", p.stderr
