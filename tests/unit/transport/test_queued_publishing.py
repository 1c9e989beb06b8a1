"""The world server's queued publishing (queued_publishing.py): rospy's own QueuedConnection, patched so that
write_data switches to the writer thread only once the queue is half full, not after every message. Real
QueuedConnections (with their writer threads) over a transport that records what the writer sends, where a
socket would be."""
import threading
import time

import pytest

from racebot_sim_bridge.transport import queued_publishing

from queued_transports import RecordingTransport, close, socket_connection


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


def test_with_nothing_queued_a_message_goes_to_the_socket_from_the_caller(monkeypatch):
    conn, transport = socket_connection(1)
    yields, writes = [], []
    monkeypatch.setattr(queued_publishing.time, 'sleep', lambda seconds: yields.append(seconds))
    monkeypatch.setattr(transport, 'write_data', writes.append)  # the writer thread's way: not taken
    try:
        for i in range(100):
            conn.write_data(b'message %03d;' % i)
        assert transport.received(1200) == b''.join(b'message %03d;' % i for i in range(100))
        assert yields == [] and writes == [] and conn._queue == []  # no thread switch, nothing queued or dropped
        assert (transport.stat_num_msg, transport.stat_bytes) == (100, 1200)
    finally:
        monkeypatch.undo()
        close(conn, transport)


def test_a_busy_writer_keeps_the_order():
    conn, transport = socket_connection(10)
    try:
        with conn._lock:
            conn._sending = True  # the writer is relaying: nothing may pass it
        conn.write_data(b'queued')
        assert transport.received(6) == b'queued'  # sent by the writer
    finally:
        close(conn, transport)


def test_what_the_socket_cannot_take_is_queued_and_its_rest_never_dropped():
    conn, transport = socket_connection(1, buffer=4096)
    try:
        big = bytes(range(256)) * 4096  # 1 MB: more than the socket buffers hold
        # Under the connection's lock, as write_data calls it: the writer thread cannot take the queue between the
        # three writes (it takes the whole queue whenever it gets the lock: had it taken the rest and 'dropped'
        # before 'last' came, sending 'dropped' would be right, and a test without the lock raced it under load).
        with conn._lock:
            assert queued_publishing._send_or_queue(conn, big) == 1  # part goes at once, the rest is queued
            assert 0 < transport.stat_bytes < len(big)
            queued_publishing._send_or_queue(conn, b'dropped')
            queued_publishing._send_or_queue(conn, b'last')  # a queue of one: 'dropped' goes, the rest must not
            assert conn._queue[1:] == [b'last'] and isinstance(conn._queue[0], queued_publishing._Rest)
        assert transport.received(len(big) + 4) == big + b'last'
    finally:
        transport.peer.close()  # a writer still blocked on the full socket (the test failed) gets an error and ends
        close(conn, transport)
