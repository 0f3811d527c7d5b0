"""The mesh files an MJCF model uses: which MuJoCo reads as they are, which are converted, under
which names, and the mesh assets of the spec.

MuJoCo reads STL (binary, at most 200000 faces), OBJ and its own MSH; it reads no DAE and keys
meshes by name. Every mesh file a geometry names is copied into ``<OUT stem>_meshes/`` next to the
output under a unique file name; a file in another format (DAE, PLY, an ASCII or oversized STL...)
is read with trimesh (model/meshes.py, with its size and triangle limits) and written as binary
STL, or as MSH past 200000 faces. A COLLADA file that pycollada half rejects is read leniently.
A file that cannot be read leaves its geometry out, said once, with why.

One mesh asset per file and scale (``stem``; the same file at another scale ``stem_2``...).
"""

from __future__ import annotations

from pathlib import Path

from myrabot_desc.model import meshes as meshio

MUJOCO_MESH_EXT = {".stl", ".obj", ".msh"}
STL_MAX_FACES = 200000


class MeshPlan:
    """Mesh files and assets, planned while the bodies are built; written into the output folder."""

    def __init__(self, notes):
        self.notes = notes
        self.files: dict[Path, str | None] = {}      # resolved source -> file name in the mesh folder (None: unusable)
        self.loaded: dict[Path, object] = {}         # converted meshes (Triangles or trimesh), by source
        self.why: dict[Path, str] = {}               # source -> why it cannot be used
        self.assets: dict[tuple, str] = {}           # (source, scale) -> mesh asset name
        self.missing: list[str] = []
        self.empty: list[str] = []
        self.converted: list[str] = []
        self._file_names: set[str] = set()
        self._asset_names: set[str] = set()

    def source(self, geometry) -> Path | None:
        """The mesh file of a model.Mesh, or None (recorded as missing) when it cannot be found."""
        src = geometry.path
        if src is None or not Path(src).is_file():
            self.missing.append(geometry.filename)
            return None
        return Path(src).resolve()

    def asset(self, src: Path, scale) -> str | None:
        """The mesh asset for this file at this scale, or None when the file cannot be used."""
        fname = self._file_name(src)
        if fname is None:
            return None
        key = (src, tuple(float(s) for s in scale))
        name = self.assets.get(key)
        if name is None:
            stem = Path(fname).stem
            name, k = stem, 2
            while name.lower() in self._asset_names:
                name, k = f"{stem}_{k}", k + 1
            self._asset_names.add(name.lower())
            self.assets[key] = name
        return name

    def is_converted(self, src: Path) -> bool:
        return src in self.loaded

    def file_name(self, src: Path) -> str | None:
        return self.files.get(src)

    def _file_name(self, src: Path) -> str | None:
        if src in self.files:
            return self.files[src]
        ext = src.suffix.lower()
        try:  # size and triangle limits before anything reads or copies it
            meshio.precheck(src)
        except meshio.MeshError as exc:
            return self._unusable(src, str(exc), warn=True)
        if ext not in MUJOCO_MESH_EXT or (ext == ".stl" and not binary_stl_ok(src)):
            # the lean COLLADA reader gives trimesh's triangles without its import (~1 s with
            # scipy); trimesh reads the other formats, the files the lean reader leaves to it,
            # and the meshes too big for STL (MSH keeps trimesh's own vertex list)
            lean = meshio.lean_triangles(src)
            if lean is not None and 0 < len(lean[1]) <= STL_MAX_FACES:
                mesh = Triangles(*lean)
            else:
                try:
                    mesh = meshio.load(src, process=False)
                except meshio.MeshError as exc:  # unreadable: leave the geometry out, say which file and why
                    mesh = meshio.lenient_dae(src, self.notes) \
                        if ext == ".dae" and "holds no triangles" in str(exc) else None
                    if mesh is None:
                        return self._unusable(src, str(exc), warn=True)
            if mesh is None or mesh.is_empty or len(mesh.faces) == 0:
                self.empty.append(src.name)
                return self._unusable(src, "holds no triangles")
            # MuJoCo's STL reader takes binary files of at most 200000 faces; its own MSH has no such
            # limit and is written in milliseconds (OBJ text took seconds for a 350k-face trunk)
            out_ext = ".stl" if len(mesh.faces) <= STL_MAX_FACES else ".msh"
            self.loaded[src] = mesh
            self.converted.append(src.name)
        else:
            out_ext = ext
        stem = "".join(ch if ch.isalnum() or ch in "-_" else "_" for ch in src.stem) or "mesh"
        name, k = f"{stem}{out_ext}", 2
        while name.lower() in self._file_names:
            name, k = f"{stem}_{k}{out_ext}", k + 1
        self._file_names.add(name.lower())
        self.files[src] = name
        return name

    def _unusable(self, src: Path, why: str, warn: bool = False) -> None:
        if warn:
            self.notes.warn(f"mesh {src.name}: {why}; geometry left out")
        self.why[src] = why
        self.files[src] = None
        return None

    def add_to(self, spec) -> None:
        """The mesh assets, in the order the geometries first named them."""
        files = {}
        for (src, scale), name in self.assets.items():
            files[name] = (self.files[src], scale)
        for name, (fname, scale) in files.items():
            spec.add_mesh(name=name, file=fname, scale=list(scale))

    def warn_left_out(self) -> None:
        if self.missing:
            shown = ", ".join(sorted(set(self.missing))[:5])
            self.notes.warn(f"{len(self.missing)} mesh geometry(ies) left out: file not found ({shown})")
        if self.empty:
            self.notes.warn(f"{len(self.empty)} mesh file(s) with no triangles left out: "
                            f"{', '.join(sorted(set(self.empty)))}")

    @property
    def used(self) -> bool:
        return bool(self.assets)

    def write(self, folder: Path) -> None:
        """Copy or convert every file an asset uses into ``folder``."""
        import shutil

        folder.mkdir(parents=True, exist_ok=True)
        used = {src for src, _ in self.assets}
        for src, name in sorted(((s, n) for s, n in self.files.items() if n and s in used), key=lambda kv: kv[1]):
            dest = folder / name
            mesh = self.loaded.get(src)
            if mesh is None:
                shutil.copyfile(src, dest)
            elif dest.suffix == ".msh":
                write_msh(dest, mesh)
            else:
                mesh.export(str(dest), file_type="stl")


class Triangles:
    """A mesh read by the lean readers, with the parts of trimesh's Trimesh this module uses."""

    def __init__(self, vertices, faces):
        self.vertices, self.faces = vertices, faces

    @property
    def is_empty(self) -> bool:
        return len(self.faces) == 0

    def export(self, dest: str, file_type: str = "stl") -> None:
        if file_type != "stl":
            raise ValueError(f"cannot write {file_type}")
        Path(dest).write_bytes(stl_bytes(self.vertices, self.faces))


def stl_bytes(vertices, faces) -> bytes:
    """Binary STL as trimesh's export writes it: an 80-byte zero header, the face count, and per
    face its unit normal (cross product of the edges v1 - v0 and v2 - v1; zero for a face whose
    cross product is below 100 float64 resolutions), its corners as float32, and a zero attribute."""
    import numpy as np

    tri = np.asarray(vertices, dtype=np.float64)[np.asarray(faces)]
    edges = tri[:, 1:, :] - tri[:, :2, :]
    cross = np.cross(edges[:, 0], edges[:, 1])
    norm = np.sqrt(np.dot(cross * cross, [1.0, 1.0, 1.0]))
    valid = norm > float(np.finfo(np.float64).resolution * 100)
    norm[valid] **= -1
    unit = cross * norm.reshape((-1, 1))
    normals = np.zeros((len(tri), 3), dtype=np.float64)
    normals[valid] = unit[valid]
    packed = np.zeros(len(tri), dtype=np.dtype([("normals", "<f4", (3)), ("vertices", "<f4", (3, 3)),
                                                ("attributes", "<u2")]))
    packed["normals"] = normals
    packed["vertices"] = tri
    return bytes(80) + len(tri).to_bytes(4, "little") + packed.tobytes()


def write_msh(dest: Path, mesh) -> None:
    """MuJoCo's binary MSH: int32 nvertex, nnormal, ntexcoord, nface; float32 vertices; int32 faces."""
    import numpy as np

    v = np.ascontiguousarray(mesh.vertices, dtype="<f4")
    f = np.ascontiguousarray(mesh.faces, dtype="<i4")
    with open(dest, "wb") as fh:
        fh.write(np.array([len(v), 0, 0, len(f)], dtype="<i4").tobytes())
        fh.write(v.tobytes())
        fh.write(f.tobytes())


def binary_stl_ok(path: Path) -> bool:
    """A binary STL MuJoCo can read: size = 84 + 50 n with 1 <= n <= 200000."""
    try:
        size = path.stat().st_size
        with open(path, "rb") as fh:
            head = fh.read(84)
    except OSError:
        return False
    if len(head) < 84:
        return False
    n = int.from_bytes(head[80:84], "little")
    return size == 84 + 50 * n and 1 <= n <= STL_MAX_FACES
