"""The click group: ``myrabot-desc`` and its subcommands.

Subcommands live in their own modules (commands/<name>.py) and are imported only when invoked,
so ``myrabot-desc --help`` stays fast: it imports no subcommand module and no heavy library
(no trimesh, yourdfpy, pinocchio or mujoco).
"""

from __future__ import annotations

import importlib

import click

from myrabot_desc import __version__
from myrabot_desc.commands.version import describe
from myrabot_desc.safety import limits_help

# name -> (module, attribute, one-line help shown by --help without importing)
COMMANDS = {
    "build": ("myrabot_desc.commands.build", "build_cmd", "Expand a xacro file (legacy syntax too) into URDF, without ROS."),
    "check": ("myrabot_desc.commands.check", "check_cmd", "Lint a robot model: tree, inertia, sensors, plugins, meshes, physics."),
    "diff": ("myrabot_desc.commands.diff", "diff_cmd", "Show what changed in the built robot between two models or revisions."),
    "convert": ("myrabot_desc.commands.convert", "convert_cmd", "Convert a model to SDF (gz-sim), an SDF world, or MJCF (MuJoCo)."),
    "materials": ("myrabot_desc.commands.materials", "materials_cmd", "Read an OGRE .material script; print SDF <material> blocks or JSON."),
    "sim": ("myrabot_desc.commands.sim", "sim_cmd", "Run the seed's programs in a built-in kinematic/diff-drive simulator."),
    "info": ("myrabot_desc.commands.info", "info_cmd", "Show the robot: tree, DOF, limits, mass, centre of mass, frames."),
    "view": ("myrabot_desc.commands.view", "view_cmd", "Open the robot in a web viewer: joint sliders, frames, inertia, findings."),
    "render": ("myrabot_desc.commands.render", "render_cmd", "Render the robot to a PNG with no display (iso/front/side/top)."),
}


class LazyGroup(click.Group):
    def list_commands(self, ctx):
        return list(COMMANDS)

    def get_command(self, ctx, name):
        if name not in COMMANDS:
            return None
        module, attr, _ = COMMANDS[name]
        return getattr(importlib.import_module(module), attr)

    def format_commands(self, ctx, formatter):
        rows = [(name, helptext) for name, (_, _, helptext) in COMMANDS.items()]
        with formatter.section("Commands"):
            formatter.write_dl(rows)


EPILOG = """\b
Examples:
  myrabot-desc build -o out/myrabot.urdf          # the bundled MYRAbot
  myrabot-desc build old_robot.urdf.xacro -p my_pkg=../my_pkg
  myrabot-desc check --inertia robot.urdf.xacro
  myrabot-desc diff robot.urdf.xacro --rev main    # what the branch changed
  myrabot-desc convert --to sdf -o out/myrabot.sdf
  myrabot-desc sim vuelta --plot out/vuelta.png
  myrabot-desc info
  myrabot-desc view                                # browser viewer with joint sliders
  myrabot-desc render --view all -o out/myrabot.png

FILE defaults to the bundled MYRAbot assembly. Exit codes: 0 ok, 1 findings
(check) or failed verdict (sim), 2 input could not be processed.

\b
Model files are untrusted: ${} runs through an allow-list, files are read only
from the model's folder and package roots, and these limits apply (environment):
"""


def _version(ctx, param, value):
    if not value or ctx.resilient_parsing:
        return
    click.echo(f"myrabot-desc, version {describe(__version__)}")
    ctx.exit()


@click.group(cls=LazyGroup, epilog=EPILOG + limits_help() + "\n", context_settings={"help_option_names": ["-h", "--help"]})
@click.option("--version", is_flag=True, expose_value=False, is_eager=True, callback=_version,
              help="Show the version (and the commit, when it is not a release) and exit.")
def main():
    """Robot descriptions without ROS: build xacro (old and new), check what is
    wrong and why, convert for today's simulators, and smoke-test the motion."""


def render_help() -> str:
    """The group's ``--help`` as click prints it on a terminal of 80 columns (commands/plain_help.py
    stores it)."""
    import contextlib
    import io
    import os

    buf, saved = io.StringIO(), os.environ.get("COLUMNS")
    os.environ["COLUMNS"] = "80"
    try:
        with contextlib.redirect_stdout(buf):
            main(["--help"], prog_name="myrabot-desc", standalone_mode=False)
    finally:
        if saved is None:
            os.environ.pop("COLUMNS")
        else:
            os.environ["COLUMNS"] = saved
    return buf.getvalue()


def write_help() -> None:
    """Store ``render_help()`` in commands/help_text.py, for the click-free ``--help``."""
    from pathlib import Path

    text = render_help()
    Path(__file__).with_name("help_text.py").write_text(
        '"""The top-level ``--help`` text, as click renders it at 80 columns (commands/plain_help.py).\n\n'
        "Generated: .venv/bin/python -m myrabot_desc.commands.main --write-help (do not edit).\n"
        '"""\n\nTEXT = ' + repr(text) + "\n")


if __name__ == "__main__":
    import sys

    if sys.argv[1:] != ["--write-help"]:
        sys.exit("usage: python -m myrabot_desc.commands.main --write-help")
    write_help()
