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


def _legend_texts(ax) -> list[str]:
    return [t.get_text() for t in ax.get_legend().get_texts()]


def test_legends_list_what_is_drawn_and_axes_name_quantities():
    """escoja: the base stays put (one footprint, no start/end pair or path in the legend) and the
    table and both cans are in the legend; drive: each lane names its quantity with its unit."""
    from myrabot_desc.model.loader import load_robot
    from myrabot_desc.sim import drive, pointing
    from myrabot_desc.sim.plot import figure
    from myrabot_desc.expand.packages import data_root
    from myrabot_desc.sim.scene import load_layout

    robot = load_robot()
    res = pointing.run_escoja(robot, load_layout(data_root() / "layouts" / "escoja.yaml"), which="1")
    top = figure(res).axes[0]
    texts = _legend_texts(top)
    assert "robot (the base does not move)" in texts
    assert not {"robot at start", "robot at end", "base path (axle midpoint)"} & set(texts)
    assert {"mesa", "lata_cocacola", "lata_amstel"} <= set(texts), texts
    res = drive.run(robot, script=[(0.1, 0.3, 3.0)])
    fig = figure(res)
    top, *lanes = fig.axes
    assert [a.get_ylabel() for a in lanes] == ["speed\n(m/s)", "turn rate\n(rad/s)"]
    assert {"robot at start", "robot at end", "base path (axle midpoint)"} <= set(_legend_texts(top))
