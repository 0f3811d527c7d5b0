"""Generate large URDF trees for the scale benchmarks: a chain (each link the child of the last)
or a star (every link a child of the base). Usage: gen_tree.py chain|star N OUT."""

from __future__ import annotations

import sys


def tree_urdf(kind: str, n: int) -> str:
    out = ['<?xml version="1.0"?>', f'<robot name="{kind}_{n}">']
    inertial = ('<inertial><mass value="0.1"/><inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/>'
                '</inertial>')
    out.append(f'<link name="l0">{inertial}<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>'
               '</link>')
    for i in range(1, n):
        parent = f"l{i - 1}" if kind == "chain" else "l0"
        out.append(f'<link name="l{i}">{inertial}<collision><geometry><box size="0.02 0.02 0.02"/></geometry>'
                   '</collision></link>')
        out.append(f'<joint name="j{i}" type="revolute"><parent link="{parent}"/><child link="l{i}"/>'
                   f'<origin xyz="{0.01 if kind == "chain" else 0.3 * (i % 100)} 0 0.01"/><axis xyz="0 0 1"/>'
                   '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>')
    out.append("</robot>")
    return "\n".join(out) + "\n"


if __name__ == "__main__":
    kind, n, dest = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    with open(dest, "w") as f:
        f.write(tree_urdf(kind, n))
