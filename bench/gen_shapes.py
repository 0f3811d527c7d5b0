"""Generated xacro files of several shapes, for the byte-identity tests and the benchmarks.

    python bench/gen_shapes.py SHAPE N > file.xacro      # SHAPE: see SHAPES

Each shape stresses one part of xacro's expansion: long sibling lists (flat),
recursion and deep element nesting (deep), single and multi blocks passed
through nested macros (blocks), xacro:if/unless with comments around them
(conditionals), property scopes and lazy evaluation (properties), comments in
front of macro calls and eval-comments (comments), xacro:element/attribute,
xacro:call and namespace lifting (elements), and seeded random mixes of all of
them (random). Everything here stays inside what both plain xacro and our
safe evaluator accept.
"""

from __future__ import annotations

import random
import sys

HEAD = '<?xml version="1.0"?>\n<robot name="{name}" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
TAIL = "</robot>\n"


def flat(n: int) -> str:
    sys.path.insert(0, __file__.rsplit("/", 1)[0])
    from gen_flat import flat_xacro

    return flat_xacro(n)


def deep(n: int) -> str:
    """A recursive macro chain of depth n (one link+joint per level) and n-deep nested elements."""
    return HEAD.format(name=f"deep{n}") + f"""  <xacro:macro name="chain" params="i parent">
    <link name="c${{i}}"/>
    <joint name="cj${{i}}" type="fixed"><parent link="${{parent}}"/><child link="c${{i}}"/>
      <origin xyz="0 0 ${{0.01*i}}"/></joint>
    <xacro:if value="${{i > 1}}">
      <xacro:chain i="${{i-1}}" parent="c${{i}}"/>
    </xacro:if>
  </xacro:macro>
  <xacro:macro name="nest" params="d">
    <group level="${{d}}">
      <!-- level ${{d}} -->
      <xacro:unless value="${{d == 0}}">
        <xacro:nest d="${{d-1}}"/>
      </xacro:unless>
      text ${{d*2}}
    </group>
  </xacro:macro>
  <link name="root"/>
  <xacro:chain i="{n}" parent="root"/>
  <gazebo>
    <xacro:nest d="{min(n, 60)}"/>
  </gazebo>
""" + TAIL


def blocks(n: int) -> str:
    calls = "\n".join(f"""  <xacro:wrap name="b{i}" parent="{'base' if i == 0 else f'b{i - 1}'}">
    <origin xyz="{i * 0.1} 0 0" rpy="0 0 ${{{i}*0.01}}"/>
    <shapes>
      <visual><geometry><box size="0.1 0.1 ${{0.1+{i}*0.001}}"/></geometry></visual>
      <collision><geometry><sphere radius="0.05"/></geometry></collision>
    </shapes>
  </xacro:wrap>""" for i in range(n))
    return HEAD.format(name=f"blocks{n}") + f"""  <xacro:macro name="inner" params="name parent *origin **shapes">
    <link name="${{name}}">
      <xacro:insert_block name="shapes"/>
    </link>
    <joint name="${{name}}_j" type="fixed">
      <xacro:insert_block name="origin"/>
      <parent link="${{parent}}"/><child link="${{name}}"/>
    </joint>
  </xacro:macro>
  <!-- the same origin block inserted twice, blocks passed on into a nested macro -->
  <xacro:macro name="wrap" params="name parent *origin *shapes">
    <xacro:inner name="${{name}}" parent="${{parent}}">
      <xacro:insert_block name="origin"/>
      <xacro:insert_block name="shapes"/>
    </xacro:inner>
    <frame_copy of="${{name}}"><xacro:insert_block name="origin"/></frame_copy>
  </xacro:macro>
  <link name="base"/>
{calls}
""" + TAIL


def conditionals(n: int) -> str:
    parts = []
    for i in range(n):
        parts.append(f"""  <!-- case {i} -->
  <xacro:if value="${{{i} % 3 == 0}}">
    <!-- inside if {i} -->
    <link name="if{i}"/>
    <xacro:unless value="${{{i} % 2 == 0}}">
      <link name="unless{i}"/>
    </xacro:unless>
  </xacro:if>
  <xacro:unless value="${{{i} % 3 == 0}}">
    <xacro:part i="{i}" big="${{{i} > {n // 2}}}"/>
  </xacro:unless>
""")
    return HEAD.format(name=f"cond{n}") + """  <xacro:macro name="part" params="i big:=false">
    <xacro:if value="${big}"><link name="big${i}"/></xacro:if>
    <xacro:if value="${not big}"><link name="small${i}"/></xacro:if>
    <xacro:if value="true"><!-- always --></xacro:if>
    <xacro:unless value="1"><link name="never${i}"/></xacro:unless>
  </xacro:macro>
""" + "".join(parts) + TAIL


def properties(n: int) -> str:
    lines = []
    for i in range(n):
        lines.append(f"""  <xacro:property name="p{i}" value="${{p{i - 1 if i else 'base'} * 1.01 + {i}}}"/>
  <xacro:property name="s{i}" value="name_{i}"/>
  <xacro:scoped k="{i}" v="${{p{i}}}"/>
  <link name="${{s{i}}}"><inertial><mass value="${{p{i}}}"/></inertial></link>""")
    return HEAD.format(name=f"props{n}") + """  <xacro:property name="lazy" value="${later * 2}"/>
  <xacro:property name="later" value="21"/>
  <xacro:property name="pbase" value="1.5"/>
  <xacro:property name="lst" value="${[1, 2, 3]}"/>
  <xacro:property name="blk">
    <origin xyz="1 2 3" rpy="0 0 ${pi/2}"/>
  </xacro:property>
  <xacro:macro name="scoped" params="k v">
    <xacro:property name="local" value="${v + k}"/>
    <xacro:property name="up_${k}" value="${local}" scope="parent"/>
    <xacro:property name="g_${k}" value="${k*k}" scope="global"/>
    <frame name="f${k}" value="${local}" up="${lst[k % 3]}" lazy="${lazy}">
      <xacro:insert_block name="blk"/>
    </frame>
  </xacro:macro>
""" + "\n".join(lines) + f"""
  <summary last="${{up_{max(n - 1, 0)}}}" g="${{g_{max(n - 1, 0)}}}" pi="${{pi}}" e="${{e}}" s="${{sin(0.5)}}"/>
""" + TAIL


def comments(n: int) -> str:
    body = []
    for i in range(n):
        gap = "\n" if i % 4 == 0 else ""
        body.append(f"""  <!-- comment a {i} -->
  <!-- comment b {i} -->{gap}
  <xacro:thing i="{i}"/>
  <!-- trailing {i} -->
  <link name="plain{i}"/>
""")
    return ("<?xml version=\"1.0\"?>\n<!-- before the root -->\n"
            + HEAD.split("\n", 1)[1].format(name=f"comments{n}")
            + """  <xacro:property name="who" value="eval"/>
  <!-- xacro:eval-comments -->
  <!-- evaluated: ${who} -->
  <!-- xacro:eval-comments:off -->
  <!-- not evaluated: ${who} -->
  <xacro:macro name="thing" params="i">
    <!-- inside the macro ${i} -->
    <link name="t${i}"/>
  </xacro:macro>
""" + "".join(body) + TAIL + "<!-- after the root -->\n")


def elements(n: int) -> str:
    calls = "\n".join(f"""  <xacro:call macro="${{'mk_' + kinds[{i} % 2]}}" i="{i}"/>
  <xacro:element xacro:name="${{'link' if {i} % 2 else 'frame'}}" name="e{i}">
    <xacro:attribute name="extra" value="v${{{i}*3}}"/>
  </xacro:element>""" for i in range(n))
    return HEAD.format(name=f"elements{n}") + f"""  <xacro:property name="kinds" value="${{['a', 'b']}}"/>
  <xacro:macro name="mk_a" params="i" xmlns:foo="http://example.com/foo">
    <foo:thing id="${{i}}"/>
  </xacro:macro>
  <xacro:macro name="mk_b" params="i">
    <link name="b${{i}}">
      <xacro:attribute name="type" value="b"/>
    </link>
  </xacro:macro>
{calls}
""" + TAIL


def random_mix(seed: int) -> str:
    """A seeded random mix: macros calling earlier macros, blocks, conditions, comments, text."""
    rnd = random.Random(seed)
    macros = []
    out = [HEAD.format(name=f"random{seed}")]
    out.append('  <xacro:property name="k" value="%s"/>\n' % rnd.choice(["0.5", "2", "${3/4}"]))

    def stmt(depth, names, in_macro):
        r = rnd.random()
        ind = "  " * (depth + 1)
        if r < 0.15:
            return f"{ind}<!-- c{rnd.randint(0, 99)} -->\n"
        if r < 0.25:
            return f"{ind}<item v=\"${{k*{rnd.randint(1, 9)}}}\">t{rnd.randint(0, 9)}</item>\n"
        if r < 0.35 and depth < 4:
            inner = "".join(stmt(depth + 1, names, in_macro) for _ in range(rnd.randint(0, 3)))
            tag = rnd.choice(["xacro:if", "xacro:unless"])
            return f"{ind}<{tag} value=\"${{{rnd.randint(0, 3)} > 1}}\">\n{inner}{ind}</{tag}>\n"
        if r < 0.55 and names:
            m = rnd.choice(names)
            block = f"{ind}  <origin xyz=\"{rnd.randint(0, 5)} 0 0\"/>\n"
            pre = f"{ind}<!-- call {m} -->\n" if rnd.random() < 0.5 else ""
            return f"{pre}{ind}<xacro:{m} n=\"${{k+{rnd.randint(0, 9)}}}\">\n{block}{ind}</xacro:{m}>\n"
        if r < 0.65 and in_macro:
            return f"{ind}<placed><xacro:insert_block name=\"origin\"/></placed>\n"
        if r < 0.75 and depth < 4:
            inner = "".join(stmt(depth + 1, names, in_macro) for _ in range(rnd.randint(0, 3)))
            return f"{ind}<group id=\"${{n}}\" a=\"{rnd.randint(0, 9)}\">\n{inner}{ind}</group>\n" if in_macro \
                else f"{ind}<group a=\"{rnd.randint(0, 9)}\">\n{inner}{ind}</group>\n"
        return f"{ind}<link name=\"l{rnd.randint(0, 10**6)}\"/>\n"

    for i in range(rnd.randint(2, 6)):
        name = f"m{i}"
        body = "".join(stmt(1, list(macros), True) for _ in range(rnd.randint(1, 6)))
        out.append(f"  <xacro:macro name=\"{name}\" params=\"n *origin\">\n{body}  </xacro:macro>\n")
        macros.append(name)
    for _ in range(rnd.randint(5, 40)):
        out.append(stmt(0, macros, False))
    out.append(TAIL)
    return "".join(out)


SHAPES = {"flat": flat, "deep": deep, "blocks": blocks, "conditionals": conditionals, "properties": properties,
          "comments": comments, "elements": elements, "random": random_mix}


if __name__ == "__main__":
    sys.stdout.write(SHAPES[sys.argv[1]](int(sys.argv[2]) if len(sys.argv) > 2 else 10))
