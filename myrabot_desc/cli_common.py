"""Options and error handling shared by every command that reads a model.

Use::

    @click.command()
    @input_options            # FILE argument, -p, --package-path, NAME:=VALUE, ...
    @click.pass_context
    def my_cmd(ctx, inputs, ...):
        with guarded():
            robot = inputs.load()         # builds xacro, or reads .urdf
"""

from __future__ import annotations

import sys
from collections import namedtuple

from myrabot_desc.errors import InputError

# click is imported inside the functions that build click options: `build`'s plain-argv fast
# path (build/run.py) parses the same option tables without it (click costs ~25 ms of start-up).


class Opt(namedtuple("Opt", "decls dest kind help metavar choices")):
    """One command-line option, the one definition of it: click's option and the fast parser
    (parse_plain) both come from it. kind: "flag", "value" (one string, default None),
    "multi" (repeatable, a tuple), "choice" (default choices[0], shown), "count" (a whole
    number >= 1, default None)."""

    __slots__ = ()

    def click_option(self):
        import click

        kw = {"help": self.help}
        if self.kind == "flag":
            kw["is_flag"] = True
        elif self.kind == "multi":
            kw["multiple"] = True
        elif self.kind == "choice":
            kw.update(type=click.Choice(list(self.choices)), default=self.choices[0], show_default=True)
        elif self.kind == "count":
            kw.update(type=click.IntRange(min=1), default=None)
        else:
            kw["default"] = None
        if self.metavar:
            kw["metavar"] = self.metavar
        return click.option(*self.decls, self.dest, **kw)


# FILE [NAME:=VALUE ...] come first (click.argument "args"); then these, in --help order.
INPUT_OPTS = (
    Opt(("-p", "--package"), "packages", "multi",
        "Where package NAME lives (for $(find NAME) and package://NAME). Repeatable.", "NAME=PATH", None),
    Opt(("--package-path",), "package_paths", "multi",
        "Folder searched for packages (package.xml or manifest.xml). Repeatable.", "DIR", None),
    Opt(("--legacy",), "legacy", "choice",
        "Upgrade ROS Electric/Fuerte xacro syntax (un-prefixed tags, bare macro calls).", None, ("auto", "on", "off")),
    Opt(("--unsafe-eval",), "unsafe_eval", "flag",
        "Evaluate ${} expressions without the allow-list (trusted files only).", None, None),
    Opt(("--no-env",), "no_env", "flag", "Refuse $(env) and $(optenv).", None, None),
    Opt(("--allow-path",), "allow_paths", "multi",
        "Also allow includes and load_yaml under DIR. Repeatable.", "DIR", None),
)


def parse_plain(argv, opts) -> dict | None:
    """``argv`` parsed as click would parse it for these options (values by dest, the
    positionals under "args"), when it uses only plain forms: ``--name VALUE``,
    ``--name=VALUE``, ``-p VALUE``, flags, positionals. Anything else (``--help``, ``--``,
    unknown or bundled short options, a missing or bad value, a value that starts with
    ``-``) gives None: click then parses it, with its own messages and exit codes."""
    by_decl = {d: o for o in opts for d in o.decls}
    values = {o.dest: False if o.kind == "flag" else () if o.kind == "multi" else
              o.choices[0] if o.kind == "choice" else None for o in opts}
    args = []
    i, n = 0, len(argv)
    while i < n:
        a = argv[i]
        i += 1
        if a[:1] != "-":
            args.append(a)
            continue
        name, eq, value = a.partition("=") if a.startswith("--") else (a, "", None)
        o = by_decl.get(name)
        if o is None:
            return None
        if o.kind == "flag":
            if eq:
                return None
            values[o.dest] = True
            continue
        if not eq:
            if i >= n or (argv[i][:1] == "-" and argv[i] != "-"):
                return None
            value = argv[i]
            i += 1
        if o.kind == "multi":
            values[o.dest] += (value,)
        elif o.kind == "choice":
            if value not in o.choices:
                return None
            values[o.dest] = value
        elif o.kind == "count":
            if not (value.isascii() and value.isdigit() and int(value) >= 1):
                return None
            values[o.dest] = int(value)
        else:
            values[o.dest] = value
    values["args"] = tuple(args)
    return values


class Inputs:
    """What the user asked to read, and how to build it."""

    def __init__(self, files=None, packages=None, package_paths=None, mappings=None, legacy: str = "auto",
                 unsafe_eval: bool = False, no_env: bool = False, allow_paths=None):
        self.files: list[str] = list(files or [])
        self.packages: dict[str, str] = dict(packages or {})       # -p NAME=PATH
        self.package_paths: list[str] = list(package_paths or [])  # --package-path DIR
        self.mappings: dict[str, str] = dict(mappings or {})       # NAME:=VALUE
        self.legacy = legacy
        self.unsafe_eval = unsafe_eval
        self.no_env = no_env
        self.allow_paths: list[str] = list(allow_paths or [])

    def __repr__(self) -> str:
        return f"Inputs({', '.join(f'{k}={v!r}' for k, v in vars(self).items())})"

    def __eq__(self, other):
        return vars(self) == vars(other) if isinstance(other, Inputs) else NotImplemented

    @property
    def file(self) -> str | None:
        return self.files[0] if self.files else None

    def build_options(self) -> dict:
        return dict(packages=self.packages, package_paths=self.package_paths, mappings=self.mappings,
                    legacy=self.legacy, unsafe_eval=self.unsafe_eval, no_env=self.no_env,
                    allow_paths=self.allow_paths)

    def load(self, path: str | None = None):
        """Load one model (the first FILE, or the bundled MYRAbot) into a Robot."""
        from myrabot_desc.model.loader import load_robot

        return load_robot(path if path is not None else self.file, **self.build_options())


class UsageProblem(Exception):
    """Options that parse but do not make sense (click shows it as a usage error)."""

    def __init__(self, message: str, param_hint: str | None = None):
        super().__init__(message)
        self.param_hint = param_hint


def _split_args(args: tuple[str, ...]) -> tuple[list[str], dict[str, str]]:
    files, mappings = [], {}
    for a in args:
        if ":=" in a:
            k, v = a.split(":=", 1)
            mappings[k] = v
        else:
            files.append(a)
    return files, mappings


def _parse_packages(values: tuple[str, ...]) -> dict[str, str]:
    out = {}
    for v in values:
        if "=" not in v:
            raise UsageProblem(f"expected NAME=PATH, got {v!r}", param_hint="-p/--package")
        k, p = v.split("=", 1)
        out[k.strip()] = p
    return out


def make_inputs(values: dict, multiple: bool = False) -> Inputs:
    """The Inputs of parsed option values (click's or parse_plain's); UsageProblem if they do not fit."""
    files, mappings = _split_args(values.get("args", ()))
    if len(files) > 1 and not multiple:
        raise UsageProblem(f"expected one FILE, got {len(files)}: {' '.join(files)}")
    return Inputs(files=files, packages=_parse_packages(values.get("packages", ())),
                  package_paths=list(values.get("package_paths", ())), mappings=mappings,
                  legacy=values.get("legacy", "auto"), unsafe_eval=values.get("unsafe_eval", False),
                  no_env=values.get("no_env", False), allow_paths=list(values.get("allow_paths", ())))


def input_options(multiple: bool = False):
    """Decorator: FILE [NAME:=VALUE ...] plus the package and safety options.

    With ``multiple=True`` several FILEs are accepted (``check`` lints a folder's models).
    Passes ``inputs`` (an :class:`Inputs`) to the command.
    """
    import functools

    import click

    def deco(f):
        opts = [click.argument("args", nargs=-1, metavar="[FILE]..." if multiple else "[FILE] [NAME:=VALUE]...")]
        opts += [o.click_option() for o in INPUT_OPTS]
        for o in reversed(opts):
            f = o(f)
        names = ("args",) + tuple(o.dest for o in INPUT_OPTS)

        @functools.wraps(f)
        def wrapper(*a, **kw):
            values = {k: kw.pop(k) for k in names if k in kw}
            try:
                inputs = make_inputs(values, multiple)
            except UsageProblem as exc:
                if exc.param_hint:
                    raise click.BadParameter(str(exc), param_hint=exc.param_hint) from None
                raise click.UsageError(str(exc)) from None
            return f(*a, inputs=inputs, **kw)

        return wrapper

    return deco


_ANSI = None


def echo(message: str, err: bool = True) -> None:
    """click.echo of one line, without click: a newline added, ANSI styles stripped when the
    stream is not a terminal, flushed."""
    global _ANSI
    stream = sys.stderr if err else sys.stdout
    if stream is None:
        return
    out = message + "\n"
    try:
        tty = stream.isatty()
    except Exception:
        tty = False
    if not tty and "\033" in out:
        if _ANSI is None:
            import re

            _ANSI = re.compile(r"\033\[[0-?]*[ -/]*[@-~]")   # click's own pattern (click._compat)
        out = _ANSI.sub("", out)
    stream.write(out)
    stream.flush()


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
        import os

        if exc_type is None or issubclass(exc_type, (SystemExit, KeyboardInterrupt)):
            return False
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
        if issubclass(exc_type, RecursionError):
            echo("error: input nests too deeply (recursion limit reached)")
            sys.exit(2)
        if issubclass(exc_type, MemoryError):
            echo("error: input too large (out of memory)")
            sys.exit(2)
        if issubclass(exc_type, Exception):  # a bug of ours: still one line, still exit 2
            if os.environ.get("MYRABOT_DESC_DEBUG") or _is_click_exception(exc):
                return False
            echo(f"error: internal error ({type(exc).__name__}: {exc}); "
                 "set MYRABOT_DESC_DEBUG=1 for a traceback and please report it")
            sys.exit(2)
        return False
