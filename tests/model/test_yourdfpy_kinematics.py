"""``Robot.to_yourdfpy()``: the robot as a yourdfpy.URDF, and yourdfpy as an independent check of our
forward kinematics (model/kinematics.py): every link's world pose agrees to 1e-9 at the zero pose
and at a random pose within the limits, on the bundled robot and every corpus robot."""

from __future__ import annotations

import math

import numpy as np
import pytest

from helpers import corpus_env, corpus_model, corpus_robots
from myrabot_desc.model.kinematics import world_transforms
from myrabot_desc.model.loader import load_robot

MOVING = ("revolute", "continuous", "prismatic")
ROBOTS = corpus_robots()


def _load_corpus(robot, monkeypatch):
    for k, v in corpus_env(robot).items():
        monkeypatch.setenv(k, v)
    return corpus_model(robot)


def _poses(robot, seed: int):
    """The zero pose and a random pose within the limits, over the joints that move on their own."""
    rng = np.random.default_rng(seed)
    free = [j for j in robot.joints.values() if j.type in MOVING and j.mimic is None]
    rand = {}
    for j in free:
        lo, hi = (j.limit.lower, j.limit.upper) if j.limit is not None and j.type != "continuous" else (None, None)
        if lo is None or hi is None or not (math.isfinite(lo) and math.isfinite(hi)) or lo > hi:
            lo, hi = -math.pi, math.pi
        rand[j.name] = float(rng.uniform(lo, hi))
    return {j.name: 0.0 for j in free}, rand


def _agree(robot, seed: int = 0):
    ours_by_pose, theirs = [], robot.to_yourdfpy()
    base = theirs.base_link
    for q in _poses(robot, seed):
        ours = world_transforms(robot, q)
        theirs.update_cfg({name: q[name] for name in theirs.actuated_joint_names})
        worst = 0.0
        for link, T in ours.items():
            if link not in theirs.link_map:
                continue
            other = theirs.get_transform(frame_to=link, frame_from=base)
            worst = max(worst, float(np.abs(np.asarray(T) - other).max()))
        ours_by_pose.append((len(ours), worst))
    return ours_by_pose


def test_to_yourdfpy_reads_the_bundled_robot():
    robot = load_robot()
    urdf = robot.to_yourdfpy()
    assert urdf.robot.name == robot.name
    assert set(urdf.link_map) == set(robot.links) and set(urdf.joint_map) == set(robot.joints)


STL = (b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\n"
       b"endfacet\nendsolid t\n")


def test_to_yourdfpy_meshes_come_through_the_robot_resolver(tmp_path):
    """A mesh the robot resolves (its folder, the one above, its packages) loads; one outside those
    is never opened."""
    bundled = load_robot().to_yourdfpy(load_meshes=True)
    assert bundled.scene.geometry                     # package://myrabot_description/... resolved
    folder = tmp_path / "a" / "robot"
    folder.mkdir(parents=True)
    (folder / "inside.stl").write_bytes(STL)
    (tmp_path / "outside.stl").write_bytes(STL)       # two folders up: outside the robot's roots
    for name, uri, loaded in (("inside", "inside.stl", 1), ("outside", f"file://{tmp_path / 'outside.stl'}", 0)):
        (folder / f"{name}.urdf").write_text(f'<robot name="r"><link name="a"><visual><geometry><mesh filename="{uri}"/>'
                                             '</geometry></visual></link></robot>')
        robot = load_robot(str(folder / f"{name}.urdf"))
        assert (robot.resolve_uri(uri) is not None) == bool(loaded)
        assert len(robot.to_yourdfpy(load_meshes=True).scene.geometry) == loaded, name


def test_bundled_robot_kinematics_agree_with_yourdfpy():
    for n, worst in _agree(load_robot()):
        assert n > 10 and worst < 1e-9


@pytest.mark.corpus
@pytest.mark.parametrize("robot", ROBOTS, ids=[r["id"] for r in ROBOTS])
def test_corpus_robot_kinematics_agree_with_yourdfpy(robot, monkeypatch):
    for n, worst in _agree(_load_corpus(robot, monkeypatch), seed=len(robot["id"])):
        assert n >= 1 and worst < 1e-9, (robot["id"], worst)
