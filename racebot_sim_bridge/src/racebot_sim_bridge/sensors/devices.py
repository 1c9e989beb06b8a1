"""The simulated sensors, one class per gazebo_ros plugin: laser, camera, depth camera, IMU.

Each sensor runs the pipeline on the physics thread after every step: its schedule says whether an
update is due (schedule.py); if anybody listens it measures (laser: raycast.py; IMU: imu.py;
cameras: a frame from the render worker or, without one, rendered here: render.py,
render_worker.py) and builds the messages (messages.py), stamped with the sim time of the
measurement. A camera frame rendered by the worker is published from the worker's reader thread
when it is ready, still stamped with the sim time whose poses it shows.
"""
import time as walltime

import numpy as np
from gazebo_msgs.msg import ContactsState
from sensor_msgs.msg import CameraInfo, Image, Imu, LaserScan, PointCloud2, Range
from sensor_msgs.srv import SetCameraInfo

from racebot_sim_bridge.sensors import messages as msgs
from racebot_sim_bridge.kinematics.rotations import quaternion_multiply, rpy_to_quaternion
from racebot_sim_bridge.engine.sim_time import ros_time
from racebot_sim_bridge.sensors.camera import PinholeCamera, mask_depth
from racebot_sim_bridge.sensors.contact import contact_collision_after_lumping, group_contacts, urdf_collision_shapes
from racebot_sim_bridge.sensors.contact_points import CollisionKinds, CollisionNames, link_com, read_contacts
from racebot_sim_bridge.sensors.imu_reading import ImuKinematics, quaternion_to_matrix
from racebot_sim_bridge.sensors.mount import SensorMount
from racebot_sim_bridge.sensors.noise import AxisNoise, make_noise
from racebot_sim_bridge.sensors.ray import ScanGeometry
from racebot_sim_bridge.sensors.range_reading import radiation_type, range_reading, ray_lengths
from racebot_sim_bridge.sensors.raycast import cast_rays
from racebot_sim_bridge.sensors.render import TINY, CameraFrames
from racebot_sim_bridge.sensors.render_worker import FrameBuffers, InFlight
from racebot_sim_bridge.sensors.schedule import FrameThrottle, RateMeter, UpdateSchedule


# Frames of one camera the worker may hold at once. With one, the worker sat idle after each frame
# until the camera's next due time; with two, the next frame already waits in its queue (measured:
# 11.7 -> 12.5 Hz for the 800 x 800 camera). Each frame is still of the sim time it is stamped with.
FRAMES_IN_WORKER = 2


def _serialized(msg):
    from io import BytesIO
    buf = BytesIO()
    msg.serialize(buf)
    return buf.getvalue()


class Sensor(object):
    """One simulated sensor: its schedule, mount, publishers and rate meter."""
    main_topic = None  # the role whose rate is reported

    def __init__(self, manager, robot, spec, config):
        self.manager = manager
        self.sim = manager.sim
        self.robot_name = robot.name
        self.spec = spec
        self.config = config
        self.mount = SensorMount(self.sim.world, robot.body, robot.model, spec.reference, spec.pose)
        self.schedule = UpdateSchedule(config.rate, start=self.sim.time)
        self.meter = RateMeter()
        self.publishers = {}
        self.failed = False

    def advertise(self, role, msg_class, queue_size):
        self.publishers[role] = self.manager.rospy.Publisher(self.config.topics[role], msg_class,
                                                             queue_size=queue_size)

    def listened(self, *roles):
        """True when any of the roles' topics (all, if none named) has a subscriber."""
        publishers = self.publishers
        for role in roles or publishers:  # a loop, not any(...): every sensor asks at every update
            if publishers[role].get_num_connections() > 0:
                return True
        return False

    def wake_time(self):
        """The sim time this sensor next needs a step(): its next update (the manager skips it till then)."""
        return self.schedule.next

    def step(self, time):
        if not self.schedule.due(time):
            return
        self.schedule.advance(time)
        self.update(time, ros_time(self.manager.rospy.Time, time))

    def update(self, time, stamp):
        raise NotImplementedError

    def close(self):
        publishers, self.publishers = self.publishers, {}
        for p in publishers.values():
            p.unregister()
        service, self.service = getattr(self, 'service', None), None
        if service is not None:
            service.shutdown()
        buffers = getattr(self, 'buffers', None)
        if buffers is not None:
            buffers.close()

    @property
    def topic(self):
        return self.config.topics[self.main_topic]


class LaserSensor(Sensor):
    main_topic = 'scan'

    def __init__(self, manager, robot, spec, config):
        super(LaserSensor, self).__init__(manager, robot, spec, config)
        self.geometry = ScanGeometry(spec.ray)
        ray = spec.ray
        self.noise = make_noise(ray.noise_type, ray.noise_mean, ray.noise_stddev, manager.noise_enabled)
        self.advertise('scan', LaserScan, 5)

    def update(self, time, stamp):
        if not self.listened():
            return
        position, orientation = self.mount.pose()
        starts, ends = self.geometry.endpoints(position, quaternion_to_matrix(orientation))
        world = self.sim.world
        retro = world.laser_retro
        intensities = None
        if retro:  # Gazebo's ray intensity: the laser_retro of the collision hit, 0 for a miss or none set
            fractions, hit, objects = cast_rays(world, starts, ends, objects=True)
            intensities = [retro.get(o, 0.0) for o in objects]
        else:
            fractions, hit = cast_rays(world, starts, ends)
        ranges = self.geometry.report(self.geometry.ranges_from_hits(fractions, hit), self.noise)
        self.publishers['scan'].publish(msgs.laser_scan(stamp, self.config.frame_id, self.geometry, ranges,
                                                        intensities))
        self.meter.tick()


class CameraSensor(Sensor):
    """gazebo_ros_camera: image + camera_info."""
    main_topic = 'image'

    def __init__(self, manager, robot, spec, config):
        super(CameraSensor, self).__init__(manager, robot, spec, config)
        cam = spec.camera
        self.encoding = msgs.image_encoding(cam.format)
        if cam.format not in msgs.IMAGE_ENCODINGS:
            config.warnings.append("sensor '%s': image format %r is not one gazebo_ros_camera knows (L8, L16, R8G8B8, "
                                   "B8G8R8, R16G16B16, BAYER_RGGB8, ...); published as bgr8, as upstream does"
                                   % (spec.name, cam.format))
        self.stored_info = None  # a camera_info set through set_camera_info (camera_info_manager's), else None
        self.camera = PinholeCamera(cam.width, cam.height, cam.horizontal_fov, cam.clip_near, cam.clip_far)
        noise = make_noise(cam.noise_type, cam.noise_mean, cam.noise_stddev, manager.noise_enabled)
        self.frames = CameraFrames(self.camera, noise)  # frames rendered in the physics thread
        # What the worker needs to make this camera's frames (hashable: it keys them by it).
        self.worker_camera = (self.camera.width, self.camera.height, self.camera.hfov, self.camera.near,
                              self.camera.far, noise.mean if noise else 0.0, noise.stddev if noise else None)
        self.buffers = None  # FrameBuffers shared with the worker, made for the first frame it renders
        self.in_worker = InFlight(FRAMES_IN_WORKER)  # frames sent to the worker, not rendered yet
        self.throttle = FrameThrottle(config.params.get('update_rate', 0.0))
        self.advertise('image', Image, 2)
        self.advertise('info', CameraInfo, 2)
        self.service = manager.rospy.Service(config.params['set_camera_info'], SetCameraInfo, self.set_camera_info)

    def set_camera_info(self, req):
        """camera_info_manager's set_camera_info: the camera_info published from now on (until the model goes).
        Upstream also writes it to ~/.ros/camera_info/<camera>.yaml; racebot keeps it in memory only."""
        from sensor_msgs.srv import SetCameraInfoResponse
        info = req.camera_info
        if (info.width, info.height) not in ((0, 0), (self.camera.width, self.camera.height)):
            return SetCameraInfoResponse(False, 'camera_info is %d x %d; this camera is %d x %d'
                                         % (info.width, info.height, self.camera.width, self.camera.height))
        self.stored_info = info  # one assignment: the publishing thread sees the old or the new one
        return SetCameraInfoResponse(True, 'camera_info stored (in memory: racebot writes no calibration file)')

    def info(self, stamp):
        stored = self.stored_info
        if stored is not None:
            msg = CameraInfo()
            msg.deserialize(_serialized(stored))  # a copy: the stored one is published from two threads
            msg.header.stamp = stamp
            return msg
        p = self.config.params
        return msgs.camera_info(stamp, self.config.frame_id, self.camera, p['baseline'], p['distortion'],
                                self.camera.reported_intrinsics(p.get('focal_length', 0.0), p.get('cx', 0.0),
                                                                p.get('cy', 0.0)))

    def capture(self, time, stamp, wanted, want_depth):
        """A frame of the world at sim `time`, published as `wanted` roles when it is ready: from the
        render worker when there is one, else rendered here within the render budget. A frame
        that cannot be taken is skipped (counted)."""
        manager = self.manager
        if manager.worker_expected():
            worker = manager.worker
            if not worker.ready or not self.in_worker.take():
                self.meter.skip()  # starting, restarting, or this camera's frames not rendered yet
                return
            if self.buffers is None:
                self.buffers = FrameBuffers(self.camera.width, self.camera.height, FRAMES_IN_WORKER + 1)
            slot = self.buffers.take()
            if slot is None:  # every buffer still being rendered or published
                self.in_worker.give_back()
                self.meter.skip()
                return
            position, orientation = self.mount.pose()
            buffers = self.buffers

            def done(rgb, depth):
                self.in_worker.give_back()
                try:
                    self.publish_frame(stamp, wanted, rgb, depth)
                finally:
                    buffers.give_back(slot)

            def failed(reason):
                self.in_worker.give_back()
                buffers.give_back(slot)
                self.meter.skip()
                manager.frame_failed(self, reason)

            if not worker.submit(self.sim.world, manager.snapshot(), self.worker_camera, position,
                                 quaternion_to_matrix(orientation), want_depth, buffers, slot, done, failed):
                self.in_worker.give_back()
                buffers.give_back(slot)
                self.meter.skip()
            return
        budget = manager.budget
        if not budget.allow(self):
            self.meter.skip()
            return
        start = walltime.perf_counter()
        planes = manager.scene_colours().planes
        position, orientation = self.mount.pose()
        rgb, depth = self.frames.make(self.sim.world, TINY, planes, position, quaternion_to_matrix(orientation),
                                      want_depth)
        budget.spend(walltime.perf_counter() - start)
        self.publish_frame(stamp, wanted, rgb, depth)

    def update(self, time, stamp):
        if not self.listened('image'):
            if self.listened('info'):  # camera_info alone needs no render
                self.publishers['info'].publish(self.info(stamp))
            return
        if not self.throttle.passes(time):  # gazebo_ros_camera's updateRate: skips whole frames
            return
        self.capture(time, stamp, {'image'}, want_depth=False)

    def publish_frame(self, stamp, wanted, rgb, depth):
        pubs = self.publishers  # the reader thread may publish while the robot is deleted
        if self.failed or not pubs:
            return
        pubs['image'].publish(msgs.rgb_image(stamp, self.config.frame_id, rgb, self.encoding))
        pubs['info'].publish(self.info(stamp))
        self.meter.tick()


class DepthCameraSensor(CameraSensor):
    """gazebo_ros_openni_kinect: rgb image, depth image (32FC1 m), point cloud, two camera_infos.
    Depth is worked out only while its depth image or point cloud has a subscriber."""
    main_topic = 'depth'

    def __init__(self, manager, robot, spec, config):
        super(DepthCameraSensor, self).__init__(manager, robot, spec, config)
        self.advertise('depth', Image, 2)
        self.advertise('depth_info', CameraInfo, 2)
        self.advertise('points', PointCloud2, 2)
        self.rays = None  # per-pixel rays of the point cloud, made when first needed

    def update(self, time, stamp):
        wanted = {role for role in ('image', 'depth', 'points') if self.listened(role)}
        if not wanted:
            for role in ('info', 'depth_info'):
                if self.listened(role):
                    self.publishers[role].publish(self.info(stamp))
            return
        self.capture(time, stamp, wanted, want_depth=bool(wanted & {'depth', 'points'}))

    def publish_frame(self, stamp, wanted, rgb, depth):
        pubs = self.publishers
        if self.failed or not pubs:
            return
        frame_id = self.config.frame_id
        if depth is not None and wanted & {'depth', 'points'}:
            depth = mask_depth(depth, self.config.params['cutoff'], self.config.params['cutoff_max'])
            if 'depth' in wanted:
                millimetres = self.config.params.get('depth_16uc1', False)
                pubs['depth'].publish(msgs.depth_image(stamp, frame_id, depth, millimetres))
            if 'points' in wanted:
                if self.rays is None:
                    self.rays = self.camera.rays_optical()
                points = self.camera.points(depth, self.rays)
                pubs['points'].publish(msgs.point_cloud(stamp, frame_id, points, rgb))
        if 'image' in wanted:
            pubs['image'].publish(msgs.rgb_image(stamp, frame_id, rgb, self.encoding))
        for role in ('info', 'depth_info'):
            pubs[role].publish(self.info(stamp))
        self.meter.tick()


class ImuSensor(Sensor):
    """gazebo_ros_imu_sensor on Gazebo's ImuSensor: per-axis noise with bias (<imu><angular_velocity><x>...),
    the plugin's gaussianNoise on every field, rpyOffset, initialOrientationAsReference, and the acceleration
    over the physics step that ends at each update (the velocity is recorded one step before: wake_time)."""
    main_topic = 'imu'

    def __init__(self, manager, robot, spec, config):
        super(ImuSensor, self).__init__(manager, robot, spec, config)
        reference = self.mount.pose()[1] if config.params.get('initial_orientation_as_reference') else None
        self.kinematics = ImuKinematics(manager.sim.world.gravity, reference)
        enabled = manager.noise_enabled
        imu = spec.imu
        self.gyro_noise = AxisNoise.make(imu.angular_velocity_noise, enabled)
        self.accel_noise = AxisNoise.make(imu.linear_acceleration_noise, enabled)
        self.plugin_stddev = config.params['gaussian_noise']
        self.plugin_noise = make_noise('gaussian', 0.0, self.plugin_stddev, enabled)
        self.offset = rpy_to_quaternion(*config.params['rpy_offset'])
        self.advertise('imu', Imu, 10)

    def wake_time(self):
        # The step before an update primes the velocity, while somebody listens; unheard, only the update
        # (which resets the kinematics: the first update heard again primes the next).
        if self.listened():
            return self.schedule.next - self.sim.step_size
        return self.schedule.next

    def step(self, time):
        if not self.schedule.due(time):
            if time >= self.schedule.next - self.sim.step_size - 1e-9 and self.listened():
                self.kinematics.prime(time, self.mount.motion()[2])
            return
        super(ImuSensor, self).step(time)

    def update(self, time, stamp):
        if not self.listened():
            self.kinematics.reset()  # a silence: the next update after it has no velocity to start from
            return
        _, orientation, velocity, omega = self.mount.motion()
        m = self.kinematics.measure(time, orientation, velocity, omega)
        if m is None:
            return
        q = np.asarray(quaternion_multiply(self.offset, m.orientation))  # the plugin's rpyOffset
        gyro, accel = m.angular_velocity, m.linear_acceleration
        if self.gyro_noise is not None:
            gyro = self.gyro_noise.apply(gyro)
        if self.accel_noise is not None:
            accel = self.accel_noise.apply(accel)
        if self.plugin_noise is not None:  # gazebo_ros_imu_sensor's gaussianNoise: on every field
            gyro, accel = self.plugin_noise.apply(gyro), self.plugin_noise.apply(accel)
            q = self.plugin_noise.apply(q)
            q = q / np.linalg.norm(q)  # unlike the plugin, keep it a unit quaternion
        self.publishers['imu'].publish(msgs.imu(stamp, self.config.frame_id, q, gyro, accel, self.plugin_stddev))
        self.meter.tick()


class RangeSensor(Sensor):
    """gazebo_ros_range: the ray sensor's shortest ray as sensor_msgs/Range (range_reading.py)."""
    main_topic = 'range'

    def __init__(self, manager, robot, spec, config):
        super(RangeSensor, self).__init__(manager, robot, spec, config)
        self.geometry = ScanGeometry(spec.ray)
        self.throttle = FrameThrottle(config.params['update_rate'])
        stddev = config.params['gaussian_noise']
        self.noise = make_noise('gaussian', 0.0, stddev, manager.noise_enabled) if stddev > 0 else None
        self.radiation = radiation_type(config.params['radiation'])
        self.advertise('range', Range, 1)

    def update(self, time, stamp):
        if not self.throttle.passes(time) or not self.listened():
            return
        position, orientation = self.mount.pose()
        starts, ends = self.geometry.endpoints(position, quaternion_to_matrix(orientation))
        fractions, hit = cast_rays(self.sim.world, starts, ends)
        g = self.geometry
        sample = float(self.noise.apply(0.0)) if self.noise is not None else 0.0
        reading = range_reading(ray_lengths(fractions, hit, g.range_min, g.range_max), g.range_max, sample)
        self.publishers['range'].publish(msgs.range_message(
            stamp, self.config.frame_id, self.radiation, self.config.params['fov'], g.range_min, g.range_max,
            reading))
        self.meter.tick()


class BumperSensor(Sensor):
    """gazebo_ros_bumper: the contacts of the sensor's <contact><collision>s as
    gazebo_msgs/ContactsState, every sensor update (an empty list when nothing touches)."""
    main_topic = 'bumper'

    def __init__(self, manager, robot, spec, config):
        super(BumperSensor, self).__init__(manager, robot, spec, config)
        self.body_id = robot.body.id
        self.model_name = robot.name
        self.link = self.mount.link
        self.shapes = urdf_collision_shapes(robot.model, self.link)
        known = [shape.name for shape in self.shapes]
        self.wanted = set()
        for written in config.params['collisions']:
            name = contact_collision_after_lumping(robot.model, spec.reference, written)
            self.wanted.add(name)
            if name not in known:  # Gazebo's bumper would report nothing, silently: say why once
                config.warnings.append(
                    "sensor '%s': <contact><collision> %r%s names no collision of link %r, so the bumper reports "
                    'no contact, as in Gazebo; Gazebo names its collisions %s'
                    % (spec.name, written, '' if name == written else ' (which sdformat rewrites to %r)' % name,
                       self.link, ', '.join(repr(k) for k in known) or '(it has none)'))
        self.names = CollisionNames(self.sim.world)
        self.kinds = CollisionKinds(self.sim.world.client)
        self.bodies_seen = None
        self.advertise('bumper', ContactsState, 1)

    def update(self, time, stamp):
        if not self.listened():
            return
        world = self.sim.world
        bodies = tuple(id(b) for b in world.bodies.values())
        if bodies != self.bodies_seen:  # a body came or went: PyBullet ids may have been reused
            self.names.forget()
            self.kinds.forget()
            self.bodies_seen = bodies
        index = self.mount.index
        points = read_contacts(world, self.names, self.body_id, index, self.shapes, self.model_name, self.link,
                               self.wanted, self.kinds)
        com, orientation = link_com(world.client, self.body_id, index)
        groups = group_contacts(points, com, orientation)
        self.publishers['bumper'].publish(msgs.contacts_state(stamp, self.config.frame_id, groups, stamp.to_sec()))
        self.meter.tick()


def make_sensors(manager, robot, spec, config):
    """[Sensor] for a SensorConfig: one, or one camera per side of a multicamera."""
    if config.kind == 'multicamera':
        return [CameraSensor(manager, robot, part_spec, part) for part_spec, part in config.params['parts']]
    return [SENSOR_CLASSES[config.kind](manager, robot, spec, config)]


SENSOR_CLASSES = {'laser': LaserSensor, 'camera': CameraSensor, 'depth': DepthCameraSensor, 'imu': ImuSensor,
                  'range': RangeSensor, 'bumper': BumperSensor}
