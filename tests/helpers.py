"""What the test folders share: where things are, and the CLI run in-process.

Importable from every test folder (``pythonpath = ["tests"]`` in pyproject.toml)::

    from helpers import ROOT, FIXTURES, invoke
"""

from __future__ import annotations

from pathlib import Path

from click.testing import CliRunner

from myrabot_desc.commands.main import main

ROOT = Path(__file__).resolve().parents[1]      # the repository
TESTS = ROOT / "tests"
FIXTURES = TESTS / "fixtures"                   # the seed's files, small xacro cases, wander_bot
BAD = TESTS / "bad"                             # hostile inputs (hardening)
CORPUS = TESTS / "corpus"                       # the real-robot corpus (data, see its README.md)
SHIM = TESTS / "corpus_shim"                    # the test-only ament_index_python for the xacro CLI
DATA = TESTS / "data"                           # schemas
SEED = FIXTURES / "seed_myrabot"
WANDER = FIXTURES / "wander_bot"


def _erd() -> Path:
    import sysconfig

    return Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix" / "share" / "example-robot-data" / "robots"


ERD = _erd()                                    # example-robot-data's robots (URDF, SRDF, meshes)


def invoke(*args, **kwargs):
    """``myrabot-desc ARGS`` in this process (click's CliRunner); the Result."""
    return CliRunner().invoke(main, [str(a) for a in args], **kwargs)


def corpus_robots() -> list[dict]:
    """The entries of tests/corpus/robots.yaml (see its header)."""
    import yaml

    return yaml.safe_load((CORPUS / "robots.yaml").read_text())["robots"]


def drive_robots() -> list[dict]:
    """The entries of tests/corpus/drives.yaml (real bases of every drive kind, issue 25), or []."""
    import yaml

    index = CORPUS / "drives.yaml"
    return yaml.safe_load(index.read_text())["robots"] if index.is_file() else []


def drive_args(robot: dict) -> list[str]:
    """The CLI arguments of a drives.yaml base: its args split like a POSIX shell (one holds a space)."""
    import shlex

    return [str(CORPUS / robot["top"]), *shlex.split(robot.get("args") or ""), "--package-path",
            str(corpus_package_path(robot))]


def corpus_package_path(robot: dict) -> Path:
    return CORPUS / robot.get("package_path", ".")


def corpus_args(robot: dict) -> list[str]:
    """The command-line arguments that read a corpus robot: its top file, its xacro args, --package-path."""
    return [str(CORPUS / robot["top"]), *robot.get("args", "").split(), "--package-path",
            str(corpus_package_path(robot))]


def corpus_env(robot: dict) -> dict[str, str]:
    """The environment a corpus robot is read with (the $(optenv) accessories its launch files set)."""
    return {k: str(v) for k, v in robot.get("env", {}).items()}


def corpus_robot(robot_id: str) -> dict:
    return next(r for r in corpus_robots() if r["id"] == robot_id)


def corpus_model(robot: dict):
    """The Robot of a corpus entry, read with its xacro args and package path (its environment, for
    the few entries that have one, is the caller's: monkeypatch corpus_env(robot))."""
    from myrabot_desc.model.loader import load_robot

    mappings = dict(a.split(":=", 1) for a in robot.get("args", "").split())
    return load_robot(CORPUS / robot["top"], mappings=mappings, package_paths=[corpus_package_path(robot)])


def corpus_models():
    """(id, Robot) of every corpus entry this environment builds (``corpus_model``); an entry that
    does not build is left out (its own tests say why)."""
    for rb in corpus_robots():
        try:
            yield rb["id"], corpus_model(rb)
        except Exception:
            continue


def erd_urdfs() -> list[Path]:
    """example-robot-data's URDF files (its */urdf and */robots folders); [] when it is not installed."""
    return sorted(ERD.glob("*/urdf/*.urdf")) + sorted(ERD.glob("*/robots/*.urdf"))


def erd_models():
    """(file name, Robot) of every ``erd_urdfs`` file the loader reads (the others are refused
    elsewhere, with their reasons)."""
    from myrabot_desc.model.loader import load_robot

    for f in erd_urdfs():
        try:
            yield f.name, load_robot(f)
        except Exception:
            continue


# ---------------------------------------------------------------- time limits in CPU time
# A limit inside a test is CPU time, never wall time: on a loaded machine (five engineers' tests on
# two cores, or a CI runner) wall time measures the neighbours. A generous wall-clock guard stays
# only to stop a run that blocks without using CPU (a FIFO, a deadlock): tests/hardening/limited.py.


class cpu_time:
    """``with cpu_time() as t: ...``; ``t.seconds`` is the CPU time (user + system) this process and
    the children it waited for used inside the block."""

    def __enter__(self):
        import resource
        import time

        self._p = time.process_time()
        c = resource.getrusage(resource.RUSAGE_CHILDREN)
        self._c = c.ru_utime + c.ru_stime
        self.seconds = 0.0
        return self

    def __exit__(self, *exc):
        import resource
        import time

        c = resource.getrusage(resource.RUSAGE_CHILDREN)
        self.seconds = (time.process_time() - self._p) + (c.ru_utime + c.ru_stime - self._c)
        return False


# ------------------------------------------------------------------ planted defects (physics tests)
def planted_panda(tmp_path, drop: float = 0.28):
    """ERD's panda with panda_link5's collision moved ``drop`` m down (in the world at the rest pose) onto
    panda_link2, a pair Franka's SRDF does not disable."""
    import numpy as np

    from myrabot_desc.model.kinematics import world_transforms
    from myrabot_desc.model.loader import load_robot

    panda = ERD / "panda_description/urdf/panda.urdf"
    src = panda.read_text()
    r = load_robot(panda)
    R5 = world_transforms(r, r.rest_pose())["panda_link5"][:3, :3]
    x, y, z = R5.T @ np.array([0.0, 0.0, -drop])
    i = src.index('<link name="panda_link5"')
    j = src.index("<collision>", i) + len("<collision>")
    f = tmp_path / "panda_planted.urdf"
    f.write_text(src[:j] + f'\n      <origin xyz="{x:.4f} {y:.4f} {z:.4f}" rpy="0 0 0"/>' + src[j:])
    return f


def weak(tmp_path, src, joint: str, effort: str = "0.1"):
    """A copy of URDF ``src`` whose ``joint`` has the effort limit ``effort``."""
    text = src.read_text()
    i = text.index(f'name="{joint}"')
    k = text.index('effort="', i)
    e = text.index('"', k + 8)
    f = tmp_path / f"{src.stem}_weak.urdf"
    f.write_text(text[:k] + f'effort="{effort}"' + text[e + 1:])
    return f
