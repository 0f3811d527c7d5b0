"""Snippets the rule examples share (see checks/rule.py): a small diff-drive base, an Electric-era
controller, ASCII STL meshes. They are documentation data; no rule reads them."""

from __future__ import annotations

# Example snippets (placed in checks.rule.TEMPLATE, whose only link is base_link): a diff-drive
# base with wheels of radius 0.08 m at y ±0.15 and a caster, standing on base_link's origin (z 0);
# the ROS 1 plugin's numbers match it.
_WHEEL = """<link name="{side}_wheel">
  <inertial>
    <mass value="0.5"/>
    <inertia ixx="0.00087" ixy="0" ixz="0" iyy="0.00087" iyz="0" izz="0.0016"/>
  </inertial>
  <collision>
    <origin rpy="1.5708 0 0"/>
    <geometry><cylinder radius="0.08" length="0.04"/></geometry>
  </collision>
</link>
<joint name="{side}_wheel_joint" type="{jtype}">
  <origin xyz="{x} {y} {z}"/>
  <parent link="base_link"/>
  <child link="{side}_wheel"/>
  <axis xyz="{axis}"/>
</joint>"""
_CASTER = """<link name="caster">
  <inertial>
    <mass value="0.1"/>
    <inertia ixx="6.4e-05" ixy="0" ixz="0" iyy="6.4e-05" iyz="0" izz="6.4e-05"/>
  </inertial>
  <collision><geometry><sphere radius="0.04"/></geometry></collision>
</link>
<joint name="caster_joint" type="fixed">
  <origin xyz="-0.12 0 0.04"/>
  <parent link="base_link"/>
  <child link="caster"/>
</joint>"""
_PLUGIN = """<gazebo>
  <plugin name="diff_drive" filename="libgazebo_ros_diff_drive.so">
    <legacyMode>false</legacyMode>
    <leftJoint>{left}</leftJoint>
    <rightJoint>right_wheel_joint</rightJoint>
    <wheelSeparation>{sep}</wheelSeparation>
    <wheelDiameter>{dia}</wheelDiameter>
    <wheelTorque>5</wheelTorque>{extra}
    <commandTopic>cmd_vel</commandTopic>
    <odometryTopic>odom</odometryTopic>
    <odometryFrame>odom</odometryFrame>
    <robotBaseFrame>base_link</robotBaseFrame>
  </plugin>
</gazebo>"""


def drive_example(sep="0.3", dia="0.16", left="left_wheel_joint", jtype="continuous", axis="0 1 0", extra="",
           z="0.08", caster=True, x="0"):
    extra = "".join(f"\n    {line}" for line in extra.splitlines())
    return "\n".join([_WHEEL.format(side="left", x=x, y="0.15", z=z, jtype=jtype, axis=axis),
                      _WHEEL.format(side="right", x=x, y="-0.15", z=z, jtype="continuous", axis="0 1 0"),
                      *([_CASTER] if caster else []), _PLUGIN.format(left=left, sep=sep, dia=dia, extra=extra)])


ELECTRIC_IMU = """<?xml version="1.0"?>
<robot name="example" xmlns:controller="http://playerstage.sourceforge.net/gazebo/xmlschema/#controller"
       xmlns:interface="http://playerstage.sourceforge.net/gazebo/xmlschema/#interface">
  <link name="base_link">
    <inertial>
      <mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>
    </inertial>
  </link>
  <gazebo>
    <controller:gazebo_ros_imu name="imu_controller" {attr}="libgazebo_ros_imu.so">
      <alwaysOn>true</alwaysOn>
      <updateRate>50</updateRate>
      <bodyName>base_link</bodyName>
      <topicName>imu/data</topicName>
      <interface:position name="imu_position"/>
    </controller:gazebo_ros_imu>
  </gazebo>
</robot>
"""
MODERN_IMU = """<gazebo>
  <plugin name="imu_controller" filename="libgazebo_ros_imu.so">
    <updateRate>50</updateRate>
    <bodyName>base_link</bodyName>
    <topicName>imu/data</topicName>
  </plugin>
</gazebo>"""


def tetrahedron_stl(size: float, flipped: bool = False, open_: bool = False) -> str:
    """An ASCII STL tetrahedron with corners at the origin and on the three axes at ``size`` m, for
    mesh examples: faces wound outward, or inward (``flipped``), or with the slanted face missing
    (``open_``, not watertight)."""
    s = size
    faces = [((0, 0, 0), (0, s, 0), (s, 0, 0)), ((0, 0, 0), (s, 0, 0), (0, 0, s)),
             ((0, 0, 0), (0, 0, s), (0, s, 0)), ((s, 0, 0), (0, s, 0), (0, 0, s))]
    if open_:
        faces = faces[:3]
    if flipped:
        faces = [f[::-1] for f in faces]
    out = ["solid tetrahedron"]
    for f in faces:
        out += ["  facet normal 0 0 0", "    outer loop"]
        out += [f"      vertex {x:g} {y:g} {z:g}" for x, y, z in f]
        out += ["    endloop", "  endfacet"]
    return "\n".join(out + ["endsolid tetrahedron", ""])
