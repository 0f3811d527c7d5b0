"""Running ``check`` over many files: the inputs expanded (folders, -r), the configuration applied
per file, the shard taken, each file checked in a worker (cache first), results in input order.

commands/check.py is the command line of this; nothing here imports click (a progress bar is
handed in by the caller, see :func:`run_tasks`).
"""

import gc
import importlib
import os
import re
from contextlib import nullcontext
from pathlib import Path

from myrabot_desc.checks import CheckOptions, cache, check_robot
from myrabot_desc.checks.codes import known_codes, split_codes, unknown_code_message
from myrabot_desc.checks.config import Finder
from myrabot_desc.checks.registry import load_all
from myrabot_desc.checks.report import FileResult
from myrabot_desc.diagnostics import Loc
from myrabot_desc.errors import InputError, UsageProblem
from myrabot_desc.expand.driver import build_file
from myrabot_desc.expand.packages import resolve_resource_uri
from myrabot_desc.model.loader import is_xacro, load_robot
from myrabot_desc.records import Struct
from myrabot_desc.safety import LIMIT_ENV, SKIP_DIRS, included_names, walk_models

MODEL_SUFFIXES = (".urdf", ".xacro")


# Never descended into by --recursive: VCS data, build trees, environments.


def expand_inputs(files: list[str], recursive: bool = False) -> list[str]:
    """Folders become their top-level model files: *.urdf and *.xacro directly inside (with
    ``recursive``, anywhere below, hidden and build folders skipped), minus the files git ignores
    (.gitignore) and the xacro files that another xacro file of the folder includes (parts, not
    robots)."""
    out: list[str] = []
    for f in files:
        p = Path(f)
        if not p.is_dir():
            out.append(f)
            continue
        # the walk checks every file against the folder (no symlink out, no FIFO or device) and is
        # bounded; the include scan is linear (model files are untrusted)
        found = sorted(walk_models(p, recursive, MODEL_SUFFIXES, SKIP_DIRS))
        from myrabot_desc.checks.gitignore import not_ignored     # a folder's walk only (it loads git's helpers)

        models = not_ignored(found, p)
        included = set()
        for c in models:
            if c.name.endswith(".xacro"):
                included |= included_names(c)
        picked = [str(c) for c in models if c.name not in included or c.name.endswith(".urdf")]
        if not picked:
            hint = "" if recursive else " (-r looks in its subfolders too)"
            if found and not models:
                hint = f" ({len(found)} ignored by .gitignore)"
            raise UsageProblem(f"{f}: no .urdf or .xacro model files in this folder{hint}")
        out.extend(picked)
    return out


class Task(Struct):
    """Everything one worker needs to check one file (picklable)."""

    path: str | None
    build: dict                 # load_robot keyword options
    options: object             # CheckOptions
    select: tuple
    ignore: tuple
    limits: tuple               # ((MYRABOT_DESC_MAX_* variable, value), ...) from the configuration
    strict: bool
    cache_dir: str | None
    config: str | None = None   # the configuration file in force (its content keys the cache)


def check_one(task: Task):
    """FileResult for one input (never raises for bad input: failure holds the one line)."""
    path = task.path
    res = FileResult(file=path or "", strict=task.strict)
    saved = {k: os.environ.get(k) for k, _v in task.limits}
    os.environ.update({k: str(v) for k, v in task.limits})
    # The collector stays off while one file is checked: a robot's records make no cycles worth
    # finding mid-check, and every full pass rescanned all of them (~10% of a 20,000-link
    # check). Turned back on after each file, it frees what that file's build left.
    collecting = gc.isenabled()
    gc.disable()
    try:
        cached = None
        if task.cache_dir:
            cached = cache.lookup(task)
        if cached is not None:
            return cached
        with cache.Recorder() if task.cache_dir else nullcontext() as read:
            robot = load_robot(path, **task.build)
            diags, ctx = check_robot(robot, task.options, task.select, task.ignore, unused=False)
        res.diagnostics = diags
        res.suppressions_seen, res.suppressions_used = ctx.suppressions_seen, ctx.suppressions_used
        res.suppressed = list(ctx.suppressed)
        res.robot = robot.name
        res.links, res.joints = len(robot.links), len(robot.joints)
        res.suggestions = list(ctx.suggestions)
        if task.cache_dir:
            cache.store(task, robot, res, read.paths)
    except InputError as exc:
        res.failure = str(exc).splitlines()[0]
        res.failure_loc = exc.loc or Loc(path or "")
    except (RecursionError, MemoryError) as exc:
        res.failure = f"{path}: error: input too large or nested too deeply ({type(exc).__name__})"
        res.failure_loc = Loc(path or "")
    finally:
        if collecting:
            gc.enable()
        for k, v in saved.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v
    return res


def parse_shard(value: str | None) -> tuple[int, int] | None:
    if value is None:
        return None
    m = re.fullmatch(r"\s*(\d+)\s*/\s*(\d+)\s*", value)
    if not m or not (1 <= int(m.group(1)) <= int(m.group(2))):
        raise UsageProblem(f"expected K/N with 1 <= K <= N (e.g. 2/4), got {value!r}", param_hint="--shard")
    return int(m.group(1)), int(m.group(2))


def shard(paths: list, k: int, n: int) -> list:
    """The K-th of N parts of the file list (1-based): every N-th file, starting at the K-th. The
    list is the sorted expansion of the same arguments on every machine, so the parts are
    disjoint, together they are the whole list, and their sizes differ by at most one."""
    return paths[k - 1::n]


def default_jobs() -> int:
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):
        return max(1, os.cpu_count() or 1)


def run_tasks(tasks: list, jobs: int, progressbar=None) -> list:
    """Results in task order; ``jobs`` worker processes when there is more than one file.
    ``progressbar(results, length)``, when given, is a context manager that yields the results
    while it draws them (the command hands in click's progress bar)."""
    try:
        return _run_tasks(tasks, jobs, progressbar)
    finally:
        gc.unfreeze()       # what _preload froze for the workers is the collector's again here


def _run_tasks(tasks: list, jobs: int, progressbar) -> list:
    jobs = max(1, min(jobs, len(tasks)))
    pool = nullcontext()
    if jobs > 1:
        import multiprocessing
        from concurrent.futures import ProcessPoolExecutor

        # fork: the workers inherit the imported modules (no re-import per worker)
        method = "fork" if "fork" in multiprocessing.get_all_start_methods() else None
        if method == "fork":
            _preload(tasks)
        pool = ProcessPoolExecutor(jobs, mp_context=multiprocessing.get_context(method))
    with pool as ex:
        if ex is None:
            it = map(check_one, tasks)
        else:
            it = _balanced(ex, tasks)
        if progressbar is None:
            return list(it)
        out = []
        with progressbar(it, len(tasks)) as bar:
            for r in bar:
                out.append(r)
        return out


def check_group(tasks: list) -> list:
    """FileResults of files checked one after the other in one worker (they share its mesh cache)."""
    return [check_one(t) for t in tasks]


def _balanced(ex, tasks: list):
    """Results in task order from workers given the biggest work first. Files of one folder (variants
    of one robot, sharing meshes) stay together; folders go largest first, one at a time, so no
    worker is left with a big robot at the end while the others wait (longest-processing-time order).
    The size of a folder's model files stands in for its work."""
    groups: list[list[int]] = []
    for i, t in enumerate(tasks):
        folder = os.path.dirname(t.path or "")
        if groups and os.path.dirname(tasks[groups[-1][0]].path or "") == folder:
            groups[-1].append(i)
        else:
            groups.append([i])

    def size(i):
        try:
            return os.path.getsize(tasks[i].path) if tasks[i].path else 0
        except OSError:
            return 0

    order = sorted(range(len(groups)), key=lambda g: -sum(size(i) for i in groups[g]))
    futures = {g: ex.submit(check_group, [tasks[i] for i in groups[g]]) for g in order}
    for g in range(len(groups)):             # in task order: the report does not depend on the timing
        yield from futures[g].result()


def _preload(tasks) -> None:
    """Import what the workers need once, before forking: they share those pages (numpy, xacro
    and their imports, which each would otherwise hold) and skip the imports. gc.freeze() keeps
    the collector from touching (and so copying) them."""
    names = ["xacro", "numpy", "myrabot_desc.model.loader", "myrabot_desc.checks.registry"]
    if any(t.options.load_meshes for t in tasks):
        # the lean mesh readers (STL, COLLADA, OBJ) need numpy and, for COLLADA, lxml and pycollada;
        # trimesh (0.6 s, ~60 MB) is imported only by a worker meeting a format they do not read.
        # (Without meshes lxml reads only a URDF file over 500 kB or what expat refuses: xmltree.py.)
        names += ["myrabot_desc.model.meshes", "lxml.etree", "collada"]
    for name in names:
        try:
            importlib.import_module(name)
        except ImportError:
            pass
    load_all()
    gc.freeze()


def exit_code(results) -> int:
    if any(r.failure for r in results):
        return 2
    if any(r.count("error") or (r.strict and r.count("warning")) for r in results):
        return 1
    return 0


def plan(inputs, inertia, suggest, meshes, select, ignore, strict, recursive, config_file, isolated, shard_spec,
         no_cache, cache_dir=None, srdf=None):
    """The task list: inputs expanded, configuration applied per file, the shard taken
    (UsageProblem for a code, shard or folder that does not fit)."""
    cache.reset()
    sel, ign = split_codes(select), split_codes(ignore)
    for flag, codes in (("--select", sel), ("--ignore", ign)):
        for c in codes:
            msg = unknown_code_message(c, known_codes())
            if msg:
                raise UsageProblem(msg, param_hint=flag)
    part = parse_shard(shard_spec)
    finder = Finder(known_codes, config_file, isolated)
    paths = expand_inputs(inputs.files, recursive) if inputs.files else [None]
    if inputs.files:                        # exclude = from the configuration, for folder expansions
        given = {str(f) for f in inputs.files}
        paths = [p for p in paths if p in given or not finder.for_file(p).excluded(p)]
    if part:
        paths = shard(paths, *part)
    # the cache folder is the runner's choice (--cache-dir, MYRABOT_DESC_CACHE_DIR), else the user's
    # cache folder: never one a repository names
    cache_home = cache_dir or os.environ.get("MYRABOT_DESC_CACHE_DIR") or cache.default_dir()
    tasks, help_url = [], None
    for p in paths:
        cfg = finder.for_file(p)
        if help_url is None:
            help_url = cfg.help_url
        build = inputs.build_options()
        build["packages"] = {**cfg.packages, **build["packages"]}
        build["package_paths"] = list(build["package_paths"]) + cfg.package_paths
        build["allow_paths"] = list(build["allow_paths"]) + cfg.allow_paths
        build["mappings"] = {**cfg.args_for(p), **build["mappings"]}
        build["no_env"] = build["no_env"] or cfg.no_env
        use_inertia = inertia or suggest or cfg.inertia
        options = CheckOptions(inertia=use_inertia, suggest=suggest, meshes=meshes or cfg.meshes, srdf=srdf)
        limits = tuple((LIMIT_ENV[k], v) for k, v in sorted(cfg.limits.items()))
        use_cache = None         # a project (a configuration file) opts in, or the runner names a folder
        if not no_cache and cfg.cache and (cfg.path or cache_dir or os.environ.get("MYRABOT_DESC_CACHE_DIR")):
            use_cache = cache_home
        tasks.append(Task(p, build, options, tuple(sel or cfg.select), tuple(cfg.ignores_for(p) + ign), limits,
                          strict or cfg.strict, use_cache, str(cfg.path) if cfg.path else None))
    return tasks, help_url


# ---------------------------------------------------------------------------------------- --changed-since
_MESH = re.compile(r"""<mesh\b[^>]*?\bfilename\s*=\s*["']([^"']+)["']""")


def model_sources(task: Task) -> set[Path] | None:
    """Every file the build of ``task`` reads (the input, its includes and YAML files, the meshes the
    URDF names), resolved; None when the model does not build (then it is checked, and its failure
    reported)."""
    src = Path(task.path)
    build = dict(task.build)
    mappings = build.pop("mappings", None)
    try:
        data = src.read_bytes() if not src.name.endswith(".xacro") else None
        if data is None or is_xacro(src, data):
            res = build_file(src, mappings, **build)
            files, text, roots = [Path(d) for d in res.deps], res.text, res.package_roots
        else:
            files, text, roots = [src], data.decode("utf-8", "replace"), {}
    except (InputError, OSError, RecursionError, MemoryError):
        return None
    out = {f.resolve() for f in files}
    for uri in set(_MESH.findall(text)):
        p = resolve_resource_uri(uri, roots, src.parent, tuple(Path(d).expanduser().resolve()
                                                              for d in build.get("allow_paths") or ()))
        if p is not None:
            out.add(Path(p).resolve())
    return out


def changed_since(tasks: list, rev: str) -> tuple[list, int]:
    """(the tasks whose model reads a file that changed since git revision ``rev``, how many were left
    out). Files changed: committed since ``rev``, staged, unstaged or untracked (not ignored); a
    model outside any repository is kept."""
    from myrabot_desc.vcs import changed_files, repo_top     # --changed-since only

    changed: dict = {}
    kept = []
    for t in tasks:
        if t.path is None:
            kept.append(t)
            continue
        top = repo_top(t.path)
        if top is None:
            kept.append(t)
            continue
        if top not in changed:
            changed[top] = changed_files(top, rev)
        if not changed[top]:
            continue
        deps = model_sources(t)
        if deps is None or deps & changed[top]:
            kept.append(t)
    return kept, len(tasks) - len(kept)
