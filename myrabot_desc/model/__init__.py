"""The robot model: the typed Robot (parts.py), how it is read (loader.py), and every fact
derived from it once (kinematics, transforms, shapes, inertia, meshes, drive)."""
