"""Render check results: text (terminal), json (stable schema), github annotations, SARIF 2.1.0.

A result is one :class:`FileResult` per input file. Paths are shown relative to the
current folder when they lie under it (stable across machines in CI).
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from pathlib import Path

import click

JSON_SCHEMA = "myrabot-desc/check-report/1"
SARIF_LEVEL = {"error": "error", "warning": "warning", "info": "note"}
GITHUB_LEVEL = {"error": "error", "warning": "warning", "info": "notice"}
STYLE = {"error": dict(fg="red", bold=True), "warning": dict(fg="yellow", bold=True), "info": dict(fg="cyan")}


@dataclass
class FileResult:
    file: str                                   # as given ('' = the bundled model)
    diagnostics: list = field(default_factory=list)
    robot: str | None = None
    links: int = 0
    joints: int = 0
    failure: str | None = None                  # one-line reason when the file could not be processed
    suggestions: list = field(default_factory=list)   # (link, '<inertia .../>')

    def count(self, severity: str) -> int:
        return sum(1 for d in self.diagnostics if d.severity == severity)


def rel(path: str | None) -> str | None:
    if not path:
        return path
    try:
        p = Path(path)
        if p.is_absolute():
            r = os.path.relpath(p, Path.cwd())
            if not r.startswith(".."):
                return r
    except ValueError:
        pass
    return path


def where(d) -> str:
    if d.loc is None:
        return ""
    f = rel(d.loc.file)
    return f"{f}:{d.loc.line}" if d.loc.line else f


def totals(results) -> dict:
    return {"files": len(results), "failed": sum(1 for r in results if r.failure),
            "errors": sum(r.count("error") for r in results),
            "warnings": sum(r.count("warning") for r in results),
            "info": sum(r.count("info") for r in results)}


def _plural(n, word):
    return f"{n} {word}" if n == 1 or word == "info" else f"{n} {word}s"


# ---------------------------------------------------------------- text
def render_text(results, color: bool | None = None) -> str:
    lines: list[str] = []
    many = len(results) > 1
    for r in results:
        name = rel(r.file) or "(bundled MYRAbot)"
        if r.failure:
            lines.append(click.style(r.failure, **STYLE["error"]))
            continue
        if many or r.diagnostics:
            lines.append(click.style(f"{name}", bold=True) + f": robot {r.robot or '?'}, "
                         f"{_plural(r.links, 'link')}, {_plural(r.joints, 'joint')}")
        for sev in ("error", "warning", "info"):
            ds = [d for d in r.diagnostics if d.severity == sev]
            if not ds:
                continue
            lines.append(click.style(f"  {sev}s ({len(ds)})" if sev != "info" else f"  info ({len(ds)})", **STYLE[sev]))
            for d in ds:
                w = where(d)
                lines.append(f"    {w + ': ' if w else ''}" + click.style(d.code, **STYLE[sev]) + f" {d.message}")
        if r.suggestions:
            lines.append(click.style("  suggested inertias (solid body of the collision geometry at the declared "
                                     "mass, in the inertial frame):", bold=True))
            for link, line in r.suggestions:
                lines.append(f"    {link}: {line}")
    t = totals(results)
    summary = (f"{_plural(t['errors'], 'error')}, {_plural(t['warnings'], 'warning')}, {t['info']} info "
               f"in {_plural(t['files'], 'file')}")
    if t["failed"]:
        summary += f" ({t['failed']} could not be processed)"
    style = STYLE["error"] if t["errors"] or t["failed"] else (STYLE["warning"] if t["warnings"] else dict(fg="green"))
    lines.append(click.style(summary, **style))
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------- json
def diag_json(d) -> dict:
    data = {k: v for k, v in d.data.items() if k != "rule"}
    return {"code": d.code, "severity": d.severity, "rule": d.data.get("rule") or _rule_name(d.code),
            "message": d.message, "file": rel(d.loc.file) if d.loc else None,
            "line": d.loc.line if d.loc else None, "data": _plain(data)}


def _plain(x):
    """JSON-safe, deterministic: numpy scalars/arrays to Python, floats rounded to 9 significant digits."""
    import math

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
        doc["files"].append(entry)
    return json.dumps(doc, indent=2, ensure_ascii=False) + "\n"


# ---------------------------------------------------------------- github
def _gh_escape(s: str, prop: bool = False) -> str:
    s = s.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")
    if prop:
        s = s.replace(":", "%3A").replace(",", "%2C")
    return s


def render_github(results) -> str:
    out = []
    for r in results:
        if r.failure:
            out.append(f"::error title=check failed::{_gh_escape(r.failure)}")
            continue
        for d in r.diagnostics:
            props = []
            if d.loc:
                props.append(f"file={_gh_escape(rel(d.loc.file), True)}")
                if d.loc.line:
                    props.append(f"line={d.loc.line}")
            props.append(f"title={_gh_escape(d.code + ' ' + (d.data.get('rule') or _rule_name(d.code)), True)}")
            out.append(f"::{GITHUB_LEVEL[d.severity]} {','.join(props)}::{_gh_escape(d.message)}")
    t = totals(results)
    out.append(f"{t['errors']} errors, {t['warnings']} warnings, {t['info']} info in {t['files']} files")
    return "\n".join(out) + "\n"


# ---------------------------------------------------------------- sarif
def _rule_name(code: str) -> str:
    from myrabot_desc.checks.registry import EXTERNAL, RULES

    if code in RULES:
        return RULES[code].name
    return EXTERNAL.get(code, (code.lower(),))[0]


def rule_table():
    """[(code, name, severity, summary, full doc)] for every known code, sorted."""
    from myrabot_desc.checks.registry import EXTERNAL, load_all

    rows = [(c, r.name, r.severity, r.summary, r.doc) for c, r in load_all().items()]
    rows += [(c, n, s, summ, summ) for c, (n, s, summ) in EXTERNAL.items()]
    return sorted(rows)


def render_sarif(results, version: str) -> str:
    table = rule_table()
    index = {c: i for i, (c, *_rest) in enumerate(table)}
    rules = [{"id": c, "name": n, "shortDescription": {"text": summ},
              "fullDescription": {"text": doc}, "defaultConfiguration": {"level": SARIF_LEVEL[sev]},
              "helpUri": f"https://github.com/myrabot/myrabot-desc/blob/main/docs/rules.md#{c.lower()}"}
             for c, n, sev, summ, doc in table]
    res = []
    for r in results:
        if r.failure:
            res.append({"ruleId": "X000", "level": "error", "message": {"text": r.failure},
                        "locations": [{"physicalLocation": {"artifactLocation": {"uri": rel(r.file) or "."}}}]})
            continue
        for d in r.diagnostics:
            item = {"ruleId": d.code, "level": SARIF_LEVEL[d.severity], "message": {"text": d.message}}
            if d.code in index:
                item["ruleIndex"] = index[d.code]
            if d.loc:
                phys = {"artifactLocation": {"uri": Path(rel(d.loc.file)).as_posix()}}
                if d.loc.line:
                    phys["region"] = {"startLine": d.loc.line}
                item["locations"] = [{"physicalLocation": phys}]
            props = _plain({k: v for k, v in d.data.items() if k != "rule"})
            if props:
                item["properties"] = props
            res.append(item)
    doc = {"$schema": "https://json.schemastore.org/sarif-2.1.0.json", "version": "2.1.0",
           "runs": [{"tool": {"driver": {"name": "myrabot-desc", "version": version,
                                         "informationUri": "https://github.com/myrabot/myrabot-desc",
                                         "rules": rules}},
                     "results": res}]}
    return json.dumps(doc, indent=2, ensure_ascii=False) + "\n"
