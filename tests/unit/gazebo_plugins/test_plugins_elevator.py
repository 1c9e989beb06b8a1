"""gazebo_ros_elevator on a real Simulator: upstream's elevator (an 800 kg car on a prismatic lift from the world, a
1 kg door sliding on the car, elevator.world's damping and effort limits) goes to the floor a std_msgs/String names,
opening its door there, closing it after door_wait_time; a message while busy is dropped."""
import pytest
from std_msgs.msg import String

from model_plugin_sim import PluginWorld

FLOOR = 3.075
ELEVATOR = """<robot name="elevator">
 <link name="world"/>
 <link name="link"><inertial><mass value="800"/><inertia ixx="300" iyy="300" izz="300" ixy="0" ixz="0" iyz="0"/>
  </inertial><collision><geometry><box size="2.25 2.25 0.15"/></geometry></collision></link>
 <link name="door"><inertial><mass value="1"/><inertia ixx="0.5" iyy="0.5" izz="0.1" ixy="0" ixz="0" iyz="0"/>
  </inertial></link>
 <joint name="lift" type="prismatic"><parent link="world"/><child link="link"/><origin xyz="0 0 0.075"/>
  <axis xyz="0 0 1"/><limit lower="0" upper="10" effort="100000" velocity="100"/><dynamics damping="50"/></joint>
 <joint name="door" type="prismatic"><parent link="link"/><child link="door"/><origin xyz="1.0745 -0.5 1.125"/>
  <axis xyz="0 1 0"/><limit lower="0" upper="1" effort="10" velocity="100"/><dynamics damping="2"/></joint>
 <gazebo><plugin filename="libgazebo_ros_elevator.so" name="elevator_plugin">%s</plugin></gazebo>
</robot>"""
PARAMS = ('<lift_joint>elevator::lift</lift_joint><door_joint>elevator::door</door_joint>'
          '<floor_height>3.075</floor_height><door_wait_time>4</door_wait_time><topic>elevator</topic>')


def joints(w, robot):
    return [s.position for s in robot.body.joint_states([robot.body.joints[n].index
                                                                       for n in ('lift', 'door')])]


def test_it_goes_to_the_floor_opens_waits_and_closes(tmp_path):
    w = PluginWorld(tmp_path)
    try:
        robot = w.spawn('elevator', ELEVATOR % PARAMS)
        w.run(1.0)
        assert joints(w, robot) == pytest.approx([0.0, 0.0], abs=0.01)  # held at floor 0, door closed
        w.fake.subscribers['/elevator'](String(data=' 1'))
        opened = None
        for step in range(400):  # 40 s in 0.1 s steps
            w.run(0.1)
            lift, door = joints(w, robot)
            if opened is None and door > 0.95:
                opened = w.sim.time
                assert lift == pytest.approx(FLOOR, abs=0.15)  # the door opens only at the floor
            if step == 100:
                w.fake.subscribers['/elevator'](String(data='0'))  # busy: dropped, as upstream
        assert opened is not None
        lift, door = joints(w, robot)
        assert lift == pytest.approx(FLOOR, abs=0.1)  # p 1e5 against 800 kg of gravity: 0.08 m short at most
        assert door == pytest.approx(0.0, abs=0.05)  # closed again after the wait
    finally:
        w.close()


def test_without_floor_height_it_warns_and_uses_3_m(tmp_path):
    w = PluginWorld(tmp_path)
    try:
        robot = w.spawn('elevator', ELEVATOR % '<lift_joint>lift</lift_joint><door_joint>door</door_joint>')
        assert w.warnings('No <floor_height> specified for elevator plugin. Using a height of 3 meters')
        w.fake.subscribers['/elevator'](String(data='2'))
        w.run(25.0)
        assert joints(w, robot)[0] == pytest.approx(6.0, abs=0.1)
        w.fake.subscribers['/elevator'](String(data='up'))
        assert w.errors('Unable to process elevator message[up]')
    finally:
        w.close()


def test_an_unknown_joint_refuses_it(tmp_path):
    w = PluginWorld(tmp_path)
    try:
        w.spawn('elevator', ELEVATOR % '<lift_joint>lift</lift_joint><door_joint>gate</door_joint>')
        assert w.errors('Unable to find door joint[gate]')
    finally:
        w.close()
