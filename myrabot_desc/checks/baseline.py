"""What a finding is, line numbers aside, and ``check --baseline FILE``: adopt the lint in a repository
that has old findings.

A finding's *subject* is its code and the elements its data names (link, joint, plugin...): the same
finding after an edit elsewhere in the file has the same subject even though its line moved. The
baseline records, per model file, each finding's code, subject and message (file:line references
inside the message made line-free), and how many times it occurs. A later run drops the findings the
baseline holds (as many of each as it recorded) and reports, and fails on, the others.

The file is JSON, sorted, with paths relative to the baseline's own folder, so that it can be
committed and reviewed.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

from myrabot_desc.errors import InputError
from myrabot_desc.output import write_output

SCHEMA = "myrabot-desc/baseline/1"
SUBJECT_KEYS = ("link", "links", "joint", "plugin", "param", "sensor", "frame", "attribute", "element", "reference")
_LINE_REF = re.compile(r"(\.(?:xacro|urdf|xml|yaml|yml|gazebo|sdf|launch|dae|stl|obj)):\d+(?::\d+)?")
_LINE_WORD = re.compile(r"\b(line)s? \d+(?:[-–]\d+)?")


def subject(d) -> tuple:
    """What a finding is about (its code and the elements it names): the same finding after a fix
    has the same subject even when its numbers or line change."""
    data = d.data or {}
    return (d.code,) + tuple((k, str(data[k])) for k in SUBJECT_KEYS if k in data)


def line_free(message: str) -> str:
    """A message with its file:line references and 'line N' made line-free."""
    return _LINE_WORD.sub(r"\1 N", _LINE_REF.sub(r"\1", message))


def finding_key(d, with_message: bool = True) -> tuple:
    """The key a finding is matched on: its subject, with its line-free message."""
    s = subject(d)
    return s + (line_free(d.message),) if with_message else s


def _model_name(file: str, base: Path) -> str:
    if not file:
        return "<bundled>"
    p = Path(file).resolve()
    try:
        return Path(os.path.relpath(p, base)).as_posix()
    except ValueError:
        return p.as_posix()


def record(results, path) -> int:
    """Write the findings of ``results`` (checks/report.FileResult) as the baseline ``path``; the count."""
    import json
    base = Path(path).resolve().parent
    counts: dict = {}
    for r in results:
        if r.failure:
            continue
        m = _model_name(r.file, base)
        for d in r.diagnostics:
            k = (m,) + finding_key(d)
            counts[k] = counts.get(k, 0) + 1
    rows = []
    for k in sorted(counts, key=lambda k: json.dumps(k)):
        model, code, *rest = k
        subj, message = rest[:-1], rest[-1]
        rows.append({"model": model, "code": code, "subject": {a: b for a, b in subj}, "message": message,
                     "count": counts[k]})
    text = json.dumps({"schema": SCHEMA, "findings": rows}, indent=1, ensure_ascii=False) + "\n"
    write_output(str(path), text)
    return sum(counts.values())


def load(path) -> dict:
    """(model, code, subject..., message) -> count, from a baseline file (InputError when unreadable)."""
    import json
    p = Path(path)
    try:
        doc = json.loads(p.read_text(encoding="utf-8"))
    except OSError as exc:
        raise InputError(f"{path}: cannot read the baseline ({exc.strerror})") from None
    except (ValueError, UnicodeDecodeError) as exc:
        raise InputError(f"{path}:1: error: not a baseline file (invalid JSON: {exc})") from None
    if not isinstance(doc, dict) or doc.get("schema") != SCHEMA or not isinstance(doc.get("findings"), list):
        raise InputError(f"{path}:1: error: not a baseline file (schema {SCHEMA} expected)")
    out: dict = {}
    for row in doc["findings"]:
        try:
            subj = tuple((str(k), str(v)) for k, v in row["subject"].items())
            k = (str(row["model"]), str(row["code"])) + subj + (str(row["message"]),)
            out[k] = out.get(k, 0) + int(row.get("count", 1))
        except (KeyError, TypeError, ValueError, AttributeError):
            raise InputError(f"{path}:1: error: a baseline entry is malformed: {str(row)[:80]}") from None
    return out


def apply(results, path) -> int:
    """Drop from ``results`` the findings that the baseline ``path`` holds; the number dropped."""
    known = load(path)
    base = Path(path).resolve().parent
    dropped = 0
    for r in results:
        if r.failure:
            continue
        m = _model_name(r.file, base)
        left = dict()
        kept = []
        for d in r.diagnostics:
            k = (m,) + finding_key(d)
            n = left.get(k, known.get(k, 0))
            if n > 0:
                left[k] = n - 1
                dropped += 1
            else:
                left[k] = 0
                kept.append(d)
        r.diagnostics = kept
    return dropped
