"""The YAML loader's libyaml fast path gives exactly what the pure-Python reader gives (values on
every YAML file of the real-robot corpus and the fixtures; the error wording of a bad file), and
refuses what the reader refuses (code tags, alias bombs, deep nesting)."""


import pytest
import yaml

from helpers import TESTS
from myrabot_desc.expand import yaml_load
from myrabot_desc.errors import InputError

ROOT = TESTS
GOOD = sorted(p for p in ROOT.rglob("*.yaml") if "bad" not in p.parts)

pytestmark = pytest.mark.skipif(not yaml.__with_libyaml__, reason="PyYAML without libyaml")


def _both(text):
    out = []
    for loader in (yaml_load._safe_loader(), yaml_load._fast_loader()):
        try:
            out.append(("ok", yaml_load._load(loader, text, "f.yaml")))
        except InputError as e:
            out.append(("error", str(e)))
    return out


def test_fast_path_is_used():
    assert yaml_load._fast_loader() is not None


@pytest.mark.parametrize("path", GOOD, ids=lambda p: str(p.relative_to(ROOT)))
def test_same_values_on_real_files(path):
    slow, fast = _both(path.read_text(encoding="utf-8"))
    assert slow[0] == "ok"
    assert fast == slow


def test_many_real_files_compared():
    assert len(GOOD) >= 10     # the corpus's UR, franka, kortex, husky... parameter files


def test_error_wording_is_the_pure_python_readers():
    text = "a: [1, 2\nb: : 3\n"
    slow, fast = _both(text)
    assert slow[0] == fast[0] == "error" and slow[1] != fast[1]     # libyaml words it its own way...
    with pytest.raises(InputError) as exc:
        yaml_load.loads(text, "f.yaml")
    assert str(exc.value) == slow[1]                                # ...loads() gives the reader's words


@pytest.mark.parametrize("text, message", [
    ("x: !!python/object/apply:os.system ['true']\n", "is not allowed"),
    ("[" * 100_000, "nests too deeply"),
    ("- " * 100_000 + "x\n", "nests too deeply"),
    ("a: &a [1, 2, 3, 4, 5, 6, 7, 8, 9, 10]\n" + "".join(
        f"{c}: &{c} [{', '.join(['*' + p] * 10)}]\n" for p, c in zip("abcdef", "bcdefg")), "alias bomb"),
])
def test_refusals_are_kept(text, message):
    with pytest.raises(InputError, match=message):
        yaml_load.loads(text, "f.yaml")


def test_unit_tags():
    assert yaml_load.loads("x: !degrees 90\ny: !millimeters 5\n", "f.yaml") == pytest.approx(
        {"x": 1.5707963267948966, "y": 0.005})


_DEFERRED_PROBE = r"""
import re, sys
compile_ = re.compile
from myrabot_desc.expand import driver
driver._lazy_yaml()                      # what a build does before xacro imports PyYAML
from myrabot_desc.expand import yaml_load   # imports no PyYAML: the first document parsed loads it
yaml_load.loads("a: 1\n", "f.yaml")
import yaml.reader
p = yaml.reader.Reader.NON_PRINTABLE
print(type(p).__name__, re.compile is compile_)
try:
    yaml_load.loads("a: 1\nb: \x07\n", "f.yaml")
except Exception as e:
    print(type(e).__name__, str(e).replace("\n", " | "))
try:
    yaml.load("b: \x07", Loader=yaml.SafeLoader)     # the pure-Python reader, which uses the pattern
except yaml.YAMLError as e:
    print(type(e).__name__, str(e).replace("\n", " | "))
print(type(p).__name__, [bool(p.search(s)) for s in ("ok", "\x07", "\ufffe", "\U0001f600", "\x85")])
"""


def test_pyyaml_reader_pattern_compiled_only_when_used():
    """The build imports PyYAML with its pure-Python reader's character class left uncompiled
    (~5 ms); that reader still refuses the same characters, with the same words, when it runs."""
    import subprocess
    import sys

    out = subprocess.run([sys.executable, "-c", _DEFERRED_PROBE], capture_output=True, text=True, check=True)
    lines = out.stdout.splitlines()
    assert lines[0] == "_DeferredPattern True"         # deferred (a new PyYAML pattern fails here) and re restored
    plain = yaml.reader.Reader.NON_PRINTABLE           # this process: PyYAML imported the usual way
    assert lines[1].startswith("InputError f.yaml:2") and "#x0007" in lines[1]
    try:
        yaml.load("b: \x07", Loader=yaml.SafeLoader)
    except yaml.YAMLError as e:
        assert lines[2] == f"{type(e).__name__} " + str(e).replace("\n", " | ")
    expected = [bool(plain.search(s)) for s in ("ok", "\x07", "\ufffe", "\U0001f600", "\x85")]
    assert lines[3] == f"_DeferredPattern {expected}" and expected == [False, True, True, False, False]
