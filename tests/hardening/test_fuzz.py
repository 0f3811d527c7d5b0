"""Property-based fuzzing (issue 7): mutated URDF, xacro and OGRE files never crash a command.

Seeds: example-robot-data URDFs, the bundled MYRAbot (built), the seed fixtures and bundled
xacro files, tests/fixtures/materials/*.material, and the corpus' small diff-drive robot.
Mutations and the command come from the case number (tests/bad/fuzzlib.py); hypothesis draws
the numbers, derandomized so that `make test` runs the same 200 cases every time. The long run
(bench/fuzz_long.py, 10,000+ cases) uses the same cases.
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from helpers import BAD

sys.path.insert(0, str(BAD))

import fuzzlib  # noqa: E402
import harness  # noqa: E402


@pytest.fixture(scope="module")
def seeds():
    harness.prepare_worker()    # audit hook (inactive outside a run) and the alarm handler
    return fuzzlib.seed_files()


SCRATCH = Path(tempfile.mkdtemp(prefix="myrabot_fuzz_"))


def test_seeds_cover_every_kind(seeds):
    assert len(seeds["urdf"]) >= 30 and len(seeds["xacro"]) >= 20 and len(seeds["material"]) >= 5
    assert any(p.name == "myrabot.urdf" for p in seeds["urdf"])


@settings(max_examples=200, deadline=None, derandomize=True, database=None,
          suppress_health_check=list(HealthCheck))
@given(case=st.integers(min_value=0, max_value=2**31 - 1))
def test_mutated_inputs_end_cleanly(seeds, case):
    r = fuzzlib.run_case(case, seeds, SCRATCH)
    assert not r["problems"], f"case {case} ({r['command']} on {r['what']}): {r['problems']}"


def test_mutations_are_reproducible(seeds, tmp_path):
    a, b = tmp_path / "a", tmp_path / "b"
    fa = fuzzlib.make_case(12345, seeds, a)
    fb = fuzzlib.make_case(12345, seeds, b)
    assert fa[1:] == fb[1:] and fa[0].read_bytes() == fb[0].read_bytes()
