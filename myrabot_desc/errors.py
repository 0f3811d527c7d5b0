"""The one error type for input that cannot be processed (exit code 2), and the one for options
that parse but do not make sense together (the command line shows it as a usage error)."""

from __future__ import annotations

from myrabot_desc.diagnostics import Loc
from myrabot_desc.sanitize import clean


class InputError(Exception):
    """Bad or unprocessable input. Rendered as ``file:line: error: message``.

    ``stack`` holds extra context lines (for example the macro call stack).
    """

    def __init__(self, message: str, loc: Loc | None = None, stack: list[str] | None = None,
                 code: str | None = None, more: list | None = None):
        super().__init__(message)
        self.message = message
        self.loc = loc
        self.stack = stack or []
        self.code = code
        self.more = more or []          # further errors of the same input, each its own line

    def __str__(self) -> str:
        # the message and location quote model text and file names: one printable line each
        where = f"{clean(self.loc)}: " if self.loc else ""
        code = f"{clean(self.code)} " if self.code else ""
        text = f"{where}error: {code}{clean(self.message)}"
        for line in self.stack:
            text += f"\n  {clean(line)}"
        for other in self.more:
            text += f"\n{other}"
        return text


class UsageProblem(Exception):
    """Options that parse but do not make sense (the command line shows it as a usage error: click's
    BadParameter when ``param_hint`` names the option, else its UsageError)."""

    def __init__(self, message: str, param_hint: str | None = None):
        super().__init__(message)
        self.param_hint = param_hint
