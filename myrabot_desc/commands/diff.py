"""``myrabot-desc diff``: what a change does to the built robot (diff/run.py). The click command
of commands/fastdiff.py's run_diff, its options from the one table (options.DIFF_OPTS)."""

from __future__ import annotations

import sys

import click

from myrabot_desc.commands.common import input_options
from myrabot_desc.commands.fastdiff import run_diff
from myrabot_desc.commands.options import DIFF_OPTS, usage_error
from myrabot_desc.errors import UsageProblem


def _diff_options(f):
    for o in reversed(DIFF_OPTS):
        f = o.click_option()(f)
    return f


@click.command("diff")
@input_options(multiple=True)
@_diff_options
def diff_cmd(inputs, **values):
    """Show what changed in the built robot between two models, or one model at two git revisions.

    Links, joints and sensors added, removed or renamed; frames moved (mm, deg) at the zero and
    the rest pose; masses, centres of mass, inertias; joint types, axes, limits; visual and
    collision shapes and meshes; the drive and what it does for the same command; the robot's
    mass and centre of mass; the findings of `check` that appear or disappear. Each change
    names the xacro file:line where its new value is written. Package and arg options are
    those of `build`.

    \b
    Examples:
      myrabot-desc diff old/robot.urdf.xacro new/robot.urdf.xacro
      myrabot-desc diff urdf/robot.urdf.xacro --rev main          # main vs the work tree
      myrabot-desc diff urdf/robot.urdf.xacro --rev v1.0..v1.1 --format markdown
      myrabot-desc diff robot.urdf.xacro --rev HEAD~1..HEAD --format json -o diff.json
      myrabot-desc diff robot.urdf.xacro --rev main --picture out/before_after.png

    \b
    Exit codes (as `git diff --exit-code`): 0 no change; 1 changes; 2 a model could not be
    built or the command line is wrong.
    """
    try:
        code = run_diff(inputs, **values)
    except UsageProblem as exc:
        raise usage_error(exc) from None
    sys.exit(code)
