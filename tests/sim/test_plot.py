"""sim --plot: matplotlib lanes and a top view people can read (labels with units, legends off the data)."""

from __future__ import annotations

import pytest
from click.testing import CliRunner

from myrabot_desc.commands.main import main


@pytest.fixture(scope="module")
def vuelta():
    from myrabot_desc.model.loader import load_robot
    from myrabot_desc.sim import vuelta

    return vuelta.run(load_robot(), duration=3.0, check_collisions=False)


def test_lanes_and_labels(vuelta):
    from myrabot_desc.sim.plot import figure

    fig = figure(vuelta)
    fig.canvas.draw()
    top, *lanes = fig.axes
    assert (top.get_xlabel(), top.get_ylabel()) == ("x (m)", "y (m)")
    # one lane per arm joint, each with its own name and unit
    assert [a.get_ylabel() for a in lanes] == [f"{n}\n(deg)" for n in vuelta.arm_names]
    assert lanes[-1].get_xlabel() == "time (s)"
    # the footprint polygon (the Roomba's outline) is drawn, not a circle marker
    polys = [p for p in top.patches if p.get_label() in ("robot at start", "robot at end")]
    assert len(polys) == 2 and len(polys[0].get_xy()) >= len(vuelta.outline())
    # the legend sits below the top view, outside its data area
    r = fig.canvas.get_renderer()
    leg = top.get_legend().get_window_extent(r)
    assert leg.y1 <= top.get_window_extent(r).y0


def test_plot_file_is_deterministic(tmp_path):
    from PIL import Image

    a, b = tmp_path / "a.png", tmp_path / "b.png"
    for f in (a, b):
        r = CliRunner().invoke(main, ["sim", "drive", "--twist", "0.1,0.3,3", "--plot", str(f)])
        assert r.exit_code == 0, r.output
    assert a.read_bytes() == b.read_bytes()
    assert Image.open(a).size == (1400, 700)
