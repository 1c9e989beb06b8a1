"""The world server's queued publishing (queued_publishing.py): rospy's own QueuedConnection, patched so that
write_data switches to the writer thread only once the queue is half full, not after every message. Real
QueuedConnections (with their writer threads) over a transport that records what the writer sends, where a
socket would be."""
import threading
import time

import pytest

from racebot_sim_bridge import queued_publishing


class RecordingTransport:
    """What QueuedConnection wraps: its writer thread calls write_data; `done` ends that thread. With `hold`, the
    first write waits for it: the writer is busy and what the caller writes meanwhile stays queued."""

    def __init__(self, hold=None):
        self.sent, self.done, self.hold = [], False, hold
        self.writing = threading.Event()

    def set_cleanup_callback(self, callback):
        self.cleanup = callback

    def write_data(self, data):
        self.writing.set()
        if self.hold is not None:
            self.hold.wait(10.0)
        self.sent.append(data)


@pytest.fixture
def connection():
    made = []

    def make(queue_size, hold=None):
        transport = RecordingTransport(hold)
        conn = queued_publishing.install()(transport, queue_size)
        made.append((conn, transport))
        return conn, transport
    yield make
    for conn, transport in made:
        if transport.hold is not None:
            transport.hold.set()
        transport.done = True
        conn._closed_connection_callback(transport)
        conn._thread.join(5.0)


def _wait(condition, timeout=5.0):
    deadline = time.monotonic() + timeout
    while not condition() and time.monotonic() < deadline:
        threading.Event().wait(0.005)
    return condition()


def test_install_replaces_rospys_write_data_once():
    cls = queued_publishing.install()
    assert cls.write_data is queued_publishing.write_data
    assert queued_publishing.install() is cls and len(queued_publishing._installed) == 1


def test_every_message_arrives_in_order_when_the_writer_keeps_up(connection):
    conn, transport = connection(10)
    for i in range(3000):
        conn.write_data(i)
        # the writer keeps up: on a loaded machine it may get no core for a while, so wait for it rather than
        # let the queue fill (then dropping the oldest is what queue_size asks for, tested below)
        assert _wait(lambda: len(conn._queue) < 5)
    assert _wait(lambda: len(transport.sent) == 3000)
    assert transport.sent == list(range(3000))


def test_the_caller_yields_to_the_writer_only_once_the_queue_is_half_full(connection, monkeypatch):
    hold = threading.Event()
    conn, transport = connection(10, hold)
    conn.write_data(0)
    assert transport.writing.wait(5.0)  # the writer took message 0 and is busy with it
    yields = []
    monkeypatch.setattr(queued_publishing.time, 'sleep', lambda seconds: yields.append(seconds))
    for i in range(1, 5):
        conn.write_data(i)
    assert yields == []  # 4 queued of 10: rospy would have yielded 4 times
    conn.write_data(5)
    assert yields == [0]  # half full: the writer gets its turn
    monkeypatch.undo()


def test_a_full_queue_drops_the_oldest_as_rospy_does(connection):
    hold = threading.Event()
    conn, transport = connection(3, hold)
    conn.write_data(0)
    assert transport.writing.wait(5.0)
    for i in range(1, 8):
        conn.write_data(i)
    hold.set()
    assert _wait(lambda: len(transport.sent) == 4)
    assert transport.sent == [0, 5, 6, 7]


def test_a_writer_error_reaches_the_next_caller_once(connection):
    conn, _ = connection(10)
    conn._error = RuntimeError('connection lost')
    with pytest.raises(RuntimeError, match='connection lost'):
        conn.write_data(1)
    assert conn.write_data(2) is True
