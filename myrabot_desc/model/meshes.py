"""Load mesh files from untrusted models with size and triangle limits.

check (--inertia, --meshes), convert --to mjcf and sim read meshes named by model files. A
mesh is refused before trimesh sees it when the file is larger than ``max_mesh_bytes`` or a
binary STL header announces more than ``max_mesh_triangles`` faces; after loading, when it
holds more triangles than that. Both limits are in safety.LIMITS
(MYRABOT_DESC_MAX_MESH_BYTES, MYRABOT_DESC_MAX_MESH_TRIANGLES).
"""

from __future__ import annotations

import os
import struct
from pathlib import Path

from myrabot_desc.errors import InputError

ENV_BYTES = "MYRABOT_DESC_MAX_MESH_BYTES"
ENV_TRIANGLES = "MYRABOT_DESC_MAX_MESH_TRIANGLES"


class MeshError(ValueError):
    """A mesh that cannot or may not be loaded (message names the file and why)."""


def limits() -> tuple[int, int]:
    from myrabot_desc.safety import limit

    return limit("max_mesh_bytes"), limit("max_mesh_triangles")


def precheck(path: Path) -> int:
    """Refuse a mesh file by size or announced face count before parsing it; returns its size."""
    max_bytes, max_tris = limits()
    try:
        if not path.is_file():      # also refuses FIFOs and devices (is_file: regular files only)
            raise MeshError(f"{path.name} is not a file")
        size = path.stat().st_size
    except OSError as exc:
        raise MeshError(f"cannot read {path.name}: {exc.strerror}") from None
    if size == 0:
        raise MeshError(f"{path.name} is empty (0 bytes)")
    if size > max_bytes:
        raise MeshError(f"{path.name} is {size} bytes, over the {max_bytes}-byte mesh limit ({ENV_BYTES})")
    if path.suffix.lower() == ".stl" and size >= 84:
        try:
            with open(path, "rb") as fh:
                head = fh.read(84)
        except OSError as exc:
            raise MeshError(f"cannot read {path.name}: {exc.strerror}") from None
        if not head[:5].lower() == b"solid":
            n = struct.unpack("<I", head[80:84])[0]
            if n > max_tris:
                raise MeshError(f"{path.name}: the STL header announces {n} triangles, over the {max_tris} "
                                f"limit ({ENV_TRIANGLES})")
    return size


ZIP_EXTS = {".zip", ".3mf", ".zae"}
MAX_ARCHIVE_MEMBERS = 10_000


def _read(path: Path, max_bytes: int) -> bytes:
    """The mesh's bytes: a regular file only (a FIFO or device would block or never end)."""
    from myrabot_desc.safety import read_checked

    try:
        return read_checked(path, None, max_bytes, what="mesh")
    except InputError as exc:
        raise MeshError(f"{path.name}: {exc.message}") from None


def _check_archive(path: Path, data: bytes, max_bytes: int) -> None:
    """A zip/3MF is limited by what it inflates to, not by its size on disk (a 1.5 MB zip can
    hold 2 GB). zipfile stops each member at its declared size, so the declared sizes bound it."""
    import io
    import zipfile

    try:
        with zipfile.ZipFile(io.BytesIO(data)) as z:
            infos = z.infolist()
    except (zipfile.BadZipFile, ValueError, OSError) as exc:
        raise MeshError(f"{path.name}: not a readable zip archive ({exc})") from None
    if len(infos) > MAX_ARCHIVE_MEMBERS:
        raise MeshError(f"{path.name} holds {len(infos)} files, over {MAX_ARCHIVE_MEMBERS}")
    total = sum(i.file_size for i in infos)
    if total > max_bytes:
        raise MeshError(f"{path.name} inflates to {total} bytes, over the {max_bytes}-byte mesh limit ({ENV_BYTES})")


def _resolver(path: Path, max_bytes: int):
    """trimesh's resolver for the files a mesh names (OBJ mtllib, DAE images, glTF buffers): inside
    the mesh's folder (trimesh's own rule), regular files only, each within the mesh byte limit."""
    from trimesh.resolvers import FilePathResolver

    from myrabot_desc.safety import read_checked

    class Resolver(FilePathResolver):
        def get(self, name):
            for candidate in (name.strip(), name.strip().lstrip("/"), os.path.split(name)[-1]):
                try:
                    p = self.absolute(candidate)
                except ValueError:
                    continue
                if p.exists():
                    return read_checked(p, [Path(self.parent).resolve()], max_bytes, what="file")
            self.absolute(name)
            raise FileNotFoundError(name)

    return Resolver(str(path))


def load(path: Path, process: bool = True, textures: bool = True):
    """trimesh.Trimesh of ``path`` (one mesh), or MeshError saying why not.

    ``textures=False`` opens no file but ``path`` (geometry only): a Collada file's JPEG
    textures took 80% of the time and 370 MB for anymal_c's meshes in ``check --inertia``."""
    import io

    import trimesh

    path = Path(path)
    precheck(path)
    max_bytes, max_tris = limits()
    data = _read(path, max_bytes)
    ext = path.suffix.lower()
    if ext in ZIP_EXTS or data[:4] == b"PK\x03\x04":
        _check_archive(path, data, max_bytes)
    try:
        resolver = _resolver(path, max_bytes) if textures else _NoFiles()
        mesh = trimesh.load(io.BytesIO(data), file_type=ext.lstrip(".") or None, force="mesh", process=process,
                            resolver=resolver)
    except (RecursionError, MemoryError) as exc:
        raise MeshError(f"cannot read {path.name}: {type(exc).__name__}") from None
    except Exception as exc:  # every reader has its own errors: one line naming the file
        msg = " ".join(str(exc).split())[:200]
        raise MeshError(f"cannot read {path.name}: {type(exc).__name__}: {msg}") from None
    if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
        raise MeshError(f"{path.name} holds no triangles")
    if len(mesh.faces) > max_tris:
        raise MeshError(f"{path.name} has {len(mesh.faces)} triangles, over the {max_tris} limit ({ENV_TRIANGLES})")
    import numpy as np

    if not np.isfinite(mesh.vertices).all():
        raise MeshError(f"{path.name} has vertices that are not finite numbers (NaN or inf)")
    return mesh


def load_or_input_error(path: Path, loc=None):
    """``load`` for callers that stop on a bad mesh: InputError with the model's file:line."""
    try:
        return load(path)
    except MeshError as exc:
        raise InputError(f"mesh {exc}", loc) from None


def vertices(path: Path, loc=None):
    """The distinct vertices (n, 3) of a mesh's triangles, for extents and hulls; InputError like
    ``load_or_input_error``.

    A well-formed binary STL (size = 84 + 50 n) is read directly: trimesh takes ~2 ms a file for
    the same numbers (its STL reader also reads float32). Anything else goes through ``load``.
    """
    import numpy as np

    path = Path(path)
    try:
        size = precheck(path)
        if path.suffix.lower() == ".stl" and size >= 84:
            data = _read(path, limits()[0])
            n = struct.unpack("<I", data[80:84])[0]
            if data[:5].lower() != b"solid" and n > 0 and len(data) == 84 + 50 * n:
                rec = np.frombuffer(data, np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]),
                                    count=n, offset=84)
                v = rec["v"].reshape(-1, 3).astype(np.float64)
                if not np.isfinite(v).all():
                    raise MeshError(f"{path.name} has vertices that are not finite numbers (NaN or inf)")
                return np.unique(v, axis=0)
        m = load(path)
    except OSError as exc:
        raise InputError(f"mesh cannot read {path.name}: {exc.strerror}", loc) from None
    except MeshError as exc:
        raise InputError(f"mesh {exc}", loc) from None
    return np.asarray(m.vertices)


def _NoFiles():
    """A trimesh resolver that serves no file (textures, .mtl): geometry comes from the mesh file."""
    from trimesh.resolvers import Resolver

    class NoFiles(Resolver):
        def __init__(self, *args, **kwargs):
            pass

        def get(self, name):
            raise FileNotFoundError(name)

        def write(self, name, data):
            raise OSError("read-only")

        def keys(self):
            return []

        def namespaced(self, namespace):
            return self

    return NoFiles()


def lenient_dae(path: Path, notes):
    """A COLLADA file trimesh reads as empty because pycollada rejects part of it (a malformed
    colour such as ``0.0 0.0 0.01.0`` drops the geometry's scene node): read the geometries with
    pycollada ignoring the broken parts, and place them by the visual scene's node transforms
    read from the XML. None when that finds no triangle either. ``notes.warn`` says what was done
    (convert --to mjcf uses it; the file has passed ``precheck``)."""
    import numpy as np
    import trimesh

    from myrabot_desc.safety import parse_xml_bytes

    try:
        import collada
        from collada.common import DaeBrokenRefError, DaeMalformedError, DaeUnsupportedError

        try:
            collada.Collada(str(path))
            reason = "a broken part"
        except Exception as exc:  # the strict read's reason, for the message
            reason = " ".join(str(exc).split())[:160]
        c = collada.Collada(str(path), ignore=[DaeMalformedError, DaeUnsupportedError, DaeBrokenRefError])
        by_id = {}
        for g in c.geometries:
            tris = []
            for prim in g.primitives:
                ts = prim if isinstance(prim, collada.triangleset.TriangleSet) else \
                    (prim.triangleset() if hasattr(prim, "triangleset") else None)
                if ts is not None and len(ts.vertex_index):
                    tris.append(np.asarray(ts.vertex)[np.asarray(ts.vertex_index)].reshape(-1, 3))
            if tris:
                by_id[g.id] = np.concatenate(tris)
        root = parse_xml_bytes(path.read_bytes(), str(path))
    except Exception:
        return None

    def local(el):
        return el.tag.rsplit("}", 1)[-1] if isinstance(el.tag, str) else ""

    def node_T(node):
        T = np.eye(4)
        for t in node:
            vals = [float(x) for x in (t.text or "").split()] if local(t) in ("matrix", "translate", "rotate",
                                                                              "scale") else None
            M = np.eye(4)
            if local(t) == "matrix" and len(vals) == 16:
                M = np.array(vals).reshape(4, 4)
            elif local(t) == "translate" and len(vals) == 3:
                M[:3, 3] = vals
            elif local(t) == "scale" and len(vals) == 3:
                M = np.diag(vals + [1.0])
            elif local(t) == "rotate" and len(vals) == 4:
                a = np.asarray(vals[:3]) / (np.linalg.norm(vals[:3]) or 1.0)
                th = np.radians(vals[3])
                K = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
                M[:3, :3] = np.eye(3) + np.sin(th) * K + (1 - np.cos(th)) * K @ K
            T = T @ M
        return T

    parts = []

    def walk(node, T):
        T = T @ node_T(node)
        for ch in node:
            if local(ch) == "instance_geometry":
                v = by_id.get((ch.get("url") or "").lstrip("#"))
                if v is not None:
                    parts.append(v @ T[:3, :3].T + T[:3, 3])
            elif local(ch) == "node":
                walk(ch, T)

    for scene in (el for el in root.iter() if local(el) == "visual_scene"):
        for node in scene:
            if local(node) == "node":
                walk(node, np.eye(4))
    if not parts:
        parts = list(by_id.values())
    if not parts:
        return None
    v = np.concatenate(parts)
    mesh = trimesh.Trimesh(vertices=v, faces=np.arange(len(v)).reshape(-1, 3), process=False)
    notes.warn(f"mesh {path.name}: pycollada rejects it ({reason}) and trimesh then sees no triangles; its "
               f"{len(mesh.faces)} triangles were read ignoring the broken part")
    return mesh
