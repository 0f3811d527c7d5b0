"""``myrabot-desc render``: a PNG of the robot with no display (MuJoCo's offscreen renderer).

The scene (``view.scene``) is placed at the asked joint values by our kinematics and handed to
MuJoCo as static geoms: MuJoCo only draws, so the picture shows exactly what ``view`` and the
other commands compute. Cameras are orthographic, so the image keeps the robot's proportions
(front: y across, z up; side: x across; top: x across, y up). Overlays: collision geometry,
link frames (axes, names drawn with Pillow), equivalent inertia boxes and centres of mass.

MuJoCo needs an OpenGL context without a display: EGL (libegl1 + Mesa) or OSMesa (libosmesa6).
``MUJOCO_GL`` picks one; unset, EGL is used when its library is found, else OSMesa.
"""

from __future__ import annotations

import math
import os

from myrabot_desc.diagnostics import Loc
from myrabot_desc.errors import InputError
from myrabot_desc.expand.yaml_load import load_path
from myrabot_desc.model.kinematics import center_of_mass
from myrabot_desc.records import Struct
from myrabot_desc.safety import limit
from myrabot_desc.view.facts import inertia_box
from myrabot_desc.view.scene import parse_joint_values

# (azimuth, elevation) in degrees, MuJoCo's convention: the camera looks along
# (cos el cos az, cos el sin az, sin el).
VIEWS = {
    "iso": (135.0, -30.0),       # from front-right, above
    "front": (180.0, 0.0),       # from +x: the robot faces the camera
    "side": (90.0, 0.0),         # from -y: the robot faces right
    "top": (90.0, -89.999),      # from above: x right, y up
}
ALL = ("iso", "front", "side", "top")
BACKGROUND = (228, 232, 238)      # light blue-grey: white parts stay visible
MAX_PIXELS = 4096 * 4096


class Layers(Struct):
    collision: bool = False
    frames: bool = False
    inertia: bool = False


class Camera(Struct):
    lookat: object       # (3,) numpy
    forward: object
    right: object
    up: object
    height: float        # metres shown from the image's bottom to its top
    width: float
    depth: float         # extent of the points along the view direction
    azimuth: float
    elevation: float


# ------------------------------------------------------------------ GL
def choose_gl() -> str:
    """Set MUJOCO_GL (before mujoco is imported) to a backend whose library exists; say what is missing."""
    import ctypes.util

    want = os.environ.get("MUJOCO_GL", "").strip().lower()
    libs = {"egl": "EGL", "osmesa": "OSMesa"}
    if want in libs:
        if ctypes.util.find_library(libs[want]) is None:
            raise InputError(f"MUJOCO_GL={want} but lib{libs[want]} is not installed "
                             f"(Debian: apt-get install {'libegl1 libgl1-mesa-dri' if want == 'egl' else 'libosmesa6'})")
        return want
    if want and want != "auto":
        return want          # glfw or another backend the user set up
    for name in ("egl", "osmesa"):
        if ctypes.util.find_library(libs[name]) is not None:
            os.environ["MUJOCO_GL"] = name
            return name
    raise InputError("cannot render offscreen: neither libEGL nor libOSMesa is installed "
                     "(Debian: apt-get install libegl1 libgl1-mesa-dri, or libosmesa6; `make install` does it)")


# ------------------------------------------------------------------ camera
def camera_for(points, view: str, aspect: float, margin: float = 0.06) -> Camera:
    """An orthographic camera for ``view`` framing ``points`` (n, 3) with ``aspect`` = width / height."""
    import numpy as np

    az, el = VIEWS[view]
    a, e = math.radians(az), math.radians(el)
    f = np.array([math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e)])
    r = np.cross(f, [0.0, 0.0, 1.0])
    if np.linalg.norm(r) < 1e-6:
        r = np.array([math.sin(a), -math.cos(a), 0.0])
    r /= np.linalg.norm(r)
    u = np.cross(r, f)
    pts = np.asarray(points, dtype=float)
    if len(pts) == 0:
        pts = np.zeros((1, 3))
    x, y, z = pts @ r, pts @ u, pts @ f
    w, h = float(np.ptp(x)), float(np.ptp(y))
    w, h = max(w, 1e-3), max(h, 1e-3)
    if w / h > aspect:
        h = w / aspect
    else:
        w = h * aspect
    h *= 1 + 2 * margin
    w *= 1 + 2 * margin
    centre = r * (x.min() + x.max()) / 2 + u * (y.min() + y.max()) / 2 + f * (z.min() + z.max()) / 2
    return Camera(centre, f, r, u, h, w, max(float(np.ptp(z)), 1e-3), az, el)


def project(cam: Camera, p, W: int, H: int) -> tuple[float, float]:
    """Pixel (column, row) of world point ``p`` in a W x H image of ``cam``."""
    import numpy as np

    d = np.asarray(p, dtype=float) - cam.lookat
    return W / 2 + (d @ cam.right) / cam.width * W, H / 2 - (d @ cam.up) / cam.height * H


# ------------------------------------------------------------------ the MuJoCo model
def build_model(scene, q: dict, layers: Layers):
    """An MjModel with every part placed at ``q`` (static geoms) and the overlays; also the frames
    (link -> 4x4) for labels and the points that frame the picture."""
    import mujoco
    import numpy as np

    T = scene.transforms(q)
    spec = mujoco.MjSpec()
    spec.modelname = "render"
    spec.compiler.degree = False
    vis = spec.visual
    vis.headlight.ambient = [0.35, 0.35, 0.35]
    vis.headlight.diffuse = [0.45, 0.45, 0.45]
    vis.headlight.specular = [0.1, 0.1, 0.1]
    vis.global_.orthographic = 1
    vis.quality.offsamples = 4
    spec.add_texture(name="sky", type=mujoco.mjtTexture.mjTEXTURE_SKYBOX, builtin=mujoco.mjtBuiltin.mjBUILTIN_FLAT,
                     rgb1=[c / 255 for c in BACKGROUND], rgb2=[c / 255 for c in BACKGROUND], width=8, height=8)
    world = spec.worldbody
    world.add_light(pos=[0, 0, 10], dir=[-0.4, 0.6, -1.0], type=mujoco.mjtLightType.mjLIGHT_DIRECTIONAL, diffuse=[0.45, 0.45, 0.45],
                    castshadow=False)
    quat = np.zeros(4)
    points = []
    mesh_ids: dict = {}

    def place(M, **kw):
        mujoco.mju_mat2Quat(quat, np.ascontiguousarray(M[:3, :3]).reshape(-1))
        return world.add_geom(pos=M[:3, 3].tolist(), quat=quat.tolist(), contype=0, conaffinity=0, **kw)

    shown = [p for p in scene.parts if p.link in T and (p.layer == "visual" or layers.collision)]
    for k, part in enumerate(shown):
        M = T[part.link] @ part.local
        ident = id(part.vertices)
        name = mesh_ids.get(ident)
        if name is None:
            name = f"m{len(mesh_ids)}"
            mesh_ids[ident] = name
            spec.add_mesh(name=name, uservert=np.asarray(part.vertices, dtype=np.float64).reshape(-1).tolist(),
                          userface=np.asarray(part.faces, dtype=np.int32).reshape(-1).tolist(),
                          inertia=mujoco.mjtMeshInertia.mjMESH_INERTIA_SHELL)
        rgba = list(part.rgba)
        if layers.collision and part.layer == "visual":
            rgba[3] = min(rgba[3], 0.25)           # ghost the visuals so the collision shapes show
        elif layers.frames:
            rgba[3] = min(rgba[3], 0.45)           # and so the frames inside the links show
        place(M, type=mujoco.mjtGeom.mjGEOM_MESH, meshname=name, rgba=rgba, group=0 if part.layer == "visual" else 1)
        v = np.asarray(part.vertices, dtype=float)
        points.append(v @ M[:3, :3].T + M[:3, 3])
    pts = np.vstack(points) if points else np.zeros((1, 3))
    diag = float(np.linalg.norm(np.ptp(pts, axis=0))) or 1.0
    extra: list = []          # overlay points that the picture must hold too
    if layers.frames:
        L, rad = 0.08 * diag, 0.003 * diag
        for link, M in T.items():
            for axis, colour in ((0, [0.9, 0.1, 0.1, 1]), (1, [0.1, 0.75, 0.1, 1]), (2, [0.1, 0.2, 0.95, 1])):
                a = M[:3, 3]
                b = a + M[:3, axis] * L
                world.add_geom(type=mujoco.mjtGeom.mjGEOM_CAPSULE, fromto=[*a, *b], size=[rad, 0, 0], rgba=colour,
                               contype=0, conaffinity=0, group=2)
                extra.append(b)
    boxes: list = []
    marks: dict = {}
    dots: list = []           # (world point, "link" | "robot"): centres of mass
    if layers.inertia:
        for link in scene.robot.links.values():
            if link.name not in T:
                continue
            box = inertia_box(link.inertial)
            if box is None:
                continue
            M = T[link.name] @ box.pose
            # half extents, 0.5 mm proud: a box that fits its geometry exactly would flicker into it
            size = [max(s / 2, 1e-4) + 0.0005 for s in box.size]
            corners = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]) * size
            boxes.append(corners @ M[:3, :3].T + M[:3, 3])
            place(M, type=mujoco.mjtGeom.mjGEOM_BOX, size=size,
                  rgba=[0.15, 0.35, 1.0, 0.45] if box.valid else [1.0, 0.1, 0.1, 0.6], group=3)
            marks["impossible" if not box.valid else "box"] = True
            dots.append((M[:3, 3], "link"))          # drawn over the picture (render_image): never hidden
        mass, com = center_of_mass(scene.robot, scene.pose(q))
        if mass > 0:
            dots.append((np.asarray(com, dtype=float), "robot"))
    model = spec.compile()
    if boxes:
        # the picture frames the robot: an inertia box adds to the frame only as far as it stays
        # near the robot (a wrong inertia can make a box metres wide around a link of millimetres;
        # framing it would shrink the robot to a dot inside a blue cube)
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        reach = 0.08 * diag
        extra.extend(np.clip(np.vstack(boxes), lo - reach, hi + reach))
    if extra:
        pts = np.vstack([pts, np.asarray(extra, dtype=float).reshape(-1, 3)])
    marks["dots"] = dots
    return model, T, pts, marks


# ------------------------------------------------------------------ drawing
def render_image(scene, q: dict | None = None, views=("iso",), size=(800, 600), layers: Layers = Layers()):
    """A PIL image: one view, or a 2x2 grid for four (each tile labelled)."""
    import mujoco
    import numpy as np
    from PIL import Image

    W, H = size
    tiles = len(views) > 1
    tw, th = (W // 2, H // 2) if tiles else (W, H)
    model, T, pts, marks = build_model(scene, q or {}, layers)
    model.vis.global_.offwidth = max(tw, 64)
    model.vis.global_.offheight = max(th, 64)
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    opt = mujoco.MjvOption()
    for g in range(6):
        opt.geomgroup[g] = 1
    out = Image.new("RGB", (W, H), BACKGROUND)
    renderer = open_renderer(mujoco, model, th, tw)
    try:
        for i, view in enumerate(views):
            cam = camera_for(pts, view, tw / th)
            mcam = mujoco.MjvCamera()
            mcam.type = mujoco.mjtCamera.mjCAMERA_FREE
            mcam.orthographic = 1
            mcam.lookat[:] = cam.lookat
            mcam.azimuth, mcam.elevation = cam.azimuth, cam.elevation
            mcam.distance = 2.0 * cam.depth + 0.1
            model.vis.global_.fovy = cam.height
            renderer.update_scene(data, camera=mcam, scene_option=opt)
            img = Image.fromarray(np.ascontiguousarray(renderer.render()))
            if layers.frames:
                _label_frames(img, cam, T)
            _dots(img, cam, marks["dots"])
            if tiles:
                _caption(img, view)
            out.paste(img, ((i % 2) * tw, (i // 2) * th))
    finally:
        renderer.close()
    _legend(out, layers, marks)
    return out


def _dots(img, cam: Camera, dots) -> None:
    """Centres of mass as dots over the picture (inside a link's geometry a sphere would be hidden):
    black for each link, a larger magenta one for the robot, each with a white ring."""
    from PIL import ImageDraw

    d = ImageDraw.Draw(img)
    base = max(2, min(img.width, img.height) // 250)
    for p, kind in sorted(dots, key=lambda t: t[1] == "robot"):
        x, y = project(cam, p, img.width, img.height)
        r = base * (2 if kind == "robot" else 1)
        d.ellipse([x - r - 1.5, y - r - 1.5, x + r + 1.5, y + r + 1.5], fill=(255, 255, 255))
        d.ellipse([x - r, y - r, x + r, y + r], fill=(255, 0, 204) if kind == "robot" else (25, 25, 25))


# (colour, shape, text) of every mark a layer draws
LEGEND = {
    "collision": [((255, 140, 25), "square", "collision geometry")],
    "frames": [((230, 25, 25), "line", "x"), ((25, 190, 25), "line", "y"), ((25, 50, 240), "line", "z axis of a link frame")],
    "inertia": [((40, 90, 255), "square", "equivalent inertia box"), ((255, 25, 25), "square", "impossible moments"),
                ((25, 25, 25), "dot", "link centre of mass"), ((255, 0, 204), "dot", "robot centre of mass")],
}


def _legend(img, layers: Layers, marks: dict | None = None) -> None:
    """A key for the overlays drawn (bottom left): every colour and mark of the picture named."""
    from PIL import ImageDraw

    marks = marks or {}
    items = [it for name in ("collision", "frames", "inertia") if getattr(layers, name) for it in LEGEND[name]]
    if not marks.get("impossible"):
        items = [it for it in items if it[2] != "impossible moments"]
    if not any(kind == "robot" for _, kind in marks.get("dots", ())):
        items = [it for it in items if it[2] != "robot centre of mass"]
    if not items:
        return
    d = ImageDraw.Draw(img)
    size = max(11, min(16, img.height // 50))
    font = _font(size)
    x, y = 8, img.height - size - 10
    width = sum(d.textlength(text, font=font) + size + 20 for _, _, text in items) + 8
    d.rectangle([x - 4, y - 5, x + width, y + size + 5], fill=(250, 250, 252), outline=(190, 190, 200))
    for rgb, shape, text in items:
        box = [x, y + 2, x + size - 4, y + size - 2]
        if shape == "square":
            d.rectangle(box, fill=rgb)
        elif shape == "dot":
            d.ellipse(box, fill=rgb)
        else:
            d.line([box[0], (box[1] + box[3]) / 2, box[2], (box[1] + box[3]) / 2], fill=rgb, width=3)
        x += size + 2
        d.text((x, y), text, fill=(40, 40, 40), font=font)
        x += d.textlength(text, font=font) + 16


def open_renderer(mujoco, model, height: int, width: int):
    """mujoco.Renderer, or InputError saying which GL backend failed and what it needs."""
    import warnings

    try:
        with warnings.catch_warnings():        # glfw warns on stderr before it fails without a display
            warnings.simplefilter("ignore")
            return mujoco.Renderer(model, height, width)
    except Exception as exc:  # each backend fails with its own error type
        gl = os.environ.get("MUJOCO_GL", "")
        why = " ".join(str(exc).split())[:160]
        raise InputError(f"cannot render offscreen with MUJOCO_GL={gl}: {why} (unset MUJOCO_GL to pick EGL or "
                         "OSMesa; EGL needs libegl1 and libgl1-mesa-dri, OSMesa needs libosmesa6)") from None


def _font(size: int):
    from PIL import ImageFont

    try:
        return ImageFont.load_default(size=size)
    except TypeError:          # Pillow < 10.1
        return ImageFont.load_default()


def _label_frames(img, cam: Camera, T: dict) -> None:
    """Link names next to their frame origins; a name whose spot is taken is left out."""
    from PIL import ImageDraw

    d = ImageDraw.Draw(img)
    font = _font(10)
    taken: list = []
    for link, M in sorted(T.items(), key=lambda kv: kv[0]):
        x, y = project(cam, M[:3, 3], img.width, img.height)
        box = d.textbbox((x + 3, y - 12), link, font=font)
        if any(not (box[2] < b[0] or b[2] < box[0] or box[3] < b[1] or b[3] < box[1]) for b in taken):
            continue
        taken.append(box)
        d.text((x + 3, y - 12), link, fill=(20, 20, 20), font=font)


def _caption(img, text: str) -> None:
    from PIL import ImageDraw

    ImageDraw.Draw(img).text((8, 6), text, fill=(90, 90, 90), font=_font(14))


def png_bytes(img) -> bytes:
    import io

    buf = io.BytesIO()
    img.save(buf, format="PNG")
    return buf.getvalue()


# ------------------------------------------------------------------ inputs
def parse_size(text: str) -> tuple[int, int]:
    w, sep, h = text.lower().partition("x")
    try:
        W, H = int(w), int(h)
    except ValueError:
        raise InputError(f"--size {text!r}: expected WIDTHxHEIGHT in pixels, e.g. 1200x900") from None
    if not sep or W < 64 or H < 64 or W * H > MAX_PIXELS:
        raise InputError(f"--size {text!r}: each side at least 64 pixels, at most {MAX_PIXELS} pixels in all")
    return W, H


def read_pose(path: str, scene) -> dict[str, float]:
    """Joint values from a YAML file: ``NAME: VALUE`` lines, optionally under ``joints:``.

    The file is untrusted: read by the one YAML loader (expand/yaml_load.py: safety.read_checked,
    so regular files only and the input size limit; no tags but xacro's units, no alias bombs),
    never by PyYAML's shared loaders, which a build's ``load_yaml`` may have extended."""

    doc = load_path(path, limit("max_input_bytes"), name=str(path))
    if isinstance(doc, dict) and set(doc) == {"joints"}:
        doc = doc["joints"]
    if doc is None:
        return {}
    if not isinstance(doc, dict):
        raise InputError("a pose file holds joint values as NAME: VALUE lines (optionally under joints:)",
                         Loc(path, 1))
    items = []
    for k, v in doc.items():
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise InputError(f"joint {k!r}: {v!r} is not a number", Loc(path, None))
        items.append(f"{k}={v}")
    return parse_joint_values(items, scene, where=path + ":")
