"""SensorConfig (what a sensor plugin's load makes of its <sensor> block) and the helpers sensor plugins read their
parameters with: topics, frames, numbers, as gazebo_ros's plugins resolve them.

No rospy, no pybullet, no registry: each plugin's load() (../gazebo_plugins/sensor_plugin.py's Sensor.configure calls
it) fills a SensorConfig with these.
"""
from dataclasses import dataclass, field


class SensorConfigError(ValueError):
    """A sensor block that cannot be simulated as written; the message says why."""


@dataclass
class SensorConfig:
    name: str
    kind: str                       # the sensor class's kind: laser, camera, depth, imu, range, ...
    reference: str                  # the link Gazebo mounts it on (SensorSpec.reference: after lumping)
    frame_id: str
    rate: float                     # Hz of sim time; 0 = every world update
    topics: dict = field(default_factory=dict)   # role -> absolute topic name
    params: dict = field(default_factory=dict)   # kind-specific numbers (cutoffs, baseline, noise)
    warnings: list = field(default_factory=list)
    sensor_class: type = None       # the registered sensor plugin class that runs it


def join_topic(namespace, *parts):
    """Resolves a topic as a ros::NodeHandle in `namespace` would: an absolute last part stays."""
    names = [p for p in parts if p]
    if names and names[-1].startswith('/'):
        return '/' + names[-1].strip('/')
    pieces = [namespace] + names
    return '/' + '/'.join(p.strip('/') for p in pieces if p and p.strip('/'))


def number(params, key, default, warnings, what):
    """The plugin parameter `key` as a number; `default` when absent or empty, and when not a number (warned)."""
    text = params.get(key)
    if text is None or text == '':
        return default
    try:
        return float(text)
    except ValueError:
        warnings.append('%s: <%s> %r is not a number; using %g' % (what, key, text, default))
        return default


def tf_resolve(prefix, frame):
    """tf::resolve (noetic): a frame with a leading slash loses it and ignores the prefix; else
    prefix/frame (the prefix without a leading slash), or the frame alone without a prefix."""
    if frame.startswith('/'):
        return frame.lstrip('/')
    prefix = prefix.lstrip('/')
    return '%s/%s' % (prefix, frame) if prefix else frame


def set_frame(config, params, default, namespace):
    """Sets a config's frame as gazebo_ros's laser, range, bumper and camera plugins' Load() do: frameName (or
    `default`) resolved with the tf_prefix parameter of the plugin's namespace; the manager reads that parameter
    (config.params['tf_prefix_param']) and calls resolve_frame. Without it: tf_resolve('', frame)."""
    text = params.get('frameName')
    config.params['frame_name'] = (default if text is None else text).strip()
    config.params['tf_prefix_param'] = namespace.rstrip('/') + '/tf_prefix'
    config.frame_id = tf_resolve('', config.params['frame_name'])


def resolve_frame(config, tf_prefix):
    """Gives a config whose plugin reads tf_prefix (config.params['tf_prefix_param']) its frame."""
    config.frame_id = tf_resolve(str(tf_prefix or ''), config.params['frame_name'])
