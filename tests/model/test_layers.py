"""The package layout is a pipeline, and stays one (docs/architecture.md):

- the import contracts of pyproject.toml ``[tool.importlinter]`` hold (import-linter): the layers
  commands → render, info → view → checks, convert, sim → model → expand → base, no import loop
  between sibling packages or modules at any depth, click only in commands/;
- a contract that is broken makes ``lint-imports`` fail (a violation planted in a copy);
- our own modules are imported at module top: a function-level import of one is one of
  the exceptions that keep the command line's start-up (LAZY_OWN);
- heavy third-party libraries are not imported at any module's top (lxml: convert only; click:
  commands only).
"""

from __future__ import annotations

import ast
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from helpers import ROOT

PACKAGE = ROOT / "myrabot_desc"
LINT_IMPORTS = Path(sys.executable).with_name("lint-imports")

# module -> our modules it may import inside a function, and why (start-up, bench/bench_start.py)
LAZY_OWN = {
    # the console script picks the click-free plain build, check or diff, or the click group: none pays for
    # another
    "myrabot_desc.commands.entry": {"myrabot_desc.commands.fastbuild", "myrabot_desc.commands.fastcheck",
                                    "myrabot_desc.commands.fastdiff", "myrabot_desc.commands.main"},
    # `build --help` and click's usage errors do not load the build engine
    "myrabot_desc.commands.build": {"myrabot_desc.commands.fastbuild"},
    # `diff` loads the renderer and the scene for --picture only (~10 ms of a small robot's ~300 ms diff)
    "myrabot_desc.commands.fastdiff": {"myrabot_desc.render", "myrabot_desc.view.scene"},
    # `check` loads the fixer for --fix and --diff only (~5 ms of every lint run), the baseline for --baseline
    "myrabot_desc.commands.fastcheck": {"myrabot_desc.fix.report", "myrabot_desc.fix.run", "myrabot_desc.fix.write",
                                        "myrabot_desc.checks.baseline"},
    # a lint run of one file reads no .gitignore, git state or SRDF unless asked (a folder, --changed-since,
    # --srdf), nor the source spans only a fix or a diff reads (~2 ms together)
    "myrabot_desc.checks.run": {"myrabot_desc.checks.gitignore", "myrabot_desc.vcs"},
    "myrabot_desc.checks.collisions": {"myrabot_desc.model.srdf"},
    "myrabot_desc.model.parts": {"myrabot_desc.model.sources"},
    # the OGRE script reader (~3 ms) for a material name that is not a stock one: a model whose names are
    # all stock (or that has none) is checked with the stock table alone
    "myrabot_desc.checks.plugins": {"myrabot_desc.materials.resolve"},
    "myrabot_desc.materials": {"myrabot_desc.materials.resolve"},
    "myrabot_desc.materials.stock": {"myrabot_desc.materials.ogre"},
}
HEAVY = {"numpy", "scipy", "trimesh", "pinocchio", "mujoco", "yourdfpy", "viser", "matplotlib", "PIL", "coal",
         "collada", "networkx", "yaml", "xacro", "lxml", "click"}
TOP_ALLOWED = {"lxml": "myrabot_desc.convert", "click": "myrabot_desc.commands"}


def _lint(cwd: Path, env: dict | None = None) -> subprocess.CompletedProcess:
    return subprocess.run([str(LINT_IMPORTS), "--no-cache", str(ROOT / "pyproject.toml")], cwd=cwd,
                          capture_output=True, text=True, env=env, timeout=300)


def _modules():
    for path in sorted(PACKAGE.rglob("*.py")):
        parts = path.relative_to(ROOT).with_suffix("").parts
        name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        yield name, path, ast.parse(path.read_text(encoding="utf-8"))


def _imports(tree):
    """(node, imported module names, inside a function, under `if TYPE_CHECKING`) for every import."""
    out = []

    def visit(node, in_func, typing_only):
        for child in ast.iter_child_nodes(node):
            f = in_func or isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda))
            t = typing_only or (isinstance(child, ast.If) and "TYPE_CHECKING" in ast.unparse(child.test))
            if isinstance(child, ast.Import):
                out.append((child, [a.name for a in child.names], in_func, t))
            elif isinstance(child, ast.ImportFrom) and child.level == 0 and child.module:
                out.append((child, [child.module], in_func, t))
            visit(child, f, t)

    visit(tree, False, False)
    return out


def test_import_contracts_hold():
    res = _lint(ROOT)
    assert res.returncode == 0, res.stdout[-4000:] + res.stderr[-2000:]
    assert "0 broken" in res.stdout


@pytest.mark.parametrize("plant", [
    ("model/tree.py", "from myrabot_desc.commands import options  # noqa\n", "layers"),
    ("expand/legacy.py", "import myrabot_desc.model.tree  # noqa\n", "loop"),
    ("checks/rule.py", "import myrabot_desc.sim.servo  # noqa\n", "siblings"),
    ("info.py", "import click  # noqa\n", "click"),
], ids=lambda p: p[2])
def test_a_planted_violation_breaks_the_contracts(plant, tmp_path):
    """The contracts bite: the same check fails on a copy of the package with one forbidden import
    added (a lower layer importing a higher one, a package loop, two consumers of one layer, click)."""
    rel, line, _ = plant
    shutil.copytree(PACKAGE, tmp_path / "myrabot_desc", ignore=shutil.ignore_patterns("__pycache__"))
    target = tmp_path / "myrabot_desc" / rel
    text = target.read_text(encoding="utf-8")
    head, sep, rest = text.partition("from __future__ import annotations\n")
    target.write_text(head + sep + line + rest if sep else line + text, encoding="utf-8")
    env = dict(os.environ, PYTHONPATH=str(tmp_path))
    res = _lint(tmp_path, env)
    assert res.returncode != 0 and "BROKEN" in res.stdout.upper(), res.stdout[-3000:]


def test_own_modules_are_imported_at_module_top():
    """A function-level import of our own module hides the structure (a cycle, or a module that
    imports something heavy at its top): only the command line's start-up ones are allowed."""
    found = []
    for name, path, tree in _modules():
        for node, targets, in_func, _ in _imports(tree):
            own = [t for t in targets if t == "myrabot_desc" or t.startswith("myrabot_desc.")]
            if in_func and own and not set(own) <= LAZY_OWN.get(name, set()):
                found.append(f"{path.relative_to(ROOT)}:{node.lineno}: {', '.join(own)}")
    assert found == []


def test_no_heavy_library_at_a_module_top():
    """numpy, trimesh, pinocchio, mujoco, PyYAML, xacro... are imported inside the functions that use
    them, so that importing a module costs nothing heavy (lxml: convert; click: commands)."""
    found = []
    for name, path, tree in _modules():
        for node, targets, in_func, typing_only in _imports(tree):
            if in_func or typing_only:
                continue
            for t in targets:
                top = t.split(".")[0]
                allowed = TOP_ALLOWED.get(top)
                if top in HEAVY and not (allowed and (name == allowed or name.startswith(allowed + "."))):
                    found.append(f"{path.relative_to(ROOT)}:{node.lineno}: {t}")
    assert found == []
