"""Test-only stand-in for ROS 2's ``ament_index_python``: see ``packages.py``."""
