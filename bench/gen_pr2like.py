"""Generate a synthetic PR2-sized robot description as a multi-file xacro package.

    python bench/gen_pr2like.py OUTDIR        # writes OUTDIR/pr2like_description/...; prints the top file

There is no PR2 xacro offline, so this stands in for it in the benchmarks: the
same size (99 links; 135 <joint> elements = 98 joints + 37 transmission joint
references; about 146 kB of URDF) and the same xacro features the real PR2
description uses: a package with includes in several files, properties and
math (pi, trig, radians, products of properties), macros nested three deep,
``reflect``/``side`` parameters for left/right copies, single (``*origin``) and
multi (``**inertial``) block parameters, ``xacro:if``/``unless``, ``xacro:arg``,
comments in front of macro calls, transmissions and Gazebo blocks with sensors
and plugins. It is synthetic: the numbers are plausible, not PR2's.
"""

from __future__ import annotations

import sys
from pathlib import Path

NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
PKG = "pr2like_description"

COMMON = f"""<?xml version="1.0"?>
<robot {NS}>
  <!-- shared constants, materials and inertia helpers -->
  <xacro:property name="M_PI" value="3.1415926535897931"/>
  <xacro:property name="caster_offset_x" value="0.2246"/>
  <xacro:property name="caster_offset_y" value="0.2246"/>
  <xacro:property name="wheel_offset_y" value="0.049"/>
  <xacro:property name="wheel_radius" value="0.074792"/>
  <xacro:property name="wheel_length" value="0.034"/>
  <xacro:property name="shoulder_offset_y" value="0.188"/>
  <xacro:property name="upper_arm_len" value="0.4"/>
  <xacro:property name="forearm_len" value="0.321"/>
  <xacro:property name="finger_len" value="0.09137"/>
  <xacro:property name="cal" value="${{[0.0, 0.0]}}"/>
  <material name="Grey"><color rgba="0.7 0.7 0.7 1.0"/></material>
  <material name="DarkGrey"><color rgba="0.3 0.3 0.3 1.0"/></material>
  <material name="Blue"><color rgba="0.0 0.0 0.8 1.0"/></material>
  <material name="Green"><color rgba="0.0 0.8 0.0 1.0"/></material>
  <material name="Red"><color rgba="0.8 0.0 0.0 1.0"/></material>
  <material name="White"><color rgba="1.0 1.0 1.0 1.0"/></material>
  <material name="Black"><color rgba="0.05 0.05 0.05 1.0"/></material>

  <xacro:macro name="box_inertial" params="m x y z *origin">
    <inertial>
      <mass value="${{m}}"/>
      <xacro:insert_block name="origin"/>
      <inertia ixx="${{m*(y*y+z*z)/12}}" ixy="0.0" ixz="0.0" iyy="${{m*(x*x+z*z)/12}}" iyz="0.0"
               izz="${{m*(x*x+y*y)/12}}"/>
    </inertial>
  </xacro:macro>

  <xacro:macro name="cyl_inertial" params="m r l">
    <inertial>
      <mass value="${{m}}"/>
      <origin xyz="0 0 0" rpy="0 0 0"/>
      <inertia ixx="${{m*(3*r*r+l*l)/12}}" ixy="0.0" ixz="0.0" iyy="${{m*(3*r*r+l*l)/12}}" iyz="0.0"
               izz="${{m*r*r/2}}"/>
    </inertial>
  </xacro:macro>

  <!-- a part: link with multi-block inertial, mesh visual and box/mesh collision -->
  <xacro:macro name="part" params="name mesh color:=Grey **inertial">
    <link name="${{name}}">
      <xacro:insert_block name="inertial"/>
      <visual name="${{name}}_visual">
        <origin xyz="0 0 0" rpy="0 0 0"/>
        <geometry>
          <mesh filename="package://{PKG}/meshes/${{mesh}}.dae"/>
        </geometry>
        <material name="${{color}}"/>
      </visual>
      <collision name="${{name}}_collision">
        <origin xyz="0 0 0" rpy="0 0 0"/>
        <geometry>
          <mesh filename="package://{PKG}/meshes/${{mesh}}.stl"/>
        </geometry>
      </collision>
    </link>
    <gazebo reference="${{name}}">
      <material>Gazebo/${{color}}</material>
      <mu1>0.9</mu1>
      <mu2>0.9</mu2>
      <kp>1000000.0</kp>
      <kd>1.0</kd>
      <minDepth>0.001</minDepth>
      <maxVel>100.0</maxVel>
      <maxContacts>10</maxContacts>
      <selfCollide>false</selfCollide>
      <dampingFactor>0.01</dampingFactor>
      <laserRetro>0</laserRetro>
      <fdir1>0 0 0</fdir1>
      <slip1>0.0</slip1>
      <slip2>0.0</slip2>
      <gravity>true</gravity>
      <turnGravityOff>false</turnGravityOff>
    </gazebo>
  </xacro:macro>

  <xacro:macro name="frame" params="name parent *origin">
    <link name="${{name}}"/>
    <joint name="${{name}}_joint" type="fixed">
      <xacro:insert_block name="origin"/>
      <parent link="${{parent}}"/>
      <child link="${{name}}"/>
    </joint>
  </xacro:macro>

  <xacro:macro name="trans" params="joint reduction">
    <transmission name="${{joint}}_trans">
      <type>transmission_interface/SimpleTransmission</type>
      <pr2_type>pr2_mechanism_model/SimpleTransmission</pr2_type>
      <joint name="${{joint}}">
        <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
      </joint>
      <actuator name="${{joint}}_motor">
        <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        <mechanicalReduction>${{reduction}}</mechanicalReduction>
        <motorTorqueConstant>${{0.0418 * 1}}</motorTorqueConstant>
        <maxMotorCurrent>${{fabs(reduction) * 0.1}}</maxMotorCurrent>
      </actuator>
      <compensator k_belt="4000.0" kd_motor="10.0" lambda_combined="0.0" lambda_joint="60.0" lambda_motor="60.0"
                   mass_motor="0.05"/>
      <simulated_actuated_joint name="${{joint}}_sim" passive_actuated_joint="${{joint}}_passive"
                                simulated_reduction="${{fabs(reduction) * 50}}"/>
    </transmission>
  </xacro:macro>

  <xacro:macro name="revolute" params="name parent child axis lower upper effort velocity *origin">
    <joint name="${{name}}" type="revolute">
      <axis xyz="${{axis}}"/>
      <limit lower="${{lower}}" upper="${{upper}}" effort="${{effort}}" velocity="${{velocity}}"/>
      <safety_controller k_position="100" k_velocity="10" soft_lower_limit="${{lower+0.15}}"
                         soft_upper_limit="${{upper-0.15}}"/>
      <calibration rising="${{cal[1]}}"/>
      <dynamics damping="1.0"/>
      <xacro:insert_block name="origin"/>
      <parent link="${{parent}}"/>
      <child link="${{child}}"/>
    </joint>
    <xacro:trans joint="${{name}}" reduction="${{-1.0 * 60.0}}"/>
    <gazebo reference="${{name}}">
      <implicitSpringDamper>1</implicitSpringDamper>
      <provideFeedback>true</provideFeedback>
      <stopKd>1000000.0</stopKd>
      <stopKp>1000000.0</stopKp>
      <cfmDamping>true</cfmDamping>
      <fudgeFactor>1.0</fudgeFactor>
    </gazebo>
  </xacro:macro>

  <xacro:macro name="continuous" params="name parent child axis:='0 0 1' velocity:=10 *origin">
    <joint name="${{name}}" type="continuous">
      <axis xyz="${{axis}}"/>
      <limit effort="30" velocity="${{velocity}}"/>
      <dynamics damping="0.1"/>
      <xacro:insert_block name="origin"/>
      <parent link="${{parent}}"/>
      <child link="${{child}}"/>
    </joint>
    <xacro:trans joint="${{name}}" reduction="${{79.2}}"/>
  </xacro:macro>
</robot>
"""

BASE = f"""<?xml version="1.0"?>
<robot {NS}>
  <xacro:macro name="wheel" params="suffix parent reflect">
    <xacro:part name="${{parent}}_${{suffix}}_wheel_link" mesh="base_v0/wheel" color="DarkGrey">
      <xacro:cyl_inertial m="0.44036" r="${{wheel_radius}}" l="${{wheel_length}}"/>
    </xacro:part>
    <xacro:continuous name="${{parent}}_${{suffix}}_wheel_joint" parent="${{parent}}_rotation_link"
                      child="${{parent}}_${{suffix}}_wheel_link" axis="0 1 0">
      <origin xyz="0 ${{reflect*wheel_offset_y}} 0" rpy="0 0 0"/>
    </xacro:continuous>
  </xacro:macro>

  <!-- caster: rotation link and two wheels; reflect params place the four copies -->
  <xacro:macro name="caster" params="suffix parent *origin ref_position">
    <xacro:part name="${{suffix}}_caster_rotation_link" mesh="base_v0/caster">
      <inertial>
        <mass value="3.473082"/>
        <origin xyz="0 0 0.07" rpy="0 0 0"/>
        <inertia ixx="0.012411765597" ixy="-0.000711733678" ixz="0.00050272983"
                 iyy="0.015218160428" iyz="-0.000004273467" izz="0.011763977943"/>
      </inertial>
    </xacro:part>
    <xacro:continuous name="${{suffix}}_caster_rotation_joint" parent="${{parent}}"
                      child="${{suffix}}_caster_rotation_link">
      <xacro:insert_block name="origin"/>
    </xacro:continuous>
    <xacro:wheel suffix="l" parent="${{suffix}}_caster" reflect="1"/>
    <xacro:wheel suffix="r" parent="${{suffix}}_caster" reflect="-1"/>
  </xacro:macro>

  <xacro:macro name="base" params="name">
    <xacro:part name="${{name}}_link" mesh="base_v0/base" color="Green">
      <inertial>
        <mass value="116.0"/>
        <origin xyz="-0.061 0.0 0.1465" rpy="0 0 0"/>
        <inertia ixx="5.652232699207" ixy="-0.009719934438" ixz="1.293988226423"
                 iyy="5.669473158652" iyz="-0.007379583694" izz="3.683196351726"/>
      </inertial>
    </xacro:part>
    <xacro:part name="${{name}}_bellow_link" mesh="base_v0/bellow" color="Black">
      <xacro:box_inertial m="1.0" x="0.05" y="0.37" z="0.3"><origin xyz="0 0 0"/></xacro:box_inertial>
    </xacro:part>
    <joint name="${{name}}_bellow_joint" type="fixed">
      <origin xyz="-0.29 0 0.8" rpy="0 0 0"/>
      <parent link="${{name}}_link"/>
      <child link="${{name}}_bellow_link"/>
    </joint>
    <xacro:frame name="${{name}}_footprint" parent="${{name}}_link">
      <origin xyz="0 0 -0.051" rpy="0 0 0"/>
    </xacro:frame>
    <xacro:caster suffix="fl" parent="${{name}}_link" ref_position="0">
      <origin xyz="${{caster_offset_x}} ${{caster_offset_y}} 0.0282" rpy="0 0 0"/>
    </xacro:caster>
    <xacro:caster suffix="fr" parent="${{name}}_link" ref_position="0">
      <origin xyz="${{caster_offset_x}} ${{-caster_offset_y}} 0.0282" rpy="0 0 0"/>
    </xacro:caster>
    <xacro:caster suffix="bl" parent="${{name}}_link" ref_position="${{M_PI}}">
      <origin xyz="${{-caster_offset_x}} ${{caster_offset_y}} 0.0282" rpy="0 0 0"/>
    </xacro:caster>
    <xacro:caster suffix="br" parent="${{name}}_link" ref_position="${{M_PI}}">
      <origin xyz="${{-caster_offset_x}} ${{-caster_offset_y}} 0.0282" rpy="0 0 0"/>
    </xacro:caster>
    <xacro:part name="${{name}}_laser_link" mesh="sensors/hokuyo" color="Blue">
      <xacro:box_inertial m="0.16" x="0.05" y="0.05" z="0.07"><origin xyz="0 0 0"/></xacro:box_inertial>
    </xacro:part>
    <joint name="${{name}}_laser_joint" type="fixed">
      <origin xyz="0.275 0.0 0.252" rpy="0 0 0"/>
      <parent link="${{name}}_link"/>
      <child link="${{name}}_laser_link"/>
    </joint>
    <gazebo reference="${{name}}_laser_link">
      <sensor type="ray" name="${{name}}_laser">
        <update_rate>20.0</update_rate>
        <ray>
          <scan><horizontal><samples>640</samples><resolution>1</resolution>
            <min_angle>${{-130*M_PI/180}}</min_angle><max_angle>${{130*M_PI/180}}</max_angle>
          </horizontal></scan>
          <range><min>0.08</min><max>10.0</max><resolution>0.01</resolution></range>
        </ray>
        <plugin name="${{name}}_laser_controller" filename="libgazebo_ros_laser.so">
          <gaussianNoise>0.005</gaussianNoise>
          <topicName>${{name}}_scan</topicName>
          <frameName>${{name}}_laser_link</frameName>
        </plugin>
      </sensor>
    </gazebo>
  </xacro:macro>
</robot>
"""

ARM = f"""<?xml version="1.0"?>
<robot {NS}>
  <!-- one segment of the arm: part + revolute joint; nested inside the arm macro -->
  <xacro:macro name="segment" params="side name parent mesh m lower upper axis:='0 1 0' *origin">
    <xacro:part name="${{side}}_${{name}}_link" mesh="${{mesh}}" color="${{'Blue' if side == 'l' else 'Red'}}">
      <xacro:box_inertial m="${{m}}" x="0.1" y="0.1" z="${{m*0.02}}">
        <origin xyz="0.0 0.0 ${{-m*0.005}}" rpy="0 0 0"/>
      </xacro:box_inertial>
    </xacro:part>
    <xacro:revolute name="${{side}}_${{name}}_joint" parent="${{parent}}" child="${{side}}_${{name}}_link"
                    axis="${{axis}}" lower="${{lower}}" upper="${{upper}}" effort="30" velocity="${{2.088 + m*0.1}}">
      <xacro:insert_block name="origin"/>
    </xacro:revolute>
  </xacro:macro>

  <xacro:macro name="finger" params="side lr reflect parent">
    <xacro:part name="${{side}}_gripper_${{lr}}_finger_link" mesh="gripper_v0/l_finger">
      <xacro:box_inertial m="0.17126" x="0.09" y="0.02" z="0.02"><origin xyz="0.035 0 0"/></xacro:box_inertial>
    </xacro:part>
    <xacro:revolute name="${{side}}_gripper_${{lr}}_finger_joint" parent="${{parent}}"
                    child="${{side}}_gripper_${{lr}}_finger_link" axis="0 0 ${{reflect}}" lower="0.0" upper="0.548"
                    effort="1000" velocity="0.5">
      <origin xyz="0.07691 ${{reflect*0.01}} 0" rpy="0 0 0"/>
    </xacro:revolute>
    <xacro:part name="${{side}}_gripper_${{lr}}_finger_tip_link" mesh="gripper_v0/l_finger_tip">
      <xacro:box_inertial m="0.04419" x="0.03" y="0.02" z="0.02"><origin xyz="0.004 0 0"/></xacro:box_inertial>
    </xacro:part>
    <joint name="${{side}}_gripper_${{lr}}_finger_tip_joint" type="revolute">
      <axis xyz="0 0 ${{-reflect}}"/>
      <origin xyz="${{finger_len}} ${{reflect*0.00495}} 0" rpy="0 0 0"/>
      <limit lower="0.0" upper="0.548" effort="1000" velocity="0.5"/>
      <mimic joint="${{side}}_gripper_l_finger_joint" multiplier="1" offset="0"/>
      <parent link="${{side}}_gripper_${{lr}}_finger_link"/>
      <child link="${{side}}_gripper_${{lr}}_finger_tip_link"/>
    </joint>
    <gazebo reference="${{side}}_gripper_${{lr}}_finger_tip_link">
      <sensor type="contact" name="${{side}}_gripper_${{lr}}_finger_tip_contact">
        <update_rate>100.0</update_rate>
        <contact><collision>${{side}}_gripper_${{lr}}_finger_tip_link_collision</collision></contact>
        <plugin name="${{side}}_gripper_${{lr}}_finger_tip_bumper" filename="libgazebo_ros_bumper.so">
          <bumperTopicName>${{side}}_gripper_${{lr}}_finger_tip_bumper</bumperTopicName>
          <frameName>${{side}}_gripper_${{lr}}_finger_tip_link</frameName>
        </plugin>
      </sensor>
    </gazebo>
  </xacro:macro>

  <xacro:macro name="gripper" params="side parent">
    <xacro:part name="${{side}}_gripper_palm_link" mesh="gripper_v0/palm">
      <xacro:box_inertial m="0.58007" x="0.1" y="0.08" z="0.05"><origin xyz="0.06623 0.00053 -0.00119"/></xacro:box_inertial>
    </xacro:part>
    <joint name="${{side}}_gripper_palm_joint" type="fixed">
      <origin xyz="0 0 0" rpy="0 0 0"/>
      <parent link="${{parent}}"/>
      <child link="${{side}}_gripper_palm_link"/>
    </joint>
    <xacro:part name="${{side}}_gripper_motor_slider_link" mesh="gripper_v0/motor_slider">
      <xacro:box_inertial m="0.01" x="0.02" y="0.02" z="0.02"><origin xyz="0 0 0"/></xacro:box_inertial>
    </xacro:part>
    <joint name="${{side}}_gripper_motor_slider_joint" type="prismatic">
      <axis xyz="0 1 0"/>
      <origin xyz="0.16828 0 0" rpy="${{M_PI/2}} 0 0"/>
      <limit lower="-0.1" upper="0.1" effort="10000" velocity="0.2"/>
      <parent link="${{side}}_gripper_palm_link"/>
      <child link="${{side}}_gripper_motor_slider_link"/>
    </joint>
    <xacro:part name="${{side}}_gripper_motor_screw_link" mesh="gripper_v0/motor_screw">
      <xacro:box_inertial m="0.01" x="0.02" y="0.02" z="0.02"><origin xyz="0 0 0"/></xacro:box_inertial>
    </xacro:part>
    <joint name="${{side}}_gripper_motor_screw_joint" type="continuous">
      <axis xyz="0 1 0"/>
      <origin xyz="0 0 0" rpy="0 0 0"/>
      <dynamics damping="0.0001"/>
      <parent link="${{side}}_gripper_motor_slider_link"/>
      <child link="${{side}}_gripper_motor_screw_link"/>
    </joint>
    <xacro:frame name="${{side}}_gripper_l_finger_tip_frame" parent="${{side}}_gripper_r_finger_tip_link">
      <origin xyz="0 0 0" rpy="0 0 0"/>
    </xacro:frame>
    <xacro:finger side="${{side}}" lr="l" reflect="1" parent="${{side}}_gripper_palm_link"/>
    <xacro:finger side="${{side}}" lr="r" reflect="-1" parent="${{side}}_gripper_palm_link"/>
    <xacro:frame name="${{side}}_gripper_tool_frame" parent="${{side}}_gripper_palm_link">
      <origin xyz="0.18 0 0" rpy="0 0 0"/>
    </xacro:frame>
    <xacro:frame name="${{side}}_gripper_motor_accelerometer_link" parent="${{side}}_gripper_palm_link">
      <origin xyz="0 0 0" rpy="0 0 0"/>
    </xacro:frame>
    <xacro:frame name="${{side}}_gripper_led_frame" parent="${{side}}_gripper_palm_link">
      <origin xyz="0.0513 0.0 0.0244" rpy="0 0 0"/>
    </xacro:frame>
  </xacro:macro>

  <!-- the arm: seven segments, forearm camera, gripper; reflect mirrors the right arm -->
  <xacro:macro name="arm" params="side reflect parent">
    <xacro:segment side="${{side}}" name="shoulder_pan" parent="${{parent}}" mesh="shoulder_v0/shoulder_pan"
                   m="25.799" lower="${{reflect*M_PI/4-1.5}}" upper="${{reflect*M_PI/4+1.5}}" axis="0 0 1">
      <origin xyz="0.0 ${{reflect*shoulder_offset_y}} 0.0" rpy="0 0 0"/>
    </xacro:segment>
    <xacro:segment side="${{side}}" name="shoulder_lift" parent="${{side}}_shoulder_pan_link"
                   mesh="shoulder_v0/shoulder_lift" m="2.749" lower="-0.5236" upper="1.3963">
      <origin xyz="0.1 0 0" rpy="0 0 0"/>
    </xacro:segment>
    <xacro:segment side="${{side}}" name="upper_arm_roll" parent="${{side}}_shoulder_lift_link"
                   mesh="shoulder_v0/upper_arm_roll" m="0.1" lower="${{reflect*1.55-2.35}}"
                   upper="${{reflect*1.55+2.35}}" axis="1 0 0">
      <origin xyz="0 0 0" rpy="0 0 0"/>
    </xacro:segment>
    <xacro:segment side="${{side}}" name="upper_arm" parent="${{side}}_upper_arm_roll_link"
                   mesh="upper_arm_v0/upper_arm" m="6.01769" lower="${{-M_PI}}" upper="${{M_PI}}" axis="1 0 0">
      <origin xyz="0 0 0" rpy="0 0 0"/>
    </xacro:segment>
    <xacro:segment side="${{side}}" name="elbow_flex" parent="${{side}}_upper_arm_link" mesh="upper_arm_v0/elbow_flex"
                   m="1.90327" lower="-2.3213" upper="0.00">
      <origin xyz="${{upper_arm_len}} 0 0" rpy="0 0 0"/>
    </xacro:segment>
    <xacro:segment side="${{side}}" name="forearm_roll" parent="${{side}}_elbow_flex_link"
                   mesh="upper_arm_v0/forearm_roll" m="0.1" lower="${{-M_PI}}" upper="${{M_PI}}" axis="1 0 0">
      <origin xyz="0 0 0" rpy="0 0 0"/>
    </xacro:segment>
    <xacro:segment side="${{side}}" name="forearm" parent="${{side}}_forearm_roll_link" mesh="forearm_v0/forearm"
                   m="2.57968" lower="${{-M_PI}}" upper="${{M_PI}}" axis="1 0 0">
      <origin xyz="0 0 0" rpy="0 0 0"/>
    </xacro:segment>
    <xacro:segment side="${{side}}" name="wrist_flex" parent="${{side}}_forearm_link" mesh="forearm_v0/wrist_flex"
                   m="0.61402" lower="-2.18" upper="0.0">
      <origin xyz="${{forearm_len}} 0 0" rpy="0 0 0"/>
    </xacro:segment>
    <xacro:segment side="${{side}}" name="wrist_roll" parent="${{side}}_wrist_flex_link" mesh="forearm_v0/wrist_roll"
                   m="0.1" lower="${{-M_PI}}" upper="${{M_PI}}" axis="1 0 0">
      <origin xyz="0 0 0" rpy="0 0 0"/>
    </xacro:segment>
    <xacro:frame name="${{side}}_forearm_cam_frame" parent="${{side}}_forearm_roll_link">
      <origin xyz="0.135 0 0.044" rpy="${{-M_PI/2}} ${{-0.562}} 0"/>
    </xacro:frame>
    <xacro:frame name="${{side}}_forearm_cam_optical_frame" parent="${{side}}_forearm_cam_frame">
      <origin xyz="0 0 0" rpy="${{-M_PI/2}} 0 ${{-M_PI/2}}"/>
    </xacro:frame>
    <xacro:if value="${{reflect == 1}}">
      <!-- the left arm carries the extra accelerometer frame -->
      <xacro:frame name="${{side}}_upper_arm_accel_frame" parent="${{side}}_upper_arm_link">
        <origin xyz="0.2 0 0" rpy="0 0 0"/>
      </xacro:frame>
    </xacro:if>
    <xacro:unless value="${{reflect == 1}}">
      <xacro:frame name="${{side}}_upper_arm_mount_frame" parent="${{side}}_upper_arm_link">
        <origin xyz="0.2 0 ${{0.01*reflect}}" rpy="0 0 0"/>
      </xacro:frame>
    </xacro:unless>
    <xacro:gripper side="${{side}}" parent="${{side}}_wrist_roll_link"/>
    <!-- calibration frames, one per arm joint group -->
    <xacro:frame name="${{side}}_shoulder_cal_frame" parent="${{side}}_shoulder_pan_link">
      <origin xyz="0 0 ${{0.05*reflect}}" rpy="0 0 0"/>
    </xacro:frame>
    <xacro:frame name="${{side}}_elbow_cal_frame" parent="${{side}}_elbow_flex_link">
      <origin xyz="0 0 0" rpy="0 ${{M_PI/8}} 0"/>
    </xacro:frame>
    <xacro:frame name="${{side}}_wrist_cal_frame" parent="${{side}}_wrist_flex_link">
      <origin xyz="0 0 0" rpy="0 ${{-M_PI/8}} 0"/>
    </xacro:frame>
    <xacro:frame name="${{side}}_forearm_cal_frame" parent="${{side}}_forearm_link">
      <origin xyz="${{forearm_len/2}} 0 0" rpy="0 0 0"/>
    </xacro:frame>
    <gazebo reference="${{side}}_forearm_cam_frame">
      <sensor type="camera" name="${{side}}_forearm_cam_sensor">
        <update_rate>25.0</update_rate>
        <camera>
          <horizontal_fov>${{radians(90)}}</horizontal_fov>
          <image><format>R8G8B8</format><width>640</width><height>480</height></image>
          <clip><near>0.1</near><far>100</far></clip>
        </camera>
        <plugin name="${{side}}_forearm_cam_controller" filename="libgazebo_ros_camera.so">
          <cameraName>${{side}}_forearm_cam</cameraName>
          <frameName>${{side}}_forearm_cam_optical_frame</frameName>
          <hackBaseline>0.0</hackBaseline>
        </plugin>
      </sensor>
    </gazebo>
  </xacro:macro>
</robot>
"""

HEAD = f"""<?xml version="1.0"?>
<robot {NS}>
  <xacro:macro name="stereo_cam" params="name parent baseline *origin">
    <xacro:frame name="${{name}}_frame" parent="${{parent}}">
      <xacro:insert_block name="origin"/>
    </xacro:frame>
    <xacro:frame name="${{name}}_optical_frame" parent="${{name}}_frame">
      <origin xyz="0 0 0" rpy="${{-M_PI/2}} 0.0 ${{-M_PI/2}}"/>
    </xacro:frame>
    <xacro:frame name="${{name}}_r_stereo_camera_frame" parent="${{name}}_frame">
      <origin xyz="0 ${{-baseline}} 0" rpy="0 0 0"/>
    </xacro:frame>
    <xacro:frame name="${{name}}_r_stereo_camera_optical_frame" parent="${{name}}_r_stereo_camera_frame">
      <origin xyz="0 0 0" rpy="${{-M_PI/2}} 0.0 ${{-M_PI/2}}"/>
    </xacro:frame>
    <gazebo reference="${{name}}_frame">
      <sensor type="multicamera" name="${{name}}_sensor">
        <update_rate>${{25.0 if baseline > 0.05 else 30.0}}</update_rate>
        <camera name="left">
          <horizontal_fov>${{radians(45 if baseline > 0.05 else 90)}}</horizontal_fov>
          <image><width>640</width><height>480</height><format>L8</format></image>
          <clip><near>0.1</near><far>100</far></clip>
        </camera>
        <camera name="right">
          <pose>0 ${{-baseline}} 0 0 0 0</pose>
          <horizontal_fov>${{radians(45 if baseline > 0.05 else 90)}}</horizontal_fov>
          <image><width>640</width><height>480</height><format>L8</format></image>
          <clip><near>0.1</near><far>100</far></clip>
        </camera>
        <plugin name="${{name}}_controller" filename="libgazebo_ros_multicamera.so">
          <cameraName>${{name}}</cameraName>
          <frameName>${{name}}_optical_frame</frameName>
          <hackBaseline>${{baseline}}</hackBaseline>
        </plugin>
      </sensor>
    </gazebo>
  </xacro:macro>

  <xacro:macro name="head" params="parent">
    <xacro:segment side="head" name="pan" parent="${{parent}}" mesh="head_v0/head_pan" m="6.339" lower="-3.007"
                   upper="3.007" axis="0 0 1">
      <origin xyz="-0.01707 0.0 0.38145" rpy="0 0 0"/>
    </xacro:segment>
    <xacro:segment side="head" name="tilt" parent="head_pan_link" mesh="head_v0/head_tilt" m="4.479" lower="-0.471"
                   upper="1.396">
      <origin xyz="0.068 0 0" rpy="0 0 0"/>
    </xacro:segment>
    <xacro:frame name="head_plate_frame" parent="head_tilt_link">
      <origin xyz="0.0232 0 0.0645" rpy="0 0 0"/>
    </xacro:frame>
    <xacro:stereo_cam name="narrow_stereo" parent="head_plate_frame" baseline="${{0.09}}">
      <origin xyz="0.067 -0.03 0.0" rpy="0 0 0"/>
    </xacro:stereo_cam>
    <xacro:stereo_cam name="wide_stereo" parent="head_plate_frame" baseline="${{0.045*1}}">
      <origin xyz="0.067 0.03 0.0" rpy="0 0 0"/>
    </xacro:stereo_cam>
    <xacro:stereo_cam name="projector_wg6802418" parent="head_plate_frame" baseline="${{0.09}}">
      <origin xyz="0.0 0.11 0.0546" rpy="0 0 0"/>
    </xacro:stereo_cam>
    <xacro:part name="head_mount_link" mesh="sensors/kinect_mount" color="White">
      <xacro:box_inertial m="0.05" x="0.07" y="0.27" z="0.04"><origin xyz="0 0 0.02"/></xacro:box_inertial>
    </xacro:part>
    <joint name="head_mount_joint" type="fixed">
      <origin xyz="-0.138 0 0.155" rpy="0 0 0"/>
      <parent link="head_plate_frame"/>
      <child link="head_mount_link"/>
    </joint>
    <xacro:frame name="head_mount_kinect_ir_link" parent="head_mount_link">
      <origin xyz="0.0325 0.0125 0.0860" rpy="0 0 0"/>
    </xacro:frame>
    <xacro:frame name="head_mount_kinect_ir_optical_frame" parent="head_mount_kinect_ir_link">
      <origin xyz="0 0 0" rpy="${{-M_PI/2}} 0.0 ${{-M_PI/2}}"/>
    </xacro:frame>
    <xacro:frame name="head_mount_kinect_rgb_link" parent="head_mount_link">
      <origin xyz="0.0325 0.0375 0.0860" rpy="0 0 0"/>
    </xacro:frame>
    <xacro:frame name="head_mount_kinect_rgb_optical_frame" parent="head_mount_kinect_rgb_link">
      <origin xyz="0 0 0" rpy="${{-M_PI/2}} 0.0 ${{-M_PI/2}}"/>
    </xacro:frame>
    <xacro:frame name="head_mount_prosilica_link" parent="head_mount_link">
      <origin xyz="0.0465 0 0.0375" rpy="0 0 0"/>
    </xacro:frame>
    <xacro:frame name="head_mount_prosilica_optical_frame" parent="head_mount_prosilica_link">
      <origin xyz="0 0 0" rpy="${{-M_PI/2}} 0.0 ${{-M_PI/2}}"/>
    </xacro:frame>
    <gazebo reference="head_mount_kinect_ir_link">
      <sensor type="depth" name="head_mount_kinect_sensor">
        <update_rate>20.0</update_rate>
        <camera>
          <horizontal_fov>${{radians(57)}}</horizontal_fov>
          <image><format>B8G8R8</format><width>640</width><height>480</height></image>
          <clip><near>0.05</near><far>5</far></clip>
        </camera>
        <plugin name="head_mount_kinect_controller" filename="libgazebo_ros_openni_kinect.so">
          <cameraName>head_mount_kinect</cameraName>
          <frameName>head_mount_kinect_ir_optical_frame</frameName>
          <pointCloudCutoff>0.4</pointCloudCutoff>
        </plugin>
      </sensor>
    </gazebo>
    <xacro:frame name="high_def_frame" parent="head_plate_frame">
      <origin xyz="0.046457 -0.11 0.0546" rpy="0 0 0"/>
    </xacro:frame>
    <xacro:frame name="high_def_optical_frame" parent="high_def_frame">
      <origin xyz="0 0 0" rpy="${{-M_PI/2}} 0.0 ${{-M_PI/2}}"/>
    </xacro:frame>
  </xacro:macro>
</robot>
"""

TOP = f"""<?xml version="1.0"?>
<!-- Synthetic PR2-sized robot for benchmarks (myrabot-desc bench/gen_pr2like.py); not PR2's real numbers. -->
<robot name="pr2like" {NS}>
  <xacro:arg name="with_arms" default="true"/>
  <xacro:include filename="common.xacro"/>
  <xacro:include filename="base.xacro"/>
  <xacro:include filename="arm.xacro"/>
  <xacro:include filename="head.xacro"/>

  <!-- base with four casters -->
  <xacro:base name="base"/>

  <!-- torso -->
  <xacro:segment side="torso" name="lift" parent="base_link" mesh="torso_v0/torso_lift" m="36.248046"
                 lower="0.0" upper="0.33" axis="0 0 1">
    <origin xyz="-0.05 0 0.739675" rpy="0 0 0"/>
  </xacro:segment>
  <xacro:part name="torso_lift_motor_screw_link" mesh="torso_v0/screw">
    <xacro:cyl_inertial m="1.0" r="0.02" l="0.3"/>
  </xacro:part>
  <joint name="torso_lift_motor_screw_joint" type="continuous">
    <axis xyz="0 0 1"/>
    <origin xyz="-0.15 0.0 -0.7" rpy="0 0 0"/>
    <parent link="base_link"/>
    <child link="torso_lift_motor_screw_link"/>
  </joint>
  <xacro:frame name="imu_link" parent="torso_lift_link">
    <origin xyz="-0.02977 -0.1497 0.164" rpy="0 ${{M_PI}} 0"/>
  </xacro:frame>
  <xacro:frame name="laser_tilt_mount_link" parent="torso_lift_link">
    <origin xyz="0.09893 0 0.227" rpy="0 0 0"/>
  </xacro:frame>
  <xacro:frame name="laser_tilt_link" parent="laser_tilt_mount_link">
    <origin xyz="0 0 0.03" rpy="0 0 0"/>
  </xacro:frame>

  <!-- head and its cameras -->
  <xacro:head parent="torso_lift_link"/>

  <!-- arms: left and right copies from one macro -->
  <xacro:if value="$(arg with_arms)">
    <xacro:arm side="l" reflect="1" parent="torso_lift_link"/>
    <xacro:arm side="r" reflect="-1" parent="torso_lift_link"/>
  </xacro:if>

  <gazebo>
    <plugin name="ros_control" filename="libgazebo_ros_control.so">
      <robotNamespace>/pr2like</robotNamespace>
      <controlPeriod>${{1.0/1000}}</controlPeriod>
    </plugin>
  </gazebo>
</robot>
"""

PACKAGE_XML = f"""<?xml version="1.0"?>
<package format="2">
  <name>{PKG}</name>
  <version>0.0.1</version>
  <description>Synthetic PR2-sized description for myrabot-desc benchmarks.</description>
  <maintainer email="bench@example.com">bench</maintainer>
  <license>BSD</license>
</package>
"""


def write_pr2like(out_dir) -> Path:
    """Write the package under ``out_dir``; return the top-level xacro file."""
    pkg = Path(out_dir) / PKG
    (pkg / "urdf").mkdir(parents=True, exist_ok=True)
    (pkg / "package.xml").write_text(PACKAGE_XML)
    for name, text in (("common.xacro", COMMON), ("base.xacro", BASE), ("arm.xacro", ARM),
                       ("head.xacro", HEAD), ("pr2like.urdf.xacro", TOP)):
        (pkg / "urdf" / name).write_text(text)
    return pkg / "urdf" / "pr2like.urdf.xacro"


if __name__ == "__main__":
    print(write_pr2like(sys.argv[1] if len(sys.argv) > 1 else "."))
