"""``myrabot-desc check``: the command line of the rule registry (checks/run.py runs the files)."""

from __future__ import annotations

import gc
import sys
from pathlib import Path

import click

from myrabot_desc import __version__
from myrabot_desc.checks import baseline as baselines
from myrabot_desc.checks.report import merge_sarif_files, render, rule_table
from myrabot_desc.checks.run import changed_since, default_jobs, exit_code, plan, run_tasks
from myrabot_desc.checks.suppress import unused_findings
from myrabot_desc.commands.common import input_options
from myrabot_desc.commands.console import guarded
from myrabot_desc.commands import options
from myrabot_desc.commands.options import usage_error
from myrabot_desc.errors import UsageProblem
from myrabot_desc.fix.report import summary, unified_diff
from myrabot_desc.fix.run import fix_tasks
from myrabot_desc.fix.write import write_fixed
from myrabot_desc.output import write_output
from myrabot_desc.sanitize import clean


def _progressbar(results, length):
    """click's progress bar on stderr (it shows only when stderr is a terminal)."""
    return click.progressbar(results, length=length, label="checking", file=sys.stderr,
                             item_show_func=lambda r: (Path(r.file).name if r and r.file else ""))


@click.command("check")
@input_options(multiple=True)
@click.option("--inertia", is_flag=True,
              help="Load collision meshes and compare every inertia with the solid body of its collision geometry.")
@click.option("--suggest", is_flag=True, help="With --inertia: print a ready <inertia .../> line per link.")
@click.option("--meshes", is_flag=True, help="Load every mesh (visual too) to check scale, watertightness and normals.")
@click.option("--srdf", type=click.Path(dir_okay=False), metavar="FILE",
              help="The robot's SRDF: the link pairs its <disable_collisions> lets touch are not self-collisions "
                   "(P005), and an overlap it does not allow is an error.")
@click.option("--format", "fmt", type=click.Choice(["text", "json", "github", "sarif", "junit"]), default="text",
              show_default=True, help="Report format.")
@click.option("--select", "select", multiple=True, metavar="CODES",
              help="Only these codes or prefixes (comma-separated or repeated), e.g. I,G001. Replaces the "
                   "configuration's select.")
@click.option("--ignore", "ignore", multiple=True, metavar="CODES",
              help="Skip these codes or prefixes (added to the configuration's ignore).")
@click.option("--strict", is_flag=True, help="Warnings fail too (exit 1).")
@click.option("-o", "--output", type=click.Path(dir_okay=False), default="-", show_default=True,
              help="Write the report to a file instead of stdout.")
@click.option("-r", "--recursive", is_flag=True,
              help="Folders: look for models in their subfolders too (hidden and build folders skipped).")
@click.option("--config", "config_file", type=click.Path(dir_okay=False), metavar="FILE",
              help="Use this configuration for every file (pyproject.toml or myrabot-desc.toml) instead of the "
                   "nearest one.")
@click.option("--isolated", is_flag=True, help="Ignore every configuration file.")
@click.option("-j", "--jobs", type=click.IntRange(min=1), default=None, metavar="N",
              help="Worker processes (default: the CPUs available). The report is the same for any N.")
@click.option("--shard", "shard_spec", metavar="K/N",
              help="Check only the K-th of N deterministic parts of the file list (a CI matrix job each).")
@click.option("-q", "--quiet", is_flag=True, help="No progress bar; text reports only the findings.")
@click.option("--no-cache", is_flag=True,
              help="Do not read or write the result cache (a project with a configuration file uses it; entries "
                   "are kept in the user's cache folder, ~/.cache/myrabot-desc, and signed with a per-user key).")
@click.option("--cache-dir", "cache_dir", type=click.Path(file_okay=False), metavar="DIR", default=None,
              help="Keep the cache entries in DIR (e.g. a repository-local .myrabot-desc-cache) instead of the "
                   "user's cache folder (or MYRABOT_DESC_CACHE_DIR); entries stay signed with the user's key.")
@click.option("--merge-sarif", is_flag=True,
              help="The FILEs are SARIF reports (from --shard jobs): merge them into one report.")
@click.option("--fix", "fix_", is_flag=True,
              help="Repair the findings whose rule has a safe fix, in the files where the values are written "
                   "(proven by a rebuild and recheck first; all files written together or none).")
@click.option("--unsafe-fixes", is_flag=True, help="With --fix or --diff: the unsafe fixes too (docs/rules.md says "
              "which fixes are unsafe and why).")
@click.option("--diff", "diff_", is_flag=True,
              help="Show the fixes as a unified diff and write nothing (exit 1 when there is something to fix).")
@click.option("--baseline", "baseline", type=click.Path(dir_okay=False), metavar="FILE",
              help="Findings recorded in FILE are known: only new ones are reported and fail. A missing FILE is "
                   "written with today's findings (matched by code, element and message, not by line).")
@click.option("--update-baseline", is_flag=True, help="With --baseline: write today's findings to FILE again.")
@click.option("--changed-since", "since", metavar="REV",
              help="Check only the models that read a file (include, YAML, mesh) changed since git revision REV.")
@click.option("--list-rules", is_flag=True, help="List every rule code and exit.")
def check_cmd(inputs, inertia, suggest, meshes, srdf, fmt, select, ignore, strict, output, recursive, config_file,
              isolated, jobs, shard_spec, quiet, no_cache, cache_dir, merge_sarif, fix_, unsafe_fixes, diff_,
              baseline, update_baseline, since, list_rules):
    """Lint robot models: tree, inertia, sensors and frames, Gazebo plugins, meshes, physics.

    Each finding has a stable code (X build, T tree, I inertia, S sensors/frames,
    G Gazebo/plugins, M meshes, P physics), a severity, the numbers that matter and the
    xacro file:line it comes from. docs/rules.md explains every rule and its fix.

    \b
    Settings come from the nearest pyproject.toml [tool.myrabot-desc] or myrabot-desc.toml
    (walking up from each file); a finding is silenced in the model with
      <!-- myrabot-desc: ignore[I008] why -->
    on the line before the element (or inside it); see docs/check.md.

    \b
    Examples:
      myrabot-desc check                              # the bundled MYRAbot
      myrabot-desc check robot.urdf.xacro -p my_pkg=../my_pkg
      myrabot-desc check --inertia --suggest robot.urdf
      myrabot-desc check urdf/ --format github        # every top-level model in a folder
      myrabot-desc check -r . --strict                # every model of a repository (CI)
      myrabot-desc check -r . --shard 2/4 --format sarif -o part2.sarif
      myrabot-desc check --merge-sarif part*.sarif -o check.sarif
      myrabot-desc check robot.urdf --select I,P --strict
      myrabot-desc check --inertia panda.urdf --srdf panda.srdf   # self-collision (P005) as the SRDF allows
      myrabot-desc check --fix robot.urdf.xacro        # repair the safe findings in the sources
      myrabot-desc check --diff --unsafe-fixes -r .    # show every fix as a diff, write nothing
      myrabot-desc check -r . --baseline .myrabot-desc-baseline.json   # fail only on new findings
      myrabot-desc check -r . --changed-since origin/main --format junit -o check.xml

    \b
    Exit codes: 0 no errors (no warnings either with --strict), 1 errors found,
    2 a file could not be processed (one line each, the other files are still checked)
    or the command line / configuration is wrong.
    """
    with guarded():
        if list_rules:
            for code, name, sev, summary, _doc in rule_table():
                click.echo(f"{code}  {sev:<7}  {name:<28} {summary}")
            return
        if merge_sarif:
            text = merge_sarif_files(inputs.files)
            if output == "-":
                click.echo(text, nl=False)
            else:
                write_output(output, text)
            return
        if unsafe_fixes and not (fix_ or diff_):
            raise click.UsageError("--unsafe-fixes goes with --fix or --diff")
        if update_baseline and not baseline:
            raise click.UsageError("--update-baseline goes with --baseline FILE")
        try:
            tasks, help_url = plan(inputs, inertia, suggest, meshes, select, ignore, strict, recursive, config_file,
                                   isolated, shard_spec, no_cache or fix_ or diff_, cache_dir, srdf=srdf)
        except UsageProblem as exc:
            raise usage_error(exc) from None
        if since is not None:
            tasks, skipped = changed_since(tasks, since)
            if not quiet and fmt == "text":
                click.echo(f"--changed-since {since}: {len(tasks)} model(s) to check, {skipped} unchanged", err=True)
        if fix_ or diff_:
            sys.exit(_fix(tasks, fmt, output, quiet, help_url, shard_spec, unsafe_fixes, write=not diff_))
        progress = not quiet and sys.stderr.isatty()
        one_shot = options.ONE_SHOT and len(tasks) == 1
        if one_shot:
            # one file in a process that ends with it: the collector would only rescan the model's
            # records (they make no cycles worth finding) and free them one by one at exit (~15 %)
            gc.disable()
        results = run_tasks(tasks, jobs or default_jobs(), _progressbar if progress else None) if tasks else []
        unused_findings(results)
        if baseline:
            _baseline(results, baseline, update_baseline, quiet or fmt != "text")
        code = exit_code(results)
        text = render(fmt, results, __version__, exit_code=code, quiet=quiet, help_url=help_url,
                      shard=shard_spec)
        if output == "-":
            click.echo(text, nl=False)
        else:
            write_output(output, click.unstyle(text))
        for r in results:
            if r.failure and (fmt != "text" or output != "-"):
                click.echo(clean(r.failure), err=True)
        if one_shot:
            gc.freeze()
    sys.exit(code)


def _baseline(results, path, update: bool, quiet: bool) -> None:
    """Record the findings in the baseline ``path`` (missing, or --update-baseline), else drop the
    ones it holds from ``results``."""
    if update or not Path(path).exists():
        n = baselines.record(results, path)
        if not quiet:
            click.echo(f"baseline {path}: {n} finding(s) recorded", err=True)
        for r in results:
            r.diagnostics = []
        return
    n = baselines.apply(results, path)
    if not quiet:
        click.echo(f"baseline {path}: {n} known finding(s) not reported", err=True)


def _fix(tasks, fmt, output, quiet, help_url, shard_spec, unsafe, write: bool) -> int:
    """check --fix / --diff (fix/run.py). --fix writes every changed file as one transaction and
    reports what remains; --diff writes nothing: a unified diff in text format, else the report of the
    models as they are with each fix proposed (JSON "fixes", SARIF "fixes")."""
    run = fix_tasks(tasks, unsafe, write)
    results = run.results
    unused_findings(results)
    count = {}
    for r in results:
        for f in r.fixes or ():
            count[f["status"]] = count.get(f["status"], 0) + 1
    failed = any(r.failure for r in results)
    remaining = sum(len(f.after) for f in run.fixes if f is not None)
    if write:
        write_fixed(run.files)
        code = exit_code(results)
    else:
        code = 2 if failed else (1 if run.files else 0)
    line = summary(count.get("applied", count.get("proposed", 0)), count.get("unsafe", 0),
                   count.get("not-editable", 0), count.get("refused", 0), remaining, write)
    if not write and fmt == "text":
        text = unified_diff(run.files)
    else:
        text = render(fmt, results, __version__, exit_code=code, quiet=quiet, help_url=help_url, shard=shard_spec)
    if output == "-":
        click.echo(text, nl=False)
    else:
        write_output(output, click.unstyle(text))
    if not quiet and fmt == "text":
        click.echo(line, err=True)
    for r in results:
        if r.failure and (fmt != "text" or output != "-" or not write):
            click.echo(clean(r.failure), err=True)
    return code
