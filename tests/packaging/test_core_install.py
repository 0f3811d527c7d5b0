"""``pip install myrabot-desc`` without extras, in a fresh virtual environment: how big it is, that
the lint works (``check --inertia`` on the bundled robot and a corpus robot), and that every command
that needs an extra says which one in one line (exit 2).

The environment is made once per run; pip's own wheel cache (``~/.cache/pip``, or ``PIP_CACHE_DIR``
in CI) makes the second install quick. ``MYRABOT_DESC_CORE_VENV=DIR`` keeps it in DIR between runs.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from helpers import CORPUS, ROOT, corpus_args, corpus_robot

CORE_LIMIT_MB = 650


def _size_mb(folder: Path) -> float:
    """Bytes on disk under ``folder`` (as ``du``: allocated blocks, each file once), in MB."""
    seen, total = set(), 0
    for dirpath, dirnames, filenames in os.walk(folder):
        for name in filenames + dirnames:
            st = os.lstat(os.path.join(dirpath, name))
            if (st.st_dev, st.st_ino) in seen:
                continue
            seen.add((st.st_dev, st.st_ino))
            total += st.st_blocks * 512
    return total / 2**20


@pytest.fixture(scope="module")
def core(tmp_path_factory):
    """(bin folder, size in MB) of a fresh venv with ``pip install .`` (the core, no extras)."""
    keep = os.environ.get("MYRABOT_DESC_CORE_VENV")
    venv = Path(keep) if keep else tmp_path_factory.mktemp("core") / "venv"
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    base = getattr(sys, "_base_executable", sys.executable)
    if not (venv / "bin" / "python").exists():
        r = subprocess.run([base, "-m", "venv", str(venv)], capture_output=True, text=True, env=env)
        if r.returncode != 0:
            pytest.skip(f"cannot make a virtual environment here: {r.stderr.strip()[-300:]}")
    r = subprocess.run([str(venv / "bin" / "python"), "-m", "pip", "install", "-q", "--disable-pip-version-check",
                        "--force-reinstall", "--no-deps", str(ROOT)], capture_output=True, text=True, env=env) \
        if (venv / "bin" / "myrabot-desc").exists() else None
    if r is None:
        r = subprocess.run([str(venv / "bin" / "python"), "-m", "pip", "install", "-q",
                            "--disable-pip-version-check", str(ROOT)], capture_output=True, text=True, env=env)
    if r.returncode != 0:
        pytest.skip(f"cannot install the core here (no index or wheel cache?): {r.stderr.strip()[-400:]}")
    return venv / "bin", _size_mb(venv)


def _run(core, *args, cwd):
    bindir, _ = core
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    return subprocess.run([str(bindir / "myrabot-desc"), *map(str, args)], cwd=cwd, capture_output=True,
                          text=True, env=env)


@pytest.mark.slow
def test_core_is_small_and_has_no_extra(core):
    bindir, size = core
    print(f"core install: {size:.0f} MB")
    assert size <= CORE_LIMIT_MB, f"the core install is {size:.0f} MB (limit {CORE_LIMIT_MB} MB)"
    r = subprocess.run([str(bindir / "python"), "-c",
                        "import importlib.util as u; print([m for m in ('mujoco', 'viser', 'matplotlib', "
                        "'example_robot_data', 'yourdfpy', 'scipy', 'PIL') if u.find_spec(m)])"],
                       capture_output=True, text=True)
    assert r.stdout.strip() == "[]", r.stdout + r.stderr
    r = subprocess.run([str(bindir / "python"), "-c", "import pinocchio, trimesh, lxml, xacro"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr


@pytest.mark.slow
def test_core_checks_the_bundled_robot_and_a_corpus_robot(core, tmp_path):
    r = _run(core, "check", "--inertia", cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "0 errors" in r.stdout and "P004 total mass 4.605 kg" in r.stdout
    robot = corpus_robot("panda")
    r = _run(core, "check", "--inertia", *corpus_args(robot), cwd=tmp_path)
    assert r.returncode in (0, 1), r.stdout + r.stderr
    assert "robot panda" in r.stdout and "Traceback" not in r.stderr
    assert str(CORPUS) in r.stdout or "franka_description" in r.stdout
    r = _run(core, "convert", "-o", tmp_path / "m.sdf", cwd=tmp_path)
    assert r.returncode == 0 and (tmp_path / "m.sdf").is_file(), r.stderr
    r = _run(core, "sim", "vuelta", "--no-collisions", cwd=tmp_path)
    assert r.returncode == 0 and "verdict: PASS" in r.stdout, r.stdout + r.stderr


@pytest.mark.slow
@pytest.mark.parametrize("args,extra", [
    (["render", "-o", "r.png"], "render"),
    (["view", "--port", "0"], "view"),
    (["sim", "vuelta", "--plot", "v.png"], "plot"),
    (["convert", "--to", "mjcf", "-o", "mjcf/m.xml"], "mjcf"),
])
def test_a_command_without_its_extra_says_which_to_install(core, tmp_path, args, extra):
    r = _run(core, *args, cwd=tmp_path)
    assert r.returncode == 2
    assert r.stdout == ""
    lines = r.stderr.splitlines()
    assert len(lines) == 1, r.stderr
    assert lines[0].startswith("error: ") and f"pip install 'myrabot-desc[{extra}]'" in lines[0]
    assert list(tmp_path.iterdir()) == []           # nothing written


def _head() -> str | None:
    r = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "HEAD"], capture_output=True, text=True)
    return r.stdout.strip() if r.returncode == 0 else None


@pytest.mark.slow
def test_installed_version_names_the_commit_it_was_built_from(core, tmp_path):
    head = _head()
    if head is None:
        pytest.skip("not a git checkout")
    r = _run(core, "--version", cwd=tmp_path)
    assert r.returncode == 0
    assert r.stdout.startswith("myrabot-desc, version 0.") and f"commit {head}" in r.stdout, r.stdout


def test_checkout_version_names_the_commit_and_local_changes():
    from helpers import invoke

    head = _head()
    if head is None:
        pytest.skip("not a git checkout")
    out = invoke("--version").output
    dirty = subprocess.run(["git", "-C", str(ROOT), "status", "--porcelain", "--untracked-files=no"],
                           capture_output=True, text=True).stdout != ""
    assert f"commit {head}" in out and ("with local changes" in out) == dirty, out
    assert out.rstrip().endswith("not a release)") or "(release v" in out
