"""OGRE material scripts: reader (ogre), Gazebo's stock colours (stock), name resolution (resolve),
explicit values for the `materials` command (export).

``check`` and ``convert`` use :func:`myrabot_desc.materials.resolve.resolver_for`.
"""

__all__ = ["MaterialResolver", "ResolvedMaterial", "resolver_for"]


def __getattr__(name: str):
    # resolve (and the OGRE reader under it) loads when asked: `check` needs only the stock table of
    # a model whose materials are all stock names
    if name in __all__:
        import myrabot_desc.materials.resolve as resolve

        return getattr(resolve, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
