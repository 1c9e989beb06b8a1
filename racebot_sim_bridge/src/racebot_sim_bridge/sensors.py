"""The simulated sensors: what gazebo_ros's laser, camera, depth camera and IMU plugins publish.

SensorManager(rospy, sim) hooks into a Simulator: when a URDF robot spawns, every
<gazebo reference><sensor> block of its URDF that carries a gazebo_ros plugin becomes a sensor
(sensors_config says which topics, frame and rate); after every physics step each sensor whose
update is due in sim time measures the world and publishes, stamped with that sim time.

Cost is paid only for what somebody reads: a sensor whose topics have no subscriber does no
ray cast, render or message at all. Ray casts and renders run on the physics client inside the
step (under the simulator's lock), so what a sensor reports is the world at its stamp. Cameras
share a wall-time render budget (sensors_schedule.RenderBudget): frames beyond it are skipped,
and the rates really achieved are measured and reported.

Private parameters of the world server node (/gazebo), read once at start:
  ~sensors/noise          (bool, true)  false: all sensor noise off, whatever the URDF declares
                                        (tests that compare readings with the world's geometry)
  ~sensors/render_budget  (float, 0.5)  share of wall time camera rendering may use; >= 1 renders
                                        every due frame, slowing the simulation instead
  ~sensors/report_period  (s, 10)       wall seconds between rate reports; 0 = none
Reported: a loginfo line per period with each busy topic's rate in sim time and wall time,
frames skipped and the real-time factor, and the same numbers in the parameter ~sensors/rates
({real_time_factor, topics: [{topic, sim_hz, wall_hz, skipped}]}).
"""
import math
import threading
import time as walltime

import numpy as np
from sensor_msgs.msg import CameraInfo, Image, Imu, LaserScan, PointCloud2

from . import sensors_messages as msgs
from .sdf_world import quaternion_multiply, rpy_to_quaternion
from .sensors_bullet import SceneColours, SensorMount, cast_rays, render
from .sensors_camera import PinholeCamera, mask_depth
from .sensors_config import SensorConfigError, sensor_config
from .sensors_imu import ImuKinematics, quaternion_to_matrix
from .sensors_noise import ImageNoise, make_noise
from .sensors_ray import ScanGeometry
from .sensors_schedule import RateMeter, RenderBudget, UpdateSchedule

DEFAULT_RENDER_BUDGET = 0.5
DEFAULT_REPORT_PERIOD = 10.0


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
        pubs = [self.publishers[r] for r in roles] if roles else self.publishers.values()
        return any(p.get_num_connections() > 0 for p in pubs)

    def step(self, time):
        if not self.schedule.due(time):
            return
        self.schedule.advance(time)
        self.update(time, self.manager.rospy.Time.from_sec(time))

    def update(self, time, stamp):
        raise NotImplementedError

    def close(self):
        for p in self.publishers.values():
            p.unregister()
        self.publishers = {}

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
        fractions, hit = cast_rays(self.sim.world, starts, ends)
        ranges = self.geometry.report(self.geometry.ranges_from_hits(fractions, hit), self.noise)
        self.publishers['scan'].publish(msgs.laser_scan(stamp, self.config.frame_id, self.geometry, ranges))
        self.meter.tick()


class CameraSensor(Sensor):
    """gazebo_ros_camera: image + camera_info."""
    main_topic = 'image'

    def __init__(self, manager, robot, spec, config):
        super(CameraSensor, self).__init__(manager, robot, spec, config)
        cam = spec.camera
        if cam.format not in ('R8G8B8', 'RGB_INT8'):
            config.warnings.append("sensor '%s': image format %s is published as rgb8" % (spec.name, cam.format))
        self.camera = PinholeCamera(cam.width, cam.height, cam.horizontal_fov, cam.clip_near, cam.clip_far)
        self.projection = self.camera.projection_matrix()
        self.rays3 = None  # per-pixel rays, made on the first frame that needs them
        self.noise = make_noise(cam.noise_type, cam.noise_mean, cam.noise_stddev, manager.noise_enabled)
        self.image_noise = None  # its sample pool (MBs) is made on the first frame
        self.advertise('image', Image, 2)
        self.advertise('info', CameraInfo, 2)

    def info(self, stamp):
        return msgs.camera_info(stamp, self.config.frame_id, self.camera, self.config.params['baseline'],
                                self.config.params['distortion'])

    def render(self):
        """(rgb, depth along the optical axis in metres; `far` where nothing is) of the world now,
        or None when the render budget is spent."""
        budget = self.manager.budget
        if not budget.allow(self):
            self.meter.skip()
            return None
        start = walltime.perf_counter()
        self.manager.colours.refresh()  # models spawned since the last frame get their colours
        position, orientation = self.mount.pose()
        rotation = quaternion_to_matrix(orientation)
        view = self.camera.view_matrix(position, rotation)
        rgb, buffer = render(self.sim.world, self.camera.width, self.camera.height, view, self.projection)
        depth = self.camera.linear_depth(buffer).astype(np.float32)
        planes = self.manager.colours.planes
        if planes:
            rgb = rgb.copy()
            if self.rays3 is None:
                self.rays3 = self.camera.rays_optical_3d()
            for plane in planes:
                t = self.camera.plane_depth(self.rays3, position, rotation, plane.point, plane.normal)
                nearer = (t >= self.camera.near) & (t < depth)
                rgb[nearer] = plane.rgb
                depth[nearer] = t[nearer]
        budget.spend(walltime.perf_counter() - start)
        if self.noise is not None:
            if self.image_noise is None:
                self.image_noise = ImageNoise.from_noise(self.noise, rgb.size)
            rgb = self.image_noise.apply(rgb)
        return rgb, depth

    def update(self, time, stamp):
        want_image = self.listened('image')
        if not want_image:
            if self.listened('info'):  # camera_info alone needs no render
                self.publishers['info'].publish(self.info(stamp))
            return
        frame = self.render()
        if frame is None:
            return
        self.publishers['image'].publish(msgs.rgb_image(stamp, self.config.frame_id, frame[0]))
        self.publishers['info'].publish(self.info(stamp))
        self.meter.tick()


class DepthCameraSensor(CameraSensor):
    """gazebo_ros_openni_kinect: rgb image, depth image (32FC1 m), point cloud, two camera_infos."""
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
        frame = self.render()
        if frame is None:
            return
        rgb, depth = frame
        frame_id = self.config.frame_id
        if wanted & {'depth', 'points'}:
            depth = mask_depth(depth, self.config.params['cutoff'], self.config.params['cutoff_max'])
            if 'depth' in wanted:
                self.publishers['depth'].publish(msgs.depth_image(stamp, frame_id, depth))
            if 'points' in wanted:
                if self.rays is None:
                    self.rays = self.camera.rays_optical()
                points = self.camera.points(depth, self.rays)
                self.publishers['points'].publish(msgs.point_cloud(stamp, frame_id, points, rgb))
        if 'image' in wanted:
            self.publishers['image'].publish(msgs.rgb_image(stamp, frame_id, rgb))
        for role in ('info', 'depth_info'):
            self.publishers[role].publish(self.info(stamp))
        self.meter.tick()


class ImuSensor(Sensor):
    main_topic = 'imu'

    def __init__(self, manager, robot, spec, config):
        super(ImuSensor, self).__init__(manager, robot, spec, config)
        self.kinematics = ImuKinematics(manager.sim.world.gravity)
        enabled = manager.noise_enabled
        imu = spec.imu
        self.gyro_noise = make_noise('gaussian', imu.angular_velocity_noise[0], imu.angular_velocity_noise[1],
                                     enabled)
        self.accel_noise = make_noise('gaussian', imu.linear_acceleration_noise[0],
                                      imu.linear_acceleration_noise[1], enabled)
        self.plugin_stddev = config.params['gaussian_noise']
        self.plugin_noise = make_noise('gaussian', 0.0, self.plugin_stddev, enabled)
        self.offset = rpy_to_quaternion(*config.params['rpy_offset'])
        self.advertise('imu', Imu, 10)

    def update(self, time, stamp):
        if not self.listened():
            self.kinematics.reset()  # the next sample after a silence primes the acceleration
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


SENSOR_CLASSES = {'laser': LaserSensor, 'camera': CameraSensor, 'depth': DepthCameraSensor, 'imu': ImuSensor}


class SensorManager(object):
    def __init__(self, rospy, sim, clock=walltime.perf_counter):
        self.rospy = rospy
        self.sim = sim
        self.clock = clock
        self.noise_enabled = bool(rospy.get_param('~sensors/noise', True))
        self.budget = RenderBudget(self._number('~sensors/render_budget', DEFAULT_RENDER_BUDGET), clock)
        self.report_period = self._number('~sensors/report_period', DEFAULT_REPORT_PERIOD)
        self.sensors = {}  # robot name -> [Sensor]
        self._active = []
        self._last_report = None
        self.colours = SceneColours(sim.world)
        with sim.lock:
            self.colours.refresh(sim.spec.models)
        sim.on_spawn.append(self.on_spawn)
        sim.on_delete.append(self.on_delete)
        sim.after_step.append(self.after_step)
        if not self.noise_enabled:
            rospy.loginfo('sensors: noise off (~sensors/noise is false)')
        self._reporter = None
        if self.report_period > 0:
            self._reporter = threading.Thread(target=self._report_loop, name='sensor_rates', daemon=True)
            self._reporter.start()

    def _number(self, name, default):
        value = self.rospy.get_param(name, default)
        try:
            value = float(value)
            if math.isfinite(value) and value >= 0:
                return value
        except (TypeError, ValueError):
            pass
        self.rospy.logwarn('%s must be a number >= 0, got %r; using %g' % (name, value, default))
        return default

    # -- hooks (called under sim.lock) ----------------------------------------------------------
    def on_spawn(self, robot):
        created = []
        for spec in robot.model.sensors:
            try:
                config = sensor_config(spec)
            except SensorConfigError as err:
                self.rospy.logwarn('%s: %s; not simulated' % (robot.name, err))
                continue
            if config is None:
                self.rospy.loginfo("%s: sensor '%s' has no gazebo_ros plugin we simulate; it publishes nothing"
                                   % (robot.name, spec.name))
                continue
            try:
                sensor = SENSOR_CLASSES[config.kind](self, robot, spec, config)
            except (KeyError, ValueError) as err:
                self.rospy.logwarn("%s: sensor '%s' cannot be simulated: %s" % (robot.name, spec.name, err))
                continue
            for w in config.warnings:
                self.rospy.logwarn('%s: %s' % (robot.name, w))
            created.append(sensor)
            self.rospy.loginfo("%s: %s sensor '%s' on %s at %s, frame %s: %s" % (
                robot.name, config.kind, spec.name, spec.reference,
                '%g Hz' % config.rate if config.rate > 0 else 'every update', config.frame_id,
                ', '.join(sorted(config.topics.values()))))
        if created:
            self.sensors[robot.name] = created
            self._active = [s for group in self.sensors.values() for s in group]

    def on_delete(self, robot):
        for sensor in self.sensors.pop(robot.name, []):
            sensor.close()
        self._active = [s for group in self.sensors.values() for s in group]

    def after_step(self, time):
        for sensor in self._active:
            if sensor.failed:
                continue
            try:
                sensor.step(time)
            except Exception as err:  # one broken sensor must not stop the world
                sensor.failed = True
                self.rospy.logerr("sensor '%s' of %s failed and is switched off: %s: %s"
                                  % (sensor.spec.name, sensor.robot_name, type(err).__name__, err))

    # -- rates --------------------------------------------------------------------------------
    def report(self):
        """One rate report: {topic: (sim Hz, wall Hz, skipped)} and the real-time factor since the
        previous call (None the first time)."""
        now, sim_time = self.clock(), self.sim.time
        rates = {}
        for sensor in list(self._active):
            r = sensor.meter.snapshot(sim_time, now)
            if r is not None:
                rates[sensor.topic] = r
        previous = self._last_report
        self._last_report = (sim_time, now)
        rtf = None
        if previous is not None and now > previous[1]:
            rtf = (sim_time - previous[0]) / (now - previous[1])
        return rates, rtf

    def _report_loop(self):
        self.report()
        while not self.rospy.is_shutdown():
            walltime.sleep(self.report_period)
            rates, rtf = self.report()
            busy = {t: r for t, r in rates.items() if r[0] > 0 or r[2] > 0}
            if not busy or rtf is None or rtf <= 0:
                continue
            self.rospy.loginfo('sensor rates (sim time / wall time): %s; real-time factor %.2f' % (
                ', '.join('%s %.1f/%.1f Hz%s' % (t, r[0], r[1], ', %d skipped' % r[2] if r[2] else '')
                          for t, r in sorted(busy.items())), rtf))
            summary = {'real_time_factor': round(rtf, 3),
                       'topics': [{'topic': t, 'sim_hz': round(r[0], 2), 'wall_hz': round(r[1], 2), 'skipped': r[2]}
                                  for t, r in sorted(busy.items())]}
            try:
                self.rospy.set_param('~sensors/rates', summary)
            except Exception:  # the master is going away: nothing to report to
                pass
