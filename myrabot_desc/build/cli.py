"""``myrabot-desc build``: xacro -> URDF."""

from __future__ import annotations

import click

from myrabot_desc.cli_common import guarded, input_options


@click.command("build")
@input_options()
@click.option("-o", "--output", default=None, metavar="OUT.urdf",
              help="Write the URDF here ('-' for stdout). Default: stdout.")
@click.option("--deps", is_flag=True, help="List the files the build reads (input, includes, YAML), one per line.")
@click.option("--resolve-uris", is_flag=True, help="Rewrite package:// URIs into absolute file:// paths.")
@click.option("--allow-errors", is_flag=True, help="Write the URDF even when the build reports errors (X002).")
@click.option("--max-input-bytes", type=int, default=None, help="Largest input file accepted [20000000].")
@click.option("--max-include-depth", type=int, default=None, help="Deepest include nesting [32].")
@click.option("--max-macro-depth", type=int, default=None, help="Deepest macro call nesting [200].")
@click.option("--max-macro-calls", type=int, default=None, help="Most macro calls in one build [20000].")
@click.option("--max-elements", type=int, default=None, help="Most elements macros may produce [200000].")
def build_cmd(inputs, output, deps, resolve_uris, allow_errors, max_input_bytes, max_include_depth,
              max_macro_depth, max_macro_calls, max_elements):
    """Expand a xacro file into URDF, with no ROS installed.

    FILE defaults to the bundled MYRAbot (xacro/myrabot.urdf.xacro). Files written
    for ROS Electric/Fuerte (un-prefixed <macro>, <include>, <property>,
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
    Limits (flags here, or for every command the environment):
      MYRABOT_DESC_MAX_INPUT_BYTES, MYRABOT_DESC_MAX_INCLUDE_DEPTH,
      MYRABOT_DESC_MAX_MACRO_DEPTH, MYRABOT_DESC_MAX_MACRO_CALLS, MYRABOT_DESC_MAX_ELEMENTS;
      meshes: MYRABOT_DESC_MAX_MESH_BYTES [50000000], MYRABOT_DESC_MAX_MESH_TRIANGLES [2000000];
      material scripts: MYRABOT_DESC_MAX_MATERIAL_BYTES [5242880].

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
    from myrabot_desc.safety import Limits
    from myrabot_desc.output import write_output

    with guarded():
        limits = Limits()
        if max_input_bytes:
            limits.max_input_bytes = max_input_bytes
        if max_include_depth:
            limits.max_include_depth = max_include_depth
        if max_macro_depth:
            limits.max_macro_depth = max_macro_depth
        if max_macro_calls:
            limits.max_macro_calls = max_macro_calls
        if max_elements:
            limits.max_output_elements = max_elements
        src = inputs.file
        if src is None:
            from myrabot_desc.model.loader import bundled_path  # imports the model classes (~25 ms): only when needed

            src = str(bundled_path())
        result = build_file(src, inputs.mappings, packages=inputs.packages, package_paths=inputs.package_paths,
                            legacy=inputs.legacy, unsafe_eval=inputs.unsafe_eval, no_env=inputs.no_env,
                            allow_paths=inputs.allow_paths, limits=limits)
        gc.freeze()
        for d in result.diagnostics:
            click.echo(str(d), err=True)
        if deps:
            write_output(output or "-", "\n".join(result.deps) + "\n")
            return
        if result.errors and not allow_errors:
            click.echo(f"{len(result.errors)} error(s): nothing written (use --allow-errors to write anyway)",
                       err=True)
            sys.exit(1)
        text = result.text
        if resolve_uris:
            text = _resolve_uris(result)
        write_output(output or "-", text)
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
