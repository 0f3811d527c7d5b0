"""``myrabot-desc convert``: SDF for gz-sim, an SDF demo world, or MJCF for MuJoCo."""

from __future__ import annotations

import click

from myrabot_desc.commands.common import input_options
from myrabot_desc.commands.console import guarded
from myrabot_desc.commands.extras import require
from myrabot_desc.convert.mjcf import convert_mjcf
from myrabot_desc.convert.preflight import problems, refuse_or_record
from myrabot_desc.convert.report import Report
from myrabot_desc.convert.sdf import SdfOptions, to_sdf
from myrabot_desc.convert.world import to_world
from myrabot_desc.output import write_output


@click.command("convert")
@input_options()
@click.option("--to", "target", type=click.Choice(["sdf", "world", "mjcf"]), default="sdf", show_default=True,
              help="sdf: the robot as an SDF 1.9 model; world: a gz-sim world with the robot and the demo "
                   "objects; mjcf: a MuJoCo model (meshes copied next to it).")
@click.option("-o", "--output", default="-", metavar="OUT", show_default=True,
              help="Output file ('-' = stdout; MJCF with meshes needs a file).")
@click.option("--lump/--no-lump", default=False, show_default=True,
              help="Merge fixed joints into their parent link (like `gz sdf -p`), keeping every removed "
                   "link and joint as an SDF <frame>. Default keeps fixed joints.")
@click.option("--uri-style", type=click.Choice(["absolute", "model"]), default="absolute", show_default=True,
              help="Meshes and textures as absolute paths (load as they are on this machine) or model:// URIs "
                   "(portable; set GZ_SIM_RESOURCE_PATH as printed).")
@click.option("--layout", type=click.Choice(["escoja", "seguir"]), default="escoja", show_default=True,
              help="World only: the seed demo whose table and cans to place.")
@click.option("--base", type=click.Choice(["auto", "free", "fixed"]), default="auto", show_default=True,
              help="MJCF only: free = the root gets a free joint; fixed = welded to the world; auto = free for "
                   "mobile bases (a drive plugin or wheel joints), else what MuJoCo's URDF reader does (it welds "
                   "the root). Use free for legged robots.")
@click.option("--scene/--no-scene", default=True, show_default=True,
              help="MJCF only: also write scene.xml next to the model (floor, light, the robot included), as "
                   "MuJoCo Menagerie does: python -m mujoco.viewer --mjcf scene.xml")
@click.option("--report", "report_path", metavar="FILE", default=None,
              help="Write what became of every element of the source (kept, translated, approximated, dropped, "
                   "with file:line): JSON if FILE ends in .json, else text.")
@click.option("--allow-errors", is_flag=True,
              help="Convert a model that has errors (no tree, unreadable values, unreadable collision meshes) "
                   "anyway, leaving those parts out; the report lists them.")
@click.option("-q", "--quiet", is_flag=True, help="Do not print warnings.")
def convert_cmd(inputs, target, output, lump, uri_style, layout, base, scene, report_path, allow_errors, quiet):
    """Convert a robot for today's simulators: gz-sim (SDF) or MuJoCo (MJCF).

    FILE defaults to the bundled MYRAbot. On the way to SDF every link, joint,
    frame and sensor is kept: fixed joints stay (or, with --lump, become
    <frame>s), massless links stay (with a placeholder inertial and a
    warning), joints declared in <gazebo> blocks are copied, and the Gazebo
    extensions are translated, the ROS Electric dialect included (angles in
    degrees become radians): cameras, the Kinect (rgbd_camera), lasers and
    sonars (gpu_lidar), the IMU, the Create/Roomba and other diff drives
    (gz-sim DiffDrive with the wheel separation and radius measured on the
    URDF), joint states and arm joint controllers. Plugins with no gz-sim
    equivalent stay as XML comments; --report lists them with everything else
    that was translated, approximated or dropped. Gazebo/OGRE material names
    become explicit
    colours and PBR textures.

    \b
    Examples:
      myrabot-desc convert -o out/myrabot.sdf
      myrabot-desc convert --to world --layout seguir -o out/seguir.sdf
      myrabot-desc convert --to mjcf -o out/mjcf/myrabot.xml --report out/mjcf/report.json
      myrabot-desc convert robot.urdf.xacro --lump --uri-style model -o robot.sdf
      myrabot-desc convert old/myrabot.urdf.xacro --package-path old/ -o old.sdf

    MJCF (MuJoCo Menagerie's form): the model with actuators (position for
    arm joints, velocity for wheels), a `home` keyframe standing on the floor,
    contact exclusions for bodies that touch at rest, mimic joints as equality
    constraints; plus scene.xml. Links without <inertial> are massless (as
    urdfdom, KDL and Pinocchio read them), not given MuJoCo's density.

    \b
    Warnings go to stderr, then a one-line summary of the report. Exit codes:
    0 converted; 2 the input could not be processed or has errors (a
    file:line line for each, nothing written).
    """
    with guarded():
        if target == "mjcf":
            require("mjcf", "convert --to mjcf")
        robot = inputs.load()
        report = Report(target, str(robot.source) if robot.source else "")
        found = problems(robot) if robot.links else []
        if not allow_errors:
            refuse_or_record(found, False)
        if target == "mjcf":
            result = convert_mjcf(robot, output, base=base, scene="scene.xml" if scene else None, report=report,
                                  allow_errors=allow_errors)
            refuse_or_record(found, True, report, result.notes)
            _report(result.notes, quiet)
            _write_report(report, report_path, quiet)
            if output != "-":
                click.echo(f"wrote {output} ({result.summary})", err=True)
            return
        opts = SdfOptions(lump=lump, uri_style=uri_style)
        if target == "world":
            text, res = to_world(robot, layout, opts, load=inputs.load, report=report)
        else:
            text, res = to_sdf(robot, opts, report=report)
        write_output(output, text)
        refuse_or_record(found, True, report, res.notes)
        _report(res.notes, quiet)
        _write_report(report, report_path, quiet)
        if uri_style == "model" and res.resource_dirs:
            click.echo("set GZ_SIM_RESOURCE_PATH=" + ":".join(res.resource_dirs), err=True)
        if output != "-":
            click.echo(f"wrote {output} ({len(res.links)} links, {len(res.joints)} joints, {len(res.frames)} "
                       f"frames, {len(res.sensors)} sensors)", err=True)


def _report(notes, quiet):
    if quiet:
        return
    for w in notes.warnings:
        click.echo(w, err=True)


def _write_report(report, path, quiet):
    if path:
        write_output(path, report.render(path))
    if not quiet and report.entries:
        click.echo(report.summary(), err=True)
