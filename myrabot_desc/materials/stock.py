"""Gazebo classic's stock materials (``Gazebo/Grey`` and friends) as explicit values.

Facts copied from ``gazebo.material``: the copy gz-sim keeps at
``src/rendering/MaterialParser/gazebo.material`` (gazebosim/gz-sim, read at commit 29dc2aab),
which is Gazebo classic's ``media/materials/scripts/gazebo.material`` (gazebosim/gazebo-classic
56a89a1c) plus ``Gray``/``DarkGray`` aliases, ``DarkYellow``, ``Indigo``, ``BlackTransparent`` and
a few editor materials. Colours are kept as written (3, 4 or 5 numbers; ``specular r g b [a]
shininess``), pass by pass, so inheritance (``WhiteGlow : White``) works as in a script. Program-only
materials (DepthMap, LaserScan*, camera noise/distortion...) and ``PointCloud`` (vertex colours)
are left out: they are not surface colours.

Why explicit colours: gz-sim cannot read OGRE scripts. For a ``Gazebo/...`` name it looks the
values up in its copy of this file with ``MaterialParser::GetMaterialValues``, which matches by
**substring** over every material name in (sorted) order and lets later matches overwrite
earlier ones, reading only the first pass, and does not follow parents (anchors.md §6.2). So in
gz-sim ``Gazebo/Grey`` picks up ``Gazebo/GreyTransparent``'s 0.5 grey, ``Gazebo/Gray`` gets nothing,
and ``Gazebo/White``'s diffuse is lost (it lives in the second pass). :func:`gz_sim_values`
emulates that rule so ``check`` can say what gz-sim would show; ``convert`` writes the values of
:func:`stock_material` instead. The emulation is read from the code, not observed in a running
gz-sim.
"""

from __future__ import annotations

from functools import lru_cache

# name -> (parent, passes); a pass is a dict of the script's values as written.
# Keys: name, ambient, diffuse, specular (raw: r g b [a] shininess), emissive, lighting,
# scene_blend, depth_write, texture, scale, manual (colour_op_ex src_manual r g b),
# alpha (alpha_op_ex src_manual a).
_GREY_ROAD = dict(ambient=(0.1, 0.1, 0.1, 1.0), diffuse=(0.8, 0.8, 0.8, 1.0), specular=(0.01, 0.01, 0.01, 1.0, 2.0))
_WHITE_TEX = dict(ambient=(1.0, 1.0, 1.0, 1.0), diffuse=(1.0, 1.0, 1.0, 1.0), specular=(0.2, 0.2, 0.2, 1.0, 12.5))
_SPEC01 = (0.1, 0.1, 0.1, 1, 1)
_BLEND = dict(scene_blend="alpha_blend", depth_write=False)

STOCK_SOURCE: dict[str, tuple[str | None, list[dict]]] = {
    "Gazebo/Grey": (None, [dict(name="main", ambient=(.3, .3, .3, 1.0), diffuse=(.7, .7, .7, 1.0),
                                specular=(0.01, 0.01, 0.01, 1.0, 1.5))]),
    "Gazebo/Gray": ("Gazebo/Grey", []),
    "Gazebo/DarkGrey": (None, [dict(name="main", ambient=(.175, .175, .175, 1.0), diffuse=(.175, .175, .175, 1.0),
                                    specular=(.175, .175, .175, 1.0, 1.5))]),
    "Gazebo/DarkGray": ("Gazebo/DarkGrey", []),
    "Gazebo/White": (None, [dict(name="ambient", ambient=(1, 1, 1, 1)),
                            dict(name="light", diffuse=(1, 1, 1, 1), specular=(.1, .1, .1, 128))]),
    "Gazebo/FlatBlack": (None, [dict(ambient=(0.1, 0.1, 0.1), diffuse=(0.1, 0.1, 0.1),
                                     specular=(0.01, 0.01, 0.01, 1.0, 1.0))]),
    "Gazebo/Black": (None, [dict(ambient=(0, 0, 0, 1), diffuse=(0, 0, 0, 1), specular=(0.1, 0.1, 0.1, 1, 5.0))]),
    "Gazebo/Red": (None, [dict(name="ambient", ambient=(1, 0, 0), diffuse=(1, 0, 0), specular=_SPEC01)]),
    "Gazebo/RedBright": (None, [dict(name="ambient", ambient=(0.87, 0.26, 0.07), diffuse=(0.87, 0.26, 0.07),
                                     specular=(0.87, 0.26, 0.07, 1, 1))]),
    "Gazebo/Green": (None, [dict(name="ambient", ambient=(0, 1, 0), diffuse=(0, 1, 0), specular=_SPEC01)]),
    "Gazebo/Blue": (None, [dict(name="ambient", ambient=(0, 0, 1), diffuse=(0, 0, 1), specular=_SPEC01)]),
    "Gazebo/SkyBlue": (None, [dict(name="ambient", ambient=(0.13, 0.44, 0.70), diffuse=(0, 0, 1), specular=_SPEC01)]),
    "Gazebo/Yellow": (None, [dict(name="ambient", ambient=(1, 1, 0, 1), diffuse=(1, 1, 0, 1), specular=(0, 0, 0, 0, 0))]),
    "Gazebo/ZincYellow": (None, [dict(name="ambient", ambient=(0.9725, 0.9529, 0.2078, 1),
                                      diffuse=(0.9725, 0.9529, 0.2078, 1), specular=(0.9725, 0.9529, 0.2078, 1, 1))]),
    "Gazebo/DarkYellow": (None, [dict(name="ambient", ambient=(0.7, 0.7, 0, 1), diffuse=(0.7, 0.7, 0, 1),
                                      specular=(0, 0, 0, 0, 0))]),
    "Gazebo/Purple": (None, [dict(name="ambient", ambient=(1, 0, 1), diffuse=(1, 0, 1), specular=_SPEC01)]),
    "Gazebo/Turquoise": (None, [dict(name="ambient", ambient=(0, 1, 1), diffuse=(0, 1, 1), specular=_SPEC01)]),
    "Gazebo/Orange": (None, [dict(name="ambient", lighting=True, ambient=(1, 0.5088, 0.0468, 1),
                                  diffuse=(1, 0.5088, 0.0468, 1), specular=(0.5, 0.5, 0.5, 128))]),
    "Gazebo/Indigo": (None, [dict(name="ambient", ambient=(0.33, 0.0, 0.5), diffuse=(0.33, 0.0, 0.5),
                                  specular=(0.1, 0.1, 0.1, 1))]),
    "Gazebo/WhiteGlow": ("Gazebo/White", [dict(name="light", emissive=(1, 1, 1))]),
    "Gazebo/RedGlow": (None, [dict(name="ambient", ambient=(1, 0, 0), diffuse=(1, 0, 0), emissive=(1, 0, 0),
                                   specular=(0, 0, 0, 128)),
                              dict(name="light", ambient=(1, 0, 0), diffuse=(1, 0, 0), emissive=(1, 0, 0),
                                   specular=(1, 0, 0, 128))]),
    "Gazebo/GreenGlow": ("Gazebo/Green", [dict(name="ambient", emissive=(0, 1, 0)),
                                          dict(name="light", emissive=(0, 1, 0))]),
    "Gazebo/BlueGlow": ("Gazebo/Blue", [dict(name="light", emissive=(0, 0, 1))]),
    "Gazebo/YellowGlow": ("Gazebo/Yellow", [dict(name="light", emissive=(1, 1, 0))]),
    "Gazebo/PurpleGlow": ("Gazebo/Purple", [dict(name="light", emissive=(1, 0, 1))]),
    "Gazebo/TurquoiseGlow": ("Gazebo/Turquoise", [dict(name="light", emissive=(0, 1, 1))]),
    "Gazebo/TurquoiseGlowOutline": (None, [
        dict(name="ambient", scene_blend="alpha_blend", diffuse=(0, 1, 1, 1), specular=(.1, .1, .1, 128)),
        dict(name="ambient2", scene_blend="alpha_blend", diffuse=(0, 1, 1), specular=(.1, .1, .1, 128),
             emissive=(0, 1, 1))]),
    "Gazebo/RedTransparentOverlay": (None, [dict(**_BLEND, lighting=False, manual=(1, 0, 0), alpha=0.5)]),
    "Gazebo/BlueTransparentOverlay": (None, [dict(**_BLEND, lighting=False, manual=(0, 0, 1), alpha=0.5)]),
    "Gazebo/GreenTransparentOverlay": (None, [dict(**_BLEND, lighting=False, manual=(0, 1, 0), alpha=0.5)]),
    "Gazebo/OrangeTransparentOverlay": (None, [dict(**_BLEND, lighting=False, ambient=(1, 0.5088, 0.0468),
                                                    manual=(1, 0.5088, 0.0468), alpha=0.8)]),
    "Gazebo/DarkOrangeTransparentOverlay": (None, [dict(**_BLEND, lighting=False, ambient=(0.6, 0.305, 0.028),
                                                        manual=(0.6, 0.305, 0.028), alpha=0.8)]),
    "Gazebo/RedTransparent": (None, [dict(**_BLEND, lighting=False, manual=(1, 0, 0), alpha=0.5)]),
    "Gazebo/GreenTransparent": (None, [dict(**_BLEND, ambient=(0.0, 1.0, 0.0, 1), diffuse=(0.0, 1.0, 0.0, 1), alpha=0.5)]),
    "Gazebo/BlueTransparent": (None, [dict(**_BLEND, ambient=(0.0, 0.0, 1.0, 1), diffuse=(0.0, 0.0, 1.0, 1), alpha=0.5)]),
    "Gazebo/DarkMagentaTransparent": (None, [dict(**_BLEND, ambient=(0.6, 0.0, 0.6, 1), diffuse=(0.6, 0.0, 0.6, 1),
                                                  alpha=0.5)]),
    "Gazebo/GreyTransparent": (None, [dict(**_BLEND, ambient=(0.5, 0.5, 0.5, 1), diffuse=(0.5, 0.5, 0.5, 1), alpha=0.5)]),
    "Gazebo/BlackTransparent": (None, [dict(**_BLEND, ambient=(0.0, 0.0, 0.0, 1), diffuse=(0.0, 0.0, 0.0, 1), alpha=0.5)]),
    "Gazebo/YellowTransparent": (None, [dict(**_BLEND, ambient=(1.0, 1.0, 0.0, 1), diffuse=(1.0, 1.0, 0.0, 1), alpha=0.5)]),
    "Gazebo/LightOn": (None, [dict(name="ambient", diffuse=(0, 1, 0), ambient=(0, 1, 0), emissive=(0, 1, 0))]),
    "Gazebo/LightOff": (None, [dict(name="ambient", diffuse=(1, 0, 0), ambient=(1, 0, 0), emissive=(1, 0, 0))]),
    "Gazebo/LightBlueLaser": (None, [dict(**_BLEND, ambient=(0.5, 0.5, 1.0, 1), diffuse=(0.5, 0.5, 1.0, 1), alpha=0.4)]),
    "Gazebo/BlueLaser": (None, [dict(**_BLEND, ambient=(0.0, 0.0, 1.0, 1), diffuse=(0.0, 0.0, 1.0, 1), alpha=0.4)]),
    "Gazebo/OrangeTransparent": (None, [dict(**_BLEND, ambient=(1.0, 0.44, 0.0, 1), diffuse=(1.0, 0.44, 0.0, 1), alpha=0.4)]),
    "Gazebo/JointAnchor": (None, [dict(ambient=(1, 1, 1, 1), diffuse=(1, 1, 1, 1), specular=(1, 1, 1, 1),
                                       emissive=(1, 1, 1, 1), lighting=False)]),
    "Gazebo/CoM": (None, [dict(ambient=(0.5, 0.5, 0.5, 1), texture="com.png")]),
    "Gazebo/WoodFloor": (None, [dict(ambient=(0.5, 0.5, 0.5, 1), texture="hardwood_floor.jpg")]),
    "Gazebo/CeilingTiled": (None, [dict(ambient=(0.5, 0.5, 0.5, 1), texture="ceiling_tiled.jpg")]),
    "Gazebo/PaintedWall": (None, [dict(ambient=(1.0, 1.0, 1.0, 1), texture="paintedWall.jpg")]),
    "Gazebo/PioneerBody": (None, [
        dict(name="Ambient", ambient=(0.5, 0, 0), texture="pioneerBody.jpg"),
        dict(name="DirectionalLight", ambient=(0, 0, 0), diffuse=(1, 0, 0, 1), specular=(0.5, 0, 0, 1, 10),
             texture="pioneerBody.jpg"),
        dict(name="PointLight", ambient=(0, 0, 0), diffuse=(1, 0, 0, 1), specular=(0.5, 0, 0, 1, 10),
             texture="pioneerBody.jpg")]),
    "Gazebo/Pioneer2Body": (None, [dict(ambient=(0.481193, 0.000123, 0.000123, 1.0),
                                        diffuse=(0.681193, 0.000923, 0.000923, 1.0),
                                        specular=(0.5, 0.5, 0.5, 1.0, 12.5), emissive=(0.0, 0.0, 0.0, 1.0))]),
    "Gazebo/Gold": (None, [dict(ambient=(0.4, 0.248690, 0.020759, 1.0), diffuse=(0.8, 0.648690, 0.120759, 1.0),
                                specular=(0.4, 0.4, 0.4, 1.0, 12.5))]),
    "Gazebo/GreyGradientSky": (None, [dict(depth_write=False, lighting=False, texture="grey_gradient.jpg")]),
    "Gazebo/CloudySky": (None, [dict(depth_write=False, lighting=False, texture="clouds.jpg")]),
    "Gazebo/WoodPallet": (None, [dict(ambient=(0.5, 0.5, 0.5, 1.0), diffuse=(1.0, 1.0, 1.0, 1.0),
                                      specular=(0.0, 0.0, 0.0, 1.0, 0.5), texture="WoodPallet.png")]),
    "Gazebo/Wood": (None, [dict(**_WHITE_TEX, texture="wood.jpg")]),
    "Gazebo/Bricks": (None, [dict(**_WHITE_TEX, texture="bricks.png")]),
    "Gazebo/Road": (None, [dict(**_GREY_ROAD, texture="road1.jpg")]),
    "Gazebo/Residential": (None, [dict(**_GREY_ROAD, texture="residential.jpg")]),
    "Gazebo/Tertiary": (None, [dict(**_GREY_ROAD, texture="residential.jpg")]),
    "Gazebo/Pedestrian": (None, [dict(**_GREY_ROAD, texture="sidewalk.jpg")]),
    "Gazebo/Footway": (None, [dict(**_GREY_ROAD, texture="sidewalk.jpg")]),
    "Gazebo/Motorway": (None, [dict(**_GREY_ROAD, texture="motorway.jpg")]),
    "Gazebo/Lanes_6": (None, [dict(**_GREY_ROAD, texture="motorway.jpg")]),
    "Gazebo/Trunk": (None, [dict(**_GREY_ROAD, texture="trunk.jpg")]),
    "Gazebo/Lanes_4": (None, [dict(**_GREY_ROAD, texture="trunk.jpg")]),
    "Gazebo/Primary": (None, [dict(**_GREY_ROAD, texture="primary.jpg")]),
    "Gazebo/Lanes_2": (None, [dict(**_GREY_ROAD, texture="primary.jpg")]),
    "Gazebo/Secondary": (None, [dict(**_GREY_ROAD, texture="secondary.jpg")]),
    "Gazebo/Lane_1": (None, [dict(**_GREY_ROAD, texture="secondary.jpg")]),
    "Gazebo/Steps": (None, [dict(**_GREY_ROAD, texture="steps.jpeg")]),
    "drc/san_fauxcity_sign": (None, [dict(ambient=(0.8, 0.8, 0.8, 1.0), diffuse=(0.8, 0.8, 0.8, 1.0),
                                          specular=(0.1, 0.1, 0.1, 1.0, 2.0), texture="san_fauxcity.png")]),
    "Gazebo/PointHandle": (None, [dict(lighting=False, scene_blend="alpha_blend", depth_write=False)]),
    "Gazebo/BuildingFrame": (None, [dict(**_WHITE_TEX, texture="building_frame.png")]),
    "Gazebo/Runway": (None, [dict(ambient=(0.5, 0.5, 0.5, 1.0), texture="runway.png")]),
    "Gazebo/Grass": (None, [dict(ambient=(0.5, 0.5, 0.5, 1.0), texture="grass.jpg", scale=(.02, .02))]),
    "Gazebo/Editor": (None, [dict(name="ambient", ambient=(1.0, 1.0, 1.0, 1.0), diffuse=(1.0, 1.0, 1.0, 1),
                                  specular=(.1, .1, .1, 128))]),
    "Gazebo/EditorPlane": (None, [dict(scene_blend="colour_blend", ambient=(.3, .3, .3, 1.0), diffuse=(.7, .7, .7, 1.0),
                                       specular=(0.01, 0.01, 0.01, 1.0, 1.5))]),
}

# Names in gz-sim's gazebo.material that carry no surface colour (programs, vertex colours);
# they still take part in gz-sim's substring matching, but never set a value.
_NO_COLOUR_NAMES = ("grid", "Gazebo/DepthMap", "Gazebo/XYZPoints", "Gazebo/Reflectance", "Gazebo/XYZNormals",
                    "Gazebo/LaserScan1st", "Gazebo/LaserScan2nd", "Gazebo/GaussianCameraNoise",
                    "Gazebo/CameraDistortionMap", "Gazebo/WideLensMap", "Gazebo/CameraLensFlare",
                    "Gazebo/PointCloud")


def _rgba(v) -> tuple[float, float, float, float]:
    v = tuple(float(x) for x in v)
    return v if len(v) == 4 else (*v, 1.0)


def _pass(d: dict):
    """The ogre.Pass of a pass as written in STOCK_SOURCE."""
    from myrabot_desc.materials.ogre import Pass, TextureUnit    # (the reader only for values: see stock_material)

    props: dict = {}
    for k in ("ambient", "diffuse", "emissive"):
        if k in d:
            props[k] = _rgba(d[k])
    if "specular" in d:
        s = tuple(float(x) for x in d["specular"])
        if len(s) == 5:
            props["specular"], props["shininess"] = s[:4], s[4]
        elif len(s) == 4:
            props["specular"], props["shininess"] = (*s[:3], 1.0), s[3]
        else:
            props["specular"] = _rgba(s)
    for k in ("lighting", "scene_blend", "depth_write"):
        if k in d:
            props[k] = d[k]
    units = ()
    if "texture" in d or "manual" in d or "alpha" in d:
        units = (TextureUnit(texture=d.get("texture"), scale=d.get("scale", (1.0, 1.0)),
                             manual_colour=tuple(float(x) for x in d["manual"]) if "manual" in d else None,
                             manual_alpha=d.get("alpha")),)
    return Pass(name=d.get("name"), props=props, texture_units=units)


def names() -> list[str]:
    """Every stock material name we know, in the file's order."""
    return list(STOCK_SOURCE)


def is_stock(name: str) -> bool:
    return name in STOCK_SOURCE


@lru_cache(maxsize=None)
def stock_material(name: str):
    """The stock material ``name`` as an ogre.Material (parents applied), or None when it is not a
    stock name."""
    # the OGRE reader's records only here: `check` asks is_stock of a model's names, not their values
    from myrabot_desc.materials.ogre import Technique, _merge_list, _merge_technique, summarize

    if name not in STOCK_SOURCE:
        return None
    parent, passes = STOCK_SOURCE[name]
    techs = [Technique(passes=tuple(_pass(p) for p in passes))] if passes else []
    base: list = list(stock_material(parent).techniques) if parent else []
    return summarize(name, parent, tuple(_merge_list(base, techs, _merge_technique)), None)


def gz_sim_values(name: str) -> dict[str, tuple] | None:
    """What gz-sim's ``MaterialParser::GetMaterialValues(name)`` would return, emulated.

    Substring match over all names in sorted order, later matches overwrite; first pass only;
    ambient/diffuse as rgb (alpha 1); specular = the first four numbers as written (so
    ``specular .1 .1 .1 128`` gives alpha 128). Returns None when nothing matched with values.
    """
    values: dict[str, tuple] = {}
    keys = sorted(list(STOCK_SOURCE) + list(_NO_COLOUR_NAMES))
    for key in keys:
        header = key
        parent = STOCK_SOURCE.get(key, (None, []))[0]
        if parent:
            header = f"{key} : {parent}"          # the header line is what gets searched
        if name not in header:
            continue
        passes = STOCK_SOURCE.get(key, (None, []))[1]
        if not passes:
            continue
        first = passes[0]
        for k in ("ambient", "diffuse"):
            if k in first:
                values[k] = (*(float(x) for x in first[k][:3]), 1.0)
        if "specular" in first:
            s = [float(x) for x in first["specular"]]
            values["specular"] = tuple(s[:4]) if len(s) >= 4 else (*s, 1.0)
    return values or None
