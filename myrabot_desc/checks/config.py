"""``check``'s project configuration: ``[tool.myrabot-desc]`` in pyproject.toml or a
``myrabot-desc.toml`` (same keys at top level), found as ruff finds its own.

For each checked file the nearest configuration wins: walking up from the file's folder,
the first folder with a ``myrabot-desc.toml`` (preferred) or a ``pyproject.toml`` that has a
``[tool.myrabot-desc]`` table. Paths inside a configuration are relative to its folder.
``--config FILE`` uses one file for every input; ``--isolated`` reads none.

Unknown keys, wrong types and unknown rule codes are errors at the key's file:line (exit 2).
"""

from __future__ import annotations

import fnmatch
import os
import re
from dataclasses import dataclass, field
from pathlib import Path

from myrabot_desc.checks.codes import closest, unknown_code_message
from myrabot_desc.diagnostics import Loc
from myrabot_desc.errors import InputError
from myrabot_desc.safety import LIMITS, display

TOOL_TABLE = "myrabot-desc"
OWN_NAME = "myrabot-desc.toml"
MAX_CONFIG_BYTES = 1_000_000

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


@dataclass
class Config:
    """One configuration file's settings (paths already absolute)."""

    path: Path | None = None                    # None: the defaults (no file found / --isolated)
    select: list[str] = field(default_factory=list)
    ignore: list[str] = field(default_factory=list)
    per_file_ignores: list[tuple[str, list[str]]] = field(default_factory=list)
    strict: bool = False
    inertia: bool = False
    meshes: bool = False
    package_paths: list[str] = field(default_factory=list)
    packages: dict[str, str] = field(default_factory=dict)
    allow_paths: list[str] = field(default_factory=list)
    no_env: bool = False
    args: list[tuple[str, dict[str, str]]] = field(default_factory=list)
    limits: dict[str, int] = field(default_factory=dict)     # Limits field -> value
    exclude: list[str] = field(default_factory=list)
    help_url: str | None = None
    cache: bool = True

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

    def _matches(self, pattern: str, file: str | None) -> bool:
        rel = self._rel(file)
        if rel is None or rel.startswith(".."):
            return False
        pat = pattern.rstrip("/")
        return (fnmatch.fnmatchcase(rel, pat) or fnmatch.fnmatchcase(Path(rel).name, pat)
                or rel.startswith(pat + "/"))

    def ignores_for(self, file: str | None) -> list[str]:
        """The codes skipped for ``file``: ``ignore`` plus every matching per-file-ignores entry."""
        out = list(self.ignore)
        for pattern, codes in self.per_file_ignores:
            if self._matches(pattern, file):
                out += codes
        return out

    def args_for(self, file: str | None) -> dict[str, str]:
        out: dict[str, str] = {}
        for pattern, values in self.args:
            if self._matches(pattern, file):
                out.update(values)
        return out

    def excluded(self, file: str) -> bool:
        return any(self._matches(p, file) for p in self.exclude)


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

    def fail(self, key: str, message: str, within: str | None = None):
        line = _line_of(self.text, key, within or self.table)
        raise InputError(message, Loc(_display(self.path), line))

    def codes(self, key: str, value, known) -> list[str]:
        if isinstance(value, str):
            value = [c for c in value.split(",")]
        if not isinstance(value, list) or not all(isinstance(c, str) for c in value):
            self.fail(key, f"{key}: expected a list of rule codes, e.g. [\"I008\", \"G\"]")
        out = [c.strip().upper() for c in value if c.strip()]
        for c in out:
            msg = unknown_code_message(c, known())
            if msg:
                self.fail(key, f"{key}: {msg}")
        return out

    def path_list(self, key: str, value) -> list[str]:
        if isinstance(value, str):
            value = [value]
        if not isinstance(value, list) or not all(isinstance(p, str) for p in value):
            self.fail(key, f"{key}: expected a list of folders")
        return [str((self.path.parent / p).resolve()) for p in value]


def _display(path: Path) -> str:
    return display(path)


def read_config(path: Path, known_codes) -> Config | None:
    """Read one configuration file; None when it is a pyproject.toml without our table.
    ``known_codes()`` gives the valid codes (called only when the file names some)."""
    try:
        import tomllib
    except ModuleNotFoundError:          # Python 3.10
        import tomli as tomllib

    try:
        if path.stat().st_size > MAX_CONFIG_BYTES:
            raise InputError(f"configuration over {MAX_CONFIG_BYTES} bytes", Loc(_display(path)))
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise InputError(f"cannot read configuration: {exc.strerror}", Loc(_display(path))) from None
    except UnicodeDecodeError:
        raise InputError("configuration is not UTF-8 text", Loc(_display(path))) from None
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        m = re.search(r"line (\d+)", str(exc))
        raise InputError(f"invalid TOML: {exc}", Loc(_display(path), int(m.group(1)) if m else None)) from None
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
            cfg.exclude = list(value)
        elif kind == "str":
            if not isinstance(value, str):
                r.fail(key, f"{key}: expected a string")
            cfg.help_url = value
        elif not isinstance(value, dict):
            r.fail(key, f"{key}: expected a table")
        elif kind == "table-codes":
            cfg.per_file_ignores = [(g, _Reader(path, text, sub).codes(g, v, known_codes)) for g, v in value.items()]
        elif kind == "table-paths":
            for name, p in value.items():
                if not isinstance(p, str):
                    _Reader(path, text, sub).fail(name, f"{key}.{name}: expected a folder (a string)")
                cfg.packages[name] = str((path.parent / p).resolve())
        elif kind == "table-args":
            for glob, values in value.items():
                if not isinstance(values, dict):
                    _Reader(path, text, sub).fail(glob, f"{key}.{glob}: expected a table of xacro args")
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
                cfg.limits[names[name]] = v
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
            if not p.is_file():
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
