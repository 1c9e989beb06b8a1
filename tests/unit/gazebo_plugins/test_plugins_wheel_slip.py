"""gazebo_ros_wheel_slip on a real Simulator: the wheels are read as WheelSlipPlugin reads them (radius from the
cylinder, upstream's errors for a bad wheel), the dynamic_reconfigure server sits under <model>/wheel_slip with
WheelSlip.cfg's parameters and sets every wheel's compliance, and the warning says the slip is not simulated: a
wheel driven against its load grips exactly as without the plugin."""
import pytest

from model_plugin_sim import PluginWorld

WHEEL = """<link name="%s"><inertial><mass value="1"/>
 <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
 <collision><origin rpy="1.5708 0 0"/><geometry><cylinder radius="0.1" length="0.05"/></geometry>
 </collision></link>
<joint name="%s_joint" type="continuous"><parent link="base"/><child link="%s"/><origin xyz="%s"/>
 <axis xyz="0 1 0"/></joint>"""
ROBOT = """<robot name="cart">
 <link name="base"><inertial><mass value="20"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
  <collision><geometry><box size="0.6 0.4 0.1"/></geometry></collision></link>
 %s
 <gazebo>%s</gazebo>
</robot>""" % (''.join(WHEEL % (n, n, n, xyz) for n, xyz in (('left', '0 0.25 -0.05'), ('right', '0 -0.25 -0.05'))),
               '%s')
PLUGIN = """<plugin name="wheel_slip" filename="libgazebo_ros_wheel_slip.so">%s
 <wheel link_name="left"><slip_compliance_lateral>0.5</slip_compliance_lateral>
  <slip_compliance_longitudinal>1.5</slip_compliance_longitudinal><wheel_normal_force>98</wheel_normal_force></wheel>
 <wheel link_name="right"><wheel_normal_force>98</wheel_normal_force><wheel_radius>0.11</wheel_radius></wheel>
</plugin>"""


def spawn(tmp_path, plugin, namespace='/'):
    w = PluginWorld(tmp_path)
    return w, w.spawn('cart', ROBOT % plugin, namespace, pose=(0.0, 0.0, 0.16))


def roll(w, robot, seconds=1.0):
    """Drives both wheels with 4 N m each; the cart's forward speed."""
    body = robot.body
    for _ in range(int(seconds / w.sim.step_size)):
        body.apply_efforts([body.joints['left_joint'].index, body.joints['right_joint'].index],
                                  [4.0, 4.0])
        w.sim.step()
    return body.twist().linear[0]


def test_wheels_reconfigure_and_the_warning(tmp_path):
    w, robot = spawn(tmp_path, PLUGIN % '')
    try:
        plugin = w.manager.plugins['cart'][0]
        left, right = plugin.wheels
        assert (left.link, left.lateral, left.longitudinal, left.normal_force, left.radius) == ('left', 0.5, 1.5, 98,
                                                                                               0.1)
        assert (right.lateral, right.longitudinal, right.radius) == (0.0, 0.0, 0.11)
        server = w.servers['/cart/wheel_slip']
        assert server.config == {'slip_compliance_unitless_lateral': -1.0,
                                 'slip_compliance_unitless_longitudinal': -1.0}  # -1: nothing changed
        assert left.lateral == 0.5
        server.change(slip_compliance_unitless_lateral=2.5)
        assert (left.lateral, right.lateral, left.longitudinal) == (2.5, 2.5, 1.5)
        assert w.warnings('slip compliance is not simulated')
    finally:
        w.close()


def test_the_wheels_grip_as_without_the_plugin(tmp_path):
    w, robot = spawn(tmp_path, PLUGIN % '')
    w.manager.plugins['cart'][0]  # loaded
    with_plugin = roll(w, robot)
    w.close()
    w, robot = spawn(tmp_path, '')
    without = roll(w, robot)
    w.close()
    assert with_plugin == pytest.approx(without, abs=1e-9) and abs(without) > 0.1


def test_namespace_and_bad_wheels(tmp_path):
    bad = ('<robotNamespace>slip</robotNamespace><wheel><wheel_normal_force>1</wheel_normal_force></wheel>'
           '<wheel link_name="base"><wheel_normal_force>1</wheel_normal_force></wheel>'
           '<wheel link_name="nowhere"/>')
    w, robot = spawn(tmp_path, PLUGIN % bad)
    try:
        assert '/cart/slip' in w.servers
        assert w.errors('wheel element missing link_name attribute')
        assert w.errors('There should be 1 parent joint for link named [base] in model [cart], but 0 were found')
        assert w.errors('Could not find link named [nowhere]')
        assert len(w.manager.plugins['cart'][0].wheels) == 2
    finally:
        w.close()
    w, robot = spawn(tmp_path, PLUGIN % '', namespace='/fleet')  # spawn_model -robot_namespace /fleet
    try:
        assert list(w.servers) == ['/cart/fleet']  # upstream: NodeHandle('cart//fleet/')
    finally:
        w.close()
    w, robot = spawn(tmp_path, '<plugin name="s" filename="libgazebo_ros_wheel_slip.so"><wheel link_name="left"/>'
                     '</plugin>')
    try:
        assert w.errors('Found wheel normal force [0], which is not positive in link named [left]')
        assert w.errors('No ODE links and surfaces found, plugin is disabled')
    finally:
        w.close()
