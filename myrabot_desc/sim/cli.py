"""``myrabot-desc sim``: run the seed's programs in the built-in simulator and give a verdict."""

from __future__ import annotations

import functools
import sys

import click

from myrabot_desc.cli_common import guarded, input_options


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
        click.option("--progress/--no-progress", default=None,
                     help="Progress bar (default: on a terminal, for runs of 60 simulated seconds or more)."),
    ]
    for o in reversed(opts):
        f = o(f)
    return f


def _drive_options(f):
    opts = [
        click.option("--wheels", type=click.Choice(["plugin", "urdf"]), default="plugin", show_default=True,
                     help="Whose wheel separation/diameter turn cmd_vel into wheel rates: the diff-drive "
                          "plugin's (as Gazebo does) or the URDF's. The URDF's always move the robot."),
        click.option("--wheel-speed-max", type=click.FloatRange(min=0, min_open=True), default=None,
                     metavar="RAD/S", help="Wheel joint rate limit (both wheels scale, keeping the curvature)."),
        click.option("--wheel-accel-max", type=click.FloatRange(min=0, min_open=True), default=None,
                     metavar="RAD/S2", help="Wheel joint acceleration limit (linear ramps)."),
    ]
    for o in reversed(opts):
        f = o(f)
    return f


def _finish(res, as_json, csv_path, plot_path):
    from myrabot_desc.output import write_output

    if plot_path:
        from myrabot_desc.sim.plot import render

        write_output(plot_path, render(res))
    if csv_path:
        write_output(csv_path, res.csv_bytes())
    if csv_path != "-":
        click.echo(res.as_json() if as_json else res.summary(), nl=False)
    sys.exit(0 if res.passed else 1)


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
    """Run the seed's programs in a built-in kinematic and diff-drive simulator.

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
def vuelta_cmd(inputs, duration, rate, as_json, csv_path, plot_path, progress, wheels, wheel_speed_max,
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
    from myrabot_desc.sim import vuelta

    duration = 25.0 if duration is None else duration
    with guarded():
        robot = inputs.load()
        prog, close = _runner(duration, progress)
        try:
            res = vuelta.run(robot, rate=rate, duration=duration, presses=presses or (1.0,),
                             feedback_rate=feedback_rate, wheels=wheels, wheel_speed_max=wheel_speed_max,
                             wheel_accel_max=wheel_accel_max, check_collisions=not no_collisions,
                             progress=prog)
        finally:
            close()
        _finish(res, as_json, csv_path, plot_path)


@sim_cmd.command("drive")
@input_options()
@_outputs
@_drive_options
@click.option("--twist", "twists", multiple=True, metavar="V,W,SECONDS",
              help="A script segment: linear m/s, angular rad/s, seconds. Repeatable. "
                   "Default: 0.2,0,5 then 0,0.5,4 then 0.2,0.4,5.")
@click.option("--tolerance", type=click.FloatRange(min=0), default=0.02, show_default=True,
              help="Allowed relative error of the achieved speed and turn rate.")
def drive_cmd(inputs, duration, rate, as_json, csv_path, plot_path, progress, wheels, wheel_speed_max,
              wheel_accel_max, twists, tolerance):
    """Drive any robot with a diff-drive plugin through a scripted twist.

    \b
    Compares the commanded motion with what the URDF's wheels make of the
    plugin's wheel rates. A plugin whose wheelSeparation/wheelDiameter disagree
    with the URDF shows here: the Korean wander_bot (plugin 0.4/0.2, URDF
    0.30/0.16) drives at 0.8x the speed and turns at 0.8 x 0.4/0.30 = 1.067x.

    \b
    Examples:
      myrabot-desc sim drive tests/fixtures/wander_bot/urdf/robot.xacro -p wander_bot=tests/fixtures/wander_bot
      myrabot-desc sim drive robot.urdf --wheels urdf
      myrabot-desc sim drive --twist 0.1,0.3,21 --plot out/circle.png     # the bundled MYRAbot
    """
    from myrabot_desc.sim import drive

    try:
        script = tuple(drive.parse_twist(t) for t in twists) or drive.DEFAULT_SCRIPT
    except ValueError as exc:
        raise click.BadParameter(str(exc), param_hint="--twist") from None
    with guarded():
        robot = inputs.load()
        prog, close = _runner(duration or sum(s for *_, s in script), progress)
        try:
            res = drive.run(robot, rate=rate, duration=duration, script=script, wheels=wheels,
                            wheel_speed_max=wheel_speed_max, wheel_accel_max=wheel_accel_max,
                            tolerance=tolerance, progress=prog)
        finally:
            close()
        _finish(res, as_json, csv_path, plot_path)
