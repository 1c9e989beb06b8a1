"""The world server's attach point for windows (viewer.AttachedWindows) and the window's side of it
(viewer_process.serve), over the real Unix socket with a real PyBullet world; no display, no master.

What gzclient and the world server rely on: a window that says hello is sent the world's bodies and
poses; it is sent the next update only once it has applied the last (the physics never waits for a
window); bodies spawned or deleted after it attached appear and go; a window that goes is forgotten
and said once; several windows at once; close() tells each window why and removes the socket."""
import os
import socket
import threading
import time
from multiprocessing.connection import Connection

import pytest

from racebot_sim_bridge.description import sdf_reader, urdf_reader
from racebot_sim_bridge.window import viewer, viewer_process
from racebot_sim_bridge.window.gzclient import connect, display_problem
from racebot_sim_bridge.engine.physics import PhysicsWorld

from fakes import FakeLog

WORLD = """<?xml version="1.0"?><sdf version="1.6"><world name="default">
  <model name="wall"><static>true</static><pose>2 0 0.5 0 0 0</pose><link name="link">
    <collision name="c"><geometry><box><size>0.1 2 1</size></box></geometry></collision>
    <visual name="v"><geometry><box><size>0.1 2 1</size></box></geometry></visual></link></model>
</world></sdf>"""
BOX_URDF = """<?xml version="1.0"?><robot name="box"><link name="base">
  <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
  <visual><geometry><box size="0.2 0.2 0.2"/></geometry></visual>
  <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link></robot>"""
WAIT = 10.0


@pytest.fixture
def world():
    w = PhysicsWorld()
    w.load_world(sdf_reader.parse_world(WORLD))
    yield w
    w.close()


@pytest.fixture
def windows(world):
    log = FakeLog()
    attached = viewer.AttachedWindows(world, log)
    attached.log_lines = log.lines
    yield attached
    attached.close()


def spawn_box(world, name='box', z=1.0):
    return world.spawn_urdf(name, urdf_reader.parse_urdf(BOX_URDF), BOX_URDF, position=(0.0, 0.0, z))


def sync_until(windows, condition, what):
    """Runs the physics thread's sync (as the world server does ~30 times a second) until condition()."""
    deadline = time.monotonic() + WAIT
    while time.monotonic() < deadline:
        windows.sync()
        if condition():
            return
        time.sleep(0.01)
    raise AssertionError('timed out waiting for ' + what)


def attach(windows, name='/gazebo_gui'):
    conn = connect(windows.address)
    assert conn is not None, 'nobody answers at ' + windows.address
    conn.send(('hello', 4242, name))
    return conn


def next_update(windows, conn):
    sync_until(windows, lambda: conn.poll(0), 'an update for the window')
    return conn.recv()


def test_a_window_that_says_hello_gets_the_world(world, windows):
    assert windows.count == 0
    conn = attach(windows)
    kind, bodies, names, shot, follow = next_update(windows, conn)
    assert kind == 'sync' and windows.count == 1
    assert set(bodies) == set(names) == set(shot) == {'wall'}
    assert ('info', 'a window attached: /gazebo_gui (process 4242)') in windows.log_lines
    assert follow is None  # no robot to follow yet
    conn.close()


def test_the_next_update_waits_until_the_window_has_applied_the_last(world, windows):
    conn = attach(windows)
    next_update(windows, conn)
    for _ in range(5):  # the window has not answered: the physics thread goes on, sending nothing
        windows.sync()
    assert not conn.poll(0.2)
    conn.send(('shown',))
    kind, bodies, names, shot, _ = next_update(windows, conn)
    assert kind == 'sync' and bodies == {}, 'bodies already sent are not sent again'
    assert set(shot) == {'wall'}
    conn.close()


def test_bodies_spawned_and_deleted_after_attaching_appear_and_go(world, windows):
    conn = attach(windows)
    next_update(windows, conn)
    conn.send(('shown',))
    spawn_box(world)
    _, bodies, names, shot, follow = next_update(windows, conn)
    assert set(bodies) == {'box'} and set(names) == {'wall', 'box'} and follow == 'box'
    conn.send(('shown',))
    world.remove('box')
    _, bodies, names, shot, follow = next_update(windows, conn)
    assert bodies == {} and names == ['wall'] and set(shot) == {'wall'} and follow is None
    conn.close()


def test_a_respawn_under_the_same_name_is_sent_again(world, windows):
    spawn_box(world)
    conn = attach(windows)
    first = next_update(windows, conn)[1]['box'][0]
    conn.send(('shown',))
    world.remove('box')
    spawn_box(world, z=2.0)
    bodies = next_update(windows, conn)[1]
    assert set(bodies) == {'box'} and bodies['box'][0] != first
    conn.close()


def test_the_physics_thread_never_waits_for_a_window_that_does_not_read(world, windows):
    for i in range(1000):  # a first update (~1 MB) larger than what a Unix socket holds (~230 kB)
        spawn_box(world, 'box%d' % i, z=1.0 + i)
    conn = attach(windows)  # says hello, then reads nothing

    def physics_thread():
        sync_until(windows, lambda: windows.count == 1, 'the window to attach')
        for _ in range(5):
            windows.sync()
    thread = threading.Thread(target=physics_thread, daemon=True)
    thread.start()
    thread.join(2 * WAIT)  # a hang detector: sync would block for ever if it wrote to the socket itself
    assert not thread.is_alive(), 'sync waited for a window that does not read'
    _, bodies, names, _, _ = conn.recv()  # the update arrives whole once the window reads
    assert len(bodies) == len(names) == 1001
    conn.close()


def test_a_window_that_goes_is_forgotten_and_said_once(world, windows):
    conn = attach(windows)
    next_update(windows, conn)
    conn.close()
    sync_until(windows, lambda: windows.count == 0 and not windows.links, 'the window to be forgotten')
    warnings = [text for level, text in windows.log_lines if level == 'warn']
    assert len(warnings) == 1 and 'the simulation goes on without it' in warnings[0], warnings
    for _ in range(3):
        windows.sync()
    assert len([1 for level, _ in windows.log_lines if level == 'warn']) == 1


def test_several_windows_at_once(world, windows):
    a, b = attach(windows, '/a'), attach(windows, '/b')
    assert next_update(windows, a)[0] == next_update(windows, b)[0] == 'sync'
    assert windows.count == 2
    a.close()
    sync_until(windows, lambda: windows.count == 1, 'one window left')
    b.send(('shown',))
    assert next_update(windows, b)[0] == 'sync'
    b.close()


def test_a_connection_that_is_not_a_window_is_dropped(world, windows):
    stranger = connect(windows.address)
    stranger.send(('hi there',))
    sync_until(windows, lambda: any('not a hello' in text for _, text in windows.log_lines),
               'the stranger to be dropped, and said')
    assert windows.count == 0 and not windows.links
    silent = connect(windows.address)
    sync_until(windows, lambda: windows.links, 'the silent connection to be taken in')
    windows.sync(now=time.monotonic() + viewer.HELLO_TIMEOUT + 1.0)
    assert not windows.links and any('did not say hello' in text for _, text in windows.log_lines)
    silent.close()


def test_a_window_slower_to_open_than_the_hello_timeout_stays_attached(world, windows):
    """gzclient says hello for its window as it starts the window's process; the window opens its GUI (seconds of
    software OpenGL on a busy machine) before it reads a thing, and must not be dropped for it."""
    import os
    from multiprocessing.connection import Connection
    from racebot_sim_bridge.window import gzclient
    sock = gzclient.connect_socket(windows.address)
    ours = Connection(os.dup(sock.fileno()))
    window = Connection(sock.detach())  # the window process's side
    gzclient.say_hello(ours, 4242, '/gazebo_gui')
    sync_until(windows, lambda: windows.count == 1, 'the window to count as attached')
    windows.sync(now=time.monotonic() + viewer.HELLO_TIMEOUT + 5.0)  # the window still opening, reading nothing
    assert windows.count == 1 and not any('did not say hello' in text for _, text in windows.log_lines)
    assert next_update(windows, window)[0] == 'sync'
    window.close()


def test_close_tells_each_window_why_and_removes_the_socket(world):
    windows = viewer.AttachedWindows(world, FakeLog())
    conn = attach(windows)
    next_update(windows, conn)
    windows.close('the world server shut down')
    assert conn.recv() == ('stop', 'the world server shut down')
    assert not os.path.exists(windows.address) and connect(windows.address) is None


def test_close_tells_also_a_window_that_connected_since_the_last_sync(world):
    windows = viewer.AttachedWindows(world, FakeLog())
    conn = attach(windows)  # accepted by the accept thread, not yet taken in by a sync
    deadline = time.monotonic() + WAIT
    while not windows._new and time.monotonic() < deadline:
        time.sleep(0.01)
    assert windows._new, 'the accept thread did not take the connection'
    windows.close('the world server shut down')
    assert conn.poll(WAIT) and conn.recv() == ('stop', 'the world server shut down')


def test_the_socket_is_private_to_this_user(windows):
    assert os.stat(os.path.dirname(windows.address)).st_mode & 0o077 == 0


class FakeWindow:
    def __init__(self):
        self.shown = []

    def show(self, *update):
        self.shown.append(update)


def pair():
    a, b = socket.socketpair()
    return Connection(a.detach()), Connection(b.detach())


def test_serve_shows_updates_and_answers_until_the_server_stops():
    server, conn = pair()
    window = FakeWindow()
    result = []
    thread = threading.Thread(target=lambda: result.append(viewer_process.serve(conn, window)))
    thread.start()
    server.send(('sync', {}, ['wall'], {}, None))
    assert server.poll(WAIT) and server.recv() == ('shown',)
    server.send(('stop', 'it shuts down'))
    thread.join(WAIT)
    assert result == [viewer_process.EXIT_STOPPED]
    assert window.shown == [({}, ['wall'], {}, None)]


def test_serve_ends_when_the_server_is_lost():
    server, conn = pair()
    server.close()
    assert viewer_process.serve(conn, FakeWindow()) == viewer_process.EXIT_LOST


class SlowWindow(FakeWindow):
    """Shows an update only when let (an update that takes a while: a GUI under load)."""

    def __init__(self):
        super().__init__()
        self.showing, self.go_on = threading.Event(), threading.Event()

    def show(self, *update):
        self.showing.set()
        assert self.go_on.wait(WAIT)
        super().show(*update)


def serve_closed_while_showing(then_stop):
    """serve()'s exit code when the server closes (after a 'stop' if then_stop) while an update is shown."""
    server, conn = pair()
    window = SlowWindow()
    result = []
    thread = threading.Thread(target=lambda: result.append(viewer_process.serve(conn, window)))
    thread.start()
    server.send(('sync', {}, ['wall'], {}, None))
    assert window.showing.wait(WAIT)
    if then_stop:
        server.send(('stop', 'it shuts down'))
    server.close()
    window.go_on.set()
    thread.join(WAIT)
    return result


def test_a_stop_that_comes_while_an_update_is_shown_is_read_though_the_answer_cannot_go():
    # The world server sends 'stop' and closes while the window is still showing the last update (a
    # fresh-root CI run hit this): the window's ('shown',) then fails (EPIPE), but the stop is waiting
    # in its socket, so it ends as told (EXIT_STOPPED), not as if the server had crashed.
    assert serve_closed_while_showing(then_stop=True) == [viewer_process.EXIT_STOPPED]


def test_an_answer_that_cannot_go_without_a_stop_is_a_lost_server():
    assert serve_closed_while_showing(then_stop=False) == [viewer_process.EXIT_LOST]


def test_a_closed_window_is_told_apart_by_its_exit_code():
    # Xlib ends a process whose X connection was killed with exit(1): no other ending may use 1
    others = (viewer_process.EXIT_STOPPED, viewer_process.EXIT_LOST, viewer_process.EXIT_CRASHED,
              viewer_process.EXIT_NO_WINDOW)
    assert viewer_process.EXIT_CLOSED == 1 and 1 not in others and len(set(others)) == len(others)


def test_no_display_is_said_in_words(monkeypatch):
    monkeypatch.delenv('DISPLAY', raising=False)
    assert display_problem() == 'there is no display (DISPLAY is unset)'
    assert 'cannot be opened' in display_problem(':97531')
