"""OGRE material scripts: reader (ogre), Gazebo's stock colours (stock), name resolution (resolve),
explicit values for the `materials` command (export).

``check`` and ``convert`` use :func:`myrabot_desc.materials.resolve.resolver_for`.
"""

from myrabot_desc.materials.resolve import (
    MaterialResolver,
    ResolvedMaterial,
    resolver_for,
)

__all__ = ["MaterialResolver", "ResolvedMaterial", "resolver_for"]
