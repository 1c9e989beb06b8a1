"""The speed ceiling: bare PyBullet stepping of our own racebot, no ROS.

The same world file and model the simulator gets, loaded the same way (physics.PhysicsWorld:
fixed links merged, links without <inertial> made negligible, friction, joint motors off), the car
at the pose spawn_model gives it. Each step reads the six joint states and writes six torques
(the tutorial's gains as a plain PD toward standing still: the least a controller can do), then
steps. What the simulator adds on top (controllers, limits, /clock, services) is what the
bridge/ceiling ratio measures.
"""

import pybullet as pb

from racebot_sim_bridge.description import sdf_reader, urdf_reader
from racebot_sim_bridge.engine.physics import PhysicsWorld

from . import common

# Per joint (by name): position gain, velocity gain. racebot_control.yaml: wheels p 1 / 0.5 on
# velocity, hinges p 10, d 0.5 on position.
GAINS = {'left_rear_wheel_joint': (0.0, 1.0), 'right_rear_wheel_joint': (0.0, 1.0),
         'left_front_wheel_joint': (0.0, 0.5), 'right_front_wheel_joint': (0.0, 0.5),
         'left_steering_hinge_joint': (10.0, 0.5), 'right_steering_hinge_joint': (10.0, 0.5)}
SETTLE_S = 0.5  # sim seconds before timing: the car lands on its wheels


class Ceiling:
    def __init__(self, world_file, urdf_xml=None):
        spec = sdf_reader.load_world(world_file)
        self.step_size = spec.physics.max_step_size
        self.world = PhysicsWorld(self.step_size, spec.physics.gravity)
        self.world.load_world(spec)
        xml = urdf_xml or common.render_racebot()
        body = self.world.spawn_urdf('racebot', urdf_reader.parse_urdf(xml), xml)
        frame = body.com_pose_for_frame((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))  # as spawn_model -x 0 -y 0 -z 0
        body.set_pose(frame.position, frame.orientation)
        missing = set(GAINS) - set(body.joints)
        if missing:
            raise common.BenchError('the racebot model has no joints %s' % sorted(missing))
        self.body_id = body.id
        self.client = self.world.client.id  # the id itself: the ceiling is bare PyBullet calls, no bound functions
        self.indices = [body.joints[n].index for n in sorted(GAINS)]
        self.kp = [GAINS[n][0] for n in sorted(GAINS)]
        self.kd = [GAINS[n][1] for n in sorted(GAINS)]
        self.steps = 0
        self.run_steps(int(round(SETTLE_S / self.step_size)))

    def run_steps(self, n):
        body, client, indices = self.body_id, self.client, self.indices
        gains = list(zip(self.kp, self.kd))
        get, set_, step, torque = pb.getJointStates, pb.setJointMotorControlArray, pb.stepSimulation, pb.TORQUE_CONTROL
        for _ in range(n):
            states = get(body, indices, physicsClientId=client)
            forces = [-kp * s[0] - kd * s[1] for (kp, kd), s in zip(gains, states)]
            set_(body, indices, torque, forces=forces, physicsClientId=client)
            step(physicsClientId=client)
        self.steps += n

    def measure(self, wall_seconds, chunk=200):
        """Steps for about wall_seconds; returns steps per wall second."""
        return common.steps_per_second(self.run_steps, wall_seconds, chunk)

    def close(self):
        self.world.close()
