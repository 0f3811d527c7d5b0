"""Mesh stand-ins for the real-robot corpus (tests/corpus): boxes of each real mesh's extents.

The corpus keeps the robots' URDF/xacro sources but not their meshes (size, licences). Every mesh a
corpus robot names is replaced by a box with the same axis-aligned extents, in a file of the same
name and format (binary STL, COLLADA .dae, Wavefront .obj), so loaders, `check` and `convert` see a
mesh of the right size where the robot expects one.

Two steps, so the stand-ins can be rewritten without the original packages:

  measure  read the real meshes (a checkout of the original packages laid out like tests/corpus)
           and record their extents in tests/corpus/standins.json;
  write    (re)write every stand-in from tests/corpus/standins.json.

  python tools/corpus_standins.py measure --from ~/src/pkgs --from ~/src/ros2_pkgs \\
      --list meshes.txt           # one corpus-relative mesh path a line
  python tools/corpus_standins.py write

Extents are the mesh's vertices as trimesh reads them, in the file's own frame (COLLADA node
transforms applied, the <unit> and <up_axis> not applied: the stand-in copies both, so every loader
scales and turns it as it does the original). A mesh whose file is absent from its source (large
files some mirrors drop) or cannot be read gets DEFAULT_HALF_SIZE around the origin, recorded as
"source": "default" in the JSON.
"""

from __future__ import annotations

import argparse
import json
import os
import struct
import sys
import tempfile
from pathlib import Path

CORPUS = Path(__file__).resolve().parent.parent / "tests" / "corpus"
TABLE = CORPUS / "standins.json"
DEFAULT_HALF_SIZE = 0.05  # m: a 10 cm cube where the real mesh is missing or unreadable

# The 12 triangles of a box, as corner indices (corner i has x = max if i & 1, y if i & 2, z if i & 4),
# wound counter-clockwise seen from outside.
_FACES = [(0, 2, 3), (0, 3, 1), (4, 5, 7), (4, 7, 6), (0, 1, 5), (0, 5, 4),
          (2, 6, 7), (2, 7, 3), (0, 4, 6), (0, 6, 2), (1, 3, 7), (1, 7, 5)]


def _corners(lo, hi):
    return [(hi[0] if i & 1 else lo[0], hi[1] if i & 2 else lo[1], hi[2] if i & 4 else lo[2]) for i in range(8)]


def _normal(a, b, c):
    u = [b[k] - a[k] for k in range(3)]
    v = [c[k] - a[k] for k in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    length = sum(x * x for x in n) ** 0.5 or 1.0
    return [x / length for x in n]


def stl_bytes(lo, hi) -> bytes:
    pts = _corners(lo, hi)
    out = bytearray(b"corpus stand-in box".ljust(80, b" "))
    out += struct.pack("<I", len(_FACES))
    for f in _FACES:
        a, b, c = (pts[i] for i in f)
        out += struct.pack("<12fH", *_normal(a, b, c), *a, *b, *c, 0)
    return bytes(out)


def obj_bytes(lo, hi) -> bytes:
    lines = ["# corpus stand-in box"]
    lines += [f"v {x!r} {y!r} {z!r}" for x, y, z in _corners(lo, hi)]
    lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in _FACES]
    return ("\n".join(lines) + "\n").encode()


def dae_bytes(lo, hi, unit: float = 1.0, up_axis: str = "Z_UP") -> bytes:
    pts = " ".join(repr(v) for p in _corners(lo, hi) for v in p)
    idx = " ".join(str(i) for f in _FACES for i in f)
    return f"""<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset>
    <contributor><authoring_tool>corpus stand-in box</authoring_tool></contributor>
    <unit name="unit" meter="{unit!r}"/>
    <up_axis>{up_axis}</up_axis>
  </asset>
  <library_geometries>
    <geometry id="box" name="box">
      <mesh>
        <source id="box-positions">
          <float_array id="box-positions-array" count="24">{pts}</float_array>
          <technique_common>
            <accessor source="#box-positions-array" count="8" stride="3">
              <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
            </accessor>
          </technique_common>
        </source>
        <vertices id="box-vertices"><input semantic="POSITION" source="#box-positions"/></vertices>
        <triangles count="12">
          <input semantic="VERTEX" source="#box-vertices" offset="0"/>
          <p>{idx}</p>
        </triangles>
      </mesh>
    </geometry>
  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="scene" name="scene">
      <node id="box-node" name="box"><instance_geometry url="#box"/></node>
    </visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
""".encode()


def _dae_asset(path: Path) -> tuple[float, str]:
    """COLLADA <unit meter> and <up_axis> of a file (defaults 1.0, Y_UP as the spec says)."""
    from lxml import etree

    root = etree.parse(str(path), etree.XMLParser(resolve_entities=False, no_network=True, recover=True)).getroot()
    unit, up = 1.0, "Y_UP"
    for el in root.iter():
        tag = etree.QName(el).localname if isinstance(el.tag, str) else ""
        if tag == "unit" and el.get("meter"):
            unit = float(el.get("meter"))
        elif tag == "up_axis" and el.text:
            up = el.text.strip()
        elif tag.startswith("library_"):
            break
    return unit, up


def _dae_raw_bounds(path: Path):
    from lxml import etree

    root = etree.parse(str(path), etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=True, recover=True)).getroot()
    arrays = {el.get("id"): el for el in root.iter("{*}float_array")}
    sources = {el.get("id"): el for el in root.iter("{*}source")}
    lo, hi = [float("inf")] * 3, [float("-inf")] * 3
    for vin in root.iter("{*}vertices"):
        for inp in vin.iter("{*}input"):
            if inp.get("semantic") != "POSITION":
                continue
            src = sources.get(inp.get("source", "").lstrip("#"))
            arr = arrays.get(src.find("{*}float_array").get("id")) if src is not None else None
            vals = [float(v) for v in (arr.text or "").split()] if arr is not None else []
            for i in range(0, len(vals) - 2, 3):
                for k in range(3):
                    lo[k], hi[k] = min(lo[k], vals[i + k]), max(hi[k], vals[i + k])
    if lo[0] == float("inf"):
        raise ValueError("no positions")
    return lo, hi


def measure(path: Path) -> dict:
    """Extents of a real mesh, and for COLLADA its unit and up axis."""
    import trimesh

    try:
        mesh = trimesh.load(str(path), force="mesh", process=False)
        if mesh.is_empty or len(mesh.vertices) == 0:
            raise ValueError("no vertices")
        (lo, hi), how = mesh.bounds, "measured"
    except Exception:
        if path.suffix.lower() != ".dae":
            raise
        # pycollada refuses some files real loaders accept (a malformed colour, say): read the
        # POSITION arrays directly, node transforms not applied.
        lo, hi = _dae_raw_bounds(path)
        how = "measured (raw COLLADA positions)"
    entry = {"min": [round(float(v), 9) for v in lo], "max": [round(float(v), 9) for v in hi], "source": how}
    if path.suffix.lower() == ".dae":
        entry["unit"], entry["up_axis"] = _dae_asset(path)
    return entry


def default_entry(path: Path, why: str) -> dict:
    h = DEFAULT_HALF_SIZE
    entry = {"min": [-h, -h, -h], "max": [h, h, h], "source": "default", "why": why}
    if path.suffix.lower() == ".dae":
        entry["unit"], entry["up_axis"] = 1.0, "Z_UP"
    return entry


def standin_bytes(rel: str, entry: dict) -> bytes:
    ext = Path(rel).suffix.lower()
    if ext == ".stl":
        return stl_bytes(entry["min"], entry["max"])
    if ext == ".obj":
        return obj_bytes(entry["min"], entry["max"])
    if ext == ".dae":
        return dae_bytes(entry["min"], entry["max"], entry.get("unit", 1.0), entry.get("up_axis", "Z_UP"))
    raise ValueError(f"{rel}: no stand-in writer for {ext}")


def _write_atomic(path: Path, data: bytes) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".tmp-")
    with os.fdopen(fd, "wb") as f:
        f.write(data)
    os.replace(tmp, path)


def cmd_measure(sources: list[Path], listing: Path) -> None:
    table = json.loads(TABLE.read_text()) if TABLE.exists() else {}
    for rel in filter(None, (line.strip() for line in listing.read_text().splitlines())):
        found = next((s / rel for s in sources if (s / rel).is_file()), None)
        if found is None:
            table[rel] = default_entry(Path(rel), "absent from the source")
            continue
        try:
            table[rel] = measure(found)
        except Exception as exc:  # a mesh trimesh cannot read: recorded, not fatal
            table[rel] = default_entry(found, f"unreadable: {type(exc).__name__}")
    _write_atomic(TABLE, (json.dumps(dict(sorted(table.items())), indent=1) + "\n").encode())
    print(f"{TABLE}: {len(table)} meshes, {sum(e['source'] == 'default' for e in table.values())} default-sized")


def cmd_write() -> None:
    table = json.loads(TABLE.read_text())
    for rel, entry in table.items():
        _write_atomic(CORPUS / rel, standin_bytes(rel, entry))
    print(f"wrote {len(table)} stand-ins under {CORPUS}")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    sub = ap.add_subparsers(dest="cmd", required=True)
    m = sub.add_parser("measure", help="record the real meshes' extents in standins.json")
    m.add_argument("--from", dest="sources", action="append", type=Path, required=True,
                   help="folder laid out like tests/corpus holding the real meshes (repeatable, first match wins)")
    m.add_argument("--list", type=Path, required=True, help="file of corpus-relative mesh paths, one a line")
    sub.add_parser("write", help="write every stand-in from standins.json")
    args = ap.parse_args(argv)
    if args.cmd == "measure":
        cmd_measure(args.sources, args.list)
    else:
        cmd_write()
    return 0


if __name__ == "__main__":
    sys.exit(main())
