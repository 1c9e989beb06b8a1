"""make bench's camera budget (issue 30): what one frame of each camera of racebot.launch costs, stage by stage,
in CPU milliseconds, and so what the declared rates need of two cores.

Run in a process of its own (`python -m bench.camera_budget RESULT.json`, from tools/): the EGL plugin is loaded
as the render worker loads it (one thread, the worker's LP_NUM_THREADS), the room world and the car are built
the way the world server builds them, and each camera is rendered from its mount on the car at rest. Stages,
each the median CPU time (time.process_time: the machine's other load does not count) of FRAMES frames:
- worker: `render` (PyBullet's getCameraImage: llvmpipe's rasterisation plus the read-back and PyBullet's
  per-pixel copies; `readback` is the same call with nothing in view, the part a frame pays whatever it shows)
  and `convert` (render.CameraFrames.finish: ground planes, packed rgb, depth in metres, noise);
- world server: `message` (the ROS messages the plugin publishes for that frame, built as
  gazebo_ros_camera / gazebo_ros_openni_kinect build them, with their code), `serialize` (as rospy does:
  into a BytesIO) and `send` (the bytes written to a local TCP socket, as TCPROS writes them);
- subscriber: `receive` (the reading end of that socket, 1 MB reads: a lower bound for any subscriber).
The world server's physics is the real-time part's CPU with nothing subscribed (report.camera_budget_rows).
"""
import io
import json
import os
import socket
import statistics
import sys
import threading
import time

FRAMES = 30
WARM_UP = 3
SEND_CHUNK = 1 << 20


def cpu_ms(call, frames=FRAMES):
    """Median CPU milliseconds of `call()` (after WARM_UP calls) and its last result."""
    for _ in range(WARM_UP):
        result = call()
    times = []
    for _ in range(frames):
        t0 = time.process_time()
        result = call()
        times.append(time.process_time() - t0)
    return 1000.0 * statistics.median(times), result


class Drain:
    """A local TCP connection read by a thread of its own; each end's CPU is counted on its own thread's clock."""

    def __init__(self):
        server = socket.socket()
        server.bind(('127.0.0.1', 0))
        server.listen(1)
        self.sender = socket.create_connection(server.getsockname())
        self.receiver, _ = server.accept()
        server.close()
        self.expected = 0
        self.received = 0
        self.cpu = 0.0
        self.cond = threading.Condition()
        self.thread = threading.Thread(target=self._read, daemon=True)
        self.thread.start()

    def _read(self):
        buf = bytearray(SEND_CHUNK)
        while True:
            t0 = time.thread_time()
            n = self.receiver.recv_into(buf)
            self.cpu += time.thread_time() - t0
            if not n:
                return
            with self.cond:
                self.received += n
                self.cond.notify_all()

    def send(self, data):
        """Writes `data` and waits until it has been read; returns the sender's CPU seconds for the write."""
        t0 = time.thread_time()
        self.sender.sendall(data)
        spent = time.thread_time() - t0
        with self.cond:
            self.expected += len(data)
            self.cond.wait_for(lambda: self.received >= self.expected, 10.0)
        return spent


def serialized(msg):
    buff = io.BytesIO()
    msg.serialize(buff)
    return buff.getvalue()


def frame_messages(kind, camera, params, rgb, depth, rays, stamp):
    """The messages one frame publishes with every topic subscribed, built by the plugins' own code (depth:
    gazebo_ros_openni_kinect.frame_messages with the sensor's parameters), camera_infos included."""
    from racebot_sim_bridge.gazebo_plugins.gazebo_ros_openni_kinect import frame_messages as depth_frame
    from racebot_sim_bridge.sensors import messages as msgs
    info = msgs.camera_info(stamp, 'camera', camera)
    if kind == 'depth':
        return [m for _, m in depth_frame(camera, params, 'camera', 'rgb8', rays, stamp, {'image', 'depth', 'points'},
                                          rgb, depth)] + [info, msgs.camera_info(stamp, 'camera', camera)]
    return [msgs.rgb_image(stamp, 'camera', rgb), info]


def measure():
    import numpy as np
    import pybullet as pb
    import rospy
    from racebot_sim_bridge.description import sdf_reader, urdf_reader
    from racebot_sim_bridge.engine.physics import PhysicsWorld
    from racebot_sim_bridge.sensors.camera import PinholeCamera
    from racebot_sim_bridge.gazebo_plugins.sensor_manager import sensor_config
    from racebot_sim_bridge.sensors.noise import make_noise
    from racebot_sim_bridge.sensors.render import CameraFrames, load_renderer
    from racebot_sim_bridge.sensors.scene import SceneColours

    from bench import common

    world = PhysicsWorld()
    renderer, description = load_renderer(world, 'auto')  # before any body, as the render worker does
    world.load_world(sdf_reader.load_world(common.ROOM_WORLD))
    xml = common.render_racebot()
    model = urdf_reader.parse_urdf(xml)
    body = world.spawn_urdf('racebot', model, xml, position=(0.0, 0.0, 0.05))
    colours = SceneColours(world, renderer)
    colours.refresh()
    drain = Drain()
    stamp = rospy.Time(1, 0)
    cameras = {}
    for spec in model.sensors:
        if spec.type not in ('camera', 'depth') or spec.camera is None:
            continue
        cam = spec.camera
        camera = PinholeCamera(cam.width, cam.height, cam.horizontal_fov, cam.clip_near, cam.clip_far)
        frames = CameraFrames(camera, make_noise(cam.noise_type, cam.noise_mean, cam.noise_stddev, True))
        (link_pos, link_orn), _ = body.links[spec.reference].state()
        x, y, z, roll, pitch, yaw = spec.pose
        pos, orn = pb.multiplyTransforms(link_pos, link_orn, (x, y, z), pb.getQuaternionFromEuler((roll, pitch, yaw)))
        position = np.asarray(pos)
        rotation = np.asarray(pb.getMatrixFromQuaternion(orn)).reshape(3, 3)
        want_depth = spec.type == 'depth'
        stages = {}
        stages['render'], (rgba, buffer) = cpu_ms(lambda: frames.render(world, renderer, position, rotation))
        sky = np.array([[0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]])  # looking up at nothing
        stages['readback'], _ = cpu_ms(lambda: frames.render(world, renderer, np.array([0.0, 0.0, 50.0]), sky))
        stages['convert'], (rgb, depth) = cpu_ms(lambda: frames.finish(
            rgba.copy(), buffer.copy(), colours.planes, position, rotation, want_depth))
        copy_ms, _ = cpu_ms(lambda: (rgba.copy(), buffer.copy()))
        stages['convert'] = max(0.0, stages['convert'] - copy_ms)  # the measurement's own copies
        rays = camera.rays_optical()
        params = sensor_config(spec).params
        stages['message'], msgs = cpu_ms(lambda: frame_messages(spec.type, camera, params, rgb, depth, rays, stamp))
        stages['serialize'], blobs = cpu_ms(lambda: [serialized(m) for m in msgs])
        sends = []
        before = drain.cpu
        for _ in range(FRAMES):
            sends.append(sum(drain.send(b) for b in blobs))
        stages['send'] = 1000.0 * statistics.median(sends)
        stages['receive'] = 1000.0 * (drain.cpu - before) / FRAMES
        cameras[spec.name] = {'type': spec.type, 'width': cam.width, 'height': cam.height,
                              'rate_hz': spec.update_rate, 'bytes': sum(len(b) for b in blobs),
                              'topics': len(blobs), 'ms': {k: round(v, 3) for k, v in stages.items()}}
    return {'renderer': description, 'lp_num_threads': os.environ.get('LP_NUM_THREADS'), 'frames': FRAMES,
            'cameras': cameras}


def run(out_file, timeout=300):
    """Runs measure() in a child process (the EGL plugin wants a process with one thread) -> its result."""
    import subprocess

    from racebot_sim_bridge.sensors.render_worker import llvmpipe_threads

    from bench import common
    env = dict(os.environ)
    env.setdefault('LP_NUM_THREADS', llvmpipe_threads(os.cpu_count() or 2))
    tools = os.path.join(common.REPO, 'tools')
    log = out_file + '.log'
    with open(log, 'w') as f:
        code = subprocess.call([common.python(), '-m', 'bench.camera_budget', out_file], cwd=tools, env=env,
                               stdout=f, stderr=subprocess.STDOUT, timeout=timeout)
    if code != 0 or not os.path.exists(out_file):
        with open(log) as f:
            raise common.BenchError('camera budget failed (exit %s): %s' % (code, f.read()[-2000:]))
    with open(out_file) as f:
        return json.load(f)


if __name__ == '__main__':
    result = measure()
    with open(sys.argv[1], 'w') as f:
        json.dump(result, f, indent=1)
