"""The render worker process: `python -m racebot_sim_bridge.sensors.render_process FD`.

Started by render_worker.RenderWorker with one end of a socket pair (FD). It holds a DIRECT client
with the EGL renderer when that loads (else the TinyRenderer) and a world_copy.WorldCopy; for each
request it brings the copy to the request's bodies and snapshot, renders the camera's frame and
writes it into the frame buffer the request names, then replies. It exits when asked, when its
socket closes, or when the simulator dies (child_process.helper_main).
"""
import sys

import numpy as np

from racebot_sim_bridge.engine.child_process import helper_main
from racebot_sim_bridge.engine.physics import PhysicsWorld
from racebot_sim_bridge.sensors.camera import PinholeCamera
from racebot_sim_bridge.sensors.noise import GaussianNoise
from racebot_sim_bridge.sensors.render import CameraFrames, RendererError, load_renderer
from racebot_sim_bridge.sensors.render_worker import view_slot
from racebot_sim_bridge.sensors.scene import SceneColours
from racebot_sim_bridge.engine.world_copy import WorldCopy


def worker_main(fd):
    conn = helper_main(fd)

    _, choice = conn.recv()
    world = PhysicsWorld()
    try:
        renderer, description = load_renderer(world, choice)
    except RendererError as err:
        conn.send(('error', None, str(err)))
        return
    conn.send(('ready', renderer, description))
    copy = WorldCopy(world)
    colours = SceneColours(world, renderer)
    cameras = {}  # camera tuple -> CameraFrames
    maps = {}     # (path, offset, width, height) -> (rgb, depth) views
    while True:
        try:
            message = conn.recv()
        except (EOFError, OSError):
            return
        if message[0] == 'stop':
            return
        (_, request_id, bodies, names, shot, camera, position, rotation, want_depth, path, offset) = message
        try:
            copy.sync(bodies)
            copy.prune(set(names))
            colours.refresh()
            copy.pose(shot)
            frames = cameras.get(camera)
            if frames is None:
                width, height, hfov, near, far, mean, stddev = camera
                noise = GaussianNoise(mean, stddev) if stddev is not None else None
                frames = cameras[camera] = CameraFrames(PinholeCamera(width, height, hfov, near, far), noise)
            rgb, depth = frames.make(world, renderer, colours.planes, np.asarray(position),
                                     np.asarray(rotation), want_depth)
            key = (path, offset, frames.camera.width, frames.camera.height)
            views = maps.get(key)
            if views is None:
                views = maps[key] = view_slot(path, offset, frames.camera.width, frames.camera.height)
            views[0][...] = rgb
            if depth is not None:
                views[1][...] = depth
            conn.send(('frame', request_id, None, depth is not None))
        except Exception as err:  # one bad frame is reported, the worker goes on
            conn.send(('frame', request_id, '%s: %s' % (type(err).__name__, err), False))


if __name__ == '__main__':
    worker_main(int(sys.argv[1]))
