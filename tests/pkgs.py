"""Small ROS packages for the contract tests and the catalogue examples: a wheeled base or an arm, with a
<ros2_control> block, Gazebo plugins and a controller file. Every defect a test seeds is one argument away from
its clean twin."""
from __future__ import annotations

PACKAGE_XML = """<?xml version="1.0"?>
<package format="3">
  <name>bot_description</name>
  <version>0.1.0</version>
  <description>Example robot</description>
  <maintainer email="dev@example.com">dev</maintainer>
  <license>Apache-2.0</license>
</package>
"""

INERTIA = ('<inertial><mass value="1.0"/>'
           '<inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>')


def wheel(name, xyz, axis="0 1 0", rpy="0 0 0", parent="base_link", radius=0.05):
    """A continuous wheel joint and its link (cylinder lying along the joint axis y)."""
    return f"""  <link name="{name}_link">
    {INERTIA}
    <collision>
      <origin xyz="0 0 0" rpy="1.5708 0 0"/>
      <geometry><cylinder radius="{radius}" length="0.04"/></geometry>
    </collision>
  </link>
  <joint name="{name}_joint" type="continuous">
    <parent link="{parent}"/>
    <child link="{name}_link"/>
    <origin xyz="{xyz}" rpy="{rpy}"/>
    <axis xyz="{axis}"/>
  </joint>
"""


def steer(name, xyz):
    """A revolute steering joint (z) with a link under it."""
    return f"""  <link name="{name}_link">{INERTIA}</link>
  <joint name="{name}_joint" type="revolute">
    <parent link="base_link"/>
    <child link="{name}_link"/>
    <origin xyz="{xyz}"/>
    <axis xyz="0 0 1"/>
    <limit lower="-0.6" upper="0.6" effort="10" velocity="1"/>
  </joint>
"""


def arm_joint(name, parent, child, kind="revolute"):
    return f"""  <link name="{child}">{INERTIA}</link>
  <joint name="{name}" type="{kind}">
    <parent link="{parent}"/>
    <child link="{child}"/>
    <origin xyz="0 0 0.1"/>
    <axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
"""


def r2c(joints, sensors=(), gpios=(), sim=False):
    """<ros2_control>: joints as {name: (command interfaces, state interfaces)}; sensors/gpios: names."""
    items = []
    for j, (cmd, st) in joints.items():
        inner = "".join(f'<command_interface name="{c}"/>' for c in cmd)
        inner += "".join(f'<state_interface name="{s}"/>' for s in st)
        items.append(f'    <joint name="{j}">{inner}</joint>')
    for s in sensors:
        items.append(f'    <sensor name="{s}"><state_interface name="orientation.x"/></sensor>')
    for g in gpios:
        items.append(f'    <gpio name="{g}"><command_interface name="out"/><state_interface name="out"/></gpio>')
    plugin = "gazebo_ros2_control/GazeboSystem" if sim else "mock_components/GenericSystem"
    body = "\n".join(items)
    return f"""  <ros2_control name="hw" type="system">
    <hardware><plugin>{plugin}</plugin></hardware>
{body}
  </ros2_control>
"""


def robot(*parts, name="bot"):
    body = "".join(parts)
    return f"""<?xml version="1.0"?>
<robot name="{name}">
  <link name="base_link">
    <visual><geometry><box size="0.5 0.3 0.1"/></geometry></visual>
  </link>
{body}</robot>
"""


def gazebo(plugin_xml):
    return f"  <gazebo>\n{plugin_xml}  </gazebo>\n"


def write(folder, urdf, files):
    """The package in `folder`: package.xml, urdf/bot.urdf and `files` ({relative path: text}); the URDF path."""
    (folder / "urdf").mkdir(parents=True, exist_ok=True)
    (folder / "package.xml").write_text(PACKAGE_XML, encoding="utf-8")
    (folder / "urdf" / "bot.urdf").write_text(urdf, encoding="utf-8")
    for rel, text in files.items():
        p = folder / rel
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text, encoding="utf-8")
    return folder / "urdf" / "bot.urdf"
