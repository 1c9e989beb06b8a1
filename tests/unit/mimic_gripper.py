"""A gripper URDF with URDF <mimic> joints and gazebo_ros_control (gripper), and how the tests read and drive
its joints on a Simulator."""


INERTIAL = ('<inertial><origin xyz="0.05 0 0"/><mass value="0.3"/><inertia ixx="0.001" iyy="0.001" izz="0.001" '
            'ixy="0" ixz="0" iyz="0"/></inertial>')


def _link(name):
    return '<link name="%s">%s</link>\n' % (name, INERTIAL)


def _joint(name, child, kind='revolute', xyz='0 0 0.2', axis='0 1 0', extra=''):
    return ('<joint name="%s" type="%s"><parent link="base"/><child link="%s"/><origin xyz="%s"/><axis xyz="%s"/>'
            '<limit lower="-2" upper="2" effort="50" velocity="5"/>%s</joint>\n'
            % (name, kind, child, xyz, axis, extra))


def _transmission(joint, interface='PositionJointInterface'):
    return ('<transmission name="t_%s"><type>transmission_interface/SimpleTransmission</type><joint name="%s">'
            '<hardwareInterface>hardware_interface/%s</hardwareInterface></joint>'
            '<actuator name="m_%s"><mechanicalReduction>1</mechanicalReduction></actuator></transmission>\n'
            % (joint, joint, interface, joint))


def gripper(mimics, transmissions=('leader',)):
    """A fixed base with a leader joint and one joint per (name, kind, <mimic> attributes) of `mimics`; the
    mimic joints' links carry their mass off the axis, so gravity loads them."""
    body = '<link name="world"/>' + _link('base') + _link('leader_link')
    body += '<joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>\n'
    body += _joint('leader', 'leader_link')
    for i, (name, kind, attributes) in enumerate(mimics):
        body += _link(name + '_link')
        axis = '0 0 1' if kind == 'prismatic' else '0 1 0'
        body += _joint(name, name + '_link', kind, '0 %g 0.2' % (0.2 * (i + 1)), axis,
                       '<mimic %s/>' % attributes if attributes is not None else '')
    body += ''.join(_transmission(j) for j in transmissions)
    body += '<gazebo><plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so"/></gazebo>'
    return '<robot name="gripper">%s</robot>' % body


def positions(sim, robot, *names):
    states = robot.body.joint_states([robot.body.joints[n].index for n in names])
    return [s.position for s in states]


def drive(sim, robot, target, seconds):
    handle = robot.control.hw.handles['leader']
    for _ in range(int(round(seconds / sim.step_size))):
        handle.command = target
        sim.step()
