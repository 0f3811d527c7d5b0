"""What every click command that reads a model shares: the FILE and package options (click's side
of the one table in options.py), the inputs that load a Robot, and UsageProblem as click's error."""

from __future__ import annotations

import functools

import click

from myrabot_desc.commands.options import INPUT_OPTS, Inputs, UsageProblem, make_inputs
from myrabot_desc.model.loader import load_robot


class ModelInputs(Inputs):
    """Inputs that load the model."""

    def load(self, path: str | None = None):
        """Load one model (the first FILE, or the bundled MYRAbot) into a Robot."""
        return load_robot(path if path is not None else self.file, **self.build_options())


def usage_error(exc: UsageProblem) -> click.UsageError:
    """click's error for a UsageProblem: BadParameter when it names the option, else UsageError."""
    if exc.param_hint:
        return click.BadParameter(str(exc), param_hint=exc.param_hint)
    return click.UsageError(str(exc))


def input_options(multiple: bool = False):
    """Decorator: FILE [NAME:=VALUE ...] plus the package and safety options.

    With ``multiple=True`` several FILEs are accepted (``check`` lints a folder's models).
    Passes ``inputs`` (a :class:`ModelInputs`) to the command.
    """

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
                inputs = make_inputs(values, multiple, cls=ModelInputs)
            except UsageProblem as exc:
                raise usage_error(exc) from None
            return f(*a, inputs=inputs, **kw)

        return wrapper

    return deco
