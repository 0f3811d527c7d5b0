"""A non-editable install finds the bundled model (pip install ., run from elsewhere)."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest
from helpers import ROOT



@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("wheel")
    r = subprocess.run([sys.executable, "-m", "pip", "wheel", str(ROOT), "--no-deps", "-q", "-w", str(tmp / "whl")],
                       capture_output=True, text=True)
    if r.returncode != 0:
        pytest.skip(f"cannot build a wheel here (no build backend?): {r.stderr.strip()[-300:]}")
    wheel = next((tmp / "whl").glob("*.whl"))
    target = tmp / "site"
    subprocess.run([sys.executable, "-m", "pip", "install", "--no-deps", "-q", "--target", str(target), str(wheel)],
                   check=True, capture_output=True)
    return target


def test_installed_wheel_builds_the_bundled_robot_from_another_folder(installed, tmp_path):
    env = dict(os.environ, PYTHONPATH=str(installed))
    code = ("import sys; from myrabot_desc.model.loader import data_root; print(data_root()); "
            "from myrabot_desc.commands.main import main; main(['build', '-o', 'm.urdf'])")
    r = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env=env, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip().startswith(str(installed))
    text = (tmp_path / "m.urdf").read_text()
    assert 'name="MYRAbot"' in text and "ultrasonidos_5_link" in text
    # meshes and materials travelled with the wheel
    share = installed / "myrabot_desc" / "share" / "myrabot_description"
    assert (share / "package.xml").is_file() and any((share / "meshes").glob("*.stl"))
    assert (share / "materials" / "scripts" / "myrabot.material").is_file() and (share / "layouts").is_dir()
