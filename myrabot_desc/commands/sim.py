"""``myrabot-desc sim``: run the seed's programs in the built-in simulator and give a verdict."""

from __future__ import annotations

import functools
import sys
from pathlib import Path

import click

from myrabot_desc.commands.common import input_options
from myrabot_desc.commands.console import guarded
from myrabot_desc.commands.extras import require
from myrabot_desc.expand.packages import data_root
from myrabot_desc.model.kinematics import require_tree
from myrabot_desc.output import write_outputs
from myrabot_desc.sanitize import clean_lines
from myrabot_desc.sim import drive, plot, pointing, vuelta
from myrabot_desc.physics import drive as physics_drive
from myrabot_desc.physics import plot as physics_plot
from myrabot_desc.physics import settle, sweep
from myrabot_desc.physics.result import junit_bytes
from myrabot_desc.sim.scene import load_layout


def _outputs(f):
    opts = [
        click.option("--duration", type=click.FloatRange(min=0.001, max=86400), default=None,
                     help="Simulated seconds (each program has its own default)."),
        click.option("--rate", type=click.FloatRange(min=1, max=100000), default=1000.0, show_default=True,
                     help="Fixed time step rate in Hz."),
        click.option("--json", "as_json", is_flag=True, help="Print the summary as JSON."),
        click.option("--csv", "csv_path", metavar="FILE",
                     help="Write the time series (base pose, arm joints, wheel angles) as CSV ('-' = stdout)."),
        click.option("--plot", "plot_path", metavar="PNG", help="Draw the top view and the time series."),
        click.option("--junit", "junit_path", metavar="FILE",
                     help="Write the verdict as JUnit XML for CI (one test case per check; '-' = stdout)."),
        click.option("--progress/--no-progress", default=None,
                     help="Progress bar (default: on a terminal, for runs of 60 simulated seconds or more)."),
    ]
    for o in reversed(opts):
        f = o(f)
    return f


def _drive_options(f, names: bool = False):
    wheels = (click.option("--wheels", default="plugin", show_default=True, metavar="plugin|urdf|LEFT,RIGHT",
                           help="Whose wheel separation/diameter turn cmd_vel into wheel rates: the drive "
                                "plugin's (as Gazebo does) or the URDF's (the URDF's always move the robot); "
                                "or the two wheel joints, left then right, where nothing declares them "
                                "(then the URDF's geometry commands them).")
              if names else
              click.option("--wheels", type=click.Choice(["plugin", "urdf"]), default="plugin", show_default=True,
                           help="Whose wheel separation/diameter turn cmd_vel into wheel rates: the diff-drive "
                                "plugin's (as Gazebo does) or the URDF's. The URDF's always move the robot."))
    opts = [
        wheels,
        click.option("--wheel-speed-max", type=click.FloatRange(min=0, min_open=True), default=None,
                     metavar="RAD/S", help="Wheel joint rate limit (both wheels scale, keeping the curvature)."),
        click.option("--wheel-accel-max", type=click.FloatRange(min=0, min_open=True), default=None,
                     metavar="RAD/S2", help="Wheel joint acceleration limit (linear ramps)."),
    ]
    if names:
        opts += [
            click.option("--left-wheel", "left_wheels", multiple=True, metavar="JOINT",
                         help="A left wheel joint (repeatable: a skid-steer base's left wheels turn together)."),
            click.option("--right-wheel", "right_wheels", multiple=True, metavar="JOINT",
                         help="A right wheel joint (repeatable)."),
        ]
    for o in reversed(opts):
        f = o(f)
    return f


def _wheel_names(wheels, left_wheels, right_wheels):
    """(command geometry, left joints, right joints) from --wheels and --left-wheel/--right-wheel."""
    left, right = tuple(left_wheels), tuple(right_wheels)
    if wheels not in ("plugin", "urdf"):
        parts = [p.strip() for p in wheels.split(",")]
        if len(parts) != 2 or not all(parts):
            raise click.BadParameter(f"expected plugin, urdf or LEFT,RIGHT (two wheel joints), got {wheels!r}",
                                     param_hint="--wheels")
        if left or right:
            raise click.BadParameter("give the wheels either as --wheels LEFT,RIGHT or with --left-wheel/"
                                     "--right-wheel, not both", param_hint="--wheels")
        left, right, wheels = (parts[0],), (parts[1],), "urdf"
    elif bool(left) != bool(right):
        raise click.BadParameter("name both sides: --left-wheel and --right-wheel", param_hint="--left-wheel")
    elif left:
        wheels = "urdf"
    return wheels, left, right


def _finish(res, as_json, csv_path, plot_path, junit_path=None):
    """Write the outputs asked for (all or none), print the verdict, exit 0 (PASS) or 1 (FAIL)."""
    outputs = []
    physics = hasattr(res, "causes")
    if plot_path:
        if physics:
            outputs.append((plot_path, physics_plot.render(res)))
        else:
            outputs.append((plot_path, plot.render(res)))
    if csv_path:
        outputs.append((csv_path, res.csv_bytes()))
    if junit_path:
        outputs.append((junit_path, res.junit_bytes() if physics else
                        junit_bytes(res.program, res.robot, res.checks, (), res.info, res.wall)))
    if sum(1 for p, _ in outputs if p == "-") > 1:
        raise click.UsageError("only one of --csv, --junit may go to stdout ('-')")
    write_outputs(outputs)          # all or none
    if csv_path != "-" and junit_path != "-":
        click.echo(res.as_json() if as_json else clean_lines(res.summary()), nl=False)
    sys.exit(0 if res.passed else 1)


def _load(inputs, plot_path=None):
    """The model, which must be one tree to move (a broken one fails here with file:line, not deep inside).
    A plot needs the [plot] extra: said before anything runs."""
    if plot_path:
        require("plot", "sim --plot")
    robot = inputs.load()
    require_tree(robot)
    return robot


def _runner(duration, progress_flag):
    """A progress callback (0…1) drawn on stderr when wanted, and its closer."""
    want = progress_flag if progress_flag is not None else (sys.stderr.isatty() and (duration or 0) >= 60)
    if not want:
        return None, lambda: None
    bar = click.progressbar(length=1000, label="simulating", file=sys.stderr)
    bar.__enter__()
    state = {"done": 0}

    def progress(frac):
        n = int(min(max(frac, 0.0), 1.0) * 1000)
        if n > state["done"]:
            bar.update(n - state["done"])
            state["done"] = n

    return progress, functools.partial(bar.__exit__, None, None, None)


@click.group(name="sim", context_settings={"help_option_names": ["-h", "--help"]})
def sim_cmd():
    """Run the seed's programs in a built-in kinematic and diff-drive simulator, and physics
    verdicts in MuJoCo (settle, sweep, drive --engine mujoco).

    \b
    A fixed time step (1 kHz by default), deterministic; the base moves on exact
    arcs from the wheels' rates, the arm under position control in the lab's
    servo units (0…1023 over 300°, 511 at the centre, the integer-truncating
    conversion of its code), at the servo's speed.

    \b
    Examples:
      myrabot-desc sim vuelta --plot out/vuelta.png
      myrabot-desc sim escoja --object 2 --json
      myrabot-desc sim seguir --csv out/seguir.csv
      myrabot-desc sim drive tests/fixtures/wander_bot/urdf/robot.xacro -p wander_bot=tests/fixtures/wander_bot
      myrabot-desc sim drive robot.urdf --wheels urdf --twist 0.2,0,5 --twist 0,0.5,4
      myrabot-desc sim settle robot.urdf --junit out/settle.xml      # MuJoCo: does it stand?
      myrabot-desc sim sweep robot.urdf                               # MuJoCo: each joint through its range

    Exit codes: 0 the verdict passes, 1 it fails, 2 the input could not be processed.
    """


@sim_cmd.command("vuelta")
@input_options()
@_outputs
@_drive_options
@click.option("--press", "presses", multiple=True, type=click.FloatRange(min=0), metavar="SECONDS",
              help="Time of a start_button press (true); each press toggles. Repeatable. Default: 1.0.")
@click.option("--feedback-rate", type=click.FloatRange(min=0.1, max=100000), default=100.0, show_default=True,
              help="pose_arm messages per second (the node reacts to each).")
@click.option("--no-collisions", is_flag=True, help="Skip the arm/structure collision check.")
def vuelta_cmd(inputs, duration, rate, as_json, csv_path, plot_path, junit_path, progress, wheels, wheel_speed_max,
               wheel_accel_max, presses, feedback_rate, no_collisions):
    """The seed's "vuelta al ruedo": drive a circle, swing the arm.

    \b
    A start-button press switches the program on: the arm homes (511 on every
    joint), the base drives at 0.1 m/s and 0.3 rad/s, and the arm's base joint
    swings 718 <-> 304 (reversing when the reading is within ±110) while the
    others stay at 511. Verdict: circle radius v/w = 0.333 m within 1 %, period
    2π/0.3 = 20.94 s within 1 %, swings made, no arm/structure collision, and
    the tip-over margin under the turn's centripetal acceleration.

    \b
    Examples:
      myrabot-desc sim vuelta
      myrabot-desc sim vuelta --duration 60 --plot out/vuelta.png --csv out/vuelta.csv
      myrabot-desc sim vuelta --press 1 --press 12    # on, then off (the base keeps turning)
    """
    duration = 25.0 if duration is None else duration
    with guarded():
        robot = _load(inputs, plot_path)
        prog, close = _runner(duration, progress)
        try:
            res = vuelta.run(robot, rate=rate, duration=duration, presses=presses or (1.0,),
                             feedback_rate=feedback_rate, wheels=wheels, wheel_speed_max=wheel_speed_max,
                             wheel_accel_max=wheel_accel_max, check_collisions=not no_collisions,
                             progress=prog)
        finally:
            close()
        _finish(res, as_json, csv_path, plot_path, junit_path)


@sim_cmd.command("drive")
@input_options()
@_outputs
@functools.partial(_drive_options, names=True)
@click.option("--twist", "twists", multiple=True, metavar="V,W,SECONDS",
              help="A script segment: linear m/s, angular rad/s, seconds; or VX,VY,W,SECONDS with a sideways "
                   "speed (mecanum, omni, planar and swerve bases). Repeatable. "
                   "Default: 0.2,0,5 then 0,0.5,4 then 0.2,0.4,5.")
@click.option("--tolerance", type=click.FloatRange(min=0), default=None,
              help="Allowed relative error of the achieved speed and turn rate: against the command (builtin, "
                   "default 0.02) or against the kinematic prediction (mujoco, default 0.10).")
@click.option("--engine", type=click.Choice(["builtin", "mujoco"]), default="builtin", show_default=True,
              help="builtin: the kind's kinematic model (exact arcs from the wheel rates). mujoco: the same "
                   "command to the actuators of our MJCF (wheels; steering of a swerve or Ackermann base; the "
                   "planar base of a mecanum, omni or planar one), the base standing on a floor, compared "
                   "with the kinematic prediction; a mismatch names its cause (wheel gains, a wheel rubbing, "
                   "steering short of its angle, slip, mass on casters, friction).")
def drive_cmd(inputs, duration, rate, as_json, csv_path, plot_path, junit_path, progress, wheels, wheel_speed_max,
              wheel_accel_max, left_wheels, right_wheels, twists, tolerance, engine):
    """Drive any wheeled robot through a scripted twist.

    \b
    The drive is the one check and convert see (a diff-drive or skid-steer
    plugin of any dialect, ros_control velocity wheels, or the joints named
    with --wheels). Compares the commanded motion with what the URDF's wheels
    make of the plugin's wheel rates. A plugin whose wheelSeparation/
    wheelDiameter disagree with the URDF shows here: the Korean wander_bot
    (plugin 0.4/0.2, URDF 0.30/0.16) drives at 0.8x the speed and turns at
    0.8 x 0.4/0.30 = 1.067x; a ROS 1 plugin in legacy mode turns at -1x.
    A skid-steer base drives as its equivalent diff drive. A mecanum, omni,
    planar, swerve or Ackermann base (model/drive.base) runs its kind's
    kinematic model: an omni twist, steered modules, or a bicycle model that
    turns no tighter than its minimum turning radius; --engine mujoco drives
    the same base in MuJoCo against that model.

    \b
    Examples:
      myrabot-desc sim drive tests/fixtures/wander_bot/urdf/robot.xacro -p wander_bot=tests/fixtures/wander_bot
      myrabot-desc sim drive robot.urdf --wheels urdf
      myrabot-desc sim drive robot.urdf --wheels l_wheel_joint,r_wheel_joint
      myrabot-desc sim drive --twist 0.1,0.3,21 --plot out/circle.png     # the bundled MYRAbot
      myrabot-desc sim drive --engine mujoco --junit out/drive.xml          # in MuJoCo, a verdict for CI
    """
    wheels, left, right = _wheel_names(wheels, left_wheels, right_wheels)
    if engine == "mujoco" and (wheel_speed_max or wheel_accel_max or duration):
        raise click.UsageError("--wheel-speed-max, --wheel-accel-max and --duration belong to the builtin engine: "
                               "MuJoCo's wheels have their joints' limits, and the script sets the length")

    try:
        script = tuple(drive.parse_twist(t) for t in twists) or drive.DEFAULT_SCRIPT
    except ValueError as exc:
        raise click.BadParameter(str(exc), param_hint="--twist") from None
    with guarded():
        robot = _load(inputs, plot_path)
        prog, close = _runner(duration or sum(s for *_, s in script), progress)
        try:
            if engine == "mujoco":
                res = physics_drive.run(robot, script=script, wheels=wheels, left=left, right=right,
                                        tolerance=physics_drive.TOLERANCE if tolerance is None else tolerance,
                                        progress=prog)
            else:
                res = drive.run(robot, rate=rate, duration=duration, script=script, wheels=wheels,
                                left=left, right=right, wheel_speed_max=wheel_speed_max,
                                wheel_accel_max=wheel_accel_max, tolerance=0.02 if tolerance is None else tolerance,
                                progress=prog)
        finally:
            close()
        _finish(res, as_json, csv_path, plot_path, junit_path)


def _pointing_options(f):
    opts = [
        click.option("--layout", "layout_path", metavar="YAML", default=None,
                     help="Scene file (default: the bundled layouts/<program>.yaml)."),
        click.option("--object", "which", default="1", show_default=True, metavar="N|NAME",
                     help="Object to point at, like the seed's selected_object: 1, 2, … in spawn order "
                          "among the objects above the floor, or a model name."),
        click.option("--select-at", type=click.FloatRange(min=0), default=0.5, show_default=True,
                     metavar="SECONDS", help="When the object is selected."),
        click.option("--speed", "speed_units", type=click.IntRange(0, 1023), default=400, show_default=True,
                     help="Servo speed register (AX-12 units of 0.111 rpm; 0 = full speed)."),
        click.option("--standoff", type=click.FloatRange(min=0), default=0.05, show_default=True, metavar="M",
                     help="Distance kept between the gripper tip and the object's surface."),
        click.option("--tolerance", type=click.FloatRange(min=0), default=5.0, show_default=True, metavar="DEG",
                     help="Largest pointing error that passes."),
        click.option("--units", "units_mode", type=click.Choice(["nearest", "lab"]), default="nearest",
                     show_default=True,
                     help="Angle -> servo units: the unit nearest the angle, or the lab's truncating "
                          "conversion (up to ~1.3° low per joint)."),
    ]
    for o in reversed(opts):
        f = o(f)
    return f


def _layout(name, path):
    return load_layout(Path(path) if path else data_root() / "layouts" / f"{name}.yaml")


@sim_cmd.command("escoja")
@input_options()
@_outputs
@_pointing_options
@click.option("--hold", type=click.FloatRange(min=0), default=2.0, show_default=True, metavar="SECONDS",
              help="How long the arm points before it returns home.")
def escoja_cmd(inputs, duration, rate, as_json, csv_path, plot_path, junit_path, progress, layout_path, which, select_at,
               speed_units, standoff, tolerance, units_mode, hold):
    """The seed's "escoja": point at the chosen can, hold, return home.

    \b
    The table and the two cans stand where the seed's myrabot_latas.launch put
    them (layouts/escoja.yaml): object 1 is the cola can (the robot's right),
    object 2 the beer can (its left). The arm aims its gripper axis (the
    forearm's line through the wrist) at the can's centre, keeping the tip
    --standoff from it. Verdict: pointing error in degrees, the return home,
    and no collision with the robot, the table or the cans.

    \b
    Examples:
      myrabot-desc sim escoja --object 2
      myrabot-desc sim escoja --object lata_amstel --units lab --json
      myrabot-desc sim escoja --plot out/escoja.png
    """
    with guarded():
        robot = _load(inputs, plot_path)
        objects = _layout("escoja", layout_path)
        prog, close = _runner(duration, progress)
        try:
            res = pointing.run_escoja(robot, objects, which=which, rate=rate, duration=duration,
                                      select_at=select_at, hold=hold, speed_units=speed_units,
                                      standoff=standoff, tolerance=tolerance, units_mode=units_mode,
                                      progress=prog)
        finally:
            close()
        _finish(res, as_json, csv_path, plot_path, junit_path)


@sim_cmd.command("seguir")
@input_options()
@_outputs
@_pointing_options
@click.option("--keys", default=None, metavar="SCRIPT",
              help="mover_objetos key presses, e.g. 'D*16 w*30': C/D move x ±0.005 m, w/s y, A/B z "
                   "(a d e q tilt). Default: 'D*16 w*30 C*16 s*60 w*30'.")
@click.option("--move-at", type=click.FloatRange(min=0), default=2.0, show_default=True, metavar="SECONDS",
              help="When the first key press moves the can (then one step per 0.1 s).")
@click.option("--track-rate", type=click.FloatRange(min=0.1, max=1000), default=10.0, show_default=True,
              metavar="HZ", help="How often the arm re-aims at the can.")
def seguir_cmd(inputs, duration, rate, as_json, csv_path, plot_path, junit_path, progress, layout_path, which, select_at,
               speed_units, standoff, tolerance, units_mode, keys, move_at, track_rate):
    """The seed's "seguir": the arm follows a can moved like mover_objetos moves it.

    \b
    One beer can on the table (layouts/seguir.yaml). From --move-at it is
    moved in 0.005 m steps, one per 0.1 s (mover_objetos' retardo), along a
    key script; the arm re-aims at --track-rate. Verdict: tracking error (the
    pointing error while the can moves) and no collision.

    \b
    Examples:
      myrabot-desc sim seguir
      myrabot-desc sim seguir --keys 'C*20 A*10 B*10 D*20' --csv out/seguir.csv
      myrabot-desc sim seguir --track-rate 2 --plot out/seguir.png
    """
    try:
        if keys is not None:
            pointing.parse_keys(keys)
    except ValueError as exc:
        raise click.BadParameter(str(exc), param_hint="--keys") from None
    with guarded():
        robot = _load(inputs, plot_path)
        objects = _layout("seguir", layout_path)
        prog, close = _runner(duration, progress)
        try:
            res = pointing.run_seguir(robot, objects, which=which, keys=keys or pointing.DEFAULT_KEYS, rate=rate,
                                      duration=duration, select_at=select_at, move_at=move_at,
                                      track_rate=track_rate, speed_units=speed_units, standoff=standoff,
                                      tolerance=tolerance, units_mode=units_mode, progress=prog)
        finally:
            close()
        _finish(res, as_json, csv_path, plot_path, junit_path)


def _physics_outputs(f):
    opts = [
        click.option("--json", "as_json", is_flag=True, help="Print the summary as JSON."),
        click.option("--csv", "csv_path", metavar="FILE", help="Write the time series (or the sweep's poses) as CSV "
                     "('-' = stdout)."),
        click.option("--plot", "plot_path", metavar="PNG", help="Draw the series (or the sweep) as a PNG."),
        click.option("--junit", "junit_path", metavar="FILE",
                     help="Write the verdict as JUnit XML for CI (one test case per check; '-' = stdout)."),
        click.option("--srdf", type=click.Path(dir_okay=False), metavar="FILE",
                     help="The robot's SRDF: the link pairs its <disable_collisions> lets touch may touch; with "
                          "--state, its reference configuration is the start pose."),
        click.option("--progress/--no-progress", default=None, help="Progress bar (default: on a terminal)."),
    ]
    for o in reversed(opts):
        f = o(f)
    return f


@sim_cmd.command("settle")
@input_options()
@_physics_outputs
@click.option("--duration", type=click.FloatRange(min=0.01, max=3600), default=3.0, show_default=True,
              help="Simulated seconds.")
@click.option("--base", type=click.Choice(["auto", "free", "fixed"]), default="auto", show_default=True,
              help="auto: a free base for wheeled robots and robots that stand on legs (the ground touched only by "
                   "limbs of two or more joints, on two or more limbs), else welded where it stands.")
@click.option("--pose", "pose_file", type=click.Path(dir_okay=False), metavar="YAML",
              help="Start pose: joint: value pairs (top level, or under initial_positions/joints/pose).")
@click.option("--state", metavar="NAME", help="Start pose: the SRDF's <group_state> of that name (needs --srdf).")
def settle_cmd(inputs, as_json, csv_path, plot_path, junit_path, srdf, progress, duration, base, pose_file, state):
    """Does it stand? N seconds in MuJoCo from its start pose, actuators holding it.

    \b
    The model is our own `convert --to mjcf`, built in memory. From the start
    pose (--pose, --srdf --state, the package's ros2_control initial
    positions, else the rest pose: every joint at 0 or its nearer limit) the
    robot stands on a floor, every joint held by its position actuator.
    Verdict: no NaN, the base's height, tilt and horizontal drift, the
    ground touched only by what it stood on (feet, wheels, casters), no
    self-contact, joints within 0.1 rad of their start, no energy growth.
    A failure names its cause at its file:line: the centre of mass outside
    the support polygon by X mm, a joint that cannot hold (torque needed T >
    effort E), a link penetrating another by D mm.

    \b
    Examples:
      myrabot-desc sim settle                              # the bundled MYRAbot
      myrabot-desc sim settle robot.urdf --junit out/settle.xml
      myrabot-desc sim settle talos.urdf --srdf talos.srdf --state half_sitting
      myrabot-desc sim settle arm.urdf.xacro --pose config/initial_positions.yaml --plot out/settle.png

    Exit codes: 0 it stands (PASS), 1 it does not (FAIL), 2 the input could not be processed.
    """
    if state and not srdf:
        raise click.UsageError("--state NAME names a <group_state> of the SRDF given with --srdf FILE")
    if state and pose_file:
        raise click.UsageError("give the start pose either with --pose or with --srdf --state, not both")
    with guarded():
        robot = _load(inputs)
        prog, close = _runner(60.0 if progress else 0.0, progress)
        try:
            res = settle.run(robot, duration=duration, base=base, pose_file=pose_file, srdf=srdf, state=state,
                             progress=prog)
        finally:
            close()
        _finish(res, as_json, csv_path, plot_path, junit_path)


@sim_cmd.command("sweep")
@input_options()
@_physics_outputs
@click.option("--samples", type=click.IntRange(min=2, max=10000), default=25, show_default=True,
              help="Values per joint range.")
def sweep_cmd(inputs, as_json, csv_path, plot_path, junit_path, srdf, progress, samples):
    """Each movable joint through its range, the others at rest, in MuJoCo.

    \b
    The robot is welded where it stands. At every pose: self-collisions
    between bodies that are not parent and child (the pairs touching at the
    rest pose, which check P005 reports, and the SRDF's allowed pairs left
    out), with the depth and both collisions' file:line; and the gravity
    torque on every joint against its effort limit (over twice the limit
    fails; between 1x and 2x is a note, as check P006 warns).

    \b
    Examples:
      myrabot-desc sim sweep                               # the bundled MYRAbot's arm
      myrabot-desc sim sweep panda.urdf --srdf panda.srdf --csv out/sweep.csv
      myrabot-desc sim sweep robot.urdf --samples 13 --junit out/sweep.xml

    Exit codes: 0 PASS, 1 FAIL, 2 the input could not be processed.
    """
    with guarded():
        robot = _load(inputs)
        prog, close = _runner(60.0 if progress else 0.0, progress)
        try:
            res = sweep.run(robot, samples=samples, srdf=srdf, progress=prog)
        finally:
            close()
        _finish(res, as_json, csv_path, plot_path, junit_path)
