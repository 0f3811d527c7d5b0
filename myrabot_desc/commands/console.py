"""Terminal output and exit codes without click: one echoed line, and :class:`guarded`, which turns
InputError (and any unexpected error) into one clear line and exit code 2.

Used by every command, the click-free plain ``build`` path (commands/fastbuild.py) included, so
nothing here imports click.
"""

from __future__ import annotations

import errno
import os
import re
import sys

from myrabot_desc.errors import InputError, UsageProblem
from myrabot_desc.sanitize import clean

_FULL = {errno.ENOSPC, errno.EDQUOT, errno.EFBIG}     # a full disk or quota, a file past its size limit
_ANSI = None            # compiled on first use (a plain build rarely prints a style)


def unstyle(text: str) -> str:
    """``text`` without ANSI styles (click.unstyle)."""
    global _ANSI
    if "\033" not in text:
        return text
    if _ANSI is None:
        _ANSI = re.compile(r"\033\[[0-?]*[ -/]*[@-~]")   # click's own pattern (click._compat)
    return _ANSI.sub("", text)


def is_terminal(stream) -> bool:
    """Is ``stream`` a terminal (styles are kept for it only)? False for a closed or odd stream."""
    try:
        return bool(stream.isatty())
    except Exception:
        return False


def _write(stream, text: str) -> None:
    """click.echo's writing: ANSI styles stripped when the stream is not a terminal, flushed."""
    if stream is None:
        return
    stream.write(text if is_terminal(stream) else unstyle(text))
    stream.flush()


def echo(message: str, err: bool = True) -> None:
    """click.echo of one line, without click: a newline added, on stderr unless ``err`` is False."""
    _write(sys.stderr if err else sys.stdout, message + "\n")


def out(text: str) -> None:
    """click.echo(text, nl=False) on stdout: a report as it is."""
    _write(sys.stdout, text)


def _is_click_exception(exc) -> bool:
    click = sys.modules.get("click")      # not imported: it cannot be one of its exceptions
    return click is not None and isinstance(exc, (click.exceptions.Exit, click.exceptions.Abort,
                                                  click.ClickException))


class guarded:
    """``with guarded():`` turns InputError (and any unexpected error) into one clear line and
    exit code 2. Never prints a traceback; set MYRABOT_DESC_DEBUG=1 to see one.
    (A class, not contextlib.contextmanager: contextlib costs ``build``'s start ~1 ms.)"""

    def __enter__(self):
        return self

    def __exit__(self, exc_type, exc, tb):
        if exc_type is None or issubclass(exc_type, (SystemExit, KeyboardInterrupt, UsageProblem)):
            return False      # a UsageProblem is the command line's: click reports it
        if issubclass(exc_type, InputError):
            echo(str(exc))
            sys.exit(2)
        if issubclass(exc_type, BrokenPipeError):  # `... | head` closed the pipe: not an error of ours
            try:
                devnull = os.open(os.devnull, os.O_WRONLY)
                os.dup2(devnull, sys.stdout.fileno())
            except OSError:
                pass
            sys.exit(0)
        if issubclass(exc_type, OSError) and exc.errno in _FULL:   # the disk's, not a bug of ours
            echo(f"error: cannot write the output ({os.strerror(exc.errno)})")
            sys.exit(2)
        if issubclass(exc_type, RecursionError):
            echo("error: input nests too deeply (recursion limit reached)")
            sys.exit(2)
        if issubclass(exc_type, MemoryError):
            echo("error: input too large (out of memory)")
            sys.exit(2)
        if issubclass(exc_type, Exception):  # a bug of ours: still one line, still exit 2
            if os.environ.get("MYRABOT_DESC_DEBUG") or _is_click_exception(exc):
                return False
            echo(f"error: internal error ({type(exc).__name__}: {clean(exc)}); "
                 "set MYRABOT_DESC_DEBUG=1 for a traceback and please report it")
            sys.exit(2)
        return False


def no_mujoco_log() -> None:
    """MuJoCo's default log writes MUJOCO_LOG.TXT into the working folder (and WARNING lines to
    stdout) on a model's warnings: off for this process (its warnings still reach us through the
    Python bindings, which the converters report)."""
    import os

    # no GL probing while importing (convert never renders; render has chosen its backend already);
    # only while importing, so that a process started later chooses its own
    saved = os.environ.get("MUJOCO_GL")
    os.environ.setdefault("MUJOCO_GL", "disable")
    try:
        import mujoco
    except ImportError:
        return
    finally:
        if saved is None:
            os.environ.pop("MUJOCO_GL", None)
    config = getattr(mujoco, "MjLogConfig", None)
    if config is not None:
        cfg = config()
        cfg.logto_file = False
        cfg.logto_console = False
        cfg.set()
