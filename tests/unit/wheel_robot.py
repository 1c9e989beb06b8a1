"""An empty world (1 ms steps) and a robot of one effort-driven wheel with the gazebo_ros_control plugin
(its <robotNamespace> element given as text): what the ros_control and gazebo_ros tests spawn."""


EMPTY_WORLD = '<sdf version="1.6"><world name="w"><physics type="ode"><max_step_size>0.001</max_step_size>' \
              '</physics></world></sdf>'


def _robot(control_ns_element):
    return ('<robot name="bot"><link name="base"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" '
            'iyy="0.01" iyz="0" izz="0.01"/></inertial></link><link name="wheel"><inertial><mass value="0.1"/>'
            '<inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial></link>'
            '<joint name="wheel_joint" type="continuous"><parent link="base"/><child link="wheel"/>'
            '<axis xyz="0 1 0"/></joint><transmission name="t"><type>transmission_interface/SimpleTransmission'
            '</type><joint name="wheel_joint"><hardwareInterface>hardware_interface/EffortJointInterface'
            '</hardwareInterface></joint><actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator>'
            '</transmission><gazebo><plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so">%s'
            '</plugin></gazebo></robot>' % control_ns_element)
