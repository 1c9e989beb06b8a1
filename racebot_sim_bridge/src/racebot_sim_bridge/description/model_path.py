"""Where Gazebo and ROS find files: package://, file://, model:// URIs, plain paths and world files.

No rospy, no pybullet. Resolution follows Gazebo classic 11 with gazebo_ros (common/SystemPaths.cc,
gazebo_ros_paths_plugin.cpp):
- package://PKG/rel: the package's folder on the ROS package path (rospkg, as roslib does);
- model://NAME/rel: NAME/rel under the first folder of the model path that holds it (the whole
  path is tried under each folder, as SystemPaths::FindFileURI does); the model path is, in this order,
  ~/.gazebo/models (SystemPaths puts it first), every entry of GAZEBO_MODEL_PATH, then the
  `gazebo_model_path` exports of packages (<export><gazebo_ros gazebo_model_path="${prefix}/models"/>
  </export>, which gazebo_ros_paths_plugin adds after them);
- the resource path (resource_path): every entry of GAZEBO_RESOURCE_PATH, then the `gazebo_media_path`
  exports, as the paths plugin adds them; worlds (world_name:=worlds/x.world) and relative file:// URIs
  are looked for in it by find_file, SystemPaths::FindFile's search: the working directory, then under
  each folder NAME, models/NAME, media/models/NAME and Media/models/NAME;
- file:///abs/path and absolute paths: the path, else the path under each model folder (SystemPaths
  looks there for absolute paths that do not exist, for worlds saved on another machine);
- plain relative paths: relative to `base_dir` (a model's folder, or the world file's), else as find_file.

A URI that cannot be found raises ResolveError naming the URI and every place searched, and a file in one of those
folders whose name differs only in upper and lower case ("did you mean ...").
"""
from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from collections.abc import Mapping
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import rospkg

from racebot_sim_bridge.description import xml_document

__all__ = ['ResolveError', 'resolve_uri', 'model_path', 'resource_path', 'find_file', 'find_model', 'model_sdf_file',
           'package_dir', 'nearest_match']


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


def _exported_paths(rospack, attribute):
    """The `attribute` exports (gazebo_model_path, gazebo_media_path) of every package on the ROS package path,
    as gazebo_ros_paths_plugin reads them: <export><gazebo_ros ATTRIBUTE="..."/></export>, ${prefix} the package's
    folder, several folders separated by ':'."""
    paths = []
    for name in sorted(rospack.list()):
        try:
            manifest = rospack.get_manifest(name)
        except Exception:  # a broken package.xml elsewhere must not stop model loading
            continue
        for export in manifest.exports:
            value = export.get(attribute) if export.tag == 'gazebo_ros' else None
            if value:
                prefix = rospack.get_path(name)
                paths.extend(p.replace('${prefix}', prefix) for p in value.split(os.pathsep) if p)
    return paths


def _with_exports(paths: list[str], attribute: str, rospack: rospkg.RosPack | None) -> list[str]:
    """`paths`, then the packages' `attribute` exports (none when rospkg is not installed)."""
    try:
        return paths + _exported_paths(rospack or _rospack(), attribute)
    except ImportError:
        return paths


def _unique(paths):
    """Absolute, each once, in order (SystemPaths::InsertUnique)."""
    seen, result = set(), []
    for p in paths:
        p = os.path.abspath(os.path.expanduser(p))
        if p not in seen:
            seen.add(p)
            result.append(p)
    return result


def _env_paths(environ: Mapping[str, str], variable: str) -> list[str]:
    return [p for p in environ.get(variable, '').split(os.pathsep) if p]


def model_path(environ: Mapping[str, str] | None = None, rospack: rospkg.RosPack | None = None) -> list[str]:
    """The folders model:// names are looked for in, in Gazebo's order: ~/.gazebo/models, GAZEBO_MODEL_PATH,
    the packages' gazebo_model_path exports."""
    environ = os.environ if environ is None else environ
    home = environ.get('HOME') or os.path.expanduser('~')
    paths = [os.path.join(home, '.gazebo', 'models')] + _env_paths(environ, 'GAZEBO_MODEL_PATH')
    return _unique(_with_exports(paths, 'gazebo_model_path', rospack))


def resource_path(environ: Mapping[str, str] | None = None,
                  rospack: rospkg.RosPack | None = None) -> list[str]:
    """Gazebo's resource path (its "gazebo paths", where worlds/ and media/ are): GAZEBO_RESOURCE_PATH, then the
    packages' gazebo_media_path exports, which gazebo_ros_paths_plugin adds to it."""
    environ = os.environ if environ is None else environ
    return _unique(_with_exports(_env_paths(environ, 'GAZEBO_RESOURCE_PATH'), 'gazebo_media_path', rospack))


# SystemPaths' search path suffixes: NAME is also looked for under these in each resource folder.
RESOURCE_SUFFIXES = ('', 'models', os.path.join('media', 'models'), os.path.join('Media', 'models'))


def find_file(name: str, resources: list[str] | None = None,
              cwd: str | None = None) -> tuple[str | None, list[str]]:
    """(path, [places searched]) of a relative file or folder `name` as SystemPaths::FindFile finds it: in the
    working directory, then NAME, models/NAME, media/models/NAME and Media/models/NAME under each folder of the
    resource path in turn (`resources`, default resource_path()). The path is None when it is nowhere."""
    candidates = [os.path.join(cwd or os.getcwd(), name)]
    for folder in resource_path() if resources is None else resources:
        candidates.extend(os.path.join(folder, suffix, name) for suffix in RESOURCE_SUFFIXES)
    found = next((c for c in candidates if os.path.exists(c)), None)
    return (os.path.abspath(found) if found else None), candidates


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
            root = xml_document.parse(config)
        except (ET.ParseError, OSError, ValueError, LookupError) as err:
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


def resolve_uri(uri: str | None, base_dir: str | None = None, search: list[str] | None = None,
                resources: list[str] | None = None) -> str:
    """The absolute path of an existing file named by `uri`; ResolveError when not found.

    `search`: the model path (default: model_path()), consulted for model:// URIs and for absolute paths that do
    not exist; `resources`: the resource path (default: resource_path()), for relative file:// URIs and relative
    paths not found under `base_dir`. Both are looked up only when needed."""
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
    if '://' in uri and not uri.startswith('file://'):
        raise ResolveError("%s: unknown URI scheme '%s'; use package://, model://, file:// or a path"
                           % (uri, uri.split('://')[0]))
    path = uri[len('file://'):] if uri.startswith('file://') else os.path.expanduser(uri)
    if os.path.isabs(path):
        if os.path.isfile(path):
            return os.path.abspath(path)
        # SystemPaths::FindFile: an absolute path that does not exist is looked for under each model folder
        search = model_path() if search is None else search
        return _existing(uri, [path] + [os.path.join(folder, path.lstrip(os.sep)) for folder in search])
    # file://REL is SystemPaths::FindFile(REL): the working directory, then the resource path. A plain relative
    # path is first looked for relative to the model's (or the world file's) folder.
    candidates = [os.path.join(base_dir, path)] if base_dir and not uri.startswith('file://') else []
    if candidates and os.path.isfile(candidates[0]):
        return os.path.abspath(candidates[0])
    found, searched = find_file(path, resources)
    if found is not None and os.path.isfile(found):
        return found
    return _existing(uri, candidates + searched, hint='a relative file:// URI is looked for in the working directory '
                     'and the resource path (GAZEBO_RESOURCE_PATH, gazebo_media_path exports); write model://NAME/'
                     '%s to find it in its model folder' % path if uri.startswith('file://') else None)


def _existing(uri, candidates, hint=None):
    for c in candidates:
        if os.path.isfile(c):
            return os.path.abspath(c)
    near = nearest_match(candidates)
    if near is not None:  # a model made on Windows or macOS, whose file systems ignore case
        hint = 'did you mean %s? (a file of that name in other capitals; file names are case-sensitive here, ' \
               'as for Gazebo on Linux)%s' % (near, '; %s' % hint if hint else '')
    raise ResolveError('%s not found; searched %s%s' % (
        uri, ', '.join(candidates) if candidates else 'nowhere (the search path is empty)',
        '; %s' % hint if hint else ''))


def nearest_match(candidates: list[str]) -> str | None:
    """The first file, in the order of `candidates` (paths that do not exist), in a candidate's own folder whose
    name is the candidate's but for upper and lower case (aws_Spotlight_01.DAE for aws_spotlight_01.dae), or
    None."""
    for candidate in candidates:
        folder, name = os.path.split(candidate)
        try:
            entries = sorted(os.listdir(folder or '.'))
        except OSError:
            continue
        for entry in entries:
            path = os.path.join(folder, entry)
            if entry != name and entry.lower() == name.lower() and os.path.isfile(path):
                return os.path.abspath(path)
    return None
