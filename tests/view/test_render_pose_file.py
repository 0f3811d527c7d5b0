"""render --pose reads through safety.read_checked: a FIFO, a device or a file over the input limit
is one error line, exit 2, no picture (and no hang on the FIFO)."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest


def _render(tmp_path, pose, env=None):
    out = tmp_path / "r.png"
    p = subprocess.run([sys.executable, "-m", "myrabot_desc", "render", "-o", str(out), "--size", "64x64",
                        "--pose", str(pose)], capture_output=True, text=True, timeout=120,
                       env={**os.environ, **(env or {})})
    return p, out


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs here")
def test_fifo_pose_is_refused_not_waited_on(tmp_path):
    fifo = tmp_path / "pose.yaml"
    os.mkfifo(fifo)                       # nobody writes: a plain open() would block forever
    p, out = _render(tmp_path, fifo)
    assert p.returncode == 2, p.stderr
    assert p.stderr.strip().splitlines() == [f"error: X006 refusing to read {fifo}: a FIFO, not a regular file"]
    assert not out.exists()


def test_device_pose_is_refused(tmp_path):
    p, out = _render(tmp_path, "/dev/zero")
    assert p.returncode == 2
    assert p.stderr.strip().splitlines() == ["error: X006 refusing to read /dev/zero: a device, not a regular file"]
    assert not out.exists()


def test_pose_over_the_input_limit(tmp_path):
    big = tmp_path / "big.yaml"
    big.write_text("# padding\n" * 3000 + "arti1: 1.0\n")         # 30,011 bytes
    # the bundled model's files are at most 12 kB: only the pose file is over 20 kB
    p, out = _render(tmp_path, big, {"MYRABOT_DESC_MAX_INPUT_BYTES": "20000"})
    assert p.returncode == 2
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and "is over the 20000-byte limit (see MYRABOT_DESC_MAX_INPUT_BYTES)" in lines[0]
    assert not out.exists()


def test_missing_pose_file(tmp_path):
    p, out = _render(tmp_path, tmp_path / "nope.yaml")
    assert p.returncode == 2
    assert p.stderr.strip().splitlines() == [f"error: no such YAML file: {tmp_path / 'nope.yaml'}"]
    assert not out.exists()


def test_pose_yaml_goes_through_the_one_yaml_loader(tmp_path):
    """xacro's unit tags are numbers (as in a model's load_yaml), never code; other tags refused."""
    from myrabot_desc.errors import InputError
    from myrabot_desc.model.loader import load_robot
    from myrabot_desc.render import read_pose
    from myrabot_desc.view.scene import build_scene

    scene = build_scene(load_robot(), collision=False)
    good = tmp_path / "deg.yaml"
    good.write_text("joints:\n  arti1: !degrees 45\n  base: 0.5\n")
    q = read_pose(str(good), scene)
    assert q["arti1"] == pytest.approx(0.785398163, abs=1e-9) and q["base"] == 0.5
    bad = tmp_path / "code.yaml"
    bad.write_text("arti1: !radians __import__('os').system('touch pwned')\n")
    with pytest.raises(InputError) as e:
        read_pose(str(bad), scene)
    assert str(e.value).startswith(f"{bad}:1: error:")
    assert not (tmp_path / "pwned").exists() and not os.path.exists("pwned")
