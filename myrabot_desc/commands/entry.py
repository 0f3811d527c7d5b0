"""The console entry point (``myrabot-desc``).

A plain ``build ...`` command line runs straight from commands/fastbuild.py, parsed from the same
option tables as the click command, without importing click (``build`` must start faster
than the xacro CLI); a plain ``diff ...`` runs from commands/fastdiff.py (a diff's target is
twice the time of two builds, which import no click: ~12 ms of a small robot's ~300 ms diff), and a
plain ``check ...`` from commands/fastcheck.py (a lint run on every commit: click is a tenth of a
small robot's check).
The top-level ``--help`` prints click's own text, stored (commands/plain_help.py).
Everything else, including a command's ``--help`` and any command line the plain parser does not take
(unusual forms, errors), goes to the click group in commands/main.py, which gives its usual
output and exit codes.

The imports inside main() are the point of this module: it picks which path to load, so that
none pays for another's imports, and the build engine is loaded only for a command line the
plain path takes (not for ``build --help``). With commands/build.py's and
commands/main.py's lazy subcommand table they are the only function-level imports of our own
modules (tests/model/test_layers.py).
"""

from __future__ import annotations

import gc
import os
import sys

from myrabot_desc.commands import options
from myrabot_desc.commands.console import guarded, out
from myrabot_desc.commands.plain_help import top_help
from myrabot_desc.commands.options import BUILD_OPTS, CHECK_OPTS, DIFF_OPTS, INPUT_OPTS, parse_plain


def main(argv=None) -> int:
    # Our numpy work is on small arrays: one BLAS thread is as fast, and OpenBLAS starting a
    # thread pool per core costs ~50 ms of every command that imports numpy (check, convert,
    # sim), more in each `check -j N` worker. The user's own setting wins.
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    args = sys.argv[1:] if argv is None else list(argv)
    options.ONE_SHOT = argv is None
    if options.ONE_SHOT:
        # One short process that keeps what it allocates (modules, classes, a model's records): at
        # the default young generation (700 objects) the collector rescans them ~35 times in a small
        # robot's check (~8 ms). Larger generations free the same garbage, less often.
        gc.set_threshold(50_000, 20, 10)
    if args in (["--help"], ["-h"]):
        text = top_help()
        if text is not None:
            with guarded():          # a full disk or a closed stdout: one line, as every command says it
                out(text)
            return 0
    if args[:1] == ["build"] and parse_plain(args[1:], INPUT_OPTS + BUILD_OPTS) is not None:
        from myrabot_desc.commands.fastbuild import fast_build

        code = fast_build(args[1:])
        if code is not None:
            return code
    if args[:1] == ["diff"] and parse_plain(args[1:], INPUT_OPTS + DIFF_OPTS) is not None:
        from myrabot_desc.commands.fastdiff import fast_diff

        code = fast_diff(args[1:])
        if code is not None:
            return code
    if args[:1] == ["check"] and parse_plain(args[1:], INPUT_OPTS + CHECK_OPTS) is not None:
        from myrabot_desc.commands.fastcheck import fast_check

        code = fast_check(args[1:])
        if code is not None:
            return code
    from myrabot_desc.commands.main import main as cli

    with guarded():                  # click's own writing (a --help on a full disk) included
        return cli(args=args)


if __name__ == "__main__":
    sys.exit(main())
