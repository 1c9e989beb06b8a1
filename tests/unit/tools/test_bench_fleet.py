"""The bench's fleet ceiling (tools/bench/fleet.py) does the sensors' own work: its laser casts the rays the laser
sensor casts (same origin, same directions) and its wheels turn at the speeds the command asks. A ceiling that casts
other rays (once 0.6 mm higher: from the base's centre of mass) measures other work, and the ratio means nothing.
Real PyBullet, no master."""
import math

import numpy as np
import pybullet as pb

from bench import common, fleet

import model_plugin_sim as mps
from racebot_sim_bridge.sensors.imu_reading import quaternion_to_matrix
from racebot_sim_bridge.gazebo_plugins.sensor_manager import SensorManager


def test_the_ceilings_laser_casts_the_laser_sensors_rays(tmp_path):
    urdf = mps.fixture_urdf('diffbot_plugins')
    w = mps.PluginWorld(tmp_path)
    sensors = SensorManager(mps.PluginRospy({'~sensors/report_period': 0, '~sensors/render_worker': False}), w.sim)
    ceiling = None
    try:
        w.spawn('robot0', urdf, '/robot0', (0.0, 0.0, 0.02))
        w.run(0.3)  # settled on its wheels, a little pitched and rolled perhaps: a pose of its own
        laser = next(s for s in sensors.sensors['robot0'] if s.spec.name == 'laser')
        with common.quiet_stdout():
            ceiling = fleet.FleetCeiling(common.fast_world(common.EMPTY_WORLD, str(tmp_path / 'e.world')), urdf, 1)
        # the ceiling's robot where the simulator's is; then the laser pose each works out
        pose = pb.getBasePositionAndOrientation(w.sim.robots['robot0'].body.id, physicsClientId=w.sim.world.client.id)
        pb.resetBasePositionAndOrientation(ceiling.bodies[0], *pose, physicsClientId=ceiling.client)
        origin, orientation = pb.multiplyTransforms(*pb.getBasePositionAndOrientation(
            ceiling.bodies[0], physicsClientId=ceiling.client), *ceiling.laser_offset)
        sensor_origin, sensor_orientation = laser.mount.pose()
        assert np.abs(np.array(origin) - sensor_origin).max() < 1e-9
        assert np.abs(quaternion_to_matrix(orientation) - quaternion_to_matrix(sensor_orientation)).max() < 1e-6
        assert np.abs(ceiling.directions - laser.geometry.directions).max() < 1e-12
        assert (laser.geometry.range_min, laser.geometry.range_max) == fleet.LASER_RANGE
        assert math.isclose(ceiling.laser_every * ceiling.step_size, 1.0 / laser.spec.update_rate)
    finally:
        if ceiling is not None:
            ceiling.close()
        sensors.close()
        w.close()
