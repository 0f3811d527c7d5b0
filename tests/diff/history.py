"""The model-history fixtures (tests/fixtures/model_history) as real git repositories, and the
oracle's expected changes set beside ``diff``'s."""

from __future__ import annotations

import math
import shutil
import subprocess
from pathlib import Path

import yaml

from helpers import FIXTURES

HISTORY = FIXTURES / "model_history"
CASES = sorted(p.parent.name for p in HISTORY.glob("*/case.yaml"))


def case(case_id: str) -> dict:
    return yaml.safe_load((HISTORY / case_id / "case.yaml").read_text())


def git(repo: Path, *args: str) -> str:
    env = {"GIT_AUTHOR_NAME": "t", "GIT_AUTHOR_EMAIL": "t@example.org", "GIT_COMMITTER_NAME": "t",
           "GIT_COMMITTER_EMAIL": "t@example.org", "HOME": str(repo), "PATH": "/usr/bin:/bin"}
    return subprocess.run(["git", *args], cwd=repo, check=True, capture_output=True, text=True, env=env).stdout


def replace_tree(repo: Path, src: Path) -> None:
    """The work tree of ``repo`` becomes a copy of ``src`` (its .git kept)."""
    for p in repo.iterdir():
        if p.name != ".git":
            shutil.rmtree(p) if p.is_dir() else p.unlink()
    shutil.copytree(src, repo, dirs_exist_ok=True)


def commit_all(repo: Path, message: str = "step") -> None:
    """Commit the whole work tree. The index is emptied first: a file copied with its time and size
    kept (0.040 -> 0.020) would otherwise look unchanged to git's stat check."""
    git(repo, "read-tree", "--empty")
    git(repo, "add", "-A")


def history_repo(case_id: str, dest: Path) -> Path:
    """A git repository with two commits: the case's old tree, then its new tree."""
    dest.mkdir(parents=True, exist_ok=True)
    git(dest, "init", "-q", "-b", "main")
    for side in ("old", "new"):
        replace_tree(dest, HISTORY / case_id / side)
        commit_all(dest)
        git(dest, "commit", "-q", "--allow-empty", "-m", side)
    return dest


def close(a, b, tol=2e-4) -> bool:
    """Same structure, numbers within ``tol`` (relative for large ones)."""
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(close(a[k], b[k], tol) for k in a)
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(close(x, y, tol) for x, y in zip(a, b))
    if isinstance(a, (int, float)) and isinstance(b, (int, float)) and not isinstance(a, bool):
        return math.isclose(a, b, rel_tol=1e-6, abs_tol=tol)
    return a == b


OURS_ONLY = ("findings_added", "findings_removed", "findings_changed", "frames_moved_rest_pose", "drive",
             "sensors_added", "sensors_removed", "sensors_renamed")


def comparable(changes: dict) -> dict:
    """diff's changes without what the oracle does not compute (findings, the rest pose, sensors) and
    without the drive (compared by drive_changes)."""
    return {k: v for k, v in changes.items() if k not in OURS_ONLY}


def drive_changes(block: dict | None) -> dict:
    """{separation_mm / wheelbase_mm / radius_mm: (old, new)} of a drive block whose measured numbers changed."""
    if not block or not block.get("old") or not block.get("new"):
        return {}
    o, n = block["old"], block["new"]
    out = {}
    for k in ("separation_mm", "wheelbase_mm"):
        if o.get(k) is not None and n.get(k) is not None and not math.isclose(o[k], n[k], abs_tol=1e-3):
            out[k] = (o[k], n[k])
    ro = {round(v, 3) for v in o.get("radius_mm", {}).values() if v is not None}
    rn = {round(v, 3) for v in n.get("radius_mm", {}).values() if v is not None}
    if ro != rn:
        out["radius_mm"] = (sorted(ro), sorted(rn))
    return out
