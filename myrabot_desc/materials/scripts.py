"""Read OGRE scripts as Gazebo does: parents not defined in the script or its imports come
from Gazebo's stock materials. (The reader, ogre.py, takes its parents from the caller,
so that it does not depend on the stock table, which is built from its classes.)"""

from __future__ import annotations

from myrabot_desc.materials import ogre, stock


def parse_text(text: str, file: str = "<string>", *, parents=None, **kw) -> ogre.Script:
    return ogre.parse_text(text, file, parents=parents or stock.stock_material, known=stock.names(), **kw)


def parse_file(path, *, parents=None, **kw) -> ogre.Script:
    return ogre.parse_file(path, parents=parents or stock.stock_material, known=stock.names(), **kw)
