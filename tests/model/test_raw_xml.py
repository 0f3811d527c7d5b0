"""model/ is the only reader of the robot's XML (docs/architecture.md): every other module reads the
typed model (model/parts.py, model/nodes.py for markup carried as it is, model/values.py for values).

An AST scan of every module of the package outside model/, the build (expand/, which writes
the document the model reads) and xmltree.py (the element tree the model reads it into) fails on
what reads raw robot XML:

- the raw accessors: ``.root_element``, ``.element`` (the parts' compatibility name for ``ref``),
  ``.element_locs``, ``.urdf_text``, ``loc_of(...)`` (the location of a raw element), or anything
  read through a part's ``ref`` (``part.ref.get(...)``: ``ref`` is an opaque handle for
  ``Robot.sources``, passed, never opened);
- a namespace stripped from a tag by hand (``tag.rsplit("}", 1)``): the model's nodes carry local
  names.

The raw-syntax rules that judge the XML itself are the exception, and ALLOWED says why; the scan
also fails when an exception is no longer needed (so the list stays true).
"""

from __future__ import annotations

import ast

import pytest

from helpers import ROOT

PACKAGE = ROOT / "myrabot_desc"
RAW_ATTRIBUTES = {"root_element", "element", "element_locs", "urdf_text", "loc_of"}

# module -> (what it may read, why)
ALLOWED = {
    "myrabot_desc.checks.urdf_syntax": (
        {"root_element", "loc_of", "namespace stripped by hand"},
        "T005/T006/T007 judge the XML itself: elements and attributes no reader knows, a <ros> block "
        "where nobody reads it; the typed model holds only what a reader keeps"),
    "myrabot_desc.checks.context": (
        {"loc_of"},
        "Context.loc_of: the location of a raw element, for the raw-syntax rules above"),
}


def _modules():
    for path in sorted(PACKAGE.rglob("*.py")):
        rel = path.relative_to(ROOT).with_suffix("").parts
        name = ".".join(rel[:-1] if rel[-1] == "__init__" else rel)
        if name.startswith(("myrabot_desc.model", "myrabot_desc.expand", "myrabot_desc.xmltree")):
            continue
        yield name, path


def _raw_reads(tree) -> list[tuple[int, str]]:
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute):
            if node.attr in RAW_ATTRIBUTES:
                out.append((node.lineno, node.attr))
            if isinstance(node.value, ast.Attribute) and node.value.attr == "ref":
                out.append((node.lineno, f"ref.{node.attr}"))
        elif isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) \
                and node.func.attr in ("rsplit", "split", "partition", "rpartition") and node.args \
                and isinstance(node.args[0], ast.Constant) and node.args[0].value == "}":
            out.append((node.lineno, "namespace stripped by hand"))
    return out


def test_no_module_outside_model_reads_raw_robot_xml():
    found, used = [], {}
    for name, path in _modules():
        allowed = ALLOWED.get(name, (set(), ""))[0]
        for line, what in _raw_reads(ast.parse(path.read_text(encoding="utf-8"))):
            if what in allowed:
                used.setdefault(name, set()).add(what)
            else:
                found.append(f"{path.relative_to(ROOT)}:{line}: {what}")
    assert found == [], "raw robot XML read outside model/ (read the typed model):\n" + "\n".join(found)
    assert {n: a for n, (a, _) in ALLOWED.items()} == used, "an exception of ALLOWED is no longer needed"


@pytest.mark.parametrize("snippet, what", [
    ("robot.root_element.findall('joint')", "root_element"),
    ("for c in plugin.element: pass", "element"),
    ("sensor.ref.get('name')", "ref.get"),
    ("ctx.loc_of(el)", "loc_of"),
    ("tag.rsplit('}', 1)[-1]", "namespace stripped by hand"),
])
def test_the_scan_sees_each_raw_read(snippet, what):
    assert [w for _, w in _raw_reads(ast.parse(snippet))] == [what]


def test_the_scan_lets_the_typed_model_through():
    ok = ("robot.sources.field(plugin, 'wheelSeparation')\n"
          "plugin.node.find('ros', 'namespace')\n"
          "robot.origin(sensor, 'update_rate')\n"
          "Sources(part.ref)\n")
    assert _raw_reads(ast.parse(ok)) == []
