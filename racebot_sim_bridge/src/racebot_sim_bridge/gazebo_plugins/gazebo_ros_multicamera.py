"""libgazebo_ros_multicamera.so (gazebo_plugins noetic-devel): a multicamera sensor whose cameras each publish as
a gazebo_ros_camera under <cameraName>/left or <cameraName>/right.

Each <camera> whose name holds 'left' is a gazebo_ros_camera (gazebo_ros_camera_utils' parameters, the plugin's)
under <cameraName>/left with no baseline; one whose name holds 'right', under <cameraName>/right with the plugin's
hackBaseline (P[3] = -f * it); each posed at the sensor's pose + its own. A camera with neither in its name
publishes nothing (warned). gazebo_ros_triggered_multicamera reads its cameras the same way (it is a
MultiCameraSensor too).
"""
from dataclasses import replace

from racebot_sim_bridge.gazebo_plugins.gazebo_ros_camera import CameraSensor
from racebot_sim_bridge.gazebo_plugins.sensor_plugin import SensorKind
from racebot_sim_bridge.kinematics.rotations import as_xyz_rpy, compose
from racebot_sim_bridge.sensors.config_types import SensorConfigError

# gazebo_ros_multicamera gives a camera whose name holds 'left' the namespace suffix /left and no
# baseline, one whose name holds 'right' /right and the plugin's hackBaseline (P[3] = -f * it).
STEREO_SIDES = (('left', False), ('right', True))


class MultiCameraSensor(CameraSensor, libraries=('libgazebo_ros_multicamera.so',), sensor_types=('multicamera',),
                        kind=SensorKind.MULTICAMERA):
    """One camera of a multicamera sensor: a CameraSensor of its own, with its own pose and topics."""
    block = None  # it reads every <camera>

    @classmethod
    def load(cls, config, sdf):
        """A multicamera sensor's SensorConfig: params['parts'] holds (camera SensorSpec, camera SensorConfig) pairs,
        each <camera> as the gazebo_ros_camera that gazebo_ros_multicamera makes of it; its topics are the parts'
        (as '<camera name>/<role>'), its warnings theirs once."""
        spec, plugin, what, warnings = sdf.spec, sdf.plugin, sdf.what, config.warnings
        if not spec.cameras:
            raise SensorConfigError('%s: the multicamera sensor has no <camera> block' % what)
        parts = []
        camera_name = (plugin.params.get('cameraName') or '').strip()
        for camera in spec.cameras:
            side = next(((name, baseline) for name, baseline in STEREO_SIDES if name in camera.name), None)
            if side is None:
                warnings.append("%s: camera '%s' has neither 'left' nor 'right' in its name, so "
                                'gazebo_ros_multicamera publishes nothing for it' % (what, camera.name))
                continue
            params = dict(plugin.params, cameraName='%s/%s' % (camera_name, side[0]))
            params['hackBaseline'] = (plugin.params.get('hackBaseline') or '0') if side[1] else '0'
            part_plugin = replace(plugin, filename='libgazebo_ros_camera.so', params=params)
            part_spec = replace(spec, type='camera', camera=camera, cameras=[camera],
                                pose=as_xyz_rpy(compose(spec.pose, camera.pose)), plugins=[part_plugin])
            part = CameraSensor.configure(part_spec, part_plugin, sdf.spawn_namespace, sdf.model_name,
                                          sdf.node_namespace)
            if part is not None:
                parts.append((part_spec, part))
        for part_spec, part in parts:
            config.topics.update({'%s/%s' % (part_spec.camera.name, role): topic
                                  for role, topic in part.topics.items()})
            warnings.extend(w for w in part.warnings if w not in warnings)  # both sides share the plugin's
            part.warnings = []
        if parts:
            config.frame_id = parts[0][1].frame_id
        config.params['parts'] = parts
        return config

    @classmethod
    def create(cls, manager, robot, spec, config):
        """One sensor per side: config.params['parts'] holds each camera's (SensorSpec, SensorConfig)."""
        return [cls(manager, robot, part_spec, part) for part_spec, part in config.params['parts']]
