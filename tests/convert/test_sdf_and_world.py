"""`convert --to sdf|world`: the bundled robot, its demo objects and worlds, the seed's Electric
files, wander_bot, and what `ign sdf -p` keeps next to what we keep. Every SDF we write is run
through the real validator (`ign sdf -k`, sdformat 12) when it is installed."""

from __future__ import annotations

import math
import shutil
import subprocess
import sysconfig
from pathlib import Path

import pytest
from click.testing import CliRunner
from lxml import etree

from helpers import FIXTURES, CORPUS, BAD
from myrabot_desc.expand.packages import data_root
from myrabot_desc.commands.main import main
from myrabot_desc.convert.sdf import SdfOptions, to_sdf
from myrabot_desc.model.loader import load_robot

FIX = FIXTURES
SEED = FIX / "seed_myrabot"
SEED_ROBOT = SEED / "myrabot_fer_modelo" / "urdf" / "myrabot.urdf.xacro"
WANDER = FIX / "wander_bot" / "urdf" / "robot.xacro"
OBJECTS = ["xacro/mesa.urdf.xacro", "xacro/lata_cerveza.urdf.xacro", "xacro/lata_cola.urdf.xacro"]


def _ign_ok() -> bool:
    if shutil.which("ign") is None:
        return False
    r = subprocess.run(["ign", "sdf", "--versions"], capture_output=True, text=True)
    return r.returncode == 0 and r.stdout.strip() != ""


IGN = _ign_ok()
needs_ign = pytest.mark.skipif(not IGN, reason="`ign sdf` not installed (apt-get install ignition-tools "
                                                "libsdformat-dev; `make install-tools`)")


def ign_check(path: Path) -> None:
    r = subprocess.run(["ign", "sdf", "-k", str(path)], capture_output=True, text=True)
    assert r.returncode == 0 and "Valid." in r.stdout, f"ign sdf -k {path}:\n{r.stdout}\n{r.stderr}"


def run(args, tmp_path=None):
    return CliRunner().invoke(main, args, catch_exceptions=False)


@pytest.fixture(scope="module")
def bundled():
    return load_robot(None)


@pytest.fixture(scope="module")
def bundled_sdf(bundled):
    text, res = to_sdf(bundled)
    return etree.fromstring(text.encode()), res, text


def sensors(root):
    return {s.get("name"): s for s in root.iter("sensor")}


# ------------------------------------------------------------------ the bundled robot
def test_bundled_robot_sensors(bundled_sdf):
    root, res, _ = bundled_sdf
    s = sensors(root)
    sonars = [s[f"ultrasonidos_{i}"] for i in range(1, 6)]
    for i, son in enumerate(sonars, 1):
        assert son.get("type") == "gpu_lidar"
        h = son.find("lidar/scan/horizontal")
        assert int(h.findtext("samples")) == 5
        assert float(h.findtext("min_angle")) == pytest.approx(-math.radians(16))
        assert float(h.findtext("max_angle")) == pytest.approx(math.radians(16))
        assert int(son.findtext("lidar/scan/vertical/samples")) == 1
        assert float(son.findtext("lidar/range/max")) == 7
        assert son.findtext("topic") == f"ultrasonidos_{i}"
        assert son.findtext("gz_frame_id") == f"ultrasonidos_{i}_link"
        # the note that gz-sim has no sonar sits right before the sensor
        notes = [c.text for c in son.getparent() if isinstance(c, etree._Comment)]
        assert any("gz-sim has no sonar" in n for n in notes)
    laser = s["laser"]
    assert laser.get("type") == "gpu_lidar" and laser.getparent().get("name") == "laser"
    assert int(laser.findtext("lidar/scan/horizontal/samples")) == 180
    assert float(laser.findtext("lidar/scan/horizontal/max_angle")) == pytest.approx(math.radians(30))
    assert laser.findtext("topic") == "scan"
    imu = [x for x in s.values() if x.get("type") == "imu"]
    assert len(imu) == 1 and imu[0].getparent().get("name") == "gyro_link"
    assert imu[0].findtext("topic") == "imu/data" and float(imu[0].findtext("update_rate")) == 30
    assert float(imu[0].find("imu/angular_velocity/x/noise").findtext("stddev")) == pytest.approx(0.0017 ** 2)
    cam, web = s["camera"], s["webcam"]
    assert cam.get("type") == "rgbd_camera"
    assert cam.findtext("camera/optical_frame_id") == "camera_depth_optical_frame"
    assert cam.findtext("gz_frame_id") == "camera_depth_optical_frame"
    assert float(cam.findtext("camera/horizontal_fov")) == pytest.approx(math.radians(60))
    assert web.findtext("camera/optical_frame_id") == "e_webcam_optical_frame"
    assert float(web.findtext("camera/horizontal_fov")) == pytest.approx(math.radians(63.09))
    assert (int(web.findtext("camera/image/width")), int(web.findtext("camera/image/height"))) == (640, 480)
    # every optical frame named is a real link of the model
    links = {l.get("name") for l in root.iter("link")}
    assert {"camera_depth_optical_frame", "e_webcam_optical_frame"} <= links


def test_bundled_robot_diff_drive_and_systems(bundled_sdf):
    root, res, _ = bundled_sdf
    plugins = {p.get("filename"): p for p in root.findall("model/plugin")}
    dd = plugins["gz-sim-diff-drive-system"]
    assert dd.get("name") == "gz::sim::systems::DiffDrive"
    assert float(dd.findtext("wheel_separation")) == pytest.approx(0.26, abs=1e-9)
    assert float(dd.findtext("wheel_radius")) == pytest.approx(0.033, abs=1e-9)
    assert (dd.findtext("left_joint"), dd.findtext("right_joint")) == ("left_wheel_joint", "right_wheel_joint")
    assert dd.findtext("topic") == "cmd_vel" and dd.findtext("odom_topic") == "odom"
    assert "gz-sim-joint-state-publisher-system" in plugins
    arm = [p.findtext("joint_name") for p in root.findall("model/plugin")
           if p.get("filename") == "gz-sim-joint-position-controller-system"]
    assert len(arm) == 5
    # continuous wheels became unlimited revolute joints
    j = root.find("model/joint[@name='left_wheel_joint']")
    assert j.get("type") == "revolute" and j.find("axis/limit/lower") is None


def test_bundled_robot_keeps_everything(bundled, bundled_sdf):
    root, res, _ = bundled_sdf
    assert set(res.links) == set(bundled.links)            # --no-lump: every URDF link is a link
    assert len(res.joints) == len(bundled.joints)
    assert res.frames == []
    # surfaces from the seed's attribute syntax <mu1 value="10"/> and <fdir value=.../>
    wheel = root.find("model/link[@name='left_wheel_link']/collision")
    assert float(wheel.findtext("surface/friction/ode/mu")) == 10
    assert wheel.findtext("surface/friction/ode/fdir1") == "1 0 0"
    assert float(wheel.findtext("surface/contact/ode/kp")) == 1e8
    # explicit colours everywhere a material was named; no OGRE script reference survives
    assert root.find(".//material/script") is None
    assert len(root.findall(".//visual/material/diffuse")) > 40


@needs_ign
@pytest.mark.parametrize("args", [[], ["--lump"], ["--uri-style", "model"]], ids=["no-lump", "lump", "model-uris"])
def test_bundled_robot_validates(tmp_path, args):
    out = tmp_path / "myrabot.sdf"
    r = run(["convert", "-o", str(out), *args])
    assert r.exit_code == 0, r.output
    ign_check(out)


def test_lump_keeps_every_link_as_frame(bundled):
    text, res = to_sdf(bundled, SdfOptions(lump=True))
    root = etree.fromstring(text.encode())
    names = {e.get("name") for e in root.iter("link")} | {e.get("name") for e in root.iter("frame")}
    assert set(bundled.links) <= names
    fixed = [j.name for j in bundled.joints.values() if j.type == "fixed"]
    assert set(fixed) <= {e.get("name") for e in root.iter("frame")}
    assert len(res.links) + len([f for f in res.frames if f in bundled.links]) == len(bundled.links)
    # mass is conserved by the lumping (the placeholder of massless kept links aside)
    total = sum(float(m.text) for m in root.iter("mass"))
    assert total == pytest.approx(bundled.total_mass, rel=1e-9, abs=1e-3 * len(res.links))
    # sensors moved into their host link still point the same way: the optical frame is a frame now
    s = sensors(root)
    assert s["camera"].getparent().get("name") == "base_footprint"
    assert root.find("model/frame[@name='camera_depth_optical_frame']") is not None


@needs_ign
def test_ign_print_vs_ours(tmp_path, bundled):
    """Same URDF: `ign sdf -p` lumps and drops; we keep every link, frame and sensor."""
    urdf = tmp_path / "myrabot.urdf"
    urdf.write_text(bundled.urdf_text)
    p = subprocess.run(["ign", "sdf", "-p", str(urdf)], capture_output=True, text=True)
    assert p.returncode == 0
    # ign copies the Electric blobs verbatim with undeclared prefixes: parse leniently
    theirs = etree.fromstring(p.stdout.encode(), etree.XMLParser(recover=True))
    their_links = {e.get("name") for e in theirs.iter("link")}
    their_frames = {e.get("name") for e in theirs.iter("frame")}
    their_sensors = [e for e in theirs.iter("sensor")]
    ours_text, res = to_sdf(bundled)
    ours = etree.fromstring(ours_text.encode())
    our_frames_or_links = {e.get("name") for e in ours.iter("link")} | {e.get("name") for e in ours.iter("frame")}
    lost_by_ign = set(bundled.links) - their_links - their_frames
    assert len(their_links) < 10 and len(lost_by_ign) > 60     # 76 URDF links -> 8 links, no frames
    assert their_sensors == []                                  # the Electric sensors are not SDF sensors
    assert set(bundled.links) <= our_frames_or_links            # we keep every frame
    assert len(res.sensors) == 14
    # and in lump mode too, with frames instead of links
    text, res = to_sdf(bundled, SdfOptions(lump=True))
    lumped = etree.fromstring(text.encode())
    kept = {e.get("name") for e in lumped.iter("link")} | {e.get("name") for e in lumped.iter("frame")}
    assert set(bundled.links) <= kept and len(res.sensors) == 14


@needs_ign
def test_ign_drops_massless_subtree_we_keep(tmp_path):
    """A classic (ROS 1/2 style) robot: massless camera link with an SDF camera sensor."""
    urdf = tmp_path / "cam.urdf"
    urdf.write_text("""<robot name="cam">
  <link name="base_link"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
  <joint name="pan" type="revolute"><parent link="base_link"/><child link="camera_link"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <link name="camera_link"/>
  <joint name="optical" type="fixed"><parent link="camera_link"/><child link="camera_optical"/><origin rpy="-1.5708 0 -1.5708"/></joint>
  <link name="camera_optical"/>
  <gazebo reference="camera_link">
    <sensor type="camera" name="cam">
      <update_rate>30</update_rate>
      <camera><horizontal_fov>1.2</horizontal_fov><image><width>320</width><height>240</height></image>
        <clip><near>0.1</near><far>20</far></clip></camera>
      <plugin name="cam_plugin" filename="libgazebo_ros_camera.so">
        <cameraName>front</cameraName><imageTopicName>image_raw</imageTopicName><frameName>camera_optical</frameName>
      </plugin>
    </sensor>
  </gazebo>
  <gazebo reference="base_link"><sensor type="ray" name="scan"><ray><scan><horizontal><samples>90</samples>
    <min_angle>-1</min_angle><max_angle>1</max_angle></horizontal></scan><range><min>0.1</min><max>5</max></range></ray>
    <plugin name="l" filename="libgazebo_ros_ray_sensor.so"><ros><remapping>~/out:=scan</remapping></ros></plugin></sensor></gazebo>
</robot>""")
    p = subprocess.run(["ign", "sdf", "-p", str(urdf)], capture_output=True, text=True)
    theirs = etree.fromstring(p.stdout.encode())
    assert {e.get("name") for e in theirs.iter("link")} == {"base_link"}     # camera subtree silently gone
    assert "cam" not in {e.get("name") for e in theirs.iter("sensor")}
    out = tmp_path / "ours.sdf"
    r = run(["convert", str(urdf), "-o", str(out)])
    assert r.exit_code == 0
    assert "massless link(s) kept" in r.output and "camera_link" in r.output
    ours = etree.parse(str(out)).getroot()
    assert {e.get("name") for e in ours.iter("link")} == {"base_link", "camera_link", "camera_optical"}
    s = sensors(ours)
    assert s["cam"].getparent().get("name") == "camera_link"
    assert s["cam"].findtext("topic") == "front/image_raw"
    assert s["cam"].findtext("camera/optical_frame_id") == "camera_optical"
    assert s["scan"].get("type") == "gpu_lidar" and s["scan"].find("lidar") is not None
    assert s["scan"].find("ray") is None and s["scan"].findtext("topic") == "scan"
    assert ours.find(".//sensor/plugin") is None
    ign_check(out)


# ------------------------------------------------------------------ objects and worlds
@pytest.mark.parametrize("rel", OBJECTS)
def test_objects_convert(tmp_path, rel):
    out = tmp_path / (Path(rel).stem + ".sdf")
    r = run(["convert", str(data_root() / rel), "-o", str(out)])
    assert r.exit_code == 0, r.output
    root = etree.parse(str(out)).getroot()
    assert root.find("model/link") is not None
    assert root.find(".//material/diffuse") is not None
    if IGN:
        ign_check(out)


@pytest.mark.parametrize("layout,models", [("escoja", ["MYRAbot", "mesa", "lata_cocacola", "lata_amstel"]),
                                           ("seguir", ["MYRAbot", "mesa", "lata_amstel"])])
def test_worlds(tmp_path, layout, models):
    out = tmp_path / f"{layout}.sdf"
    r = run(["convert", "--to", "world", "--layout", layout, "-o", str(out), "-q"])
    assert r.exit_code == 0, r.output
    world = etree.parse(str(out)).getroot().find("world")
    assert [m.get("name") for m in world.findall("model")] == ["ground_plane", *models]
    assert world.find("light[@name='sun']") is not None
    systems = {p.get("name").rsplit("::", 1)[1] for p in world.findall("plugin")}
    assert systems == {"Physics", "UserCommands", "SceneBroadcaster", "Sensors", "Imu"}
    assert world.find("plugin[@filename='gz-sim-sensors-system']/render_engine").text == "ogre2"
    poses = {m.get("name"): [float(x) for x in m.findtext("pose").split()] for m in world.findall("model")[1:]}
    assert poses["mesa"] == [0.55, 0, 0, 0, 0, -1.57]
    can = poses["lata_amstel"]
    assert can == ([0.38, 0.17, 0.74, 0, 0, -1.57] if layout == "escoja" else [0.5, 0, 0.74, 0, 0, -1.57])
    if IGN:
        ign_check(out)


# ------------------------------------------------------------------ the seed as written (Electric)
def test_seed_electric_degrees_to_radians(tmp_path):
    robot = load_robot(str(SEED_ROBOT), package_paths=[str(SEED)])
    text, res = to_sdf(robot)
    root = etree.fromstring(text.encode())
    s = sensors(root)
    assert float(s["camera"].findtext("camera/horizontal_fov")) == pytest.approx(math.radians(60))
    assert float(s["webcam"].findtext("camera/horizontal_fov")) == pytest.approx(math.radians(63.09))
    h = s["laser"].find("lidar/scan/horizontal")
    assert float(h.findtext("min_angle")) == pytest.approx(-math.pi / 6)
    assert float(h.findtext("max_angle")) == pytest.approx(math.pi / 6)
    # the seed's webcam controller says filename= (never loaded by Gazebo 1.0): a plain camera, said so
    assert s["webcam"].get("type") == "camera" and s["webcam"].findtext("topic") == "/webcam/image_raw"
    assert any("filename=" in w for w in res.notes.warnings)
    # its Roomba base: separation and radius measured on the wheels
    dd = root.find("model/plugin[@filename='gz-sim-diff-drive-system']")
    assert float(dd.findtext("wheel_separation")) == pytest.approx(0.26)
    assert float(dd.findtext("wheel_radius")) == pytest.approx(0.033)
    # the seed's impossible inertias (base_link izz 0.5 > ixx + iyy) are repaired with a warning
    assert any("triangle inequality" in w and "base_link" in w for w in res.notes.warnings)
    izz = float(root.find("model/link[@name='base_link']/inertial/inertia/izz").text)
    ixx = float(root.find("model/link[@name='base_link']/inertial/inertia/ixx").text)
    assert izz == 0.5 and 2 * ixx >= izz
    # Gazebo 0.x joint stops (stopKp/stopKd) became ODE limit erp/cfm
    assert root.find("model/joint[@name='arti1']/physics/ode/limit/erp") is not None
    if IGN:
        out = tmp_path / "seed.sdf"
        out.write_text(text)
        ign_check(out)


def test_seed_ultrasonidos_electric_sonar(tmp_path):
    """The seed's sonar macro (not included by its assembly) on a small robot of our own."""
    urdf = tmp_path / "sonar.urdf.xacro"
    urdf.write_text(f"""<?xml version="1.0"?>
<robot name="ring" xmlns:xacro="http://ros.org/wiki/xacro">
  <xacro:include filename="$(find myrabot_fer_modelo)/urdf/ultrasonidos.xacro"/>
  <link name="e_base_2_link"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <xacro:ultrasonidos id="1" parent="e_base_2_link" d_centro="0.150"><origin rpy="0 0 1.57" xyz="0.135 0.135 0.02"/></xacro:ultrasonidos>
</robot>""")
    r = run(["convert", str(urdf), "--package-path", str(SEED), "-o", str(tmp_path / "ring.sdf")])
    assert r.exit_code == 0, r.output
    root = etree.parse(str(tmp_path / "ring.sdf")).getroot()
    son = sensors(root)["ultrasonidos_1"]
    # the seed's sensor link has no <inertial>: ign sdf -p would drop it with its sensor; we keep it
    assert son.getparent().get("name") == "ultrasonidos_1_link"
    assert "massless link(s) kept" in r.output
    assert float(son.findtext("lidar/scan/vertical/min_angle")) == pytest.approx(math.radians(-16))
    assert float(son.findtext("lidar/noise/stddev")) == 0.005


def test_wander_bot_diff_drive_mismatch():
    """Seed B's robot 'moves strangely': its plugin's geometry disagrees with its wheels."""
    robot = load_robot(str(WANDER))
    text, res = to_sdf(robot)
    root = etree.fromstring(text.encode())
    dd = root.find("model/plugin[@filename='gz-sim-diff-drive-system']")
    assert float(dd.findtext("wheel_separation")) == pytest.approx(0.3)
    assert float(dd.findtext("wheel_radius")) == pytest.approx(0.08)
    warned = [w for w in res.notes.warnings if "the plugin says" in w]
    assert len(warned) == 2 and "0.4" in warned[0] and "robot.gazebo:4" in warned[0]


# ------------------------------------------------------------------ a real corpus
ERD = Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix/share/example-robot-data/robots"
ERD_URDFS = sorted(ERD.rglob("*.urdf")) if ERD.is_dir() else []


@needs_ign
@pytest.mark.skipif(not ERD_URDFS, reason="example-robot-data is not installed")
@pytest.mark.parametrize("urdf", ERD_URDFS, ids=[p.stem for p in ERD_URDFS])
def test_example_robot_data_validates(tmp_path, urdf):
    out = tmp_path / "robot.sdf"
    r = CliRunner().invoke(main, ["convert", str(urdf), "-o", str(out), "-q"])
    robot = load_robot(str(urdf))
    if not robot.links:                     # ur3.urdf is an empty shell: a clean refusal
        assert r.exit_code == 2 and "no links" in r.output and not out.exists()
        return
    if r.exit_code == 2:                    # check's errors (I004/I005...): refused, converted on request
        assert ": error: " in r.output and not out.exists(), r.output
        r = CliRunner().invoke(main, ["convert", str(urdf), "-o", str(out), "-q", "--allow-errors"])
    assert r.exit_code == 0, r.output
    ign_check(out)
    root = etree.parse(str(out)).getroot()
    # every link is kept (an empty URDF `world` link is the SDF world itself)
    expected = {n for n, l in robot.links.items()
                if not (n == "world" and not l.visuals and not l.collisions and l.inertial is None)}
    assert {e.get("name") for e in root.iter("link")} == expected
    # every joint and sensor `ign sdf -p` keeps on the same URDF, we keep (it lumps fixed joints away;
    # they stay here), under the same name and type
    p = subprocess.run(["ign", "sdf", "-p", str(urdf)], capture_output=True, text=True, timeout=120)
    if p.returncode != 0:       # the talos files: ign reads a NaN-free file as "Pose values must be finite"
        assert "Error" in p.stderr and not p.stdout.strip()
        return
    theirs = etree.fromstring(p.stdout.encode(), etree.XMLParser(recover=True))
    their_joints = {e.get("name"): e.get("type") for e in theirs.findall("model/joint")}
    our_joints = {e.get("name"): e.get("type") for e in root.findall("model/joint")}
    # (a joint with a link's name is renamed NAME_joint: SDF 1.8+ wants unique names; so100's 'gripper')
    assert {(n if n in our_joints else f"{n}_joint", t) for n, t in their_joints.items()} <= our_joints.items()
    assert {e.get("name") for e in theirs.iter("sensor")} <= {e.get("name") for e in root.iter("sensor")}


# ------------------------------------------------------------------ CLI behaviour
def test_unknown_plugin_kept_as_comment(tmp_path):
    urdf = tmp_path / "p.urdf"
    urdf.write_text("""<robot name="p"><link name="a"><inertial><mass value="1"/>
      <inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <gazebo><plugin name="mystery" filename="libmystery_plugin.so"><speed>3</speed></plugin>
      <plugin name="other" filename="libother.so"/></gazebo></robot>""")
    r = run(["convert", str(urdf)])
    assert r.exit_code == 0
    assert "2 plugin(s) with no gz-sim equivalent kept as XML comments: mystery (libmystery_plugin.so), other" in r.output
    assert "<!-- not converted (no gz-sim equivalent known): <plugin name=\"mystery\"" in r.output


def test_deterministic(bundled):
    a, _ = to_sdf(bundled)
    b, _ = to_sdf(load_robot(None))
    assert a == b


def test_stdout_and_help():
    r = CliRunner().invoke(main, ["convert", "--help"])
    assert r.exit_code == 0 and "Examples:" in r.output and "--to world --layout seguir" in r.output
    r = CliRunner().invoke(main, ["convert", str(data_root() / OBJECTS[1])])
    assert r.exit_code == 0 and r.output.lstrip().startswith("<?xml") and "<sdf version=\"1.9\">" in r.output


@pytest.mark.parametrize("args,expect", [
    (["no/such/robot.urdf"], "no such file"),
    (["BAD"], "error"),
])
def test_bad_input_one_line_exit_2_nothing_written(tmp_path, args, expect):
    if args == ["BAD"]:
        bad = tmp_path / "bad.urdf"
        bad.write_text("<robot name='x'><link name='a'></robot>")
        args = [str(bad)]
    out = tmp_path / "out" / "x.sdf"
    r = CliRunner().invoke(main, ["convert", *args, "-o", str(out)])
    assert r.exit_code == 2
    assert expect in r.output and "Traceback" not in r.output
    assert len(r.output.strip().splitlines()) == 1
    assert not out.exists()
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())


def test_uri_styles(tmp_path):
    """absolute (default): files that exist; model: model://<package>/... for meshes and textures."""
    r = run(["convert", "--to", "world", "-o", str(tmp_path / "abs.sdf"), "-q"])
    assert r.exit_code == 0
    root = etree.parse(str(tmp_path / "abs.sdf")).getroot()
    uris = [e.text for e in root.iter("uri")] + [e.text for e in root.iter("albedo_map")]
    assert uris and all(Path(u).is_absolute() and Path(u).is_file() for u in uris)
    assert any(u.endswith(".png") for u in uris)          # the cans' and table's textures
    r = run(["convert", "--to", "world", "--uri-style", "model", "-o", str(tmp_path / "model.sdf")])
    assert r.exit_code == 0 and "GZ_SIM_RESOURCE_PATH=" in r.output
    root = etree.parse(str(tmp_path / "model.sdf")).getroot()
    uris = [e.text for e in root.iter("uri")] + [e.text for e in root.iter("albedo_map")]
    assert all(u.startswith("model://myrabot_description/") for u in uris)


DIFF_BASE = """<robot name="rover">
  <link name="base_link"><inertial><mass value="5"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.4 0.3 0.1"/></geometry></collision></link>
  <link name="wl"><inertial><mass value="0.5"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin rpy="1.5708 0 0"/><geometry><cylinder radius="0.05" length="0.02"/></geometry></collision></link>
  <link name="wr"><inertial><mass value="0.5"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin rpy="1.5708 0 0"/><geometry><cylinder radius="0.05" length="0.02"/></geometry></collision></link>
  <joint name="jl" type="continuous"><parent link="base_link"/><child link="wl"/><origin xyz="0 0.17 0"/><axis xyz="0 1 0"/></joint>
  <joint name="jr" type="continuous"><parent link="base_link"/><child link="wr"/><origin xyz="0 -0.17 0"/><axis xyz="0 1 0"/></joint>
  <link name="imu_link"/>
  <joint name="imu_joint" type="fixed"><parent link="base_link"/><child link="imu_link"/></joint>
  {gazebo}
</robot>"""


@pytest.mark.parametrize("plugin,topic", [
    ("""<plugin name="dd" filename="libgazebo_ros_diff_drive.so"><ros><namespace>/demo</namespace>
        <remapping>cmd_vel:=cmd_demo</remapping></ros><left_joint>jl</left_joint><right_joint>jr</right_joint>
        <wheel_separation>0.34</wheel_separation><wheel_diameter>0.1</wheel_diameter>
        <max_wheel_acceleration>2</max_wheel_acceleration></plugin>""", "/demo/cmd_demo"),
    ("""<plugin filename="gz-sim-diff-drive-system" name="gz::sim::systems::DiffDrive"><left_joint>jl</left_joint>
        <right_joint>jr</right_joint><wheel_separation>1.0</wheel_separation><wheel_radius>0.2</wheel_radius>
        <topic>cmd_vel</topic></plugin>""", "cmd_vel"),
], ids=["ros2-classic", "gz"])
def test_diff_drive_dialects(tmp_path, plugin, topic):
    urdf = tmp_path / "rover.urdf"
    urdf.write_text(DIFF_BASE.format(gazebo=f"""<gazebo>{plugin}</gazebo>
      <gazebo reference="imu_link"><sensor name="imu" type="imu"><update_rate>100</update_rate>
        <plugin name="imu_plugin" filename="libgazebo_ros_imu_sensor.so"><ros><remapping>~/out:=imu</remapping></ros>
        </plugin></sensor></gazebo>"""))
    text, res = to_sdf(load_robot(str(urdf)))
    root = etree.fromstring(text.encode())
    dd = root.findall("model/plugin[@filename='gz-sim-diff-drive-system']")
    assert len(dd) == 1
    assert float(dd[0].findtext("wheel_separation")) == pytest.approx(0.34)
    assert float(dd[0].findtext("wheel_radius")) == pytest.approx(0.05)
    assert dd[0].findtext("topic") == topic
    if "ros2" in plugin or "libgazebo_ros" in plugin:
        # max_wheel_acceleration is the wheel surface's m/s^2 (the plugin ramps r * omega): the same
        # vehicle limit, not multiplied by the radius again; turning, 2a/s bounds the yaw acceleration
        assert float(dd[0].findtext("max_linear_acceleration")) == pytest.approx(2.0)
        assert float(dd[0].findtext("max_angular_acceleration")) == pytest.approx(2 * 2.0 / 0.34)
    else:   # the gz plugin's own 1.0 / 0.2 disagree with the wheels: said, and the wheels win
        assert sum("the plugin says" in w for w in res.notes.warnings) == 2
    imu = sensors(root)["imu"]
    assert imu.getparent().get("name") == "imu_link" and imu.findtext("topic") == "imu"
    if IGN:
        (tmp_path / "rover.sdf").write_text(text)
        ign_check(tmp_path / "rover.sdf")


def test_unreadable_values_are_warned_not_converted_silently(tmp_path):
    """A NaN the loader cannot take: check calls it an error, so convert refuses it; with --allow-errors it
    is left out of the SDF, with a warning at its file:line."""
    bad = BAD / "numbers" / "ixy_nan.urdf"
    r = CliRunner().invoke(main, ["convert", str(bad), "-o", str(tmp_path / "r.sdf")])
    assert r.exit_code == 2 and f"{bad}:7: error: T010" in r.output and not (tmp_path / "r.sdf").exists()
    r = CliRunner().invoke(main, ["convert", str(bad), "-o", str(tmp_path / "r.sdf"), "--allow-errors"])
    assert r.exit_code == 0
    assert f"{bad}:7: warning: T010 <inertia ixy=\"nan\">: not a finite number: left out of the conversion" \
        in r.output
    ine = etree.parse(str(tmp_path / "r.sdf")).find(".//link[@name='base_link']/inertial/inertia")
    assert ine.findtext("ixy") == "0" and ine.findtext("ixx") == "0.02"      # the NaN read as the default 0


# ------------------------------------------------------------------ the real-robot corpus vs ign


def _corpus():
    if not (CORPUS / "robots.yaml").is_file():
        return []
    import yaml

    return yaml.safe_load((CORPUS / "robots.yaml").read_text())["robots"]


@needs_ign
@pytest.mark.skipif(not _corpus(), reason="the real-robot corpus (tests/corpus) is not here")
@pytest.mark.parametrize("robot", _corpus(), ids=[r["id"] for r in _corpus()])
def test_corpus_keeps_what_ign_keeps(tmp_path, robot):
    """Each corpus robot, built to URDF: every joint and sensor `ign sdf -p` keeps is in our SDF
    (same name and type), the <gazebo> joints included; ours passes `ign sdf -k`."""
    env = {k: str(v) for k, v in (robot.get("env") or {}).items()}
    pkg = ["--package-path", str(CORPUS / robot.get("package_path", "."))]
    src = [str(CORPUS / robot["top"]), *robot.get("args", "").split(), *pkg]
    urdf = tmp_path / "robot.urdf"
    r = CliRunner().invoke(main, ["build", *src, "-o", str(urdf)], env=env)
    if r.exit_code == 2 and "--unsafe-eval allows it" in r.output:
        r = CliRunner().invoke(main, ["build", *src, "--unsafe-eval", "-o", str(urdf)], env=env)
    assert r.exit_code == 0, r.output
    out = tmp_path / "robot.sdf"
    r = CliRunner().invoke(main, ["convert", str(urdf), *pkg, "-o", str(out), "-q", "--report",
                                  str(tmp_path / "r.json")])
    if "no links" in r.output:                       # rotors' .gazebo top file: a refusal, as for ign
        return
    if r.exit_code == 2:       # check's reviewed errors (tests/realrobots REAL_ERRORS): converted on request
        assert ": error: " in r.output and not out.exists(), r.output
        r = CliRunner().invoke(main, ["convert", str(urdf), *pkg, "-o", str(out), "-q", "--allow-errors", "--report",
                                      str(tmp_path / "r.json")])
    assert r.exit_code == 0, r.output
    ign_check(out)
    p = subprocess.run(["ign", "sdf", "-p", str(urdf)], capture_output=True, text=True, timeout=120)
    if p.returncode != 0:
        return
    theirs = etree.fromstring(p.stdout.encode(), etree.XMLParser(recover=True))
    ours = etree.parse(str(out)).getroot()
    their_joints = {e.get("name"): e.get("type") for e in theirs.findall("model/joint")}
    our_joints = {e.get("name"): e.get("type") for e in ours.findall("model/joint")}
    assert their_joints.items() <= our_joints.items(), set(their_joints.items()) - set(our_joints.items())
    assert {e.get("name") for e in theirs.iter("sensor")} <= {e.get("name") for e in ours.iter("sensor")}
    if robot["id"] == "pr2":
        import json

        rep = json.loads((tmp_path / "r.json").read_text())
        gz = [e for e in rep["elements"] if e["kind"] == "gazebo-joint"]
        # 15 joints in PR2's <gazebo> blocks (screws, parallel linkages); two share a URDF joint's name
        assert len(gz) == 15 and sum(e["fate"] == "kept" for e in gz) == 13
        assert {e["name"] for e in gz if e["fate"] == "translated"} == {"r_gripper_joint", "l_gripper_joint"}
        assert {"r_gripper_joint_gazebo", "l_gripper_joint_gazebo", "torso_lift_screw_torso_lift_joint"} <= set(our_joints)


def test_negative_effort_is_no_limit_for_the_joint_controllers(tmp_path):
    """effort="-1" (Audibot's, SDF's "no limit"): the velocity controller gets no cmd_max -1 /
    cmd_min 1 and the position controller no p_gain -10, as the MJCF writer reads it (no limit)."""
    inertial = '<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>'
    f = tmp_path / "arm.urdf"
    f.write_text(f'''<robot name="arm"><link name="base_link">{inertial}</link><link name="arm">{inertial}</link>
      <link name="wheel">{inertial}</link>
      <joint name="shoulder" type="revolute"><parent link="base_link"/><child link="arm"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="-1" velocity="-1"/></joint>
      <joint name="spinner" type="continuous"><parent link="base_link"/><child link="wheel"/><axis xyz="0 0 1"/>
        <limit effort="-1" velocity="-1"/></joint>
      <ros2_control name="arm" type="system"><hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
        <joint name="shoulder"><command_interface name="position"/></joint>
        <joint name="spinner"><command_interface name="velocity"/></joint></ros2_control></robot>''')
    out = tmp_path / "arm.sdf"
    res = CliRunner().invoke(main, ["convert", str(f), "--to", "sdf", "-o", str(out)])
    assert res.exit_code == 0, res.output[-1500:]
    root = etree.parse(str(out)).getroot()
    plugins = {p.findtext("joint_name"): p for p in root.iter("plugin") if p.findtext("joint_name")}
    assert set(plugins) == {"shoulder", "spinner"}
    assert plugins["spinner"].find("cmd_max") is None and plugins["spinner"].find("cmd_min") is None
    assert (plugins["shoulder"].findtext("p_gain"), plugins["shoulder"].findtext("d_gain")) == ("1", "0.1")
    assert plugins["shoulder"].find("cmd_max") is None
