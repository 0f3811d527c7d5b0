"""The robot model: the typed Robot (parts.py), how it is read (loader.py: the only reader of the
robot's XML), its values (values.py: the one parser), the markup it carries as it is (nodes.py),
where each value was written (sources.py), and every fact derived from it once (tree, kinematics,
transforms, shapes, inertia, meshes, gazebo properties, drive, plugins, support)."""
