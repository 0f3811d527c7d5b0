"""Write the fixed sources: every file of the run in one transaction, each keeping its mode."""

from __future__ import annotations

import os

from myrabot_desc.diagnostics import Loc
from myrabot_desc.errors import InputError
from myrabot_desc.output import write_outputs


def write_fixed(files) -> None:
    """``files``: FileFix records. A file changed on disk since it was read is not overwritten (the
    whole run is refused: nothing is written)."""
    if not files:
        return
    modes = {}
    for f in files:
        try:
            if f.path.read_bytes() != f.old:
                raise InputError(f"{f.name} changed while it was being fixed: nothing written", Loc(f.name))
            modes[f.path] = os.stat(f.path).st_mode & 0o7777
        except OSError as exc:
            raise InputError(f"cannot read {f.name}: {exc.strerror}", Loc(f.name)) from None
    write_outputs([(f.path, f.new) for f in files])
    for path, mode in modes.items():
        try:
            os.chmod(path, mode)
        except OSError:
            pass
