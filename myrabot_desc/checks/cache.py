"""A result cache for ``check`` (what makes a pre-commit run cheap), like ruff's .ruff_cache:
in ``.myrabot-desc-cache/`` next to the project's configuration file (or MYRABOT_DESC_CACHE_DIR);
a check with no configuration file writes nothing.

One JSON entry per (file, options, tool version, working folder): the file's findings and
a signature of every folder the check may read from: the input's folder and the package
roots the build resolved (the only places a model may read from), as (path, size, mtime)
of each file in them. An entry is used only when the signature still matches and every
``$(env)`` variable the build read (X007) still has its value. Entries are JSON (never
pickle: a cache folder is as untrusted as the models), written atomically; one entry per
(file, options), so the folder does not grow with edits.
"""

from __future__ import annotations

import hashlib
import json
import os
from pathlib import Path

from myrabot_desc import __version__
from myrabot_desc.checks.report import FileResult, _plain
from myrabot_desc.diagnostics import Diagnostic, Loc
from myrabot_desc.expand.packages import bundled_path
from myrabot_desc.safety import LIMITS, SKIP_DIRS

ENTRY_FORMAT = 1
MAX_TREE_FILES = 20_000          # a folder bigger than this (a home folder) is not watched: no caching
MAX_ENTRY_BYTES = 20_000_000
ENV_KEYS = ("ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH")

_trees: dict[str, str | None] = {}     # folder -> signature, once per process (one command run)


def reset() -> None:
    _trees.clear()


def _tree_signature(root: str) -> str | None:
    """Hash of (relative path, size, mtime) of every file under ``root``; None when too big."""
    if root in _trees:
        return _trees[root]

    h = hashlib.sha256()
    n = 0
    sig: str | None = None
    for folder, dirs, names in os.walk(root):
        dirs[:] = sorted(d for d in dirs if d not in SKIP_DIRS and not d.startswith("."))
        for name in sorted(names):
            try:
                st = os.stat(os.path.join(folder, name))
            except OSError:
                continue
            n += 1
            if n > MAX_TREE_FILES:
                _trees[root] = None
                return None
            h.update(f"{os.path.relpath(os.path.join(folder, name), root)}\0{st.st_size}\0{st.st_mtime_ns}\n"
                     .encode("utf-8", "surrogateescape"))
    sig = h.hexdigest()
    _trees[root] = sig
    return sig


def _key(task) -> str:
    opts = task.options
    env = {k: os.environ.get(k) for k in ENV_KEYS + tuple(lim.env for lim in LIMITS)}
    material = {"format": ENTRY_FORMAT, "version": __version__, "cwd": os.getcwd(),
                "file": str(Path(task.path).resolve()) if task.path else None,
                "build": {k: (sorted(v.items()) if isinstance(v, dict) else v) for k, v in sorted(task.build.items())},
                "options": [opts.inertia, opts.suggest, opts.meshes, _file_key(getattr(opts, "srdf", None))],
                "select": list(task.select),
                "ignore": list(task.ignore), "limits": list(task.limits), "env": env}
    return hashlib.sha256(json.dumps(material, sort_keys=True, default=str).encode()).hexdigest()


def _file_key(path) -> list | None:
    """An extra input file (--srdf) as (path, size, mtime): its edit changes the key."""
    if not path:
        return None
    try:
        st = os.stat(path)
    except OSError:
        return [str(path)]
    return [str(Path(path).resolve()), st.st_size, st.st_mtime_ns]


def _entry_path(task) -> Path:
    return Path(task.cache_dir) / "check" / f"{_key(task)}.json"


def _roots(task, robot) -> list[str]:
    src = Path(task.path) if task.path else bundled_path()
    roots = {str(src.resolve().parent)}
    roots.update(str(Path(p).resolve()) for p in robot.package_roots.values())
    roots.update(str(Path(p).resolve()) for p in task.build.get("allow_paths", ()))
    # a folder inside another is covered by the outer walk
    return sorted(r for r in roots if not any(r != o and r.startswith(o.rstrip(os.sep) + os.sep) for o in roots))


def lookup(task):
    """The cached FileResult of ``task``, or None (no entry, or anything it depends on changed)."""
    p = _entry_path(task)
    try:
        if p.stat().st_size > MAX_ENTRY_BYTES:
            return None
        entry = json.loads(p.read_text(encoding="utf-8"))
        if entry.get("format") != ENTRY_FORMAT:
            return None
        for name, value in entry["env"].items():
            if os.environ.get(name) != value:
                return None
        for root, sig in entry["trees"].items():
            if _tree_signature(root) != sig:
                return None
        return _result(entry["result"], task)
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        return None


def store(task, robot, res) -> None:
    """Write the entry for ``res`` (best effort: a read-only folder just means no cache)."""
    trees = {}
    for root in _roots(task, robot):
        sig = _tree_signature(root)
        if sig is None:
            return
        trees[root] = sig
    env = {}
    for d in robot.build_warnings:
        if d.code == "X007":
            env = {k: os.environ.get(k) for k in d.data.get("environment", {})}
    entry = {"format": ENTRY_FORMAT, "trees": trees, "env": env, "result": _plain_result(res)}
    p = _entry_path(task)
    try:
        p.parent.mkdir(parents=True, exist_ok=True)
        ignore = p.parent.parent / ".gitignore"
        if not ignore.exists():
            ignore.write_text("# created by myrabot-desc check\n*\n")
        tmp = p.with_suffix(f".{os.getpid()}.tmp")
        tmp.write_text(json.dumps(entry, ensure_ascii=False), encoding="utf-8")
        os.replace(tmp, p)
    except OSError:
        pass


def _plain_result(res) -> dict:
    return {"robot": res.robot, "links": res.links, "joints": res.joints,
            "suggestions": [list(s) for s in res.suggestions],
            "seen": [list(k) for k in res.suppressions_seen], "used": [list(k) for k in res.suppressions_used],
            "diagnostics": [[d.code, d.severity, d.message, d.loc.file if d.loc else None,
                             d.loc.line if d.loc else None, _plain(d.data)] for d in res.diagnostics]}


def _result(e: dict, task):
    res = FileResult(file=task.path or "", strict=task.strict, robot=e["robot"], links=e["links"],
                     joints=e["joints"], suggestions=[tuple(s) for s in e["suggestions"]])
    res.suppressions_seen = [tuple(k) for k in e["seen"]]
    res.suppressions_used = [tuple(k) for k in e["used"]]
    res.diagnostics = [Diagnostic(c, s, m, Loc(f, ln) if f is not None else None, dict(data))
                       for c, s, m, f, ln, data in e["diagnostics"]]
    return res
