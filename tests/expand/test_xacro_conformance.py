"""build behaves like the xacro 2.x CLI on the behaviours xacro's own test suite pins (issue 13).

Each case is a small file of our own, built by ``myrabot-desc build`` and by the real xacro CLI
(the pip ``xacro`` library we build on, run as a process, no ROS): stdout must be the same bytes,
and where the case says so, stderr too. The deliberate differences are pinned at the end
(README, "Differences from the xacro CLI").
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from myrabot_desc.commands.main import main

X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def xacro_cli(cwd: Path, *args):
    """The real xacro CLI (xacro.main) in a fresh interpreter."""
    code = "import sys, xacro; sys.argv[0] = 'xacro'; xacro.main()"
    return subprocess.run([sys.executable, "-c", code, *args], cwd=cwd, capture_output=True, text=True,
                          timeout=60)


def ours(cwd: Path, monkeypatch, *args):
    monkeypatch.chdir(cwd)
    return CliRunner().invoke(main, ["build", *args, "-o", "-"], catch_exceptions=False)


def write(folder: Path, files: dict[str, str]) -> None:
    for name, text in files.items():
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_text(text)


# name -> (files, extra args, compare stderr too)
SAME = {
    # any root: SDF, roslaunch (its <arg>/<include> are roslaunch's, not legacy xacro), generic XML
    "sdf_root": ({"in.xacro": f'<sdf version="1.9" {X}><xacro:property name="r" value="0.1"/><model name="m">'
                  '<link name="l"><visual name="v"><geometry><sphere><radius>${r*2}</radius></sphere>'
                  "</geometry></visual></link></model></sdf>"}, [], True),
    "launch_root": ({"in.xacro": f'<launch {X}><arg name="x" default="1"/><include file="a.launch"/>'
                     '<xacro:property name="n" value="3"/><node name="n${n}" pkg="p" type="t"/></launch>'},
                    [], True),
    # a plain <foo> is not X002 outside a robot, even with a macro foo defined next to it
    "plain_element_named_like_a_macro": ({"in.xacro": f"<a {X}><foo>bar</foo></a>",
                                          "defs.xacro": f'<a {X}><xacro:macro name="foo"><x/></xacro:macro></a>'},
                                         [], True),
    "macro_only_file": ({"in.xacro": f'<a {X}><xacro:macro name="m"><x/></xacro:macro></a>'}, [], True),
    # old-xacro rules: an <include> with element children is no include; an <arg> without default no arg
    "include_with_children": ({"in.xacro": '<a><include filename="nada"><tag/></include></a>'}, [], True),
    "roslaunch_arg_in_robot": ({"in.xacro": f'<robot name="r" {X}><xacro:arg name="a" default="1"/>'
                                '<link name="l$(arg a)"/></robot>'}, ["a:=7"], True),
    # namespaced includes: macros and properties under the namespace, inner includes propagate
    "namespaced_include": ({"in.xacro": f'<robot name="r" {X}><xacro:property name="var" value="main"/>'
                            '<xacro:include filename="inc/b.xacro" ns="B"/><xacro:B.m/>'
                            '<link name="${var}_${B.var}_${B.inner.v}"/></robot>',
                            "inc/b.xacro": f'<a {X}><xacro:property name="var" value="2"/>'
                            '<xacro:include filename="c.xacro" ns="inner"/>'
                            '<xacro:macro name="m"><link name="from_b"/><xacro:inner.m/></xacro:macro></a>',
                            "inc/c.xacro": f'<a {X}><xacro:property name="v" value="3"/>'
                            '<xacro:macro name="m"><link name="from_c"/></xacro:macro></a>'}, [], True),
    # property scoping: macro scope, scope="parent", scope="global", a redefinition inside a macro
    "property_scopes": ({"in.xacro": f'<robot name="r" {X}><xacro:property name="p" value="outer"/>'
                         '<xacro:macro name="inner"><xacro:property name="g" value="${2*f}" scope="global"/>'
                         '</xacro:macro>'
                         '<xacro:macro name="m" params="f"><xacro:property name="p" value="in_macro"/>'
                         '<link name="${p}"/><xacro:property name="q" value="${21*f}" scope="parent"/>'
                         "<xacro:inner/></xacro:macro>"
                         '<xacro:m f="2"/><link name="${p}_${q}_${g}"/></robot>'}, [], True),
    "tokenize": ({"in.xacro": f'<robot name="r" {X}><xacro:property name="t" value="${{xacro.tokenize(\'a,b c;d\')}}"/>'
                  '<link name="${t[1]}${len(t)}"/><link name="${xacro.tokenize(\'x y\', sep=\' \')[0]}"/></robot>'},
                 [], True),
    "dotify_yaml": ({"in.xacro": f'<robot name="r" {X}>'
                     '<xacro:property name="s" value="${xacro.dotify(xacro.load_yaml(\'s.yaml\'))}"/>'
                     '<link name="l${s.wheel.radius * 2}"/></robot>',
                     "s.yaml": "wheel:\n  radius: 0.05\n"}, [], True),
    "arg_function": ({"in.xacro": f'<robot name="r" {X}><xacro:arg name="w" default="0.3"/>'
                      "<link name=\"${xacro.arg('w')}\"/></robot>"}, ["w:=0.5"], True),
    "target_namespace": ({"in.xacro": f'<a {X} xacro:targetNamespace="http://example.org"><b/></a>'}, [], True),
    "element_and_attribute": ({"in.xacro": f'<a {X}><xacro:macro name="m" params="t k v"><xacro:element '
                               'xacro:name="${t}"><xacro:attribute name="${k}" value="${v}"/></xacro:element>'
                               '</xacro:macro><xacro:m t="x" k="y" v="z"/></a>'}, [], True),
    # the file's own output: message, warning and error (with location), print_location
    "message_functions": ({"in.xacro": f"<robot name=\"r\" {X}>${{xacro.message('hello', 2, 3.5)}}"
                           "${xacro.warning('careful')}${xacro.error('bad', print_location=False)}"
                           '<link name="l"/></robot>'}, [], True),
    "print_location_in_macro_and_include": ({"in.xacro": f'<robot name="r" {X}><xacro:macro name="scope">'
                                             '<xacro:include filename="loc.xacro"/></xacro:macro>'
                                             '<xacro:scope/><link name="l"/></robot>',
                                             "loc.xacro": f"<a {X}>${{xacro.print_location()}}</a>"}, [], True),
    # xacro's own warnings stay X007 findings; the URDF is the same
    "redefined_global": ({"in.xacro": f'<robot name="r" {X}><xacro:property name="pi" value="3"/>'
                          '<link name="l${pi}"/></robot>'}, [], False),
}


@pytest.mark.parametrize("case", sorted(SAME))
def test_same_output_as_xacro(case, tmp_path, monkeypatch):
    files, args, same_stderr = SAME[case]
    write(tmp_path, files)
    ref = xacro_cli(tmp_path, "./in.xacro", *args)
    assert ref.returncode == 0, ref.stderr
    r = ours(tmp_path, monkeypatch, "./in.xacro", *args)
    assert r.exit_code == 0, r.stderr
    assert r.stdout == ref.stdout           # byte-identical, banner ("from ./in.xacro") included
    if same_stderr:
        assert r.stderr == ref.stderr


def test_message_text_reaches_stderr(tmp_path, monkeypatch):
    """The texts themselves (the comparison above would also pass if both printed nothing)."""
    write(tmp_path, SAME["message_functions"][0])
    err = ours(tmp_path, monkeypatch, "./in.xacro").stderr
    assert err == "hello 2 3.5\nwarning: careful\nwhen processing file: ./in.xacro\nerror: bad\n"
    write(tmp_path, SAME["print_location_in_macro_and_include"][0])
    err = ours(tmp_path, monkeypatch, "./in.xacro").stderr
    assert err == "when instantiating macro: scope (./in.xacro)\nin file: ./loc.xacro\nincluded from: ./in.xacro\n"


def test_scopes_and_namespaces_values(tmp_path, monkeypatch):
    write(tmp_path, SAME["property_scopes"][0])
    out = ours(tmp_path, monkeypatch, "./in.xacro").stdout
    assert '<link name="in_macro"/>' in out and '<link name="outer_42_4"/>' in out
    write(tmp_path, SAME["namespaced_include"][0])
    out = ours(tmp_path, monkeypatch, "./in.xacro").stdout
    assert [ln.strip() for ln in out.splitlines() if "<link" in ln] == [
        '<link name="from_b"/>', '<link name="from_c"/>', '<link name="main_2_3"/>']


# name -> (files, args, what both say)
BOTH_FAIL = {
    # xacro 2.x (and 1.x) require default= on xacro:arg, even when the arg is given
    "arg_without_default": ({"in.xacro": f'<robot name="r" {X}><xacro:arg name="a"/><link name="l"/></robot>'},
                            ["a:=1"], "xacro:arg: missing attribute 'default'"),
    "arg_used_unset": ({"in.xacro": f'<robot name="r" {X}><link name="$(arg a)"/></robot>'}, [], "a"),
    "fatal": ({"in.xacro": f"<robot name=\"r\" {X}>${{xacro.fatal('stop', 'here')}}<link name=\"l\"/></robot>"},
              [], "stop here"),
    "undefined_macro": ({"in.xacro": f'<a {X}><xacro:nothing/></a>'}, [], "unknown macro name: xacro:nothing"),
}


@pytest.mark.parametrize("case", sorted(BOTH_FAIL))
def test_same_errors_as_xacro(case, tmp_path, monkeypatch):
    files, args, text = BOTH_FAIL[case]
    write(tmp_path, files)
    ref = xacro_cli(tmp_path, "./in.xacro", *args)
    assert ref.returncode == 2 and text in ref.stderr
    r = ours(tmp_path, monkeypatch, "./in.xacro", *args)
    assert r.exit_code == 2 and r.stdout == ""
    first = r.stderr.splitlines()[0]
    assert first.startswith("in.xacro:1: error: ") and text in first


# ------------------------------------------------------------------ what only robots get
def test_x002_still_applies_to_robots(tmp_path, monkeypatch):
    write(tmp_path, {"in.xacro": f'<robot name="r" {X}><link name="l"/><foo parent="l"/></robot>',
                     "defs.xacro": f'<a {X}><xacro:macro name="foo" params="parent"><x/></xacro:macro></a>'})
    r = ours(tmp_path, monkeypatch, "./in.xacro")
    assert r.exit_code == 1 and "X002 <foo> looks like a call of macro 'foo'" in r.stderr


def test_legacy_upgrade_only_for_robots(tmp_path, monkeypatch):
    old = '<macro name="m"><link name="l"/></macro><m/>'
    write(tmp_path, {"in.xacro": f'<robot name="r">{old}</robot>', "in2.xacro": f"<a>{old}</a>"})
    r = ours(tmp_path, monkeypatch, "./in.xacro")
    assert r.exit_code == 0 and '<link name="l"/>' in r.stdout and "X001" in r.stderr
    r = ours(tmp_path, monkeypatch, "./in2.xacro")
    assert r.exit_code == 0 and "<macro" in r.stdout and "X001" not in r.stderr
    r = ours(tmp_path, monkeypatch, "./in2.xacro", "--legacy", "on")
    assert r.exit_code == 0 and "<macro" not in r.stdout and '<link name="l"/>' in r.stdout


@pytest.mark.parametrize("command", [["check"], ["info"], ["convert", "--to", "sdf"], ["sim", "drive"]])
def test_robot_commands_say_what_a_non_robot_is(command, tmp_path, monkeypatch):
    write(tmp_path, SAME["sdf_root"][0])
    monkeypatch.chdir(tmp_path)
    extra = ["-o", str(tmp_path / "o.sdf")] if command[0] == "convert" else []
    r = CliRunner().invoke(main, [*command, "in.xacro", *extra], catch_exceptions=False)
    assert r.exit_code == 2
    assert "in.xacro:1: error: an SDF model (root <sdf>, not <robot>)" in r.output
    assert not (tmp_path / "o.sdf").exists()


# ------------------------------------------------------------------ deliberate differences
def test_refusals_are_kept(tmp_path, monkeypatch):
    """Python escapes stay refused (X005); xacro refuses these two as well, with another message."""
    for expr in ["__import__('os').getcwd()", "''.__class__.__base__.__subclasses__()"]:
        write(tmp_path, {"in.xacro": f'<robot name="r" {X}><link name="${{{expr}}}"/></robot>'})
        assert xacro_cli(tmp_path, "./in.xacro").returncode == 2
        r = ours(tmp_path, monkeypatch, "./in.xacro")
        assert r.exit_code == 2 and "in.xacro:1: error: X005 refused expression" in r.stderr


def test_errors_are_one_line_with_the_macro_trail(tmp_path, monkeypatch):
    """xacro prints a multi-line message and 'when instantiating macro:' lines; we print one
    file:line line and the macro calls with their lines."""
    write(tmp_path, {"in.xacro": f'<robot name="r" {X}>\n<xacro:property name="a" value="${{b}}"/>\n'
                     '<xacro:property name="b" value="${2*a}"/>\n<xacro:macro name="m">\n<link name="${a}"/>\n'
                     "</xacro:macro>\n<xacro:m/>\n</robot>\n"})
    ref = xacro_cli(tmp_path, "./in.xacro")
    assert ref.returncode == 2 and "circular variable definition: a -> b -> a\nConsider" in ref.stderr
    assert "when instantiating macro: m" in ref.stderr
    r = ours(tmp_path, monkeypatch, "./in.xacro")
    lines = r.stderr.splitlines()
    assert r.exit_code == 2 and lines[0].startswith("in.xacro:5: error: circular variable definition: a -> b -> a "
                                                    "Consider disabling lazy evaluation")
    assert lines[1:] == ["  in macro 'm' called at in.xacro:7"]
