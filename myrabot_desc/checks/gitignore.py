"""``check -r`` leaves out what git ignores: the ``.gitignore`` files of the folder's repository
(from its top down to each file's folder) and ``.git/info/exclude``, read with pathspec's
gitignore rules (a deeper file's rule wins; ``!pattern`` re-includes). As in git, a tracked file is
never ignored: when a rule would leave out a file of a repository, ``git ls-files`` says whether it
is tracked (a pull request adding a pattern cannot drop a committed robot from the lint). A
folder outside any repository reads the ``.gitignore`` files from the given folder down.
"""

from __future__ import annotations

from pathlib import Path

from myrabot_desc.vcs import repo_top, tracked

MAX_BYTES = 1_000_000


def _spec(path: Path):
    import pathspec

    try:
        if not path.is_file() or path.stat().st_size > MAX_BYTES:
            return None
        lines = path.read_text(encoding="utf-8", errors="replace").splitlines()
    except OSError:
        return None
    return pathspec.GitIgnoreSpec.from_lines(lines)


class Ignores:
    def __init__(self, folder):
        folder = Path(folder).resolve()
        self.top = repo_top(folder) or folder      # outside a repository: the folder's own files
        self._specs: dict[Path, object] = {}

    def _at(self, d: Path):
        if d not in self._specs:
            self._specs[d] = _spec(d / ".gitignore")
        return self._specs[d]

    def ignored(self, path) -> bool:
        p = Path(path).resolve()
        try:
            rel = p.relative_to(self.top)
        except ValueError:
            return False
        verdict = None
        info = self._specs.get(("info",)) if ("info",) in self._specs else None
        if ("info",) not in self._specs:
            info = self._specs[("info",)] = _spec(self.top / ".git" / "info" / "exclude")
        if info is not None:
            r = info.check_file(rel.as_posix()).include
            verdict = r if r is not None else verdict
        d = self.top
        for part in (None, *rel.parts[:-1]):
            if part is not None:
                d = d / part
            spec = self._at(d)
            if spec is None:
                continue
            r = spec.check_file(p.relative_to(d).as_posix()).include
            if r is not None:
                verdict = r
        return bool(verdict)


def not_ignored(paths: list, folder) -> list:
    """``paths`` (files found below ``folder``) less those git ignores (untracked and matched)."""
    ig = Ignores(folder)
    kept = [p for p in paths if not ig.ignored(p)]
    if len(kept) == len(paths) or not (ig.top / ".git").exists():
        return kept
    keep = set(kept)
    left = {Path(p).resolve(): p for p in paths if p not in keep}
    keep |= {left[r] for r in tracked(ig.top, left, folder)}
    return [p for p in paths if p in keep]
