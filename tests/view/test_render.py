"""render: real PNGs of the bundled robot through the CLI (MuJoCo offscreen in a subprocess, since
the GL backend is fixed when mujoco is first imported)."""

from __future__ import annotations

import io
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from myrabot_desc.render import BACKGROUND

ERD = Path(sys.prefix) / "lib" / f"python{sys.version_info.major}.{sys.version_info.minor}" / "site-packages" / \
    "cmeel.prefix" / "share" / "example-robot-data" / "robots"


def _has_gl() -> bool:
    import ctypes.util

    return any(ctypes.util.find_library(n) for n in ("EGL", "OSMesa"))


pytestmark = pytest.mark.skipif(not _has_gl(), reason="no libEGL or libOSMesa: `make install` installs them")


def render(tmp_path, *args, name="r.png", expect=0):
    out = tmp_path / name
    env = {k: v for k, v in os.environ.items() if k != "MUJOCO_GL"}
    p = subprocess.run([sys.executable, "-m", "myrabot_desc", "render", "-o", str(out), "--size", "480x480", *args],
                       capture_output=True, text=True, env=env, timeout=120)
    assert p.returncode == expect, p.stderr
    return (load(out) if expect == 0 else None), p.stderr


def load(path):
    from PIL import Image

    with Image.open(path) as im:
        return np.asarray(im.convert("RGB")).astype(int)


def bbox(img):
    """(x0, y0, x1, y1) of the pixels that are not background."""
    fg = np.abs(img - np.array(BACKGROUND)).sum(axis=2) > 6
    ys, xs = np.nonzero(fg)
    return xs.min(), ys.min(), xs.max() + 1, ys.max() + 1


@pytest.fixture(scope="module")
def extents():
    """The bundled robot's visual extents (m) at zero, from the scene every command shares."""
    from myrabot_desc.model.loader import load_robot
    from myrabot_desc.view.scene import build_scene

    v = build_scene(load_robot(), collision=False).world_vertices()
    return np.ptp(v, axis=0)


@pytest.fixture(scope="module")
def shots(tmp_path_factory):
    d = tmp_path_factory.mktemp("render")
    out = {}
    for key, args in {"front": ["--view", "front"], "side": ["--view", "side"], "top": ["--view", "top"],
                      "iso": [], "arti1": ["--joint", "arti1=1.0"], "collision": ["--collision"],
                      "frames": ["--frames"], "inertia": ["--inertia"]}.items():
        out[key] = render(d, *args, name=f"{key}.png")[0]
    return out


@pytest.mark.parametrize("view,across,up", [("front", 1, 2), ("side", 0, 2), ("top", 0, 1)])
def test_picture_keeps_the_robots_proportions(shots, extents, view, across, up):
    x0, y0, x1, y1 = bbox(shots[view])
    ratio = (y1 - y0) / (x1 - x0)
    expected = extents[up] / extents[across]
    assert ratio == pytest.approx(expected, rel=0.10), (view, ratio, expected)
    # the robot fills the picture (the camera frames it) and is centred
    assert max(x1 - x0, y1 - y0) > 0.8 * 480
    assert abs((x0 + x1) / 2 - 240) < 10 and abs((y0 + y1) / 2 - 240) < 10


def test_joint_moves_the_arm(shots):
    a, b = shots["iso"], shots["arti1"]
    diff = np.abs(a - b).sum(axis=2) > 30
    assert diff.mean() > 0.01
    # the change is in the upper part of the picture, where the arm is, not at the wheels (the
    # camera frames the whole robot, so a raised arm may shift the rest by a pixel)
    rows = np.nonzero(diff)[0]
    assert (rows > 0.75 * 480).mean() < 0.03


@pytest.mark.parametrize("layer", ["collision", "frames", "inertia"])
def test_layers_change_the_picture(shots, layer):
    diff = np.abs(shots["iso"] - shots[layer]).sum(axis=2) > 30
    assert diff.mean() > 0.005, layer


def test_inertia_layer_draws_blue_boxes(shots):
    img = shots["inertia"]
    blueish = (img[:, :, 2] > img[:, :, 0] + 60) & (img[:, :, 2] > img[:, :, 1] + 30)
    base = shots["iso"]
    before = (base[:, :, 2] > base[:, :, 0] + 60) & (base[:, :, 2] > base[:, :, 1] + 30)
    assert blueish.sum() > before.sum() + 2000


def test_same_input_same_bytes(tmp_path):
    render(tmp_path, "--view", "top", name="a.png")
    render(tmp_path, "--view", "top", name="b.png")
    assert (tmp_path / "a.png").read_bytes() == (tmp_path / "b.png").read_bytes()


def test_pose_file_equals_joint_option(tmp_path):
    pose = tmp_path / "pose.yaml"
    pose.write_text("joints:\n  arti1: 1.0\n")
    a, _ = render(tmp_path, "--pose", str(pose), "--view", "side", name="a.png")
    b, _ = render(tmp_path, "--joint", "arti1=1.0", "--view", "side", name="b.png")
    c, _ = render(tmp_path, "--view", "side", name="c.png")
    assert np.array_equal(a, b)
    assert not np.array_equal(a, c)


@pytest.mark.parametrize("args,needle", [
    (["--joint", "arti9=1"], "no movable joint named 'arti9' (did you mean arti"),
    (["--joint", "pinza"], "expected NAME=VALUE"),
    (["--joint", "base_footprint_joint=1"], "is fixed, it cannot be set"),
    (["--size", "10x10"], "at least 64 pixels"),
    (["--size", "big"], "expected WIDTHxHEIGHT"),
])
def test_bad_options_exit_2_in_one_line(tmp_path, args, needle):
    _, err = render(tmp_path, *args, expect=2)
    assert needle in err
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "r.png").exists()


def test_pose_yaml_is_read_safely(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("arti1: !!python/object/apply:os.system ['touch pwned']\n")
    _, err = render(tmp_path, "--pose", str(bad), expect=2)
    assert f"{bad}:1: error: not valid YAML" in err
    assert not (tmp_path / "pwned").exists()
    text = tmp_path / "text.yaml"
    text.write_text("arti1: [1, 2]\n")
    _, err = render(tmp_path, "--pose", str(text), expect=2)
    assert "is not a number" in err


def test_no_gl_says_what_is_missing(monkeypatch):
    import ctypes.util

    from myrabot_desc.errors import InputError
    from myrabot_desc.render import choose_gl

    monkeypatch.delenv("MUJOCO_GL", raising=False)
    monkeypatch.setattr(ctypes.util, "find_library", lambda name: None)
    with pytest.raises(InputError, match="neither libEGL nor libOSMesa is installed.*libegl1"):
        choose_gl()
    monkeypatch.setenv("MUJOCO_GL", "osmesa")
    with pytest.raises(InputError, match="libOSMesa is not installed.*libosmesa6"):
        choose_gl()


def test_example_robot_data_robot(tmp_path):
    urdf = ERD / "ur_description/urdf/ur5_robot.urdf"
    if not urdf.is_file():
        pytest.skip("example-robot-data is not installed")
    img, err = render(tmp_path, str(urdf), "--view", "front")
    x0, y0, x1, y1 = bbox(img)
    assert (x1 - x0) * (y1 - y0) > 0.1 * 480 * 480


def test_a_backend_that_cannot_start_exits_2(tmp_path):
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    env["MUJOCO_GL"] = "glfw"            # needs a display, which a test run has not
    p = subprocess.run([sys.executable, "-m", "myrabot_desc", "render", "-o", str(tmp_path / "r.png")],
                       capture_output=True, text=True, env=env, timeout=120)
    assert p.returncode == 2
    assert p.stderr.startswith("error: cannot render offscreen with MUJOCO_GL=glfw")
    assert "unset MUJOCO_GL" in p.stderr and len(p.stderr.strip().splitlines()) == 1
    assert not (tmp_path / "r.png").exists()


def test_a_model_that_is_not_a_tree_exits_2(tmp_path):
    cyc = tmp_path / "cyc.urdf"
    cyc.write_text('<robot name="e"><link name="a"/><link name="b"/>'
                   '<joint name="j" type="fixed"><parent link="b"/><child link="a"/></joint>'
                   '<joint name="k" type="fixed"><parent link="a"/><child link="b"/></joint></robot>')
    _, err = render(tmp_path, str(cyc), expect=2)
    assert f"{cyc}:1: error: the model needs exactly one root link" in err


TINY = """<?xml version="1.0"?>
<robot name="tiny_links">
  <material name="green"><color rgba="0.1 0.8 0.1 1"/></material>
  <link name="base"><visual><geometry><box size="0.3 0.2 0.1"/></geometry><material name="green"/></visual>
    <inertial><mass value="2"/><inertia ixx="0.008" iyy="0.017" izz="0.022" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="arm"><visual><origin xyz="0 0 0.15"/><geometry><cylinder radius="0.03" length="0.3"/></geometry>
    <material name="green"/></visual>
    <inertial><origin xyz="0 0 0.15"/><mass value="0.5"/><inertia ixx="0.0039" iyy="0.0039" izz="0.0002" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/><origin xyz="0 0 0.05"/>
    <axis xyz="0 1 0"/><limit lower="-1.5" upper="1.5" effort="1" velocity="1"/></joint>
  <link name="tiny1"><visual><geometry><sphere radius="0.005"/></geometry></visual>
    <inertial><mass value="0.01"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="t1" type="fixed"><parent link="base"/><child link="tiny1"/><origin xyz="0.1 0.05 0.06"/></joint>
  <link name="tiny2"><visual><geometry><sphere radius="0.005"/></geometry></visual>
    <inertial><mass value="0.01"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="t2" type="fixed"><parent link="arm"/><child link="tiny2"/><origin xyz="0 0 0.3"/></joint>
</robot>
"""


def _green(img) -> int:
    """The robot's own pixels (it is green; under a translucent blue box green still leads, while
    the background under a box turns blue)."""
    r, g, b = img[..., 0], img[..., 1], img[..., 2]
    return int(((g - r > 40) & (g > b))[: int(img.shape[0] * 0.9)].sum())


def test_inertia_frames_the_robot_not_its_boxes(tmp_path):
    """Two tiny links with 1 m radius of gyration: their boxes are metres wide. The picture frames
    the robot (its pixels about as many as without the boxes), and a legend names every mark."""
    f = tmp_path / "tiny.urdf"
    f.write_text(TINY)
    plain, _ = render(tmp_path, str(f), name="plain.png")
    boxed, _ = render(tmp_path, str(f), "--inertia", name="boxed.png")
    assert _green(plain) > 10_000
    # framed on the robot (plus a margin for the boxes near it): a third of the plain picture's
    # pixels and more (the boxes' blue covers some); framed on the boxes, the robot had none
    assert _green(boxed) > 0.3 * _green(plain), (_green(boxed), _green(plain))
    # the legend (bottom left): a magenta dot for the robot's centre of mass, black for each link's
    legend = boxed[-40:, :300]
    magenta = (legend[..., 0] > 200) & (legend[..., 1] < 60) & (legend[..., 2] > 160)
    black = (legend.sum(axis=2) < 120)
    assert magenta.sum() > 20 and black.sum() > 20
    # the dots themselves, over the picture
    body = boxed[:-40]
    assert ((body[..., 0] > 200) & (body[..., 1] < 60) & (body[..., 2] > 160)).sum() > 50


def test_a_clamped_joint_value_is_said(tmp_path):
    f = tmp_path / "tiny.urdf"
    f.write_text(TINY)
    img, err = render(tmp_path, str(f), "--joint", "shoulder=5")
    assert "warning: joint shoulder = 5 rad is outside its limits [-1.5, 1.5]; drawn at 1.5" in err
    same, err2 = render(tmp_path, str(f), "--joint", "shoulder=1.5", name="r2.png")
    assert "outside" not in err2 and np.array_equal(img, same)
