"""Compiled sensor plugins: a <sensor>'s `<plugin filename>` whose library a package built against racebot's Gazebo
plugin API (a velodyne_gazebo_plugins build, a lab's own RayPlugin), hosted as Gazebo hosts it.

For a <sensor type="ray"> or "gpu_ray" that carries such a plugin, racebot's plugin host (gazebo_host) makes a
sensors::RaySensor or GpuRaySensor (compiled_plugins.CompiledPlugins.add_ray_sensor) and loads each of the sensor's
compiled plugins with it: Load(sensor, <plugin>), Init(). CompiledRaySensor is what the SensorManager steps for
it: at the sensor's update rate (one the plugin sets with SetUpdateRate included), while the sensor IsActive()
(<always_on>, SetActive, a transport subscriber of its scan topic: Gazebo's RaySensor::IsActive), it casts the
sensor's rays in the physics world and hands the C++ sensor one measurement: the scan as Gazebo 11's RaySensor
reports it (../sensors/ray.py, the <noise> included; intensities the laser_retro of what each ray hit) and the raw
rays its MultiRayShape holds (../sensors/ray_shape.py). The C++ side then fires what Gazebo's RaySensor::Update
fires, in its order (newLaserScans, the LaserScanStamped to subscribers, the updated event), with the plugins'
callbacks running without the interpreter lock. A plugin whose Load, Init or callback throws is reported and
unloaded (gazebo_host), the world goes on.

A <sensor type="imu"> with such a plugin gets a sensors::ImuSensor (CompiledImuSensor here): at its update rate,
while it IsActive() (<always_on>, SetActive, a transport subscriber of its imu topic), one measurement with
Gazebo's ImuSensor::UpdateImpl arithmetic: the link's world angular velocity in the sensor frame; the world velocity
of the sensor point differenced since the previous measurement (the first: since the sensor was made, from the
velocity it had then, as Gazebo's Load records it), minus gravity, in the sensor frame; then the <imu> element's
per-axis noise (../sensors/noise.py's AxisNoise: Gazebo's GaussianNoiseModel). The C++ sensor keeps both the noisy
and the noise-free values and turns the orientation into its reference frame (SetWorldToReferenceOrientation).

A <sensor type="contact"> gets a sensors::ContactSensor (CompiledContactSensor): once an update finds it active,
the contacts of its <contact><collision>s are read after every physics step (../sensors/contact_points.py and
contact.py, as gazebo_ros_bumper.py reads them), as Gazebo's contact manager hands the sensor one message a step;
each update hands the C++ sensor every contact of the steps since the last one (at most 100 steps, Gazebo's limit).
The first update after it became active has no steps yet and does nothing, as in Gazebo.

A <sensor type="camera"> gets a sensors::CameraSensor with its rendering::Camera (CompiledCameraSensor): at its
update rate while it is active (CameraPlugin's Load switches it on), a frame is rendered in the physics thread with
the TinyRenderer from the world as the step left it (../sensors/render.py's CameraFrames: the ground planes drawn,
the <noise> added), at the camera's size and horizontal field of view now (a plugin may SetHFOV), converted into
its <image><format> (../sensors/messages.py's image_data) and handed over: the camera's new-frame event
(CameraPlugin::OnNewFrame), then the sensor's updated event.
"""
import collections

import numpy as np

from racebot_sim_bridge.description.urdf_model import CameraSpec, ImuSpec
from racebot_sim_bridge.sensors.camera import PinholeCamera
from racebot_sim_bridge.sensors.contact import urdf_collision_shapes
from racebot_sim_bridge.sensors.contact_points import CONTACT_STEPS_KEPT, LinkContacts
from racebot_sim_bridge.sensors.imu_reading import ImuKinematics, quaternion_to_matrix
from racebot_sim_bridge.sensors.messages import IMAGE_ENCODINGS, image_data
from racebot_sim_bridge.sensors.mount import SensorMount
from racebot_sim_bridge.sensors.noise import AxisNoise, make_noise
from racebot_sim_bridge.sensors.ray import ScanGeometry
from racebot_sim_bridge.sensors.ray_shape import RayShape
from racebot_sim_bridge.sensors.raycast import cast_with_retro
from racebot_sim_bridge.sensors.render import TINY, CameraFrames
from racebot_sim_bridge.sensors.schedule import RateMeter, UpdateSchedule

# the <sensor> types whose compiled plugins racebot hosts
HOSTED_TYPES = ('ray', 'gpu_ray', 'imu', 'contact', 'camera')


def ray_geometry(ray):
    """A urdf_model.RaySpec as gazebo_host.add_ray_sensor takes it (MultiRayShape::Geometry's order)."""
    return (int(ray.samples), float(ray.resolution), float(ray.min_angle), float(ray.max_angle),
            int(ray.vertical_samples), float(ray.vertical_resolution), float(ray.vertical_min_angle),
            float(ray.vertical_max_angle), float(ray.range_min), float(ray.range_max), float(ray.range_resolution))


def pose_tuple(position, orientation):
    """A pose as gazebo_host takes one: (x, y, z, qx, qy, qz, qw), Python floats."""
    return tuple(float(v) for v in position) + tuple(float(v) for v in orientation)


def sensor_topic(world_name, model, link, sensor, leaf):
    """A sensor's Gazebo topic as Gazebo decodes it ("~/model/link/sensor/scan": RaySensor::Topic(); .../imu; a
    contact sensor's has no leaf)."""
    return '/gazebo/%s/%s/%s/%s' % (world_name, model, link, sensor) + ('/' + leaf if leaf else '')


def scan_topic(world_name, model, link, sensor):
    return sensor_topic(world_name, model, link, sensor, 'scan')


class CompiledSensor:
    """A sensor whose plugins are compiled: racebot measures, the plugins read the C++ sensor.

    `mount`: where it is (mount_of); `host`: the gazebo_host.Host; `sensor_id`: its sensor; `plugin_ids`: the
    plugins loaded on it (unloaded with close()). What the SensorManager asks of a sensor: step, wake_time, meter,
    topic, failed, spec, robot_name. A subclass measures (`measure`) at the sensor's update rate while it is active."""
    topic_leaf = None

    def __init__(self, manager, robot, spec, mount, host, sensor_id, plugin_ids, unload):
        self.manager = manager
        self.sim = manager.sim
        self.robot_name = robot.name
        self.spec = spec
        self.host = host
        self.sensor_id = sensor_id
        self.plugin_ids = list(plugin_ids)
        self.unload = unload  # CompiledPlugins.unload(plugin id)
        self.mount = mount  # mount_of's
        self.rate = float(spec.update_rate)
        self.schedule = UpdateSchedule(self.rate, start=self.sim.time)
        self.meter = RateMeter()
        self.failed = False
        self.topic = sensor_topic(self.sim.spec.name, robot.name, self.mount.link, spec.name, self.topic_leaf)

    @staticmethod
    def mount_of(sim, robot, spec):
        """Where the sensor is: its link (after sdformat's lumping) and its pose there (SensorMount; KeyError when
        that link is not a link of the spawned body)."""
        return SensorMount(sim.world, robot.body, robot.model, spec.reference, spec.pose)

    def wake_time(self):
        return self.schedule.next

    def step(self, time):
        if not self.schedule.due(time):
            return
        active, rate = self.host.sensor_state(self.sensor_id)
        if rate != self.rate:  # the plugin called SetUpdateRate: from now on at that rate
            self.rate = rate
            self.schedule = UpdateSchedule(rate, start=time)
        self.schedule.advance(time)
        if active:
            self.measure(time)

    def measure(self, time):
        raise NotImplementedError

    def close(self):
        for plugin_id in self.plugin_ids:
            self.unload(plugin_id)
        self.plugin_ids = []
        self.host.remove_sensor(self.sensor_id)


class CompiledRaySensor(CompiledSensor):
    """A ray or gpu_ray sensor whose plugins are compiled."""
    topic_leaf = 'scan'

    def __init__(self, manager, robot, spec, mount, host, sensor_id, plugin_ids, unload, rng=None):
        super().__init__(manager, robot, spec, mount, host, sensor_id, plugin_ids, unload)
        ray = spec.ray
        self.geometry = ScanGeometry(ray)
        self.shape = RayShape(ray)
        # Gazebo casts one ray per sample and interpolates the scan from them; racebot casts each scan range as a
        # ray of its own (ray.py), so a resolution other than 1 needs the raw rays cast too
        self.one_cast = self.shape.directions.shape == self.geometry.directions.shape and \
            np.allclose(self.shape.directions, self.geometry.directions)
        self.noise = make_noise(ray.noise_type, ray.noise_mean, ray.noise_stddev, manager.noise_enabled, rng=rng)

    def _cast(self, directions_of, position, rotation):
        """(fractions, hit, retro per ray) of one set of rays: directions_of is the ScanGeometry or RayShape."""
        return cast_with_retro(self.sim.world, *directions_of.endpoints(position, rotation))

    def measure(self, time):
        position, orientation = self.mount.pose()
        rotation = quaternion_to_matrix(orientation)
        fractions, hit, intensities = self._cast(self.geometry, position, rotation)
        ranges = self.geometry.report(self.geometry.ranges_from_hits(fractions, hit), self.noise)
        if self.one_cast:
            raw, retro = self.shape.ranges(fractions, hit), intensities
        else:
            raw_fractions, raw_hit, retro = self._cast(self.shape, position, rotation)
            raw = self.shape.ranges(raw_fractions, raw_hit)
        pose = pose_tuple(position, orientation)
        self.host.measure_ray(self.sensor_id, time, pose, ranges, intensities, raw, retro)
        self.meter.tick()


class CompiledImuSensor(CompiledSensor):
    """An imu sensor whose plugins are compiled: Gazebo's ImuSensor::UpdateImpl measurement (the module's doc)."""
    topic_leaf = 'imu'

    def __init__(self, manager, robot, spec, mount, host, sensor_id, plugin_ids, unload, rng=None):
        super().__init__(manager, robot, spec, mount, host, sensor_id, plugin_ids, unload)
        imu = spec.imu if spec.imu is not None else ImuSpec()
        self.gyro_noise = AxisNoise.make(imu.angular_velocity_noise, manager.noise_enabled, rng)
        self.accel_noise = AxisNoise.make(imu.linear_acceleration_noise, manager.noise_enabled, rng)
        self.kinematics = ImuKinematics(self.sim.world.gravity)
        # Gazebo's Load records the sensor point's velocity: the first measurement differences from it
        self.kinematics.prime(self.sim.time, self.mount.motion()[2])

    def measure(self, time):
        position, orientation, velocity, omega = self.mount.motion()
        m = self.kinematics.measure(time, orientation, velocity, omega)
        if m is None:  # no time passed since the last one (Gazebo's dt > 0)
            return
        gyro, accel = m.angular_velocity, m.linear_acceleration
        noisy_gyro = gyro if self.gyro_noise is None else self.gyro_noise.apply(gyro)
        noisy_accel = accel if self.accel_noise is None else self.accel_noise.apply(accel)
        pose = pose_tuple(position, orientation)
        self.host.measure_imu(self.sensor_id, time, pose, *(tuple(float(v) for v in vector) for vector in
                                                            (gyro, accel, noisy_gyro, noisy_accel)))
        self.meter.tick()


class CompiledContactSensor(CompiledSensor):
    """A contact sensor whose plugins are compiled: the contacts of every step since the last update (module doc)."""
    topic_leaf = ''

    def __init__(self, manager, robot, spec, mount, host, sensor_id, plugin_ids, unload, rng=None):
        super().__init__(manager, robot, spec, mount, host, sensor_id, plugin_ids, unload)
        self.contacts = LinkContacts(self.sim.world, robot.body.id, mount.index,
                                     urdf_collision_shapes(robot.model, mount.link), robot.name, mount.link,
                                     spec.contact_collisions)
        self.steps = collections.deque(maxlen=CONTACT_STEPS_KEPT)  # per step since the last update: its contacts
        self.collecting = False  # active at an update: every step's contacts are read from then on
        self.next_wake = self.schedule.next

    def wake_time(self):
        return self.next_wake

    def step(self, time):
        if self.collecting:
            if self.host.sensor_state(self.sensor_id)[0]:
                self.steps.append(self._contacts(time))
            else:  # switched off between updates: Gazebo's ContactSensor drops its subscription at the next one
                self.collecting = False
                self.steps.clear()
        if self.schedule.due(time):
            super().step(time)
        self.next_wake = time + self.sim.step_size if self.collecting else self.schedule.next

    def measure(self, time):
        if not self.collecting:  # the first update it is active at subscribes; the steps after it come in
            self.collecting = True
            return
        if not self.steps:
            return
        contacts = [contact for step in self.steps for contact in step]
        self.steps.clear()
        self.host.measure_contacts(self.sensor_id, time, contacts)
        self.meter.tick()

    def _contacts(self, time):
        """This step's contacts of the sensor's collisions, as measure_contacts takes them."""
        return [(g.collision1, g.collision2, time, g.positions, g.normals, g.depths, g.forces, g.torques)
                for g in self.contacts.read()]


def camera_spec(spec):
    """The sensor's <camera> (urdf_model.CameraSpec), sdformat's defaults when it has none."""
    return spec.camera if spec.camera is not None else CameraSpec()


def camera_geometry(camera):
    """A urdf_model.CameraSpec as gazebo_host.add_camera_sensor takes it: (width, height, format, hfov, near, far),
    and the distortion (k1, k2, k3, p1, p2, cx, cy; Gazebo's default centre 0.5 0.5), empty when it has none."""
    distortion = [float(v) for v in camera.distortion]
    return ((int(camera.width), int(camera.height), camera.format, float(camera.horizontal_fov),
             float(camera.clip_near), float(camera.clip_far)), distortion + [0.5, 0.5] if any(distortion) else [])


class CompiledCameraSensor(CompiledSensor):
    """A camera sensor whose plugins are compiled: a frame rendered here at each update (module doc)."""
    topic_leaf = 'image'

    def __init__(self, manager, robot, spec, mount, host, sensor_id, plugin_ids, unload, rng=None):
        super().__init__(manager, robot, spec, mount, host, sensor_id, plugin_ids, unload)
        self.camera_spec = camera_spec(spec)
        cam = self.camera_spec
        self.noise = make_noise(cam.noise_type, cam.noise_mean, cam.noise_stddev, manager.noise_enabled, rng=rng)
        self.frames = None
        self.geometry = None

    def measure(self, time):
        width, height, image_format, hfov = self.host.camera_state(self.sensor_id)
        if self.geometry != (width, height, hfov):  # the first frame, or a plugin's SetHFOV
            self.geometry = (width, height, hfov)
            cam = self.camera_spec
            self.frames = CameraFrames(PinholeCamera(width, height, hfov, cam.clip_near, cam.clip_far), self.noise)
        position, orientation = self.mount.pose()
        rgb, _ = self.frames.make(self.sim.world, TINY, self.manager.scene_colours().planes, position,
                                  quaternion_to_matrix(orientation), want_depth=False)
        _, pixels = image_data(rgb, IMAGE_ENCODINGS.get(image_format, 'rgb8'))
        pose = pose_tuple(position, orientation)
        self.host.measure_camera(self.sensor_id, time, pose, pixels.tobytes())
        self.meter.tick()
