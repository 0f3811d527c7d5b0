"""The bundled MYRAbot model (xacro/, meshes/, materials/, layouts/): built
through the CLI and the library, checked against the seed's numbers
(../shared/research/seed-spec.md §2.0, §2.2-2.9, §4; arm-facts.md §2, §4, §6)."""

from __future__ import annotations

import math
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import yaml
from click.testing import CliRunner
from lxml import etree

from myrabot_desc.expand.packages import data_root
from myrabot_desc.commands.main import main as cli
from myrabot_desc.model.kinematics import pose_matrix, world_transforms
from myrabot_desc.model.loader import load_robot

ROOT = data_root()

# seed-spec §2.0: position in base_footprint of every frame the issue names
# (the table gives 1 mm; the arm mount is arm-facts §6.1's (0.1015, -0.0001)).
SEED_FRAMES = {
    "base_link": (0, 0, 0.017),
    "wall_sensor_link": (0.09, -0.12, 0.059),
    "left_cliff_sensor_link": (0.07, 0.14, 0.027),
    "right_cliff_sensor_link": (0.07, -0.14, 0.027),
    "leftfront_cliff_sensor_link": (0.15, 0.04, 0.027),
    "rightfront_cliff_sensor_link": (0.15, -0.04, 0.027),
    "left_wheel_link": (0, 0.13, 0.032),
    "right_wheel_link": (0, -0.13, 0.032),
    "front_wheel_link": (0.13, 0, 0.017),
    "rear_wheel_link": (-0.13, 0, 0.017),
    "gyro_link": (0, 0, 0.057),
    "laser": (-0.065, 0, 0.587),
    "e_base_1_link": (0.135, -0.135, 0.080),
    "e_base_2_link": (0.135, -0.135, 0.215),
    "e_pilar_link": (0.135, -0.135, 0.235),
    "e_ultrasonidos_link": (0.135, -0.135, 0.235),
    "e_botonera_link": (0.135, -0.135, 0.235),
    "e_start_button_1_link": (0.135, -0.195, 0.335),
    "e_emergency_button_1_link": (0.135, -0.075, 0.335),
    "e_base_kinect_link": (0.135, -0.135, 0.475),
    "e_base_brazo_1_link": (0.135, -0.135, 0.703),
    "e_base_brazo_2_link": (0.135, -0.135, 0.777),
    "e_soporte_1_link": (0.135, -0.135, 0.437),
    "e_soporte_2_link": (-0.065, -0.135, 1.047),
    "e_monitor_link": (0.144, -0.135, 0.982),
    "e_pantalla_link": (0.035, 0.000, 1.055),
    "camera_link": (0.045, 0.000, 0.587),
    "camera_depth_frame": (0.045, 0.018, 0.587),
    "camera_rgb_frame": (0.045, -0.005, 0.587),
    "camera_rgb_optical_frame": (0.045, -0.005, 0.587),
    "camera_depth_optical_frame": (0.045, 0.018, 0.587),
    "base_brazo_link": (0.1015, -0.0001, 0.778),      # the arm mount
    "e_webcam_1_link": (0.133, -0.135, 1.073),
    "e_webcam_2_link": (0.038, -0.135, 1.160),
    "e_webcam_optica_link": (0.060, 0.000, 1.141),
    "e_webcam_optical_frame": (0.060, 0.000, 1.141),
    "ultrasonidos_1_link": (0.000, 0.158, 0.2425),
    "ultrasonidos_2_link": (-0.112, 0.111, 0.2425),
    "ultrasonidos_3_link": (-0.157, 0.000, 0.2425),
    "ultrasonidos_4_link": (-0.111, -0.112, 0.2425),
    "ultrasonidos_5_link": (0.000, -0.157, 0.2425),
}
# Wheel joints (their origin = the wheel centre) and the arm joints at zero
# (arm-facts §6.2: base 0.818, arti1/2/3 0.8565/0.9605/1.0645, pinza (0.1015, 0.0072, 1.1245)).
SEED_JOINTS = {
    "left_wheel_joint": (0, 0.13, 0.032),
    "right_wheel_joint": (0, -0.13, 0.032),
    "base_brazo_joint": (0.1015, -0.0001, 0.778),
    "base": (0.1015, -0.0001, 0.818),
    "arti1": (0.1015, -0.0001, 0.8565),
    "arti2": (0.1015, -0.0001, 0.9605),
    "arti3": (0.1015, -0.0001, 1.0645),
    "pinza": (0.1015, 0.0072, 1.1245),
}

# Declared masses (kg): seed-spec §2.0 (arm excluded) and arm-facts §2.3 (simple arm).
SEED_MASS = {"roomba": 3.6821, "estructura": 0.5871, "kinect": 0.023, "webcam": 0.021, "sonars": 0.005,
             "brazo": 0.2865}
TOKEN_MASS = 1e-5
TOKEN_LINKS = {"laser", "e_webcam_optical_frame"} | {f"ultrasonidos_{i}_link" for i in range(1, 6)}
ARM_LINKS = {"base_brazo_link", "hombro_link", "muneca_link", "muneca_link_B", "muneca_link_SI", "muneca_link_SD",
             "muneca_link_P", "muneca_link_PS", "pinza_link", "pinza_link_B", "pinza_link_SI", "pinza_link_SD"} | {
    f"{seg}_link{suf}" for seg in ("brazo", "antebrazo") for suf in ("", "_B", "_SI", "_SD")}


def component(link: str) -> str:
    if link in ARM_LINKS:
        return "brazo"
    if link.startswith("camera_"):
        return "kinect"
    if link.startswith("e_webcam"):
        return "webcam"
    if link.startswith("ultrasonidos_"):
        return "sonars"
    if link.startswith("e_"):
        return "estructura"
    return "roomba"


def check_urdf_binary():
    venv_bin = Path(sys.executable).parent / "check_urdf"
    return str(venv_bin) if venv_bin.exists() else shutil.which("check_urdf")


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """`myrabot-desc build -o FILE` with no input: the whole bundled robot."""
    out = tmp_path_factory.mktemp("build") / "myrabot.urdf"
    res = CliRunner().invoke(cli, ["build", "-o", str(out)])
    assert res.exit_code == 0, res.output
    return out


@pytest.fixture(scope="module")
def robot(built):
    return load_robot(built)


@pytest.fixture(scope="module")
def bundled():
    return load_robot(None)


# ---------------------------------------------------------------- structure

def test_build_writes_whole_robot(built):
    doc = etree.parse(str(built)).getroot()
    assert doc.tag == "robot" and doc.get("name") == "MYRAbot"
    links = doc.findall("link")
    joints = doc.findall("joint")
    assert len(links) == 76
    assert len(joints) == 75
    kinds = sorted(j.get("type") for j in joints if j.get("type") != "fixed")
    assert kinds == ["continuous"] * 2 + ["revolute"] * 5
    # nothing left unexpanded: no xacro tags, no ${...}, no raw macro calls
    text = built.read_text()
    assert "xacro" not in text.split("-->")[-1] and "${" not in text
    assert {el.tag for el in doc} <= {"link", "joint", "material", "gazebo", "transmission", etree.Comment}


def test_cli_build_and_library_agree(robot, bundled):
    assert set(robot.links) == set(bundled.links) and set(robot.joints) == set(bundled.joints)
    assert robot.root == bundled.root == "base_footprint"
    for name, j in bundled.joints.items():
        assert robot.joints[name].origin == j.origin


def test_five_sonars_present(robot):
    for i in range(1, 6):
        assert f"ultrasonidos_{i}_link_fisico" in robot.links
        assert robot.joints[f"ultrasonidos_{i}_joint_fisico"].parent == "e_base_2_link"
    sonars = [s for s in robot.sensors() if s.name and s.name.startswith("ultrasonidos_")]
    assert sorted(s.reference for s in sonars) == [f"ultrasonidos_{i}_link" for i in range(1, 6)]


def test_arm_joints_and_limits(robot):
    arm = ["base", "arti1", "arti2", "arti3", "pinza"]
    for name in arm:
        j = robot.joints[name]
        assert j.type == "revolute"
        assert (j.limit.lower, j.limit.upper, j.limit.effort, j.limit.velocity) == (-2.62, 2.62, 100.0, 3.0)
    assert [robot.joints[n].axis for n in arm] == [(0, 0, 1), (1, 0, 0), (1, 0, 0), (1, 0, 0), (0, 1, 0)]
    # L1 = L2 = 104 mm, Lp = 60 mm along the arm
    assert robot.joints["arti2"].origin.xyz == (0, 0, 0.104)
    assert robot.joints["arti3"].origin.xyz == (0, 0, 0.104)
    assert robot.joints["pinza"].origin.xyz[2] == 0.06
    assert robot.joints["base_brazo_joint"].origin.xyz == (0.135, 0.0335, 0.075)
    assert robot.joints["base_brazo_joint"].origin.rpy == (0, 0, 3.1416)
    assert len(robot.transmissions) == 5


# ---------------------------------------------------------------- frames

def test_frame_positions_match_seed(robot):
    T = world_transforms(robot)
    errors = {n: float(np.linalg.norm(T[n][:3, 3] - np.array(p))) for n, p in SEED_FRAMES.items()}
    bad = {n: round(e * 1000, 2) for n, e in errors.items() if e > 0.001}
    assert not bad, f"frames off by more than 1 mm (mm): {bad}"


def test_joint_positions_match_seed(robot):
    from myrabot_desc.model.kinematics import joint_world_transforms

    T = joint_world_transforms(robot)
    bad = {n: T[n][:3, 3].round(4).tolist() for n, p in SEED_JOINTS.items()
           if np.linalg.norm(T[n][:3, 3] - np.array(p)) > 0.001}
    assert not bad


def test_fingertips_at_zero(robot):
    """Top edges of the two finger plates (arm-facts §4.1/§6.2): z 1.2005, y = -+0.03425."""
    T = world_transforms(robot)
    tips = {}
    for link in ("muneca_link_P", "pinza_link"):
        vis = robot.links[link].visuals[0]
        top = pose_matrix(vis.origin) @ np.array([0, 0, vis.geometry.size[2] / 2, 1.0])
        tips[link] = (T[link] @ top)[:3]
    assert np.allclose(tips["muneca_link_P"], (0.1015, -0.03425, 1.2005), atol=0.001)
    assert np.allclose(tips["pinza_link"], (0.1015, 0.03425, 1.2005), atol=0.001)
    # the gap between the fingers' inner faces is 0.0665 (arm-facts §3.1)
    gap = abs(tips["muneca_link_P"][1] - tips["pinza_link"][1]) - 0.002
    assert gap == pytest.approx(0.0665, abs=1e-6)


def test_cameras_report_in_optical_frames(robot):
    T = world_transforms(robot)
    for optical, body in (("camera_rgb_optical_frame", "camera_link"), ("e_webcam_optical_frame", "e_webcam_optica_link")):
        # REP 103: optical z = the body's viewing direction (+x), optical x = the body's -y
        assert np.allclose(T[optical][:3, 2], T[body][:3, 0], atol=1e-6)
        assert np.allclose(T[optical][:3, 0], -T[body][:3, 1], atol=1e-6)
    # the webcam looks forward and 40.1 degrees down (seed-spec §2.0)
    view = T["e_webcam_optica_link"][:3, 0]
    assert math.degrees(math.asin(-view[2])) == pytest.approx(40.1, abs=0.1)
    frames = {p.params.get("frameName") for p in robot.plugins() if p.name and "camera_controller" in p.name}
    assert frames == {"camera_depth_optical_frame", "e_webcam_optical_frame"}


def test_pinocchio_agrees_on_frames(robot):
    import pinocchio as pin

    model = robot.pinocchio()
    data = model.createData()
    pin.framesForwardKinematics(model, data, pin.neutral(model))
    T = world_transforms(robot)
    for name in SEED_FRAMES:
        p = data.oMf[model.getFrameId(name)].translation
        assert np.allclose(p, T[name][:3, 3], atol=1e-9), name


# ---------------------------------------------------------------- mass and inertia

def test_total_mass_is_the_seeds(robot):
    import pinocchio as pin

    model = robot.pinocchio(floating=True)
    expected = sum(SEED_MASS.values()) + TOKEN_MASS * len(TOKEN_LINKS)
    assert pin.computeTotalMass(model) == pytest.approx(expected, abs=1e-9)
    assert robot.total_mass == pytest.approx(expected, abs=1e-9)
    per = {}
    for name, link in robot.links.items():
        if name not in TOKEN_LINKS:
            per[component(name)] = per.get(component(name), 0.0) + link.mass
    assert per == pytest.approx(SEED_MASS, abs=1e-9)
    assert all(robot.links[n].mass == TOKEN_MASS for n in TOKEN_LINKS)


def _solid_inertia(geom, mass):
    """Diagonal of the solid-body inertia of a primitive, in its own frame."""
    if geom.kind == "box":
        x, y, z = geom.size
        return np.array([y * y + z * z, x * x + z * z, x * x + y * y]) * mass / 12
    if geom.kind == "cylinder":
        r, h = geom.radius, geom.length
        side = mass * (3 * r * r + h * h) / 12
        return np.array([side, side, mass * r * r / 2])
    if geom.kind == "sphere":
        return np.full(3, 2 * mass * geom.radius ** 2 / 5)
    raise AssertionError(geom.kind)


def test_every_inertia_is_physical(robot):
    for name, link in robot.links.items():
        assert link.inertial is not None, f"{name} has no inertial"
        ev = np.linalg.eigvalsh(link.inertial.tensor())
        a, b, c = sorted(ev)
        assert a > 0 and a + b >= c * (1 - 1e-9), name
        # radius of gyration no larger than the link's size (or 1 cm for frames)
        assert math.sqrt(c / link.mass) < 0.35, name


def test_primitive_inertias_match_geometry(robot):
    """Links drawn with one primitive: the inertia is the solid body's, about its centre."""
    checked = 0
    for name, link in robot.links.items():
        geoms = [v for v in link.visuals if v.geometry is not None]
        if len(geoms) != 1 or geoms[0].geometry.kind == "mesh":
            continue
        vis = geoms[0]
        R = pose_matrix(vis.origin)[:3, :3]
        expected = R @ np.diag(_solid_inertia(vis.geometry, link.mass)) @ R.T
        # (the seed's rotated visuals use 1.5707 / 1.57 for pi/2: products up to 1e-4 of the diagonal)
        assert np.allclose(link.inertial.tensor(), expected, rtol=1e-3, atol=1e-3 * expected.max()), name
        assert np.allclose(link.inertial.origin.xyz, vis.origin.xyz), name
        checked += 1
    assert checked == 48   # 6 base + 16 structure + 20 arm + webcam lens + 5 sonar emitters


def test_mesh_inertias_match_the_meshes(robot):
    """Mesh links: the generated mesh's solid-body inertia at the declared mass, about its centroid."""
    import trimesh

    mesh_links = 0
    for name, link in robot.links.items():
        meshes = [v for v in link.visuals if v.geometry is not None and v.geometry.kind == "mesh"]
        if not meshes:
            continue
        vis = meshes[0]
        assert vis.geometry.filename.startswith("package://myrabot_description/meshes/")
        assert vis.geometry.scale == (1.0, 1.0, 1.0)
        m = trimesh.load(robot.resolve_uri(vis.geometry.filename), force="mesh")
        assert m.is_watertight and m.is_volume
        com = np.asarray(m.center_mass) + np.asarray(vis.origin.xyz)
        assert np.allclose(link.inertial.origin.xyz, com, atol=1e-6), name
        # inside the geometry's bounding box (in the material for the solid parts)
        lo, hi = m.bounds + np.asarray(vis.origin.xyz)
        assert np.all(lo <= com) and np.all(com <= hi), name
        expected = np.asarray(m.moment_inertia) * link.mass / m.volume
        assert np.allclose(link.inertial.tensor(), expected, rtol=1e-4, atol=1e-10), name
        mesh_links += 1
    assert mesh_links == 11


def test_inertias_use_no_placeholder(robot):
    """The seed gave 0.01/0.001/0.0001 to nearly every link; here no two links of different
    mass or size share a tensor unless they are the same part."""
    values = {}
    for name, link in robot.links.items():
        key = tuple(np.round(np.diag(link.inertial.tensor()), 15))
        values.setdefault(key, set()).add(name.rstrip("0123456789_").split("_link")[0])
    assert not any(k in values for k in [(0.01,) * 3, (0.001,) * 3, (0.0001,) * 3])


# ---------------------------------------------------------------- validators

def test_check_urdf_accepts_built_urdf(built):
    exe = check_urdf_binary()
    if exe is None:
        pytest.skip("check_urdf not installed")
    res = subprocess.run([exe, str(built)], capture_output=True, text=True, timeout=60)
    assert res.returncode == 0, res.stderr
    assert "Successfully Parsed XML" in res.stdout
    assert "root Link: base_footprint" in res.stdout


def test_pinocchio_loads_with_the_arm(robot):
    model = robot.pinocchio()
    # 2 continuous wheels (cos/sin each) + 5 revolute arm joints
    assert (model.nq, model.nv) == (9, 7)
    assert [model.names[i] for i in range(1, model.njoints)] == [
        "left_wheel_joint", "right_wheel_joint", "base", "arti1", "arti2", "arti3", "pinza"]


# ---------------------------------------------------------------- gazebo and resources

def test_one_package_name_everywhere(robot):
    text = robot.urdf_text
    import re

    uris = set(re.findall(r'filename="([^"]+)"', text))
    meshes = {u for u in uris if u.endswith(".stl")}
    assert meshes and all(u.startswith("package://myrabot_description/meshes/") for u in meshes)
    for u in meshes:
        assert robot.resolve_uri(u) is not None and robot.resolve_uri(u).is_file()
    assert "myrabot_fer_modelo" not in text and "myrabot_robot_model" not in text


def test_gazebo_blocks_reference_real_links_and_resolve(robot):
    from myrabot_desc.materials.resolve import MaterialResolver

    assert not [el for el in robot.root_element.iter() if el.tag == "gaezebo"]
    names = set(robot.links) | set(robot.joints)
    res = MaterialResolver([ROOT])
    used = set()
    for g in robot.gazebo:
        assert g.reference is None or g.reference in names, g.reference
        if "material" in g.properties:
            used.add(g.properties["material"])
    unresolved = sorted(m for m in used if res.lookup(m) is None)
    assert not unresolved
    assert {"myrabot/LightWood", "myrabot/Black", "myrabot/White", "brazo/Black", "brazo/White",
            "brazo/WhiteTransparent"} <= used


def test_sensor_parameters(robot):
    sensors = {s.name: s for s in robot.sensors()}
    assert set(sensors) >= {"camera", "webcam", "laser", "wall_sensor"} | {f"ultrasonidos_{i}" for i in range(1, 6)}
    assert sensors["camera"].reference == "camera_link" and sensors["camera"].param("hfov") == "60"
    assert sensors["webcam"].param("hfov") == "63.09"
    assert sensors["laser"].reference == "laser"
    for i in range(1, 6):
        s = sensors[f"ultrasonidos_{i}"]
        assert (s.param("minAngle"), s.param("maxAngle"), s.param("maxRange")) == ("-16", "16", "7")
        (plugin,) = s.plugins
        assert float(plugin.params["fov"]) == pytest.approx(math.radians(32))
        assert plugin.params["frameId"] == f"ultrasonidos_{i}_link"
    for p in robot.plugins():
        assert p.dialect == "electric" and p.file_attr == "plugin", p.name
    drive = next(p for p in robot.plugins() if p.library == "libgazebo_ros_roomba.so")
    wheels = robot.joints["left_wheel_joint"].origin.xyz[1] - robot.joints["right_wheel_joint"].origin.xyz[1]
    assert float(drive.params["wheel_separation"]) == pytest.approx(wheels)
    radius = robot.links["left_wheel_link"].collisions[0].geometry.radius
    assert float(drive.params["wheel_diameter"]) == pytest.approx(2 * radius)


# ---------------------------------------------------------------- objects and layouts

@pytest.mark.parametrize("name, links, mass", [
    ("mesa", 5, 17.0), ("lata_cerveza", 3, 0.012), ("lata_cola", 3, 0.012)])
def test_objects_build(tmp_path, name, links, mass):
    out = tmp_path / f"{name}.urdf"
    res = CliRunner().invoke(cli, ["build", str(ROOT / "xacro" / f"{name}.urdf.xacro"), "-o", str(out)])
    assert res.exit_code == 0, res.output
    obj = load_robot(out)
    assert obj.name == name and len(obj.links) == links and len(obj.joints) == links - 1
    assert obj.total_mass == pytest.approx(mass)
    import pinocchio as pin

    assert pin.computeTotalMass(obj.pinocchio(floating=True)) == pytest.approx(mass)
    exe = check_urdf_binary()
    if exe:
        assert subprocess.run([exe, str(out)], capture_output=True, timeout=60).returncode == 0
    for link in obj.links.values():
        a, b, c = sorted(np.linalg.eigvalsh(link.inertial.tensor()))
        assert a > 0 and a + b >= c


def _top_z(robot):
    T = world_transforms(robot)
    top = 0.0
    for name, link in robot.links.items():
        for c in link.collisions:
            z = (T[name] @ pose_matrix(c.origin))[2, 3]
            g = c.geometry
            half = g.size[2] / 2 if g.kind == "box" else g.length / 2
            top = max(top, z + half)
    return top


def test_object_dimensions():
    mesa = load_robot(ROOT / "xacro" / "mesa.urdf.xacro")
    assert _top_z(mesa) == pytest.approx(0.74)
    assert mesa.links["mesa_link"].visuals[0].geometry.size == (2, 0.75, 0.03)
    for can in ("lata_cerveza", "lata_cola"):
        lata = load_robot(ROOT / "xacro" / f"{can}.urdf.xacro")
        assert _top_z(lata) == pytest.approx(0.12)
        assert {lk.visuals[0].geometry.radius for lk in lata.links.values()} == {0.0325}
    labels = {g.reference: g.properties["material"] for g in load_robot(ROOT / "xacro" / "lata_cola.urdf.xacro").gazebo}
    assert labels["lata_link"] == "myrabot/CocaCola"


@pytest.mark.parametrize("layout, models", [
    ("escoja", ["mesa", "lata_cocacola", "lata_amstel"]),
    ("seguir", ["mesa", "lata_amstel"])])
def test_layouts(layout, models):
    data = yaml.safe_load((ROOT / "layouts" / f"{layout}.yaml").read_text())
    assert data["name"] == layout
    assert data["robot"]["model"] == "MYRAbot"
    assert [o["model"] for o in data["objects"]] == models
    loaded = {}
    for entry in [data["robot"], *data["objects"]]:
        assert set(entry["pose"]) == {"x", "y", "z", "yaw"}
        loaded[entry["model"]] = load_robot(ROOT / entry["file"])
    table = next(o for o in data["objects"] if o["model"] == "mesa")["pose"]
    assert (table["x"], table["y"], table["yaw"]) == (0.55, 0.0, -1.57)
    top = _top_z(loaded["mesa"])
    for o in data["objects"]:
        if o["model"].startswith("lata"):
            p = o["pose"]
            assert p["z"] == pytest.approx(top)  # standing on the table top
            # inside the table (2 x 0.75 turned by -1.57 about (0.55, 0))
            c, s = math.cos(-table["yaw"]), math.sin(-table["yaw"])
            lx, ly = c * (p["x"] - table["x"]) - s * (p["y"] - table["y"]), s * (p["x"] - table["x"]) + c * (p["y"] - table["y"])
            assert abs(lx) < 1.0 - 0.0325 and abs(ly) < 0.375 - 0.0325
    if layout == "escoja":
        poses = {o["model"]: (o["pose"]["x"], o["pose"]["y"], o["pose"]["z"]) for o in data["objects"]}
        assert poses["lata_cocacola"] == (0.38, -0.18, 0.74) and poses["lata_amstel"] == (0.38, 0.17, 0.74)
    else:
        assert (data["objects"][1]["pose"]["x"], data["objects"][1]["pose"]["y"]) == (0.5, 0.0)


# ---------------------------------------------------------------- generated assets

def test_assets_regenerate_identically(tmp_path):
    """`python -m tools.make_meshes` is deterministic and the committed files are its output."""
    res = subprocess.run([sys.executable, "-m", "tools.make_meshes", "--root", str(tmp_path)],
                         capture_output=True, text=True, timeout=120)
    assert res.returncode == 0, res.stderr
    written = sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*") if p.is_file())
    assert len(written) == 11 + 1 + 3
    for rel in written:
        assert (tmp_path / rel).read_bytes() == (ROOT / rel).read_bytes(), f"{rel} differs from a fresh generation"


# arm-facts.md §9.2 bounding boxes (mm, the seed files' own coordinates) and the kinect.dae's (m)
SEED_BBOX_MM = {
    "e_base_brazo_1": ((80, 3, 0), (190, 165, 75)),
    "e_base_brazo_2": ((95, 3, 35), (175, 83, 39)),
    "e_base_kinect": ((87.5, 80, 0), (182.5, 165, 60)),
    "e_monitor": ((0, 95, 0), (270, 130, 185)),
    "e_pilar": ((55, 165, 0), (215, 270, 700)),
    "e_soporte_1": ((127.5, 170, 0), (142.5, 230, 640)),
    "e_soporte_2": ((132.5, 130, 0), (137.5, 230, 60)),
    "e_ultrasonidos": ((0.122, 44.778, 0), (319.878, 294.608, 40)),
    "webcam_1": ((134, 79.5, 40.83), (191, 169.55, 101.5)),
    "webcam_2": ((115, 53.4, 77.026), (204.899, 89, 116.974)),
    "kinect": ((-68, -138, -53), (6, 138, 19)),
}


@pytest.mark.parametrize("name", sorted(SEED_BBOX_MM))
def test_meshes_are_metres_in_seed_coordinates(name):
    import trimesh

    m = trimesh.load(ROOT / "meshes" / f"{name}.stl", force="mesh")
    assert m.is_watertight and m.is_volume
    lo, hi = (np.array(v) / 1000 for v in SEED_BBOX_MM[name])
    # within 0.5 mm (the sonar ring is a 96-segment arc)
    assert np.allclose(m.bounds, [lo, hi], atol=5e-4), m.bounds.tolist()
    assert (ROOT / "meshes" / f"{name}.stl").read_bytes()[:5] != b"solid"  # binary STL


def test_sonar_ring_leaves_the_sonars_clear(robot):
    """The ring mesh has a hole at each sonar: no ray origin lies inside it."""
    import trimesh

    T = world_transforms(robot)
    link = robot.links["e_ultrasonidos_link"]
    vis = link.visuals[0]
    ring = trimesh.load(robot.resolve_uri(vis.geometry.filename), force="mesh")
    ring.apply_transform(T["e_ultrasonidos_link"] @ pose_matrix(vis.origin))
    for i in range(1, 6):
        origin = T[f"ultrasonidos_{i}_link"][:3, 3]
        ahead = origin + 0.01 * T[f"ultrasonidos_{i}_link"][:3, 0]
        assert not ring.contains([origin, ahead]).any(), i
    # and the ring sits on the upper plate, centred on it
    centre = ring.bounds.mean(axis=0)
    assert abs(ring.bounds[:, 0].mean()) < 0.2 and abs(centre[1]) < 0.002


def test_check_finds_only_the_kept_seed_quirks():
    """`myrabot-desc check` on the bundled robot: no errors; the warnings are the seed's
    quirks docs/model.md keeps on purpose (seed masses I008, fixed castor joints G004,
    sonar minRange 0 S005), and none of what the fixes removed (e.g. S004: a sensor on a
    massless link)."""
    import json

    res = CliRunner().invoke(cli, ["check", "--format", "json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.output)
    (report,) = doc["files"]
    assert report["counts"]["error"] == 0
    codes = {d["code"] for d in report["diagnostics"] if d["severity"] != "info"}
    assert codes <= {"G004", "I008", "S005"}, codes
    flagged = {d["data"].get("link") for d in report["diagnostics"] if d["code"] == "I008"}
    # only seed-declared masses are implausible, never an inertia or a frame of ours
    assert flagged and all(robot_link in SEED_DENSITY_FLAGGED for robot_link in flagged)


# links whose declared (seed) mass is far too light for their size
SEED_DENSITY_FLAGGED = {"e_base_1_link", "e_base_2_link", "e_botonera_link", "e_pantalla_link", "rear_wheel_link",
                        "brazo_link_B", "antebrazo_link_B", "muneca_link_B", "base_footprint"}
