"""``myrabot-desc render``: a PNG of the robot with no display (render.py draws it)."""

from __future__ import annotations

import time

import click

from myrabot_desc.commands.common import input_options
from myrabot_desc.commands.console import guarded, no_mujoco_log
from myrabot_desc.commands.extras import require
from myrabot_desc.errors import InputError
from myrabot_desc.model.kinematics import require_tree
from myrabot_desc.output import write_output
from myrabot_desc.render import ALL, VIEWS, Layers, choose_gl, parse_size, png_bytes, read_pose, render_image
from myrabot_desc.safety import limit
from myrabot_desc.sanitize import clean
from myrabot_desc.view.scene import build_scene, clamp_notes, parse_joint_values


@click.command("render")
@input_options()
@click.option("-o", "--output", default="robot.png", show_default=True, metavar="PNG",
              help="Where to write the picture.")
@click.option("--view", "view", type=click.Choice([*VIEWS, "all"]), default="iso", show_default=True,
              help="Camera: iso, front (from +x), side (from -y), top; all = the four in a 2x2 grid.")
@click.option("--joint", "joints", multiple=True, metavar="NAME=VALUE",
              help="A joint's position (rad or m); a value outside its limits is drawn at the limit, and said. Repeatable.")
@click.option("--pose", "pose_file", metavar="FILE.yaml",
              help="Joint values from YAML (NAME: VALUE, as `view` copies them); --joint wins.")
@click.option("--collision", is_flag=True, help="Draw the collision geometry (orange) over ghosted visuals.")
@click.option("--frames", is_flag=True, help="Draw every link frame as axes (x red, y green, z blue) with its name.")
@click.option("--inertia", is_flag=True,
              help="Draw each link's equivalent inertia box (blue; red when the moments are impossible), "
                   "the link centres of mass (black) and the robot's (magenta).")
@click.option("--size", "size_text", default="1200x900", show_default=True, metavar="WxH", help="Image size in pixels.")
def render_cmd(inputs, output, view, joints, pose_file, collision, frames, inertia, size_text):
    """Render the robot to a PNG without a display (MuJoCo offscreen, EGL or OSMesa).

    Works for any URDF/xacro the other commands read, with the same package options.

    \b
    Examples:
      myrabot-desc render -o out/myrabot.png                      # the bundled MYRAbot, iso view
      myrabot-desc render --view all --inertia -o out/inertia.png
      myrabot-desc render --joint arti1=1.0 --joint base=0.5 --frames -o out/arm.png
      myrabot-desc render robot.urdf.xacro -p my_pkg=../my_pkg --pose pose.yaml --collision
    """
    with guarded():
        require("render", "render")
        t0 = time.perf_counter()
        size = parse_size(size_text)
        most = limit("max_render_pixels")
        if size[0] * size[1] > most:
            raise click.BadParameter(f"{size_text!r} is {size[0] * size[1]} pixels, over the {most}-pixel limit "
                                     "(MYRABOT_DESC_MAX_RENDER_PIXELS)", param_hint="--size")
        choose_gl()
        no_mujoco_log()
        robot = inputs.load()
        require_tree(robot)                 # a cycle or a second root: one line, like sim and view
        if frames and len(robot.links) > limit("max_render_frames"):
            raise InputError(f"--frames draws every link frame: {len(robot.links)} links, over the "
                             f"{limit('max_render_frames')}-frame limit (MYRABOT_DESC_MAX_RENDER_FRAMES)", robot.loc)
        scene = build_scene(robot, collision=collision)
        q = read_pose(pose_file, scene) if pose_file else {}
        asked = parse_joint_values(joints, scene)
        q.update(asked)
        for line in clamp_notes(q, scene):
            click.echo(line, err=True)
        for line in scene.problems:
            click.echo(clean(line), err=True)
        _check_scales(robot, collision)
        try:
            img = render_image(scene, q, ALL if view == "all" else (view,), size, Layers(collision, frames, inertia))
        except ValueError as exc:          # MuJoCo refuses what it cannot draw (its message names the part)
            raise InputError(f"MuJoCo cannot draw this model: {' '.join(str(exc).split())[:300]}", robot.loc) from None
        write_output(output, png_bytes(img))
        click.echo(f"wrote {output} ({size[0]}x{size[1]}, {view} view, {time.perf_counter() - t0:.2f} s)", err=True)


MIN_SCALE = 1e-6


def _check_scales(robot, collision: bool) -> None:
    """A mesh scale MuJoCo cannot draw (0, denormal 5e-324, NaN, inf): one file:line error."""
    import math

    for link in robot.links.values():
        parts = list(link.visuals) + (list(link.collisions) if collision else [])
        for part in parts:
            g = part.geometry
            scale = getattr(g, "scale", None) if getattr(g, "kind", None) == "mesh" else None
            if scale and not all(isinstance(v, float) and math.isfinite(v) and abs(v) >= MIN_SCALE for v in scale):
                raise InputError(f"mesh {g.filename} of link '{link.name}' has scale "
                                 f"{' '.join(f'{v:g}' for v in scale)}: each factor must be a number of magnitude "
                                 f"{MIN_SCALE:g} or more to be drawn", part.loc or link.loc)
