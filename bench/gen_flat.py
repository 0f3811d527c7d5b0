"""Generate a xacro file with N top-level macro calls (the xacro #292 worst case)."""

import sys


def flat_xacro(n: int) -> str:
    calls = "\n".join(f'  <xacro:seg id="{i}" parent="l{i}" seglen="${{0.1 + {i} * 0.001}}"/>' for i in range(n))
    return f"""<?xml version="1.0"?>
<robot name="flat{n}" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="seg_angle" value="3.141592653589793"/>
  <xacro:macro name="seg" params="id parent seglen">
    <!-- one link and one joint per call -->
    <link name="l${{id+1}}">
      <inertial>
        <mass value="${{0.1*seglen}}"/>
        <inertia ixx="${{0.1*seglen*seglen/12}}" ixy="0" ixz="0" iyy="${{0.1*seglen*seglen/12}}" iyz="0" izz="1e-6"/>
      </inertial>
    </link>
    <joint name="j${{id}}" type="revolute">
      <parent link="${{parent}}"/>
      <child link="l${{id+1}}"/>
      <origin xyz="0 0 ${{seglen}}" rpy="0 ${{seg_angle/4}} 0"/>
      <axis xyz="0 1 0"/>
      <limit lower="${{-seg_angle}}" upper="${{seg_angle}}" effort="1" velocity="1"/>
    </joint>
  </xacro:macro>
  <link name="l0"/>
{calls}
</robot>
"""


if __name__ == "__main__":
    sys.stdout.write(flat_xacro(int(sys.argv[1]) if len(sys.argv) > 1 else 1000))
