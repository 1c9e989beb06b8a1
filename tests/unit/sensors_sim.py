"""SensorManager on a real Simulator (PyBullet DIRECT, the room world, a robot from its URDF) with FakeRospy:
what the sensor and sensor-plugin tests build, and how they listen and step."""
from pathlib import Path

from racebot_sim_bridge.description import sdf_reader
from racebot_sim_bridge.gazebo_plugins.sensor_manager import SensorManager
from racebot_sim_bridge.engine.simulator import Simulator

from fakes import FakeLog, FakeRospy, NullIO

REPO = Path(__file__).resolve().parents[2]
ROOM = REPO / 'racebot_gazebo' / 'worlds' / 'room_mini.world'


def make_world(racebot_xml, params=None, pose=(0.0, 0.0, 0.0)):
    spec = sdf_reader.load_world(str(ROOM))
    sim = Simulator(spec, NullIO(), FakeLog(), lambda path: None)
    # Rendering in the physics thread (the old path), synchronous; test_render_worker.py covers the worker.
    fake = FakeRospy(dict({'~sensors/report_period': 0, '~sensors/render_budget': 1.0,
                           '~sensors/noise': False, '~sensors/render_worker': False}, **(params or {})))
    manager = SensorManager(fake, sim)
    robot = sim.spawn_urdf('racebot', racebot_xml, '/', pose)  # '/': spawn_model at the root
    frame = robot.body.com_pose_for_frame(pose, (0, 0, 0, 1))  # as spawn_urdf_model places it
    robot.body.set_pose(frame.position, frame.orientation)
    return sim, fake, manager, robot


def listen(fake, *topics):
    for t in topics:
        fake.publishers[t].connections = 1


def run(sim, seconds):
    for _ in range(int(round(seconds / sim.step_size))):
        sim.step()


def sensor_of(manager, kind):
    return next(s for s in manager._active if s.config.kind == kind)


RED_BOX = """<sdf version="1.6"><world name="w"><model name="red_box"><static>true</static>
<pose>{x} {y} {z} 0 0 0</pose><link name="link">
<collision name="c"><geometry><box><size>{s} {s} {s}</size></box></geometry></collision>
<visual name="v"><geometry><box><size>{s} {s} {s}</size></box></geometry>
<material><ambient>1 0 0 1</ambient><diffuse>1 0 0 1</diffuse></material></visual>
</link></model></world></sdf>"""


def add_red_box(sim, x, y, z, size):
    model = sdf_reader.parse_world(RED_BOX.format(x=x, y=y, z=z, s=size)).models[0]
    with sim.lock:
        sim.world.add_sdf_model(model)
