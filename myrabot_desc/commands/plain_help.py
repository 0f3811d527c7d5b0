"""``myrabot-desc --help`` without importing click (a third of the command's start-up).

The text is the click group's own help, rendered by click and stored in commands/help_text.py.
Click draws help at the terminal's width capped at 80 columns, so on any terminal of 80 columns
or more (and when stdout is not a terminal: click's fallback is 80) the stored text is exactly
what click prints; a narrower terminal goes to click. tests/expand/test_plain_help.py renders
the help with click and compares; after changing the group's docstring, epilog, options, a
command's one-line help or a limit, regenerate the stored text with

    .venv/bin/python -m myrabot_desc.commands.main --write-help
"""

from __future__ import annotations

import os
import sys

from myrabot_desc.commands import help_text

WIDTH = 80        # click's max_content_width default: wider terminals get the same text


def columns() -> int:
    """The terminal width as click asks it (shutil.get_terminal_size, without importing shutil):
    COLUMNS when it is a positive number, else the size of stdout's terminal, else 80."""
    try:
        cols = int(os.environ["COLUMNS"])
    except (KeyError, ValueError):
        cols = 0
    if cols <= 0:
        try:
            cols = os.get_terminal_size(sys.__stdout__.fileno()).columns
        except (AttributeError, ValueError, OSError):
            cols = 0
    return cols or WIDTH


def top_help() -> str | None:
    """The top-level help text, or None when click must draw it (a terminal under 80 columns)."""
    return help_text.TEXT if columns() >= WIDTH else None
