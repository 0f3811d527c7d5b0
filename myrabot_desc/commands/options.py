"""The option tables every command shares, and the command line parsed without click.

One definition per option (:class:`Opt`): click's option (``Opt.click_option``, :func:`input_options`)
and the plain parser (:func:`parse_plain`, the fast ``build`` path in commands/fastbuild.py) both
come from it. :class:`Inputs` is what the user asked to read (FILE, NAME:=VALUE, packages, safety
options); commands/common.py adds loading the model. Nothing here imports click at its top (the
functions that make click's options import it when called), lxml or the model: a plain ``build``
and ``build --help`` import this module and must start fast (bench/bench_start.py).
"""

from __future__ import annotations

import os

from myrabot_desc.errors import UsageProblem
from myrabot_desc.records import Struct
from myrabot_desc.safety import LIMITS

__all__ = ["BUILD_OPTS", "CHECK_OPTS", "DIFF_OPTS", "INPUT_OPTS", "Inputs", "Opt", "UsageProblem", "input_options", "make_inputs",
           "parse_plain", "usage_error"]


class Opt(Struct):
    """One command-line option, the one definition of it: click's option and the fast parser
    (parse_plain) both come from it. kind: "flag", "value" (one string), "multi" (repeatable, a
    tuple), "choice" (default choices[0], shown), "count" (a whole number >= 1), "file" (a path
    that is not a folder), "folder" (a path that is not a file). ``default``: of "value", "count",
    "file" and "folder" (None; shown when set)."""

    decls: tuple
    dest: str
    kind: str
    help: str
    metavar: str | None
    choices: tuple | None
    default: object = None

    def click_option(self):
        import click      # here, not at the top: the plain build path must not pay for click

        kw = {"help": self.help}
        if self.kind == "flag":
            kw["is_flag"] = True
        elif self.kind == "multi":
            kw["multiple"] = True
        elif self.kind == "choice":
            kw.update(type=click.Choice(list(self.choices)), default=self.choices[0], show_default=True)
        else:
            if self.kind == "count":
                kw["type"] = click.IntRange(min=1)
            elif self.kind == "file":
                kw["type"] = click.Path(dir_okay=False)
            elif self.kind == "folder":
                kw["type"] = click.Path(file_okay=False)
            kw["default"] = self.default
            if self.default is not None:
                kw["show_default"] = True
        if self.metavar:
            kw["metavar"] = self.metavar
        return click.option(*self.decls, self.dest, **kw)


# FILE [NAME:=VALUE ...] come first (click.argument "args"); then these, in --help order.
# True in a process the console entry started (commands/entry.py, no argv given): a command may then
# leave the cyclic collector off and freeze what it made instead of freeing it at exit, as a plain
# build does. Never in a process that goes on (tests, library use).
ONE_SHOT = False

INPUT_OPTS = (
    Opt(("-p", "--package"), "packages", "multi",
        "Where package NAME lives (for $(find NAME) and package://NAME). Repeatable.", "NAME=PATH", None),
    Opt(("--package-path",), "package_paths", "multi",
        "Folder searched for packages (package.xml or manifest.xml). Repeatable.", "DIR", None),
    Opt(("--legacy",), "legacy", "choice",
        "Upgrade ROS Electric/Fuerte xacro syntax (un-prefixed tags, bare macro calls).", None, ("auto", "on", "off")),
    Opt(("--unsafe-eval",), "unsafe_eval", "flag",
        "Evaluate ${} expressions without the allow-list (trusted files only).", None, None),
    Opt(("--no-env",), "no_env", "flag", "Refuse $(env) and $(optenv).", None, None),
    Opt(("--allow-path",), "allow_paths", "multi",
        "Also allow includes and load_yaml under DIR. Repeatable.", "DIR", None),
)


# build's own options (commands/fastbuild.py runs them; commands/build.py is their click command).
BUILD_OPTS = (
    Opt(("-o", "--output"), "output", "value", "Write the URDF here ('-' for stdout). Default: stdout.",
        "OUT.urdf", None),
    Opt(("--deps",), "deps", "flag", "List the files the build reads (input, includes, YAML), one per line.",
        None, None),
    Opt(("--resolve-uris",), "resolve_uris", "flag", "Rewrite package:// URIs into absolute file:// paths.",
        None, None),
    Opt(("--allow-errors",), "allow_errors", "flag",
        "Write the URDF even when the build reports errors (X002).", None, None),
) + tuple(   # a --max-* flag for every limit of the table that has one
    Opt((lim.flag,), lim.flag[2:].replace("-", "_"), "count", f"{lim.help[0].upper()}{lim.help[1:]} [{lim.default}].",
        None, None) for lim in LIMITS if lim.flag)


# diff's own options (commands/fastdiff.py runs them; commands/diff.py is their click command).
DIFF_OPTS = (
    Opt(("--rev",), "rev", "value", "Compare FILE at git revision A with revision B (A..B) or with the work tree (A). "
        "The revisions are read with git into a temporary folder; the work tree is not touched.", "A..B | A", None),
    Opt(("--format",), "fmt", "choice", "Report format (markdown: a pull-request comment).", None,
        ("text", "json", "markdown")),
    Opt(("--no-check",), "no_check", "flag", "Do not compare the findings of `check` (faster).", None, None),
    Opt(("--select",), "select", "multi", "Only these check codes or prefixes.", "CODES", None),
    Opt(("--ignore",), "ignore", "multi", "Skip these check codes or prefixes.", "CODES", None),
    Opt(("--image",), "image", "value", "Markdown: show this before/after picture (e.g. --picture's, uploaded).",
        "URL", None),
    Opt(("--picture",), "picture", "value", "Render the robot before and after, side by side, into this PNG "
        "(MuJoCo offscreen, as `render`).", "PNG", None),
    Opt(("--limit",), "limit", "count", "Markdown: rows in the table (the largest changes).", None, None, 25),
    Opt(("-o", "--output"), "output", "file", "Write the report to a file instead of stdout.", None, None, "-"),
    Opt(("--exit-zero",), "exit_zero", "flag", "Exit 0 when there are changes too (a report, not a gate).",
        None, None),
)


# check's own options (commands/fastcheck.py runs them; commands/check.py is their click command).
CHECK_OPTS = (
    Opt(("--inertia",), "inertia", "flag",
        "Load collision meshes and compare every inertia with the solid body of its collision geometry.", None, None),
    Opt(("--suggest",), "suggest", "flag", "With --inertia: print a ready <inertia .../> line per link.", None, None),
    Opt(("--meshes",), "meshes", "flag", "Load every mesh (visual too) to check scale, watertightness and normals.",
        None, None),
    Opt(("--srdf",), "srdf", "file", "The robot's SRDF: the link pairs its <disable_collisions> lets touch are not "
        "self-collisions (P005), and an overlap it does not allow is an error.", "FILE", None),
    Opt(("--format",), "fmt", "choice", "Report format.", None, ("text", "json", "github", "sarif", "junit")),
    Opt(("--select",), "select", "multi", "Only these codes or prefixes (comma-separated or repeated), e.g. I,G001. "
        "Replaces the configuration's select.", "CODES", None),
    Opt(("--ignore",), "ignore", "multi", "Skip these codes or prefixes (added to the configuration's ignore).",
        "CODES", None),
    Opt(("--strict",), "strict", "flag", "Warnings fail too (exit 1).", None, None),
    Opt(("-o", "--output"), "output", "file", "Write the report to a file instead of stdout.", None, None, "-"),
    Opt(("-r", "--recursive"), "recursive", "flag",
        "Folders: look for models in their subfolders too (hidden and build folders skipped).", None, None),
    Opt(("--config",), "config_file", "file", "Use this configuration for every file (pyproject.toml or "
        "myrabot-desc.toml) instead of the nearest one.", "FILE", None),
    Opt(("--isolated",), "isolated", "flag", "Ignore every configuration file.", None, None),
    Opt(("-j", "--jobs"), "jobs", "count",
        "Worker processes (default: the CPUs available). The report is the same for any N.", "N", None),
    Opt(("--shard",), "shard_spec", "value",
        "Check only the K-th of N deterministic parts of the file list (a CI matrix job each).", "K/N", None),
    Opt(("-q", "--quiet"), "quiet", "flag", "No progress bar; text reports only the findings.", None, None),
    Opt(("--no-cache",), "no_cache", "flag", "Do not read or write the result cache (a project with a configuration "
        "file uses it; entries are kept in the user's cache folder, ~/.cache/myrabot-desc, and signed with a per-user "
        "key).", None, None),
    Opt(("--cache-dir",), "cache_dir", "folder", "Keep the cache entries in DIR (e.g. a repository-local "
        ".myrabot-desc-cache) instead of the user's cache folder (or MYRABOT_DESC_CACHE_DIR); entries stay signed "
        "with the user's key.", "DIR", None),
    Opt(("--merge-sarif",), "merge_sarif", "flag",
        "The FILEs are SARIF reports (from --shard jobs): merge them into one report.", None, None),
    Opt(("--fix",), "fix_", "flag", "Repair the findings whose rule has a safe fix, in the files where the values "
        "are written (proven by a rebuild and recheck first; all files written together or none).", None, None),
    Opt(("--unsafe-fixes",), "unsafe_fixes", "flag", "With --fix or --diff: the unsafe fixes too (docs/rules.md "
        "says which fixes are unsafe and why).", None, None),
    Opt(("--diff",), "diff_", "flag", "Show the fixes as a unified diff and write nothing (exit 1 when there is "
        "something to fix).", None, None),
    Opt(("--baseline",), "baseline", "file", "Findings recorded in FILE are known: only new ones are reported and "
        "fail. A missing FILE is written with today's findings (matched by code, element and message, not by line).",
        "FILE", None),
    Opt(("--update-baseline",), "update_baseline", "flag", "With --baseline: write today's findings to FILE again.",
        None, None),
    Opt(("--changed-since",), "since", "value",
        "Check only the models that read a file (include, YAML, mesh) changed since git revision REV.", "REV", None),
    Opt(("--list-rules",), "list_rules", "flag", "List every rule code and exit.", None, None),
)

def parse_plain(argv, opts) -> dict | None:
    """``argv`` parsed as click would parse it for these options (values by dest, the
    positionals under "args"), when it uses only plain forms: ``--name VALUE``,
    ``--name=VALUE``, ``-p VALUE``, flags, positionals. Anything else (``--help``, ``--``,
    unknown or bundled short options, a missing or bad value, a value that starts with
    ``-``) gives None: click then parses it, with its own messages and exit codes."""
    by_decl = {d: o for o in opts for d in o.decls}
    values = {o.dest: False if o.kind == "flag" else () if o.kind == "multi" else
              o.choices[0] if o.kind == "choice" else o.default for o in opts}
    args = []
    i, n = 0, len(argv)
    while i < n:
        a = argv[i]
        i += 1
        if a[:1] != "-":
            args.append(a)
            continue
        name, eq, value = a.partition("=") if a.startswith("--") else (a, "", None)
        o = by_decl.get(name)
        if o is None:
            return None
        if o.kind == "flag":
            if eq:
                return None
            values[o.dest] = True
            continue
        if not eq:
            if i >= n or (argv[i][:1] == "-" and argv[i] != "-"):
                return None
            value = argv[i]
            i += 1
        if o.kind == "multi":
            values[o.dest] += (value,)
        elif o.kind == "choice":
            if value not in o.choices:
                return None
            values[o.dest] = value
        elif o.kind == "count":
            if not (value.isascii() and value.isdigit() and int(value) >= 1):
                return None
            values[o.dest] = int(value)
        elif o.kind == "file" or o.kind == "folder":
            if os.path.isdir(value) if o.kind == "file" else os.path.isfile(value):
                return None
            values[o.dest] = value
        else:
            values[o.dest] = value
    values["args"] = tuple(args)
    return values


class Inputs:
    """What the user asked to read, and how to build it (commands/common.ModelInputs also loads it)."""

    def __init__(self, files=None, packages=None, package_paths=None, mappings=None, legacy: str = "auto",
                 unsafe_eval: bool = False, no_env: bool = False, allow_paths=None):
        self.files: list[str] = list(files or [])
        self.packages: dict[str, str] = dict(packages or {})       # -p NAME=PATH
        self.package_paths: list[str] = list(package_paths or [])  # --package-path DIR
        self.mappings: dict[str, str] = dict(mappings or {})       # NAME:=VALUE
        self.legacy = legacy
        self.unsafe_eval = unsafe_eval
        self.no_env = no_env
        self.allow_paths: list[str] = list(allow_paths or [])

    def __repr__(self) -> str:
        return f"Inputs({', '.join(f'{k}={v!r}' for k, v in vars(self).items())})"

    def __eq__(self, other):
        return vars(self) == vars(other) if isinstance(other, Inputs) else NotImplemented

    @property
    def file(self) -> str | None:
        return self.files[0] if self.files else None

    def build_options(self) -> dict:
        return dict(packages=self.packages, package_paths=self.package_paths, mappings=self.mappings,
                    legacy=self.legacy, unsafe_eval=self.unsafe_eval, no_env=self.no_env,
                    allow_paths=self.allow_paths)


def _split_args(args: tuple[str, ...]) -> tuple[list[str], dict[str, str]]:
    files, mappings = [], {}
    for a in args:
        if ":=" in a:
            k, v = a.split(":=", 1)
            mappings[k] = v
        else:
            files.append(a)
    return files, mappings


def _parse_packages(values: tuple[str, ...]) -> dict[str, str]:
    out = {}
    for v in values:
        if "=" not in v:
            raise UsageProblem(f"expected NAME=PATH, got {v!r}", param_hint="-p/--package")
        k, p = v.split("=", 1)
        out[k.strip()] = p
    return out


def make_inputs(values: dict, multiple: bool = False, cls: type = Inputs) -> Inputs:
    """The Inputs (of class ``cls``) of parsed option values (click's or parse_plain's); UsageProblem
    if they do not fit."""
    files, mappings = _split_args(values.get("args", ()))
    if len(files) > 1 and not multiple:
        raise UsageProblem(f"expected one FILE, got {len(files)}: {' '.join(files)}")
    return cls(files=files, packages=_parse_packages(values.get("packages", ())),
                  package_paths=list(values.get("package_paths", ())), mappings=mappings,
                  legacy=values.get("legacy", "auto"), unsafe_eval=values.get("unsafe_eval", False),
                  no_env=values.get("no_env", False), allow_paths=list(values.get("allow_paths", ())))


def usage_error(exc: UsageProblem):
    """click's error for a UsageProblem: BadParameter when it names the option, else UsageError."""
    import click

    if exc.param_hint:
        return click.BadParameter(str(exc), param_hint=exc.param_hint)
    return click.UsageError(str(exc))


def input_options(multiple: bool = False, cls: type = Inputs):
    """Decorator: FILE [NAME:=VALUE ...] plus the package and safety options.

    With ``multiple=True`` several FILEs are accepted (``check`` lints a folder's models).
    Passes ``inputs`` (a ``cls``) to the command.
    """
    import functools

    import click

    def deco(f):
        opts = [click.argument("args", nargs=-1, metavar="[FILE]..." if multiple else "[FILE] [NAME:=VALUE]...")]
        opts += [o.click_option() for o in INPUT_OPTS]
        for o in reversed(opts):
            f = o(f)
        names = ("args",) + tuple(o.dest for o in INPUT_OPTS)

        @functools.wraps(f)
        def wrapper(*a, **kw):
            values = {k: kw.pop(k) for k in names if k in kw}
            try:
                inputs = make_inputs(values, multiple, cls)
            except UsageProblem as exc:
                raise usage_error(exc) from None
            return f(*a, inputs=inputs, **kw)

        return wrapper

    return deco
