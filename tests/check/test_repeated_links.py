"""Links that repeat their values (a macro's copies, a generated tree) are measured once per
distinct set of value objects (checks/inertia_geometry.py): their findings must be exactly those of
the same links written so that nothing is shared."""

from __future__ import annotations

from myrabot_desc.checks import CheckOptions, check_robot
from myrabot_desc.checks.context import Context
from myrabot_desc.checks.inertia_geometry import hull_points
from myrabot_desc.model.loader import load_robot

CODES = ("I004", "I005", "I006", "I007", "I008", "I010")

# (box size, collision origin, inertial origin, mass, ixx=iyy=izz): each written as the first
# spelling in the shared robot and with one of the others in the robot that shares nothing
KINDS = [
    ('<box size="0.02 0.02 0.02"/>', "", "", "0.1", "1e-4"),
    ('<box size="0.02 0.02 0.02"/>', '<origin xyz="0.01 0 0"/>', '<origin xyz="0.5 0 0"/>', "0.1", "1e-4"),
    ('<box size="0.02 0.02 0.02"/>', "", '<origin rpy="0 0 0.5"/>', "0.1", "1e-4"),
    ('<cylinder radius="0.05" length="0.2"/>', '<origin xyz="0 0 0.1" rpy="0.3 0 0"/>', "", "2", "1"),
]
# tensors I004 and I005 judge: (ixx iyy izz, ixy): a rod-like triangle violation, a negative moment
TENSORS = [("0.002 0 0", "0"), ("9e-08 3.5e-08 1e-08", "6.3e-08")]


def _respell(text: str, k: int) -> str:
    """``text`` with each number in its attributes written another way (one of three, by ``k``)."""
    import re

    def number(m):
        v = m.group(0)
        return ["0" + v if v[0] != "-" else v, "+" + v, f"{float(v):e}"][k % 3]
    return re.sub(r'="([^"]*)"', lambda m: '="' + re.sub(r"[-+]?[\d.]+(?:e[-+]?\d+)?", number, m.group(1)) + '"', text)


def _urdf(tmp_path, name: str, shared: bool, copies: int = 3):
    out = ['<?xml version="1.0"?>', '<robot name="r">',
           '<link name="base"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" '
           'izz="0.01"/></inertial></link>']
    n = 0
    for size, corigin, iorigin, mass, moment in KINDS:
        for c in range(copies):
            body = (f'<inertial>{iorigin}<mass value="{mass}"/><inertia ixx="{moment}" ixy="0" ixz="0" '
                    f'iyy="{moment}" iyz="0" izz="{moment}"/></inertial><collision>{corigin}<geometry>{size}'
                    '</geometry></collision>')
            if not shared:
                body = _respell(body, n)
            out.append(f'<link name="l{n}">{body}</link>')
            out.append(f'<joint name="j{n}" type="revolute"><parent link="base"/><child link="l{n}"/>'
                       '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="100" velocity="1"/></joint>')
            n += 1
    for moments, ixy in TENSORS:
        for c in range(3):
            ixx, iyy, izz = moments.split()
            body = (f'<inertial><mass value="0.001"/><inertia ixx="{ixx}" ixy="{ixy}" ixz="0" iyy="{iyy}" iyz="0" '
                    f'izz="{izz}"/></inertial>')
            if not shared:
                body = _respell(body, n)
            out.append(f'<link name="l{n}">{body}</link>')
            out.append(f'<joint name="j{n}" type="fixed"><parent link="base"/><child link="l{n}"/></joint>')
            n += 1
    out.append("</robot>")
    p = tmp_path / name
    p.write_text("\n".join(out) + "\n")
    return load_robot(p)


def _findings(r, **opts):
    diags, ctx = check_robot(r, CheckOptions(**opts), select=CODES)
    return [(d.code, d.severity, d.message, d.loc.line, d.data) for d in diags], ctx.suggestions


def test_repeated_links_give_the_findings_of_links_that_share_nothing(tmp_path):
    shared = _urdf(tmp_path, "shared.urdf", True)
    alone = _urdf(tmp_path, "alone.urdf", False)
    # the loader shares the objects of equal texts: that is what the rules key on
    l0, l1 = shared.links["l0"], shared.links["l1"]
    assert l0.inertial.ixx is l1.inertial.ixx and l0.collisions[0].geometry.size is l1.collisions[0].geometry.size
    assert alone.links["l0"].inertial.ixx is not alone.links["l1"].inertial.ixx
    for opts in ({}, {"inertia": True, "suggest": True}):
        got, suggestions = _findings(shared, **opts)
        want, want_suggestions = _findings(alone, **opts)
        assert got == want
        assert suggestions == want_suggestions
        assert {c for c, *_ in got} == {"I004", "I005", "I006", "I007", "I010"}
        # every copy is reported, not only the first of each kind
        assert sum(1 for c, *_ in got if c == "I006") == len(KINDS) * 3


def test_repeated_shapes_share_their_points(tmp_path):
    r = _urdf(tmp_path, "shared.urdf", True)
    pts = hull_points(Context(r))
    assert pts["l0"] is pts["l1"] and not pts["l0"].flags.writeable
    assert pts["l0"] is not pts["l3"]             # another collision origin: its own points
    alone = hull_points(Context(_urdf(tmp_path, "alone.urdf", False)))
    for name, p in pts.items():
        assert (p is None) == (alone[name] is None)
        if p is not None:
            assert p.tolist() == alone[name].tolist()
