"""Small models shared by the report, baseline, plugin and pre-commit tests."""

GOOD = '<robot name="r">\n  <link name="base_link"/>\n</robot>\n'

# a typo <orign>: U002, at line 5
BAD = """<robot name="r">
  <link name="base_link"/>
  <link name="arm"/>
  <joint name="j" type="fixed">
    <orign xyz="0 0 0.5"/>
    <parent link="base_link"/>
    <child link="arm"/>
  </joint>
</robot>
"""

# the same typo inside a macro called twice: two findings, one source line, two call sites
MACROS = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="leg" params="prefix">
    <link name="${prefix}_leg"/>
    <joint name="${prefix}_j" type="fixed">
      <orign xyz="0 0 0"/>
      <parent link="base_link"/>
      <child link="${prefix}_leg"/>
    </joint>
  </xacro:macro>
  <link name="base_link"/>
  <xacro:leg prefix="l"/>
  <xacro:leg prefix="r"/>
</robot>
"""
