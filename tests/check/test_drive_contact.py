"""G019 reads a mecanum wheel's contact in Gazebo classic's form too (mu1, mu2, fdir1 in a
<gazebo reference> block); a value sdformat cannot read is one T010 at its element, not a crash."""

from __future__ import annotations

import json

from helpers import invoke

# fdir1 in the collision's frame (the cylinder turned about x: its z is the root's -y)
CORNERS = {"fl": (0.2, 0.2, "1 0 1"), "fr": (0.2, -0.2, "1 0 -1"), "rl": (-0.2, 0.2, "1 0 -1"),
           "rr": (-0.2, -0.2, "1 0 1")}
INERTIA = '<inertia ixx="{0}" iyy="{0}" izz="{0}" ixy="0" ixz="0" iyz="0"/>'


def _base(tmp_path, mu1="1", mu2="0", swap=False):
    parts = [f'<robot name="m"><link name="base_link"><inertial><mass value="5"/>{INERTIA.format(0.1)}</inertial>'
             '</link>']
    for name, (x, y, fdir) in CORNERS.items():
        if swap:
            fdir = "1 0 -1" if fdir == "1 0 1" else "1 0 1"
        parts.append(
            f'<link name="{name}_wheel"><inertial><mass value="0.5"/>{INERTIA.format(0.001)}</inertial><collision>'
            '<origin rpy="1.5708 0 0"/><geometry><cylinder radius="0.05" length="0.03"/></geometry></collision>'
            f'</link><joint name="{name}_wheel_joint" type="continuous"><parent link="base_link"/>'
            f'<child link="{name}_wheel"/><origin xyz="{x} {y} 0.05"/><axis xyz="0 1 0"/>'
            '<limit effort="5" velocity="10"/></joint>'
            f'<gazebo reference="{name}_wheel"><mu1>{mu1}</mu1><mu2>{mu2}</mu2><fdir1>{fdir}</fdir1></gazebo>')
    parts.append('<gazebo><plugin name="m" filename="libgz-sim-mecanum-drive-system.so">'
                 + "".join(f"<{c}_joint>{n}_wheel_joint</{c}_joint>" for c, n in
                           (("front_left", "fl"), ("front_right", "fr"), ("back_left", "rl"), ("back_right", "rr")))
                 + "<wheel_separation>0.4</wheel_separation><wheelbase>0.4</wheelbase>"
                 "<wheel_radius>0.05</wheel_radius></plugin></gazebo></robot>")
    f = tmp_path / "mecanum.urdf"
    f.write_text("".join(parts))
    return f


def _codes(f) -> dict:
    res = invoke("check", str(f), "--format", "json")
    assert res.exit_code in (0, 1), res.output[-1500:]
    return {d["code"]: d for d in json.loads(res.stdout)["files"][0]["diagnostics"]}


def test_classic_diagonal_contact_rolls_sideways(tmp_path):
    assert "G019" not in _codes(_base(tmp_path))


def test_classic_plain_or_swapped_wheels_are_found(tmp_path):
    g = _codes(_base(tmp_path, mu2="1"))["G019"]
    assert "a sideways command drives sideways at 0×" in g["message"]
    g = _codes(_base(tmp_path, swap=True))["G019"]
    assert "sideways at -1×" in g["message"]


def test_an_unreadable_friction_is_one_error_at_its_line_not_a_crash(tmp_path):
    """`<mu1>abc</mu1>`: sdformat's converter aborts on it (`ign sdf -p`: std::invalid_argument from
    stod), so it is T010 at the element, once per block; G019 judges the rest with the default."""
    f = _base(tmp_path, mu1="abc")
    res = invoke("check", str(f), "--format", "json")
    assert res.exit_code == 1, res.output[-1500:]
    diags = json.loads(res.stdout)["files"][0]["diagnostics"]
    t010 = [d for d in diags if d["code"] == "T010"]
    assert len(t010) == 4 and all(d["message"] == "<mu1>abc</mu1>: not a number (sdformat's URDF converter aborts "
                                  "on it)" for d in t010)
    assert not [d for d in diags if d["code"] in ("G017", "G019")]
    res = invoke("convert", str(f), "--to", "sdf", "-o", str(tmp_path / "out.sdf"))
    assert res.exit_code == 2 and not (tmp_path / "out.sdf").exists()


def test_a_short_fdir1_is_found(tmp_path):
    f = _base(tmp_path)
    f.write_text(f.read_text().replace("<fdir1>1 0 1</fdir1>", "<fdir1>1 0</fdir1>", 1))
    (d,) = [d for d in _diags(f) if d["code"] == "T010"]
    assert d["message"].startswith("<fdir1>1 0</fdir1>: ")


def _diags(f) -> list:
    res = invoke("check", str(f), "--format", "json")
    assert res.exit_code in (0, 1), res.output[-1500:]
    return json.loads(res.stdout)["files"][0]["diagnostics"]
