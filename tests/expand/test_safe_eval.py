"""The ${} sandbox (issue 13: safe AND complete) and the isolation of builds (issue 17).

Every expression form real xacro files use builds by default, byte-identical with the xacro CLI;
what reaches code, files or shared state is refused with X005 at file:line; YAML tags never run
code, whatever a previous build did to PyYAML; one build cannot change the next.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
from helpers import cpu_time
from click.testing import CliRunner

from myrabot_desc.expand.driver import build_file
from myrabot_desc.commands.main import main
from myrabot_desc.errors import InputError

HEAD = '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
XACRO = Path(sys.executable).parent / "xacro"


def _model(tmp_path, body: str, name="m.urdf.xacro") -> Path:
    f = tmp_path / name
    f.write_text(HEAD + body + "\n</robot>\n")
    return f


def _xacro_cli(f: Path) -> str:
    return subprocess.run([str(XACRO), str(f)], capture_output=True, text=True, check=True,
                          cwd=f.parent).stdout


# Forms real robots use (issue 13's list), each as a one-link model. (xacro's lexer ends ${ at the
# first '}', so dict and set displays and comprehensions cannot appear in ${} at all.)
FORMS = {
    "str_split": "${'a b c'.split()[1]}",
    "str_upper": "${prefix.upper()}",
    "str_methods": "${prefix.replace('arm', 'leg').strip('_').startswith('left')}_${'-'.join(['a', 'b'])}",
    "str_more": "${'x_y'.endswith('y')}_${' a '.lstrip()}_${'abc'.index('b')}_${'aab'.count('a')}_${'AB'.lower()}",
    "dict_call": "${dict(a=1, b=2)['b']}",
    "dict_methods": "${sorted(dict(a=1, b=2).keys())}_${dict(a=1).get('z', 7)}_${list(dict(a=1).items())}",
    "map": "${list(map(lambda x: x * 2, [1, 2, 3]))}",
    "range": "${list(python.range(1, 7, 2))}",
    "list_comp": "${[i * i for i in python.range(4) if i % 2 == 0]}",
    "dict_from_pairs": "${dict([(k, v) for k, v in python.zip(['a', 'b'], [1, 2])])['b']}",
    "set_from_genexp": "${sorted(python.set(c for c in 'abca'))}",
    "genexp": "${python.sum(x for x in python.range(5))}_${python.any(x > 3 for x in [1, 5])}",
    "nested_comp": "${[[j for j in python.range(i)] for i in python.range(3)]}",
    "lambda_sorted": "${sorted(['bb', 'a', 'ccc'], key=lambda s: len(s))}",
    "conditional": "${'yes' if 2 > 1 else 'no'}_${1 if 'b' in 'abc' else 0}",
    "slicing": "${'abcdef'[1:4]}_${[1, 2, 3, 4][::-1]}_${(1, 2, 3)[-1]}",
    "builtins": "${len([1, 2])}_${min(3, 1)}_${max([1, 5])}_${python.abs(-2)}_${round(2.567, 1)}_${int('7')}_"
                "${float('1.5')}_${str(3)}_${bool(0)}_${list((1, 2))}",
    "python_ns": "${python.tuple([1])}_${python.all([1, 1])}_${list(python.enumerate(['a']))}",
    "zip_enumerate": "${list(python.zip([1, 2], 'ab'))}_${[i for i, _ in python.enumerate('xy')]}",
    "filter": "${list(python.filter(lambda v: v > 1, [1, 2, 3]))}",
    "math": "${math.pi / 2}_${radians(90)}_${math.sqrt(16)}_${sin(0)}_${math.floor(2.7)}",
    "string_ops": "${prefix + '_link'}_${'%s_%d' % ('j', 3)}_${'ab' * 3}",
    "tokenize": "${xacro.tokenize('a,b;c')}_${xacro.tokenize('a b', sep=' ')}",
    "dotify": "${xacro.dotify(dict(a=dict(b=3))).a['b']}",
    "starred": "${max(*[1, 9, 3])}_${dict(**dict(a=1))}",
    "own_list_mutators": "${[levels.pop(0).strip(), levels][1]}_${python.sorted(levels)}_${[l.append(3), l][1]}",
}


@pytest.mark.skipif(not XACRO.exists(), reason="the xacro CLI is not installed in this environment")
@pytest.mark.parametrize("form", sorted(FORMS))
def test_every_form_real_files_use_builds_like_xacro(tmp_path, form):
    expr = FORMS[form]
    f = _model(tmp_path, '<xacro:property name="prefix" value="left_arm_"/>\n'
                         '<xacro:property name="levels" value="${\'a, b,c\'.split(\',\')}"/>\n'
                         '<xacro:property name="l" value="${[1, 2]}"/>\n'
                         f'<link name="{expr.replace("<", "&lt;").replace(chr(34), "&quot;")}"/>')
    ours = build_file(f).text
    assert ours == _xacro_cli(f), form


def test_yaml_unit_tags_use_our_arithmetic(tmp_path):
    (tmp_path / "p.yaml").write_text("a: !degrees 90\nb: !radians pi/4\nc: !millimeters 2*25.4\nd: [1, 2]\n")
    f = _model(tmp_path, "<xacro:property name=\"y\" value=\"${xacro.load_yaml('p.yaml')}\"/>\n"
                         '<link name="${y.a}_${y.b}_${y.c}_${y.d[1]}"/>')
    text = build_file(f).text
    assert '<link name="1.5707963267948966_0.7853981633974483_0.0508_2"/>' in text
    if XACRO.exists():
        assert text == _xacro_cli(f)


def test_yaml_tags_never_run_code_even_after_xacro_registered_its_own(tmp_path):
    """xacro.load_yaml puts !degrees on PyYAML's shared SafeLoader with an unsandboxed evaluator;
    a layout read afterwards in the same process must not run its tag (it ran /bin/sh)."""
    import xacro
    import yaml

    from myrabot_desc.sim.scene import load_layout

    (tmp_path / "p.yaml").write_text("a: !degrees 90\n")
    f = _model(tmp_path, "<link name=\"${xacro.load_yaml('p.yaml').a}\"/>")
    build_file(f)
    assert "!degrees" not in yaml.SafeLoader.__dict__.get("yaml_constructors", {})
    xacro.init_stacks(str(f))
    xacro.load_yaml(str(tmp_path / "p.yaml"))       # xacro's own: registers on the shared loader
    build_file(f)                                    # our build takes it off again
    assert "!degrees" not in yaml.SafeLoader.__dict__.get("yaml_constructors", {})
    marker = tmp_path / "PWNED"
    layout = tmp_path / "evil.yaml"
    layout.write_text("objects:\n  - model: x\n    file: !degrees __import__('os').system('touch "
                      f"{marker}')\n    pose: {{x: 0}}\n")
    with pytest.raises(InputError) as e:
        load_layout(layout)
    assert "evil.yaml:3" in str(e.value) and "only numbers and arithmetic" in str(e.value)
    assert not marker.exists()
    r = CliRunner().invoke(main, ["sim", "escoja", "--layout", str(layout), "--duration", "0.1"])
    assert r.exit_code == 2 and "evil.yaml:3: error:" in r.output and not marker.exists()


def test_yaml_python_tags_and_alias_bombs_are_refused(tmp_path):
    from myrabot_desc.expand import yaml_load

    with pytest.raises(InputError, match="not allowed"):
        yaml_load.loads("!!python/object/apply:os.system ['true']\n", "x.yaml")
    bomb = "a: &a [x,x,x,x,x,x,x,x,x,x]\n" + "".join(
        f"{chr(98 + i)}: &{chr(98 + i)} [{', '.join(['*' + chr(97 + i)] * 10)}]\n" for i in range(9))
    with pytest.raises(InputError, match="alias bomb"):
        yaml_load.loads(bomb, "x.yaml")
    with pytest.raises(InputError, match="YAML nests too deeply|not valid YAML"):
        yaml_load.loads("[" * 100_000, "x.yaml")
    assert yaml_load.arith("-pi/2") == pytest.approx(-1.5707963)
    for bad in ("__import__('os')", "2**10**10", "x", "(1).real", "[1]"):
        with pytest.raises(ValueError):
            yaml_load.arith(bad)


def test_one_model_cannot_change_the_next(tmp_path):
    """Each build has its own namespace: a hostile first file leaves nothing for the second."""
    attacks = ["${python.sorted(['pi', 'e'], key=python.pop)}", "${xacro.clear()}", "${xacro.root}",
               "${python.update(dict(pi=1))}", "${math.pop('pi')}"]
    good = _model(tmp_path, '<link name="${pi}_${radians(180)}_${python.len([1])}"/>', "good.urdf.xacro")
    expected = build_file(good).text
    for i, attack in enumerate(attacks):
        bad = _model(tmp_path, f'<link name="{attack}"/>', f"bad{i}.urdf.xacro")
        with pytest.raises(InputError):
            build_file(bad)
        assert build_file(good).text == expected
    import xacro

    assert "pi" in xacro._global_symbols and "pop" not in xacro._global_symbols["python"]
    # two builds never share a namespace object
    seen = []
    from myrabot_desc.expand import safe_eval

    orig = safe_eval.fresh_namespace

    def spy(load_yaml):
        g = orig(load_yaml)
        seen.append(g)
        return g

    safe_eval.fresh_namespace = spy
    try:
        build_file(good)
        build_file(good)
    finally:
        safe_eval.fresh_namespace = orig
    assert seen[0] is not seen[1] and seen[0]["python"] is not seen[1]["python"]


REFUSED = {
    "format": "${'{0}'.format(1)}",
    "format_map": "${'{a}'.format_map(dict(a=1))}",
    "dunder_name": "${__import__('os')}",
    "dunder_attr": "${(1).__class__}",
    "func_attr": "${xacro.load_yaml.__globals__}",
    "gen_frame": "${(x for x in []).gi_frame}",
    "mutating_namespace": "${python.clear()}",
    "doubling_list": "${[L.extend(L) for L in [[0]] for _ in python.range(40)]}",
    "doubling_dict": "${[d.update(d) or d.update(dict(python.zip(python.range(len(d), 2 * len(d)), d))) "
                     "for d in [dict(a=1)] for _ in python.range(40)]}",
    "open": "${open('/etc/passwd')}",
    "getattr": "${getattr(1, 'real')}",
    "lambda_dunder": "${(lambda: 1).__code__}",
    "bytes_repeat": "${b'a' * 400000000}",
    "percent_key": "${'%(a)01000000000d' % dict(a=1)}",
    "bytes_percent": "${b'%01000000000d' % 1}",
    "concat_loop": "${len([s + s for s in ['x' * 900000 for _ in python.range(100)]])}",
    "copy_loop": "${len([list(python.range(100000)) for _ in python.range(1000)])}",
    "join_bomb": "${'ab'.join(['x' * 100000 for _ in python.range(100)])}",
    "replace_bomb": "${('a' * 10000).replace('', 'bbbbbbbbbb' * 100)}",
    "ljust_bomb": "${'x'.ljust(10**9)}",
    "loop_bomb": "${[0 for a in python.range(10**6) for b in python.range(10**6)]}",
    "lambda_recursion": "${(lambda f: f(f))(lambda f: f(f))}",
    "walrus": "${(y := 3)}",
    "huge_range": "${python.sum(python.range(10**12))}",
}


@pytest.mark.parametrize("case", sorted(REFUSED))
def test_what_reaches_code_or_grows_without_bound_is_refused(tmp_path, case):
    f = _model(tmp_path, f'<link name="{REFUSED[case].replace(chr(34), "&quot;")}"/>')
    with cpu_time() as t, pytest.raises(InputError) as e:
        build_file(f)
    assert t.seconds < 60      # a bound in CPU time, not a benchmark (the machine may be shared)
    msg = str(e.value)
    assert "m.urdf.xacro:2: error:" in msg, msg
    if case not in ("dunder_name", "mutating_namespace"):
        assert "X005 refused expression" in msg, msg
