"""``myrabot-desc build``: xacro -> URDF."""

from __future__ import annotations

import click

from myrabot_desc.commands.options import BUILD_OPTS, input_options


def build_options(func):
    """click's options of the one table (options.BUILD_OPTS)."""
    for o in reversed(BUILD_OPTS):
        func = o.click_option()(func)
    return func


@click.command("build")
@input_options()
@build_options
def build_cmd(inputs, **options):
    """Expand a xacro file into URDF (or any XML: SDF, SRDF, launch), with no ROS installed.

    FILE defaults to the bundled MYRAbot (xacro/myrabot.urdf.xacro). <robot> files
    written for ROS Electric/Fuerte (un-prefixed <macro>, <include>, <property>,
    <insert_block>, bare macro calls) are upgraded and reported (X001). Packages
    for $(find pkg) and package://pkg come from -p, the input's own package
    (package.xml or manifest.xml), --package-path, ROS_PACKAGE_PATH,
    AMENT_PREFIX_PATH and packages installed in Python.

    \b
    Examples:
      myrabot-desc build -o out/myrabot.urdf
      myrabot-desc build robot.urdf.xacro use_gpu:=false -o robot.urdf
      myrabot-desc build old/myrabot.urdf.xacro --package-path old/ -o -
      myrabot-desc build robot.urdf.xacro --deps

    \b
    Limits: the --max-* flags here; for every command the environment variables
    listed by `myrabot-desc --help` (MYRABOT_DESC_MAX_*).

    \b
    Exit codes: 0 built; 1 built with errors (e.g. X002, nothing written);
    2 the input could not be processed (one line with file:line).
    """
    # the build engine is loaded when a build runs, not for `build --help` or a usage error
    # (start-up, bench/bench_start.py; one of the three function-level imports of our own
    # modules, all in commands/: tests/model/test_layers.py)
    from myrabot_desc.commands.fastbuild import run_build

    run_build(inputs, **options)
