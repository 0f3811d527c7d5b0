"""What the viewer sends the browser: model text escaped for Markdown, meshes within a triangle budget."""

from __future__ import annotations

import sysconfig
from pathlib import Path

import numpy as np
import pytest

from myrabot_desc.view.text import md, md_code, md_code_block, visible


def test_markdown_escapes():
    out = md("<iframe srcdoc=\"<script>alert(1)</script>\">a_b*c`d\n# h")
    assert "<" not in out and ">" not in out and "\n" not in out
    assert "\\_" in out and "\\*" in out and "\\`" in out and "\\#" in out
    assert md_code("a`b") == "``a`b``" and md_code("``x") == "``` ``x ```"
    assert "\n" not in md_code("a\n\nb")                      # a blank line would end the span
    block = md_code_block("j\n```\n<img src=x>", "yaml")
    fence = block.splitlines()[0]
    assert fence == "````yaml" and block.rstrip().endswith("````")
    assert visible("a\nb\x07") == "a\\nb\\x07"


ERD = Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix" / "share" / "example-robot-data" / "robots"


def test_big_meshes_are_simplified_for_the_browser_only():
    from myrabot_desc.model.loader import load_robot
    from myrabot_desc.view.decimate import BUDGET, browser_parts, cluster
    from myrabot_desc.view.scene import build_scene

    # a sphere of 24,000 faces to 2,000
    rng = np.random.default_rng(1)
    pts = rng.normal(size=(12_000, 3))
    pts /= np.linalg.norm(pts, axis=1)[:, None]
    import scipy.spatial

    hull = scipy.spatial.ConvexHull(pts)
    nv, nf = cluster(pts.astype(np.float32), hull.simplices.astype(np.uint32), 2_000)
    assert 500 < len(nf) <= 2_000 and nf.max() < len(nv)
    assert np.allclose(np.linalg.norm(nv, axis=1), 1.0, atol=0.15)     # still the sphere
    # the bundled robot is under the budget: sent as it is
    scene = build_scene(load_robot())
    assert all(a is b for a, b in zip(browser_parts(scene.parts), scene.parts))
    g1 = ERD / "g1_description" / "urdf" / "g1_29dof_with_hand_rev_1_0.urdf"
    if not g1.is_file():
        pytest.skip("example-robot-data is not installed")
    scene = build_scene(load_robot(g1))
    full = sum(len(p.faces) for p in scene.parts if p.layer == "visual")
    sent = browser_parts(scene.parts)
    light = sum(len(p.faces) for p in sent if p.layer == "visual")
    assert full > 400_000 and light <= BUDGET * 1.05, (full, light)
    assert len(sent) == len(scene.parts)                        # every part still there
    assert sum(len(p.faces) for p in scene.parts if p.layer == "visual") == full     # the scene keeps its own
