"""convert --to mjcf reads COLLADA meshes with the lean reader (model/meshes.lean_triangles) and writes
their binary STL itself (convert/mjcf/assets.stl_bytes): the same bytes as trimesh's read and export,
without trimesh's import (and scipy's with it)."""

from __future__ import annotations

import subprocess
import sys

import pytest
from helpers import CORPUS, corpus_args, corpus_robot

from myrabot_desc.convert.mjcf.assets import stl_bytes
from myrabot_desc.model import meshes as meshio

DAE = sorted((CORPUS / "ur_description" / "meshes" / "ur5e" / "visual").glob("*.dae"))


@pytest.mark.parametrize("path", DAE[:4], ids=lambda p: p.name)
def test_lean_stl_equals_trimesh_export(path):
    lean = meshio.lean_triangles(path)
    assert lean is not None
    assert stl_bytes(*lean) == meshio.load(path, process=False).export(file_type="stl")


def test_lean_reader_leaves_other_formats_and_broken_files_to_trimesh(tmp_path):
    assert meshio.lean_triangles(CORPUS / "p2os_urdf" / "meshes" / "p3at_meshes" / "chassis.stl") is None
    bad = tmp_path / "bad.dae"
    bad.write_text("<COLLADA><library_geometries></COLLADA>")
    assert meshio.lean_triangles(bad) is None


def test_convert_mjcf_of_a_dae_robot_imports_no_trimesh(tmp_path):
    argv = ["convert", "--to", "mjcf", *corpus_args(corpus_robot("ur5e")), "-o", str(tmp_path / "o" / "u.xml")]
    code = ("import sys; from click.testing import CliRunner; from myrabot_desc.commands.main import main;"
            f"r = CliRunner().invoke(main, {argv!r});"
            "print(r.exit_code, sorted(m for m in ('trimesh', 'scipy', 'networkx') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.split(None, 1) == ["0", "[]\n"]
    assert any(p.suffix == ".stl" for p in (tmp_path / "o" / "u_meshes").iterdir())
