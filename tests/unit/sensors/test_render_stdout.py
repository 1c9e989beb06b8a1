"""render.load_egl reads the EGL plugin's driver line from fd 1. fd 1 is the whole process's: while
another thread writes to it, none of that thread's output may go missing."""
import os
import subprocess
import sys
import threading

import pytest

from racebot_sim_bridge.engine.physics import PhysicsWorld
from racebot_sim_bridge.sensors import render


def load_egl_in_a_new_world():
    world = PhysicsWorld()
    try:
        return render.load_egl(world.client)
    except render.RendererError as err:
        pytest.skip('no EGL here: %s' % err)
    finally:
        world.close()


def test_another_threads_output_survives_the_plugin_load(capfd):
    stop = threading.Event()
    written = []

    def chatter():
        while not stop.is_set():
            os.write(1, b'tick %d\n' % len(written))
            written.append(1)
    thread = threading.Thread(target=chatter, daemon=True)
    thread.start()
    try:
        for _ in range(2):
            driver = load_egl_in_a_new_world()
    finally:
        stop.set()
        thread.join()
    out = capfd.readouterr().out
    ticks = out.count('tick ')  # the plugin's own lines may land in between
    assert ticks == len(written), '%d of the thread\'s %d lines went missing' % (len(written) - ticks, len(written))
    assert 'not read' in driver


def test_alone_the_driver_is_read():
    """As in the render worker process: a fresh interpreter with one thread."""
    script = ('import threading, test_render_stdout as t; assert threading.active_count() == 1; '
              'print("DRIVER:" + t.load_egl_in_a_new_world())')
    done = subprocess.run([sys.executable, '-c', script], capture_output=True, text=True, timeout=120,
                          cwd=os.path.dirname(os.path.abspath(__file__)))
    if 'no EGL here' in done.stderr:
        pytest.skip('no EGL here')
    assert done.returncode == 0, done.stderr[-2000:]
    driver = done.stdout.split('DRIVER:', 1)[1].strip()
    assert 'not read' not in driver and driver != 'unknown driver', driver
