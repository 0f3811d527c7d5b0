"""``check --fix``: repair one model in its sources, proven before anything is written.

Each pass: check the model, turn the rules' fixes into source edits (plan.py), apply them to
in-memory copies of the files, rebuild from those copies and check again. A change is kept when
its finding is gone and no new error appeared; when a batch fails, the changes are tried one by one
so that one bad fix does not hold back the others. Passes repeat (a mass added by one fix lets
another rule compute an inertia) until nothing is left to fix. Nothing is written here: the command
writes every file of the run as one transaction.
"""

import os
from pathlib import Path

from myrabot_desc.checks import check_robot
from myrabot_desc.checks.baseline import SUBJECT_KEYS, subject  # noqa: F401  (fix's notion of a finding's subject)
from myrabot_desc.checks.report import FileResult
from myrabot_desc.diagnostics import Loc
from myrabot_desc.errors import InputError
from myrabot_desc.expand.packages import bundled_path
from myrabot_desc.fix.edits import Conflict, apply
from myrabot_desc.fix.plan import Change, Planner
from myrabot_desc.fix.report import change_data, not_fixed_data
from myrabot_desc.model.loader import load_robot
from myrabot_desc.records import Struct

MAX_PASSES = 4


class FileFix(Struct):
    """One source file: what it holds on disk and what the fixes make of it."""

    name: str                         # as shown in reports
    path: Path
    old: bytes
    new: bytes


class FixResult(Struct):
    model: str
    robot: object                     # the fixed model (Robot)
    context: object                   # its check Context
    applied: list                     # Change: proven, to write
    unsafe: list                      # Change: available with --unsafe-fixes
    refused: list                     # (Change, why): the proof failed
    not_fixed: list                   # NotFixed: the value is computed, given on the command line...
    files: list                       # FileFix, for files that change
    before: list                      # Diagnostics of the model as it is
    after: list                       # Diagnostics of the fixed model
    applied_data: list                # change_data of each applied Change (offsets in the bytes it edited)


def _counts(diags) -> dict:
    out: dict = {}
    for d in diags:
        k = subject(d)
        out[k] = out.get(k, 0) + 1
    return out


class _Session:
    def __init__(self, path, build: dict, check_args: tuple, overlay: dict | None, writable):
        self.path = path
        self.build = build
        self.check_args = check_args
        self.overlay: dict[Path, bytes] = dict(overlay or {})   # resolved path -> bytes (fixed so far)
        self.writable = [Path(w).resolve() for w in writable]
        self.names: dict[Path, str] = {}
        self.original: dict[Path, bytes] = {}

    def load(self, overlay=None):
        robot = load_robot(self.path, overlay=dict(overlay if overlay is not None else self.overlay), **self.build)
        diags, ctx = check_robot(robot, *self.check_args, unused=False)
        return robot, diags, ctx

    def files_of(self, robot) -> dict:
        return {name: Path(p).resolve() for name, p in robot.sources.files().items() if p is not None}

    def with_changes(self, robot, changes) -> dict:
        """The overlay with ``changes`` applied to the bytes ``robot`` was built from."""
        by_file: dict[str, list] = {}
        for ch in changes:
            for e in ch.edits:
                by_file.setdefault(e.file, []).append(e)
        files = self.files_of(robot)
        overlay = dict(self.overlay)
        for name, edits in by_file.items():
            path = files.get(name)
            if path is None:
                raise Conflict(f"{name} is not a file of this model")
            if not any(path.is_relative_to(w) for w in self.writable):
                raise Conflict(f"{name} lies outside the folders being fixed")
            data = robot.sources.data(name)
            self.original.setdefault(path, path.read_bytes() if path.is_file() else data)
            self.names.setdefault(path, name)
            overlay[path] = apply(data, edits)
        return overlay

    def prove(self, robot, diags, changes):
        """(overlay, robot, diags, ctx) after ``changes`` when each one's finding is gone and no new
        error appeared, else (None, why)."""
        try:
            overlay = self.with_changes(robot, changes)
        except Conflict as exc:
            return None, f"the edits overlap ({exc})"
        try:
            robot2, diags2, ctx2 = self.load(overlay)
        except Exception as exc:          # InputError and anything a broken edit provokes
            return None, f"the fixed sources no longer build: {str(exc).splitlines()[0]}"
        before, after = _counts(diags), _counts(diags2)
        fixed: dict = {}
        for ch in changes:
            fixed[ch.key] = fixed.get(ch.key, 0) + 1
        for key, n in fixed.items():
            if after.get(key, 0) > before.get(key, 0) - n:
                return None, f"{key[0]} is still reported after the fix"
        old_errors = _counts(d for d in diags if d.severity == "error")
        for k, n in _counts(d for d in diags2 if d.severity == "error").items():
            if n > old_errors.get(k, 0):
                return None, f"the fix makes a new error {k[0]}"
        return (overlay, robot2, diags2, ctx2), None


class _Keyed(Struct):
    change: Change
    key: tuple

    def __getattr__(self, name):
        return getattr(self.change, name)


def fix_model(path, build: dict | None = None, options=None, select=(), ignore=(), unsafe: bool = False,
              overlay: dict | None = None, writable=None) -> FixResult:
    """Fix ``path`` in memory (see the module doc); InputError when the model cannot be read.

    ``overlay``: files already fixed by this run (resolved path -> bytes); ``writable``: the folders
    whose files may be edited (default: the model's folder and the working folder); an edit
    elsewhere (an installed package) is refused."""
    if writable is None:
        writable = [Path(path if path is not None else bundled_path()).resolve().parent, Path.cwd()]
    s = _Session(path, dict(build or {}), (options, select, ignore), overlay, writable)
    robot, diags, ctx = s.load()
    before = diags
    applied, applied_data, refused = [], [], []
    tried: set = set()
    for _ in range(MAX_PASSES):
        current = _still_found(ctx.fixes, diags)
        changes, _nf = Planner(robot).plan(current)
        by_msg = {d.message: d for d, _f in current}
        todo = []
        for ch in changes:
            k = (ch.code, ch.message)
            if ch.safety == "unsafe" and not unsafe:
                continue
            if k in tried:
                continue
            tried.add(k)
            todo.append(_Keyed(ch, subject(by_msg[ch.message])))
        if not todo:
            break
        done, why = s.prove(robot, diags, todo)
        if done is None:                   # one at a time: keep the ones that prove alone
            kept = []
            for ch in todo:
                r, why1 = s.prove(robot, diags, kept + [ch])
                if r is None:
                    refused.append((ch.change, why1))
                else:
                    kept.append(ch)
                    done = r
            todo = kept
        if done is None:
            break
        applied.extend(ch.change for ch in todo)
        applied_data.extend(change_data(ch.change, robot.sources, "applied") for ch in todo)
        s.overlay, robot, diags, ctx = done
    # what is left, planned on the fixed model (its offsets are those of the fixed files)
    left, nf = Planner(robot).plan(_still_found(ctx.fixes, diags))
    refused_keys = {(c.code, c.message) for c, _why in refused}
    unsafe_left = [c for c in left if c.safety == "unsafe" and not unsafe and (c.code, c.message) not in refused_keys]
    files = [FileFix(s.names[p], p, s.original[p], data) for p, data in s.overlay.items()
             if p in s.original and data != s.original[p]]
    return FixResult(str(path) if path is not None else "", robot, ctx, applied, unsafe_left, refused, nf, files,
                     before, diags, applied_data)


class RunResult(Struct):
    results: list                     # FileResult per model (the fixed model's findings)
    files: list                       # FileFix over the whole run (one per changed file)
    fixes: list                       # FixResult per model (None where the model failed)


def fix_tasks(tasks, unsafe: bool, write: bool = True) -> RunResult:
    """Fix every model of a `check` run in turn, each on top of the files the ones before fixed (two
    models sharing an include see one fixed copy). Nothing is written here. ``write``: the results
    report the fixed models (--fix); else the models as they are, with the fixes proposed (--diff)."""
    overlay: dict = {}
    originals: dict = {}
    names: dict = {}
    results, fixes = [], []
    for task in tasks:
        res = FileResult(file=task.path or "", strict=task.strict)
        saved = {k: os.environ.get(k) for k, _v in task.limits}
        os.environ.update({k: str(v) for k, v in task.limits})
        try:
            fr = fix_model(task.path, task.build, task.options, task.select, task.ignore, unsafe, overlay)
        except InputError as exc:
            res.failure = str(exc).splitlines()[0]
            res.failure_loc = exc.loc or Loc(task.path or "")
            results.append(res)
            fixes.append(None)
            continue
        finally:
            for k, v in saved.items():
                if v is None:
                    os.environ.pop(k, None)
                else:
                    os.environ[k] = v
        for f in fr.files:
            originals.setdefault(f.path, f.old)
            names.setdefault(f.path, f.name)
            overlay[f.path] = f.new
        res.diagnostics = fr.after if write else fr.before
        res.robot, res.links, res.joints = fr.robot.name, len(fr.robot.links), len(fr.robot.joints)
        res.suppressions_seen, res.suppressions_used = fr.context.suppressions_seen, fr.context.suppressions_used
        res.suggestions = list(fr.context.suggestions)
        done = fr.applied_data if write else [dict(d, status="proposed") for d in fr.applied_data]
        res.fixes = (list(done)
                     + [change_data(c, fr.robot.sources, "unsafe") for c in fr.unsafe]
                     + [not_fixed_data(n) for n in fr.not_fixed]
                     + [dict(change_data(c, fr.robot.sources, "refused"), reason=why) for c, why in fr.refused])
        results.append(res)
        fixes.append(fr)
    files = [FileFix(names[p], p, originals[p], data) for p, data in overlay.items() if data != originals[p]]
    return RunResult(results, files, fixes)


def _still_found(fixes, diags) -> list:
    """The (diagnostic, fix) pairs whose diagnostic is one of ``diags`` (the same object: suppressions
    and --select drop some), by identity in one set (a large model has thousands of each)."""
    found = {id(d) for d in diags}
    return [(d, f) for d, f in fixes if id(d) in found]
