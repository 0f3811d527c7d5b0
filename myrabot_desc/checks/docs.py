"""Generate docs/rules.md from the registry: each rule's docstring and the example kept with it.

    python -m myrabot_desc.checks.docs > docs/rules.md

A test keeps docs/rules.md equal to this output; tests/check/test_rule_examples.py runs every example
shown here through `check`.
"""

from __future__ import annotations

import re

from myrabot_desc.checks.external import EXTERNAL_RULES
from myrabot_desc.checks.registry import FAMILIES, load_all
from myrabot_desc.checks.rule import TEMPLATE

def _split(doc: str):
    """(summary, why, fix) from a rule docstring."""
    lines = doc.strip().splitlines()
    summary = lines[0].strip()
    body = " ".join(l.strip() for l in lines[1:]).strip()
    why, fix = body, ""
    m = re.search(r"\bFix:\s*", body)
    if m:
        why, fix = body[:m.start()].strip(), body[m.end():].strip()
        fix = fix[:1].upper() + fix[1:]
    return summary, why, fix


def _example(code: str, ex) -> list[str]:
    """The example's lines: the file (or snippet) as written, the command when it needs options, what check prints."""
    out = ["**Example.**" + (f" `{ex.filename}`" if ex.filename != "robot.urdf" else "")
           + (f" ({ex.note})" if ex.note else ""), "", "```xml", ex.bad.rstrip("\n"), "```", ""]
    if ex.options:
        out += ["```", f"myrabot-desc check {' '.join('--' + o for o in ex.options)} {ex.filename}", "```", ""]
    out += ["```", ex.message if code == "X000" else f"{code} {ex.message}", "```", ""]
    return out


def render() -> str:
    rules = load_all()
    out = ["# check rules", "",
           "Generated from the rule registry (`python -m myrabot_desc.checks.docs > docs/rules.md`).",
           "Every finding has a stable code (a code never changes meaning), a severity, a message with the",
           "numbers that matter and the xacro `file:line` it comes from. Select or ignore codes or prefixes",
           "with `--select I,G001` / `--ignore I008`; `--strict` makes warnings fail.", "",
           "Without `--inertia`, mesh files are not opened (only their existence is checked) and inertias are",
           "compared with primitive geometry only; `--inertia` loads collision meshes (STL, COLLADA and OBJ with",
           "our own readers, which give trimesh's vertices, volume and inertia; other formats through trimesh)",
           "and compares watertight ones too; `--meshes` also opens visual meshes for M002/M004. Severities: **error** (exit 1), **warning**,",
           "**info**. Some rules raise or lower the severity of one finding; their text says when.", ""]
    out += ["Each rule below shows an example that `check` reports (tests run every one of them) and its",
            "fix. An example that is not a whole file is a snippet placed in this minimal robot:", "",
            "```xml", TEMPLATE.replace("{snippet}", "  <!-- the snippet -->").rstrip("\n"), "```", ""]
    out += ["`check --fix` repairs a finding in the file where the value is written (a literal in place; a",
            "property or a parameter's default is a definition every use shares, so editing it is unsafe; a",
            "computed value is not edited: the report gives the value needed and the expression's location).",
            "**Safe** fixes keep the model's meaning or restore one the model states elsewhere; **unsafe** ones",
            "need `--unsafe-fixes`. Each fix is proven first: the fixed sources are rebuilt and rechecked, and",
            "written only when the finding is gone and no new error appears. `--diff` shows the edits.", ""]
    rows = [(c, r.name, r.severity, r.summary) for c, r in rules.items()]
    rows += [(c, r.name, r.severity, r.summary) for c, r in EXTERNAL_RULES.items()]
    order = list(FAMILIES)
    rows.sort(key=lambda r: (order.index(r[0][0]), r[0]))
    out += ["| code | name | severity | what |", "|---|---|---|---|"]
    for c, n, s, summ in rows:
        cell = summ.replace("|", "\\|")
        out.append(f"| [{c}](#{c.lower()}) | {n} | {s} | {cell} |")
    out.append("")
    family = None
    for c, n, s, summ in rows:
        if c[0] != family:
            family = c[0]
            out += [f"## {family}: {FAMILIES[family]}", ""]
        if c in rules:
            _, why, fix = _split(rules[c].doc)
            ex = rules[c].example
        else:
            e = EXTERNAL_RULES[c]
            why, fix, ex = e.why, e.fix, e.example
        out += [f"### {c}", "", f"**{n}** · {s}", "", f"**What it does.** {summ}", "",
                f"**Why is this bad?** {why}", ""]
        out += _example(c, ex)
        out += [f"**Fix.** {fix}".rstrip(), ""] if fix or ex.good is not None else []
        if c in rules:
            out += [_fix_line(rules[c].fix), ""]
        if ex.good is not None:
            out += ["```xml", ex.good.rstrip("\n"), "```", ""]
    out += ["## JSON report schema (`--format json`)", "",
            "`schema` is `myrabot-desc/check-report/1`; fields are only ever added under a new schema number.", "",
            "```json",
            '{"schema": "myrabot-desc/check-report/1",',
            ' "tool": {"name": "myrabot-desc", "version": "0.1.0"},',
            ' "summary": {"files": 1, "failed": 0, "errors": 4, "warnings": 14, "info": 1},',
            ' "files": [{"file": "urdf/robot.xacro", "robot": "mobile_robot", "links": 5, "joints": 4,',
            '            "status": "errors",            // ok | errors | failed',
            '            "failure": null,               // the one-line reason when status is failed',
            '            "counts": {"error": 4, "warning": 14, "info": 1},',
            '            "diagnostics": [{"code": "G001", "severity": "error", "rule": "drive-wheel-separation",',
            '                             "message": "wheelSeparation 0.4 m, but ...", "file": "urdf/robot.gazebo",',
            '                             "line": 4, "data": {"value": 0.4, "urdf": 0.3, "fix": 0.3, ...}}],',
            '            "suggestions": [{"link": "base_link", "inertia": "<inertia ixx=... />"}]}]}',
            "```", "",
            "Paths are relative to the current folder when under it. Diagnostics are sorted by severity, code,",
            "location and message; floats are rounded to 9 significant digits, so the same input gives the same",
            "bytes. `--format github` prints `::error file=F,line=L,title=CODE name::message` workflow commands",
            "(`::notice` for info); `--format sarif` writes SARIF 2.1.0 with one `rules` entry per code above.", ""]
    return "\n".join(out)


def _fix_line(info) -> str:
    """'**--fix:** always, safe. What is edited and why.' (or that there is none)."""
    if info.availability == "never":
        return "**`--fix`:** never (the repair needs a decision only the model's author can make)."
    return f"**`--fix`:** {info.availability}, {info.safety}. {info.how[:1].upper()}{info.how[1:]}"


if __name__ == "__main__":
    import sys

    sys.stdout.write(render())
