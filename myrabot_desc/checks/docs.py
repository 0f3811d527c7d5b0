"""Generate docs/rules.md from the registry (docstrings) and the examples below.

    python -m myrabot_desc.checks.docs > docs/rules.md

A test keeps docs/rules.md equal to this output, so every rule is documented.
"""

from __future__ import annotations

import re

from myrabot_desc.checks.registry import EXTERNAL, FAMILIES, load_all

# code -> (bad snippet, message as check prints it, good snippet)
EXAMPLES: dict[str, tuple[str, str, str]] = {
    "X000": ("<robot name='x'><link name='a'></robot>",
             "broken.urdf:1: error: XML syntax error: Opening and ending tag mismatch: link line 1 and robot", ""),
    "X001": ('<macro name="wheel" params="side">…</macro>\n<wheel side="left"/>',
             "legacy <macro> upgraded to <xacro:macro>; xacro 2.x would copy it into the URDF unexpanded",
             '<xacro:macro name="wheel" params="side">…</xacro:macro>\n<xacro:wheel side="left"/>'),
    "X002": ('<ultrasonidos id="1" parent="e_base_2_link" d_centro="0.150">…</ultrasonidos>\n'
             '<!-- ultrasonidos.xacro is never included -->',
             "<ultrasonidos> looks like a call of macro 'ultrasonidos' (defined in ultrasonidos.xacro), but it was "
             "not expanded: the file defining it is not included",
             '<xacro:include filename="$(find myrabot_fer_modelo)/urdf/ultrasonidos.xacro"/>\n'
             '<xacro:ultrasonidos id="1" parent="e_base_2_link" d_centro="0.150">…</xacro:ultrasonidos>'),
    "X003": ('<robot xmlns:xacro="…"><xacro:macro name="quadrotor_base">…</xacro:macro></robot>',
             "this file defines 1 macro(s) (quadrotor_base) and instantiates none",
             '<xacro:include filename="quadrotor_base.urdf.xacro"/>\n<xacro:quadrotor_base/>'),
    "X004": ('<mesh filename="package://myrabot_robot_model/meshes/webcam_1.stl"/>',
             "package 'myrabot_robot_model' of package://myrabot_robot_model/meshes/webcam_1.stl cannot be found",
             "myrabot-desc check robot.xacro -p myrabot_robot_model=../myrabot_fer_modelo"),
    "X005": ('<xacro:property name="x" value="${__import__(\'os\').getcwd()}"/>',
             "expression refused: calls outside the allow-list", '<xacro:property name="x" value="${0.1 * 2}"/>'),
    "X006": ('<xacro:include filename="/etc/robot_parts.xacro"/>', "include outside the allowed folders",
             "myrabot-desc check robot.xacro --allow-path /etc"),
    "T001": ('<link name="base"/>\n<link name="island"/>', "2 root links (base, island): a URDF is one tree",
             '<joint name="island_joint" type="fixed"><parent link="base"/><child link="island"/></joint>'),
    "T002": ('<joint name="ab" …><parent link="a"/><child link="b"/></joint>\n'
             '<joint name="cb" …><parent link="c"/><child link="b"/></joint>',
             "link b is the child of 2 joints (ab, cb): a link has one parent",
             "<!-- keep one parent; close the loop in SDF (<gazebo><joint>) or MJCF (equality) -->"),
    "T003": ('<joint name="j" type="fixed"><parent link="base_lnk"/><child link="arm"/></joint>',
             "joint j: parent link 'base_lnk' does not exist; did you mean base_link?", '<parent link="base_link"/>'),
    "T004": ('<xacro:wheel/>\n<xacro:wheel/>   <!-- both make link "wheel" -->',
             "2 top-level <link> elements are named 'wheel'",
             '<xacro:wheel prefix="left_"/>\n<xacro:wheel prefix="right_"/>'),
    "T005": ("<gaezebo>\n  <material>Gazebo/White</material>\n</gaezebo>",
             "unknown element <gaezebo> in <robot name=\"MYRAbot\">: URDF parsers ignore it; did you mean <gazebo>?",
             '<gazebo reference="base_link">\n  <material>Gazebo/White</material>\n</gazebo>'),
    "T006": ('<box size="0.3 0.24 0.1" rpy="0 0 0"/>\n<dynamics damping="0" fricction="0"/>',
             "unknown attribute rpy=\"0 0 0\" on <box>: URDF parsers ignore it; rpy is not an attribute of <box>; "
             "put the rotation on the <origin> of the <visual>/<collision>",
             '<origin xyz="0 0 0" rpy="0 0 0"/>\n<geometry><box size="0.3 0.24 0.1"/></geometry>\n'
             '<dynamics damping="0" friction="0"/>'),
    "T007": ("<robot name=\"mobile_robot\">\n  …\n  <ros><namespace>/</namespace><argument>/cmd_vel:=cmd_vel</argument></ros>\n</robot>",
             "ROS 2 <ros> block at robot level (<namespace>/, <argument>/cmd_vel:=cmd_vel) is read by no one",
             '<plugin name="diff_drive" filename="libgazebo_ros_diff_drive.so">\n'
             '  <ros><namespace>/</namespace><remapping>cmd_vel:=cmd_vel</remapping></ros>\n  …\n</plugin>'),
    "T008": ('<joint name="j" type="revolute"><axis xyz="0 0 0"/>…</joint>', "joint j (revolute) has axis 0 0 0: no direction",
             '<axis xyz="0 0 1"/>'),
    "T009": ('<joint name="elbow" type="revolute">…<!-- no <limit> --></joint>', "revolute joint elbow has no <limit>",
             '<limit lower="-2.6" upper="2.6" effort="1.5" velocity="5.2"/>'),
    "T010": ('<mass value="0,5"/>', "<mass value=\"0,5\">: not a number", '<mass value="0.5"/>'),
    "T011": ('<limit lower="-1" upper="1" effort="0" velocity="0"/>', "joint joint2: effort 0, velocity 0 (must be > 0)",
             '<limit lower="-1" upper="1" effort="2.5" velocity="3"/>'),
    "T012": ('<mimic joint="index_q1" multiplier="1.05"/>',
             "joint Left_index_q2 mimics 'index_q1', which does not exist; did you mean Left_index_q1?",
             '<mimic joint="Left_index_q1" multiplier="1.05"/>'),
    "T013": ('<joint name="j_wheel_2" type="revolute"><limit effort="50" velocity="10"/></joint>',
             "revolute joint j_wheel_2 has range [0, 0] (no lower/upper given: both default to 0): it cannot move",
             '<joint name="j_wheel_2" type="continuous"><limit effort="50" velocity="10"/></joint>'),
    "T014": ('<axis xyz="0 0 10"/>', "joint j axis 0 0 10 has length 10; parsers normalise it", '<axis xyz="0 0 1"/>'),
    "T015": ('<limit lower="1.5" upper="-1.5" effort="1" velocity="1"/>', "joint j: lower 1.5 > upper -1.5",
             '<limit lower="-1.5" upper="1.5" effort="1" velocity="1"/>'),
    "T016": ('<joint name="j" type="revolut">', "joint j has type 'revolut', not a URDF joint type; did you mean revolute?",
             '<joint name="j" type="revolute">'),
    "I001": ('<link name="RFinger13Link"><visual>…</visual><!-- no <inertial> --></link>\n'
             '<joint name="RFinger13" type="revolute">…<child link="RFinger13Link"/></joint>',
             "link RFinger13Link moves (joint RFinger13, revolute) and has geometry but no mass",
             '<inertial><mass value="0.01"/><inertia ixx="1e-6" ixy="0" ixz="0" iyy="1e-6" iyz="0" izz="1e-6"/></inertial>'),
    "I002": ('<link name="middle_abdomen_virtual"/>  <!-- between two revolute joints -->',
             "link middle_abdomen_virtual (joint middle_lumbar_Z, revolute) has no mass and no geometry; converting "
             "to SDF drops it with its children (middle_abdomen)",
             '<link name="middle_abdomen_virtual">\n  <inertial><mass value="0.001"/>'
             '<inertia ixx="1e-6" ixy="0" ixz="0" iyy="1e-6" iyz="0" izz="1e-6"/></inertial>\n</link>'),
    "I003": ('<mass value="-1"/>', "link l1 has mass -1 kg", '<mass value="1"/>'),
    "I004": ('<inertia ixx="9e-08" ixy="0" ixz="6.3e-08" iyy="3.5e-08" iyz="0" izz="1e-08"/>',
             "link base_antenna_left_link: inertia not positive definite, principal moments -3.535e-08/3.501e-08/9.087e-08",
             "<!-- the solid-body tensor: myrabot-desc check --inertia --suggest -->"),
    "I005": ('<mass value="1.0"/>\n<inertia ixx="1.0" ixy="0" ixz="0" iyy="10.0" iyz="0" izz="1.0"/>',
             "link scanner_link: impossible inertia, principal moments 1 + 1 = 2 < 10 (triangle inequality)",
             '<inertia ixx="0.0005146" ixy="0" ixz="0" iyy="0.0005146" iyz="0" izz="0.0006125"/>  '
             '<!-- cylinder r 0.035 l 0.05, 1 kg -->'),
    "I006": ('<collision><geometry><box size="0.3 0.25 0.1"/></geometry></collision>\n'
             '<inertial><mass value="1.0"/><inertia ixx="1.0" ixy="0" ixz="0" iyy="1.0" iyz="0" izz="1.0"/></inertial>',
             "link base_link: inertia ixx/iyy/izz 1/1/1 kg·m², but a solid box 0.3×0.25×0.1 m of 1 kg gives "
             "0.00604/0.00833/0.0127 (ratio 166×/120×/79×)",
             '<inertia ixx="0.006042" ixy="0" ixz="0" iyy="0.008333" iyz="0" izz="0.01271"/>'),
    "I007": ('<cylinder length="0.063" radius="0.17"/>  <!-- Roomba base, 3.6 kg -->\n'
             '<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.5"/>',
             "link base_link: radius of gyration √(0.5/3.6) = 0.373 m about axis (0 0 1), but no point of the "
             "geometry is farther than 0.17 m from that axis",
             '<inertia ixx="0.02720" ixy="0" ixz="0" iyy="0.02720" iyz="0" izz="0.05202"/>'),
    "I008": ('<cylinder radius="0.135" length="0.015"/>  <!-- a wooden plate -->\n<mass value="0.05"/>',
             "link e_base_1_link: 0.05 kg in cylinder r 0.135 l 0.015 m (0.000859 m³) is a density of 58.2 kg/m³",
             '<mass value="0.52"/>  <!-- plywood, ~600 kg/m³ × 0.000859 m³ -->'),
    "I009": ('<xacro:macro name="default_inertia_e"><inertia ixx="0.01" … izz="0.01"/></xacro:macro>\n'
             '<!-- used on a 0.1 g screen and a 100 g plate -->',
             "the same inertia 0.01/0.01/0.01 is used by 29 links with masses 0.0001–0.1 kg (1000×): a placeholder",
             "<!-- one tensor per link, from its own geometry: check --inertia --suggest -->"),
    "I010": ('<inertial><origin xyz="0 0 0"/>…</inertial>\n<visual><origin xyz="0.125 0 0"/>…</visual>',
             "link r_upper_arm_roll_link: inertial origin (0 0 0) lies 0.117 m outside the box bounding its geometry",
             '<inertial><origin xyz="0.125 0 0"/>…</inertial>'),
    "I011": ('<collision><geometry><mesh filename="package://robot/meshes/shell.dae"/></geometry></collision>',
             "link torso: inertia not compared with geometry: mesh shell.dae is not watertight",
             "<!-- a closed collision mesh, or primitives -->"),
    "M001": ('<mesh filename="package://myrabot_robot_model/meshes/webcam_1.stl"/>',
             "mesh package://myrabot_robot_model/meshes/webcam_1.stl (collision of e_webcam_1_link) cannot be "
             "resolved: package 'myrabot_robot_model' is not found",
             '<mesh filename="package://myrabot_fer_modelo/meshes/webcam_1.stl"/>'),
    "M002": ('<mesh filename="package://robot/meshes/arm.stl"/>  <!-- exported in mm -->',
             "mesh package://robot/meshes/arm.stl (visual of arm) is 350 m across after scale 1 1 1: millimetres "
             "exported as metres?", '<mesh filename="package://robot/meshes/arm.stl" scale="0.001 0.001 0.001"/>'),
    "M003": ('<collision><geometry><mesh filename="package://robot/meshes/cover.stl"/></geometry></collision>',
             "collision mesh package://robot/meshes/cover.stl of base is not watertight (1204 faces)",
             "<!-- close the holes, or use a box/cylinder collision -->"),
    "M004": ('<mesh filename="package://robot/meshes/inside_out.stl"/>',
             "mesh package://robot/meshes/inside_out.stl (collision of b) is inside out: volume -0.001 m³",
             "<!-- flip the faces: trimesh mesh.invert(), MeshLab 'Invert faces orientation' -->"),
    "P001": ('<!-- two wheels at x 0.1, centre of mass at x 0.0875, no caster -->',
             "no static support: the ground contacts (left_wheel, right_wheel) lie on one line (x 0.1), with no "
             "caster; the centre of mass is 12.5 mm behind that line",
             '<link name="caster"><collision><geometry><sphere radius="0.04"/></geometry></collision>…</link>\n'
             '<joint name="caster_joint" type="fixed"><origin xyz="-0.12 0 -0.04"/>…</joint>'),
    "P002": ('<joint name="base_footprint_fixed" type="fixed"><origin xyz="0 0 0.03"/>…</joint>  <!-- wheels r 0.08 -->',
             "with base_footprint at z 0, collision geometry reaches z -0.05 m (left_wheel, right_wheel): the robot "
             "spawns 50 mm into the ground",
             '<joint name="base_footprint_fixed" type="fixed"><origin xyz="0 0 0.08"/>…</joint>'),
    "P003": ('<!-- fingers on revolute joints without <inertial> -->',
             "ABA returns NaN at a random configuration: nothing below joint(s) LFinger21, LFinger22 has mass",
             '<inertial><mass value="0.01"/><inertia ixx="1e-6" ixy="0" ixz="0" iyy="1e-6" iyz="0" izz="1e-6"/></inertial>'),
    "P004": ("", "total mass 4 kg; centre of mass (0.0875 0 0.03) m in base_footprint, 0.08 m above the ground contacts", ""),
    "S001": ('<gazebo reference="double_stereo_double_stereo_link"><material>Gazebo/Grey</material></gazebo>',
             "<gazebo reference=\"double_stereo_double_stereo_link\"> names no link or joint; its content is lost "
             "(material); did you mean double_stereo_link?",
             '<gazebo reference="double_stereo_link"><material>Gazebo/Grey</material></gazebo>'),
    "S002": ('<plugin name="imu" filename="libgazebo_ros_imu_sensor.so"><frame_name>imu_lnk</frame_name></plugin>',
             "plugin imu: frame_name 'imu_lnk' is not a link of this robot; did you mean imu_link?",
             "<frame_name>imu_link</frame_name>"),
    "S003": ('<controller:gazebo_ros_openni_kinect …><frameName>e_webcam_optica_link</frameName>',
             "camera webcam stamps images in e_webcam_optica_link (plugin frameName), whose z axis is (0 0 1) in "
             "e_webcam_optica_link; the camera looks along e_webcam_optica_link's +x …",
             '<link name="e_webcam_optical_frame"/>\n<joint name="e_webcam_optical_joint" type="fixed">\n'
             '  <origin rpy="-1.5708 0 -1.5708"/><parent link="e_webcam_optica_link"/>'
             '<child link="e_webcam_optical_frame"/>\n</joint>\n<frameName>e_webcam_optical_frame</frameName>'),
    "S004": ('<link name="laser"/>\n<gazebo reference="laser"><sensor:ray name="laser">…</sensor:ray></gazebo>',
             "sensor laser (ray) sits on massless leaf link laser: the Electric-era converter ignores links without mass",
             '<link name="laser"><inertial><mass value="0.001"/>'
             '<inertia ixx="1e-6" ixy="0" ixz="0" iyy="1e-6" iyz="0" izz="1e-6"/></inertial></link>'),
    "S005": ("<minRange>0</minRange>\n<maxRange>7</maxRange>",
             "sensor ultrasonidos_1: minRange/maxRange min 0 m: rays start inside the sensor's own link",
             "<minRange>0.02</minRange>\n<maxRange>4</maxRange>"),
    "S006": ("<fov>32</fov>", "sensor ultrasonidos_1: plugin gazebo_ros_ultrasonidos_1_controller fov 32 looks like "
             "degrees; expected radians (sensor_msgs/Range.field_of_view): 32° = 0.5585 rad", "<fov>0.5585</fov>"),
    "S007": ("<horizontal_fov>3.1</horizontal_fov>", "camera c: horizontal_fov 3.1 rad (178°) is outside a pinhole "
             "camera's range", "<horizontal_fov>1.047</horizontal_fov>"),
    "G001": ("<wheelSeparation>0.4</wheelSeparation>  <!-- wheel joints at y ±0.15 -->",
             "wheelSeparation 0.4 m, but the wheel joints left_wheel_joint and right_wheel_joint are 0.3 m apart "
             "(y 0.15 and -0.15): the robot turns at 1.33× the commanded rate", "<wheelSeparation>0.30</wheelSeparation>"),
    "G002": ("<wheelDiameter>0.2</wheelDiameter>  <!-- wheel cylinder radius 0.08 -->",
             "wheelDiameter 0.2 m, but wheel left_wheel (joint left_wheel_joint) has a collision diameter of 0.16 m: "
             "the robot drives at 0.8× the commanded speed", "<wheelDiameter>0.16</wheelDiameter>"),
    "G003": ("<left_joint>left_wheel_jiont</left_joint>",
             "gazebo_ros_diff_drive (ROS 2): left_joint 'left_wheel_jiont' is not a joint of this robot; did you mean "
             "left_wheel_joint?", "<left_joint>left_wheel_joint</left_joint>"),
    "G004": ('<joint name="front_castor_joint" type="fixed">  <!-- named by the Create plugin -->',
             "gazebo_ros_create/roomba (Electric): front_castor_joint front_castor_joint is fixed: fixed joints are "
             "merged away in URDF→SDF conversion, so the plugin cannot find it",
             '<joint name="front_castor_joint" type="continuous">'),
    "G005": ('<joint name="left_wheel_joint" type="continuous"><axis xyz="0 0 1"/>…</joint>',
             "gazebo_ros_diff_drive (ROS 1): left wheel joint left_wheel_joint turns about (0 0 1) in base_footprint: "
             "not across the direction of travel (y)", '<axis xyz="0 1 0"/>'),
    "G007": ("<torque>10</torque>\n<alwaysOn>true</alwaysOn>",
             "gazebo_ros_diff_drive (ROS 1) does not read <torque> (ROS 1 gazebo_ros_diff_drive reads wheelTorque)",
             "<wheelTorque>10</wheelTorque>"),
    "G008": ('<controller:gazebo_ros_openni_kinect name="webcam_camera_controller" filename="libgazebo_ros_openni_kinect.so">',
             "controller webcam_camera_controller declares its library with filename=\"libgazebo_ros_openni_kinect.so\"; "
             "the Electric controller loader reads plugin=, so it is never loaded",
             '<controller:gazebo_ros_openni_kinect name="webcam_camera_controller" plugin="libgazebo_ros_openni_kinect.so">'),
    "G009": ("<gazebo reference=\"e_webcam_1_link\"><material>myrabot_fer/Black</material></gazebo>",
             "material myrabot_fer/Black (on e_webcam_1_link, e_webcam_2_link) is not a stock Gazebo material nor in "
             "any script found", "<material>Gazebo/Black</material>  <!-- or ship the script in the package -->"),
    "G010": ("<topicName>scan</topicName>  <!-- in two laser plugins -->",
             "topic /scan is published by 2 plugins: laser (topicName), block_laser (topicName)",
             "<topicName>scan_front</topicName>"),
    "G011": ('<controller:gazebo_ros_imu name="imu_controller" plugin="libgazebo_ros_imu.so">',
             "11 Electric-era controllers and 13 sensors (<controller:…>/<sensor:…>): today's Gazebo ignores them",
             "myrabot-desc convert robot.urdf.xacro --to sdf -o robot.sdf"),
    "G012": ("<torque>10</torque>\n<wheelTorque>5</wheelTorque>",
             "gazebo_ros_diff_drive (ROS 1): <torque> 10 and <wheelTorque> 5 disagree; the plugin reads wheelTorque (5)",
             "<wheelTorque>5</wheelTorque>"),
    "G013": ('<plugin name="diff_drive" filename="libgazebo_ros_diff_drive.so">  <!-- no <legacyMode> -->',
             "gazebo_ros_diff_drive (ROS 1): no <legacyMode> given: it defaults to true, so the plugin drives "
             "left_wheel_joint (y 0.15) with the right wheel's speed and right_wheel_joint (y -0.15) with the left "
             "one's: the robot turns the wrong way (a commanded 0.5 rad/s turns at -0.5 rad/s, turn ratio -1; ...)",
             "<legacyMode>false</legacyMode>"),
    "G014": ("<leftJoint>left_wheel_joint</leftJoint>\n<rightJoint>right_wheel_joint</rightJoint>",
             "drive (gazebo_ros_diff_drive (ROS 1)): left left_wheel_joint, right right_wheel_joint; "
             "separation 0.3 m, wheel radius 0.08 m on the URDF", "(information: nothing to fix)"),
}

EXTERNAL_DOC = {
    "X000": "The input could not be processed at all (bad XML, missing file, not a `<robot>`): one line "
            "`file:line: error: ...`, exit code 2; the other files of the call are still checked.",
    "X001": "The build upgraded ROS Electric/Fuerte syntax (un-prefixed `<macro>`, `<include>`, `<property>`, "
            "`<insert_block>`, bare macro calls). Modern xacro would copy these tags into the URDF unexpanded, "
            "so the file only works with this tool or an old ROS.",
    "X002": "A tag in the URDF looks like a macro call that was never expanded (for example because the file "
            "defining the macro is not included). URDF parsers ignore the tag, so everything the macro would "
            "have added is silently missing (the seed's five sonars).",
    "X003": "The file given defines macros and instantiates none, so the robot is empty (xarm_ros #196, "
            "universal_robot #482).",
    "X004": "A `package://NAME/...` URI names a package no search path provides; meshes and textures under it "
            "cannot be found.",
    "X005": "A `${}` expression uses something outside the safe evaluator's allow-list (attribute access, "
            "imports, calls); model files are untrusted input in CI.",
    "X006": "An include or `load_yaml` points outside the input's folder and the resolved packages.",
    "T010": "A value the URDF reader needs (a mass, a vector, a limit) is not a number; the reader used the "
            "default, so the model differs from what was meant.",
}
EXTERNAL_FIX = {
    "X000": "Fix the line named in the message.", "X001": "Write `xacro:` prefixes (the build output shows the "
    "modern form).", "X002": "Include the file that defines the macro and call it as `<xacro:NAME>`.",
    "X003": "Check the top-level assembly, or include this file from one.", "X004": "Pass `-p NAME=PATH` or "
    "`--package-path DIR`, or correct the package name.", "X005": "Rewrite the expression with arithmetic and "
    "the allowed functions, or pass `--unsafe-eval` for a trusted file.", "X006": "Pass `--allow-path DIR`.",
    "T010": "Write a plain decimal number (`0.5`, not `0,5`).",
}


def _split(doc: str):
    """(summary, why, fix) from a rule docstring."""
    lines = doc.strip().splitlines()
    summary = lines[0].strip()
    body = " ".join(l.strip() for l in lines[1:]).strip()
    why, fix = body, ""
    m = re.search(r"\bFix:\s*", body)
    if m:
        why, fix = body[:m.start()].strip(), body[m.end():].strip()
        fix = fix[:1].upper() + fix[1:]
    return summary, why, fix


def render() -> str:
    rules = load_all()
    out = ["# check rules", "",
           "Generated from the rule registry (`python -m myrabot_desc.checks.docs > docs/rules.md`).",
           "Every finding has a stable code (a code never changes meaning), a severity, a message with the",
           "numbers that matter and the xacro `file:line` it comes from. Select or ignore codes or prefixes",
           "with `--select I,G001` / `--ignore I008`; `--strict` makes warnings fail.", "",
           "Without `--inertia`, mesh files are not opened (only their existence is checked) and inertias are",
           "compared with primitive geometry only; `--inertia` loads collision meshes with trimesh and compares",
           "watertight ones too; `--meshes` also opens visual meshes for M002/M004. Severities: **error** (exit 1), **warning**,",
           "**info**. Some rules raise or lower the severity of one finding; their text says when.", "",
           "| code | name | severity | what |", "|---|---|---|---|"]
    rows = [(c, r.name, r.severity, r.summary) for c, r in rules.items()]
    rows += [(c, n, s, summ) for c, (n, s, summ) in EXTERNAL.items()]
    order = list(FAMILIES)
    rows.sort(key=lambda r: (order.index(r[0][0]), r[0]))
    for c, n, s, summ in rows:
        cell = summ.replace("|", "\\|")
        out.append(f"| [{c}](#{c.lower()}) | {n} | {s} | {cell} |")
    out.append("")
    family = None
    for c, n, s, summ in rows:
        if c[0] != family:
            family = c[0]
            out += [f"## {family}: {FAMILIES[family]}", ""]
        if c in rules:
            _, why, fix = _split(rules[c].doc)
        else:
            why, fix = EXTERNAL_DOC.get(c, summ), EXTERNAL_FIX.get(c, "")
        out += [f"### {c}", "", f"**{n}** · {s}", "", f"**What it does.** {summ}", "",
                f"**Why is this bad?** {why}", ""]
        ex = EXAMPLES.get(c)
        if ex:
            bad, msg, good = ex
            out.append("**Example.**")
            out.append("")
            if bad:
                out += ["```xml", bad, "```", ""]
            out += ["```", f"{c} {msg}", "```", ""]
            if good:
                out += [f"**Fix.** {fix}".rstrip(), "", "```xml" if good.lstrip().startswith("<") else "```",
                        good, "```", ""]
                continue
        if fix:
            out += [f"**Fix.** {fix}", ""]
    out += ["## JSON report schema (`--format json`)", "",
            "`schema` is `myrabot-desc/check-report/1`; fields are only ever added under a new schema number.", "",
            "```json",
            '{"schema": "myrabot-desc/check-report/1",',
            ' "tool": {"name": "myrabot-desc", "version": "0.1.0"},',
            ' "summary": {"files": 1, "failed": 0, "errors": 4, "warnings": 14, "info": 1},',
            ' "files": [{"file": "urdf/robot.xacro", "robot": "mobile_robot", "links": 5, "joints": 4,',
            '            "status": "errors",            // ok | errors | failed',
            '            "failure": null,               // the one-line reason when status is failed',
            '            "counts": {"error": 4, "warning": 14, "info": 1},',
            '            "diagnostics": [{"code": "G001", "severity": "error", "rule": "drive-wheel-separation",',
            '                             "message": "wheelSeparation 0.4 m, but ...", "file": "urdf/robot.gazebo",',
            '                             "line": 4, "data": {"value": 0.4, "urdf": 0.3, "fix": 0.3, ...}}],',
            '            "suggestions": [{"link": "base_link", "inertia": "<inertia ixx=... />"}]}]}',
            "```", "",
            "Paths are relative to the current folder when under it. Diagnostics are sorted by severity, code,",
            "location and message; floats are rounded to 9 significant digits, so the same input gives the same",
            "bytes. `--format github` prints `::error file=F,line=L,title=CODE name::message` workflow commands",
            "(`::notice` for info); `--format sarif` writes SARIF 2.1.0 with one `rules` entry per code above.", ""]
    return "\n".join(out)


if __name__ == "__main__":
    import sys

    sys.stdout.write(render())
