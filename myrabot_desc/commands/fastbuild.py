"""What ``myrabot-desc build`` does, and its options (one table), without click.

commands/build.py makes the click command from these; the console entry (commands/entry.py) runs a
plain ``build ...`` command line straight from here, with parse_plain over the same tables, so a
build does not pay for importing click (~25 ms, a third of a small robot's build). Nothing this
module imports loads click, lxml, dataclasses, typing or inspect (tests/expand/test_plain_command_line.py).
"""

from __future__ import annotations

import gc
import sys

from myrabot_desc.commands.console import echo, guarded
from myrabot_desc.commands.options import BUILD_OPTS, INPUT_OPTS, UsageProblem, make_inputs, parse_plain
from myrabot_desc.expand.driver import build_file
from myrabot_desc.expand.packages import bundled_path, file_uris
from myrabot_desc.output import write_output
from myrabot_desc.safety import LIMITS, Limits


def fast_build(argv) -> int | None:
    """Run ``build`` for a plain command line (see cli_common.parse_plain); None when the
    command line needs click (help, errors, unusual forms): the caller hands it to click."""
    values = parse_plain(argv, INPUT_OPTS + BUILD_OPTS)
    if values is None:
        return None
    try:
        inputs = make_inputs(values)
    except UsageProblem:
        return None
    try:
        run_build(inputs, one_shot=True, **{o.dest: values[o.dest] for o in BUILD_OPTS})
    except KeyboardInterrupt:     # as click's standalone mode says it
        echo("")
        echo("Aborted!")
        return 1
    return 0


def run_build(inputs, output=None, deps=False, resolve_uris=False, allow_errors=False, one_shot=False,
              **limit_flags) -> None:
    """The build command itself (click's and the fast path's); exits 1 or 2 on errors."""
    # A one-shot process (the console script's fast path): the cyclic GC would only rescan the
    # millions of DOM objects of a big expansion once build_file re-enables it (~0.4 s at 4,000
    # macro calls), and the interpreter's final collection at exit would free them one by one
    # (another ~0.4 s): GC stays off, and what the build left is frozen out of that last
    # collection. Never in a process that goes on (tests, library use): that would leak each
    # build's document.
    if one_shot:
        gc.disable()
    with guarded():
        limits = Limits(**{lim.field: limit_flags[lim.flag[2:].replace("-", "_")] for lim in LIMITS if lim.flag})
        src = inputs.file
        if src is None:
            src = str(bundled_path())
        result = build_file(src, inputs.mappings, packages=inputs.packages, package_paths=inputs.package_paths,
                            legacy=inputs.legacy, unsafe_eval=inputs.unsafe_eval, no_env=inputs.no_env,
                            allow_paths=inputs.allow_paths, limits=limits, sources=False)
        if one_shot:
            gc.freeze()
        for d in result.diagnostics:
            echo(str(d))
        if deps:
            write_output(output or "-", "\n".join(result.deps) + "\n", protect=result.deps)
            return
        if result.errors and not allow_errors:
            echo(f"{len(result.errors)} error(s): nothing written (use --allow-errors to write anyway)")
            sys.exit(1)
        text = result.text
        if resolve_uris:
            text = file_uris(result.text, result.package_roots, result.source.parent)
        write_output(output or "-", text, protect=result.deps)   # never over its own input
        if output and output != "-":
            echo(f"wrote {output}")
        if result.errors:
            sys.exit(1)

