"""check's rules read an ordinary robot without importing numpy.

Importing numpy costs more CPU than all of check's rules on the bundled robot together, so a
rule that needs a few frames, a centre of mass or a support polygon computes them in pure Python
(model/kinematics.rest_poses, model/support) and numpy is left to loaded meshes and large models.
Each case runs `check` in a fresh process with Python's import log and asserts numpy (and what
else the case names) is absent; the findings themselves are pinned by the rules' own tests, and
the pure forms' equality with numpy's by tests/check/test_inertia_screens.py,
tests/model/test_lean_collisions.py and tests/model/test_statics_pure.py.
"""

from __future__ import annotations

import json
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


def imported(args: list[str], env: dict, select: str | None) -> tuple[set, str, int]:
    """(the top-level modules imported, output, exit code) of `check --no-cache [--select SELECT]
    ARGS` in a fresh process, from Python's import log."""
    e = {**os.environ, **env, "PYTHONPATH": str(ROOT)}
    p = subprocess.run([sys.executable, "-X", "importtime", "-m", "myrabot_desc", "check", "--no-cache",
                        *(["--select", select] if select else []), *args],
                       capture_output=True, text=True, env=e, cwd=ROOT, timeout=300)
    assert p.returncode in (0, 1, 2), p.stderr[-2000:]
    mods = {line.rsplit("|", 1)[1].strip() for line in p.stderr.splitlines() if line.startswith("import time:")}
    return mods, p.stdout, p.returncode


def test_the_whole_check_of_the_bundled_robot_imports_no_numpy_coal_or_pinocchio():
    mods, out, _ = imported([], {}, None)
    assert "warning" in out or "error" in out or "info" in out      # the rules ran and reported
    assert not {"numpy", "coal", "pinocchio", "trimesh", "scipy"} & mods, out
    # nor what a lint run on every commit need not start with: dataclasses (~10 ms with what it
    # imports; the records are plain classes and NamedTuples), the fixer (--fix and --diff only) and
    # difflib (a near miss only)
    assert not {"dataclasses", "difflib"} & mods, sorted(mods)
    assert not [m for m in mods if m.startswith("myrabot_desc.fix")], sorted(mods)
    # nor the baseline, .gitignore, git, SRDF and source-span readers (asked for by options or a fix)
    assert not {"myrabot_desc.checks.baseline", "myrabot_desc.checks.gitignore", "myrabot_desc.vcs",
                "myrabot_desc.model.srdf", "myrabot_desc.model.sources"} & mods, sorted(mods)


@pytest.mark.parametrize("name", list(CASES))
def test_the_whole_check_imports_no_lxml(name):
    # the build's output (and a small URDF file, and the suppression comments) are read by expat into
    # xmltree's elements: lxml's import, with the inspect and the rest it brings, is ~15 ms of a check
    args, env = CASES[name] or (corpus_args(corpus_robot(name)), corpus_env(corpus_robot(name)))
    mods, out, _ = imported(args, env, None)
    assert "warning" in out or "error" in out or "info" in out, out     # the rules ran and reported
    assert not {m for m in mods if m.split(".")[0] == "lxml"}, sorted(mods)


def test_collada_collision_meshes_need_no_lxml():
    # M005 looks for a COLLADA file's triangles with expat (xmltree.any_element), not lxml's tree
    entry = corpus_robot("robotiq_2f_85")
    mods, out, _ = imported(corpus_args(entry), corpus_env(entry), None)
    assert ".dae" in (ROOT / "tests" / "corpus" / entry["top"]).parent.joinpath(
        "robotiq_arg2f_85_model_macro.xacro").read_text()
    assert "lxml" not in mods and "P004" in out, sorted(mods)


def test_a_check_without_configuration_imports_no_typing():
    # typing (~3 ms) came with lxml and tomllib; the package itself uses records.Struct and collections.abc
    mods, out, _ = imported(["--isolated"], {}, None)
    assert "links" in out and "typing" not in mods and not {"tomllib", "tomli"} & mods, sorted(mods)


def test_stock_material_names_need_no_script_reader():
    # pioneer3dx names only Gazebo's stock materials: G009 answers from the stock table, without the
    # OGRE script reader (materials.resolve, materials.ogre); the bundled robot names its own scripts'
    entry = corpus_robot("pioneer3dx")
    mods, out, _ = imported(corpus_args(entry), corpus_env(entry), None)
    assert "myrabot_desc.materials.stock" in mods and "G007" in out, sorted(mods)
    assert not {"myrabot_desc.materials.resolve", "myrabot_desc.materials.ogre"} & mods, sorted(mods)
    mods, out, _ = imported(["--select", "G009"], {}, None)
    assert "myrabot_desc.materials.ogre" in mods and "G009" not in out, out


def test_a_configured_check_reads_its_table_without_typing():
    # this repository's pyproject.toml holds [tool.myrabot-desc]: tomli's compiled parser reads it, where
    # the standard library's tomllib imports typing (~4 ms of every run in a configured project)
    mods, out, _ = imported([], {}, None)
    assert "tomli" in mods and not {"typing", "tomllib"} & mods and "links" in out, sorted(mods)


# each family alone on the bundled robot (none has a finding there): what it may not import
FAMILIES = {
    "I001,I002,I003,I004,I005,I009": {"numpy"},          # mass and tensor: principal moments by eigh3
    "I004,I005,I006,I007,I008,I010": {"numpy"},          # the solid-body rules' screens
    "P001,P002,P004,S003": {"numpy"},                    # support polygon, centre of mass, optical frames
    "P005": {"numpy", "coal"},                           # the shapes' pure screen: no pair comes near
    "P006": {"numpy"},                                   # the pure gravity sweep
}


@pytest.mark.parametrize("select", list(FAMILIES))
def test_each_family_alone_imports_nothing_heavy(select):
    mods, out, rc = imported(["--format", "json"], {}, select)
    (report,) = json.loads(out)["files"]
    assert rc == 0 and report["links"] == 76 and report["status"] == "ok", out
    assert not FAMILIES[select] & mods, out


@pytest.mark.parametrize("name", list(CASES))
def test_support_mass_and_frame_rules_import_no_numpy(name):
    args, env = CASES[name] or (corpus_args(corpus_robot(name)), corpus_env(corpus_robot(name)))
    mods, out, _ = imported(args, env, "P001,P002,P004,S003")
    assert "numpy" not in mods, out
    if name == "kobuki_rosbuild":           # the lean path ran the finding's tip and its fix too
        assert "P001" in out and "it tips" in out


@pytest.mark.parametrize("name", ["kobuki_rosbuild", "turtlebot3_burger"])
def test_a_finding_on_a_rotated_part_needs_no_numpy(name):
    """I006 frames the solid body of a part whose collision shape is rotated (TurtleBot3's caster
    box, rpy -1.57 0 0) in pure Python, as its screen does."""
    entry = corpus_robot(name)
    mods, out, _ = imported(corpus_args(entry), corpus_env(entry), None)
    assert "numpy" not in mods, out
    assert "I006" in out


def test_rotors_that_come_near_but_do_not_touch_need_neither_numpy_nor_coal():
    """The firefly hexacopter's rotor discs (r 0.1 m) sit 0.215 m apart: their bounding boxes meet,
    the capsules that hold them do not (model/collisions._capsules_clear); P005 decides alone."""
    entry = corpus_robot("firefly")
    mods, out, _ = imported(corpus_args(entry), corpus_env(entry), None)
    assert not {"numpy", "coal"} & mods, out
    assert "I005" in out and "P005" not in out


def test_an_indefinite_inertia_fixed_under_a_heavy_body_needs_no_pinocchio():
    """PMB2's antennas have an indefinite inertia on a fixed joint: P003 proves the base's body
    definite (checks/physics._bodies_definite) instead of running Pinocchio."""
    entry = corpus_robot("pmb2")
    mods, out, _ = imported(corpus_args(entry), corpus_env(entry), "P003")
    assert "pinocchio" not in mods and "P003" not in out, out


def test_a_collision_model_of_spheres_needs_neither_numpy_nor_coal():
    """FR3's *_sc links are spheres and cylinders; the pairs that come near are spheres, and their
    overlaps (34.0 and 3.1 mm) are coal's closed form, computed without it."""
    entry = corpus_robot("fr3")
    mods, out, _ = imported(corpus_args(entry), corpus_env(entry), "P005")
    assert not {"numpy", "coal"} & mods, out
    assert "overlaps fr3_link1_sc by 34.0 mm" in out and "overlaps fr3_link3_sc by 3.1 mm" in out


@pytest.mark.parametrize("name, overlap", [
    # a sphere into a cylinder, and two parallel cylinders, of Franka's *_sc links
    ("panda", "panda_link7_sc overlaps panda_link5_sc by 6.1 mm"),
    # the caster wheel (rpy 1.5707: within SNAP of parallel) into the base box
    ("pioneer3dx", "center_wheel overlaps base_link by 13.5 mm"),
    # finger boxes inside the hand's safety box
    ("tiago", "hand_safety_box overlaps hand_thumb_virtual_1_link by 58.9 mm"),
])
def test_primitives_that_overlap_need_neither_numpy_nor_coal(name, overlap):
    """Real overlaps of boxes, spheres and cylinders are measured in closed form (model/penetration.py)."""
    entry = corpus_robot(name)
    mods, out, _ = imported(corpus_args(entry), corpus_env(entry), None)
    assert not {"numpy", "coal"} & mods, out
    assert overlap in out, out


def test_the_whole_check_of_create_2_imports_no_numpy():
    """I007 measures every link of primitives in pure Python, rotated shapes too (Create 2's wheels:
    cylinders and a sphere turned by rpy 0 π/2 π/2)."""
    entry = corpus_robot("create_2")
    mods, out, _ = imported(corpus_args(entry), corpus_env(entry), None)
    assert "I007" in out and "numpy" not in mods, out


@pytest.mark.parametrize("name", ["pioneer3at", "pr2", "pmb2"])
def test_radius_of_gyration_of_rotated_primitives_needs_no_numpy(name):
    # non-diagonal tensors (PR2's caster wheels, PMB2's antennas), rotated shapes (Pioneer's wheels)
    entry = corpus_robot(name)
    mods, out, _ = imported(corpus_args(entry), corpus_env(entry), "I007")
    assert "I007" in out and "numpy" not in mods, out


def test_a_centre_of_mass_among_rotated_wheels_needs_no_numpy():
    """I010 measures every link of primitives in pure Python, rotated ones too (Pioneer 3-AT's wheels:
    cylinders turned by rpy π/2 0 0): the whole check imports no numpy."""
    entry = corpus_robot("pioneer3at")
    mods, out, _ = imported(corpus_args(entry), corpus_env(entry), None)
    assert "numpy" not in mods, out
