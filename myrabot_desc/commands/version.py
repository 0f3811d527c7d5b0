"""What ``myrabot-desc --version`` says: the version, and which commit it is.

The repository is pinned by commit (``rev: <sha>``), so the version number alone does not say what
runs. The commit comes from git when the package runs from a checkout (the folder above the package
is the top of a git work tree), else from ``BUILD_COMMIT``, which the wheel build writes
(hatch_build.py), else it is said to be unknown. A release is a commit that a ``vX.Y.Z`` tag of this
version points at, with no local changes. Standard library only: hatch_build.py loads this file by
its path at build time.
"""

from __future__ import annotations

import os
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1]
BUILD_FILE = PACKAGE / "BUILD_COMMIT"


def _git(top: Path, *args: str) -> str | None:
    import subprocess           # only --version asks git: every other click command loads this module

    env = {k: v for k, v in os.environ.items() if not k.startswith("GIT_")}
    try:
        r = subprocess.run(["git", "-C", str(top), *args], capture_output=True, text=True, env=env,
                           timeout=10, stdin=subprocess.DEVNULL)
    except (OSError, subprocess.SubprocessError):
        return None
    return r.stdout.strip() if r.returncode == 0 else None


def git_state(top: Path, version: str) -> dict | None:
    """``{"commit", "dirty", "release"}`` of the checkout at ``top``, or None when ``top`` is not the
    top of a git work tree (or git is missing)."""
    if not (top / ".git").exists():
        return None
    found = _git(top, "rev-parse", "--show-toplevel")
    if found is None or Path(found).resolve() != top.resolve():
        return None
    commit = _git(top, "rev-parse", "HEAD")
    if not commit:
        return None
    status = _git(top, "status", "--porcelain", "--untracked-files=no")
    dirty = status is None or status != ""
    tags = (_git(top, "tag", "--points-at", "HEAD") or "").split()
    return {"commit": commit, "dirty": dirty, "release": f"v{version}" in tags and not dirty}


def build_state() -> dict | None:
    """What the wheel build recorded (``commit dirty|clean release|-``), or None."""
    try:
        words = BUILD_FILE.read_text(encoding="ascii").split()
    except (OSError, UnicodeDecodeError):
        return None
    if len(words) != 3 or len(words[0]) != 40 or words[1] not in ("dirty", "clean"):
        return None
    return {"commit": words[0], "dirty": words[1] == "dirty", "release": words[2] == "release"}


def describe(version: str) -> str:
    """``0.2.0`` for a release; else the version with the commit it was made from, e.g.
    ``0.2.0 (commit 6bd9305..., with local changes)``, or ``0.2.0 (commit unknown)``."""
    state = git_state(PACKAGE.parent, version) or build_state()
    if state is None:
        return f"{version} (commit unknown: not a git checkout, and not built from one)"
    if state["release"]:
        return f"{version} (release v{version}, commit {state['commit']})"
    changes = ", with local changes" if state["dirty"] else ""
    return f"{version} (commit {state['commit']}{changes}; not a release)"
