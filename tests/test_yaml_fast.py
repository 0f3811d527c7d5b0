"""The YAML loader's libyaml fast path gives exactly what the pure-Python reader gives (values on
every YAML file of the real-robot corpus and the fixtures; the error wording of a bad file), and
refuses what the reader refuses (code tags, alias bombs, deep nesting)."""

from pathlib import Path

import pytest
import yaml

from myrabot_desc.build import yaml_load
from myrabot_desc.errors import InputError

ROOT = Path(__file__).resolve().parent
GOOD = sorted(p for p in ROOT.rglob("*.yaml") if "bad" not in p.parts)

pytestmark = pytest.mark.skipif(not yaml.__with_libyaml__, reason="PyYAML without libyaml")


def _both(text):
    out = []
    for loader in (yaml_load.Loader, yaml_load._fast_loader()):
        try:
            out.append(("ok", yaml_load._load(loader(text), text, "f.yaml")))
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
