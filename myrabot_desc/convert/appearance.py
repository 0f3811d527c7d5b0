"""Explicit SDF/MJCF colours for visuals.

gz-sim reads no OGRE scripts (anchors §6.2): a ``<gazebo><material>Gazebo/Grey``
or a seed script name such as ``myrabot_fer/Black`` must become explicit
ambient/diffuse/specular/emissive, and a texture a PBR albedo map. Names are
resolved by the shared resolver (``myrabot_desc.materials.resolve``); URDF
``<color>`` is used where no Gazebo material is set.
"""

from __future__ import annotations

from dataclasses import dataclass

from myrabot_desc.convert.common import sub
from myrabot_desc.materials import textures
from myrabot_desc.materials.resolve import resolver_for


@dataclass(frozen=True)
class Look:
    ambient: tuple
    diffuse: tuple
    specular: tuple = (0.1, 0.1, 0.1, 1.0)
    emissive: tuple = (0.0, 0.0, 0.0, 1.0)
    texture: str | None = None        # resolved file path or URI of the albedo map
    lighting: bool = True
    transparency: float = 0.0         # 0 opaque .. 1 invisible (goes on the <visual>)
    source: str = ""                  # for comments: 'urdf:white', 'gazebo:Gazebo/Grey'


def _rgba(v, default=None):
    if v is None:
        return default
    v = tuple(float(x) for x in v)
    return v + (1.0,) * (4 - len(v)) if len(v) < 4 else v[:4]


class Appearance:
    def __init__(self, robot, notes):
        self.robot = robot
        self.notes = notes
        self._unresolved: dict[str, object] = {}
        self._missing_tex: dict[str, object] = {}
        try:
            pass
        except ImportError:  # the shared resolver is not installed: URDF colours only
            self.resolver = None
        else:
            self.resolver = resolver_for(robot)

    def look(self, visual, gz_material: str | None, loc=None) -> Look | None:
        """The explicit appearance of one visual: the Gazebo material wins (as in Gazebo classic)."""
        if gz_material:
            found = self._lookup(gz_material)
            if found is not None:
                return found
            self._unresolved.setdefault(gz_material, loc)
        mat = visual.material
        if mat is not None and (mat.rgba is not None or mat.texture):
            rgba = _rgba(mat.rgba, (1.0, 1.0, 1.0, 1.0))
            tex = None
            if mat.texture:
                try:
                    p = self.robot.resolve_uri(mat.texture)
                except Exception:  # a malformed URI: reported like a missing file
                    p = None
                if p is not None and p.is_file():
                    tex = str(p)
                else:
                    self._missing_tex.setdefault(f"{mat.texture} (URDF material {mat.name})", None)
            return Look(ambient=rgba, diffuse=rgba, texture=tex, source=f"urdf:{mat.name}")
        return None

    def _lookup(self, name: str) -> Look | None:
        if self.resolver is None:
            return None
        m = self.resolver.lookup(name)
        if m is None:
            return None
        diffuse = _rgba(getattr(m, "diffuse", None), (1.0, 1.0, 1.0, 1.0))
        ambient = _rgba(getattr(m, "ambient", None), diffuse)
        tex = getattr(m, "texture_path", None)
        if tex is None and getattr(m, "texture", None):
            self._missing_tex.setdefault(f"{m.texture} ({name})", None)
        return Look(ambient=ambient, diffuse=diffuse,
                    specular=_rgba(getattr(m, "specular", None), (0.0, 0.0, 0.0, 1.0)),
                    emissive=_rgba(getattr(m, "emissive", None), (0.0, 0.0, 0.0, 1.0)),
                    texture=str(tex) if tex else None,
                    lighting=bool(getattr(m, "lighting", True)),
                    transparency=float(getattr(m, "transparency", 0.0) or 0.0), source=f"gazebo:{name}")

    def finish(self) -> None:
        if self._missing_tex:
            self.notes.warn("texture image(s) not found next to their material script, colour only: "
                            + ", ".join(sorted(self._missing_tex)))
        if self._unresolved:
            names = ", ".join(sorted(self._unresolved))
            self.notes.warn(f"Gazebo material(s) not found in any script or the stock table, URDF colour "
                            f"kept: {names}")


def texture_mean_rgb(path) -> tuple[float, float, float] | None:
    """Average colour of a texture image (MuJoCo gets one rgba per geom: a can is then red-ish,
    not white). None when the image cannot be read."""

    return textures.mean_rgb(path)     # path gate, size and pixel limits (materials/textures.py)


def material_element(parent, look: Look, uri_mapper=None):
    m = sub(parent, "material")
    sub(m, "ambient", look.ambient)
    sub(m, "diffuse", look.diffuse)
    sub(m, "specular", look.specular)
    sub(m, "emissive", look.emissive)
    if not look.lighting:
        sub(m, "lighting", False)
    if look.texture:
        if uri_mapper is None:
            tex = look.texture
        elif "://" in look.texture:
            tex = uri_mapper.map(look.texture)
        else:
            tex = uri_mapper.map_file(look.texture)
        sub(sub(sub(m, "pbr"), "metal"), "albedo_map", tex)
    return m
