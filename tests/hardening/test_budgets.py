"""Work bounded inside a single call, and the limits of the one table (safety.LIMITS).

Each hostile input is made at test time and run as a real process (limited.run: CPU seconds and
peak memory from the kernel), and must end in one ``file:line: error:`` line within the issue's
budget (10 s of CPU, 1 GB), where before it ran for tens of seconds or ran out of memory.
"""

from __future__ import annotations

import bz2
import gzip
import lzma
import os
import random
import sys
import time
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).parent))
from limited import run, within_budget, write  # noqa: E402

XACRO = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def refused(r, *words) -> None:
    text = r.stdout + r.stderr
    assert not within_budget(r), (within_budget(r), text[-800:])
    assert r.code == 2, text[-800:]
    assert ": error: " in text and all(w in text for w in words), text[-800:]


# ------------------------------------------------------------------ ${} inside one call
@pytest.mark.parametrize("expr, words", [
    ("lcm(*python.range(1, 1000000))", ["lcm() of numbers of"]),
    ("gcd(*python.range(1, 1000000))", ["gcd() of numbers of"]),
    ("python.len(python.set([i * (2**61 - 1) for i in python.range(300000)]))", ["hash collision"]),
    ("python.len(dict([(i * (2**61 - 1), 0) for i in python.range(300000)]))", ["hash collision"]),
    ("python.len(python.frozenset(python.range(1)).union([i * (2**61 - 1) for i in python.range(300000)]))",
     ["hash collision"]),
    ("python.round(7, -100000000)", ["round() to"]),
    ("'ab' * 10**8", ["repetition"]),
    ("factorial(10**6)", ["factorial() of a number"]),
])
def test_one_builtin_call_cannot_run_past_the_budget(tmp_path, expr, words):
    f = write(tmp_path / "e.urdf.xacro", f'<robot name="e" {XACRO}>\n  <link name="${{{expr}}}"/>\n</robot>\n')
    refused(run(["build", f, "-o", tmp_path / "o.urdf"]), "e.urdf.xacro:2: error: X005", *words)
    assert not (tmp_path / "o.urdf").exists()


def test_hash_collision_check_is_linear_and_lets_real_sets_through():
    from myrabot_desc.expand import safe_eval

    t = time.process_time()
    safe_eval.hash_collisions(list(range(1_000_000)) + [1.5, "a", (1, 2)] * 1000)
    safe_eval.hash_collisions([7] * 1_000_000)                 # one value repeated: cheap for a set
    assert time.process_time() - t < 3
    with pytest.raises(safe_eval.RefusedExpression):
        safe_eval.hash_collisions([i * (2**61 - 1) for i in range(1000)])


def test_a_dict_display_of_many_keys_is_refused(tmp_path):
    keys = ", ".join(f"{i * (2**61 - 1)}: 0" for i in range(12_000))
    f = write(tmp_path / "d.urdf.xacro", f'<robot name="d" {XACRO}>\n  <link name="$(eval len({{{keys}}}))"/>\n</robot>\n')
    refused(run(["build", f, "-o", tmp_path / "o.urdf"]), "d.urdf.xacro:2: error: X005")


def test_the_includes_of_one_build_are_counted(tmp_path):
    """25 files each including the next twice: 2^25 includes (> 30 s) before."""
    for i in range(25):
        body = (f'<xacro:include filename="f{i + 1}.xacro"/>' * 2) if i < 24 else '<link name="l"/>'
        write(tmp_path / f"f{i}.xacro", f'<robot name="r" {XACRO}>{body}</robot>\n')
    refused(run(["build", tmp_path / "f0.xacro", "-o", tmp_path / "o.urdf"]), "over 1000 includes")
    refused(run(["build", tmp_path / "f0.xacro", "--max-includes", "10", "-o", tmp_path / "o.urdf"]), "over 10 includes")


def test_attribute_expansion_is_linear(tmp_path):
    """Millions of ${a} in one attribute grew quadratically (xacro's lexer slices the rest of the text
    after every token): now one pass, at most 100,000 pieces per attribute, and the CPU budget of the
    expressions stops many such attributes."""
    head = f'<robot name="r" {XACRO}>\n<xacro:property name="a" value="x"/>\n'
    one = write(tmp_path / "one.urdf.xacro", head + '<link name="' + "${a}" * 1_000_000 + '"/>\n</robot>\n')
    refused(run(["build", one, "-o", tmp_path / "o.urdf"]), "one.urdf.xacro:3: error:", "100000")
    many = write(tmp_path / "many.urdf.xacro", head + ('<link name="' + "${a}" * 99_000 + '"/>\n') * 40 + "</robot>\n")
    refused(run(["build", many, "-o", tmp_path / "o.urdf"]), "many.urdf.xacro", "X005")
    ok = write(tmp_path / "ok.urdf.xacro", head + '<link name="' + "${a}" * 50_000 + '"/>\n</robot>\n')
    r = run(["build", ok, "-o", tmp_path / "o.urdf"])
    assert r.code == 0 and r.cpu < 5


def test_the_fast_lexer_gives_xacros_tokens():
    import xacro

    from myrabot_desc.expand import fast

    lex = fast.make_eval_text()
    tokens = next(c.cell_contents for c in lex.__closure__ if getattr(c.cell_contents, "__name__", "") == "tokens")
    rnd = random.Random(5)
    alphabet = ["$", "{", "}", "(", ")", "a", " ", "$$", "${a}", "$(arg x)", "x"]

    def theirs(text):
        q = xacro.QuickLexer(xacro.LEXER)
        q.lex(text)
        out = []
        while q.peek():
            out.append(q.next())
        return tuple(out)

    for _ in range(5000):
        text = "".join(rnd.choice(alphabet) for _ in range(rnd.randint(0, 12)))
        try:
            want = theirs(text)
        except xacro.XacroException as exc:
            want = str(exc)
        fast._tokens.clear()
        try:
            got = tokens(text)
        except xacro.XacroException as exc:
            got = str(exc)
        assert got == want, text


# ------------------------------------------------------------------ suppression comments
def test_suppression_comments_are_parsed_and_applied_in_linear_time(tmp_path):
    from myrabot_desc.checks import suppress
    from myrabot_desc.diagnostics import Diagnostic, Loc

    t = time.process_time()
    found = suppress.comment_suppressions(" myrabot-desc:ignore[" * 200_000)
    assert found == [] and time.process_time() - t < 1.0      # the regex backtracked: > 38 s
    n = 20_000
    body = "".join(f'<!-- myrabot-desc: ignore[T009] -->\n<link name="l{i}"/>\n' for i in range(n))
    f = write(tmp_path / "s.urdf", f'<robot name="s">\n{body}</robot>\n')
    suppress._cache.clear()
    t = time.process_time()
    sups = suppress.suppressions_in(str(f))
    assert len(sups) == n and sups[5].start == 13 and sups[5].end == 13
    by_file = {str(f): sups}
    diags = [Diagnostic("T009", "error", "x", Loc(str(f), 3 + 2 * i)) for i in range(n)]
    hits = suppress._first_covering(diags, by_file)
    assert all(h is not None and h.line == 2 + 2 * i for i, h in enumerate(hits))
    assert time.process_time() - t < 5.0                      # quadratic before: 20,000 x 20,000


def test_suppressions_kept_by_content_are_bounded():
    # the bytes a model was built from are cached with their suppressions: a long run over many files
    # keeps at most a bounded number of them, and an entry dropped is parsed again, the same
    from myrabot_desc.checks import suppress

    suppress._by_content.clear()
    first = b'<robot name="r"><!-- myrabot-desc: ignore[I008] --><link name="l0"/></robot>'
    want = suppress.suppressions_of("f0.urdf", first)
    assert [(s.codes, s.line) for s in want] == [(("I008",), 1)]
    for i in range(1, 3 * suppress._BY_CONTENT_MOST):
        data = first.replace(b"l0", f"l{i}".encode())
        assert suppress.suppressions_of(f"f{i}.urdf", data)[0].codes == ("I008",)
        assert len(suppress._by_content) <= suppress._BY_CONTENT_MOST
    assert suppress.suppressions_of("f0.urdf", first) == want
    assert suppress.suppressions_of("plain.urdf", b'<robot name="r"/>') == []


def test_suppression_parsing_agrees_with_the_pattern():
    import re

    from myrabot_desc.checks.suppress import comment_suppressions

    pattern = re.compile(r"myrabot-desc:\s*(ignore-file|ignore)\s*\[([^\]]*)\]")
    rnd = random.Random(11)
    parts = ["myrabot-desc:", "ignore", "ignore-file", "[", "]", " ", "I008", ",", "x", "\n"]
    for _ in range(20_000):
        text = "".join(rnd.choice(parts) for _ in range(rnd.randint(0, 14)))
        assert comment_suppressions(text) == [(m.group(1), m.group(2)) for m in pattern.finditer(text)], text


# ------------------------------------------------------------------ meshes
def _robot(tmp_path, mesh: str, name="r.urdf"):
    return write(tmp_path / name, f'<robot name="r"><link name="base"><inertial><mass value="1"/>'
                 f'<inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>'
                 f'<collision><geometry><mesh filename="{mesh}"/></geometry></collision></link></robot>\n')


def _bz2_of_spaces(n_mb: int) -> bytes:
    c = bz2.BZ2Compressor(9)
    parts = [c.compress(b"solid x\n")] + [c.compress(b" " * 1_000_000) for _ in range(n_mb)]
    return b"".join(parts) + c.flush()


MESH_BOMBS = {
    "bomb.bz2": lambda: _bz2_of_spaces(1700),                    # 1.7 GB inflated (trimesh's bz2 loader)
    "bomb.tar.bz2": lambda: _bz2_of_spaces(300),
    "gz_named.stl": lambda: gzip.compress(b" " * 300_000_000, 9),   # any name: the bytes decide
    "xz_named.obj": lambda: lzma.compress(b" " * 300_000_000, preset=1),
    "zstd.stl": lambda: b"(\xb5/\xfd" + os.urandom(200),
    "polygon.obj": lambda: b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf " + b" ".join(b"%d" % (1 + i % 3) for i in range(7_000_000)) + b"\n",
    "many_p.dae": lambda: (b'<?xml version="1.0"?><COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" '
                           b'version="1.4.1"><library_geometries><geometry id="g"><mesh><polygons count="3000000">'
                           + b"<p>0 1 2</p>" * 3_000_000 + b"</polygons></mesh></geometry></library_geometries></COLLADA>"),
    # over the triangle limit the tests set (MESH_ENV): 250,000 facets, 13 MB
    "ascii_many.stl": lambda: b"solid x\n" + b"facet\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendfacet\n" * 250_000
                              + b"endsolid x\n",
}


MESH_ENV = {"MYRABOT_DESC_MAX_MESH_TRIANGLES": "200000"}


@pytest.fixture(scope="module")
def mesh_bombs(tmp_path_factory):
    d = tmp_path_factory.mktemp("meshbombs")
    for name, make in MESH_BOMBS.items():
        (d / name).write_bytes(make())
    return d


@pytest.mark.parametrize("name", sorted(MESH_BOMBS))
@pytest.mark.parametrize("command", [["check", "--isolated", "--inertia", "--meshes"], ["convert", "--to", "mjcf"],
                                     ["convert", "--to", "sdf"]])
def test_a_mesh_is_bounded_while_it_is_read(mesh_bombs, tmp_path, name, command):
    model = _robot(mesh_bombs, name, f"{name}.urdf")
    argv = command + [model] + (["-o", tmp_path / "o" / "x.xml"] if command[0] == "convert" else [])
    r = run(argv, cwd=tmp_path, env=MESH_ENV)
    assert not within_budget(r), (within_budget(r), r.stdout[-500:], r.stderr[-500:])
    text = r.stdout + r.stderr
    if command[0] == "check":           # M005 (always) and I011 say why
        assert r.code == 1 and "M005" in text and name in text, text[-600:]
    else:
        assert r.code == 2 and f"{name}.urdf:1: error:" in text and not (tmp_path / "o").exists(), text[-600:]


def test_mesh_limits_say_why(mesh_bombs, monkeypatch):
    from myrabot_desc.model import meshes

    monkeypatch.setenv("MYRABOT_DESC_MAX_MESH_TRIANGLES", MESH_ENV["MYRABOT_DESC_MAX_MESH_TRIANGLES"])
    why = {n: meshes.unreadable(mesh_bombs / n) for n in MESH_BOMBS}
    assert "inflates to over 50000000 bytes" in why["bomb.bz2"]
    assert "inflates to over" in why["gz_named.stl"] and "inflates to over" in why["xz_named.obj"]
    assert "zstd-compressed" in why["zstd.stl"]
    assert "holds 6999998 triangles, over the 200000 limit" in why["polygon.obj"]
    assert "triangles, over the 200000 limit" in why["many_p.dae"]     # counted on the bytes, before lxml
    monkeypatch.setenv("MYRABOT_DESC_MAX_MESH_TRIANGLES", "5000000")
    assert "3000006 XML elements, over the 500000 limit" in meshes.unreadable(mesh_bombs / "many_p.dae")
    assert "holds 250000 triangles, over the 200000 limit" in why["ascii_many.stl"]


def test_collada_triangles_are_counted_per_primitive_before_arrays(tmp_path, monkeypatch):
    """A polylist of 2.5 M triangles with stride 1 is refused by its index count while reading (the
    limit applied after the arrays were built: 5.5 M faces took 1.9 GB)."""
    from myrabot_desc.model import meshes

    monkeypatch.setenv("MYRABOT_DESC_MAX_MESH_TRIANGLES", "1000")
    n = 1500
    idx = " ".join(str(i % 3) for i in range(3 * n))
    dae = (f'<?xml version="1.0"?><COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">'
           f'<library_geometries><geometry id="g"><mesh><source id="p"><float_array id="pa" count="9">0 0 0 1 0 0 0 1 0'
           f'</float_array><technique_common><accessor source="#pa" count="3" stride="3"><param name="X" type="float"/>'
           f'<param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>'
           f'<vertices id="v"><input semantic="POSITION" source="#p"/></vertices><triangles count="{n}">'
           f'<input semantic="VERTEX" source="#v" offset="0"/><p>{idx}</p></triangles></mesh></geometry>'
           f'</library_geometries><library_visual_scenes><visual_scene id="s"><node id="n"><instance_geometry url="#g"/>'
           f'</node></visual_scene></library_visual_scenes><scene><instance_visual_scene url="#s"/></scene></COLLADA>')
    f = write(tmp_path / "t.dae", dae)
    with pytest.raises(meshes.MeshError, match="holds over 1000 triangles"):
        meshes.facts(f)
    monkeypatch.setenv("MYRABOT_DESC_MAX_MESH_TRIANGLES", "2000")
    assert meshes.facts(f).n_faces == n


def test_a_small_compressed_mesh_still_loads(tmp_path):
    from myrabot_desc.model import meshes

    from helpers import BAD

    cube = (BAD / "meshes" / "meshes" / "cube.stl").read_bytes()
    f = write(tmp_path / "cube.stl.bz2", bz2.compress(cube))
    meshes.check_content(f, f.read_bytes())
    assert meshes.unreadable(f) is None


# ------------------------------------------------------------------ textures, package.xml
def test_a_huge_texture_is_refused_from_its_header(tmp_path):
    from PIL import Image

    from myrabot_desc.materials import textures

    big = tmp_path / "big.png"
    Image.frombytes("L", (16000, 11000), b"\x80" * (16000 * 11000)).save(big)      # 176 megapixels
    t = time.process_time()
    with pytest.raises(textures.TextureError, match="16000x11000 pixels, over the 16777216-pixel"):
        textures.open_image(big)
    assert textures.mean_rgb(big) is None and time.process_time() - t < 1.0
    Image.new("RGB", (64, 64), (255, 0, 0)).save(tmp_path / "red.png")
    assert textures.mean_rgb(tmp_path / "red.png") == (1.0, 0.0, 0.0)
    os.mkfifo(tmp_path / "fifo.png")
    assert textures.mean_rgb(tmp_path / "fifo.png") is None


def test_package_xml_is_read_bounded_and_inside_its_package(tmp_path):
    from myrabot_desc.expand.packages import package_name

    pkg = tmp_path / "pkg"
    pkg.mkdir()
    with open(pkg / "package.xml", "wb") as f:          # 1.2 GB, sparse: read whole before
        f.write(b"<package><name>big</name>")
        f.truncate(1_200_000_000)
    t = time.process_time()
    assert package_name(pkg) == "pkg" and time.process_time() - t < 1.0
    (pkg / "package.xml").unlink()
    outside = write(tmp_path / "secret" / "package.xml", "<package><name>leaked</name></package>")
    (pkg / "package.xml").symlink_to(outside)
    assert package_name(pkg) == "pkg"                   # a link out of the package is not read
    (pkg / "package.xml").unlink()
    write(pkg / "package.xml", "<package><name>fine_pkg</name></package>")
    assert package_name(pkg) == "fine_pkg"


# ------------------------------------------------------------------ sim and render parameters
def test_sim_steps_are_bounded(tmp_path):
    r = run(["sim", "vuelta", "--duration", "86400", "--rate", "100000"], cwd=tmp_path)
    assert r.code == 2 and not within_budget(r) and r.cpu < 3          # out of memory after 12 s before
    assert r.stderr.startswith("error: a simulation of 86400 s at 100000 Hz is 8640000000 steps, over the 1000000")
    from myrabot_desc.errors import InputError
    from myrabot_desc.safety import sim_steps

    assert sim_steps(25, 1000) == 25_000
    for bad in ((float("inf"), 1000.0), (1e12, 1.0), (float("nan"), 10.0)):
        with pytest.raises(InputError):
            sim_steps(*bad)


def test_render_size_and_frames_are_bounded(tmp_path):
    r = run(["render", "--size", "4096x4096", "-o", tmp_path / "r.png"], cwd=tmp_path)
    assert r.code == 2 and "over the 4194304-pixel limit" in r.stderr and not (tmp_path / "r.png").exists()
    links = "".join(f'<link name="l{i}"/><joint name="j{i}" type="fixed"><parent link="l{i - 1}"/><child link="l{i}"/>'
                    f'<origin xyz="0.01 0 0"/></joint>' for i in range(1, 600))
    f = write(tmp_path / "many.urdf", f'<robot name="m"><link name="l0"/>{links}</robot>\n')
    r = run(["render", f, "--frames", "-o", tmp_path / "r.png"], cwd=tmp_path)
    if "not installed" in r.stderr:
        pytest.skip(r.stderr)
    refused(r, "many.urdf:1: error: --frames draws every link frame: 600 links")


def test_every_limit_is_in_the_table_and_the_help(tmp_path):
    from myrabot_desc.safety import LIMITS

    r = run(["--help"])
    fields = {lim.field for lim in LIMITS}
    assert {"max_includes", "max_manifest_bytes", "max_mesh_elements", "max_texture_pixels", "max_sim_steps",
            "max_render_pixels", "max_render_frames"} <= fields
    for lim in LIMITS:
        assert lim.env in r.stdout


@pytest.mark.parametrize("size", [0, 1, 100, 65_536, 65_537, 300_000])
def test_a_bounded_read_gives_what_a_read_of_the_limit_gives(tmp_path, size):
    """Every file, model or mesh, is read up to its limit + 1 bytes: the same bytes as
    ``f.read(limit + 1)`` at every size around the limit, without allocating the limit first; a
    file larger than its stat says (a /proc file says 0) and an endless one stop at the limit."""
    import os

    from myrabot_desc.safety import read_bounded, read_checked

    path = tmp_path / "f.bin"
    path.write_bytes(os.urandom(size))
    for limit in {0, 1, max(size - 1, 0), size, size + 1, 70_000, 1 << 21}:
        with open(path, "rb") as a, open(path, "rb") as b:
            assert read_bounded(a, limit) == b.read(limit + 1), limit
    assert read_checked(path, None, size) == path.read_bytes()
    with open("/dev/zero", "rb") as f:
        assert len(read_bounded(f, 200_000)) == 200_001
    with open("/proc/self/status", "rb") as f:      # st_size 0, content several hundred bytes
        assert b"Name:" in read_bounded(f, 1_000_000)
    r, w = os.pipe()
    os.write(w, b"x" * 5000)
    os.close(w)
    with os.fdopen(r, "rb") as f:
        assert read_bounded(f, 1_000_000) == b"x" * 5000
