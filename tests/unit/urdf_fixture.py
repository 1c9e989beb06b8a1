"""A small car's URDF with Gazebo extensions (FIXTURE), and helpers to write URDF around a body."""


EFFORT = 'hardware_interface/EffortJointInterface'

FIXTURE = """<?xml version="1.0"?>
<robot name="minicar">
  <material name="black"><color rgba="0 0 0 1"/></material>
  <link name="base_footprint"/>
  <link name="base_link">
    <inertial>
      <origin xyz="0 0 0.01"/>
      <mass value="4"/>
      <inertia ixx="0.0264" ixy="0" ixz="0" iyy="0.0294" iyz="0" izz="0.00364"/>
    </inertial>
    <collision><geometry><box size="0.28 0.10 0.03"/></geometry></collision>
    <visual>
      <origin xyz="0 0 0" rpy="0 0 1.5708"/>
      <geometry><mesh filename="package://minicar/meshes/body.stl" scale="0.001 0.001 0.001"/></geometry>
      <material name="black"/>
    </visual>
  </link>
  <link name="lidar"/>
  <link name="left_hinge">
    <collision><geometry><cylinder radius="0.01" length="0.005"/></geometry></collision>
  </link>
  <link name="left_wheel">
    <collision><geometry><sphere radius="0.032"/></geometry></collision>
    <visual><geometry><cylinder radius="0.033" length="0.02"/></geometry>
      <material name="red"><color rgba="1 0 0 1"/></material></visual>
  </link>
  <joint name="base_joint" type="fixed">
    <parent link="base_footprint"/><child link="base_link"/>
    <origin xyz="0 0 0.032"/>
  </joint>
  <joint name="lidar_joint" type="fixed">
    <parent link="base_link"/><child link="lidar"/>
    <origin xyz="0.09 0 0.12" rpy="0 0 1.5707963267948966"/>
  </joint>
  <joint name="left_hinge_joint" type="revolute">
    <parent link="base_link"/><child link="left_hinge"/>
    <origin xyz="0.13 0.065 0"/>
    <axis xyz="0 0 1"/>
    <limit lower="-0.6" upper="0.6" effort="5" velocity="1000"/>
  </joint>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="left_hinge"/><child link="left_wheel"/>
    <origin xyz="0 0.025 0"/>
    <axis xyz="0 1 0"/>
    <limit effort="10" velocity="1000"/>
    <dynamics damping="0.1" friction="0.2"/>
  </joint>
  <transmission name="left_hinge_trans">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="left_hinge_joint">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>
    <actuator name="left_hinge_motor">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
      <mechanicalReduction>1</mechanicalReduction>
    </actuator>
  </transmission>
  <transmission name="left_wheel_trans">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="left_wheel_joint">
      <hardwareInterface>EffortJointInterface</hardwareInterface>
    </joint>
    <actuator name="left_wheel_motor"><mechanicalReduction>2</mechanicalReduction></actuator>
  </transmission>
  <gazebo reference="left_wheel">
    <mu1>2.0</mu1><mu2>2.0</mu2><kp>1e7</kp><kd>1</kd><material>Gazebo/Black</material>
  </gazebo>
  <gazebo>
    <plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so">
      <robotNamespace>/minicar</robotNamespace>
      <controlPeriod>0.002</controlPeriod>
    </plugin>
  </gazebo>
  <gazebo reference="lidar">
    <sensor type="ray" name="hokuyo">
      <pose>0 0 0 0 0 0</pose>
      <visualize>false</visualize>
      <update_rate>40</update_rate>
      <ray>
        <scan><horizontal>
          <samples>1081</samples><resolution>1</resolution>
          <min_angle>-2.3561944902</min_angle><max_angle>2.3561944902</max_angle>
        </horizontal></scan>
        <range><min>0.1</min><max>10.0</max><resolution>0.01</resolution></range>
        <noise><type>gaussian</type><mean>0.0</mean><stddev>0.01</stddev></noise>
      </ray>
      <plugin name="laser" filename="libgazebo_ros_laser.so">
        <topicName>/scan</topicName><frameName>lidar</frameName>
      </plugin>
    </sensor>
  </gazebo>
</robot>
"""


def with_body(body, name='r'):
    return '<robot name="%s">%s</robot>' % (name, body)
