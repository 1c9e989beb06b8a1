"""PluginKind: where a gazebo_ros plugin sits (a model's, a sensor's, the robot hardware), hence who builds it."""
import enum


class PluginKind(enum.Enum):
    """Where a plugin sits, hence who builds it."""
    MODEL = 'model'                    # a model's <gazebo><plugin>: gazebo_plugins/plugin_manager.PluginManager
    SENSOR = 'sensor'                  # a <sensor>'s <plugin>: gazebo_plugins/sensor_manager.SensorManager
    ROBOT_HARDWARE = 'robot hardware'  # gazebo_ros_control's RobotHWSim: GazeboRosControlPlugin, at spawn
