"""``myrabot-desc convert``: SDF for gz-sim, an SDF demo world, or MJCF for MuJoCo."""

from __future__ import annotations

import gc

import click

from myrabot_desc.checks import CheckOptions, check_robot
from myrabot_desc.checks.registry import EXTERNAL, load_all
from myrabot_desc.commands import options
from myrabot_desc.commands.common import input_options
from myrabot_desc.commands.console import guarded, no_mujoco_log
from myrabot_desc.commands.extras import require
from myrabot_desc.convert.mjcf import check_size, convert_mjcf
from myrabot_desc.convert.preflight import Problem, problems, refuse_or_record, tree_problems
from myrabot_desc.convert.report import Report
from myrabot_desc.convert.sdf import SdfOptions, to_sdf
from myrabot_desc.convert.world import to_world
from myrabot_desc.output import write_output
from myrabot_desc.sanitize import clean, clean_lines


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
              help="Convert a model that `check` reports errors in (its tree, joint types, masses and inertias, "
                   "meshes, sensors, the build) anyway: those parts are left out, repaired or read as the URDF "
                   "default, each listed in the report and on stderr. Without it such a model is refused (exit 2).")
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
    if options.ONE_SHOT:
        # a process that ends with this conversion: the collector would only rescan the model's
        # records (no cycles worth finding) over and over while the output is built
        gc.disable()
    with guarded():
        if target == "mjcf":
            require("mjcf", "convert --to mjcf")
        robot = inputs.load()
        _keep(robot)
        report = Report(target, str(robot.source) if robot.source else "")
        found = refusals(robot) if robot.links else []
        if not allow_errors:
            refuse_or_record(found, False)
        if target == "mjcf":
            if robot.links:
                check_size(robot)       # a model over the limit is refused before importing MuJoCo
            no_mujoco_log()
            result = convert_mjcf(robot, output, base=base, scene="scene.xml" if scene else None, report=report,
                                  allow_errors=allow_errors)
            refuse_or_record(found, True, report, result.notes)
            _report(result.notes, quiet)
            _write_report(report, report_path, quiet)
            if output != "-":
                click.echo(f"wrote {output} ({result.summary})", err=True)
            _keep(report, result)
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
        _keep(report, res, text)


_KEPT: list = []


def _keep(*made) -> None:
    """In a one-shot process, what the conversion made stays referenced (from a frozen cycle the
    final collection skips) until the process ends: freeing the model, the report and the output
    tree object by object on return and at exit is only work; the OS takes the memory back at once."""
    if options.ONE_SHOT:
        if not _KEPT:
            _KEPT.append(_KEPT)
        _KEPT.extend(made)
        gc.freeze()


def _report(notes, quiet):
    if quiet:
        return
    for w in notes.warnings:
        click.echo(clean(w), err=True)


def _write_report(report, path, quiet):
    if path:
        write_output(path, report.render(path))
    if not quiet and report.entries:
        click.echo(clean_lines(report.summary()), err=True)


# check's rules on what convert writes: the tree and joint types, masses and inertias, geometry and
# meshes, sensors, the joints the drive plugin names, the build itself (X). Not the whole robot's
# physics verdicts (P: it tips over, its dynamics are singular), nor what convert translates
# itself: the drive plugin's wheel numbers (G001/G002: it writes the ones measured on the URDF)
# and ROS Electric sensor angles in degrees (S006: it converts them to radians).
CONVERT_CHECKS = ("T", "I", "M", "X", "S001", "S002", "S005", "G003", "G004", "G005", "G008")


def check_errors(robot) -> list:
    """The errors ``check`` reports (inline suppressions apply) on what convert writes, as Problems.
    Only the rules that can report an error run (the SDF path stays free of numpy), with the codes
    the build and the loader give."""
    def ours(code):
        return code.startswith(CONVERT_CHECKS)

    select = tuple(c for c, r in load_all().items() if r.severity == "error" and ours(c)) + \
        tuple(c for c in EXTERNAL if ours(c))
    diags, _ctx = check_robot(robot, CheckOptions(), select=select, unused=False)
    return [Problem(f"{d.code} {d.message}", d.loc, "value") for d in diags if d.severity == "error"]


def refusals(robot) -> list:
    """Why convert refuses ``robot``: the preflight's own reasons (a tree it cannot walk, a collision
    mesh no reader takes, an <inertial> without <inertia>), then check's errors at other places."""
    tree_found = tree_problems(robot)
    found = problems(robot, tree_found)
    seen = {p.loc for p in found}
    # the preflight words the tree's faults itself (every root, every second parent): check's T001
    # and T002 would say them again
    skip = ("T001 ", "T002 ") if tree_found else ()
    return found + [p for p in check_errors(robot) if p.loc not in seen and not p.message.startswith(skip or "\0")]
