"""The render worker (sensors/render_worker.py) on a real Simulator with the racebot, no master:
frames show the world at their stamp, both renderers agree with the pinhole model, depth is
worked out only when a depth topic is subscribed, and a dying worker does not stop the simulator.

The worker renders asynchronously: these tests step the simulation and wait (with a generous
wall-time limit, not a speed assertion) for the frames they need."""
import os
import signal
import socket
import time

import numpy as np
import pytest

from racebot_sim_bridge.engine.physics import PhysicsWorld
from racebot_sim_bridge.sensors import render as render_module
from racebot_sim_bridge.sensors import render_worker
from racebot_sim_bridge.sensors.camera import OPTICAL_FROM_SENSOR
from racebot_sim_bridge.sensors.imu_reading import quaternion_to_matrix

from sensors_sim import add_red_box, listen, make_world, run, sensor_of

WAIT = 90.0  # wall seconds a test waits for frames before it fails (the machine is shared)
CAMERA = '/rrbot/camera1/image_raw'
DEPTH = '/real_sense/depth/image_raw'


def egl_available():
    world = PhysicsWorld()
    try:
        return render_module.load_renderer(world, 'auto')[0] == render_module.EGL
    finally:
        world.close()


def worker_world(racebot_xml, renderer='auto'):
    return make_world(racebot_xml, {'~sensors/render_worker': True, '~sensors/renderer': renderer})


def step_until(sim, condition, what, seconds=0.01):
    """Steps the simulation `seconds` at a time (a little wall time between) until condition() holds."""
    deadline = time.monotonic() + WAIT
    while not condition():
        assert time.monotonic() < deadline, 'timed out waiting for ' + what
        run(sim, seconds)
        time.sleep(0.002)


def red_pixels(img):
    rgb = np.frombuffer(img.data, dtype=np.uint8).reshape(img.height, img.width, 3).astype(int)
    red = (rgb[..., 0] > 120) & (rgb[..., 1] < 60) & (rgb[..., 2] < 60)
    return red


def projected(manager, info, point):
    """Pixel (u, v) of a world point, with the camera's pose and camera_info's K."""
    position, orientation = sensor_of(manager, 'camera').mount.pose()
    x, y, z = OPTICAL_FROM_SENSOR @ (quaternion_to_matrix(orientation).T @ (np.asarray(point) - position))
    return info.K[0] * x / z + info.K[2], info.K[4] * y / z + info.K[5]


@pytest.fixture(autouse=True)
def default_socket_timeout():
    """As in the world server: rospy sets a default socket timeout, which makes new sockets
    non-blocking underneath; the worker's socket pair must work all the same."""
    before = socket.getdefaulttimeout()
    socket.setdefaulttimeout(60.0)
    yield
    socket.setdefaulttimeout(before)


@pytest.fixture
def closing():
    made = []
    yield made.append
    for sim, manager in made:
        manager.close()
        sim.close()


@pytest.mark.parametrize('renderer', ['tiny', 'egl'])
def test_worker_frames_agree_with_the_pinhole_model(racebot_xml, closing, renderer):
    if renderer == 'egl' and not egl_available():
        pytest.skip('no EGL driver on this machine')
    sim, fake, manager, robot = worker_world(racebot_xml, renderer)
    closing((sim, manager))
    add_red_box(sim, 1.2, 0.25, 0.1, 0.1)
    listen(fake, CAMERA, '/rrbot/camera1/camera_info')
    images = fake.publishers[CAMERA].messages
    step_until(sim, lambda: len(images) >= 2, 'two camera frames')
    assert manager.worker.renderer == renderer
    assert manager.worker.restarts == 0 and 'worker process' in manager.renderer  # frames from the worker
    assert not [msg for level, msg in fake.logs if level == 'error']
    img = images[-1]
    info = fake.publishers['/rrbot/camera1/camera_info'].messages[-1]
    assert (img.width, img.height, img.encoding) == (800, 800, 'rgb8')
    red = red_pixels(img)
    assert red.sum() > 200
    vs, us = np.nonzero(red)
    u, v = projected(manager, info, [1.2, 0.25, 0.1])
    assert us.mean() == pytest.approx(u, abs=6) and vs.mean() == pytest.approx(v, abs=12)


def test_a_frame_shows_the_world_at_its_stamp(racebot_xml, closing):
    """The box is moved right after a frame is requested: the frame must still show it where it
    was at the frame's stamp, as the snapshot sent with the request says."""
    sim, fake, manager, robot = worker_world(racebot_xml, 'tiny')
    closing((sim, manager))
    add_red_box(sim, 1.2, 0.25, 0.1, 0.1)
    box = sim.world.bodies['red_box']
    listen(fake, CAMERA, '/rrbot/camera1/camera_info')
    images = fake.publishers[CAMERA].messages
    step_until(sim, lambda: len(images) >= 1, 'the first frame')
    requested = []  # sim times of the frame requests the worker took
    submit = manager.worker.submit

    def recording(*args):
        queued = submit(*args)
        if queued:
            requested.append(sim.time)
        return queued
    manager.worker.submit = recording
    # Step until a request is made, then move the box at once (before the worker renders it).
    step_until(sim, lambda: requested, 'a frame request', sim.step_size)
    with sim.lock:
        stamp_of_request = requested[-1]
        sim.world.client.resetBasePositionAndOrientation(box.id, [1.2, -0.25, 0.1], [0, 0, 0, 1])

    def stamped(t):
        return [m for m in images if abs(m.header.stamp.to_sec() - t) < 1e-9]
    step_until(sim, lambda: stamped(stamp_of_request), 'the requested frame')
    img = stamped(stamp_of_request)[0]
    info = fake.publishers['/rrbot/camera1/camera_info'].messages[-1]
    vs, us = np.nonzero(red_pixels(img))
    before, after = projected(manager, info, [1.2, 0.25, 0.1]), projected(manager, info, [1.2, -0.25, 0.1])
    assert us.mean() == pytest.approx(before[0], abs=6)  # where it was at the stamp
    step_until(sim, lambda: images[-1].header.stamp.to_sec() > stamp_of_request + 1e-9, 'a later frame')
    vs, us = np.nonzero(red_pixels(images[-1]))
    assert us.mean() == pytest.approx(after[0], abs=6)  # and the next frame sees it moved
    assert manager.worker.restarts == 0


def test_depth_only_while_a_depth_topic_is_subscribed(racebot_xml, closing, monkeypatch):
    sim, fake, manager, robot = worker_world(racebot_xml, 'tiny')
    closing((sim, manager))
    requests = []
    submit = render_worker.RenderWorker.submit

    def recording(self, world, shot, camera, position, rotation, want_depth, *rest):
        requests.append((camera[:2], want_depth))
        return submit(self, world, shot, camera, position, rotation, want_depth, *rest)
    monkeypatch.setattr(render_worker.RenderWorker, 'submit', recording)
    rgb_topic = '/real_sense/rgb/image_raw'
    listen(fake, rgb_topic)
    step_until(sim, lambda: len(fake.publishers[rgb_topic].messages) >= 2, 'rgb frames')
    assert requests and all(not want for size, want in requests)
    assert not fake.publishers[DEPTH].messages
    listen(fake, DEPTH)
    step_until(sim, lambda: len(fake.publishers[DEPTH].messages) >= 1, 'a depth frame')
    assert requests[-1] == ((640, 480), True)
    d = fake.publishers[DEPTH].messages[-1]
    depth = np.frombuffer(d.data, dtype='<f4').reshape(480, 640)
    assert np.isfinite(depth).sum() > 1000


def test_the_simulator_survives_its_worker(racebot_xml, closing):
    sim, fake, manager, robot = worker_world(racebot_xml, 'tiny')
    closing((sim, manager))
    listen(fake, CAMERA)
    images = fake.publishers[CAMERA].messages
    step_until(sim, lambda: len(images) >= 1, 'the first frame')
    first_pid = manager.worker.process.pid
    os.kill(first_pid, signal.SIGKILL)
    count = len(images)
    step_until(sim, lambda: len(images) > count + 1, 'frames after the worker was killed')
    assert manager.worker.process.pid != first_pid and manager.worker.restarts == 1
    assert any(level == 'error' and 'died' in msg for level, msg in fake.logs)
    # Killed more often than it may restart: cameras go on in the physics thread.
    for _ in range(render_worker.MAX_RESTARTS):
        step_until(sim, lambda: manager.worker.ready, 'a restarted worker')
        os.kill(manager.worker.process.pid, signal.SIGKILL)
        step_until(sim, lambda: not manager.worker.ready, 'the worker to be seen dead')
    step_until(sim, lambda: not manager.worker.alive, 'the worker to be given up')
    count = len(images)
    run(sim, 0.1)
    assert len(images) >= count + 2  # rendered synchronously in the physics thread now
    assert 'physics thread' in manager.renderer


def test_close_leaves_no_process(racebot_xml):
    sim, fake, manager, robot = worker_world(racebot_xml, 'tiny')
    listen(fake, CAMERA)
    step_until(sim, lambda: manager.worker is not None and manager.worker.ready, 'the worker')
    process = manager.worker.process
    path = sensor_of(manager, 'camera').buffers.path if sensor_of(manager, 'camera').buffers else None
    manager.close()
    sim.close()
    assert process.poll() is not None
    assert path is None or not os.path.exists(path)


def test_egl_is_used_when_it_loads_and_checked_once(monkeypatch):
    world = PhysicsWorld()
    try:
        monkeypatch.setattr(render_module, 'load_egl', lambda client: 'fake driver')
        monkeypatch.setattr(render_module, 'renderer_draws_correctly', lambda world, renderer: False)
        renderer, description = render_module.load_renderer(world, 'auto')
        assert renderer == 'tiny' and 'drew a wrong test image' in description
        with pytest.raises(render_module.RendererError):
            render_module.load_renderer(world, 'egl')

        def no_plugin(client):
            raise render_module.RendererError('the EGL plugin did not load')
        monkeypatch.setattr(render_module, 'load_egl', no_plugin)
        assert render_module.load_renderer(world, 'auto')[0] == 'tiny'
    finally:
        world.close()


def test_the_test_render_tells_a_working_renderer():
    world = PhysicsWorld()
    try:
        assert render_module.renderer_draws_correctly(world, 'tiny')
    finally:
        world.close()


def test_the_copy_follows_a_respawn_under_the_same_name():
    """Delete a model and spawn another under its name (PyBullet may reuse the body id): the copy
    must be rebuilt from the new model, and posed by the snapshot."""
    from racebot_sim_bridge.description import sdf_reader
    from racebot_sim_bridge.engine.world_copy import WorldCopy, snapshot, sources
    from sensors_sim import RED_BOX
    world, other = PhysicsWorld(), PhysicsWorld()
    try:
        copy = WorldCopy(other)
        world.add_sdf_model(sdf_reader.parse_world(RED_BOX.format(x=1, y=0, z=0.1, s=0.1)).models[0])
        copy.sync(sources(world))
        world.remove('red_box')
        body = world.add_sdf_model(sdf_reader.parse_world(RED_BOX.format(x=1, y=0, z=0.1, s=0.6)).models[0])
        world.client.resetBasePositionAndOrientation(body.id, [2.0, 1.0, 0.5], [0, 0, 0, 1])
        copy.sync(sources(world))
        copy.prune(set(world.bodies))
        copy.pose(snapshot(world))
        lo, hi = other.client.getAABB(other.bodies['red_box'].id)
        assert hi[0] - lo[0] == pytest.approx(0.6, abs=0.05)  # the new model, not the old
        assert (np.array(lo) + np.array(hi)) / 2 == pytest.approx([2.0, 1.0, 0.5], abs=1e-3)
    finally:
        world.close()
        other.close()


@pytest.mark.parametrize('renderer', ['tiny', 'egl'])
def test_worker_depth_sees_the_floor(racebot_xml, closing, renderer):
    """The ground plane is in the depth image where the pinhole model puts it, with both renderers
    (PyBullet's OpenGL renderer does not draw a plane collision shape: scene.py draws it)."""
    if renderer == 'egl' and not egl_available():
        pytest.skip('no EGL driver on this machine')
    sim, fake, manager, robot = worker_world(racebot_xml, renderer)
    closing((sim, manager))
    listen(fake, DEPTH)
    frames = fake.publishers[DEPTH].messages
    step_until(sim, lambda: len(frames) >= 2, 'depth frames')
    assert manager.worker.renderer == renderer and manager.worker.restarts == 0
    depth = np.frombuffer(frames[-1].data, dtype='<f4').reshape(480, 640)
    sensor = sensor_of(manager, 'depth')
    position, orientation = sensor.mount.pose()
    expected = sensor.camera.plane_depth(sensor.camera.rays_optical_3d(), position,
                                         quaternion_to_matrix(orientation), [0.0, 0.0, 0.0], [0.0, 0.0, 1.0])
    rows = [r for r in range(240, 480) if 0.6 < expected[r, 320] < 1.0]  # floor 0.6-1 m ahead, nothing on it
    assert rows
    assert depth[rows, 320] == pytest.approx(expected[rows, 320], abs=0.02)
