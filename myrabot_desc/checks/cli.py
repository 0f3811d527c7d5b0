"""``myrabot-desc check``: the command line of the rule registry."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import click

from myrabot_desc.cli_common import guarded, input_options

MODEL_SUFFIXES = (".urdf", ".xacro")
INCLUDE_RE = re.compile(r"""<(?:xacro:)?include\s[^>]*filename\s*=\s*["']([^"']+)["']""")


# Never descended into by --recursive: VCS data, build trees, environments.
SKIP_DIRS = {".git", ".hg", ".svn", "build", "install", "log", "devel", "node_modules", "__pycache__",
             ".venv", "venv", ".tox"}


def expand_inputs(files: list[str], recursive: bool = False) -> list[str]:
    """Folders become their top-level model files: *.urdf and *.xacro directly inside (with
    ``recursive``, anywhere below, hidden and build folders skipped), minus the xacro files
    that another xacro file of the folder includes (parts, not robots)."""
    out: list[str] = []
    for f in files:
        p = Path(f)
        if not p.is_dir():
            out.append(f)
            continue
        models = sorted(_model_files(p, recursive))
        included = set()
        for c in models:
            if c.name.endswith(".xacro"):
                try:
                    text = c.read_text(encoding="utf-8", errors="replace")
                except OSError:
                    continue
                included |= {Path(m).name for m in INCLUDE_RE.findall(text)}
        picked = [str(c) for c in models if c.name not in included or c.name.endswith(".urdf")]
        if not picked:
            hint = "" if recursive else " (-r looks in its subfolders too)"
            raise click.UsageError(f"{f}: no .urdf or .xacro model files in this folder{hint}")
        out.extend(picked)
    return out


def _model_files(folder: Path, recursive: bool):
    if not recursive:
        yield from (c for c in folder.iterdir() if c.is_file() and c.name.endswith(MODEL_SUFFIXES))
        return
    import os

    for root, dirs, names in os.walk(folder):        # does not follow symlinked folders (no loops)
        dirs[:] = sorted(d for d in dirs if d not in SKIP_DIRS and not d.startswith("."))
        yield from (Path(root) / n for n in names if n.endswith(MODEL_SUFFIXES))


def check_one(inputs, path, options, select, ignore):
    """FileResult for one input (never raises for bad input: failure holds the one line)."""
    from myrabot_desc.checks import check_robot
    from myrabot_desc.checks.report import FileResult
    from myrabot_desc.errors import InputError

    res = FileResult(file=path or "")
    try:
        robot = inputs.load(path) if path is not None else inputs.load(None)
        diags, ctx = check_robot(robot, options, select, ignore)
    except InputError as exc:
        res.failure = str(exc).splitlines()[0]
        return res
    except (RecursionError, MemoryError) as exc:
        res.failure = f"{path}: error: input too large or nested too deeply ({type(exc).__name__})"
        return res
    res.diagnostics = diags
    res.robot = robot.name
    res.links, res.joints = len(robot.links), len(robot.joints)
    res.suggestions = list(ctx.suggestions)
    return res


@click.command("check")
@input_options(multiple=True)
@click.option("--inertia", is_flag=True,
              help="Load collision meshes and compare every inertia with the solid body of its collision geometry.")
@click.option("--suggest", is_flag=True, help="With --inertia: print a ready <inertia .../> line per link.")
@click.option("--meshes", is_flag=True, help="Load every mesh (visual too) to check scale, watertightness and normals.")
@click.option("--format", "fmt", type=click.Choice(["text", "json", "github", "sarif"]), default="text",
              show_default=True, help="Report format.")
@click.option("--select", "select", multiple=True, metavar="CODES",
              help="Only these codes or prefixes (comma-separated or repeated), e.g. I,G001.")
@click.option("--ignore", "ignore", multiple=True, metavar="CODES", help="Skip these codes or prefixes.")
@click.option("--strict", is_flag=True, help="Warnings fail too (exit 1).")
@click.option("-o", "--output", type=click.Path(dir_okay=False), default="-", show_default=True,
              help="Write the report to a file instead of stdout.")
@click.option("-r", "--recursive", is_flag=True,
              help="Folders: look for models in their subfolders too (hidden and build folders skipped).")
@click.option("--list-rules", is_flag=True, help="List every rule code and exit.")
def check_cmd(inputs, inertia, suggest, meshes, fmt, select, ignore, strict, output, recursive, list_rules):
    """Lint robot models: tree, inertia, sensors and frames, Gazebo plugins, meshes, physics.

    Each finding has a stable code (X build, T tree, I inertia, S sensors/frames,
    G Gazebo/plugins, M meshes, P physics), a severity, the numbers that matter and the
    xacro file:line it comes from. docs/rules.md explains every rule and its fix.

    \b
    Examples:
      myrabot-desc check                              # the bundled MYRAbot
      myrabot-desc check robot.urdf.xacro -p my_pkg=../my_pkg
      myrabot-desc check --inertia --suggest robot.urdf
      myrabot-desc check urdf/ --format github        # every top-level model in a folder
      myrabot-desc check -r . --strict                # every model of a repository (CI)
      myrabot-desc check robot.urdf --select I,P --strict
      myrabot-desc check robot.urdf --format sarif -o check.sarif

    \b
    Exit codes: 0 no errors (no warnings either with --strict), 1 errors found,
    2 a file could not be processed (one line each, the other files are still checked).
    """
    from myrabot_desc import __version__
    from myrabot_desc.checks import CheckOptions
    from myrabot_desc.checks.report import (
        render_github,
        render_json,
        render_sarif,
        render_text,
        rule_table,
    )
    from myrabot_desc.output import write_output

    with guarded():
        if list_rules:
            for code, name, sev, summary, _doc in rule_table():
                click.echo(f"{code}  {sev:<7}  {name:<28} {summary}")
            return
        if suggest and not inertia:
            inertia = True          # --suggest needs the comparison
        sel = [c for s in select for c in s.split(",") if c.strip()]
        ign = [c for s in ignore for c in s.split(",") if c.strip()]
        options = CheckOptions(inertia=inertia, suggest=suggest, meshes=meshes)
        paths = expand_inputs(inputs.files, recursive) if inputs.files else [None]
        results = []
        show_bar = fmt == "text" and output == "-" and len(paths) >= 5 and sys.stderr.isatty()
        if show_bar:
            with click.progressbar(paths, label="checking", file=sys.stderr,
                                   item_show_func=lambda p: Path(p).name if p else "") as bar:
                for p in bar:
                    results.append(check_one(inputs, p, options, sel, ign))
        else:
            for p in paths:
                results.append(check_one(inputs, p, options, sel, ign))

        if fmt == "json":
            text = render_json(results, __version__)
        elif fmt == "github":
            text = render_github(results)
        elif fmt == "sarif":
            text = render_sarif(results, __version__)
        else:
            text = render_text(results)
        if output == "-":
            click.echo(text, nl=False)
        else:
            write_output(output, click.unstyle(text))
        for r in results:
            if r.failure and fmt != "text":
                click.echo(r.failure, err=True)

    if any(r.failure for r in results):
        sys.exit(2)
    if any(r.count("error") for r in results) or (strict and any(r.count("warning") for r in results)):
        sys.exit(1)
