"""``myrabot-desc build``: xacro -> URDF."""

from __future__ import annotations

import click

from myrabot_desc.cli_common import guarded, input_options
from myrabot_desc.safety import LIMITS


def limit_options(func):
    """A ``--max-*`` flag for every limit of the table that has one."""
    for lim in reversed(LIMITS):
        if lim.flag:
            func = click.option(lim.flag, type=click.IntRange(min=1), default=None,
                                help=f"{lim.help[0].upper()}{lim.help[1:]} [{lim.default}].")(func)
    return func


@click.command("build")
@input_options()
@click.option("-o", "--output", default=None, metavar="OUT.urdf",
              help="Write the URDF here ('-' for stdout). Default: stdout.")
@click.option("--deps", is_flag=True, help="List the files the build reads (input, includes, YAML), one per line.")
@click.option("--resolve-uris", is_flag=True, help="Rewrite package:// URIs into absolute file:// paths.")
@click.option("--allow-errors", is_flag=True, help="Write the URDF even when the build reports errors (X002).")
@limit_options
def build_cmd(inputs, output, deps, resolve_uris, allow_errors, **limit_flags):
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
    import gc
    import sys

    # One-shot command: the cyclic GC would only rescan the millions of DOM objects of a
    # big expansion once build_file re-enables it (~0.4 s at 4,000 macro calls), and the
    # interpreter's final collection at exit would free them one by one (another ~0.4 s):
    # GC stays off, and what the build left is frozen out of that last collection.
    gc.disable()
    from myrabot_desc.build.driver import build_file
    from myrabot_desc.output import write_output
    from myrabot_desc.safety import LIMITS, Limits

    with guarded():
        limits = Limits(**{lim.field: limit_flags[lim.flag[2:].replace("-", "_")] for lim in LIMITS if lim.flag})
        src = inputs.file
        if src is None:
            from myrabot_desc.model.loader import (
                bundled_path,  # imports the model classes (~25 ms): only when needed
            )

            src = str(bundled_path())
        result = build_file(src, inputs.mappings, packages=inputs.packages, package_paths=inputs.package_paths,
                            legacy=inputs.legacy, unsafe_eval=inputs.unsafe_eval, no_env=inputs.no_env,
                            allow_paths=inputs.allow_paths, limits=limits)
        gc.freeze()
        for d in result.diagnostics:
            click.echo(str(d), err=True)
        if deps:
            write_output(output or "-", "\n".join(result.deps) + "\n", protect=result.deps)
            return
        if result.errors and not allow_errors:
            click.echo(f"{len(result.errors)} error(s): nothing written (use --allow-errors to write anyway)",
                       err=True)
            sys.exit(1)
        text = result.text
        if resolve_uris:
            text = _resolve_uris(result)
        write_output(output or "-", text, protect=result.deps)   # never over its own input
        if output and output != "-":
            click.echo(f"wrote {output}", err=True)
        if result.errors:
            sys.exit(1)


def _resolve_uris(result) -> str:
    """package://pkg/x -> file:///abs/x for every resolvable URI (others stay)."""
    import re

    from myrabot_desc.build.packages import resolve_resource_uri

    def sub(m):
        uri = m.group(2)
        p = resolve_resource_uri(uri, result.package_roots, result.source.parent)
        return f'{m.group(1)}"file://{p}"' if p else m.group(0)

    return re.sub(r'(filename=)"(package://[^"]+)"', sub, result.text)
