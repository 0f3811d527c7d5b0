"""Render check results: text (terminal), json (stable schema), github annotations, SARIF 2.1.0.

A result is one :class:`FileResult` per input file. Paths are shown relative to the
current folder when they lie under it (stable across machines in CI).
"""

from __future__ import annotations

import functools
import math
import os
from pathlib import Path

from myrabot_desc.checks.registry import EXTERNAL, RULES, load_all
from myrabot_desc.diagnostics import Loc
from myrabot_desc.errors import InputError
from myrabot_desc.expand.packages import bundled_path
from myrabot_desc.records import Record
from myrabot_desc.sanitize import clean, json_safe

JSON_SCHEMA = "myrabot-desc/check-report/1"
SARIF_LEVEL = {"error": "error", "warning": "warning", "info": "note"}
GITHUB_LEVEL = {"error": "error", "warning": "warning", "info": "notice"}
STYLE = {"error": dict(fg="red", bold=True), "warning": dict(fg="yellow", bold=True), "info": dict(fg="cyan")}
_FG = {"red": 31, "green": 32, "yellow": 33, "cyan": 36}


def style(text: str, fg: str | None = None, bold: bool = False) -> str:
    """``text`` in ANSI colour and weight, as click.style writes them (the command strips them when
    stdout is not a terminal, click.echo's rule)."""
    return (f"\033[{_FG[fg]}m" if fg else "") + ("\033[1m" if bold else "") + text + "\033[0m"


class FileResult(Record):
    """What check found in one file. Each list not given is a new empty one."""

    __slots__ = ("file", "diagnostics", "robot", "links", "joints", "failure", "suggestions", "strict",
                 "failure_loc", "suppressions_seen", "suppressions_used", "fixes", "suppressed")

    def __init__(self, file: str,                        # as given ('' = the bundled model)
                 diagnostics: list | None = None,
                 robot: str | None = None,
                 links: int = 0,
                 joints: int = 0,
                 failure: str | None = None,             # one-line reason when the file could not be processed
                 suggestions: list | None = None,        # (link, '<inertia .../>')
                 strict: bool = False,                   # warnings fail this file (--strict or its configuration)
                 failure_loc: object = None,             # Loc of the failure (the input when nothing better is known)
                 suppressions_seen: list | None = None,  # (file, line, code) for codes the run checks
                 suppressions_used: list | None = None,  # those that silenced a finding
                 fixes: list | None = None,              # check --fix/--diff: each fix as data (fix/report.change_data)
                 suppressed: list | None = None):        # (finding, (file, line, code)): listed in SARIF only
        self.file = file
        self.diagnostics = [] if diagnostics is None else diagnostics
        self.robot = robot
        self.links = links
        self.joints = joints
        self.failure = failure
        self.suggestions = [] if suggestions is None else suggestions
        self.strict = strict
        self.failure_loc = failure_loc
        self.suppressions_seen = [] if suppressions_seen is None else suppressions_seen
        self.suppressions_used = [] if suppressions_used is None else suppressions_used
        self.fixes = fixes
        self.suppressed = [] if suppressed is None else suppressed

    def count(self, severity: str) -> int:
        return sum(1 for d in self.diagnostics if d.severity == severity)


def rel(path: str | None) -> str | None:
    """``path`` relative to the working folder when it lies below it (a report names a file once
    per finding: a 20,000-link robot's report asked for the same answer 40,000 times)."""
    if not path:
        return path
    return _rel(path, os.getcwd())


@functools.lru_cache(maxsize=4096)
def _rel(path: str, cwd: str) -> str:
    try:
        if os.path.isabs(path):
            r = os.path.relpath(path, cwd)
            if not r.startswith(".."):
                return r
    except ValueError:
        pass
    return path


def where(d) -> str:
    if d.loc is None:
        return ""
    f = clean(rel(d.loc.file))
    return f"{f}:{d.loc.line}" if d.loc.line else f


def totals(results) -> dict:
    return {"files": len(results), "failed": sum(1 for r in results if r.failure),
            "errors": sum(r.count("error") for r in results),
            "warnings": sum(r.count("warning") for r in results),
            "info": sum(r.count("info") for r in results)}


def _plural(n, word):
    return f"{n} {word}" if n == 1 or word == "info" else f"{n} {word}s"


# ---------------------------------------------------------------- text
def render(fmt: str, results, version: str, exit_code: int = 0, quiet: bool = False, help_url: str | None = None,
           shard: str | None = None, color: bool | None = None) -> str:
    if fmt == "json":
        return render_json(results, version)
    if fmt == "github":
        return render_github(results)
    if fmt == "sarif":
        return render_sarif(results, version, exit_code=exit_code, help_url=help_url, shard=shard)
    if fmt == "junit":
        return render_junit(results)
    return render_text(results, color=color, quiet=quiet)


def _unstyled(text: str, fg: str | None = None, bold: bool = False) -> str:
    return text


def render_text(results, color: bool | None = None, quiet: bool = False) -> str:
    """The text report, styled unless ``color`` is False: the plain text is the styled one with the
    styles stripped (no field holds an escape: clean() writes them out), without making them for a
    file that would strip them again (a 20,000-link star's report is 9 MB)."""
    paint = _unstyled if color is False else style
    lines: list[str] = []
    many = len(results) > 1 and not quiet
    for r in results:
        # every field below may quote the model or a file name: clean() makes each one printable line
        name = clean(rel(r.file) or "(bundled MYRAbot)")
        if r.failure:
            lines.append(paint(clean(r.failure), **STYLE["error"]))
            continue
        if many or r.diagnostics:
            lines.append(paint(f"{name}", bold=True) + f": robot {clean(r.robot or '?')}, "
                         f"{_plural(r.links, 'link')}, {_plural(r.joints, 'joint')}")
        for sev in ("error", "warning", "info"):
            ds = [d for d in r.diagnostics if d.severity == sev]
            if not ds:
                continue
            lines.append(paint(f"  {sev}s ({len(ds)})" if sev != "info" else f"  info ({len(ds)})", **STYLE[sev]))
            # where() and the styled code once per file and code: a big robot has 40,000 findings
            # in a few files and codes
            places: dict = {}
            codes: dict = {}
            add = lines.append
            for d in ds:
                loc = d.loc
                if loc is None:
                    w = ""
                else:
                    f = places.get(loc.file)
                    if f is None:
                        f = places[loc.file] = clean(rel(loc.file))
                    w = f"{f}:{loc.line}" if loc.line else f
                c = codes.get(d.code)
                if c is None:
                    c = codes[d.code] = paint(clean(d.code), **STYLE[sev])
                add(f"    {w + ': ' if w else ''}{c} {clean(d.message)}")
        if r.suggestions:
            lines.append(paint("  suggested inertias (solid body of the collision geometry at the declared "
                                     "mass, in the inertial frame):", bold=True))
            for link, line in r.suggestions:
                lines.append(f"    {clean(link)}: {clean(line)}")
    if quiet:
        return "".join(line + "\n" for line in lines)
    t = totals(results)
    summary = (f"{_plural(t['errors'], 'error')}, {_plural(t['warnings'], 'warning')}, {t['info']} info "
               f"in {_plural(t['files'], 'file')}")
    if t["failed"]:
        summary += f" ({t['failed']} could not be processed)"
    summary_style = STYLE["error"] if t["errors"] or t["failed"] else (
        STYLE["warning"] if t["warnings"] else dict(fg="green"))
    lines.append(paint(summary, **summary_style))
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------- json
def diag_json(d) -> dict:
    data = {k: v for k, v in d.data.items() if k != "rule"}
    return {"code": d.code, "severity": d.severity, "rule": d.data.get("rule") or _rule_name(d.code),
            "message": d.message, "file": rel(d.loc.file) if d.loc else None,
            "line": d.loc.line if d.loc else None, "data": _plain(data)}


def _plain(x):
    """JSON-safe, deterministic: numpy scalars/arrays to Python, floats rounded to 9 significant digits."""
    t = x.__class__
    if t is float:                      # the common leaves first (a big report has millions)
        if math.isfinite(x):
            return float(f"{x:.9g}")
    elif t is str or t is int or t is bool or x is None:
        return x
    if isinstance(x, dict):
        return {str(k): _plain(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_plain(v) for v in x]
    if hasattr(x, "tolist"):
        return _plain(x.tolist())
    if isinstance(x, float):
        if not math.isfinite(x):
            return None if math.isnan(x) else ("inf" if x > 0 else "-inf")
        return float(f"{x:.9g}")
    if isinstance(x, (str, int, bool)) or x is None:
        return x
    return str(x)


def render_json(results, version: str) -> str:
    doc = {"schema": JSON_SCHEMA, "tool": {"name": "myrabot-desc", "version": version},
           "summary": totals(results), "files": []}
    for r in results:
        entry = {"file": rel(r.file) or None, "robot": r.robot, "links": r.links, "joints": r.joints,
                 "status": "failed" if r.failure else ("errors" if r.count("error") else "ok"),
                 "failure": r.failure,
                 "counts": {s: r.count(s) for s in ("error", "warning", "info")},
                 "diagnostics": [diag_json(d) for d in r.diagnostics],
                 "suggestions": [{"link": l, "inertia": s} for l, s in r.suggestions]}
        if r.fixes is not None:
            entry["fixes"] = _plain(r.fixes)
        doc["files"].append(entry)
    return _dumps_safe(doc) + "\n"


class _Unusual(Exception):
    """A value _dumps_safe leaves to json.dumps."""


def _dumps_safe(doc) -> str:
    """``json.dumps(_json_safe(doc), indent=2, ensure_ascii=False)``, the same text, in one pass:
    json's indenting encoder is pure Python (only the compact one is C) and took most of a
    40,000-finding report's time. A key that is not a string or that json_safe changes goes to
    json.dumps itself (two keys could become one there)."""
    import json
    from json.encoder import encode_basestring as enc

    out: list[str] = []
    add = out.append
    inf = float("inf")

    def value(x, ind: str, safe: bool) -> None:
        # the order of json's own tests (bool before int: it is one)
        if isinstance(x, str):
            add(enc(json_safe(x) if safe else x))
        elif x is None:
            add("null")
        elif x is True:
            add("true")
        elif x is False:
            add("false")
        elif isinstance(x, int):
            add(int.__repr__(x))
        elif isinstance(x, float):
            add("NaN" if x != x else "Infinity" if x == inf else "-Infinity" if x == -inf else float.__repr__(x))
        elif isinstance(x, (list, tuple)):
            if not x:
                add("[]")
                return
            inner = ind + "  "
            sep = ",\n" + inner
            add("[\n" + inner)
            safe = safe and isinstance(x, list)     # _json_safe does not enter tuples
            first = True
            for v in x:
                if first:
                    first = False
                else:
                    add(sep)
                value(v, inner, safe)
            add("\n" + ind + "]")
        elif isinstance(x, dict):
            if not x:
                add("{}")
                return
            inner = ind + "  "
            sep = ",\n" + inner
            add("{\n" + inner)
            first = True
            for k, v in x.items():
                if not isinstance(k, str) or (safe and json_safe(k) is not k):
                    raise _Unusual
                if first:
                    first = False
                else:
                    add(sep)
                add(enc(k) + ": ")
                value(v, inner, safe)
            add("\n" + ind + "}")
        else:
            raise _Unusual

    try:
        value(doc, "", True)
    except _Unusual:
        return json.dumps(_json_safe(doc), indent=2, ensure_ascii=False)
    return "".join(out)


def _json_safe(x):
    """Every string of a report UTF-8-encodable (a non-UTF-8 file name's bytes escaped)."""
    if isinstance(x, str):
        return json_safe(x)
    if isinstance(x, dict):
        return {_json_safe(k): _json_safe(v) for k, v in x.items()}
    if isinstance(x, list):
        return [_json_safe(v) for v in x]
    return x


# ---------------------------------------------------------------- github
def _gh_escape(s: str, prop: bool = False) -> str:
    s = clean(s)        # no terminal escapes or other control characters in a CI log
    s = s.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")
    if prop:
        s = s.replace(":", "%3A").replace(",", "%2C")
    return s


def render_github(results) -> str:
    out = []
    for r in results:
        if r.failure:
            props = [f"file={_gh_escape(rel(_failure_file(r)), True)}"]
            if r.failure_loc is not None and r.failure_loc.line:
                props.append(f"line={r.failure_loc.line}")
            props.append("title=X000 input-unprocessable")
            out.append(f"::error {','.join(props)}::{_gh_escape(r.failure)}")
            continue
        for d in r.diagnostics:
            props = [f"file={_gh_escape(rel(d.loc.file if d.loc and d.loc.file else _input(r)), True)}"]
            if d.loc and d.loc.line:
                props.append(f"line={d.loc.line}")
            props.append(f"title={_gh_escape(d.code + ' ' + (d.data.get('rule') or _rule_name(d.code)), True)}")
            out.append(f"::{GITHUB_LEVEL.get(d.severity, 'error')} {','.join(props)}::{_gh_escape(d.message)}")
    t = totals(results)
    out.append(f"{t['errors']} errors, {t['warnings']} warnings, {t['info']} info in {t['files']} files")
    return "\n".join(out) + "\n"


# ---------------------------------------------------------------- sarif
def _failure_file(r) -> str:
    loc = r.failure_loc
    return (loc.file if loc is not None and loc.file else r.file) or _bundled_name()


def _input(r) -> str:
    """The checked file (for a finding without a location of its own)."""
    return r.file or _bundled_name()


def _bundled_name() -> str:
    return rel(str(bundled_path()))


def _rule_name(code: str) -> str:
    if code in RULES:
        return RULES[code].name
    return EXTERNAL.get(code, (code.lower(),))[0]


def _cleandoc(doc: str) -> str:
    """A docstring without its source indentation (the first line has none; the rest share it)."""
    import textwrap      # here: only SARIF, JUnit and the rule list show docs

    first, _, rest = (doc or "").expandtabs().partition("\n")
    return (first.strip() + "\n" + textwrap.dedent(rest)).strip()


def rule_table():
    """[(code, name, severity, summary, full doc)] for every known code, sorted."""

    rows = [(c, r.name, r.severity, r.summary, _cleandoc(r.doc)) for c, r in load_all().items()]
    rows += [(c, n, s, summ, summ) for c, (n, s, summ) in EXTERNAL.items()]
    return sorted(rows)


SARIF_SCHEMA = "https://docs.oasis-open.org/sarif/sarif/v2.1.0/errata01/os/schemas/sarif-schema-2.1.0.json"


def _uri(path: str) -> str:
    """A SARIF artifact URI: the relative path, percent-encoded (RFC 3986; a file name's
    undecodable bytes too)."""
    from urllib.parse import quote

    return quote(os.fsencode(Path(rel(path)).as_posix()), safe="/")


def render_sarif(results, version: str, exit_code: int = 0, help_url: str | None = None,
                 shard: str | None = None) -> str:
    """One run: the rules, the results, every file involved as an artifact, and one invocation
    (exit code; each unprocessable file as a tool execution notification)."""
    table = rule_table()
    index = {c: i for i, (c, *_rest) in enumerate(table)}
    rules = []
    for c, n, sev, summ, doc in table:
        rule = {"id": c, "name": n, "shortDescription": {"text": summ},
                "fullDescription": {"text": doc}, "defaultConfiguration": {"level": SARIF_LEVEL[sev]},
                "help": {"text": doc}}
        if help_url:              # docs/rules.md of a published copy: headings "### X000" -> #x000
            rule["helpUri"] = f"{help_url.split('#')[0]}#{c.lower()}"
        rules.append(rule)
    artifacts: dict[str, int] = {}

    def location(file: str, line: int | None) -> dict:
        uri = _uri(file)
        artifacts.setdefault(uri, len(artifacts))
        phys = {"artifactLocation": {"uri": uri, "index": artifacts[uri]}}
        if line:
            phys["region"] = {"startLine": line}
        return {"physicalLocation": phys}

    res, notes = [], []
    for r in results:
        if r.failure:
            loc = location(_failure_file(r), r.failure_loc.line if r.failure_loc is not None else None)
            res.append({"ruleId": "X000", "ruleIndex": index["X000"], "level": "error",
                        "message": {"text": r.failure}, "locations": [loc]})
            notes.append({"level": "error", "message": {"text": r.failure}, "locations": [loc],
                          "descriptor": {"id": "X000", "index": index["X000"]}})
            continue
        # the suppressed findings too, each with the inline comment that silenced it: code
        # scanning shows them as dismissed instead of not knowing about them
        for d, key in [(d, None) for d in r.diagnostics] + list(r.suppressed):
            item = {"ruleId": d.code, "level": SARIF_LEVEL.get(d.severity, "error"), "message": {"text": d.message}}
            if d.code in index:
                item["ruleIndex"] = index[d.code]
            item["locations"] = [location(d.loc.file, d.loc.line) if d.loc and d.loc.file else location(_input(r), None)]
            props = _plain({k: v for k, v in d.data.items() if k != "rule"})
            if props:
                item["properties"] = props
            fixes = [sarif_fix(f, location) for f in (r.fixes or ())
                     if key is None and f.get("edits") and f["status"] in ("proposed", "unsafe")
                     and (f["code"], f["message"]) == (d.code, d.message)]
            if fixes:
                item["fixes"] = fixes
            if key is not None:
                file, line, code = key
                item["suppressions"] = [{"kind": "inSource", "status": "accepted",
                                         "justification": f"myrabot-desc: ignore[{code}] at {_uri(file)}:{line}",
                                         "location": location(file, line)}]
            res.append(item)
    invocation = {"executionSuccessful": exit_code in (0, 1), "exitCode": exit_code,
                  "toolExecutionNotifications": notes}
    if shard:
        invocation["properties"] = {"shard": shard}
    run = {"tool": {"driver": {"name": "myrabot-desc", "version": version, "semanticVersion": version,
                               "rules": rules}},
           "invocations": [invocation],
           "artifacts": [{"location": {"uri": u}} for u in artifacts],
           "columnKind": "unicodeCodePoints",
           "results": res}
    doc = {"$schema": SARIF_SCHEMA, "version": "2.1.0", "runs": [run]}
    return _dumps_safe(doc) + "\n"


def sarif_fix(f: dict, location) -> dict:
    """A proposed fix (fix/report.change_data) as a SARIF fix: one artifactChange per file, each edit a
    replacement of a byte region."""
    changes: dict = {}
    for e in f["edits"]:
        changes.setdefault(e["file"], []).append(
            {"deletedRegion": {"byteOffset": e["start"], "byteLength": e["end"] - e["start"]},
             "insertedContent": {"text": e["new"]}})
    text = f["title"] + (" (unsafe: --unsafe-fixes)" if f["safety"] == "unsafe" else "")
    return {"description": {"text": text},
            "artifactChanges": [{"artifactLocation": location(file, None)["physicalLocation"]["artifactLocation"],
                                 "replacements": reps} for file, reps in changes.items()]}


def merge_sarif(docs: list[dict]) -> dict:
    """Several of our SARIF reports (shards of one run) as one: one run whose results, artifacts
    and invocations are the union, artifact indexes renumbered; rules from the first report."""
    if not docs:
        raise ValueError("no reports to merge")
    runs = [run for d in docs for run in d.get("runs", [])]
    if not runs:
        raise ValueError("the reports hold no runs")
    artifacts: dict[str, int] = {}
    results, invocations = [], []

    def remap(loc_holder):
        for loc in loc_holder.get("locations", []):
            art = loc.get("physicalLocation", {}).get("artifactLocation")
            if art and "uri" in art:
                art["index"] = artifacts.setdefault(art["uri"], len(artifacts))

    for run in runs:
        for a in run.get("artifacts", []):
            uri = a.get("location", {}).get("uri")
            if uri is not None:
                artifacts.setdefault(uri, len(artifacts))
        for item in run.get("results", []):
            remap(item)
            results.append(item)
        for inv in run.get("invocations", []):
            for n in inv.get("toolExecutionNotifications", []):
                remap(n)
            invocations.append(inv)
    first = runs[0]
    merged = {"tool": first["tool"], "invocations": invocations,
              "artifacts": [{"location": {"uri": u}} for u in artifacts],
              "columnKind": first.get("columnKind", "unicodeCodePoints"), "results": results}
    return {"$schema": docs[0].get("$schema", SARIF_SCHEMA), "version": "2.1.0", "runs": [merged]}


def merge_sarif_files(files: list[str]) -> str:
    import json
    if not files:
        raise InputError("--merge-sarif: give the SARIF files to merge")
    docs = []
    for f in files:
        try:
            doc = json.loads(Path(f).read_text(encoding="utf-8"))
        except OSError as exc:
            raise InputError(f"cannot read: {exc.strerror}", Loc(f)) from None
        except (UnicodeDecodeError, json.JSONDecodeError) as exc:
            line = getattr(exc, "lineno", None)
            raise InputError(f"not a JSON file: {exc}", Loc(f, line)) from None
        if not isinstance(doc, dict) or doc.get("version") != "2.1.0" or not isinstance(doc.get("runs"), list):
            raise InputError("not a SARIF 2.1.0 report", Loc(f))
        docs.append(doc)
    try:
        return json.dumps(merge_sarif(docs), indent=2, ensure_ascii=False) + "\n"
    except (ValueError, KeyError, TypeError, AttributeError) as exc:
        raise InputError(f"cannot merge: {exc}", Loc(files[0])) from None


# ---------------------------------------------------------------------------------------- JUnit XML
def _xml_text(s) -> str:
    """Model text inside XML: escaped, and the characters XML 1.0 cannot hold replaced."""
    from xml.sax.saxutils import escape

    s = "".join(ch if ch in "\t\n\r" or (" " <= ch <= "\ud7ff") or ("\ue000" <= ch <= "\ufffd")
                or ch >= "\U00010000" else "?" for ch in str(s))
    return escape(s, {'"': "&quot;"})


def render_junit(results) -> str:
    """JUnit XML for CI systems that show test results: one test case per model, one <failure> per
    error (per warning too for a --strict model), an <error> for a model that could not be processed;
    warnings and info as the test's output."""
    cases, failures, errors = [], 0, 0
    for r in results:
        name = rel(r.file) or _bundled_name()
        body = []
        if r.failure:
            errors += 1
            body.append(f'    <error message="{_xml_text(r.failure)}" type="input"/>')
        else:
            fail = [d for d in r.diagnostics if d.severity == "error" or (r.strict and d.severity == "warning")]
            failures += len(fail)
            for d in fail:
                w = where(d)
                body.append(f'    <failure message="{_xml_text(d.code + " " + d.message)}" type="{_xml_text(d.code)}">'
                            f"{_xml_text((w + ': ' if w else '') + d.code + ' ' + d.message)}</failure>")
            rest = [d for d in r.diagnostics if d not in fail]
            if rest:
                out = "\n".join(f"{where(d) + ': ' if where(d) else ''}{d.severity} {d.code} {d.message}" for d in rest)
                body.append(f"    <system-out>{_xml_text(out)}</system-out>")
        cases.append(f'  <testcase classname="myrabot-desc.check" name="{_xml_text(name)}"'
                     + (">\n" + "\n".join(body) + "\n  </testcase>" if body else "/>"))
    head = (f'<?xml version="1.0" encoding="UTF-8"?>\n<testsuites name="myrabot-desc check" tests="{len(results)}" '
            f'failures="{failures}" errors="{errors}">\n<testsuite name="myrabot-desc check" tests="{len(results)}" '
            f'failures="{failures}" errors="{errors}">')
    return head + "\n" + "\n".join(cases) + "\n</testsuite>\n</testsuites>\n"
