"""check's rules read an ordinary robot without importing numpy.

Importing numpy costs more CPU than all of check's rules on the bundled robot together, so a
rule that needs a few frames, a centre of mass or a support polygon computes them in pure Python
(model/kinematics.rest_poses, model/support) and numpy is left to loaded meshes and large models.
Each case runs `check` in a fresh process with Python's import log and asserts numpy is absent;
the findings themselves are pinned by the rules' own tests.
"""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from helpers import ROOT, corpus_args, corpus_env, corpus_robot

CASES = {
    # the bundled robot: a Create base, a structure of primitives, cameras, an arm
    "bundled": ([], {}),
    # a base whose ground contacts lie on one line: P001 reports it, tips it and adds a caster
    "kobuki_rosbuild": None,
    # optical frames named by REP-103 (S003's naming branch)
    "realsense_d435": None,
}


def imported(args: list[str], env: dict, select: str | None) -> tuple[set, str]:
    """(the top-level modules imported, output) of `check --no-cache [--select SELECT] ARGS` in a fresh
    process, from Python's import log."""
    e = {**os.environ, **env, "PYTHONPATH": str(ROOT)}
    p = subprocess.run([sys.executable, "-X", "importtime", "-m", "myrabot_desc", "check", "--no-cache",
                        *(["--select", select] if select else []), *args],
                       capture_output=True, text=True, env=e, cwd=ROOT, timeout=300)
    assert p.returncode in (0, 1, 2), p.stderr[-2000:]
    return {line.rsplit("|", 1)[1].strip() for line in p.stderr.splitlines() if line.startswith("import time:")}, \
        p.stdout


def imports_numpy(args: list[str], env: dict, select: str) -> tuple[bool, str]:
    mods, out = imported(args, env, select)
    return "numpy" in mods, out


def test_the_whole_check_of_the_bundled_robot_imports_no_numpy_coal_or_pinocchio():
    mods, out = imported([], {}, None)
    assert "warning" in out or "error" in out or "info" in out      # the rules ran and reported
    assert not {"numpy", "coal", "pinocchio", "trimesh", "scipy"} & mods, out


@pytest.mark.parametrize("name", list(CASES))
def test_support_mass_and_frame_rules_import_no_numpy(name):
    args, env = CASES[name] or (corpus_args(corpus_robot(name)), corpus_env(corpus_robot(name)))
    numpy, out = imports_numpy(args, env, "P001,P002,P004,S003")
    assert not numpy, out
    if name == "kobuki_rosbuild":           # the lean path ran the finding's tip and its fix too
        assert "P001" in out and "it tips" in out
