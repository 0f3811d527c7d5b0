"""OGRE material scripts: reader, stock table, shared resolver, `materials` command."""

from __future__ import annotations

import json
from types import SimpleNamespace

import pytest
from click.testing import CliRunner
from hypothesis import given, settings
from hypothesis import strategies as st
from lxml import etree

from helpers import FIXTURES
from myrabot_desc.commands.materials import materials_cmd
from myrabot_desc.errors import InputError
from myrabot_desc.materials import ogre, scripts, stock
from myrabot_desc.materials.resolve import (
    MaterialResolver,
    resolver_for,
    search_dirs_for,
)
from myrabot_desc.model.loader import load_robot

FIX = FIXTURES / "materials"
OBJETOS = FIX / "objetos_fer_modelos"
BRAZO = FIX / "brazo_fer_modelo"
FER = OBJETOS / "Media/materials/scripts/myrabot_fer.material"
BRAZO_FER = BRAZO / "Media/materials/scripts/brazo_fer.material"
SEED_OBJETOS = FIXTURES / "seed_myrabot" / "objetos_fer_modelos"


# ------------------------------------------------------------------ the seed's script
def test_seed_myrabot_fer_blocks():
    s = scripts.parse_file(FER)
    assert list(s.materials) == ["material_fer/NOMBRE_DEL_NUEVO_MATERIAL", "material_fer/Amstel",
                                 "Gazebo/CocaCola"]
    assert [m.loc.line for m in s.materials.values()] == [1, 29, 57]
    amstel = s.materials["material_fer/Amstel"]
    assert amstel.texture == "amstel.png"
    assert amstel.texture_rotate == 180.0 and amstel.texture_scale == (1.0, 1.0)
    assert amstel.lighting is False
    assert amstel.ambient == (1, 1, 1, 1) and amstel.diffuse == (1, 1, 1, 1)
    # "specular 0 0 0 0" is r g b + shininess 0 (Ogre), "emissive 0 0 0" gets alpha 1
    assert amstel.specular == (0, 0, 0, 1) and amstel.shininess == 0
    assert amstel.emissive == (0, 0, 0, 1)
    assert amstel.alpha_rejection == "greater 128" and amstel.depth_write is True
    unit = amstel.techniques[0].passes[0].texture_units[0]
    assert unit.colour_op == "modulate" and unit.tex_coord_set == 0 and unit.line == 45
    assert s.materials["Gazebo/CocaCola"].texture == "coca_cola.png"
    assert s.materials["material_fer/NOMBRE_DEL_NUEVO_MATERIAL"].texture == "NUESTRO_ARCHIVO_DE_IMAGEN"


def test_fixture_copy_matches_seed_fixture():
    # Our copy is the seed's file byte for byte (the seed-fixtures helper extracted it from C.7).
    seed = SEED_OBJETOS / "Media/materials/scripts/myrabot_fer.material"
    if seed.exists():
        assert seed.read_bytes() == FER.read_bytes()


def test_brazo_fer_two_named_passes_and_transparency():
    s = scripts.parse_file(BRAZO_FER)
    black, white, wt = (s.materials[n] for n in ("brazo_fer/Black", "brazo_fer/White", "brazo_fer/WhiteTransparent"))
    assert black.ambient == (0, 0, 0, 1) and black.diffuse == (0, 0, 0, 1) and black.lighting is True
    passes = white.techniques[0].passes
    assert [p.name for p in passes] == ["Ambient", "PointLight"]
    assert all(p.props["specular"] == (0.8, 0.8, 0.8, 1.0) and p.props["shininess"] == 20 for p in passes)
    assert white.specular == (0.8, 0.8, 0.8, 1.0) and white.shininess == 20
    assert wt.scene_blend == "alpha_blend" and wt.depth_write is False
    assert wt.transparency == pytest.approx(0.6)          # alpha_op_ex ... src_manual 0.4
    assert wt.diffuse == (1, 1, 1, 1) and black.transparency == 0


# ------------------------------------------------------------------ inheritance, comments
def test_inheritance_override_by_name_position_stock_and_import():
    s = scripts.parse_file(FIX / "inheritance.material")
    base, glow, red = s.materials["fer/Base"], s.materials["fer/Glow"], s.materials["fer/GlowRed"]
    assert base.ambient == (0.2, 0.2, 0.2, 1) and base.diffuse == (0.6, 0.6, 0.6, 1) and base.shininess == 64
    assert glow.parent == "fer/Base"
    assert [p.name for p in glow.techniques[0].passes] == ["ambient", "light"]   # overridden, not appended
    assert glow.emissive == (0, 0.5, 0, 1) and glow.ambient == base.ambient and glow.diffuse == base.diffuse
    assert red.ambient == (1, 0, 0, 1) and red.emissive == (0, 0.5, 0, 1)        # unnamed pass -> position 0
    assert "emissive" not in base.explicit and "emissive" in glow.explicit
    shiny = s.materials["fer/GreyShiny"]                                          # parent from the stock table
    assert shiny.ambient == (0.3, 0.3, 0.3, 1) and shiny.diffuse == (0.7, 0.7, 0.7, 1)
    assert shiny.specular == (1, 1, 1, 1) and shiny.shininess == 50
    painted = s.materials["fer/Painted"]                                          # parent from the import
    assert painted.texture == "paint.jpg" and painted.texture_scale == (2.0, 0.5)
    assert painted.diffuse == (0.4, 0.5, 0.6, 0.5) and painted.transparency == pytest.approx(0.5)
    assert s.imports == ["imported.material"] and "imported/Paint" not in s.materials


def test_new_named_pass_is_appended():
    text = ("material A { technique { pass one { ambient 0.1 0.1 0.1 } } }\n"
            "material B : A { technique { pass two { diffuse 0 0 1 } } }\n")
    s = scripts.parse_text(text, "t.material")
    assert [p.name for p in s.materials["B"].techniques[0].passes] == ["one", "two"]
    assert s.materials["B"].ambient == (0.1, 0.1, 0.1, 1) and s.materials["B"].diffuse == (0, 0, 1, 1)


def test_comments_programs_and_quotes_are_skipped():
    s = scripts.parse_file(FIX / "comments.material")
    assert list(s.materials) == ["fer/Water", "fer/OneLine"]                     # fer/Ghost is commented out
    water = s.materials["fer/Water"]
    assert water.ambient == (0, 0.3, 0.6, 1)                                       # /* inline */ removed
    assert water.diffuse == (0, 0.4, 0.8, 1) and water.specular == (0.5, 0.5, 0.5, 1) and water.shininess == 32
    assert water.emissive == (0, 0, 0.1, 1)
    assert water.texture == "water surface.png" and water.texture_rotate == 90 and water.texture_scale == (0.25, 0.25)
    assert water.loc.line == 17
    assert s.materials["fer/OneLine"].diffuse == (0.9, 0.8, 0.7, 1)
    assert any("does_not_exist.material" in w and ":4:" in w for w in s.warnings)


@pytest.mark.parametrize("text,check", [
    ("material A { technique { pass { specular 0.5 0.5 0.5 128 } } }",
     lambda m: m.specular == (0.5, 0.5, 0.5, 1) and m.shininess == 128),
    ("material A { technique { pass { specular 0.1 0.2 0.3 0.4 5 } } }",
     lambda m: m.specular == (0.1, 0.2, 0.3, 0.4) and m.shininess == 5),
    ("material A { technique { pass { ambient vertexcolour\n diffuse .5 .5 .5 } } }",
     lambda m: "ambient" not in m.explicit and m.diffuse == (0.5, 0.5, 0.5, 1)),
    ("abstract material A { technique { pass { ambient 0 0 1 } } }\nmaterial B:A { }",
     lambda m: m.name == "B" and m.ambient == (0, 0, 1, 1)),
    ("material A { technique { pass { lighting off\n scene_blend add } } }",
     lambda m: m.lighting is False and m.scene_blend == "add" and m.transparency == 0),
    ("material A { technique { pass { texture_unit { colour_op_ex source1 src_manual src_current 1 0 0\n"
     " alpha_op_ex source1 src_manual src_current 0.25 } scene_blend alpha_blend } } }",
     lambda m: m.diffuse == (1, 0, 0, 1) and m.transparency == 0.75),
])
def test_pass_attributes(text, check):
    mats = scripts.parse_text(text, "t.material").materials
    assert check(list(mats.values())[-1])


# ------------------------------------------------------------------ errors with lines
@pytest.mark.parametrize("name,line,words", [
    ("unbalanced", 13, "a '}' is missing before line 13"),
    ("extra_brace", 11, "unexpected '}'"),
    ("bad_number", 8, "'O.5' is not a number"),
    ("unknown_parent", 2, "parent 'Gazebo/Gris' is not defined"),
    ("truncated", 8, "never closed: the file ends at line 10"),
    ("unclosed_comment", 3, "'/*' comment is never closed"),
    ("cycle", 5, "inheritance cycle"),
    ("wrong_count", 7, "ambient takes 3 or 4 numbers"),
])
def test_malformed_scripts_raise_with_line(name, line, words):
    path = FIX / "malformed" / f"{name}.material"
    with pytest.raises(InputError) as ei:
        scripts.parse_file(path)
    assert ei.value.loc.file == str(path) and ei.value.loc.line == line
    assert words in ei.value.message


@pytest.mark.parametrize("text,line,words", [
    ("material A\n{\n technique { pass { specular 1 2 } }\n}", 3, "specular takes"),
    ("material A {\n technique { pass {\n lighting maybe } } }", 3, "'on' or 'off'"),
    ("material A {\n technique { pass { ambient 1 nan 1 } } }", 2, "not a number"),
    ("\n{ }", 2, "'{' without a block name"),
    ("material A : \n{ }", 1, "without a parent name"),
    ("material A", 1, "has no '{ ... }' body"),
    ("ambient 1 1 1", 1, "outside any block"),
    ('import * from "x.material\n', 1, "unterminated string"),
])
def test_inline_errors(text, line, words):
    with pytest.raises(InputError) as ei:
        scripts.parse_text(text, "inline.material")
    assert ei.value.loc.line == line and words in ei.value.message


def test_limits_size_and_depth(tmp_path):
    deep = "material A\n" + "{ x\n" * 40 + "}\n" * 40
    with pytest.raises(InputError, match="deeper than 32"):
        scripts.parse_text(deep, "deep.material")
    scripts.parse_text("material A\n" + "{ x\n" * 30 + "}\n" * 30, "ok.material")      # 31 levels is fine
    big = tmp_path / "big.material"
    big.write_bytes(b"// padding\n" * ((5 * 1024 * 1024) // 11 + 1))
    with pytest.raises(InputError, match="over the 5242880-byte limit"):
        scripts.parse_file(big)
    with pytest.raises(InputError, match="over the 100-byte limit"):
        scripts.parse_file(BRAZO_FER, max_bytes=100)


def test_size_limit_from_the_environment(tmp_path, monkeypatch):
    """Like the other limits, the 5 MB one is set with MYRABOT_DESC_MAX_MATERIAL_BYTES."""
    big = tmp_path / "big.material"
    big.write_bytes(b"// padding\n" * ((5 * 1024 * 1024) // 11 + 1) + b"material A { }\n")
    monkeypatch.setenv("MYRABOT_DESC_MAX_MATERIAL_BYTES", str((5 * 1024 * 1024) * 2))
    assert "A" in scripts.parse_file(big).materials
    monkeypatch.setenv("MYRABOT_DESC_MAX_MATERIAL_BYTES", "100")
    r = _run(BRAZO_FER)
    assert r.exit_code == 2
    assert "over the 100-byte limit (MYRABOT_DESC_MAX_MATERIAL_BYTES)" in r.output


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(min_value=0, max_value=1, allow_nan=False).map(lambda v: round(v, 4)),
                min_size=4, max_size=4), st.booleans())
def test_colour_round_trip(vals, four):
    cols = vals if four else vals[:3]
    text = f"material R {{ technique {{ pass {{ diffuse {' '.join(repr(v) for v in cols)} }} }} }}"
    m = scripts.parse_text(text, "r.material").materials["R"]
    assert m.diffuse == (tuple(cols) if four else (*cols, 1.0))


# ------------------------------------------------------------------ stock table
def test_stock_values_from_gazebo_material():
    grey = stock.stock_material("Gazebo/Grey")
    assert grey.ambient == (0.3, 0.3, 0.3, 1) and grey.diffuse == (0.7, 0.7, 0.7, 1)
    assert grey.specular == (0.01, 0.01, 0.01, 1) and grey.shininess == 1.5
    gray = stock.stock_material("Gazebo/Gray")                      # `Gazebo/Gray : Gazebo/Grey`
    assert (gray.ambient, gray.diffuse, gray.parent) == (grey.ambient, grey.diffuse, "Gazebo/Grey")
    white = stock.stock_material("Gazebo/White")                    # ambient pass + light pass
    assert white.ambient == (1, 1, 1, 1) and white.diffuse == (1, 1, 1, 1) and white.shininess == 128
    assert stock.stock_material("Gazebo/WhiteGlow").emissive == (1, 1, 1, 1)
    assert stock.stock_material("Gazebo/Orange").diffuse == (1, 0.5088, 0.0468, 1)
    assert stock.stock_material("Gazebo/Indigo").ambient == (0.33, 0.0, 0.5, 1)
    assert stock.stock_material("Gazebo/Wood").texture == "wood.jpg"
    assert stock.stock_material("Gazebo/RedTransparent").diffuse == (1, 0, 0, 1)
    assert stock.stock_material("Gazebo/GreyTransparent").transparency == 0.5
    assert stock.stock_material("Gazebo/Gold").diffuse == (0.8, 0.64869, 0.120759, 1)
    assert stock.stock_material("Gazebo/LightWood") is None         # Electric-era name, not in the file
    assert len(stock.names()) == 78


def test_gz_sim_substring_quirk_emulated():
    # anchors.md §6.2: Grey takes GreyTransparent's 0.5; Orange's diffuse from OrangeTransparent;
    # Gray (inherits) gets nothing; Blue is unaffected (the only name gz-sim's test checks).
    assert stock.gz_sim_values("Gazebo/Grey")["ambient"] == (0.5, 0.5, 0.5, 1)
    assert stock.gz_sim_values("Gazebo/Orange")["diffuse"] == (1, 0.44, 0, 1)
    assert stock.gz_sim_values("Gazebo/Gray") is None
    assert stock.gz_sim_values("Gazebo/White") == {"ambient": (1, 1, 1, 1)}
    blue = stock.gz_sim_values("Gazebo/Blue")
    assert blue["ambient"] == blue["diffuse"] == (0, 0, 1, 1)


# ------------------------------------------------------------------ resolver
def test_resolver_on_ros1_media_layout():
    r = MaterialResolver([OBJETOS, BRAZO])
    amstel = r.lookup("material_fer/Amstel")
    assert amstel.texture == "amstel.png"
    assert amstel.texture_path == OBJETOS / "Media/materials/textures/amstel.png"
    assert amstel.source.endswith("myrabot_fer.material:29") and not amstel.is_stock
    cola = r.lookup("Gazebo/CocaCola")                               # from the script, not stock
    assert cola.texture == "coca_cola.png" and cola.texture_path is None and not cola.is_stock
    assert r.lookup("material_fer/CocaCola") is None                 # what lata_cola.xacro asks for (seed defect)
    assert r.lookup("Gazebo/LightWood") is None                      # mesa.xacro's name: nowhere to be found
    grey = r.lookup("Gazebo/Grey")
    assert grey.is_stock and grey.diffuse == (0.7, 0.7, 0.7, 1)
    assert r.lookup("brazo_fer/WhiteTransparent").transparency == pytest.approx(0.6)
    assert r.errors == [] and len(r.scripts) == 2
    assert r.names() == sorted(["material_fer/NOMBRE_DEL_NUEVO_MATERIAL", "material_fer/Amstel",
                                "Gazebo/CocaCola", "brazo_fer/Black", "brazo_fer/White",
                                "brazo_fer/WhiteTransparent"])


def test_resolver_keeps_going_past_bad_scripts_and_links_parents_across_files(tmp_path):
    scripts = tmp_path / "materials" / "scripts"
    scripts.mkdir(parents=True)
    (scripts / "a.material").write_text("material kid : mum { technique { pass { emissive 1 0 0 } } }\n")
    (scripts / "b.material").write_text("material mum { technique { pass { ambient 0 0 1 } } }\n")
    (scripts / "c.material").write_text("material broken {\n")
    (scripts / "d.material").write_text("material orphan : nobody { }\n")
    r = MaterialResolver([tmp_path])
    kid = r.lookup("kid")
    assert kid.ambient == (0, 0, 1, 1) and kid.emissive == (1, 0, 0, 1)
    errs = sorted(str(e) for e in r.errors)
    assert len(errs) == 2
    assert "c.material:1: error:" in errs[0] and "never closed" in errs[0]
    assert "d.material:1: error:" in errs[1] and "'nobody' is not defined" in errs[1]
    assert r.lookup("orphan") is None


def test_resolver_for_walks_up_to_the_package_root():
    robot = SimpleNamespace(package_roots={"objetos_fer_modelos": OBJETOS},
                            source=OBJETOS / "urdf" / "lata_cerveza.xacro")
    dirs = search_dirs_for(robot)
    assert dirs[0] == OBJETOS and (OBJETOS / "urdf").resolve() in dirs and FIX.resolve() not in dirs
    assert resolver_for(robot).lookup("material_fer/Amstel").texture_path.name == "amstel.png"


def test_resolver_for_a_loaded_seed_model():
    xacro_file = SEED_OBJETOS / "urdf" / "lata_cerveza.xacro"
    robot = load_robot(str(xacro_file))
    res = resolver_for(robot)
    assert res.lookup("material_fer/Amstel").texture == "amstel.png"
    assert res.lookup("PR2/Grey0") is None


# ------------------------------------------------------------------ the command
def _run(*args):
    return CliRunner().invoke(materials_cmd, [str(a) for a in args])


def test_cli_sdf_blocks():
    res = _run(BRAZO_FER)
    assert res.exit_code == 0, res.output
    root = etree.fromstring(f"<r>{res.output}</r>".encode())
    blocks = root.findall("material")
    assert len(blocks) == 3
    white = blocks[1]
    assert white.findtext("ambient") == "1 1 1 1" and white.findtext("specular") == "0.8 0.8 0.8 1"
    assert "transparency 0.6" in res.output


def test_cli_sdf_texture_and_lighting():
    res = _run(FER, "--name", "material_fer/Amstel")
    assert res.exit_code == 0, res.output
    mat = etree.fromstring(f"<r>{res.output}</r>".encode()).find("material")
    assert mat.findtext("lighting") == "false"
    assert mat.findtext("pbr/metal/albedo_map") == str((OBJETOS / "Media/materials/textures/amstel.png").resolve())
    res = _run(FER, "--name", "Gazebo/CocaCola", "--texture-prefix", "model://latas/materials/textures/")
    assert "<albedo_map>model://latas/materials/textures/coca_cola.png</albedo_map>" in res.output


def test_cli_json_to_file_is_deterministic(tmp_path):
    out = tmp_path / "m.json"
    assert _run(FIX / "inheritance.material", "--to", "json", "-o", out).exit_code == 0
    first = out.read_bytes()
    doc = json.loads(first)
    mats = {m["name"]: m for m in doc["materials"]}
    assert mats["fer/Glow"]["parent"] == "fer/Base" and mats["fer/Glow"]["emissive"] == [0, 0.5, 0, 1]
    assert mats["fer/GreyShiny"]["ambient"] == [0.3, 0.3, 0.3, 1]
    assert mats["fer/Painted"]["texture"] == "paint.jpg" and mats["fer/Painted"]["texture_path"] is None
    assert mats["fer/Base"]["loc"].endswith("inheritance.material:5")
    assert _run(FIX / "inheritance.material", "--to", "json", "-o", out).exit_code == 0
    assert out.read_bytes() == first


@pytest.mark.parametrize("name,line", [("unbalanced", 13), ("bad_number", 8), ("unknown_parent", 2),
                                       ("truncated", 8)])
def test_cli_errors_one_line_exit_2_nothing_written(tmp_path, name, line):
    out = tmp_path / "out.sdf"
    path = FIX / "malformed" / f"{name}.material"
    res = _run(path, "-o", out)
    assert res.exit_code == 2
    lines = [x for x in res.output.splitlines() if x.strip()]
    assert len(lines) == 1 and lines[0].startswith(f"{path}:{line}: error: ")
    assert "Traceback" not in res.output and not out.exists() and list(tmp_path.iterdir()) == []


def test_cli_missing_file_and_unknown_name():
    res = _run(FIX / "nope.material")
    assert res.exit_code == 2 and "nope.material: error: no such file" in res.output
    res = _run(BRAZO_FER, "--name", "brazo_fer/Pink")
    assert res.exit_code == 2 and "no material named 'brazo_fer/Pink'" in res.output


def test_cli_help_has_example():
    res = _run("--help")
    assert res.exit_code == 0 and "Examples:" in res.output and "myrabot-desc materials" in res.output


def test_cli_through_the_main_group():
    from myrabot_desc.commands.main import main

    res = CliRunner().invoke(main, ["materials", str(BRAZO_FER), "--to", "json"])
    assert res.exit_code == 0, res.output
    assert [m["name"] for m in json.loads(res.output)["materials"]] == [
        "brazo_fer/Black", "brazo_fer/White", "brazo_fer/WhiteTransparent"]


def test_seed_robot_gazebo_materials_resolve_with_the_arm_script_on_the_path():
    """The seed MYRAbot's <gazebo><material> names: stock ones become colours, the arm's come
    from brazo_fer.material once it is on the media path, and the seed's gaps stay visible."""
    seed = FIXTURES / "seed_myrabot"
    robot = load_robot(str(seed / "myrabot_fer_modelo/urdf/myrabot.urdf.xacro"),
                       packages={"brazo_fer_modelo": str(seed / "brazo_fer_modelo"),
                                 "myrabot_fer_modelo": str(seed / "myrabot_fer_modelo")})
    names = {g.properties["material"] for g in robot.gazebo if g.properties.get("material")}
    res = MaterialResolver(search_dirs_for(robot) + [BRAZO])
    found = {n: res.lookup(n) for n in sorted(names)}
    assert {n for n, m in found.items() if m is None} == {
        "Gazebo/LightWood", "myrabot_fer/Black", "myrabot_fer/White"}
    assert {n for n, m in found.items() if m is not None and m.is_stock} == {
        "Gazebo/Black", "Gazebo/Green", "Gazebo/Grey", "Gazebo/Red"}
    assert found["brazo_fer/WhiteTransparent"].transparency == pytest.approx(0.6)
    assert found["brazo_fer/White"].source.endswith("brazo_fer.material:20")


def test_cli_stock_table():
    res = _run("--stock", "--name", "Gazebo/Grey", "--to", "json")
    assert res.exit_code == 0, res.output
    grey = json.loads(res.output)["materials"][0]
    assert grey["ambient"] == [0.3, 0.3, 0.3, 1.0] and grey["diffuse"] == [0.7, 0.7, 0.7, 1.0]
    assert grey["gz_sim_lookup"]["ambient"] == [0.5, 0.5, 0.5, 1.0]        # the substring quirk, shown
    res = _run("--stock")
    assert res.exit_code == 0 and res.output.count("<material>") == 78
    assert _run().exit_code == 2 and _run("--stock", FER).exit_code == 2
    res = _run("--stock", "--name", "Gazebo/LightWood")
    assert res.exit_code == 2 and "no material named 'Gazebo/LightWood' in Gazebo's stock table" in res.output


def test_latin1_and_crlf_scripts(tmp_path):
    p = tmp_path / "viejo.material"
    p.write_bytes("// añadir al final del archivo\r\nmaterial fer/Añejo\r\n{\r\n technique\r\n {\r\n"
                  "  pass\r\n  {\r\n   diffuse 0.5 0.25 0 1\r\n  }\r\n }\r\n}\r\n".encode("latin-1"))
    m = scripts.parse_file(p).materials["fer/Añejo"]
    assert m.diffuse == (0.5, 0.25, 0, 1) and m.loc.line == 2


def test_variables_and_abstract_templates():
    s = scripts.parse_file(FIX / "variables.material")
    assert list(s.materials) == ["fer/TintedRed", "fer/TintedDefault"]          # the template is not output
    red, plain = s.materials["fer/TintedRed"], s.materials["fer/TintedDefault"]
    assert red.diffuse == (1, 0, 0, 1) and red.specular == (0.5, 0.5, 0.5, 1) and red.shininess == 16
    assert red.texture == "rojo.png" and red.ambient == (0.2, 0.2, 0.2, 1)
    assert plain.diffuse == (1, 1, 1, 1) and plain.texture == "blank.png"       # the template's defaults
    text = (FIX / "variables.material").read_text() + "\nmaterial fer/NoShine : fer/Tinted\n{\n}\n"
    with pytest.raises(InputError) as ei:
        scripts.parse_text(text, "v.material")
    assert ei.value.loc.line == 12 and "variable $shine is not set" in ei.value.message


def test_sdf_blocks_pass_the_sdformat_validator(tmp_path):
    """Every block we print (bundled-style script, the seed's, the whole stock table) is valid SDF 1.9."""
    import re
    import shutil
    import subprocess

    ign = shutil.which("ign") or shutil.which("gz")
    if ign is None:
        pytest.skip("ign/gz (ignition-tools + libsdformat) not installed; the Makefile's install step adds them")
    out = "".join(_run(f).output for f in (FER, BRAZO_FER, FIX / "inheritance.material", FIX / "comments.material"))
    out += _run("--stock").output
    blocks = re.findall(r"<material>.*?</material>", out, re.S)
    assert len(blocks) == 3 + 3 + 5 + 2 + 78
    links = "".join(f'<link name="l{i}"><visual name="v"><geometry><box><size>1 1 1</size></box></geometry>'
                    f"{b}</visual></link>" for i, b in enumerate(blocks))
    sdf = tmp_path / "materials.sdf"
    sdf.write_text(f'<?xml version="1.0"?>\n<sdf version="1.9"><model name="m"><static>true</static>{links}'
                   "</model></sdf>\n")
    r = subprocess.run([ign, "sdf", "-k", str(sdf)], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0 and "Valid" in r.stdout, r.stdout + r.stderr


def test_search_dirs_stay_inside_the_model_folder_without_a_package(tmp_path):
    model = tmp_path / "a" / "b" / "robot.urdf"
    model.parent.mkdir(parents=True)
    (tmp_path / "a" / "evil.material").write_text("material x { }\n")
    robot = SimpleNamespace(package_roots={}, source=model)
    assert search_dirs_for(robot) == [model.parent.resolve()]
    (tmp_path / "a" / "package.xml").write_text("<package/>")
    assert search_dirs_for(robot) == [model.parent.resolve(), (tmp_path / "a").resolve()]
    assert "Gazebo/Grey" in resolver_for(robot).names(include_stock=True)


def test_similar_names_for_the_seed_defects():
    r = MaterialResolver([OBJETOS])
    assert r.similar("material_fer/CocaCola")[0] == "Gazebo/CocaCola"     # lata_cola.xacro vs the script
    assert r.similar("Gazebo/Gris") and "Gazebo/Grey" in r.similar("Gazebo/Gris", n=3)
    assert r.similar("Gazebo/LightWood")[0] == "Gazebo/Wood"              # mesa.xacro: the nearest stock wood
