"""model.meshes.triangles: the lean STL/COLLADA readers give the very vertices and faces trimesh
gives (so the viewer's and render's pictures do not change), and a render of the bundled robot
no longer imports trimesh."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from helpers import ROOT
from myrabot_desc.model import meshes

ERD = Path(sys.prefix) / "lib" / f"python{sys.version_info.major}.{sys.version_info.minor}" / "site-packages" / \
    "cmeel.prefix" / "share" / "example-robot-data" / "robots"
SAMPLE = sorted(p for p in (ERD / "talos_data").rglob("*") if p.suffix.lower() in (".stl", ".dae"))[:12] + \
    sorted(p for p in (ERD / "anymal_c_simple_description").rglob("*.dae"))[:4] + \
    sorted(p for p in (ROOT / "myrabot_desc").rglob("*.stl"))[:6]


def test_sample_is_real():
    assert len(SAMPLE) >= 15 and {p.suffix.lower() for p in SAMPLE} >= {".stl", ".dae"}


@pytest.mark.parametrize("path", SAMPLE, ids=lambda p: p.name)
def test_triangles_equal_trimesh(path):
    v, f = meshes.triangles(path)
    m = meshes.load(path)
    assert np.array_equal(v, m.vertices) and np.array_equal(f, m.faces)
    assert len(f) > 0


@pytest.mark.parametrize("path", [p for p in SAMPLE if p.suffix.lower() == ".dae"][:4], ids=lambda p: p.name)
def test_vertices_of_collada_equal_trimesh(path):
    """``vertices`` (diff, extents and hulls) reads COLLADA with the lean reader: trimesh's vertices."""
    assert np.array_equal(meshes.vertices(path), meshes.load(path).vertices)


def test_obj_in_face_order_goes_through_trimesh(tmp_path):
    obj = tmp_path / "quad.obj"
    obj.write_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n")
    v, f = meshes.triangles(obj)
    assert v.shape == (4, 3) and f.shape == (2, 3)


def test_bad_mesh_is_a_mesh_error(tmp_path):
    stl = tmp_path / "empty.stl"
    stl.write_bytes(b"\0" * 80 + (0).to_bytes(4, "little"))
    with pytest.raises(meshes.MeshError):
        meshes.triangles(stl)


def test_scene_of_bundled_robot_imports_no_trimesh():
    code = ("import sys\nfrom myrabot_desc.model.loader import load_robot, bundled_path\n"
            "from myrabot_desc.view.scene import build_scene\n"
            "s = build_scene(load_robot(str(bundled_path())))\n"
            "print(len(s.parts), 'trimesh' in sys.modules)")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    parts, imported = p.stdout.split()
    assert int(parts) > 20 and imported == "False"


OBJ = sorted((ERD / "alex_description" / "meshes").rglob("*.obj"))[:6]


def _triangle_set(v, f) -> list:
    """The triangles as sorted rows of corner coordinates: what does not depend on the faces' order."""
    return sorted(map(tuple, np.asarray(v)[np.asarray(f)].reshape(len(f), 9).tolist()))


@pytest.mark.parametrize("path", OBJ, ids=lambda p: p.name)
def test_obj_in_any_order_is_trimeshs_triangles(path):
    """A touch test (P005) reads OBJ with the lean reader: trimesh's vertices and triangles, faces in
    another order."""
    v, f = meshes.triangles(path, any_order=True)
    m = meshes.load(path)
    assert np.array_equal(np.unique(v, axis=0), np.unique(m.vertices, axis=0))
    assert len(f) == len(m.faces) > 100
    assert _triangle_set(v, f) == _triangle_set(m.vertices, m.faces)


def test_check_inertia_of_an_obj_robot_imports_no_trimesh():
    """P005 tests alex's OBJ meshes triangle against triangle (three pairs whose hulls meet), and
    --inertia measures them: neither imports trimesh (~1 s and ~80 MB of a check)."""
    urdf = ERD / "alex_description" / "urdf" / "alex_nub_hands.urdf"
    code = ("import sys\nfrom myrabot_desc.commands.entry import main\n"
            f"code = main(['check', '--inertia', '--no-cache', '--select', 'P005,I006', {str(urdf)!r}])\n"
            "print(code, 'trimesh' in sys.modules, file=sys.stderr)")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300, cwd=ROOT)
    assert "meshes themselves do not touch" in p.stdout and "LeftWristYawLink overlaps" in p.stdout
    assert p.stderr.split()[-2:] == ["0", "False"], p.stderr[-500:]     # warnings only: exit 0


def test_unique_rows_is_numpys_bit_for_bit():
    """meshes.unique_rows (the binary STL path of ``vertices``) gives np.unique(axis=0)'s array, in
    its order and bits, with duplicates, ties on the first columns, -0.0 and an empty array."""
    rng = np.random.default_rng(7)
    cases = [np.zeros((0, 3)), np.array([[1.0, 2.0, 3.0]])]
    for n in (2, 10, 200, 5000):
        grid = rng.integers(-3, 4, size=(n, 3)).astype(float) * 0.25        # many equal rows and ties
        cases += [grid, grid + rng.normal(0, 1e-9, size=grid.shape), rng.normal(size=(n, 3))]
    signed = cases[3].copy()
    signed[::7, 0] = -0.0
    cases.append(signed)
    for v in cases:
        want, got = np.unique(v, axis=0), meshes.unique_rows(v)
        assert got.shape == want.shape and got.tobytes() == want.tobytes()
    for path in SAMPLE:
        if path.suffix.lower() == ".stl":
            v = meshes.triangles(path)[0]
            assert meshes.unique_rows(v).tobytes() == np.unique(v, axis=0).tobytes()
