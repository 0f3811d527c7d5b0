"""One drive model: `check`, `convert` and `sim drive` report the same wheels, separation and radius.

Every robot here goes through the three commands (the CLI, as a user runs them) and through
model/drive.py; the wheel joints, the separation and the radius must agree everywhere. The
robots: the bundled MYRAbot (Electric Roomba controller), the wander_bot seed (ROS 1 plugin),
the wheeled example-robot-data robots (ros_control / ros2_control velocity wheels), the
real-robot corpus when it is there, and one small rover per plugin dialect.
"""

from __future__ import annotations

import json
import sysconfig
from pathlib import Path

import pytest
from click.testing import CliRunner
from lxml import etree

from helpers import FIXTURES, CORPUS
from myrabot_desc.commands.main import main
from myrabot_desc.model import drive as D
from myrabot_desc.model.loader import load_robot

FIX = FIXTURES
ERD = Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix" / "share" / "example-robot-data" / "robots"

ROVER = """<robot name="rover">
  <link name="base_link"><inertial><mass value="5"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.4 0.3 0.1"/></geometry></collision></link>
  {wheels}
  {extra}
</robot>"""
WHEEL = """<link name="{n}_link"><inertial><mass value="0.5"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin rpy="1.5708 0 0"/><geometry><cylinder radius="0.05" length="0.02"/></geometry></collision></link>
  <joint name="{n}" type="continuous"><parent link="base_link"/><child link="{n}_link"/><origin xyz="{x} {y} 0"/><axis xyz="0 1 0"/></joint>"""
TWO = "".join(WHEEL.format(n=n, x=0, y=y) for n, y in (("jl", 0.17), ("jr", -0.17)))
FOUR = "".join(WHEEL.format(n=n, x=x, y=y) for n, x, y in
               (("fl", 0.15, 0.2), ("rl", -0.15, 0.2), ("fr", 0.15, -0.2), ("rr", -0.15, -0.2)))

DIALECTS = {
    "ros1": (TWO, """<gazebo><plugin name="dd" filename="libgazebo_ros_diff_drive.so"><legacyMode>false</legacyMode>
        <leftJoint>jl</leftJoint><rightJoint>jr</rightJoint><wheelSeparation>0.34</wheelSeparation>
        <wheelDiameter>0.1</wheelDiameter><wheelAcceleration>1</wheelAcceleration></plugin></gazebo>"""),
    "ros2": (TWO, """<gazebo><plugin name="dd" filename="libgazebo_ros_diff_drive.so"><left_joint>jl</left_joint>
        <right_joint>jr</right_joint><wheel_separation>0.34</wheel_separation><wheel_diameter>0.1</wheel_diameter>
        </plugin></gazebo>"""),
    "ros2-two-pairs": (FOUR, """<gazebo><plugin name="dd" filename="libgazebo_ros_diff_drive.so">
        <num_wheel_pairs>2</num_wheel_pairs><left_joint>fl</left_joint><right_joint>fr</right_joint>
        <left_joint>rl</left_joint><right_joint>rr</right_joint><wheel_separation>0.4</wheel_separation>
        <wheel_separation>0.4</wheel_separation><wheel_diameter>0.1</wheel_diameter><wheel_diameter>0.1</wheel_diameter>
        </plugin></gazebo>"""),
    "gz": (TWO, """<gazebo><plugin filename="gz-sim-diff-drive-system" name="gz::sim::systems::DiffDrive">
        <left_joint>jl</left_joint><right_joint>jr</right_joint><wheel_separation>0.34</wheel_separation>
        <wheel_radius>0.05</wheel_radius></plugin></gazebo>"""),
    "kobuki": (TWO, """<gazebo><plugin name="kobuki_controller" filename="libgazebo_ros_kobuki.so">
        <publish_tf>1</publish_tf><left_wheel_joint_name>jl</left_wheel_joint_name>
        <right_wheel_joint_name>jr</right_wheel_joint_name><wheel_separation>.34</wheel_separation>
        <wheel_diameter>0.1</wheel_diameter><torque>1.0</torque><velocity_command_timeout>0.6</velocity_command_timeout>
        </plugin></gazebo>"""),
    "skid": (FOUR, """<gazebo><plugin name="skid" filename="libgazebo_ros_skid_steer_drive.so">
        <leftFrontJoint>fl</leftFrontJoint><rightFrontJoint>fr</rightFrontJoint><leftRearJoint>rl</leftRearJoint>
        <rightRearJoint>rr</rightRearJoint><wheelSeparation>0.4</wheelSeparation><wheelDiameter>0.1</wheelDiameter>
        <torque>20</torque></plugin></gazebo>"""),
    "ros_control": (FOUR, "".join(f"""<transmission name="{n}_trans"><type>transmission_interface/SimpleTransmission</type>
        <joint name="{n}"><hardwareInterface>{'hardware_interface/' if n[0] == 'f' else ''}VelocityJointInterface</hardwareInterface></joint>
        <actuator name="{n}_motor"><mechanicalReduction>1</mechanicalReduction></actuator></transmission>"""
                                  for n in ("fl", "fr", "rl", "rr"))),
    "ros2_control": (TWO, """<ros2_control name="base" type="system"><hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="jl"><command_interface name="velocity"/><state_interface name="velocity"/></joint>
        <joint name="jr"><command_interface name="velocity"/><state_interface name="position"/></joint>
        </ros2_control>"""),
}


def _dialect(tmp_path, name):
    wheels, extra = DIALECTS[name]
    f = tmp_path / f"{name}.urdf"
    f.write_text(ROVER.format(wheels=wheels, extra=extra))
    return [str(f)]


def _robots():
    out = [pytest.param([], id="bundled"),
           pytest.param([str(FIX / "wander_bot/urdf/robot.xacro"), "-p", f"wander_bot={FIX / 'wander_bot'}"],
                        id="wander_bot")]
    for rel in ("tiago_description/robots/tiago.urdf", "tiago_description/robots/tiago_dual.urdf",
                "tiago_pro_description/robots/tiago_pro.urdf"):
        out.append(pytest.param([str(ERD / rel)], id=rel.rsplit("/", 1)[-1]))
    out += [pytest.param(name, id=name) for name in DIALECTS]
    out += [pytest.param(args, id=f"corpus-{rid}") for rid, args in _corpus_robots()]
    return out




def _corpus_robots():
    """The real-robot corpus's wheeled robots with a diff or skid-steer drive (its robots.yaml says which)."""
    index = CORPUS / "robots.yaml"
    if not index.is_file():
        return []
    import yaml

    out = []
    for r in yaml.safe_load(index.read_text())["robots"]:
        drive = r.get("drive") or {}
        if not drive.get("wheels") or r.get("env"):
            continue
        args = [str(CORPUS / r["top"]), "--package-path", str(CORPUS / r.get("package_path", "."))]
        args += (r.get("args") or "").split()
        if r.get("legacy"):
            args += ["--legacy", "on"]
        out.append((r["id"], args))
    return out


def _args(tmp_path, robot):
    return _dialect(tmp_path, robot) if isinstance(robot, str) else robot


def _load(args):
    if not args:
        return load_robot()
    opts, mappings, rest = {}, {}, list(args[1:])
    while rest:
        a = rest.pop(0)
        if a == "-p":
            k, v = rest.pop(0).split("=", 1)
            opts.setdefault("packages", {})[k] = v
        elif a == "--package-path":
            opts.setdefault("package_paths", []).append(rest.pop(0))
        elif a == "--legacy":
            opts["legacy"] = rest.pop(0)
        else:
            k, v = a.split(":=", 1)
            mappings[k] = v
    return load_robot(args[0], mappings=mappings or None, **opts)


def invoke(*args):
    return CliRunner().invoke(main, [str(a) for a in args], catch_exceptions=False)


@pytest.mark.parametrize("robot", _robots())
def test_check_convert_and_sim_see_the_same_drive(tmp_path, robot):
    args = _args(tmp_path, robot)
    model = _load(args)
    d = D.main_drive(model)
    assert d is not None, "every robot here has a declared drive"
    g = D.measure(model, d)
    assert g.left and g.right and g.separation > 0 and g.radius > 0

    # check: its G014 line is the drive model's drive
    r = invoke("check", "--format", "json", *args)
    assert r.exit_code in (0, 1), r.output[-2000:]
    diags = json.loads(r.stdout)["files"][0]["diagnostics"]
    summary = [x["data"] for x in diags if x["code"] == "G014"]
    assert summary, [x["message"] for x in diags if x["code"].startswith("G")]
    s = summary[0]
    assert (tuple(s["left"]), tuple(s["right"])) == (d.left, d.right)
    assert s["separation"] == pytest.approx(g.separation, abs=1e-9)
    assert s["radius"] == pytest.approx(g.radius, abs=1e-9)

    # convert: the gz DiffDrive system drives those joints with those numbers
    out = tmp_path / "robot.sdf"
    r = invoke("convert", "-q", "--allow-errors", "-o", out, *args)   # (wander_bot has check errors)
    assert r.exit_code == 0, r.output
    root = etree.parse(str(out)).getroot()
    dd = root.findall("model/plugin[@filename='gz-sim-diff-drive-system']")
    base = D.base(model)
    if base.kind in ("differential", "skid_steer"):
        assert len(dd) == 1
        assert tuple(e.text for e in dd[0].findall("left_joint")) == d.left
        assert tuple(e.text for e in dd[0].findall("right_joint")) == d.right
        assert float(dd[0].findtext("wheel_separation")) == pytest.approx(g.separation, abs=1e-8)
        assert float(dd[0].findtext("wheel_radius")) == pytest.approx(g.radius, abs=1e-8)
    else:
        # TIAGo Pro: mecanum wheels with mu 0 under a planar-move plugin: the body is moved, no DiffDrive
        assert dd == [] and root.findall("model/plugin[@filename='gz-sim-velocity-control-system']")
    # never a position controller on a wheel or any velocity joint
    pos = {e.findtext("joint_name") for e in root.findall("model/plugin")
           if e.get("filename") == "gz-sim-joint-position-controller-system"}
    assert not pos & (set(d.joints) | set(D.velocity_joints(model)[0]))

    if base.kind not in ("differential", "skid_steer"):
        r = invoke("sim", "drive", "--json", "--twist", "0.2,0.1,0.5,1", *args)   # the kind's own model
        assert json.loads(r.stdout)["info"]["drive kind"] == base.kind
        return
    # sim drive: the same wheels (each side's first wheel stands for the side) move the robot
    csv = tmp_path / "drive.csv"
    r = invoke("sim", "drive", "--json", "--wheels", "urdf", "--twist", "0.2,0.5,1", "--csv", csv, *args)
    assert r.exit_code in (0, 1), r.output[-2000:]
    info = json.loads(r.stdout)["info"]
    assert info["URDF wheel separation"] == pytest.approx(g.separation, abs=1e-6)
    assert info["URDF wheel radius"] == pytest.approx(g.radius, abs=1e-6)
    head = csv.read_text().splitlines()[0].split(",")          # wheel angle columns: <joint>_rad
    assert head[-2:] == [f"{d.left[0]}_rad", f"{d.right[0]}_rad"]
    # and its plugin-geometry run, when the plugin gives numbers, uses the plugin's
    if d.source == "plugin" and d.separation is not None and d.radius is not None:
        r = invoke("sim", "drive", "--json", "--twist", "0.2,0,1", "--twist", "0,0.5,1", *args)
        doc = json.loads(r.stdout)
        info = doc["info"]
        assert info["plugin wheel separation"] == pytest.approx(d.separation)
        assert info["plugin wheel radius"] == pytest.approx(d.radius)
        # the ratios it measures (straight, then turning on the spot) are the drive model's:
        # r_urdf / r_plugin, times s_plugin / s_urdf turning (times -1 in legacy mode)
        kv = g.radius / d.radius
        kw = kv * d.separation / g.separation * D.turn_sign(d)
        ratios = {c["name"]: c["value"] for c in doc["checks"]}
        assert ratios["speed ratio"] == pytest.approx(kv, rel=1e-4)
        assert ratios["turn-rate ratio"] == pytest.approx(kw, rel=1e-4)


def test_dialect_numbers_and_units(tmp_path):
    """Each dialect's keys, as the plugins read them; units as they use them."""
    got = {}
    for name in DIALECTS:
        r = load_robot(_dialect(tmp_path, name)[0])
        d = D.main_drive(r)
        got[name] = (d.source, d.left, d.right, d.separation, d.radius, d.skid)
    assert got["ros1"] == ("plugin", ("jl",), ("jr",), 0.34, 0.05, False)
    assert got["ros2-two-pairs"] == ("plugin", ("fl", "rl"), ("fr", "rr"), 0.4, 0.05, True)
    assert got["gz"] == ("plugin", ("jl",), ("jr",), 0.34, 0.05, False)
    assert got["kobuki"] == ("plugin", ("jl",), ("jr",), 0.34, 0.05, False)
    assert got["skid"] == ("plugin", ("fl", "rl"), ("fr", "rr"), 0.4, 0.05, True)
    assert got["ros_control"] == ("ros_control", ("fl", "rl"), ("fr", "rr"), None, None, True)
    assert got["ros2_control"] == ("ros2_control", ("jl",), ("jr",), None, None, False)
    ros1 = D.main_drive(load_robot(_dialect(tmp_path, "ros1")[0]))
    assert (ros1.accel, ros1.spec.accel_unit, ros1.legacy, ros1.legacy_explicit) == (1.0, "wheel m/s^2", False, True)
    # measured: 0.34 m between the wheel centres, radius 0.05 (a cylinder about the axle)
    g = D.measure(load_robot(_dialect(tmp_path, "skid")[0]), D.main_drive(load_robot(_dialect(tmp_path, "skid")[0])))
    assert (round(g.separation, 12), g.radius) == (0.4, 0.05)


def test_wheel_acceleration_is_not_scaled_by_the_radius(tmp_path):
    """ROS 1 wheelAcceleration ramps the wheel surface (m/s^2): gz gets 1 m/s^2, not 1 x 0.05."""
    out = tmp_path / "r.sdf"
    assert invoke("convert", "-q", "-o", out, *_dialect(tmp_path, "ros1")).exit_code == 0
    dd = etree.parse(str(out)).getroot().find("model/plugin[@filename='gz-sim-diff-drive-system']")
    assert float(dd.findtext("max_linear_acceleration")) == pytest.approx(1.0)
    assert float(dd.findtext("max_angular_acceleration")) == pytest.approx(2 * 1.0 / 0.34)


LEGACY = """<gazebo><plugin name="dd" filename="libgazebo_ros_diff_drive.so">
        <leftJoint>jl</leftJoint><rightJoint>jr</rightJoint><wheelSeparation>0.34</wheelSeparation>
        <wheelDiameter>0.1</wheelDiameter></plugin></gazebo>"""


def test_legacy_mode_default_turns_the_wrong_way_in_check_convert_and_sim(tmp_path):
    f = tmp_path / "legacy.urdf"
    f.write_text(ROVER.format(wheels=TWO, extra=LEGACY))
    d = D.main_drive(load_robot(str(f)))
    assert (d.legacy, d.legacy_explicit) == (True, False)
    r = invoke("check", "--format", "json", f)
    g13 = [x for x in json.loads(r.stdout)["files"][0]["diagnostics"] if x["code"] == "G013"]
    assert len(g13) == 1 and g13[0]["severity"] == "warning"
    assert "defaults to true" in g13[0]["message"] and "turn ratio -1" in g13[0]["message"]
    assert g13[0]["data"]["turn_ratio"] == -1.0
    # sim drives it as the plugin does: the turn comes out reversed, the speed right
    r = invoke("sim", "drive", "--json", "--twist", "0,0.5,2", "--twist", "0.2,0,2", f)
    doc = json.loads(r.stdout)
    ratios = {c["name"]: c["value"] for c in doc["checks"]}
    assert ratios["turn-rate ratio"] == pytest.approx(-1.0, abs=1e-6)
    assert ratios["speed ratio"] == pytest.approx(1.0, abs=1e-6)
    # convert writes a DiffDrive that turns the REP-103 way, and says why it differs
    out = tmp_path / "legacy.sdf"
    assert invoke("convert", "-q", "-o", out, f).exit_code == 0
    assert "legacy mode" in out.read_text()
    # with <legacyMode>false</legacyMode> nothing is reported
    f.write_text(ROVER.format(wheels=TWO, extra=LEGACY.replace("<leftJoint>", "<legacyMode>false</legacyMode><leftJoint>")))
    r = invoke("check", "--format", "json", f)
    assert not [x for x in json.loads(r.stdout)["files"][0]["diagnostics"] if x["code"] == "G013"]


def test_sim_drive_with_named_wheels(tmp_path):
    """Wheels nobody declares and whose names do not say "wheel" (l_drive / r_drive): named with
    --wheels or --left/--right-wheel. (l_wheel_joint / r_wheel_joint are found by where they sit.)"""
    f = tmp_path / "bare.urdf"
    f.write_text(ROVER.format(wheels="".join(WHEEL.format(n=n, x=0, y=y) for n, y in
                                             (("l_drive", 0.15), ("r_drive", -0.15))), extra=""))
    r = invoke("sim", "drive", f)
    assert r.exit_code == 2 and "--wheels LEFT,RIGHT" in r.output and "Traceback" not in r.output
    for names in (["--wheels", "l_drive,r_drive"],
                  ["--left-wheel", "l_drive", "--right-wheel", "r_drive"]):
        r = invoke("sim", "drive", "--json", "--twist", "0.2,0.5,2", *names, f)
        assert r.exit_code == 0, r.output
        info = json.loads(r.stdout)["info"]
        assert info["URDF wheel separation"] == pytest.approx(0.3) and info["URDF wheel radius"] == pytest.approx(0.05)
    r = invoke("sim", "drive", "--wheels", "l_drive,nope", f)
    assert r.exit_code == 2 and "'nope' is not in the model" in r.output
    r = invoke("sim", "drive", "--wheels", "a,b,c", f)
    assert r.exit_code == 2 and "LEFT,RIGHT" in r.output
    f.write_text(f.read_text().replace("l_drive", "l_wheel_joint").replace("r_drive", "r_wheel_joint"))
    r = invoke("sim", "drive", "--json", "--twist", "0.2,0.5,2", f)
    assert r.exit_code == 0, r.output
    assert json.loads(r.stdout)["info"]["URDF wheel separation"] == pytest.approx(0.3)


def test_one_imu_sensor_per_imu(tmp_path):
    """A link's imu sensor and a model-level gazebo_ros_imu plugin on that link are one sensor, noise kept."""
    f = tmp_path / "imu.urdf"
    f.write_text(ROVER.format(wheels=TWO + """<link name="imu_link"/>
      <joint name="imu_joint" type="fixed"><parent link="base_link"/><child link="imu_link"/></joint>""", extra="""
      <gazebo reference="imu_link"><sensor type="imu" name="imu"><always_on>true</always_on></sensor></gazebo>
      <gazebo><plugin name="imu_plugin" filename="libgazebo_ros_imu.so"><bodyName>imu_link</bodyName>
        <frameName>imu_link</frameName><topicName>imu</topicName><gaussianNoise>0.01</gaussianNoise>
        <updateRate>200</updateRate></plugin></gazebo>"""))
    out = tmp_path / "imu.sdf"
    assert invoke("convert", "-q", "-o", out, f).exit_code == 0
    imus = [s for s in etree.parse(str(out)).getroot().iter("sensor") if s.get("type") == "imu"]
    assert [s.get("name") for s in imus] == ["imu"]
    s = imus[0]
    assert (s.findtext("topic"), s.findtext("update_rate")) == ("imu", "200")
    stddevs = {float(n.findtext("stddev")) for n in s.iter("noise")}
    assert stddevs == {0.01} and len(list(s.iter("noise"))) == 6


def test_legacy_mode_on_an_old_package_with_swapped_wheel_names_turns_right(tmp_path):
    """Written for legacy mode (leftJoint names the wheel at -y): the two swaps cancel, nothing is reported."""
    f = tmp_path / "old.urdf"
    f.write_text(ROVER.format(wheels=TWO, extra=LEGACY.replace("<leftJoint>jl", "<leftJoint>jr")
                              .replace("<rightJoint>jr", "<rightJoint>jl")))
    r = invoke("check", "--format", "json", f)
    codes = [x["code"] for x in json.loads(r.stdout)["files"][0]["diagnostics"]]
    assert "G013" not in codes and "G005" not in codes
    doc = json.loads(invoke("sim", "drive", "--json", "--twist", "0,0.5,2", f).stdout)
    assert {c["name"]: c["value"] for c in doc["checks"]}["turn-rate ratio"] == pytest.approx(1.0, abs=1e-6)
    assert any("the two cancel" in n for n in doc["notes"])


def test_surface_points_one_sampling():
    """Box corners, cylinder rims of n, sphere great circles of n/2: all on the surface, pure Python."""
    from myrabot_desc.model.parts import Box, Cylinder, Sphere
    from myrabot_desc.model.shapes import surface_points

    box = surface_points(Box((0.2, 0.4, 0.6)))
    assert sorted(box) == sorted((x, y, z) for x in (-0.1, 0.1) for y in (-0.2, 0.2) for z in (-0.3, 0.3))
    cyl = surface_points(Cylinder(0.05, 0.02), 16)
    assert isinstance(cyl, list) and len(cyl) == 32
    assert all(abs((x * x + y * y) ** 0.5 - 0.05) < 1e-12 and abs(abs(z) - 0.01) < 1e-12 for x, y, z in cyl)
    sph = surface_points(Sphere(0.1), 16)
    assert len(sph) == 24 and all(abs(sum(c * c for c in p) ** 0.5 - 0.1) < 1e-12 for p in sph)
    assert (0.0, 0.0, -0.1) in [tuple(round(c, 12) + 0.0 for c in p) for p in sph]   # the lowest point
