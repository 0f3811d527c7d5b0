"""``check``'s project configuration: ``[tool.myrabot-desc]`` in pyproject.toml or a
``myrabot-desc.toml`` (same keys at top level), found as ruff finds its own.

For each checked file the nearest configuration wins: walking up from the file's folder,
the first folder with a ``myrabot-desc.toml`` (preferred) or a ``pyproject.toml`` that has a
``[tool.myrabot-desc]`` table. Paths inside a configuration are relative to its folder.
``--config FILE`` uses one file for every input; ``--isolated`` reads none.

Unknown keys, wrong types and unknown rule codes are errors at the key's file:line (exit 2).

A configuration comes with the repository, so a pull request can change it: it may narrow what a
check does, never widen what it may touch. Limits can only be lowered (a value above the one in
force, the default or the runner's MYRABOT_DESC_MAX_* variable, is the one in force); folders
(``allow-paths``, ``package-paths``, ``packages``) must lie inside the repository (the work tree
holding the configuration, else its folder), symlinks resolved; the file, its tables and lists
have bounded sizes. Globs are gitignore patterns (pathspec's translation) compiled once into a
:class:`GlobSet`, matched in time linear in the files and the patterns.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

from myrabot_desc.checks.codes import closest, unknown_code_message
from myrabot_desc.diagnostics import Loc
from myrabot_desc.errors import InputError
from myrabot_desc.safety import LIMITS, display, limit, read_checked

TOOL_TABLE = "myrabot-desc"
# Where a pyproject.toml can hold [tool.myrabot-desc]: a line that opens that table (or a bare [tool]
# table, whose keys could be ours) or starts a top-level ``tool`` key naming it. A project that only
# lists us as a dependency or a script cannot, and is not parsed.
_OUR_TABLE = re.compile(r"""(?mx)^[ \t]*(?:
      \[\[?[ \t]*(?P<q1>["']?)tool(?P=q1)[ \t]*(?:\]|\.[ \t]*(?P<q2>["']?)myrabot-desc(?P=q2)[ \t]*[\].])
    | (?P<q3>["']?)tool(?P=q3)[ \t]*(?:=|\.[ \t]*(?P<q4>["']?)myrabot-desc(?P=q4)[ \t]*[.=]))""")
OWN_NAME = "myrabot-desc.toml"
MAX_CONFIG_BYTES = 1_000_000
MAX_PATTERNS = 1_000          # globs of one key (exclude, per-file-ignores, args)
MAX_UNINDEXED = 100           # of those, patterns with no literal part (tried on every file)
MAX_ITEMS = 1_000             # codes, folders, packages, xacro args of one key
MAX_NESTING = 16              # arrays and tables inside each other

# key -> (kind, help); kinds: codes, bool, paths, str, table-codes, table-args, table-paths, table-limits
KEYS = {
    "select": ("codes", "only these codes or prefixes (like --select)"),
    "ignore": ("codes", "skip these codes or prefixes (like --ignore; the command line adds to it)"),
    "per-file-ignores": ("table-codes", "glob (relative to the configuration's folder) -> codes skipped there"),
    "strict": ("bool", "warnings fail too (like --strict)"),
    "inertia": ("bool", "compare inertias with the collision geometry (like --inertia)"),
    "meshes": ("bool", "load every mesh (like --meshes)"),
    "package-paths": ("paths", "folders searched for packages (like --package-path)"),
    "packages": ("table-paths", "package name -> folder (like -p NAME=PATH)"),
    "allow-paths": ("paths", "extra folders includes may read (like --allow-path)"),
    "no-env": ("bool", "refuse $(env)/$(optenv) (like --no-env)"),
    "args": ("table-args", "glob -> {xacro arg = value} for the files it matches (like NAME:=VALUE)"),
    "limits": ("table-limits", "limit name (max-input-bytes, ...) -> value (like the MYRABOT_DESC_MAX_* variables)"),
    "exclude": ("globs", "files or folders skipped by folder and -r inputs"),
    "help-url": ("str", "base URL of the rule documentation for SARIF helpUri (\"\" omits the links)"),
    "cache": ("bool", "keep results in .myrabot-desc-cache/ next to this file (default true)"),
}


class Config:
    """One configuration file's settings (paths already absolute). A plain class, not a
    dataclass (see checks/rule.py); each list or dict not given is a new empty one."""

    def __init__(self, path: Path | None = None,           # None: the defaults (no file found / --isolated)
                 select: list[str] | None = None,
                 ignore: list[str] | None = None,
                 per_file_ignores: list[tuple[str, list[str]]] | None = None,
                 strict: bool = False,
                 inertia: bool = False,
                 meshes: bool = False,
                 package_paths: list[str] | None = None,
                 packages: dict[str, str] | None = None,
                 allow_paths: list[str] | None = None,
                 no_env: bool = False,
                 args: list[tuple[str, dict[str, str]]] | None = None,
                 limits: dict[str, int] | None = None,     # Limits field -> value
                 exclude: list[str] | None = None,
                 help_url: str | None = None,
                 cache: bool = True):
        self.path = path
        self.select = [] if select is None else select
        self.ignore = [] if ignore is None else ignore
        self.per_file_ignores = [] if per_file_ignores is None else per_file_ignores
        self.strict = strict
        self.inertia = inertia
        self.meshes = meshes
        self.package_paths = [] if package_paths is None else package_paths
        self.packages = {} if packages is None else packages
        self.allow_paths = [] if allow_paths is None else allow_paths
        self.no_env = no_env
        self.args = [] if args is None else args
        self.limits = {} if limits is None else limits
        self.exclude = [] if exclude is None else exclude
        self.help_url = help_url
        self.cache = cache

    @property
    def root(self) -> Path:
        return self.path.parent if self.path else Path.cwd()

    def _rel(self, file: str | None) -> str | None:
        if not file:
            return None
        try:
            return Path(os.path.relpath(Path(file).resolve(), self.root.resolve())).as_posix()
        except ValueError:
            return None

    def _matching(self, which: str, patterns: list, file: str | None) -> list[int]:
        """Indexes of the ``patterns`` (compiled once per configuration) matching ``file``."""
        rel = self._rel(file)
        if rel is None or rel.startswith("..") or not patterns:
            return []
        sets = self.__dict__.setdefault("_globsets", {})
        gs = sets.get(which)
        if gs is None:
            gs = sets[which] = GlobSet(patterns)
        return gs.matching(rel)

    def ignores_for(self, file: str | None) -> list[str]:
        """The codes skipped for ``file``: ``ignore`` plus every matching per-file-ignores entry."""
        out = list(self.ignore)
        for i in self._matching("per-file-ignores", [p for p, _c in self.per_file_ignores], file):
            out += self.per_file_ignores[i][1]
        return out

    def args_for(self, file: str | None) -> dict[str, str]:
        out: dict[str, str] = {}
        for i in self._matching("args", [p for p, _v in self.args], file):
            out.update(self.args[i][1])
        return out

    def excluded(self, file: str) -> bool:
        return bool(self._matching("exclude", self.exclude, file))


_GLOB_CHARS = set("*?[\\")


class GlobSet:
    """Gitignore-style patterns, compiled once (pathspec translates each to a regular expression).

    ``matching(path)`` gives the indexes of the patterns that match, in time linear in the path's
    length and the patterns that can match it: every pattern is indexed by one of its segments
    that must equal, end or start a component of any path it matches (``robots/*.urdf`` by
    ``.urdf`` as a suffix, ``build/**`` by ``build``), so a path only tries the patterns one of
    its components selects, plus the few (MAX_UNINDEXED) that have no literal segment."""

    def __init__(self, patterns):
        import warnings

        from pathspec.patterns.gitwildmatch import GitWildMatchPattern

        self.regex = []
        self.names: dict[str, list[int]] = {}
        self.suffixes: dict[str, list[int]] = {}
        self.prefixes: dict[str, list[int]] = {}
        self.always: list[int] = []
        for i, pat in enumerate(patterns):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", DeprecationWarning)
                regex, include = GitWildMatchPattern.pattern_to_regex(pat)
            if regex is None or not include:
                self.regex.append(None)
                continue
            self.regex.append(re.compile(regex))
            kind, key = _index_key(pat)
            if kind is None:
                self.always.append(i)
            else:
                index = {"name": self.names, "suffix": self.suffixes, "prefix": self.prefixes}[kind]
                index.setdefault(key, []).append(i)
        self.suffix_lengths = sorted({len(k) for k in self.suffixes})
        self.prefix_lengths = sorted({len(k) for k in self.prefixes})

    def matching(self, path: str) -> list[int]:
        cands = set(self.always)
        for comp in path.split("/"):
            cands.update(self.names.get(comp, ()))
            n = len(comp)
            for k in self.suffix_lengths:
                if k > n:
                    break
                cands.update(self.suffixes.get(comp[n - k:], ()))
            for k in self.prefix_lengths:
                if k > n:
                    break
                cands.update(self.prefixes.get(comp[:k], ()))
        return sorted(i for i in cands if self.regex[i] is not None and self.regex[i].search(path))


def _index_key(pattern: str):
    """(kind, key) of the most selective segment of a gitignore pattern that a component of any
    matching path must equal (name), end with (suffix) or start with (prefix); (None, None) when
    no segment is such."""
    best = (None, None, -1)
    for seg in pattern.strip("/").split("/"):
        if not seg or seg == "**":
            continue
        if not _GLOB_CHARS & set(seg):
            cand = ("name", seg, 3 * len(seg) + 2)
        elif seg[0] == "*" and len(seg) > 1 and not _GLOB_CHARS & set(seg[1:]):
            cand = ("suffix", seg[1:], 3 * len(seg) + 1)
        elif seg[-1] == "*" and len(seg) > 1 and not _GLOB_CHARS & set(seg[:-1]):
            cand = ("prefix", seg[:-1], 3 * len(seg))
        else:
            continue
        if cand[2] > best[2]:
            best = cand
    return best[0], best[1]


def _line_of(text: str, key: str, table: str | None = None) -> int | None:
    """The 1-based line where ``key`` is written (``key =``, ``"key" =`` or a ``[...key]`` header),
    searched after the ``table`` header when given. tomllib keeps no positions, so we scan."""
    lines = text.splitlines()
    start = 0
    if table:
        for i, ln in enumerate(lines):
            if re.match(r"\s*\[\s*" + re.escape(table).replace(r"\.", r"\s*\.\s*") + r"\s*\]", ln.replace('"', "")):
                start = i
                break
    k = re.escape(key)
    pat = re.compile(r"""^\s*(?:["']?%s["']?\s*=|\[\s*[^\]]*\b%s["']?\s*\])""" % (k, k))
    inline = re.compile(r"""(?:^|[{,\s])["']?%s["']?\s*=""" % k)
    for i in range(start, len(lines)):
        if pat.search(lines[i]):
            return i + 1
    for i in range(start, len(lines)):
        if inline.search(lines[i]):
            return i + 1
    return None


class _Reader:
    def __init__(self, path: Path, text: str, table: str | None):
        self.path, self.text, self.table = path, text, table

    def globs(self, key: str, patterns: list) -> None:
        """At most MAX_PATTERNS patterns, MAX_UNINDEXED of them without a literal segment; no
        negation (``!``)."""
        self.bounded(key, patterns, MAX_PATTERNS)
        unindexed = 0
        for p in patterns:
            if p.startswith("!"):
                self.fail(key, f"{key}: negated patterns ({p!r}) are not supported")
            if _index_key(p)[0] is None:
                unindexed += 1
        if unindexed > MAX_UNINDEXED:
            self.fail(key, f"{key}: {unindexed} patterns without a literal part (like '*' or '?x'); at most "
                      f"{MAX_UNINDEXED} are allowed")

    def fail(self, key: str, message: str, within: str | None = None):
        line = _line_of(self.text, key, within or self.table)
        raise InputError(message, Loc(_display(self.path), line))

    def codes(self, key: str, value, known) -> list[str]:
        if isinstance(value, str):
            value = [c for c in value.split(",")]
        if not isinstance(value, list) or not all(isinstance(c, str) for c in value):
            self.fail(key, f"{key}: expected a list of rule codes, e.g. [\"I008\", \"G\"]")
        self.bounded(key, value)
        out = [c.strip().upper() for c in value if c.strip()]
        for c in out:
            msg = unknown_code_message(c, known())
            if msg:
                self.fail(key, f"{key}: {msg}")
        return out

    def bounded(self, key: str, value, most: int = MAX_ITEMS) -> None:
        if len(value) > most:
            self.fail(key, f"{key}: {len(value)} entries, at most {most} are allowed")

    def path_list(self, key: str, value) -> list[str]:
        if isinstance(value, str):
            value = [value]
        if not isinstance(value, list) or not all(isinstance(p, str) for p in value):
            self.fail(key, f"{key}: expected a list of folders")
        self.bounded(key, value)
        return [self.inside(key, p) for p in value]

    def inside(self, key: str, folder: str) -> str:
        """``folder`` (relative to the configuration's folder) resolved, refused unless it lies in
        the repository: a configuration may not open the runner's other files to the build."""
        top = repository_root(self.path)
        try:
            real = (self.path.parent / folder).resolve()
        except (OSError, RuntimeError, ValueError):
            self.fail(key, f"{key}: cannot resolve {folder!r}")
        if real != top and not real.is_relative_to(top):
            self.fail(key, f"{key}: {folder!r} is outside the repository ({display(top)}); a configuration "
                      "may name folders inside it only (give --allow-path / -p on the command line instead)")
        return str(real)


def _display(path: Path) -> str:
    return display(path)


def repository_root(config: Path) -> Path:
    """The work tree holding ``config`` (the nearest folder above it with a ``.git``), else the
    configuration's own folder; symlinks resolved."""
    here = config.resolve().parent
    for folder in [here, *here.parents]:
        if (folder / ".git").exists():
            return folder
    return here


def _nesting_line(text: str) -> int | None:
    """The line where arrays or inline tables first nest deeper than MAX_NESTING (outside strings,
    roughly: TOML strings are skipped when quoted on one line)."""
    depth = 0
    line = 1
    quote = None
    for ch in text:
        if ch == "\n":
            line += 1
            quote = None if quote in ('"', "'") else quote
            continue
        if quote:
            if ch == quote:
                quote = None
            continue
        if ch in "\"'":
            quote = ch
        elif ch in "[{":
            depth += 1
            if depth > MAX_NESTING:
                return line
        elif ch in "]}":
            depth = max(0, depth - 1)
    return None


def read_config(path: Path, known_codes) -> Config | None:
    """Read one configuration file; None when it is a pyproject.toml without our table.
    ``known_codes()`` gives the valid codes (called only when the file names some)."""
    try:      # the path gate: a regular file (no FIFO or device), read no further than the limit
        data = read_checked(path, None, MAX_CONFIG_BYTES, what="configuration")
    except InputError as exc:
        msg = exc.message.replace("(see MYRABOT_DESC_MAX_INPUT_BYTES)", "").strip()
        raise InputError(f"cannot read configuration: {msg}", Loc(_display(path))) from None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        raise InputError("configuration is not UTF-8 text", Loc(_display(path))) from None
    if path.name == "pyproject.toml" and (TOOL_TABLE not in text or not _OUR_TABLE.search(text)):
        # cannot hold our table: not parsed (tomllib and datetime cost ~5 ms of every check run
        # walking past a project's pyproject.toml; one that is not valid TOML is not ours to judge;
        # a table name spelled with \\u escapes is the one spelling missed)
        return None
    try:
        import tomli as tomllib          # compiled (mypyc): no typing import, a faster parse; the same errors
    except ModuleNotFoundError:          # a source install without it
        import tomllib

    deep = _nesting_line(text)
    if deep is not None:
        raise InputError(f"arrays or tables nest deeper than {MAX_NESTING}", Loc(_display(path), deep))
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        m = re.search(r"line (\d+)", str(exc))
        raise InputError(f"invalid TOML: {exc}", Loc(_display(path), int(m.group(1)) if m else None)) from None
    except RecursionError:
        raise InputError("arrays or tables nest too deeply", Loc(_display(path), _nesting_line(text))) from None
    if path.name == "pyproject.toml":
        table = doc.get("tool", {}).get(TOOL_TABLE) if isinstance(doc.get("tool"), dict) else None
        if table is None:
            return None
        prefix = f"tool.{TOOL_TABLE}"
    else:
        table, prefix = doc, None
    if not isinstance(table, dict):
        raise InputError(f"[tool.{TOOL_TABLE}] must be a table", Loc(_display(path), _line_of(text, TOOL_TABLE)))
    r = _Reader(path, text, prefix)
    cfg = Config(path=path)
    for key, value in table.items():
        if key not in KEYS:
            guess = closest(key, KEYS)
            r.fail(key, f"unknown configuration key '{key}'" + (f"; did you mean '{guess}'?" if guess else
                                                                   f" (known: {', '.join(KEYS)})"))
        kind = KEYS[key][0]
        sub = f"{prefix}.{key}" if prefix else key
        if kind == "codes":
            setattr(cfg, key, r.codes(key, value, known_codes))
        elif kind == "bool":
            if not isinstance(value, bool):
                r.fail(key, f"{key}: expected true or false")
            setattr(cfg, key.replace("-", "_"), value)
        elif kind == "paths":
            setattr(cfg, key.replace("-", "_"), r.path_list(key, value))
        elif kind == "globs":
            if isinstance(value, str):
                value = [value]
            if not isinstance(value, list) or not all(isinstance(p, str) for p in value):
                r.fail(key, f"{key}: expected a list of glob patterns")
            r.globs(key, value)
            cfg.exclude = list(value)
        elif kind == "str":
            if not isinstance(value, str):
                r.fail(key, f"{key}: expected a string")
            cfg.help_url = value
        elif not isinstance(value, dict):
            r.fail(key, f"{key}: expected a table")
        elif kind == "table-codes":
            r.globs(key, list(value))
            cfg.per_file_ignores = [(g, _Reader(path, text, sub).codes(g, v, known_codes)) for g, v in value.items()]
        elif kind == "table-paths":
            r.bounded(key, value)
            for name, p in value.items():
                if not isinstance(p, str):
                    _Reader(path, text, sub).fail(name, f"{key}.{name}: expected a folder (a string)")
                cfg.packages[name] = _Reader(path, text, sub).inside(name, p)
        elif kind == "table-args":
            r.globs(key, list(value))
            for glob, values in value.items():
                if not isinstance(values, dict):
                    _Reader(path, text, sub).fail(glob, f"{key}.{glob}: expected a table of xacro args")
                _Reader(path, text, sub).bounded(glob, values)
                cfg.args.append((glob, {str(k): _scalar(v) for k, v in values.items()}))
        elif kind == "table-limits":
            names = {lim.field.replace("_", "-"): lim.field for lim in LIMITS}
            for name, v in value.items():
                rr = _Reader(path, text, sub)
                if name not in names:
                    guess = closest(name, names)
                    rr.fail(name, f"unknown limit '{name}'" + (f"; did you mean '{guess}'?" if guess else
                                                               f" (known: {', '.join(names)})"))
                if isinstance(v, bool) or not isinstance(v, int) or v <= 0:
                    rr.fail(name, f"limits.{name}: expected a positive whole number")
                # lowered only: raising a limit is the runner's decision (flag or environment)
                cfg.limits[names[name]] = min(v, limit(names[name]))
    return cfg


def _scalar(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    return str(v)


class Finder:
    """Nearest configuration per checked file, each file read once per run."""

    def __init__(self, known_codes, config_file: str | None = None, isolated: bool = False):
        self.known = known_codes
        self.isolated = isolated
        self.by_dir: dict[Path, Config] = {}
        self.by_file: dict[Path, Config | None] = {}
        self.fixed: Config | None = None
        if config_file is not None:
            p = Path(config_file)
            if not p.exists():
                raise InputError(f"--config {config_file}: no such file")
            cfg = read_config(p, known_codes)
            if cfg is None:
                raise InputError(f"no [tool.{TOOL_TABLE}] table", Loc(_display(p)))
            self.fixed = cfg

    def for_file(self, file: str | None) -> Config:
        if self.fixed is not None:
            return self.fixed
        if self.isolated:
            return Config()
        start = Path(file).resolve().parent if file else Path.cwd().resolve()
        walked = []
        found = Config()
        for folder in [start, *start.parents]:
            if folder in self.by_dir:
                found = self.by_dir[folder]
                break
            walked.append(folder)
            cfg = self._in_folder(folder)
            if cfg is not None:
                found = cfg
                break
        for folder in walked:
            self.by_dir[folder] = found
        return found

    def _in_folder(self, folder: Path) -> Config | None:
        for name in (OWN_NAME, "pyproject.toml"):
            p = folder / name
            if p.is_file():
                if p not in self.by_file:
                    self.by_file[p] = read_config(p, self.known)
                if self.by_file[p] is not None:
                    return self.by_file[p]
        return None
