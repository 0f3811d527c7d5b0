"""A physics run's verdict in the form of the other ``sim`` programs (PASS/FAIL lines with numbers, the
verdict, ``--json``, ``--csv``), with each failure's cause in model terms at its file:line, and JUnit
XML for CI (one test case per check; a failure carries the cause)."""

from __future__ import annotations

import json
import math
import re
from dataclasses import dataclass, field

from myrabot_desc.sim.result import Check, _fmt, _plain

_CONTROL = re.compile(r"[\x00-\x08\x0b-\x1f\x7f-\x9f]")


def printable(text: str) -> str:
    """Model text as it may reach a terminal, a CI log or XML: control characters shown as \\xNN."""
    return _CONTROL.sub(lambda m: f"\\x{ord(m.group()):02x}", str(text))


def where(loc) -> str:
    """``file:line`` of a Loc (or ``file``), '' for None."""
    if loc is None:
        return ""
    return f"{loc.file}:{loc.line}" if getattr(loc, "line", None) else str(loc.file)


@dataclass
class Cause:
    """Why a check fails, in model terms, and where in the sources."""

    text: str
    loc: object = None           # diagnostics.Loc
    check: str = ""              # the check it explains

    def line(self) -> str:
        w = where(self.loc)
        return printable(f"{w}: {self.text}" if w else self.text)

    def as_dict(self) -> dict:
        return {"check": self.check, "cause": self.text, "file": self.loc.file if self.loc else None,
                "line": getattr(self.loc, "line", None) if self.loc else None}


@dataclass
class PhysicsResult:
    program: str                 # settle | sweep | drive
    robot: str
    engine: str                  # "MuJoCo 4.0.0"
    duration: float              # simulated seconds (sweep: 0)
    timestep: float
    steps: int = 0
    checks: list = field(default_factory=list)
    causes: list = field(default_factory=list)
    info: dict = field(default_factory=dict)
    notes: list = field(default_factory=list)
    t: object = None             # time samples of ``series`` (or sweep's pose index)
    series: dict = field(default_factory=dict)   # column name (with unit) -> values
    joints: list = field(default_factory=list)   # the series that are joint values (drawn in one lane)
    table: list = field(default_factory=list)    # sweep's rows (dicts) for the CSV
    wall: float = 0.0

    @property
    def passed(self) -> bool:
        return bool(all(c.passed for c in self.checks))

    def add(self, check: Check, causes=()) -> None:
        self.checks.append(check)
        for c in causes:
            c.check = check.name
            self.causes.append(c)

    # ------------------------------------------------------------ text
    def summary(self) -> str:
        if self.program == "sweep":
            head = f"sim sweep · {self.robot} · {self.engine} · {self.steps} poses ({self.wall:.2f} s wall)"
        else:
            rate = 1.0 / self.timestep if self.timestep else 0.0
            head = (f"sim {self.program} · {self.robot} · {self.duration:g} s in {self.engine} at {rate:g} Hz "
                    f"({self.steps} steps, {self.wall:.2f} s wall)")
        lines = [printable(head)]
        w = max((len(c.name) for c in self.checks), default=10)
        for c in self.checks:
            val = _fmt(c.value)
            unit = f" {c.unit}" if c.unit and val not in ("none", "-") else ""
            exp = f"   ({c.expected})" if c.expected else ""
            lines.append(printable(f"  {'PASS' if c.passed else 'FAIL'}  {c.name:<{w}}  {val}{unit}{exp}"))
            if c.detail:
                lines.append(printable(f"        {'':<{w}}  {c.detail}"))
            for cause in self.causes:
                if cause.check == c.name:
                    lines.append(f"        {'':<{w}}  cause: {cause.line()}")
        for k, v in self.info.items():
            lines.append(printable(f"  info  {k}: {_fmt(v)}"))
        for note in self.notes:
            lines.append(printable(f"  note  {note}"))
        lines.append(f"verdict: {'PASS' if self.passed else 'FAIL'}")
        return "\n".join(lines) + "\n"

    def as_json(self) -> str:
        d = {"program": self.program, "robot": self.robot, "engine": self.engine, "duration": self.duration,
             "timestep": self.timestep, "steps": self.steps, "passed": self.passed,
             "verdict": "pass" if self.passed else "fail", "checks": [c.as_dict() for c in self.checks],
             "causes": [c.as_dict() for c in self.causes], "info": {k: _plain(v) for k, v in self.info.items()},
             "notes": list(self.notes)}
        return json.dumps(d, indent=2, ensure_ascii=False) + "\n"

    # ------------------------------------------------------------ csv
    def csv_bytes(self) -> bytes:
        """The time series (settle, drive: ``time_s`` then each column with its unit) or the sweep's
        table (one row per pose)."""
        import csv
        import io

        buf = io.StringIO()
        if self.table:
            cols = list(self.table[0])
            w = csv.writer(buf, lineterminator="\n")
            w.writerow(cols)
            for row in self.table:
                w.writerow([_cell(row.get(c)) for c in cols])
            return buf.getvalue().encode()
        import numpy as np

        names = list(self.series)
        data = np.column_stack([np.asarray(self.t, dtype=float)] + [np.asarray(self.series[n], dtype=float)
                                                                     for n in names])
        buf.write(",".join(["time_s"] + [printable(n).replace(",", ";") for n in names]) + "\n")
        np.savetxt(buf, data, delimiter=",", fmt="%.6f")
        return buf.getvalue().replace("-0.000000", "0.000000").encode()

    # ------------------------------------------------------------ junit
    def junit_bytes(self) -> bytes:
        return junit_bytes(self.program, self.robot, self.checks, self.causes, self.info, self.wall)


def junit_bytes(program: str, robot: str, checks, causes=(), info=None, wall: float = 0.0) -> bytes:
    """JUnit XML of a sim run (any program): a test suite per run, a test case per check; a failing one
    carries its numbers and causes, which CI systems show next to the job."""
    from xml.etree import ElementTree as ET

    suite = ET.Element("testsuite", name=_xml(f"myrabot-desc sim {program} {robot}"), tests=str(len(checks)),
                       failures=str(sum(not c.passed for c in checks)), errors="0", skipped="0", time=f"{wall:.3f}")
    if info:
        props = ET.SubElement(suite, "properties")
        for k, v in info.items():
            ET.SubElement(props, "property", name=_xml(k), value=_xml(_fmt(v)))
    for c in checks:
        case = ET.SubElement(suite, "testcase", classname=_xml(f"sim.{program}.{robot}"), name=_xml(c.name), time="0")
        text = f"{_fmt(c.value)}{(' ' + c.unit) if c.unit else ''}" + (f" ({c.expected})" if c.expected else "")
        if not c.passed:
            body = [text] + ([c.detail] if c.detail else []) + \
                [f"cause: {cause.line()}" for cause in causes if cause.check == c.name]
            fail = ET.SubElement(case, "failure", message=_xml(body[-1] if len(body) > 1 else text), type="FAIL")
            fail.text = _xml("\n".join(body))
        else:
            out = ET.SubElement(case, "system-out")
            out.text = _xml(text)
    root = ET.Element("testsuites", name="myrabot-desc sim", tests=suite.get("tests"), failures=suite.get("failures"))
    root.append(suite)
    ET.indent(root, space="  ")
    return b'<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="utf-8") + b"\n"


def _xml(text) -> str:
    """Text XML 1.0 can carry (control characters shown as \\xNN)."""
    return printable(text)


def _cell(v):
    if isinstance(v, float):
        return "" if math.isnan(v) else f"{v:.6f}"
    return "" if v is None else printable(v)
