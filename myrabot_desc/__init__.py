"""myrabot-desc: build, check, convert and smoke-simulate robot descriptions.

Importing this package is cheap on purpose: heavy libraries (trimesh, yourdfpy,
pinocchio, mujoco) are imported inside the functions that need them.
"""

__version__ = "0.2.0"
