"""``diff`` on 18 real commits of 8 description packages (tests/fixtures/model_history): each case's
two revisions are committed into a git repository built here, ``diff FILE --rev HEAD~1..HEAD`` reads
them through git, and its changes must be the independent oracle's (case.yaml ``expected:``, from
expected.py: the real xacro CLI, lxml and numpy), number for number, and nothing else; each change's
file:line must be the one the case says wrote it; the findings of check that change are listed here."""

from __future__ import annotations

import json
import re

import pytest

from helpers import invoke
from history import CASES, case, close, comparable, drive_changes, history_repo

# The findings of `check` that change with each commit (the oracle does not lint): code -> how.
FINDINGS = {
    "husky_track_narrowed": {"changed": ["G014"]},
    "panda_sc_capsule_moved": {"changed": ["I001"]},
    "pmb2_laser_yaw": {"changed": ["P004"]},
    "tb3_burger_wheel_inertia": {"removed": ["I006", "I006", "I007", "I007", "I009"]},
    "tb3_waffle_lidar_moved": {"changed": ["P004"]},
    "ur10e_dynamics_update": {"changed": ["P004"]},
    "ur5e_link_masses": {"changed": ["P004"]},
}
# The drive's effect for the same command, where the wheels changed.
EFFECT = {
    "husky_track_narrowed": {"turn_factor": 570.8 / 550.0},
}
# Where diff names another place than the case, and why that place is right too.
ALSO = {
    # the type is the literal `continuous` of the xacro:unless branch that the YAML flag
    # (joint_limits.yaml:75, has_position_limits: false) selects: the literal is where it is written
    ("ur3_infinite_wrist", "ur_description/config/ur3/joint_limits.yaml"): ("ur_description/urdf/inc/ur_common.xacro", [87]),
}
_WHERE = re.compile(r"^(\S+?):(\d+(?:-\d+)?(?:, \d+(?:-\d+)?)*)")


def run_diff(case_id, tmp_path, monkeypatch, fmt="json"):
    c = case(case_id)
    repo = history_repo(case_id, tmp_path / case_id)
    monkeypatch.chdir(repo)
    for k, v in (c.get("env") or {}).items():
        monkeypatch.setenv(k, str(v))
    return invoke("diff", c["top"], *str(c.get("args") or "").split(), "--rev", "HEAD~1..HEAD",
                  "--package-path", ".", "--format", fmt)


def where_lines(c) -> list[tuple[str, list[int]]]:
    """(file, lines) of each change the case says where it is written (one of the lines, for a range)."""
    out = []
    for w in c.get("where") or []:
        if w["change"].startswith("(no built change)"):
            continue
        m = _WHERE.match(w["source"])
        if not m:
            continue
        for part in m.group(2).split(", "):
            a, _, b = part.partition("-")
            out.append((m.group(1), list(range(int(a), int(b or a) + 1))))
    return out


@pytest.mark.parametrize("case_id", CASES)
def test_diff_reports_exactly_the_commit(case_id, tmp_path, monkeypatch):
    c = case(case_id)
    expected = c["expected"] or {}
    res = run_diff(case_id, tmp_path, monkeypatch)
    assert res.exit_code == (1 if expected else 0), res.output
    doc = json.loads(res.output)
    changes = doc["changes"]
    # every number of the oracle, and nothing else
    assert close(comparable(changes), {k: v for k, v in expected.items() if k != "drive"}), \
        json.dumps(comparable(changes), indent=1)[:3000]
    assert drive_changes(changes.get("drive")) == drive_changes(expected.get("drive"))
    assert "frames_moved_rest_pose" not in changes          # these commits move no frame differently at rest
    assert not any(k.startswith("sensors_") for k in changes)
    # the findings that change
    want = FINDINGS.get(case_id, {})
    for how in ("added", "removed", "changed"):
        assert sorted(f["code"] for f in changes.get(f"findings_{how}", [])) == sorted(want.get(how, [])), how
    # the drive's effect
    eff = (changes.get("drive") or {}).get("effect", {})
    assert close(eff, EFFECT.get(case_id, {}), 1e-3)
    # where each change is written: the file:line the case names, among the changes' places
    places = {}
    for it in doc["items"]:
        if it["where"]:
            f, line = re.match(r"(.*?):(\d+)", it["where"]).groups()
            places.setdefault(f, set()).add(int(line))
    for f, lines in where_lines(c):
        f, lines = ALSO.get((case_id, f), (f, lines))
        assert places.get(f, set()) & set(lines), (f, lines, places)
    if not expected:
        assert doc["items"] == []


@pytest.mark.parametrize("case_id", [c for c in CASES if not case(c)["expected"]])
def test_no_change_prints_nothing(case_id, tmp_path, monkeypatch):
    res = run_diff(case_id, tmp_path, monkeypatch, fmt="text")
    assert res.exit_code == 0 and res.output == ""
