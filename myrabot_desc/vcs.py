"""Reading a git repository without touching its work tree: the files changed since a revision
(``check --changed-since``) and a revision's files exported into a folder of ours (``diff --rev``).

Everything goes through the ``git`` command (``git diff``, ``git ls-files``, ``git archive``), run
with a fixed argument list (no shell) and a time limit; the export is a tar stream unpacked with
tarfile's ``data`` filter (no absolute paths, no links out of the folder, no devices). A problem is
an InputError: one line, exit 2.
"""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

from myrabot_desc.errors import InputError

TIMEOUT = 120.0


def _git(args: list[str], cwd: Path, binary: bool = False, check: bool = True):
    env = {k: v for k, v in os.environ.items() if not k.startswith("GIT_")}
    env["GIT_TERMINAL_PROMPT"] = "0"
    try:
        res = subprocess.run(["git", *args], cwd=str(cwd), capture_output=True, timeout=TIMEOUT, env=env)
    except FileNotFoundError:
        raise InputError("git is not installed (needed to read revisions)") from None
    except subprocess.TimeoutExpired:
        raise InputError(f"git {args[0]} took longer than {TIMEOUT:g} s") from None
    if check and res.returncode:
        msg = res.stderr.decode("utf-8", "replace").strip().splitlines()
        raise InputError(f"git {args[0]}: {msg[-1] if msg else 'failed'}")
    return res if binary else res.stdout.decode("utf-8", "replace")


def repo_top(path) -> Path | None:
    """The top folder of the git work tree holding ``path`` (a file or folder), or None."""
    p = Path(path).resolve()
    d = p if p.is_dir() else p.parent
    res = _git(["rev-parse", "--show-toplevel"], d, binary=True, check=False)
    if res.returncode:
        return None
    return Path(res.stdout.decode().strip()).resolve()


def commit_of(top: Path, rev: str) -> str:
    """The commit a revision names (InputError when it names none)."""
    if not rev or rev.startswith("-"):
        raise InputError(f"not a revision: {rev!r}")
    res = _git(["rev-parse", "--verify", "--quiet", "--end-of-options", f"{rev}^{{commit}}"], top, binary=True,
               check=False)
    if res.returncode:
        raise InputError(f"{top}: unknown revision {rev!r}")
    return res.stdout.decode().strip()


def changed_files(top: Path, rev: str) -> set[Path]:
    """Files (absolute) that differ between ``rev`` and the work tree, staged or not, plus untracked
    files that are not ignored; deleted files are included (a model that read one changed)."""
    commit = commit_of(top, rev)
    out = _git(["diff", "--name-only", "-z", "--no-renames", commit, "--"], top)
    names = [n for n in out.split("\0") if n]
    untracked = _git(["ls-files", "--others", "--exclude-standard", "-z"], top)
    names += [n for n in untracked.split("\0") if n]
    return {(top / n).resolve() for n in names}


def export(top: Path, rev: str, dest: Path) -> str:
    """The files of revision ``rev`` unpacked into ``dest`` (an empty folder); returns the commit."""
    import io
    import tarfile

    commit = commit_of(top, rev)
    res = _git(["archive", "--format=tar", commit], top, binary=True)
    with tarfile.open(fileobj=io.BytesIO(res.stdout), mode="r:") as tar:
        tar.extractall(dest, filter="data")
    return commit
