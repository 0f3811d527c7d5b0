"""``myrabot-desc diff``: what a change does to the built robot (diff/run.py)."""

from __future__ import annotations

import gc
import sys

import click

from myrabot_desc import __version__
from myrabot_desc.commands.common import input_options
from myrabot_desc.commands.console import guarded
from myrabot_desc.commands import options
from myrabot_desc.commands.options import usage_error
from myrabot_desc.diff.report import markdown, text, to_json
from myrabot_desc.diff.run import diff_paths, diff_revisions
from myrabot_desc.errors import UsageProblem
from myrabot_desc.output import write_output


@click.command("diff")
@input_options(multiple=True)
@click.option("--rev", "rev", metavar="A..B | A",
              help="Compare FILE at git revision A with revision B (A..B) or with the work tree (A). The revisions "
                   "are read with git into a temporary folder; the work tree is not touched.")
@click.option("--format", "fmt", type=click.Choice(["text", "json", "markdown"]), default="text", show_default=True,
              help="Report format (markdown: a pull-request comment).")
@click.option("--no-check", is_flag=True, help="Do not compare the findings of `check` (faster).")
@click.option("--select", "select", multiple=True, metavar="CODES", help="Only these check codes or prefixes.")
@click.option("--ignore", "ignore", multiple=True, metavar="CODES", help="Skip these check codes or prefixes.")
@click.option("--image", metavar="URL", help="Markdown: show this before/after picture (e.g. --picture's, uploaded).")
@click.option("--picture", metavar="PNG", help="Render the robot before and after, side by side, into this PNG "
              "(MuJoCo offscreen, as `render`).")
@click.option("--limit", type=click.IntRange(min=1), default=25, show_default=True,
              help="Markdown: rows in the table (the largest changes).")
@click.option("-o", "--output", type=click.Path(dir_okay=False), default="-", show_default=True,
              help="Write the report to a file instead of stdout.")
@click.option("--exit-zero", is_flag=True, help="Exit 0 when there are changes too (a report, not a gate).")
def diff_cmd(inputs, rev, fmt, no_check, select, ignore, image, picture, limit, output, exit_zero):
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
    if options.ONE_SHOT:
        # a process that ends with this diff: the collector would rescan the two builds' documents
        # and the two models (records without cycles worth finding) over and over, then free them one
        # by one at exit; a fifth of a large robot's diff
        gc.disable()
    with guarded():
        files = inputs.files
        try:
            if rev is not None:
                if len(files) != 1:
                    raise UsageProblem(f"--rev takes one FILE, got {len(files)}")
            elif len(files) != 2:
                raise UsageProblem(f"expected OLD NEW (two files) or FILE --rev A..B, got {len(files)} file(s)")
            build = inputs.build_options()
            kw = dict(checks=not no_check, select=_codes(select), ignore=_codes(ignore),
                      while_open=(lambda res: _picture(res, picture)) if picture else None)
            if rev is not None:
                res = diff_revisions(files[0], rev, build, **kw)
            else:
                res = diff_paths(files[0], files[1], build, **kw)
        except UsageProblem as exc:
            raise usage_error(exc) from None
        if fmt == "json":
            out = to_json(res, __version__)
        elif fmt == "markdown":
            out = markdown(res, limit=limit, image=image or picture)
        else:
            out = text(res)
        if output == "-":
            click.echo(out, nl=False)
        else:
            write_output(output, out)
    if options.ONE_SHOT:
        gc.freeze()
    sys.exit(1 if res.items and not exit_zero else 0)


def _codes(values) -> tuple:
    out = []
    for v in values:
        out += [c.strip() for c in v.split(",") if c.strip()]
    return tuple(out)


def _picture(res, path: str) -> None:
    """The two robots at their rest pose, iso view, side by side (before | after), into ``path``."""
    from PIL import ImageDraw

    # the renderer and the scene (with lxml, convert's appearance and the viewer's facts) load only
    # for --picture: a tenth of a small robot's diff otherwise
    from myrabot_desc.render import Layers, choose_gl, png_bytes, render_image
    from myrabot_desc.view.scene import build_scene

    choose_gl()
    tiles = []
    for robot in (res.old, res.new):
        scene = build_scene(robot)
        tiles.append(render_image(scene, robot.rest_pose(), ("iso",), (600, 450), Layers()))
    img = tiles[0].resize((1200, 450))
    img.paste(tiles[0], (0, 0))
    img.paste(tiles[1], (600, 0))
    draw = ImageDraw.Draw(img)
    draw.line([(600, 0), (600, 450)], fill=(160, 160, 160), width=2)
    for x, label in ((12, "before"), (612, "after")):
        draw.text((x, 10), label, fill=(0, 0, 0))
    write_output(path, png_bytes(img))
