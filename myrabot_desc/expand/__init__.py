"""Expand: xacro sources -> URDF text, without ROS (driver.py runs xacro with our hooks).

The ``build`` command runs this package; it is named for what it does (a folder named ``build/``
is what many tools skip as generated output)."""
