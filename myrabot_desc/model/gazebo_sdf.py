"""SDF elements declared in model-level ``<gazebo>`` blocks: a parallel linkage's closing joint, a
screw joint, extra links, frames or models that only Gazebo (sdformat) sees. `convert --to sdf`
copies them; `convert --to mjcf` reports them dropped.
"""

from __future__ import annotations

from myrabot_desc.records import Struct

SDF_MODEL_CHILDREN = ("joint", "link", "frame", "model")


class SdfElement(Struct):
    tag: str                 # 'joint', 'link', 'frame' or 'model'
    name: str | None
    loc: object = None          # where it was written (the block's location when unknown)
    node: object = None         # the element as a model/nodes.Node, for a converter that copies it


def sdf_elements(robot) -> list[SdfElement]:
    """The joints, links, frames and models of every ``<gazebo>`` block without a reference, in order."""
    out = []
    for g in robot.gazebo:
        if g.reference is not None:
            continue
        for c in g.node.elements:
            if c.tag in SDF_MODEL_CHILDREN:
                out.append(SdfElement(c.tag, c.get("name"), c.loc or g.loc, c))
    return out
