"""What ``myrabot-desc check`` does, without click (commands/check.py is its click command).

The console entry (commands/entry.py) runs a plain ``check ...`` command line straight from here,
parsed with parse_plain from the same option tables (options.INPUT_OPTS, options.CHECK_OPTS): a
pre-commit check of one file then does not pay for importing click, as a plain ``build`` does not.
A command line the plain parser does not take, or a usage problem found here, goes to the click
command, which gives click's messages and exit codes. click is imported here only to draw the
progress bar on a terminal.
"""

from __future__ import annotations

import gc
import sys
from pathlib import Path

from myrabot_desc import __version__
from myrabot_desc.checks.report import merge_sarif_files, render, rule_table
from myrabot_desc.checks.run import changed_since, default_jobs, exit_code, plan, run_tasks
from myrabot_desc.checks.suppress import unused_findings
from myrabot_desc.commands import options
from myrabot_desc.commands.console import echo, guarded, is_terminal, out, unstyle
from myrabot_desc.commands.options import CHECK_OPTS, INPUT_OPTS, UsageProblem, make_inputs, parse_plain
from myrabot_desc.output import write_output
from myrabot_desc.sanitize import clean


def fast_check(argv) -> int | None:
    """Run ``check`` for a plain command line; None when it needs click (help, errors, unusual
    forms, a usage problem): the caller hands it to click."""
    values = parse_plain(argv, INPUT_OPTS + CHECK_OPTS)
    if values is None:
        return None
    try:
        inputs = make_inputs(values, multiple=True)
        return run_check(inputs, **{o.dest: values[o.dest] for o in CHECK_OPTS})
    except UsageProblem:
        return None
    except KeyboardInterrupt:     # as click's standalone mode says it
        echo("")
        echo("Aborted!")
        return 1


def _progressbar(results, length):
    """click's progress bar on stderr (it shows only when stderr is a terminal)."""
    import click      # a terminal's progress bar only: the plain path imports no click otherwise

    return click.progressbar(results, length=length, label="checking", file=sys.stderr,
                             item_show_func=lambda r: (Path(r.file).name if r and r.file else ""))


def _color(output: str) -> bool | None:
    """render's ``color``: styled for a terminal only; a file or a pipe gets the plain text _write would
    strip the styles to (render makes none: a 20,000-link star's report is 9 MB to strip)."""
    return None if output == "-" and is_terminal(sys.stdout) else False


def _write(text: str, output: str) -> None:
    """The report on stdout (styles stripped unless it is a terminal, as click.echo) or in a file."""
    if output == "-":
        out(text)
    else:
        write_output(output, unstyle(text))


def run_check(inputs, inertia=False, suggest=False, meshes=False, srdf=None, fmt="text", select=(), ignore=(),
              strict=False, output="-", recursive=False, config_file=None, isolated=False, jobs=None,
              shard_spec=None, quiet=False, no_cache=False, cache_dir=None, merge_sarif=False, fix_=False,
              unsafe_fixes=False, diff_=False, baseline=None, update_baseline=False, since=None,
              list_rules=False) -> int:
    """The check command itself (click's and the plain path's): the exit code; UsageProblem for a
    command line that does not fit, raised before anything is checked or written."""
    with guarded():
        if list_rules:
            out("".join(f"{code}  {sev:<7}  {name:<28} {summary}\n" for code, name, sev, summary, _doc in rule_table()))
            return 0
        if merge_sarif:
            _write(merge_sarif_files(inputs.files), output)
            return 0
        if unsafe_fixes and not (fix_ or diff_):
            raise UsageProblem("--unsafe-fixes goes with --fix or --diff")
        if update_baseline and not baseline:
            raise UsageProblem("--update-baseline goes with --baseline FILE")
        tasks, help_url = plan(inputs, inertia, suggest, meshes, select, ignore, strict, recursive, config_file,
                               isolated, shard_spec, no_cache or fix_ or diff_, cache_dir, srdf=srdf)
        if since is not None:
            tasks, skipped = changed_since(tasks, since)
            if not quiet and fmt == "text":
                echo(f"--changed-since {since}: {len(tasks)} model(s) to check, {skipped} unchanged")
        if fix_ or diff_:
            return _fix(tasks, fmt, output, quiet, help_url, shard_spec, unsafe_fixes, write=not diff_)
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
        _write(render(fmt, results, __version__, exit_code=code, quiet=quiet, help_url=help_url, shard=shard_spec,
                      color=_color(output)), output)
        for r in results:
            if r.failure and (fmt != "text" or output != "-"):
                echo(clean(r.failure))
        if one_shot:
            gc.freeze()
    return code


def _baseline(results, path, update: bool, quiet: bool) -> None:
    """Record the findings in the baseline ``path`` (missing, or --update-baseline), else drop the
    ones it holds from ``results``."""
    import myrabot_desc.checks.baseline as baselines     # --baseline only

    if update or not Path(path).exists():
        n = baselines.record(results, path)
        if not quiet:
            echo(f"baseline {path}: {n} finding(s) recorded")
        for r in results:
            r.diagnostics = []
        return
    n = baselines.apply(results, path)
    if not quiet:
        echo(f"baseline {path}: {n} known finding(s) not reported")


def _fix(tasks, fmt, output, quiet, help_url, shard_spec, unsafe, write: bool) -> int:
    """check --fix / --diff (fix/run.py). --fix writes every changed file as one transaction and
    reports what remains; --diff writes nothing: a unified diff in text format, else the report of the
    models as they are with each fix proposed (JSON "fixes", SARIF "fixes")."""
    # the fixer only for --fix and --diff: a lint run on every commit does not load it
    from myrabot_desc.fix.report import summary, unified_diff
    from myrabot_desc.fix.run import fix_tasks
    from myrabot_desc.fix.write import write_fixed

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
        text = render(fmt, results, __version__, exit_code=code, quiet=quiet, help_url=help_url, shard=shard_spec,
                      color=_color(output))
    _write(text, output)
    if not quiet and fmt == "text":
        echo(line)
    for r in results:
        if r.failure and (fmt != "text" or output != "-" or not write):
            echo(clean(r.failure))
    return code
