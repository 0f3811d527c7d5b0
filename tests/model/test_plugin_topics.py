"""One home for a plugin's topic names (model/plugins.py): check's G010 and convert's gz-sim
sensors and drive systems name the same topics."""

from __future__ import annotations


import pytest
from click.testing import CliRunner
from lxml import etree

from helpers import CORPUS, corpus_args, corpus_env, corpus_robot
from myrabot_desc.checks import run_checks
from myrabot_desc.commands.main import main
from myrabot_desc.model import plugins as P
from myrabot_desc.model.loader import load_robot



def _sdf_topics(tmp_path, *args, env=None) -> dict:
    """sensor name -> <topic> in `convert --to sdf` output; plugin filename -> <topic> for systems."""
    out = tmp_path / "m.sdf"
    r = CliRunner().invoke(main, ["convert", *args, "-o", str(out)], env=env)
    assert r.exit_code == 0, r.output
    root = etree.parse(str(out)).getroot()
    got = {s.get("name"): s.findtext("topic") for s in root.iter("sensor")}
    got.update({p.get("filename"): p.findtext("topic") for p in root.iter("plugin") if p.find("topic") is not None})
    return got


def _agree(robot, topics):
    """Every sensor plugin's topic is the converted sensor's, and check's G010 sees it absolute."""
    n = 0
    for s in robot.sensors():
        for p in s.plugins[:1]:
            t = P.sensor_topic(p)
            if t is None or s.dialect == "electric" and P.kind(p) in P.CAMERA_KINDS:
                continue          # Electric cameras become rgbd/plain cameras named after cameraName
            assert topics[s.name] == t, s.name
            absolute = t if t.startswith("/") else "/" + t
            assert absolute in [full for full, _ in P.published_topics(p)], (s.name, t)
            n += 1
    return n


def test_bundled_lasers_and_sonars(tmp_path):
    robot = load_robot()
    topics = _sdf_topics(tmp_path)
    assert _agree(robot, topics) == 6                  # the Hokuyo and five sonars
    assert topics["laser"] == "scan" and topics["ultrasonidos_3"] == "ultrasonidos_3"
    assert "G010" not in {d.code for d in run_checks(robot)}


@pytest.mark.corpus
def test_husky_lasers_under_the_root_namespace(tmp_path):
    """robotNamespace "/" is no namespace: topicName front/scan stays relative in SDF (gz-sim
    qualifies it to /front/scan, as ROS resolved it), and check sees /front/scan."""
    r = corpus_robot("husky_lasers")
    env = corpus_env(r)
    args = corpus_args(r)
    with pytest.MonkeyPatch.context() as mp:
        for k, v in env.items():
            mp.setenv(k, v)
        robot = load_robot(CORPUS / r["top"], package_paths=[CORPUS])
    topics = _sdf_topics(tmp_path, *args, env=env)
    assert _agree(robot, topics) == 2
    assert (topics["front_laser"], topics["rear_laser"]) == ("front/scan", "rear/scan")


def _robot(tmp_path, gazebo: str):
    p = tmp_path / "r.urdf"
    p.write_text('<robot name="r"><link name="base"/><link name="cam"/><joint name="j" type="fixed">'
                 f'<parent link="base"/><child link="cam"/></joint>{gazebo}</robot>')
    return load_robot(p)


def test_namespaces_cameras_and_remaps(tmp_path):
    robot = _robot(tmp_path, """
<gazebo reference="cam"><sensor name="c1" type="camera"><camera><image><width>64</width><height>48</height></image>
</camera><plugin name="c1p" filename="libgazebo_ros_camera.so"><robotNamespace>r1</robotNamespace>
<cameraName>front</cameraName><imageTopicName>image_raw</imageTopicName>
<cameraInfoTopicName>camera_info</cameraInfoTopicName></plugin></sensor></gazebo>
<gazebo reference="cam"><sensor name="l1" type="ray"><plugin name="l1p" filename="libgazebo_ros_ray_sensor.so">
<ros><namespace>/demo</namespace><remapping>~/out:=scan</remapping></ros></plugin></sensor></gazebo>
<gazebo reference="cam"><sensor name="l2" type="ray"><plugin name="l2p" filename="libgazebo_ros_laser.so">
<robotNamespace>r1</robotNamespace><topicName>/abs_scan</topicName></plugin></sensor></gazebo>
<gazebo><plugin name="imu" filename="libgazebo_ros_imu.so"><robotNamespace>/</robotNamespace>
<bodyName>cam</bodyName></plugin></gazebo>""")
    by = {p.name: p for p in robot.plugins()}
    assert P.sensor_topic(by["c1p"]) == "r1/front/image_raw"
    assert P.published_topics(by["c1p"]) == [("/r1/front/image_raw", "imageTopicName"),
                                              ("/r1/front/camera_info", "cameraInfoTopicName")]
    assert P.sensor_topic(by["l1p"]) == "/demo/scan"              # ROS 2 remapping under its namespace
    assert P.sensor_topic(by["l2p"]) == "/abs_scan"               # an absolute name ignores the namespace
    assert P.published_topics(by["l2p"]) == [("/abs_scan", "topicName")]
    assert P.namespace(by["imu"]) == "" and P.sensor_topic(by["imu"], default="imu") == "imu"
    topics = _sdf_topics(tmp_path, str(tmp_path / "r.urdf"))
    assert (topics["c1"], topics["l1"], topics["l2"], topics["imu"]) == \
        ("r1/front/image_raw", "/demo/scan", "/abs_scan", "imu")


def test_two_lasers_on_one_resolved_topic_is_g010(tmp_path):
    """scan under namespace r1 and /r1/scan are one topic for check, as they are for convert."""
    robot = _robot(tmp_path, """
<gazebo reference="cam"><sensor name="a" type="ray"><plugin name="pa" filename="libgazebo_ros_laser.so">
<robotNamespace>/r1/</robotNamespace><topicName>scan</topicName></plugin></sensor></gazebo>
<gazebo reference="base"><sensor name="b" type="ray"><plugin name="pb" filename="libgazebo_ros_laser.so">
<topicName>/r1/scan</topicName></plugin></sensor></gazebo>""")
    assert [P.sensor_topic(p) for p in robot.plugins()] == ["/r1/scan", "/r1/scan"]
    g010 = [d for d in run_checks(robot) if d.code == "G010"]
    assert len(g010) == 1 and g010[0].data["topic"] == "/r1/scan"


def test_resolve():
    assert P.resolve(None, "ns") is None and P.resolve("", "ns") is None
    assert P.resolve("scan") == "scan"
    assert P.resolve("scan", "", "cam") == "cam/scan"
    assert P.resolve("scan", "/ns/", "cam") == "/ns/cam/scan"
    assert P.resolve("/scan", "/ns", "cam") == "/scan"


def test_ros2_remapped_lasers_collide_but_a_ring_of_sonars_does_not(tmp_path):
    """G010 reads a ROS 2 ray sensor's ~/out remapping (the topic convert carries over): two
    lasers remapped to one topic collide; Range sensors sharing one topic are a design."""
    laser = ('<gazebo reference="{link}"><sensor name="{n}" type="ray"><plugin name="{n}p" '
             'filename="libgazebo_ros_ray_sensor.so"><ros><namespace>/r</namespace><remapping>~/out:={topic}'
             '</remapping></ros><output_type>sensor_msgs/{out}</output_type></plugin></sensor></gazebo>')
    robot = _robot(tmp_path, laser.format(link="cam", n="front", topic="scan", out="LaserScan")
                   + laser.format(link="base", n="rear", topic="scan", out="LaserScan")
                   + "".join(laser.format(link="base", n=f"sonar{i}", topic="sonar_base", out="Range")
                             for i in range(3)))
    by = {p.name: p for p in robot.plugins()}
    assert P.published_topics(by["frontp"]) == [("/r/scan", "remapping ~/out")]
    assert P.sensor_topic(by["frontp"]) == "/r/scan"                    # convert's answer, the same topic
    assert [P.publishes_ranges(by[f"sonar{i}p"]) for i in range(3)] == [True] * 3
    assert not P.publishes_ranges(by["frontp"])
    g010 = [d for d in run_checks(robot) if d.code == "G010"]
    assert [d.data["topic"] for d in g010] == ["/r/scan"]
    assert g010[0].data["publishers"] == ["frontp (remapping ~/out)", "rearp (remapping ~/out)"]


@pytest.mark.corpus
def test_tiago_sonars_share_a_topic_without_g010():
    """TIAGo (ROS 2): its base laser, IMU and three sonars are found by their remappings; the
    sonars share /sonar_base by design, so G010 stays quiet."""
    robot = load_robot(CORPUS / "tiago_description/robots/tiago.urdf.xacro", package_paths=[CORPUS])
    found = {p.name: P.published_topics(p) for p in robot.plugins() if P.published_topics(p)}
    assert found["base_laser"] == [("/scan_raw", "remapping ~/out")]
    assert found["base_imu"] == [("/base_imu", "remapping ~/out")]
    sonars = [n for n, t in found.items() if t == [("/sonar_base", "remapping ~/out")]]
    assert len(sonars) == 3
    assert "G010" not in {d.code for d in run_checks(robot)}
