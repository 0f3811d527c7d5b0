"""Load mesh files from untrusted models with size and triangle limits.

check (--inertia, --meshes), convert --to mjcf and sim read meshes named by model files. A
mesh is refused before any reader builds an array from it (``_read``: every path reads the bytes
there) when

* the file is larger than ``max_mesh_bytes``, or a compressed one (zip/3MF/ZAE by the sizes its
  directory declares, gzip/bzip2/xz by inflating it in bounded steps, whatever its name) would
  inflate past that; zstd and other compressions no reader here takes are refused;
* it announces or holds more than ``max_mesh_triangles`` triangles, counted on the bytes before
  parsing: a binary STL's header, an ASCII STL's ``facet`` words, a PLY header's face count, an
  OBJ's polygon corners (one 7-million-corner polygon is 7 million triangles), a COLLADA file's
  index numbers;
* a COLLADA file has more than ``max_mesh_elements`` elements (3 million ``<p>``: seconds of
  parsing and a gigabyte before a single triangle), counted as tags in the bytes.

After loading, a mesh with more triangles than the limit is refused too. The limits are in
safety.LIMITS (MYRABOT_DESC_MAX_MESH_BYTES, _TRIANGLES, _ELEMENTS).
"""

from __future__ import annotations

import os
import struct
from pathlib import Path

from myrabot_desc import xmltree
from myrabot_desc.errors import InputError
from myrabot_desc.safety import check_xml_bytes, limit, open_checked, parse_xml_bytes, read_checked, safe_parser

ENV_BYTES = "MYRABOT_DESC_MAX_MESH_BYTES"
ENV_TRIANGLES = "MYRABOT_DESC_MAX_MESH_TRIANGLES"


class MeshError(ValueError):
    """A mesh that cannot or may not be loaded (message names the file and why)."""


def limits() -> tuple[int, int]:
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
        if not head[:5].lower() == b"solid" and not any(head.startswith(m) for m in COMPRESSED):
            n = struct.unpack("<I", head[80:84])[0]
            if n > max_tris:
                raise MeshError(f"{path.name}: the STL header announces {n} triangles, over the {max_tris} "
                                f"limit ({ENV_TRIANGLES})")
    return size


def unreadable(path: Path) -> str | None:
    """Why a mesh file holds no triangles a reader can take, or None: the limits (``precheck``, and
    ``check_content`` on its bytes: compression, counts), then a structural look without numpy: a
    binary STL's size must match its header, an ASCII STL needs a facet, an OBJ a face, a COLLADA
    file must be XML with a triangle, polygon or polylist element with a count. (check's M005 and
    convert's preflight ask it of collision meshes.)"""
    try:
        size = precheck(path)
        ext = path.suffix.lower()
        with open_checked(path, None, "mesh") as fh:
            head = fh.read(84)
        if ext == ".stl" and head[:5].lower() != b"solid" and not any(head.startswith(m) for m in COMPRESSED):
            n = int.from_bytes(head[80:84], "little") if len(head) >= 84 else -1
            if n <= 0 or size != 84 + 50 * n:
                return (f"{path.name} is not a binary STL ({size} bytes, its header announces {n} triangles)"
                        if n > 0 else f"{path.name} holds no triangles")
            return None                   # a well-formed binary STL: its header said it all (precheck)
        data = _read(path, limit("max_mesh_bytes"))          # check_content: compression, counts, elements
    except MeshError as exc:
        return str(exc)
    except InputError as exc:
        return f"cannot read {path.name}: {exc.message}"
    if ext not in (".stl", ".obj", ".dae") or any(data.startswith(m) for m in COMPRESSED) or data[:4] == b"PK\x03\x04":
        return None
    if ext == ".stl":
        if b"facet" in data:
            return None
        # a binary STL whose 80-byte header starts with "solid": readers check the size instead
        n = int.from_bytes(data[80:84], "little") if len(data) >= 84 else 0
        return None if n > 0 and size == 84 + 50 * n else f"{path.name} holds no triangles (no facet)"
    if ext == ".obj":
        return None if data.startswith(b"f ") or b"\nf " in data else f"{path.name} holds no faces"
    try:
        try:            # expat, already loaded, where it reads the file as lxml would (xmltree.py)
            check_xml_bytes(data, path.name)
            found = xmltree.any_element(data, _counted_primitive)
        except xmltree.Refused:
            root = parse_xml_bytes(data, path.name)
            found = any(_counted_primitive(el.tag.rsplit("}", 1)[-1] if isinstance(el.tag, str) else "", el.attrib)
                        for el in root.iter())
    except InputError as exc:
        return f"{path.name} is not readable COLLADA: {exc.message}"
    return None if found else f"{path.name} holds no triangles (no <triangles>, <polylist> or <polygons> with a count)"


_DAE_PRIMITIVES = {"triangles", "polylist", "polygons", "trifans", "tristrips"}


def _counted_primitive(tag: str, attrs) -> bool:
    """A COLLADA element (local name, attributes) that lists faces: a primitive with a count."""
    return tag in _DAE_PRIMITIVES and attrs.get("count", "0") != "0"


ZIP_EXTS = {".zip", ".3mf", ".zae"}
MAX_ARCHIVE_MEMBERS = 10_000


def _read(path: Path, max_bytes: int) -> bytes:
    """The mesh's bytes: a regular file only (a FIFO or device would block or never end), checked
    by :func:`check_content` before anything parses them."""

    try:
        data = read_checked(path, None, max_bytes, what="mesh")
    except InputError as exc:
        raise MeshError(f"{path.name}: {exc.message}") from None
    check_content(path, data)
    return data


DAE_STRIDE = 4          # index numbers per corner (VERTEX, NORMAL, TEXCOORD, COLOR)
COMPRESSED = {b"\x1f\x8b": "gzip", b"BZh": "bzip2", b"\xfd7zXZ\x00": "xz", b"(\xb5/\xfd": "zstd",
              b"\x5d\x00\x00": "lzma"}
INFLATE_STEP = 1 << 20


def check_content(path: Path, data: bytes) -> None:
    """The limits on a mesh's bytes (see the module docstring); MeshError naming the file and why."""
    max_bytes = limit("max_mesh_bytes")
    max_tris = limit("max_mesh_triangles")
    ext = path.suffix.lower()
    if ext in ZIP_EXTS or data[:4] == b"PK\x03\x04" or ext == ".3dxml":
        _check_archive(path, data, max_bytes)
        return
    kind = next((k for magic, k in COMPRESSED.items() if data.startswith(magic)), None)
    if kind is not None:
        _check_inflated(path, data, kind, max_bytes)
        return
    n = _announced_triangles(ext, data)
    if n is not None and n > max_tris:
        raise MeshError(f"{path.name} holds {n} triangles, over the {max_tris} limit ({ENV_TRIANGLES})")
    if ext == ".dae" or data.lstrip()[:5] in (b"<?xml", b"<COLL"):
        # every element has a '<' that does not start an end tag: an upper bound, counted in C
        n = data.count(b"<") - data.count(b"</")
        most = limit("max_mesh_elements")
        if n > most:
            raise MeshError(f"{path.name} has {n} XML elements, over the {most} limit "
                            "(MYRABOT_DESC_MAX_MESH_ELEMENTS)")


def _check_inflated(path: Path, data: bytes, kind: str, max_bytes: int) -> None:
    """Inflate ``data`` in bounded steps (nothing kept), refusing it past ``max_bytes``; several
    concatenated streams count together (as bz2/gzip readers read them)."""
    import bz2
    import lzma
    import zlib

    makers = {"gzip": lambda: zlib.decompressobj(31), "bzip2": bz2.BZ2Decompressor, "xz": lzma.LZMADecompressor,
              "lzma": lambda: lzma.LZMADecompressor(format=lzma.FORMAT_ALONE)}
    if kind not in makers:
        raise MeshError(f"{path.name} is {kind}-compressed, which no mesh reader here takes")
    total, rest, streams = 0, data, 0
    try:
        while rest:
            streams += 1
            if streams > MAX_ARCHIVE_MEMBERS:
                raise MeshError(f"{path.name} holds over {MAX_ARCHIVE_MEMBERS} compressed streams")
            d = makers[kind]()
            if kind == "gzip":
                out = d.decompress(rest, INFLATE_STEP)
                total += len(out)
                while d.unconsumed_tail and total <= max_bytes:
                    out = d.decompress(d.unconsumed_tail, INFLATE_STEP)
                    total += len(out)
                rest = d.unused_data if d.eof else b""
            else:
                out = d.decompress(rest, max_length=INFLATE_STEP)
                total += len(out)
                while not d.eof and not d.needs_input and total <= max_bytes:
                    out = d.decompress(b"", max_length=INFLATE_STEP)
                    total += len(out)
                rest = d.unused_data if d.eof else b""
            if total > max_bytes:
                raise MeshError(f"{path.name} inflates to over {max_bytes} bytes, over the mesh limit ({ENV_BYTES})")
            rest = rest.lstrip(b"\x00")
    except MeshError:
        raise
    except (OSError, EOFError, ValueError, lzma.LZMAError, zlib.error) as exc:
        raise MeshError(f"{path.name}: not a readable {kind} stream ({exc})") from None


def _count_tokens(text) -> int:
    """Whitespace-separated tokens of a (possibly huge) str or bytes, without a list of them."""
    if len(text) < 1_000_000:
        return len(text.split())
    import numpy as np

    b = np.frombuffer(text.encode("utf-8", "replace") if isinstance(text, str) else text, dtype=np.uint8)
    space = (b == 32) | (b == 9) | (b == 10) | (b == 13) | (b == 11) | (b == 12)
    return int(np.count_nonzero(~space[1:] & space[:-1]) + (0 if space[0] else 1)) if len(b) else 0


def _announced_triangles(ext: str, data: bytes) -> int | None:
    """The triangles a file announces or holds, from its bytes alone (None: nothing cheap to say)."""
    import re

    if ext == ".stl":
        if data[:5].lower() == b"solid" and len(data) != 84 + 50 * int.from_bytes(data[80:84], "little"):
            return data.count(b"facet") // 2 or data.count(b"vertex") // 3
        return int.from_bytes(data[80:84], "little") if len(data) >= 84 else None
    if ext == ".ply":
        head = data[:4096]
        m = re.search(rb"element\s+face\s+(\d+)", head)
        return int(m.group(1)) if m else None
    if ext == ".obj":
        if data.count(b" ") + data.count(b"\t") < limit("max_mesh_triangles"):
            return None          # fewer separators than the limit: fewer corners too
        n = 0
        pos = 0
        while True:     # face lines: a polygon of k corners is k - 2 triangles (fanned)
            i = data.find(b"f ", pos)
            if i < 0:
                return n
            if i == 0 or data[i - 1:i] == b"\n":
                end = data.find(b"\n", i)
                end = len(data) if end < 0 else end
                n += max(_count_tokens(data[i + 2:end]) - 2, 0)
                pos = end
            else:
                pos = i + 2
    if ext == ".dae":
        # triangles are made of index numbers in <p> elements, three corners of 1 to DAE_STRIDE
        # numbers each: a file over the limit even at that stride is refused before any parse (the
        # lean reader counts each primitive exactly, with its stride, as it reads it)
        if data.count(b" ") < 3 * DAE_STRIDE * limit("max_mesh_triangles"):
            return None
        total = 0
        pos = 0
        while True:
            i = data.find(b"<p>", pos)
            if i < 0:
                return total // (3 * DAE_STRIDE)
            j = data.find(b"</p>", i)
            j = len(data) if j < 0 else j
            total += _count_tokens(data[i + 3:j])
            pos = j + 4
    return None


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
    data = _read(path, max_bytes)        # every limit on the bytes (archives, compression, counts)
    ext = path.suffix.lower()
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
    the same numbers (its STL reader also reads float32). Anything else goes through the lean
    readers (``triangles``: ``load``'s vertices), and trimesh only for what they do not read.
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
                return unique_rows(v)
        v, _f = _triangles(path, path.suffix.lower())    # the lean readers; trimesh for other formats
    except OSError as exc:
        raise InputError(f"mesh cannot read {path.name}: {exc.strerror}", loc) from None
    except MeshError as exc:
        raise InputError(f"mesh {exc}", loc) from None
    return np.asarray(v)


def unique_rows(v):
    """``np.unique(v, axis=0)`` of finite (n, 3) points, bit for bit, by one lexsort: several times
    faster on small meshes (numpy sorts the rows as records). A -0.0 makes the representative of
    equal rows depend on numpy's sort, so such an array goes to numpy itself."""
    import numpy as np

    if len(v) == 0 or (np.signbit(v) & (v == 0)).any():
        return np.unique(v, axis=0)
    s = v[np.lexsort((v[:, 2], v[:, 1], v[:, 0]))]
    keep = np.empty(len(s), dtype=bool)
    keep[0] = True
    keep[1:] = (s[1:] != s[:-1]).any(axis=1)
    return s[keep]


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
    if notes is not None:
        notes.warn(f"mesh {path.name}: pycollada rejects it ({reason}) and trimesh then sees no triangles; its "
                   f"{len(mesh.faces)} triangles were read ignoring the broken part")
    return mesh


# ------------------------------------------------------------------ the facts check needs
# ``check --inertia`` needs of a mesh only its vertices (extremes, lowest points), its size, whether it
# is a closed outward surface, and its volume, centroid and inertia. Building full trimesh scenes for
# that (pycollada's DOM, per-vertex visuals, caches) took ~6 s and ~300 MB over the 69
# example-robot-data robots; reading the triangles straight into numpy takes a fraction of both.
# The facts are trimesh's, computed the way it computes them for ``load(process=True)`` (vertices
# merged on 1e-8 m, and on normals and texture coordinates where the file gives them; each COLLADA
# primitive merged on its own, then placed), so check reports the same findings whichever reader
# ran. Files the lean readers do not fully understand go through trimesh.

MERGE_DIGITS = 8            # trimesh's tol.merge (1e-8): vertices closer than this are one vertex
NORMAL_DIGITS, UV_DIGITS = 2, 4
_HASH_MULT = (0x9E3779B97F4A7C15, 0xC2B2AE3D27D4EB4F, 0x165667B19E3779F9, 0xD6E8FEB86659FD93)
MASS_CHUNK = 200_000        # triangles per step of the volume integrals (bounds the temporary arrays)


class _NotLean(Exception):
    """The lean reader does not handle this file: trimesh reads it."""


class MeshFacts:
    """A mesh as check uses it, with trimesh's attribute names (vertices, faces, bounds, extents,
    volume, center_mass, moment_inertia, is_watertight, is_winding_consistent, is_volume) and
    ``n_faces``. The faces are kept for the self-collision test's triangles (read once for every
    rule)."""

    __slots__ = ("vertices", "faces", "n_faces", "volume", "center_mass", "moment_inertia", "is_watertight",
                 "is_winding_consistent", "reader", "_bounds")

    def __init__(self, vertices, faces, reader: str):
        self.vertices = vertices
        self.faces = faces
        self.n_faces = len(faces)
        self.reader = reader
        self.is_watertight, self.is_winding_consistent = _watertight(faces)
        closed = self.is_watertight and self.is_winding_consistent
        self.volume, self.center_mass, self.moment_inertia = _mass_properties(vertices, faces, closed)

    @classmethod
    def from_trimesh(cls, mesh) -> "MeshFacts":
        import numpy as np

        self = cls.__new__(cls)
        self.vertices = np.asarray(mesh.vertices, dtype=np.float64)
        self.faces = np.asarray(mesh.faces, dtype=np.int64)
        self.n_faces = len(self.faces)
        self.reader = "trimesh"
        self.is_watertight, self.is_winding_consistent = bool(mesh.is_watertight), bool(mesh.is_winding_consistent)
        self.volume = float(mesh.volume)
        self.center_mass = np.asarray(mesh.center_mass, dtype=np.float64)
        self.moment_inertia = np.asarray(mesh.moment_inertia, dtype=np.float64)
        return self

    @property
    def bounds(self):
        import numpy as np

        b = getattr(self, "_bounds", None)
        if b is None:
            b = self._bounds = np.array([self.vertices.min(axis=0), self.vertices.max(axis=0)])
        return b.copy()

    @property
    def extents(self):
        lo, hi = self.bounds
        return hi - lo

    @property
    def is_volume(self) -> bool:
        import numpy as np

        return bool(self.is_watertight and self.is_winding_consistent and np.isfinite(self.center_mass).all()
                    and self.volume > 0.0)


def facts(path: Path, scale=(1.0, 1.0, 1.0)) -> MeshFacts:
    """The MeshFacts of one mesh file with a URDF ``scale`` applied (limits as ``load``), or MeshError
    saying why not."""
    import numpy as np

    path = Path(path)
    precheck(path)
    max_bytes, max_tris = limits()
    ext = path.suffix.lower()
    S = np.diag([*map(float, scale), 1.0])
    readers = {".stl": _stl_parts, ".dae": _dae_parts, ".obj": _obj_parts}
    if ext in readers:
        data = _read(path, max_bytes)
        try:
            parts = _named(path, readers[ext], data)
            del data
            v, f = _concatenate(path, parts, max_tris)
            v, f = _place(v, f, S)
            return MeshFacts(v, f, ext.lstrip("."))
        except _NotLean:
            pass
    m = load(path, process=True, textures=False)
    if tuple(scale) != (1.0, 1.0, 1.0):
        m.apply_transform(S)
    return MeshFacts.from_trimesh(m)


def triangles(path: Path, notes=None, any_order: bool = False):
    """(vertices (n, 3), faces (m, 3)) of one mesh, equal to ``load(path)``'s, read by the lean STL
    and COLLADA readers when they understand the file (no trimesh import: ~0.6 s of a render),
    else by trimesh, and a COLLADA file pycollada half-rejects by ``lenient_dae`` as convert reads
    it (``notes.warn`` says so); MeshError saying why not. ``any_order``: the caller does not depend
    on the order of the faces (a touch test), so the lean OBJ reader serves too (the same vertices
    and triangles, another face order)."""
    import numpy as np

    path = Path(path)
    ext = path.suffix.lower()
    try:
        return _triangles(path, ext, any_order)
    except MeshError as exc:
        m = lenient_dae(path, notes) if ext == ".dae" and "holds no triangles" in str(exc) else None
        if m is None:
            raise
    return np.asarray(m.vertices), np.asarray(m.faces)


def lean_triangles(path: Path):
    """(vertices, faces) of a COLLADA file by the lean reader, without importing trimesh; None when
    the file is another format or one the reader leaves to trimesh, or when it fails (trimesh then
    reads it and words the error). Its triangles are ``load(path, process=False)``'s, corner for
    corner (convert's MJCF assets; tests/convert/test_mjcf_lean_meshes.py)."""
    if path.suffix.lower() != ".dae":
        return None
    try:
        precheck(path)
        max_bytes, max_tris = limits()
        return _concatenate(path, _named(path, _dae_parts, _read(path, max_bytes)), max_tris)
    except (_NotLean, MeshError, OSError):
        return None


def _triangles(path: Path, ext: str, any_order: bool = False):
    import numpy as np

    readers = {".stl": _stl_parts, ".dae": _dae_parts}   # OBJ: same triangles, another face order
    if any_order:
        readers[".obj"] = _obj_parts
    if ext in readers:
        precheck(path)
        max_bytes, max_tris = limits()
        data = _read(path, max_bytes)
        try:
            return _concatenate(path, _named(path, readers[ext], data), max_tris)
        except _NotLean:
            pass
    m = load(path)
    return np.asarray(m.vertices), np.asarray(m.faces)


def _named(path: Path, reader, data):
    """A lean reader's parts; its MeshError names the file."""
    try:
        return reader(data)
    except MeshError as exc:
        raise MeshError(f"{path.name} {exc}") from None


def _place(v, f, T):
    """trimesh's apply_transform for what check keeps: the points moved (nothing for an identity
    within 1e-8), the faces turned when the transform mirrors."""
    import numpy as np

    if T is None or np.abs(T - np.eye(4)).max() < 1e-8:
        return v, f
    v = np.dot(T, np.column_stack((v, np.ones(len(v)))).T).T[:, :3]
    if np.abs(T[:3, :3] - np.eye(3)).max() > 1e-6 and np.linalg.det(T[:3, :3]) < 0:
        f = np.ascontiguousarray(f[:, ::-1])
    return np.ascontiguousarray(v), f


def _concatenate(path: Path, parts, max_tris: int):
    """(vertices, faces) of parts [(corners (3k, 3) float64, merge attributes or None, 4x4 pose or
    None)]: each part merged on its own (trimesh's process), placed, then concatenated."""
    import numpy as np

    parts = [p if len(p) == 4 else (*p, None) for p in parts]
    n = sum(len(p[0]) // 3 for p in parts)
    if n == 0:
        raise MeshError(f"{path.name} holds no triangles")
    if n > max_tris:
        raise MeshError(f"{path.name} has {n} triangles, over the {max_tris} limit ({ENV_TRIANGLES})")
    verts, faces, offset = [], [], 0
    parts.reverse()
    while parts:
        corners, attrs, T, rank = parts.pop()        # each part's corner arrays are freed once merged
        if not np.isfinite(corners).all():
            raise _NotLean("non-finite vertices")   # trimesh drops them with their faces
        v, f = _merge(corners, attrs, rank)
        del corners, attrs
        v, f = _place(v, f, T)
        verts.append(v)
        faces.append(f + offset)
        offset += len(v)
    v = verts[0] if len(verts) == 1 else np.concatenate(verts)
    f = faces[0] if len(faces) == 1 else np.concatenate(faces)
    return v, f


def _merge(corners, attrs, rank=None):
    """(vertices, faces) of triangle corners with equal vertices merged as trimesh's merge_vertices:
    equal when position (1e-8) and the given attributes (normals 1e-2, texture coordinates 1e-4)
    round alike; each vertex keeps the value and the place of its first corner (first in ``rank``, a
    permutation of the corners, when given)."""
    import numpy as np

    if rank is not None:
        v, f = _merge(corners[rank], None if attrs is None else attrs[rank])
        inverse = np.empty(len(rank), dtype=np.int64)
        inverse[rank] = f.ravel()
        return v, inverse.reshape(-1, 3)

    key = corners * (10 ** MERGE_DIGITS)
    if attrs is not None:
        key = np.column_stack([key, attrs])
    key = np.ascontiguousarray(key.round().astype(np.int64))
    # one 64-bit hash per row sorts far faster than the rows; a collision (rows that differ but hash
    # alike) is caught below, and then the rows themselves are compared
    h = np.zeros(len(key), dtype=np.uint64)
    for j in range(key.shape[1]):
        h ^= key[:, j].view(np.uint64) * np.uint64(_HASH_MULT[j % len(_HASH_MULT)])
        h = (h << np.uint64(7)) | (h >> np.uint64(57))
    _, first, inverse = np.unique(h, return_index=True, return_inverse=True)
    del h
    inverse = inverse.ravel()
    if not (key[first[inverse]] == key).all():
        rows = key.view(np.dtype((np.void, key.dtype.itemsize * key.shape[1]))).ravel()
        _, first, inverse = np.unique(rows, return_index=True, return_inverse=True)
        inverse = inverse.ravel()
        del rows
    del key
    order = np.argsort(first, kind="stable")
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    faces = rank[inverse.ravel()].reshape(-1, 3)
    return corners[first[order]], faces


def _watertight(faces) -> tuple[bool, bool]:
    """(every edge shared by exactly two faces, every such pair of edges runs opposite ways): trimesh's
    is_watertight and is_winding_consistent, from two sorts of edge keys."""
    import numpy as np

    e = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2).astype(np.int64)
    n = int(faces.max()) + 1
    lo, hi = e.min(axis=1), e.max(axis=1)
    und = np.sort(lo * n + hi)
    starts = np.flatnonzero(np.r_[True, und[1:] != und[:-1]])
    counts = np.diff(np.r_[starts, len(und)])
    watertight = bool((counts == 2).all())
    # a pair runs the same way when its directed key repeats (an edge from a vertex to itself, which
    # trimesh counts as opposite, excepted)
    directed = np.sort(e[:, 0] * n + e[:, 1])
    again = directed[1:][directed[1:] == directed[:-1]]
    u, v = again // n, again % n
    again = again[u != v]
    if len(again):
        u, v = again // n, again % n
        key = np.minimum(u, v) * n + np.maximum(u, v)
        pair = (np.searchsorted(und, key, "right") - np.searchsorted(und, key, "left")) == 2
        return watertight, not bool(pair.any())
    return watertight, True


def _mass_properties(vertices, faces, inertia: bool = True):
    """(volume, centroid, inertia about the centroid at density 1) of a closed triangle surface.

    The volume is trimesh's sum (Eberly, "Polyhedral Mass Properties": the x part of the divergence
    theorem over the faces), so a closed surface wound both ways gets trimesh's number too (M004).
    Centroid and second moments, asked only of a closed, consistently wound surface, sum the
    tetrahedra (origin, a, b, c) of the faces: first moment det/24 (a + b + c), second moments
    det/120 (aaᵀ + bbᵀ + ccᵀ + (a+b+c)(a+b+c)ᵀ), four 3×3 products per block of faces. Without
    ``inertia`` the centroid and inertia are NaN (an open surface has neither)."""
    import numpy as np

    volume6 = 0.0
    first = np.zeros(3)
    second = np.zeros((3, 3))
    for k in range(0, len(faces), MASS_CHUNK):
        fc = faces[k:k + MASS_CHUNK]
        a, b, c = vertices[fc[:, 0]], vertices[fc[:, 1]], vertices[fc[:, 2]]
        e1, e2 = b - a, c - a
        cross_x = e1[:, 1] * e2[:, 2] - e1[:, 2] * e2[:, 1]
        volume6 += float(np.dot(cross_x, a[:, 0] + b[:, 0] + c[:, 0]))
        if not inertia:
            continue
        del e1, e2
        det = np.einsum("ij,ij->i", a, np.cross(b, c))
        s = a + b + c
        first += det @ s
        for p in (a, b, c, s):
            second += (p * det[:, None]).T @ p
    volume = volume6 / 6.0
    if not inertia:
        return volume, np.full(3, np.nan), np.full((3, 3), np.nan)
    first /= 24.0
    second /= 120.0
    with np.errstate(divide="ignore", invalid="ignore"):
        com = first / volume
    # about the origin: tr(S) 1 - S; then to the centroid (parallel axes)
    I = np.trace(second) * np.eye(3) - second
    I -= volume * (float(com @ com) * np.eye(3) - np.outer(com, com))
    return volume, com, (I + I.T) / 2


def _stl_ascii_parts(data: bytes):
    """An ASCII STL with one solid, as trimesh reads it: the numbers after each ``vertex``, three by
    three (several solids, which trimesh keeps apart, go to trimesh)."""
    import numpy as np

    try:
        text = data.decode("utf-8").lower()
    except UnicodeDecodeError:
        raise _NotLean("not text") from None
    start, end = text.find("solid"), text.find("endsolid")
    if start < 0 or end < start or text.count("endsolid") != 1:
        raise _NotLean("not one solid")
    pieces = text[start:end].split("vertex")[1:]
    corners = _numbers(" ".join(p[:p.find("\n")] for p in pieces), np.float64)
    if len(corners) < 3 or len(corners) % 9:
        raise _NotLean("vertex count")
    return [(corners.reshape(-1, 3), None, None)]


def _fix_rigid(M):
    """trimesh's scene graph repairs a transform whose rotation is within 1e-5 of orthonormal (float32
    round-off in a COLLADA <matrix>) to the nearest rotation: the same here, so vertices agree."""
    import numpy as np

    R = M[:3, :3]
    dev = np.abs(np.dot(R, R.T) - np.eye(3)).max()
    if 1e-13 < dev < 1e-5:
        U, _, V = np.linalg.svd(R)
        out = np.eye(4)
        out[:3, :3] = np.dot(U, V)
        out[:3, 3] = M[:3, 3]
        return out
    return M


def _numbers(text, dtype):
    """The whitespace-separated numbers of a text (numpy's C parser); _NotLean when some of it is not
    a number (numpy would stop there with a warning and return what it read)."""
    import warnings

    import numpy as np

    if not text or not text.strip():
        return np.zeros(0, dtype)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        try:
            return np.fromstring(text, dtype=dtype, sep=" ")
        except (ValueError, DeprecationWarning):
            raise _NotLean("not a list of numbers") from None


def _stl_parts(data: bytes):
    """A binary STL (size 84 + 50 n; trimesh's test too, whatever the header says) as one part, else
    an ASCII one."""
    import numpy as np

    if len(data) < 84:
        raise _NotLean("short")
    n = struct.unpack("<I", data[80:84])[0]
    if len(data) != 84 + 50 * n:
        return _stl_ascii_parts(data)
    rec = np.frombuffer(data, np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]), count=n, offset=84)
    return [(rec["v"].reshape(-1, 3).astype(np.float64), None, None)]


_DAE_TRANSFORMS = ("matrix", "translate", "rotate", "scale")
_DAE_SKIP = {"instance_camera", "instance_light", "instance_controller", "extra", "asset"}


def _dae_parts(data: bytes):
    """The triangles of a COLLADA file as trimesh reads them through pycollada: every <triangles>,
    <polylist> and <polygons> (fanned) of every geometry instance in the scene, in scene order, with
    the node transforms (float32, as pycollada) and the merge attributes (normals; texture coordinates
    when the primitive's material is bound). Anything outside that subset raises _NotLean."""
    import numpy as np
    from lxml import etree

    if b"<!DOCTYPE" in data[:65536] or b"<!ENTITY" in data[:65536]:
        raise _NotLean("DTD")

    try:
        root = etree.fromstring(data, safe_parser(huge_tree=True, remove_comments=True, remove_pis=True))
    except (etree.XMLSyntaxError, ValueError, RecursionError) as exc:
        raise _NotLean(str(exc)) from None
    if not isinstance(root.tag, str) or not root.tag.endswith("COLLADA"):
        raise _NotLean("not COLLADA")
    ns = root.tag[:-len("COLLADA")]

    def tag(name):
        return ns + name

    ids = {}
    for el in root.iter():
        i = el.get("id")
        if i is not None:
            if i in ids:
                raise _NotLean("duplicate id")
            ids[i] = el

    def ref(url):
        if not url or not url.startswith("#") or url[1:] not in ids:
            raise _NotLean(f"broken reference {url}")
        return ids[url[1:]]

    def floats32(text):
        return _numbers(text, np.float32)

    sources = {}
    counted = [0]
    max_tris = limit("max_mesh_triangles")

    def source(el, want):
        """(data (n, k) float32, k) of a <source>: pycollada's FloatSource (NaN read as 0)."""
        key = id(el)
        if key not in sources:
            arr = el.find(tag("float_array"))
            params = el.findall(f"{tag('technique_common')}/{tag('accessor')}/{tag('param')}")
            if arr is None or not params:
                raise _NotLean("source without float_array or accessor")
            try:
                d = floats32(arr.text)
            except ValueError:
                raise _NotLean("bad float_array") from None
            d[np.isnan(d)] = 0
            names = tuple(p.get("name") for p in params)
            if names == ("U", "V"):
                names = ("S", "T")
            if names == ("S", "T", "P"):
                if d.size % 3:
                    raise _NotLean("bad texcoords")
                d, names = d.reshape(-1, 3)[:, :2].ravel(), ("S", "T")
            if d.size % len(names):
                raise _NotLean("source size")
            sources[key] = (d.reshape(-1, len(names)), names)
        d, names = sources[key]
        if names != want:
            raise _NotLean(f"source components {names}")
        return d

    def prim_parts(prim, bound):
        """(corners, attrs) of one primitive, or None when it has no triangles."""
        kind = etree.QName(prim).localname
        inputs = []             # (offset, semantic, source element) in pycollada's order
        for inp in prim.findall(tag("input")):
            try:
                off = int(inp.get("offset"))
            except (TypeError, ValueError):
                raise _NotLean("input offset") from None
            sem, src = inp.get("semantic"), ref(inp.get("source"))
            if sem == "VERTEX":
                if etree.QName(src).localname != "vertices":
                    raise _NotLean("VERTEX not a <vertices>")
                for vi in src.findall(tag("input")):
                    s = vi.get("semantic")
                    inputs.append((off, "VERTEX" if s == "POSITION" else s, ref(vi.get("source"))))
            else:
                inputs.append((off, sem, src))
        sems = [s for _o, s, _e in inputs]
        if "VERTEX" not in sems or any(s not in ("VERTEX", "NORMAL", "TEXCOORD") for s in sems):
            raise _NotLean(f"inputs {sems}")
        stride = max(o for o, _s, _e in inputs) + 1
        ps = prim.findall(tag("p"))
        # the triangles this primitive adds, from its index count, before any array is made
        # (a polygon of k corners adds at most k - 2; a list of triangles a third of its corners)
        corners = sum(_count_tokens(p.text or "") for p in ps) // stride
        if kind == "triangles":
            counted[0] += corners // 3
        else:                     # fanned: k corners make k - 2 triangles
            vc = prim.find(tag("vcount")) if kind == "polylist" else None
            polygons = _count_tokens(vc.text or "") if vc is not None else len(ps)
            counted[0] += max(corners - 2 * polygons, 0)
        if counted[0] > max_tris:
            raise MeshError(f"holds over {max_tris} triangles, the limit ({ENV_TRIANGLES})")
        if kind == "polygons":
            if prim.find(tag("ph")) is not None:
                raise _NotLean("polygons with holes")
            chunks = [_numbers(p.text, np.int32) for p in ps]
            if any(c.size % stride for c in chunks):
                raise _NotLean("polygon index count")
            vcount = np.array([c.size // stride for c in chunks], dtype=np.int64)
            idx = np.concatenate(chunks) if chunks else np.zeros(0, np.int32)
        else:
            if len(ps) > 1:
                raise _NotLean("several <p>")
            text = ps[0].text if ps else ""
            idx = _numbers(text, np.int32)
            vcount = None
            if kind == "polylist":
                vc = prim.find(tag("vcount"))
                if vc is None:
                    raise _NotLean("polylist without vcount")
                vcount = _numbers(vc.text, np.int64)
        if idx.size % stride:
            raise _NotLean("index count")
        idx = idx.reshape(-1, stride)
        if vcount is not None:                       # fan each polygon: (c0, ci, ci+1)
            if (vcount < 3).any() or vcount.sum() != len(idx):
                raise _NotLean("vcount")
            ends = np.cumsum(vcount)
            starts = ends - vcount
            keep = np.ones(len(idx), dtype=bool)
            keep[ends - 1] = False
            keep[ends - 2] = False
            sel = np.flatnonzero(keep)
            first = np.repeat(starts, vcount)[sel]
            idx = np.stack([idx[first], idx[sel + 1], idx[sel + 2]], axis=1).reshape(-1, stride)
        if len(idx) % 3:
            raise _NotLean("triangle corners")
        if len(idx) == 0:
            return None

        def first_of(sem, want):
            for off, s, el in inputs:
                if s == sem:
                    d = source(el, want)
                    i = idx[:, off]
                    if i.min() < 0 or i.max() >= len(d):
                        raise _NotLean("index out of range")
                    return d[i]
            return None

        corners = first_of("VERTEX", ("X", "Y", "Z")).astype(np.float64)
        attrs = []
        normals = first_of("NORMAL", ("X", "Y", "Z"))
        if normals is not None:
            attrs.append(normals.astype(np.float64) * (10 ** NORMAL_DIGITS))
        if prim.get("material") in bound and "TEXCOORD" in sems:
            attrs.append(first_of("TEXCOORD", ("S", "T")).astype(np.float64) * (10 ** UV_DIGITS))
        return corners, (np.column_stack(attrs) if attrs else None)

    def node_matrix(node):
        M = np.identity(4, dtype=np.float32)
        for t in node:
            name = etree.QName(t).localname if isinstance(t.tag, str) else ""
            if name not in _DAE_TRANSFORMS:
                continue
            try:
                f = floats32(t.text)
            except ValueError:
                raise _NotLean("transform") from None
            T = np.identity(4, dtype=np.float32)
            if name == "matrix" and f.size == 16:
                T = f.reshape(4, 4)
            elif name == "translate" and f.size == 3:
                T[:3, 3] = f
            elif name == "scale" and f.size == 3:
                T[0, 0], T[1, 1], T[2, 2] = f
            elif name == "rotate" and f.size == 4:
                x, y, z = f[:3]
                a = f[3] * np.pi / 180.0          # float32 throughout, as pycollada
                c, s = np.cos(a), np.sin(a)
                t1 = 1 - c
                T = np.array([[t1 * x * x + c, t1 * x * y - s * z, t1 * x * z + s * y, 0],
                              [t1 * x * y + s * z, t1 * y * y + c, t1 * y * z - s * x, 0],
                              [t1 * x * z - s * y, t1 * y * z + s * x, t1 * z * z + c, 0],
                              [0, 0, 0, 1]], dtype=np.float32)
            else:
                raise _NotLean(f"transform {name}")
            M = np.dot(M, T)
        return M

    loaded = []

    def materials_ok() -> set:
        """The ids of the materials pycollada reads (an effect with a broken texture reference or a
        malformed colour is dropped, and with it every geometry instance bound to it): pycollada
        itself on the file's images, effects and materials alone, without the heavy geometry."""
        if not loaded:
            import copy
            import io

            try:
                import collada
                from collada import common as cc
            except ImportError:
                raise _NotLean("pycollada") from None
            mini = etree.Element(root.tag, root.attrib, nsmap=root.nsmap)
            for el in root:
                if isinstance(el.tag, str) and etree.QName(el).localname in (
                        "asset", "library_images", "library_effects", "library_materials"):
                    mini.append(copy.deepcopy(el))
            ignore = [cc.DaeError, cc.DaeIncompleteError, cc.DaeMalformedError, cc.DaeBrokenRefError,
                      cc.DaeUnsupportedError]
            try:
                c = collada.Collada(io.BytesIO(etree.tostring(mini)), ignore=ignore)
                loaded.append({m.id for m in c.materials})
            except Exception as exc:    # pycollada's own errors: the full read would fail as well
                raise _NotLean(f"materials: {exc}") from None
        return loaded[0]

    parts = []

    def walk(node, parent, depth):
        if depth > 256:
            raise _NotLean("nodes nest too deeply")
        M = None
        for ch in node:
            if not isinstance(ch.tag, str):
                continue
            name = etree.QName(ch).localname
            if name in _DAE_TRANSFORMS or name in _DAE_SKIP:
                continue
            if M is None:
                M = np.dot(parent, node_matrix(node))
            if name == "node":
                walk(ch, M, depth + 1)
            elif name == "instance_geometry":
                geom = ref(ch.get("url"))
                mesh = geom.find(tag("mesh"))
                if etree.QName(geom).localname != "geometry" or mesh is None:
                    raise _NotLean("geometry without <mesh>")
                bound = set()
                targets = []
                for im in ch.iter(tag("instance_material")):
                    targets.append(ref(im.get("target")).get("id"))
                    bound.add(im.get("symbol"))
                if targets and not set(targets) <= materials_ok():
                    continue        # pycollada drops an instance whose material it could not read
                for prim in mesh:
                    pname = etree.QName(prim).localname if isinstance(prim.tag, str) else ""
                    if pname in ("triangles", "polylist", "polygons"):
                        got = prim_parts(prim, bound)
                        if got is not None:
                            parts.append((got[0], got[1], _fix_rigid(M)))
                    elif pname in ("tristrips", "trifans"):
                        raise _NotLean(pname)
            else:
                raise _NotLean(f"scene element {name}")

    scene = root.find(tag("scene"))
    ivs = scene.find(tag("instance_visual_scene")) if scene is not None else None
    if ivs is None:
        raise _NotLean("no scene")
    for node in ref(ivs.get("url")):
        if isinstance(node.tag, str) and etree.QName(node).localname == "node":
            walk(node, np.eye(4), 0)
    return parts


def _obj_parts(data: bytes):
    """A Wavefront OBJ as trimesh reads it without its .mtl (check opens no file but the mesh): one
    part per ``usemtl`` material (trimesh's order: the last used first), triangles and quads, corners
    merged on position and, where the faces give them, texture coordinates and normals, each vertex
    taken from the corner trimesh keeps. The subset: v/vt/vn lines of fixed width, faces all written
    alike (v, v/vt, v//vn or v/vt/vn) with positive indices, polygons fanned. Anything else raises
    _NotLean."""
    import re

    import numpy as np

    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        raise _NotLean("not UTF-8") from None
    text = text.replace("\r\n", "\n").replace("\\\n", "")
    lines = text.split("\n")
    # trimesh reads lines that start with "v ", "vt ", "vn ", "f " and "usemtl" (no indent)
    rows = {k: [ln[len(k) + 1:] for ln in lines if ln.startswith(k + " ")] for k in ("v", "vt", "vn")}
    groups: dict = {}
    if "usemtl" not in text:
        groups[None] = [ln[2:] for ln in lines if ln.startswith("f ")]
    else:
        if text.count("usemtl") != ("\n" + text).count("\nusemtl"):
            raise _NotLean("usemtl inside a line")
        material = None
        for ln in lines:
            if ln.startswith("f "):
                groups.setdefault(material, []).append(ln[2:])
            elif ln.startswith("usemtl"):
                material = ln[6:].strip()
    if not any(groups.values()) or not rows["v"]:
        raise _NotLean("no faces")
    groups = {k: g for k, g in groups.items() if g}

    def table(key, width):
        vals = rows[key]
        if not vals:
            return None
        arr = _numbers(" ".join(vals), np.float64)
        per = len(vals[0].split())
        if per < width or arr.size != per * len(vals):       # v x y z [w | r g b]: x y z
            raise _NotLean(f"{key} rows")
        return arr.reshape(len(vals), per)[:, :width]

    v, vt, vn = table("v", 3), table("vt", 2), table("vn", 3)
    parts = []
    for faces in reversed(list(groups.values())):
        joined = " ".join(faces)
        ntok, slashes, double = len(joined.split()), joined.count("/"), joined.count("//")
        sizes = (np.full(len(faces), 3) if ntok == 3 * len(faces) else np.array([len(f.split()) for f in faces]))
        if (sizes < 3).any() or (sizes.min() == sizes.max() > 4):
            raise _NotLean("face corners")     # (trimesh's reading of all-n-gon groups is not ours)
        style = {(0, 0): (False, False), (ntok, 0): (True, False), (2 * ntok, ntok): (False, True),
                 (2 * ntok, 0): (True, True)}.get((slashes, double))
        if style is not None:                  # every corner written alike: v, v/vt, v//vn or v/vt/vn
            has_vt, has_vn = style
            width = 1 + has_vt + has_vn
            flat = _numbers(joined.replace("/", " "), np.int64)
        else:
            # corners written differently: a group keeps texture coordinates (normals) only when
            # every one of its corners gives them, as trimesh's per-corner reading does
            tok = [t.split("/") for f in faces for t in f.split()]
            if any(len(t) > 3 or not t[0] for t in tok):
                raise _NotLean("face tokens")
            has_vt = all(len(t) > 1 and t[1] for t in tok)
            has_vn = all(len(t) > 2 and t[2] for t in tok)
            keep = [0] + ([1] if has_vt else []) + ([2] if has_vn else [])
            width = len(keep)
            try:
                flat = np.array([int(t[k]) for t in tok for k in keep], dtype=np.int64)
            except ValueError:
                raise _NotLean("face indices") from None
        if flat.size != sizes.sum() * width or (flat <= 0).any():
            raise _NotLean("face indices")
        flat = flat.reshape(-1, width) - 1
        # the triangles, then the quads' halves (0 1 2) and (2 3 0), as trimesh splits them
        starts = np.concatenate([[0], np.cumsum(sizes)[:-1]])
        tri, quad = starts[sizes == 3], starts[sizes == 4]
        fans = [np.stack([s0, s0 + i + 1, s0 + i + 2], 1).ravel()          # larger polygons: fans
                for n in np.unique(sizes[sizes > 4]) for s0 in [starts[sizes == n]] for i in range(n - 2)]
        order = np.concatenate([np.stack([tri, tri + 1, tri + 2], 1).ravel(),
                                np.stack([quad, quad + 1, quad + 2], 1).ravel(),
                                np.stack([quad + 2, quad + 3, quad], 1).ravel()] + fans)
        idx = flat[order]
        for col, table_ in zip(range(width), [v] + ([vt] if has_vt else []) + ([vn] if has_vn else [])):
            if table_ is None or idx[:, col].max() >= len(table_):
                raise _NotLean("index out of range")
        attrs = []
        if has_vt:
            attrs.append(vt[idx[:, 1]] * (10 ** UV_DIGITS))
        if has_vn:
            attrs.append(vn[idx[:, width - 1]] * (10 ** NORMAL_DIGITS))
        rank = _obj_rank(idx)
        parts.append((v[idx[:, 0]], np.column_stack(attrs) if attrs else None, None, rank))
    return parts


def _obj_rank(idx):
    """The corners in the order of the vertices trimesh builds from OBJ index tuples (v[, vt][, vn]):
    the distinct tuples ordered by their packed value (vn, then vt, then v), then by vertex index
    with numpy's default sort, as trimesh's unmerge does; merging then keeps the first of each."""
    import numpy as np

    if idx.shape[1] == 1:
        return np.argsort(idx[:, 0], kind="stable")
    bits = 64 // idx.shape[1]
    if idx.max() >= (1 << (bits - 1)) - 1:
        raise _NotLean("indices too large to pack")
    key = np.zeros(len(idx), dtype=np.uint64)
    for k in range(idx.shape[1]):
        key |= (idx[:, k] + (1 << (bits - 1))).astype(np.uint64) << np.uint64(k * bits)
    _, first, inverse = np.unique(key, return_index=True, return_inverse=True)
    order = idx[first, 0].argsort()
    remap = np.empty(len(order), dtype=np.int64)
    remap[order] = np.arange(len(order))
    return np.argsort(remap[inverse.ravel()], kind="stable")
