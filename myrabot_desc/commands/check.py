"""``myrabot-desc check``: the command line of the rule registry. The click command of
commands/fastcheck.py's run_check (checks/run.py runs the files), its options from the one table
(options.CHECK_OPTS)."""

from __future__ import annotations

import sys

import click

from myrabot_desc.commands.common import input_options
from myrabot_desc.commands.fastcheck import run_check
from myrabot_desc.commands.options import CHECK_OPTS, usage_error
from myrabot_desc.errors import UsageProblem


def _check_options(f):
    for o in reversed(CHECK_OPTS):
        f = o.click_option()(f)
    return f


@click.command("check")
@input_options(multiple=True)
@_check_options
def check_cmd(inputs, **values):
    """Lint robot models: tree, inertia, sensors and frames, Gazebo plugins, meshes, physics.

    Each finding has a stable code (X build, T tree, I inertia, S sensors/frames,
    G Gazebo/plugins, M meshes, P physics), a severity, the numbers that matter and the
    xacro file:line it comes from. docs/rules.md explains every rule and its fix.

    \b
    Settings come from the nearest pyproject.toml [tool.myrabot-desc] or myrabot-desc.toml
    (walking up from each file); a finding is silenced in the model with
      <!-- myrabot-desc: ignore[I008] why -->
    on the line before the element (or inside it); see docs/check.md.

    \b
    Examples:
      myrabot-desc check                              # the bundled MYRAbot
      myrabot-desc check robot.urdf.xacro -p my_pkg=../my_pkg
      myrabot-desc check --inertia --suggest robot.urdf
      myrabot-desc check urdf/ --format github        # every top-level model in a folder
      myrabot-desc check -r . --strict                # every model of a repository (CI)
      myrabot-desc check -r . --shard 2/4 --format sarif -o part2.sarif
      myrabot-desc check --merge-sarif part*.sarif -o check.sarif
      myrabot-desc check robot.urdf --select I,P --strict
      myrabot-desc check --inertia panda.urdf --srdf panda.srdf   # self-collision (P005) as the SRDF allows
      myrabot-desc check --fix robot.urdf.xacro        # repair the safe findings in the sources
      myrabot-desc check --diff --unsafe-fixes -r .    # show every fix as a diff, write nothing
      myrabot-desc check -r . --baseline .myrabot-desc-baseline.json   # fail only on new findings
      myrabot-desc check -r . --changed-since origin/main --format junit -o check.xml

    \b
    Exit codes: 0 no errors (no warnings either with --strict), 1 errors found,
    2 a file could not be processed (one line each, the other files are still checked)
    or the command line / configuration is wrong.
    """
    try:
        code = run_check(inputs, **values)
    except UsageProblem as exc:
        raise usage_error(exc) from None
    sys.exit(code)
