"""``myrabot-desc view``: the robot in a local web viewer (view/server.py serves it)."""

from __future__ import annotations

import time

import click

from myrabot_desc.commands.common import input_options
from myrabot_desc.commands.console import guarded
from myrabot_desc.commands.extras import require
from myrabot_desc.sanitize import clean
from myrabot_desc.view.scene import clamp_notes, parse_joint_values
from myrabot_desc.view.server import Viewer


@click.command("view")
@input_options()
@click.option("--host", default="127.0.0.1", show_default=True,
              help="Address to listen on (127.0.0.1: this machine only).")
@click.option("--port", type=int, default=8080, show_default=True,
              help="Port to listen on; the next free one is taken when it is busy (0: any free port).")
@click.option("--open", "open_browser", is_flag=True, help="Open the viewer in the default web browser.")
@click.option("--watch/--no-watch", default=True, show_default=True,
              help="Reload when the model's files change, keeping the joint values.")
@click.option("--check/--no-check", "findings", default=True, show_default=True,
              help="Run `check --inertia` and list its findings in the viewer.")
@click.option("--joint", "joints", multiple=True, metavar="NAME=VALUE", help="Initial joint value. Repeatable.")
def view_cmd(inputs, host, port, open_browser, watch, findings, joints):
    """Show the robot in a web viewer (viser): joint sliders, frames, centres of mass, inertia boxes,
    support polygon, drive wheels, and check's findings highlighted on the model.

    Works for any URDF/xacro the other commands read, with the same package options.
    Stop with Ctrl-C.

    \b
    Examples:
      myrabot-desc view                                  # the bundled MYRAbot, http://127.0.0.1:8080
      myrabot-desc view robot.urdf.xacro -p my_pkg=../my_pkg --open
      myrabot-desc view robot.urdf --port 0 --no-watch   # any free port, no reloading
    """
    with guarded():
        require("view", "view")
        if not 0 <= port <= 65535:
            raise click.BadParameter(f"{port} is not a port number", param_hint="--port")
        viewer = Viewer(inputs.load, host=host, port=port, findings=findings)
        if joints:
            asked = parse_joint_values(joints, viewer.scene)
            for line in clamp_notes(asked, viewer.scene):
                click.echo(line, err=True)
            viewer.set_joints(asked)
        for line in viewer.scene.problems:
            click.echo(clean(line), err=True)
        if watch:
            viewer.watch()
        # the address once, on stdout (viser's own banner is off); what is served on stderr
        click.echo(f"myrabot-desc view: {clean(viewer.robot.name)}, Ctrl-C stops", err=True)
        click.echo(viewer.url)
        if open_browser:
            import webbrowser

            webbrowser.open(viewer.url)
        try:
            while True:
                time.sleep(3600)
        except KeyboardInterrupt:
            pass
        finally:
            viewer.stop()
