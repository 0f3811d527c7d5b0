"""Reading a git repository without touching its work tree: the files changed since a revision
(``check --changed-since``) and a revision's files exported into a folder of ours (``diff --rev``).

Everything goes through the ``git`` command (``git diff``, ``git ls-files``, ``git archive``), run
with a fixed argument list (no shell) and a time limit; the export is a tar stream unpacked into
our own folder (folders, files and links that stay inside it; no absolute path, no ``..``). A problem is
an InputError: one line, exit 2. subprocess is imported where git runs: ``check`` imports this module
for ``--changed-since`` only.
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

from myrabot_desc.errors import InputError

TIMEOUT = 120.0


def _git(args: list[str], cwd: Path, binary: bool = False, check: bool = True):
    import subprocess

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
    """The top folder of the git work tree holding ``path`` (a file or folder), or None: the nearest
    folder above holding ``.git`` (a folder, or the file of a linked work tree or submodule)."""
    p = Path(path).resolve()
    d = p if p.is_dir() else p.parent
    for c in (d, *d.parents):
        if (c / ".git").exists():
            return c
    return None


def tracked(top: Path, paths, folder: Path) -> set[Path]:
    """Those of ``paths`` (absolute, below ``folder``, in the work tree at ``top``) that git tracks:
    git never ignores a tracked file, whatever a ``.gitignore`` says. One ``git ls-files`` of the
    folder (a literal path, no fsmonitor hook); empty when git cannot tell."""
    paths = {Path(p) for p in paths}
    if not paths:
        return set()
    try:
        out = _git(["--literal-pathspecs", "-c", "core.fsmonitor=false", "ls-files", "-z", "--cached", "--",
                    os.path.relpath(Path(folder).resolve(), top)], top)
    except InputError:
        return set()
    listed = {(top / n) for n in out.split("\0") if n}
    return {p for p in paths if p in listed}


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


def load_export() -> None:
    """Import what ``export`` reads a revision with (a caller exporting two revisions in two
    processes, ``diff``, imports it once, before forking)."""
    import tarfile  # noqa: F401


def export(top: Path, rev: str, dest: Path, like: Path | None = None) -> None:
    """The files of revision ``rev`` unpacked into ``dest`` (an empty folder of ours). ``like``: a
    folder of ours holding another revision's export: a file with the same bytes at the same place
    there is linked (a second name of the same file) instead of written again. Two revisions share
    most of their files, and writing a file (a new inode) costs far more than naming one (on the
    machine of bench/bench_diff.py, 0.3 ms a file in a fresh folder under /tmp against 0.01 ms a
    link: most of a diff's system time)."""
    import io
    import tarfile

    if not rev or rev.startswith("-"):
        raise InputError(f"not a revision: {rev!r}")
    res = _git(["archive", "--format=tar", rev], top, binary=True, check=False)
    if res.returncode:
        raise InputError(f"{top}: unknown revision {rev!r}")
    with tarfile.open(fileobj=io.BytesIO(res.stdout), mode="r:") as tar:
        _unpack(tar, Path(dest), Path(like) if like is not None else None)


def _unpack(tar, dest: Path, like: Path | None = None) -> None:
    """git archive's members into ``dest``: folders, regular files, and symbolic links that stay
    inside ``dest``; a name that is absolute or climbs out (``..``) is refused. (tarfile's own
    ``data`` filter does the same with a realpath per member: ten times slower on a corpus.) A file
    whose bytes the regular file at the same place under ``like`` already holds is linked to it."""
    made = {dest}
    links = []
    for m in tar:
        parts = m.name.split("/")
        if m.name.startswith("/") or ".." in parts or "\0" in m.name:
            raise InputError(f"the revision holds a path that leaves its folder: {m.name!r}")
        target = dest.joinpath(*[p for p in parts if p and p != "."])
        if m.isdir():
            if target not in made:
                target.mkdir(parents=True, exist_ok=True)
                made.add(target)
            continue
        if target.parent not in made:
            target.parent.mkdir(parents=True, exist_ok=True)
            made.add(target.parent)
        if m.isfile():
            f = tar.extractfile(m)
            data = f.read() if f is not None else b""
            if like is None or not _link_same(like.joinpath(*target.relative_to(dest).parts), data, target):
                target.write_bytes(data)
        elif m.issym():
            links.append((target, m.linkname))
    for target, link in links:         # a link is made once every file is there; it must stay inside
        if link.startswith("/"):
            continue
        resolved = (target.parent / link).resolve()
        if resolved.is_relative_to(dest.resolve()):
            target.symlink_to(link)


def _link_same(other: Path, data: bytes, target: Path) -> bool:
    """Link ``target`` to ``other`` when ``other`` is a regular file holding ``data``; False when it
    is not (or the file system cannot link): the caller writes it."""
    try:
        st = os.lstat(other)
        if not stat.S_ISREG(st.st_mode) or st.st_size != len(data) or other.read_bytes() != data:
            return False
        os.link(other, target)
    except OSError:
        return False
    return True
