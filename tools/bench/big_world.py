"""The big-world part of the bench: a world of about 90 mesh models, started at once (racebot issue 30).

From `roslaunch` with no master running (as the start-up part) to the first /clock message and to
/gazebo/get_world_properties listing every model of the world, with the mesh cache ($RACEBOT_MESH_CACHE,
description/meshes.py) empty (cold: every mesh converted) and filled by an earlier start (warm); the world
server's RSS once all models are in. Cold and warm starts alternate, so load that comes and goes hits both.
How much of a cold start is mesh conversion: the same mesh files converted into an empty cache by a fresh
process (its trimesh import included), beside the cold-minus-warm difference.

The world: the corpus's AWS small house (row aws_small_house of tools/corpus/manifest.yaml: 87 models of
COLLADA meshes) started by its own launch file, its models found through its package's gazebo_model_path
export, when a clone of it is on this machine (tools/corpus/sources.py finds it; the bench never fetches);
else a world written here: GENERATED_MODELS models, each one DAE or STL mesh made with trimesh, in a package
with the same export, started by `roslaunch gazebo_ros empty_world.launch`. Nothing of the house is copied.
"""
import glob
import json
import logging
import math
import os
import sys
import time
import xml.etree.ElementTree as ET

from . import common, stats
from .common import BenchError

GENERATED_MODELS = 90
GENERATED_PACKAGE = 'racebot_bench_big_world'
HOUSE_ROW = 'aws_small_house'
# Gazebo's built-in includes that are lights, not models (get_world_properties lists models only)
_LIGHT_URIS = ('model://sun',)



def cache_counts(cache):
    """{'cached_meshes': meshes converted to OBJ, 'prism_meshes': static meshes' one-sided prisms} in the mesh cache
    (engine/one_sided_mesh.py writes its prisms there too, as prisms_*.obj)."""
    objs = [os.path.basename(f) for f in glob.glob(os.path.join(cache, '*.obj'))]
    prisms = sum(1 for name in objs if name.startswith('prisms_'))
    return {'cached_meshes': len(objs) - prisms, 'prism_meshes': prisms}

def world_models(world_file):
    """How many models get_world_properties lists once the world is in: the top-level <model>s and
    <include>s of its <world> (an <include> of the sun is a light)."""
    world = ET.parse(world_file).getroot().find('world')
    if world is None:
        raise BenchError('%s has no <world>' % world_file)
    return sum(1 for e in world if e.tag == 'model' or (
        e.tag == 'include' and (e.findtext('uri') or '').strip() not in _LIGHT_URIS))


# -- the world written here ---------------------------------------------------------------------------
def _shape(kind, rng):
    """One trimesh primitive of a few hundred to a few thousand triangles, its size drawn from rng (so every
    model's file differs: the mesh cache is keyed by content)."""
    import trimesh
    u = lambda lo, hi: float(rng.uniform(lo, hi))
    n = lambda lo, hi: int(rng.integers(lo, hi))
    if kind == 0:
        return trimesh.creation.icosphere(subdivisions=n(2, 5), radius=u(0.2, 0.5))
    if kind == 1:
        return trimesh.creation.cylinder(radius=u(0.1, 0.4), height=u(0.3, 1.2), sections=n(24, 160))
    if kind == 2:
        return trimesh.creation.capsule(height=u(0.2, 0.8), radius=u(0.1, 0.3), count=[n(16, 48), n(16, 48)])
    if kind == 3:
        return trimesh.creation.torus(major_radius=u(0.3, 0.5), minor_radius=u(0.05, 0.15),
                                      major_sections=n(24, 80), minor_sections=n(12, 40))
    if kind == 4:
        return trimesh.creation.cone(radius=u(0.2, 0.5), height=u(0.3, 1.0), sections=n(24, 160))
    if kind == 5:
        return trimesh.creation.box(extents=[u(0.2, 1.0), u(0.2, 1.0), u(0.2, 1.0)]).subdivide().subdivide()
    return trimesh.creation.annulus(r_min=u(0.1, 0.2), r_max=u(0.25, 0.5), height=u(0.1, 0.6), sections=n(24, 160))


PACKAGE_XML = """<?xml version="1.0"?>
<!-- written by tools/bench/big_world.py: the bench's mesh-heavy world, its models on the model path
     through this export as a world package's are -->
<package format="2">
  <name>%s</name>
  <version>0.0.0</version>
  <description>The bench's big world: %d models of DAE and STL meshes.</description>
  <maintainer email="racebot@example.com">racebot bench</maintainer>
  <license>BSD</license>
  <buildtool_depend>catkin</buildtool_depend>
  <exec_depend>gazebo_ros</exec_depend>
  <export>
    <gazebo_ros gazebo_model_path="${prefix}/models"/>
  </export>
</package>
"""
MODEL_CONFIG = """<?xml version="1.0"?>
<model>
  <name>%s</name>
  <version>1.0</version>
  <sdf version="1.6">model.sdf</sdf>
  <description>written by tools/bench/big_world.py</description>
</model>
"""
MODEL_SDF = """<?xml version="1.0"?>
<sdf version="1.6">
  <model name="%(name)s">
    <static>true</static>
    <link name="link">
      <collision name="collision">
        <geometry><mesh><uri>model://%(name)s/meshes/%(file)s</uri></mesh></geometry>
      </collision>
      <visual name="visual">
        <geometry><mesh><uri>model://%(name)s/meshes/%(file)s</uri></mesh></geometry>
      </visual>
    </link>
  </model>
</sdf>
"""
WORLD = """<?xml version="1.0"?>
<!-- written by tools/bench/big_world.py: %d models of meshes on a ground plane -->
<sdf version="1.6">
  <world name="default">
    <include><uri>model://ground_plane</uri></include>
    <include><uri>model://sun</uri></include>
%s
    <physics type="ode">
      <max_step_size>0.001</max_step_size>
      <real_time_factor>1</real_time_factor>
      <real_time_update_rate>1000</real_time_update_rate>
    </physics>
  </world>
</sdf>
"""


def generate_world(root, count=GENERATED_MODELS, seed=0):
    """Writes the package GENERATED_PACKAGE under root: count models (bench_mesh_NN), each one mesh, DAE for
    even NN and STL for odd, used as its visual and its collision, and worlds/big.world including them all
    (model://) on a grid. Returns {'package_dir', 'world_file', 'models' (names), 'meshes' (paths),
    'triangles'}. The same seed writes the same shapes (a COLLADA file's ids and dates differ)."""
    import numpy as np
    import trimesh
    rng = np.random.default_rng(seed)
    package = os.path.join(root, GENERATED_PACKAGE)
    common.ensure_dir(os.path.join(package, 'worlds'))
    with open(os.path.join(package, 'package.xml'), 'w') as f:
        f.write(PACKAGE_XML % (GENERATED_PACKAGE, count))
    names, paths, includes, triangles = [], [], [], 0
    side = int(math.ceil(math.sqrt(count)))
    quiet = logging.getLogger('trimesh')
    level = quiet.level
    quiet.setLevel(logging.ERROR)  # the DAE export warns that scipy is missing, then does without it
    try:
        for i in range(count):
            name = 'bench_mesh_%02d' % i
            mesh = _shape(i % 7, rng)
            mesh.apply_translation([0.0, 0.0, -float(mesh.bounds[0][2])])  # standing on the ground
            file_name = 'mesh.dae' if i % 2 == 0 else 'mesh.stl'
            folder = common.ensure_dir(os.path.join(package, 'models', name, 'meshes'))
            if i % 2 == 0:  # trimesh labels its COLLADA Y up; these vertices are Z up, as Gazebo's are
                data = trimesh.exchange.dae.export_collada(mesh).replace(b'<up_axis>Y_UP<', b'<up_axis>Z_UP<', 1)
            else:
                data = mesh.export(file_type='stl')
            with open(os.path.join(folder, file_name), 'wb') as f:
                f.write(data)
            with open(os.path.join(package, 'models', name, 'model.config'), 'w') as f:
                f.write(MODEL_CONFIG % name)
            with open(os.path.join(package, 'models', name, 'model.sdf'), 'w') as f:
                f.write(MODEL_SDF % {'name': name, 'file': file_name})
            x, y = 2.0 * (i % side), 2.0 * (i // side)
            includes.append('    <include><uri>model://%s</uri><name>%s</name><pose>%g %g 0 0 0 %.3f</pose>'
                            '</include>' % (name, name, x, y, float(rng.uniform(-math.pi, math.pi))))
            names.append(name)
            paths.append(os.path.join(folder, file_name))
            triangles += len(mesh.faces)
    finally:
        quiet.setLevel(level)
    world_file = os.path.join(package, 'worlds', 'big.world')
    with open(world_file, 'w') as f:
        f.write(WORLD % (count, '\n'.join(includes)))
    return {'package_dir': package, 'world_file': world_file, 'models': names, 'meshes': paths,
            'triangles': triangles}


# -- which world ----------------------------------------------------------------------------------------
def _corpus():
    tools = os.path.join(common.REPO, 'tools')
    if tools not in sys.path:
        sys.path.insert(0, tools)
    from corpus import manifest, sources
    return manifest, sources


def house(env=os.environ):
    """The corpus's small house at its pinned commit, when a clone is on this machine: (spec, None), else
    (None, why). Its launch is the row's command plus gui:=false, its world the row's world check."""
    manifest, sources = _corpus()
    row = next(r for r in manifest.load() if r['name'] == HOUSE_ROW)
    repo = row['repos'][0]
    kind, where = sources.resolve(repo['repo'], env)
    if kind == 'missing':
        return None, where
    if kind == 'clone' and not os.path.exists(where) and not sources.cached(repo['repo'], repo['commit'], env):
        return None, ('no clone of %s on this machine (the bench does not fetch: `make corpus` clones it, or set '
                      'RACEBOT_CORPUS_MIRRORS / RACEBOT_CORPUS_DIR)' % repo['repo'])
    try:
        tree, note = sources.checkout(repo['repo'], repo['commit'], env)
    except sources.SourceError as err:
        return None, str(err)
    command = row['commands'][0].split()
    if command[0] != 'roslaunch' or repo['packages'] != ['.']:
        raise BenchError('row %s: expected one package at the repository root started by roslaunch' % HOUSE_ROW)
    package = command[1]
    check = next(c for c in row['checks'] if c['kind'] == 'world')
    world_file = check['world'].replace('$(find %s)' % package, tree)
    return {'kind': 'house', 'name': 'AWS small house (corpus row %s, %s at %s%s)' % (
                HOUSE_ROW, repo['repo'], repo['commit'][:7], '; ' + note if note else ''),
            'launch': command[1:] + ['gui:=false'], 'package_path': tree, 'world_file': world_file,
            'models': world_models(world_file), 'note': note}, None


def generated(root, count):
    world = generate_world(root, count)
    return {'kind': 'generated', 'name': 'written by the bench: %d models of DAE/STL meshes, %d triangles' % (
                count, world['triangles']),
            'launch': ['gazebo_ros', 'empty_world.launch', 'world_name:=' + world['world_file'], 'gui:=false'],
            'package_path': world['package_dir'], 'world_file': world['world_file'],
            'models': world_models(world['world_file'])}


# -- one start (a child process of tools/run_bench.py, --scenario big_world) ---------------------------------
def start(p, out):
    """roslaunch with no master running -> the first /clock, and all p['models'] in get_world_properties;
    the world server's RSS and CPU time then; how many meshes the cache holds."""
    from .ros_node import WORLD_SERVER, node_pid
    port = p['port']
    os.environ['RACEBOT_MESH_CACHE'] = p['mesh_cache']
    os.environ['ROS_PACKAGE_PATH'] = os.pathsep.join([p['package_path'], os.environ.get('ROS_PACKAGE_PATH', '')])
    os.environ['ROS_MASTER_URI'] = 'http://localhost:%d' % port
    started = time.monotonic()
    launch = common.roslaunch(p['launch'], port, os.path.join(out, 'logs', 'big_world_%s.log' % p['label']))
    try:
        common.wait_for(lambda: common.master_online(port), 60, 'the master', launch, period=0.02)
        master_s = time.monotonic() - started
        import rospy
        from gazebo_msgs.srv import GetWorldProperties
        from rosgraph_msgs.msg import Clock
        rospy.init_node('racebot_bench_big_world', anonymous=True, disable_signals=True)
        first = []
        sub = rospy.Subscriber('/clock', Clock, lambda _msg: first or first.append(time.monotonic()), queue_size=1)
        proxy = rospy.ServiceProxy('/gazebo/get_world_properties', GetWorldProperties)

        def all_models():
            try:
                names = proxy().model_names
            except Exception:  # not served yet (rospy raises several kinds)
                return None
            return names if len(names) >= p['models'] else None
        names = common.wait_for(all_models, p['timeout_s'], '%d models in /gazebo/get_world_properties'
                                % p['models'], launch, period=0.02)
        models_s = time.monotonic() - started
        common.wait_for(lambda: first, 30, 'the first /clock message', launch, period=0.005)
        pid = node_pid(WORLD_SERVER, port)
        result = {'label': p['label'], 'cache': p['cache'], 'master_s': master_s, 'clock_s': first[0] - started,
                  'models_s': models_s, 'models': len(names), 'rss_bytes': common.rss_bytes(pid),
                  'cpu_s': common.cpu_seconds(pid), **cache_counts(p['mesh_cache'])}
        sub.unregister()
        return result
    finally:
        launch.stop()


def convert_all(p, out):
    """Every mesh a cold start converted (the sources its cache names) converted again into an empty cache by
    this fresh process: the conversion's share of a cold start, trimesh's import included."""
    sources = []
    for info in sorted(glob.glob(os.path.join(p['filled_cache'], '*.obj.json'))):
        with open(info) as f:
            sources.append(json.load(f)['source'])
    os.environ['RACEBOT_MESH_CACHE'] = p['mesh_cache']
    t0, c0 = time.perf_counter(), time.process_time()
    from racebot_sim_bridge.description import meshes
    import trimesh  # noqa: F401  (the world server imports it with the first mesh to convert)
    import_s = time.perf_counter() - t0
    triangles = sum(meshes.convert(path).triangles for path in sources)
    return {'files': len(sources), 'triangles': triangles, 'source_bytes': sum(os.path.getsize(s) for s in sources),
            'import_s': import_s, 'wall_s': time.perf_counter() - t0, 'cpu_s': time.process_time() - c0}


def scenario(p, out):
    return {'start': start, 'convert': convert_all}[p['measure']](p, out)


# -- the part -------------------------------------------------------------------------------------------------
def run(cfg, out, run_scenario):
    """cfg: runs (cold and warm starts each), world ('auto': the house when its clone is here, else the
    generated world; 'generated'), models (of the generated world), timeout_s. run_scenario is tools/run_bench.py's."""
    root = common.clean_dir(os.path.join(out, 'tmp', 'big_world'))
    spec, why_not_house = (None, 'asked for the generated world') if cfg['world'] == 'generated' else house()
    if spec is None:
        spec = generated(root, cfg['models'])
    print(' [%s world: %s]' % (spec['kind'], spec['name']), end='', flush=True)
    params = {k: spec[k] for k in ('launch', 'package_path', 'models')}
    params.update(measure='start', timeout_s=cfg['timeout_s'])
    warm_cache = os.path.join(root, 'cache_cold_1')
    runs = []
    for i in range(1, cfg['runs'] + 1):  # cold, warm, cold, warm, ...: load that comes and goes hits both
        cold_cache = os.path.join(root, 'cache_cold_%d' % i)
        runs.append(run_scenario('big_world', dict(params, cache='cold', label='cold_%d' % i, mesh_cache=cold_cache),
                                 out, timeout=cfg['timeout_s'] + 120))
        runs.append(run_scenario('big_world', dict(params, cache='warm', label='warm_%d' % i, mesh_cache=warm_cache),
                                 out, timeout=cfg['timeout_s'] + 120))
    conversion = run_scenario('big_world', {'measure': 'convert', 'filled_cache': warm_cache,
                                            'mesh_cache': os.path.join(root, 'cache_convert')}, out, timeout=600)
    result = {'world': spec['name'], 'world_kind': spec['kind'], 'models': spec['models'],
              'launch': 'roslaunch ' + ' '.join(spec['launch']).replace(common.REPO + os.sep, ''),
              'why_not_house': why_not_house if spec['kind'] != 'house' else None, 'runs': runs,
              'conversion': conversion, 'loadavg': common.loadavg()}
    for cache in ('cold', 'warm'):
        these = [r for r in runs if r['cache'] == cache]
        result[cache] = {k: stats.spread([r[k] for r in these]) for k in ('master_s', 'clock_s', 'models_s', 'cpu_s')}
        result[cache]['rss_mb'] = stats.spread([r['rss_bytes'] / 1048576.0 for r in these])
    result['cold_minus_warm_s'] = result['cold']['models_s']['median'] - result['warm']['models_s']['median']
    # what the empty cache costs the world server: its CPU time to all models in, cold minus warm
    result['cold_minus_warm_cpu_s'] = result['cold']['cpu_s']['median'] - result['warm']['cpu_s']['median']
    return result
