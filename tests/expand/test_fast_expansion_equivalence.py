"""The fast expansion (expand/fast.py, hooked by expand/driver.py) gives exactly plain xacro's output.

`build` replaces xacro 2.1.1's quadratic node replacement, its eval_all, minidom's
clone and the pretty-printer with faster equivalents (issue 8). Here the text of
`build_file` is compared byte for byte with the unmodified xacro library's
(`xacro.process_file` + `toprettyxml(indent='  ')`, `$(find)` mapped to our
resolver) on a generated corpus of several shapes and sizes and on every xacro
file the tests use: tests/**/*.xacro, the bundled model's xacro/*.xacro and
example-robot-data's hector files. Where plain xacro fails, `build` must fail too.
Files we upgrade from the Electric dialect (X001) are compared with --legacy off,
which is plain xacro's reading of them.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from helpers import TESTS
from myrabot_desc.expand.driver import build_file
from myrabot_desc.expand.packages import data_root
from myrabot_desc.errors import InputError

HERE = TESTS
ROOT = HERE.parent
FIX = HERE / "fixtures"
ERD = Path(sys.prefix) / "lib" / f"python{sys.version_info.major}.{sys.version_info.minor}" / "site-packages" / \
    "cmeel.prefix" / "share" / "example-robot-data"

sys.path.insert(0, str(ROOT / "bench"))
from gen_pr2like import write_pr2like  # noqa: E402
from gen_shapes import SHAPES  # noqa: E402


def plain_xacro(path: Path, package_paths=()) -> str:
    """What the unmodified xacro library produces, with $(find) mapped to our package resolver."""
    import xacro.substitution_args as sa

    import xacro
    from myrabot_desc.expand.packages import PackageResolver

    resolver = PackageResolver(package_paths=package_paths, input_file=path)

    def find(pkg):
        p = resolver.find(pkg)
        if p is None:
            raise sa.SubstitutionException(f"package not found: {pkg}")
        return str(p)

    saved = sa._eval_find, sa._eval_dict.get("find")
    sa._eval_find = sa._eval_dict["find"] = find
    try:
        xacro.all_includes = []
        xacro.substitution_args_context["arg"] = {}
        return xacro.process_file(str(path)).toprettyxml(indent="  ")
    finally:
        sa._eval_find = saved[0]
        sa._eval_dict["find"] = saved[1]


def assert_same_as_xacro(path: Path, package_paths=()) -> str:
    """Build ``path`` both ways; assert identical text (or that both fail). Returns the text."""
    try:
        expected = plain_xacro(path, package_paths)
    except Exception as exc:  # plain xacro rejects the file: so must we, reading it as xacro does
        with pytest.raises(InputError):
            build_file(path, package_paths=package_paths, legacy="off")
        return f"both fail: {type(exc).__name__}"
    res = build_file(path, package_paths=package_paths)
    if any(d.code == "X001" for d in res.diagnostics):  # we upgraded Electric syntax; xacro copies it verbatim
        res = build_file(path, package_paths=package_paths, legacy="off")
    assert res.text == expected, f"{path}: output differs from plain xacro"
    return res.text


# ------------------------------------------------------------------ generated corpus
CORPUS = [("flat", n) for n in (1, 7, 250, 2000)] + [("deep", n) for n in (1, 10, 60)] + \
    [("blocks", n) for n in (1, 15, 200)] + [("conditionals", n) for n in (1, 12, 150)] + \
    [("properties", n) for n in (1, 25, 200)] + [("comments", n) for n in (1, 9, 200)] + \
    [("elements", n) for n in (1, 6, 100)] + [("random", seed) for seed in range(40)]


@pytest.mark.parametrize("shape,n", CORPUS, ids=[f"{s}-{n}" for s, n in CORPUS])
def test_generated_corpus_is_byte_identical(tmp_path, shape, n):
    f = tmp_path / f"{shape}{n}.urdf.xacro"
    f.write_text(SHAPES[shape](n))
    text = assert_same_as_xacro(f)
    assert not text.startswith("both fail"), text  # every generated file is valid xacro
    assert text.count("<") > 5


def test_pr2_sized_synthetic_package_is_byte_identical_and_pr2_sized(tmp_path):
    top = write_pr2like(tmp_path)
    text = assert_same_as_xacro(top)
    from lxml import etree

    root = etree.fromstring(text.encode())
    assert len(root.findall("link")) == 99
    assert len(root.findall(".//joint")) == 135        # 98 joints + 37 transmission references
    assert len(root.findall("transmission")) == 37
    assert 140_000 < len(text.encode()) < 155_000


# ------------------------------------------------------------------ every xacro the tests use
def _test_xacros():
    # tests/bad/ holds hostile inputs (entity and power bombs, /dev/zero includes, XXE, endless
    # recursion) that `build` refuses by design and plain xacro must not even be run on here.
    # tests/corpus/ (real robots) is compared with the real xacro CLI in tests/realrobots/test_corpus.py, robot by
    # robot with its args, environment and packages.
    return sorted(p for p in HERE.rglob("*.xacro") if ".pytest_cache" not in p.parts
                  and p.relative_to(HERE).parts[0] not in ("bad", "corpus"))


def _package_paths(path: Path):
    legacy = FIX / "legacy" / ("old" if "old" in path.relative_to(HERE).parts else "new")
    return [legacy, FIX / "seed_myrabot", data_root().parent]


@pytest.mark.parametrize("path", _test_xacros(), ids=lambda p: str(p.relative_to(HERE)))
def test_every_test_xacro_is_byte_identical(path):
    assert_same_as_xacro(path, _package_paths(path))


def test_the_test_xacro_list_is_not_empty():
    files = _test_xacros()
    assert len(files) >= 20
    assert any(p.name == "myrabot.urdf.xacro" for p in files)


BUNDLED = sorted((data_root() / "xacro").glob("*.xacro"))


@pytest.mark.parametrize("path", BUNDLED, ids=lambda p: p.name)
def test_bundled_model_xacros_are_byte_identical(path):
    text = assert_same_as_xacro(path, [data_root().parent])
    if path.name == "myrabot.urdf.xacro":
        assert text.count("<link ") > 20


HECTOR = sorted((ERD / "robots" / "hector_description" / "robots").glob("*.xacro"))


@pytest.mark.parametrize("path", HECTOR, ids=lambda p: p.name)
def test_example_robot_data_hector_xacros_are_byte_identical(path):
    assert_same_as_xacro(path)


def test_hector_through_find_is_byte_identical(tmp_path):
    top = tmp_path / "quad.urdf.xacro"
    top.write_text('<?xml version="1.0"?>\n<robot name="quad" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                   '  <xacro:include filename="$(find example-robot-data)/robots/hector_description/robots/'
                   'quadrotor_base.urdf.xacro"/>\n  <xacro:quadrotor_base_macro/>\n</robot>\n')
    text = assert_same_as_xacro(top)
    assert 'name="base_link"' in text


# ------------------------------------------------------------------ safe_eval's vetting by shape
SHAPE_CASES = ["0.1 + 17 * 0.001", "-3.5e-2 * 2", "(1 + 2) / 4.0", "sin(0.5) * 2", "pi * 0.25", "1 if x else 2",
               "x * 0.5", "2 ** 10", "9**9**9", "1(2)", "(1).__class__", "09", "1_000 + 1", "0x10 * 2", "1j * 2",
               "[1, 2, 3][1]", "x.real + 1", "abs(-1.5)", "factorial(3)", "1 << 3", "7 % 3",
               "-(2 * 3) + 1", "2 * 3 * 4 * 5", "0.5 - 0.25 // 2 + 10 % 3 * 2", "'ab' * 3", "(1 + 2) * x",
               "1 / 0 + 1", "+".join(["1"] * 60), "*".join(["99"] * 40) + " % 7"]


@pytest.mark.parametrize("expr", SHAPE_CASES)
def test_vetting_by_shape_agrees_with_the_full_vetting(expr):
    """The shape shortcut (numbers -> 1) gives the same value, or the same refusal, as the full path."""
    from myrabot_desc.expand import safe_eval as S

    def outcome(use_shapes):
        refusals = []

        def refuse(e, reason):
            refusals.append(reason)
            raise S.RefusedExpression(reason)

        S._PREPARED.clear()                     # the compiled expressions are shared by a process's builds
        saved = S._prepare_by_shape
        if not use_shapes:
            S._prepare_by_shape = lambda e, shapes: None
        try:
            se = S.make_safe_eval(None, refuse)
            import xacro

            symbols = xacro.Table(xacro._global_symbols)
            symbols["x"] = 3
            try:
                return ("value", se(expr, symbols))
            except S.RefusedExpression:
                return ("refused", refusals[-1])
            except Exception as exc:
                return ("error", type(exc).__name__)
        finally:
            S._prepare_by_shape = saved

    assert outcome(True) == outcome(False)


@pytest.mark.parametrize("expr,bounded", [("0.1 + 17 * 0.001", False), ("-(2 * 3) + 1.5", False),
                                          ("2 * 3 * 4 * 5 % 7", False), ("x + 1", True), ("'a' * 3", True),
                                          ("2 ** 3 * 2", True), ("(2 << 3) + 1", True), ("[1] * 3", True),
                                          ("+".join(["2"] * 30) + " * 3", True)])
def test_arithmetic_of_number_literals_needs_no_run_time_bound(expr, bounded):
    """A generated file's ${0.1 + 17 * 0.001}: a number made of number literals cannot grow a sequence,
    so it is left to Python and its shape is vetted once; anything with a name, a string, a list, ** or
    <<, or nested deeper than a few levels, is bounded at run time as before."""
    import ast

    from myrabot_desc.expand.safe_eval import _needs_bound, check_expression

    assert any(_needs_bound(n) for n in ast.walk(check_expression(expr))) == bounded


def test_build_cli_writes_what_the_xacro_cli_writes(tmp_path):
    """The whole command (GC off, frozen exit, atomic write) against the stock `xacro` script."""
    import subprocess

    bindir = Path(sys.executable).parent
    if not (bindir / "xacro").exists():
        pytest.skip("the xacro console script is not installed next to this Python")
    f = tmp_path / "flat.urdf.xacro"
    f.write_text(SHAPES["flat"](300))
    ours, theirs = tmp_path / "ours.urdf", tmp_path / "theirs.urdf"
    subprocess.run([str(bindir / "myrabot-desc"), "build", str(f), "-o", str(ours)], check=True, capture_output=True)
    subprocess.run([str(bindir / "xacro"), str(f), "-o", str(theirs)], check=True, capture_output=True)
    assert ours.read_bytes() == theirs.read_bytes()
