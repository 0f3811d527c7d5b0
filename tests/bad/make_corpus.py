"""Write the hostile-input corpus under tests/bad/ (committed as files) and its manifest README.md.

Run ``python tests/bad/make_corpus.py`` after changing a case. The files are deterministic
(seeded random bytes). Two kinds of input cannot live in git and are made at test time by
:func:`materialize` in a copy of the corpus: symlinks that point out of the corpus
(``paths/link_*``) and the unreadable (chmod 000) mesh.

Each case is (path, targets, expect, what):
  targets  "model"    -> build, check, check --inertia, info, convert sdf/mjcf, sim drive
           "material" -> materials
           "asset"    -> not an input itself (a mesh, an included file, YAML)
  expect   "reject"   -> every command exits 2 with one file:line message
           "defect"   -> the model loads; check reports errors (exit 1); build may succeed;
                         info/convert/sim either work on what is there or exit 2 cleanly
           "warn"     -> the model loads; some commands may warn; nothing may crash
"""

from __future__ import annotations

import json
import os
import random
import shutil
import struct
from pathlib import Path
from xml.sax.saxutils import quoteattr

HERE = Path(__file__).resolve().parent
CASES: list[dict] = []
XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'

# ---------------------------------------------------------------- a small valid diff-drive robot
DEFAULTS = dict(
    name="badbot", mass="2.0", ixx="0.02", iyy="0.02", izz="0.03", ixy="0", ixz="0", iyz="0",
    base_xyz="0 0 0.05", base_rpy="0 0 0", box="0.3 0.24 0.1",
    wheel_mass="0.2", wheel_radius="0.05", wheel_length="0.03", wheel_axis="0 1 0",
    caster_radius="0.02", arm_lower="-1.57", arm_upper="1.57", arm_effort="5", arm_velocity="1",
    arm_axis="0 0 1", arm_xyz="0 0 0.1", base_collision='<box size="0.3 0.24 0.1"/>',
    wheel_collision=None, sep="0.2", diam="0.1", extra="", arm_mass="0.3",
)


def robot(**kw) -> str:
    v = dict(DEFAULTS)
    v.update(kw)
    wheel_geom = v["wheel_collision"] or f'<cylinder radius="{v["wheel_radius"]}" length="{v["wheel_length"]}"/>'

    def wheel(side, y):
        return f"""
  <link name="{side}_wheel">
    <inertial><mass value="{v['wheel_mass']}"/>
      <inertia ixx="0.0002" ixy="0" ixz="0" iyy="0.0003" iyz="0" izz="0.0002"/></inertial>
    <visual><origin xyz="0 0 0" rpy="1.5708 0 0"/><geometry>{wheel_geom}</geometry></visual>
    <collision><origin xyz="0 0 0" rpy="1.5708 0 0"/><geometry>{wheel_geom}</geometry></collision>
  </link>
  <joint name="{side}_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="{side}_wheel"/>
    <origin xyz="0 {y} 0" rpy="0 0 0"/><axis xyz="{v['wheel_axis']}"/>
  </joint>"""

    return f"""<?xml version="1.0"?>
<robot name="{v['name']}">
  <link name="base_link">
    <inertial>
      <origin xyz="{v['base_xyz']}" rpy="{v['base_rpy']}"/>
      <mass value="{v['mass']}"/>
      <inertia ixx="{v['ixx']}" ixy="{v['ixy']}" ixz="{v['ixz']}" iyy="{v['iyy']}" iyz="{v['iyz']}" izz="{v['izz']}"/>
    </inertial>
    <visual><origin xyz="0 0 0.05"/><geometry><box size="{v['box']}"/></geometry></visual>
    <collision><origin xyz="0 0 0.05"/><geometry>{v['base_collision']}</geometry></collision>
  </link>{wheel('left', 0.1)}{wheel('right', -0.1)}
  <link name="caster">
    <inertial><mass value="0.05"/><inertia ixx="1e-5" ixy="0" ixz="0" iyy="1e-5" iyz="0" izz="1e-5"/></inertial>
    <collision><geometry><sphere radius="{v['caster_radius']}"/></geometry></collision>
  </link>
  <joint name="caster_joint" type="fixed">
    <parent link="base_link"/><child link="caster"/><origin xyz="-0.12 0 -0.03"/>
  </joint>
  <link name="arm">
    <inertial><mass value="{v['arm_mass']}"/><inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.0005"/></inertial>
    <collision><origin xyz="0 0 0.05"/><geometry><cylinder radius="0.02" length="0.1"/></geometry></collision>
  </link>
  <joint name="arm_joint" type="revolute">
    <parent link="base_link"/><child link="arm"/><origin xyz="{v['arm_xyz']}" rpy="0 0 0"/>
    <axis xyz="{v['arm_axis']}"/>
    <limit lower="{v['arm_lower']}" upper="{v['arm_upper']}" effort="{v['arm_effort']}" velocity="{v['arm_velocity']}"/>
  </joint>
  <gazebo>
    <plugin name="diff_drive" filename="libgazebo_ros_diff_drive.so">
      <leftJoint>left_wheel_joint</leftJoint><rightJoint>right_wheel_joint</rightJoint>
      <wheelSeparation>{v['sep']}</wheelSeparation><wheelDiameter>{v['diam']}</wheelDiameter>
      <commandTopic>cmd_vel</commandTopic><robotBaseFrame>base_link</robotBaseFrame>
    </plugin>
  </gazebo>{v['extra']}
</robot>
"""


def add(rel: str, data, targets: str, expect: str, what: str) -> None:
    path = HERE / rel
    path.parent.mkdir(parents=True, exist_ok=True)
    if isinstance(data, str):
        data = data.encode("utf-8")
    if data is not None:
        path.write_bytes(data)
    CASES.append({"path": rel, "targets": targets, "expect": expect, "what": what})


def escape(expr: str) -> str:
    return quoteattr(expr)[1:-1]


def xacro(body: str, name="badbot") -> str:
    return f'<?xml version="1.0"?>\n<robot name="{name}" {XACRO_NS}>\n{body}\n</robot>\n'


LINK = '<link name="base_link"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" ' \
       'iyz="0" izz="0.01"/></inertial></link>'


# ---------------------------------------------------------------- meshes
def stl_binary(tris, count=None) -> bytes:
    out = bytearray(b"badbot corpus".ljust(80, b" "))
    out += struct.pack("<I", len(tris) if count is None else count)
    for a, b, c in tris:
        out += struct.pack("<3f", 0, 0, 0)
        for p in (a, b, c):
            out += struct.pack("<3f", *p)
        out += b"\0\0"
    return bytes(out)


def cube_tris(s=0.1, flip=False, drop=0):
    h = s / 2
    v = [(x, y, z) for x in (-h, h) for y in (-h, h) for z in (-h, h)]
    faces = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1),
             (2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]
    tris = [(v[a], v[b], v[c]) for a, b, c in faces]
    if flip:
        tris = [(a, c, b) for a, b, c in tris]
    return tris[drop:]


def sphere_tris(n):
    """A UV sphere with about 2 n^2 triangles (for the triangle-count limit)."""
    import math

    pts = lambda i, j: (0.05 * math.sin(math.pi * i / n) * math.cos(2 * math.pi * j / n),  # noqa: E731
                        0.05 * math.sin(math.pi * i / n) * math.sin(2 * math.pi * j / n),
                        0.05 * math.cos(math.pi * i / n))
    tris = []
    for i in range(n):
        for j in range(n):
            a, b, c, d = pts(i, j), pts(i + 1, j), pts(i + 1, j + 1), pts(i, j + 1)
            tris += [(a, b, c), (a, c, d)]
    return tris


DAE_HEAD = '<?xml version="1.0" encoding="utf-8"?>\n'
DAE_OK_BODY = """<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit meter="1" name="meter"/><up_axis>Z_UP</up_axis></asset>
  <library_geometries/>
  <library_visual_scenes><visual_scene id="s"/></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
"""


def make_meshes():
    rnd = random.Random(7)
    m = "meshes/meshes/"
    add("meshes/package.xml", "<package><name>bad_meshes</name></package>\n", "asset", "-", "makes meshes/ a package")
    add(m + "cube.stl", stl_binary(cube_tris()), "asset", "-", "a good 10 cm cube (reference)")
    add(m + "empty.stl", b"", "asset", "-", "0-byte STL")
    add(m + "garbage.stl", bytes(rnd.randrange(256) for _ in range(3000)), "asset", "-", "random bytes")
    add(m + "truncated.stl", stl_binary(cube_tris(), count=1000)[:84 + 50 * 3], "asset", "-",
        "binary STL whose header claims 1000 faces, 3 present")
    add(m + "huge_count.stl", stl_binary(cube_tris(), count=0xFFFFFFFF), "asset", "-",
        "binary STL claiming 4 294 967 295 faces")
    add(m + "bad_ascii.stl", "solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 zero\n", "asset", "-",
        "ASCII STL with a non-number and no endsolid")
    add(m + "open_box.stl", stl_binary(cube_tris(drop=2)), "asset", "-", "cube with one face missing (not watertight)")
    add(m + "inverted.stl", stl_binary(cube_tris(flip=True)), "asset", "-", "cube with inward normals")
    add(m + "flat.stl", stl_binary([((0, 0, 0), (1, 0, 0), (0, 1, 0)), ((1, 0, 0), (1, 1, 0), (0, 1, 0))]),
        "asset", "-", "two coplanar triangles (zero volume)")
    nan = float("nan")
    add(m + "nan.stl", stl_binary([((nan, 0, 0), (1, 0, 0), (0, 1, 0))] + cube_tris()), "asset", "-",
        "NaN vertex coordinates")
    add(m + "dense.stl", stl_binary(sphere_tris(50)), "asset", "-", "5 000 triangles (for a low --max triangle limit)")
    add(m + "garbage.dae", bytes(rnd.randrange(256) for _ in range(2000)), "asset", "-", "random bytes as COLLADA")
    add(m + "empty.dae", DAE_HEAD + DAE_OK_BODY, "asset", "-", "valid COLLADA without geometry")
    add(m + "truncated.dae", (DAE_HEAD + DAE_OK_BODY)[:200], "asset", "-", "COLLADA cut mid-element")
    add(m + "xxe.dae", DAE_HEAD + '<!DOCTYPE c [<!ENTITY x SYSTEM "file:///etc/passwd">]>\n'
        + DAE_OK_BODY.replace('name="meter"', 'name="&x;"'), "asset", "-", "COLLADA with an external entity")
    add(m + "laughs.dae", DAE_HEAD + "<!DOCTYPE c [" + "".join(
        f'<!ENTITY l{i} "{("&l%d;" % (i - 1)) * 10 if i else "lol"}">' for i in range(10)) + "]>\n"
        + DAE_OK_BODY.replace('name="meter"', 'name="&l9;"'), "asset", "-", "COLLADA billion laughs")
    add(m + "garbage.obj", "v 1 2\nf 1 2 3 4 5\nv a b c\nf 9 9 9\n", "asset", "-", "OBJ with bad vertices/faces")
    (HERE / m / "folder.stl").mkdir(parents=True, exist_ok=True)
    (HERE / m / "folder.stl" / "README").write_text("a folder named like a mesh\n")
    CASES.append({"path": m + "folder.stl", "targets": "asset", "expect": "-", "what": "a folder named .stl"})

    for stem, mesh, expect, what in [
        ("missing", "package://bad_meshes/meshes/nope.stl", "defect", "mesh file does not exist"),
        ("empty_stl", "package://bad_meshes/meshes/empty.stl", "defect", "0-byte STL"),
        ("garbage_stl", "package://bad_meshes/meshes/garbage.stl", "defect", "random bytes as STL"),
        ("truncated_stl", "package://bad_meshes/meshes/truncated.stl", "defect", "truncated binary STL"),
        ("huge_count_stl", "package://bad_meshes/meshes/huge_count.stl", "defect", "STL header claims 2^32-1 faces"),
        ("bad_ascii_stl", "package://bad_meshes/meshes/bad_ascii.stl", "defect", "malformed ASCII STL"),
        ("open_box", "package://bad_meshes/meshes/open_box.stl", "defect", "non-watertight mesh"),
        ("inverted", "package://bad_meshes/meshes/inverted.stl", "defect", "inverted mesh"),
        ("flat", "package://bad_meshes/meshes/flat.stl", "defect", "zero-volume mesh"),
        ("nan_vertices", "package://bad_meshes/meshes/nan.stl", "defect", "NaN vertices"),
        ("garbage_dae", "package://bad_meshes/meshes/garbage.dae", "defect", "garbage COLLADA"),
        ("empty_dae", "package://bad_meshes/meshes/empty.dae", "defect", "COLLADA without geometry"),
        ("truncated_dae", "package://bad_meshes/meshes/truncated.dae", "defect", "truncated COLLADA"),
        ("xxe_dae", "package://bad_meshes/meshes/xxe.dae", "defect", "COLLADA with XXE"),
        ("laughs_dae", "package://bad_meshes/meshes/laughs.dae", "defect", "COLLADA billion laughs"),
        ("garbage_obj", "package://bad_meshes/meshes/garbage.obj", "defect", "garbage OBJ"),
        ("folder_mesh", "package://bad_meshes/meshes/folder.stl", "defect", "mesh path is a folder"),
        ("unreadable", "package://bad_meshes/meshes/unreadable.stl", "defect",
         "chmod 000 mesh (made at test time; root reads it anyway)"),
        ("unknown_package", "package://no_such_pkg/meshes/cube.stl", "defect", "package:// of an unknown package"),
        ("http_mesh", "http://127.0.0.1:9/cube.stl", "defect", "mesh over http (must not be fetched)"),
        ("dense", "package://bad_meshes/meshes/dense.stl", "warn", "5 000-triangle mesh (limit test)"),
        # issue 17 (the files are made at test time: materialize())
        ("fifo_mesh", "package://bad_meshes/meshes/fifo.stl", "defect", "mesh that is a FIFO (would block)"),
        ("zero_mesh", "package://bad_meshes/meshes/zero.stl", "defect", "symlink to /dev/zero as a mesh"),
        ("zip_bomb", "package://bad_meshes/meshes/bomb.zip", "defect", "zip inflating to 60 MB (mesh limit 50 MB)"),
        ("threemf_bomb", "package://bad_meshes/meshes/bomb.3mf", "defect", "3MF inflating to 60 MB"),
        ("obj_mtl_fifo", "package://bad_meshes/meshes/mtl_fifo.obj", "warn", "OBJ whose mtllib is a FIFO"),
        ("abs_outside", "/etc/passwd", "defect", "an existing file outside the roots as a mesh"),
    ]:
        geom = f'<mesh filename="{mesh}"/>'
        add(f"meshes/{stem}.urdf", robot(base_collision=geom), "model", expect, f"base collision: {what}")
    add("meshes/wheel_garbage.urdf", robot(wheel_collision='<mesh filename="package://bad_meshes/meshes/garbage.stl"/>'),
        "model", "defect", "wheel collision mesh is garbage (sim drive measures wheels)")
    add("meshes/wheel_empty.urdf", robot(wheel_collision='<mesh filename="package://bad_meshes/meshes/empty.stl"/>'),
        "model", "defect", "wheel collision mesh is empty")
    add("meshes/wheel_flat.urdf", robot(wheel_collision='<mesh filename="package://bad_meshes/meshes/flat.stl"/>'),
        "model", "defect", "wheel collision mesh is flat")
    add("meshes/bad_scale.urdf", robot(base_collision='<mesh filename="package://bad_meshes/meshes/cube.stl" '
                                                      'scale="nan 1 1"/>'), "model", "defect", "mesh scale NaN")
    add("meshes/zero_scale.urdf", robot(base_collision='<mesh filename="package://bad_meshes/meshes/cube.stl" '
                                                       'scale="0 0 0"/>'), "model", "defect", "mesh scale 0 0 0")
    add("meshes/negative_scale.urdf", robot(base_collision='<mesh filename="package://bad_meshes/meshes/cube.stl" '
                                                           'scale="-1 1 1"/>'), "model", "defect", "mesh scale -1 1 1")
    add("meshes/text_scale.urdf", robot(base_collision='<mesh filename="package://bad_meshes/meshes/cube.stl" '
                                                       'scale="big"/>'), "model", "defect", "mesh scale not numbers")
    add("meshes/huge_scale.urdf", robot(base_collision='<mesh filename="package://bad_meshes/meshes/cube.stl" '
                                                       'scale="1e300 1e300 1e300"/>'), "model", "defect",
        "mesh scale 1e300 (volume overflows)")


# ---------------------------------------------------------------- XML level
def make_xml():
    rnd = random.Random(11)
    good = robot()
    add("xml/empty.urdf", b"", "model", "reject", "empty file")
    add("xml/empty.urdf.xacro", b"", "model", "reject", "empty xacro file")
    add("xml/whitespace.urdf", b"\n  \n\t\n", "model", "reject", "whitespace only")
    add("xml/garbage.urdf", bytes(rnd.randrange(256) for _ in range(4096)), "model", "reject", "random bytes")
    add("xml/garbage.urdf.xacro", bytes(rnd.randrange(256) for _ in range(4096)), "model", "reject", "random bytes")
    add("xml/nul_bytes.urdf", good.encode()[:200] + b"\0" * 100 + good.encode()[200:], "model", "reject",
        "NUL bytes inside")
    add("xml/png_header.urdf", b"\x89PNG\r\n\x1a\n" + bytes(rnd.randrange(256) for _ in range(500)), "model",
        "reject", "a PNG named .urdf")
    add("xml/gzip.urdf", b"\x1f\x8b\x08\x00" + bytes(rnd.randrange(256) for _ in range(500)), "model", "reject",
        "gzip bytes")
    for frac in (0.1, 0.33, 0.5, 0.77, 0.99):
        cut = int(len(good) * frac)
        add(f"xml/truncated_{int(frac * 100):02d}.urdf", good[:cut], "model", "reject", f"cut at {frac:.0%}")
        add(f"xml/truncated_{int(frac * 100):02d}.urdf.xacro", good[:cut], "model", "reject", f"xacro cut at {frac:.0%}")
    add("xml/mismatched.urdf", good.replace("</inertial>", "</inertia>", 1), "model", "reject", "mismatched end tag")
    add("xml/unclosed_attr.urdf", good.replace('value="2.0"', 'value="2.0', 1), "model", "reject", "unclosed quote")
    add("xml/unquoted_attr.urdf", good.replace('value="2.0"', "value=2.0", 1), "model", "reject", "unquoted attribute")
    add("xml/duplicate_attr.urdf", good.replace('<mass value="2.0"/>', '<mass value="2.0" value="3"/>'), "model",
        "reject", "duplicate attribute")
    add("xml/two_roots.urdf", good + "<robot name='again'/>\n", "model", "reject", "two top-level elements")
    add("xml/text_only.urdf", "this is not xml\n", "model", "reject", "plain text")
    add("xml/json.urdf", json.dumps({"robot": {"name": "x"}}), "model", "reject", "JSON")
    add("xml/bad_utf8.urdf", good.encode().replace(b"badbot", b"bad\xff\xfebot", 1), "model", "reject",
        "invalid UTF-8")
    add("xml/control_char.urdf", good.replace("badbot", "bad\x01bot", 1), "model", "reject", "control character")
    add("xml/bad_entity_ref.urdf", good.replace("badbot", "bad&nosuch;bot", 1), "model", "reject",
        "reference to an undeclared entity")
    add("xml/lt_in_attr.urdf", good.replace('name="badbot"', 'name="a<b"', 1), "model", "reject", "< in attribute")
    deep = "<a>" * 3000 + "</a>" * 3000
    add("xml/deep_nesting.urdf", f'<?xml version="1.0"?>\n<robot name="d">{deep}</robot>\n', "model", "reject",
        "3000 nested elements")
    add("xml/deep_nesting.urdf.xacro", f'<?xml version="1.0"?>\n<robot name="d" {XACRO_NS}>{deep}</robot>\n',
        "model", "reject", "3000 nested elements (xacro)")
    add("xml/wrong_root_sdf.urdf", '<?xml version="1.0"?>\n<sdf version="1.9"><model name="m"/></sdf>\n', "model",
        "not-robot", "an SDF file")
    add("xml/wrong_root_html.urdf", "<html><body><p>robot</p></body></html>\n", "model", "not-robot", "HTML")
    add("xml/wrong_root_launch.urdf.xacro", '<?xml version="1.0"?>\n<launch><node name="n" pkg="p" type="t"/>'
        "</launch>\n", "model", "not-robot", "a roslaunch file")
    add("xml/wrong_root_ns.urdf", '<?xml version="1.0"?>\n<x:robot xmlns:x="urn:x" name="n"><x:link name="a"/>'
        "</x:robot>\n", "model", "not-robot", "namespaced <robot>")
    add("xml/comment_only.urdf", '<?xml version="1.0"?>\n<!-- nothing here -->\n', "model", "reject",
        "only a comment")
    add("xml/xml_decl_only.urdf", '<?xml version="1.0"?>\n', "model", "reject", "only the XML declaration")
    add("xml/xinclude.urdf", good.replace("<robot ", '<robot xmlns:xi="http://www.w3.org/2001/XInclude" ', 1)
        .replace("</robot>", '<xi:include href="/etc/passwd" parse="text"/></robot>'), "model", "warn",
        "XInclude of /etc/passwd (must stay an inert element)")
    add("xml/stylesheet_pi.urdf", good.replace('<?xml version="1.0"?>', '<?xml version="1.0"?>\n'
        '<?xml-stylesheet type="text/xsl" href="http://127.0.0.1:9/x.xsl"?>'), "model", "warn",
        "xml-stylesheet PI pointing at the network (must not be fetched)")
    add("xml/utf16.urdf", good.replace('<?xml version="1.0"?>', '<?xml version="1.0" encoding="UTF-16"?>')
        .encode("utf-16"), "model", "reject", "UTF-16 (refused as binary)")
    add("xml/no_robot_name.urdf", good.replace(' name="badbot"', "", 1), "model", "warn", "<robot> without a name")
    add("xml/empty_robot.urdf", '<?xml version="1.0"?>\n<robot name="nothing"/>\n', "model", "warn",
        "<robot> with no links (a placeholder: check says T017, info)")
    add("xml/only_joints.urdf", '<?xml version="1.0"?>\n<robot name="j"><joint name="j" type="fixed">'
        '<parent link="a"/><child link="b"/></joint></robot>\n', "model", "defect", "joints but no links")
    add("xml/huge_attribute.urdf", good.replace('name="badbot"', 'name="' + "x" * 300_000 + '"', 1), "model", "warn",
        "a 300 kB robot name")


# ---------------------------------------------------------------- DTDs and entities
def make_dtd():
    ents = "".join(f'<!ENTITY l{i} "{("&l%d;" % (i - 1)) * 10 if i else "lol"}">' for i in range(10))
    body = '<link name="&l9;"/>'
    add("dtd/billion_laughs.urdf", f'<?xml version="1.0"?>\n<!DOCTYPE robot [{ents}]>\n<robot name="b">{body}</robot>\n',
        "model", "reject", "billion laughs")
    add("dtd/billion_laughs.urdf.xacro",
        f'<?xml version="1.0"?>\n<!DOCTYPE robot [{ents}]>\n<robot name="b" {XACRO_NS}>{body}</robot>\n',
        "model", "reject", "billion laughs (xacro)")
    big = "x" * 50_000
    quad = f'<?xml version="1.0"?>\n<!DOCTYPE robot [<!ENTITY a "{big}">]>\n<robot name="q">' + \
        '<link name="l"><visual name="' + "&a;" * 2000 + '"/></link></robot>\n'
    add("dtd/quadratic.urdf", quad, "model", "reject", "quadratic blowup (one 50 kB entity used 2000 times)")
    for stem, decl, use in [
        ("xxe_file", '<!ENTITY x SYSTEM "file:///etc/passwd">', "&x;"),
        ("xxe_relative", '<!ENTITY x SYSTEM "../../../../../../../../etc/hostname">', "&x;"),
        ("xxe_http", '<!ENTITY x SYSTEM "http://127.0.0.1:9/x">', "&x;"),
        ("xxe_parameter", '<!ENTITY % p SYSTEM "http://127.0.0.1:9/p.dtd"> %p;', "x"),
        ("xxe_external_dtd", "", "x"),
    ]:
        if stem == "xxe_external_dtd":
            head = '<!DOCTYPE robot SYSTEM "http://127.0.0.1:9/robot.dtd">'
        else:
            head = f"<!DOCTYPE robot [{decl}]>"
        for ext in (".urdf", ".urdf.xacro"):
            ns = f" {XACRO_NS}" if ext.endswith("xacro") else ""
            add(f"dtd/{stem}{ext}", f'<?xml version="1.0"?>\n{head}\n<robot name="x"{ns}><link name="a">'
                f"<visual><geometry><box size=\"1 1 1\"/></geometry></visual></link><gazebo>{use}</gazebo></robot>\n",
                "model", "reject", f"external entity / DTD: {stem}")
    # The DOCTYPE hidden behind 70 kB of comment, and in UTF-7 (no '<!' bytes in the file).
    late = '<?xml version="1.0"?>\n<!--' + "c" * 70_000 + '-->\n<!DOCTYPE robot [<!ENTITY a "aaaa">]>\n' \
        '<robot name="&a;"><link name="l"/></robot>\n'
    add("dtd/late_doctype.urdf", late, "model", "reject", "DOCTYPE after a 70 kB comment")
    add("dtd/late_doctype.urdf.xacro", late.replace('<robot name="&a;"', f'<robot name="&a;" {XACRO_NS}'), "model",
        "reject", "DOCTYPE after a 70 kB comment (xacro)")
    u7 = '<?xml version="1.0" encoding="UTF-7"?>\n<!DOCTYPE robot [<!ENTITY a "aaaaaaaaaa">' \
         '<!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;">]>\n<robot name="&b;"><link name="l"/></robot>\n'
    add("dtd/utf7_doctype.urdf", u7.replace("<!", "+ADwAIQ-").encode(), "model", "reject",
        "UTF-7 encoded DOCTYPE and entities (no '<!' bytes)")
    add("dtd/utf7_doctype.urdf.xacro", u7.replace("<!", "+ADwAIQ-").replace('<robot name="&b;"',
        f'<robot name="&b;" {XACRO_NS}').encode(), "model", "reject", "UTF-7 DOCTYPE (xacro)")
    add("dtd/include_target.xacro", f'<?xml version="1.0"?>\n<!DOCTYPE robot [<!ENTITY x SYSTEM "file:///etc/passwd">]>'
        f'\n<robot {XACRO_NS}><link name="&x;"/></robot>\n', "asset", "-", "an included file with XXE")
    add("dtd/include_xxe.urdf.xacro", xacro('<xacro:include filename="include_target.xacro"/>\n' + LINK), "model",
        "reject", "includes a file that declares an external entity")


# ---------------------------------------------------------------- numbers
def make_numbers():
    bad = {"nan": "nan", "inf": "inf", "neginf": "-inf", "overflow": "1e999", "huge": "1e300", "neg": "-1",
           "zero": "0", "text": "heavy", "empty": ""}
    fields = {
        "mass": ["nan", "inf", "neginf", "overflow", "huge", "neg", "zero", "text", "empty"],
        "ixx": ["nan", "inf", "huge", "neg", "zero", "text"],
        "izz": ["neg", "nan"],
        "ixy": ["huge", "nan"],
        "base_xyz": ["nan", "inf", "huge", "text", "empty"],
        "base_rpy": ["nan", "huge", "text"],
        "wheel_axis": ["nan", "zero", "text", "empty"],
        "arm_axis": ["zero", "nan", "huge"],
        "arm_lower": ["nan", "inf", "text"],
        "arm_upper": ["neginf", "text", "neg"],
        "arm_effort": ["neg", "nan", "text"],
        "arm_velocity": ["neg", "zero", "inf"],
        "box": ["nan", "neg", "zero", "text", "huge"],
        "wheel_radius": ["zero", "neg", "nan", "huge", "text"],
        "wheel_length": ["neg", "inf"],
        "caster_radius": ["neg", "zero", "nan"],
        "sep": ["zero", "nan", "text", "neg"],
        "diam": ["zero", "inf", "text"],
        "arm_xyz": ["overflow"],
    }
    for fld, kinds in fields.items():
        for k in kinds:
            val = bad[k]
            if fld in ("base_xyz", "base_rpy", "wheel_axis", "arm_axis", "box", "arm_xyz"):
                val = f"{val} 0 0" if k not in ("text", "empty") else val
            if fld == "box":
                val = f"0.3 {bad[k]} 0.1" if k not in ("text",) else "big"
                kw = {"box": val, "base_collision": f'<box size="{val}"/>'}
            else:
                kw = {fld: val}
            add(f"numbers/{fld}_{k}.urdf", robot(**kw), "model", "defect", f"{fld} = {val!r}")
    add("numbers/vector_short.urdf", robot(base_xyz="1 2"), "model", "defect", "origin xyz with 2 numbers")
    add("numbers/vector_long.urdf", robot(base_xyz="1 2 3 4"), "model", "defect", "origin xyz with 4 numbers")
    add("numbers/hex_number.urdf", robot(mass="0x10"), "model", "defect", "mass in hex")
    add("numbers/comma_decimal.urdf", robot(mass="2,5"), "model", "defect", "decimal comma")
    add("numbers/xacro_nan.urdf.xacro", xacro('<xacro:property name="m" value="${float(\'nan\')}"/>\n'
        '<link name="a"><inertial><mass value="${m}"/><inertia ixx="${m}" ixy="0" ixz="0" iyy="1" iyz="0" '
        'izz="1"/></inertial></link>'), "model", "defect", "NaN made by a xacro expression")
    add("numbers/xacro_inf.urdf.xacro", xacro('<link name="a"><inertial><mass value="${1e308*10}"/>'
        '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>'), "model", "defect",
        "inf made by a xacro expression")


# ---------------------------------------------------------------- tree
def make_tree():
    def urdf(body):
        return f'<?xml version="1.0"?>\n<robot name="tree">\n{body}\n</robot>\n'

    def link(n):
        return f'<link name="{n}"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" ' \
               f'iyz="0" izz="0.01"/></inertial><collision><geometry><box size="0.1 0.1 0.1"/></geometry>' \
               f'</collision></link>'

    def joint(n, p, c, t="revolute"):
        lim = '<limit lower="-1" upper="1" effort="1" velocity="1"/>' if t == "revolute" else ""
        return f'<joint name="{n}" type="{t}"><parent link="{p}"/><child link="{c}"/><axis xyz="0 0 1"/>{lim}</joint>'

    cases = {
        "cycle": (link("base") + link("a") + link("b") + joint("j1", "base", "a") + joint("j2", "a", "b")
                  + joint("j3", "b", "a"), "base -> a -> b -> a"),
        "cycle_no_root": (link("a") + link("b") + joint("j1", "a", "b") + joint("j2", "b", "a"), "a <-> b, no root"),
        "self_loop": (link("a") + joint("j", "a", "a"), "joint from a link to itself"),
        "two_roots": (link("base") + link("a") + link("island") + joint("j", "base", "a"), "two root links"),
        "all_islands": ("".join(link(f"l{i}") for i in range(20)), "20 links, no joints"),
        "parent_missing": (link("a") + joint("j", "nonexistent", "a"), "joint parent link missing"),
        "child_missing": (link("a") + joint("j", "a", "ghost"), "joint child link missing"),
        "both_missing": (link("a") + joint("j", "x", "y"), "joint parent and child missing"),
        "duplicate_link": (link("a") + link("a") + link("b") + joint("j", "a", "b"), "duplicate link name"),
        "duplicate_joint": (link("a") + link("b") + link("c") + joint("j", "a", "b") + joint("j", "a", "c"),
                            "duplicate joint name"),
        "two_parents": (link("a") + link("b") + link("c") + joint("j1", "a", "c") + joint("j2", "b", "c"),
                        "a child with two parents"),
        "no_joint_type": (link("a") + link("b") + '<joint name="j"><parent link="a"/><child link="b"/></joint>',
                          "joint without type"),
        "bad_joint_type": (link("a") + link("b") + joint("j", "a", "b", "spherical"), "unknown joint type"),
        "revolute_no_limit": (link("a") + link("b") + '<joint name="j" type="revolute"><parent link="a"/>'
                              '<child link="b"/></joint>', "revolute without <limit>"),
        "no_parent_tag": (link("a") + link("b") + '<joint name="j" type="fixed"><child link="b"/></joint>',
                          "joint without <parent>"),
        "link_no_name": (link("a") + "<link/>", "link without a name"),
        "joint_no_name": (link("a") + link("b") + '<joint type="fixed"><parent link="a"/><child link="b"/></joint>',
                          "joint without a name"),
        "mimic_missing": (link("a") + link("b") + joint("j", "a", "b").replace("</joint>",
                          '<mimic joint="nope" multiplier="nan"/></joint>'), "mimic of a missing joint"),
        "mimic_cycle": (link("a") + link("b") + link("c") + joint("j1", "a", "b").replace("</joint>",
                        '<mimic joint="j2"/></joint>') + joint("j2", "a", "c").replace("</joint>",
                        '<mimic joint="j1"/></joint>'), "two joints mimicking each other"),
        "empty_geometry": (link("a").replace('<box size="0.1 0.1 0.1"/>', ""), "empty <geometry>"),
        "unknown_geometry": (link("a").replace('<box size="0.1 0.1 0.1"/>', '<capsule radius="1" length="1"/>'),
                             "unknown geometry"),
        "transmission_missing": (link("a") + link("b") + joint("j", "a", "b") + '<transmission name="t">'
                                 '<joint name="nope"/><actuator name="m"/></transmission>',
                                 "transmission of a missing joint"),
        "gazebo_missing_ref": (link("a") + '<gazebo reference="ghost"><sensor type="camera" name="c">'
                               '<update_rate>nan</update_rate></sensor></gazebo>', "gazebo block for a missing link"),
    }
    cases["child_no_link"] = (link("a") + link("b") + '<joint name="j" type="fixed"><parent link="a"/><child/>'
                              '</joint>', "<child> without link= (found by the fuzzer: T002 crashed)")
    for stem, (body, what) in cases.items():
        add(f"tree/{stem}.urdf", urdf(body), "model", "defect", what)
    for stem, what in GENERATED_TREES.items():
        # valid trees, checked in linear time; only Pinocchio refuses them (depth, size), and check's
        # P003 no longer needs Pinocchio when the inertias prove the dynamics finite
        add(f"tree/{stem}.urdf", None, "model", "warn", what + " (made at test time)")
    # the diff-drive robot with a broken tree, so that sim drive gets past "no drive" (fuzzer finds)
    add("tree/drive_island.urdf", robot(extra='\n  <link name="island"/>'), "model", "defect",
        "diff-drive robot with a second root link (sim: KeyError before)")
    add("tree/drive_wheel_ghost.urdf", robot().replace('<child link="left_wheel"/>', '<child link="ghost"/>'),
        "model", "defect", "diff-drive robot whose wheel joint names a missing link (sim: KeyError before)")
    add("tree/drive_wheel_cycle.urdf", robot(extra='\n  <joint name="loop" type="fixed"><parent link="arm"/>'
                                                  '<child link="base_link"/></joint>'), "model", "defect",
        "diff-drive robot with a joint closing a cycle to the base")
    chain = link("l0") + "".join(link(f"l{i}") + joint(f"j{i}", f"l{i - 1}", f"l{i}") for i in range(1, 1500))
    add("tree/long_chain.urdf", urdf(chain), "model", "warn", "a 1500-link serial chain (recursion depth)")
    big_cycle = "".join(link(f"c{i}") for i in range(300)) + "".join(
        joint(f"j{i}", f"c{i}", f"c{(i + 1) % 300}") for i in range(300))
    add("tree/big_cycle.urdf", urdf(link("root") + joint("jr", "root", "c0") + big_cycle), "model", "defect",
        "a 300-link cycle hanging off the root")


# ---------------------------------------------------------------- xacro semantics
def make_xacro():
    x = "xacro/"
    blocks = '<xacro:property name="b0"><a/><a/></xacro:property>' + "".join(
        f'<xacro:property name="b{i}"><xacro:insert_block name="b{i - 1}"/><xacro:insert_block name="b{i - 1}"/>'
        "</xacro:property>" for i in range(1, 30)) + '<link name="l"><xacro:insert_block name="b29"/></link>'
    cases = {
        "block_bomb": (blocks, "property blocks nested to 2^30 elements, no macro call"),
        "attribute_space": ('<link name="a"><xacro:attribute name="a b" value="1"/></link>',
                            "xacro:attribute name with a space"),
        "attribute_inject": ('<link name="a"><xacro:attribute name=\'x="1"&gt;&lt;/link&gt;&lt;joint name="j" '
                             'type="fixed"/&gt;&lt;link name="q\' value="1"/></link>',
                             "xacro:attribute name injecting a <joint>"),
        "element_lt": ('<xacro:element xacro:name="a&lt;b"/>', "xacro:element name with <"),
        "big_attribute": ('<xacro:property name="s" value="${\'a\' * 900000}"/><link name="a"><visual name="'
                          + "${s}" * 17 + '"/></link>', "a 15 MB attribute built by ${}"),
        "yaml_tag_code": ("<xacro:property name=\"y\" value=\"${xacro.load_yaml('tag_code.yaml')}\"/>"
                          '<link name="${y.a}"/>', "YAML unit tag holding Python code"),
        "yaml_fifo": ("<xacro:property name=\"y\" value=\"${xacro.load_yaml('fifo.yaml')}\"/>"
                      '<link name="${y}"/>', "load_yaml of a FIFO (made at test time)"),
        "include_fifo": ('<xacro:include filename="fifo.xacro"/>', "include of a FIFO (made at test time)"),
        "undefined_property": ('<link name="${nope}"/>', "undefined property"),
        "undefined_macro": ('<xacro:nope parent="base_link"/>' + LINK, "call of an undefined macro"),
        "undefined_arg": ('<link name="$(arg nope)"/>', "undefined arg"),
        "undefined_in_math": ('<xacro:property name="a" value="1"/><link name="l${a + b}"/>', "undefined name in math"),
        "macro_missing_param": ('<xacro:macro name="m" params="a b"><link name="${a}${b}"/></xacro:macro>'
                                '<xacro:m a="x"/>', "macro call missing a parameter"),
        "macro_extra_param": ('<xacro:macro name="m" params="a"><link name="${a}"/></xacro:macro>'
                              '<xacro:m a="x" zzz="1"/>', "macro call with an unknown parameter"),
        "macro_missing_block": ('<xacro:macro name="m" params="*b"><xacro:insert_block name="b"/></xacro:macro>'
                                '<xacro:m/>', "macro call without its block"),
        "insert_undefined_block": ('<xacro:insert_block name="nope"/>', "insert_block of an undefined block"),
        "infinite_recursion": ('<xacro:macro name="m" params="n"><link name="l${n}"/><xacro:m n="${n+1}"/>'
                               '</xacro:macro><xacro:m n="0"/>', "a macro calling itself forever"),
        "mutual_recursion": ('<xacro:macro name="a"><xacro:b/></xacro:macro><xacro:macro name="b"><xacro:a/>'
                             '</xacro:macro><xacro:a/>', "two macros calling each other"),
        "deep_recursion_300": ('<xacro:macro name="m" params="n"><xacro:if value="${n > 0}"><xacro:m n="${n-1}"/>'
                               '</xacro:if><link name="l${n}"/></xacro:macro><xacro:m n="300"/>',
                               "recursion 300 deep (over the 200 default; xacro dies near 400)"),
        "deep_recursion_1000": ('<xacro:macro name="m" params="n"><xacro:if value="${n > 0}"><xacro:m n="${n-1}"/>'
                                '</xacro:if></xacro:macro><xacro:m n="1000"/>' + LINK, "recursion 1000 deep"),
        "exponential_macros": ("".join(f'<xacro:macro name="m{i}"><xacro:m{i - 1}/><xacro:m{i - 1}/></xacro:macro>'
                                       for i in range(1, 40)).join(['<xacro:macro name="m0"><link name="l"/>'
                                                                    '</xacro:macro>', '<xacro:m39/>']),
                               "each macro calls the previous twice, 40 levels (2^39 links)"),
        "property_self": ('<xacro:property name="a" value="${a}"/><link name="${a}"/>', "property defined by itself"),
        "property_cycle": ('<xacro:property name="a" value="${b}"/><xacro:property name="b" value="${a}"/>'
                           '<link name="${a}"/>', "two properties defined by each other"),
        "division_by_zero": ('<link name="a"><inertial><mass value="${1/0}"/></inertial></link>', "1/0"),
        "syntax_error": ('<link name="${1 +* 2}"/>', "syntax error in ${}"),
        "unterminated": ('<link name="${1 + 2"/>', "unterminated ${"),
        "unterminated_subst": ('<link name="$(arg x"/>', "unterminated $("),
        "bad_if": ('<xacro:if value="maybe">' + LINK + "</xacro:if>", "xacro:if with a non-boolean"),
        "if_no_value": ("<xacro:if>" + LINK + "</xacro:if>", "xacro:if without value"),
        "element_empty_name": ('<xacro:element xacro:name=""/>', "xacro:element with an empty name"),
        "attribute_outside": ('<xacro:attribute name="x" value="1"/>', "xacro:attribute at robot level"),
        "macro_no_name": ('<xacro:macro params="a"><link name="${a}"/></xacro:macro>', "macro without a name"),
        "property_no_name": ('<xacro:property value="1"/>', "property without a name"),
        "include_no_filename": ("<xacro:include/>", "include without filename"),
        "include_missing": ('<xacro:include filename="no_such_file.xacro"/>', "include of a missing file"),
        "include_self": ('<xacro:include filename="include_self.urdf.xacro"/>' + LINK, "includes itself"),
        "include_cycle_a": ('<xacro:include filename="include_cycle_b.xacro"/>' + LINK, "a includes b includes a"),
        "include_folder": ('<xacro:include filename="."/>', "include of a folder"),
        "include_binary": ('<xacro:include filename="../xml/garbage.urdf.xacro"/>', "include of random bytes"),
        "include_truncated": ('<xacro:include filename="../xml/truncated_50.urdf.xacro"/>', "include of a cut file"),
        "include_glob_none": ('<xacro:include filename="nothing_*.xacro"/>' + LINK, "glob matching nothing"),
        "find_unknown": ('<xacro:include filename="$(find no_such_package)/x.xacro"/>', "$(find) of unknown package"),
        "yaml_missing": ('<xacro:property name="y" value="${xacro.load_yaml(\'nope.yaml\')}"/><link name="${y}"/>',
                         "load_yaml of a missing file"),
        "yaml_garbage": ('<xacro:property name="y" value="${xacro.load_yaml(\'garbage.yaml\')}"/>'
                         '<link name="${y.a}"/>', "load_yaml of malformed YAML"),
        "yaml_python_tag": ('<xacro:property name="y" value="${xacro.load_yaml(\'python_tag.yaml\')}"/>'
                            '<link name="${y}"/>', "YAML with !!python/object/apply:os.system"),
        "yaml_laughs": ('<xacro:property name="y" value="${xacro.load_yaml(\'laughs.yaml\')}"/>'
                        '<link name="${y}"/>', "YAML alias bomb printed as a string"),
        "yaml_missing_key": ('<xacro:property name="y" value="${xacro.load_yaml(\'ok.yaml\')}"/>'
                             '<link name="${y.nope}"/>', "missing key in YAML"),
        "yaml_control_char": ('<xacro:property name="y" value="${xacro.load_yaml(\'control.yaml\')}"/>'
                              '<link name="${y.a}"/>', "YAML with a control character (BEL) on line 2"),
        "big_string": ('<xacro:property name="s" value="${\'a\' * 900000}"/>' + "".join(
            f'<link name="l{i}${{s}}"/>' for i in range(80)), "a 900 kB string used in 80 names"),
        "unknown_xacro_tag": ("<xacro:frobnicate/>" + LINK, "unknown xacro: tag (treated as a macro call)"),
        "call_dynamic_unknown": ('<xacro:call macro="${\'no\' + \'pe\'}"/>', "xacro:call of an unknown macro"),
        "env_no_env": ('<link name="$(env HOME)"/>', "$(env) -- run with --no-env"),
        "optenv_no_env": ('<link name="$(optenv HOME default)"/>', "$(optenv) -- run with --no-env"),
        "eval_env_no_env": ('<link name="$(eval env(\'HOME\'))"/>', "env() inside $(eval) -- run with --no-env"),
    }
    for stem, (body, what) in cases.items():
        expect = {"attribute_outside": "defect", "include_glob_none": "warn"}.get(stem, "reject")
        add(f"{x}{stem}.urdf.xacro", xacro(body), "model", expect, what)
    add(f"{x}sibling_scan.urdf.xacro", xacro('<wheel parent="base_link"/>' + LINK), "model", "defect",
        "an unexpanded call: the search for its macro meets the FIFO fifo.xacro next to it")
    add(x + "include_cycle_b.xacro", xacro('<xacro:include filename="include_cycle_a.urdf.xacro"/>'), "asset", "-",
        "half of an include cycle")
    # an include chain deeper than the 32 default
    for i in range(40):
        nxt = f'<xacro:include filename="chain_{i + 1:02d}.xacro"/>' if i < 39 else LINK
        add(f"{x}chain/chain_{i:02d}.xacro", xacro(nxt), "asset", "-", "a 40-file include chain")
    add(x + "chain/include_depth_40.urdf.xacro", xacro('<xacro:include filename="chain_00.xacro"/>'), "model",
        "reject", "includes nest 40 deep (limit 32)")
    add(x + "garbage.yaml", "a: [1, 2\n  b: {{{\n", "asset", "-", "malformed YAML")
    add(x + "python_tag.yaml", "!!python/object/apply:os.system ['touch /tmp/myrabot_pwned']\n", "asset", "-",
        "YAML that runs a command under yaml.load")
    add(x + "laughs.yaml", "a: &a [x,x,x,x,x,x,x,x,x,x]\n" + "".join(
        f"{chr(98 + i)}: &{chr(98 + i)} [{', '.join(['*' + chr(97 + i)] * 10)}]\n" for i in range(9)), "asset", "-",
        "YAML billion laughs (aliases)")
    add(x + "ok.yaml", "a: 1\n", "asset", "-", "a small valid YAML")
    add(x + "control.yaml", "a: 1\nb: \x07\n", "asset", "-", "YAML with a control character")
    add(x + "tag_code.yaml", "a: !degrees __import__('os').system('touch /tmp/myrabot_pwned')\n", "asset", "-",
        "a unit tag holding code (xacro's own loader would run it)")


# ---------------------------------------------------------------- ${} code injection (xacro's security cases)
ALLOWED_FORMS = {"abs_filename", "lambda", "genexp"}   # harmless, and real files use them (issue 13)


def make_inject():
    cases = {
        "import": ("${__import__('os').system('touch /tmp/myrabot_pwned')}", "__import__ (xacro's own test)"),
        "subclasses": ('${"".__class__.__base__.__subclasses__()}', "__subclasses__ (xacro's own test)"),
        "builtins": ("${__builtins__}", "__builtins__"),
        "globals_attr": ("${xacro.load_yaml.__globals__}", "__globals__ attribute"),
        "format_traversal": ("${fmt.format(xacro.load_yaml)}", "the str.format traversal (anchors 1.6)"),
        "format_map": ("${fmt.format_map(xacro)}", "str.format_map traversal"),
        "lambda": ("${(lambda: 1)()}", "a lambda (allowed since issue 13: vetted body, bounded depth)"),
        "lambda_default": ("${(lambda f=xacro.load_yaml: f('/etc/passwd'))()}",
                           "lambda capturing a helper (the helper keeps its path check)"),
        "comprehension": ("${[c for c in ().__class__.__mro__]}", "comprehension walking the MRO"),
        "genexp": ("${list(x for x in range(3))}", "generator expression (allowed since issue 13)"),
        "walrus": ("${(y := 5)}", "assignment expression"),
        "fstring": ("${f'{fmt}'}", "f-string"),
        "getattr": ("${getattr('', '__class__')}", "getattr"),
        "type_call": ("${type('', (), dict())}", "type()"),
        "python_type": ("${python.type(1)}", "python.type"),
        "open": ("${open('/etc/passwd').read()}", "open()"),
        "eval": ("${eval('1+1')}", "eval()"),
        "exec": ("${exec('import os')}", "exec()"),
        "vars": ("${vars()}", "vars()"),
        "dunder_string_key": ("${xacro.__dict__['load_yaml']}", "__dict__ subscript"),
        "pow_bomb": ("${9**9**9}", "9**9**9"),
        "pow_bomb_float": ("${10.0**10**10}", "float pow overflow"),
        "pow_bomb_3arg": ("${pow(10, 10**10)}", "pow() builtin"),
        "shift_bomb": ("${1 << 10**10}", "1 << 10**10"),
        "repeat_bomb": ("${'a' * 10**10}", "'a' * 10**10"),
        "nested_repeat": ("${str([[0] * 1000000] * 1000000)}", "nested list repetition printed"),
        "nested_repeat3": ("${len(str([[[0] * 1000] * 1000] * 1000))}", "three-level repetition"),
        "sum_lists": ("${len(sum([[0] * 3000] * 3000, []))}", "quadratic sum of lists"),
        "percent_bomb": ("${'%0999999999d' % 1}", "%-format width bomb"),
        "percent_star": ("${'%*d' % (999999999, 1)}", "%-format * width bomb"),
        "factorial": ("${math.factorial(10**7)}", "math.factorial(10**7)"),
        "factorial_bare": ("${factorial(10**7)}", "factorial(10**7)"),
        "comb": ("${math.comb(10**7, 5 * 10**6)}", "math.comb huge"),
        "perm": ("${math.perm(10**6)}", "math.perm huge"),
        "prod": ("${math.prod([10**4000] * 100000)}", "math.prod of huge ints"),
        "int_digits": ("${int('9' * 100000)}", "int() of 100000 digits"),
        "str_huge_int": ("${str(10**4000 * 10**4000 * 10**4000)}", "str() of a huge int"),
        "redefine_len": ('${len("x")}', "property named len replacing the helper"),
        "math_overflow": ("${math.exp(1000)}", "math.exp overflow"),
        "math_domain": ("${math.sqrt(-1)}", "math domain error"),
        "deep_parens": ("${" + "(" * 5000 + "1" + ")" * 5000 + "}", "5000 nested parentheses"),
        "deep_lists": ("${" + "[" * 5000 + "]" * 5000 + "}", "5000 nested lists"),
        "long_expression": ("${" + "+".join(["1"] * 200000) + "}", "a 400 kB expression"),
        "load_yaml_abs": ("${xacro.load_yaml('/etc/passwd')}", "load_yaml of /etc/passwd"),
        "load_yaml_escape": ("${xacro.load_yaml('../../../../../../../../etc/passwd')}", "load_yaml ../ escape"),
        "load_yaml_bare": ("${load_yaml('/etc/hostname')}", "bare load_yaml of /etc/hostname"),
        "abs_filename": ("${xacro.abs_filename('/etc/passwd')}", "abs_filename (harmless string)"),
        "eval_open": ("$(eval open('/etc/passwd').read())", "$(eval open(...)) (xacro cuts at the first ')')"),
        "eval_open_noparen": ("$(eval open)", "$(eval open) (the builtin itself)"),
        "eval_import": ("$(eval __import__)", "$(eval __import__)"),
        "eval_lambda": ("$(eval lambda: 1)", "$(eval lambda)"),
        "eval_subclasses": ("$(eval ''.__class__.__mro__)", "$(eval __class__.__mro__)"),
        "eval_format": ("$(eval '{0.__class__}'.format)", "$(eval str.format)"),
        "eval_globals": ("$(eval find.__globals__)", "$(eval find.__globals__)"),
        "eval_percent": ("$(eval '%099999999d' % 1)", "$(eval) %-format bomb"),
        "eval_nested_repeat": ("$(eval [[0] * 1000000] * 1000000)", "$(eval) nested repetition printed"),
        "eval_pow": ("$(eval 9**9**9)", "$(eval) pow bomb"),
        "eval_repeat": ("$(eval 'a' * 10**10)", "$(eval) repetition bomb"),
        "eval_shift": ("$(eval 1 << 10**10)", "$(eval) shift bomb"),
        # issue 17
        "bytes_repeat": ("${b'a' * 400000000}", "bytes repetition"),
        "percent_key": ("${'%(a)01000000000d' % dict(a=1)}", "%-format width behind a mapping key"),
        "bytes_percent": ("${b'%01000000000d' % 1}", "bytes %-format width"),
        "concat_loop": ("${len([s + s for s in ['x' * 900000 for _ in python.range(100)]])}",
                        "string concatenation in a comprehension"),
        "copy_loop": ("${len([list(python.range(100000)) for _ in python.range(1000)])}", "list copies in a loop"),
        "join_bomb": ("${'ab'.join(['x' * 100000 for _ in python.range(100)])}", "str.join of large strings"),
        "replace_bomb": ("${('a' * 10000).replace('', 'b' * 1000)}", "str.replace growing quadratically"),
        "lambda_recursion": ("${(lambda f: f(f))(lambda f: f(f))}", "self-applied lambda (C stack)"),
        "namespace_pop": ("${python.sorted(['pi', 'e'], key=python.pop)}", "a namespace's dict method as a key"),
        "namespace_clear": ("${xacro.clear()}", "clearing xacro's namespace"),
        "loop_bomb": ("${python.sum(1 for a in python.range(10**6) for b in python.range(10**6))}",
                      "nested loops (time budget)"),
    }
    pre = '<xacro:property name="fmt" value="{0.__globals__[os]}"/>\n'
    for stem, (expr, what) in cases.items():
        body = pre
        if stem == "redefine_len":
            body += '<xacro:property name="len" value="${python.getattr}"/>\n'
        add(f"inject/{stem}.urdf.xacro", xacro(body + f'<link name="base_link"><visual name="{escape(expr)}"/></link>'),
            "model", "warn" if stem in ALLOWED_FORMS else "reject", what)


# ---------------------------------------------------------------- paths escaping the roots
def make_paths():
    up = "../" * 12
    cases = {
        "include_dotdot": (f'<xacro:include filename="{up}etc/passwd"/>', "include ../../etc/passwd"),
        "include_abs": ('<xacro:include filename="/etc/passwd"/>', "include /etc/passwd"),
        "include_abs_xacro": ('<xacro:include filename="/etc/hostname"/>', "include /etc/hostname"),
        "include_find_escape": ('<xacro:include filename="$(find bad_paths)/' + up + 'etc/passwd"/>',
                                "$(find pkg)/../../etc/passwd"),
        "include_http": ('<xacro:include filename="http://127.0.0.1:9/x.xacro"/>', "include over http"),
        "include_glob_etc": ('<xacro:include filename="/etc/*.conf"/>', "glob over /etc"),
        "include_link": ('<xacro:include filename="link_include.xacro"/>', "include of a symlink to /etc/hostname"),
        "include_link_dir": ('<xacro:include filename="link_etc/hostname"/>', "include through a symlinked folder"),
        "include_proc": ('<xacro:include filename="/proc/self/environ"/>', "include /proc/self/environ"),
        "include_dev_zero": ('<xacro:include filename="/dev/zero"/>', "include /dev/zero (endless)"),
        "include_fifo_like": ('<xacro:include filename="/dev/stdin"/>', "include /dev/stdin"),
        "yaml_link": ("<xacro:property name=\"y\" value=\"${xacro.load_yaml('link_yaml.yaml')}\"/>"
                      '<link name="${y}"/>', "load_yaml of a symlink leaving the folder"),
        "find_arg_injection": ('<xacro:include filename="$(find $(arg p))/x.xacro"/>', "$(find $(arg))"),
    }
    long = "x" * 5000
    cases["include_long_name"] = (f'<xacro:include filename="{long}.xacro"/>',
                                  "a 5000-character include name (ENAMETOOLONG; found by the fuzzer)")
    cases["yaml_long_name"] = (f"<xacro:property name=\"y\" value=\"${{xacro.load_yaml('{long}.yaml')}}\"/>"
                               '<link name="${y}"/>', "a 5000-character load_yaml name")
    add("paths/package.xml", "<package><name>bad_paths</name></package>\n", "asset", "-", "makes paths/ a package")
    for stem, (body, what) in cases.items():
        add(f"paths/{stem}.urdf.xacro", xacro(body + LINK), "model", "reject", what)
    meshes = {
        "mesh_dotdot": (f"package://bad_paths/{up}etc/passwd", "package://pkg/../../etc/passwd"),
        "mesh_file_abs": ("file:///etc/passwd", "file:///etc/passwd"),
        "mesh_relative_escape": (f"{up}etc/passwd", "relative ../../etc/passwd"),
        "mesh_abs": ("/etc/passwd", "absolute /etc/passwd"),
        "mesh_link": ("package://bad_paths/link_mesh.stl", "symlink mesh -> /etc/passwd"),
        "mesh_model_uri": (f"model://bad_paths/{up}etc/passwd", "model:// escape"),
        "mesh_encoded_dotdot": ("package://bad_paths/%2e%2e/%2e%2e/%2e%2e/%2e%2e/%2e%2e/%2e%2e/%2e%2e/etc/passwd",
                                "percent-encoded ../"),
        "mesh_dev_zero": ("file:///dev/zero", "file:///dev/zero (endless)"),
        "mesh_proc": ("file:///proc/self/environ", "/proc/self/environ"),
    }
    for stem, (uri, what) in meshes.items():
        add(f"paths/{stem}.urdf", robot(base_collision=f'<mesh filename="{uri}"/>'), "model", "defect",
            f"mesh {what}")
    add("paths/mesh_long_name.urdf", robot(base_collision=f'<mesh filename="{long}.stl"/>'), "model", "defect",
        "a 5000-character mesh name (every command crashed with ENAMETOOLONG; found by the fuzzer)")
    add("paths/texture_escape.urdf", robot(extra='\n  <material name="m"><texture filename="file:///etc/shadow"/>'
        "</material>"), "model", "warn", "texture file:///etc/shadow")


# ---------------------------------------------------------------- OGRE material scripts
def make_materials():
    rnd = random.Random(13)
    good = """material bad/Red
{
  technique
  {
    pass
    {
      ambient 0.5 0 0 1
      diffuse 1 0 0 1
      specular 0.1 0.1 0.1 1 5
      texture_unit
      {
        texture red.png
      }
    }
  }
}
"""
    cases = {
        "empty": ("", "empty script"),
        "whitespace": ("  \n\n", "whitespace only"),
        "garbage": (bytes(rnd.randrange(256) for _ in range(3000)), "random bytes"),
        "unbalanced_open": (good.rsplit("}", 1)[0], "missing closing brace"),
        "unbalanced_close": (good + "}\n}\n", "extra closing braces"),
        "only_braces": ("{{{{}}}}\n", "braces with no material"),
        "deep_braces": ("material x\n" + "{\n" * 5000 + "}\n" * 5000, "5000 nested braces"),
        "bad_number": (good.replace("diffuse 1 0 0 1", "diffuse 1 zero 0 1"), "non-number colour"),
        "nan_colour": (good.replace("diffuse 1 0 0 1", "diffuse nan 0 0 1"), "NaN colour"),
        "inf_colour": (good.replace("diffuse 1 0 0 1", "diffuse inf 0 0 1"), "inf colour"),
        "huge_colour": (good.replace("diffuse 1 0 0 1", "diffuse 1e999 0 0 1"), "overflowing colour"),
        "negative_colour": (good.replace("diffuse 1 0 0 1", "diffuse -5 0 0 1"), "negative colour"),
        "too_few": (good.replace("diffuse 1 0 0 1", "diffuse 1"), "one number for a colour"),
        "too_many": (good.replace("diffuse 1 0 0 1", "diffuse 1 0 0 1 1 1 1 1"), "eight numbers"),
        "no_name": (good.replace("material bad/Red", "material"), "material without a name"),
        "unterminated_comment": ("/* never closed\n" + good, "unterminated /* comment"),
        "unterminated_string": ('import * from "nowhere\n' + good, "unterminated string"),
        "import_escape": ('import * from "../../../../../../../../etc/passwd"\n' + good, "import of /etc/passwd"),
        "import_abs": ('import * from "/etc/passwd"\n' + good, "import of an absolute path"),
        "import_self": ('import * from "import_self.material"\n' + good, "imports itself"),
        "import_garbage": ('import * from "garbage.material"\nmaterial c : bad/Nope\n{\n}\n', "imports random bytes"),
        "import_link": ('import * from "link_material.material"\n' + good, "import of a symlink to /etc/passwd"),
        "parent_cycle": ("material a : b\n{\n}\nmaterial b : a\n{\n}\n", "a inherits b inherits a"),
        "parent_self": ("material a : a\n{\n}\n", "a inherits itself"),
        "parent_unknown": ("material a : no/such\n{\n}\n", "unknown parent"),
        "variable_loop": ("abstract material t\n{\n technique { pass { diffuse $c } }\n}\n"
                          "material u : t\n{\n set $c \"$c $c\"\n}\n", "a variable defined by itself"),
        "texture_escape": (good.replace("texture red.png", "texture ../../../../../../../etc/passwd"),
                           "texture path leaving the folder"),
        "utf16": (good.encode("utf-16"), "UTF-16 script"),
        "nul": (good.encode().replace(b"Red", b"R\0d"), "NUL in a name"),
        "latin1": (good.replace("bad/Red", "bad/Ni\xf1o").encode("latin-1"), "Latin-1 name (accepted)"),
        "long_line": ("material " + "x" * 200000 + "\n{\n}\n", "a 200 kB material name"),
        "many_materials": ("".join(f"material m{i}\n{{\n technique {{ pass {{ diffuse 1 0 0 1 }} }}\n}}\n"
                                   for i in range(1000)), "1000 materials (accepted)"),
    }
    for stem, (data, what) in cases.items():
        expect = "warn" if stem in ("latin1", "many_materials", "negative_colour", "texture_escape", "empty",
                                    "whitespace", "import_self", "long_line") else "reject"
        add(f"materials/{stem}.material", data, "material", expect, what)
    add("materials/link_material.material", None, "asset", "-", "symlink -> /etc/passwd (made at test time)")
    CASES.pop()


# ---------------------------------------------------------------- test-time inputs
SYMLINKS = {
    "paths/link_include.xacro": "/etc/hostname",
    "paths/link_etc": "/etc",
    "paths/link_yaml.yaml": "/etc/passwd",
    "paths/link_mesh.stl": "/etc/passwd",
    "materials/link_material.material": "/etc/passwd",
}
SYMLINKS["meshes/meshes/zero.stl"] = "/dev/zero"
UNREADABLE = ["meshes/meshes/unreadable.stl"]
FIFOS = ["xacro/fifo.yaml", "xacro/fifo.xacro", "meshes/meshes/fifo.stl", "meshes/meshes/fifo.mtl"]
GENERATED_TREES = {"chain_2000": "a 2,000-link chain (cycle check was cubic; Pinocchio depth)",
                   "star_2000": "a 2,000-link star (1,999 degrees of freedom: Pinocchio's data is cubic)"}
TEST_TIME = set(SYMLINKS) | set(UNREADABLE) | set(FIFOS) | {f"tree/{t}.urdf" for t in GENERATED_TREES} | {
    "meshes/meshes/bomb.zip", "meshes/meshes/bomb.3mf", "meshes/meshes/mtl_fifo.obj"}


def _zip_bomb(path: Path, member: str, inflated: int) -> None:
    """A zip whose one member inflates to ``inflated`` bytes of zeros (about 1/1000 on disk)."""
    import zipfile

    chunk = bytes(1 << 20)
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as z:
        with z.open(member, "w", force_zip64=True) as f:
            for _ in range(inflated >> 20):
                f.write(chunk)


def _tree(kind: str, n: int) -> str:
    inertial = ('<inertial><mass value="0.1"/><inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" '
                'izz="1e-4"/></inertial>')
    out = ['<?xml version="1.0"?>', f'<robot name="{kind}">', f'<link name="l0">{inertial}</link>']
    for i in range(1, n):
        parent = f"l{i - 1}" if kind == "chain" else "l0"
        out.append(f'<link name="l{i}">{inertial}</link><joint name="j{i}" type="revolute"><parent link="{parent}"/>'
                   f'<child link="l{i}"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>'
                   "</joint>")
    return "\n".join(out + ["</robot>"]) + "\n"


def materialize(dest: Path) -> Path:
    """Copy the corpus to ``dest`` and add what git cannot hold: symlinks out of it (one to /dev/zero),
    a chmod 000 file, FIFOs, zip bombs and long generated trees.

    Running as root, the chmod 000 mesh is still readable (root ignores file modes); the case then
    exercises a good mesh.
    """
    if dest.exists():
        shutil.rmtree(dest)
    shutil.copytree(HERE, dest, ignore=shutil.ignore_patterns("__pycache__", "*.py", "README.md"))
    for rel, target in SYMLINKS.items():
        p = dest / rel
        if p.is_symlink() or p.exists():
            p.unlink()
        os.symlink(target, p)
    for rel in UNREADABLE:
        p = dest / rel
        p.write_bytes(stl_binary(cube_tris()))
        p.chmod(0)
    for rel in FIFOS:
        p = dest / rel
        p.unlink(missing_ok=True)
        os.mkfifo(p)
    m = dest / "meshes/meshes"
    _zip_bomb(m / "bomb.zip", "cube.stl", 60 << 20)
    _zip_bomb(m / "bomb.3mf", "3D/3dmodel.model", 60 << 20)
    (m / "mtl_fifo.obj").write_text("mtllib fifo.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                    "f 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n")
    (dest / "tree/chain_2000.urdf").write_text(_tree("chain", 2000))
    (dest / "tree/star_2000.urdf").write_text(_tree("star", 2000))
    return dest


def main() -> None:
    for sub in ("xml", "dtd", "numbers", "tree", "xacro", "inject", "paths", "meshes", "materials"):
        shutil.rmtree(HERE / sub, ignore_errors=True)
    make_xml()
    make_dtd()
    make_numbers()
    make_tree()
    make_xacro()
    make_inject()
    make_paths()
    make_meshes()
    make_materials()
    inputs = [c for c in CASES if c["targets"] != "asset"]
    (HERE / "cases.json").write_text(json.dumps(CASES, indent=1) + "\n")
    lines = ["# tests/bad: hostile inputs", "",
             "Generated by `make_corpus.py` (run it after changing a case); `cases.json` is the machine-readable",
             "manifest that tests/hardening/test_hostile_inputs.py reads. Symlinks out of the corpus, the chmod 000 mesh, FIFOs,",
             "zip bombs and the long generated trees are made at test time in a copy (`materialize()`), since git",
             "cannot hold them portably (or should not hold megabytes of them).", "",
             f"{len(inputs)} inputs ({sum(c['targets'] == 'model' for c in inputs)} models for build, check, "
             "check --inertia, info, convert --to sdf/mjcf and sim drive; "
             f"{sum(c['targets'] == 'material' for c in inputs)} OGRE scripts for materials) and "
             f"{len(CASES) - len(inputs)} supporting files (meshes, includes, YAML).", "",
             "expect: **reject** = every command exits 2 with one `file:line: error:` line; **defect** = the",
             "model loads, `check` reports errors (exit 1), the other commands work on what is there or exit 2;",
             "**warn** = loads, may warn; **not-robot** = XML that is no URDF robot: `build` expands it (as",
             "xacro does), every other command exits 2 saying what it is. In every case: no traceback, no hang",
             "(10 s of CPU), nothing half-written, no file read outside the input's folder and package roots, no",
             "network, no subprocess.", "",
             "| input | commands | expect | what |", "|---|---|---|---|"]
    for c in CASES:
        lines.append(f"| `{c['path']}` | {c['targets']} | {c['expect']} | {c['what'].replace('|', '/')} |")
    (HERE / "README.md").write_text("\n".join(lines) + "\n")
    print(f"{len(inputs)} inputs, {len(CASES) - len(inputs)} supporting files")


if __name__ == "__main__":
    main()
