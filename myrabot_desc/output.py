"""Write outputs atomically: a temporary file in the target folder, then rename.

On any failure nothing is left behind. ``-`` means standard output.
"""

from __future__ import annotations

import errno
import os
import sys
from pathlib import Path

from myrabot_desc.diagnostics import Loc
from myrabot_desc.errors import InputError


def _check_target(target: Path, protect=()) -> None:
    if target.is_dir():
        raise InputError(f"cannot write {target}: it is a folder; give a file name (e.g. {target / 'out'})",
                         Loc(str(target)))
    try:
        real = target.resolve()
    except (OSError, RuntimeError):
        return
    if any(real == _real(p) for p in protect):
        raise InputError(f"refusing to write {target}: it is an input of this run (it would be overwritten)",
                         Loc(str(target)))


def _special(p: Path) -> bool:
    """A target to write into rather than rename over: a device or FIFO (/dev/null), anything
    under /dev or /proc (/dev/stdout is a symlink to /proc/self/fd/1). (A symlink elsewhere is
    resolved: its file is replaced atomically, the link stays.)"""
    import stat

    if str(p.absolute()).startswith(("/dev/", "/proc/")):
        return True
    try:
        mode = os.stat(p).st_mode
    except OSError:
        return False
    return not stat.S_ISREG(mode) and not stat.S_ISDIR(mode)


def _through_link(p: Path) -> Path:
    try:
        return p.resolve() if p.is_symlink() else p
    except (OSError, RuntimeError):
        return p


def _real(p) -> Path | None:
    try:
        return Path(p).resolve()
    except (OSError, RuntimeError, ValueError):
        return None


def write_output(path: str | os.PathLike, data: str | bytes, protect=()) -> None:
    """One output, atomically (temp file in the target folder, then rename). ``protect``: the
    files this run read (a model, its includes): naming one of them as the output is refused."""
    write_outputs([(path, data)], protect)


def write_outputs(items, protect=()) -> None:
    """Several outputs as one transaction: every file is written to a temporary file next to its
    target first; only when all are written are they renamed into place. On any failure no
    target is touched, no temporary file stays, and the folders made for the targets go too."""
    staged: list[tuple[str, Path]] = []
    created: list[Path] = []
    to_stdout = [data for path, data in items if str(path) == "-"]
    files = [(_through_link(Path(path)), data) for path, data in items
             if str(path) != "-" and not _special(Path(path))]
    # /dev/null, /dev/stdout, a FIFO: written into, never renamed over (as root, a rename would
    # replace /dev/null itself with a regular file)
    direct = [(Path(path), data) for path, data in items if str(path) != "-" and _special(Path(path))]
    try:
        for target, _ in files:
            _check_target(target, protect)
        for target, data in files:
            try:
                p = target.parent.absolute()
                made = []
                while not p.exists():
                    made.append(p)
                    p = p.parent
                target.parent.mkdir(parents=True, exist_ok=True)
                created.extend(reversed(made))
                # (not tempfile.mkstemp: importing tempfile costs more than the whole write of a small URDF)
                tmp = str(target.parent / f".{target.name}.{os.getpid()}.{os.urandom(6).hex()}.tmp")
                fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_CLOEXEC", 0), 0o666)
            except OSError as exc:
                raise InputError(f"cannot write {target}: {exc.strerror}", Loc(str(target))) from None
            staged.append((tmp, target))
            try:
                with os.fdopen(fd, "wb") as fh:
                    fh.write(data.encode("utf-8") if isinstance(data, str) else data)
            except OSError as exc:
                raise InputError(f"cannot write {target}: {exc.strerror}", Loc(str(target))) from None
        # /dev/null, a terminal, a FIFO: written before any staged file is renamed into place, so that
        # a failure there (/dev/full, a FIFO with no reader) leaves no file of the transaction behind
        for target, data in direct:
            _write_direct(target, data)
        for tmp, target in staged:
            os.replace(tmp, target)
    except BaseException:
        for tmp, _ in staged:
            try:
                os.unlink(tmp)
            except OSError:
                pass
        for d in reversed(created):
            try:
                d.rmdir()          # only if still empty
            except OSError:
                break
        raise
    for data in to_stdout:
        if isinstance(data, bytes):
            sys.stdout.buffer.write(data)
        else:
            sys.stdout.write(data)
        sys.stdout.flush()


def _write_direct(target: Path, data) -> None:
    """Write into a device or FIFO (appended: no truncation of what fd 1 already holds). Opened
    without blocking: a FIFO nobody reads is refused at once (ENXIO) instead of hanging."""
    import fcntl

    try:
        fd = os.open(target, os.O_WRONLY | os.O_APPEND | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    except OSError as exc:
        if exc.errno == errno.ENXIO:
            raise InputError(f"refusing to write {target}: a FIFO that nothing reads (it would block)",
                             Loc(str(target))) from None
        raise InputError(f"cannot write {target}: {exc.strerror}", Loc(str(target))) from None
    try:
        flags = fcntl.fcntl(fd, fcntl.F_GETFL)
        fcntl.fcntl(fd, fcntl.F_SETFL, flags & ~os.O_NONBLOCK)   # a reader is there: write it all
        with os.fdopen(fd, "ab") as fh:
            fd = None
            fh.write(data.encode("utf-8") if isinstance(data, str) else data)
    except OSError as exc:
        raise InputError(f"cannot write {target}: {exc.strerror}", Loc(str(target))) from None
    finally:
        if fd is not None:
            os.close(fd)


class OutputDir:
    """Stage several output files (e.g. an MJCF plus meshes) and publish them together.

    Files are written into a hidden staging folder next to the target; ``commit``
    moves them into place. If the block raises, the staging folder is removed, and so
    are the folders created for the target: a failed command leaves nothing behind.
    """

    def __init__(self, target_dir: str | os.PathLike):
        self.target = Path(target_dir)

    def __enter__(self) -> Path:
        import signal
        import tempfile
        import threading

        self.created = []                  # folders made here, innermost last
        p = self.target.absolute()
        while not p.exists():
            self.created.append(p)
            p = p.parent
        self.created.reverse()
        if self.target.exists() and not self.target.is_dir():
            raise InputError(f"cannot write into {self.target}: it is a file, not a folder")
        try:
            self.target.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise InputError(f"cannot write into {self.target}: {exc.strerror}") from None
        _clean_stale_stages(self.target)
        self.saved_term = None
        if threading.current_thread() is threading.main_thread():
            # SIGTERM: unwind through __exit__ (staging removed) instead of dying in place; set
            # before the staging folder exists, so that no moment leaves one behind
            self.saved_term = signal.signal(signal.SIGTERM, _terminate)
        # the staging folder is named for this process: a run killed with SIGKILL leaves it, and
        # the next run into the same folder removes it (the process is gone)
        try:
            self.stage = Path(tempfile.mkdtemp(prefix=f".staging.{os.getpid()}.", dir=self.target))
        except BaseException:
            if self.saved_term is not None:
                signal.signal(signal.SIGTERM, self.saved_term)
            raise
        return self.stage

    def __exit__(self, exc_type, exc, tb):
        import shutil
        import signal

        # a SIGTERM during the clean-up waits until it is done (then acts as it would have)
        blocked = self.saved_term is not None
        if blocked:
            signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGTERM})
        try:
            self._finish(exc_type, shutil)
        finally:
            if blocked:
                signal.signal(signal.SIGTERM, self.saved_term)
                signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGTERM})
        return False

    def _finish(self, exc_type, shutil) -> None:
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


def _terminate(signum, frame):
    raise SystemExit(128 + signum)


def _clean_stale_stages(folder: Path) -> None:
    """Remove ``.staging.<pid>.*`` folders of processes that no longer run."""
    import shutil

    try:
        entries = [e for e in folder.iterdir() if e.name.startswith(".staging.") and e.is_dir()]
    except OSError:
        return
    for e in entries:
        pid = e.name.split(".")[2] if e.name.count(".") >= 3 else ""
        if pid.isdigit() and int(pid) != os.getpid():
            try:
                os.kill(int(pid), 0)
                continue            # still running (another run writing here)
            except ProcessLookupError:
                pass
            except OSError:
                continue
        elif pid.isdigit():
            continue
        shutil.rmtree(e, ignore_errors=True)
