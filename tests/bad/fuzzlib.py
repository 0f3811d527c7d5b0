"""Mutation fuzzing of URDF, xacro and OGRE material files (tests/hardening/test_fuzz.py, bench/fuzz_long.py).

A case is an integer: it picks a seed file, a few mutations (delete, duplicate, swap, move and
rename elements; delete, duplicate and corrupt attributes and numbers; truncate, splice bytes;
for materials, delete/duplicate/swap lines and corrupt tokens) and a command, all from
``random.Random(case)``, so every failure is reproducible from its number::

    python bench/fuzz_long.py --case 1234 --show

The property: the command ends with exit 0, 1 or 2, with no exception escaping, no traceback or
"internal error" in its output, within the time limit, without network or subprocess, and
without opening a file outside the case folder, the package roots and Python's own folders.
"""

from __future__ import annotations

import glob
import random
import re
import shutil
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent.parent
sys.path.insert(0, str(HERE))

import harness  # noqa: E402

WEIRD_VALUES = ["nan", "inf", "-inf", "1e999", "1e300", "-1", "0", "", " ", "abc", "1 2", "1 2 3 4", "0x10", "1,5",
                "${nope}", "${1/0}", "${9**9**9}", "$(arg nope)", "$(env HOME)", "$(find nope)", "${'a'*10**9}",
                "package://nope/x.stl", "package://myrabot_description/../../../etc/passwd", "file:///etc/passwd",
                "../../../../../../etc/passwd", "/dev/zero", "x" * 5000, "ñ€\u202e", "1e-320", "-0",
                "${__import__('os')}", "&amp;", "true", "continuous", "fixed", "floating", "planar", "revolute"]
# issue 17: the sandbox's bounds and refusals, one hostile expression each
WEIRD_VALUES += ["${b'a'*400000000}", "${'%(a)01000000000d' % dict(a=1)}", "${python.sorted(['pi'], key=python.pop)}",
                 "${xacro.clear()}", "${(lambda f: f(f))(lambda f: f(f))}", "${[].append(1)}",
                 "${len([s + s for s in ['x' * 900000 for _ in python.range(40)]])}", "${'ab'.split()[5]}",
                 "${[c.upper() for c in 'abc']}", "${dict(a=1).get('a')}", "${xacro.load_yaml('/dev/zero')}"]
# names for xacro:attribute / xacro:element: valid, with a space, markup, an injection, empty
WEIRD_NAMES = ["ok_name", "a b", "a<b", 'x="1"><joint name="j" type="fixed"/><link name="q', "", "1abc", "ns:x"]
WEIRD_TAGS = ["link", "joint", "xacro:macro", "xacro:include", "xacro:property", "xacro:insert_block", "gazebo",
              "plugin", "sensor", "inertial", "mass", "origin", "geometry", "mesh", "box", "limit", "mimic",
              "xacro:if", "xacro:unless", "xacro:call", "transmission", "material", "robot"]
NUMBER = re.compile(rb"-?\d+\.?\d*(?:[eE][+-]?\d+)?")


def seed_files() -> dict[str, list[Path]]:
    """Valid inputs to mutate: (kind -> files)."""
    out = {"urdf": [], "xacro": [], "material": []}
    erd = sorted(glob.glob(str(Path(sys.prefix) / "lib/python3*/site-packages/cmeel.prefix/share/"
                                "example-robot-data/robots/*/urdf/*.urdf")))
    # the small and medium ones keep cases fast; the long run takes them all
    out["urdf"] = [Path(p) for p in erd if Path(p).stat().st_size < 120_000] + [bundled_urdf()]
    out["xacro"] = sorted(REPO.glob("tests/fixtures/seed_myrabot/*/urdf/*.xacro")) + \
        sorted(REPO.glob("tests/fixtures/xacro/*.xacro")) + sorted(REPO.glob("tests/fixtures/wander_bot/urdf/*.xacro")) + \
        sorted(REPO.glob("xacro/*.xacro")) + sorted(REPO.glob("tests/fixtures/legacy/*/*/urdf/*.xacro"))
    out["material"] = sorted(REPO.glob("tests/fixtures/materials/*.material")) + \
        sorted(REPO.glob("tests/fixtures/materials/*/Media/materials/scripts/*.material")) + \
        sorted(REPO.glob("materials/**/*.material", ))
    return out


def bundled_urdf() -> Path:
    """The bundled MYRAbot, built once (its package:// URIs point into the bundled package)."""
    import tempfile

    dest = Path(tempfile.gettempdir()) / "myrabot_fuzz_seed" / "myrabot.urdf"
    if not dest.is_file():
        from myrabot_desc.expand.driver import build_file
        from myrabot_desc.expand.packages import bundled_path

        dest.parent.mkdir(parents=True, exist_ok=True)
        dest.write_text(build_file(bundled_path()).text)
    return dest


def base_robot() -> bytes:
    import make_corpus

    return make_corpus.robot().encode()


# ------------------------------------------------------------------ XML mutations (lxml)
def mutate_xml(data: bytes, rnd: random.Random, n: int) -> bytes:
    from lxml import etree

    try:
        root = etree.fromstring(data, etree.XMLParser(remove_blank_text=False, resolve_entities=False))
    except etree.XMLSyntaxError:
        return mutate_bytes(data, rnd, n)
    for _ in range(n):
        els = [e for e in root.iter() if isinstance(e.tag, str)]
        if not els:
            break
        el = rnd.choice(els)
        op = rnd.randrange(13)
        parent = el.getparent()
        if op == 0 and parent is not None:                       # delete an element
            parent.remove(el)
        elif op == 1 and parent is not None:                     # duplicate it
            import copy

            parent.insert(parent.index(el), copy.deepcopy(el))
        elif op == 2 and parent is not None and len(parent) > 1:  # swap two siblings
            kids = list(parent)
            a, b = rnd.sample(range(len(kids)), 2)
            ka, kb = kids[a], kids[b]
            parent.replace(ka, etree.Element("tmp"))
            parent.replace(kb, ka)
            parent.replace(parent[a], kb)
        elif op == 3 and parent is not None:                     # move under another element
            target = rnd.choice(els)
            if target is not el and el not in target.iterancestors() and target is not el:
                try:
                    target.append(el)
                except (ValueError, TypeError):
                    pass
        elif op == 4 and el.attrib:                              # delete an attribute
            del el.attrib[rnd.choice(list(el.attrib))]
        elif op in (5, 6, 7) and el.attrib:                      # corrupt an attribute value
            k = rnd.choice(list(el.attrib))
            el.set(k, rnd.choice(WEIRD_VALUES))
        elif op == 8 and el.attrib:                              # corrupt one number inside a value
            k = rnd.choice(list(el.attrib))
            v = el.get(k)
            nums = list(NUMBER.finditer(v.encode()))
            if nums:
                m = rnd.choice(nums)
                v = v[:m.start()] + rnd.choice(["nan", "-1e308", "0", "1e12", "-0.0", "x", "", "99999999999"]) + v[m.end():]
                el.set(k, v)
        elif op == 9:                                            # rename the element
            try:
                tag = rnd.choice(WEIRD_TAGS)
                if ":" in tag:
                    el.tag = "{http://www.ros.org/wiki/xacro}" + tag.split(":")[1]
                else:
                    el.tag = tag
            except ValueError:
                pass
        elif op == 10:                                           # add a stray attribute
            try:
                el.set(rnd.choice(["name", "link", "value", "filename", "params", "xyz", "rpy", "type", "scale"]),
                       rnd.choice(WEIRD_VALUES))
            except ValueError:
                pass
        elif op == 11 and el.text and el.text.strip():           # corrupt text content
            el.text = rnd.choice(WEIRD_VALUES)
        elif op == 12:                                           # a xacro:attribute / xacro:element child
            kind = rnd.choice(["attribute", "element"])
            child = etree.SubElement(el, "{http://www.ros.org/wiki/xacro}" + kind)
            if kind == "attribute":
                child.set("name", rnd.choice(WEIRD_NAMES))
                child.set("value", rnd.choice(WEIRD_VALUES))
            else:
                child.set("{http://www.ros.org/wiki/xacro}name", rnd.choice(WEIRD_NAMES))
    out = etree.tostring(root, xml_declaration=True, encoding="utf-8")
    if rnd.random() < 0.05:
        out = mutate_bytes(out, rnd, 1)
    return out


def mutate_bytes(data: bytes, rnd: random.Random, n: int) -> bytes:
    for _ in range(n):
        op = rnd.randrange(5)
        i = rnd.randrange(len(data) + 1) if data else 0
        if op == 0:
            data = data[:i]                                       # truncate
        elif op == 1:
            data = data[:i] + bytes(rnd.randrange(256) for _ in range(rnd.randrange(1, 20))) + data[i:]
        elif op == 2 and data:
            j = rnd.randrange(len(data))
            data = data[:i] + data[j:j + rnd.randrange(1, 200)] + data[i:]   # splice a piece elsewhere
        elif op == 3 and data:
            data = data[:i] + data[i + rnd.randrange(1, 50):]      # delete a run
        else:
            data = data[:i] + rnd.choice([b"<", b">", b"&", b"\"", b"${", b"$(", b"}", b"]]>", b"<!--",
                                          b"<!DOCTYPE x>", b"\x00", b"\xff"]) + data[i:]
    return data


# ------------------------------------------------------------------ OGRE script mutations
def mutate_material(data: bytes, rnd: random.Random, n: int) -> bytes:
    lines = data.split(b"\n")
    for _ in range(n):
        op = rnd.randrange(7)
        i = rnd.randrange(len(lines)) if lines else 0
        if not lines:
            lines = [b""]
        if op == 0:
            del lines[i]
        elif op == 1:
            lines.insert(i, lines[i])
        elif op == 2 and len(lines) > 1:
            j = rnd.randrange(len(lines))
            lines[i], lines[j] = lines[j], lines[i]
        elif op == 3:
            nums = list(NUMBER.finditer(lines[i]))
            if nums:
                m = rnd.choice(nums)
                lines[i] = lines[i][:m.start()] + rnd.choice([b"nan", b"inf", b"-5", b"1e999", b"x", b"", b"1 2 3"]) \
                    + lines[i][m.end():]
        elif op == 4:
            lines.insert(i, rnd.choice([b"{", b"}", b"material", b"material x : y", b"import * from \"../x.material\"",
                                        b"/*", b"*/", b"//", b"set $x \"$x\"", b"texture ../../../etc/passwd",
                                        b"pass", b"technique", b"\"", b"abstract material t"]))
        elif op == 5:
            toks = lines[i].split()
            if toks:
                toks[rnd.randrange(len(toks))] = rnd.choice([b"{", b"}", b"nan", b"material", b":", b"$x", b""])
                lines[i] = b" ".join(toks)
        else:
            lines = lines[:i]
    return b"\n".join(lines)


# ------------------------------------------------------------------ cases
MODEL_COMMANDS = ["build", "check", "check", "check-inertia", "info", "convert-sdf", "convert-sdf", "convert-mjcf",
                  "sim-drive"]


def make_case(case: int, seeds: dict, workdir: Path) -> tuple[Path, str, str]:
    """Write the mutated input of ``case`` under ``workdir``; returns (file, command, description)."""
    rnd = random.Random(case)
    kind = rnd.choices(["urdf", "base", "xacro", "material"], [4, 2, 4, 2])[0]
    n = rnd.choice([1, 1, 1, 2, 2, 3, 5, 8])
    if kind == "material":
        src = rnd.choice(seeds["material"])
        shutil.copytree(src.parent, workdir, dirs_exist_ok=True, ignore=shutil.ignore_patterns("*.png", "*.jpg"))
        dest = workdir / src.name
        dest.write_bytes(mutate_material(src.read_bytes(), rnd, n))
        return dest, "materials", f"{src.name} x{n}"
    if kind == "xacro":
        src = rnd.choice(seeds["xacro"])
        pkg = _package_of(src)
        skip = shutil.ignore_patterns("*.stl", "*.dae", "*.png", "*.jpg", "__pycache__")
        workdir.mkdir(parents=True, exist_ok=True)
        if pkg == REPO:   # the bundled package: its xacro folder and package.xml are enough
            shutil.copy(REPO / "package.xml", workdir / "package.xml")
            shutil.copytree(src.parent, workdir / src.parent.name, ignore=skip)
        else:
            shutil.copytree(pkg, workdir, dirs_exist_ok=True, ignore=skip)
        dest = workdir / src.relative_to(pkg)
        data = src.read_bytes()
    elif kind == "base":
        dest, data, src = workdir / "robot.urdf", base_robot(), Path("base_robot.urdf")
    else:
        src = rnd.choice(seeds["urdf"])
        dest, data = workdir / src.name, src.read_bytes()
    dest.parent.mkdir(parents=True, exist_ok=True)
    dest.write_bytes(mutate_xml(data, rnd, n) if rnd.random() < 0.95 else mutate_bytes(data, rnd, n))
    return dest, rnd.choice(MODEL_COMMANDS), f"{src.name} x{n}"


def _package_of(path: Path) -> Path:
    for folder in path.parents:
        if (folder / "package.xml").is_file() or (folder / "manifest.xml").is_file():
            return folder
        if folder == REPO:
            break
    return path.parent


def run_case(case: int, seeds: dict, scratch: Path, time_limit: float = harness.TIME_LIMIT) -> dict:
    """Build, run and judge one case; returns the harness result with ``problems``."""
    import os

    work = scratch / f"c{case}"
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    src, command, what = make_case(case, seeds, work / "in")
    out = work / "out"
    out.mkdir()
    cwd = os.getcwd()
    os.chdir(work)
    if command == "convert-mjcf":   # big unmutated models take seconds there (b1-z1: 5.5 s): a hang is >20 s
        time_limit = max(time_limit, 20.0)
    try:
        run = harness.invoke(harness.argv_for(command, src, out), time_limit=time_limit)
    finally:
        os.chdir(cwd)
    problems = harness.problems(run, command, "fuzz", work / "in", out, src, time_limit)
    run.update(case=case, command=command, what=what, problems=problems)
    shutil.rmtree(work, ignore_errors=True)
    return run
