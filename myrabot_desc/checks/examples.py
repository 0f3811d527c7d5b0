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


# A diff-drive base driven by ros2_control: the example wheels (y ±0.15, radius 0.08), their
# velocity interfaces, and a gz ros2_control plugin naming the controllers file (CONTROLLERS).
_ROS2_CONTROL = """<ros2_control name="base" type="system">
  <hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
  <joint name="left_wheel_joint"><command_interface name="velocity"/><state_interface name="velocity"/></joint>
  <joint name="right_wheel_joint"><command_interface name="velocity"/><state_interface name="velocity"/></joint>
</ros2_control>
<gazebo>
  <plugin filename="gz_ros2_control-system" name="gz_ros2_control::GazeboSimROS2ControlPlugin">
    <parameters>{yaml}</parameters>
  </plugin>
</gazebo>"""
CONTROLLERS = """controller_manager:
  ros__parameters:
    diff_drive_base_controller:
      type: diff_drive_controller/DiffDriveController
diff_drive_base_controller:
  ros__parameters:
    left_wheel_names: [left_wheel_joint]
    right_wheel_names: [right_wheel_joint]
    wheel_separation: {sep}
    wheel_radius: {radius}
    wheel_separation_multiplier: {mult}
"""


def ros2_control_example(yaml="controllers.yaml") -> str:
    return "\n".join([_WHEEL.format(side="left", x="0", y="0.15", z="0.08", jtype="continuous", axis="0 1 0"),
                      _WHEEL.format(side="right", x="0", y="-0.15", z="0.08", jtype="continuous", axis="0 1 0"),
                      _CASTER, _ROS2_CONTROL.format(yaml=yaml)])


def controllers_yaml(sep="0.3", radius="0.08", mult="1.0", name="controllers.yaml") -> dict:
    return {name: CONTROLLERS.format(sep=sep, radius=radius, mult=mult)}


# A car-like base: front wheels on steering hinges (revolute about z, ±0.5 rad) 0.5 m ahead of the
# rear axle, tracks 0.4 m, wheels of radius 0.1 m, driven by gz-sim's AckermannSteering.
_CAR_WHEEL = """<link name="{name}_wheel">
  <inertial>
    <mass value="1"/>
    <inertia ixx="0.003" ixy="0" ixz="0" iyy="0.005" iyz="0" izz="0.003"/>
  </inertial>
  <collision>
    <origin rpy="1.5708 0 0"/>
    <geometry><cylinder radius="0.1" length="0.05"/></geometry>
  </collision>
</link>
<joint name="{name}_wheel_joint" type="continuous">
  <origin xyz="{xyz}"/>
  <parent link="{parent}"/>
  <child link="{name}_wheel"/>
  <axis xyz="0 1 0"/>
</joint>"""
_HINGE = """<link name="{side}_steering">
  <inertial>
    <mass value="0.2"/>
    <inertia ixx="0.0001" ixy="0" ixz="0" iyy="0.0001" iyz="0" izz="0.0001"/>
  </inertial>
</link>
<joint name="{side}_steering_joint" type="revolute">
  <origin xyz="0.5 {y} 0.1"/>
  <parent link="base_link"/>
  <child link="{side}_steering"/>
  <axis xyz="0 0 1"/>
  <limit lower="-0.5" upper="0.5" effort="10" velocity="2"/>
</joint>"""
_ACKERMANN = """<gazebo>
  <plugin filename="gz-sim-ackermann-steering-system" name="gz::sim::systems::AckermannSteering">
    <left_joint>front_left_wheel_joint</left_joint>
    <left_joint>rear_left_wheel_joint</left_joint>
    <right_joint>front_right_wheel_joint</right_joint>
    <right_joint>rear_right_wheel_joint</right_joint>
    <left_steering_joint>left_steering_joint</left_steering_joint>
    <right_steering_joint>right_steering_joint</right_steering_joint>
    <kingpin_width>0.4</kingpin_width>
    <steering_limit>{limit}</steering_limit>
    <wheel_base>{base}</wheel_base>
    <wheel_separation>0.4</wheel_separation>
    <wheel_radius>0.1</wheel_radius>
  </plugin>
</gazebo>"""


def ackermann_example(base="0.5", limit="0.5") -> str:
    parts = [_HINGE.format(side="left", y="0.2"), _HINGE.format(side="right", y="-0.2")]
    for name, xyz, parent in (("front_left", "0 0 0", "left_steering"), ("front_right", "0 0 0", "right_steering"),
                              ("rear_left", "0 0.2 0.1", "base_link"), ("rear_right", "0 -0.2 0.1", "base_link")):
        parts.append(_CAR_WHEEL.format(name=name, xyz=xyz, parent=parent))
    return "\n".join(parts + [_ACKERMANN.format(base=base, limit=limit)])


# A mecanum base: four wheels of radius 0.05 m at (±0.2, ±0.2), driven by gz-sim's MecanumDrive;
# with ``rollers`` each wheel's contact grips only along a diagonal (mu 1 along fdir1, mu2 0), as
# gz-sim's mecanum example sets it: FL and RR along (1 -1 0), FR and RL along (1 1 0).
_MECANUM_FRICTION = """<gazebo reference="{name}_wheel">
  <collision><surface><friction><ode>
    <mu>1</mu>
    <mu2>0</mu2>
    <fdir1 gz:expressed_in="base_link" xmlns:gz="http://gazebosim.org/schema">{fdir}</fdir1>
  </ode></friction></surface></collision>
</gazebo>"""
_MECANUM_DRIVE = """<gazebo>
  <plugin filename="gz-sim-mecanum-drive-system" name="gz::sim::systems::MecanumDrive">
    <front_left_joint>front_left_wheel_joint</front_left_joint>
    <front_right_joint>front_right_wheel_joint</front_right_joint>
    <back_left_joint>rear_left_wheel_joint</back_left_joint>
    <back_right_joint>rear_right_wheel_joint</back_right_joint>
    <wheel_separation>0.4</wheel_separation>
    <wheelbase>0.4</wheelbase>
    <wheel_radius>0.05</wheel_radius>
  </plugin>
</gazebo>"""


def mecanum_example(rollers=True) -> str:
    parts = []
    for name, x, y, fdir in (("front_left", "0.2", "0.2", "1 -1 0"), ("front_right", "0.2", "-0.2", "1 1 0"),
                             ("rear_left", "-0.2", "0.2", "1 1 0"), ("rear_right", "-0.2", "-0.2", "1 -1 0")):
        parts.append(_CAR_WHEEL.format(name=name, xyz=f"{x} {y} 0.05", parent="base_link")
                     .replace('radius="0.1"', 'radius="0.05"'))
        if rollers:
            parts.append(_MECANUM_FRICTION.format(name=name, fdir=fdir))
    return "\n".join(parts + [_MECANUM_DRIVE])
