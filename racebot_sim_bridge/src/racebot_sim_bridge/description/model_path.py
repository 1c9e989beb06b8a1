"""Where Gazebo and ROS find files: package://, file://, model:// URIs and plain paths.

No rospy, no pybullet. Resolution follows Gazebo classic with gazebo_ros:
- package://PKG/rel: the package's folder on the ROS package path (rospkg, as roslib does);
- model://NAME/rel: NAME/rel under the first folder of the model path that holds it (the whole
  path is tried under each folder, as Gazebo does); the model path is, in this order,
  every entry of GAZEBO_MODEL_PATH, the `gazebo_model_path` exports of packages
  (<export><gazebo_ros gazebo_model_path="${prefix}/models"/></export>, which gazebo_ros adds
  to GAZEBO_MODEL_PATH), then ~/.gazebo/models (Gazebo's own download folder);
- file:///abs/path and plain paths (relative ones relative to `base_dir`, e.g. a model's folder).

A URI that cannot be found raises ResolveError naming the URI and every place searched.
"""
from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from collections.abc import Mapping
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import rospkg

__all__ = ['ResolveError', 'resolve_uri', 'model_path', 'find_model', 'model_sdf_file', 'package_dir']


class ResolveError(ValueError):
    """A URI names no existing file; the message lists where it was looked for."""


_ROSPACKS = {}  # ROS_PACKAGE_PATH -> rospkg.RosPack


def _rospack():
    """One RosPack per ROS_PACKAGE_PATH: a new one crawls the whole path again (~13 ms here for each
    package:// mesh, ~40 ms for each model path with its manifest exports), and it caches what it read:
    a package made on disk later, under an unchanged ROS_PACKAGE_PATH, is not seen until a restart."""
    import rospkg  # Debian's python3-rospkg; imported late so that pure users need no ROS
    key = os.environ.get('ROS_PACKAGE_PATH', '')
    rospack = _ROSPACKS.get(key)
    if rospack is None:
        rospack = _ROSPACKS[key] = rospkg.RosPack()
    return rospack


def package_dir(name: str, rospack: rospkg.RosPack | None = None) -> str | None:
    """The folder of ROS package `name`, or None."""
    import rospkg
    try:
        return (rospack or _rospack()).get_path(name)
    except rospkg.ResourceNotFound:
        return None


def _exported_model_paths(rospack):
    """gazebo_model_path exports of every package on the ROS package path (gazebo_ros's rule)."""
    paths = []
    for name in sorted(rospack.list()):
        try:
            manifest = rospack.get_manifest(name)
        except Exception:  # a broken package.xml elsewhere must not stop model loading
            continue
        for export in manifest.exports:
            value = export.get('gazebo_model_path') if export.tag == 'gazebo_ros' else None
            if value:
                prefix = rospack.get_path(name)
                paths.extend(p.replace('${prefix}', prefix) for p in value.split(os.pathsep) if p)
    return paths


def model_path(environ: Mapping[str, str] | None = None, rospack: rospkg.RosPack | None = None) -> list[str]:
    """The folders model:// names are looked for in, in Gazebo's order."""
    environ = os.environ if environ is None else environ
    paths = [p for p in environ.get('GAZEBO_MODEL_PATH', '').split(os.pathsep) if p]
    try:
        paths += _exported_model_paths(rospack or _rospack())
    except ImportError:
        pass
    home = environ.get('HOME') or os.path.expanduser('~')
    paths.append(os.path.join(home, '.gazebo', 'models'))
    seen, result = set(), []
    for p in paths:
        p = os.path.abspath(os.path.expanduser(p))
        if p not in seen:
            seen.add(p)
            result.append(p)
    return result


def find_model(name: str, search: list[str] | None = None) -> tuple[str | None, list[str]]:
    """(path, [folders searched]) for model://name; the path is None when not found.

    As Gazebo's SystemPaths::FindFileURI: the whole of `name` (``some_pkg/models/track`` too, as
    packages exporting gazebo_model_path="${prefix}/.." write it) is tried under each model folder
    in turn, and the first that exists wins, be it a folder or not (the caller checks which)."""
    search = model_path() if search is None else search
    for folder in search:
        candidate = os.path.join(folder, name)
        if os.path.exists(candidate):
            return candidate, search
    return None, search


def model_sdf_file(model_dir: str) -> str:
    """The SDF file of a model folder: model.config's <sdf> entry with the highest version
    (as Gazebo picks), else model.sdf. ResolveError when there is none."""
    config = os.path.join(model_dir, 'model.config')
    choices = []
    if os.path.isfile(config):
        try:
            root = ET.parse(config).getroot()
        except ET.ParseError as err:
            raise ResolveError('%s is not valid XML (%s); fix it or give the model a model.sdf' % (config, err))
        for elem in root.findall('sdf'):
            text = (elem.text or '').strip()
            if text:
                choices.append((_version(elem.get('version')), text))
    choices.sort(key=lambda c: c[0], reverse=True)
    for _, name in choices:
        path = os.path.join(model_dir, name)
        if os.path.isfile(path):
            return path
    fallback = os.path.join(model_dir, 'model.sdf')
    if os.path.isfile(fallback):
        return fallback
    raise ResolveError('model folder %s has no SDF file (looked for %s); a Gazebo model has a model.config '
                       'naming its <sdf>model.sdf</sdf>' % (model_dir, ', '.join(
                           [os.path.join(model_dir, n) for _, n in choices] + [fallback])))


def _version(text):
    try:
        return tuple(int(p) for p in (text or '0').split('.'))
    except ValueError:
        return (0,)


def resolve_uri(uri: str | None, base_dir: str | None = None, search: list[str] | None = None) -> str:
    """The absolute path of an existing file named by `uri`; ResolveError when not found.

    `search`: the model path (default: model_path()), only consulted for model:// URIs."""
    uri = (uri or '').strip()
    if not uri:
        raise ResolveError('an empty URI; give package://PKG/path, model://NAME/path, file:///path or a path')
    if uri.startswith('package://'):
        rest = uri[len('package://'):]
        pkg, _, rel = rest.partition('/')
        folder = package_dir(pkg)
        if folder is None:
            raise ResolveError("%s: package '%s' is not on the ROS package path (ROS_PACKAGE_PATH=%s); "
                               "source its workspace's setup.bash" % (uri, pkg, os.environ.get('ROS_PACKAGE_PATH', '')))
        return _existing(uri, [os.path.join(folder, rel)])
    if uri.startswith('model://'):
        rest = uri[len('model://'):]
        name, _, rel = rest.partition('/')
        search = model_path() if search is None else search
        return _existing(uri, [os.path.join(folder, name, rel) for folder in search],
                         hint='add the folder holding %s/ to GAZEBO_MODEL_PATH' % name)
    if uri.startswith('file://'):
        return _existing(uri, [uri[len('file://'):]])
    if '://' in uri:
        raise ResolveError("%s: unknown URI scheme '%s'; use package://, model://, file:// or a path"
                           % (uri, uri.split('://')[0]))
    path = os.path.expanduser(uri)
    if not os.path.isabs(path):
        path = os.path.join(base_dir or os.getcwd(), path)
    return _existing(uri, [path])


def _existing(uri, candidates, hint=None):
    for c in candidates:
        if os.path.isfile(c):
            return os.path.abspath(c)
    raise ResolveError('%s not found; searched %s%s' % (
        uri, ', '.join(candidates) if candidates else 'nowhere (the search path is empty)',
        '; %s' % hint if hint else ''))
