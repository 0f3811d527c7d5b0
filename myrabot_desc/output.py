"""Write outputs atomically: a temporary file in the target folder, then rename.

On any failure nothing is left behind. ``-`` means standard output.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

from myrabot_desc.errors import InputError


def write_output(path: str | os.PathLike, data: str | bytes) -> None:
    if str(path) == "-":
        if isinstance(data, bytes):
            sys.stdout.buffer.write(data)
        else:
            sys.stdout.write(data)
        sys.stdout.flush()
        return
    target = Path(path)
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        # (not tempfile.mkstemp: importing tempfile costs more than the whole write of a small URDF)
        tmp = str(target.parent / f".{target.name}.{os.getpid()}.{os.urandom(6).hex()}.tmp")
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_CLOEXEC", 0), 0o666)
    except OSError as exc:
        raise InputError(f"cannot write {target}: {exc.strerror}") from None
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data.encode("utf-8") if isinstance(data, str) else data)
        os.replace(tmp, target)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise


class OutputDir:
    """Stage several output files (e.g. an MJCF plus meshes) and publish them together.

    Files are written into a hidden staging folder next to the target; ``commit``
    moves them into place. If the block raises, the staging folder is removed, and so
    are the folders created for the target: a failed command leaves nothing behind.
    """

    def __init__(self, target_dir: str | os.PathLike):
        self.target = Path(target_dir)

    def __enter__(self) -> Path:
        import tempfile

        self.created = []                  # folders made here, innermost last
        p = self.target.absolute()
        while not p.exists():
            self.created.append(p)
            p = p.parent
        self.created.reverse()
        self.target.mkdir(parents=True, exist_ok=True)
        self.stage = Path(tempfile.mkdtemp(prefix=".staging.", dir=self.target))
        return self.stage

    def __exit__(self, exc_type, exc, tb):
        import shutil

        try:
            if exc_type is None:
                for item in sorted(self.stage.rglob("*")):
                    if item.is_file():
                        dest = self.target / item.relative_to(self.stage)
                        dest.parent.mkdir(parents=True, exist_ok=True)
                        os.replace(item, dest)
        finally:
            shutil.rmtree(self.stage, ignore_errors=True)
            if exc_type is not None:
                for d in reversed(self.created):
                    try:
                        d.rmdir()          # only if still empty
                    except OSError:
                        break
        return False
