"""The Robot -> MJCF for MuJoCo (Menagerie's form: actuators, a ``home`` keyframe on the floor,
contact exclusions, ``scene.xml``), built through MuJoCo's own model-building API, ``MjSpec``.
writer.py has the steps; ``convert_mjcf`` is the entry point."""

from myrabot_desc.convert.mjcf.writer import MjcfResult, check_size, convert_mjcf

__all__ = ["MjcfResult", "check_size", "convert_mjcf"]
