"""``convert``: the Robot model to SDF (gz-sim), an SDF demo world, or MJCF (MuJoCo).

Modules: ``sdf`` (model: links, joints, lumping, frames), ``gazebo`` (per-link
extension properties: materials, surfaces), ``sensors`` and ``systems`` (Gazebo
extensions, Electric dialect included), ``world`` (demo worlds), ``mjcf``
(MuJoCo through its own URDF compiler); the command is commands/convert.py.
"""
