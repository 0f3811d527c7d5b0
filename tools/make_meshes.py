"""Generate the bundled model's meshes, mesh inertials and textures.

The seed's CAD meshes are not available, so the bundled MYRAbot uses simple
watertight solids built here from the real files' bounding boxes
(arm-facts.md §9.2) and from what the seed mounts on them. Everything is
deterministic and offline; run ``python -m tools.make_meshes`` to regenerate

- ``meshes/*.stl``: binary STL in **metres**, in the same coordinates as the
  seed's files (their mm corner-origin coordinates divided by 1000), so the
  seed's visual origins apply unchanged and no ``scale`` is needed;
- ``xacro/mesh_inertials.xacro``: one ``<xacro:NAME_inertial mass=...>`` macro
  per mesh giving the solid-body inertia at the declared mass, about the
  mesh's centroid;
- ``materials/textures/*.png``: plain generated textures (no trademark art).
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

# Which link uses each mesh and where the mesh sits in that link (the visual
# origin xyz); the inertial origin is the mesh centroid shifted by it.
MESH_USERS = {
    "e_pilar": ("e_pilar_link", (0.0, 0.0, 0.0)),
    "e_soporte_1": ("e_soporte_1_link", (0.0, 0.0, 0.0)),
    "e_soporte_2": ("e_soporte_2_link", (0.0, -0.2, -0.03)),
    "e_monitor": ("e_monitor_link", (0.0, 0.0, 0.0)),
    "e_base_kinect": ("e_base_kinect_link", (0.0, 0.0, 0.0)),
    "e_base_brazo_1": ("e_base_brazo_1_link", (0.0, 0.0, 0.0)),
    "e_base_brazo_2": ("e_base_brazo_2_link", (0.0, 0.0, 0.0)),
    "e_ultrasonidos": ("e_ultrasonidos_link", (-0.025, 0.0, 0.0)),
    "webcam_1": ("e_webcam_1_link", (0.0, 0.0, 0.0)),
    "webcam_2": ("e_webcam_2_link", (0.0, -0.084, -0.097)),
    "kinect": ("camera_link", (0.0, 0.0, 0.0)),
}

# Sonar yaws of the assembly (seed-spec §2.9); the ring gets a hole at each.
SONAR_YAWS = (1.57, 2.36, 3.14, 3.93, 4.71)


def _box(lo, hi):
    import trimesh

    lo, hi = list(map(float, lo)), list(map(float, hi))
    ext = [h - l for l, h in zip(lo, hi)]
    ctr = [(l + h) / 2 for l, h in zip(lo, hi)]
    return trimesh.creation.box(extents=ext, transform=trimesh.transformations.translation_matrix(ctr))


def _prism(poly_xy, z0, z1):
    """Extrude a polygon given in the mesh's xy plane from z0 to z1."""
    import trimesh
    from shapely.geometry import Polygon

    m = trimesh.creation.extrude_polygon(Polygon(poly_xy), z1 - z0)
    m.apply_translation([0, 0, z0])
    return m


def _prism_yz(poly_yz, x0, x1):
    """Extrude a polygon drawn in the (y, z) plane along x from x0 to x1."""
    import numpy as np

    m = _prism(poly_yz, x0, x1)  # polygon in (x', y'), extruded along z'
    # (x', y', z') -> (x, y, z) = (z', x', y'): a proper rotation, so normals stay outward
    perm = np.array([[0, 0, 1, 0], [1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0, 1]], dtype=float)
    m.apply_transform(perm)
    return m


def _union(parts):
    import trimesh

    return trimesh.boolean.union(parts, engine="manifold")


def _difference(a, cutters):
    import trimesh

    return trimesh.boolean.difference([a, *cutters], engine="manifold")


def _ring_sector(cx, cy, r_in, r_out, a0, a1, z0, z1, n=64):
    pts = []
    for i in range(n + 1):
        a = a0 + (a1 - a0) * i / n
        pts.append((cx + r_out * math.cos(a), cy + r_out * math.sin(a)))
    for i in range(n, -1, -1):
        a = a0 + (a1 - a0) * i / n
        pts.append((cx + r_in * math.cos(a), cy + r_in * math.sin(a)))
    return _prism(pts, z0, z1)


def build_meshes():
    """Return {name: trimesh.Trimesh} in metres, in the seed file's coordinates."""
    import numpy as np
    import trimesh

    meshes = {}
    # Pillar: U channel 160 x 105 x 700 mm, web at the front (y 0.165), open at
    # the back; the monitor support (e_soporte_1) slides in the channel.
    meshes["e_pilar"] = _prism(
        [(0.055, 0.165), (0.215, 0.165), (0.215, 0.270), (0.210, 0.270),
         (0.210, 0.170), (0.060, 0.170), (0.060, 0.270), (0.055, 0.270)], 0.0, 0.700)
    # Monitor support bar and its top bracket (bboxes of e_soporte_1/2.stl).
    meshes["e_soporte_1"] = _box((0.1275, 0.170, 0.0), (0.1425, 0.230, 0.640))
    meshes["e_soporte_2"] = _box((0.1325, 0.130, 0.0), (0.1375, 0.230, 0.060))
    # Monitor housing 270 x 35 x 185 mm with a recess for the screen
    # (e_pantalla_link: 0.22 x 0.130 at (0.135, 0.0999, 0.086)).
    housing = _box((0.0, 0.095, 0.0), (0.270, 0.130, 0.185))
    recess = _box((0.025, 0.090, 0.021), (0.245, 0.0999, 0.151))
    meshes["e_monitor"] = _difference(housing, [recess])
    # Kinect shelf: a wedge bracket on the pillar's front face; its top
    # (z 0.06) carries the Kinect's foot.
    meshes["e_base_kinect"] = _prism_yz(
        [(0.165, 0.0), (0.165, 0.060), (0.080, 0.060), (0.080, 0.055)], 0.0875, 0.1825)
    # Arm bracket: base plate, upright against the pillar, and a pedestal under
    # the arm's base servo and the four standoffs.
    meshes["e_base_brazo_1"] = _union([
        _box((0.080, 0.003, 0.0), (0.190, 0.165, 0.005)),
        _box((0.080, 0.155, 0.005), (0.190, 0.165, 0.075)),
        _box((0.100, 0.003, 0.005), (0.170, 0.090, 0.075)),
    ])
    meshes["e_base_brazo_2"] = _box((0.095, 0.003, 0.035), (0.175, 0.083, 0.039))
    # Sonar ring: a 10 mm band, outer radius 0.16, 40 mm high, over the arc
    # that the real file's bbox implies (-34.3 deg .. 214.3 deg about its
    # centre (0.160, 0.135)), with a hole in front of each sonar.
    a0 = -math.asin((0.135 - 0.044778) / 0.16)
    ring = _ring_sector(0.160, 0.135, 0.150, 0.160, a0, math.pi - a0, 0.0, 0.040, n=96)
    holes = []
    for yaw in SONAR_YAWS:
        d = np.array([math.sin(yaw), -math.cos(yaw), 0.0])  # sonar +x in the ring frame
        c = np.array([0.160, 0.135, 0.0075]) + 0.155 * d
        cyl = trimesh.creation.cylinder(radius=0.008, height=0.04, sections=32)
        rot = trimesh.geometry.align_vectors([0, 0, 1], d)
        rot[:3, 3] = c
        cyl.apply_transform(rot)
        holes.append(cyl)
    meshes["e_ultrasonidos"] = _difference(ring, holes)
    # Webcam clip over the monitor's top edge: top bar and a wedge-shaped foot
    # resting on the monitor's back (monitor: y 0.095..0.13, top at z 0.0925).
    meshes["webcam_1"] = _prism_yz(
        [(0.0795, 0.0925), (0.0795, 0.1015), (0.16955, 0.1015), (0.16955, 0.04083),
         (0.130, 0.0925)], 0.134, 0.191)
    # Webcam body (Logitech 9000): 90 x 35.6 x 40 mm.
    meshes["webcam_2"] = _box((0.115, 0.0534, 0.077026), (0.204899, 0.089, 0.116974))
    # Kinect: sensor bar, neck and foot; metres in camera_link (kinect.dae bbox).
    meshes["kinect"] = _union([
        _box((-0.062, -0.138, -0.019), (0.006, 0.138, 0.019)),
        _box((-0.040, -0.010, -0.045), (-0.020, 0.010, -0.019)),
        _box((-0.068, -0.035, -0.053), (0.000, 0.035, -0.045)),
    ])
    for name, m in meshes.items():
        m.merge_vertices()
        m.fix_normals()
        if not (m.is_watertight and m.is_volume):
            raise RuntimeError(f"generated mesh {name} is not a closed volume")
    return meshes


def mass_properties(mesh):
    """(volume, centroid, inertia per kg about the centroid) of a solid mesh."""
    import numpy as np

    mp = mesh.mass_properties  # density 1
    vol = float(mp["volume"] if isinstance(mp, dict) else mp.volume)
    com = np.asarray(mp["center_mass"] if isinstance(mp, dict) else mp.center_mass, dtype=float)
    inertia = np.asarray(mp["inertia"] if isinstance(mp, dict) else mp.inertia, dtype=float)
    return vol, com, inertia / vol


def _g(x):
    v = float(x)
    if abs(v) < 1e-12:
        v = 0.0
    return format(v, ".8g")


def _times_mass(v):
    return "0" if v == 0 else f"${{mass*{_g(v)}}}"


def mesh_inertials_xacro(meshes):
    """Text of xacro/mesh_inertials.xacro (one inertial macro per mesh)."""
    lines = [
        '<?xml version="1.0"?>',
        "<!-- Generated by `python -m tools.make_meshes`; do not edit.",
        "     Solid-body inertia of each generated mesh at the link's declared mass:",
        "     <xacro:NAME_inertial mass=\"M\"/> gives the <inertial> with its origin at",
        "     the mesh centroid (mesh coordinates + the link's visual origin) and",
        "     I = M * (inertia per kg about the centroid, mesh axes). -->",
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">',
    ]
    for name in sorted(meshes):
        link, off = MESH_USERS[name]
        vol, com, ipk = mass_properties(meshes[name])
        # boolean ops leave ~1e-11 products of inertia on symmetric parts: clear them
        ipk = ipk.copy()
        scale = max(abs(ipk[i, i]) for i in range(3))
        ipk[abs(ipk) < 1e-7 * scale] = 0.0
        org = [com[i] + off[i] for i in range(3)]
        lines += [
            "",
            f"  <!-- {name}.stl on {link}: volume {_g(vol)} m^3, centroid ({_g(com[0])}, {_g(com[1])}, {_g(com[2])}) -->",
            f'  <xacro:macro name="{name}_inertial" params="mass">',
            "    <inertial>",
            '      <mass value="${mass}"/>',
            f'      <origin xyz="{_g(org[0])} {_g(org[1])} {_g(org[2])}" rpy="0 0 0"/>',
            f'      <inertia ixx="{_times_mass(ipk[0, 0])}" ixy="{_times_mass(ipk[0, 1])}" ixz="{_times_mass(ipk[0, 2])}"',
            f'               iyy="{_times_mass(ipk[1, 1])}" iyz="{_times_mass(ipk[1, 2])}" izz="{_times_mass(ipk[2, 2])}"/>',
            "    </inertial>",
            "  </xacro:macro>",
        ]
    lines += ["", "</robot>", ""]
    return "\n".join(lines)


def stl_bytes(mesh):
    """Binary STL with a fixed header, so the bytes depend on the geometry only."""
    import numpy as np

    tris = np.asarray(mesh.triangles, dtype="<f4")
    normals = np.asarray(mesh.face_normals, dtype="<f4")
    n = len(tris)
    rec = np.zeros(n, dtype=[("normal", "<f4", 3), ("v", "<f4", (3, 3)), ("attr", "<u2")])
    rec["normal"] = normals
    rec["v"] = tris
    header = b"tools.make_meshes: generated mesh, metres".ljust(80, b" ")
    return header + np.uint32(n).tobytes() + rec.tobytes()


# ---------------------------------------------------------------- textures

def _wood_texture(size=256):
    """Light grey grain (0.78..1.0): the material's wood colour modulates it."""
    import numpy as np
    from PIL import Image

    rng = np.random.default_rng(20140212)  # the seed page's revision date
    y, x = np.mgrid[0:size, 0:size].astype(float)
    wobble = 6.0 * np.sin(2 * np.pi * x / size) + 3.0 * np.sin(6 * np.pi * x / size + 1.3)
    rings = 0.5 + 0.5 * np.sin(2 * np.pi * 8 * (y + wobble) / size)
    noise = rng.normal(0.0, 0.02, (size, size))
    t = np.clip(0.80 + 0.18 * rings + noise, 0, 1)
    img = (255 * t).round().astype(np.uint8)
    return Image.fromarray(np.stack([img] * 3, axis=-1), "RGB")


def _can_texture(background, band, stripe, wave=False, size=(512, 256)):
    """A can label: background colour, a wide band and two thin stripes
    (or a sine wave for the cola can). Plain shapes, no lettering."""
    import numpy as np
    from PIL import Image

    w, h = size
    img = np.empty((h, w, 3), dtype=np.uint8)
    img[:] = background
    y, x = np.mgrid[0:h, 0:w]
    if wave:
        centre = h / 2 + 0.18 * h * np.sin(2 * np.pi * x / w)
        img[np.abs(y - centre) < 0.08 * h] = band
        img[np.abs(y - centre - 0.12 * h) < 0.015 * h] = stripe
    else:
        img[np.abs(y - h / 2) < 0.16 * h] = band
        for yc in (0.28 * h, 0.72 * h):
            img[np.abs(y - yc) < 0.02 * h] = stripe
    return Image.fromarray(img, "RGB")


TEXTURES = {
    "wood.png": lambda: _wood_texture(),
    "amstel.png": lambda: _can_texture((242, 240, 232), (200, 16, 30), (212, 170, 60)),
    "coca_cola.png": lambda: _can_texture((196, 0, 14), (255, 255, 255), (255, 255, 255), wave=True),
}


def _png_bytes(img):
    import io

    buf = io.BytesIO()
    img.save(buf, format="PNG", optimize=False, compress_level=9)
    return buf.getvalue()


# ---------------------------------------------------------------- driver

def default_root() -> Path:
    """Folder of the bundled ROS package (the one holding package.xml)."""
    try:
        from myrabot_desc.expand.packages import data_root

        return Path(data_root())
    except Exception:  # the loader is optional here; fall back to the source tree
        return Path(__file__).resolve().parent.parent


def generate(root=None):
    """Write meshes, mesh inertials and textures under ``root``; return the paths written."""
    root = Path(root) if root is not None else default_root()
    meshes = build_meshes()
    out = {}
    for name in sorted(meshes):
        out[root / "meshes" / f"{name}.stl"] = stl_bytes(meshes[name])
    out[root / "xacro" / "mesh_inertials.xacro"] = mesh_inertials_xacro(meshes).encode()
    for name in sorted(TEXTURES):
        out[root / "materials" / "textures" / name] = _png_bytes(TEXTURES[name]())
    for path, data in out.items():
        path.parent.mkdir(parents=True, exist_ok=True)
        if not path.exists() or path.read_bytes() != data:
            tmp = path.with_suffix(path.suffix + ".tmp")
            tmp.write_bytes(data)
            tmp.replace(path)
    return sorted(out)


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m tools.make_meshes", description=__doc__.split("\n\n")[0])
    ap.add_argument("--root", help="package folder to write into (default: the bundled package)")
    args = ap.parse_args(argv)
    for p in generate(args.root):
        print(p)
    return 0


if __name__ == "__main__":
    sys.exit(main())
