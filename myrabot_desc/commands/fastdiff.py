"""What ``myrabot-desc diff`` does, without click (commands/diff.py is its click command).

The console entry (commands/entry.py) runs a plain ``diff ...`` command line straight from here,
parsed with parse_plain from the same option tables (options.INPUT_OPTS, options.DIFF_OPTS): a
diff then does not pay for importing click, as a plain ``build`` does not. A command line the
plain parser does not take, or a usage problem found here, goes to the click command, which gives
click's messages and exit codes.
"""

from __future__ import annotations

import gc
import sys

from myrabot_desc import __version__
from myrabot_desc.commands import options
from myrabot_desc.commands.console import guarded
from myrabot_desc.commands.options import DIFF_OPTS, INPUT_OPTS, UsageProblem, make_inputs, parse_plain
from myrabot_desc.diff.report import markdown, text, to_json
from myrabot_desc.diff.run import diff_paths, diff_revisions, parse_rev
from myrabot_desc.output import write_output


def fast_diff(argv) -> int | None:
    """Run ``diff`` for a plain command line; None when it needs click (help, errors, unusual
    forms, a usage problem): the caller hands it to click."""
    values = parse_plain(argv, INPUT_OPTS + DIFF_OPTS)
    if values is None:
        return None
    try:
        inputs = make_inputs(values, multiple=True)
        return run_diff(inputs, **{o.dest: values[o.dest] for o in DIFF_OPTS})
    except UsageProblem:
        return None


def run_diff(inputs, rev=None, fmt="text", no_check=False, select=(), ignore=(), image=None, picture=None,
             limit=25, output="-", exit_zero=False) -> int:
    """The diff command itself (click's and the plain path's): the exit code; UsageProblem for a
    command line that does not fit, raised before anything is built or written."""
    files = inputs.files
    if rev is not None:
        if len(files) != 1:
            raise UsageProblem(f"--rev takes one FILE, got {len(files)}")
    elif len(files) != 2:
        raise UsageProblem(f"expected OLD NEW (two files) or FILE --rev A..B, got {len(files)} file(s)")
    if rev is not None:
        parse_rev(rev)
    if options.ONE_SHOT:
        # a process that ends with this diff: the collector would rescan the two builds' documents
        # and the two models (records without cycles worth finding) over and over, then free them one
        # by one at exit
        gc.disable()
    with guarded():
        build = inputs.build_options()
        kw = dict(checks=not no_check, select=_codes(select), ignore=_codes(ignore),
                  while_open=(lambda res: _picture(res, picture)) if picture else None)
        if rev is not None:
            res = diff_revisions(files[0], rev, build, **kw)
        else:
            res = diff_paths(files[0], files[1], build, **kw)
        if fmt == "json":
            out = to_json(res, __version__)
        elif fmt == "markdown":
            out = markdown(res, limit=limit, image=image or picture)
        else:
            out = text(res)
        if output == "-":
            sys.stdout.write(out)
            sys.stdout.flush()
        else:
            write_output(output, out)
    if options.ONE_SHOT:
        gc.freeze()
    return 1 if res.items and not exit_zero else 0


def _codes(values) -> tuple:
    out = []
    for v in values:
        out += [c.strip() for c in v.split(",") if c.strip()]
    return tuple(out)


def _picture(res, path: str) -> None:
    """The two robots at their rest pose, iso view, side by side (before | after), into ``path``."""
    from PIL import ImageDraw

    # the renderer and the scene (with lxml, convert's appearance and the viewer's facts) load only
    # for --picture: ~10 ms of a small robot's ~300 ms diff otherwise
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
