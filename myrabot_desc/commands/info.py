"""``myrabot-desc info``: what the robot is."""

from __future__ import annotations

import json

import click

from myrabot_desc.commands.common import input_options
from myrabot_desc.commands.console import guarded
from myrabot_desc.info import summarize, text_lines


@click.command("info")
@input_options()
@click.option("--json", "as_json", is_flag=True, help="Print the summary as JSON.")
@click.option("--no-tree", is_flag=True, help="Leave out the link tree.")
def info_cmd(inputs, as_json, no_tree):
    """Show what the robot is: the link tree (joint types and axes), degrees of
    freedom, joint limits, total mass, centre of mass at the zero configuration,
    and every frame's world position.

    \b
    Examples:
      myrabot-desc info                      # the bundled MYRAbot
      myrabot-desc info robot.urdf --json
    """
    with guarded():
        robot = inputs.load()
        for d in robot.build_warnings:
            if d.severity == "error":
                click.echo(str(d), err=True)
        s = summarize(robot)
        if as_json:
            click.echo(json.dumps(s, indent=2))
            return
        for line in text_lines(robot, s, tree=not no_tree):
            click.echo(line)
