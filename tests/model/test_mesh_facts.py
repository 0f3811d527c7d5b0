"""The lean mesh reader of check --inertia (model/meshes.py MeshFacts) against trimesh on real files.

check measures collision meshes from binary STL and COLLADA without building trimesh scenes; the
facts must be trimesh's (same merge, same watertightness, same volume and inertia), or the findings
of ``check --inertia`` would change with the reader. The meshes are example-robot-data's.
"""

from __future__ import annotations

import sysconfig
from pathlib import Path

import numpy as np
import pytest

from myrabot_desc.checks.examples import tetrahedron_stl
from myrabot_desc.model import meshes as M

ROBOTS = Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix" / "share" / "example-robot-data" / "robots"

# binary STL; COLLADA with node matrices trimesh repairs to rotations (b1 trunk), with per-corner
# normals and bound texture coordinates (kinova hand), with several primitives and instances
# (asr flange), a <polylist> file (romeo hand), and one whose textured material pycollada rejects
# (anymal foot: trimesh then sees no triangles, and so must we)
FILES = [
    "ur_description/meshes/ur5/collision/base.stl",
    "so_arm_description/meshes/so101/wrist_roll_pitch_so101_v2.stl",
    "b1_description/meshes/trunk.dae",
    "kinova_description/meshes/hand_2finger.dae",
    "asr_twodof_description/qb_meshes/dae/qb_c_flange_m.dae",
    "romeo_description/meshes/V1/collision/LHand.dae",
    "panda_description/meshes/visual/link7.dae",
    "anymal_b_simple_description/meshes/foot/anymal_foot.dae",
    # OBJ: usemtl parts with v/vt/vn (laikago trunk), vertex colours (laikago hip), polygons of up to
    # 38 corners (alex wrist), v//vn and v/vt/vn corners in one file (alex palm), plain v/f (solo cube)
    "laikago_description/meshes/trunk.obj",
    "laikago_description/meshes/hip.obj",
    "alex_description/meshes/wristmesh.updated.obj",
    "alex_description/meshes/SakePalmLink.obj",
    "solo_description/meshes/cube.obj",
    # ASCII STL
    "simple_humanoid_description/meshes/box.stl",
]


def _trimesh_facts(path: Path, scale=(1.0, 1.0, 1.0)):
    """What check used before the lean reader: trimesh, processed, geometry only."""
    mesh = M.load(path, process=True, textures=False)
    if tuple(scale) != (1.0, 1.0, 1.0):
        mesh.apply_transform(np.diag([*scale, 1.0]))
    return M.MeshFacts.from_trimesh(mesh)


def _same(lean, ref):
    assert lean.n_faces == ref.n_faces
    assert (lean.is_watertight, lean.is_winding_consistent, lean.is_volume) == \
        (ref.is_watertight, ref.is_winding_consistent, ref.is_volume)
    assert lean.vertices.shape == ref.vertices.shape
    assert np.array_equal(lean.vertices, ref.vertices)          # same merge, same order, same values
    np.testing.assert_allclose(lean.extents, ref.extents, rtol=0, atol=0)
    assert lean.volume == pytest.approx(ref.volume, rel=1e-9, abs=1e-18)
    if ref.is_volume:
        np.testing.assert_allclose(lean.center_mass, ref.center_mass, rtol=1e-9, atol=1e-15)
        scale = np.abs(ref.moment_inertia).max()
        np.testing.assert_allclose(lean.moment_inertia, ref.moment_inertia, rtol=1e-7, atol=1e-9 * scale)


@pytest.mark.parametrize("name", FILES)
def test_lean_facts_are_trimesh_facts(name):
    path = ROBOTS / name
    try:
        ref = _trimesh_facts(path)
    except M.MeshError as exc:
        with pytest.raises(M.MeshError) as lean_exc:
            M.facts(path)
        assert str(lean_exc.value) == str(exc) == "anymal_foot.dae holds no triangles"
        return
    lean = M.facts(path)
    assert lean.reader == path.suffix.lower().lstrip(".")      # read without trimesh
    _same(lean, ref)


def test_real_numbers_of_a_closed_mesh():
    """ur5's collision base: closed and outward; its volume by the signed tetrahedra of the raw STL
    triangles (no merge, another formula), its size and faces as trimesh 4.x/5.x gives them."""
    path = ROBOTS / "ur_description/meshes/ur5/collision/base.stl"
    f = M.facts(path)
    raw = np.frombuffer(path.read_bytes(), np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]),
                        offset=84)["v"].astype(np.float64)
    volume = np.einsum("ij,ij->i", raw[:, 0], np.cross(raw[:, 1], raw[:, 2])).sum() / 6
    assert f.is_volume and f.n_faces == len(raw) == 578
    assert f.volume == pytest.approx(volume, rel=1e-12) == pytest.approx(0.000347546637520049, rel=1e-12)
    np.testing.assert_allclose(f.extents, [0.14721271, 0.18355154, 0.0240027], rtol=1e-6)
    np.testing.assert_allclose(f.center_mass, [1.85407484e-05, -7.55011851e-04, 7.87396865e-03], rtol=1e-6)
    assert np.all(np.linalg.eigvalsh(f.moment_inertia) > 0)


def test_scale_and_mirror_as_trimesh(tmp_path):
    """A URDF scale is applied as trimesh's apply_transform: a mirror (one negative factor) turns the
    faces back, so the mesh stays a positive volume."""
    path = ROBOTS / "ur_description/meshes/ur5/collision/base.stl"
    for scale in ((0.001, 0.001, 0.001), (-1.0, 1.0, 1.0), (2.0, 1.0, 0.5)):
        _same(M.facts(path, scale), _trimesh_facts(path, scale))
        assert M.facts(path, scale).volume > 0


def test_tetrahedron_volume_and_open_and_inverted(tmp_path):
    """Binary STL tetrahedra written here: volume s³/6; one face missing is open; wound inward is a
    closed surface of negative volume (M004)."""
    import trimesh

    for kind, kw in (("closed", {}), ("open", {"open_": True}), ("flipped", {"flipped": True})):
        ascii_path = tmp_path / f"{kind}.ascii.stl"
        ascii_path.write_text(tetrahedron_stl(0.1, **kw))
        binary = tmp_path / f"{kind}.stl"
        trimesh.load(str(ascii_path), process=False).export(str(binary))
        f = M.facts(binary)
        assert f.reader == "stl"
        if kind == "closed":
            assert f.is_volume and f.volume == pytest.approx(0.1 ** 3 / 6, rel=1e-6)
        elif kind == "open":
            assert not f.is_watertight and not f.is_volume
        else:
            assert f.is_watertight and f.volume == pytest.approx(-0.1 ** 3 / 6, rel=1e-6) and not f.is_volume
        _same(f, _trimesh_facts(binary))


def test_triangle_limit_before_anything_is_kept(tmp_path, monkeypatch):
    monkeypatch.setenv(M.ENV_TRIANGLES, "100")
    with pytest.raises(M.MeshError, match="over the 100 limit"):
        M.facts(ROBOTS / "b1_description/meshes/trunk.dae")


def test_principal_moments_match_numpy():
    from myrabot_desc.model.inertia import principal_moments as principal
    from myrabot_desc.model.parts import Inertial

    ine = Inertial(mass=0.001, origin=None, ixx=9e-08, iyy=3.5e-08, izz=1e-08, ixy=0.0, ixz=6.3e-08, iyz=0.0)
    ev = principal(ine)
    np.testing.assert_allclose(ev, np.linalg.eigvalsh(ine.tensor()), rtol=1e-12, atol=1e-20)
    assert ev[0] == pytest.approx(-2.463e-08, rel=1e-3)    # I004's example: not positive definite


def test_what_the_lean_readers_do_not_read_goes_through_trimesh(tmp_path):
    """Two solids in one ASCII STL (trimesh keeps them apart) and a PLY: trimesh's facts."""
    two = tmp_path / "two.stl"
    two.write_text(tetrahedron_stl(0.1) + tetrahedron_stl(0.1).replace("solid tetrahedron", "solid second"))
    f = M.facts(two)
    assert f.reader == "trimesh" and f.n_faces == 8
    _same(f, _trimesh_facts(two))
    import trimesh

    ply = tmp_path / "t.ply"
    trimesh.load(str(ROBOTS / "ur_description/meshes/ur5/collision/base.stl")).export(str(ply))
    g = M.facts(ply)
    assert g.reader == "trimesh" and g.is_volume
    assert g.volume == pytest.approx(M.facts(ROBOTS / "ur_description/meshes/ur5/collision/base.stl").volume,
                                     rel=1e-9)


def test_malformed_numbers_fall_back_to_trimesh(tmp_path):
    """A vertex line numpy cannot read to its end: the lean reader steps aside, trimesh decides."""
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1x\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
    try:
        ref = _trimesh_facts(bad)
    except M.MeshError as exc:
        with pytest.raises(M.MeshError) as got:
            M.facts(bad)
        assert str(got.value) == str(exc)
        return
    f = M.facts(bad)
    assert f.reader == "trimesh"
    _same(f, ref)


@pytest.mark.parametrize("faces", [
    [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],                 # closed, outward
    [[0, 2, 1], [0, 1, 3], [0, 3, 2]],                            # open
    [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 3, 2]],                 # closed, one face turned
    [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3], [0, 1, 4], [1, 0, 4]],   # an edge of four faces
    [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3], [0, 0, 1]],      # a degenerate face
])
def test_watertight_and_winding_as_trimesh(faces):
    import trimesh

    f = np.array(faces)
    mesh = trimesh.Trimesh(np.random.default_rng(1).random((5, 3)), f, process=False)
    assert M._watertight(f) == (mesh.is_watertight, mesh.is_winding_consistent)
