"""A <sensor> of a URDF's ``<gazebo reference>`` block read into urdf_model's SensorSpec (part of urdf_reader).

Pure Python: no rospy, no pybullet. What the sensor plugins read of it, as Gazebo's sensors read SDF: update
rate, switches, pose, <ray> (or <lidar>) with its scan, range and noise, every <camera> with its image, clip,
noise and distortion, <contact> collisions, <imu> noise per axis (or the older shared <noise><rate>/<accel>),
and its <plugin>s.
"""
from __future__ import annotations

import xml.etree.ElementTree as ET

from racebot_sim_bridge.description.urdf_elements import boolean, child_text, integer, read_plugin, vector
from racebot_sim_bridge.description.urdf_model import CameraSpec, ImuSpec, RaySpec, SensorSpec, UrdfError, number

__all__ = ['read_sensor']


def read_sensor(elem: ET.Element, reference: str) -> SensorSpec:
    """The SensorSpec of a <sensor> in the <gazebo reference> block of link `reference`."""
    name = elem.get('name')
    kind = elem.get('type')
    what = "sensor '%s' (on '%s')" % (name, reference)
    if not name or not kind:
        raise UrdfError('a <sensor> on %r lacks a %s attribute; add it (type is ray, '
                        'gpu_ray, camera, depth, imu, ...)'
                        % (reference, 'name' if not name else 'type'))
    spec = SensorSpec(name, kind, reference)
    text = child_text(elem, 'update_rate')
    if text is not None:
        spec.update_rate = number(text, what + ' <update_rate>')
        if spec.update_rate < 0.0:
            raise UrdfError('%s <update_rate> must be >= 0 Hz, got %s' % (what, text))
    for tag in ('always_on', 'visualize'):
        text = child_text(elem, tag)
        if text is not None:
            setattr(spec, tag, boolean(text, '%s <%s>' % (what, tag)))
    text = child_text(elem, 'pose')
    if text:
        spec.pose = vector(text, 6, what + ' <pose>')
    ray = elem.find('ray')
    if ray is None:
        ray = elem.find('lidar')
    if ray is not None:
        spec.ray = _ray(ray, what)
    spec.cameras = [_camera(camera, what) for camera in elem.findall('camera')]
    if spec.cameras:
        spec.camera = spec.cameras[0]
    contact = elem.find('contact')
    if contact is not None:
        spec.contact_collisions = [(c.text or '').strip() for c in contact.findall('collision')]
    imu = elem.find('imu')
    if imu is not None or kind == 'imu':
        spec.imu = _imu(imu, what)
    for plugin in elem.findall('plugin'):
        spec.plugins.append(read_plugin(plugin, what, reference))
    return spec


def _fill(target, elem, fields, what, convert=number):
    """Set attributes of ``target`` from child paths of ``elem`` that are present."""
    if elem is None:
        return
    for attr, path in fields:
        text = child_text(elem, path)
        if text is not None:
            setattr(target, attr, convert(text, '%s <%s>' % (what, path)))


def _noise(elem, what):
    """(type, mean, stddev) of a <noise> element (child elements or SDF 1.6 type attr)."""
    if elem is None:
        return 'none', 0.0, 0.0
    kind = child_text(elem, 'type') or elem.get('type') or 'none'
    mean = child_text(elem, 'mean')
    stddev = child_text(elem, 'stddev')
    return (kind,
            0.0 if mean is None else number(mean, what + ' <noise><mean>'),
            0.0 if stddev is None else number(stddev, what + ' <noise><stddev>'))


def _noise_with_bias(elem, what):
    """(mean, stddev, bias_mean, bias_stddev) of a <noise> element, zeros without one."""
    if elem is None:
        return (0.0, 0.0, 0.0, 0.0)
    values = []
    for key in ('mean', 'stddev', 'bias_mean', 'bias_stddev'):
        text = child_text(elem, key)
        values.append(0.0 if text is None else number(text, '%s <%s>' % (what, key)))
    return tuple(values)


def _ray(elem, what):
    spec = RaySpec()
    what = what + ' <%s>' % elem.tag
    _fill(spec, elem, [('samples', 'scan/horizontal/samples'),
                       ('vertical_samples', 'scan/vertical/samples')],
          what, integer)
    _fill(spec, elem, [
        ('resolution', 'scan/horizontal/resolution'),
        ('min_angle', 'scan/horizontal/min_angle'),
        ('max_angle', 'scan/horizontal/max_angle'),
        ('vertical_resolution', 'scan/vertical/resolution'),
        ('vertical_min_angle', 'scan/vertical/min_angle'),
        ('vertical_max_angle', 'scan/vertical/max_angle'),
        ('range_min', 'range/min'),
        ('range_max', 'range/max'),
        ('range_resolution', 'range/resolution'),
    ], what)
    if spec.samples < 1:
        raise UrdfError('%s needs at least 1 sample, got %d' % (what, spec.samples))
    spec.noise_type, spec.noise_mean, spec.noise_stddev = _noise(elem.find('noise'), what)
    return spec


def _camera(elem, what):
    spec = CameraSpec(name=elem.get('name') or '')
    what = what + ' <camera>'
    _fill(spec, elem, [('width', 'image/width'), ('height', 'image/height')],
          what, integer)
    _fill(spec, elem, [('horizontal_fov', 'horizontal_fov'),
                       ('clip_near', 'clip/near'), ('clip_far', 'clip/far')], what)
    spec.format = child_text(elem, 'image/format') or spec.format
    text = child_text(elem, 'pose')
    if text:
        spec.pose = vector(text, 6, what + ' <pose>')
    if spec.width < 1 or spec.height < 1:
        raise UrdfError('%s image must be at least 1 x 1 pixels, got %d x %d'
                        % (what, spec.width, spec.height))
    spec.noise_type, spec.noise_mean, spec.noise_stddev = _noise(elem.find('noise'), what)
    distortion = elem.find('distortion')
    if distortion is not None:
        values = []
        for key in ('k1', 'k2', 'k3', 'p1', 'p2'):
            text = child_text(distortion, key)
            values.append(number(text, '%s <distortion><%s>' % (what, key)) if text else 0.0)
        spec.distortion = tuple(values)
    return spec


def _imu(elem, what):
    spec = ImuSpec()
    if elem is None:
        return spec
    what = what + ' <imu>'
    for attr, group, old_form in (('angular_velocity_noise', 'angular_velocity', 'noise/rate'),
                                  ('linear_acceleration_noise', 'linear_acceleration', 'noise/accel')):
        shared = elem.find(old_form)
        axes = []
        for axis in 'xyz':
            path = '%s/%s/noise' % (group, axis)
            noise = elem.find(path)
            if noise is None and shared is not None:
                noise, path = shared, old_form
            axes.append(_noise_with_bias(noise, '%s <%s>' % (what, path)))
        setattr(spec, attr, tuple(axes))
    return spec
