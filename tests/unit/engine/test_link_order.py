"""A URDF's links in any document order load and move the same (issue 29 item 2).

PyBullet with URDF_MAINTAIN_LINK_ORDER crashed the process (SIGSEGV) on a URDF whose root link is not
written first, as a popular arm's xacro writes its `world` link last, and gave NaN states when a child link
came before its parent. The crash test spawns in a child Python, so a segfault is an exit code here.
"""
import subprocess
import sys
import textwrap

import pytest

from racebot_sim_bridge.description import urdf_reader
from racebot_sim_bridge.engine.physics import PhysicsWorld

INERTIAL = ('<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>'
            '</inertial><collision><geometry><box size="0.1 0.1 0.3"/></geometry></collision>'
            '<visual><geometry><box size="0.1 0.1 0.3"/></geometry></visual>')  # with visuals PyBullet aborted
LINKS = {
    'world': '<link name="world"/>',
    'link1': '<link name="link1">%s</link>' % INERTIAL,
    'link2': '<link name="link2">%s</link>' % INERTIAL,
    'tool': '<link name="tool">%s</link>' % INERTIAL,  # on a fixed joint: lumped into link2
}
JOINTS = (
    '<joint name="j1" type="revolute"><parent link="world"/><child link="link1"/><axis xyz="0 0 1"/>'
    '<limit lower="-1" upper="1" effort="10" velocity="1"/></joint>'
    '<joint name="j2" type="revolute"><parent link="link1"/><child link="link2"/><origin xyz="0 0 0.3"/>'
    '<axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="10" velocity="1"/></joint>'
    '<joint name="tool_joint" type="fixed"><parent link="link2"/><child link="tool"/><origin xyz="0 0 0.3"/></joint>'
)


def arm(order):
    """The arm's URDF with its links written in `order` (the joints after them)."""
    return '<robot name="arm">%s%s</robot>' % (''.join(LINKS[n] for n in order), JOINTS)


ROOT_FIRST = ('world', 'link1', 'link2', 'tool')
ORDERS = [('link1', 'link2', 'tool', 'world'),  # the arm package's xacro: root last
          ('tool', 'link2', 'link1', 'world'),  # every child before its parent
          ('link2', 'world', 'tool', 'link1')]


def swing(urdf, steps=300):
    """Spawns the arm, lets gravity swing it from j2 = 0.5, returns its joint positions and link2's pose."""
    world = PhysicsWorld(step_size=0.001)
    try:
        body = world.spawn_urdf('arm', urdf_reader.parse_urdf(urdf), urdf)
        body.joints['j2'].set_position(0.5)
        body.joints['j1'].apply_effort(0.0)
        for _ in range(steps):
            body.apply_efforts([body.joints['j1'].index], [2.0])
            world.step()
        joints = {name: round(s.position, 9) for name, s in
                  zip(body.joints, body.joint_states([j.index for j in body.joints.values()]))}
        pose = body.links['link2'].state()[0]
        return joints, tuple(round(v, 9) for v in pose.position), sorted(body.link_index)
    finally:
        world.close()


def test_root_link_written_last_does_not_crash_the_process():
    code = textwrap.dedent('''
        import sys
        from racebot_sim_bridge.description import urdf_reader
        from racebot_sim_bridge.engine.physics import PhysicsWorld
        urdf = sys.stdin.read()
        world = PhysicsWorld()
        body = world.spawn_urdf('arm', urdf_reader.parse_urdf(urdf), urdf)
        print(sorted(body.joints))
    ''')
    done = subprocess.run([sys.executable, '-c', code], input=arm(ORDERS[0]), capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, 'the spawn ended the process (exit code %d): %s' % (done.returncode, done.stderr)
    assert "['j1', 'j2']" in done.stdout


@pytest.mark.parametrize('order', ORDERS, ids=['root-last', 'children-first', 'shuffled'])
def test_any_link_order_moves_as_root_first(order):
    expected = swing(arm(ROOT_FIRST))
    assert expected[0]['j1'] > 0.05  # the effort turned it
    assert expected[2] == ['link1', 'link2', 'world']
    assert swing(arm(order)) == expected
