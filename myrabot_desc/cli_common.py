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

import contextlib
import sys
from dataclasses import dataclass, field

import click

from myrabot_desc.errors import InputError


@dataclass
class Inputs:
    """What the user asked to read, and how to build it."""

    files: list[str] = field(default_factory=list)
    packages: dict[str, str] = field(default_factory=dict)   # -p NAME=PATH
    package_paths: list[str] = field(default_factory=list)   # --package-path DIR
    mappings: dict[str, str] = field(default_factory=dict)   # NAME:=VALUE
    legacy: str = "auto"
    unsafe_eval: bool = False
    no_env: bool = False
    allow_paths: list[str] = field(default_factory=list)

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
            raise click.BadParameter(f"expected NAME=PATH, got {v!r}", param_hint="-p/--package")
        k, p = v.split("=", 1)
        out[k.strip()] = p
    return out


def input_options(multiple: bool = False):
    """Decorator: FILE [NAME:=VALUE ...] plus the package and safety options.

    With ``multiple=True`` several FILEs are accepted (``check`` lints a folder's models).
    Passes ``inputs`` (an :class:`Inputs`) to the command.
    """

    def deco(f):
        opts = [
            click.argument("args", nargs=-1, metavar="[FILE]..." if multiple else "[FILE] [NAME:=VALUE]..."),
            click.option("-p", "--package", "packages", multiple=True, metavar="NAME=PATH",
                         help="Where package NAME lives (for $(find NAME) and package://NAME). Repeatable."),
            click.option("--package-path", "package_paths", multiple=True, metavar="DIR",
                         help="Folder searched for packages (package.xml or manifest.xml). Repeatable."),
            click.option("--legacy", type=click.Choice(["auto", "on", "off"]), default="auto", show_default=True,
                         help="Upgrade ROS Electric/Fuerte xacro syntax (un-prefixed tags, bare macro calls)."),
            click.option("--unsafe-eval", is_flag=True,
                         help="Evaluate ${} expressions without the allow-list (trusted files only)."),
            click.option("--no-env", is_flag=True, help="Refuse $(env) and $(optenv)."),
            click.option("--allow-path", "allow_paths", multiple=True, metavar="DIR",
                         help="Also allow includes and load_yaml under DIR. Repeatable."),
        ]
        for o in reversed(opts):
            f = o(f)

        import functools

        @functools.wraps(f)
        def wrapper(*a, args=(), packages=(), package_paths=(), legacy="auto", unsafe_eval=False,
                    no_env=False, allow_paths=(), **kw):
            files, mappings = _split_args(args)
            if len(files) > 1 and not multiple:
                raise click.UsageError(f"expected one FILE, got {len(files)}: {' '.join(files)}")
            inputs = Inputs(files=files, packages=_parse_packages(packages), package_paths=list(package_paths),
                            mappings=mappings, legacy=legacy, unsafe_eval=unsafe_eval, no_env=no_env,
                            allow_paths=list(allow_paths))
            return f(*a, inputs=inputs, **kw)

        return wrapper

    return deco


@contextlib.contextmanager
def guarded():
    """Turn InputError (and any unexpected error) into one clear line and exit code 2.

    Never prints a traceback; set MYRABOT_DESC_DEBUG=1 to see one.
    """
    import os

    try:
        yield
    except InputError as exc:
        click.echo(str(exc), err=True)
        sys.exit(2)
    except (click.exceptions.Exit, click.exceptions.Abort, click.ClickException, SystemExit, KeyboardInterrupt):
        raise
    except BrokenPipeError:  # `... | head` closed the pipe: not an error of ours
        try:
            devnull = os.open(os.devnull, os.O_WRONLY)
            os.dup2(devnull, sys.stdout.fileno())
        except OSError:
            pass
        sys.exit(0)
    except RecursionError:
        click.echo("error: input nests too deeply (recursion limit reached)", err=True)
        sys.exit(2)
    except MemoryError:
        click.echo("error: input too large (out of memory)", err=True)
        sys.exit(2)
    except Exception as exc:  # a bug of ours: still one line, still exit 2
        if os.environ.get("MYRABOT_DESC_DEBUG"):
            raise
        click.echo(f"error: internal error ({type(exc).__name__}: {exc}); "
                   "set MYRABOT_DESC_DEBUG=1 for a traceback and please report it", err=True)
        sys.exit(2)
