"""``centers_of_mass`` (many configurations at once: sim's arm sweeps) equals ``center_of_mass`` at
each configuration, to the bit, on real robots: links no given joint moves are placed once and
broadcast, moved ones per configuration, and joint motions are built as arrays."""

from __future__ import annotations

import random

import numpy as np
import pytest

from myrabot_desc.model.kinematics import center_of_mass, centers_of_mass
from myrabot_desc.model.loader import load_robot
from helpers import corpus_model, corpus_robot

ROBOTS = ["bundled", "ur5e", "pr2", "tiago", "robotiq_2f_85", "husky"]


@pytest.mark.parametrize("name", ROBOTS)
def test_each_configuration_as_alone(name):
    robot = load_robot(None) if name == "bundled" else corpus_model(corpus_robot(name))
    rnd = random.Random(name)
    movable = [j for j in robot.joints.values() if j.type != "fixed" and not j.mimic]
    for size in (1, 3, len(movable)):
        pick = rnd.sample(movable, min(size, len(movable)))
        q = {j.name: np.array([rnd.uniform(-2.0, 2.0) for _ in range(7)]) for j in pick}
        total, coms = centers_of_mass(robot, q)
        assert coms.shape == (7, 3)
        for k in range(7):
            m, c = center_of_mass(robot, {n: float(v[k]) for n, v in q.items()})
            assert m == total
            assert np.asarray(c).tobytes() == coms[k].tobytes(), (name, k)
