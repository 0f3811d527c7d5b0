"""``diff``: two models, or one model at two git revisions, built and compared.

Two files (``diff OLD NEW``) are built as ``build`` builds them. A revision (``--rev A..B``, or
``--rev A`` against the work tree) is exported from git into a temporary folder of ours
(vcs.export), never checked out over the work tree; the model, its includes, YAML files, meshes
and every package that lies inside the repository then come from that revision: ``-p NAME=PATH``,
``--package-path`` and ``--allow-path`` folders inside the repository, and the input's own package,
are mapped into the exported tree. Packages outside the repository are read where they are.

The findings of ``check`` on both sides are compared too (by code and subject, checks/baseline.py):
those that appear, disappear, or keep their subject with another message.
"""

from __future__ import annotations

import os
import pickle
import re
import shutil
import tempfile
import threading
from pathlib import Path

from myrabot_desc.checks import CheckOptions, check_robot
from myrabot_desc.checks.baseline import finding_key
from myrabot_desc.diff.attribution import changed_lines, refine
from myrabot_desc.diagnostics import Diagnostic
from myrabot_desc.diff.compare import STRUCTURAL, Item, compare
from myrabot_desc.errors import InputError, UsageProblem
from myrabot_desc.expand.driver import build_file, load_engine
from myrabot_desc.model.loader import is_xacro, load_robot, read_urdf_text
from myrabot_desc.records import Struct
from myrabot_desc.safety import display
from myrabot_desc.vcs import export, load_export, repo_top


class DiffResult(Struct):
    old_label: str
    new_label: str
    data: dict                  # the changes (compare.Comparison.data, findings added)
    items: list                 # compare.Item, largest first
    shown: object               # file name as built -> as the user reads it (new side)
    old: object                 # the Robots
    new: object
    shown_old: object = None    # the same for the old side


class _Tree:
    """A revision exported into a temporary folder (or the work tree itself: ``rev`` None)."""

    def __init__(self, top: Path, rev: str | None):
        self.top, self.rev = top, rev
        self.dir: Path | None = None

    def __enter__(self):
        if self.rev is not None:
            self.dir = Path(tempfile.mkdtemp(prefix="myrabot-desc-rev-")).resolve()
        return self

    def export(self, like=None) -> None:
        """The revision's files into the folder (InputError for an unknown revision); ``like``: the
        other side's tree, whose files with the same bytes are linked, not written again."""
        if self.rev is not None:
            export(self.top, self.rev, self.dir, getattr(like, "dir", None))

    def __exit__(self, *exc):
        if self.dir is not None:
            shutil.rmtree(self.dir, ignore_errors=True)
        return False

    @property
    def root(self) -> Path:
        return self.dir if self.dir is not None else self.top

    def map(self, path) -> str:
        """A path of the work tree as the same path in this revision (unchanged outside the repository)."""
        p = Path(path).expanduser().resolve()
        if self.dir is not None and p.is_relative_to(self.top):
            return str(self.dir / p.relative_to(self.top))
        return str(path)


def parse_rev(spec: str) -> tuple[str, str | None]:
    """'A..B' -> (A, B); 'A' -> (A, None): A against the work tree."""
    if "..." in spec:
        raise UsageProblem("use A..B (two dots): the symmetric difference A...B names no single old revision",
                           param_hint="--rev")
    if ".." in spec:
        a, b = spec.split("..", 1)
        if not a or not b:
            raise UsageProblem(f"expected A..B or A, got {spec!r}", param_hint="--rev")
        return a, b
    if not spec:
        raise UsageProblem("expected A..B or A", param_hint="--rev")
    return spec, None


def _build_options(build: dict, tree: _Tree | None) -> dict:
    out = dict(build)
    out["packages"] = dict(build.get("packages") or {})
    out["package_paths"] = list(build.get("package_paths") or ())
    out["allow_paths"] = list(build.get("allow_paths") or ())
    if tree is not None and tree.dir is not None:
        out["packages"] = {k: tree.map(v) for k, v in out["packages"].items()}
        out["package_paths"] = [tree.map(p) for p in out["package_paths"]]
        out["allow_paths"] = [tree.map(p) for p in out["allow_paths"]]
        # packages the environment names inside the repository come from the revision too
        for var in ("ROS_PACKAGE_PATH",):
            for d in filter(None, os.environ.get(var, "").split(os.pathsep)):
                if Path(d).expanduser().resolve().is_relative_to(tree.top):
                    out["package_paths"].append(tree.map(d))
    return out


def _load(path: str, build: dict, built=None):
    """The Robot of ``path``; ``built``: its BuildResult, made in the other process (see _Side)."""
    if built is None:
        return load_robot(path, **build)
    return read_urdf_text(built.text, Path(path), locations=built.locations, package_roots=built.package_roots,
                          root=built.root, source_map=built.source_map, build_warnings=built.diagnostics,
                          from_xacro=True, packages=build.get("packages"),
                          package_paths=build.get("package_paths", ()))


def _prebuild(tree, path: str, build: dict, like=None):
    """Export the revision (when ``tree`` has one; ``like``: the other side's, already exported) and
    expand a xacro ``path``: the BuildResult, None for a plain URDF (read by the loader), or the
    InputError."""
    try:
        if tree is not None:
            tree.export(like)
        src = Path(path)
        if not src.is_file() or not is_xacro(src, src.read_bytes() if not src.name.endswith(".xacro") else None):
            return None
        b = dict(build)
        return build_file(src, b.pop("mappings", None), **b)
    except InputError as exc:
        return exc


def _idle_core() -> bool:
    """Is a core idle for the other side's build? The cores this process may use less the load of
    the last minute, at least one and a half."""
    try:
        cores = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        cores = os.cpu_count() or 1
    try:
        load = os.getloadavg()[0]
    except (AttributeError, OSError):
        return cores > 1
    return cores - load >= 1.5


class _Side:
    """One side's build, in a forked process while this one does the other side, when a core is
    idle for it (the two builds overlap). Serial where fork is missing, threads run (a fork would
    copy their locks), or the cores are busy: there the two processes only contend, and each spends
    more CPU for the same work (on the 2-core machine of bench/bench_diff.py at load 1.5, the PR2's
    diff took 1.10 s of CPU forked against 0.63 s in one process, for 0.81 against 0.93 s of wall)."""

    def __init__(self, fn):
        self.pid = None
        self.result = None
        if hasattr(os, "fork") and threading.active_count() == 1 and _idle_core():
            r, w = os.pipe()
            pid = os.fork()
            if pid == 0:                        # the child: build, send, leave without cleanup
                code = 0
                try:
                    os.close(r)
                    data = pickle.dumps(fn(), protocol=pickle.HIGHEST_PROTOCOL)
                    with os.fdopen(w, "wb") as f:
                        f.write(data)
                except BaseException:
                    code = 1
                os._exit(code)
            os.close(w)
            self.pid, self.fd = pid, r
        else:
            self.result = fn()
        self._fn = fn

    def get(self):
        if self.pid is not None:
            with os.fdopen(self.fd, "rb") as f:
                data = f.read()
            _pid, status = os.waitpid(self.pid, 0)
            self.pid = None
            self.result = pickle.loads(data) if data and os.waitstatus_to_exitcode(status) == 0 else self._fn()
        if isinstance(self.result, InputError):
            raise self.result
        return self.result


def _placeholders(robot, tree: _Tree | None) -> dict:
    out = {}
    for name, root in (robot.package_roots or {}).items():
        out[str(root)] = f"$(find {name})"
    if tree is not None:
        out[str(tree.root)] = "@tree@"
    return out


def _findings(robot, select, ignore) -> list:
    diags, _ctx = check_robot(robot, CheckOptions(), select, ignore, unused=False)
    return diags


def diff_findings(old_diags, new_diags, shown_old, shown_new, trees=(None, None)) -> tuple[dict, list]:
    """Findings that appear, disappear, or keep their subject with another message (a file named in
    a message is compared as the user reads it, not by the folder a revision was exported to)."""
    def bag(diags, tree):
        prefix = str(tree.dir) + os.sep if tree is not None and tree.dir is not None else None
        out: dict = {}
        for d in diags:
            if prefix and prefix in d.message:
                d = Diagnostic(d.code, d.severity, d.message.replace(prefix, _top(tree)), d.loc, d.data)
            out.setdefault(finding_key(d, with_message=False), []).append(d)
        return out

    a, b = bag(old_diags, trees[0]), bag(new_diags, trees[1])
    data: dict = {}
    items = []
    for k in sorted(set(a) | set(b), key=str):
        xs, ys = a.get(k, []), b.get(k, [])
        # a message that differs only in a file:line it names (a refactor moved that place) is the same
        mx = sorted(_place_free(x.message) for x in xs)
        my = sorted(_place_free(y.message) for y in ys)
        if mx == my:
            continue
        gone = [x for x in xs if _place_free(x.message) not in my]
        came = [y for y in ys if _place_free(y.message) not in mx]
        for x, y in zip(list(gone), list(came)):          # same subject, another message: changed
            data.setdefault("findings_changed", []).append(
                {"code": y.code, "severity": y.severity, "old": x.message, "new": y.message, "where": _loc(y, shown_new)})
            items.append(Item("finding", y.code, "changed", x.message, y.message, "changed", 0.5, _loc(y, shown_new)))
        n = min(len(gone), len(came))
        for x in gone[n:]:
            data.setdefault("findings_removed", []).append(
                {"code": x.code, "severity": x.severity, "message": x.message, "where": _loc(x, shown_old)})
            items.append(Item("finding", x.code, "disappears", x.message, "", "disappears",
                              STRUCTURAL / 4 if x.severity == "error" else 2.0,
                              (_loc(x, shown_old) + " (old)") if _loc(x, shown_old) else None))
        for y in came[n:]:
            data.setdefault("findings_added", []).append(
                {"code": y.code, "severity": y.severity, "message": y.message, "where": _loc(y, shown_new)})
            items.append(Item("finding", y.code, "appears", "", y.message, "appears",
                              STRUCTURAL if y.severity == "error" else 3.0, _loc(y, shown_new)))
    return data, items


_PLACE = re.compile(r"[^\s()]+\.(?:xacro|urdf|xml|yaml|yml|gazebo|sdf|launch|dae|stl|obj):\d+(?::\d+)?")


def _place_free(message: str) -> str:
    """A finding's message with the file:line places it names made alike."""
    return _PLACE.sub("FILE:N", message)


def _top(tree) -> str:
    """The work-tree folder a revision's files are read as ('' for the current folder)."""
    top = display(tree.top)
    return "" if top in ("", ".") else top.rstrip(os.sep) + os.sep


def _loc(d, shown) -> str | None:
    if d.loc is None or not d.loc.file:
        return None
    return f"{shown(d.loc.file)}:{d.loc.line}" if d.loc.line else shown(d.loc.file)


def _shower(tree: _Tree | None):
    """File name as the build shows it -> as the user reads it: a file of an exported revision by its
    place in the work tree."""
    if tree is None or tree.dir is None:
        return lambda f: f
    prefix = str(tree.dir)

    def shown(f: str) -> str:
        try:
            p = Path(f) if os.path.isabs(f) else (Path.cwd() / f)
            p = p.resolve()
        except (OSError, ValueError):
            return f
        if str(p).startswith(prefix + os.sep):
            return display(tree.top / p.relative_to(tree.dir))
        return f
    return shown


def diff_models(old_path, new_path, build: dict, old_tree=None, new_tree=None, checks: bool = True,
                select=(), ignore=(), labels=("old", "new")) -> DiffResult:
    """Build both models and compare them (InputError when one cannot be built). The trees' revisions
    are exported here (the old side's export and build run beside the new side's)."""
    ob, nb = _build_options(build, old_tree), _build_options(build, new_tree)
    load_engine()
    old_err = None
    if old_tree is not None or new_tree is not None:
        load_export()
        # the old side is exported here, before the fork, so that the new side links the files the
        # two revisions share instead of writing them again
        try:
            if old_tree is not None:
                old_tree.export()
        except InputError as exc:
            old_err = exc
    other = _Side(lambda: old_err if old_err is not None else _prebuild(None, old_path, ob))
    new_built = _prebuild(new_tree, new_path, nb, like=old_tree if old_err is None else None)
    old_built = other.get()
    if isinstance(new_built, InputError):
        raise new_built
    old = _load(old_path, ob, old_built)
    new = _load(new_path, nb, new_built)
    cmp = compare(old, new, _placeholders(old, old_tree), _placeholders(new, new_tree))
    data = dict(cmp.data)
    roots = [(Path(new_path).resolve().parent, Path(old_path).resolve().parent)]
    roots += [(new.package_roots[n], old.package_roots[n]) for n in new.package_roots if n in old.package_roots]
    if old_tree is not None and new_tree is not None:
        roots.append((new_tree.root, old_tree.root))
    items = refine(cmp.items, changed_lines(new, roots)) if cmp.items else []
    shown_old, shown_new = _shower(old_tree), _shower(new_tree)
    if checks:
        fdata, fitems = diff_findings(_findings(old, select, ignore), _findings(new, select, ignore),
                                      shown_old, shown_new, (old_tree, new_tree))
        data.update(fdata)
        items += fitems
        items.sort(key=lambda it: -it.size)
    return DiffResult(labels[0], labels[1], data, items, shown_new, old, new, shown_old)


def diff_paths(old_path: str, new_path: str, build: dict, while_open=None, **kw) -> DiffResult:
    res = diff_models(old_path, new_path, build, labels=(display(old_path), display(new_path)), **kw)
    if while_open is not None:
        while_open(res)
    return res


def diff_revisions(path: str, rev_spec: str, build: dict, while_open=None, **kw) -> DiffResult:
    """``path`` at revision A and at B (or the work tree): see the module doc. ``while_open(result)``
    runs before the exported revisions are removed (to render the two robots, whose meshes are there)."""
    a, b = parse_rev(rev_spec)
    p = Path(path)
    if not p.exists() and b is None:
        raise InputError(f"no such file: {path}")
    top = repo_top(p if p.exists() else p.parent if p.parent.exists() else Path.cwd())
    if top is None:
        raise InputError(f"{path}: not inside a git repository (--rev reads revisions with git)")
    try:
        rel = (Path.cwd() / p).resolve().relative_to(top)
    except ValueError:
        raise InputError(f"{path}: not inside the repository {top}") from None
    with _Tree(top, a) as ta, _Tree(top, b) as tb:
        old_file, new_file = ta.root / rel, tb.root / rel
        res = diff_models(str(old_file), str(new_file), build, _Missing(ta, path, a), _Missing(tb, path, b),
                          labels=(f"{display(path)}@{a}", f"{display(path)}@{b}" if b else display(path)), **kw)
        # resolve every lazily-read span and shown name while the exported files still exist
        if while_open is not None:
            while_open(res)
        items = [it._replace(where=where_text(it.where, res.shown, res.shown_old)) for it in res.items]
        same = lambda f: f        # noqa: E731
        return res._replace(items=items, shown=same, shown_old=same)


class _Missing:
    """A tree whose model file must exist once exported (else: no such file at that revision)."""

    def __init__(self, tree: _Tree, path: str, rev: str | None):
        self.tree, self.path, self.rev = tree, path, rev

    def __getattr__(self, name):
        return getattr(self.tree, name)

    def export(self, like=None) -> None:
        self.tree.export(like)
        rel = (Path.cwd() / self.path).resolve().relative_to(self.tree.top) if self.tree.dir is not None else None
        if rel is not None and not (self.tree.dir / rel).is_file():
            raise InputError(f"{self.path}: no such file at revision {self.rev}")


def where_text(w, shown, shown_old=None) -> str | None:
    """A Where as 'file:line:col (how)', its file named as the user reads it."""
    if w is None:
        return None
    if isinstance(w, str):
        return w
    return w.text(shown_old if w.side == "old" and shown_old is not None else shown)


__all__ = ["DiffResult", "diff_paths", "diff_revisions", "diff_models", "parse_rev", "where_text"]
