"""Build: xacro sources -> URDF text, without ROS (driver.py runs xacro with our hooks)."""
