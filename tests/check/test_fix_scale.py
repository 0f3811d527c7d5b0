"""--fix/--diff on a large model: linear in its size. Placing each value (line and column) counted
the newlines up to it, the planner compared every fix with every finding, and the literals' uses
were found twice; a 20,000-link star's --diff ran for over ten minutes."""

from __future__ import annotations

import random
from pathlib import Path

from helpers import cpu_time
from myrabot_desc.fix.run import fix_model
from myrabot_desc.model.sources import _File

_INERTIAL = ('<inertial><mass value="0.1"/><inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/>'
             '</inertial><collision><geometry><box size="0.02 0.02 0.02"/></geometry></collision>')


def _star(n: int) -> str:
    """n spokes 0.3 m apart around a base, each with a placeholder inertia (I006, an unsafe fix) and
    nothing else to find: no two shapes meet, so the cost is the fixes'."""
    out = ['<?xml version="1.0"?>', f'<robot name="star_{n}">', f'<link name="l0">{_INERTIAL}</link>']
    for i in range(1, n):
        out.append(f'<link name="l{i}">{_INERTIAL}</link>')
        out.append(f'<joint name="j{i}" type="revolute"><parent link="l0"/><child link="l{i}"/>'
                   f'<origin xyz="{0.3 * i:.1f} 0 0.01"/><axis xyz="0 0 1"/>'
                   '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>')
    return "\n".join(out + ["</robot>"]) + "\n"


def test_line_col_is_the_count_of_newlines():
    rng = random.Random(7)
    data = "".join(rng.choice(["a", "é", "\n", "<x/>", "\r\n", "ü\n"]) for _ in range(3000)).encode()
    f = _File("f", None, data)
    for offset in [0, 1, len(data) - 1, len(data)] + [rng.randrange(len(data) + 1) for _ in range(300)]:
        start = data.rfind(b"\n", 0, offset) + 1
        want = (data.count(b"\n", 0, offset) + 1, len(data[start:offset].decode("utf-8", "replace")) + 1)
        assert f.line_col(offset) == want, offset


def _fix_cpu(tmp_path: Path, n: int) -> tuple[float, int]:
    src = tmp_path / f"star{n}.urdf"
    src.write_text(_star(n))
    with cpu_time() as t:
        res = fix_model(src)
    return t.seconds, len(res.unsafe)


def test_diff_of_a_star_grows_linearly(tmp_path):
    """Every link's inertia is fixable (I006): three times the links cost about three times the CPU
    (quadratic would be nine)."""
    _fix_cpu(tmp_path, 50)                     # imports and first-use caches out of the timing
    # the better of two runs each: on two busy cores one run's CPU time can double (shared caches)
    (small, n_small), (large, n_large) = (min(_fix_cpu(tmp_path, n) for _ in range(2)) for n in (600, 1800))
    assert n_small >= 599 and n_large >= 1799
    assert large / small < 5.5, (small, large)
